"""Linear stability with speed-dependent friction: eq. (16) extended in place, the Exudyn
linearization and a finite-difference Jacobian of the nonlinear contact law agree; self-locking verdicts."""
import dataclasses
import math

import numpy as np
import pytest

from exudyn_worm.model.contact import ContactOptions, MeshContact
from exudyn_worm.model.friction import MATH_OPS
from exudyn_worm.model.friction import StribeckFriction, TableFriction
from exudyn_worm.analysis.stability.linearization import ExudynStabilityAnalysis, LinearStabilityOfDrive
from exudyn_worm.drive.presets import ElasticDriveFromParameters, GetPreset
from exudyn_worm.model.selflocking import GREY_ZONE, Rating, SelfLocking
from exudyn_worm.model.stability import (AnalyzeStability, CharacteristicCoefficients, EigenvaluesFromPolynomial,
                                         EigenvaluesFromStateMatrix, FirstCriterionLimit, LinearMatrices,
                                         OperatingPoint, OperatingPointAt, OperatingPointFromParameters,
                                         PolynomialCoefficients)
from exudyn_worm.drive.wholedrive import ResolveDrive
import exudyn_worm.analysis.simulation.reelchanger as rc

P3 = GetPreset('reel-P3')
DRIVE = ElasticDriveFromParameters(P3)
V0 = DRIVE.gear.SlidingSpeed(P3['motorSpeed'])


def StribeckThrough(mu0, muStatic, stribeckVelocity, v0=V0):
    """A Stribeck law with mu(v0) = mu0: the kinetic mu solves mu + (muStatic - mu) exp(-(v0/vS)^2) = mu0."""
    e = math.exp(-(v0 / stribeckVelocity)**2)
    return StribeckFriction((mu0 - muStatic * e) / (1 - e), muStatic, stribeckVelocity)


def Stribeck(drive=DRIVE, law=None):
    law = law or StribeckThrough(0.132, 0.2, 0.9)
    return drive.Replace(gear=drive.gear.Replace(mu=getattr(law, 'mu', drive.gear.mu), friction=law))


def test_constant_mu_at_its_operating_point_is_bit_identical():
    op = OperatingPointFromParameters(P3, DRIVE.gear)
    assert op.dmuDv == 0. and op.mu == DRIVE.gear.mu
    for S in (1, -1):
        assert np.array_equal(CharacteristicCoefficients(DRIVE, S, op), CharacteristicCoefficients(DRIVE, S))
    a, b = AnalyzeStability(DRIVE), AnalyzeStability(DRIVE, op)
    assert a.fuesgenLimit == b.fuesgenLimit and a.firstCriterionLimit == b.firstCriterionLimit


def test_operating_point_of_steady_lowering():
    drive = Stribeck()
    op = OperatingPointFromParameters(P3, drive.gear)
    g = drive.gear
    assert op.slidingSpeed == pytest.approx(g.r1 * P3['motorSpeed'] / math.cos(g.gamma), rel=1e-15)
    assert op.mu == pytest.approx(0.132, rel=1e-12) and op.dmuDv == g.friction.Slope(op.slidingSpeed) < 0
    c4 = g.r2 * (math.cos(g.alphaN) * math.cos(g.gamma) + op.mu * math.sin(g.gamma))      # S = -1
    assert op.normalForce == pytest.approx(P3['loadMass'] * 9.81 * P3['leverArm'] / c4, rel=1e-12)
    assert OperatingPointFromParameters({k: v for k, v in P3.items() if k != 'loadMass'}, g) is None
    assert op.ToDict() == {'slidingSpeed': op.slidingSpeed, 'mu': op.mu, 'dmuDv': op.dmuDv,
                           'normalForce': op.normalForce, 'S': -1}


