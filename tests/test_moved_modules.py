"""The module paths before the subpackages (issue 17, item 2) still import, with a DeprecationWarning."""
import importlib
import subprocess
import sys

import pytest

from exudyn_worm._moved import MOVED


@pytest.mark.parametrize('old', sorted(MOVED))
def test_every_new_path_exists(old):
    assert importlib.util.find_spec(f'exudyn_worm.{MOVED[old]}') is not None


@pytest.mark.messages
def test_an_old_path_gives_the_new_module_and_says_where_it_went():
    code = ('import warnings, sys\n'
            'warnings.simplefilter("always")\n'
            'with warnings.catch_warnings(record=True) as caught:\n'
            '    from exudyn_worm.reelchanger import SimulateReelChanger\n'
            '    import exudyn_worm.commands.chart as chart\n'
            'import exudyn_worm.analysis.reelchanger as new\n'
            'assert SimulateReelChanger is new.SimulateReelChanger\n'
            'assert chart is sys.modules["exudyn_worm.cli.chart"]\n'
            'print("|".join(str(w.message) for w in caught if w.category is DeprecationWarning))\n')
    out = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True, check=True).stdout
    assert 'exudyn_worm.reelchanger is now exudyn_worm.analysis.reelchanger' in out
    assert 'exudyn_worm.commands.chart is now exudyn_worm.cli.chart' in out


def test_the_new_paths_import_without_a_warning():
    code = ('import warnings\nwarnings.simplefilter("error")\n'
            'import exudyn_worm.setups.presets, exudyn_worm.analysis.study, exudyn_worm.cli.main\n')
    subprocess.run([sys.executable, '-c', code], check=True)


def test_an_unknown_module_is_still_an_import_error():
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module('exudyn_worm.nosuchmodule')
