"""Unit and property tests of the analytical stability model, eqs. (14)-(21)."""
import math

import numpy as np
import pytest
from hypothesis import assume, given, settings, strategies as st
from numpy.testing import assert_allclose

from exudyn_worm.model.drive import ElasticDrive, MeshDampingFromMeasure, TorsionalDampingFromMeasure
from exudyn_worm.model.gear import WormGear
from exudyn_worm.drive.presets import ApplyOverrides, ElasticDriveFromParameters, GetPreset
from exudyn_worm.model.stability import (AnalyzeStability, CharacteristicCoefficients, ContactStability,
                                   EigenvaluesFromPolynomial, EigenvaluesFromStateMatrix, FirstCriterionLimit,
                                   FuesgenLimit, HurwitzConditions, HurwitzStable, StateMatrix)
from validation.analytical import GEOMETRY_28
from validation.runner import InputRounding, ReadingInterval

# random gears of the property tests include worms larger than their wheels: warned, not wrong here
pytestmark = pytest.mark.filterwarnings('ignore::exudyn_worm.params.plausibility.ImplausibleValueWarning')

deg = math.radians


def Reel(**overrides) -> ElasticDrive:
    """Set (28) with mu = 0.132, the friction the paper's b1..b4 and (19) were computed with."""
    return ElasticDriveFromParameters(ApplyOverrides(GetPreset('reel-P1'), {'mu': 0.132, **overrides}))


def _Match(a, b):
    """Pair each element of ``a`` with its nearest unused element of ``b``; return b reordered."""
    b = list(b)
    out = []
    for z in a:
        i = int(np.argmin([abs(z - w) for w in b]))
        out.append(b.pop(i))
    return np.array(out)


# --- set (28), section 3.1 ----------------------------------------------------------------------------------

@pytest.mark.physics
def test_printed_coefficients_of_set28():
    # section 3.1: b1 = 13.615 1/s, b2 = 1.279e5, b3 = 9.004e5, b4 = 4.224e9; (19) = -2.607e10 (S = -1)
    b = CharacteristicCoefficients(Reel(), -1)
    for value, printed, half in zip(b, (13.615, 1.279e5, 9.004e5, 4.224e9), (5e-4, 50, 50, 5e5)):
        assert abs(value - printed) <= half
    # (19) = -2.607e10: half a unit of the printed digit + the propagated rounding of the printed geometry gamma,
    # r1, r2, computed by the validation's one propagation function (validation/README.md)
    parts = InputRounding(lambda q: HurwitzConditions(CharacteristicCoefficients(ElasticDriveFromParameters(q), -1))[2],
                          ApplyOverrides(GetPreset('reel-P1'), {'mu': 0.132}), GEOMETRY_28)
    lo, hi = ReadingInterval('printed', '-2.607e10', sum(parts.values()))
    assert lo <= HurwitzConditions(b)[2] <= hi
    assert b[0] > 0 and HurwitzConditions(b)[2] < 0  # (17) holds, (19) fails: unstable


@pytest.mark.physics
def test_set28_verdicts():
    a = AnalyzeStability(Reel())
    assert a.contact[+1].stable and not a.contact[-1].stable and not a.stable
    assert a.contact[-1].eigenvalues.real.max() > 0
    d = a.ToDict()
    assert d['stable'] is False and d['selfLocking'] is True and set(d['S']) == {'+1', '-1'}


@pytest.mark.physics
def test_coefficients_equal_state_matrix_polynomial():
    d = Reel()
    for S in (+1, -1):
        b = CharacteristicCoefficients(d, S)
        poly = np.real(np.poly(np.linalg.eigvals(StateMatrix(d, S))))
        assert_allclose(poly[1:], b, rtol=1e-9)


@pytest.mark.messages
def test_contact_state_must_be_pm1():
    with pytest.raises(ValueError, match=r"contact parameter 'S' must be \+1 or -1, got 0"):
        CharacteristicCoefficients(Reel(), 0)


@pytest.mark.messages
def test_analyze_requires_drive():
    with pytest.raises(TypeError, match=r"AnalyzeStability: 'drive' must be an ElasticDrive, got str"):
        AnalyzeStability('reel')


