"""The operating points of a drive's own duty: where the motor runs at a steady speed, in each direction of power.

A linear analysis needs the state it is linearized about: the sliding speed (for mu(v) and its slope), the static
normal force and the contact state S. They follow from the duty of the :class:`~exudyn_worm.drive.wholedrive.Drive`:

**Steady phases** (the motor at a constant speed):

- ``constantSpeed``: the whole duty at ``motorSpeed``;
- ``startStop``: the plateau between the end of the start ramp and ``brakeTime`` (one wheel rotation if the
  drive does not stop);
- ``speedTable``: every span between two rows with the same speed other than 0, and the last row's speed if it
  is not 0 (the table holds it beyond its end); a span at speed 0 is a standstill, not a steady phase;
- ``characteristic``: the speed where the motor's line carries the load of the phase (iterated, since mu
  depends on the speed): ``stallTorque (1 - omega / noLoadSpeed)`` = the torque the worm needs,
  ``S c2(S, mu) Fn`` (eqs. (10), (12): the wheel's balance ``c4(S, mu) Fn = |M|``).

**Load torque of a phase.** The load law is sampled along the rigid kinematics of the phase (wheel angle
phi0(t) / u), ``SAMPLES_PER_PHASE`` samples: a constant torque is itself, a lever or a table over angle or time
varies. The value taken is **the largest magnitude of the load torque in each direction of power flow** within
the phase: where the load opposes the motion (lifting, S = +1) and where it drives the gear (lowering, S = -1).
A reel changer's rotation at constant speed so gives two operating points, lifting and lowering, each at
m g l, the value the paper's analysis takes.

The static normal force is ``|M| / c4(S, mu0)``; mesh damping, the chains and the axial bearing do not change it
at steady speed.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Dict, List, Optional, Tuple

import numpy as np

from ..model.friction import MATH_OPS
from ..model.profiles import SpeedTable, StartStopProfile
from ..model.stability import OperatingPoint, OperatingPointAt
from .duty import DefaultEndTime
from .wholedrive import Drive

__all__ = ['DutyPoint', 'SteadyPhase', 'SteadyPhases', 'DutyOperatingPoints', 'SAMPLES_PER_PHASE', 'PHASE_NAMES']

#: samples of the load law along one steady phase (a lever's largest torque is then within 1e-5 of m g l)
SAMPLES_PER_PHASE = 721
#: phase name by contact state
PHASE_NAMES = {+1: 'lifting', -1: 'lowering'}
_RPM = 60. / (2 * math.pi)


@dataclass(frozen=True)
class SteadyPhase:
    """A span of the duty in which the motor runs at a steady speed.

    Attributes
    ----------
    t0, t1 : float
        Start and end in s.
    motorSpeed : float or None
        Motor speed in rad/s (signed); None for a motor on its characteristic (found per load).
    source : str
        Which part of the duty it is (``'constant speed'``, ``'speed table'``, ...).
    """
    t0: float
    t1: float
    motorSpeed: Optional[float]
    source: str


@dataclass(frozen=True)
class DutyPoint:
    """One operating point of a drive's duty: a steady phase in one direction of power flow.

    Attributes
    ----------
    phase : str
        ``'lifting'`` (the load opposes the motion, S = +1) or ``'lowering'`` (the load drives, S = -1).
    motorSpeed : float
        Motor speed in rad/s (signed).
    loadTorque : float
        Load torque in N*m (signed, on the wheel or the last load-side inertia): the largest magnitude in this
        direction of power flow within the phase.
    window : (float, float) or None
        The steady phase in s; None for a point that is not of the duty's time line (a chart's speed).
    source : str
        Which part of the duty (``'constant speed'``, ``'speed table'``, ``'start/stop plateau'``,
        ``'characteristic'``).
    operatingPoint : OperatingPoint
        Sliding speed, mu(v0), dmu/dv, static normal force and S.
    """
    phase: str
    motorSpeed: float
    loadTorque: float
    window: Optional[Tuple[float, float]]
    source: str
    operatingPoint: OperatingPoint

    @property
    def S(self) -> int:
        """Contact state of the steady motion: +1 lifting, -1 lowering."""
        return self.operatingPoint.S

    def Label(self) -> str:
        """E.g. ``'lowering at -100 rpm (speed table, 1.8-2.8 s)'``."""
        if self.window is None:
            return f"{self.phase} at {self.motorSpeed * _RPM:.4g} rpm ({self.source})"
        return (f"{self.phase} at {self.motorSpeed * _RPM:.4g} rpm ({self.source}, "
                f"{self.window[0]:.4g}-{self.window[1]:.4g} s)")

    def ToDict(self) -> Dict:
        """JSON-ready: ``phase, motorSpeed, loadTorque, slidingSpeed, mu, dmuDv, normalForce, S, window, source``."""
        op = self.operatingPoint
        return {'phase': self.phase, 'motorSpeed': self.motorSpeed, 'loadTorque': self.loadTorque,
                'slidingSpeed': op.slidingSpeed, 'mu': op.mu, 'dmuDv': op.dmuDv, 'normalForce': op.normalForce,
                'S': op.S, 'window': None if self.window is None else list(self.window), 'source': self.source}


def _OneRotation(drive: Drive, speed: float) -> float:
    return 2 * math.pi * drive.gear.ratio / abs(speed)


def SteadyPhases(drive: Drive) -> List[SteadyPhase]:
    """The spans of the duty in which the motor runs at a steady speed (module text); empty without a motor.

    Parameters
    ----------
    drive : Drive
        The drive.

    Returns
    -------
    list of SteadyPhase
    """
    motor, kind = drive.motor, drive.motorType
    if motor is None:
        return []
    if kind == 'characteristic':
        return [SteadyPhase(0., _OneRotation(drive, motor.noLoadSpeed), None, 'characteristic')]
    if isinstance(motor, StartStopProfile):
        end = motor.brakeTime if motor.brakeTime is not None else motor.rampTime + _OneRotation(drive, motor.speed)
        return [SteadyPhase(motor.rampTime, end, motor.speed, 'start/stop plateau')] if end > motor.rampTime \
            and motor.speed != 0 else []
    if isinstance(motor, SpeedTable):
        points, out = motor.points, []
        scale = max(abs(w) for _, w in points) or 1.
        for (ta, wa), (tb, wb) in zip(points, points[1:]):
            if wa != 0 and abs(wb - wa) <= 1e-9 * scale:
                out.append(SteadyPhase(ta, tb, 0.5 * (wa + wb), 'speed table'))
        tEnd, wEnd = points[-1]
        if wEnd != 0:                                       # held beyond the table's end
            out.append(SteadyPhase(tEnd, tEnd + _OneRotation(drive, wEnd), wEnd, 'speed table, after its end'))
        return out
    speed = motor.speed
    if speed == 0:
        return []
    end = DefaultEndTime(drive.parameters, drive.gear.ratio)
    return [SteadyPhase(0., end if end > 0 else _OneRotation(drive, speed), speed, 'constant speed')]


def _LoadSamples(drive: Drive, phase: SteadyPhase, speed: float) -> np.ndarray:
    """Load torque along the rigid kinematics of ``phase`` at motor speed ``speed``."""
    load, u = drive.load, drive.gear.ratio
    times = np.linspace(phase.t0, phase.t1, SAMPLES_PER_PHASE)
    if phase.motorSpeed is None:                            # a motor on its characteristic: steady from t = 0
        angles = speed * times
    else:
        angles = np.array([drive.motor.AngleAndSpeed(float(t), MATH_OPS)[0] for t in times])
    return np.array([float(load.Torque(a / u, speed / u, float(t), MATH_OPS)) for a, t in zip(angles, times)])


def _CharacteristicSpeed(drive: Drive, loadTorque: float, S: int) -> Optional[float]:
    """The speed in rad/s where the motor line carries ``|loadTorque|`` in contact state ``S``; None if it cannot."""
    motor, gear = drive.motor, drive.gear
    speed = motor.noLoadSpeed
    for _ in range(100):
        op = OperatingPointAt(gear, speed, abs(loadTorque), S)
        _, c2, _, _ = gear.Coefficients(S, mu=op.mu if gear.speedDependentFriction else None)
        required = S * c2 * op.normalForce                 # torque the worm needs in the direction of motion
        if required >= motor.stallTorque:
            return None
        new = motor.noLoadSpeed * (1. - required / motor.stallTorque)
        if abs(new - speed) <= 1e-12 * motor.noLoadSpeed:
            return new
        speed = new
    return speed


def DutyOperatingPoints(drive: Drive) -> Tuple[DutyPoint, ...]:
    """The operating points of ``drive``'s duty: each steady phase in each direction of power flow it has.

    Parameters
    ----------
    drive : Drive
        The drive.

    Returns
    -------
    tuple of DutyPoint
        In time order, lifting before lowering within a phase; empty if the drive has no motor, no load torque
        or no steady phase (then a linear analysis can only be made at rest).

    Raises
    ------
    ValueError
        If a motor on its characteristic cannot carry a load of its duty (the torque reaches its stall torque).
    """
    return drive.Cached('dutyOperatingPoints', lambda: _DutyOperatingPoints(drive))


def _DutyOperatingPoints(drive: Drive) -> Tuple[DutyPoint, ...]:
    if drive.load is None:
        return ()
    out: List[DutyPoint] = []
    for phase in SteadyPhases(drive):
        probe = phase.motorSpeed if phase.motorSpeed is not None else drive.motor.noLoadSpeed
        torques = _LoadSamples(drive, phase, probe)
        scale = max(float(np.max(np.abs(torques))), 1e-300)
        power = torques * math.copysign(1., probe)           # > 0: the load drives (lowering)
        for S in (+1, -1):
            mine = torques[(power * -S) > 1e-9 * scale]
            if mine.size == 0:
                continue
            torque = float(mine[np.argmax(np.abs(mine))])
            speed = phase.motorSpeed
            if speed is None:
                speed = _CharacteristicSpeed(drive, torque, S)
                if speed is None:
                    raise ValueError(f"DutyOperatingPoints: the motor on its characteristic cannot carry the "
                                     f"{PHASE_NAMES[S]} load of {abs(torque):.4g} N*m: the worm needs at least its "
                                     f"stall torque {drive.motor.stallTorque:g} N*m")
            out.append(DutyPoint(phase=PHASE_NAMES[S], motorSpeed=float(speed), loadTorque=torque,
                                 window=(float(phase.t0), float(phase.t1)), source=phase.source,
                                 operatingPoint=OperatingPointAt(drive.gear, speed, abs(torque), S)))
    return tuple(out)
