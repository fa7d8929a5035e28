"""The analytical chatter map of a two-parameter study: where the linear model predicts chatter while lowering.

Computes what :func:`~exudyn_worm.plotting.plot_study.PlotChatterMap` draws under the simulated runs of a
:class:`~exudyn_worm.analysis.studies.studyfiles.StudyResult`: the S = -1 stability chart over a J1-kT map at fixed damping measures
(:func:`~exudyn_worm.analysis.charts.stabilitychart.ComputeStabilityChart`), else the largest real part of the S = -1 eigenvalues on a
grid (:func:`AnalyticalMap`). No matplotlib here.
"""
from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import TYPE_CHECKING, List, Optional, Tuple

import numpy as np

from ..._spacing import IsLogSpaced
from ..charts.stabilitychart import ChartCoordinates, ComputeStabilityChart
from ..stability.drivestability import AnalyzeDrive, DriveAnalysis
from ...drive.wholedrive import Drive

if TYPE_CHECKING:
    from .studyfiles import StudyResult

__all__ = ['ChatterMap', 'ComputeChatterMap', 'AnalyticalMap', 'LoweringGrowth', 'WHOLE_DRIVE_RESOLUTION']

#: points per axis of the map of the linearized whole drive (a drive with a chain or an axial bearing) in
#: :func:`ComputeChatterMap`: one Exudyn linearization a point, so 400 points take about 12 s
WHOLE_DRIVE_RESOLUTION = 20


def LoweringGrowth(analysis: DriveAnalysis) -> float:
    """Largest real part in 1/s of the duty's lowering operating points (S = -1), what the map's simulated chatter
    while lowering is compared with; for a duty without a lowering point, the drive's deciding point.

    Parameters
    ----------
    analysis : DriveAnalysis
        From :func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive`.

    Returns
    -------
    float
    """
    if analysis.operatingPoints and not any(p.S == -1 for p in analysis.operatingPoints):
        return float(analysis.maxRealPart)
    return float(analysis.State(-1).maxRealPart)


def AnalyticalMap(drive: Drive, x: str, xValues, y: str, yValues) -> np.ndarray:
    """Largest real part (1/s) of the linear model at the duty's lowering operating points (S = -1,
    :func:`LoweringGrowth`) over a grid of two parameters, the others as in ``drive``: > 0 means chatter predicted
    while lowering. The model is that of :func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive` at each point
    (mu(v) and its slope at the operating point): eqs. (15)-(16) for the two-mass drive, the linearized whole
    drive (about 30 ms a point) for any other (chains, axial bearing, motor on its characteristic).

    Parameters
    ----------
    drive : Drive
        The drive whose two parameters are varied (each point a :meth:`~exudyn_worm.drive.wholedrive.Drive.Replace`).
    x, y : str
        Parameter keys.
    xValues, yValues : array_like
        Grid values (SI).

    Returns
    -------
    numpy.ndarray
        Shape (len(yValues), len(xValues)).
    """
    out = np.empty((len(yValues), len(xValues)))
    for (i, yv), (j, xv) in itertools.product(enumerate(yValues), enumerate(xValues)):
        out[i, j] = LoweringGrowth(AnalyzeDrive(drive.Replace(**{x: float(xv), y: float(yv)})))
    return out


def _Chart(whole: Drive, x, xValues, y, yValues, resolution):
    """The stability chart (:func:`~exudyn_worm.analysis.charts.stabilitychart.ComputeStabilityChart`) over a J1-kT map, in the map's
    coordinates: ``(xGrid, yGrid, unstable, [(xLine, yLine), ...])``; None unless the map's keys are J1 and kT,
    the damping is given as measures (D_T or D_TV, D_V), which is what a chart holds fixed, and the drive is the
    two-mass drive the chart describes (no component beyond Figure 2) with a constant mu (with mu(v) the verdict
    at the operating point is not the chart's, which is at constant mu)."""
    if {x, y} != {'J1', 'kT'} or 'dT' in whole.parameters or 'dV' in whole.parameters:
        return None
    if not whole.isTwoMass or whole.gear.speedDependentFriction:
        return None
    drive = whole.elastic
    c = ChartCoordinates(drive)
    g = drive.gear
    scale = {'kT': g.kV * g.r1**2, 'J1': drive.J2}             # x = kT/(kV r1^2), y = J1/J2
    kT, J1 = (xValues, yValues) if x == 'kT' else (yValues, xValues)
    chart = ComputeStabilityChart(g, drive.J2, c['DV'], c['DTV'], xRange=(kT[0] / scale['kT'], kT[-1] / scale['kT']),
                                  yRange=(J1[0] / scale['J1'], J1[-1] / scale['J1']), resolution=resolution, S=-1)
    kTGrid, J1Grid = np.asarray(chart.x) * scale['kT'], np.asarray(chart.y) * scale['J1']
    lines = [(line[:, 0] * scale['kT'], line[:, 1] * scale['J1']) for line in chart.boundaries]
    unstable = np.asarray(chart.unstable)                      # shape (len(y), len(x)) of the chart
    if x == 'kT':
        return kTGrid, J1Grid, unstable, lines
    return J1Grid, kTGrid, unstable.T, [(b, a) for a, b in lines]


