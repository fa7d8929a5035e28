"""The contact law: backlash, no pull, friction state, the linear law of eqs. (1)-(2), and backend identity."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import exudyn as exu
from exudyn_worm.model.contact import ContactOptions, MeshContact, SymbolicOps
from exudyn_worm.model.friction import MATH_OPS, NUMPY_OPS
from exudyn_worm.drive.presets import ElasticDriveFromParameters, GetPreset

GEAR = ElasticDriveFromParameters(GetPreset('reel-P1')).gear
GEAR_BACKLASH = GEAR.Replace(backlash=0.5e-3)


def _AtDeltaS(gear, deltaS, rate=0., omega1=50., options=ContactOptions()):
    """Contact state for a given normal displacement and rate (wheel at rest)."""
    omega2 = omega1 / gear.ratio          # rolling without relative motion ...
    return MeshContact(gear, deltaS / gear.normalLever, 0., omega1 + rate / gear.normalLever, omega2, options,
                       MATH_OPS)           # ... plus the relative normal rate


@pytest.mark.physics
def test_no_force_inside_backlash():
    for ds in (-0.24e-3, 0., 0.1e-3, 0.2499e-3):
        s = _AtDeltaS(GEAR_BACKLASH, ds, rate=1e-3)
        assert s.normalForce == 0 and s.wormTorque == 0 and s.wheelTorque == 0


@pytest.mark.physics
def test_elastic_force_beyond_backlash():
    s = _AtDeltaS(GEAR_BACKLASH, 0.25e-3 + 1e-5)
    assert s.normalForce == pytest.approx(GEAR.kV * 1e-5, rel=1e-9)
    s = _AtDeltaS(GEAR_BACKLASH, -0.25e-3 - 1e-5)
    assert s.normalForce == pytest.approx(-GEAR.kV * 1e-5, rel=1e-9)


@pytest.mark.physics
def test_mesh_cannot_pull_unless_asked():
    # fast separation: damping alone would make the normal force change sign
    ds, rate = 1e-6, -1.0
    assert GEAR.kV * ds + GEAR.dV * rate < 0
    assert _AtDeltaS(GEAR, ds, rate).normalForce == 0.
    pulled = _AtDeltaS(GEAR, ds, rate, options=ContactOptions(dampingCanPull=True)).normalForce
    assert pulled == pytest.approx(GEAR.kV * ds + GEAR.dV * rate, rel=1e-9)


@pytest.mark.physics
def test_friction_state_and_contact_parameter():
    opts = ContactOptions(frictionSpeed=0.05, frictionModel='regularized')
    assert _AtDeltaS(GEAR, 1e-5, omega1=1.).sf == 1. and _AtDeltaS(GEAR, 1e-5, omega1=1.).S == 1.
    assert _AtDeltaS(GEAR, -1e-5, omega1=1.).S == -1.           # wheel drives: lowering, eq. (8)
    assert _AtDeltaS(GEAR, 1e-5, omega1=-1.).S == -1.
    assert _AtDeltaS(GEAR, 1e-5, omega1=0.025, options=opts).sf == pytest.approx(0.5)
    assert _AtDeltaS(GEAR, 1e-5, omega1=0.025, options=ContactOptions(frictionSpeed=0.,
                                                                      frictionModel='regularized')).sf == 1.
    # sticking model without a state (evaluating the law): the exact Coulomb sign, whatever frictionSpeed
    assert _AtDeltaS(GEAR, 1e-5, omega1=0.025).sf == 1. and _AtDeltaS(GEAR, 1e-5, omega1=-0.025).sf == -1.


@pytest.mark.parametrize('S', [1, -1])
def test_friction_force_form_equals_equations_10_12(S):
    """The sticking model's torques (normal and friction force through their levers) are eqs. (10), (12) at S = +-1."""
    omega1 = float(S)
    a = _AtDeltaS(GEAR, 1e-5, omega1=omega1)
    b = _AtDeltaS(GEAR, 1e-5, omega1=omega1, options=ContactOptions(frictionModel='regularized'))
    assert a.wormTorque == pytest.approx(b.wormTorque, rel=1e-12)
    assert a.wheelTorque == pytest.approx(b.wheelTorque, rel=1e-12)
    assert a.frictionForce == pytest.approx(b.frictionForce, rel=1e-9)
    assert a.frictionForce == pytest.approx(GEAR.mu * S * abs(a.normalForce), rel=1e-12)


