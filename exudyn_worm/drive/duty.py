"""Duty cycles: what loads the wheel side and how the motor moves, from a flat parameter set.

**Load** (``loadType``, drive-file ``[load] type``), acting on the wheel or, with a load-side chain, on its last
inertia:

- ``lever`` (default, the reel changer of section 3.2): ``loadMass`` on ``leverArm``, M = -m g l cos(phi)
  (:class:`~exudyn_worm.model.profiles.GravityLeverTorque`);
- ``constant``: ``loadTorque`` in N*m (:class:`~exudyn_worm.model.profiles.ConstantTorque`);
- ``timeTable``: ``loadTorqueOverTime``, rows (t in s, M in N*m);
- ``angleTable``: ``loadTorqueOverAngle``, rows (angle in rad, M in N*m) (:class:`~exudyn_worm.model.profiles.TorqueTable`);
- ``none``: no load torque.

**Motor** (``motorType``, ``[motor] type``), prescribed on the motor side of the drive shaft:

- ``constantSpeed`` (default): ``motorSpeed`` in rad/s;
- ``startStop``: (1 - cos)/2 ramps to ``motorSpeed`` in ``rampTime`` s, braking from ``brakeTime`` s if given
  (:class:`~exudyn_worm.model.profiles.StartStopProfile`);
- ``speedTable``: ``motorSpeedOverTime``, rows (t in s from 0, speed in rad/s)
  (:class:`~exudyn_worm.model.profiles.SpeedTable`);
- ``characteristic``: a free motor rotor (``motorInertia``) driven by the torque-speed line
  M = ``stallTorque`` (1 - omega / ``noLoadSpeed``) (:class:`~exudyn_worm.model.profiles.LinearMotorCharacteristic`),
  started at the speed where that line carries the initial load (:func:`SteadyMotorSpeed`). The linear analysis
  then has the motor rotor with the line's slope as a damper to ground (instead of a motor held on its path).

**Phases.** A load that opposes the motion is lifted (load power M omega < 0, contact state S = +1 expected);
a load that drives the gear is lowered (M omega > 0: the self-locking worm brakes it, S = -1, where chatter
occurs); without load torque or motion the phase is ``idle``. :func:`DutyPhases` finds the phases of a duty from
the rigid kinematics (wheel angle phi0(t) / u) and gives the default evaluation windows of ``simulate`` and
``sweep``; for the reel changer (lever, constant speed) they are the lift / lower / lift quarters of each rotation.
"""
from __future__ import annotations

import io
import math
from typing import Any, List, Mapping, Optional, Tuple

import numpy as np

from .._files import MAX_TABLE_FILE_BYTES, ReadRegularFile
from .presets import REEL_KEYS, AxialBearingFromParameters, ElasticDriveFromParameters, DriveSideChain, LoadSideChain
from ..params.parameters import MissingParameterError, ParameterError
from ..model.profiles import (ConstantSpeed, ConstantTorque, GravityLeverTorque, LinearMotorCharacteristic, SpeedTable,
                       StartStopProfile, TorqueTable)
from ..model.friction import MATH_OPS
from ..items.equilibrium import SteadyInitialState

__all__ = ['LOAD_TYPES', 'MOTOR_TYPES', 'LoadType', 'MotorType', 'DutyKeys', 'CheckDutyKeys', 'LoadFromParameters',
           'MotorFromParameters', 'MotorMotion', 'SteadyMotorSpeed', 'IsReelChangerDuty', 'DefaultEndTime',
           'CheckSimulationKeys',
           'DutyPhases']

#: the keys each load type needs
LOAD_TYPES = {'lever': ('loadMass', 'leverArm'), 'constant': ('loadTorque',), 'timeTable': ('loadTorqueOverTime',),
              'angleTable': ('loadTorqueOverAngle',), 'none': ()}
#: the keys each motor type needs (``brakeTime`` is optional)
MOTOR_TYPES = {'constantSpeed': ('motorSpeed',), 'startStop': ('motorSpeed', 'rampTime'),
               'speedTable': ('motorSpeedOverTime',), 'characteristic': ('stallTorque', 'noLoadSpeed', 'motorInertia')}
#: samples per wheel rotation (at least 2000 in all) with which DutyPhases looks for a change of phase
_SAMPLES = 2000


def LoadType(parameters: Mapping) -> str:
    """The load type of a parameter set (``'lever'`` if not given).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set.
    """
    return parameters.get('loadType', 'lever')


