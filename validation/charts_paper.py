"""The section 2.3 chart statements measured where the paper computed them: the ``charts-paper`` group.

The rows of :mod:`validation.charts` measure over the project's own, wider domain on log axes. Section 2.3
states where the paper computed its charts: set (25) with J1 from 1e-6 to 1e-3 kg*m^2 and kT from 5e-3 to 5 N*m.
The figures are not in the text, so whether their axes are linear or logarithmic is unknown; every statement is
therefore a row twice, once per axis reading (``chart_paper_log_<key>``, ``chart_paper_lin_<key>``, ``<key>`` the
statement of the wide-domain row ``chart_<key>``). The rules below were fixed (with ``validation/README.md``)
before any of these rows' results was computed.

Domain: x = kT/(kV r1^2) from 5e-3/(kV r1^2) to 5/(kV r1^2) and y = J1/J2 from 1e-6/J2 to 1e-3/J2 on set (25)
(:func:`validation.charts.DisplayedDomain`: 2.6950e-4 .. 0.26950 and 1e-5 .. 1e-2), 600 x 600 log grid, S = -1
unless stated. The bound rows ("no instability for stiffness ratios bigger than X"; the paper places the bounds
1 and 3 outside the displayed area, so it computed beyond the stated kT range) keep the stated J1 range and extend
x to :data:`BOUND_X_END` (the upper end of the project's domain); their value is the upper end of the unstable x
range (the ridge of the unstable set, bisected).

Log reading: the measures of :mod:`validation.charts` unchanged (area in log10-log10 coordinates, x extent in log10
decades, mean log10 J1/J2 extent over the grid columns with x < 0.10, ratio of log10 x extents; bound rule
``chart-bound``). Linear reading: area in x*y units over the cells that tile the domain in linear coordinates
(:func:`LinearCellWidths`), x extent x_max - x_min, the mean linear J1/J2 extent over x < 0.10 weighted by the
columns' linear widths, ratio of linear x extents; bound rule ``chart-bound-linear`` (+- half a unit of the last
printed digit). Both readings: comparisons are strict inequalities of the reading's measure; "virtually ceased to
exist" an area ratio of at most 0.1; "about 15 times" 15 +- 1.5; "no unstable regions for S = +1" zero unstable
grid points on the paper's domain.
"""
from __future__ import annotations

from functools import lru_cache
from typing import TYPE_CHECKING, Dict, List

import numpy as np

from .charts import (BOUND_DTV, DTV_VALUES, RESOLUTION, SMALL_X, Area, Chart, DisplayedDomain, SmallXYExtent, StatementValues,
                     TailText, XExtent, Y_RANGE, _Set25)
from .runner import Check, Fmt, ValidationContext

if TYPE_CHECKING:   # a hint only: the chart module is imported when a chart is computed
    from exudyn_worm.analysis.charts.stabilitychart import StabilityChart

__all__ = ['AXIS_READINGS', 'BOUND_X_END', 'PaperChart', 'BoundChart', 'LinearCellWidths',
           'LinearArea', 'LinearXExtent', 'SmallXLinearYExtent',
           'PaperChartChecks']

#: the two readings of the figures' axes: both logarithmic, both linear
AXIS_READINGS = ('log', 'lin')
#: upper end of x for the bound rows (the paper computed the bounds 1 and 3 beyond its displayed area)
BOUND_X_END = 1e2


def PaperChart(DV: float, DTV: float, S: int = -1) -> 'StabilityChart':
    """The stability chart of set (25) on the domain section 2.3 states (cached; shared with the report's table).

    Parameters
    ----------
    DV : float
        Mesh damping measure D_V.
    DTV : float
        Damping ratio D_TV = D_T / D_V.
    S : int, optional
        Contact state.

    Returns
    -------
    exudyn_worm.analysis.charts.stabilitychart.StabilityChart
    """
    return Chart(DV, DTV, S, displayed=True)


