"""The section 2.3 statements about the stability charts (Figures 4 and 5): the ``charts`` group of the validation.

Domain and measures are fixed in ``validation/README.md`` (with the reading rules, before any chart result):
set (25), x = kT/(kV r1^2) from 1e-4 to 1e2, y = J1/J2 from 1e-6 to 1, a 600 x 600 log grid; "smaller D_TV"
than 1 means 0.2 and 0.5; an area is measured in log10-log10 coordinates, an extent in log10 decades.
The charts come from :func:`exudyn_worm.analysis.charts.stabilitychart.ComputeStabilityChart`.
"""
from __future__ import annotations

import math
from functools import lru_cache
from typing import TYPE_CHECKING, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np

from exudyn_worm.model.gear import WormGear
from exudyn_worm.drive.presets import GearFromParameters, GetPreset

from .runner import Check, Fmt, ValidationContext

if TYPE_CHECKING:   # a hint only: the chart module is imported when a chart is computed
    from exudyn_worm.analysis.charts.stabilitychart import StabilityChart

__all__ = ['X_RANGE', 'Y_RANGE', 'RESOLUTION', 'DTV_VALUES', 'BOUND_DTV', 'Chart', 'DisplayedDomain', 'Area', 'XExtent', 'SmallXYExtent',
           'Tail', 'TailText', 'StatementValues', 'ChartChecks']

#: chart domain of the section 2.3 rows (validation/README.md)
X_RANGE = (1e-4, 1e2)
Y_RANGE = (1e-6, 1.)
RESOLUTION = 600
#: the damping ratios D_TV compared at D_V = 0.014 (Figure 4 has 1, 5, 25; "smaller" means 0.2 and 0.5)
DTV_VALUES = (0.2, 0.5, 1., 5., 25.)
#: the bound statements ("no instability for stiffness ratios bigger than X", X in the rows): key -> D_TV
BOUND_DTV = {'bound_DTV25': 25., 'bound_DTV5': 5., 'bound_DTV1': 1.}
#: stiffness ratio below which the J1/J2 interval is compared ("small stiffness ratios (< 0.10)")
SMALL_X = 0.10


def _Set25() -> Tuple[WormGear, float]:
    p = GetPreset('chart')
    return GearFromParameters(p, meshDamping=False), p['J2']


@lru_cache(maxsize=None)
def Chart(DV: float, DTV: float, S: int = -1, displayed: bool = False):
    """The stability chart of set (25) on the fixed domain (cached).

    Parameters
    ----------
    DV : float
        Mesh damping measure D_V.
    DTV : float
        Damping ratio D_TV = D_T / D_V.
    S : int, optional
        Contact state.
    displayed : bool, optional
        Use the area the paper displays (:func:`DisplayedDomain`) instead of the fixed domain of the rows
        (for the report's information only).

    Returns
    -------
    exudyn_worm.analysis.charts.stabilitychart.StabilityChart
    """
    from exudyn_worm.analysis.charts.stabilitychart import ComputeStabilityChart
    gear, J2 = _Set25()
    xRange, yRange = DisplayedDomain() if displayed else (X_RANGE, Y_RANGE)
    return ComputeStabilityChart(gear, J2, DV, DTV, xRange=xRange, yRange=yRange, resolution=RESOLUTION, S=S)


def DisplayedDomain() -> Tuple[Tuple[float, float], Tuple[float, float]]:
    """The area of Figures 4 and 5 from the ranges section 2.3 states: J1 from 1e-6 to 1e-3 kg*m^2 and kT from
    5e-3 to 5 N*m on set (25).

    Returns
    -------
    ((float, float), (float, float))
        x range kT/(kV r1^2) and y range J1/J2.
    """
    p = GetPreset('chart')
    k = p['kV'] * p['r1']**2
    return (5e-3 / k, 5. / k), (1e-6 / p['J2'], 1e-3 / p['J2'])


def _Steps(chart) -> Tuple[float, float]:
    return (float(np.mean(np.diff(np.log10(chart.x)))), float(np.mean(np.diff(np.log10(chart.y)))))


