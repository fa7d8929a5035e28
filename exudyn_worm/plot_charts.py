"""Plots of the stability charts: Figures 3, 4 and 5 of the paper.

Imports matplotlib inside the functions (``import exudyn_worm.charts`` never pulls it in). Figures are
made as in :mod:`exudyn_worm.plot` (a plain :class:`~matplotlib.figure.Figure`, or through pyplot if the
caller already uses it); save them with :func:`exudyn_worm.plot.SaveFigure`.

The unstable region is shaded with matplotlib's ``contourf`` of the chart's margin field (its zero level
set is the boundary); the boundary lines themselves are the chart's own marching-squares curves
(:attr:`~exudyn_worm.charts.StabilityChart.boundaries`).
"""
from __future__ import annotations

import math
from typing import Mapping, Optional, Sequence

import numpy as np

__all__ = ['STIFFNESS_RATIO_LABEL', 'INERTIA_RATIO_LABEL', 'PlotStabilityChart', 'PlotStabilityCharts', 'PlotSpeedChart',
           'PlotFirstCriterion']

#: axis label of the abscissa of Figures 4 and 5
STIFFNESS_RATIO_LABEL = r'stiffness ratio $k_T\,/\,(k_V\,r_1^2)$'
#: axis label of the ordinate of Figures 3-5
INERTIA_RATIO_LABEL = r'inertia ratio $J_1\,/\,J_2$'

_COLORS = ('#c0392b', '#1e8449', '#1f4e79', '#b9770e', '#7d3c98', '#17a589')


def _Axes(ax, figsize=(7.5, 5.8)):
    if ax is not None:
        return ax
    from .plot import _NewFigure
    _, axes = _NewFigure(figsize=figsize)
    return axes[0, 0]


def _PointXY(value):
    """(x, y) of a point given as (x, y), as a dict with 'x' and 'y', or as an ElasticDrive."""
    from .charts import ChartCoordinates
    from .drive import ElasticDrive
    if isinstance(value, ElasticDrive):
        c = ChartCoordinates(value)
        return c['x'], c['y']
    if isinstance(value, Mapping):
        return float(value['x']), float(value['y'])
    x, y = value
    return float(x), float(y)


def _Points(where: str, points) -> Mapping:
    """``points`` as ``{label: point}``: a mapping as it is, or a sequence of preset names (``'reel-P1'``, or
    ``'P1'`` for ``'reel-P1'``) as their chart coordinates (:func:`~exudyn_worm.charts.PresetChartPoints`)."""
    if points is None or isinstance(points, Mapping):
        return points or {}
    from .presets import PRESETS
    if isinstance(points, str) or not isinstance(points, (list, tuple)) or \
            not all(isinstance(p, str) for p in points):
        raise TypeError(f"{where}: 'points' must be a mapping {{label: (x, y), a dict with 'x' and 'y', or an "
                        f"ElasticDrive}} or a list of preset names (e.g. ['reel-P1', 'reel-P7']), got "
                        f"{type(points).__name__} {points!r}")
    names = []
    for p in points:
        name = p if p in PRESETS else f'reel-{p}' if f'reel-{p}' in PRESETS else None
        if name is None:
            raise ValueError(f"{where}: 'points': unknown preset {p!r}; expected preset names: {', '.join(PRESETS)} "
                             f"(or P1 ... P7 for reel-P1 ... reel-P7)")
        names.append(name)
    from .charts import PresetChartPoints
    return PresetChartPoints(names)


def _DrawPoints(ax, points):
    if not points:
        return
    for label, value in points.items():
        x, y = _PointXY(value)
        ax.plot([x], [y], 'o', ms=4.5, mfc='white', mec='black', mew=1.1, zorder=5)
        ax.annotate(label, (x, y), xytext=(4, 3), textcoords='offset points', fontsize=8.5, zorder=6,
                    bbox=dict(boxstyle='round,pad=0.1', fc='white', ec='none', alpha=0.7))


def _DrawChart(ax, chart, color, shade, lineLabel):
    if shade and chart.unstable.any():
        lowest = float(np.min(chart.margin))
        ax.contourf(chart.x, chart.y, chart.margin, levels=[lowest - 1., 0.], colors=[color], alpha=0.13)
    for k, line in enumerate(chart.boundaries):
        ax.plot(line[:, 0], line[:, 1], color=color, lw=1.4, label=lineLabel if k == 0 else None)


