"""Plots of the stability charts: Figures 3, 4 and 5 of the paper.

Imports matplotlib inside the functions (``import exudyn_worm.analysis.charts.stabilitychart`` never pulls it in). Figures are
made as in :mod:`exudyn_worm.plotting.plot` (a plain :class:`~matplotlib.figure.Figure`, or through pyplot if the
caller already uses it); save them with :func:`exudyn_worm.plotting.plot.SaveFigure`.

The unstable region is shaded with matplotlib's ``contourf`` of the chart's margin field (its zero level
set is the boundary); the boundary lines themselves are the chart's own marching-squares curves
(:attr:`~exudyn_worm.analysis.charts.stabilitychart.StabilityChart.boundaries`).
"""
from __future__ import annotations

import math
from typing import Mapping, Optional, Sequence, Tuple, Union

import numpy as np
from ..analysis.charts.stabilitychart import FirstCriterionCurves, StabilityChart
from .plot import _NewFigure
from ..analysis.charts.speedchart import RPM, SpeedChart

__all__ = ['STIFFNESS_RATIO_LABEL', 'INERTIA_RATIO_LABEL', 'POINT_SIZE', 'HATCHES', 'ZOOM_DECADES',
           'PlotStabilityChart', 'PlotStabilityCharts', 'PlotSpeedChart', 'PlotFirstCriterion', 'NearestBoundary',
           'PointsToZoom']

#: axis label of the abscissa of Figures 4 and 5
STIFFNESS_RATIO_LABEL = r'stiffness ratio $k_T\,/\,(k_V\,r_1^2)$'
#: axis label of the ordinate of Figures 3-5
INERTIA_RATIO_LABEL = r'inertia ratio $J_1\,/\,J_2$'

_COLORS = ('#c0392b', '#1e8449', '#1f4e79', '#b9770e', '#7d3c98', '#17a589')


def _Axes(ax, figsize=(7.5, 5.8)):
    if ax is not None:
        return ax
    _, axes = _NewFigure(figsize=figsize)
    return axes[0, 0]


def _PointXY(value):
    """(x, y) of a point given as (x, y) or as a dict with 'x' and 'y'."""
    if isinstance(value, Mapping):
        return float(value['x']), float(value['y'])
    x, y = value
    return float(x), float(y)


def _Points(where: str, points) -> Mapping:
    """``points`` as ``{label: (x, y)}``; only draws, so preset names and drives must be resolved before
    (:func:`~exudyn_worm.analysis.charts.stabilitychart.ChartPoints`, which :meth:`StabilityChart.plot
    <exudyn_worm.analysis.charts.stabilitychart.StabilityChart.plot>` calls)."""
    if points is None:
        return {}
    form = ("a mapping {label: (x, y) or a dict with 'x' and 'y'}; preset names and ElasticDrives are resolved by "
            "exudyn_worm.analysis.charts.stabilitychart.ChartPoints (StabilityChart.plot does it)")
    if not isinstance(points, Mapping):
        raise TypeError(f"{where}: 'points' must be {form}, got {type(points).__name__} {points!r}")
    out = {}
    for label, value in points.items():
        try:
            out[label] = _PointXY(value)
        except (TypeError, ValueError, KeyError):
            raise TypeError(f"{where}: 'points' must be {form}, got {type(value).__name__} for {label!r}") from None
    return out


#: marker size of the points on a chart (small: a point near a boundary stays clear of the line)
POINT_SIZE = 3.5


def _DrawPoints(ax, points, labels: bool = True):
    if not points:
        return
    for label, value in points.items():
        x, y = _PointXY(value)
        ax.plot([x], [y], 'o', ms=POINT_SIZE, mfc='white', mec='black', mew=1., zorder=5, gid=f'point {label}')
        if labels:
            ax.annotate(label, (x, y), xytext=(4, 3), textcoords='offset points', fontsize=8.5, zorder=6,
                        bbox=dict(boxstyle='round,pad=0.1', fc='white', ec='none', alpha=0.7))


#: hatches of the unstable regions in :func:`PlotStabilityCharts` (one chart each; crossing where they overlap)
HATCHES = ('///', '\\\\\\', '||', '--', '++', 'xx')


