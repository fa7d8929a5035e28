"""The chatter rule of SimulationResult.Chatter: relative to the mesh torque, and never on an unloaded mesh."""
import numpy as np
import pytest

from exudyn_worm import GetPreset, SimulateReelChanger
from exudyn_worm.items.results import CHATTER_MIN_MESH_TORQUE, SimulationResult


def _Result(meshTorque, acceleration):
    t = np.linspace(0., 1., 1001)
    wiggle = np.sin(2 * np.pi * 40. * t)
    series = {'wheelTorque': meshTorque * (1. + 0.1 * wiggle), 'alpha2': acceleration * wiggle}
    return SimulationResult(time=t, series=series, J2=33., r2=0.106)


def test_relative_rule_and_floor():
    assert _Result(2000., 10.).Chatter(0., 1.)                 # 330 N*m of inertia torque > 10 % of 2200 N*m
    assert not _Result(2000., 5.).Chatter(0., 1.)              # 165 N*m < 220 N*m
    # the same proportions at round-off level: no load, no chatter
    assert not _Result(2e-7, 1e-9).Chatter(0., 1.)
    assert _Result(10 * CHATTER_MIN_MESH_TORQUE, 1e-3).Chatter(0., 1.)


@pytest.mark.physics
def test_unloaded_reel_changer_does_not_chatter():
    """loadMass = 0: the mesh carries only round-off (|phi2''| about 1e-9 rad/s^2), which the relative rule
    alone called chatter in both windows."""
    p = dict(GetPreset('reel-P1'), loadMass=0.)
    result = SimulateReelChanger(p, endTime=4., progress=False)
    metrics = result.WindowMetrics([(0., 2.), (2., 4.)])
    assert max(m['maxAbsWheelAcceleration'] for m in metrics) < 1e-6
    assert [m['chatter'] for m in metrics] == [False, False]
