"""Start-up of the command line: light subcommands do not import exudyn, scipy, pint, matplotlib or tqdm.

Correctness of the import structure, not a timing test (the start-up time is measured in benchmarks/).
"""
import json
import subprocess
import sys

import pytest

import exudyn_worm

HEAVY = ('exudyn', 'scipy', 'pint', 'matplotlib', 'tqdm')

_SCRIPT = """
import json, sys
{code}
print(json.dumps(sorted({{m.split('.')[0] for m in sys.modules}} & set({heavy!r}))))
"""


def _HeavyModulesAfter(code: str):
    out = subprocess.run([sys.executable, '-c', _SCRIPT.format(code=code, heavy=HEAVY)], capture_output=True,
                         text=True, check=True).stdout
    return json.loads(out.splitlines()[-1])


@pytest.mark.parametrize('code', [
    'import exudyn_worm.cli.main',
    'import exudyn_worm',
    'from exudyn_worm import SimulateReelChanger, AnalyzeStability',
    'from exudyn_worm.cli.main import BuildParser; BuildParser()',
    'from exudyn_worm.cli.main import Main; Main(["stability", "--preset", "reel-P1"])',
    'from exudyn_worm.cli.main import Main; Main(["stability", "--preset", "reel-P1", "--json"])',
])
def test_light_paths_import_no_heavy_module(code):
    assert _HeavyModulesAfter(code) == []


def test_lazy_package_attributes_still_resolve():
    for name in exudyn_worm.__all__:
        assert getattr(exudyn_worm, name) is not None
