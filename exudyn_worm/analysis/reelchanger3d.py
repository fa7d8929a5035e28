"""The reel changer with worm and wheel as 3D rigid bodies, on ideal revolute joints or on elastic bearings.

:func:`BuildRigidBodyReelChanger` builds the drive of :func:`~exudyn_worm.setups.build.BuildReelChanger`
(motor at constant speed, drive shaft kT, dT, worm, mesh, wheel, the reel's lever load) with the worm and the wheel
as ``mbs.CreateRigidBody`` bodies coupled by :func:`~exudyn_worm.items.rigidmesh.CreateRigidBodyWormGear`. Each
shaft sits on ideal revolute joints to ground, or on :func:`~exudyn_worm.items.bearings.CreateShaftBearings`
(two radial bearings and an axial bearing, stiffness and damping). Both bodies use Tait-Bryan nodes (``Rxyz``):
the worm turns about global x (its first angle), the wheel about global z (its last angle), so the drive shaft and
the load act on those coordinates (the torque about the axis, for any tilt of the wheel and to first order in the
worm's tilt). The centre line is global +y; the pitch point is at y = r1.

Parameter sets: those of the reel changer without drive-side or load-side chains, with a constant-speed motor (the
presets reel-P1 ... reel-P7); an axial bearing ``kA, dA, mA`` lets the worm (of mass mA) slide on its revolute
joint against the axial spring-damper, the model of :func:`~exudyn_worm.items.connector.CreateWormAxialBearing`.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, Mapping, Optional

import numpy as np

from .._checks import CheckPositive
from ..items.bearings import ShaftBearings, CreateShaftBearings
from ..items.drivetrain import CreatePrescribedRotation, CreateRotor
from ..items.equilibrium import SteadyInitialState
from ..items._userfunctions import SetGenericForceLaw
from ..items.rigidmesh import CreateRigidBodyWormGear, RigidBodyWormGearConnector
from ..model.contact import ContactOptions
from ..model.profiles import ConstantSpeed
from ..setups.duty import LoadFromParameters
from ..setups.presets import AxialBearingFromParameters, ElasticDriveFromParameters, DriveSideChain, LoadSideChain

__all__ = ['RigidBodyReelChanger', 'BuildRigidBodyReelChanger', 'WORM_MASS', 'WHEEL_MASS']

#: default mass in kg of the worm body (a steel worm shaft of the reel changer's size; only the bearings feel it)
WORM_MASS = 5.
#: default mass in kg of the wheel body
WHEEL_MASS = 30.


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
    """
    systemContainer: Any
    mbs: Any
    connector: RigidBodyWormGearConnector
    bodies: Dict[str, Any]
    bearings: Dict[str, Any]
    drive: Any
    initial: Dict[str, float] = field(default_factory=dict)


