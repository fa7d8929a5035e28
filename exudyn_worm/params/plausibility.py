"""Plausibility of a worm gear: values far outside what a worm gear can be, with the likely unit slip.

Each value of a :class:`~exudyn_worm.model.gear.WormGear` is range-checked on its own (``r1 > 0``, ``gamma`` in
(0, pi/2), ...); this module checks them against each other, as the backlash is checked against the worm
radius. Refused (``ValueError``): what no worm gear can be, or where the model loses its meaning. Warned
(:class:`ImplausibleValueWarning`): what is far from usual but possible, e.g. for a "what if" study. The
reasons for each choice are in docs/gear-data.md, "Plausibility checks".

- ratio u = r2 / (r1 tan(gamma)) of eq. (3) below 1: **refused**. A worm gear reduces the speed: u = z2 / z1,
  and the wheel has at least as many teeth as the worm has starts. The usual cause is a radius in mm given
  as m (``r1 = 18.05``), or a lead angle in degrees given as rad.
- efficiency with the worm driving <= 0, i.e. gamma + rho >= 90 deg: **refused**. The worm could not turn the
  wheel at all; the lever c4 of eq. (12) changes sign for S = +1 and the coefficients of eqs. (9)-(12) lose
  their meaning (they are positive for gamma + rho < 90 deg, section 2.2).
- flank friction mu above 0.5: **warned**. Far above the paper's 0.132, but the model stays valid while
  gamma + rho < 90 deg; mu >= 1 is named as a percentage given as a number (``5`` for 5 %).
- worm radius r1 above the wheel radius r2: **warned**. Unusual (the diameter quotient q above the number
  of wheel teeth z2) but not impossible when u >= 1.

Speeds and loads of a simulation (:func:`CheckWormRotation` before it, :func:`CheckWormSpeed` after it):

- one rotation of the worm at the motor's largest speed shorter than :data:`MIN_STEPS_PER_ROTATION` time steps:
  **warned**. The mesh is not resolved in time; the usual cause is a speed in rpm given as rad/s.
- the worm's speed, averaged over :data:`RUNAWAY_SPAN` (a vibration of the worm, stick-slip or chatter, averages
  out; a worm that the load drives away does not), faster than :data:`MAX_WORM_SPEED_RATIO` times the motor's
  largest speed: **warned**. The load overpowers the drive (``loadMass = 1e9`` kg spins the worm backwards at
  millions of rad/s); the usual cause is a mass, lever or torque off by orders of magnitude.
"""
from __future__ import annotations

import math
import warnings
from typing import Any, Mapping, Optional, Sequence

import numpy as np

from .parameters import PARAMETERS, ParameterError

__all__ = ['ImplausibleValueWarning', 'UnresolvedRotationWarning', 'MAX_PLAUSIBLE_MU', 'MIN_STEPS_PER_ROTATION', 'MAX_WORM_SPEED_RATIO',
           'RUNAWAY_SPAN',
           'CheckGearPlausibility', 'CheckWormRotation', 'CheckWormSpeed']

#: flank friction coefficient above which a gear is warned about; the paper's gears have 0.132
MAX_PLAUSIBLE_MU = 0.5
#: time steps per worm rotation below which a run is warned about (the mesh of each tooth passes in a few steps)
MIN_STEPS_PER_ROTATION = 10
#: worm speed, in multiples of the motor's largest speed, above which a run is warned about (chatter moves the worm
#: by a fraction of its speed; ten times the motor's speed means the load drives the worm)
MAX_WORM_SPEED_RATIO = 10.
#: worm radius in m from which a message suggests mm given as m (a worm of 1 m diameter; a hint, not a limit)
_LARGE_RADIUS = 0.5
#: lead angle in rad above which a message suggests degrees given as rad (28.6 deg)
_LARGE_GAMMA = 0.5


class ImplausibleValueWarning(UserWarning):
    """A value far outside what a worm gear usually has, but possible; the message names the likely slip.

    Issued from one place (``stacklevel=1``), so that Python's default filter shows each message once per
    place; the command line shows each message once per run (filter ``'once'``).
    """


class UnresolvedRotationWarning(ImplausibleValueWarning):
    """One rotation of the worm in fewer than :data:`MIN_STEPS_PER_ROTATION` time steps (:func:`CheckWormRotation`);
    a class of its own so that a caller that has said it once can silence the repetitions of the same run."""


def _FileLine(key: str, value: float, unit: str) -> str:
    """``[gear] wormRadius = "18.05 mm"``: the line of a drive file that gives ``key`` in ``unit``."""
    parameter = PARAMETERS[key]
    return f'[{parameter.table}] {parameter.fileKey} = "{value:g} {unit}"'