def MotorType(parameters: Mapping) -> str:
    """The motor type of a parameter set (``'constantSpeed'`` if not given).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set.
    """
    return parameters.get('motorType', 'constantSpeed')


def DutyKeys(parameters: Mapping) -> Tuple[str, ...]:
    """The keys the duty of ``parameters`` needs: those of its load type and of its motor type.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set.

    Returns
    -------
    tuple of str
    """
    return LOAD_TYPES.get(LoadType(parameters), ()) + MOTOR_TYPES.get(MotorType(parameters), ())


def CheckDutyKeys(parameters: Mapping, where: str) -> None:
    """Refuse a duty whose keys are missing (e.g. ``loadType = constant`` without ``loadTorque``).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set.
    where : str
        Who needs them, first in the message.

    Raises
    ------
    MissingParameterError
        A ValueError naming the missing keys and the duty that needs them.
    """
    load, motor = LoadType(parameters), MotorType(parameters)
    missing = [k for k in DutyKeys(parameters) if k not in parameters]
    if missing:
        raise MissingParameterError(
            f"{where}: the duty (load {load}, motor {motor}) needs {', '.join(DutyKeys(parameters))}; missing "
            f"{', '.join(missing)} (give them with --set KEY=VALUE or in [load] / [motor] of the drive file; "
            f"the reel-P* presets give the reel changer's lever and speed)", missing)


def IsReelChangerDuty(parameters: Mapping) -> bool:
    """True for the reel changer's duty: a lever load at constant motor speed (the defaults).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set.
    """
    return LoadType(parameters) == 'lever' and MotorType(parameters) == 'constantSpeed'


def CheckSimulationKeys(parameters: Mapping, where: str) -> None:
    """Refuse a parameter set without a duty to simulate: the reel changer's own keys (``REEL_KEYS``: loadMass,
    leverArm, motorSpeed), e.g. missing in the ``chart`` preset, named with how to give them; for another duty
    (``loadType``, ``motorType``) the keys that duty needs (:func:`CheckDutyKeys`).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set (at the boundary, before it is resolved into a drive).
    where : str
        Who needs them (function or command), first in the message.

    Raises
    ------
    MissingParameterError
        A ValueError naming the missing keys.
    """
    if not IsReelChangerDuty(parameters):         # another duty (loadType / motorType): its own keys
        CheckDutyKeys(parameters, where)
        return
    missing = [k for k in REEL_KEYS if k not in parameters]
    if missing:
        raise MissingParameterError(f"{where}: the reel-changer simulation needs {', '.join(REEL_KEYS)}; missing "
                                    f"{', '.join(missing)} (use a reel-P* preset or give them with --set KEY=VALUE "
                                    f"or in the config file)", missing)


def _Table(parameters: Mapping, key: str, where: str):
    """The rows of a table key: given rows, or a CSV file (two columns, ``#`` comments) named by a path."""
    value = parameters[key]
    if not isinstance(value, str):
        return value
    try:
        raw = ReadRegularFile(value, MAX_TABLE_FILE_BYTES, 'it', 'a table file')
    except ValueError as err:          # named at the drive file's line of the key (ParameterError)
        raise ParameterError(where, f"'{key}': the table file '{value}': {str(err).removeprefix('it: ')}",
                             (key,)) from None
    try:
        rows = np.genfromtxt(io.BytesIO(raw), delimiter=',', comments='#', dtype=float, ndmin=2)
    except ValueError as err:
        raise ParameterError(where, f"'{key}': the file '{value}' must hold two numeric columns separated by commas "
                             f"(SI units): {' '.join(str(err).split())}", (key,)) from None
    if rows.ndim != 2 or rows.shape[1] != 2 or not np.all(np.isfinite(rows)):
        raise ParameterError(where, f"'{key}': the file '{value}' must hold two numeric columns separated by commas "
                             f"(SI units), got shape {rows.shape}", (key,))
    return [tuple(r) for r in rows]


def LoadFromParameters(parameters: Mapping, where: str = 'LoadFromParameters') -> Optional[Any]:
    """The load law of a parameter set's duty (see the module docstring), or None for ``loadType = none``.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set.
    where : str, optional
        Caller named in messages.

    Returns
    -------
    GravityLeverTorque, ConstantTorque, TorqueTable or None

    Raises
    ------
    ValueError
        For a missing key (:func:`CheckDutyKeys`) or a bad table.
    """
    CheckDutyKeys(parameters, where)
    return _LoadLaw(parameters, where)


