"""Plot of a design check: the drive's point on its stability chart, the boundary and the recommended moves.

Imports matplotlib inside the function (as :mod:`exudyn_worm.plot`), so importing the package never pulls it in.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ['PlotDesignCheck']

_C_PLUS, _C_POINT, _C_MOVE, _C_PAIR = '#b9770e', '#1f4e79', '#2e7d32', '#8e24aa'


def PlotDesignCheck(result, ax=None, title: str = ''):
    """Draw a :class:`~exudyn_worm.design.DesignCheckResult` on the chart plane (x = kT/(kV r1^2), y = J1/J2).

    The drive's stability charts at its D_V and D_TV (:func:`~exudyn_worm.design.LocalCharts`, drawn with
    :func:`~exudyn_worm.plot_charts.PlotStabilityChart`; S = +1 only where it has an unstable point) within
    2 decades of the drive's point; recommended changes of J1, J2 and kT are
    arrows to the changed drive's point; changes of the damping (which change the chart, not the point) and a
    best pair are listed in the legend. Where the parameter set holds damping constants (dT, dV), a change
    of J1, J2 or kT also changes D_TV, so the arrow's end lies on a slightly different chart.

    Parameters
    ----------
    result : DesignCheckResult
        From :func:`~exudyn_worm.design.DesignCheck`.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into (default: a new figure).
    title : str, optional
        First title line, e.g. the drive's name (the check's D_V, D_TV and margin follow).

    Returns
    -------
    matplotlib.figure.Figure
    """
    from .design import DesignCheckResult, LocalCharts
    from .plot_charts import PlotStabilityChart
    if not isinstance(result, DesignCheckResult):
        raise TypeError(f"PlotDesignCheck: 'result' must be a DesignCheckResult, got {type(result).__name__}")
    charts = LocalCharts(result.parameters)
    ax = PlotStabilityChart(charts[-1], ax=ax, label='boundary, S = -1')
    if charts[+1].unstable.any():
        PlotStabilityChart(charts[+1], ax=ax, color=_C_PLUS, label='boundary, S = +1')
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
        else:
            ax.plot([], [], ' ', label=f'{r.parameter} {factor} (changes the chart: D_V {_Fmt(q["DV"])}, '
                                       f'D_TV {_Fmt(q["DTV"])})')
    for q, labels in arrows.values():
        ax.annotate('', xy=(q['x'], q['y']), xytext=(p['x'], p['y']),
                    arrowprops=dict(arrowstyle='->', color=_C_MOVE, lw=1.5), zorder=4)
        ax.plot(q['x'], q['y'], 's', color=_C_MOVE, ms=5, zorder=5)
        # the label beyond the arrow's end, away from the arrow, on a white ground (it may cross a boundary)
        right = q['x'] >= p['x'] if abs(math.log10(q['x'] / p['x'])) > 1e-9 else True
        up = q['y'] > p['y']
        vertical = abs(math.log10(q['y'] / p['y'])) > abs(math.log10(q['x'] / p['x']))
        offset = (8, 0) if vertical else ((8 if right else -8), 0)
        ax.annotate(' = '.join(labels), xy=(q['x'], q['y']), xytext=offset, textcoords='offset points',
                    fontsize=8, color=_C_MOVE, ha='left' if (vertical or right) else 'right',
                    va=('bottom' if up else 'top') if vertical else 'center', zorder=6,
                    bbox=dict(boxstyle='round,pad=0.15', fc='white', ec='none', alpha=0.85))
    if result.bestPair is not None:
        q = result.bestPair.chartPointAfter
        ax.annotate('', xy=(q['x'], q['y']), xytext=(p['x'], p['y']),
                    arrowprops=dict(arrowstyle='->', color=_C_PAIR, lw=1.5, ls='--'), zorder=4)
        ax.plot(q['x'], q['y'], 'D', color=_C_PAIR, ms=5, zorder=5, label='best pair: ' + ', '.join(
            f'{k} x{f:.3g}' if f >= 1 else f'{k} /{1 / f:.3g}'
            for k, f in zip(result.bestPair.parameters, result.bestPair.factors)))
    ax.set_title((f"{title}\n" if title else '') + f"Design check at D_V = {_Fmt(p['DV'])}, D_TV = {_Fmt(p['DTV'])} "
                 f"(margin {result.margin:g} decades)", fontsize=10)
    ax.legend(fontsize=8, loc='lower right')
    return fig


def _Fmt(v) -> str:
    return 'inf' if v is None or (isinstance(v, float) and math.isinf(v)) else f'{np.float64(v):.3g}'
