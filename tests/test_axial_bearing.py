"""The worm's axial bearing: contact-law kinematics, default off, builder, equilibrium start."""
import math
import os

import exudyn as exu
import numpy as np
import pytest

from exudyn_worm.drive.config import ParseSetOption
from exudyn_worm.model.drive import AxialBearing
from exudyn_worm.model.contact import ContactOptions, MeshContact
from exudyn_worm.model.friction import MATH_OPS, NUMPY_OPS
from exudyn_worm.drive.presets import (PARAMETER_UNITS, ApplyOverrides, AxialBearingFromParameters, ElasticDriveFromParameters,
                                 DriveSideChain, GetPreset)
from exudyn_worm.analysis.simulation.reelchanger import SimulateReelChanger
from exudyn_worm.builders.oneangle import BuildReelChanger
from exudyn_worm.drive.wholedrive import ResolveDrive

P1 = GetPreset('reel-P1')


@pytest.mark.physics
def test_contact_law_axial_displacement_acts_like_a_worm_rotation():
    """xA shifts the thread like a worm rotation xA/(r1 tan gamma): Delta s grows by cos(alphaN) cos(gamma) xA."""
    gear = ElasticDriveFromParameters(P1).gear
    xA, vA = 3e-5, -2e-3
    equivalent = 1. / (gear.r1 * math.tan(gear.gamma))        # rad per m of axial shift
    phi1, phi2, w1, w2 = 1e-4, 2e-7, 49., 0.78
    withAxial = MeshContact(gear, phi1, phi2, w1, w2, ContactOptions(), MATH_OPS, axialDisplacement=xA, axialSpeed=vA)
    rotated = MeshContact(gear, phi1 + xA * equivalent, phi2, w1 + vA * equivalent, w2, ContactOptions(), MATH_OPS)
    assert withAxial.deltaS == pytest.approx(rotated.deltaS, rel=1e-12)
    assert withAxial.normalForce == pytest.approx(rotated.normalForce, rel=1e-12)
    assert withAxial.wormTorque == pytest.approx(rotated.wormTorque, rel=1e-12)
    assert withAxial.deltaPhi == pytest.approx(phi1 - gear.ratio * phi2, rel=1e-15)   # rotations only
    assert gear.axialLever == pytest.approx(gear.normalLever * equivalent, rel=1e-14)
    # the worm takes the reaction to the wheel's tangential force
    assert withAxial.axialForce == pytest.approx(-withAxial.wheelTorque / gear.r2, rel=1e-15)


@pytest.mark.physics
def test_axial_force_is_the_spring_energy_gradient_without_friction():
    """rho = 0: the axial force is -dU/dxA of the mesh spring energy U = kV Delta s^2 / 2."""
    gear = ElasticDriveFromParameters(ApplyOverrides(P1, {'mu': 0.})).gear
    xA = np.linspace(-1e-5, 1e-5, 7)
    state = MeshContact(gear, 0., 0., 0., 0., ContactOptions(dampingCanPull=True), NUMPY_OPS,
                        axialDisplacement=xA, axialSpeed=0.)
    np.testing.assert_allclose(state.axialForce, -gear.kV * gear.axialLever**2 * xA, rtol=1e-12)


@pytest.mark.physics
def test_contact_law_without_axial_arguments_is_unchanged():
    gear = ElasticDriveFromParameters(ApplyOverrides(P1, {'backlash': 1e-4})).gear
    args = (np.linspace(-1e-3, 1e-3, 11), 1e-6, np.linspace(-1, 1, 11), 0.01)
    plain = MeshContact(gear, *args, ContactOptions(), NUMPY_OPS)
    zero = MeshContact(gear, *args, ContactOptions(), NUMPY_OPS, axialDisplacement=0., axialSpeed=0.)
    for name in ('deltaS', 'normalForce', 'S', 'wormTorque', 'wheelTorque'):
        np.testing.assert_array_equal(getattr(plain, name), getattr(zero, name))


@pytest.mark.physics
def test_default_off_keeps_every_result_bit_identical(tmp_path, monkeypatch):
    """Absent keys and kA = 0 build the same two-mass system and give bit-identical P1 series (chatter run)."""
    monkeypatch.chdir(tmp_path)
    model = BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=P1))
    assert model.axialBearing is None and model.chain == () and model.connector.axialNodeNumber is None
    base = SimulateReelChanger(ResolveDrive(parameters=P1))
    off = SimulateReelChanger(ResolveDrive(parameters=ApplyOverrides(P1, {'kA': 0., 'dA': 1e4, 'mA': 5.})))
    assert np.max(np.abs(base.series['alpha2'])) > 50          # P1 chatters: a meaningful comparison
    assert sorted(off.series) == sorted(base.series)
    for key, values in base.series.items():
        np.testing.assert_array_equal(off.series[key], values, err_msg=key)
    assert os.listdir(tmp_path) == []