def _DrawChart(ax, chart, color, shade, lineLabel, hatch: Optional[str] = None):
    """Unstable region (a light opaque fill, or with ``hatch`` a hatch in ``color`` on no fill, so regions of
    several charts overlap without mixing into an unexplained colour) and the boundary lines."""
    if shade and chart.unstable.any():
        lowest = float(np.min(chart.margin))
        if hatch is None:
            region = ax.contourf(chart.x, chart.y, chart.margin, levels=[lowest - 1., 0.],
                                 colors=[_Light(color)])
        else:
            region = ax.contourf(chart.x, chart.y, chart.margin, levels=[lowest - 1., 0.], colors='none',
                                 hatches=[hatch])
            if hasattr(region, 'set_hatchcolor'):
                region.set_hatchcolor(color)
            else:                                     # matplotlib < 3.10: the hatch takes the edge colour
                region.set_edgecolor(color)
            region.set_linewidth(0.)
            if hasattr(region, 'set_hatch_linewidth'):  # matplotlib >= 3.10: thin hatches, the lines stay bolder
                region.set_hatch_linewidth(0.6)
        region.set_gid(f'region DTV={chart.DTV:g}')
    for k, line in enumerate(chart.boundaries):
        ax.plot(line[:, 0], line[:, 1], color=color, lw=1.4, label=lineLabel if k == 0 else None,
                gid=f'boundary DTV={chart.DTV:g}')


def _Light(color: str, share: float = 0.15):
    """``color`` mixed with white (an opaque light tint: ``share`` of the colour)."""
    from matplotlib.colors import to_rgb
    return tuple(1. - share * (1. - c) for c in to_rgb(color))


def NearestBoundary(chart: 'StabilityChartData', point: Tuple[float, float]) -> float:
    """Distance in decades (Euclidean in log10 x, log10 y) from a point to the nearest boundary vertex of a
    chart; inf for a chart without boundary.

    Parameters
    ----------
    chart : StabilityChart
        The chart.
    point : (float, float) or mapping
        The point, as (x, y) or a dict with 'x' and 'y' (:meth:`StabilityChart.NearestBoundary
        <exudyn_worm.analysis.charts.stabilitychart.StabilityChart.NearestBoundary>` computes it).

    Returns
    -------
    float
    """
    return chart.NearestBoundary(_PointXY(point))


def _Decorate(ax, chart):
    ax.set_xscale('log')
    ax.set_yscale('log')
    ax.set_xlim(chart.x[0], chart.x[-1])
    ax.set_ylim(chart.y[0], chart.y[-1])
    ax.set_xlabel(STIFFNESS_RATIO_LABEL)
    ax.set_ylabel(INERTIA_RATIO_LABEL)
    ax.grid(True, which='major', lw=0.4, alpha=0.5)