def _LoadLaw(parameters: Mapping, where: str) -> Optional[Any]:
    """The load law of :func:`LoadFromParameters`, its keys already checked."""
    load = LoadType(parameters)
    if load == 'lever':
        return GravityLeverTorque(mass=parameters['loadMass'], leverArm=parameters['leverArm'])
    if load == 'constant':
        return ConstantTorque(parameters['loadTorque'])
    if load == 'timeTable':
        return TorqueTable(_Table(parameters, 'loadTorqueOverTime', where), 'time')
    if load == 'angleTable':
        return TorqueTable(_Table(parameters, 'loadTorqueOverAngle', where), 'angle')
    return None


def MotorFromParameters(parameters: Mapping, where: str = 'MotorFromParameters') -> Any:
    """The prescribed motor motion of a parameter set's duty (see the module docstring).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set.
    where : str, optional
        Caller named in messages.

    Returns
    -------
    ConstantSpeed, StartStopProfile, SpeedTable or LinearMotorCharacteristic
        A prescribed motion (``AngleAndSpeed``), or for ``characteristic`` the torque law (``Torque``).

    Raises
    ------
    ValueError
        For a missing key (:func:`CheckDutyKeys`), a bad table or a brake time before the ramp ends.
    """
    CheckDutyKeys(parameters, where)
    return _MotorLaw(parameters, where)


def _MotorLaw(parameters: Mapping, where: str) -> Any:
    """The motor of :func:`MotorFromParameters`, its keys already checked."""
    motor = MotorType(parameters)
    if motor == 'characteristic':
        return LinearMotorCharacteristic(parameters['stallTorque'], parameters['noLoadSpeed'])
    if motor == 'startStop':
        ramp, brake = parameters['rampTime'], parameters.get('brakeTime')
        if brake is not None and brake < ramp:       # said here, where the keys' sources can be named
            raise ParameterError(where, f"'brakeTime' must be >= rampTime = {ramp:g} s (motorType startStop), got "
                                 f"{brake:g} s", ('brakeTime', 'rampTime'))
        return StartStopProfile(parameters['motorSpeed'], parameters['rampTime'], parameters.get('brakeTime'))
    if motor == 'speedTable':
        return SpeedTable(_Table(parameters, 'motorSpeedOverTime', where))
    return ConstantSpeed(parameters['motorSpeed'])


def SteadyMotorSpeed(parameters: Mapping, where: str = 'SteadyMotorSpeed') -> float:
    """The speed in rad/s at which a motor on its characteristic carries the initial load: M(omega) equals the
    drive-shaft torque of the static equilibrium (:func:`~exudyn_worm.items.equilibrium.SteadyInitialState`) at omega.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set with ``motorType = characteristic``.
    where : str, optional
        Caller named in messages.

    Returns
    -------
    float

    Raises
    ------
    ValueError
        If the motor cannot carry the load (the required torque reaches the stall torque).
    """
    motor = MotorFromParameters(parameters, where)
    drive = ElasticDriveFromParameters(parameters)
    load = LoadFromParameters(parameters, where) or ConstantTorque(0.)
    chain = DriveSideChain(parameters)
    speed = motor.noLoadSpeed
    for _ in range(20):                    # the required torque depends on the speed only through the friction law
        state = SteadyInitialState(drive, load, speed, axialBearing=AxialBearingFromParameters(parameters),
                                   chain=chain, loadSide=LoadSideChain(parameters))
        motorSide = state['phi4'] if chain else 0.
        required = drive.kT * (motorSide - state['phi1'])          # torque of the drive shaft on the worm
        if required >= motor.stallTorque:
            raise ValueError(f"{where}: the motor cannot carry the load: it needs {required:.4g} N*m at the worm "
                             f"shaft, at least the stall torque {motor.stallTorque:g} N*m")
        new = motor.noLoadSpeed * (1. - max(required, 0.) / motor.stallTorque)
        if abs(new - speed) <= 1e-12 * motor.noLoadSpeed:
            break
        speed = new
    return new


def MotorMotion(parameters: Mapping, where: str = 'MotorMotion') -> Any:
    """The motor's motion ``AngleAndSpeed`` for the rigid kinematics of the phases: the prescribed one, or for a
    motor on its characteristic constant speed at :func:`SteadyMotorSpeed`.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set.
    where : str, optional
        Caller named in messages.
    """
    motor = MotorFromParameters(parameters, where)
    if isinstance(motor, LinearMotorCharacteristic):
        return ConstantSpeed(SteadyMotorSpeed(parameters, where))
    return motor


