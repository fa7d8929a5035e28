"""examples/friction_speed.py: mu(v), the largest real part and the simulated chatter
amplitude over motor speed, and the gear that is self-locking at rest but runs away once moving."""
import math

import numpy as np
import pytest

import exudyn_worm as ew
from conftest import LoadScript
from exudyn_worm.analysis.charts.speedchart import RPM


@pytest.fixture(scope='module')
def example():
    return LoadScript('examples/friction_speed.py', 'friction_speed')


def test_friction_curves(example):
    mu = example.FrictionCurves([0., 0.897, 3.])
    np.testing.assert_allclose(mu['constant'], 0.132)
    assert mu['stribeck'][0] == pytest.approx(0.2) and mu['stribeck'][1] == pytest.approx(0.132, abs=5e-4)
    assert mu['agma'][0] == 0.15 and mu['agma'][1] == pytest.approx(0.0453, abs=5e-5)   # docs/friction.md
    assert np.all(np.diff(mu['agma']) < 0) and np.all(np.diff(mu['stribeck']) < 0)


def test_speed_chart(example):
    charts = example.SpeedChart(np.geomspace(20., 2000., 41))
    assert charts['constant'].unstableRanges == []                    # constant mu: speed does not matter
    (low, high), = charts['stribeck'].unstableRanges
    assert 80 < low / RPM < 110 and 480 < high / RPM < 700


def test_simulated_amplitude_follows_the_linear_verdict_away_from_the_boundary(example):
    # 250 rpm: max Re +5.2 1/s, far inside the unstable range; 1600 rpm: -3.25 1/s, far outside
    sim = example.ChatterAmplitudes((250., 1600.))
    assert list(sim['chatter']) == [True, False]
    assert sim['amplitude'][0] > 100 * sim['amplitude'][1]


def test_statically_but_not_dynamically_self_locking_runs_away(example):
    agma, constant = example.RunAway('agma'), example.RunAway('constant')
    assert agma['verdict'].static.selfLocking and not agma['verdict'].dynamic.selfLocking
    assert agma['verdict'].dangerous
    assert constant['verdict'].static.selfLocking and constant['verdict'].dynamic.selfLocking
    start = agma['omega1'][0]
    assert agma['omega1'][-1] > 2 * start                               # the load drives the worm faster
    assert np.all(np.diff(agma['omega1'][len(agma['omega1']) // 10:]) > 0)
    assert abs(constant['omega1'][-1]) < 0.01 * start                   # constant mu brakes it (to a creep)


def test_the_same_gear_holds_from_rest(example):
    hold = example.HoldAtRest('agma', endTime=8.)
    assert hold['verdict'].dangerous
    k = int(np.searchsorted(hold['time'], 5.))      # after the mesh's own lightly damped oscillation decayed
    assert np.max(np.abs(hold['phi2'][k:] - hold['phi2'][k])) < 1e-6     # no creep (required: below 1e-6 rad)
    # still at the horizontal, but for the mesh's elastic deflection under the load: Delta s = Fn / kV with
    # Fn = M / c4 (eq. (12)), seen at the wheel as Delta s / (u r1 cos(alphaN) sin(gamma)) (eqs. (3)-(5))
    p = ew.GetPreset('reel-P1')
    gear = ew.ElasticDriveFromParameters(p).gear
    fn = p['loadMass'] * 9.81 * p['leverArm'] / gear.LeverArms(-1)[1]
    deflection = fn / gear.kV / (gear.ratio * gear.normalLever)
    assert abs(hold['phi2'][-1] - math.pi) == pytest.approx(deflection, rel=0.05)


def test_bad_law(example):
    with pytest.raises(ValueError, match="'law' must be 'agma' or 'constant', got 'stribek'"):
        example.RunAway('stribek')