def _RadiusSlip(name: str, value: float) -> str:
    if value < _LARGE_RADIUS:
        return f"; check '{name}' and its unit (m)"
    return (f"; '{name}' is in m: mm given as m? {value:g} mm = {value * 1e-3:g} m "
            f"(on the command line --set '{name}={value:g} mm', in a drive file {_FileLine(name, value, 'mm')})")


def _GammaSlip(gamma: float) -> str:
    if gamma <= _LARGE_GAMMA:
        return ''
    return (f"; 'gamma' = {gamma:g} rad is {math.degrees(gamma):.4g} deg: degrees given as rad? {gamma:g} deg = "
            f"{math.radians(gamma):.4g} rad (--set 'gamma={gamma:g} deg', in a drive file "
            f"{_FileLine('gamma', gamma, 'deg')})")


def _MuSlip(mu: float) -> str:
    return f"; percent given as a number? {mu:g} % = {mu / 100:g}" if mu >= 1 else ''


def CheckGearPlausibility(gear: 'WormGear', where: str = 'WormGear') -> None:
    """Refuse or warn about a gear whose values cannot belong to a worm gear (see the module docstring).

    Parameters
    ----------
    gear : WormGear
        A gear whose values passed their own range checks (``r1``, ``r2``, ``gamma``, ``alphaN``, ``mu``, ``rho``).
    where : str
        Prefix of the errors (a warning starts with ``the gear:``, what a user of the command line knows it by).

    Raises
    ------
    ValueError
        For a ratio u below 1 or an efficiency with the worm driving <= 0 (gamma + rho >= 90 deg).

    Warns
    -----
    ImplausibleValueWarning
        For mu above :data:`MAX_PLAUSIBLE_MU` or r1 above r2.
    """
    r1, r2, gamma, mu, rho = gear.r1, gear.r2, gear.gamma, gear.mu, gear.rho
    u = r2 / (r1 * math.tan(gamma))                                   # eq. (3)
    values = f"r1 = {r1:g} m, r2 = {r2:g} m, gamma = {math.degrees(gamma):.4g} deg"
    if u < 1.:
        slip = _RadiusSlip('r1', r1) if r1 > r2 else _GammaSlip(gamma)
        raise ParameterError(where, f"the transmission ratio u = r2/(r1 tan(gamma)) of eq. (3) must be >= 1 (a worm "
                             f"gear has u = z2/z1), got u = {u:.3g} from {values}{slip}",
                             ('r1', 'r2', 'gamma') if r1 > r2 else ('gamma', 'r1', 'r2'))
    if gamma + rho >= 0.5 * math.pi:
        slip = _MuSlip(mu) or _GammaSlip(gamma)
        raise ParameterError(where, f"gamma + rho must be < 90 deg (else the worm cannot drive the wheel: efficiency "
                             f"tan(gamma)/tan(gamma + rho) <= 0), got gamma = {math.degrees(gamma):.4g} deg, rho = "
                             f"{math.degrees(rho):.4g} deg (mu = {mu:g}){slip}",
                             ('mu', 'rho', 'gamma') if _MuSlip(mu) else ('gamma', 'mu', 'rho'))
    if mu > MAX_PLAUSIBLE_MU:
        warnings.warn(f"the gear: flank friction mu = {mu:g} (rho = {math.degrees(rho):.4g} deg) is far above what a "
                      f"lubricated worm gear has (the paper's gears: 0.132; warned above {MAX_PLAUSIBLE_MU:g})"
                      f"{_MuSlip(mu)}", ImplausibleValueWarning, stacklevel=1)
    if r1 > r2:
        warnings.warn(f"the gear: the worm radius r1 = {r1:g} m is larger than the wheel radius r2 = {r2:g} m "
                      f"(unusual: diameter quotient q above the wheel teeth z2){_RadiusSlip('r1', r1)}",
                      ImplausibleValueWarning, stacklevel=1)


def _MotorSpeed(parameters: Mapping[str, Any]) -> float:
    """The motor's largest speed in rad/s from a flat parameter set: ``motorSpeed``, ``noLoadSpeed`` and the speeds
    of a ``motorSpeedOverTime`` given as rows (0 if none is given)."""
    speeds = [abs(float(parameters[k])) for k in ('motorSpeed', 'noLoadSpeed') if k in parameters]
    table = parameters.get('motorSpeedOverTime')
    if table is not None and not isinstance(table, str):
        speeds += [abs(float(row[1])) for row in table]
    return max(speeds, default=0.)