def DefaultEndTime(parameters: Mapping, ratio: float) -> float:
    """The simulated time of a duty when none is given: one wheel rotation for the reel changer (2 pi u /
    motorSpeed); otherwise the end of its tables and profiles (speed or torque table, start/stop ramps), or one
    wheel rotation at ``motorSpeed`` if it has none.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set.
    ratio : float
        Transmission ratio u of the gear.

    Returns
    -------
    float
        Time in s.
    """
    ends = []
    motor = MotorMotion(parameters, 'DefaultEndTime')
    load = LoadFromParameters(parameters, 'DefaultEndTime')
    if isinstance(motor, SpeedTable):
        ends.append(motor.endTime)
    if isinstance(motor, StartStopProfile):
        ends.append(motor.rampTime if motor.brakeTime is None else motor.brakeTime + motor.rampTime)
    if isinstance(load, TorqueTable) and load.over == 'time':
        ends.append(load.points[-1][0])
    ends = [e for e in ends if e > 0]
    if IsReelChangerDuty(parameters) or not ends:      # one wheel rotation
        return 2 * math.pi * ratio / abs(motor.speed)
    return max(ends)


def _Phase(power: float, scale: float) -> str:
    return 'lower' if power > 1e-9 * scale else 'lift' if power < -1e-9 * scale else 'idle'


def DutyPhases(parameters: Mapping, ratio: float, endTime: float, minLength: float = 0.
               ) -> List[Tuple[float, float, str]]:
    """Lift, lower and idle phases of a duty up to ``endTime``, from the rigid kinematics (wheel angle phi0(t) / u).

    A phase is ``'lower'`` where the load power M(phi2, omega2, t) omega2 > 0 (the load drives the gear),
    ``'lift'`` where it is < 0 and ``'idle'`` where it is 0. The boundaries are found on a grid of at least 2000
    samples per wheel rotation and refined by bisection.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set.
    ratio : float
        Transmission ratio u of the gear.
    endTime : float
        Simulated time in s.
    minLength : float
        A phase shorter than this (in s) or than two samples joins the one before it (the first phase: the next).

    Returns
    -------
    list of (float, float, str)
        ``(t0, t1, phase)`` in time order, covering [0, endTime].
    """
    motor, load = MotorMotion(parameters, 'DutyPhases'), LoadFromParameters(parameters, 'DutyPhases')
    if load is None:
        return [(0., float(endTime), 'idle')]
    speedBound = max(abs(motor.AngleAndSpeed(t, MATH_OPS)[1]) for t in np.linspace(0., endTime, 101)) / ratio
    scale = max(load.maximum, 1e-300) * speedBound        # power below 1e-9 of it counts as none

    def Power(t):
        angle, speed = motor.AngleAndSpeed(t, MATH_OPS)
        return load.Torque(angle / ratio, speed / ratio, t, MATH_OPS) * speed / ratio

    n = max(_SAMPLES, int(math.ceil(_SAMPLES * speedBound * endTime / (2 * math.pi))))
    times = np.linspace(0., endTime, n + 1)
    phases = [_Phase(Power(t), scale) for t in times]
    out, start = [], 0.
    for i in range(1, len(times)):
        if phases[i] != phases[i - 1]:
            a, b = times[i - 1], times[i]
            for _ in range(60):                       # bisection to the change of phase
                mid = 0.5 * (a + b)
                if _Phase(Power(mid), scale) == phases[i - 1]:
                    a = mid
                else:
                    b = mid
            out.append((start, float(b), phases[i - 1]))
            start = float(b)
    out.append((start, float(endTime), phases[-1]))
    # a phase shorter than two samples (the instant a speed or torque passes zero) or than minLength joins its
    # neighbour: the one before, or the next for the first phase
    shortest = max(minLength, 2. * endTime / n)
    while len(out) > 1:
        lengths = [t1 - t0 for t0, t1, _ in out]
        i = min(range(len(out)), key=lambda k: lengths[k])
        if lengths[i] >= shortest:
            break
        if i == 0:
            out[:2] = [(out[0][0], out[1][1], out[1][2])]
        else:
            out[i - 1:i + 1] = [(out[i - 1][0], out[i][1], out[i - 1][2])]
    merged = [out[0]]
    for t0, t1, phase in out[1:]:                     # neighbours of one phase become one
        if merged[-1][2] == phase:
            merged[-1] = (merged[-1][0], t1, phase)
        else:
            merged.append((t0, t1, phase))
    return merged
