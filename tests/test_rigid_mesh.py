"""The worm mesh between 3D rigid bodies: textbook forces, node types, reductions to the one-angle connector,
bearing statics and bad input."""
import math

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import (CoordinateSpringDamper, MarkerBodyRigid, MarkerNodeCoordinate, NodePointGround,
                                  ObjectGround, ObjectJointGeneric)
from exudyn.rigidBodyUtilities import (InertiaCylinder, RigidBodyInertia, RotationMatrixX, RotationMatrixY,
                                       RotationMatrixZ)

from exudyn_worm.analysis.simulation.reelchanger import SolverSettings
from exudyn_worm.builders.oneangle import BuildReelChanger
from exudyn_worm.builders.rigidbody import BuildRigidBodyReelChanger
from exudyn_worm.analysis.simulation.stepsize import RecommendedStepSize
from exudyn_worm.items.bearings import CreateShaftBearings, ShaftBearings, StoredBearingLoads
from exudyn_worm.items.rigidmesh import CreateRigidBodyWormGear, MeshForceComponents
from exudyn_worm.model.contact import MATH_OPS, ContactOptions, MeshContact
from exudyn_worm.drive.presets import ElasticDriveFromParameters, GetPreset
from exudyn_worm.items._rigidnodes import RIGID_NODES
from exudyn_worm.items.connector import CreateWormGear
from exudyn_worm.items.drivetrain import CreateRotor
from exudyn_worm.drive.wholedrive import ResolveDrive

exu = pytest.importorskip('exudyn')
P1 = GetPreset('reel-P1')
GEAR = ElasticDriveFromParameters(P1).gear
NODE_TYPES = ('RotationEulerParameters', 'RotationRxyz', 'RotationRotationVector')


def _Pair(nodeType='RotationRxyz', phi1=0., phi2=0., omega1=0., omega2=0., gear=GEAR, wheelSide=1., joints=True,
          wormRotation=None):
    """Worm (axis global x) and wheel (axis global z, at y = wheelSide * a) as rigid bodies of a new system."""
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    nt = getattr(exu.NodeType, nodeType)
    a = gear.r1 + gear.r2
    R0 = np.eye(3) if wormRotation is None else wormRotation       # the worm's reference rotation
    worm = mbs.CreateRigidBody(inertia=InertiaCylinder(7800., 0.1, gear.r1, axis=0), nodeType=nt,
                               referenceRotationMatrix=R0, initialRotationMatrix=RotationMatrixX(phi1),
                               initialAngularVelocity=[omega1, 0., 0.], returnDict=True)
    wheel = mbs.CreateRigidBody(inertia=InertiaCylinder(7800., 0.03, gear.r2, axis=2), nodeType=nt,
                                referencePosition=[0., wheelSide * a, 0.], initialRotationMatrix=RotationMatrixZ(phi2),
                                initialAngularVelocity=[0., 0., omega2], returnDict=True)
    if joints:
        for body, rot in ((worm, np.eye(3)), (wheel, RotationMatrixY(-np.pi / 2))):
            pos = mbs.GetNode(body['nodeNumber'])['referenceCoordinates'][:3]
            ground = mbs.AddObject(ObjectGround(referencePosition=list(pos)))
            R = np.asarray(mbs.GetNodeOutput(body['nodeNumber'], exu.OutputVariableType.RotationMatrix,
                                             configuration=exu.ConfigurationType.Reference)).reshape(3, 3)
            m0 = mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localHT=exu.HT(rotation=rot)))
            m1 = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body['bodyNumber'], localHT=exu.HT(rotation=R.T @ rot)))
            mbs.AddObject(ObjectJointGeneric(markerNumbers=[m0, m1], constrainedAxes=[1, 1, 1, 0, 1, 1]))
    return SC, mbs, worm, wheel


