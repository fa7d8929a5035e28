"""``exudyn-worm sweep``: a parameter study of the reel changer on every core, on an MPI cluster or as a job array."""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from .main import (BadInput, InterruptedLine, CheckFigurePath, CheckOutputPath, ParametersFromArgs, PositiveInt, PrintJson, SourceText, StdoutToStderr, Subcommand, UsageError)
from .._files import WriteAtomically

__all__ = ['COMMAND']

#: the metric plotted by default, in the first window of the phase that decides the linear verdict
_DEFAULT_METRIC = 'maxAbsWheelAcceleration'


def _AddArguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument('--vary', action='append', default=[], metavar='KEY=SPEC', required=True,
                        help="vary one parameter: a grid KEY=START:STOP:COUNT (e.g. J1=0.01:0.4:8) or a list "
                             "with units (e.g. 'backlash=0,0.25mm,0.5mm'); repeatable: full factorial")
    parser.add_argument('--log', action='store_true', help='log spacing for the grids (or append :log to one grid)')
    parser.add_argument('--zip', action='store_true', help='pair the --vary values instead of the full factorial')
    parser.add_argument('--output', metavar='FILE.csv', default=None,
                        help='results table, one row per run, written as runs finish, with the sidecar '
                             'FILE.study.json; an existing one of the same study is resumed')
    parser.add_argument('--overwrite', action='store_true',
                        help='start --output afresh instead of resuming it; replace an existing --plot file')
    parser.add_argument('--workers', type=int, default=None, metavar='N',
                        help='worker processes (default: every available CPU)')
    parser.add_argument('--engine', choices=('process', 'mpi'), default='process',
                        help="process: a pool on this machine (default); mpi: mpi4py.futures.MPIPoolExecutor, run "
                             "under 'mpiexec -n N python -m mpi4py.futures -m exudyn_worm sweep ...'")
    parser.add_argument('--shard', metavar='i/N', default=None,
                        help='run only the runs i, i+N, i+2N, ... (0 <= i < N), e.g. one task of a job array')
    parser.add_argument('--max-runs', type=PositiveInt('runs'), default=None, metavar='N',
                        help='refuse a study (or shard) of more than N runs before any run, saying into how many '
                             'shards to split it (default 100000: the parent holds about 9 kB per run)')
    parser.add_argument('--end-time', type=float, default=None, metavar='S',
                        help='simulated time in s (default: one rotation of each run)')
    parser.add_argument('--step-size', type=float, default=None, metavar='S',
                        help="time step in s (default: each run's recommended step, 0.039 / its highest natural "
                             "frequency, as simulate)")
    parser.add_argument('--check-step', action=argparse.BooleanOptionalAction, default=None,
                        help="run each point again at half the step; a window whose chatter verdict changes is "
                             "'unresolved' (default: on for the runs whose linear margin is small, as simulate)")
    parser.add_argument('--max-steps', type=PositiveInt('steps'), default=None, metavar='N',
                        help='record as failed the runs of more solver steps than N (default 1e6, as simulate)')
    parser.add_argument('--windows', default=None, metavar='T0:T1,...',
                        help='evaluation windows in s (default: the lift / lower / lift phases of each run; for '
                             'another duty the phases of the first run\'s duty, the same windows for every run)')
    parser.add_argument('--plot', default=None, metavar='FILE.png',
                        help='one varied key: --metric against it; two: the chatter map over them (a stiffness '
                             'across and an inertia up, as the stability charts)')
    parser.add_argument('--metric', default=None, metavar='COLUMN',
                        help=f"column plotted against one varied key (default w{{i}}.{_DEFAULT_METRIC}: the "
                             f"largest |phi2''| in the first window i of the phase that decides the linear verdict "
                             f"of the first run, lifting or lowering; window 1, the lowering, for the reel changer)")
    parser.add_argument('--quiet', action='store_true', help='no progress bar')


def _Study(args: argparse.Namespace):
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..drive.duty import CheckSimulationKeys
    from ..analysis.studies.studygrid import ParseVariation, Study
    from .simulate import ParseWindows
    parameters = ParametersFromArgs(args)
    if args.overwrite and not (args.output or args.plot):
        raise UsageError("--overwrite only applies with --output FILE.csv or --plot FILE.png")
    if args.metric is not None and not args.plot:
        raise UsageError(f"--metric {args.metric} only applies with --plot FILE.png")
    with BadInput():
        variations = [ParseVariation(text, log=args.log) for text in args.vary]
        fixed = {text.split('=', 1)[0].strip() for text in args.set}
        both = [v.key for v in variations if v.key in fixed]
        if both:
            raise ValueError(f"'{both[0]}' is both set (--set) and varied (--vary); give it only once")
        CheckSimulationKeys({**parameters, **{v.key: v.values[0] for v in variations}}, 'sweep')
        windows = ParseWindows(args.windows) if args.windows else None
        for name in ('end_time', 'step_size'):
            value = getattr(args, name)
            if value is not None and not value > 0:
                raise ValueError(f"--{name.replace('_', '-')} must be > 0 s, got {value:g}")
        if windows and args.end_time is not None and max(t1 for _, t1 in windows) > args.end_time:
            raise ValueError(f"--windows: a window ends after --end-time = {args.end_time:g} s")
        return Study(parameters, variations, zipped=args.zip, windows=windows, endTime=args.end_time,
                     stepSize=args.step_size, source=SourceText(args), maxSteps=args.max_steps,
                     checkStep=args.check_step)


