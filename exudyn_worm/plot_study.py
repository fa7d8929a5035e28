"""Plots of parameter studies (:mod:`exudyn_worm.study`): a metric against one parameter, and the chatter
map over two parameters drawn over the analytical stability boundary.

matplotlib is imported inside the functions only (through :mod:`exudyn_worm.plot`).
"""
from __future__ import annotations

import itertools
from typing import Dict, Mapping, Optional, Tuple

import numpy as np

from .parameters import PARAMETERS

__all__ = ['PlotMetric', 'PlotChatterMap', 'AnalyticalMap', 'AxisLabel', 'ChartAxes', 'WHOLE_DRIVE_RESOLUTION']

#: points per axis of the map of the linearized whole drive (a drive with a chain or an axial bearing) in
#: :func:`PlotChatterMap`: one Exudyn linearization a point, so 400 points take about 12 s
WHOLE_DRIVE_RESOLUTION = 20

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


def _IsLog(values) -> bool:
    v = np.unique(np.asarray(values, float))
    if v.size < 3 or np.any(v <= 0):
        return False
    ratios = v[1:] / v[:-1]
    return bool(np.allclose(ratios, ratios[0], rtol=1e-6) and not np.allclose(np.diff(v), np.diff(v)[0], rtol=1e-6))


def _Axes(ax, figsize):
    from .plot import _NewFigure
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
        Result of :func:`~exudyn_worm.study.RunStudy`.
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
    if _IsLog([r[x] for r in result.rows]):
        ax.set_xscale('log')
    ax.set_xlabel(xLabel)
    ax.set_ylabel(yLabel)
    ax.grid(True, alpha=0.3)
    if others or label:
        ax.legend(fontsize='small')
    ax.set_title(title or (f'{metric} against {x} (filled: chatter in {window or "the window"})'
                           + (f'\n{subtitle}' if subtitle else '')), fontsize='medium')
    return fig


def AnalyticalMap(base: Mapping[str, float], x: str, xValues, y: str, yValues) -> np.ndarray:
    """Largest real part (1/s) of the S = -1 eigenvalues of the linear model over a grid of two parameters, the
    others as in ``base``: > 0 means chatter predicted while lowering. The model is that of
    :func:`~exudyn_worm.linearization.DriveStability` at each point: eqs. (15)-(16) for the two-mass drive, the
    linearized whole drive (about 30 ms a point) for one with a drive-side chain or a worm axial bearing.

    Parameters
    ----------
    base : mapping
        Flat parameter set.
    x, y : str
        Parameter keys.
    xValues, yValues : array_like
        Grid values (SI).

    Returns
    -------
    numpy.ndarray
        Shape (len(yValues), len(xValues)).
    """
    from .linearization import DriveStability
    from .presets import ApplyOverrides
    out = np.empty((len(yValues), len(xValues)))
    for (i, yv), (j, xv) in itertools.product(enumerate(yValues), enumerate(xValues)):
        out[i, j] = DriveStability(ApplyOverrides(base, {x: float(xv), y: float(yv)})).State(-1).maxRealPart
    return out


def _Chart(base, x, xValues, y, yValues, resolution):
    """The stability chart (:func:`~exudyn_worm.charts.ComputeStabilityChart`) over a J1-kT map, in the map's
    coordinates: ``(xGrid, yGrid, unstable, [(xLine, yLine), ...])``; None unless the map's keys are J1 and kT,
    the damping is given as measures (D_T or D_TV, D_V), which is what a chart holds fixed, and the drive is the
    two-mass drive the chart describes (no drive-side chain, no axial bearing)."""
    from .presets import DriveFromParameters, ExtraComponents
    if {x, y} != {'J1', 'kT'} or 'dT' in base or 'dV' in base or ExtraComponents(base):
        return None
    from .charts import ChartCoordinates, ComputeStabilityChart
    drive = DriveFromParameters(base)
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