@dataclass(frozen=True)
class ChatterMap:
    """The analytical S = -1 region over the plane of two varied keys of a study (SI values).

    Parameters
    ----------
    x, y : str
        Keys on the horizontal and vertical axis.
    xLimits, yLimits : (float, float)
        Axis limits: the runs' span with half a grid step beyond the outer runs.
    logX, logY : bool
        Log axes (log-spaced values, or positive values spanning more than 50x).
    xGrid, yGrid : numpy.ndarray
        Grid of ``unstable`` (and of ``growth``).
    unstable : numpy.ndarray
        Boolean, shape (len(yGrid), len(xGrid)): chatter predicted while lowering.
    growth : numpy.ndarray or None
        Largest real part of the S = -1 eigenvalues (1/s) on the grid (:func:`AnalyticalMap`); None where the
        stability chart gave the region.
    lines : list of (numpy.ndarray, numpy.ndarray)
        Boundary lines of the stability chart (empty for ``growth``: its zero contour is the boundary).
    source : str
        What computed it: 'stability chart', 'linear model' or 'linearized whole drive'.
    """
    x: str
    y: str
    xLimits: Tuple[float, float]
    yLimits: Tuple[float, float]
    logX: bool
    logY: bool
    xGrid: np.ndarray
    yGrid: np.ndarray
    unstable: np.ndarray
    growth: Optional[np.ndarray]
    lines: List[Tuple[np.ndarray, np.ndarray]]
    source: str


def ComputeChatterMap(result: 'StudyResult', x: str, y: str, resolution: int = 60) -> ChatterMap:
    """The analytical chatter map of a study over its varied keys ``x`` and ``y``.

    For a map of J1 and kT at fixed damping measures the stability chart of
    :func:`~exudyn_worm.analysis.charts.stabilitychart.ComputeStabilityChart` (at least 300 points per axis), else :func:`AnalyticalMap`
    on a grid of ``resolution`` points per axis (at most :data:`WHOLE_DRIVE_RESOLUTION` for the linearized whole
    drive). The grid reaches half a grid step (at most 15 % of the span) beyond the outer runs.

    Parameters
    ----------
    result : StudyResult
        Result of :func:`~exudyn_worm.analysis.studies.study.RunStudy`.
    x, y : str
        Varied keys on the horizontal and vertical axis.
    resolution : int, optional
        Points per axis of the analytical grid.

    Returns
    -------
    ChatterMap

    Raises
    ------
    ValueError
        For ``x`` or ``y`` not a varied key of the study.
    """
    keys = result.study.keys
    for name, key in (('x', x), ('y', y)):
        if key not in keys:
            raise ValueError(f"ComputeChatterMap: '{name}' must be a varied key ({', '.join(keys)}), got {key!r}")
    xs, ys = result.Values(x), result.Values(y)
    # log axes for log-spaced values or positive values spanning more than 50x (the grid and the axis alike)
    logX, logY = (IsLogSpaced(v) or bool(np.nanmin(v) > 0 and np.nanmax(v) / np.nanmin(v) > 50) for v in (xs, ys))

    def grid(v, log, count=resolution):
        lo, hi = np.nanmin(v), np.nanmax(v)
        n = len(np.unique(np.asarray(v)[np.isfinite(v)]))
        if lo == hi:                                    # one value only: show a factor 2 around it
            lo, hi = (lo / 2, hi * 2) if lo > 0 else (lo - 1, hi + 1)
        if n > 1:              # half a grid step (at most 15 % of the span) beyond the outer runs: no clipped markers
            share = min(0.5 / (n - 1), 0.15)
            if log:
                pad = (hi / lo) ** share
                lo, hi = lo / pad, hi * pad
            else:
                pad = (hi - lo) * share
                lo, hi = (lo - pad if lo <= 0 or lo > pad else lo / 2), hi + pad   # a positive key stays positive
        return np.geomspace(lo, hi, count) if log else np.linspace(lo, hi, count)

    gx, gy = grid(xs, logX), grid(ys, logY)
    limits = dict(xLimits=(float(gx[0]), float(gx[-1])), yLimits=(float(gy[0]), float(gy[-1])), logX=logX, logY=logY)
    base = Drive.FromParameters(result.study.base)     # the study's base set (as its files keep it), one drive
    chart = _Chart(base, x, gx, y, gy, max(resolution, 300))
    if chart is not None:                   # J1 and kT at fixed damping measures: the stability chart itself
        cx, cy, unstable, lines = chart
        return ChatterMap(x=x, y=y, xGrid=cx, yGrid=cy, unstable=unstable, growth=None, lines=lines,
                          source='stability chart', **limits)
    wholeDrive = not base.isTwoMass
    if wholeDrive:                          # one Exudyn linearization a point (about 30 ms): a coarser grid
        count = min(resolution, WHOLE_DRIVE_RESOLUTION)
        gx, gy = grid(xs, logX, count), grid(ys, logY, count)
    growth = AnalyticalMap(base, x, gx, y, gy)
    return ChatterMap(x=x, y=y, xGrid=gx, yGrid=gy, unstable=growth > 0, growth=growth, lines=[],
                      source='linearized whole drive' if wholeDrive else 'linear model', **limits)