@pytest.mark.physics
def test_contact_stability_from_eigenvalues_roundtrip():
    c = AnalyzeStability(Reel()).contact[-1]
    back = ContactStability.FromEigenvalues(-1, c.eigenvalues)
    assert_allclose(back.b, c.b, rtol=1e-9)
    assert_allclose(back.eigenvalues, c.eigenvalues, rtol=1e-9)
    with pytest.raises(ValueError, match='expected 4 eigenvalues, got 2'):
        ContactStability.FromEigenvalues(-1, c.eigenvalues[:2])


@pytest.mark.physics
def test_frequencies_and_lehr_damping_definitions():
    # section 3.1: f_i = omega_i/(2 pi), D_i = delta_i/omega_i (positive for decaying modes)
    c = ContactStability.FromEigenvalues(+1, [-2.3 + 209.0j, -2.3 - 209.0j, -5.8 + 328.1j, -5.8 - 328.1j])
    assert_allclose(c.frequenciesHz, [209.0 / (2 * math.pi), 328.1 / (2 * math.pi)])
    assert_allclose(c.lehrDamping, [2.3 / 209.0, 5.8 / 328.1])
    assert c.stable


@pytest.mark.physics
def test_first_criterion_limit_is_the_b1_root():
    # eq. (20): b1(S = -1) = 0 exactly at J1/J2 = limit (dT held fixed); for set (28) the shaft damping
    # removes the first-criterion region (limit < 0, b1 > 0), so take a lightly damped shaft
    assert FirstCriterionLimit(Reel()) < 0 < CharacteristicCoefficients(Reel(), -1)[0]
    d = Reel().Replace(dT=0.01)
    limit = FirstCriterionLimit(d)
    assert limit > 0
    at = d.Replace(J1=limit * d.J2)
    assert abs(CharacteristicCoefficients(at, -1)[0]) < 1e-9 * CharacteristicCoefficients(d, -1)[0]
    assert CharacteristicCoefficients(d.Replace(J1=0.9 * limit * d.J2), -1)[0] < 0


@pytest.mark.physics
def test_fuesgen_limit_eq21():
    d = Reel()
    g = d.gear
    expected = math.tan(g.rho - g.gamma) / (g.ratio**2 * math.tan(g.gamma))
    assert FuesgenLimit(d) == pytest.approx(expected, rel=1e-12)
    # eq. (20) reduces to (21) for dT = 0
    assert FirstCriterionLimit(d.Replace(dT=0.)) == pytest.approx(expected, rel=1e-12)
    assert FirstCriterionLimit(d.Replace(dT=0.)) > FirstCriterionLimit(d)  # shaft damping shrinks the region
    assert FirstCriterionLimit(d.Replace(gear=g.Replace(dV=0.))) == -math.inf
    # a gear that is not self-locking has a negative limit: no chatter of this kind
    assert FuesgenLimit(d.Replace(gear=g.Replace(gamma=deg(12)))) < 0


# --- property tests on random valid drives -----------------------------------------------------------------

@st.composite
def Drives(draw, selfLocking=None):
    """Random valid elastic drives around the paper's ranges (Figures 3-5, sets (25) and (28))."""
    alphaN = deg(draw(st.floats(10., 30.)))
    gamma = deg(draw(st.floats(1., 20.)))
    rho = deg(draw(st.floats(1., 15.)))
    if selfLocking is not None:
        assume((gamma < rho) == selfLocking and abs(gamma - rho) > 1e-6)
    r1 = 10**draw(st.floats(-2.7, -1.3))
    u = draw(st.floats(10., 100.))
    r2 = u * r1 * math.tan(gamma)
    kV = 10**draw(st.floats(5., 9.))
    J2 = 10**draw(st.floats(-2., 2.))
    J1 = J2 * 10**draw(st.floats(-5., -1.))
    kT = kV * r1**2 * 10**draw(st.floats(-3., 1.))
    DV = draw(st.floats(1e-3, 0.1))
    DT = DV * draw(st.floats(0., 30.))
    gear = WormGear(alphaN=alphaN, gamma=gamma, r1=r1, r2=r2, kV=kV, dV=MeshDampingFromMeasure(DV, kV, r2, J2),
                    rho=rho)
    return ElasticDrive(gear, J1=J1, J2=J2, kT=kT, dT=TorsionalDampingFromMeasure(DT, kT, J1))