def _RegionHandle(color: str, hatch: Optional[str]):
    """Legend handle of a region and its boundary: the region's fill or hatch with the boundary line over it."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    patch = (Patch(fc=_Light(color), ec='none') if hatch is None else
             Patch(fc='none', ec=color, hatch=hatch, lw=0.))
    return patch, Line2D([], [], color=color, lw=1.4)


def _Legend(ax, entries, **kwargs):
    """A legend of ``[(handle or (patch, line), text), ...]`` (tuples drawn on top of each other)."""
    from matplotlib.legend_handler import HandlerTuple
    return ax.legend([h for h, _ in entries], [t for _, t in entries],
                     handler_map={tuple: HandlerTuple(ndivide=1)}, **kwargs)


def PlotStabilityChart(chart, ax=None, points: Optional[Mapping] = None, color: Optional[str] = None,
                       label: Optional[str] = None, shade: bool = True, title: Optional[str] = None,
                       hatch: Optional[str] = None):
    """Draw one stability chart: shaded unstable region, boundary curves, log axes, marked points.

    The legend names the region and its boundary together (the shading is part of the entry).

    Parameters
    ----------
    chart : StabilityChart
        From :func:`~exudyn_worm.analysis.charts.stabilitychart.ComputeStabilityChart`.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into (default: a new figure).
    points : mapping, optional
        ``{label: point}`` with a point as (x, y) or as a dict with 'x' and 'y' (e.g. from
        :func:`~exudyn_worm.analysis.charts.stabilitychart.ChartCoordinates`). Preset names and ElasticDrives are resolved before
        drawing by :func:`~exudyn_worm.analysis.charts.stabilitychart.ChartPoints` (as :meth:`StabilityChart.plot
        <exudyn_worm.analysis.charts.stabilitychart.StabilityChart.plot>` does).
    color : str, optional
        Colour of region and boundary.
    label : str, optional
        Legend entry of the region and its boundary (default ``D_TV = ...: unstable region, boundary``).
    shade : bool, optional
        Shade the unstable region (default True).
    title : str, optional
        Axes title (default: D_V, S and which criterion).
    hatch : str, optional
        Hatch the region in ``color`` instead of an opaque light fill (to draw a second chart over a first).

    Returns
    -------
    matplotlib.axes.Axes

    Raises
    ------
    TypeError, ValueError
        For a ``chart`` that is not a StabilityChart, or ``points`` of another form.
    """
    if not isinstance(chart, StabilityChart):
        raise TypeError(f"PlotStabilityChart: 'chart' must be a StabilityChart, got {type(chart).__name__}")
    points = _Points('PlotStabilityChart', points)
    ax = _Axes(ax)
    color = color or _COLORS[0]
    text = label or (fr'$D_{{TV}}$ = {chart.DTV:g}: unstable region' + (', boundary' if chart.boundaries else ''))
    _DrawChart(ax, chart, color, shade, None, hatch)
    handle = _RegionHandle(color, hatch) if shade and chart.unstable.any() else _RegionHandle(color, hatch)[1]
    # the chart's entries, kept on the axes so that a second chart drawn into it adds its own
    entries = getattr(ax, '_chartEntries', [])
    if chart.boundaries or chart.unstable.any():
        entries.append((handle, text))
    ax._chartEntries = entries
    _Decorate(ax, chart)
    _DrawPoints(ax, points)
    ax.set_title(title if title is not None else
                 fr'Stability chart, $S$ = {chart.S:+d}, $D_V$ = {chart.DV:g} (unstable region shaded)')
    if entries:
        _Legend(ax, entries, loc='upper left', fontsize=9)
    return ax


def PlotStabilityCharts(charts: Sequence, points: Optional[Mapping] = None, title: Optional[str] = None,
                        ax=None, note: Optional[str] = None, pointsLabel: Optional[str] = None,
                        outlines: Sequence = (), zoom: Union[str, bool] = 'auto', zoomDecades: float = 0.25):
    """Several charts of one D_V on one axes (the layout of Figures 4 and 5: one region per D_TV).

    Each unstable region is hatched in its chart's colour on no fill (crossed hatches where regions overlap,
    no blended colour); one legend below the axes explains every region, the crossing hatches, the points
    and any outlines.

    Parameters
    ----------
    charts : sequence of StabilityChart
        Charts on the same grid (e.g. D_TV = 1, 5, 25).
    points : mapping, optional
        Points to mark, as for :func:`PlotStabilityChart`.
    title : str, optional
        Axes title.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into (default: a new figure).
    note : str, optional
        A last line of the legend (e.g. which gear the chart is of).
    pointsLabel : str, optional
        Legend entry of the points (default: ``'points at their chart coordinates'``).
    outlines : sequence of (StabilityChart, str), optional
        Further charts drawn as a dashed boundary only, with their legend text (e.g. the chart of one point's
        own D_TV).
    zoom : str or sequence of str or None, optional
        Label(s) of at most two points to show in insets (lower right, then upper left) with ``zoomDecades``
        around each: where the point lies relative to a nearby boundary, which the main axes cannot resolve.
        An inset's title states the point's verdict on every chart and its distance to the nearest boundary.
        Default ``'auto'``: the points :func:`PointsToZoom` names; None: no inset.
    zoomDecades : float, optional
        Half width of the inset in decades (default 0.25).

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
    if isinstance(zoom, str) and zoom == 'auto':
        zoom = PointsToZoom(charts, {k: _PointXY(v) for k, v in points.items()})
    zoom = [] if zoom is None else [zoom] if isinstance(zoom, str) else list(zoom)
    if len(zoom) > len(_INSETS) or any(z not in points for z in zoom):
        raise ValueError(f"PlotStabilityCharts: 'zoom' must be at most {len(_INSETS)} labels of points "
                         f"({', '.join(points) or 'none'}), got {zoom!r}")
    ax = _Axes(ax, figsize=(7.5, 7.))
    entries = []

    def draw(axes, withLabels):
        for k, chart in enumerate(charts):
            _DrawChart(axes, chart, _COLORS[k % len(_COLORS)], True, None, HATCHES[k % len(HATCHES)])
        for chart, _ in outlines:
            for line in chart.boundaries:
                axes.plot(line[:, 0], line[:, 1], color='0.35', lw=1., ls='--', gid=f'outline DTV={chart.DTV:g}')
        _DrawPoints(axes, points, labels=withLabels)

    draw(ax, True)
    for k, chart in enumerate(charts):
        text = fr'$D_{{TV}}$ = {chart.DTV:g}: unstable (hatched), boundary' if chart.unstable.any() else \
            fr'$D_{{TV}}$ = {chart.DTV:g}: no unstable point'
        entries.append((_RegionHandle(_COLORS[k % len(_COLORS)], HATCHES[k % len(HATCHES)]), text))
    if len(charts) > 1:
        entries.append((Patch(fc='none', ec='0.3', hatch=HATCHES[0] + HATCHES[1], lw=0.),
                        'crossed hatches: unstable for each of those $D_{TV}$'))
    entries.append((Patch(fc='white', ec='0.5', lw=0.6), 'no hatch: stable for every $D_{TV}$ drawn'))
    for chart, text in outlines:
        entries.append((Line2D([], [], color='0.35', lw=1., ls='--'), text))
    if points:
        entries.append((Line2D([], [], ls='none', marker='o', ms=POINT_SIZE + 1, mfc='white', mec='black'),
                        pointsLabel or 'points at their chart coordinates'))
    if note:                                   # in the legend: a text in a corner could meet an inset or data
        entries.append((Line2D([], [], ls='none'), note))
    _Decorate(ax, charts[0])
    _Legend(ax, entries, loc='upper center', bbox_to_anchor=(0.5, -0.11), ncols=2, fontsize=8.5,
            frameon=False, title='unstable region of criteria (17), (19)', title_fontsize=8.5)
    c0 = charts[0]
    ax.set_title(title if title is not None else
                 fr'Stability chart, $S$ = {c0.S:+d}, $D_V$ = {c0.DV:g}, criteria (17) and (19)')
    for label, where in zip(zoom, _INSETS):
        _ZoomInset(ax, charts, points, label, zoomDecades, draw, where)
    return ax


