"""The two-mass drive on its stability charts: the local charts around its chart point and its distance to the
stability boundary, in decades (Euclidean in the chart plane log10 x, log10 y at the drive's D_V and D_TV), on the
charts at the operating point that decides in each contact state (mu(v0) and its slope). The chart does not
describe a whole drive (chains, axial bearing, motor on its characteristic): it then has no chart distance.
"""
from __future__ import annotations

import math
from typing import Dict, Optional, Tuple

import numpy as np

from ..._checks import CheckRange
from ...model.stability import CONTACT_STATES
from ...drive.wholedrive import CheckDrive, Drive
from ..charts.stabilitychart import ChartCoordinates, ComputeStabilityChart
from ..stability.drivestability import AnalyzeDrive, DriveAnalysis

__all__ = ['LocalCharts', 'ChartGrid']

_CHART_DECADES = 2.         # the chart-plane distance is searched within +-2 decades of the drive's point


_CHART_STEP = 0.01


def _DecidingPerState(analysis: DriveAnalysis) -> Dict[int, object]:
    """Per contact state of the duty: the operating point with the largest real part (None: at rest, both)."""
    if not analysis.operatingPoints:
        return {S: None for S in CONTACT_STATES}
    out = {}
    for p in sorted(analysis.operatingPoints, key=lambda p: p.maxRealPart):
        out[p.S] = p.point.operatingPoint
    return dict(sorted(out.items()))


def LocalCharts(drive: Drive, decades: float = _CHART_DECADES,
                step: float = _CHART_STEP):
    """The two-mass drive's stability charts (:func:`~exudyn_worm.analysis.charts.stabilitychart.ComputeStabilityChart`) on a log
    grid of +-``decades`` around its chart point, at its D_V and D_TV, one per contact state of its duty, each at the
    operating point that decides in that state (mu(v0) and its slope; without a steady phase: both contact states
    at rest, constant mu).

    Parameters
    ----------
    drive : Drive
        The two-mass drive.
    decades : float, optional
        Half-width of the grid in decades of x and y, > 0.
    step : float, optional
        Grid step in decades, in (0, decades].

    Returns
    -------
    dict
        ``{S: StabilityChart}`` (S = -1 and/or +1), on the same grid with the drive's point at its centre.

    Raises
    ------
    ValueError
        For a drive beyond two masses (the chart of eqs. (15)-(19) does not describe it).
    """
    CheckRange('LocalCharts', 'decades', decades, low=0., lowOpen=True)
    CheckRange('LocalCharts', 'step', step, low=0., high=decades, lowOpen=True)
    CheckDrive('LocalCharts', drive)
    if not drive.isTwoMass:
        raise ValueError(f"LocalCharts: the stability chart (eqs. (15)-(19)) describes the two-mass drive of Figure 2; "
                         f"this drive has {drive.ComponentsText()}")
    core = drive.elastic
    p = ChartCoordinates(core)
    n = 2 * int(math.ceil(decades / step)) + 1
    span = 10. ** decades
    return {S: ComputeStabilityChart(core.gear, core.J2, p['DV'], p['DTV'], xRange=(p['x'] / span, p['x'] * span),
                                     yRange=(p['y'] / span, p['y'] * span), resolution=n, S=S, operatingPoint=op)
            for S, op in _DecidingPerState(AnalyzeDrive(drive)).items()}


def ChartGrid(drive: Drive, decades: float = _CHART_DECADES, step: float = _CHART_STEP):
    """Stability (every chart of :func:`LocalCharts`) on the grid around the drive's chart point.

    Parameters
    ----------
    drive : Drive
        The two-mass drive.
    decades : float, optional
        Half-width of the grid in decades of x and y, > 0.
    step : float, optional
        Grid step in decades, in (0, decades].

    Returns
    -------
    x, y, stable : numpy.ndarray
        1-D grids of x = kT/(kV r1^2) and y = J1/J2 and the boolean stability of shape ``(len(y), len(x))``.
    """
    charts = list(LocalCharts(drive, decades, step).values())
    return charts[0].x, charts[0].y, ~np.logical_or.reduce([c.unstable for c in charts])


def _ChartDistance(drive: Drive) -> Tuple[Optional[float], Optional[Dict[str, float]]]:
    """Distance in decades from the drive's point to the nearest point of opposite verdict in the chart plane
    (grid of :func:`LocalCharts`, then refined along the ray to that point with the charts' exact verdict)."""
    charts = list(LocalCharts(drive).values())
    x, y = charts[0].x, charts[0].y
    stable = ~np.logical_or.reduce([c.unstable for c in charts])
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
    ray = ~np.logical_or.reduce([chart.IsUnstable(rx, ry) for chart in charts])
    first = int(np.argmax(ray != ray[0]))
    distance = float(r[first]) if first > 0 else length
    return distance, {'x': float(x[c] * 10. ** (distance * direction[0])),
                      'y': float(y[c] * 10. ** (distance * direction[1]))}
