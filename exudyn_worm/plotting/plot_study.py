"""Plots of parameter studies (:mod:`exudyn_worm.analysis.studies.study`): a metric against one parameter, and the chatter
map over two parameters drawn over the analytical stability boundary.

matplotlib is imported inside the functions only (through :mod:`exudyn_worm.plotting.plot`).
"""
from __future__ import annotations

from typing import Dict, Mapping, Optional, Tuple

import numpy as np

from ..params.parameters import PARAMETERS
from .._spacing import IsLogSpaced
from .plot import _NewFigure
from ..analysis.studies.studymap import ChatterMap

__all__ = ['PlotMetric', 'PlotChatterMap', 'AxisLabel', 'ChartAxes']

_C_CHATTER, _C_QUIET, _C_FAILED, _C_BOUNDARY = '#c0392b', '#1f4e79', '#7f7f7f', '#2c2c2c'
_METRIC_LABELS = {'maxAbsWheelAcceleration': (r"max $|\ddot\varphi_2|$", 'rad/s²', 1.),
                  'maxNormalForce': (r'max $F_n$', 'kN', 1e-3),
                  'dominantFrequencyHz': ('dominant frequency', 'Hz', 1.),
                  'fractionSNegative': ('share of S = -1', '–', 1.),
                  'minWormSpeed': (r"min $\dot\varphi_1$", 'rad/s', 1.),
                  'vibrationSeconds': ('vibration lasts', 's', 1.),
                  'seconds': ('run time', 's', 1.), 'solveSeconds': ('solve time', 's', 1.)}


def AxisLabel(column: str) -> Tuple[str, float]:
    """Axis label and the factor from SI to the unit shown, for a parameter or a results column.

    Parameters
    ----------
    column : str
        A parameter key (``'J1'``) or a column of the results table (``'w1.maxNormalForce'``).

    Returns
    -------
    (str, float)
    """
    if column in PARAMETERS:
        return PARAMETERS.AxisLabel(column)
    window, _, name = column.rpartition('.')
    text, unit, factor = _METRIC_LABELS.get(name, (name, '', 1.))
    where = f', window {window[1:]}' if window.startswith('w') else ''
    return f'{text}{where} [{unit}]', factor


def ChartAxes(x: str, y: str) -> Tuple[str, str]:
    """The two keys of a chatter map in the stability charts' order: a stiffness (kT, kV, k3, ...) on the
    horizontal axis, an inertia (J1, J2, ...) on the vertical one, as the charts' x = kT/(kV r1^2) and
    y = J1/J2; any other pair as given.

    Parameters
    ----------
    x, y : str
        The varied keys in the order given (e.g. ``--vary J1=... --vary kT=...``).

    Returns
    -------
    (str, str)
        (horizontal key, vertical key).
    """
    inertia = lambda key: key.startswith('J')
    stiffness = lambda key: key.startswith('k')
    return (y, x) if inertia(x) and stiffness(y) else (x, y)


def _Axes(ax, figsize):
    if ax is not None:
        return ax.figure, ax
    fig, axes = _NewFigure(figsize=figsize)
    return fig, axes[0, 0]