def _ClearOfBoundary(b, lam) -> bool:
    """False within a tiny relative margin of the stability boundary, where the two classifications may
    legitimately disagree through rounding: Re of an eigenvalue or the value of (19) near zero."""
    b1, b2, b3, b4 = b
    scale19 = abs(b1 * b2 * b3) + b1**2 * abs(b4) + b3**2
    return (np.min(np.abs(lam.real)) > 1e-7 * np.max(np.abs(lam))
            and abs(HurwitzConditions(b)[2]) > 1e-9 * scale19 and abs(b1) > 1e-9 * np.max(np.abs(lam)))


@pytest.mark.physics
@settings(max_examples=300, deadline=None)
@given(drive=Drives(), S=st.sampled_from([+1, -1]))
def test_hurwitz_equals_eigenvalue_classification(drive, S):
    b = CharacteristicCoefficients(drive, S)
    lam = EigenvaluesFromStateMatrix(drive, S)
    assume(_ClearOfBoundary(b, lam))
    assert HurwitzStable(b) == bool(np.all(lam.real < 0))
    if b[2] > 0 and b[3] > 0 and HurwitzConditions(b)[2] > 0:
        assert HurwitzConditions(b)[1] > 0  # (18) follows from (19) when b3, b4 > 0 (section 2.2)


def test_generator_covers_stable_and_unstable():
    """The random drives of the property tests contain both verdicts (else the test above is vacuous)."""
    rng = np.random.default_rng(0)
    verdicts = set()
    for _ in range(300):
        gamma, rho = deg(rng.uniform(1, 20)), deg(rng.uniform(1, 15))
        r1, u, kV, J2 = 10**rng.uniform(-2.7, -1.3), rng.uniform(10, 100), 10**rng.uniform(5, 9), 10**rng.uniform(-2, 2)
        J1, r2 = J2 * 10**rng.uniform(-5, -1), u * r1 * math.tan(gamma)
        kT, DV = kV * r1**2 * 10**rng.uniform(-3, 1), rng.uniform(1e-3, 0.1)
        gear = WormGear(alphaN=deg(20), gamma=gamma, r1=r1, r2=r2, kV=kV,
                        dV=MeshDampingFromMeasure(DV, kV, r2, J2), rho=rho)
        d = ElasticDrive(gear, J1=J1, J2=J2, kT=kT, dT=TorsionalDampingFromMeasure(DV * rng.uniform(0, 30), kT, J1))
        verdicts.add(HurwitzStable(CharacteristicCoefficients(d, -1)))
    assert verdicts == {True, False}


@pytest.mark.physics
@settings(max_examples=200, deadline=None)
@given(drive=Drives(selfLocking=False))
def test_no_first_criterion_instability_without_self_locking(drive):
    """gamma > rho: c1 > 0 for both S, so b1 > 0 -- condition (17) cannot fail (section 2.2, eq. (20))."""
    assert not drive.gear.selfLocking
    for S in (+1, -1):
        assert drive.gear.Coefficients(S)[0] > 0
        assert CharacteristicCoefficients(drive, S)[0] > 0
    assert FuesgenLimit(drive) < 0 and FirstCriterionLimit(drive) < drive.inertiaRatio


@pytest.mark.physics
@settings(max_examples=200, deadline=None)
@given(drive=Drives(selfLocking=True))
def test_self_locking_first_criterion(drive):
    """gamma < rho: b1(S = -1) < 0 exactly when J1/J2 is below the limit of (20)."""
    limit = FirstCriterionLimit(drive)
    b1 = CharacteristicCoefficients(drive, -1)[0]
    assume(abs(drive.inertiaRatio - limit) > 1e-9 * max(limit, drive.inertiaRatio))
    assert (b1 < 0) == (drive.inertiaRatio < limit)
    assert CharacteristicCoefficients(drive, +1)[0] > 0  # S = +1 is never affected


@pytest.mark.physics
@settings(max_examples=300, deadline=None)
@given(drive=Drives(), S=st.sampled_from([+1, -1]))
def test_polynomial_roots_equal_state_matrix_eigenvalues(drive, S):
    poly = EigenvaluesFromPolynomial(CharacteristicCoefficients(drive, S))
    state = EigenvaluesFromStateMatrix(drive, S)
    scale = np.max(np.abs(state))
    assert_allclose(_Match(state, poly), state, atol=1e-6 * scale, rtol=0)