def Area(chart) -> float:
    """Unstable area in log10-log10 coordinates (decades^2): unstable grid cells times the cell size.

    Parameters
    ----------
    chart : StabilityChart

    Returns
    -------
    float
    """
    dx, dy = _Steps(chart)
    return float(np.count_nonzero(chart.unstable)) * dx * dy


def XExtent(chart) -> float:
    """Extent of the unstable set along x in log10 decades.

    Parameters
    ----------
    chart : StabilityChart
        A chart of :func:`Chart`.

    Returns
    -------
    float
        log10(max x / min x) over the unstable points; 0 if nothing is unstable.
    """
    rng = chart.unstableXRange
    return 0. if rng is None else math.log10(rng[1] / rng[0])


def SmallXYExtent(chart, xMax: float = SMALL_X) -> float:
    """Mean log10 extent of the unstable y (J1/J2) over the grid columns with x < ``xMax`` (empty columns count 0).

    Parameters
    ----------
    chart : StabilityChart
    xMax : float, optional
        Column limit.

    Returns
    -------
    float
    """
    logY = np.log10(chart.y)
    extents = []
    for j in np.nonzero(chart.x < xMax)[0]:
        col = chart.unstable[:, j]
        extents.append(float(logY[col].max() - logY[col].min()) if col.any() else 0.)
    return float(np.mean(extents)) if extents else 0.


def Tail(chart: 'StabilityChart', bound: float) -> Optional[Dict[str, object]]:
    """Where the unstable set ends along x, measured from a stated bound: the width of the tail beyond it.

    Parameters
    ----------
    chart : StabilityChart
        A chart (``unstable[i, j]`` at ``(x[j], y[i])``, with ``unstableXRange``).
    bound : float
        The stated bound X of the stiffness ratio, > 0.

    Returns
    -------
    dict or None
        None if nothing is unstable; else ``end`` (the upper end of the unstable x range), ``decades``
        (log10(end / bound): the tail's width beyond the bound, negative where the set ends before it), ``band``
        (the J1/J2 range of the unstable points in the last unstable grid column: where the band ends) and
        ``edges`` (the chart's sides that the band's end touches, among 'right', 'top', 'bottom': there it
        continues beyond the chart).

    Raises
    ------
    ValueError
        If ``bound`` is not > 0.
    """
    if not bound > 0:
        raise ValueError(f"Tail: 'bound' must be a stiffness ratio > 0, got {bound!r}")
    rng = chart.unstableXRange
    if rng is None:
        return None
    j = int(np.nonzero(chart.unstable.any(axis=0))[0][-1])
    rows = np.nonzero(chart.unstable[:, j])[0]
    return {'end': float(rng[1]), 'decades': math.log10(rng[1] / bound),
            'band': (float(chart.y[rows[0]]), float(chart.y[rows[-1]])),
            'edges': [side for side, touches in (('right', j == chart.x.size - 1), ('top', rows[-1] == chart.y.size - 1),
                                                 ('bottom', rows[0] == 0)) if touches]}


def TailText(chart: 'StabilityChart', bound: float) -> str:
    """:func:`Tail` in words, for a row's detail and the report.

    Parameters
    ----------
    chart : StabilityChart
        A chart.
    bound : float
        The stated bound X, > 0.

    Returns
    -------
    str
    """
    tail = Tail(chart, bound)
    if tail is None:
        return 'nothing unstable'
    (y0, y1), d = tail['band'], tail['decades']
    where = f'{d:.3f} decades beyond {bound:g}' if d > 0 else f'{-d:.3f} decades before {bound:g}'
    return (f"the unstable band ends at x = {tail['end']:.4g} ({where}), at J1/J2 {y0:.3g} .. {y1:.3g}"
            + (f" (at the {' and '.join(tail['edges'])} edge of the chart: it continues beyond)" if tail['edges'] else ''))


def _Increasing(values: List[float]) -> bool:
    return all(a < b for a, b in zip(values, values[1:]))


def _Upper(chart) -> float:
    return math.nan if chart.unstableXRange is None else chart.unstableXRange[1]


