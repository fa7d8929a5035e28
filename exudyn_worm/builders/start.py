"""Where a linearization model starts: the worm turned into contact at rest, or the steady state of an operating
point (speed and the static mesh deflection), for the one-angle and the 3D model alike."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Optional, Tuple

from ..model.stability import OperatingPoint

if TYPE_CHECKING:
    from ..model.gear import WormGear

__all__ = ['LinearizationStart']

#: normal pre-deflection in m beyond half the backlash at which the 2-DOF model is linearized (any value > 0
#: gives the same result: with S held the law is linear in the deflection)
_PRELOAD = 1e-6


def LinearizationStart(gear: 'WormGear', S: Optional[int] = None, operatingPoint: Optional[OperatingPoint] = None
                       ) -> Tuple[float, float]:
    """Worm speed in rad/s and the worm's turn into contact in rad of a linearization model (wheel at angle 0).

    At rest (no ``operatingPoint``) the worm is turned over half the backlash and a small preload; at an operating
    point everything turns at the worm speed ``slidingSpeed cos(gamma) / r1`` and the worm is turned so that the
    mesh carries the point's normal force on the flank sigma = S.

    Parameters
    ----------
    gear : WormGear
        The gear.
    S : int, optional
        The flank to load at the operating point (+1 or -1).
    operatingPoint : OperatingPoint, optional
        The steady state; None: at rest.

    Returns
    -------
    (float, float)
    """
    if operatingPoint is None:
        return 0., (0.5 * gear.backlash + _PRELOAD) / gear.normalLever
    speed = operatingPoint.slidingSpeed * math.cos(gear.gamma) / gear.r1
    deflection = operatingPoint.normalForce / gear.kV if operatingPoint.normalForce > 0 else _PRELOAD
    return speed, S * (0.5 * gear.backlash + deflection) / gear.normalLever
