"""``exudyn-worm chart``: stability charts (Figures 4 and 5) of the gear of a parameter set, or (``--speed``) the
drive's stability over motor speed at the load of its own duty.

The gear (angles, friction, r1, r2, kV) and J2 come from the preset/config/``--set``; J1, kT and the damping
constants are what the chart sweeps (x = kT/(kV r1^2), y = J1/J2, D_T = D_TV D_V), so they need not be given.
When they are (a whole drive), the drive itself is marked on its chart, with its own verdict at its operating
points.
"""
from __future__ import annotations

import argparse
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, List

from .main import (_LazyHelp, AddOverwriteOption, BadInput, CheckFigurePath, ParametersFromArgs, PrintJson, SourceInfo, SourceText, Subcommand, UsageError, WholeDriveFromArgs)
from .formatchart import FormatChartTable, FormatSpeedChart
from .._files import WriteAtomically

__all__ = ['COMMAND', 'PAPER_DTV']

#: D_TV values of the paper's Figures 4 and 5 (the default of --DTV)
PAPER_DTV = (1., 5., 25.)


def _AddArguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument('--DV', type=float, default=None, metavar='D_V',
                        help="mesh damping measure D_V of eq. (23) (default: the parameter set's, from DV or dV)")
    parser.add_argument('--DTV', type=float, nargs='+', default=list(PAPER_DTV), metavar='D_TV',
                        help='one or more damping ratios D_TV = D_T/D_V, one chart each (default: 1 5 25)')
    for k, (option, kwargs, text) in enumerate((
            ('--x-range', dict(type=float, nargs=2, metavar=('MIN', 'MAX')), 'stiffness-ratio range kT/(kV r1^2)'),
            ('--y-range', dict(type=float, nargs=2, metavar=('MIN', 'MAX')), 'inertia-ratio range J1/J2'),
            ('--resolution', dict(type=int, metavar='N'), 'grid points per axis'))):
        action = parser.add_argument(option, default=None, help=text + ' (default: %(text)s)', **kwargs)
        action.text = _LazyHelp(lambda k=k: str(_Defaults()[k]))
    parser.add_argument('--S', type=int, choices=(-1, 1), default=-1, dest='S',
                        help='contact state: -1 (load lowering, the paper\'s charts; default) or +1')
    parser.add_argument('--points', nargs='+', default=[], metavar='NAME',
                        help='presets to mark at their chart coordinates, e.g. reel-P1 reel-P2 (or P1 P2); '
                             'their verdict on each chart is listed (a whole drive given with --config, --preset '
                             'or --set is marked too, labelled by its file or preset)')
    parser.add_argument('--output', default=None, metavar='FILE.png',
                        help='draw the charts (one axes, one region per D_TV) into FILE (.png, .pdf or .svg)')
    AddOverwriteOption(parser, 'the --output file')
    parser.add_argument('--quiet', action='store_true', help='no progress bar on stderr')
    parser.add_argument('--speed', default=None, metavar='SPEC',
                        help="instead of the J1-kT chart: the largest real part of each direction of the drive's "
                             "duty (lifting, lowering) against motor speed, at the load torque of its operating "
                             "points (the two-mass drive: eq. (16) with the friction slope; any other drive: its "
                             "linearized whole drive); with a speed-dependent friction law the drive may chatter "
                             "only in a speed range. SPEC as 'sweep --vary motorSpeed=SPEC' takes it: "
                             "START:STOP:COUNT[:log] or a list, e.g. '20rpm:2000rpm:40:log'")


def _PresetName(name: str) -> str:
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..drive.presets import PRESETS
    # a point needs J1 and kT: the 'chart' preset has neither (it is the gear the chart is drawn for)
    drives = [p for p in PRESETS if p != 'chart']
    if name in drives:
        return name
    if f'reel-{name}' in drives:
        return f'reel-{name}'
    why = " ('chart' is the gear of the chart, it has no J1 or kT to mark)" if name == 'chart' else ''
    raise UsageError(f"--points: '{name}' is not a drive to mark{why}; expected one of: {', '.join(drives)} "
                     f"(or P1 ... P7 for reel-P1 ... reel-P7)")


def _MeshDampingMeasure(parameters: Dict[str, float], gear) -> float:
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..model.drive import MeshDampingMeasure
    if 'DV' in parameters:
        return parameters['DV']
    if 'dV' in parameters:
        return MeshDampingMeasure(parameters['dV'], gear.kV, gear.r2, parameters['J2'])
    raise UsageError("give --DV (the parameter set has neither 'DV' nor 'dV')")


