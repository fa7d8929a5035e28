"""The 3D model of a drive, added to a new Exudyn system: worm and wheel as rigid bodies, on ideal revolute joints or
on elastic bearings.

:func:`BuildRigidBodyReelChanger` builds the drive of :func:`~exudyn_worm.builders.oneangle.BuildReelChanger`
(motor at constant speed, drive shaft kT, dT, worm, mesh, wheel, the reel's lever load) with the worm and the wheel
as ``mbs.CreateRigidBody`` bodies coupled by :func:`~exudyn_worm.items.rigidmesh.CreateRigidBodyWormGear`. Each
shaft sits on ideal revolute joints to ground, or on :func:`~exudyn_worm.items.bearings.CreateShaftBearings`
(two radial bearings and an axial bearing, stiffness and damping). Both bodies use Tait-Bryan nodes (``Rxyz``)
turning about their last angle (the worm's reference rotation puts its local z on global -y, the wheel turns about
global z), so the drive shaft and the load act on those coordinates (the torque about the axis, for any tilt) and
the mesh law runs in C++ (``useSymbolic``, :func:`~exudyn_worm.items.rigidmesh.CreateRigidBodyWormGear`). The
centre line is global +x; the pitch point is at x = r1.

Parameter sets: those of the reel changer without a drive-side chain (a load-side chain acts on the wheel's turn,
the load on its last stage), with a constant-speed motor (the
presets reel-P1 ... reel-P7); an axial bearing ``kA, dA, mA`` lets the worm (of mass mA) slide on its revolute
joint against the axial spring-damper, the model of :func:`~exudyn_worm.items.connector.CreateWormAxialBearing`.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, NamedTuple, Optional, Sequence, Tuple

import numpy as np

from .._checks import CheckBool, CheckPositive
from ..items.bearings import WHEEL_MASS, WORM_MASS, ShaftBearings, CreateShaftBearings
from ..items.drivetrain import CreateLoadSideChain, CreatePrescribedRotation, CreateRotor, CreateRotorTorque
from ..items.equilibrium import SteadyInitialState
from ..items._userfunctions import AddCoordinateForce
from ..items.rigidmesh import CreateRigidBodyWormGear, RigidBodyWormGearConnector
from ..items.smallmesh import CreateSmallDisplacementWormGear, SmallDisplacementBody
from ..model.contact import ContactOptions, MeshContact
from ..model.friction import MATH_OPS
from ..model.profiles import ConstantSpeed
from ..drive.wholedrive import CheckDrive, Drive
from .oneangle import CheckModelDrive
from .start import LinearizationPoint

__all__ = ['WORM_AXIS', 'WHEEL_AXIS', 'WORM_REFERENCE', 'TURN', 'MODELS', 'RigidBodyReelChanger',
           'BuildRigidBodyReelChanger', 'BodyInertiaTensor', 'BodyInertiaTensors', 'DefaultModel']


#: the worm's axis (global): its turn is about -y, so that with the wheel's axis +z and the centre line +x a positive
#: worm rotation turns the wheel positively, as in the one-angle model's sign conventions; the mesh's hand is then
#: h = +1, a left-handed thread (:attr:`~exudyn_worm.items.rigidmesh.MeshGeometry.rightHanded`)
WORM_AXIS = np.array([0., -1., 0.])
#: the wheel's axis (global)
WHEEL_AXIS = np.array([0., 0., 1.])
#: the worm node's reference rotation: its local z (the last Rxyz angle, its turn) onto WORM_AXIS
WORM_REFERENCE = np.array([[1., 0., 0.], [0., 0., -1.], [0., 1., 0.]])
#: index of the bodies' turn among their node coordinates (the last Tait-Bryan angle)
TURN = 5
#: the 3D models :func:`BuildRigidBodyReelChanger` builds: ``'small'`` the small-displacement model of shafts on linear
#: bearings (:mod:`exudyn_worm.items.smallmesh`), ``'exact'`` worm and wheel as Exudyn rigid bodies
#: (:mod:`exudyn_worm.items.rigidmesh`)
MODELS = ('small', 'exact')


def DefaultModel(wormBearings: Optional[ShaftBearings], wheelBearings: Optional[ShaftBearings],
                 axialBearing: Optional[Any] = None, loadSideChain: Sequence = ()) -> str:
    """The 3D model :func:`BuildRigidBodyReelChanger` builds by default: ``'small'`` when both shafts sit on
    linear bearings (and the worm has no separate axial bearing, the wheel no load-side chain), else ``'exact'``.

    Parameters
    ----------
    wormBearings, wheelBearings : ShaftBearings or None
        The shafts' bearings (None: an ideal revolute joint).
    axialBearing : AxialBearing, optional
        The worm's axial bearing ``kA, dA, mA`` on its joint.
    loadSideChain : sequence, optional
        The load-side chain ``(J, k, d), ...`` on the wheel's turn.

    Returns
    -------
    str
        An entry of :data:`MODELS`.
    """
    return ('small' if wormBearings is not None and wheelBearings is not None and axialBearing is None
            and not loadSideChain else 'exact')


class BodyInertiaTensor(NamedTuple):
    """One body of the 3D model: what :func:`BodyInertiaTensors` gives for it.

    Attributes
    ----------
    mass : float
        The body's mass in kg.
    tensor : numpy.ndarray
        3x3 inertia tensor in kg*m^2 about the centre of mass (the body's reference point), in body coordinates
        with the local z along the axis: ``diag(tilt, tilt, polar)`` with the body's own polar inertia.
    shaftInertia : float
        Inertia in kg*m^2 about the axis that turns with the body without tilting with it (the shaft's J1 or J2 less
        the body's own polar inertia: a motor rotor behind a coupling, a reel on its own bearings); it acts on the
        body's turn alone.
    tiltGiven : bool
        Whether the tilt inertia came from the drive; False for a body on an ideal revolute joint without it, whose
        tilt the joint holds: its tilt entries are then half the polar one and enter no result.
    """
    mass: float
    tensor: np.ndarray
    shaftInertia: float
    tiltGiven: bool


def BodyInertiaTensors(drive: Drive) -> Dict[str, BodyInertiaTensor]:
    """The inertias of the 3D model's worm and wheel bodies: the one place the model builders take them from.

    Each body is a body of revolution turning about its local z: its tensor about its centre is
    ``diag(tilt, tilt, polar)`` with its own polar and tilt inertia (``[worm] tiltInertia``, ``polarInertia`` or a
    shape, :func:`~exudyn_worm.drive.presets.ShaftSupportsFromParameters`); what else is on its shaft (J1 or J2
    less its own polar inertia) turns with it but does not tilt with it (``shaftInertia``). Without a tilt inertia
    the drive's body must be on an ideal joint (the drive refuses elastic bearings without it); its tensor is then
    ``diag(J/2, J/2, J)`` with the shaft's J, which the joint's held tilt keeps out of every result.

    Parameters
    ----------
    drive : Drive
        The drive (:func:`~exudyn_worm.drive.wholedrive.ResolveDrive`).

    Returns
    -------
    dict
        ``'worm'``, ``'wheel'``: a :class:`BodyInertiaTensor` each.

    Raises
    ------
    TypeError
        If ``drive`` is not a Drive.
    """
    CheckDrive('BodyInertiaTensors', drive, 'drive')
    supports, elastic = drive.shaftSupports, drive.elastic
    axial = drive.axialBearing
    out = {}
    for body, J, default in (('worm', elastic.J1, WORM_MASS), ('wheel', elastic.J2, WHEEL_MASS)):
        own = None if supports is None else getattr(supports, body + 'Inertia')
        mass = default if supports is None else getattr(supports, body + 'Mass')
        if body == 'worm' and axial is not None:
            mass = axial.mass
        if own is None:
            out[body] = BodyInertiaTensor(mass, np.diag([J / 2., J / 2., J]), 0., False)
        else:
            out[body] = BodyInertiaTensor(own.mass, np.diag([own.tilt, own.tilt, own.polar]), J - own.polar, True)
    return out


@dataclass
class RigidBodyReelChanger:
    """The Exudyn system of :func:`BuildRigidBodyReelChanger` and what is needed to read its results.

    Attributes
    ----------
    systemContainer, mbs : exudyn objects
        The container (kept alive with the system) and the system, not yet assembled.
    connector : RigidBodyWormGearConnector
        The mesh.
    bodies : dict
        ``worm``, ``wheel``: the ``returnDict`` of ``mbs.CreateRigidBody``.
    bearings : dict
        ``worm``, ``wheel``: the items of :func:`~exudyn_worm.items.bearings.CreateShaftBearings` (None: revolute
        joints, under ``'joint'`` then).
    drive : ElasticDrive
        The two-mass drive of the parameter set.
    initial : dict
        The static equilibrium the run starts from (:func:`~exudyn_worm.items.equilibrium.SteadyInitialState`).
    motor : dict
        The motor rotor (:func:`~exudyn_worm.items.drivetrain.CreateRotor`).
    load : object or None
        The load law on the wheel.
    axialBearing : AxialBearing or None
        The worm's axial bearing ``kA, dA, mA`` (the worm slides on its joint), if the parameter set gives one.
    sensors : dict
        Sensors by name (:func:`AddSeriesSensors`).
    model : str
        ``'exact'`` (rigid bodies) or ``'small'`` (the small-displacement model; ``connector`` is then a
        :class:`~exudyn_worm.items.smallmesh.SmallWormGearConnector`, ``bodies`` its two nodes, ``inputs`` and
        ``shafts``, and ``bearings`` the shafts' names: its bearing loads come from the connector).
    loadRotors : list of dict
        The rotors of the drive's load-side chain on the wheel's turn (``[[loadSide]]``, wheel side first; the load
        acts on the last), :func:`~exudyn_worm.items.drivetrain.CreateLoadSideChain`.
    """
    systemContainer: Any
    mbs: Any
    connector: Any
    bodies: Dict[str, Any]
    bearings: Dict[str, Any]
    drive: Any
    initial: Dict[str, float] = field(default_factory=dict)
    motor: Optional[Dict[str, Any]] = None
    load: Optional[Any] = None
    axialBearing: Optional[Any] = None
    sensors: Dict[str, Any] = field(default_factory=dict)
    model: str = 'exact'
    loadRotors: List[Dict[str, Any]] = field(default_factory=list)


def BuildRigidBodyReelChanger(mbs, drive: Drive, contactOptions: ContactOptions = ContactOptions(),
                              useSymbolic: bool = True, wormBearings: Optional[ShaftBearings] = None,
                              wheelBearings: Optional[ShaftBearings] = None, wormMass: Optional[float] = None,
                              wheelMass: Optional[float] = None, profile: Optional[Any] = None,
                              startFromEquilibrium: bool = True, model: Optional[str] = None,
                              linearization: Optional[LinearizationPoint] = None,
                              motorConstraint: bool = True) -> RigidBodyReelChanger:
    """Add the 3D model of a drive to ``mbs``: worm and wheel as rigid bodies (module docstring), starting in
    equilibrium. The one builder of this model: the time simulation, the linear analysis and the lowering-phase
    orbit use it.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system to add the items to (``SC.AddSystem()``); it is not assembled here.
    drive : Drive
        The drive (:func:`~exudyn_worm.drive.wholedrive.ResolveDrive`), without a drive-side chain or a motor on its
        characteristic (e.g. ``ResolveDrive('reel-P1')``), with a duty; its shafts' bearings and masses
        (``drive.shaftSupports``) are used where the arguments below do not give them.
    contactOptions : ContactOptions
        Options of the contact law.
    useSymbolic : bool
        C++ symbolic user functions (default) or plain Python for the drive, the load and the mesh law
        (:func:`~exudyn_worm.items.rigidmesh.CreateRigidBodyWormGear`, docs/mesh-3d.md, "Speed").
    wormBearings, wheelBearings : ShaftBearings, optional
        Elastic bearings of the shafts; None (default): those of the parameter set, else ideal revolute joints.
    wormMass, wheelMass : float, optional
        Masses in kg of the bodies (> 0); default those of the parameter set, else :data:`WORM_MASS`,
        :data:`WHEEL_MASS`. The moments of inertia are those of :func:`BodyInertiaTensors`; a body on elastic
        bearings needs its tilt inertia in the drive (``wormTiltInertia`` or its shape, docs/mesh-3d.md).
    profile : optional
        Motor motion with ``AngleAndSpeed(t, ops)`` (default: the duty's motor,
        :func:`~exudyn_worm.drive.duty.MotorFromParameters`).
    startFromEquilibrium : bool
        Start in the static equilibrium under the initial load at the motor's initial speed (default); otherwise
        at rest with zero angles.
    model : str, optional
        ``'small'``: the small-displacement model (:mod:`exudyn_worm.items.smallmesh`; both shafts on linear
        bearings, no separate axial bearing of the worm); ``'exact'``: worm and wheel as Exudyn rigid bodies
        (:mod:`exudyn_worm.items.rigidmesh`), the reference for large motions. None (default):
        :func:`DefaultModel` (``'small'`` with both shafts' bearings, docs/mesh-3d.md).
    linearization : LinearizationPoint, optional
        Build the model to be linearized at this point instead
        (:class:`~exudyn_worm.builders.start.LinearizationPoint`: no load, the motor held at the point's speed, the
        worm turned into contact while the bearings are undeflected: their springs are linear, the linearization
        does not depend on their preload; the exact model, whose linearization Exudyn computes); the drive needs no
        duty then, ``profile``, ``startFromEquilibrium`` and ``model`` are not used.
    motorConstraint : bool
        True (default): the motor is held on its path by a constraint; False: a constant-speed motor of the
        small-displacement model is a flywheel instead (``CreatePrescribedRotation(..., constraint=False)``, the
        same motion without the constraint's equation; for time simulations: the orbits and the linearization
        hold the motor by the constraint). The exact model always has the constraint.

    Returns
    -------
    RigidBodyReelChanger

    Raises
    ------
    ValueError
        For a parameter set with a drive-side chain, a motor on its characteristic, a bearing given twice, a bad
        mass, a body on elastic bearings without its tilt inertia, or a model that is not one of :data:`MODELS` or
        does not fit the supports.
    """
    w = 'BuildRigidBodyReelChanger'
    CheckModelDrive(w, drive, linearization)
    CheckBool(w, 'motorConstraint', motorConstraint)
    whole, supports = drive, drive.shaftSupports
    for name, value in (('wormBearings', wormBearings), ('wheelBearings', wheelBearings)):
        if value is not None and supports is not None and getattr(supports, name) is not None:
            raise ValueError(f"{w}: '{name}' are given twice, as the argument and in the parameter set; give them once")
    if supports is not None:
        wormBearings = wormBearings or supports.wormBearings
        wheelBearings = wheelBearings or supports.wheelBearings
        wormMass = supports.wormMass if wormMass is None else wormMass
        wheelMass = supports.wheelMass if wheelMass is None else wheelMass
    wormMass = CheckPositive(w, 'wormMass', WORM_MASS if wormMass is None else wormMass, 'kg')
    wheelMass = CheckPositive(w, 'wheelMass', WHEEL_MASS if wheelMass is None else wheelMass, 'kg')
    inertias = BodyInertiaTensors(whole)
    for body, bearings in (('worm', wormBearings), ('wheel', wheelBearings)):
        if bearings is not None and not inertias[body].tiltGiven:
            raise ValueError(f"{w}: the {body} on elastic bearings needs its tilt inertia: give {body}TiltInertia "
                             f"(kg*m^2, or its shape {body}Radius, {body}Length) in the drive, with the bearings "
                             f"([{body}] tiltInertia, [{body}Bearing]); the polar inertia is never used for it")
    if whole.driveSideChain:
        raise ValueError(f"{w}: the rigid-body reel changer has no drive-side chain: remove J4.. from the parameter "
                         f"set")
    loadChain = whole.loadSideChain
    axial = whole.axialBearing
    if axial is not None and wormBearings is not None:
        raise ValueError(f"{w}: give the worm's axial bearing once: as kA, dA, mA of the parameter set or in "
                         f"'wormBearings'")
    if whole.hasMotorCharacteristic:
        raise ValueError(f"{w}: the rigid-body reel changer holds the motor on its path; a motor on its "
                         f"characteristic (motorType = characteristic) is not supported")
    drive = whole.elastic
    if linearization is not None:        # every body at the point's speed, the worm turned into contact
        speed, deltaPhi = linearization.Start(drive.gear)
        wheelSpeed = speed / drive.gear.ratio
        init = {'phi0': 0., 'omega0': speed, 'phi1': deltaPhi, 'omega1': speed, 'phi2': 0., 'omega2': wheelSpeed,
                **{f'omegaL{i}': wheelSpeed for i in range(1, len(loadChain) + 1)}}
        return _Build(mbs, drive, linearization.ContactOptions(contactOptions), useSymbolic, wormBearings,
                      wheelBearings, axial.mass if axial is not None else wormMass, wheelMass, axial, init,
                      ConstantSpeed(speed), None, inertias, loadChain)
    load = whole.load
    profile = whole.motor if profile is None else profile
    angle0, motorSpeed = (float(x) for x in profile.AngleAndSpeed(0., MATH_OPS))
    if startFromEquilibrium:
        init = SteadyInitialState(drive, load, motorSpeed, contactOptions, axial, loadSide=loadChain)
    else:
        init, angle0, motorSpeed = {'phi1': 0., 'omega1': 0., 'phi2': 0., 'omega2': 0.}, 0., 0.
    init['phi0'], init['omega0'] = angle0, motorSpeed
    wormMass = axial.mass if axial is not None else wormMass
    default = DefaultModel(wormBearings, wheelBearings, axial, loadChain)
    model = default if model is None else model
    if model not in MODELS:
        raise ValueError(f"{w}: 'model' must be one of {', '.join(map(repr, MODELS))} or None, got {model!r}")
    if model == 'small' and default != 'small':
        raise ValueError(f"{w}: model='small' needs both shafts on linear bearings (wormBearings and wheelBearings, "
                         f"no kA of the parameter set) and no load-side chain; use model='exact'")
    if model == 'small':
        if startFromEquilibrium:
            init['shafts'] = _SmallStaticCoordinates(drive, contactOptions, wormBearings, wheelBearings, wormMass,
                                                     wheelMass, inertias, init, load)
        return _BuildSmall(mbs, drive, contactOptions, useSymbolic, wormBearings, wheelBearings, wormMass,
                           wheelMass, inertias, init, profile, load, motorConstraint)
    if startFromEquilibrium and (wormBearings is not None or wheelBearings is not None):
        init.update(_StaticPoses(drive, contactOptions, wormBearings, wheelBearings, wormMass, wheelMass,
                                 axial, init, profile, load, inertias, loadChain))
    return _Build(mbs, drive, contactOptions, useSymbolic, wormBearings, wheelBearings, wormMass, wheelMass,
                  axial, init, profile, load, inertias, loadChain)


def _StaticSettings():
    """Settings of the static solves that deflect the bearings at the start."""
    import exudyn as exu
    ss = exu.SimulationSettings()
    ss.solution.file.write = False
    ss.staticSolver.newton.relativeTolerance = 1e-10
    ss.staticSolver.verboseMode = 0
    ss.linearSolver.solverType = exu.LinearSolverType.EigenDense
    return ss


def _SmallStaticCoordinates(drive, contactOptions, wormBearings, wheelBearings, wormMass, wheelMass, inertias, init,
                            load) -> np.ndarray:
    """The shafts' 12 coordinates of the small-displacement model with the bearings deflected by the initial mesh
    force (as :func:`_StaticPoses` for the exact model): a static solve at t = 0 with the contact state held."""
    import exudyn as exu
    S = 1 if init['omega1'] == 0. else int(np.sign(_StartS(drive, load, init, contactOptions)))
    static = _BuildSmall(exu.SystemContainer().AddSystem(), drive, ContactOptions(fixedS=S, frictionModel='regularized'),
                         True, wormBearings, wheelBearings, wormMass, wheelMass, inertias,
                         {**init, 'omega0': 0., 'omega1': 0., 'omega2': 0.}, ConstantSpeed(0.), load)
    mbs = static.mbs
    mbs.Assemble()
    mbs.SolveStatic(_StaticSettings())
    z = np.concatenate([np.asarray(mbs.GetNodeOutput(n, exu.OutputVariableType.Coordinates), dtype=float)
                        for n in static.connector.nodeNumbers])
    return static.connector.toShafts @ z


def _BuildSmall(mbs, drive, contactOptions, useSymbolic, wormBearings, wheelBearings, wormMass, wheelMass, inertias,
                init, profile, load, motorConstraint: bool = True) -> RigidBodyReelChanger:
    """The small-displacement system of :func:`BuildRigidBodyReelChanger` from the initial state ``init`` (phi0,
    omega0, phi1, omega1, phi2, omega2; ``shafts``: the 12 coordinates with the bearings deflected)."""
    from exudyn.itemInterface import CoordinateSpringDamper
    w = 'BuildRigidBodyReelChanger'
    gear = drive.gear
    q0 = np.zeros(12)
    q0[TURN], q0[6 + TURN] = init['phi1'], init['phi2']
    if 'shafts' in init:
        q0 = np.asarray(init['shafts'], dtype=float).copy()
    v0 = np.zeros(12)
    v0[TURN], v0[6 + TURN] = init['omega1'], init['omega2']
    bodies = [SmallDisplacementBody(referencePosition=[0., 0., 0.], referenceRotation=WORM_REFERENCE, mass=wormMass,
                                    inertia=inertias['worm'].tensor, bearings=wormBearings, spinSpeed=init['omega1'],
                                    shaftInertia=inertias['worm'].shaftInertia),
              SmallDisplacementBody(referencePosition=[gear.r1 + gear.r2, 0., 0.], referenceRotation=np.eye(3),
                                    mass=wheelMass, inertia=inertias['wheel'].tensor, bearings=wheelBearings,
                                    spinSpeed=init['omega2'], shaftInertia=inertias['wheel'].shaftInertia)]
    connector = CreateSmallDisplacementWormGear(mbs, bodies, gear, contactOptions, initialCoordinates=q0,
                                                initialVelocities=v0, name='wormGear', useSymbolic=useSymbolic)
    motor = CreateRotor(mbs, 1e-3, initialAngle=init['phi0'], initialSpeed=init['omega0'], name='motor')
    CreatePrescribedRotation(mbs, motor, profile, name='motorDrive', useSymbolic=useSymbolic,
                             constraint=motorConstraint)
    wormAngle, _ = connector.CoordinateMarker(mbs, 'worm', TURN)
    mbs.AddObject(CoordinateSpringDamper(markerNumbers=[motor['markerNumber'], wormAngle], stiffness=drive.kT,
                                         damping=drive.dT, name='driveShaft'))
    if load is not None:                       # the load torque on the wheel's turn
        wheelAngle, wheelNode = connector.CoordinateMarker(mbs, 'wheel', TURN)
        AddCoordinateForce(mbs, wheelNode, wheelAngle,
                           lambda t, phi, omega, ops: load.Torque(phi, omega, t, ops), name='reelLoad',
                           useSymbolic=useSymbolic, where=w, signature='load.Torque(phi, omega, t, ops)')
    nodes = {'inputs': {'nodeNumber': connector.nodeNumbers[0]}, 'shafts': {'nodeNumber': connector.nodeNumbers[1]}}
    return RigidBodyReelChanger(mbs.GetSystemContainer(), mbs, connector, nodes,
                                {'worm': {'small': 'worm'}, 'wheel': {'small': 'wheel'}}, drive, dict(init),
                                motor=motor, load=load, model='small')


def _StaticPoses(drive, contactOptions, wormBearings, wheelBearings, wormMass, wheelMass, axial, init,
                 profile, load, inertias, loadChain=()) -> Dict[str, Any]:
    """The bodies' poses with the bearings deflected by the initial mesh force: a static solve of the model at
    t = 0 with the contact state of the one-angle equilibrium ``init`` held, so that a run starts without the
    bearings' transient. Returns ``wormPose``, ``wheelPose`` (displacement, rotation matrix) and the angles
    ``phiL1, ...`` of the load-side chain's rotors."""
    import exudyn as exu
    S = 1 if init['omega1'] == 0. else int(np.sign(_StartS(drive, load, init, contactOptions)))
    resting = {k: 0. for k in init if k.startswith('omega')}
    static = _Build(exu.SystemContainer().AddSystem(), drive, ContactOptions(fixedS=S, frictionModel='regularized'), True, wormBearings,
                    wheelBearings, wormMass, wheelMass, axial, {**init, **resting},
                    ConstantSpeed(0.), load, inertias, loadChain)
    mbs = static.mbs
    mbs.Assemble()
    mbs.SolveStatic(_StaticSettings())
    out = {}
    for body in ('worm', 'wheel'):
        node = static.bodies[body]['nodeNumber']
        position = np.asarray(mbs.GetNodeOutput(node, exu.OutputVariableType.Displacement), dtype=float)
        rotation = np.asarray(mbs.GetNodeOutput(node, exu.OutputVariableType.RotationMatrix), dtype=float).reshape(3, 3)
        out[body + 'Pose'] = (position, rotation)
    for i, rotor in enumerate(static.loadRotors, start=1):   # the load-side chain twisted onto the wheel's pose
        out[f'phiL{i}'] = float(np.ravel(mbs.GetNodeOutput(rotor['nodeNumber'], exu.OutputVariableType.Coordinates))[0])
    return out


def _StartS(drive, load, init, contactOptions) -> float:
    """The contact parameter S of the one-angle mesh at the start ``init`` (the flank and the sliding direction)."""
    return float(np.asarray(MeshContact(drive.gear, init['phi1'], init['phi2'], init['omega1'], init['omega2'],
                                        options=contactOptions, axialDisplacement=init.get('xA'),
                                        axialSpeed=init.get('vA')).S))


def _Build(mbs, drive, contactOptions, useSymbolic, wormBearings, wheelBearings, wormMass, wheelMass,
           axial, init, profile, load, inertias, loadChain=()) -> RigidBodyReelChanger:
    """The system of :func:`BuildRigidBodyReelChanger` from the initial state ``init`` (phi0, omega0, phi1, omega1,
    phi2, omega2, xA, vA, phiL1, omegaL1, ...), the motor ``profile``, the ``load`` (None: none; on the last stage of
    the load-side chain ``loadChain`` if there is one) and the bodies' ``inertias`` (:func:`BodyInertiaTensors`)."""
    import exudyn as exu
    from exudyn.itemInterface import CoordinateSpringDamper, MarkerNodeCoordinate
    from exudyn.rigidBodyUtilities import RigidBodyInertia, RotationMatrixZ

    w = 'BuildRigidBodyReelChanger'
    gear = drive.gear
    a = gear.r1 + gear.r2
    # Rxyz nodes turning about their last angle (what the law in C++ needs, CreateRigidBodyWormGear): the worm's
    # local z turned onto global -y by its reference rotation, the wheel's local z is global z; centre line +x
    # a pose (displacement, rotation matrix) from the bearings' static deflection (_StaticPoses), else the turn alone
    wormPose = init.get('wormPose', (init.get('xA', 0.) * WORM_AXIS, WORM_REFERENCE @ RotationMatrixZ(init['phi1'])))
    wheelPose = init.get('wheelPose', (np.zeros(3), RotationMatrixZ(init['phi2'])))
    worm = mbs.CreateRigidBody(name='worm', nodeType=exu.NodeType.RotationRxyz, referencePosition=[0., 0., 0.],
                               referenceRotationMatrix=WORM_REFERENCE,
                               inertia=RigidBodyInertia(mass=wormMass, inertiaTensor=inertias['worm'].tensor),
                               initialRotationMatrix=WORM_REFERENCE.T @ wormPose[1],
                               initialDisplacement=list(wormPose[0]),
                               initialVelocity=list(init.get('vA', 0.) * WORM_AXIS),
                               initialAngularVelocity=list(init['omega1'] * WORM_AXIS), returnDict=True)
    wheel = mbs.CreateRigidBody(name='wheel', nodeType=exu.NodeType.RotationRxyz, referencePosition=[a, 0., 0.],
                                inertia=RigidBodyInertia(mass=wheelMass, inertiaTensor=inertias['wheel'].tensor),
                                initialRotationMatrix=wheelPose[1], initialDisplacement=list(wheelPose[0]),
                                initialAngularVelocity=list(init['omega2'] * WHEEL_AXIS), returnDict=True)
    for body, name in ((worm, 'worm'), (wheel, 'wheel')):
        _ShaftInertia(mbs, body['nodeNumber'], inertias[name].shaftInertia, name)
    bearings = {'worm': _Support(mbs, worm, WORM_AXIS, wormBearings, 'worm', axial),
                'wheel': _Support(mbs, wheel, WHEEL_AXIS, wheelBearings, 'wheel')}
    motor = CreateRotor(mbs, 1e-3, initialAngle=init['phi0'], initialSpeed=init['omega0'], name='motor')
    CreatePrescribedRotation(mbs, motor, profile, name='motorDrive', useSymbolic=useSymbolic)
    wormAngle = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=worm['nodeNumber'], coordinate=TURN))
    mbs.AddObject(CoordinateSpringDamper(markerNumbers=[motor['markerNumber'], wormAngle], stiffness=drive.kT,
                                         damping=drive.dT, name='driveShaft'))
    wheelAngle = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=wheel['nodeNumber'], coordinate=TURN))
    # the load-side chain on the wheel's turn (its last Rxyz angle): wheel --kL1-- loadInertia1 --kL2-- ...
    loadRotors = CreateLoadSideChain(mbs, {'markerNumber': wheelAngle, 'nodeNumber': wheel['nodeNumber']}, loadChain,
                                     init)
    if load is not None and loadRotors:        # the load torque on the chain's last stage
        CreateRotorTorque(mbs, loadRotors[-1], load, name='reelLoad', useSymbolic=useSymbolic)
    elif load is not None:                     # the load torque on the wheel's turn about z
        AddCoordinateForce(mbs, wheel['nodeNumber'], wheelAngle,
                           lambda t, phi, omega, ops: load.Torque(phi, omega, t, ops), name='reelLoad',
                           useSymbolic=useSymbolic, where=w, signature='load.Torque(phi, omega, t, ops)')
    connector = CreateRigidBodyWormGear(mbs, [worm, wheel], gear=gear, wormAxis=[0., 0., 1.], wheelAxis=[0., 0., 1.],
                                        name='wormGear', contactOptions=contactOptions, useSymbolic=useSymbolic)
    return RigidBodyReelChanger(mbs.GetSystemContainer(), mbs, connector, {'worm': worm, 'wheel': wheel}, bearings, drive, dict(init),
                                motor=motor, load=load, axialBearing=axial, loadRotors=loadRotors)