def _CheckPlot(args, study) -> None:
    if not args.plot:
        return
    CheckFigurePath(args.plot, '--plot', args.overwrite)
    if len(study.keys) not in (1, 2):
        raise UsageError(f"--plot needs one or two varied keys, got {len(study.keys)}")
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.studies.studypoint import RUN_COLUMNS, WINDOW_METRICS
    if len(study.keys) == 1:
        if args.metric is None:
            args.metric = _DefaultMetric(study)
        names = [f'w{i}.{m}' for i in range(study.numberOfWindows) for m in WINDOW_METRICS
                 if m != 'chatterState'] + list(RUN_COLUMNS[3:6])         # a number per run: not the state's word
        if args.metric not in names:
            raise UsageError(f"--metric: unknown column '{args.metric}'; expected one of: {' '.join(names)}")


def _DefaultMetric(study) -> str:
    """The default ``--metric``: the largest |phi2''| in the first window of the phase that decides the first run's
    linear verdict (window 1, the lowering, if no window belongs to it)."""
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.studies.studypoint import DecidingWindow
    from ..drive.wholedrive import ResolveDrive
    with BadInput():
        window = DecidingWindow(ResolveDrive(parameters=study.Parameters(0)), study.windows, study.endTime)
    return f"w{1 if window is None else window}.{_DEFAULT_METRIC}"


def _Run(args: argparse.Namespace) -> int:
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.studies.study import RunStudy
    from ..analysis.studies.studygrid import CheckStudySize, ParseShard
    from ..analysis.studies.studyfiles import StudySidecarPath
    from ..analysis.simulation.reelchanger import RunSizeError
    from .formatsweep import FormatStudy
    study = _Study(args)
    with BadInput():              # a grid too large for one call is refused before anything is built or written
        CheckStudySize(study, ParseShard(args.shard), args.max_runs, 'sweep', ('--max-runs', '--shard'))
    if args.output:
        # an existing results file is resumed (same study) or refused naming what differs (RunStudy)
        CheckOutputPath(args.output, '--output', overwrite=True)
    _CheckPlot(args, study)
    if args.workers is not None and args.workers < 1:
        raise UsageError(f"--workers must be >= 1, got {args.workers}")
    try:
        with BadInput(), StdoutToStderr(args.json):
            result = RunStudy(study, output=args.output, workers=args.workers, engine=args.engine,
                              shard=args.shard, quiet=True if args.quiet else None, overwrite=args.overwrite,
                              maxRuns=args.max_runs)
    except KeyboardInterrupt as err:
        return InterruptedLine(err, f"finished runs are saved in '{args.output}'; run the same command again to "
                                    f"resume" if args.output else
                               "nothing was saved (give --output FILE.csv to keep finished runs and resume)")
    written = []
    if args.output:
        written += [Path(args.output), StudySidecarPath(args.output)]
    if args.plot:
        # lazy: start-up (exudyn-worm --help imports every command module)
        from ..plotting import plot
        from ..plotting.plot_study import ChartAxes            # kT across, J1 up, as the stability charts
        subtitle = f"exudyn-worm sweep: {SourceText(args)}"
        figure = (result.plot(study.keys[0], metric=args.metric, subtitle=subtitle) if len(study.keys) == 1
                  else result.plot(*ChartAxes(study.keys[0], study.keys[1]), subtitle=subtitle))
        WriteAtomically(args.plot, lambda tmp: plot.SaveFigure(figure, tmp))
        written.append(Path(args.plot))
    if args.json:
        PrintJson(result.ToDict())
    else:
        print('\n'.join(FormatStudy(result, title=f"exudyn-worm sweep: {SourceText(args)}")))
    for path in written:
        print(f"wrote {path.resolve()}", file=sys.stderr)
    failed = sum(r['status'] != 'ok' for r in result.rows)
    if failed:
        print(f"exudyn-worm: warning: {failed} of {len(result.rows)} runs failed; their reason is in the "
              f"'error' column{' of ' + repr(str(args.output)) if args.output else ' (--json or --output)'}"
              + ('; runs longer than the step limit are refused: raise it with --max-steps N'
                 if any((r['error'] or '').startswith(RunSizeError.__name__ + ':') for r in result.rows) else ''),
              file=sys.stderr)
    return 1 if failed else 0                            # as documented: 1 when any run failed


COMMAND = Subcommand('sweep', 'parameter study: many simulations over a grid, on every core or an MPI cluster',
                     _AddArguments, _Run)
