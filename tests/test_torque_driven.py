"""The benchmark lever 'worm driven by the shaft torque' (benchmarks/torque_driven.py) is the same model as
SimulateReelChanger (motor prescribed through a constraint): results compared, never times."""
import numpy as np
import pytest

from exudyn_worm.drive.presets import GetPreset
from exudyn_worm.analysis.simulation.reelchanger import SimulateReelChanger
from exudyn_worm.drive.wholedrive import ResolveDrive

from conftest import LoadScript


@pytest.fixture(scope='module')
def runs():
    torqueDriven = LoadScript('benchmarks/torque_driven.py', 'torque_driven')
    p1 = GetPreset('reel-P1')
    return (SimulateReelChanger(ResolveDrive(parameters=p1), stepSize=5e-4, endTime=3.),
            torqueDriven.SimulateTorqueDriven(p1, 5e-4, endTime=3.))


@pytest.mark.physics
def test_same_lifting_phase(runs):
    ours, torque = runs
    np.testing.assert_allclose(torque.time, ours.time, atol=1e-12)
    m = ours.time <= 2.
    # measured 3e-6 N of 21 kN; a 0.1 % change of the load moves the force by 21 N
    assert np.max(np.abs(torque.normalForce[m] - ours.normalForce[m])) < 1e-3
    assert np.max(np.abs(torque.phi1[m] - ours.phi1[m])) < 1e-9


@pytest.mark.physics
def test_same_chatter_onset(runs):
    ours, torque = runs
    late = ours.time >= 2.5
    assert np.max(np.abs(torque.alpha2[late])) == pytest.approx(np.max(np.abs(ours.alpha2[late])), rel=1e-4)
