"""A law written with a Python `if` or math function records as a constant: the builders refuse it at creation."""
import math

import exudyn as exu
import numpy as np
import pytest

import exudyn_worm as ew


def _System():
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    return SC, mbs, ew.CreateRotor(mbs, 1.)


@pytest.mark.messages
@pytest.mark.parametrize('law', [
    lambda phi, om, t, ops: 1. if t < 0.5 else 0.,                 # a Python if on the time
    lambda phi, om, t, ops: 10. * math.cos(phi),
    lambda phi, om, t, ops: min(10. * t, 50.),
    lambda phi, om, t, ops: -2. * om if om > 0 else 0.,
], ids=['if-on-t', 'math.cos', 'builtin-min', 'if-on-omega'])
def test_rotor_torque_recorded_as_constant_is_refused(law):
    SC, mbs, rotor = _System()
    objects = mbs.systemData.NumberOfObjects()
    with pytest.raises(ValueError, match=r"CreateRotorTorque: the law gives .* when recorded as a symbolic \(C\+\+\) "
                                         r"user function but .* in Python at t = .*Likely cause: a Python 'if'"):
        ew.CreateRotorTorque(mbs, rotor, law)
    assert mbs.systemData.NumberOfObjects() == objects                  # nothing added
    ew.CreateRotorTorque(mbs, rotor, law, useSymbolic=False)            # plain Python is exact


@pytest.mark.parametrize('law', [
    lambda phi, om, t, ops: ops.where(t < 0.5, 1., 0.),
    lambda phi, om, t, ops: 10. * ops.cos(phi),
    lambda phi, om, t, ops: ops.min(10. * t, 50.),
    lambda phi, om, t, ops: 3.,                                        # a constant is a constant
    ew.GravityLeverTorque(mass=175., leverArm=1.2),
    ew.CoulombViscousFriction(coulombTorque=2., viscous=0.1),
    ew.LinearMotorCharacteristic(stallTorque=100., noLoadSpeed=50.),
])
def test_correct_laws_pass(law):
    SC, mbs, rotor = _System()
    ew.CreateRotorTorque(mbs, rotor, law)


@pytest.mark.messages
def test_numpy_on_symbolic_arguments_is_a_clear_type_error():
    SC, mbs, rotor = _System()
    with pytest.raises(TypeError, match=r"CreateRotorTorque: the law cannot be recorded .* write it with the "
                                        r"functions of 'ops'"):
        ew.CreateRotorTorque(mbs, rotor, lambda phi, om, t, ops: np.cos(phi))


class _IfProfile:
    """A motor profile written with a Python if: stops at t = 1 s."""

    def AngleAndSpeed(self, t, ops):
        return (10. * t, 10.) if t < 1. else (10., 0.)


@pytest.mark.messages
def test_prescribed_rotation_recorded_as_constant_is_refused():
    SC, mbs, rotor = _System()
    nodes = mbs.systemData.NumberOfNodes()
    with pytest.raises(ValueError, match=r"CreatePrescribedRotation: the law gives .* in Python at t = "):
        ew.CreatePrescribedRotation(mbs, rotor, _IfProfile())
    assert mbs.systemData.NumberOfNodes() == nodes
    ew.CreatePrescribedRotation(mbs, rotor, ew.StartStopProfile(speed=49.48, rampTime=0.5))


@pytest.mark.messages
def test_worm_gear_on_one_node_is_refused():
    SC, mbs, rotor = _System()
    drive = ew.ElasticDriveFromParameters(ew.GetPreset('reel-P1'))
    n = rotor['nodeNumber']
    with pytest.raises(ValueError, match=r"CreateWormGear: worm, wheel \(and axial\) nodes must be different nodes, "
                                         r"got nodeNumbers = \[0, 0\]"):
        ew.CreateWormGear(mbs, [n, n], gear=drive.gear)
