"""Design check: which change of J1 or kT makes an unstable (chattering) drive stable.

Uses the analytical model (:func:`~exudyn_worm.stability.AnalyzeStability`); the paper's Figure 4 shows
that stability can be reached by increasing or decreasing J1 or kT, so both directions are searched.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Dict, List, Mapping, Optional

import numpy as np

from ._checks import CheckRange
from .presets import ApplyOverrides, DriveFromParameters
from .stability import AnalyzeStability

__all__ = ['DESIGN_KEYS', 'StableRange', 'NearestStableValue', 'StabilizingChanges']

#: parameters the design check varies, with the chart ratio they are shown as and their unit
DESIGN_KEYS = {'J1': ('J1/J2', 'kg*m^2'), 'kT': ('kT/(kV r1^2)', 'N*m/rad')}


def _Stable(parameters: Mapping[str, float], key: str, value: float) -> bool:
    return AnalyzeStability(DriveFromParameters(ApplyOverrides(parameters, {key: value}))).stable


def NearestStableValue(parameters: Mapping[str, float], key: str, direction: int, span: float = 100.,
                       steps: int = 80) -> Optional[float]:
    """Nearest value of ``key`` below (``direction = -1``) or above (+1) the given one that makes both
    contact states stable, other parameters as given; None if there is none within ``span`` times.

    Geometric scan (``steps`` steps to ``span``), then bisection to 1e-12 relative. Damping given as a
    measure (D_T, D_TV) stays a measure, as in the paper's charts; damping given as dT stays dT.
    """
    if direction not in (-1, 1):
        raise ValueError(f"NearestStableValue: 'direction' must be -1 or +1, got {direction!r}")
    CheckRange('NearestStableValue', 'span', span, low=1., lowOpen=True)
    base = parameters[key]
    last = 1.
    for f in np.geomspace(1., span ** direction, steps + 1)[1:]:
        if _Stable(parameters, key, base * f):
            lo, hi = math.log(last), math.log(f)        # unstable at lo, stable at hi
            for _ in range(40):
                mid = 0.5 * (lo + hi)
                lo, hi = (lo, mid) if _Stable(parameters, key, base * math.exp(mid)) else (mid, hi)
            return base * math.exp(hi)
        last = f
    return None


@dataclass(frozen=True)
class StableRange:
    """Nearest stable values of one parameter on both sides of the given value (None: not found)."""
    key: str
    given: float
    below: Optional[float]
    above: Optional[float]
    ratioName: str
    ratioScale: float       #: multiply a value by this to get the chart ratio
    unit: str


def StabilizingChanges(parameters: Mapping[str, float], span: float = 100.) -> List[StableRange]:
    """For J1 and kT separately: the nearest values that make the drive stable.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set (see :func:`~exudyn_worm.presets.DriveFromParameters`).
    span : float
        Search from 1/span to span times the given value, > 1.

    Returns
    -------
    list of StableRange
    """
    drive = DriveFromParameters(parameters)
    scales: Dict[str, float] = {'J1': 1. / drive.J2, 'kT': 1. / (drive.gear.kV * drive.gear.r1**2)}
    return [StableRange(key, parameters[key], NearestStableValue(parameters, key, -1, span),
                        NearestStableValue(parameters, key, +1, span), ratioName, scales[key], unit)
            for key, (ratioName, unit) in DESIGN_KEYS.items()]
