"""A preload angle of the rigid-body mesh (CreateRigidBodyWormGear(referenceAngles=...)): it shifts the law's worm and
wheel angles as the one-angle connector's node references do, with the law in Python and in C++, statically and in a
dynamic run."""
import math

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import (CoordinateSpringDamper, MarkerBodyRigid, MarkerNodeCoordinate, Node1D,
                                  NodePointGround, ObjectGround, ObjectJointGeneric, ObjectRotationalMass1D)
from exudyn.rigidBodyUtilities import InertiaCylinder, RotationMatrixX, RotationMatrixY

from exudyn_worm.analysis.simulation.reelchanger import SolverSettings
from exudyn_worm.drive.presets import ElasticDriveFromParameters, GetPreset
from exudyn_worm.items.connector import CreateWormGear
from exudyn_worm.items.rigidmesh import CreateRigidBodyWormGear
from exudyn_worm.model.contact import NUMPY_OPS, ContactOptions, MeshContact

pytest.importorskip('exudyn')
GEAR = ElasticDriveFromParameters(GetPreset('reel-P1')).gear
#: the worm's preload angle in rad (the wheel's is 0)
PRELOAD = 0.01
#: friction at rest is zero (sf = 0): the statics are those of the normal force alone
OPTIONS = ContactOptions(frictionModel='regularized')
#: full Newton to a tight tolerance: the models agree to round-off, not to the default tolerance (1e-6)
TIGHT = {'timeIntegration.newton.relativeTolerance': 1e-10, 'timeIntegration.newton.useModifiedNewton': False}
LEVER = GEAR.normalLever                       # r1 cos(alphaN) sin(gamma): Delta s = LEVER (phi1 - u phi2)
#: torsion springs holding the turns, about as stiff as the mesh seen from each shaft (worm: kV LEVER^2, wheel: u^2
#: that)
SPRINGS = (GEAR.kV * LEVER**2, GEAR.ratio**2 * GEAR.kV * LEVER**2)


def _Inertias():
    return InertiaCylinder(7800., 0.1, GEAR.r1, axis=2), InertiaCylinder(7800., 0.03, GEAR.r2, axis=2)


def _Springs(mbs, nodes, coordinate):
    """Torsion springs from ground on each node's turn (its coordinate ``coordinate``, reference value 0)."""
    ground = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=mbs.AddNode(NodePointGround()), coordinate=0))
    for node, k in zip(nodes, SPRINGS):
        marker = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=node, coordinate=coordinate))
        mbs.AddObject(CoordinateSpringDamper(markerNumbers=[ground, marker], stiffness=k))


def _RigidPair(useSymbolic):
    """Worm (axis global -y) and wheel (axis global z, at x = r1 + r2) as Rxyz bodies turning about their last angle
    (the layout of BuildRigidBodyReelChanger), on ideal joints, each turn held by a torsion spring; the mesh preloaded
    by ``referenceAngles=[PRELOAD, 0]``."""
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    wormInertia, wheelInertia = _Inertias()
    nt = exu.NodeType.RotationRxyz
    wormRotation = RotationMatrixX(math.pi / 2)          # body z on global -y, no Tait-Bryan singularity
    worm = mbs.CreateRigidBody(inertia=wormInertia, nodeType=nt, referenceRotationMatrix=wormRotation,
                               returnDict=True)
    wheel = mbs.CreateRigidBody(inertia=wheelInertia, nodeType=nt, referencePosition=[GEAR.r1 + GEAR.r2, 0., 0.],
                                returnDict=True)
    # each joint frame's x on the body's axis (body z), free about it
    toAxis = RotationMatrixY(-math.pi / 2)               # marker x on body z
    for body, rotation in ((worm, wormRotation), (wheel, np.eye(3))):
        pos = mbs.GetNode(body['nodeNumber'])['referenceCoordinates'][:3]
        ground = mbs.AddObject(ObjectGround(referencePosition=list(pos)))
        m0 = mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localHT=exu.HT(rotation=rotation @ toAxis)))
        m1 = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body['bodyNumber'], localHT=exu.HT(rotation=toAxis)))
        mbs.AddObject(ObjectJointGeneric(markerNumbers=[m0, m1], constrainedAxes=[1, 1, 1, 0, 1, 1]))
    nodes = [worm['nodeNumber'], wheel['nodeNumber']]
    _Springs(mbs, nodes, 5)
    mesh = CreateRigidBodyWormGear(mbs, [worm, wheel], gear=GEAR, wormAxis=[0., 0., 1.], wheelAxis=[0., 0., 1.],
                                   contactOptions=OPTIONS, referenceAngles=[PRELOAD, 0.], useSymbolic=useSymbolic)
    mesh.AddSensors(mbs)
    return SC, mbs, mesh


