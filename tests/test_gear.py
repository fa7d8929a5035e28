"""Unit and property tests of the worm-gear model: eqs. (3), (5), (9)-(13) and the damping measures (22)-(23)."""
import math
import re

import pytest
from hypothesis import given, settings, strategies as st
from numpy.testing import assert_allclose

from exudyn_worm.model.drive import (ElasticDrive, MeshDampingFromMeasure, MeshDampingMeasure,
                               TorsionalDampingFromMeasure, TorsionalDampingMeasure)
from exudyn_worm.model.gear import WormGear

# random gears of the property tests include worms larger than their wheels: warned, not wrong here
pytestmark = pytest.mark.filterwarnings('ignore::exudyn_worm.params.plausibility.ImplausibleValueWarning')

deg = math.radians

# set (28) of the paper (section 3.1); friction given as rho so mu follows from eq. (13)
REEL = dict(alphaN=deg(20), gamma=deg(5.3228), r1=18.05e-3, r2=105.95e-3, kV=2e8, dV=21470.)
# set (25) of the paper (section 2.3)
CHART = dict(alphaN=deg(20), gamma=deg(5.3228), r1=3.235e-3, r2=18.98e-3, kV=1.7728e6, dV=1250.)


# --- argument validation: the message names function, argument, range with unit, and value ------------

@pytest.mark.messages
@pytest.mark.parametrize('name, value, pattern', [
    ('r1', -0.001, r"WormGear: 'r1' must be > 0 m, got -0.001 m"),
    ('r2', 0., r"WormGear: 'r2' must be > 0 m, got 0 m"),
    ('kV', -5., r"WormGear: 'kV' must be > 0 N/m, got -5 N/m"),
    ('dV', -1., r"WormGear: 'dV' must be >= 0 N\*s/m, got -1 N\*s/m"),
    ('backlash', -1e-4, r"WormGear: 'backlash' must be >= 0 m, got -0.0001 m"),
    ('alphaN', 2., r"WormGear: 'alphaN' must be in \(0, pi/2\) rad.*got 2 rad"),
    ('gamma', 0., r"WormGear: 'gamma' must be in \(0, pi/2\) rad.*got 0 rad"),
    ('mu', -0.1, r"WormGear: 'mu' must be >= 0, got -0.1"),
    ('r1', math.nan, r"WormGear: 'r1' must be finite \(m\), got nan"),
])
def test_gear_rejects_out_of_range(name, value, pattern):
    kwargs = {**REEL, 'rho': deg(8), name: value}
    if name == 'mu':
        kwargs.pop('rho')
    with pytest.raises(ValueError, match=pattern):
        WormGear(**kwargs)


@pytest.mark.messages
def test_gear_rejects_rho_out_of_range():
    with pytest.raises(ValueError, match=r"WormGear: 'rho' must be in \[0, pi/2\) rad, got 1.6 rad"):
        WormGear(**REEL, rho=1.6)


@pytest.mark.messages
def test_gear_rejects_non_numbers():
    with pytest.raises(TypeError, match=r"WormGear: 'r1' must be a real number in m, got str '1'"):
        WormGear(**{**REEL, 'r1': '1'}, rho=deg(8))
    with pytest.raises(TypeError, match=r"'kV' must be a real number"):
        WormGear(**{**REEL, 'kV': True}, rho=deg(8))


@pytest.mark.messages
def test_gear_needs_friction():
    with pytest.raises(ValueError, match=r"give the friction as 'mu'.*or as 'rho'.*got neither"):
        WormGear(**REEL)


@pytest.mark.messages
def test_drive_rejects_out_of_range():
    gear = WormGear(**REEL, rho=deg(8))
    with pytest.raises(ValueError, match=r"ElasticDrive: 'J1' must be > 0 kg\*m\^2, got -0.1 kg\*m\^2"):
        ElasticDrive(gear, J1=-0.1, J2=33., kT=7000., dT=0.74)
    with pytest.raises(ValueError, match=r"ElasticDrive: 'dT' must be >= 0 N\*m\*s/rad, got -1 N\*m\*s/rad"):
        ElasticDrive(gear, J1=0.1, J2=33., kT=7000., dT=-1.)
    with pytest.raises(TypeError, match=r"ElasticDrive: 'gear' must be a WormGear, got dict"):
        ElasticDrive({}, J1=0.1, J2=33., kT=7000., dT=0.74)