def _Decorate(ax, chart):
    ax.set_xscale('log')
    ax.set_yscale('log')
    ax.set_xlim(chart.x[0], chart.x[-1])
    ax.set_ylim(chart.y[0], chart.y[-1])
    ax.set_xlabel(STIFFNESS_RATIO_LABEL)
    ax.set_ylabel(INERTIA_RATIO_LABEL)
    ax.grid(True, which='major', lw=0.4, alpha=0.5)


def PlotStabilityChart(chart, ax=None, points: Optional[Mapping] = None, color: Optional[str] = None,
                       label: Optional[str] = None, shade: bool = True, title: Optional[str] = None):
    """Draw one stability chart: shaded unstable region, boundary curves, log axes, marked points.

    Parameters
    ----------
    chart : StabilityChart
        From :func:`~exudyn_worm.charts.ComputeStabilityChart`.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into (default: a new figure).
    points : mapping or list of str, optional
        ``{label: point}`` with a point as (x, y), as a dict with 'x' and 'y' (e.g. from
        :func:`~exudyn_worm.charts.ChartCoordinates`) or as an ElasticDrive; or a list of preset names
        (``['reel-P1', 'P7']``; ``'P1'`` stands for ``'reel-P1'``), marked at their chart coordinates.
    color : str, optional
        Colour of region and boundary.
    label : str, optional
        Legend entry of the boundary (default ``D_TV = ...``).
    shade : bool, optional
        Shade the unstable region (default True).
    title : str, optional
        Axes title (default: D_V, S and which criterion).

    Returns
    -------
    matplotlib.axes.Axes

    Raises
    ------
    TypeError, ValueError
        For a ``chart`` that is not a StabilityChart, or ``points`` of another form or with an unknown preset name.
    """
    from .charts import StabilityChart
    if not isinstance(chart, StabilityChart):
        raise TypeError(f"PlotStabilityChart: 'chart' must be a StabilityChart, got {type(chart).__name__}")
    points = _Points('PlotStabilityChart', points)
    ax = _Axes(ax)
    _DrawChart(ax, chart, color or _COLORS[0], shade, label or fr'$D_{{TV}}$ = {chart.DTV:g}')
    _Decorate(ax, chart)
    _DrawPoints(ax, points)
    ax.set_title(title if title is not None else
                 fr'Stability chart, $S$ = {chart.S:+d}, $D_V$ = {chart.DV:g} (unstable region shaded)')
    if chart.boundaries:
        ax.legend(loc='upper left', fontsize=9)
    return ax


def PlotStabilityCharts(charts: Sequence, points: Optional[Mapping] = None, title: Optional[str] = None,
                        ax=None, note: Optional[str] = None):
    """Several charts of one D_V on one axes (the layout of Figures 4 and 5: one region per D_TV).

    Parameters
    ----------
    charts : sequence of StabilityChart
        Charts on the same grid (e.g. D_TV = 1, 5, 25).
    points : mapping or list of str, optional
        Points to mark, as for :func:`PlotStabilityChart` (a mapping or a list of preset names).
    title : str, optional
        Axes title.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into (default: a new figure).
    note : str, optional
        Small text in the lower right corner (e.g. which D_TV the points have).

    Returns
    -------
    matplotlib.axes.Axes
    """
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    charts = list(charts)
    if not charts:
        raise ValueError("PlotStabilityCharts: 'charts' must hold at least one StabilityChart, got none")
    points = _Points('PlotStabilityCharts', points)
    ax = _Axes(ax)
    handles = []
    for k, chart in enumerate(charts):
        color = _COLORS[k % len(_COLORS)]
        _DrawChart(ax, chart, color, True, None)
        text = fr'$D_{{TV}}$ = {chart.DTV:g}' + ('' if chart.unstable.any() else ' (no unstable point)')
        handles.append((Patch(fc=color, alpha=0.3, ec=color), Line2D([], [], color=color, lw=1.4), text))
    _Decorate(ax, charts[0])
    _DrawPoints(ax, points)
    from matplotlib.legend_handler import HandlerTuple
    ax.legend([(p, l) for p, l, _ in handles], [t for _, _, t in handles], loc='upper left', fontsize=9,
              handler_map={tuple: HandlerTuple(ndivide=1)}, title='unstable region', title_fontsize=9)
    c0 = charts[0]
    ax.set_title(title if title is not None else
                 fr'Stability chart, $S$ = {c0.S:+d}, $D_V$ = {c0.DV:g}, criteria (17) and (19)')
    if note:
        ax.text(0.99, 0.01, note, transform=ax.transAxes, ha='right', va='bottom', fontsize=8, color='0.3')
    return ax