def PlotMetric(result, x: str, metric: str = 'w1.maxAbsWheelAcceleration', ax=None, title: Optional[str] = None,
               label: Optional[str] = None, subtitle: str = ''):
    """A metric of every run against one varied parameter; one line per combination of the other varied
    parameters; filled markers where the metric's window chatters, open ones where it does not.

    Parameters
    ----------
    result : StudyResult
        Result of :func:`~exudyn_worm.analysis.studies.study.RunStudy`.
    x : str
        Varied key on the horizontal axis.
    metric : str, optional
        Results column, e.g. ``'w1.maxNormalForce'`` (default: the largest wheel acceleration in window 1).
    ax : matplotlib.axes.Axes, optional
        Draw into these axes (default: a new figure).
    title : str, optional
        Axes title.
    label : str, optional
        Legend label of the study (prefixed to the values of the other varied keys).
    subtitle : str, optional
        Second line of the default title, e.g. the study's preset and fixed keys.

    Returns
    -------
    matplotlib.figure.Figure
    """
    keys = result.study.keys
    if x not in keys:
        raise ValueError(f"PlotMetric: 'x' must be a varied key ({', '.join(keys)}), got {x!r}")
    fig, ax = _Axes(ax, (7., 4.2))
    xLabel, xFactor = AxisLabel(x)
    yLabel, yFactor = AxisLabel(metric)
    others = [k for k in keys if k != x]
    window = metric.split('.')[0] if metric.startswith('w') and '.' in metric else None
    groups: Dict[tuple, list] = {}
    for r in result.rows:
        groups.setdefault(tuple(r[k] for k in others), []).append(r)
    for group, rows in sorted(groups.items(), key=lambda kv: kv[0]):
        rows = sorted((r for r in rows if r['status'] == 'ok' and r.get(metric) is not None), key=lambda r: r[x])
        if not rows:
            continue
        xs = np.array([r[x] for r in rows]) * xFactor
        ys = np.array([r[metric] for r in rows], float) * yFactor
        text = ', '.join([label] * bool(label) + [f'{k} = {v:.3g}' for k, v in zip(others, group)]) or None
        color = f'C{len(ax.lines) // 3 % 10}'
        ax.plot(xs, ys, '-', color=color, lw=1., label=text)
        chatter = (np.array([r.get(f'{window}.chatter') is True for r in rows]) if window    # 'unresolved': open
                   else np.zeros(len(rows), bool))
        ax.plot(xs[chatter], ys[chatter], 'o', color=color, ms=5)
        ax.plot(xs[~chatter], ys[~chatter], 'o', mfc='white', color=color, ms=5)
    if not ax.lines:                    # every run failed or lacks the metric: say so instead of empty axes
        ax.text(0.5, 0.5, f'no successful run with a value of {metric}', transform=ax.transAxes,
                ha='center', va='center', color='0.3')
    if IsLogSpaced([r[x] for r in result.rows]):
        ax.set_xscale('log')
    ax.set_xlabel(xLabel)
    ax.set_ylabel(yLabel)
    ax.grid(True, alpha=0.3)
    if others or label:
        ax.legend(fontsize='small')
    ax.set_title(title or (f'{metric} against {x} (filled: chatter in {window or "the window"})'
                           + (f'\n{subtitle}' if subtitle else '')), fontsize='medium')
    return fig