def CheckWormRotation(parameters: Mapping[str, Any], stepSize: float, where: str = 'CheckWormRotation') -> None:
    """Warn if one rotation of the worm at the motor's largest speed takes fewer than
    :data:`MIN_STEPS_PER_ROTATION` time steps.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set (``motorSpeed``, ``noLoadSpeed`` or ``motorSpeedOverTime`` in rad/s).
    stepSize : float
        Time step of the simulation in s, > 0.
    where : str
        Prefix of the message.

    Warns
    -----
    UnresolvedRotationWarning
        (an :class:`ImplausibleValueWarning`) naming the speed in rad/s and rpm, the rotation time, the step and the
        likely slip (rpm given as rad/s).
    """
    speed = _MotorSpeed(parameters)
    if not speed > 0. or 2. * math.pi / speed >= MIN_STEPS_PER_ROTATION * stepSize:
        return
    key = next((k for k in ('motorSpeed', 'noLoadSpeed') if abs(float(parameters.get(k, 0.))) == speed),
               'motorSpeedOverTime')
    rpm = speed * 30. / math.pi
    warnings.warn(f"{where}: '{key}' = {speed:g} rad/s ({rpm:.4g} rpm) turns the worm once in "
                  f"{2. * math.pi / speed:.3g} s, fewer than {MIN_STEPS_PER_ROTATION} time steps of {stepSize:.3g} s: "
                  f"the mesh is not resolved; rpm given as rad/s? {speed:g} rpm = {speed * math.pi / 30.:.4g} rad/s "
                  f"(--set '{key}={speed:g} rpm')", UnresolvedRotationWarning, stacklevel=1)


#: the worm's speed is averaged over this span (s; at most a tenth of the run) before it is compared with the motor:
#: a vibration of 10 Hz or more (the drives' chatter and stick-slip) averages out, a runaway lasts longer
RUNAWAY_SPAN = 0.1


def CheckWormSpeed(wormSpeed: Sequence[float], motorSpeed: Sequence[float], parameters: Mapping[str, Any],
                   where: str = 'the simulation', time: Optional[Sequence[float]] = None) -> None:
    """Warn if the worm of a simulation ran, on average over :data:`RUNAWAY_SPAN`, faster than
    :data:`MAX_WORM_SPEED_RATIO` times the motor (the load drives the worm away; a vibration does not count).

    Parameters
    ----------
    wormSpeed : array_like
        The worm's speed over the run in rad/s.
    motorSpeed : array_like
        The motor's speed over the run in rad/s.
    parameters : mapping
        The run's flat parameter set (its load keys are named in the message).
    where : str
        Prefix of the message: what ran, in the user's words (never a function's name).
    time : array_like, optional
        The output times in s (None: the samples are compared one by one).

    Warns
    -----
    ImplausibleValueWarning
        Naming the worm's extreme mean speed, the motor's largest speed, their ratio and the load values.
    """
    worm = np.asarray(wormSpeed, dtype=float)
    if worm.size == 0 or not np.isfinite(worm).all():
        return
    span = 1
    if time is not None and worm.size > 1:
        t = np.asarray(time, dtype=float)
        dt = float(t[-1] - t[0]) / (t.size - 1)
        span = max(1, int(round(min(RUNAWAY_SPAN, 0.1 * float(t[-1] - t[0])) / dt))) if dt > 0. else 1
    mean = np.convolve(worm, np.ones(span) / span, mode='valid') if span > 1 else worm
    reference = max(float(np.max(np.abs(motorSpeed))) if np.size(motorSpeed) else 0., _MotorSpeed(parameters))
    extreme = float(mean[np.argmax(np.abs(mean))])
    if abs(extreme) <= MAX_WORM_SPEED_RATIO * reference:
        return
    ratio = f", {abs(extreme) / reference:.3g} times the motor's largest speed {reference:.4g} rad/s" \
        if reference > 0. else ' while the motor stands'
    over = f" on average over {span * dt:.3g} s" if span > 1 else ''
    load = ', '.join(f"{k} = {parameters[k]:g} {PARAMETERS[k].unit}".rstrip() for k in
                     ('loadMass', 'leverArm', 'loadTorque') if isinstance(parameters.get(k), (int, float)))
    if 'loadTorqueOverTime' in parameters:
        load = ', '.join(filter(None, (load, 'loadTorqueOverTime (largest magnitude '
                                       f"{_LargestTableValue(parameters['loadTorqueOverTime']):g} N*m)")))
    warnings.warn(f"{where}: the worm turned at {extreme:.3g} rad/s{over}{ratio} (warned above "
                  f"{MAX_WORM_SPEED_RATIO:g} times): the load overpowers the drive{' (' + load + ')' if load else ''}; "
                  f"check the load values and their units", ImplausibleValueWarning, stacklevel=1)


def _LargestTableValue(rows) -> float:
    """The largest magnitude in the second column of a (time, value) table (0 where it cannot be read)."""
    try:
        return max(abs(float(r[1])) for r in rows)
    except (TypeError, ValueError, IndexError):
        return 0.