# inset positions in axes fractions: lower right, upper left (the corners a chart of Figures 4/5 leaves empty)
_INSETS = ([0.6, 0.05, 0.37, 0.33], [0.07, 0.6, 0.3, 0.27])


#: a point closer than this (decades) to the boundary of a chart on which it is stable gets a zoomed inset
ZOOM_DECADES = 0.05


def PointsToZoom(charts: Sequence, points: Mapping, decades: float = ZOOM_DECADES) -> list:
    """Labels of the points (at most two, nearest first) closer than ``decades`` to the boundary of a chart
    on which they are stable: at a whole chart's scale they look as if on the line or inside (P3 and P5 next to
    D_TV = 25 in Figure 4).

    Parameters
    ----------
    charts : sequence of StabilityChart
        The charts drawn.
    points : mapping
        ``{label: point}``, a point as for :func:`PlotStabilityChart`.
    decades : float, optional
        Distance threshold in decades (default :data:`ZOOM_DECADES`).

    Returns
    -------
    list of str
    """
    near = {}
    for label, value in points.items():
        x, y = _PointXY(value)
        for chart in charts:
            d = NearestBoundary(chart, (x, y))
            if d < decades and not chart.IsUnstable(x, y):
                near[label] = min(d, near.get(label, d))
    return sorted(near, key=near.get)[:len(_INSETS)]


