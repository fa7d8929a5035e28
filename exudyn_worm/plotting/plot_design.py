"""Plot of a design check: the drive's point on its stability chart, the boundary and the recommended moves.

Imports matplotlib inside the function (as :mod:`exudyn_worm.plotting.plot`), so importing the package never pulls it in.
"""
from __future__ import annotations

import math
import re
import textwrap
from typing import Mapping, Optional

import numpy as np
from ..analysis.design.designcheck import DesignCheckResult
from ..analysis.design.designscan import SPEED_KEY
from .plot import _NewFigure
from .plot_charts import _Legend, PlotStabilityChart

__all__ = ['PlotDesignCheck']

_C_PLUS, _C_POINT, _C_MOVE, _C_PAIR = '#b9770e', '#1f4e79', '#2e7d32', '#8e24aa'


def PlotDesignCheck(result, charts: Optional[Mapping[int, 'StabilityChart']], ax=None, title: str = ''):
    """Draw a :class:`~exudyn_worm.analysis.design.designcheck.DesignCheckResult`: on the chart plane (x = kT/(kV r1^2),
    y = J1/J2) for the two-mass drive, as the stable ranges of the scanned parameters for any other drive.

    Only draws: the charts are computed by the caller (:meth:`DesignCheckResult.plot
    <exudyn_worm.analysis.design.designcheck.DesignCheckResult.plot>` passes :func:`~exudyn_worm.analysis.design.designchart.LocalCharts`).
    **Two-mass drive**: the charts that decide, at the drive's D_V and D_TV and at the operating point that decides in
    each contact state of its duty (mu(v0) and its slope; the title names it where the friction depends on speed),
    drawn with :func:`~exudyn_worm.plotting.plot_charts.PlotStabilityChart` (S = +1 only where it has an unstable
    point, unless it is the only contact state) within 2 decades of the drive's point; recommended changes of J1, J2
    and kT are arrows to the changed drive's point; changes of the damping or the speed (which change the chart,
    not the point) and a best pair are listed in the legend. Where the parameter set holds damping constants (dT,
    dV), a change of J1, J2 or kT also changes D_TV, so the arrow's end lies on a slightly different chart.
    **Any other drive** (``charts`` None): the chart of eqs. (15)-(19) does not describe it, and the figure says so;
    it shows, per scanned parameter, where the whole drive is stable over the factor of the change, and the
    recommended changes.

    Parameters
    ----------
    result : DesignCheckResult
        From :func:`~exudyn_worm.analysis.design.designcheck.DesignCheck`.
    charts : mapping of int to StabilityChart, or None
        ``{S: chart}`` for the contact states of the duty (:func:`~exudyn_worm.analysis.design.designchart.LocalCharts` of
        ``result.drive``); None for a drive the chart does not describe (``result.chartApplies`` False).
    ax : matplotlib.axes.Axes, optional
        Axes to draw into (default: a new figure).
    title : str, optional
        First title line, e.g. the drive's name (the check's D_V, D_TV and margin follow).

    Returns
    -------
    matplotlib.figure.Figure
    """
    if not isinstance(result, DesignCheckResult):
        raise TypeError(f"PlotDesignCheck: 'result' must be a DesignCheckResult, got {type(result).__name__}")
    if not result.chartApplies:
        if charts is not None:
            raise ValueError(f"PlotDesignCheck: 'charts' must be None for a drive the stability chart does not "
                             f"describe (it has {result.drive.ComponentsText()}), got {type(charts).__name__}")
        return _PlotScans(result, ax, title)
    if not isinstance(charts, Mapping) or not charts or not set(charts) <= {-1, +1}:
        raise TypeError(f"PlotDesignCheck: 'charts' must be a mapping {{S: StabilityChart}} with S in -1, +1 "
                        f"(designchart.LocalCharts(result.drive)), got {type(charts).__name__}")
    primary = -1 if -1 in charts else +1
    ax = PlotStabilityChart(charts[primary], ax=ax, label=f'$S = {primary:+d}$: unstable region (shaded), boundary')
    if primary == -1 and +1 in charts and charts[+1].unstable.any():
        PlotStabilityChart(charts[+1], ax=ax, color=_C_PLUS, hatch='///',
                           label='$S = +1$: unstable region (hatched), boundary')
    fig = ax.figure
    p = result.chartPoint
    ax.plot(p['x'], p['y'], 'o', color=_C_POINT, ms=8, zorder=5,
            label=f"drive ({'stable' if result.stable else 'unstable'})")
    arrows = {}                  # J1 x f and J2 / f end at the same point: one arrow, one label
    for r in result.recommendations:
        q = r.chartPointAfter
        factor = f'x{r.factor:.3g}' if r.factor >= 1 else f'/{1 / r.factor:.3g}'
        if r.parameter in ('J1', 'J2', 'kT'):
            end = (round(math.log10(q['x']), 6), round(math.log10(q['y']), 6))
            arrows.setdefault(end, (q, []))[1].append(f'{r.parameter} {factor}')
        elif r.parameter == SPEED_KEY:
            ax.plot([], [], ' ', label=f'motor speed {factor} (moves the operating point: another chart)')
        else:
            ax.plot([], [], ' ', label=f'{_Math(r.parameter)} {factor} (changes the chart: $D_V$ = {_Fmt(q["DV"])}, '
                                       f'$D_{{TV}}$ = {_Fmt(q["DTV"])})')
    texts = []
    for q, labels in arrows.values():
        ax.annotate('', xy=(q['x'], q['y']), xytext=(p['x'], p['y']),
                    arrowprops=dict(arrowstyle='->', color=_C_MOVE, lw=1.5), zorder=4)
        ax.plot(q['x'], q['y'], 's', color=_C_MOVE, ms=5, zorder=5)
        # the label beyond the arrow's end, away from the arrow; no ground under it, and moved off any
        # boundary line below (_PlaceClear), so it hides no part of the boundary
        right = q['x'] >= p['x'] if abs(math.log10(q['x'] / p['x'])) > 1e-9 else True
        up = q['y'] > p['y']
        vertical = abs(math.log10(q['y'] / p['y'])) > abs(math.log10(q['x'] / p['x']))
        first = ((8, 0), 'left', 'bottom' if up else 'top') if vertical else \
            (((8 if right else -8), 0), 'left' if right else 'right', 'center')
        text = ax.annotate(' = '.join(_Math(v) for v in labels), xy=(q['x'], q['y']), xytext=first[0],
                           textcoords='offset points', fontsize=8, color=_C_MOVE, ha=first[1], va=first[2],
                           zorder=6, gid='move label')
        texts.append((text, first))
    if result.bestPair is not None:
        q = result.bestPair.chartPointAfter
        ax.annotate('', xy=(q['x'], q['y']), xytext=(p['x'], p['y']),
                    arrowprops=dict(arrowstyle='->', color=_C_PAIR, lw=1.5, ls='--'), zorder=4)
        ax.plot(q['x'], q['y'], 'D', color=_C_PAIR, ms=5, zorder=5, label='best pair: ' + ', '.join(
            f'{_Math(k)} x{f:.3g}' if f >= 1 else f'{_Math(k)} /{1 / f:.3g}'
            for k, f in zip(result.bestPair.parameters, result.bestPair.factors)))
    ax.set_title((f"{title}\n" if title else '') + f"Design check at $D_V$ = {_Fmt(p['DV'])}, "
                 f"$D_{{TV}}$ = {_Fmt(p['DTV'])} (margin {result.margin:g} decades)" + _AtPoints(result, charts),
                 fontsize=10)
    # one legend below the axes (it covers no part of the chart): the regions with their shading, then the rest
    handles, labels = ax.get_legend_handles_labels()
    _Legend(ax, list(getattr(ax, '_chartEntries', [])) + list(zip(handles, labels)), fontsize=8,
            loc='upper center', bbox_to_anchor=(0.5, -0.11), ncols=1, frameon=False)
    lines = [line.get_xydata() for line in ax.lines if (line.get_gid() or '').startswith('boundary')]
    for text, first in texts:
        _PlaceClear(ax, text, first, lines)
    return fig


