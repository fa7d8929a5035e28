"""Text tables of stability charts: what ``exudyn-worm chart`` prints (the numbers come from
:mod:`exudyn_worm.analysis.charts`; this module only formats them).
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Dict, List, Optional, Sequence

if TYPE_CHECKING:
    from .charts import StabilityChart

__all__ = ['FormatChartTable']


def FormatChartTable(charts: Sequence[StabilityChart], points: Optional[Dict[str, Dict[str, float]]] = None
                     ) -> List[str]:
    """Text table of charts: D_V, D_TV, unstable x and y ranges, unstable fraction, clipped sides, and the
    verdict at each point.

    Parameters
    ----------
    charts : sequence of StabilityChart
        The charts, one row each.
    points : dict, optional
        ``{label: {'x', 'y', ...}}`` (e.g. :func:`~exudyn_worm.analysis.charts.PresetChartPoints`): each chart's exact verdict at the
        point's (x, y) is listed (U unstable, s stable).

    Returns
    -------
    list of str
        The lines.
    """
    r = lambda t: 'none' if t is None else f'{t[0]:.4g} .. {t[1]:.4g}'
    points = points or {}
    head = (f"{'D_V':>7} {'D_TV':>6} {'S':>3}  {'unstable kT/(kV r1^2)':>22}  {'unstable J1/J2':>22}  "
            f"{'fraction':>8}  {'clipped at':<12}" + ''.join(f' {k:>3}' for k in points))
    lines = [head]
    for c in charts:
        marks = ''.join(f" {'U' if c.IsUnstable(p['x'], p['y']) else 's':>3}" for p in points.values())
        lines.append(f"{c.DV:>7.4g} {c.DTV:>6g} {c.S:>+3d}  {r(c.unstableXRange):>22}  {r(c.unstableYRange):>22}  "
                     f"{c.unstableFraction:>8.4f}  {', '.join(c.clippedSides) or '-':<12}" + marks)
    return lines