def PlotChatterMap(result, x: str, y: str, ax=None, labels: Optional[Mapping[str, Tuple[float, float]]] = None,
                   resolution: int = 60, title: Optional[str] = None, subtitle: str = ''):
    """Chatter while lowering of every run over two varied parameters, over the analytical S = -1 region.

    The shaded region and its boundary line are where the linear model (eqs. (15)-(16), S = -1) predicts
    chatter: for a map of J1 and kT at fixed damping measures the stability chart of
    :func:`~exudyn_worm.charts.ComputeStabilityChart`, else :func:`AnalyticalMap` on a finer grid; red filled dots: the simulation chatters
    while lowering; blue open circles: it does not; grey crosses: failed runs. Runs whose simulated verdict
    differs from the analytical one are ringed.

    Parameters
    ----------
    result : StudyResult
        Result of :func:`~exudyn_worm.study.RunStudy` with a lowering window.
    x, y : str
        Varied keys on the horizontal and vertical axis.
    ax : matplotlib.axes.Axes, optional
        Draw into these axes (default: a new figure).
    labels : mapping, optional
        Named points to mark, ``{'P1': (xValue, yValue), ...}`` (SI).
    resolution : int, optional
        Points per axis of the analytical grid (the stability chart is vectorized and gets at least 300).
    title : str, optional
        Axes title (default: what is drawn and the agreement).
    subtitle : str, optional
        Second line of the default title, e.g. the study's preset and fixed keys.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from .presets import ExtraComponents
    keys = result.study.keys
    for name, key in (('x', x), ('y', y)):
        if key not in keys:
            raise ValueError(f"PlotChatterMap: '{name}' must be a varied key ({', '.join(keys)}), got {key!r}")
    fig, ax = _Axes(ax, (6.4, 6.))
    xs, ys = result.Values(x), result.Values(y)
    # log axes for log-spaced values or positive values spanning more than 50x (the grid and the axis alike)
    logX, logY = (_IsLog(v) or bool(np.nanmin(v) > 0 and np.nanmax(v) / np.nanmin(v) > 50) for v in (xs, ys))

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
    (xLabel, xf), (yLabel, yf) = AxisLabel(x), AxisLabel(y)
    chart = _Chart(result.study.base, x, gx, y, gy, max(resolution, 300))
    if chart is not None:                   # J1 and kT at fixed damping measures: the stability chart itself
        cx, cy, unstable, lines = chart
        ax.contourf(cx * xf, cy * yf, unstable.astype(float), levels=[0.5, 1.5], colors=['#f6d5d1'])
        for lx, ly in lines:
            ax.plot(lx * xf, ly * yf, color=_C_BOUNDARY, lw=1.2)
        source = 'stability chart'
    else:
        wholeDrive = bool(ExtraComponents(result.study.base))
        if wholeDrive:              # one Exudyn linearization a point (about 30 ms): a coarser grid
            count = min(resolution, WHOLE_DRIVE_RESOLUTION)
            gx, gy = grid(xs, logX, count), grid(ys, logY, count)
        growth = AnalyticalMap(result.study.base, x, gx, y, gy)
        ax.contourf(gx * xf, gy * yf, (growth > 0).astype(float), levels=[0.5, 1.5], colors=['#f6d5d1'])
        if np.any(growth > 0) and np.any(growth <= 0):
            ax.contour(gx * xf, gy * yf, growth, levels=[0.], colors=[_C_BOUNDARY], linewidths=1.2)
        source = 'linearized whole drive' if wholeDrive else 'linear model'
    ok = [r for r in result.rows if r['status'] == 'ok' and r['loweringChatter'] in (True, False)]
    chatter = [r for r in ok if r['loweringChatter']]
    quiet = [r for r in ok if not r['loweringChatter']]
    unresolved = [r for r in result.rows if r['status'] == 'ok' and r['loweringChatter'] == 'unresolved']
    failed = [r for r in result.rows if r not in ok and r not in unresolved]
    differ = [r for r in ok if r['analyticStableLowering'] is not None
              and r['loweringChatter'] == r['analyticStableLowering']]
    pts = lambda rows: (np.array([r[x] for r in rows]) * xf, np.array([r[y] for r in rows]) * yf)
    ax.plot(*pts(chatter), 'o', color=_C_CHATTER, ms=5, label='simulation: chatter while lowering')
    ax.plot(*pts(quiet), 'o', mfc='white', color=_C_QUIET, ms=5, label='simulation: no chatter')
    if unresolved:
        ax.plot(*pts(unresolved), 'D', mfc='white', color=_C_FAILED, ms=5,
                label='simulation: unresolved (changes at half the step)')
    if failed:
        ax.plot(*pts(failed), 'x', color=_C_FAILED, ms=6, label='failed run')
    if differ:
        ax.plot(*pts(differ), 'o', mfc='none', color='black', ms=11, mew=1.2, label='differs from analytical')
    ax.plot([], [], color=_C_BOUNDARY, lw=1.2, label=f'analytical S = -1 boundary, {source} (shaded: unstable)')
    for name, (px, py) in (labels or {}).items():
        ax.plot(px * xf, py * yf, '*', color='#e69f00', ms=11, mec='black', mew=0.5)
        ax.annotate(name, (px * xf, py * yf), xytext=(4, 4), textcoords='offset points', fontsize='small')
    if logX:
        ax.set_xscale('log')
    if logY:
        ax.set_yscale('log')
    ax.set_xlim(gx[0] * xf, gx[-1] * xf)
    ax.set_ylim(gy[0] * yf, gy[-1] * yf)
    ax.set_xlabel(xLabel)
    ax.set_ylabel(yLabel)
    agreement = result.agreement
    ax.set_title(title or ('Chatter while lowering: simulation over the analytical chart'
                           + ('' if agreement is None else f' (agreement {100 * agreement:.0f} %)')
                           + (f'\n{subtitle}' if subtitle else '')),
                 fontsize='medium')
    ax.legend(fontsize='x-small', loc='upper center', bbox_to_anchor=(0.5, -0.13), ncol=2, frameon=False)
    return fig