def _Forces(connector, mbs):
    """Generalized forces of the mesh law at the initial state, split per node."""
    q, v = connector._InitialVectors(mbs)
    Q = np.array(connector._ForceLaw(connector.options)(0., q, v, MATH_OPS))
    n = connector._kinematics.bodies[0].size
    return Q[:n], Q[n:], q


def _Moment(node, Qrot, qNode, mbs):
    """Global moment of the generalized forces on a node's rotation coordinates (Q = G^T R^T M)."""
    info = mbs.GetNode(node)
    kin = RIGID_NODES[info['nodeType']]
    theta = np.asarray(info['referenceCoordinates'], dtype=float)[3:] + np.asarray(qNode[3:])
    R = np.array(kin.rotationMatrix(list(theta), MATH_OPS))
    G = np.eye(3) if kin.velocityMap is None else np.array(kin.velocityMap(list(theta), MATH_OPS))
    tauLocal = np.linalg.lstsq(G.T, Qrot, rcond=None)[0]
    return R @ tauLocal


@pytest.mark.physics
@pytest.mark.parametrize('nodeType', NODE_TYPES)
@pytest.mark.parametrize('S', [1, -1])
def test_mesh_forces_are_the_textbook_worm_gear_forces(nodeType, S):
    """Sliding contact on the first flank: normal force W, wheel tangential W (cos aN cos g - S mu sin g), worm
    tangential W (cos aN sin g + S mu cos g), separating W sin aN, acting at the pitch point on both bodies; S = +1:
    the worm drives, S = -1: the wheel drives (power flows back)."""
    gear = ElasticDriveFromParameters({**P1, 'DV': 0.}).gear  # no mesh damping: Exudyn's initial Euler-parameter rates
    deflection = 2e-4                               # carry 5e-9 of the worm speed; Fn = kV lever deflection
    omega1 = S * 40.
    SC, mbs, worm, wheel = _Pair(nodeType, phi1=deflection, omega1=omega1, omega2=omega1 / gear.ratio, gear=gear)
    options = ContactOptions(frictionModel='regularized', frictionSpeed=1e-3)
    mesh = CreateRigidBodyWormGear(mbs, [worm, wheel], gear=gear, wormAxis=[1, 0, 0], wheelAxis=[0, 0, 1],
                                   contactOptions=options)
    state = mesh.InitialMeshState(mbs)
    W = gear.kV * gear.normalLever * deflection
    assert state.normalForce == pytest.approx(W, rel=1e-9)
    aN, g, mu = gear.alphaN, gear.gamma, gear.mu
    parts = MeshForceComponents(mesh, state)
    assert parts['wheelTangential'] == pytest.approx(W * (math.cos(aN) * math.cos(g) - S * mu * math.sin(g)), rel=1e-9)
    assert parts['wormTangential'] == pytest.approx(-W * (math.cos(aN) * math.sin(g) + S * mu * math.cos(g)), rel=1e-9)
    assert parts['wormRadial'] == pytest.approx(-W * math.sin(aN), rel=1e-9)
    assert parts['wheelRadial'] == pytest.approx(-W * math.sin(aN), rel=1e-9)
    # the worm's axial force is the wheel's tangential force, the wheel's axial force the worm's tangential force
    assert parts['wormAxial'] == pytest.approx(-parts['wheelTangential'], rel=1e-12)
    assert parts['wheelAxial'] == pytest.approx(-parts['wormTangential'], rel=1e-12)
    # the generalized forces are these forces at the pitch point P = (0, r1, 0) on the worm, -F on the wheel
    Qworm, Qwheel, q = _Forces(mesh, mbs)
    Fworm = np.asarray(parts['wormForce'])
    P = mesh.geometry.meshPoint
    np.testing.assert_allclose(Qworm[:3], Fworm, rtol=1e-9, atol=1e-9 * W)
    np.testing.assert_allclose(Qwheel[:3], -Fworm, rtol=1e-9, atol=1e-9 * W)
    n = mesh._kinematics.bodies[0].size
    np.testing.assert_allclose(_Moment(mesh.nodeNumbers[0], Qworm[3:], q[:n], mbs), np.cross(P, Fworm),
                               rtol=1e-7, atol=1e-7 * W * gear.r1)
    wheelCentre = np.array([0., gear.r1 + gear.r2, 0.])
    np.testing.assert_allclose(_Moment(mesh.nodeNumbers[1], Qwheel[3:], q[n:], mbs), np.cross(P - wheelCentre, -Fworm),
                               rtol=1e-7, atol=1e-7 * W * gear.r2)