@pytest.mark.physics
@settings(max_examples=60, deadline=None)
@given(dphi=st.floats(-1e-2, 1e-2).filter(lambda x: abs(x) > 1e-9), rate=st.floats(-5, 5), S=st.sampled_from([1, -1]))
def test_linear_law_is_equations_1_and_2(dphi, rate, S):
    """With S held, no backlash and the linear law, the torques are those of eqs. (1)-(2)."""
    c1, c2, c3, c4 = GEAR.Coefficients(S)
    s = MeshContact(GEAR, dphi, 0., rate, 0., ContactOptions(fixedS=S, dampingCanPull=True), MATH_OPS)
    scale = GEAR.kV * c3 * 1e-2
    assert s.wormTorque == pytest.approx(-(GEAR.kV * c1 * dphi + GEAR.dV * c1 * rate), abs=1e-9 * scale)
    assert s.wheelTorque == pytest.approx(GEAR.kV * c3 * dphi + GEAR.dV * c3 * rate, abs=1e-9 * scale)


def _SymbolicTorques(gear, options):
    esym = exu.symbolic
    rec = esym.GetRecording()
    esym.SetRecording(True)
    try:
        v = [esym.Real(name, 0.) for name in ('phi1', 'phi2', 'omega1', 'omega2')]
        s = MeshContact(gear, *v, options, SymbolicOps())
    finally:
        esym.SetRecording(rec)
    return v, s


@pytest.mark.physics
@settings(max_examples=60, deadline=None)
@given(phi1=st.floats(-1e-2, 1e-2), phi2=st.floats(-1e-4, 1e-4), omega1=st.floats(-0.2, 0.2),
       omega2=st.floats(-1e-2, 1e-2), pull=st.booleans())
def test_backends_agree(phi1, phi2, omega1, omega2, pull):
    """Python floats, numpy arrays and the C++ symbolic expression evaluate the same law."""
    options = ContactOptions(dampingCanPull=pull)
    ref = MeshContact(GEAR_BACKLASH, phi1, phi2, omega1, omega2, options, MATH_OPS)
    arr = MeshContact(GEAR_BACKLASH, np.array([phi1]), np.array([phi2]), np.array([omega1]), np.array([omega2]),
                      options, NUMPY_OPS)
    variables, sym = _SymbolicTorques(GEAR_BACKLASH, options)
    for var, value in zip(variables, (phi1, phi2, omega1, omega2)):
        var.SetValue(value)
    scale = 1. + abs(ref.wheelTorque)
    for name in ('wormTorque', 'wheelTorque', 'normalForce', 'S', 'sf'):
        assert getattr(arr, name)[0] == pytest.approx(getattr(ref, name), abs=1e-12 * scale)
    assert sym.wormTorque.Evaluate() == pytest.approx(ref.wormTorque, abs=1e-9 * scale)
    assert sym.wheelTorque.Evaluate() == pytest.approx(ref.wheelTorque, abs=1e-9 * scale)


@pytest.mark.messages
def test_options_are_validated():
    with pytest.raises(ValueError, match="'frictionSpeed' must be >= 0 rad/s, got -1"):
        ContactOptions(frictionSpeed=-1.)
    with pytest.raises(ValueError, match="'fixedS'"):
        ContactOptions(fixedS=0)


def test_python_backend_accepts_numpy_scalars():
    s = MeshContact(GEAR, np.float64(1e-3), np.float64(0.), np.float64(50.), np.float64(50. / GEAR.ratio),
                    ContactOptions(), MATH_OPS)
    assert s.S == 1. and s.normalForce > 0