def _RunSpeed(args: argparse.Namespace) -> int:
    """``chart --speed SPEC``: the drive's stability over motor speed at the load of its own duty
    (:mod:`exudyn_worm.analysis.charts.speedchart`)."""
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.charts.speedchart import SpeedStabilityChart
    from ..analysis.studies.studygrid import ParseVariation
    from ..progress import ProgressBar
    output = CheckFigurePath(args.output, '--output', args.overwrite) if args.output else None
    drive = WholeDriveFromArgs(args)
    with BadInput():
        spec = args.speed.strip()
        variation = ParseVariation(f'motorSpeed={spec}')
        with ProgressBar(desc='chart over speed', unit='point', quiet=True if args.quiet else None) as bar:
            chart = SpeedStabilityChart(drive, variation.values, progress=bar.update)
    if output:
        # lazy: start-up (exudyn-worm --help imports every command module)
        from ..plotting.plot import SaveFigure
        ax = chart.plot(title=f'{SourceText(args)}: stability over motor speed ({chart.frictionLaw} friction)')
        path = WriteAtomically(output, lambda tmp: SaveFigure(ax.figure, tmp))
        print(f'wrote {path.resolve()}', file=sys.stderr)
    if args.json:
        PrintJson(chart.ToDict())
        return 0
    print('\n'.join(FormatSpeedChart(chart, SourceText(args))))
    return 0


def _ChartDrive(args: argparse.Namespace, parameters: Dict[str, float]):
    """(the user's own drive, its label on the chart), or (None, None) for the gear of a chart alone.

    A complete drive (J1, kT and the shaft damping given: a drive file, a preset, ``--set``) is the user's own
    drive, marked at its chart coordinates. The gear of a chart alone (no J1 or kT, which the chart sweeps) is no
    drive: nothing is marked, and nothing is made up to build one.
    """
    if 'J1' not in parameters or 'kT' not in parameters or not any(k in parameters for k in ('dT', 'DT', 'DTV')):
        return None, None
    info = SourceInfo(args)
    label = (Path(info['config']).stem if info['config'] else (info['preset'] or 'drive').replace('reel-', ''))
    if info['overrides']:
        label += ' (--set)'
    return WholeDriveFromArgs(args), label


@dataclass(frozen=True)
class _OwnVerdict:
    """The marked drive's own verdict at the operating points of its duty (as ``exudyn-worm stability``)."""
    drive: object
    label: str

    def ToDict(self) -> Dict:
        # lazy: start-up (exudyn-worm --help imports every command module)
        from ..analysis.charts.stabilitychart import ChartCoordinates
        from ..analysis.stability.drivestability import AnalyzeDrive
        analysis = AnalyzeDrive(self.drive)
        return {'label': self.label, **ChartCoordinates(self.drive.elastic), 'stable': analysis.stable,
                'instability': analysis.instability, 'maxRealPart': analysis.maxRealPart,
                'decidingText': analysis.decidingText, 'components': [c.text for c in self.drive.components],
                'cause': analysis.CauseText()}

    def Text(self) -> str:
        # lazy: start-up (exudyn-worm --help imports every command module)
        from ..analysis.stability.drivestability import VerdictWord
        d = self.ToDict()
        parts = f"; it has {' and '.join(d['components'])}, which the chart does not" if d['components'] else ''
        return (f"this drive ({self.label}) is marked at x = {d['x']:.4g}, y = {d['y']:.4g} (own D_V = {d['DV']:.4g}, "
                f"D_TV = {d['DTV']:.4g}){parts}; its verdict at the operating points of its duty (as exudyn-worm "
                f"stability, mu(v) and the whole drive): {VerdictWord(d['stable'], d['instability'])} "
                f"({d['decidingText']})" + (f"; {d['cause']}" if d['cause'] else ''))


def _Defaults():
    """The defaults of --x-range, --y-range and --resolution (the charts' own)."""
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.charts.stabilitychart import DEFAULT_RESOLUTION, DEFAULT_X_RANGE, DEFAULT_Y_RANGE
    return list(DEFAULT_X_RANGE), list(DEFAULT_Y_RANGE), DEFAULT_RESOLUTION


