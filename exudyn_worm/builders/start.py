"""Where a linearization model starts: the worm turned into contact at rest, or the steady state of an operating
point (speed and the static mesh deflection), for the one-angle and the 3D model alike."""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Optional, Tuple

from ..model.contact import ContactOptions
from ..model.stability import OperatingPoint

if TYPE_CHECKING:
    from ..model.gear import WormGear

__all__ = ['LinearizationStart', 'LinearizationPoint']

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


@dataclass(frozen=True)
class LinearizationPoint:
    """Where a model builder makes its model to be linearized instead of to be simulated: no load, the motor held
    on its path at the point's speed (a motor on its characteristic stays free), every rotor turning at that speed
    and the worm turned into contact (:func:`LinearizationStart`), the contact state ``S`` held in the mesh law.

    Attributes
    ----------
    S : int or None
        Contact parameter held in the mesh, +1 or -1; None: S follows eq. (8) (for
        :func:`~exudyn_worm.analysis.stability.linearization.AnalyzeLinearStability`, which holds it itself).
    operatingPoint : OperatingPoint or None
        The steady state to start in (needs ``S``, the flank to load); None: at rest.
    """
    S: Optional[int] = None
    operatingPoint: Optional[OperatingPoint] = None

    def __post_init__(self):
        if self.S is not None and (isinstance(self.S, bool) or self.S not in (1, -1)):
            raise ValueError(f"LinearizationPoint: 'S' must be None, +1 or -1, got {self.S!r}")
        if self.operatingPoint is not None and self.S is None:
            raise ValueError("LinearizationPoint: with an 'operatingPoint' give 'S' (+1 or -1), the flank to load, "
                             "got None")

    def Start(self, gear: 'WormGear') -> Tuple[float, float]:
        """Worm speed in rad/s and the worm's turn into contact in rad (:func:`LinearizationStart`).

        Parameters
        ----------
        gear : WormGear
            The gear.
        """
        return LinearizationStart(gear, self.S, self.operatingPoint)

    def ContactOptions(self, options: ContactOptions) -> ContactOptions:
        """``options`` with the contact state held (S fixed, damping that may pull: the law stays linear about
        the start); unchanged for S = None.

        Parameters
        ----------
        options : ContactOptions
            The caller's options.
        """
        return options if self.S is None else replace(options, fixedS=self.S, dampingCanPull=True)
