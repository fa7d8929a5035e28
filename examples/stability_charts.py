"""The paper's stability charts (section 2.3): Figures 3, 4 and 5 as PNG files.

==========  ===================================================================  ==============================
figure      content                                                              file
==========  ===================================================================  ==============================
3           first criterion (20) with dT = 0: J1/J2 limit against the pitch      fig03_first_criterion.png
            angle gamma, friction angles rho = 4 ... 10 deg (u = 63, set (25)),
            from gamma = atan(1/u) = 0.91 deg (a smaller one: worm above wheel)
4           second criterion (17), (19), S = -1, D_V = 0.014, D_TV = 1, 5, 25    fig04_chart_DV0.014.png
5           the same for D_V = 0.056                                             fig05_chart_DV0.056.png
==========  ===================================================================  ==============================

The charts use the gear of parameter set (25) (preset 'chart', J2 = 0.1 kg*m^2); x = kT/(kV r1^2) and
y = J1/J2 are swept on log grids over the domain fixed in validation/README.md (1e-4..1e2, 1e-6..1), the
damping follows eqs. (22)-(24). The points P1-P7 (presets reel-P1 ... reel-P7, set (28) and its
variations) are marked at their chart coordinates: the chart is dimensionless, and sets (25) and (28)
share angles and friction (their r2/r1 differ by 0.05 %); the legend says so. P1-P5 and P7 have D_TV = 1;
P6 has D_TV = 2 (section 3.2.4): its own boundary is drawn dashed. Each unstable region is hatched in its
chart's colour (crossed hatches where regions overlap); a point closer than ZOOM_DECADES to the boundary of a
chart on which it is stable (P3 and P5 next to D_TV = 25 in Figure 4; :func:`PointsToZoom`) is shown again in a
zoomed inset whose title gives its verdict on every chart and its distance to that boundary.

Run ``python examples/stability_charts.py --out DIR``. The computation (:func:`ComputeFigures`,
:func:`Summary`) is importable and checked by ``tests/test_example_stability_charts.py``; only
:func:`main` writes files.
"""
from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import Dict, List, Optional, Sequence

import numpy as np

from exudyn_worm.analysis.charts.stabilitychart import (ComputeStabilityChart, FirstCriterionChart, FirstCriterionCurves, PresetChartPoints,
                                StabilityChart)
from exudyn_worm.cli.formatchart import FormatChartTable
from exudyn_worm._checks import CheckOutputFolder
from exudyn_worm.plotting.plot_charts import ZOOM_DECADES, PointsToZoom
from exudyn_worm.drive.presets import GearFromParameters, GetPreset

__all__ = ['CHART_PRESET', 'FIGURE_DV', 'DTV_VALUES', 'POINT_PRESETS', 'FIGURE3_RHO_DEG', 'ZOOM_DECADES',
           'Figure3PitchAngles', 'ComputeFigures', 'Summary', 'FormatSummary', 'DrawFigures', 'WriteFigures', 'PointsToZoom', 'main']

#: the gear of parameter set (25)
CHART_PRESET = 'chart'
#: D_V of Figures 4 and 5
FIGURE_DV = {4: 0.014, 5: 0.056}
#: damping ratios drawn in Figures 4 and 5
DTV_VALUES = (1., 5., 25.)
#: presets marked as points P1-P7
POINT_PRESETS = tuple(f'reel-P{k}' for k in range(1, 8))
#: friction angles of Figure 3 in degrees (the paper does not list its values: a range around rho = 8 deg)
FIGURE3_RHO_DEG = (4., 6., 8., 10.)
#: default grid points per axis of Figures 4 and 5
RESOLUTION = 600


def Figure3PitchAngles(ratio: float, points: int = 400) -> np.ndarray:
    """The pitch angles of Figure 3 in rad: from the smallest at which the worm is no larger than the wheel, up to
    10 deg.

    Figure 3 keeps the ratio u of set (25); a gear of ratio u has r2/r1 = u tan(gamma) (eq. (3)), so below
    gamma = atan(1/u) (0.91 deg for u = 63) its worm would be larger than its wheel, which no worm gear is (the
    gear check warns about each such gear).

    Parameters
    ----------
    ratio : float
        The transmission ratio u, > 1.
    points : int
        Number of angles.

    Returns
    -------
    ndarray
        Evenly spaced pitch angles in rad.
    """
    return np.linspace(math.atan(1. / ratio), math.radians(10.), points)


def ComputeFigures(resolution: int = RESOLUTION) -> Dict:
    """Compute the data of Figures 3, 4 and 5.

    Parameters
    ----------
    resolution : int, optional
        Grid points per axis of the charts.

    Returns
    -------
    dict
        ``{3: FirstCriterionCurves, 4: [StabilityChart per D_TV], 5: [...], 'points': {label: coords},
        'P6': {4: chart, 5: chart}}`` (the charts of P6's own D_TV = 2).
    """
    parameters = GetPreset(CHART_PRESET)
    gear = GearFromParameters(parameters, meshDamping=False)
    out: Dict = {3: FirstCriterionChart(gear, Figure3PitchAngles(gear.ratio), np.radians(FIGURE3_RHO_DEG))}
    for figure, DV in FIGURE_DV.items():
        out[figure] = [ComputeStabilityChart(gear, parameters['J2'], DV, DTV, resolution=resolution)
                       for DTV in DTV_VALUES]
    out['points'] = PresetChartPoints(POINT_PRESETS)
    # P6 has D_TV = 2 (section 3.2.4): its own boundary is drawn dashed in both figures
    out['P6'] = {figure: ComputeStabilityChart(gear, parameters['J2'], DV, out['points']['P6']['DTV'],
                                               resolution=resolution) for figure, DV in FIGURE_DV.items()}
    return out


