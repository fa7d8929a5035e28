"""Design check: is a drive stable, how far is it from the stability boundary, and which change makes it stable.

The analytical model (:func:`~exudyn_worm.model.stability.AnalyzeStability`, both contact states S = +1 and
S = -1) decides stability. The paper's Figure 4 shows that a chattering drive (P1) can be made stable by
increasing or by decreasing J1 or kT (section 3.2.4 reads P2-P5 off the chart), so every design parameter
is searched in both directions.

**Design parameters.** J1, J2, kT, the shaft damping and the mesh damping, each in the form the parameter
set holds it: the shaft damping as ``dT`` (constant), ``DT`` (measure, eq. (22)) or ``DTV`` (ratio,
eq. (24)); the mesh damping as ``dV`` or ``DV`` (eq. (23)). **What is held** when one of them changes
is what the parameter set holds: the presets hold the measures D_T, D_V (as the paper's chart points
assume), so a larger J1 or kT brings a larger dT = 2 D_T sqrt(kT J1); a set that gives ``dT``/``dV``
keeps those constants. With ``DTV`` a change of D_V changes D_T in proportion (the paper's move of P6
from Figure 4 to Figure 5).

**Margin rule** (one rule, applied everywhere; ``margin`` = delta in decades, default
:data:`DEFAULT_MARGIN` = 0.1, i.e. a factor 10^0.1 = 1.26): a drive is *stable with margin* along a
parameter if it stays stable when that parameter alone is multiplied by any factor between 10^-delta and
10^+delta. A recommendation is the smallest change of one parameter (smallest increase and smallest
decrease, each within a factor ``span`` = 100) after which the drive is stable with margin along that
parameter: usually the boundary crossed plus delta decades, further where the stable band beyond the
boundary is narrower than 2 delta. A pair of parameters (given only where no single parameter suffices)
must be stable for every combination of both factors within 10^-delta..10^+delta, and the best pair is
the one with the smallest Euclidean change in decades. A drive gets recommendations iff it is not stable
with margin along some design parameter; the changes are then along those parameters (for an unstable
drive: all of them). The distance to the stability boundary is measured in the same unit: decades,
Euclidean in the chart plane (log10 x, log10 y) at the drive's D_V and D_TV.

Searches scan the log factor on a grid (:data:`SCAN_STEP` decades) with the Hurwitz conditions
(17)-(19) of all candidate drives at once, then refine each boundary by bisection with the scalar model.
The candidate drives are built from the probed scaling of J1, J2, kT, dT and dV with each design parameter
(all are monomials of the parameters, eqs. (22)-(24)), so no formula of the model is repeated here.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from itertools import combinations
from typing import Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np

from .._checks import CheckRange, JsonNumber
from ..setups.presets import (PARAMETER_UNITS, ApplyOverrides, CheckParameterKeys, ElasticDriveFromParameters, ExtraComponents,
                      LumpedLoadSide)
from .charts import ChartCoordinates, ComputeStabilityChart
from ..model.stability import (CONTACT_STATES, AnalyzeStability, CharacteristicCoefficients, HurwitzStable,
                        OperatingPointFromParameters, PolynomialCoefficients)
from .drivestability import DriveStability
from .loadside import DiagnoseLoadSide, LoadSideNotLumpable
from .reelchanger import CheckReelChangerKeys, DefaultPhases
from ..model.selflocking import SelfLocking
from . import reelchanger

__all__ = ['DEFAULT_MARGIN', 'DEFAULT_SPAN', 'SCAN_STEP', 'DesignParameters', 'LocalCharts', 'ChartGrid',
           'AxisScan', 'ScanParameter', 'Recommendation', 'PairRecommendation', 'DesignCheckResult',
           'DesignCheck', 'ChatterWhileLowering', 'ConfirmBySimulation',
           'StableRange', 'NearestStableValue', 'StabilizingChanges', 'ScanMotorSpeed', 'SPEED_KEY']

#: default margin in decades of a parameter factor (10^0.1 = 1.26: a 26 % error keeps the drive stable)
DEFAULT_MARGIN = 0.1
#: default search range: factors from 1/100 to 100
DEFAULT_SPAN = 100.
#: grid step of the 1-D scans in decades (boundaries are then refined by bisection)
SCAN_STEP = 0.005
_PAIR_STEP = 0.01           # grid step of the pair search in decades
_CHART_DECADES = 2.         # the chart-plane distance is searched within +-2 decades of the drive's point
_CHART_STEP = 0.01
_REFINE_TOLERANCE = 1e-10   # bisection tolerance in decades

_SHAFT_DAMPING_FORMS = ('dT', 'DT', 'DTV')      # precedence as in ElasticDriveFromParameters
_MESH_DAMPING_FORMS = ('dV', 'DV')
#: the drive quantities a design parameter acts on
_QUANTITIES = ('J1', 'J2', 'kT', 'dT', 'dV')


def DesignParameters(parameters: Mapping[str, float]) -> List[str]:
    """The design parameters of a parameter set: J1, J2, kT and the damping keys in the form it holds them.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set (see :func:`~exudyn_worm.setups.presets.DriveFromParameters`).

    Returns
    -------
    list of str
        ``['J1', 'J2', 'kT', <dT|DT|DTV>, <dV|DV>]`` (a damping key only if present).
    """
    keys = ['J1', 'J2', 'kT']
    for forms in (_SHAFT_DAMPING_FORMS, _MESH_DAMPING_FORMS):
        key = next((k for k in forms if k in parameters), None)
        if key is not None:
            keys.append(key)
    return keys


def _MaxRealPart(analysis) -> float:
    return float(max(np.max(c.eigenvalues.real) for c in analysis.contact.values()))


def _Scaled(parameters: Mapping[str, float], changes: Mapping[str, float]) -> Dict[str, float]:
    """Parameters with ``key`` multiplied by 10**logFactor for each item of ``changes``."""
    return ApplyOverrides(parameters, {k: parameters[k] * 10. ** t for k, t in changes.items()})


def _OperatingPoint(parameters, drive):
    """The operating point of steady lowering for a speed-dependent friction law (None for constant mu, where the
    linear model does not depend on it, or without load and speed): the scans use mu(v0) and its slope there."""
    return OperatingPointFromParameters(parameters, drive.gear) if drive.gear.speedDependentFriction else None


def _StableAt(parameters, changes) -> bool:
    # Routh-Hurwitz on (16) is the same verdict as AnalyzeStability(...).stable without the polynomial roots
    # (10x faster; the stability command's hint evaluates about 100 drives at start-up)
    scaled = _Scaled(parameters, changes)
    drive = ElasticDriveFromParameters(scaled)
    op = _OperatingPoint(scaled, drive)
    return all(HurwitzStable(CharacteristicCoefficients(drive, S, op)) for S in CONTACT_STATES)


class _ScaledDrives:
    """Stability of many drives at once: the drive with design parameters multiplied by 10**t.

    J1, J2, kT, dT and dV are monomials of the parameters (eqs. (22)-(24)); their exponents are probed once
    per design parameter with :func:`DriveFromParameters` (and checked at a second factor), so the model's
    formulas stay in :mod:`presets`, :mod:`drive` and :mod:`stability`.
    """

    def __init__(self, parameters: Mapping[str, float], keys: Sequence[str]):
        self.drive = ElasticDriveFromParameters(parameters)
        self.operatingPoint = _OperatingPoint(parameters, self.drive)   # J1, J2, kT, dT, dV do not move it
        self.q0 = self._Quantities(self.drive)
        self.exponents = {}
        probe = 0.05       # decades: a small factor, so a drive at the edge of the allowed ranges is not refused
        for key in keys:
            up, down = (self._Quantities(ElasticDriveFromParameters(_Scaled(parameters, {key: s}))) for s in (probe, -probe))
            with np.errstate(divide='ignore', invalid='ignore'):
                e = np.where(self.q0 > 0, np.log10(up / self.q0) / probe, 0.)
            if not np.allclose(down, self.q0 * 10. ** (-e * probe), rtol=1e-9, atol=0.):
                raise RuntimeError(f"design: the drive does not scale as a power of '{key}' (internal error)")
            self.exponents[key] = e

    @staticmethod
    def _Quantities(drive) -> np.ndarray:
        return np.array([drive.J1, drive.J2, drive.kT, drive.dT, drive.gear.dV])

    def Stable(self, logFactors: Mapping[str, np.ndarray]) -> np.ndarray:
        """Boolean array: stable for S = +1 and S = -1 (Hurwitz (17)-(19) with b3, b4 > 0)."""
        shape = np.broadcast(*logFactors.values()).shape
        q = [self.q0[i] * 10. ** (np.zeros(shape) + sum(self.exponents[k][i] * np.asarray(t)
                                                         for k, t in logFactors.items()))
             for i in range(len(_QUANTITIES))]
        stable = np.ones(shape, dtype=bool)
        for S in CONTACT_STATES:
            stable &= HurwitzStable(PolynomialCoefficients(self.drive.gear, S, *q, operatingPoint=self.operatingPoint))
        return stable


def LocalCharts(parameters: Mapping[str, float], decades: float = _CHART_DECADES, step: float = _CHART_STEP):
    """The drive's stability charts (:func:`~exudyn_worm.analysis.charts.ComputeStabilityChart`, S = +1 and S = -1)
    on a log grid of +-``decades`` around its chart point, at its D_V and D_TV.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set.
    decades : float, optional
        Half-width of the grid in decades of x and y, > 0.
    step : float, optional
        Grid step in decades, in (0, decades].

    Returns
    -------
    dict
        ``{S: StabilityChart}`` for S = +1 and -1, on the same grid with the drive's point at its centre.
    """
    CheckRange('LocalCharts', 'decades', decades, low=0., lowOpen=True)
    CheckRange('LocalCharts', 'step', step, low=0., high=decades, lowOpen=True)
    drive = ElasticDriveFromParameters(parameters)
    p = ChartCoordinates(drive)
    n = 2 * int(math.ceil(decades / step)) + 1
    span = 10. ** decades
    return {S: ComputeStabilityChart(drive.gear, drive.J2, p['DV'], p['DTV'], xRange=(p['x'] / span, p['x'] * span),
                                     yRange=(p['y'] / span, p['y'] * span), resolution=n, S=S)
            for S in CONTACT_STATES}


def ChartGrid(parameters: Mapping[str, float], decades: float = _CHART_DECADES, step: float = _CHART_STEP):
    """Stability (S = +1 and S = -1) on the grid of :func:`LocalCharts` around the drive's chart point.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set.
    decades : float, optional
        Half-width of the grid in decades of x and y, > 0.
    step : float, optional
        Grid step in decades, in (0, decades].

    Returns
    -------
    x, y, stable : numpy.ndarray
        1-D grids of x = kT/(kV r1^2) and y = J1/J2 and the boolean stability of shape ``(len(y), len(x))``.
    """
    charts = LocalCharts(parameters, decades, step)
    c = charts[-1]
    return c.x, c.y, ~(charts[-1].unstable | charts[+1].unstable)


def _SymmetricGrid(limit, step):
    n = int(math.ceil(limit / step))
    return np.linspace(-limit, limit, 2 * n + 1)


def _ChartDistance(parameters) -> Tuple[Optional[float], Optional[Dict[str, float]]]:
    """Distance in decades from the drive's point to the nearest point of opposite verdict in the chart plane
    (grid of :func:`LocalCharts`, then refined along the ray to that point with the charts' exact verdict)."""
    charts = LocalCharts(parameters)
    x, y = charts[-1].x, charts[-1].y
    stable = ~(charts[-1].unstable | charts[+1].unstable)
    t = np.log10(x / x[x.size // 2])
    c = t.size // 2
    other = stable != stable[c, c]
    if not other.any():
        return None, None
    d2 = np.where(other, t[None, :] ** 2 + t[:, None] ** 2, np.inf)
    iy, ix = np.unravel_index(np.argmin(d2), d2.shape)
    length = math.sqrt(d2[iy, ix])
    direction = np.array([t[ix], t[iy]]) / length            # (log x, log y)
    r = np.linspace(0., length, 4001)
    rx, ry = x[c] * 10. ** (r * direction[0]), y[c] * 10. ** (r * direction[1])
    ray = ~(charts[-1].IsUnstable(rx, ry) | charts[+1].IsUnstable(rx, ry))
    first = int(np.argmax(ray != ray[0]))
    distance = float(r[first]) if first > 0 else length
    return distance, {'x': float(x[c] * 10. ** (distance * direction[0])),
                      'y': float(y[c] * 10. ** (distance * direction[1]))}


@dataclass(frozen=True)
class AxisScan:
    """Where the drive is stable when one design parameter alone is multiplied by 10**t.

    Attributes
    ----------
    parameter : str
        The parameter key.
    value : float
        Its given value.
    stableIntervals : tuple of (float, float)
        Intervals of t (decades) with a stable drive, boundaries refined by bisection; an interval that
        reaches ``limit`` may continue beyond it.
    limit : float
        The scan covered -limit <= t <= limit.
    """
    parameter: str
    value: float
    stableIntervals: Tuple[Tuple[float, float], ...]
    limit: float

    def Move(self, direction: int, margin: float, span: float) -> Optional[float]:
        """Smallest change t (decades, sign of ``direction``, ``|t| <= log10(span)``) after which every
        t' with ``|t' - t| <= margin`` is stable; 0 if the given value already is; None if there is none.

        Parameters
        ----------
        direction : int
            +1 (increase) or -1 (decrease).
        margin : float
            Margin in decades, >= 0.
        span : float
            Largest factor, > 1.
        """
        L = math.log10(span)
        moves = []
        for a, b in self.stableIntervals:
            if direction > 0:
                t = max(0., a + margin)
                if t <= L and b - t >= margin:
                    moves.append(t)
            else:
                t = min(0., b - margin)
                if t >= -L and t - a >= margin:
                    moves.append(t)
        return min(moves, key=abs) if moves else None

    def Boundaries(self) -> List[float]:
        """The refined stability boundaries (decades) inside the scanned range."""
        return sorted(t for ab in self.stableIntervals for t in ab if abs(t) < self.limit)


def ScanParameter(parameters: Mapping[str, float], key: str, limit: float, step: float = SCAN_STEP) -> AxisScan:
    """Scan the stability of the drive with ``key`` multiplied by 10**t for ``|t| <= limit``.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set.
    key : str
        A design parameter present in ``parameters`` with a value > 0.
    limit : float
        Scanned range in decades, > 0.
    step : float, optional
        Grid step in decades; boundaries are refined by bisection to 1e-10 decades.

    Returns
    -------
    AxisScan
    """
    w = 'ScanParameter'
    if key not in parameters:
        raise ValueError(f"{w}: 'key' must be a key of the parameter set, got {key!r}")
    CheckRange(w, key, parameters[key], low=0., lowOpen=True, unit=PARAMETER_UNITS.get(key, ''))
    CheckRange(w, 'limit', limit, low=0., lowOpen=True)
    CheckRange(w, 'step', step, low=0., high=limit, lowOpen=True)
    t = _SymmetricGrid(limit, step)
    stable = _ScaledDrives(parameters, (key,)).Stable({key: t})
    intervals = []
    start = None
    for i, s in enumerate(stable):
        if s and start is None:
            start = -limit if i == 0 else _Refine(parameters, key, t[i - 1], t[i])
        if not s and start is not None:
            intervals.append((start, _Refine(parameters, key, t[i], t[i - 1])))
            start = None
    if start is not None:
        intervals.append((start, limit))
    return AxisScan(key, float(parameters[key]), tuple((float(a), float(b)) for a, b in intervals), float(limit))


def _Refine(parameters, key, tUnstable, tStable) -> float:
    """Bisection between an unstable and a stable log factor; returns the stable end."""
    while abs(tStable - tUnstable) > _REFINE_TOLERANCE:
        mid = 0.5 * (tUnstable + tStable)
        if _StableAt(parameters, {key: mid}):
            tStable = mid
        else:
            tUnstable = mid
    return tStable


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
        The new value (unit of the key, :data:`~exudyn_worm.setups.presets.PARAMETER_UNITS`).
    maxRealPartAfter : float
        Largest real part of the eigenvalues (S = +1 and -1) of the changed drive in 1/s (< 0: stable).
    chartPointAfter : dict
        The changed drive's chart point (:func:`~exudyn_worm.analysis.charts.ChartCoordinates`).
    simulatedChatter : bool or None
        Chatter while lowering in the reel-changer simulation (:func:`ConfirmBySimulation`), None if
        not simulated.
    """
    parameter: str
    factor: float
    newValue: float
    maxRealPartAfter: float
    chartPointAfter: Dict[str, float]
    simulatedChatter: Optional[bool] = None

    @property
    def unit(self) -> str:
        """SI unit of the parameter."""
        return PARAMETER_UNITS.get(self.parameter, '')

    @property
    def changes(self) -> Dict[str, float]:
        """The change as ``{key: newValue}`` (for :func:`~exudyn_worm.setups.presets.ApplyOverrides`)."""
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
        Largest real part of the eigenvalues of the changed drive in 1/s.
    chartPointAfter : dict
        The changed drive's chart point.
    simulatedChatter : bool or None
        Chatter while lowering in the simulation, None if not simulated.
    """
    parameters: Tuple[str, str]
    factors: Tuple[float, float]
    newValues: Tuple[float, float]
    maxRealPartAfter: float
    chartPointAfter: Dict[str, float]
    simulatedChatter: Optional[bool] = None

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


def _MarginRule(margin: float, span: float) -> str:
    return (f"stable with margin = stable when the changed parameter alone is multiplied by any factor between "
            f"10^-{margin:g} and 10^{margin:g} ({10 ** -margin:.3g} to {10 ** margin:.3g}); a recommendation is the "
            f"smallest increase or decrease within a factor {span:g} that makes the drive stable with margin")


@dataclass(frozen=True)
class DesignCheckResult:
    """Result of :func:`DesignCheck`.

    Attributes
    ----------
    parameters : dict
        The parameter set checked.
    margin : float
        Margin in decades (see the module docstring for the rule).
    span : float
        Largest factor searched.
    analysis : StabilityAnalysis
        Analytical stability of the given drive.
    chartPoint : dict
        :func:`~exudyn_worm.analysis.charts.ChartCoordinates` of the drive.
    distanceToBoundary : float or None
        Decades from the chart point to the stability boundary (Euclidean in log10 x, log10 y at the
        drive's D_V and D_TV); None if there is none within 2 decades.
    nearestBoundaryPoint : dict or None
        ``{'x', 'y'}`` of that boundary point.
    scans : dict
        :class:`AxisScan` of each design parameter.
    marginShortBy : list of str
        Design parameters along which the drive is not stable with margin (empty: stable with margin).
    recommendations : list of Recommendation
        Smallest increases and decreases, one parameter each.
    bestPair : PairRecommendation or None
        Where no single parameter suffices: the smallest change of two.
    notes : list of str
        Parameters that could not be varied (value 0) and similar remarks.
    simulatedChatter : bool or None
        Chatter while lowering of the given drive in the simulation (None if not simulated).
    """
    parameters: Dict[str, float]
    margin: float
    span: float
    analysis: object
    chartPoint: Dict[str, float]
    distanceToBoundary: Optional[float]
    nearestBoundaryPoint: Optional[Dict[str, float]]
    scans: Dict[str, AxisScan]
    marginShortBy: List[str]
    recommendations: List[Recommendation]
    bestPair: Optional[PairRecommendation] = None
    notes: List[str] = field(default_factory=list)
    simulatedChatter: Optional[bool] = None

    @property
    def stable(self) -> bool:
        """Stable for S = +1 and S = -1."""
        return self.analysis.stable

    @property
    def stableWithMargin(self) -> bool:
        """Stable with the margin along every design parameter."""
        return self.stable and not self.marginShortBy

    @property
    def maxRealPart(self) -> float:
        """Largest real part of the eigenvalues of both contact states in 1/s."""
        return _MaxRealPart(self.analysis)

    @property
    def singleParameterSuffices(self) -> bool:
        """True if no change is needed or one parameter alone can give stability with margin."""
        return self.stableWithMargin or bool(self.recommendations)

    def Missing(self) -> List[Tuple[str, int]]:
        """(parameter, direction) for which no change within the span gives stability with margin,
        for the parameters that need a change.

        Returns
        -------
        list of (str, int)
        """
        found = {(r.parameter, 1 if r.factor > 1 else -1) for r in self.recommendations}
        return [(k, d) for k in self.marginShortBy for d in (1, -1) if (k, d) not in found]

    @property
    def selfLockingVerdict(self):
        """Static and dynamic self-locking (:func:`~exudyn_worm.model.selflocking.SelfLocking`), the dynamic one at the
        sliding speed of ``motorSpeed`` if the parameter set gives it."""
        gear = self.analysis.drive.gear
        speed = self.parameters.get('motorSpeed')
        return SelfLocking(gear, None if speed is None else gear.SlidingSpeed(speed))

    def ToDict(self) -> Dict:
        """JSON-ready dictionary (the schema of ``exudyn-worm check --json``).

        Returns
        -------
        dict
        """
        contact = {f'{S:+d}': {'stable': self.analysis.contact[S].stable,
                               'maxRealPart': float(np.max(self.analysis.contact[S].eigenvalues.real))}
                   for S in CONTACT_STATES}
        point = {k: JsonNumber(v) for k, v in self.chartPoint.items()}
        point.update(distanceToBoundary=self.distanceToBoundary, nearestBoundaryPoint=self.nearestBoundaryPoint)
        data = {'stable': self.stable, 'stableWithMargin': self.stableWithMargin, 'maxRealPart': self.maxRealPart,
                'S': contact, 'chartPoint': point,
                'margin': {'decades': self.margin, 'factor': 10. ** self.margin, 'rule': _MarginRule(self.margin, self.span)},
                'span': self.span, 'designParameters': list(self.scans), 'marginShortBy': list(self.marginShortBy),
                'recommendations': [r.ToDict() for r in self.recommendations],
                'noRecommendation': [{'parameter': k, 'direction': 'increase' if d > 0 else 'decrease'}
                                     for k, d in self.Missing()],
                'singleParameterSuffices': self.singleParameterSuffices,
                'bestPair': self.bestPair.ToDict() if self.bestPair else None,
                'notes': list(self.notes)}
        data['selfLockingVerdict'] = self.selfLockingVerdict.ToDict()
        if self.simulatedChatter is not None:
            data['simulatedChatterWhileLowering'] = self.simulatedChatter
        return data

    def plot(self, ax=None, title: str = ''):
        """Draw the drive's point, the stability boundary and the recommended moves on the chart.

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw into (default: a new figure).
        title : str, optional
            First title line, e.g. the drive's name.

        Returns
        -------
        matplotlib.figure.Figure
        """
        from ..plotting.plot_design import PlotDesignCheck   # lazy: matplotlib only when drawing
        return PlotDesignCheck(self, LocalCharts(self.parameters), ax=ax, title=title)


def _Changed(parameters, changes):
    scaled = _Scaled(parameters, changes)
    drive = ElasticDriveFromParameters(scaled)
    return _MaxRealPart(AnalyzeStability(drive, _OperatingPoint(scaled, drive))), ChartCoordinates(drive)


#: the motor speed, a design parameter when the friction depends on speed (:func:`ScanMotorSpeed`)
SPEED_KEY = 'motorSpeed'
_SPEED_STEP = 0.01          # grid step of the speed scan in decades (each point is a whole drive and operating point)


def ScanMotorSpeed(parameters: Mapping[str, float], limit: float, step: float = _SPEED_STEP) -> AxisScan:
    """Scan the stability of the drive with ``motorSpeed`` multiplied by 10**t for ``|t| <= limit``.

    With a speed-dependent friction law the operating point (mu(v0), its slope, the normal force) moves with the
    speed, so every point is a drive of its own (:func:`ScanParameter` scales J1, J2, kT, dT, dV only).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set with ``motorSpeed``, ``loadMass`` and ``leverArm``.
    limit : float
        Scanned range in decades, > 0.
    step : float, optional
        Grid step in decades; boundaries are refined by bisection.

    Returns
    -------
    AxisScan
    """
    w = 'ScanMotorSpeed'
    CheckRange(w, SPEED_KEY, parameters.get(SPEED_KEY, 0.), low=0., lowOpen=True, unit='rad/s')
    CheckRange(w, 'limit', limit, low=0., lowOpen=True)
    t = _SymmetricGrid(limit, step)
    stable = [_StableAt(parameters, {SPEED_KEY: ti}) for ti in t]
    intervals, start = [], None
    for i, s in enumerate(stable):
        if s and start is None:
            start = -limit if i == 0 else _Refine(parameters, SPEED_KEY, t[i - 1], t[i])
        if not s and start is not None:
            intervals.append((start, _Refine(parameters, SPEED_KEY, t[i], t[i - 1])))
            start = None
    if start is not None:
        intervals.append((start, limit))
    return AxisScan(SPEED_KEY, float(parameters[SPEED_KEY]), tuple((float(a), float(b)) for a, b in intervals),
                    float(limit))


def _BestPair(parameters, keys, margin, span) -> Optional[PairRecommendation]:
    """The smallest (Euclidean, in decades) change of two parameters that is stable with margin on the
    whole square of both factors within 10^+-margin; checked with the scalar model on a 5 x 5 grid."""
    L = math.log10(span)
    t = _SymmetricGrid(L + margin, _PAIR_STEP)
    half = int(round(margin / (t[1] - t[0])))
    scaled = _ScaledDrives(parameters, keys)
    candidates = []
    for a, b in combinations(keys, 2):
        stable = scaled.Stable({a: t[:, None], b: t[None, :]})
        if half > 0:
            from scipy.ndimage import binary_erosion
            stable = binary_erosion(stable, structure=np.ones((2 * half + 1,) * 2, dtype=bool), border_value=0)
        inside = (np.abs(t) <= L)
        ok = stable & inside[:, None] & inside[None, :]
        for i, j in zip(*np.nonzero(ok)):
            candidates.append((t[i] ** 2 + t[j] ** 2, a, b, float(t[i]), float(t[j])))
    offsets = np.linspace(-margin, margin, 5)
    for _, a, b, ta, tb in sorted(candidates):
        if all(_StableAt(parameters, {a: ta + da, b: tb + db}) for da in offsets for db in offsets):
            maxRe, point = _Changed(parameters, {a: ta, b: tb})
            return PairRecommendation((a, b), (10. ** ta, 10. ** tb),
                                      (parameters[a] * 10. ** ta, parameters[b] * 10. ** tb), maxRe, point)
    return None


_CHARACTERISTIC = 'a motor on its characteristic (motorType characteristic)'     # as ExtraComponents names it


def _CharacteristicNote(parameters: Mapping[str, float], where: str) -> str:
    """The note for a drive with a motor on its characteristic, checked as the two-mass drive (the motor holding its
    speed); raises if the linearized whole drive with the free motor has another verdict in either contact state."""
    whole, rigid = DriveStability(parameters), AnalyzeStability(ElasticDriveFromParameters(parameters))
    words = {True: 'stable', False: 'unstable'}
    for S in CONTACT_STATES:
        if whole.State(S).stable != rigid.State(S).stable:
            raise ValueError(
                f"{where}: the motor's characteristic changes the verdict for S = {S:+d} (the whole drive with the "
                f"free motor, motorInertia and the slope stallTorque/noLoadSpeed, is {words[whole.State(S).stable]}; "
                f"the two-mass model of the design check, whose motor holds its speed, is "
                f"{words[rigid.State(S).stable]}), so the check cannot recommend changes for it; "
                f"'exudyn-worm stability' analyses the whole drive")
    return ("the motor on its characteristic is checked as a motor holding its speed (the two-mass model): the "
            "linearized whole drive with the free motor has the same verdict for S = +1 and S = -1; confirm a "
            "recommended change with 'exudyn-worm stability'")


def DesignCheck(parameters: Mapping[str, float], margin: float = DEFAULT_MARGIN,
                span: float = DEFAULT_SPAN) -> DesignCheckResult:
    """Check a drive for chatter and recommend the smallest changes that make it stable with a margin.

    The margin rule, the design parameters and what is held when one changes are described in the
    module docstring of :mod:`exudyn_worm.analysis.design`.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set (e.g. ``GetPreset('reel-P1')``).
    margin : float, optional
        Margin in decades of a parameter factor, in [0, 1] (default 0.1: factor 1.26).
    span : float, optional
        Largest factor searched in each direction, in (1, 1e4] (default 100).

    Returns
    -------
    DesignCheckResult
        Verdict for S = +1 and -1, the largest real part, the chart point and its distance to the
        boundary, the recommendations and, where no single parameter suffices, the best pair.

    Raises
    ------
    ValueError, TypeError
        For a bad parameter set, margin or span, or a parameter set with components the two-mass model
        does not include (a drive-side chain J4, ... or a worm axial bearing kA > 0), or a motor on its
        characteristic that changes the verdict of the two-mass model (motor holding its speed) in a contact
        state; where it does not, the drive is checked as the two-mass drive with a note.
    LoadSideNotLumpable
        A ValueError: the parameter set has a load-side chain (JL1, ...) that may not be lumped into J2
        (:func:`~exudyn_worm.analysis.loadside.DiagnoseLoadSide`); the message and its ``diagnosis`` name the stage that is
        the cause. A load-side chain that may be lumped is checked as the lumped drive (a note says so).
    """
    w = 'DesignCheck'
    margin = CheckRange(w, 'margin', margin, low=0., high=1., unit='decades')
    span = CheckRange(w, 'span', span, low=1., high=1e4, lowOpen=True)
    CheckParameterKeys(parameters, w)
    parameters = dict(parameters)
    extra = ExtraComponents(parameters)
    notes = []
    if extra == ['a load-side chain (JL1, ...)']:      # the two-mass model holds if the load may be lumped into J2
        diagnosis = DiagnoseLoadSide(parameters, margin)
        if not diagnosis.lumpingSafe:
            raise LoadSideNotLumpable(f"{w}: {diagnosis.Text()}; the two-mass model of the design check (eqs. "
                                      f"(15)-(19)) does not describe this drive", diagnosis)
        parameters = LumpedLoadSide(parameters)
        notes.append(f"the load-side chain is lumped into J2 = {parameters['J2']:.4g} kg*m^2 (changes of J2 are "
                     f"changes of wheel and driven machine): {diagnosis.Text()}")
    elif extra == [_CHARACTERISTIC]:      # the two-mass model holds a motor at its speed: valid if the verdict stays
        notes.append(_CharacteristicNote(parameters, w))
    elif extra:
        raise ValueError(f"{w}: the design check uses the two-mass model of Figure 2 (eqs. (15)-(19)); this "
                         f"parameter set has {' and '.join(extra)}, which that model does not include")
    drive = ElasticDriveFromParameters(parameters)
    analysis = AnalyzeStability(drive, _OperatingPoint(parameters, drive))
    keys = []
    for key in DesignParameters(parameters):
        if parameters[key] > 0:
            keys.append(key)
        else:
            notes.append(f"{key} = 0 cannot be changed by a factor; give it a value > 0 to include it")
    limit = math.log10(span) + margin
    scans = {key: ScanParameter(parameters, key, limit) for key in keys}
    if _OperatingPoint(parameters, drive) is not None:       # the friction depends on speed: the speed is a remedy
        scans[SPEED_KEY] = ScanMotorSpeed(parameters, limit)
        keys.append(SPEED_KEY)
    short = [k for k in keys if not (analysis.stable and scans[k].Move(+1, margin, span) == 0.)]
    recommendations = []
    for key in short:
        for direction in (+1, -1):
            t = scans[key].Move(direction, margin, span)
            if t is not None and t != 0.:
                maxRe, point = _Changed(parameters, {key: t})
                recommendations.append(Recommendation(key, 10. ** t, parameters[key] * 10. ** t, maxRe, point))
    bestPair = None
    pairKeys = [k for k in keys if k != SPEED_KEY]          # the pair search scales J1, J2, kT, dT, dV only
    if short and not recommendations and len(pairKeys) >= 2:
        bestPair = _BestPair(parameters, pairKeys, margin, span)
    distance, boundaryPoint = _ChartDistance(parameters)
    return DesignCheckResult(parameters, margin, span, analysis, ChartCoordinates(drive), distance, boundaryPoint,
                             scans, short, recommendations, bestPair, notes)


def ChatterWhileLowering(parameters: Mapping[str, float], stepSize: Optional[float] = None) -> bool:
    """Time-domain verdict: does the reel changer chatter while lowering the load?

    One rotation with :func:`~exudyn_worm.analysis.reelchanger.SimulateReelChanger`; the verdict is
    :meth:`~exudyn_worm.items.results.SimulationResult.Chatter` on the lowering window of
    :func:`~exudyn_worm.analysis.reelchanger.DefaultWindows` (the rule of ``exudyn-worm simulate``); for another duty
    (:mod:`exudyn_worm.setups.duty`) on each of its lowering phases (False if it has none).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set with the reel-changer keys ``loadMass``, ``leverArm``, ``motorSpeed`` (or another duty's).
    stepSize : float, optional
        Time step in s. Default: the simulation's default, the drive's own
        :func:`~exudyn_worm.analysis.stepsize.RecommendedStepSize` (a recommended drive can have a higher natural
        frequency than the given one).

    Returns
    -------
    bool

    Raises
    ------
    ValueError
        For a parameter set without the reel-changer keys, or a ``stepSize`` the simulation refuses.
    """
    CheckReelChangerKeys(parameters, 'ChatterWhileLowering')
    lowering = [(t0, t1) for t0, t1, phase in DefaultPhases(parameters) if phase == 'lower']   # the load drives
    if not lowering:
        return False
    result = reelchanger.SimulateReelChanger(parameters, stepSize=stepSize)          # the default time the phases cover
    return any(result.Chatter(t0, t1) for t0, t1 in lowering)


def ConfirmBySimulation(result: DesignCheckResult, stepSize: Optional[float] = None,
                        progress=None) -> DesignCheckResult:
    """Simulate the given drive and every recommended drive; return the result with the simulated verdicts.

    Parameters
    ----------
    result : DesignCheckResult
        From :func:`DesignCheck`; its parameter set must hold ``loadMass``, ``leverArm``, ``motorSpeed``.
    stepSize : float, optional
        Time step in s (default: see :func:`ChatterWhileLowering`).
    progress : callable, optional
        Called with no argument after each simulation (e.g. a progress bar's ``update``).

    Returns
    -------
    DesignCheckResult
        A copy with ``simulatedChatter`` set on the result, each recommendation and the best pair.
    """
    if not isinstance(result, DesignCheckResult):
        raise TypeError(f"ConfirmBySimulation: 'result' must be a DesignCheckResult, got {type(result).__name__}")
    p = result.parameters

    def Verdict(changes):
        chatter = ChatterWhileLowering(ApplyOverrides(p, changes), stepSize)
        if progress is not None:
            progress()
        return chatter

    base = Verdict({})
    recommendations = [replace(r, simulatedChatter=Verdict(r.changes)) for r in result.recommendations]
    pair = replace(result.bestPair, simulatedChatter=Verdict(result.bestPair.changes)) if result.bestPair else None
    return replace(result, recommendations=recommendations, bestPair=pair, simulatedChatter=base)


# --- nearest stable values (the hint of ``exudyn-worm stability``): the margin-0 case of the same scan ---

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


def NearestStableValue(parameters: Mapping[str, float], key: str, direction: int,
                       span: float = DEFAULT_SPAN) -> Optional[float]:
    """Nearest value of ``key`` below (``direction = -1``) or above (+1) the given one at which the drive is
    stable (S = +1 and -1), other parameters as given; the given value if it is stable; None if there is
    none within ``span`` times (the margin-0 case of :meth:`AxisScan.Move`).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set.
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
    t = ScanParameter(parameters, key, math.log10(span)).Move(direction, 0., span)
    return None if t is None else parameters[key] * 10. ** t


def StabilizingChanges(parameters: Mapping[str, float], span: float = DEFAULT_SPAN) -> List[StableRange]:
    """For J1 and kT separately: the nearest values that make the drive stable.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set (see :func:`~exudyn_worm.setups.presets.DriveFromParameters`).
    span : float
        Search from 1/span to span times the given value, > 1.

    Returns
    -------
    list of StableRange
    """
    CheckRange('StabilizingChanges', 'span', span, low=1., lowOpen=True)
    drive = ElasticDriveFromParameters(parameters)
    scales = {'J1': 1. / drive.J2, 'kT': 1. / (drive.gear.kV * drive.gear.r1**2)}
    out = []
    for key, ratioName in _HINT_KEYS.items():
        scan = ScanParameter(parameters, key, math.log10(span))
        below, above = (scan.Move(d, 0., span) for d in (-1, 1))
        out.append(StableRange(key, parameters[key], None if below is None else parameters[key] * 10. ** below,
                               None if above is None else parameters[key] * 10. ** above, ratioName, scales[key],
                               PARAMETER_UNITS[key]))
    return out