@pytest.mark.physics
def test_wheel_on_the_other_side_is_a_left_hand_thread_with_the_same_law():
    """The wheel at y = -a: the hand flips, a positive worm rotation still turns the wheel positively (the mesh
    deflection of a worm rotation is cancelled by the wheel rotation u times smaller)."""
    SC, mbs, worm, wheel = _Pair(phi1=0.3, phi2=0.3 / GEAR.ratio, wheelSide=-1.)
    mesh = CreateRigidBodyWormGear(mbs, [worm, wheel], gear=GEAR)
    assert mesh.geometry.hand == -1.
    assert mesh.InitialMeshState(mbs).deltaS == pytest.approx(0., abs=1e-15)


@pytest.mark.physics
def test_axial_worm_shift_and_approach_enter_the_mesh_as_in_the_contact_law():
    """A worm shifted along its axis by x deflects the mesh by cos(aN) cos(g) x; an approach c by sin(aN) c."""
    SC, mbs, worm, wheel = _Pair(joints=False)
    mesh = CreateRigidBodyWormGear(mbs, [worm, wheel], gear=GEAR, contactOptions=ContactOptions(dampingCanPull=True,
                                                                                                fixedS=1))
    q, v = mesh._InitialVectors(mbs)
    x, c = 2e-6, 3e-6
    q = list(q)
    q[0], q[1] = x, c                             # worm: +x along its axis (the thread's advance), +y towards the wheel
    mesh._initialAngles = list(mesh._initialAngles)
    state = mesh.Evaluate([q], [v])
    lever = GEAR.normalLever
    assert float(state.deltaS[0]) == pytest.approx(GEAR.axialLever * x, rel=1e-9)
    W = GEAR.kV * (GEAR.axialLever * x + math.sin(GEAR.alphaN) * c)
    assert float(state.normalForce[0]) == pytest.approx(W, rel=1e-9)
    assert lever > 0


def _ReelRuns(parameters, endTime, solverOptions=None, **kwargs):
    """The reel changer with the one-angle connector and with rigid bodies on ideal joints, same settings."""
    drive = ResolveDrive(parameters=parameters)
    h = RecommendedStepSize(drive)
    out = []
    for build in (BuildReelChanger, BuildRigidBodyReelChanger):
        model = build(exu.SystemContainer().AddSystem(), drive, **kwargs)
        if build is BuildRigidBodyReelChanger:
            model.connector.AddSensors(model.mbs)
        model.mbs.Assemble()
        ss, solverType = SolverSettings(endTime, h, solverOptions)
        model.mbs.SolveDynamic(ss, solverType=solverType)
        out.append((model, model.connector.StoredMeshState(model.mbs)))
    return out


def _Relative(a, b):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


@pytest.mark.physics
def test_ideal_joints_give_the_one_angle_connector_p1_start():
    """P1, first 0.3 s: the same normal force, deltaPhi, S and torques within 1e-6 relative."""
    (m1, s1), (m3, s3) = _ReelRuns(P1, 0.3)
    np.testing.assert_allclose(s3.time, s1.time)
    for key in ('normalForce', 'deltaPhi', 'wormTorque', 'wheelTorque'):
        assert _Relative(getattr(s3, key), getattr(s1, key)) < 1e-6, key
    np.testing.assert_array_equal(s3.S, s1.S)


