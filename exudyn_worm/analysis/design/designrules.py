"""The margin rule of the design check and the recommendations it gives.

**Margin rule** (one rule, applied everywhere; ``margin`` = delta in decades, default
:data:`DEFAULT_MARGIN` = 0.1, i.e. a factor 10^0.1 = 1.26): a drive is *stable with margin* along a
parameter if it stays stable when that parameter alone is multiplied by any factor between 10^-delta and
10^+delta. A recommendation is the smallest change of one parameter (smallest increase and smallest
decrease, each within a factor ``span`` = 100) after which the drive is stable with margin along that
parameter: usually the boundary crossed plus delta decades, further where the stable band beyond the
boundary is narrower than 2 delta. A pair of parameters (given only where no single parameter suffices, for the
two-mass drive) must be stable for every combination of both factors within 10^-delta..10^+delta, and the best
pair is the one with the smallest Euclidean change in decades. A drive gets recommendations iff it is not stable
with margin along some design parameter; the changes are then along those parameters (for an unstable
drive: all of them). The search that applies the rule is :func:`~exudyn_worm.analysis.design.designcheck.DesignCheck`.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Dict, Optional, Tuple, Union

from ..._checks import JsonNumber
from ...drive.presets import PARAMETER_UNITS

__all__ = ['DEFAULT_MARGIN', 'DEFAULT_SPAN', 'MarginRule', 'Recommendation', 'PairRecommendation']

#: default margin in decades of a parameter factor (10^0.1 = 1.26: a 26 % error keeps the drive stable)
DEFAULT_MARGIN = 0.1


#: default search range: factors from 1/100 to 100
DEFAULT_SPAN = 100.


@dataclass(frozen=True)
class Recommendation:
    """One recommended change of one design parameter.

    Attributes
    ----------
    parameter : str
        The key changed.
    factor : float
        New value / given value (> 1: increase, < 1: decrease).
    newValue : float
        The new value (unit of the key, :data:`~exudyn_worm.drive.presets.PARAMETER_UNITS`).
    maxRealPartAfter : float
        Largest real part of the eigenvalues of the changed drive in 1/s at its deciding operating point (< 0:
        stable).
    chartPointAfter : dict
        The chart point of the changed drive's two-mass core (:func:`~exudyn_worm.analysis.charts.stabilitychart.ChartCoordinates`).
    simulatedChatter : bool, str or None
        Chatter while lowering in the reel-changer simulation (:func:`~exudyn_worm.analysis.design.designconfirm.ConfirmBySimulation`), None if
        not simulated.
    """
    parameter: str
    factor: float
    newValue: float
    maxRealPartAfter: float
    chartPointAfter: Dict[str, float]
    simulatedChatter: Optional[Union[bool, str]] = None

    @property
    def unit(self) -> str:
        """SI unit of the parameter."""
        return PARAMETER_UNITS.get(self.parameter, '')

    @property
    def changes(self) -> Dict[str, float]:
        """The change as ``{key: newValue}`` (for :func:`~exudyn_worm.drive.presets.ApplyOverrides`)."""
        return {self.parameter: self.newValue}

    def ToDict(self) -> Dict:
        """JSON-ready dictionary."""
        return {'parameter': self.parameter, 'factor': self.factor, 'newValue': self.newValue, 'unit': self.unit,
                'maxRealPartAfter': self.maxRealPartAfter,
                'chartPointAfter': {k: JsonNumber(v) for k, v in self.chartPointAfter.items()},
                'simulatedChatterWhileLowering': self.simulatedChatter}


@dataclass(frozen=True)
class PairRecommendation:
    """A change of two design parameters together (given where no single parameter suffices).

    Attributes
    ----------
    parameters : tuple of str
        The two keys.
    factors : tuple of float
        New value / given value of each.
    newValues : tuple of float
        The new values.
    maxRealPartAfter : float
        Largest real part of the eigenvalues of the changed drive in 1/s at its deciding operating point.
    chartPointAfter : dict
        The changed drive's chart point.
    simulatedChatter : bool, str or None
        Chatter while lowering in the simulation, None if not simulated.
    """
    parameters: Tuple[str, str]
    factors: Tuple[float, float]
    newValues: Tuple[float, float]
    maxRealPartAfter: float
    chartPointAfter: Dict[str, float]
    simulatedChatter: Optional[Union[bool, str]] = None

    @property
    def changes(self) -> Dict[str, float]:
        """The change as ``{key: newValue, ...}``."""
        return dict(zip(self.parameters, self.newValues))

    def ToDict(self) -> Dict:
        """JSON-ready dictionary."""
        return {'parameters': list(self.parameters), 'factors': list(self.factors),
                'newValues': list(self.newValues), 'units': [PARAMETER_UNITS.get(k, '') for k in self.parameters],
                'maxRealPartAfter': self.maxRealPartAfter,
                'chartPointAfter': {k: JsonNumber(v) for k, v in self.chartPointAfter.items()},
                'simulatedChatterWhileLowering': self.simulatedChatter}


def MarginRule(margin: float, span: float) -> str:
    """The margin rule in one sentence, for a report (``exudyn-worm check --json``: ``margin.rule``).

    Parameters
    ----------
    margin : float
        Margin in decades.
    span : float
        Largest factor searched.

    Returns
    -------
    str
    """
    return (f"stable with margin = stable when the changed parameter alone is multiplied by any factor between "
            f"10^-{margin:g} and 10^{margin:g} ({10 ** -margin:.3g} to {10 ** margin:.3g}); a recommendation is the "
            f"smallest increase or decrease within a factor {span:g} that makes the drive stable with margin")
