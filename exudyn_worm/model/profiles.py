"""Prescribed motions phi0(t) and load laws M(phi, omega, t), written once for every backend.

Each object is evaluated with an arithmetic backend ``ops`` (see :mod:`exudyn_worm.model.contact`), so the
same law runs as an Exudyn symbolic user function, in plain Python and on numpy arrays.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Sequence, Tuple

from .._checks import CheckNonNegative, CheckPositive, CheckReal

__all__ = ['ConstantSpeed', 'StartStopProfile', 'SpeedTable', 'GravityLeverTorque', 'ConstantTorque', 'TorqueTable',
           'LinearMotorCharacteristic', 'CoulombViscousFriction', 'STANDARD_GRAVITY']

STANDARD_GRAVITY = 9.81  #: m/s^2, as in the paper's M2 = 2060 N*m for 175 kg at 1.2 m


@dataclass(frozen=True)
class ConstantSpeed:
    """phi0(t) = phi00 + speed * t (the paper's constant motor speed).

    Parameters
    ----------
    speed : float
        Motor speed in rad/s.
    initialAngle : float
        phi0(0) in rad.
    """
    speed: float
    initialAngle: float = 0.

    def __post_init__(self):
        CheckReal('ConstantSpeed', 'speed', self.speed, 'rad/s')
        CheckReal('ConstantSpeed', 'initialAngle', self.initialAngle, 'rad')

    def AngleAndSpeed(self, t, ops):
        """(phi0(t), phi0'(t))."""
        return self.initialAngle + self.speed * t, self.speed + 0. * t


@dataclass(frozen=True)
class StartStopProfile:
    """Smooth start-up, constant speed and optional smooth braking (cosine speed ramps).

    Speed: ramps from 0 to ``speed`` in ``rampTime`` with (1 - cos)/2, stays constant, and if
    ``brakeTime`` is given ramps down to 0 from ``brakeTime`` to ``brakeTime + rampTime``.

    Parameters
    ----------
    speed : float
        Final motor speed in rad/s.
    rampTime : float
        Duration of each ramp in s, > 0.
    brakeTime : float, optional
        Start of braking in s, >= rampTime.
    """
    speed: float
    rampTime: float
    brakeTime: Optional[float] = None

    def __post_init__(self):
        CheckReal('StartStopProfile', 'speed', self.speed, 'rad/s')
        CheckPositive('StartStopProfile', 'rampTime', self.rampTime, 's')
        if self.brakeTime is not None and CheckReal('StartStopProfile', 'brakeTime', self.brakeTime, 's') < self.rampTime:
            raise ValueError(f"StartStopProfile: 'brakeTime' must be >= rampTime = {self.rampTime:g} s, "
                             f"got {self.brakeTime:g} s")

    def _Ramp(self, tau, ops):
        """Angle and speed of a (1-cos)/2 speed ramp after time tau in [0, rampTime] (per unit speed)."""
        T = self.rampTime
        return 0.5 * tau - T / (2 * math.pi) * ops.sin(math.pi * tau / T), 0.5 - 0.5 * ops.cos(math.pi * tau / T)

    def AngleAndSpeed(self, t, ops):
        """(phi0(t), phi0'(t))."""
        T, w = self.rampTime, self.speed
        tau = ops.max(0., ops.min(t, T))
        a, v = self._Ramp(tau, ops)
        angle = w * (a + ops.max(t - T, 0.))
        speed = w * v
        if self.brakeTime is not None:
            tb = ops.max(0., ops.min(t - self.brakeTime, T))        # time into braking
            ab, vb = self._Ramp(tb, ops)
            angle = angle - w * ab - w * ops.max(t - self.brakeTime - T, 0.)
            speed = speed - w * vb
        return angle, speed


def _Points(where: str, points, names: Tuple[str, str], units: Tuple[str, str]) -> Tuple[Tuple[float, float], ...]:
    """Rows (x, y) of a table as floats, at least one, x strictly increasing."""
    if isinstance(points, (str, bytes, dict)) or not hasattr(points, '__len__'):
        raise TypeError(f"{where}: 'points' must be rows ({names[0]} in {units[0]}, {names[1]} in {units[1]}), got "
                        f"{type(points).__name__} {points!r}")
    rows = []
    for i, row in enumerate(points):
        if isinstance(row, (str, bytes, dict)) or not hasattr(row, '__len__') or len(row) != 2:
            raise ValueError(f"{where}: row {i} of 'points' must be ({names[0]}, {names[1]}), got {row!r}")
        rows.append((CheckReal(where, f'points[{i}] {names[0]}', row[0], units[0]),
                     CheckReal(where, f'points[{i}] {names[1]}', row[1], units[1])))
    if not rows:
        raise ValueError(f"{where}: 'points' must hold at least one row ({names[0]}, {names[1]}), got none")
    for i in range(1, len(rows)):
        if not rows[i][0] > rows[i - 1][0]:
            raise ValueError(f"{where}: the {names[0]} of 'points' must increase, got {rows[i - 1][0]:g} then "
                             f"{rows[i][0]:g} (rows {i - 1} and {i})")
    return tuple(rows)


def _Interpolate(points, x, ops):
    """Piecewise-linear interpolation through ``points`` (constant beyond the ends), written with ``ops.min`` and
    ``ops.max`` only, so that it records as an Exudyn symbolic expression: y0 + sum of clipped ramps."""
    y = points[0][1] + 0. * x
    for (x0, y0), (x1, y1) in zip(points, points[1:]):
        y = y + (y1 - y0) / (x1 - x0) * (ops.max(x0, ops.min(x, x1)) - x0)
    return y


@dataclass(frozen=True)
class SpeedTable:
    """Motor speed tabulated over time, linear between the rows (constant beyond the last); the angle is its integral.

    Parameters
    ----------
    points : sequence of (float, float)
        Rows (time in s, speed in rad/s), time strictly increasing from 0 (the first row is the speed at t = 0).
    initialAngle : float
        phi0(0) in rad.
    """
    points: Tuple[Tuple[float, float], ...]
    initialAngle: float = 0.

    def __post_init__(self):
        points = _Points('SpeedTable', self.points, ('time', 'speed'), ('s', 'rad/s'))
        if points[0][0] != 0.:
            raise ValueError(f"SpeedTable: the first row of 'points' must be at time 0 s (the speed at the start), "
                             f"got {points[0][0]:g} s")
        object.__setattr__(self, 'points', points)
        CheckReal('SpeedTable', 'initialAngle', self.initialAngle, 'rad')

    @property
    def endTime(self) -> float:
        """Time of the last row in s."""
        return self.points[-1][0]

    def AngleAndSpeed(self, t, ops):
        """(phi0(t), phi0'(t)): the integral of the piecewise-linear speed, and the speed."""
        angle = self.initialAngle + 0. * t
        for (t0, v0), (t1, v1) in zip(self.points, self.points[1:]):
            tau = ops.max(0., ops.min(t, t1) - t0)              # time spent in this segment so far
            angle = angle + v0 * tau + 0.5 * (v1 - v0) / (t1 - t0) * tau * tau
        angle = angle + self.points[-1][1] * ops.max(t - self.endTime, 0.)
        return angle, _Interpolate(self.points, t, ops)


@dataclass(frozen=True)
class ConstantTorque:
    """A constant load torque M in N*m on the wheel side (negative: against positive wheel rotation, i.e. lifting).

    Parameters
    ----------
    torque : float
        Torque in N*m.
    """
    torque: float

    def __post_init__(self):
        CheckReal('ConstantTorque', 'torque', self.torque, 'N*m')

    @property
    def maximum(self) -> float:
        """Largest ``|M|`` in N*m."""
        return abs(self.torque)

    def Torque(self, phi, omega, t, ops):
        """Load torque in N*m."""
        return self.torque + 0. * t


@dataclass(frozen=True)
class TorqueTable:
    """A load torque tabulated over time or over the angle of the rotor it acts on, linear between the rows and
    constant beyond the ends.

    Parameters
    ----------
    points : sequence of (float, float)
        Rows (time in s or angle in rad, torque in N*m), the first column strictly increasing.
    over : str
        ``'time'`` or ``'angle'`` (the angle of the rotor the torque acts on: the wheel, or the last load-side
        inertia).
    """
    points: Tuple[Tuple[float, float], ...]
    over: str = 'time'

    def __post_init__(self):
        if self.over not in ('time', 'angle'):
            raise ValueError(f"TorqueTable: 'over' must be 'time' or 'angle', got {self.over!r}")
        object.__setattr__(self, 'points', _Points('TorqueTable', self.points, (self.over, 'torque'),
                                                   ('s' if self.over == 'time' else 'rad', 'N*m')))

    @property
    def maximum(self) -> float:
        """Largest ``|M|`` of the table in N*m."""
        return max(abs(y) for _, y in self.points)

    def Torque(self, phi, omega, t, ops):
        """Load torque in N*m."""
        return _Interpolate(self.points, t if self.over == 'time' else phi, ops)


@dataclass(frozen=True)
class GravityLeverTorque:
    """Torque of a mass on a lever: M = -m g l cos(phi) (eq. (27); lifting while cos(phi) > 0).

    Parameters
    ----------
    mass : float
        Load mass in kg, >= 0.
    leverArm : float
        Lever arm in m, >= 0.
    gravity : float
        Gravitational acceleration in m/s^2.
    """
    mass: float
    leverArm: float
    gravity: float = STANDARD_GRAVITY

    def __post_init__(self):
        CheckNonNegative('GravityLeverTorque', 'mass', self.mass, 'kg')
        CheckNonNegative('GravityLeverTorque', 'leverArm', self.leverArm, 'm')
        CheckPositive('GravityLeverTorque', 'gravity', self.gravity, 'm/s^2')

    @property
    def maximum(self) -> float:
        """Largest load torque m g l in N*m."""
        return self.mass * self.gravity * self.leverArm

    def Torque(self, phi, omega, t, ops):
        """Load torque in N*m acting on the wheel."""
        return -self.maximum * ops.cos(phi)


@dataclass(frozen=True)
class LinearMotorCharacteristic:
    """Motor torque-speed line M = stallTorque * (1 - omega / noLoadSpeed), clipped at 0 above noLoadSpeed.

    Parameters
    ----------
    stallTorque : float
        Torque at standstill in N*m, > 0.
    noLoadSpeed : float
        Speed at zero torque in rad/s, > 0.
    """
    stallTorque: float
    noLoadSpeed: float

    def __post_init__(self):
        CheckPositive('LinearMotorCharacteristic', 'stallTorque', self.stallTorque, 'N*m')
        CheckPositive('LinearMotorCharacteristic', 'noLoadSpeed', self.noLoadSpeed, 'rad/s')

    def Torque(self, phi, omega, t, ops):
        """Motor torque in N*m."""
        return self.stallTorque * ops.max(0., 1. - omega * (1. / self.noLoadSpeed))


@dataclass(frozen=True)
class CoulombViscousFriction:
    """Bearing friction M1 = -(coulombTorque * sat(omega/regularizationSpeed) + viscous * omega).

    Parameters
    ----------
    coulombTorque : float
        Coulomb friction torque in N*m, >= 0.
    viscous : float
        Viscous coefficient in N*m*s/rad, >= 0.
    regularizationSpeed : float
        Speed in rad/s below which the Coulomb part grows linearly, > 0.
    """
    coulombTorque: float
    viscous: float = 0.
    regularizationSpeed: float = 0.05

    def __post_init__(self):
        CheckNonNegative('CoulombViscousFriction', 'coulombTorque', self.coulombTorque, 'N*m')
        CheckNonNegative('CoulombViscousFriction', 'viscous', self.viscous, 'N*m*s/rad')
        CheckPositive('CoulombViscousFriction', 'regularizationSpeed', self.regularizationSpeed, 'rad/s')

    def Torque(self, phi, omega, t, ops):
        """Friction torque in N*m (opposes omega)."""
        sat = ops.max(-1., ops.min(1., omega * (1. / self.regularizationSpeed)))
        return -self.coulombTorque * sat - self.viscous * omega