# --- friction: eq. (13) and the mu/rho question of set (28) -----------------------------------------------

@pytest.mark.physics
def test_friction_angle_eq13():
    # eq. (13): rho = atan(mu / cos(alphaN)); (25) prints mu = 0.132 (rho = 8 deg)
    g = WormGear(**CHART, mu=0.132)
    assert_allclose(math.degrees(g.rho), 7.9961, atol=5e-5)
    assert math.degrees(g.frictionAngle) == pytest.approx(8, abs=0.5)  # printed '8 deg' has one digit
    mu = WormGear(**CHART, rho=deg(8)).mu
    assert mu == pytest.approx(math.tan(deg(8)) * math.cos(deg(20)), rel=1e-14)
    assert_allclose(mu, 0.132, atol=5e-4)  # printed digits of (25)


@pytest.mark.messages
def test_mu_and_rho_must_be_consistent():
    # (28) prints mu = 0.134 (rho = 8 deg): inconsistent through eq. (13) if 8 deg is exact
    with pytest.raises(ValueError, match=r"'mu' and 'rho' are inconsistent through eq. \(13\).*mu = 0.134 needs "
                                         r"rho = 8.11\d* deg, got rho = 8 deg"):
        WormGear(**REEL, mu=0.134, rho=deg(8))
    mu = math.tan(deg(8)) * math.cos(deg(20))
    g = WormGear(**REEL, mu=mu, rho=deg(8))
    assert g.mu == mu and g.rho == deg(8)


def test_replace_friction():
    g = WormGear(**REEL, rho=deg(8))
    h = g.Replace(mu=0.134)
    assert_allclose(math.degrees(h.rho), 8.1157, atol=5e-5)
    assert g.Replace(rho=deg(6)).mu == pytest.approx(math.tan(deg(6)) * math.cos(deg(20)))


# --- ratio, coefficients, efficiency -------------------------------------------------------------------------

@pytest.mark.physics
@pytest.mark.parametrize('geometry', [REEL, CHART], ids=['set28', 'set25'])
def test_ratio_is_63(geometry):
    # eq. (3); both sets print "u = 63"
    g = WormGear(**geometry, rho=deg(8))
    assert g.ratio == pytest.approx(geometry['r2'] / (geometry['r1'] * math.tan(geometry['gamma'])))
    assert abs(g.ratio - 63) <= 0.5


@pytest.mark.physics
def test_coefficients_eqs_9_to_12():
    g = WormGear(**REEL, rho=deg(8))
    a, gm, r = deg(20), deg(5.3228), deg(8)
    for S in (+1, -1):
        c1, c2, c3, c4 = g.Coefficients(S)
        assert_allclose(c1, REEL['r1']**2 * math.cos(a)**2 * math.sin(gm) * math.sin(gm + r * S) / math.cos(r), rtol=1e-13)
        assert_allclose(c2, REEL['r1'] * math.cos(a) * math.sin(gm + r * S) / math.cos(r), rtol=1e-13)
        assert_allclose(c3, REEL['r1'] * REEL['r2'] * math.cos(a)**2 * math.sin(gm) * math.cos(gm + r * S) / math.cos(r),
                        rtol=1e-13)
        assert_allclose(c4, REEL['r2'] * math.cos(a) * math.cos(gm + r * S) / math.cos(r), rtol=1e-13)
        assert c1 == pytest.approx(c2 * g.normalLever) and c3 == pytest.approx(c4 * g.normalLever)
        assert c3 > 0 and c4 > 0
    # self-locking: c1, c2 < 0 for S = -1 only
    assert g.selfLocking and g.Coefficients(-1)[0] < 0 < g.Coefficients(+1)[0]


@pytest.mark.physics
def test_normal_displacement_eq5():
    g = WormGear(**REEL, rho=deg(8))
    assert g.NormalDisplacement(1e-3) == pytest.approx(REEL['r1'] * math.cos(deg(20)) * math.sin(deg(5.3228)) * 1e-3)
    assert g.RelativeAngle(1., 1. / g.ratio) == pytest.approx(0., abs=1e-15)