def test_polynomial_equals_state_matrix_with_slope():
    drive = Stribeck()
    op = OperatingPointFromParameters(P3, drive.gear)
    for S in (1, -1):
        np.testing.assert_allclose(EigenvaluesFromPolynomial(CharacteristicCoefficients(drive, S, op)),
                                   EigenvaluesFromStateMatrix(drive, S, op), rtol=1e-9)
        grid = PolynomialCoefficients(drive.gear, S, np.array([drive.J1, 2 * drive.J1]), drive.J2, drive.kT,
                                      drive.dT, operatingPoint=op)
        np.testing.assert_allclose(grid[:, 0], CharacteristicCoefficients(drive, S, op), rtol=1e-15)


def _MeshJacobian(gear, S, op):
    """-d(worm, wheel torque)/d(phi1, phi2) and /d(omega1, omega2) of the nonlinear law, by central differences,
    in the steady state of op on flank sigma = S with the worm turning forward (S = sigma sign(phi1'))."""
    omega = op.slidingSpeed * math.cos(gear.gamma) / gear.r1
    x0 = np.array([S * op.normalForce / (gear.kV * gear.normalLever), 0., omega, omega / gear.ratio])
    options = ContactOptions()           # the full law: S from eq. (8), regularized sf, the mesh cannot pull

    def Torques(x):
        state = MeshContact(gear, *x, options, MATH_OPS)
        return np.array([state.wormTorque, state.wheelTorque])
    J = np.zeros((2, 4))
    for j in range(4):
        h = 1e-6 * max(abs(x0[j]), 1e-3)
        e = np.zeros(4)
        e[j] = h
        J[:, j] = (Torques(x0 + e) - Torques(x0 - e)) / (2 * h)
    return -J[:, :2], -J[:, 2:]


@pytest.mark.parametrize('S', [1, -1])
def test_extended_damping_matches_the_nonlinear_contact_law(S):
    for law in (StribeckThrough(0.132, 0.2, 0.9), TableFriction([(0., 0.15), (0.5, 0.12), (1.5, 0.06)])):
        drive = Stribeck(law=law)
        op = OperatingPointFromParameters(P3, drive.gear)
        M, D, K = LinearMatrices(drive, S, op)
        Kmesh, Dmesh = _MeshJacobian(drive.gear, S, op)
        np.testing.assert_allclose(Kmesh, K - np.diag([drive.kT, 0.]), rtol=1e-6)
        np.testing.assert_allclose(Dmesh, D - np.diag([drive.dT, 0.]), rtol=1e-6)
        assert abs(op.dmuDv) > 0.01                                   # the slope matters here


@pytest.mark.parametrize('useSymbolic', [True, False])
def test_exudyn_linearization_agrees_with_extended_equation_16(useSymbolic):
    """The required agreement: 1e-6 relative. Eigenvalues, b2..b4 to rtol 1e-6; b1 is a difference of the damping terms
    D11/J1 and D22/J2 (it is small near the stability boundary), so it is compared relative to the size of those
    terms: Exudyn differentiates the connector by forward differences (relative step 1e-7), whose truncation error
    on the curved mu(v) is about 4e-8 N*m*s/rad on D11 here."""
    drive = Stribeck()
    op = OperatingPointFromParameters(P3, drive.gear)
    analytical, exudyn = AnalyzeStability(drive, op), ExudynStabilityAnalysis(drive, useSymbolic, op)
    assert exudyn.operatingPoint == op
    for S in (1, -1):
        a, e = analytical.contact[S], exudyn.contact[S]
        np.testing.assert_allclose(e.eigenvalues, a.eigenvalues, rtol=1e-6, atol=0)
        np.testing.assert_allclose(e.b[1:], a.b[1:], rtol=1e-6)
        M, D, K = LinearMatrices(drive, S, op)
        scale = abs(D[0, 0]) / drive.J1 + abs(D[1, 1]) / drive.J2
        assert abs(e.b[0] - a.b[0]) <= 1e-6 * scale
        assert e.stable == a.stable


