"""The hint of ``exudyn-worm stability``: the nearest stable values of J1 and kT, other parameters as given (the
margin-0 case of the design check's scan, :mod:`exudyn_worm.analysis.design.designscan`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Dict, List, Optional

from ..._checks import CheckRange
from ...drive.presets import PARAMETER_UNITS
from ...drive.wholedrive import CheckDrive, Drive
from .designrules import DEFAULT_SPAN
from .designscan import Scanner

__all__ = ['StableRange', 'NearestStableValue', 'StabilizingChanges']


@dataclass(frozen=True)
class StableRange:
    """Nearest stable values of one parameter on both sides of the given value (None: not found).

    Attributes
    ----------
    key : str
        The parameter key (``'J1'`` or ``'kT'``).
    given : float
        Its given value, in ``unit``.
    below, above : float or None
        Nearest stable value below and above the given one, in ``unit`` (None: none within the span).
    ratioName : str
        The chart ratio the parameter is shown as (``'J1/J2'``, ``'kT/(kV r1^2)'``).
    ratioScale : float
        Multiply a value by this to get the chart ratio.
    unit : str
        Unit of ``given``, ``below`` and ``above``.
    """
    key: str
    given: float
    below: Optional[float]
    above: Optional[float]
    ratioName: str
    ratioScale: float       #: multiply a value by this to get the chart ratio
    unit: str

    def ToDict(self) -> Dict:
        """JSON-ready dictionary."""
        return {'parameter': self.key, 'given': self.given, 'below': self.below, 'above': self.above,
                'unit': self.unit, 'ratioName': self.ratioName,
                'ratioBelow': None if self.below is None else self.below * self.ratioScale,
                'ratioAbove': None if self.above is None else self.above * self.ratioScale}


#: parameters of the nearest-stable hint, with the chart ratio they are shown as
_HINT_KEYS = {'J1': 'J1/J2', 'kT': 'kT/(kV r1^2)'}


def NearestStableValue(drive: Drive, key: str, direction: int,
                       span: float = DEFAULT_SPAN) -> Optional[float]:
    """Nearest value of ``key`` below (``direction = -1``) or above (+1) the given one at which the drive is
    stable (S = +1 and -1), other parameters as given; the given value if it is stable; None if there is
    none within ``span`` times (the margin-0 case of :meth:`~exudyn_worm.analysis.design.designscan.AxisScan.Move`).

    Parameters
    ----------
    drive : Drive
        The drive.
    key : str
        Parameter to vary.
    direction : int
        -1 or +1.
    span : float, optional
        Search up to this factor, > 1.

    Returns
    -------
    float or None
    """
    if direction not in (-1, 1):
        raise ValueError(f"NearestStableValue: 'direction' must be -1 or +1, got {direction!r}")
    CheckRange('NearestStableValue', 'span', span, low=1., lowOpen=True)
    CheckDrive('NearestStableValue', drive)
    t = Scanner(drive).Scan(key, math.log10(span)).Move(direction, 0., span)
    return None if t is None else drive.parameters[key] * 10. ** t


def StabilizingChanges(drive: Drive, span: float = DEFAULT_SPAN) -> List[StableRange]:
    """For J1 and kT separately: the nearest values that make the drive stable.

    Parameters
    ----------
    drive : Drive
        The drive.
    span : float
        Search from 1/span to span times the given value, > 1.

    Returns
    -------
    list of StableRange
    """
    CheckRange('StabilizingChanges', 'span', span, low=1., lowOpen=True)
    CheckDrive('StabilizingChanges', drive)
    parameters, core, scanner = drive.parameters, drive.elastic, Scanner(drive)
    scales = {'J1': 1. / core.J2, 'kT': 1. / (core.gear.kV * core.gear.r1**2)}
    out = []
    for key, ratioName in _HINT_KEYS.items():
        scan = scanner.Scan(key, math.log10(span))
        below, above = (scan.Move(d, 0., span) for d in (-1, 1))
        out.append(StableRange(key, parameters[key], None if below is None else parameters[key] * 10. ** below,
                               None if above is None else parameters[key] * 10. ** above, ratioName, scales[key],
                               PARAMETER_UNITS[key]))
    return out