@lru_cache(maxsize=None)
def BoundChart(DV: float, DTV: float) -> 'StabilityChart':
    """The chart of the bound rows: the stated J1 range, x from the stated kT's lower end to :data:`BOUND_X_END`.

    Parameters
    ----------
    DV : float
        Mesh damping measure D_V.
    DTV : float
        Damping ratio D_TV = D_T / D_V.

    Returns
    -------
    exudyn_worm.analysis.charts.stabilitychart.StabilityChart
    """
    from exudyn_worm.analysis.charts.stabilitychart import ComputeStabilityChart   # lazy: as validation.charts.Chart
    gear, J2 = _Set25()
    (x0, _), yRange = DisplayedDomain()
    return ComputeStabilityChart(gear, J2, DV, DTV, xRange=(x0, BOUND_X_END), yRange=yRange, resolution=RESOLUTION)


def LinearCellWidths(grid: np.ndarray) -> np.ndarray:
    """Widths in linear coordinates of the cells around the grid points: edges halfway between neighbouring
    points, the outer edges at the first and last point, so that the cells tile [grid[0], grid[-1]] exactly.

    Parameters
    ----------
    grid : ndarray
        Increasing grid values, shape (n,), n >= 2.

    Returns
    -------
    ndarray
        Shape (n,); sums to ``grid[-1] - grid[0]``.

    Raises
    ------
    ValueError
        If ``grid`` has fewer than two points or is not increasing.
    """
    g = np.asarray(grid, dtype=float)
    if g.ndim != 1 or g.size < 2 or not np.all(np.diff(g) > 0):
        raise ValueError(f"LinearCellWidths: 'grid' must be an increasing 1-d array of at least 2 values, got shape "
                         f"{g.shape}")
    edges = np.concatenate(([g[0]], 0.5 * (g[:-1] + g[1:]), [g[-1]]))
    return np.diff(edges)


def LinearArea(chart: 'StabilityChart') -> float:
    """Unstable area in linear x*y coordinates: the unstable cells' linear width times height, summed.

    Parameters
    ----------
    chart : StabilityChart
        A chart (``unstable[i, j]`` at ``(x[j], y[i])``).

    Returns
    -------
    float
        The area; the domain's (x1 - x0)(y1 - y0) when every point is unstable.
    """
    wx, wy = LinearCellWidths(chart.x), LinearCellWidths(chart.y)
    return float(np.sum(chart.unstable * wy[:, None] * wx[None, :]))


def LinearXExtent(chart: 'StabilityChart') -> float:
    """Extent of the unstable set along x in linear units: x_max - x_min (the bisected ends of the chart).

    Parameters
    ----------
    chart : StabilityChart

    Returns
    -------
    float
        0 if nothing is unstable.
    """
    rng = chart.unstableXRange
    return 0. if rng is None else rng[1] - rng[0]


def SmallXLinearYExtent(chart: 'StabilityChart', xMax: float = SMALL_X) -> float:
    """Mean linear J1/J2 extent (y_max - y_min of each column's unstable points, 0 without) over the columns with
    x < ``xMax``, weighted by the columns' linear widths (:func:`LinearCellWidths`).

    Parameters
    ----------
    chart : StabilityChart
    xMax : float, optional
        Column limit.

    Returns
    -------
    float
        0 if no column lies below ``xMax``.
    """
    cols = np.nonzero(chart.x < xMax)[0]
    if cols.size == 0:
        return 0.
    weights = LinearCellWidths(chart.x)[cols]
    extents = np.array([float(chart.y[col].max() - chart.y[col].min()) if col.any() else 0.
                        for col in (chart.unstable[:, j] for j in cols)])
    return float(np.sum(weights * extents) / np.sum(weights))


#: the measures of each axis reading: area, x extent, mean J1/J2 extent for x < 0.10, and how the details say it
_MEASURES = {
    'log': dict(area=Area, xExtent=XExtent, smallExtent=SmallXYExtent, fmt='.3f', extentUnit=' decades',
                yLabel='mean log10 y-extent'),
    'lin': dict(area=LinearArea, xExtent=LinearXExtent, smallExtent=SmallXLinearYExtent, fmt='.4g', extentUnit='',
                yLabel='mean linear y-extent'),
}


