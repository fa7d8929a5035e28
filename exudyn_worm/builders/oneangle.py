"""The one-angle model of a drive, added to an Exudyn system: :func:`BuildReelChanger`.

Motor (prescribed rotation phi0, or a free motor on its torque-speed characteristic) -- elastic shaft kT, dT --
worm J1 -- worm-gear mesh -- wheel J2 -- the duty's load (for the paper's reel changer of section 3.2 the lever
torque M2 = -m2 g l2 cos(phi2), eq. (27)). Optional (see :mod:`exudyn_worm.drive.presets`): the drive-side chain
of Figure 19 (``J4, k4, d4, J5, ...``: worm --kT-- J4 --k4-- J5 ... -- motor), the load-side chain
(``JL1, kL1, dL1, JL2, ...``: wheel --kL1-- JL1 --kL2-- JL2 ...; the load then acts on the last inertia) and the
worm's axial bearing (``kA, dA, mA``). The items are those of :mod:`exudyn_worm.items`; the system starts in its
steady state (:func:`~exudyn_worm.items.equilibrium.SteadyInitialState`). Solving it is
:func:`~exudyn_worm.analysis.simulation.reelchanger.SimulateReelChanger`'s job.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Dict, Optional, Tuple

from .._checks import CheckBool, CheckPositive
from ..items.connector import CreateWormAxialBearing, CreateWormGear, WormGearConnector
from ..items.drivetrain import (CreateDriveSideChain, CreateLoadSideChain, CreatePrescribedRotation, CreateRotor,
                               CreateRotorTorque)
from ..items.equilibrium import SteadyInitialState
from ..model.contact import ContactOptions
from ..model.friction import MATH_OPS
from ..model.drive import ElasticDrive
from ..model.profiles import ConstantSpeed, ConstantTorque
from ..drive.duty import CheckSimulationKeys, SteadyMotorSpeed
from ..drive.wholedrive import CheckDrive, Drive
from .start import LinearizationPoint

__all__ = ['ReelChangerModel', 'BuildReelChanger', 'CheckReelChangerKeys', 'CheckModelDrive', 'CheckModelOptions']

_MOTOR_INERTIA = 1e-3   # kg*m^2; the motor node is prescribed, its inertia does not matter


def CheckReelChangerKeys(drive: Drive, where: str) -> None:
    """Refuse a drive without a duty to simulate: without the reel changer's own keys (``REEL_KEYS``: loadMass,
    leverArm, motorSpeed), e.g. the ``chart`` preset, naming the missing ones and how to give them; for another
    duty (``loadType``, ``motorType``: :mod:`exudyn_worm.drive.duty`) the keys that duty needs.

    Parameters
    ----------
    drive : Drive
        The drive.
    where : str
        Who needs them (function or command), first in the message.

    Raises
    ------
    MissingParameterError
        A ValueError naming the missing keys, if a key is missing.
    TypeError
        If ``drive`` is not a :class:`~exudyn_worm.drive.wholedrive.Drive`.
    """
    CheckSimulationKeys(CheckDrive(where, drive).parameters, where)


def CheckModelDrive(where: str, drive: Drive, linearization: Optional[LinearizationPoint]) -> None:
    """Check the drive and the ``linearization`` of a model builder: a drive to simulate needs a duty
    (:func:`CheckReelChangerKeys`), one to linearize only to be a drive.

    Parameters
    ----------
    where : str
        The builder, first in the message.
    drive : Drive
        What the builder received.
    linearization : LinearizationPoint or None
        Where the model is linearized (None: it is simulated).

    Raises
    ------
    TypeError, ValueError
        For something else than a drive or a :class:`~exudyn_worm.builders.start.LinearizationPoint`, or a drive
        to simulate without a duty.
    """
    if linearization is not None and not isinstance(linearization, LinearizationPoint):
        raise TypeError(f"{where}: 'linearization' must be None or a LinearizationPoint, got "
                        f"{type(linearization).__name__} {linearization!r}")
    if linearization is None:
        CheckReelChangerKeys(drive, where)
    else:
        CheckDrive(where, drive)


def CheckModelOptions(where: str, contactOptions: ContactOptions, profile: Any, useSymbolic: bool,
                      startFromEquilibrium: bool) -> None:
    """Check the options of :func:`BuildReelChanger` (and of
    :func:`~exudyn_worm.analysis.simulation.reelchanger.SimulateReelChanger`, before anything is built).

    Parameters
    ----------
    where : str
        Who checks them (function or command), first in the message.
    contactOptions : ContactOptions
        Options of the worm-gear contact law.
    profile : optional
        None or an object with ``AngleAndSpeed(t, ops)``.
    useSymbolic, startFromEquilibrium : bool
        The two switches of :func:`BuildReelChanger`.

    Raises
    ------
    TypeError
        If an option has the wrong type.
    """
    if not isinstance(contactOptions, ContactOptions):
        raise TypeError(f"{where}: 'contactOptions' must be a ContactOptions (e.g. ContactOptions(frictionSpeed=0.05)), "
                        f"got {type(contactOptions).__name__} {contactOptions!r}")
    if profile is not None and not callable(getattr(profile, 'AngleAndSpeed', None)):
        raise TypeError(f"{where}: 'profile' must be None (constant motor speed) or have AngleAndSpeed(t, ops) "
                        f"(e.g. ConstantSpeed, StartStopProfile), got {type(profile).__name__} {profile!r}")
    CheckBool(where, 'useSymbolic', useSymbolic)
    CheckBool(where, 'startFromEquilibrium', startFromEquilibrium)


@dataclass
class ReelChangerModel:
    """The Exudyn system of the reel changer and what is needed to read its results.

    Attributes
    ----------
    systemContainer : exudyn.SystemContainer
        The container of ``mbs`` (``mbs.GetSystemContainer()``).
    mbs : exudyn.MainSystem
        The system the items were added to (not assembled).
    drive : ElasticDrive
        The two-mass drive of eqs. (1)-(2).
    load : GravityLeverTorque
        The reel's load torque, eq. (27).
    motorSpeed : float
        Nominal motor speed in rad/s.
    connector : WormGearConnector
        The worm-gear mesh.
    rotors : dict
        Rotor dicts of :func:`~exudyn_worm.items.drivetrain.CreateRotor` by name (``'worm'``, ``'wheel'``, ...).
    sensors : dict
        Sensors by name.
    axialBearing : dict or None
        The worm axial bearing of :func:`~exudyn_worm.items.connector.CreateWormAxialBearing` (None: rigid).
    chain : tuple of (float, float, float)
        The drive-side chain ``(J, k, d)`` of inertia4, spring-Damper4, ... (empty: none).
    loadChain : tuple of (float, float, float)
        The load-side chain ``(J, k, d)`` behind the wheel, wheel side first (empty: none).
    motorFlywheel : bool
        The motor turns at ``motorSpeed`` as a flywheel (``BuildReelChanger(..., motorConstraint=False)``): its speed
        is ``motorSpeed`` to the last bit, so it has no speed sensor (``sensors`` lacks ``'omega0'``).
    """
    systemContainer: Any
    mbs: Any
    drive: ElasticDrive
    load: Any                     # the duty's load law (GravityLeverTorque for the reel changer) or None
    motorSpeed: float             # the motor speed at t = 0 in rad/s
    connector: WormGearConnector
    rotors: Dict[str, Dict]
    sensors: Dict[str, Any]
    axialBearing: Optional[Dict[str, Any]] = None
    chain: Tuple[Tuple[float, float, float], ...] = ()
    loadChain: Tuple[Tuple[float, float, float], ...] = ()
    motorFlywheel: bool = False


def BuildReelChanger(mbs, drive: Drive, contactOptions: ContactOptions = ContactOptions(),
                     useSymbolic: bool = True, startFromEquilibrium: bool = True, profile=None,
                     linearization: Optional[LinearizationPoint] = None, motorConstraint: bool = True
                     ) -> ReelChangerModel:
    """Add the one-angle model of a drive to ``mbs``: motor, drive shaft, worm, mesh, wheel, the chains, the
    worm's axial bearing and the duty's load, each rotor with its angle (the reel changer of section 3.2 and any
    other duty). The one builder of this model: the time simulation, the linear analysis, the lowering-phase orbit
    and the studies use it.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system to add the items to (``SC.AddSystem()``); it is not assembled here.
    drive : Drive
        The drive (:func:`~exudyn_worm.drive.wholedrive.ResolveDrive`) with a duty: ``loadMass`` (kg),
        ``leverArm`` (m) and ``motorSpeed`` (rad/s) of the reel changer, or another duty (``loadType``,
        ``motorType``: :mod:`exudyn_worm.drive.duty`; the load acts where the lever would). Its drive-side chain
        gives the rotors ``inertia4``, ... and shafts ``springDamper4``, ..., its load-side chain the rotors
        ``loadInertia1``, ... and shafts ``loadShaft1``, ... (the load acts on the last one), its axial bearing the
        node ``wormAxial``.
    contactOptions : ContactOptions
        Options of the worm-gear contact law.
    useSymbolic : bool
        C++ symbolic user functions (default) or plain Python.
    startFromEquilibrium : bool
        Start in the static equilibrium under the initial load at nominal speed (default); otherwise
        all rotors start at rest with zero angles.
    profile : optional
        Motor motion: an object with ``AngleAndSpeed(t, ops)`` such as :class:`ConstantSpeed` or
        :class:`~exudyn_worm.model.profiles.StartStopProfile` (default: the drive's motor, ``drive.motor``:
        :class:`ConstantSpeed` at ``motorSpeed`` for the reel changer).
    linearization : LinearizationPoint, optional
        Build the model to be linearized at this point instead (:class:`~exudyn_worm.builders.start.LinearizationPoint`:
        no load, the motor at the point's speed, the worm turned into contact, the contact state held); the drive
        needs no duty then, and ``startFromEquilibrium`` and ``profile`` are not used.
    motorConstraint : bool
        True (default): the prescribed motor is held by a constraint (what a linearization needs); False: a motor
        at constant speed is a flywheel that turns exactly as prescribed, for a time simulation (the same numbers,
        fewer instructions; :func:`~exudyn_worm.items.drivetrain.CreatePrescribedRotation` with
        ``constraint=False``).

    Returns
    -------
    ReelChangerModel
        What was added: rotors, connector, sensors, the axial bearing.

    Raises
    ------
    ValueError, TypeError
        For a drive without a duty (:func:`CheckReelChangerKeys`), ``contactOptions`` that is not a
        :class:`~exudyn_worm.model.contact.ContactOptions`, or a ``profile`` without ``AngleAndSpeed``.

    Examples
    --------
    >>> import exudyn as exu
    >>> from exudyn_worm.drive.wholedrive import ResolveDrive
    >>> mbs = exu.SystemContainer().AddSystem()
    >>> model = BuildReelChanger(mbs, ResolveDrive('reel-P1'))
    >>> sorted(model.rotors)
    ['motor', 'wheel', 'worm']
    """
    import exudyn as exu
    from exudyn.itemInterface import SensorNode

    w = 'BuildReelChanger'
    CheckModelOptions(w, contactOptions, profile, useSymbolic, startFromEquilibrium)
    CheckBool(w, 'motorConstraint', motorConstraint)
    CheckModelDrive(w, drive, linearization)
    whole, drive = drive, drive.elastic
    if linearization is None and whole.motorType in ('constantSpeed', 'startStop'):
        CheckPositive(w, 'motorSpeed', whole.parameters['motorSpeed'], 'rad/s')
    load = whole.load if linearization is None else None     # the duty: lever, constant, table or None
    characteristic = None                               # a free motor on its torque-speed line, else prescribed
    if whole.hasMotorCharacteristic:
        if profile is not None:
            raise ValueError(f"{w}: 'profile' prescribes the motor, but the drive drives it by its "
                             f"characteristic (motorType = characteristic); give one of them")
        characteristic = whole.motor
        if linearization is None:
            profile = ConstantSpeed(SteadyMotorSpeed(whole.parameters, w))          # its start: the steady speed
    chain = whole.driveSideChain
    loadChain = whole.loadSideChain
    bearing = whole.axialBearing

    if linearization is not None:          # held at the point's speed (a free motor starts there)
        speed, deltaPhi = linearization.Start(drive.gear)
        profile, contactOptions = ConstantSpeed(speed), linearization.ContactOptions(contactOptions)
    profile = profile if profile is not None else whole.motor
    motorSpeed = float(profile.AngleAndSpeed(0., MATH_OPS)[1])         # the motor's speed at t = 0

    if linearization is not None:          # every rotor at the point's speed, the worm turned into contact
        wheelSpeed = speed / drive.gear.ratio
        init = {'phi1': deltaPhi, 'omega1': speed, 'omega2': wheelSpeed,
                **{f'omega{i}': speed for i in range(4, 4 + len(chain))},
                **{f'omegaL{i}': wheelSpeed for i in range(1, 1 + len(loadChain))}}
        init0 = (0., speed)
    elif startFromEquilibrium:
        init = SteadyInitialState(drive, load or ConstantTorque(0.), motorSpeed, contactOptions, bearing, chain,
                                  loadSide=loadChain)
        init0 = profile.AngleAndSpeed(0., MATH_OPS)
    else:
        init, init0 = {}, (0., 0.)

    motor = CreateRotor(mbs, _MOTOR_INERTIA if characteristic is None else whole.freeMotor[0],
                        initialAngle=init0[0], initialSpeed=init0[1], name='motor')
    worm = CreateRotor(mbs, drive.J1, initialAngle=init.get('phi1', 0.), initialSpeed=init.get('omega1', 0.),
                       name='worm')
    wheel = CreateRotor(mbs, drive.J2, initialAngle=init.get('phi2', 0.), initialSpeed=init.get('omega2', 0.),
                        name='wheel')
    motorFlywheel = False
    if characteristic is None:
        motorFlywheel = CreatePrescribedRotation(mbs, motor, profile, name='motorDrive', useSymbolic=useSymbolic,
                                                 constraint=motorConstraint)['objectNumber'] is None
    else:
        CreateRotorTorque(mbs, motor, characteristic, name='motorTorque', useSymbolic=useSymbolic)
    rotors = {'motor': motor, 'worm': worm, 'wheel': wheel}
    # drive-side chain, worm side first: worm --kT-- inertia4 --k4-- inertia5 ... --kn-- motor
    chainRotors = CreateDriveSideChain(mbs, motor, worm, drive.kT, drive.dT, chain, init)
    rotors.update({f'inertia{i}': r for i, r in enumerate(chainRotors, start=4)})
    axial = None
    if bearing is not None:
        axial = CreateWormAxialBearing(mbs, bearing, initialDisplacement=init.get('xA', 0.),
                                       initialSpeed=init.get('vA', 0.), name='wormAxial')
    connector = CreateWormGear(mbs, [worm['nodeNumber'], wheel['nodeNumber']], gear=drive.gear, name='wormGear',
                               contactOptions=contactOptions, useSymbolic=useSymbolic,
                               axialNodeNumber=None if axial is None else axial['nodeNumber'])
    # load-side chain, wheel side first: wheel --kL1-- loadInertia1 --kL2-- loadInertia2 ...; the load on the last
    loadRotors = CreateLoadSideChain(mbs, wheel, loadChain, init)
    rotors.update({f'loadInertia{i}': r for i, r in enumerate(loadRotors, start=1)})
    if load is not None:
        CreateRotorTorque(mbs, (loadRotors or [wheel])[-1], load, name='reelLoad', useSymbolic=useSymbolic)

    sensors = dict(connector.AddSensors(mbs))
    OVT = exu.OutputVariableType
    for index, rotor in ([('0', motor)] + [(str(i), r) for i, r in enumerate(chainRotors, start=4)]
                         + [(f'L{i}', r) for i, r in enumerate(loadRotors, start=1)]):
        quantities = (('phi', OVT.Coordinates), ('omega', OVT.Coordinates_t))
        if index == '0' and motorFlywheel:         # its speed is motorSpeed to the last bit: no sensor needed
            quantities = (('phi', OVT.Coordinates),)
        if index != '0':
            quantities += (('alpha', OVT.Coordinates_tt),)
        for prefix, ovt in quantities:
            sensors[prefix + index] = mbs.AddSensor(SensorNode(nodeNumber=rotor['nodeNumber'], outputVariableType=ovt,
                                                               storeInternal=True, writeToFile=False))
    return ReelChangerModel(mbs.GetSystemContainer(), mbs, drive, load, motorSpeed, connector, rotors, sensors, axial,
                            chain, loadChain, motorFlywheel)