def StatementValues(c14: Dict[float, object], c56: Dict[float, object], cSp: Sequence[object],
                    bound: Dict[float, object], area: Callable = Area, xExtent: Callable = XExtent,
                    smallExtent: Callable = SmallXYExtent, fmt: str = '.3f',
                    extentUnit: str = ' decades', yLabel: str = 'mean log10 y-extent') -> Dict[str, Tuple[float, str]]:
    """The values of the eleven section 2.3 statements from a set of charts and one reading's measures.

    The one place where the statements are turned into numbers: the wide-domain rows (``chart_<key>``) and the
    paper-domain rows of both axis readings (``chart_paper_<reading>_<key>``, :mod:`validation.charts_paper`)
    call it with their charts and measures.

    Parameters
    ----------
    c14 : dict
        ``{D_TV: chart}`` at D_V = 0.014 for every value of :data:`DTV_VALUES`.
    c56 : dict
        ``{D_TV: chart}`` at D_V = 0.056 for D_TV = 1, 5, 25.
    cSp : sequence
        The S = +1 charts at D_V = 0.014 (D_TV = 1, 5, 25).
    bound : dict
        ``{D_TV: chart}`` at D_V = 0.014 whose upper unstable x end is the bound (D_TV = 1, 5, 25).
    area, xExtent, smallExtent : callable, optional
        The reading's measures: ``chart -> float`` for the unstable area, the extent along x and the mean J1/J2
        extent for x < 0.10 (default: the log10 measures of this module).
    fmt : str, optional
        Format of the areas and extents in the details.
    extentUnit : str, optional
        Unit of the x extents in the details.
    yLabel : str, optional
        Name of the J1/J2 extent measure in the details.

    Returns
    -------
    dict
        ``{key: (value, detail)}`` with the keys of the rows without their ``chart_`` prefix, in row order.
    """
    area14 = {d: area(c) for d, c in c14.items()}
    area56 = {d: area(c) for d, c in c56.items()}
    areas = ', '.join(f'D_TV = {d:g}: {a:{fmt}}' for d, a in area14.items())
    small = {d: smallExtent(c14[d]) for d in (1., 5., 25.)}
    x5, x5_56 = xExtent(c14[5.]), xExtent(c56[5.])
    ratioFmt = '.4f' if fmt == '.3f' else '.4g'
    return {
        **{key: (_Upper(bound[DTV]), '') for key, DTV in BOUND_DTV.items()},
        'DTV1_smallest': (float(all(area14[1.] < a for d, a in area14.items() if d != 1.)), f'areas {areas}'),
        'broadens_smaller_DTV': (float(_Increasing([area14[1.], area14[0.5], area14[0.2]])), f'areas {areas}'),
        'broadens_bigger_DTV': (float(_Increasing([area14[1.], area14[5.], area14[25.]])), f'areas {areas}'),
        'small_x_broadens': (float(_Increasing([small[1.], small[5.], small[25.]])),
                             f'{yLabel} for x < 0.10: ' + ', '.join(f'D_TV = {d:g}: {e:{fmt}}'
                                                                         for d, e in small.items())),
        'DV056_smaller': (float(all(area56[d] < area14[d] for d in area56)),
                          'areas at D_V = 0.056 / 0.014: ' + ', '.join(f'D_TV = {d:g}: {area56[d]:{fmt}} / '
                                                                       f'{area14[d]:{fmt}}' for d in area56)),
        'DV056_DTV25_vanishes': (area56[25.] / area14[25.] if area14[25.] > 0 else math.nan,
                                 f'areas {area56[25.]:{ratioFmt}} / {area14[25.]:{ratioFmt}}'),
        'DV056_DTV5_shorter': (x5 / x5_56 if x5_56 > 0 else math.inf, f'x-extents {x5:{fmt}} / {x5_56:{fmt}}{extentUnit}'),
        'no_unstable_Sp': (float(sum(np.count_nonzero(c.unstable) for c in cSp)), ''),
    }