def _OneAnglePair():
    """The one-angle connector on two rotors with the bodies' moments of inertia and the same springs; its preload is
    the worm node's reference angle PRELOAD (the springs act on the displacement)."""
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    nodes = []
    for inertia, reference in zip(_Inertias(), (PRELOAD, 0.)):
        node = mbs.AddNode(Node1D(referenceCoordinates=[reference]))
        mbs.AddObject(ObjectRotationalMass1D(nodeNumber=node, inertia=float(inertia.Inertia()[2, 2])))
        nodes.append(node)
    _Springs(mbs, nodes, 0)
    connector = CreateWormGear(mbs, nodes, gear=GEAR, contactOptions=OPTIONS)
    connector.AddSensors(mbs)
    return SC, mbs, connector


def _StaticNormalForce():
    """Closed form: Fn = kV (LEVER (PRELOAD + phi1 - u phi2) - delta/2) with the springs' turns phi1 = -c2 Fn / kT1,
    phi2 = c4 Fn / kT2, the levers c2, c4 of eqs. (10), (12) at S = 0 (no friction at rest)."""
    kT1, kT2 = SPRINGS
    c2, c4 = GEAR.LeverArms(0.)
    compliance = GEAR.kV * LEVER * (c2 / kT1 + GEAR.ratio * c4 / kT2)
    return GEAR.kV * (LEVER * PRELOAD - 0.5 * GEAR.backlash) / (1. + compliance)


def _StaticSettings():
    ss = exu.SimulationSettings()
    ss.solution.file.write = False
    ss.staticSolver.verboseMode = 0
    ss.staticSolver.newton.relativeTolerance = 1e-10
    return ss


@pytest.mark.physics
@pytest.mark.parametrize('useSymbolic', [False, True])
def test_preload_angle_gives_the_static_normal_force(useSymbolic):
    """At the undeflected start the preload angle deflects the flank by LEVER * PRELOAD: Fn = kV LEVER PRELOAD. In the
    static equilibrium against the torsion springs (each as stiff as the mesh seen from its shaft) the normal force is
    the closed form of _StaticNormalForce (about a third of the start's), MeshContact's at the bodies' angles plus the
    preload and the one-angle connector's with the preload as its worm node's reference angle."""
    SC, mbs, mesh = _RigidPair(useSymbolic)
    start = GEAR.kV * (LEVER * PRELOAD - 0.5 * GEAR.backlash)
    assert start > 1e3
    assert mesh.InitialMeshState(mbs).normalForce == pytest.approx(start, rel=1e-12)
    mbs.Assemble()
    mbs.SolveStatic(_StaticSettings())
    q = np.hstack([mbs.GetNodeOutput(n, exu.OutputVariableType.Coordinates) for n in mesh.nodeNumbers])
    phi1, phi2 = q[5], q[6 + 5]
    assert phi1 < 0. < phi2                    # the springs give way to the mesh force
    Fn = float(mesh.Evaluate([q], [np.zeros_like(q)]).normalForce[0])
    expected = _StaticNormalForce()
    assert 0.3 * start < expected < 0.4 * start          # about a third: the springs are as stiff as the mesh
    assert Fn == pytest.approx(expected, rel=1e-8)
    law = MeshContact(GEAR, np.array([phi1 + PRELOAD]), np.array([phi2]), np.zeros(1), np.zeros(1), OPTIONS, NUMPY_OPS)
    assert Fn == pytest.approx(float(law.normalForce[0]), rel=1e-12)
    SC1, mbs1, reference = _OneAnglePair()
    mbs1.Assemble()
    mbs1.SolveStatic(_StaticSettings())
    angles = [float(np.ravel(mbs1.GetNodeOutput(n, exu.OutputVariableType.Coordinates))[0])
              for n in reference.nodeNumbers]
    assert angles == pytest.approx([phi1, phi2], rel=1e-8)
    assert float(reference.Evaluate(*angles, 0., 0.).normalForce) == pytest.approx(Fn, rel=1e-8)