@pytest.mark.slow
@pytest.mark.physics
@pytest.mark.parametrize('preset, endTime', [('reel-P1', 8.), ('reel-P7', 1.)])
def test_ideal_joints_give_the_one_angle_connector_with_backlash(preset, endTime):
    """P1 over its default 8 s and P7 (stick/slip while it chatters) over 1 s, with 10 um backlash: within 1e-6."""
    parameters = {**GetPreset(preset), 'backlash': 1e-5}
    # full Newton to a tight tolerance: at the solver's default (relative 1e-6, modified Newton) the two models,
    # equal to 1e-10 before, part by 2e-5 at the first loss of contact of P1 (2.5 s), and the chatter carries it on
    tight = {'timeIntegration.newton.relativeTolerance': 1e-10, 'timeIntegration.newton.useModifiedNewton': False}
    (m1, s1), (m3, s3) = _ReelRuns(parameters, endTime, tight)
    assert m3.connector.stickSlip.switches == m1.connector.stickSlip.switches
    for key in ('normalForce', 'deltaPhi', 'wormTorque', 'wheelTorque'):
        assert _Relative(getattr(s3, key), getattr(s1, key)) < 1e-6, key


@pytest.mark.physics
def test_axial_compliance_only_gives_the_worm_axial_bearing():
    """The worm sliding on its joint against kA, dA (mass mA) is CreateWormAxialBearing's model (0.3 s of P1)."""
    parameters = {**P1, 'kA': 5e8, 'dA': 1e3, 'mA': 5.}
    (m1, s1), (m3, s3) = _ReelRuns(parameters, 0.3)
    for key in ('normalForce', 'deltaS', 'axialForce', 'wheelTorque'):
        assert _Relative(getattr(s3, key), getattr(s1, key)) < 1e-6, key


@pytest.mark.physics
def test_shaft_bearing_reactions_are_the_statics_of_the_mesh_force():
    """A worm on two radial bearings (span L) and an axial bearing, held against turning, under a mesh force F at
    the pitch point (radius r1 on +y): the axial bearing takes F_x, the radial bearings F_y, F_z in sum and the
    couple of the axial force, r1 F_x = (L/2)(F_y1 - F_y0)... in the static equilibrium (Exudyn's static solver)."""
    gear = GEAR
    SC, mbs, worm, wheel = _Pair(joints=False)
    bearings = ShaftBearings(radialStiffness=5e8, axialStiffness=3e8, span=0.12)
    items = CreateShaftBearings(mbs, worm, axis=[1., 0., 0.], bearings=bearings, name='worm')
    # the wheel on stiff bearings, both shafts held against turning by torsion springs, the wheel pre-turned
    CreateShaftBearings(mbs, wheel, axis=[0., 0., 1.], bearings=ShaftBearings(5e9, 5e9, span=0.05), name='wheel')
    nGround = mbs.AddNode(NodePointGround())
    mGround = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nGround, coordinate=0))
    for body, coordinate, offset in ((worm, 3, 0.), (wheel, 5, -1e-3)):
        m = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=body['nodeNumber'], coordinate=coordinate))
        mbs.AddObject(CoordinateSpringDamper(markerNumbers=[mGround, m], stiffness=1e6, offset=offset))
    mesh = CreateRigidBodyWormGear(mbs, [worm, wheel], gear=gear, contactOptions=ContactOptions(frictionModel='regularized'))
    mesh.AddSensors(mbs)
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ss.solution.file.write = False
    ss.staticSolver.verboseMode = 0
    ss.staticSolver.newton.relativeTolerance = 1e-10
    mbs.SolveStatic(ss)
    q = np.hstack([mbs.GetNodeOutput(n, exu.OutputVariableType.Coordinates) for n in mesh.nodeNumbers])
    state = mesh.Evaluate([q], [np.zeros_like(q)])
    F = np.asarray(MeshForceComponents(mesh, state)['wormForce'])[0]       # on the worm, at the pitch point
    assert abs(float(state.normalForce[0])) > 100.
    force = {k: np.asarray(mbs.GetObjectOutput(items[k] if k == 'axial' else items['radial'][int(k[-1])],
                                                exu.OutputVariableType.ForceLocal)) for k in ('axial', 'radial0', 'radial1')}
    # ForceLocal: the spring's force in its frame (x along the axis), acting on the body with the opposite sign
    axial = force['axial'][0]
    across = force['radial0'][1:] + force['radial1'][1:]
    assert axial == pytest.approx(F[0], rel=1e-6)
    np.testing.assert_allclose(across, F[1:], rtol=1e-6, atol=1e-6 * abs(F).max())
    # moment about the shaft centre across the axis: the axial force on the lever r1 (about z), F_z on r1 (none)
    L = bearings.span
    couple = 0.5 * L * (force['radial1'][1] - force['radial0'][1])
    assert couple == pytest.approx(-gear.r1 * F[0], rel=1e-6)


