"""Start-up of the command line: light subcommands do not import exudyn, scipy, pint, matplotlib or tqdm.

Correctness of the import structure, not a timing test (the start-up time is measured in benchmarks/).
"""
import json
import subprocess
import sys

import pytest

import exudyn_worm

HEAVY = ('exudyn', 'scipy', 'pint', 'matplotlib', 'tqdm')
#: what the command line's help and its argument errors load without: the heavy packages and numpy (about half of
#: the start-up of `exudyn-worm --help`)
HELP_HEAVY = HEAVY + ('numpy',)

_SCRIPT = """
import json, sys
{code}
print(json.dumps(sorted({{m.split('.')[0] for m in sys.modules}} & set({heavy!r}))))
"""


def _HeavyModulesAfter(code: str, heavy=HEAVY):
    out = subprocess.run([sys.executable, '-c', _SCRIPT.format(code=code, heavy=heavy)], capture_output=True,
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


@pytest.mark.parametrize('argv', [
    ['--help'],
    ['stability', '--help'],
    ['check', '--help'],
    ['chart', '--help'],
    ['stability', '--no-such-option'],
    ['simulate', '--end-time', 'abc'],
    ['no-such-command'],
])
def test_help_and_argument_errors_import_no_numpy(argv):
    """The parser of every subcommand is built without numpy (defaults that the analyses own are read when a help
    text is printed, and then only that subcommand's)."""
    code = f'from exudyn_worm.cli.main import Main\ntry:\n    Main({argv!r})\nexcept SystemExit:\n    pass'
    loaded = _HeavyModulesAfter(code, HELP_HEAVY)
    if argv[-1] == '--help' and argv[0] != '--help':
        assert loaded == ['numpy']      # a subcommand's help names the presets, which load numpy
    else:
        assert loaded == []


def test_lazy_package_attributes_still_resolve():
    for name in exudyn_worm.__all__:
        assert getattr(exudyn_worm, name) is not None