def _AtPoints(result, charts) -> str:
    """Title line naming the operating points the charts are linearized at (where the friction depends on speed)."""
    if not result.drive.gear.speedDependentFriction or not result.analysis.operatingPoints:
        return ''
    parts = [f"$S = {S:+d}$: $\\mu(v_0)$ = {_Fmt(c.operatingPoint.mu)}, $d\\mu/dv$ = {_Fmt(c.operatingPoint.dmuDv)} s/m"
             for S, c in sorted(charts.items()) if c.operatingPoint is not None]
    return '\ncharts at the deciding operating points: ' + '; '.join(parts) if parts else ''


def _PlotScans(result, ax, title):
    """A whole drive: per scanned parameter the factors at which it is stable, the given drive and the moves."""
    import matplotlib.patches as mpatches
    keys = list(result.scans)
    if ax is None:
        _, axes = _NewFigure(figsize=(7.5, 1.6 + 0.42 * max(len(keys), 1)))
        ax = axes[0, 0]
    fig = ax.figure
    for i, key in enumerate(keys):
        scan = result.scans[key]
        ax.broken_barh([(10. ** -scan.limit, 10. ** scan.limit - 10. ** -scan.limit)], (i - 0.3, 0.6),
                       facecolors='#f2c4c0', edgecolor='none', zorder=1)
        for a, b in scan.stableIntervals:
            ax.broken_barh([(10. ** a, 10. ** b - 10. ** a)], (i - 0.3, 0.6), facecolors='#b7dfb9', edgecolor='none',
                           zorder=2)
    moves = [(keys.index(r.parameter), r.factor) for r in result.recommendations]
    if moves:
        ax.plot([f for _, f in moves], [i for i, _ in moves], 'v', color=_C_MOVE, ms=7, zorder=4,
                label='recommended change (stable with margin)')
    ax.axvline(1., color=_C_POINT, lw=1.5, zorder=3, label=f"given drive ({'stable' if result.stable else 'unstable'})")
    ax.set_xscale('log')
    ax.set_yticks(range(len(keys)), [_Math(k) for k in keys])
    ax.set_ylim(len(keys) - 0.5, -0.5)
    ax.set_xlabel('factor on the parameter (all others as given)')
    reason = textwrap.fill(f"No stability chart: the chart of eqs. (15)-(19) describes the two-mass drive; this drive "
                           f"has {result.drive.ComponentsText()}. Verdict of the whole drive at its operating points: "
                           f"{'stable' if result.stable else 'UNSTABLE'} ({result.analysis.decidingText})", 110,
                           break_on_hyphens=False)
    ax.set_title((f"{title}\n" if title else '') + f"Design check of the whole drive (margin {result.margin:g} "
                 f"decades): where the linearized drive is stable\n{reason}", fontsize=9)
    handles, labels = ax.get_legend_handles_labels()
    handles += [mpatches.Patch(color='#b7dfb9'), mpatches.Patch(color='#f2c4c0')]
    labels += ['stable at every operating point', 'unstable at an operating point']
    ax.legend(handles, labels, fontsize=8, loc='upper center', bbox_to_anchor=(0.5, -0.18), ncols=2, frameon=False)
    return fig