def PaperChartChecks(ctx: ValidationContext) -> List[Check]:
    """Group ``charts-paper``: the section 2.3 statements on the paper's stated domain, under both axis readings.

    Parameters
    ----------
    ctx : ValidationContext
        The run's context.

    Returns
    -------
    list of Check
        One check per statement and reading (rows ``chart_paper_<reading>_<key>``).
    """
    from exudyn_worm.progress import ProgressBar   # lazy: as validation.charts.ChartChecks
    todo = ([(PaperChart, (0.014, d)) for d in DTV_VALUES] + [(PaperChart, (0.056, d)) for d in (1., 5., 25.)]
            + [(PaperChart, (0.014, d, +1)) for d in (1., 5., 25.)] + [(BoundChart, (0.014, d)) for d in (1., 5., 25.)])
    with ProgressBar(total=len(todo), desc='charts on the paper domain', unit='chart', quiet=ctx.quiet,
                     leave=False) as bar:
        for function, key in todo:
            function(*key)
            bar.update(1)
    c14 = {d: PaperChart(0.014, d) for d in DTV_VALUES}
    c56 = {d: PaperChart(0.056, d) for d in (1., 5., 25.)}
    cSp = [PaperChart(0.014, d, +1) for d in (1., 5., 25.)]
    bound = {d: BoundChart(0.014, d) for d in (1., 5., 25.)}
    checks = []
    for reading in AXIS_READINGS:
        values = StatementValues(c14, c56, cSp, bound, **_MEASURES[reading])
        for key, (value, detail) in values.items():
            rowId = f'chart_paper_{reading}_{key}'
            if key in BOUND_DTV:
                detail = '; '.join(filter(None, [detail, TailText(bound[BOUND_DTV[key]], ctx.Row(rowId).published)]))
            checks.append(ctx.Compare(rowId, value, detail=detail, uses=()))
    _Section(ctx, checks, c14, c56, bound)
    return checks


def _Range(rng, like: str = '0.000') -> str:
    return 'none' if rng is None else f'{Fmt(rng[0], like)} .. {Fmt(rng[1], like)}'


def _MeasureTable(charts: Dict) -> List[str]:
    rows = ['| D_V | D_TV | unstable x range | unstable J1/J2 range | log: area (decades^2) | log: x extent (decades) '
            '| log: mean y extent, x < 0.10 | lin: area | lin: x extent | lin: mean y extent, x < 0.10 | '
            'touches the domain edge |', '|---|---|---|---|---|---|---|---|---|---|---|']
    for (DV, d), c in charts.items():
        rows.append(f'| {DV} | {d:g} | {_Range(c.unstableXRange)} | {_Range(c.unstableYRange)} | {Area(c):.3f} | '
                    f'{XExtent(c):.3f} | {SmallXYExtent(c):.3f} | {LinearArea(c):.4g} | {LinearXExtent(c):.4g} | '
                    f'{SmallXLinearYExtent(c):.4g} | {", ".join(c.clippedSides) or "no"} |')
    return rows


def _Key(check: Check) -> str:
    return check.row.id.split('_', 3)[3]