def PlotFirstCriterion(curves, ax=None, title: Optional[str] = None, mark: Optional[Mapping] = None):
    """Figure 3: the J1/J2 limit of the first criterion (20) with dT = 0 against the pitch angle.

    One curve per friction angle; the stable region lies above a curve.

    Parameters
    ----------
    curves : FirstCriterionCurves
        From :func:`~exudyn_worm.charts.FirstCriterionChart`.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into (default: a new figure).
    title : str, optional
        Axes title.
    mark : mapping, optional
        ``{label: (gamma_rad, J1/J2)}`` points to mark (e.g. a gear's design point).

    Returns
    -------
    matplotlib.axes.Axes
    """
    from .charts import FirstCriterionCurves
    if not isinstance(curves, FirstCriterionCurves):
        raise TypeError(f"PlotFirstCriterion: 'curves' must be FirstCriterionCurves, got {type(curves).__name__}")
    ax = _Axes(ax, figsize=(7.5, 5.2))
    gdeg = np.degrees(curves.gamma)
    for k, (rho, row) in enumerate(zip(curves.rho, curves.limit)):
        color = _COLORS[k % len(_COLORS)]
        ok = np.isfinite(row) & (row > 0)
        ax.plot(gdeg[ok], row[ok], color=color, lw=1.5, label=fr'$\rho$ = {math.degrees(rho):g}°')
    if mark:
        for label, (g, y) in mark.items():
            ax.plot([math.degrees(g)], [y], 'o', ms=4.5, mfc='white', mec='black', mew=1.1, zorder=5)
            ax.annotate(label, (math.degrees(g), y), xytext=(5, 4), textcoords='offset points', fontsize=8.5)
    ax.set_yscale('log')
    ax.set_xlim(0., max(float(gdeg.max()), float(np.degrees(curves.rho).max())) * 1.04)
    ax.set_xlabel(r'pitch angle $\gamma$ [°]')
    ax.set_ylabel(INERTIA_RATIO_LABEL + ' (limit)')
    ax.grid(True, which='major', lw=0.4, alpha=0.5)
    ax.legend(loc='upper right', fontsize=9, title='friction angle', title_fontsize=9)
    ax.set_title(title if title is not None else
                 fr'First criterion (20) with $d_T$ = 0, $u$ = {curves.ratio:.4g}: stable above the lines')
    return ax


def PlotSpeedChart(chart, ax=None, title: Optional[str] = None, log: bool = True):
    """Largest real part of the lowering state against motor speed, unstable speeds shaded, mu(v0) on a twin axis.

    Parameters
    ----------
    chart : SpeedChart
        From :func:`exudyn_worm.speedchart.SpeedStabilityChart`.
    ax : matplotlib Axes, optional
        Draw into these axes; default a new figure.
    title : str, optional
        Axes title.
    log : bool
        Logarithmic speed axis (default).

    Returns
    -------
    matplotlib Axes
    """
    from .speedchart import RPM, SpeedChart
    if not isinstance(chart, SpeedChart):
        raise TypeError(f"PlotSpeedChart: 'chart' must be a SpeedChart (SpeedStabilityChart), got {type(chart).__name__}")
    ax = _Axes(ax, figsize=(7.5, 4.5))
    rpm = chart.motorSpeeds / RPM
    ax.axhline(0., color='0.4', lw=0.8)
    ax.plot(rpm, chart.maxRealPart, color=_COLORS[0], lw=1.8, marker='.', label='largest real part, lowering (S = -1)')
    for a, b in chart.unstableRanges:
        ax.axvspan(a / RPM, b / RPM, color=_COLORS[0], alpha=0.12, lw=0)
    for b in chart.Boundaries():
        ax.axvline(b / RPM, color=_COLORS[0], ls='--', lw=0.8)
    if log:
        ax.set_xscale('log')
    ax.set_xlabel('motor speed [rpm]')
    ax.set_ylabel(r'max Re$(\lambda)$ [1/s]  (> 0: chatter while lowering)')
    twin = ax.twinx()
    twin.plot(rpm, chart.mu, color=_COLORS[2], lw=1.2, ls=':', label=r'$\mu(v_0)$')
    twin.set_ylabel(r'friction coefficient $\mu(v_0)$', color=_COLORS[2])
    lines = ax.get_lines()[1:2] + twin.get_lines()
    ax.legend(lines, [l.get_label() for l in lines], loc='best', fontsize=9)
    ax.set_title(title or f'stability over motor speed, {chart.frictionLaw} friction law', loc='left', fontsize=10)
    return ax
