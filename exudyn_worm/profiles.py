"""Prescribed motions phi0(t) and load laws M(phi, omega, t), written once for every backend.

Each object is evaluated with an arithmetic backend ``ops`` (see :mod:`exudyn_worm.contact`), so the
same law runs as an Exudyn symbolic user function, in plain Python and on numpy arrays.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

from ._checks import CheckNonNegative, CheckPositive, CheckReal

__all__ = ['ConstantSpeed', 'StartStopProfile', 'GravityLeverTorque', 'LinearMotorCharacteristic',
           'CoulombViscousFriction', 'STANDARD_GRAVITY']

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
