"""The variants of benchmarks/p1_floor.py mean what the benchmark README says of them: the real model is the one
SimulateReelChanger solves, and taking the post-Newton function out of P1 changes no step of its solve (its worm
never stops). Work counters compared, never times."""
import pytest

from exudyn_worm.analysis.simulation.reelchanger import SimulateReelChanger
from exudyn_worm.drive.presets import GetPreset
from exudyn_worm.drive.wholedrive import ResolveDrive

from conftest import LoadScript


@pytest.fixture(scope='module')
def floor():
    return LoadScript('benchmarks/p1_floor.py', 'p1_floor')


def test_default_variant_is_the_simulated_model_and_post_newton_changes_no_step(floor):
    _, default = floor.SolveVariant('default')
    _, without = floor.SolveVariant('noPostNewton')
    simulated = SimulateReelChanger(ResolveDrive(parameters=GetPreset('reel-P1')), progress=False).info['solver']
    assert default['newtonIterations'] == simulated['newtonIterations']
    assert default['jacobians'] == simulated['jacobians']
    assert without == default


def test_unknown_variant_is_refused(floor):
    with pytest.raises(ValueError, match=r"variant must be one of default, .*got 'fast'"):
        floor.SolveVariant('fast')
