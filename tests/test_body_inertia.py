"""The 3D model's bodies have their own polar and tilt inertia (BodyInertiaTensors): from the drive's keys or a
cylinder's shape; the tilt inertia is required on elastic bearings and enters the tilt modes."""
import math

import exudyn as exu
import numpy as np
import pytest

from exudyn_worm.analysis.simulation.reelchanger import SolverSettings
from exudyn_worm.analysis.stability.linearization import AnalyzeLinearStability, LinearizationModel
from exudyn_worm.builders.oneangle import BuildReelChanger
from exudyn_worm.builders.rigidbody import TURN, BodyInertiaTensors, BuildRigidBodyReelChanger
from exudyn_worm.drive.presets import GetPreset
from exudyn_worm.drive.wholedrive import ResolveDrive
from exudyn_worm.items.bearings import ShaftBearings
from exudyn_worm.model.bodies import BodyInertia, CylinderInertia

pytest.importorskip('exudyn')
P1 = GetPreset('reel-P1')
DRIVE_3D = 'examples/drives/reel-3d.toml'


@pytest.mark.physics
def test_cylinder_inertia_is_the_closed_form():
    """Hollow cylinder: polar m (ro^2 + ri^2) / 2, tilt m (3 (ro^2 + ri^2) + L^2) / 12 about the centre; a thin
    disc reaches the perpendicular-axis bound tilt = polar / 2."""
    body = CylinderInertia(12., 0.2, 0.3, innerRadius=0.1)
    assert (body.polar, body.tilt) == pytest.approx((12. * 0.05 / 2., 12. * (3. * 0.05 + 0.09) / 12.), rel=1e-14)
    disc = CylinderInertia(1., 0.5, 1e-9)
    assert disc.tilt == pytest.approx(disc.polar / 2., rel=1e-12)


@pytest.mark.messages
def test_a_tilt_inertia_below_half_the_polar_one_is_refused():
    with pytest.raises(ValueError, match=r"BodyInertia: 'bodyTiltInertia' must be >= half the body's polar inertia "
                                         r"\(bodyPolarInertia: 1 kg\*m\^2\).*got 0.4 kg\*m\^2"):
        BodyInertia(mass=1., polar=1., tilt=0.4)


def test_the_tensors_are_the_bodies_own_and_the_rest_of_the_shaft_turns_without_tilting():
    drive = ResolveDrive(config=DRIVE_3D)
    tensors = BodyInertiaTensors(drive)
    for body, J in (('worm', drive.elastic.J1), ('wheel', drive.elastic.J2)):
        own = getattr(drive.shaftSupports, body + 'Inertia')
        np.testing.assert_array_equal(tensors[body].tensor, np.diag([own.tilt, own.tilt, own.polar]))
        assert tensors[body].mass == own.mass and tensors[body].tiltGiven
        assert tensors[body].shaftInertia == pytest.approx(J - own.polar, rel=1e-14)
    joints = BodyInertiaTensors(ResolveDrive(parameters=P1))        # ideal joints: the joint holds the tilt
    assert not joints['wheel'].tiltGiven and joints['wheel'].shaftInertia == 0.
    np.testing.assert_array_equal(np.diag(joints['wheel'].tensor), [16.5, 16.5, 33.])


@pytest.mark.messages
def test_the_builder_refuses_elastic_bearings_without_a_tilt_inertia():
    with pytest.raises(ValueError, match=r"BuildRigidBodyReelChanger: the wheel on elastic bearings needs its tilt "
                                         r"inertia: give wheelTiltInertia"):
        BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=P1),
                                  wheelBearings=ShaftBearings(1e9, 1e9, span=0.05))


def _Modes(parameters, S=-1):
    mbs = LinearizationModel(ResolveDrive(parameters=parameters)).mbs
    return AnalyzeLinearStability(mbs).State(S).modes


@pytest.mark.physics
def test_the_wheel_tilts_on_its_bearings_with_its_tilt_inertia():
    """Undamped wheel bearings, 0.15 m apart: the wheel's tilt about the centre line (its node's first angle) does
    not move the pitch point, so its mode is the bearings' tilt stiffness k s^2 / 2 against the tilt inertia alone:
    f = sqrt(k s^2 / (2 tilt)) / (2 pi)."""
    k, s = 1e9, 0.15
    for tilt in (0.12, 1.):
        modes = _Modes({**P1, 'wheelMass': 30., 'wheelRadialStiffness': k, 'wheelAxialStiffness': k,
                        'wheelBearingSpan': s, 'wheelTiltInertia': tilt, 'wheelPolarInertia': 0.2})
        # the mode with most of its energy in that angle; the tilt about the other diameter (which moves the pitch
        # point, so the mesh stiffens it a little) lies within 1 Hz and mixes in a few percent: 1e-5
        tilting = max(modes, key=lambda m: m.energyShare.get('Node:wheel[3]', 0.))
        assert tilting.energyShare['Node:wheel[3]'] > 0.9
        assert tilting.frequencyHz == pytest.approx(math.sqrt(k * s * s / (2. * tilt)) / (2. * math.pi), rel=1e-5)