def _Section(ctx: ValidationContext, checks: List[Check], c14: Dict, c56: Dict, bound: Dict) -> None:
    (x0, x1), (y0, y1) = DisplayedDomain()
    byKey: Dict[str, Dict[str, Check]] = {}
    for c in checks:
        byKey.setdefault(_Key(c), {})[c.row.id.split('_')[2]] = c
    table = ['| statement | log reading: computed | accepted | verdict | linear reading: computed | accepted | '
             'verdict |', '|---|---|---|---|---|---|---|']
    for key, pair in byKey.items():
        cells = []
        for reading in AXIS_READINGS:
            c = pair[reading]
            cells += [Fmt(c.computed, c.row.publishedText), c.IntervalText(),
                      c.verdict if c.verdict == 'PASS' else f'**{c.verdict}**']
        table.append(f'| `{key}`: {pair["log"].row.note.split(";")[0]} | ' + ' | '.join(cells) + ' |')
    both = [k for k, p in byKey.items() if all(p[r].holds for r in AXIS_READINGS)]
    only = {r: [k for k, p in byKey.items() if p[r].holds and not all(p[s].holds for s in AXIS_READINGS)]
            for r in AXIS_READINGS}
    neither = [k for k, p in byKey.items() if not any(p[r].holds for r in AXIS_READINGS)]
    names = lambda keys: ', '.join(f'`{k}`' for k in keys) or 'none'
    why = []
    for key, pair in byKey.items():
        for reading in AXIS_READINGS:
            c = pair[reading]
            if not c.holds:
                why.append(f'- `{key}`, {"log" if reading == "log" else "linear"} reading: computed '
                           f'{Fmt(c.computed, c.row.publishedText)}, accepted {c.IntervalText()}'
                           + (f' ({c.detail})' if c.detail and not c.knownDifference else '')
                           + (f'; known difference: {c.knownDifference}' if c.knownDifference else ''))
    printed = {key: byKey[key]['log'].row.published for key in BOUND_DTV}
    tails = [f'- `{key}` (D_TV = {BOUND_DTV[key]:g}, "bigger than {printed[key]:g}"): on the stated J1/J2 range '
             f'{y0:.3g} .. {y1:.3g}, {TailText(bound[BOUND_DTV[key]], printed[key])}; on the project\'s wide domain '
             f'(J1/J2 {Y_RANGE[0]:g} .. {Y_RANGE[1]:g}), {TailText(Chart(0.014, BOUND_DTV[key]), printed[key])}'
             for key in BOUND_DTV]
    full = [r for r in AXIS_READINGS if all(p[r].holds for p in byKey.values())]
    complete = ('neither reading reproduces every statement' if not full else
                ' and '.join(f'the {"log" if r == "log" else "linear"} reading' for r in full) + ' reproduces every statement')
    fixed = {**{(0.014, d): c for d, c in c14.items()}, **{(0.056, d): c for d, c in c56.items()}}
    ctx.AddSection('Stability charts on the paper\'s domain: both axis readings', f"""
Set (25) with mu = 0.132 on the domain section 2.3 states (J1 from 1e-6 to 1e-3 kg*m^2, kT from 5e-3 to 5 N*m):
x = kT/(kV r1^2) from {x0:.5g} to {x1:.5g}, y = J1/J2 from {y0:.3g} to {y1:.3g}, {RESOLUTION} x {RESOLUTION} log
grid, S = -1 unless stated; the bound rows on x from {x0:.5g} to {BOUND_X_END:g} with the same J1/J2 range. Each
statement under both readings of the figures' axes, with the measures and rules fixed in validation/README.md
before these results were computed:

{chr(10).join(table)}

Generated from the verdicts: {'; '.join(f"with {'log' if r == 'log' else 'linear'} axes {sum(p[r].holds for p in byKey.values())} of {len(byKey)} statements hold" for r in AXIS_READINGS)}, so
{complete}. Under both readings {len(both)} of {len(byKey)} hold ({names(both)});
only under the log reading: {names(only['log'])}; only under the linear reading: {names(only['lin'])}; under
neither: {names(neither)}. Where a statement does not hold, what was measured (the known differences, listed in
`paper/differences.csv`, are the statements neither reading reproduces):

{chr(10).join(why) or 'every statement holds under both readings'}

Where the bound rows' unstable sets end, measured from the printed bounds (the tail's width in decades; the
J1/J2 band in the last unstable grid column):

{chr(10).join(tails)}

The measures of both readings per chart (the table of the wide-domain rows' section, with the linear measures
beside the log ones):

{chr(10).join(_MeasureTable(fixed))}
""")