def _Run(args: argparse.Namespace) -> int:
    for name, default in zip(('x_range', 'y_range', 'resolution'), _Defaults()):
        if getattr(args, name) is None:
            setattr(args, name, default)
    if args.speed is not None:
        return _RunSpeed(args)
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.charts.stabilitychart import MAX_CHART_POINTS, ChartCoordinates, ComputeStabilityChart, PresetChartPoints
    from ..drive.presets import ExtraComponents, GearFromParameters
    from ..params.parameters import MissingParameterError
    from ..progress import ProgressBar
    output = CheckFigurePath(args.output, '--output', args.overwrite) if args.output else None
    parameters = ParametersFromArgs(args)
    with BadInput():
        gear = GearFromParameters(parameters, meshDamping=False, where='chart')
        if 'J2' not in parameters:
            raise MissingParameterError("chart: missing parameter J2 (kg*m^2); give it with --set J2=VALUE or in the "
                                        "config file", ['J2'])
        J2 = parameters['J2']
        DV = args.DV if args.DV is not None else _MeshDampingMeasure(parameters, gear)
        points = PresetChartPoints([_PresetName(n) for n in args.points])
        drive, label = _ChartDrive(args, parameters)
        if label is not None:             # the user's own drive, at its chart coordinates
            points = {**{k: v for k, v in points.items() if k != label}, label: ChartCoordinates(drive.elastic)}
        # every argument is checked before the first chart is computed
        ComputeStabilityChart(gear, J2, DV, args.DTV[0], xRange=args.x_range, yRange=args.y_range, resolution=2,
                              S=args.S)
        for DTV in args.DTV[1:]:
            ComputeStabilityChart(gear, J2, DV, DTV, resolution=2, S=args.S)
        if not 2 <= args.resolution <= 20000 or args.resolution ** 2 > MAX_CHART_POINTS:
            ComputeStabilityChart(gear, J2, DV, args.DTV[0], resolution=args.resolution)
    components = drive.ComponentsText() if drive is not None else ' and '.join(ExtraComponents(parameters))
    if components:
        print(f"exudyn-worm chart: note: the chart is the two-mass drive of Figure 2 with this gear and J2; "
              f"{components} of the parameter set is not in it", file=sys.stderr)
    charts = []
    with ProgressBar(total=len(args.DTV), desc='charts', unit='chart', quiet=True if args.quiet else None) as bar:
        for DTV in args.DTV:
            charts.append(ComputeStabilityChart(gear, J2, DV, DTV, xRange=args.x_range, yRange=args.y_range,
                                                resolution=args.resolution, S=args.S))
            bar.update(1)
    if output:
        # lazy: start-up (exudyn-worm --help imports every command module)
        from ..plotting.plot import SaveFigure
        from ..plotting.plot_charts import PlotStabilityCharts
        ax = PlotStabilityCharts(charts, points={k: (p['x'], p['y']) for k, p in points.items()},
                                 note=f'gear: {SourceText(args)}, J2 = {J2:g} kg*m^2')
        path = WriteAtomically(output, lambda tmp: SaveFigure(ax.figure, tmp))
        print(f'wrote {path.resolve()}', file=sys.stderr)
    if args.json:
        entries: List[Dict] = []
        for c in charts:
            d = c.ToDict()
            if points:
                d['pointsUnstable'] = {k: bool(c.IsUnstable(p['x'], p['y'])) for k, p in points.items()}
            entries.append(d)
        data = {'charts': entries}
        if points:
            data['points'] = points
        if label is not None:
            data['drive'] = _OwnVerdict(drive, label).ToDict()
        PrintJson(data)
        return 0
    print(f"exudyn-worm chart: {SourceText(args)}; J2 = {J2:g} kg*m^2, {args.resolution} x {args.resolution} log grid, "
          f"x = kT/(kV r1^2) in [{args.x_range[0]:g}, {args.x_range[1]:g}], y = J1/J2 in "
          f"[{args.y_range[0]:g}, {args.y_range[1]:g}]")
    print('\n'.join(FormatChartTable(charts, points)))
    if points:
        print('points (U: unstable, s: stable on that chart, at the point\'s x and y): '
              + ', '.join(f"{k} x = {p['x']:.4g}, y = {p['y']:.4g} (own D_V = {p['DV']:.4g}, D_TV = {p['DTV']:.4g})"
                          for k, p in points.items()))
    if label is not None:
        print(_OwnVerdict(drive, label).Text())
    return 0


COMMAND = Subcommand('chart', 'stability charts (Figures 4, 5): unstable region over kT/(kV r1^2) and J1/J2',
                     _AddArguments, _Run)