@pytest.mark.physics
def test_what_turns_without_tilting_keeps_the_shafts_inertia():
    """Stiff bearings (1e13 N/m) and bodies far lighter in polar inertia than their shafts: the rest of J1, J2 on the
    turns gives the torsional modes of the one-angle model with the whole J1, J2 (1e-3)."""
    stiff = {f'{b}{k}': 1e13 for b in ('worm', 'wheel') for k in ('RadialStiffness', 'AxialStiffness')}
    stiff.update(wormMass=5., wormRadius=0.021, wormLength=0.46, wheelMass=30., wheelRadius=0.11, wheelLength=0.1,
                 wormBearingSpan=0.5, wheelBearingSpan=0.5)
    rigid = [m for m in _Modes({**P1, **stiff}) if m.frequencyHz < 200.]
    reference = AnalyzeLinearStability(BuildReelChanger(exu.SystemContainer().AddSystem(),
                                                        ResolveDrive(parameters=P1)).mbs).State(-1).modes
    got = sorted((m.eigenvalue for m in rigid if m.eigenvalue.imag > 0), key=lambda z: z.imag)
    expected = sorted((m.eigenvalue for m in reference if m.eigenvalue.imag > 0), key=lambda z: z.imag)
    np.testing.assert_allclose(got, expected, rtol=1e-3)


#: P1 with the reel (32.8 of its 33 kg*m^2) behind a load shaft of 2e5 N*m/rad: the wheel's own 0.2 kg*m^2 left as J2,
#: the mesh damping P1's (dV from D_V with J2 = 33 kg*m^2) given as such, so that the mesh is P1's
REEL_CHAIN = {'J2': 0.2, 'JL1': 32.8, 'kL1': 2e5, 'dL1': 10., 'dV': ResolveDrive('reel-P1').elastic.gear.dV}


def _WithChain(parameters):
    return {k: v for k, v in {**parameters, **REEL_CHAIN}.items() if k != 'DV'}


@pytest.mark.physics
def test_the_reel_as_a_load_side_inertia_gives_the_one_angle_chains_modes():
    """The reel as its own inertia behind a load shaft ([[loadSide]]) on the 3D model: with stiff bearings (1e13 N/m)
    the torsional modes are those of the one-angle model with the same chain (1e-3)."""
    stiff = {f'{b}{k}': 1e13 for b in ('worm', 'wheel') for k in ('RadialStiffness', 'AxialStiffness')}
    stiff.update(wormMass=5., wormRadius=0.021, wormLength=0.46, wheelMass=30., wheelTiltInertia=0.12,
                 wheelPolarInertia=0.2, wormBearingSpan=0.5, wheelBearingSpan=0.5)
    rigid = [m for m in _Modes(_WithChain({**P1, **stiff})) if m.frequencyHz < 200.]
    reference = AnalyzeLinearStability(BuildReelChanger(exu.SystemContainer().AddSystem(),
                                                        ResolveDrive(parameters=_WithChain(P1))).mbs).State(-1).modes
    got = sorted((m.eigenvalue for m in rigid if m.eigenvalue.imag > 0), key=lambda z: z.imag)
    expected = sorted((m.eigenvalue for m in reference if m.eigenvalue.imag > 0 and m.frequencyHz < 200.),
                      key=lambda z: z.imag)
    assert len(got) == len(expected) == 2
    np.testing.assert_allclose(got, expected, rtol=1e-3)


def test_the_3d_model_with_a_load_side_chain_starts_in_equilibrium():
    """reel-3d.toml with the reel behind a load shaft: the run starts in the static equilibrium of the bearings, the
    mesh and the load shaft (the chain's rotor twisted onto the wheel's deflected pose): the wheel does not
    accelerate (below 1 rad/s^2 over 0.1 s; with the one-angle model's twist alone it rang at about 500 rad/s^2)."""
    drive = ResolveDrive(config=DRIVE_3D, sets=[f'{k}={v}' for k, v in REEL_CHAIN.items()])
    model = BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), drive)
    assert len(model.loadRotors) == 1
    model.connector.AddSensors(model.mbs)
    model.mbs.Assemble()
    ss, solverType = SolverSettings(0.1, 1e-4)
    model.mbs.SolveDynamic(ss, solverType=solverType)
    omega2 = np.asarray(model.mbs.GetSensorStoredData(model.connector.sensors['wheelVelocities']))[:, 1 + TURN]
    assert np.max(np.abs(np.diff(omega2))) / 1e-4 < 1.