@pytest.mark.messages
def test_bad_input_gives_one_clear_line():
    """Axes not perpendicular, a centre distance in mm, a mass point, a body without mass: one line each."""
    SC, mbs, worm, wheel = _Pair(joints=False)
    with pytest.raises(ValueError, match=r"must cross at 90 deg .* got 78.69 deg"):
        CreateRigidBodyWormGear(mbs, [worm, wheel], gear=GEAR, wheelAxis=[0.2, 0., 1.])
    with pytest.raises(ValueError, match=r"wheelAxis' must be a finite, non-zero 3D vector"):
        CreateRigidBodyWormGear(mbs, [worm, wheel], gear=GEAR, wheelAxis=[0., 0., 0.])
    with pytest.raises(ValueError, match=r"worm and wheel must be different bodies"):
        CreateRigidBodyWormGear(mbs, [worm, worm], gear=GEAR)
    point = mbs.CreateMassPoint(mass=1., returnDict=True)
    with pytest.raises(ValueError, match=r"must be a 3D rigid body \(ObjectRigidBody.*got object type 'MassPoint'"):
        CreateRigidBodyWormGear(mbs, [worm, point['bodyNumber']], gear=GEAR)
    massless = mbs.CreateRigidBody(inertia=RigidBodyInertia(mass=0., inertiaTensor=np.zeros((3, 3))),
                                   referencePosition=[0., GEAR.r1 + GEAR.r2, 0.], returnDict=True)
    with pytest.raises(ValueError, match=r"has no mass \(mass = 0.0 kg\)"):
        CreateRigidBodyWormGear(mbs, [worm, massless], gear=GEAR)
    SC2, mbs2, worm2, wheel2 = _Pair(gear=ElasticDriveFromParameters({**P1, 'r1': 18.05, 'r2': 105.95}).gear, joints=False)
    with pytest.raises(ValueError, match=r"axes are 124 m apart .* r1 \+ r2 is 0.124 m .*in m\?"):
        CreateRigidBodyWormGear(mbs2, [worm2, wheel2], gear=GEAR)
    far = mbs.CreateRigidBody(inertia=RigidBodyInertia(mass=1., inertiaTensor=np.eye(3)),
                              referencePosition=[0., GEAR.r1 + GEAR.r2, 5.], referenceRotationMatrix=RotationMatrixZ(0.),
                              returnDict=True)
    with pytest.raises(ValueError, match=r"pitch point is 5 m along the wheel axis"):
        CreateRigidBodyWormGear(mbs, [worm, far], gear=GEAR)


def test_bearings_reject_bad_values():
    """ShaftBearings names the argument, its range and unit."""
    with pytest.raises(ValueError, match=r"radialStiffness"):
        ShaftBearings(radialStiffness=-1., axialStiffness=1e8)
    assert StoredBearingLoads.__doc__