def _ShaftInertia(mbs, node: int, inertia: float, name: str) -> Optional[int]:
    """What turns with a body without tilting with it: ``inertia`` (kg*m^2) on the node's turn coordinate alone, an
    ``ObjectGenericODE2`` with that one mass entry and no forces (nothing if ``inertia`` is 0)."""
    if inertia <= 0.:
        return None
    from exudyn.itemInterface import ObjectGenericODE2
    mass = np.zeros((6, 6))
    mass[TURN, TURN] = inertia
    return mbs.AddObject(ObjectGenericODE2(nodeNumbers=[node], massMatrix=mass, stiffnessMatrix=np.zeros((6, 6)),
                                           dampingMatrix=np.zeros((6, 6)), name=name + 'ShaftInertia'))


def _Support(mbs, body, axis, bearings: Optional[ShaftBearings], name: str, axial=None):
    """Ideal revolute joint about the global ``axis`` through the body's reference point, or the elastic bearings;
    with ``axial`` (an AxialBearing) the joint lets the body slide along the axis on the axial spring-damper.

    The ideal joint holds the node's translations and the two Tait-Bryan angles that are not the body's turn at
    their reference values, one linear ``ObjectConnectorCoordinateVector``: exact for the Rxyz nodes of this model
    (both turn about their last angle), and its Jacobian does not turn with the body
    (an ``ObjectJointGeneric`` made the modified Newton iteration take three times the iterations and a Jacobian
    every ten steps, benchmarks/README.md). Its multipliers, the forces on the held coordinates, are the bearing
    loads (global x, y, z)."""
    if bearings is not None:
        return CreateShaftBearings(mbs, body, axis=axis, bearings=bearings, name=name + 'Bearing')
    import exudyn as exu
    from exudyn.itemInterface import (MarkerNodeCoordinates, NodePointGround, ObjectConnectorCoordinateVector,
                                      SensorObject)
    node = body['nodeNumber']
    along = int(np.argmax(np.abs(axis)))                    # the translation along the (global) axis
    held = [k for k in range(6) if k != TURN and not (axial is not None and k == along)]
    reference = np.asarray(mbs.GetNode(node)['referenceCoordinates'], dtype=float)[held]
    # the item couples two markers: the second is a ground node's (no coordinates)
    joint = mbs.AddObject(ObjectConnectorCoordinateVector(
        markerNumbers=[mbs.AddMarker(MarkerNodeCoordinates(nodeNumber=node)),
                       mbs.AddMarker(MarkerNodeCoordinates(nodeNumber=mbs.AddNode(NodePointGround())))],
        scalingMarker0=np.eye(6)[held], scalingMarker1=np.zeros((len(held), 0)), offset=list(-reference),
        name=name + 'Joint'))
    OVT = exu.OutputVariableType
    out = {'joint': joint, 'heldCoordinates': held, 'axis': np.asarray(axis, dtype=float),
           'sensors': {'joint': mbs.AddSensor(SensorObject(objectNumber=joint, outputVariableType=OVT.Force,
                                                           storeInternal=True, writeToFile=False))}}
    if axial is not None:                      # the worm's axial coordinate: its node's translation along the axis
        from exudyn.itemInterface import CoordinateSpringDamper, MarkerNodeCoordinate, NodePointGround
        nGround = mbs.AddNode(NodePointGround())
        m0 = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nGround, coordinate=0))
        m1 = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=node, coordinate=along))
        out['axialSpring'] = mbs.AddObject(CoordinateSpringDamper(markerNumbers=[m0, m1], stiffness=axial.stiffness,
                                                                  damping=axial.damping, name=name + 'Axial'))
        out['sensors']['axialSpring'] = mbs.AddSensor(SensorObject(objectNumber=out['axialSpring'],
                                                                   outputVariableType=OVT.Force,
                                                                   storeInternal=True, writeToFile=False))
    return out