def PlotChatterMap(result, chatterMap: 'ChatterMap', ax=None,
                   labels: Optional[Mapping[str, Tuple[float, float]]] = None, title: Optional[str] = None,
                   subtitle: str = ''):
    """Chatter while lowering of every run over two varied parameters, over the analytical S = -1 region.

    Only draws: the region is computed by :func:`~exudyn_worm.analysis.studies.studymap.ComputeChatterMap` (which
    :meth:`StudyResult.plot <exudyn_worm.analysis.studies.studyfiles.StudyResult.plot>` calls). The shaded region and its boundary
    line are where the linear model (eqs. (15)-(16), S = -1) predicts chatter: for a map of J1 and kT at fixed
    damping measures the stability chart of :func:`~exudyn_worm.analysis.charts.stabilitychart.ComputeStabilityChart`, else
    :func:`~exudyn_worm.analysis.studies.studymap.AnalyticalMap` on a finer grid; red filled dots: the simulation chatters
    while lowering; blue open circles: it does not; grey crosses: failed runs. Runs whose simulated verdict
    differs from the analytical one are ringed.

    Parameters
    ----------
    result : StudyResult
        Result of :func:`~exudyn_worm.analysis.studies.study.RunStudy` with a lowering window.
    chatterMap : ChatterMap
        The analytical map over two varied keys, from :func:`~exudyn_worm.analysis.studies.studymap.ComputeChatterMap`.
    ax : matplotlib.axes.Axes, optional
        Draw into these axes (default: a new figure).
    labels : mapping, optional
        Named points to mark, ``{'P1': (xValue, yValue), ...}`` (SI).
    title : str, optional
        Axes title (default: what is drawn and the agreement).
    subtitle : str, optional
        Second line of the default title, e.g. the study's preset and fixed keys.

    Returns
    -------
    matplotlib.figure.Figure
    """
    if not isinstance(chatterMap, ChatterMap):
        raise TypeError(f"PlotChatterMap: 'chatterMap' must be a ChatterMap (studymap.ComputeChatterMap), "
                        f"got {type(chatterMap).__name__}")
    m = chatterMap
    x, y = m.x, m.y
    fig, ax = _Axes(ax, (6.4, 6.))
    (xLabel, xf), (yLabel, yf) = AxisLabel(x), AxisLabel(y)
    ax.contourf(m.xGrid * xf, m.yGrid * yf, m.unstable.astype(float), levels=[0.5, 1.5], colors=['#f6d5d1'])
    for lx, ly in m.lines:
        ax.plot(lx * xf, ly * yf, color=_C_BOUNDARY, lw=1.2)
    if m.growth is not None and np.any(m.growth > 0) and np.any(m.growth <= 0):
        ax.contour(m.xGrid * xf, m.yGrid * yf, m.growth, levels=[0.], colors=[_C_BOUNDARY], linewidths=1.2)
    source = m.source
    ok = [r for r in result.rows if r['status'] == 'ok' and r['loweringChatter'] in (True, False)]
    chatter = [r for r in ok if r['loweringChatter']]
    quiet = [r for r in ok if not r['loweringChatter']]
    unresolved = [r for r in result.rows if r['status'] == 'ok' and r['loweringChatter'] == 'unresolved']
    undecided = [r for r in result.rows if r['status'] == 'ok' and r['loweringChatter'] == 'undecided']
    failed = [r for r in result.rows if r not in ok and r not in unresolved and r not in undecided]
    differ = [r for r in ok if r['analyticStableLowering'] is not None
              and r['loweringChatter'] == r['analyticStableLowering']]
    pts = lambda rows: (np.array([r[x] for r in rows]) * xf, np.array([r[y] for r in rows]) * yf)
    ax.plot(*pts(chatter), 'o', color=_C_CHATTER, ms=5, label='simulation: chatter while lowering')
    ax.plot(*pts(quiet), 'o', mfc='white', color=_C_QUIET, ms=5, label='simulation: no chatter')
    if unresolved:
        ax.plot(*pts(unresolved), 'D', mfc='white', color=_C_FAILED, ms=5,
                label='simulation: unresolved (changes at half the step)')
    if undecided:
        ax.plot(*pts(undecided), 's', mfc='white', color=_C_FAILED, ms=5,
                label='simulation: undecided (decays slower than the window)')
    if failed:
        ax.plot(*pts(failed), 'x', color=_C_FAILED, ms=6, label='failed run')
    if differ:
        ax.plot(*pts(differ), 'o', mfc='none', color='black', ms=11, mew=1.2, label='differs from analytical')
    ax.plot([], [], color=_C_BOUNDARY, lw=1.2, label=f'analytical S = -1 boundary, {source} (shaded: unstable)')
    for name, (px, py) in (labels or {}).items():
        ax.plot(px * xf, py * yf, '*', color='#e69f00', ms=11, mec='black', mew=0.5)
        ax.annotate(name, (px * xf, py * yf), xytext=(4, 4), textcoords='offset points', fontsize='small')
    if m.logX:
        ax.set_xscale('log')
    if m.logY:
        ax.set_yscale('log')
    ax.set_xlim(m.xLimits[0] * xf, m.xLimits[1] * xf)
    ax.set_ylim(m.yLimits[0] * yf, m.yLimits[1] * yf)
    ax.set_xlabel(xLabel)
    ax.set_ylabel(yLabel)
    agreement = result.agreement
    ax.set_title(title or ('Chatter while lowering: simulation over the analytical chart'
                           + ('' if agreement is None else f' (agreement {100 * agreement:.0f} %)')
                           + (f'\n{subtitle}' if subtitle else '')),
                 fontsize='medium')
    ax.legend(fontsize='x-small', loc='upper center', bbox_to_anchor=(0.5, -0.13), ncol=2, frameon=False)
    return fig