@pytest.mark.physics
def test_markers_place_the_axes_through_their_points():
    """The wheel body's reference point 0.05 m off its axis: with a marker on the axis the mesh is the same as with
    the body on its axis (the same deflection for the same rotations)."""
    SC, mbs, worm, wheel = _Pair(phi1=1e-4, joints=False)
    reference = CreateRigidBodyWormGear(mbs, [worm, wheel], gear=GEAR).InitialMeshState(mbs).deltaS
    offset = mbs.CreateRigidBody(inertia=InertiaCylinder(7800., 0.03, GEAR.r2, axis=2),
                                 referencePosition=[0.05, GEAR.r1 + GEAR.r2, 0.], initialRotationMatrix=RotationMatrixZ(0.),
                                 returnDict=True)
    mWorm = mbs.AddMarker(MarkerBodyRigid(bodyNumber=worm['bodyNumber'], localPosition=[0., 0., 0.]))
    mWheel = mbs.AddMarker(MarkerBodyRigid(bodyNumber=offset['bodyNumber'], localPosition=[-0.05, 0., 0.]))
    mesh = CreateRigidBodyWormGear(mbs, markerNumbers=[mWorm, mWheel], gear=GEAR)
    assert mesh.InitialMeshState(mbs).deltaS == pytest.approx(reference, rel=1e-12)
    np.testing.assert_allclose(mesh._kinematics.bodies[1].axisPoint, [-0.05, 0., 0.], atol=1e-15)
    with pytest.raises(ValueError, match="give either 'bodyNumbers' or 'markerNumbers'"):
        CreateRigidBodyWormGear(mbs, [worm, wheel], gear=GEAR, markerNumbers=[mWorm, mWheel])


@pytest.mark.physics
@pytest.mark.parametrize('nodeType', ['RotationRxyz', 'RotationRotationVector'])
def test_free_mesh_oscillation_matches_the_one_angle_connector(nodeType):
    """Worm and wheel on ideal joints, no drive or load, the mesh pre-deflected: the mesh oscillation of the one-angle
    connector on two rotors with the bodies' moments of inertia within 1e-6 (full Newton: with modified Newton the
    rotation-vector nodes do not converge; docs/mesh-3d.md)."""
    options = ContactOptions(frictionModel='regularized')
    settings = {'timeIntegration.newton.useModifiedNewton': False}
    SC, mbs, worm, wheel = _Pair(nodeType, phi1=3e-4, omega1=40., omega2=40. / GEAR.ratio)
    J1 = mbs.GetObject(worm['bodyNumber'])['inertia'][0]
    J2 = mbs.GetObject(wheel['bodyNumber'])['inertia'][2]
    mesh = CreateRigidBodyWormGear(mbs, [worm, wheel], gear=GEAR, contactOptions=options)
    mesh.AddSensors(mbs)
    SC1 = exu.SystemContainer()
    mbs1 = SC1.AddSystem()
    rotors = [CreateRotor(mbs1, J1, 3e-4, 40.), CreateRotor(mbs1, J2, 0., 40. / GEAR.ratio)]
    reference = CreateWormGear(mbs1, rotors, gear=GEAR, contactOptions=options)
    reference.AddSensors(mbs1)
    states = []
    for system, connector in ((mbs, mesh), (mbs1, reference)):
        system.Assemble()
        ss, solverType = SolverSettings(0.015, 1e-4, settings)
        system.SolveDynamic(ss, solverType=solverType)
        states.append(connector.StoredMeshState(system))
    assert _Relative(states[0].normalForce, states[1].normalForce) < 1e-6


@pytest.mark.physics
def test_axial_force_is_the_worms_thrust_without_an_axial_bearing():
    """MeshState.axialForce is -wheelTorque / r2 also without an axial degree of freedom (the rigid bearing's thrust),
    as documented."""
    state = MeshContact(GEAR, 2e-4, 0., 40., 40. / GEAR.ratio, ContactOptions(frictionModel='regularized'))
    assert state.axialForce == pytest.approx(-state.wheelTorque / GEAR.r2, rel=1e-15)
    assert state.axialForce < 0.