def Summary(figures: Dict) -> List[Dict]:
    """One row per chart: D_V, D_TV, unstable x and y ranges, unstable fraction, clipped sides.

    Parameters
    ----------
    figures : dict
        From :func:`ComputeFigures`.
    """
    return [dict(figure=figure, **chart.ToDict()) for figure in FIGURE_DV for chart in figures[figure]]


def FormatSummary(figures: Dict) -> str:
    """The charts of Figures 4 and 5 as a text table, with the verdict at P1-P7 (U unstable, s stable).

    Parameters
    ----------
    figures : dict
        From :func:`ComputeFigures`.
    """
    charts = [chart for figure in FIGURE_DV for chart in figures[figure]]
    return '\n'.join(FormatChartTable(charts, figures['points']))


def DrawFigures(figures: Dict) -> Dict[str, object]:
    """Draw Figures 3, 4 and 5 (nothing is written).

    Parameters
    ----------
    figures : dict
        From :func:`ComputeFigures`.

    Returns
    -------
    dict
        ``{file name: matplotlib Figure}``.
    """
    from exudyn_worm.plotting.plot_charts import PlotFirstCriterion, PlotStabilityCharts

    curves: FirstCriterionCurves = figures[3]
    gear = GearFromParameters(GetPreset(CHART_PRESET), meshDamping=False)
    design = {'set (25)': (gear.gamma, curves.limit[list(np.degrees(curves.rho)).index(8.)][
        np.argmin(np.abs(curves.gamma - gear.gamma))])} if 8. in FIGURE3_RHO_DEG else None
    ax = PlotFirstCriterion(curves, mark=design,
                            title=f'Fig. 3: first criterion (20) with $d_T$ = 0, $u$ = {curves.ratio:.4g} '
                                  f'(set (25)): stable above the lines')
    drawn = {'fig03_first_criterion.png': ax.figure}
    points = {label: c for label, c in figures['points'].items()}
    other = ', '.join(f'{k}: {c["DTV"]:g}' for k, c in points.items() if not math.isclose(c['DTV'], 1.))
    pointsLabel = ('P1-P7: reel-changer drives of set (28), at their (x, y);\n'
                   'set (28) has the gear of set (25) (same angles, friction;\n'
                   fr'$r_2/r_1$ 0.05 % apart); $D_{{TV}}$ = 1' + (f' ({other})' if other else ''))
    for figure, DV in FIGURE_DV.items():
        charts: List[StabilityChart] = figures[figure]
        p6 = figures['P6'][figure]
        # a point the main axes cannot resolve from a boundary it is not inside gets an inset (P3 in Fig. 4)
        ax = PlotStabilityCharts(charts, points={k: (c['x'], c['y']) for k, c in points.items()},
                                 title=f'Fig. {figure}: stability chart for $D_V$ = {DV:g}, $S$ = -1, '
                                       f'criteria (17) and (19), set (25)', pointsLabel=pointsLabel,
                                 outlines=[(p6, fr'$D_{{TV}}$ = {p6.DTV:g} (P6): boundary only')],
                                 zoom=PointsToZoom(charts, points))
        drawn[f'fig{figure:02d}_chart_DV{DV:g}.png'] = ax.figure
    return drawn


def WriteFigures(figures: Dict, outDir) -> List[Path]:
    """Draw Figures 3, 4 and 5 (:func:`DrawFigures`) and save them as PNG files in ``outDir``.

    Parameters
    ----------
    figures : dict
        From :func:`ComputeFigures`.
    outDir : str or Path
        Output folder (created if missing).

    Returns
    -------
    list of Path
        The files written.
    """
    from exudyn_worm.plotting.plot import SaveFigure
    return [SaveFigure(fig, Path(outDir) / name) for name, fig in DrawFigures(figures).items()]


class _Parser1Line(argparse.ArgumentParser):
    """Argument errors as one line on stderr (exit status 2), without the usage block."""

    def error(self, message):
        self.exit(2, f'{self.prog}: error: {message} (see --help)\n')


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Command line: compute the charts, print the summary, write the figures. Returns the exit status.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments (default: ``sys.argv[1:]``).
    """
    parser = _Parser1Line(prog='stability_charts.py', description=__doc__.split('\n\n')[0])
    parser.add_argument('--out', required=True, metavar='DIR', help='folder for the PNG files (created if missing)')
    parser.add_argument('--resolution', type=int, default=RESOLUTION, metavar='N',
                        help=f'grid points per axis of Figures 4 and 5 (default: {RESOLUTION})')
    args = parser.parse_args(argv)
    try:
        if not 2 <= args.resolution <= 20000:
            raise ValueError(f'--resolution must be in [2, 20000], got {args.resolution}')
        folder = CheckOutputFolder(parser.prog, '--out', args.out)      # created here, before computing
    except ValueError as error:
        print(f'{parser.prog}: error: {error}', file=sys.stderr)
        return 2
    figures = ComputeFigures(args.resolution)
    print(FormatSummary(figures))
    print(f'\nwriting figures to {folder}')
    for path in WriteFigures(figures, folder):
        print(f'  {path.name}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
