"""The lowering phase of the reel changer as an autonomous system, the model the orbit functions work on.

The lowering phase is modelled as the linear analysis sees it: the motor turns at constant speed
``motorSpeed`` and the wheel carries the constant load torque ``loadMass * g * leverArm`` that drives it
forward (the reel changer's load -m g l cos(phi2) at phi2 = pi, the middle of the lowering phase). With the
angles taken relative to the steady rotation (``phi - omega t``) and the speeds relative to the steady speeds,
the drive is then autonomous, and its state is ``(phi1 - omega1 t, phi2 - omega2 t, phi1' - omega1, phi2' -
omega2)``, extended by every other free coordinate of the drive (drive-side and load-side chain rotors, the worm's
axial coordinate: :func:`BuildLoweringModel`). :func:`LoweringModelOfSystem` makes the same model of your own
Exudyn system with a worm-gear connector; :func:`SettleLowering` simulates it from its kicked steady state.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple

import numpy as np

from ...model.contact import ContactOptions
from ...model.profiles import STANDARD_GRAVITY, ConstantSpeed, ConstantTorque, GravityLeverTorque
from ..._checks import CheckPositive, CheckSystem
from ...items.connector import CONNECTORS_KEY, WormGearConnector
from ...items.rigidmesh import RIGID_CONNECTORS_KEY, RigidBodyWormGearConnector
from ...items.smallmesh import SMALL_CONNECTORS_KEY, SmallWormGearConnector
from ..stability.drivestability import AnalyzeDrive
from ...drive.wholedrive import CheckDrive, Component, Drive
from ...drive.presets import DUTY_KEYS
from ...builders.oneangle import BuildReelChanger, CheckReelChangerKeys
from ...builders.rigidbody import BuildRigidBodyReelChanger
from ...items.equilibrium import SteadyInitialState
from .exudynflow import ExudynFlow, _AddFlowSensors, _Configuration, _HeldCoordinates

__all__ = ['LoweringModel', 'LOWERING_LEVER_ARM', 'LoweringPhaseDrive', 'BuildLoweringModel', 'IN_PLACE_KEYS',
           'BuildRigidBodyLoweringModel',
           'UpdateLoweringModel', 'SettleLowering', 'EquilibriumState', 'StateScale', 'LoweringModelOfSystem']


@dataclass
class LoweringModel:
    """The Exudyn model of the lowering phase and what the shooting needs to know about it.

    Parameters
    ----------
    systemContainer : exudyn.SystemContainer
        Keeps the system alive.
    mbs : exudyn.MainSystem
        The system.
    drive : ElasticDrive
        The two-mass drive of the parameter set.
    connector : WormGearConnector
        The mesh.
    rotors : dict of str to dict
        Motor, worm and wheel rotors (:func:`~exudyn_worm.items.drivetrain.CreateRotor`).
    steady : dict of str to float
        The steady state of lowering (:func:`~exudyn_worm.items.equilibrium.SteadyInitialState`).
    motorSpeed : float
        Motor speed in rad/s.
    loadTorque : float
        Constant load torque on the wheel in N*m (loadMass g leverArm, lowering).
    staticNormalForce : float
        Normal force of the steady state in N.
    contactOptions : ContactOptions
        Options of the contact law.
    whole : Drive or None
        The drive the model was built from (None for :func:`LoweringModelOfSystem`).
    coordinates : tuple of int
        ODE2 coordinate indices of the flow state: the worm's, the wheel's, then every other free coordinate
        (drive-side and load-side chain rotors, the worm's axial coordinate, ...).
    steadySpeeds : ndarray
        Steady speed of every ODE2 coordinate of ``mbs`` (rad/s or m/s; 0 for a coordinate at rest).
    stateKeys : tuple of str
        Key of ``steady`` that holds the equilibrium position of each coordinate of ``coordinates``.
    initialCoordinates : ndarray
        ODE2 coordinates of the steady state at t = 0 (a prescribed motor's angle among them).
    nodeSensors : tuple of (int, int, int)
        Per coordinate of ``coordinates``: the node sensors of its node's positions and velocities and the
        coordinate's column in them.
    rigidBody : RigidBodyReelChanger or None
        The 3D model the system was built as (:func:`BuildRigidBodyLoweringModel`), for its bearing loads.
    dependent : (tuple of int, ndarray) or None
        The coordinates outside the state that the flow sets from the others (a rigid-body mesh law's auxiliary
        coordinates, :class:`~exudyn_worm.analysis.orbits.exudynflow.ExudynFlow` ``dependent``).
    """
    systemContainer: Any
    mbs: Any
    drive: Any
    connector: Any
    rotors: Dict[str, Dict]
    steady: Dict[str, float]
    motorSpeed: float
    loadTorque: float
    staticNormalForce: float
    contactOptions: ContactOptions
    whole: Optional[Drive]
    coordinates: Tuple[int, ...] = ()
    steadySpeeds: Any = None
    stateKeys: Tuple[str, ...] = ()
    initialCoordinates: Any = None
    nodeSensors: Tuple[Tuple[int, int, int], ...] = ()
    rigidBody: Any = None
    dependent: Any = None


#: lever arm in m with which :func:`LoweringPhaseDrive` writes a drive's lowering load torque as the reel keys
#: (the periodic-orbit analysis takes only their product ``loadMass * g * leverArm``, a constant torque)
LOWERING_LEVER_ARM = 1.


def LoweringPhaseDrive(drive: Drive) -> Drive:
    """The drive of the periodic-orbit analysis for any drive: the lowering phase of its own duty.

    The analysis follows the chatter of steady lowering: the motor at constant speed, a constant load torque that
    drives the gear (the reel changer's duty: ``motorSpeed``, ``loadMass``, ``leverArm``). The reel changer's duty is
    taken as it is. Any other duty is replaced by its lowering operating point
    (:func:`~exudyn_worm.drive.operatingpoints.DutyOperatingPoints`, S = -1; of several, the one with the largest
    real part at which the linear analysis, :func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive`,
    puts it): the speed's magnitude as ``motorSpeed`` and its load torque as ``loadMass * g * leverArm`` with
    ``leverArm`` = :data:`LOWERING_LEVER_ARM` (a drive turning backwards while lowering is its mirror image).

    Parameters
    ----------
    drive : Drive
        The drive (:func:`~exudyn_worm.drive.wholedrive.ResolveDrive`).

    Returns
    -------
    Drive
        ``drive`` itself for the reel changer's duty, else the drive with the lowering duty
        (:meth:`~exudyn_worm.drive.wholedrive.Drive.Replace`).

    Raises
    ------
    ValueError
        If the drive has no lowering phase, or a motor on its characteristic (the analysis holds the motor).
    """
    w = 'LoweringPhaseDrive'
    drive = CheckDrive(w, drive)
    if drive.hasMotorCharacteristic:
        raise ValueError(f"{w}: the periodic-orbit analysis holds the motor at constant speed (the lowering phase of "
                         f"the linear analysis); this drive has {Component.MOTOR_CHARACTERISTIC.text} (not "
                         f"supported); leave those keys out")
    if _HasReelDuty(drive):
        return drive
    analysis = AnalyzeDrive(drive)
    lowering = [p for p in analysis.operatingPoints if p.S == -1]
    if not lowering:
        raise ValueError(f"{w}: the drive's duty has no lowering phase at a steady speed (no phase in which the load "
                         f"drives the gear; {analysis.decidingText}); the periodic-orbit analysis follows the chatter "
                         f"of lowering")
    point = max(lowering, key=lambda p: p.maxRealPart).point
    changes: Dict[str, Any] = {k: None for k in DUTY_KEYS if k in drive.parameters}
    changes.update(motorSpeed=abs(point.motorSpeed), leverArm=LOWERING_LEVER_ARM,
                   loadMass=abs(point.loadTorque) / (STANDARD_GRAVITY * LOWERING_LEVER_ARM))
    return drive.Replace(**changes)


def _HasReelDuty(drive: Drive) -> bool:
    """The reel changer's duty with all its keys: a lever load at constant motor speed."""
    return drive.loadType == 'lever' and drive.motorType == 'constantSpeed' and isinstance(drive.load,
                                                                                          GravityLeverTorque)


def _LoweringDuty(drive: Drive, where: str) -> Tuple[Drive, float, float]:
    """The drive of the lowering model (the reel changer's duty with a constant load torque instead of the lever),
    its motor speed in rad/s and its load torque in N*m."""
    drive = CheckDrive(where, drive)
    CheckReelChangerKeys(drive, where)
    if drive.hasMotorCharacteristic:
        raise ValueError(f"{where}: the periodic-orbit analysis holds the motor at constant speed 'motorSpeed' (the "
                         f"lowering phase of the linear analysis); this drive has "
                         f"{Component.MOTOR_CHARACTERISTIC.text} (not supported); leave those keys out")
    if not _HasReelDuty(drive):
        raise ValueError(f"{where}: the periodic-orbit analysis needs the reel changer's duty (a lever load at "
                         f"constant motor speed, the lowering phase of the linear analysis); this drive has load "
                         f"{drive.loadType} and motor {drive.motorType}: make its lowering drive with "
                         f"LoweringPhaseDrive(drive)")
    motorSpeed = CheckPositive(where, 'motorSpeed', drive.motor.speed, 'rad/s')
    loadTorque = drive.load.maximum
    return drive.Replace(loadType='constant', loadTorque=loadTorque), motorSpeed, loadTorque


def BuildLoweringModel(drive: Drive, contactOptions: ContactOptions = ContactOptions(),
                       useSymbolic: bool = True) -> LoweringModel:
    """Exudyn model of the reel changer's lowering phase: motor at constant speed, constant load torque
    ``loadMass * g * leverArm`` driving the wheel (the last rotor of a load-side chain), starting in the steady
    state (static mesh deflection, every shaft of the chains pre-twisted by the torque it carries).

    The system is the time simulation's own (:func:`~exudyn_worm.builders.oneangle.BuildReelChanger` with the duty
    ``loadType = constant``, ``loadTorque = loadMass * g * leverArm`` and the motor at ``motorSpeed``), so the
    drive-side chain (``J4, k4, d4, ...``), the load-side chain (``JL1, kL1, dL1, ...``) and the worm's axial
    bearing (``kA, dA, mA``) are built as a simulation builds them. The flow state holds every free ODE2
    coordinate (``LoweringModel.coordinates``).

    Parameters
    ----------
    drive : Drive
        A drive with the reel changer's duty (e.g. ``ResolveDrive('reel-P1')``; any other duty through
        :func:`LoweringPhaseDrive`), with or without the chains and the axial bearing; a motor on its characteristic
        is refused.
    contactOptions : ContactOptions
        Options of the contact law.
    useSymbolic : bool
        Symbolic (C++) user functions (default) or plain Python.

    Returns
    -------
    LoweringModel

    Raises
    ------
    ValueError, TypeError
        For a drive without the reel changer's duty, or with a component the lowering model does not have (a motor
        on its characteristic: the lowering phase holds the motor at constant speed).
    """
    import exudyn as exu
    w = 'BuildLoweringModel'
    lowering, motorSpeed, loadTorque = _LoweringDuty(drive, w)
    if not isinstance(contactOptions, ContactOptions):
        raise TypeError(f"{w}: 'contactOptions' must be a ContactOptions, got {type(contactOptions).__name__}")
    # the time simulation's builder, with the lowering phase as its duty: one assembly of the chains
    reel = BuildReelChanger(exu.SystemContainer().AddSystem(), lowering, contactOptions, useSymbolic,
                            startFromEquilibrium=True, profile=ConstantSpeed(motorSpeed))
    mbs = reel.mbs
    mbs.Assemble()                                  # coordinate indices and sizes exist from here on
    steady = _SteadyState(lowering, loadTorque, motorSpeed, contactOptions)
    # the flow state: worm, wheel, then the chains' rotors and the worm's axial coordinate, each with the key of
    # its equilibrium position in ``steady`` (SteadyInitialState's names) and of its steady speed
    nodes = [(reel.rotors['worm'], 'phi1', 'omega1'), (reel.rotors['wheel'], 'phi2', 'omega2')]
    nodes += [(reel.rotors[f'inertia{i}'], f'phi{i}', f'omega{i}') for i in range(4, 4 + len(reel.chain))]
    nodes += [(reel.rotors[f'loadInertia{i}'], f'phiL{i}', f'omegaL{i}') for i in range(1, 1 + len(reel.loadChain))]
    if reel.axialBearing is not None:
        nodes.append((reel.axialBearing, 'xA', 'vA'))
    index = [mbs.GetNodeODE2Index(node['nodeNumber']) for node, _, _ in nodes]
    speeds = np.zeros(mbs.systemData.ODE2Size())
    speeds[mbs.GetNodeODE2Index(reel.rotors['motor']['nodeNumber'])] = motorSpeed
    speeds[index] = [steady[v] for _, _, v in nodes]
    sensors = _AddFlowSensors(mbs, index)
    mbs.Assemble()
    static = _MeshAt(reel.connector, steady)
    rotors = {**reel.rotors, 'driveShaft': {'objectNumber': mbs.GetObjectNumber('driveShaft')}}
    initial = np.array(mbs.systemData.GetODE2Coordinates(configuration=_Configuration().Initial), dtype=float)
    return LoweringModel(reel.systemContainer, mbs, lowering.elastic, reel.connector, rotors, steady, motorSpeed,
                         loadTorque, abs(float(static.normalForce)), contactOptions, drive, tuple(index), speeds,
                         tuple(p for _, p, _ in nodes), initial, sensors)


def BuildRigidBodyLoweringModel(drive: Drive, contactOptions: ContactOptions = ContactOptions()) -> LoweringModel:
    """The lowering model of :func:`BuildLoweringModel` on the 3D model: worm and wheel as rigid bodies on their
    shafts' bearings (:func:`~exudyn_worm.builders.rigidbody.BuildRigidBodyReelChanger`: with both shafts' bearings
    its small-displacement model, on ideal joints the rigid bodies), motor at constant
    speed ``motorSpeed``, constant load torque ``loadMass * g * leverArm`` on the wheel's turn, starting in the
    static equilibrium under that load (the mesh and the bearings deflected). The flow state holds every free ODE2
    coordinate (the small-displacement model's twelve; on joints both bodies' six, the C++ mesh law's auxiliary ones
    set by the flow: :func:`LoweringModelOfSystem`).

    Parameters
    ----------
    drive : Drive
        A drive with the reel changer's duty and the shafts' bearings (``wormRadialStiffness``, ...,
        :attr:`~exudyn_worm.drive.wholedrive.Drive.shaftSupports`), without chains.
    contactOptions : ContactOptions
        Options of the contact law.

    Returns
    -------
    LoweringModel
        ``rigidBody`` holds the 3D model (its bearings, for
        :func:`~exudyn_worm.analysis.simulation.reelchanger3d.StoredShaftLoads`).

    Raises
    ------
    ValueError, TypeError
        For a drive the lowering model or the 3D model refuses.
    """
    # lazy: the 3D model is built only for drives with shaft bearings
    from ..simulation.reelchanger3d import AddSeriesSensors
    import exudyn as exu
    w = 'BuildRigidBodyLoweringModel'
    lowering, motorSpeed, loadTorque = _LoweringDuty(drive, w)
    if not isinstance(contactOptions, ContactOptions):
        raise TypeError(f"{w}: 'contactOptions' must be a ContactOptions, got {type(contactOptions).__name__}")
    reel = BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), lowering, contactOptions,
                                     profile=ConstantSpeed(motorSpeed), startFromEquilibrium=True)
    sensors = AddSeriesSensors(reel)
    if reel.model == 'exact':
        reel.connector.sensors.update(wormAccelerations=sensors['wormAccelerations'],
                                      wheelAccelerations=sensors['wheelAccelerations'])
    reel.mbs.Assemble()
    model = LoweringModelOfSystem(reel.mbs, reel.connector)
    model.systemContainer, model.drive, model.rigidBody = reel.systemContainer, reel.drive, reel
    model.motorSpeed, model.loadTorque, model.whole = motorSpeed, loadTorque, drive
    return model


def _SteadyState(drive: Drive, loadTorque: float, motorSpeed: float, contactOptions: ContactOptions
                 ) -> Dict[str, float]:
    """The steady state of lowering with the drive's chains and axial bearing, as
    :func:`~exudyn_worm.builders.oneangle.BuildReelChanger` starts its system."""
    return SteadyInitialState(drive.elastic, ConstantTorque(loadTorque), motorSpeed, contactOptions,
                              drive.axialBearing, drive.driveSideChain, loadSide=drive.loadSideChain)


def _MeshAt(connector, state: Mapping[str, Any], mask=None):
    """The connector's mesh quantities for the states in ``state`` (keys ``phi1, phi2, omega1, omega2`` and, with
    an axial node, ``xA, vA``: a steady state or stored sensor series), at ``mask`` (None: all). A rigid-body
    connector's are in ``state['mesh']`` (:func:`_StoredStates`; the steady state's from its initial state)."""
    if isinstance(connector, (RigidBodyWormGearConnector, SmallWormGearConnector)):
        mesh = state['mesh']
        if mask is None:
            return mesh
        return _Masked(normalForce=np.asarray(mesh.normalForce)[mask], S=np.asarray(mesh.S)[mask])
    keys = ('phi1', 'phi2', 'omega1', 'omega2') + (() if connector.axialNodeNumber is None else ('xA', 'vA'))
    values = [np.asarray(state[k]) if mask is None else np.asarray(state[k])[mask] for k in keys]
    return connector.Evaluate(*values)


@dataclass
class _Masked:
    """The mesh quantities the orbit functions read, at some of the stored steps."""
    normalForce: Any
    S: Any


def _StoredStates(model: LoweringModel) -> Dict[str, Any]:
    """The stored series of the last solve with stored sensors: ``time``, ``omega1``, ``alpha2`` (the worm's and the
    wheel's turns; a rigid body's turn is its last Tait-Bryan angle) and, for a rigid-body connector, ``mesh`` (the
    mesh quantities of every stored step, :meth:`~exudyn_worm.items.rigidmesh.RigidBodyWormGearConnector.Evaluate`)."""
    connector, mbs = model.connector, model.mbs
    if isinstance(connector, SmallWormGearConnector):     # the shafts' coordinates from the model's nodes
        shafts = connector.StoredShaftStates(mbs)
        out = {'time': shafts['time'], 'mesh': connector.Evaluate(*(np.hstack([shafts['worm' + k], shafts['wheel' + k]])
                                                                     for k in ('Coordinates', 'Velocities')),
                                                                   shafts['time'])}
        for body, name in (('1', 'worm'), ('2', 'wheel')):
            out['phi' + body], out['omega' + body], out['alpha' + body] = (
                shafts[name + k][:, _RIGID_TURN] for k in ('Coordinates', 'Velocities', 'Accelerations'))
        return out
    if not isinstance(connector, RigidBodyWormGearConnector):
        return connector.StoredStates(mbs)
    time, q, v = connector._Stored(mbs)
    out = {'time': time, 'mesh': connector.Evaluate(q, v, time)}
    size = connector._kinematics.bodies[0].size
    for body, column in (('1', _RIGID_TURN), ('2', size + _RIGID_TURN)):
        out['phi' + body], out['omega' + body] = q[:, column], v[:, column]
    for body, key in (('1', 'wormAccelerations'), ('2', 'wheelAccelerations')):
        if key in connector.sensors:
            out['alpha' + body] = np.asarray(mbs.GetSensorStoredData(connector.sensors[key]))[:, 1 + _RIGID_TURN]
        else:                         # no acceleration sensor: the speed's slope
            out['alpha' + body] = np.gradient(out['omega' + body], time)
    return out


#: the turn among a rigid-body node's coordinates that the lowering model follows: the last Tait-Bryan angle of an
#: Rxyz node turning about it (as :func:`~exudyn_worm.builders.rigidbody.BuildRigidBodyReelChanger` builds them)
_RIGID_TURN = 5


def _StoredFlowStates(model: LoweringModel) -> Tuple[np.ndarray, np.ndarray]:
    """Times (s, from the start of the last solve) and flow states (one row per stored step) of the last solve
    with stored sensors."""
    data = {s: np.asarray(model.mbs.GetSensorStoredData(s)) for sensors in model.nodeSensors for s in sensors[:2]}
    t = data[model.nodeSensors[0][0]][:, 0]
    q = np.column_stack([data[p][:, 1 + c] for p, _, c in model.nodeSensors])
    v = np.column_stack([data[u][:, 1 + c] for _, u, c in model.nodeSensors])
    speeds = model.steadySpeeds[np.asarray(model.coordinates)]
    return t, np.hstack([q - np.outer(t, speeds), v - speeds])


#: parameters that :func:`UpdateLoweringModel` changes in the built system (others rebuild it)
IN_PLACE_KEYS = ('J1', 'J2', 'kT', 'DT', 'dT', 'DTV')


def UpdateLoweringModel(model: LoweringModel, drive: Drive) -> LoweringModel:
    """The lowering model of ``drive``: ``model`` changed in place if only :data:`IN_PLACE_KEYS` differ from the
    drive it was built for (inertias, shaft stiffness and damping), else a new model; the 3D model
    (``model.rigidBody``) is built anew (:func:`BuildRigidBodyLoweringModel`, about 0.02 s) for any change.

    Parameters
    ----------
    model : LoweringModel
    drive : Drive
        The new drive (e.g. ``model.whole.Replace(J1=0.2)``).

    Returns
    -------
    LoweringModel
    """
    drive = CheckDrive('UpdateLoweringModel', drive)
    old, new = model.whole.parameters, drive.parameters
    changed = {k for k in set(new) | set(old) if new.get(k) != old.get(k)}
    if not changed:
        return model
    if model.rigidBody is not None:
        return BuildRigidBodyLoweringModel(drive, model.contactOptions)
    if not changed <= set(IN_PLACE_KEYS):
        return BuildLoweringModel(drive, model.contactOptions)
    elastic = drive.elastic
    mbs = model.mbs
    mbs.SetObjectParameter(model.rotors['worm']['objectNumber'], 'inertia', elastic.J1)
    mbs.SetObjectParameter(model.rotors['wheel']['objectNumber'], 'inertia', elastic.J2)
    mbs.SetObjectParameter(model.rotors['driveShaft']['objectNumber'], 'stiffness', elastic.kT)
    mbs.SetObjectParameter(model.rotors['driveShaft']['objectNumber'], 'damping', elastic.dT)
    mbs.Assemble()
    model.drive, model.whole = elastic, drive
    model.steady = _SteadyState(drive, model.loadTorque, model.motorSpeed, model.contactOptions)
    return model


def _LoweringFlow(model: LoweringModel, stepsPerPeriod: int,
                  solverSettings: Optional[Mapping[str, Any]] = None) -> ExudynFlow:
    flow = ExudynFlow(model.mbs, model.coordinates, model.steadySpeeds, stepsPerPeriod, solverSettings=solverSettings,
                      dependent=model.dependent)
    flow.q0 = np.array(model.initialCoordinates, dtype=float)     # coordinates outside the state (the motor)
    return flow


def SettleLowering(model: LoweringModel, duration: float, kick: float = 0.01, stepSize: float = 1e-4,
                   store: bool = False) -> Tuple[np.ndarray, 'ExudynFlow']:
    """Time simulation of the lowering phase from the steady state with the worm speed kicked by ``kick``
    (relative to the motor speed); returns the flow state at the end and the flow used.

    Parameters
    ----------
    model : LoweringModel
    duration : float
        Simulated time in s.
    kick : float
        Initial worm speed disturbance as a fraction of the motor speed.
    stepSize : float
        Time step in s.
    store : bool
        Keep the sensors' samples of every step (read them with ``model.connector.StoredStates(model.mbs)``).

    Returns
    -------
    (ndarray, ExudynFlow)
    """
    steps = max(10, int(round(duration / stepSize)))
    flow = _LoweringFlow(model, steps)
    x = EquilibriumState(model)
    x[len(model.coordinates)] += kick * model.motorSpeed          # the worm's speed
    return flow.Solve(x, duration, storeSensors=store), flow


def EquilibriumState(model: LoweringModel) -> np.ndarray:
    """The static equilibrium of the lowering phase in flow coordinates (relative angles, speed deviations 0).

    Parameters
    ----------
    model : LoweringModel
    """
    return np.concatenate([[model.steady[k] for k in model.stateKeys], np.zeros(len(model.coordinates))])


def _PeriodFromSignal(t, y) -> float:
    """Median time between upward mean crossings of ``y``, with hysteresis (a crossing counts only after the
    signal has been below the mean by a quarter of its half swing), so that harmonics add no crossings."""
    y = y - np.mean(y)
    band = 0.25 * 0.5 * np.ptp(y)
    crossings, armed = [], False
    for k in range(1, y.size):
        if y[k] < -band:
            armed = True
        elif armed and y[k - 1] < 0 <= y[k]:
            crossings.append(t[k - 1] - y[k - 1] * (t[k] - t[k - 1]) / (y[k] - y[k - 1]))
            armed = False
    if len(crossings) < 3:
        return math.nan
    return float(np.median(np.diff(crossings[-6:])))


def StateScale(model: LoweringModel) -> np.ndarray:
    """Typical size of the flow state's components: the static mesh deflection as angles (each coordinate's in
    proportion to its steady speed: the worm's, the wheel's divided by the ratio; a coordinate at rest, such as
    the worm's axial one, the deflection as a length), times the chatter angular frequency (2 pi 40 Hz) as speeds.

    Parameters
    ----------
    model : LoweringModel
        The lowering model (its gear, static normal force and steady speeds).
    """
    g = model.connector.gear
    deflection = max(model.staticNormalForce / g.kV, 1e-9) / g.normalLever         # worm angle of the deflection
    speeds = np.abs(model.steadySpeeds[np.asarray(model.coordinates)])
    # a speed of round-off size (a tilt angle's rate from the rotation matrix of a rigid body's pose) is at rest
    angles = np.where(speeds > 1e-9 * speeds[0], deflection * speeds / speeds[0], deflection * g.normalLever)
    return np.concatenate([angles, angles * 2 * math.pi * 40.])


def LoweringModelOfSystem(mbs: Any, connector: WormGearConnector,
                          coordinates: Optional[Sequence[int]] = None) -> LoweringModel:
    """The model the orbit functions work on, for your own Exudyn system with a worm-gear connector.

    The system must be autonomous relative to its steady rotation, as the lowering phase is: motors held at
    constant speed, loads constant (not depending on angles or time), and it must start in that steady state:
    every coordinate at its steady speed (its initial velocity), the mesh deflected by the load and every shaft
    pre-twisted by the torque it carries (:func:`~exudyn_worm.items.equilibrium.SteadyInitialState`). The flow state
    is then ``(q - v0 t, q' - v0)`` over ``coordinates`` (:class:`~exudyn_worm.analysis.orbits.exudynflow.ExudynFlow`).

    Node sensors for the state's coordinates (and the connector's own, :meth:`WormGearConnector.AddSensors`, if it
    has none) are added to ``mbs`` and the system is assembled again; its initial state is kept.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The assembled system, in its steady state.
    connector : WormGearConnector or RigidBodyWormGearConnector
        The mesh of ``mbs`` (:func:`~exudyn_worm.items.connector.CreateWormGear`, or
        :func:`~exudyn_worm.items.rigidmesh.CreateRigidBodyWormGear` with ``useSymbolic`` on Rxyz nodes turning about
        their last angle, the worm's and the wheel's coordinate of the flow state) whose chatter is looked for; its
        worm must turn (initial worm speed != 0).
    coordinates : sequence of int, optional
        ODE2 coordinate indices of the flow state; default: every ODE2 coordinate not held by a coordinate
        constraint (``ObjectConnectorCoordinate``, e.g. the motor of ``CreatePrescribedRotation``). The worm's
        and the wheel's come first.

    Returns
    -------
    LoweringModel
        ``drive`` and ``whole`` are None, ``motorSpeed`` the worm's steady speed (kicks are fractions of
        it), ``loadTorque`` nan.

    Raises
    ------
    TypeError
        If ``mbs`` is not an ``exudyn.MainSystem`` or ``connector`` not a (rigid-body) worm-gear connector of ``mbs``.
    ValueError
        If the system is not assembled, the worm does not turn, the mesh carries no load at the initial state, or
        ``coordinates`` is not a set of ODE2 indices with the worm's and the wheel's.
    """
    w = 'LoweringModelOfSystem'
    CheckSystem(w, mbs)
    rigid = isinstance(connector, RigidBodyWormGearConnector)
    small = isinstance(connector, SmallWormGearConnector)
    if not (rigid and connector in mbs.variables.get(RIGID_CONNECTORS_KEY, [])
            or small and connector in mbs.variables.get(SMALL_CONNECTORS_KEY, [])
            or isinstance(connector, WormGearConnector) and connector in mbs.variables.get(CONNECTORS_KEY, [])):
        raise TypeError(f"{w}: 'connector' must be a WormGearConnector built in 'mbs' by CreateWormGear, a "
                        f"RigidBodyWormGearConnector built by CreateRigidBodyWormGear or a SmallWormGearConnector "
                        f"built by CreateSmallDisplacementWormGear, got {type(connector).__name__}")
    size = mbs.systemData.ODE2Size()
    if not size:
        raise ValueError(f"{w}: 'mbs' has no ODE2 coordinates: call mbs.Assemble() first")
    C = _Configuration()
    q0 = np.array(mbs.systemData.GetODE2Coordinates(configuration=C.Initial), dtype=float)
    v0 = np.array(mbs.systemData.GetODE2Coordinates_t(configuration=C.Initial), dtype=float)
    if small:                      # the turns are coordinates of the model's nodes
        worm, wheel = connector.TurnIndices(mbs)
    else:
        worm, wheel = (int(mbs.GetNodeODE2Index(n)) for n in connector.nodeNumbers)
    if rigid:                      # the turns: the flow state subtracts v0 t, exact for the last Rxyz angle only
        types = [str(mbs.GetNode(n)['nodeType']) for n in connector.nodeNumbers]
        if any(t != 'RigidBodyRxyz' for t in types) or connector.compiled is None:
            raise ValueError(f"{w}: a rigid-body mesh needs Tait-Bryan (RotationRxyz) nodes turning about their last "
                             f"angle and the law in C++ (CreateRigidBodyWormGear(useSymbolic=True)), got node types "
                             f"{', '.join(types)}" + ('' if connector.compiled is not None else ', the law in Python'))
        worm, wheel = worm + _RIGID_TURN, wheel + _RIGID_TURN
    if v0[worm] == 0.:
        raise ValueError(f"{w}: the worm's initial speed must be its steady speed (!= 0 rad/s): start the system in "
                         f"the steady rotation (SteadyInitialState), got 0 rad/s")
    dependent = _AuxiliaryCoordinates(mbs, connector) if rigid else None
    if coordinates is None:
        held = set(_HeldCoordinates(mbs)) | (set() if dependent is None else set(dependent[0].tolist()))
        coordinates = [i for i in range(size) if i not in held]
    if isinstance(coordinates, (str, bytes)) or not hasattr(coordinates, '__iter__'):
        raise TypeError(f"{w}: 'coordinates' must be a sequence of ODE2 indices, got {type(coordinates).__name__}")
    chosen = list(coordinates)
    if (any(isinstance(i, bool) or not isinstance(i, (int, np.integer)) or not 0 <= i < size for i in chosen)
            or len(set(chosen)) != len(chosen) or worm not in chosen or wheel not in chosen):
        raise ValueError(f"{w}: 'coordinates' must be distinct ODE2 indices in [0, {size - 1}] including the worm's "
                         f"({worm}) and the wheel's ({wheel}), got {chosen!r}")
    index = [worm, wheel] + sorted(int(i) for i in chosen if i not in (worm, wheel))
    sensors = _AddFlowSensors(mbs, index)               # first: it reads the assembled system's nodes
    if not connector.sensors:
        connector.AddSensors(mbs)
    mbs.Assemble()
    mbs.systemData.SetODE2Coordinates(q0.tolist(), configuration=C.Initial)
    mbs.systemData.SetODE2Coordinates_t(v0.tolist(), configuration=C.Initial)
    keys = ['phi1', 'phi2'] + [f'q{i}' for i in index[2:]]
    steady = {k: float(q0[i]) for k, i in zip(keys, index)}
    steady.update(omega1=float(v0[worm]), omega2=float(v0[wheel]))
    if rigid or small:
        steady['mesh'] = connector.InitialMeshState(mbs)
    elif connector.axialNodeNumber is not None:
        a = int(mbs.GetNodeODE2Index(connector.axialNodeNumber))
        steady.update(xA=float(q0[a]), vA=float(v0[a]))
    force = abs(float(_MeshAt(connector, steady).normalForce))
    if not force > 0:
        raise ValueError(f"{w}: the mesh carries no load at the initial state (normal force 0 N): start the system "
                         f"in the static equilibrium under its load (SteadyInitialState)")
    if dependent is not None and set(dependent[0].tolist()) & set(index):
        raise ValueError(f"{w}: 'coordinates' must leave out the mesh law's auxiliary coordinates "
                         f"{dependent[0].tolist()} (the flow sets them from the bodies' coordinates), got {chosen!r}")
    return LoweringModel(None, mbs, None, connector, {}, steady, abs(float(v0[worm])), math.nan, force,
                         connector.options, None, tuple(index), v0, tuple(keys), q0, sensors, dependent=dependent)


def _AuxiliaryCoordinates(mbs, connector: RigidBodyWormGearConnector) -> Tuple[np.ndarray, np.ndarray]:
    """The ODE2 indices of a C++ rigid-body mesh law's auxiliary coordinates and the matrix that maps all ODE2
    coordinates to them (their ties: ``X = S q_node`` up to a constant,
    :func:`~exudyn_worm.items.rigidmesh._CompileLaw`)."""
    size = mbs.systemData.ODE2Size()
    rows, maps = [], []
    for aux, tie in zip(connector.compiled['nodes'], connector.compiled['ties']):
        item = mbs.GetObject(tie)
        S = np.atleast_2d(np.asarray(item['scalingMarker1'], dtype=float))
        node = int(mbs.GetMarker(item['markerNumbers'][1])['nodeNumber'])
        first, start = int(mbs.GetNodeODE2Index(aux)), int(mbs.GetNodeODE2Index(node))
        D = np.zeros((S.shape[0], size))
        D[:, start:start + S.shape[1]] = S
        rows.extend(range(first, first + S.shape[0]))
        maps.append(D)
    return np.asarray(rows, dtype=int), np.vstack(maps)