def test_reel_p3_with_a_falling_friction_through_the_same_mu():
    """The claim, checked: reel-P3 is stable with constant mu = 0.132; with a Stribeck law through 0.132 at
    the operating speed it is unstable if the slope is steep enough (muStatic 0.2, stribeckVelocity 0.9 m/s), and
    stays stable with a gentle one (muStatic 0.15)."""
    assert AnalyzeStability(DRIVE, OperatingPointFromParameters(P3, DRIVE.gear)).stable
    steep = Stribeck(law=StribeckThrough(0.132, 0.2, 0.9))
    steepPoint = OperatingPointFromParameters(P3, steep.gear)
    analysis = AnalyzeStability(steep, steepPoint)
    assert not analysis.contact[-1].stable and analysis.contact[-1].maxRealPart > 1.
    gentle = Stribeck(law=StribeckThrough(0.132, 0.15, 0.9))
    assert AnalyzeStability(gentle, OperatingPointFromParameters(P3, gentle.gear)).stable
    # load and speed matter now: the same gear at a tenth of the load (normal force) is stable again
    light = OperatingPointAt(steep.gear, P3['motorSpeed'], 0.1 * P3['loadMass'] * 9.81 * P3['leverArm'])
    assert AnalyzeStability(steep, light).stable


def test_json_has_the_operating_point_and_the_verdicts():
    drive = Stribeck()
    data = AnalyzeStability(drive, OperatingPointFromParameters(P3, drive.gear)).ToDict()
    assert set(data['operatingPoint']) == {'slidingSpeed', 'mu', 'dmuDv', 'normalForce', 'S'}
    assert data['friction']['frictionLaw'] == 'stribeck'
    assert data['selfLockingVerdict']['static']['mu'] == 0.2
    assert AnalyzeStability(DRIVE).ToDict()['operatingPoint'] is None


def test_self_locking_verdicts():
    gear = DRIVE.gear                                      # gamma 5.32 deg < rho 8 deg
    verdict = SelfLocking(gear)
    assert verdict.static.selfLocking and verdict.dynamic.selfLocking and not verdict.dangerous
    assert verdict.static.efficiencyWormDriving == pytest.approx(math.tan(gear.gamma) / math.tan(gear.gamma + gear.rho))
    # the Stribeck gear of the hold test: mu 0.05, muStatic 0.15, 0.1 m/s: holds at rest, runs away at lowering speed
    law = StribeckFriction(0.05, 0.15, 0.1)
    stribeck = gear.Replace(mu=0.05, friction=law)
    verdict = SelfLocking(stribeck, stribeck.SlidingSpeed(P3['motorSpeed']))
    assert verdict.static.selfLocking and not verdict.dynamic.selfLocking and verdict.dangerous
    assert verdict.dynamic.mu == pytest.approx(0.05, abs=1e-12) and verdict.dynamic.rating == 'not self-locking'
    assert SelfLocking(stribeck).dynamic is None                       # speed-dependent law, no speed given
    assert gear.Replace(mu=0.03).muStatic == 0.03 and not SelfLocking(gear.Replace(mu=0.03)).static.selfLocking
    # grey zone: the mu at which the worm-driving efficiency is 0.5 is rated uncertain
    rho = math.atan(math.tan(gear.gamma) / 0.5) - gear.gamma
    state = SelfLocking(gear.Replace(rho=rho)).static
    assert state.efficiencyWormDriving == pytest.approx(0.5) and state.rating == 'uncertain'
    assert GREY_ZONE == (0.45, 0.55) and Rating(0.44) == 'self-locking' and Rating(0.56) == 'not self-locking'