def ChartChecks(ctx: ValidationContext) -> List[Check]:
    """Group ``charts``: the statements of section 2.3 about Figures 4 (D_V = 0.014) and 5 (D_V = 0.056)."""
    from exudyn_worm.progress import ProgressBar
    todo = [(0.014, d, -1) for d in DTV_VALUES] + [(0.056, d, -1) for d in (1., 5., 25.)] \
        + [(0.014, d, +1) for d in (1., 5., 25.)]
    with ProgressBar(total=len(todo), desc='charts', unit='chart', quiet=ctx.quiet, leave=False) as bar:
        for key in todo:
            Chart(*key)
            bar.update(1)
    c14 = {d: Chart(0.014, d) for d in DTV_VALUES}
    c56 = {d: Chart(0.056, d) for d in (1., 5., 25.)}
    area14 = {d: Area(c) for d, c in c14.items()}
    area56 = {d: Area(c) for d, c in c56.items()}
    values = StatementValues(c14, c56, [Chart(0.014, d, +1) for d in (1., 5., 25.)], c14)
    checks = [ctx.Compare('chart_' + key, value, uses=(), detail='; '.join(filter(None, [detail, TailText(
        c14[BOUND_DTV[key]], ctx.Row('chart_' + key).published) if key in BOUND_DTV else ''])))
        for key, (value, detail) in values.items()]
    small = {d: SmallXYExtent(c14[d]) for d in (1., 5., 25.)}
    _Section(ctx, checks, c14, c56, area14, area56, small)
    return checks


def _Range(rng, like='0.000') -> str:
    return 'none' if rng is None else f'{Fmt(rng[0], like)} .. {Fmt(rng[1], like)}'


def _MeasureTable(charts: Dict) -> List[str]:
    rows = ['| D_V | D_TV | unstable x range | unstable J1/J2 range | area (decades^2) | x extent (decades) | '
            'mean y extent, x < 0.10 | touches the domain edge |', '|---|---|---|---|---|---|---|---|']
    for (DV, d), c in charts.items():
        rows.append(f'| {DV} | {d:g} | {_Range(c.unstableXRange)} | {_Range(c.unstableYRange)} | {Area(c):.3f} | '
                    f'{XExtent(c):.3f} | {SmallXYExtent(c):.3f} | {", ".join(c.clippedSides) or "no"} |')
    return rows


def _Section(ctx, checks, c14: Dict, c56: Dict, area14: Dict, area56: Dict, small: Dict) -> None:
    fixed = {**{(0.014, d): c for d, c in c14.items()}, **{(0.056, d): c for d, c in c56.items()}}
    shown = {key: Chart(*key, S=-1, displayed=True) for key in fixed}
    (x0, x1), (y0, y1) = DisplayedDomain()
    passed = [c for c in checks if c.verdict == 'PASS']
    other = [c for c in checks if c.verdict != 'PASS']
    clipped = [key for key, c in fixed.items() if c.clippedSides]
    ctx.AddSection('Stability charts: what the section 2.3 rows measured', f"""
Set (25) with mu = 0.132, x = kT/(kV r1^2) from 1e-4 to 1e2, y = J1/J2 from 1e-6 to 1, {RESOLUTION} x {RESOLUTION}
log grid (0.01 decade per step), S = -1 unless stated, from `exudyn_worm.analysis.charts.stabilitychart.ComputeStabilityChart` (the domain
and the measures fixed in validation/README.md before the results):

{chr(10).join(_MeasureTable(fixed))}

Generated from the verdicts: {len(passed)} of {len(checks)} statements of section 2.3 hold under their reading
rules ({', '.join(f'`{c.id}`' for c in passed) or 'none'}); {'none fails' if not other else 'not holding: ' +
'; '.join(f'`{c.id}` ({c.verdict}: computed {Fmt(c.computed, c.row.publishedText)}, accepted {c.IntervalText()})' for c in other)}.
{len(clipped)} of the {len(fixed)} unstable sets touch an edge of the fixed domain
({', '.join(f'D_V = {DV}, D_TV = {d:g}' for DV, d in clipped) or 'none'}): there the region continues beyond the
chart and the areas and extents are clipped.

The same measures on the area the paper displays, from the ranges section 2.3 states (J1 from 1e-6 to 1e-3
kg*m^2, kT from 5e-3 to 5 N*m): x from {x0:.3g} to {x1:.3g}, y from {y0:.3g} to {y1:.3g} (the rows above take no
verdict from it; the rows `chart_paper_*` do, under log and linear axes, in their own section):

{chr(10).join(_MeasureTable(shown))}
""")