@pytest.mark.physics
@pytest.mark.parametrize('useSymbolic', [False, True])
def test_preload_angle_drives_the_one_angle_connectors_oscillation(useSymbolic):
    """Released from the preloaded start, the bodies oscillate against the springs as the one-angle connector's rotors
    do with the same preload: the normal force, kV LEVER PRELOAD at t = 0, within 1e-6 of the one-angle run over
    0.02 s."""
    runs = []
    for SC, mbs, connector in (_RigidPair(useSymbolic), _OneAnglePair()):
        mbs.Assemble()
        ss, solverType = SolverSettings(0.02, 1e-4, TIGHT)
        mbs.SolveDynamic(ss, solverType=solverType)
        runs.append(np.asarray(connector.StoredMeshState(mbs).normalForce, dtype=float))
    rigid, oneAngle = runs
    start = GEAR.kV * (LEVER * PRELOAD - 0.5 * GEAR.backlash)
    assert rigid[0] == pytest.approx(start, rel=1e-12)
    assert np.ptp(rigid) > 0.5 * start        # it oscillates: the preload is released
    assert np.max(np.abs(rigid - oneAngle)) < 1e-6 * np.max(np.abs(oneAngle))


@pytest.mark.physics
@pytest.mark.parametrize('useSymbolic', [False, True])
@pytest.mark.parametrize('angles', [(PRELOAD, 0.), (0., -PRELOAD / GEAR.ratio), (-PRELOAD, 0.5 * PRELOAD / GEAR.ratio),
                                    (PRELOAD, PRELOAD / GEAR.ratio)])
def test_worm_and_wheel_preload_angles_enter_as_the_one_angle_connectors(useSymbolic, angles):
    """Worm and wheel preload angles (a1, a2) at the start: the signed normal force is
    sign(d) kV (LEVER |d| - delta/2) with d = a1 - u a2 (0 for a turn of both, a1 = u a2), as MeshContact's at (a1, a2)
    and the one-angle connector's with (a1, a2) as its nodes' reference angles."""
    a1, a2 = angles
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    wormInertia, wheelInertia = _Inertias()
    worm = mbs.CreateRigidBody(inertia=wormInertia, nodeType=exu.NodeType.RotationRxyz,
                               referenceRotationMatrix=RotationMatrixX(math.pi / 2), returnDict=True)
    wheel = mbs.CreateRigidBody(inertia=wheelInertia, nodeType=exu.NodeType.RotationRxyz,
                                referencePosition=[GEAR.r1 + GEAR.r2, 0., 0.], returnDict=True)
    mesh = CreateRigidBodyWormGear(mbs, [worm, wheel], gear=GEAR, wormAxis=[0., 0., 1.], wheelAxis=[0., 0., 1.],
                                   contactOptions=OPTIONS, referenceAngles=[a1, a2], useSymbolic=useSymbolic)
    d = a1 - GEAR.ratio * a2
    expected = math.copysign(max(GEAR.kV * (LEVER * abs(d) - 0.5 * GEAR.backlash), 0.), d)
    Fn = float(mesh.InitialMeshState(mbs).normalForce)
    assert Fn == pytest.approx(expected, rel=1e-9, abs=1e-9 * GEAR.kV * LEVER * PRELOAD)
    law = MeshContact(GEAR, np.array([a1]), np.array([a2]), np.zeros(1), np.zeros(1), OPTIONS, NUMPY_OPS)
    assert Fn == pytest.approx(float(law.normalForce[0]), rel=1e-12, abs=1e-9 * GEAR.kV * LEVER * PRELOAD)
    mbs1 = exu.SystemContainer().AddSystem()
    nodes = []
    for inertia, reference in zip(_Inertias(), angles):
        nodes.append(mbs1.AddNode(Node1D(referenceCoordinates=[reference])))
        mbs1.AddObject(ObjectRotationalMass1D(nodeNumber=nodes[-1], inertia=float(inertia.Inertia()[2, 2])))
    oneAngle = CreateWormGear(mbs1, nodes, gear=GEAR, contactOptions=OPTIONS)
    assert Fn == pytest.approx(float(oneAngle.InitialMeshState(mbs1).normalForce), rel=1e-12,
                               abs=1e-9 * GEAR.kV * LEVER * PRELOAD)