def BuildRigidBodyReelChanger(parameters: Mapping[str, float], contactOptions: ContactOptions = ContactOptions(),
                              useSymbolic: bool = True, wormBearings: Optional[ShaftBearings] = None,
                              wheelBearings: Optional[ShaftBearings] = None, wormMass: float = WORM_MASS,
                              wheelMass: float = WHEEL_MASS) -> RigidBodyReelChanger:
    """Build the reel changer with worm and wheel as rigid bodies (module docstring), starting in equilibrium.

    Parameters
    ----------
    parameters : mapping
        A reel-changer parameter set without chains, axial bearing or other duty (e.g. ``GetPreset('reel-P1')``).
    contactOptions : ContactOptions
        Options of the contact law.
    useSymbolic : bool
        C++ symbolic user functions (default) or plain Python.
    wormBearings, wheelBearings : ShaftBearings, optional
        Elastic bearings of the shafts; None (default): ideal revolute joints to ground.
    wormMass, wheelMass : float
        Masses in kg of the bodies (> 0); the moments of inertia about the axes are J1 and J2 of the set.

    Returns
    -------
    RigidBodyReelChanger

    Raises
    ------
    ValueError
        For a parameter set with chains, an axial bearing or a motor other than constant speed, or a bad mass.
    """
    import exudyn as exu
    from exudyn.itemInterface import CoordinateSpringDamper, MarkerNodeCoordinate, ObjectGenericODE2
    from exudyn.rigidBodyUtilities import RigidBodyInertia, RotationMatrixX, RotationMatrixZ

    w = 'BuildRigidBodyReelChanger'
    wormMass, wheelMass = CheckPositive(w, 'wormMass', wormMass, 'kg'), CheckPositive(w, 'wheelMass', wheelMass, 'kg')
    if DriveSideChain(parameters) or LoadSideChain(parameters):
        raise ValueError(f"{w}: the rigid-body reel changer has no drive-side or load-side chain: remove J4.., JL1.. "
                         f"from the parameter set")
    axial = AxialBearingFromParameters(parameters)
    if axial is not None and wormBearings is not None:
        raise ValueError(f"{w}: give the worm's axial bearing once: as kA, dA, mA of the parameter set or in "
                         f"'wormBearings'")
    if parameters.get('motorType', 'constantSpeed') != 'constantSpeed':
        raise ValueError(f"{w}: the rigid-body reel changer drives the motor at constant speed, got motorType = "
                         f"{parameters.get('motorType')!r}")
    drive = ElasticDriveFromParameters(parameters)
    gear = drive.gear
    load = LoadFromParameters(parameters, w)
    motorSpeed = float(parameters['motorSpeed'])
    init = SteadyInitialState(drive, load, motorSpeed, contactOptions, axial)
    if axial is not None:
        wormMass = axial.mass                  # the worm moves axially as a whole

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    a = gear.r1 + gear.r2
    # Rxyz angles: the worm's first angle is its turn about global x, the wheel's last its turn about global z
    worm = mbs.CreateRigidBody(name='worm', nodeType=exu.NodeType.RotationRxyz, referencePosition=[0., 0., 0.],
                               inertia=RigidBodyInertia(mass=wormMass,
                                                        inertiaTensor=np.diag([drive.J1, drive.J1, drive.J1])),
                               initialRotationMatrix=RotationMatrixX(init['phi1']),
                               initialDisplacement=[init.get('xA', 0.), 0., 0.], initialVelocity=[init.get('vA', 0.), 0., 0.],
                               initialAngularVelocity=[init['omega1'], 0., 0.], returnDict=True)
    wheel = mbs.CreateRigidBody(name='wheel', nodeType=exu.NodeType.RotationRxyz, referencePosition=[0., a, 0.],
                                inertia=RigidBodyInertia(mass=wheelMass,
                                                         inertiaTensor=np.diag([drive.J2, drive.J2, drive.J2])),
                                initialRotationMatrix=RotationMatrixZ(init['phi2']),
                                initialAngularVelocity=[0., 0., init['omega2']], returnDict=True)
    bearings = {'worm': _Support(mbs, worm, [1., 0., 0.], wormBearings, 'worm', axial),
                'wheel': _Support(mbs, wheel, [0., 0., 1.], wheelBearings, 'wheel')}
    motor = CreateRotor(mbs, 1e-3, initialAngle=0., initialSpeed=motorSpeed, name='motor')
    CreatePrescribedRotation(mbs, motor, ConstantSpeed(motorSpeed), name='motorDrive', useSymbolic=useSymbolic)
    wormAngle = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=worm['nodeNumber'], coordinate=3))
    mbs.AddObject(CoordinateSpringDamper(markerNumbers=[motor['markerNumber'], wormAngle], stiffness=drive.kT,
                                         damping=drive.dT, name='driveShaft'))
    if load is not None:                       # the load torque on the wheel's angle about z (its last Rxyz angle)
        zeros = np.zeros((6, 6))
        oLoad = mbs.AddObject(ObjectGenericODE2(nodeNumbers=[wheel['nodeNumber']], massMatrix=zeros,
                                                stiffnessMatrix=zeros, dampingMatrix=zeros, name='reelLoad'))
        SetGenericForceLaw(mbs, oLoad, 6, lambda t, q, q_t, ops: [0.] * 5 + [load.Torque(q[5], q_t[5], t, ops)],
                           useSymbolic, where=w)
    connector = CreateRigidBodyWormGear(mbs, [worm, wheel], gear=gear, wormAxis=[1., 0., 0.], wheelAxis=[0., 0., 1.],
                                        name='wormGear', contactOptions=contactOptions)
    return RigidBodyReelChanger(SC, mbs, connector, {'worm': worm, 'wheel': wheel}, bearings, drive, dict(init))


def _Support(mbs, body, axis, bearings: Optional[ShaftBearings], name: str, axial=None):
    """Ideal revolute joint about the global ``axis`` through the body's reference point, or the elastic bearings;
    with ``axial`` (an AxialBearing) the joint lets the body slide along the axis on the axial spring-damper."""
    if bearings is not None:
        return CreateShaftBearings(mbs, body, axis=axis, bearings=bearings, name=name + 'Bearing')
    import exudyn as exu
    from exudyn.itemInterface import MarkerBodyRigid, ObjectGround, ObjectJointGeneric
    from exudyn.rigidBodyUtilities import RotationMatrixY
    position = np.asarray(mbs.GetNode(body['nodeNumber'])['referenceCoordinates'][:3], dtype=float)
    ground = mbs.AddObject(ObjectGround(referencePosition=list(position)))
    # the joint's free rotation is its x axis: turned onto the shaft axis
    rotation = np.eye(3) if axis[0] == 1. else RotationMatrixY(-np.pi / 2)
    mGround = mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localHT=exu.HT(rotation=rotation)))
    mBody = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body['bodyNumber'], localHT=exu.HT(rotation=rotation)))
    joint = mbs.AddObject(ObjectJointGeneric(markerNumbers=[mGround, mBody],
                                             constrainedAxes=[0 if axial is not None else 1, 1, 1, 0, 1, 1],
                                             name=name + 'Joint'))
    out = {'joint': joint, 'markerNumbers': [mGround, mBody]}
    if axial is not None:                      # the worm's axial coordinate: its node's x (the axis is global x)
        from exudyn.itemInterface import CoordinateSpringDamper, MarkerNodeCoordinate, NodePointGround
        nGround = mbs.AddNode(NodePointGround())
        m0 = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nGround, coordinate=0))
        m1 = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=body['nodeNumber'], coordinate=0))
        out['axialSpring'] = mbs.AddObject(CoordinateSpringDamper(markerNumbers=[m0, m1], stiffness=axial.stiffness,
                                                                  damping=axial.damping, name=name + 'Axial'))
    return out