def _PlaceClear(ax, text, first, lines):
    """Move annotation ``text`` to the first of a few positions around its point where its box touches no
    vertex of ``lines`` (data coordinates); keep ``first`` if none is clear."""
    fig = ax.figure
    fig.draw_without_rendering()
    renderer = fig._get_renderer()
    points = np.concatenate([_Dense(ax.transData.transform(line)) for line in lines]) if lines else np.empty((0, 2))
    candidates = [first, ((8, 0), 'left', 'center'), ((-8, 0), 'right', 'center'), ((0, 8), 'center', 'bottom'),
                  ((0, -8), 'center', 'top'), ((8, 8), 'left', 'bottom'), ((-8, 8), 'right', 'bottom'),
                  ((8, -8), 'left', 'top'), ((-8, -8), 'right', 'top')]
    for offset, ha, va in candidates:
        text.xyann = offset
        text.set_ha(ha)
        text.set_va(va)
        if not _Touches(text.get_window_extent(renderer).padded(2.), points):
            return
    text.xyann, (_, ha, va) = first[0], first
    text.set_ha(ha)
    text.set_va(va)


def _Dense(xy: np.ndarray, step: float = 1.) -> np.ndarray:
    """A polyline in display coordinates with extra vertices at most ``step`` pixels apart."""
    if len(xy) < 2:
        return xy
    count = np.maximum(1, np.ceil(np.hypot(*np.diff(xy, axis=0).T) / step)).astype(int)
    parts = [a + np.outer(np.arange(n) / n, b - a) for a, b, n in zip(xy[:-1], xy[1:], count)]
    return np.concatenate(parts + [xy[-1:]])


def _Touches(box, points: np.ndarray) -> bool:
    """Whether any of ``points`` (display coordinates) lies inside ``box``."""
    return bool(np.any((points[:, 0] >= box.x0) & (points[:, 0] <= box.x1) &
                       (points[:, 1] >= box.y0) & (points[:, 1] <= box.y1)))


def _Math(name: str) -> str:
    """A parameter name in mathtext: 'J1' -> '$J_1$', 'DTV' -> '$D_{TV}$' (others as they are)."""
    symbols = {'J1': '$J_1$', 'J2': '$J_2$', 'kT': '$k_T$', 'kV': '$k_V$', 'dT': '$d_T$', 'dV': '$d_V$',
               'DT': '$D_T$', 'DV': '$D_V$', 'DTV': '$D_{TV}$'}
    head, _, tail = name.partition(' ')
    if head not in symbols:        # chain keys: J4 -> $J_4$, kL1 -> $k_{L1}$
        match = re.fullmatch(r'([Jkd])(L?\d+)', head)
        if match:
            symbols[head] = f'${match[1]}_{{{match[2]}}}$'
    return symbols.get(head, head) + (f' {tail}' if tail else '')


def _Fmt(v) -> str:
    return 'inf' if v is None or (isinstance(v, float) and math.isinf(v)) else f'{np.float64(v):.3g}'
