"""Text tables of ``exudyn-worm chart``: the stability charts and the speed chart (the numbers come from
:mod:`exudyn_worm.analysis.charts.stabilitychart` and :mod:`exudyn_worm.analysis.charts.speedchart`; this module only formats them).
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Dict, List, Optional, Sequence

if TYPE_CHECKING:
    from ..analysis.charts.stabilitychart import StabilityChart
    from ..analysis.charts.speedchart import SpeedChart

__all__ = ['FormatChartTable', 'FormatSpeedChart']


def FormatSpeedChart(chart: 'SpeedChart', source: str) -> List[str]:
    """The text of ``chart --speed``: a row per speed (one real part per direction of the duty), the unstable
    ranges per direction and the verdict at the drive's own operating points.

    Parameters
    ----------
    chart : SpeedChart
        From :func:`~exudyn_worm.analysis.charts.speedchart.SpeedStabilityChart`.
    source : str
        Where the drive came from (first line).

    Returns
    -------
    list of str
    """
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.charts.speedchart import RPM
    from ..analysis.stability.drivestability import VerdictWord
    model = ('eq. (16) extended by the friction slope' if chart.model == 'analytical' else
             f"the linearized whole drive: it has {' and '.join(chart.components)}")
    lines = [f"exudyn-worm chart --speed: {source}; {chart.frictionLaw} friction law; each direction of the duty at "
             f"its load torque, linearized at each speed ({model})"]
    heads = [f"{c.phase} Re [1/s]" for c in chart.curves]
    lines.append(f"  {'motor [rpm]':>11} {'v0 [m/s]':>9} {'mu(v0)':>8} {'dmu/dv [s/m]':>13} "
                 + ' '.join(f'{h:>18}' for h in heads) + '  verdict')
    for i, (n, v, mu, slope) in enumerate(zip(chart.motorSpeeds / RPM, chart.slidingSpeeds, chart.mu, chart.dmuDv)):
        res = [c.maxRealPart[i] for c in chart.curves]
        bad = [c.phase for c, r in zip(chart.curves, res) if r > 0]
        lines.append(f"  {n:11.4g} {v:9.4g} {mu:8.4g} {slope:13.4g} " + ' '.join(f'{r:18.4g}' for r in res)
                     + ('  CHATTER while ' + ', '.join(bad) if bad else '  stable'))
    for c in chart.curves:
        ranges, bounds = c.unstableRanges, c.Boundaries()
        what = f"{c.phase} (S = {c.S:+d}, load torque {c.loadTorque:.4g} N*m)"
        lines.append(f"Chatter while {what} at " + ', '.join(f'{a / RPM:.4g} to {b / RPM:.4g} rpm' for a, b in ranges)
                     + (' (of the speeds computed; boundaries near ' + ', '.join(f'{b / RPM:.4g}' for b in bounds)
                        + ' rpm)' if bounds else '') if ranges else
                     f"No chatter while {what} at any of these speeds.")
    if chart.ownPoints:
        lines.append("At the drive's own operating points (the verdict of exudyn-worm stability): "
                     + '; '.join(f"{p.point.Label()}: {VerdictWord(p.stable, p.instability)} ({p.growthText})"
                                 for p in chart.ownPoints)
                     + f"; the drive is {VerdictWord(chart.stable, _Instability(chart))}")
    else:
        lines.append("The drive has no motor: no operating point of its own (the load is taken at every speed).")
    return lines


def _Instability(chart: 'SpeedChart'):
    """The instability of the own point with the largest real part (None: stable)."""
    unstable = [p for p in chart.ownPoints if not p.stable]
    return max(unstable, key=lambda p: p.maxRealPart).instability if unstable else None


def FormatChartTable(charts: Sequence[StabilityChart], points: Optional[Dict[str, Dict[str, float]]] = None
                     ) -> List[str]:
    """Text table of charts: D_V, D_TV, unstable x and y ranges, unstable fraction, clipped sides, and the
    verdict at each point.

    Parameters
    ----------
    charts : sequence of StabilityChart
        The charts, one row each.
    points : dict, optional
        ``{label: {'x', 'y', ...}}`` (e.g. :func:`~exudyn_worm.analysis.charts.stabilitychart.PresetChartPoints`): each chart's exact verdict at the
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