@pytest.mark.physics
def test_stiff_axial_bearing_converges_to_the_rigid_worm():
    peaks = {}
    for kA in (None, 1e10, 1e11):
        p = P1 if kA is None else ApplyOverrides(P1, {'kA': kA, 'dA': 0., 'mA': 5.})
        peaks[kA] = np.max(np.abs(SimulateReelChanger(ResolveDrive(parameters=p)).series['alpha2']))
    error10, error11 = (abs(peaks[k] / peaks[None] - 1) for k in (1e10, 1e11))
    assert error11 < 0.01 and error11 < error10 / 3


@pytest.mark.physics
@pytest.mark.parametrize('useSymbolic', [True, False])
def test_axial_bearing_and_chain_start_in_equilibrium(useSymbolic):
    p = ApplyOverrides(P1, {'kA': 5e8, 'dA': 1e4, 'mA': 5., 'J4': 0.05, 'k4': 2e4, 'd4': 1., 'J5': 0.02, 'k5': 1e5})
    r = SimulateReelChanger(ResolveDrive(parameters=p), endTime=0.2, useSymbolic=useSymbolic)
    assert np.max(np.abs(r.series['alpha2'])) < 0.01
    assert np.max(np.abs(r.series['alpha1'])) < 1. and np.max(np.abs(r.series['alpha4'])) < 1.
    # kA xA carries the mesh's axial force (lifting at t = 0: the load pushes the worm to -xA)
    assert r.series['xA'][0] < 0
    np.testing.assert_allclose(5e8 * r.series['xA'][:5], r.series['axialForce'][:5], rtol=1e-6)
    assert r.series['driveTorque'][0] == pytest.approx(r.series['wormTorque'][0], rel=1e-6)   # same as two masses


@pytest.mark.physics
def test_symbolic_and_python_agree_with_axial_bearing():
    p = ApplyOverrides(P1, {'kA': 1e9, 'dA': 1e4, 'mA': 5., 'backlash': 0.25e-3})
    fast, slow = (SimulateReelChanger(ResolveDrive(parameters=p), endTime=2.6, useSymbolic=s) for s in (True, False))
    scale = np.max(np.abs(fast.series['alpha2']))
    assert scale > 10
    np.testing.assert_allclose(slow.series['alpha2'], fast.series['alpha2'], rtol=0, atol=1e-6 * scale)
    np.testing.assert_allclose(slow.series['xA'], fast.series['xA'], rtol=0,
                               atol=1e-6 * np.max(np.abs(fast.series['xA'])))


@pytest.mark.messages
def test_parameter_keys_and_their_errors():
    assert all(k in PARAMETER_UNITS for k in ('kA', 'dA', 'mA', 'J4', 'k4', 'd4', 'J5', 'k5', 'd17'))
    assert 'J3' not in PARAMETER_UNITS and 'k0' not in PARAMETER_UNITS
    assert PARAMETER_UNITS['J12'] == 'kg*m^2' and PARAMETER_UNITS['kA'] == 'N/m'
    assert ParseSetOption('J5=0.2 kg*m^2') == ('J5', pytest.approx(0.2))
    assert ParseSetOption('kA=500 N/um') == ('kA', pytest.approx(5e8))
    assert ApplyOverrides(P1, {'J5': 1.})['J5'] == 1.
    assert AxialBearingFromParameters(P1) is None
    assert AxialBearingFromParameters({'kA': 0., 'mA': 1.}) is None
    assert AxialBearingFromParameters({'kA': 1e8, 'mA': 2.}) == AxialBearing(1e8, 0., 2.)
    assert DriveSideChain(P1) == []
    assert DriveSideChain({'J4': 1., 'k4': 2., 'J5': 3., 'k5': 4., 'd5': 0.5}) == [(1., 2., 0.), (3., 4., 0.5)]
    with pytest.raises(ValueError, match="'kA' = 1e\\+08 N/m > 0 needs the worm's axially moving mass 'mA'"):
        AxialBearingFromParameters({'kA': 1e8})
    with pytest.raises(ValueError, match="AxialBearing: 'mass' must be > 0 kg, got 0"):
        AxialBearingFromParameters({'kA': 1e8, 'mA': 0.})
    with pytest.raises(ValueError, match="missing 'J4'"):
        DriveSideChain({'J5': 1., 'k5': 1.})
    with pytest.raises(ValueError, match="'J4' needs the stiffness 'k4'"):
        DriveSideChain({'J4': 1.})
    with pytest.raises(ValueError, match="DriveSideChain: 'k4' must be > 0 N\\*m/rad, got -1"):
        DriveSideChain({'J4': 1., 'k4': -1.})
