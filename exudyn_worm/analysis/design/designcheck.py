"""Design check: is a drive stable, how far is it from the stability boundary, and which change makes it stable.

**Verdict.** The drive's verdict is the one of every command, :func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive`:
each operating point of the drive's own duty (every steady phase in each direction of power flow, with its
sliding speed, mu(v0), dmu/dv and static normal force) in its own contact state; the worst decides. The
two-mass drive of Figure 2 is analysed with eqs. (15)-(19), any other drive (drive-side or load-side chain,
worm axial bearing, motor on its characteristic) with the linearized Exudyn model of the whole drive. A drive
without a steady phase is checked at rest in both contact states (constant mu).

**Design parameters** (:func:`~exudyn_worm.analysis.design.designscan.DesignParameters`): J1, J2, kT, the shaft damping
and the mesh damping, each in the form the parameter set holds it: the shaft damping as ``dT`` (constant), ``DT``
(measure, eq. (22)) or ``DTV`` (ratio, eq. (24)); the mesh damping as ``dV`` or ``DV`` (eq. (23)); then the
drive-side chain (J4, k4, d4, ...), the load-side chain (JL1, kL1, dL1, ...) and the axial bearing (kA, dA) where
the drive has them; and the motor speed where the friction depends on speed and the motor runs at ``motorSpeed``.
The paper's Figure 4 shows that a chattering drive (P1) can be made stable by increasing or by decreasing J1 or
kT (section 3.2.4 reads P2-P5 off the chart), so every design parameter is searched in both directions.
**What is held** when one of them changes is what the parameter set holds: the presets hold the measures D_T,
D_V (as the paper's chart points assume), so a larger J1 or kT brings a larger dT = 2 D_T sqrt(kT J1); a set that
gives ``dT``/``dV`` keeps those constants. With ``DTV`` a change of D_V changes D_T in proportion (the paper's move
of P6 from Figure 4 to Figure 5).

**Margin rule** (:mod:`exudyn_worm.analysis.design.designrules`): a drive is *stable with margin* along a parameter if
it stays stable when that parameter alone is multiplied by any factor within 10^-delta..10^+delta; a
recommendation is the smallest change of one parameter after which it is (a pair where no single parameter
suffices). For the two-mass drive the distance to the stability boundary is measured in the same unit, decades,
in the chart plane (:mod:`exudyn_worm.analysis.design.designchart`). The recommendations are confirmed in the time domain
by :mod:`exudyn_worm.analysis.design.designconfirm`.

How the scans are computed and what they cost: :mod:`exudyn_worm.analysis.design.designscan`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from itertools import combinations
from typing import Callable, Dict, List, Optional, Tuple, Union

import numpy as np

from ..._checks import CheckRange, JsonNumber
from ...model.stability import CONTACT_STATES
from ...drive.wholedrive import CheckDrive, Drive
from ..charts.stabilitychart import ChartCoordinates
from .designchart import LocalCharts, _ChartDistance
from .designrules import DEFAULT_MARGIN, DEFAULT_SPAN, MarginRule, PairRecommendation, Recommendation
from .designscan import (SPEED_KEY, WHOLE_DRIVE_TOLERANCE, AxisScan, DesignKeys, Scanner,
                         _ScaledDrives, _SymmetricGrid)
from ..stability.drivestability import AnalyzeDrive, DriveAnalysis

__all__ = ['DesignCheckResult', 'DesignCheck']

_PAIR_STEP = 0.01           # grid step of the pair search in decades


@dataclass(frozen=True)
class DesignCheckResult:
    """Result of :func:`DesignCheck`.

    Attributes
    ----------
    drive : Drive
        The drive checked.
    margin : float
        Margin in decades (see the module docstring for the rule).
    span : float
        Largest factor searched.
    analysis : DriveAnalysis
        The drive's verdict at the operating points of its duty
        (:func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive`, the one of ``exudyn-worm stability``).
    chartPoint : dict
        :func:`~exudyn_worm.analysis.charts.stabilitychart.ChartCoordinates` of the drive's two-mass core.
    distanceToBoundary : float or None
        Decades from the chart point to the stability boundary (Euclidean in log10 x, log10 y at the
        drive's D_V and D_TV); None if there is none within 2 decades, or for a drive the chart does not describe.
    nearestBoundaryPoint : dict or None
        ``{'x', 'y'}`` of that boundary point.
    scans : dict
        :class:`~exudyn_worm.analysis.design.designscan.AxisScan` of each design parameter.
    marginShortBy : list of str
        Design parameters along which the drive is not stable with margin (empty: stable with margin).
    recommendations : list of Recommendation
        Smallest increases and decreases, one parameter each.
    bestPair : PairRecommendation or None
        Where no single parameter suffices: the smallest change of two (two-mass drive only).
    notes : list of str
        Parameters that could not be varied (value 0) and similar remarks.
    simulatedChatter : bool, str or None
        Chatter while lowering of the given drive in the simulation (True, False or 'undecided'; None if not
        simulated).
    evaluations : int
        Linear analyses of changed drives (``AnalyzeDrive``) the check made: a whole drive's scan points and
        confirmations and every recommended drive (the two-mass drive's Hurwitz scans are not counted).
    """
    drive: Drive
    margin: float
    span: float
    analysis: DriveAnalysis
    chartPoint: Dict[str, float]
    distanceToBoundary: Optional[float]
    nearestBoundaryPoint: Optional[Dict[str, float]]
    scans: Dict[str, AxisScan]
    marginShortBy: List[str]
    recommendations: List[Recommendation]
    bestPair: Optional[PairRecommendation] = None
    notes: List[str] = field(default_factory=list)
    simulatedChatter: Optional[Union[bool, str]] = None
    evaluations: int = 0

    @property
    def parameters(self) -> Dict[str, float]:
        """The drive's flat parameter set (a copy)."""
        return dict(self.drive.parameters)

    @property
    def chartApplies(self) -> bool:
        """True if the stability chart (eqs. (15)-(19)) describes the drive (the two-mass drive)."""
        return self.drive.isTwoMass

    @property
    def stable(self) -> bool:
        """The drive's verdict: every operating point of its duty stable (``AnalyzeDrive(drive).stable``)."""
        return bool(self.analysis.stable)

    @property
    def stableWithMargin(self) -> bool:
        """Stable with the margin along every design parameter."""
        return self.stable and not self.marginShortBy

    @property
    def maxRealPart(self) -> float:
        """Largest real part in 1/s of the deciding operating point."""
        return float(self.analysis.maxRealPart)

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
        """Static and dynamic self-locking (:func:`~exudyn_worm.model.selflocking.SelfLocking`) at the deciding
        operating point (at rest for a drive without a steady phase); every point: :attr:`selfLockingVerdicts`."""
        verdicts = self.analysis.selfLockingVerdicts
        deciding = self.analysis.deciding
        return verdicts[deciding.point.Label()] if deciding is not None else next(iter(verdicts.values()))

    @property
    def selfLockingVerdicts(self) -> Dict[str, object]:
        """Static and dynamic self-locking at every operating point, keyed by its label."""
        return self.analysis.selfLockingVerdicts

    @property
    def dangerous(self) -> bool:
        """Self-locking at rest but not while moving at one of the operating points."""
        return bool(self.analysis.dangerous)

    def ContactStates(self) -> Dict[int, object]:
        """Per contact state of the duty (both at rest without a steady phase): its result (``stable``,
        ``maxRealPart``; the operating point in that state with the largest real part).

        Returns
        -------
        dict
        """
        present = {p.S for p in self.analysis.operatingPoints} or set(CONTACT_STATES)
        return {S: self.analysis.State(S) for S in CONTACT_STATES if S in present}

    def ToDict(self) -> Dict:
        """JSON-ready dictionary (the schema of ``exudyn-worm check --json``): the keys of
        :meth:`~exudyn_worm.analysis.stability.drivestability.DriveAnalysis.ToDict` (``stable``, ``operatingPoints``,
        ``deciding``, ``dangerous``, ...) and those of the design check.

        Returns
        -------
        dict
        """
        contact = {f'{S:+d}': {'stable': bool(state.stable), 'maxRealPart': float(state.maxRealPart)}
                   for S, state in self.ContactStates().items()}
        point = {k: JsonNumber(v) for k, v in self.chartPoint.items()}
        point.update(distanceToBoundary=self.distanceToBoundary, nearestBoundaryPoint=self.nearestBoundaryPoint,
                     applies=self.chartApplies)
        data = {**self.analysis.ToDict(),
                'stable': self.stable, 'stableWithMargin': self.stableWithMargin, 'maxRealPart': self.maxRealPart,
                'S': contact, 'chartPoint': point,
                'margin': {'decades': self.margin, 'factor': 10. ** self.margin, 'rule': MarginRule(self.margin, self.span)},
                'span': self.span, 'designParameters': list(self.scans), 'marginShortBy': list(self.marginShortBy),
                'recommendations': [r.ToDict() for r in self.recommendations],
                'noRecommendation': [{'parameter': k, 'direction': 'increase' if d > 0 else 'decrease'}
                                     for k, d in self.Missing()],
                'singleParameterSuffices': self.singleParameterSuffices,
                'bestPair': self.bestPair.ToDict() if self.bestPair else None,
                'notes': list(self.notes), 'evaluations': self.evaluations,
                'scans': {k: {'stableIntervals': [list(ab) for ab in s.stableIntervals], 'limit': s.limit}
                          for k, s in self.scans.items()}}
        data['selfLockingVerdict'] = self.selfLockingVerdict.ToDict()
        if self.simulatedChatter is not None:
            data['simulatedChatterWhileLowering'] = self.simulatedChatter
        return data

    def plot(self, ax=None, title: str = ''):
        """Draw the check: for the two-mass drive its point on the charts that decide (at the deciding operating
        points), the boundary and the recommended moves; for a whole drive, which the chart does not describe,
        the stable ranges of each scanned parameter and the moves, and the figure says why there is no chart.

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
        from ...plotting.plot_design import PlotDesignCheck   # lazy: matplotlib only when drawing
        return PlotDesignCheck(self, LocalCharts(self.drive) if self.chartApplies else None, ax=ax, title=title)


def _BestPair(scanner: Scanner, keys, margin, span) -> Optional[PairRecommendation]:
    """The smallest (Euclidean, in decades) change of two parameters that is stable with margin on the
    whole square of both factors within 10^+-margin; checked with the scalar model on a 5 x 5 grid."""
    L = math.log10(span)
    t = _SymmetricGrid(L + margin, _PAIR_STEP)
    half = int(round(margin / (t[1] - t[0])))
    scaled = _ScaledDrives(scanner.drive, keys, scanner.conditions)
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
    p = scanner.parameters
    for _, a, b, ta, tb in sorted(candidates):
        if all(scanner.StableAt({a: ta + da, b: tb + db}) for da in offsets for db in offsets):
            maxRe, point = scanner.After({a: ta, b: tb})
            return PairRecommendation((a, b), (10. ** ta, 10. ** tb), (p[a] * 10. ** ta, p[b] * 10. ** tb), maxRe, point)
    return None


def DesignCheck(drive: Drive, margin: float = DEFAULT_MARGIN,
                span: float = DEFAULT_SPAN, progress: Optional[Callable[[], None]] = None) -> DesignCheckResult:
    """Check a drive for chatter and recommend the smallest changes that make it stable with a margin.

    The verdict is :func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive` (the drive's own operating points);
    the design parameters and what is held when one changes are described in the module docstring of
    :mod:`exudyn_worm.analysis.design.designcheck`, the margin rule in :mod:`exudyn_worm.analysis.design.designrules`, the scans in
    :mod:`exudyn_worm.analysis.design.designscan`.

    Parameters
    ----------
    drive : Drive
        The drive (:func:`~exudyn_worm.drive.wholedrive.ResolveDrive`, e.g. ``ResolveDrive('reel-P1')``); any
        drive: chains on both sides, axial bearing, motor on its characteristic.
    margin : float, optional
        Margin in decades of a parameter factor, in [0, 1] (default 0.1: factor 1.26).
    span : float, optional
        Largest factor searched in each direction, in (1, 1e4] (default 100).
    progress : callable, optional
        Called with no argument after each scanned parameter (:func:`~exudyn_worm.analysis.design.designscan.DesignKeys`
        lists them), e.g. a progress bar's ``update``.

    Returns
    -------
    DesignCheckResult
        The verdict at every operating point, the largest real part, for the two-mass drive the chart point and
        its distance to the boundary, the recommendations and, where no single parameter suffices, the best pair.

    Raises
    ------
    ValueError, TypeError
        For a bad drive, margin or span.
    """
    w = 'DesignCheck'
    margin = CheckRange(w, 'margin', margin, low=0., high=1., unit='decades')
    span = CheckRange(w, 'span', span, low=1., high=1e4, lowOpen=True)
    CheckDrive(w, drive)
    analysis = AnalyzeDrive(drive)
    analysis.stable
    scanner = Scanner(drive)
    keys, notes = DesignKeys(drive)
    if not drive.isTwoMass:
        notes.append(f"the drive has {drive.ComponentsText()}: every scanned drive is the linearized Exudyn model of "
                     f"the whole drive at its operating points (grid {scanner.step:g} decades, boundaries to "
                     f"{WHOLE_DRIVE_TOLERANCE:g} decades); the stability chart of the two-mass drive does not describe it")
    if drive.gear.speedDependentFriction and SPEED_KEY not in keys and analysis.operatingPoints:
        notes.append(f"the motor speed is not scanned: motorType {drive.motorType} takes no '{SPEED_KEY}'")
    limit = math.log10(span) + margin
    scans = {}
    for key in keys:
        scans[key] = scanner.Scan(key, limit)
        if progress is not None:
            progress()
    short = [k for k in keys if not (analysis.stable and scans[k].Move(+1, margin, span) == 0.)]
    recommendations = []
    for key in short:
        for direction in (+1, -1):
            t = scans[key].Move(direction, margin, span)
            if t is None or t == 0.:
                continue
            if not scanner.Confirmed(key, t, margin):
                notes.append(f"{key} {'x' if t > 0 else '/'}{10 ** abs(t):.3g} is stable at the scan's grid points but "
                             f"not everywhere within its margin: not recommended")
                continue
            maxRe, point = scanner.After({key: t})
            recommendations.append(Recommendation(key, 10. ** t, drive.parameters[key] * 10. ** t, maxRe, point))
    bestPair = None
    pairKeys = [k for k in keys if k != SPEED_KEY]          # the pair search scales J1, J2, kT, dT, dV only
    if short and not recommendations and len(pairKeys) >= 2:
        if drive.isTwoMass:
            bestPair = _BestPair(scanner, pairKeys, margin, span)
        else:
            notes.append("no pair of parameters is searched for a whole drive (each candidate is a linearized Exudyn "
                         "model); try 'exudyn-worm sweep' over two parameters")
    distance, boundaryPoint = _ChartDistance(drive) if drive.isTwoMass else (None, None)
    return DesignCheckResult(drive, margin, span, analysis, ChartCoordinates(drive.elastic), distance, boundaryPoint,
                             scans, short, recommendations, bestPair, notes, evaluations=scanner.evaluations)