@pytest.mark.physics
def test_efficiency_sign_and_self_locking():
    locking = WormGear(**REEL, rho=deg(8))
    assert locking.selfLocking
    assert locking.efficiencyWheelDriving < 0  # the wheel cannot drive the worm
    assert locking.efficiencyWheelDriving == pytest.approx(math.tan(deg(5.3228) - deg(8)) / math.tan(deg(5.3228)))
    assert locking.efficiencyWormDriving == pytest.approx(math.tan(deg(5.3228)) / math.tan(deg(13.3228)))
    free = locking.Replace(gamma=deg(20))
    assert not free.selfLocking and 0 < free.efficiencyWheelDriving < free.efficiencyWormDriving < 1


# --- damping measures (22)-(23) ----------------------------------------------------------------------------

@pytest.mark.physics
def test_damping_measures_of_set28():
    # (28): dT = 0.741 N m s (D_T = 0.014), dV = 21470 N s/m (D_V = 0.014), printed digits
    assert_allclose(TorsionalDampingMeasure(0.741, 7000., 0.1), 0.014, atol=5e-4)
    assert_allclose(TorsionalDampingFromMeasure(0.014, 7000., 0.1), 0.741, atol=5e-4)
    assert_allclose(MeshDampingMeasure(21470., 2e8, 105.95e-3, 33.), 0.014, atol=5e-4)
    assert_allclose(MeshDampingFromMeasure(0.014, 2e8, 105.95e-3, 33.), 21470., atol=5)


@pytest.mark.messages
def test_damping_measure_errors_name_argument():
    with pytest.raises(ValueError, match=r"TorsionalDampingMeasure: 'kT' must be > 0 N\*m/rad, got 0 N\*m/rad"):
        TorsionalDampingMeasure(0.7, 0., 0.1)
    with pytest.raises(ValueError, match=r"MeshDampingFromMeasure: 'DV' must be >= 0, got -0.1"):
        MeshDampingFromMeasure(-0.1, 2e8, 0.1, 33.)


# --- properties -------------------------------------------------------------------------------------------

angles = st.floats(min_value=0.5, max_value=45., allow_nan=False)


@pytest.mark.physics
@settings(max_examples=200, deadline=None)
@given(alphaN=st.floats(5., 35.), gamma=angles, rho=st.floats(0., 40.), r1=st.floats(1e-3, 0.2),
       r2=st.floats(5e-3, 1.), S=st.sampled_from([+1, -1]))
def test_c3_c4_positive(alphaN, gamma, rho, r1, r2, S):
    """c3, c4 > 0 for every valid gear with gamma + rho < 90 deg (section 2.2); a ratio u < 1 is refused as no
    worm gear (exudyn_worm/params/plausibility.py), so it is left out here."""
    if gamma + rho >= 89.9 or r2 < r1 * math.tan(deg(gamma)):
        return
    g = WormGear(alphaN=deg(alphaN), gamma=deg(gamma), r1=r1, r2=r2, kV=1e8, dV=0., rho=deg(rho))
    _, _, c3, c4 = g.Coefficients(S)
    assert c3 > 0 and c4 > 0


@pytest.mark.physics
@settings(max_examples=200, deadline=None)
@given(alphaN=st.floats(5., 35.), gamma=angles, mu=st.floats(0., 0.5))
def test_mu_rho_roundtrip_and_locking(alphaN, gamma, mu):
    g = WormGear(alphaN=deg(alphaN), gamma=deg(gamma), r1=0.02, r2=0.1, kV=1e8, dV=0., mu=mu)
    assert g.Replace(rho=g.rho).mu == pytest.approx(mu, rel=1e-12, abs=1e-15)
    # self-locking iff gamma < rho iff the wheel-driving efficiency is negative (up to the boundary)
    if abs(g.gamma - g.rho) > 1e-9:
        assert g.selfLocking == (g.efficiencyWheelDriving < 0) == (g.Coefficients(-1)[0] < 0)


@pytest.mark.messages
def test_error_message_lists_unit_and_value():
    with pytest.raises(ValueError) as err:
        WormGear(**{**REEL, 'r2': -2.}, rho=deg(8))
    msg = str(err.value)
    assert re.search(r"WormGear", msg) and "'r2'" in msg and '> 0 m' in msg and 'got -2 m' in msg
