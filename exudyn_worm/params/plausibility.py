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
"""
from __future__ import annotations

import math
import warnings

from .parameters import PARAMETERS

__all__ = ['ImplausibleValueWarning', 'MAX_PLAUSIBLE_MU', 'CheckGearPlausibility']

#: flank friction coefficient above which a gear is warned about; the paper's gears have 0.132
MAX_PLAUSIBLE_MU = 0.5
#: worm radius in m from which a message suggests mm given as m (a worm of 1 m diameter; a hint, not a limit)
_LARGE_RADIUS = 0.5
#: lead angle in rad above which a message suggests degrees given as rad (28.6 deg)
_LARGE_GAMMA = 0.5


class ImplausibleValueWarning(UserWarning):
    """A value far outside what a worm gear usually has, but possible; the message names the likely slip.

    Issued from one place (``stacklevel=1``), so that Python's default filter shows each message once per
    place; the command line shows each message once per run (filter ``'once'``).
    """


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
        Prefix of the messages.

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
        raise ValueError(f"{where}: the transmission ratio u = r2/(r1 tan(gamma)) of eq. (3) must be >= 1 (a worm "
                         f"gear has u = z2/z1), got u = {u:.3g} from {values}{slip}")
    if gamma + rho >= 0.5 * math.pi:
        slip = _MuSlip(mu) or _GammaSlip(gamma)
        raise ValueError(f"{where}: gamma + rho must be < 90 deg (else the worm cannot drive the wheel: efficiency "
                         f"tan(gamma)/tan(gamma + rho) <= 0), got gamma = {math.degrees(gamma):.4g} deg, rho = "
                         f"{math.degrees(rho):.4g} deg (mu = {mu:g}){slip}")
    if mu > MAX_PLAUSIBLE_MU:
        warnings.warn(f"{where}: flank friction mu = {mu:g} (rho = {math.degrees(rho):.4g} deg) is far above what a "
                      f"lubricated worm gear has (the paper's gears: 0.132; warned above {MAX_PLAUSIBLE_MU:g})"
                      f"{_MuSlip(mu)}", ImplausibleValueWarning, stacklevel=1)
    if r1 > r2:
        warnings.warn(f"{where}: the worm radius r1 = {r1:g} m is larger than the wheel radius r2 = {r2:g} m "
                      f"(unusual: diameter quotient q above the wheel teeth z2){_RadiusSlip('r1', r1)}",
                      ImplausibleValueWarning, stacklevel=1)