def _ZoomInset(ax, charts, points, label, decades, draw, where):
    """Inset at ``where`` with ``decades`` around point ``label``; its title gives the verdicts."""
    x, y = _PointXY(points[label])
    inset = ax.inset_axes(where)
    inset.set_gid(f'zoom {label}')
    draw(inset, False)
    inset.set_xscale('log')
    inset.set_yscale('log')
    inset.set_xlim(x / 10 ** decades, x * 10 ** decades)
    inset.set_ylim(y / 10 ** decades, y * 10 ** decades)
    inset.tick_params(labelsize=6.5, which='both')
    inset.set_facecolor('white')
    unstable = [f'{c.DTV:g}' for c in charts if c.IsUnstable(x, y)]
    nearest = min(charts, key=lambda c: NearestBoundary(c, (x, y)))
    distance = NearestBoundary(nearest, (x, y))
    verdict = ('stable on every chart' if not unstable else
               'unstable for $D_{TV}$ = ' + ', '.join(unstable))
    inset.annotate(label, (x, y), xytext=(5, -3), textcoords='offset points', fontsize=8, va='top')
    inset.set_title(f'{label}: {verdict};\nnearest boundary $D_{{TV}}$ = {nearest.DTV:g}, '
                    f'{distance:.2g} decades away', fontsize=7.5)
    ax.indicate_inset_zoom(inset, edgecolor='0.3')
    return inset


def PlotFirstCriterion(curves, ax=None, title: Optional[str] = None, mark: Optional[Mapping] = None):
    """Figure 3: the J1/J2 limit of the first criterion (20) with dT = 0 against the pitch angle.

    One curve per friction angle; the stable region lies above a curve.

    Parameters
    ----------
    curves : FirstCriterionCurves
        From :func:`~exudyn_worm.analysis.charts.stabilitychart.FirstCriterionChart`.
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


def PlotSpeedChart(chart: 'SpeedChart', ax=None, title: Optional[str] = None, log: bool = True):
    """Largest real part of each direction of the duty against motor speed, unstable speeds shaded, the drive's own
    operating points marked, mu(v0) on a twin axis.

    Parameters
    ----------
    chart : SpeedChart
        From :func:`exudyn_worm.analysis.charts.speedchart.SpeedStabilityChart`.
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
    if not isinstance(chart, SpeedChart):
        raise TypeError(f"PlotSpeedChart: 'chart' must be a SpeedChart (SpeedStabilityChart), got {type(chart).__name__}")
    ownFigure = ax is None
    ax = _Axes(ax, figsize=(7.5, 4.9))
    rpm = chart.motorSpeeds / RPM
    ax.axhline(0., color='0.4', lw=0.8)
    colors = {+1: _COLORS[2], -1: _COLORS[0]}
    for c in chart.curves:
        color = colors[c.S]
        ax.plot(rpm, c.maxRealPart, color=color, lw=1.8, marker='.',
                label=f'largest real part, {c.phase} (S = {c.S:+d}), load {c.loadTorque:.4g} N·m')
        for a, b in c.unstableRanges:
            ax.axvspan(a / RPM, b / RPM, color=color, alpha=0.12, lw=0)
        for b in c.Boundaries():
            ax.axvline(b / RPM, color=color, ls='--', lw=0.8)
    labelled = set()
    for p in chart.ownPoints:                   # the drive's own operating points (as exudyn-worm stability)
        label = f"own operating point, {p.phase}: {'stable' if p.stable else 'UNSTABLE'}"
        ax.plot(abs(p.point.motorSpeed) / RPM, p.maxRealPart, '*', ms=12, mec='black', mew=0.6, color=colors[p.S],
                label='_' + label if label in labelled else label)       # one legend entry per kind of star
        labelled.add(label)
    if log:
        ax.set_xscale('log')
    ax.set_xlabel('motor speed [rpm]')
    ax.set_ylabel(r'max Re$(\lambda)$ [1/s]  (> 0: chatter)')
    twin = ax.twinx()
    twin.plot(rpm, chart.mu, color=_COLORS[1], lw=1.2, ls=':', label=r'$\mu(v_0)$')
    twin.set_ylabel(r'friction coefficient $\mu(v_0)$', color=_COLORS[1])
    lines = [l for l in ax.get_lines()[1:] if not l.get_label().startswith('_')] + twin.get_lines()
    labels = [l.get_label() for l in lines]
    if ownFigure:                               # below the axes, over no data (constrained layout makes room)
        ax.figure.legend(lines, labels, loc='outside lower center', ncols=2, fontsize=8, frameon=False)
    else:                                       # the caller's axes: where it covers the least
        ax.legend(lines, labels, loc='best', fontsize=8)
    ax.set_title(title or f'stability over motor speed, {chart.frictionLaw} friction law', loc='left', fontsize=10)
    return ax