def test_operating_point_rejects_bad_input():
    with pytest.raises(ValueError, match=r"OperatingPoint: 'normalForce' must be >= 0 N, got -1 N"):
        OperatingPoint(1., 0.1, -0.01, -1.)
    with pytest.raises(ValueError, match=r"OperatingPointAt: 'loadTorque' must be >= 0 N\*m, got -5 N\*m"):
        OperatingPointAt(DRIVE.gear, 10., -5.)
    with pytest.raises(ValueError, match=r"SelfLocking: 'slidingSpeed' must be >= 0 m/s, got -1 m/s"):
        SelfLocking(DRIVE.gear, -1.)
    with pytest.raises(TypeError, match=r"AnalyzeStability: 'operatingPoint' must be an OperatingPoint"):
        AnalyzeStability(DRIVE, {'mu': 0.1})


def _LoweringOscillation(monkeypatch, law):
    """J2 max|phi2''| (N*m) per half second of the reel-P3 simulation, the connector using ``law``."""
    drive = ResolveDrive(parameters=P3)
    if law is not None:                     # the law given as an object: the drive's core carries it to the connector
        drive = dataclasses.replace(drive, elastic=Stribeck(drive.elastic, law), _cache={})
    result = rc.SimulateReelChanger(drive)
    t, alpha2 = result.time, result.series['alpha2']
    return np.array([P3['J2'] * np.max(np.abs(alpha2[(t >= a) & (t < a + 0.5)])) for a in np.arange(0., 8., 0.5)])


def test_simulation_grows_where_the_linear_analysis_says_unstable(monkeypatch):
    """reel-P3 lowers from t = 2 s to 6 s (S = -1), under full load near t = 4 s. With constant mu the oscillation
    left by the load reversal decays; with the steep Stribeck law (linearly unstable at full load, growth rate
    3.45 1/s, i.e. a factor 5.6 per 0.5 s) it grows while the load is high and decays again as it falls."""
    constant = _LoweringOscillation(monkeypatch, None)
    steep = _LoweringOscillation(monkeypatch, StribeckThrough(0.132, 0.2, 0.9))
    assert constant[8] < constant[7] < constant[6]                   # 3-4.5 s: decaying
    assert steep[8] > 3 * steep[7] > 9 * steep[6]                    # 3-4.5 s: growing, at more than 2.2 1/s
    assert steep[11] < steep[10]                                      # 5-6 s: the load falls, it decays again


def test_whole_drive_linearization_at_the_operating_point():
    """LinearStabilityOfDrive (the whole-drive path of `stability`) linearizes a speed-dependent law at the
    operating point: for the two-mass drive it equals the extended eq. (16)."""
    law = StribeckThrough(0.132, 0.2, 0.9)
    whole = ResolveDrive('reel-P3').Replace(frictionLaw='stribeck', mu=law.mu, muStatic=law.muStatic,
                                            stribeckVelocity=law.stribeckVelocity)
    linear = LinearStabilityOfDrive(whole)
    drive = whole.elastic
    op = OperatingPointFromParameters(P3, drive.gear)
    assert linear.operatingPoint == op and linear.ToDict()['operatingPoint'] == op.ToDict()
    analytical = AnalyzeStability(drive, op)
    for S in (1, -1):
        np.testing.assert_allclose(linear.State(S).eigenvalues, analytical.contact[S].eigenvalues, rtol=1e-6)
        assert linear.State(S).stable == analytical.contact[S].stable


def test_first_criterion_limit_includes_the_slope():
    """(20) with the slope: at J1/J2 = FirstCriterionLimit the b1 of S = -1 vanishes."""
    drive = Stribeck()
    op = OperatingPointFromParameters(P3, drive.gear)
    limit = FirstCriterionLimit(drive, op)
    assert limit != FirstCriterionLimit(drive)
    b1 = CharacteristicCoefficients(drive.Replace(J1=limit * drive.J2), -1, op)[0]
    D = LinearMatrices(drive.Replace(J1=limit * drive.J2), -1, op)[1]
    assert abs(b1) < 1e-12 * (abs(D[0, 0]) / (limit * drive.J2) + abs(D[1, 1]) / drive.J2)
