"""``exudyn-worm simulate``: time-domain simulation of the reel changer with the worm-gear connector."""
from __future__ import annotations

import argparse
import contextlib
import enum
import math
import sys
import warnings
from pathlib import Path
from typing import TYPE_CHECKING, List, Tuple

from .main import (AddOverwriteOption, BadInput, CheckOutputPath, PositiveFloat, PositiveInt, PrintJson,
                   SourceInfo, SourceText, StdoutToStderr, Subcommand, UsageError, WholeDriveFromArgs)
from .._files import WriteAtomically

if TYPE_CHECKING:
    from ..drive.wholedrive import Drive

__all__ = ['COMMAND', 'ParseWindows']


def ParseWindows(text: str) -> List[Tuple[float, float]]:
    """Parse ``'0:2,2:6,6:8'`` into [(0, 2), (2, 6), (6, 8)] (seconds).

    Parameters
    ----------
    text : str
        Comma-separated windows ``T0:T1`` in s.

    Raises
    ------
    ValueError
        For a malformed list or a window with t1 <= t0 or t0 < 0.
    """
    windows = []
    if not text.strip():
        raise ValueError("--windows: expected T0:T1[,T0:T1...] in s, e.g. 0:2,2:6,6:8, got ''")
    for part in text.split(','):
        try:
            t0, t1 = (float(x) for x in part.split(':'))
        except ValueError:
            raise ValueError(f"--windows: expected T0:T1[,T0:T1...] in s, e.g. 0:2,2:6,6:8, got '{text}'") from None
        if not (0 <= t0 < t1) or not all(map(math.isfinite, (t0, t1))):
            raise ValueError(f"--windows: each window needs 0 <= T0 < T1 (s), got '{part}'")
        windows.append((t0, t1))
    return windows


_SIMULATE_HEADER = '{:>12}  {:<22}{:>20} {:>10} {:>7} {:>6} {:>16}  chatter'.format(
    'window [s]', 'phase', "max|phi2''| rad/s^2", 'max Fn kN', 'f Hz', 'S<0 %', "min phi1' rad/s")


_BEARING_HEADER = ('peak bearing loads [kN] (3D model; radial: vector sum of a shaft\'s radial bearings)\n'
                   + '{:>12} {:>14}{:>14}{:>14}{:>14}'.format('window [s]', 'worm axial', 'worm radial', 'wheel axial',
                                                             'wheel radial'))


class _StepCheckReason(str, enum.Enum):
    """Why the verdicts were or were not checked at half the step (``stepCheck.reason`` of ``--json``)."""
    OPTION = 'option'                   # --check-step / --no-check-step
    DEFAULT = 'default'                 # the linear margin decided
    MAX_STEPS = 'maxSteps'              # the run at half the step would exceed --max-steps
    CLEAR_VERDICTS = 'clearVerdicts'    # small margin, but no window's verdict is close


def _StepCheckLine(check: dict) -> str:
    """One line saying whether and why the verdicts were checked at half the step."""
    margin = f"linear margin |Re lambda|/|lambda| = {check['margin']:.3g}"
    if check['checked']:
        why = ('--check-step' if check['reason'] is _StepCheckReason.OPTION
               else f"{margin} < {check['smallMargin']:g}, near the stability boundary, and the verdict of window(s) "
                    f"{', '.join(str(i + 1) for i in check.get('closeWindows', []))} within a factor "
                    f"{check['verdictFactor']:g} of the chatter threshold")
        return (f"step check: verdicts compared with a run at half the step ({check['halfStepSize']:g} s; {why}); "
                f"'unresolved' where they differ")
    why = {_StepCheckReason.OPTION: '--no-check-step',
           _StepCheckReason.MAX_STEPS: 'the run at half the step would exceed --max-steps',
           _StepCheckReason.CLEAR_VERDICTS: f"{margin} < {check['smallMargin']:g}, but every window's verdict is clear: its chatter "
                            f"measure is not within a factor {check['verdictFactor']:g} of the threshold"}.get(
        check['reason'], f"{margin} >= {check['smallMargin']:g}")
    return f"step check: off ({why}); --check-step compares with a run at half the step"

_SIMULATE_FIGURES = ('overview', 'acceleration', 'speed', 'normalForce', 'driveTorque')


#: the figure a run of the 3D model adds (worm and wheel as rigid bodies on their shafts' bearings)
_BEARING_FIGURE = 'bearingLoads'


def _Figures(rigidBody: bool) -> Tuple[str, ...]:
    return _SIMULATE_FIGURES + ((_BEARING_FIGURE,) if rigidBody else ())


def _SaveFigures(result, folder: Path, subtitle: str = '', quiet=None) -> List[Path]:
    """Write the standard figures of a simulation as PNG files into ``folder`` (created if missing;
    its parent was checked by :func:`~exudyn_worm.cli.main.CheckOutputPath`); a run of the 3D model adds its
    bearing loads."""
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..items.results import BEARING_LOADS
    from ..plotting import plot
    from ..progress import ProgressBar
    created = not folder.exists()
    folder.mkdir(exist_ok=True)
    paths = []
    kinds = _Figures(all(name in result.series for name in BEARING_LOADS.values()))
    try:
        with ProgressBar(total=len(kinds), desc='figures', unit='figure', quiet=quiet, delay=2.) as bar:
            for kind in kinds:
                path = folder / f'{kind}.png'
                figure = plot.PlotSimulation(result, kind=kind, subtitle=subtitle)
                WriteAtomically(path, lambda tmp: plot.SaveFigure(figure, tmp))
                paths.append(path)
                bar.update(1)
    except BaseException:            # a full disk, Ctrl-C: a folder made here is not left half-filled
        if created:
            for path in paths:
                with contextlib.suppress(OSError):
                    path.unlink()
            with contextlib.suppress(OSError):
                folder.rmdir()
        raise
    return paths


def _AddArguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument('--end-time', type=PositiveFloat('s'), default=None, metavar='S',
                        help="simulated time in s (default: one full rotation, 8 s at the paper's speed; for "
                             "another duty (loadType, motorType) the end of its tables and ramps; or the end of the "
                             "last --windows)")
    parser.add_argument('--step-size', type=PositiveFloat('s'), default=None, metavar='S',
                        help='time step in s (default: from the drive, 0.039 / its highest natural frequency); refused '
                             'if it cannot resolve that frequency (rule in exudyn_worm/analysis/simulation/stepsize.py)')
    parser.add_argument('--max-steps', type=PositiveInt('steps'), default=None, metavar='N',
                        help='refuse runs of more solver steps (= stored samples) than N (default 1e6, about 0.4 GB '
                             'of results; 780 s simulated of P1 at its default step)')
    parser.add_argument('--windows', default=None, metavar='T0:T1,...',
                        help='evaluation windows in s (default: the lift / lower / lift phases of every '
                             'rotation simulated, the last one clipped to the end time; for another duty its lift, '
                             'lower and idle phases: lowering = the load drives the gear)')
    parser.add_argument('--check-step', action=argparse.BooleanOptionalAction, default=None,
                        help="run again at half the step and report a window whose chatter verdict changes as "
                             "'unresolved' (default: on where the linear margin is small, |Re lambda|/|lambda| of "
                             "the least stable mode < 0.02; rule in docs/command-line.md)")
    parser.add_argument('--plot', default=None, metavar='DIR',
                        help='write PNG figures into the folder DIR (created if missing; its parent must exist)')
    parser.add_argument('--csv', default=None, metavar='FILE',
                        help='write the time series to FILE (CSV; its folder must exist)')
    AddOverwriteOption(parser, 'the --csv file and the figures of --plot')
    parser.add_argument('--quiet', action='store_true', help='no progress bar on stderr')
    parser.add_argument('--python-user-functions', action='store_true',
                        help='evaluate the connector in Python instead of C++ (debugging; same results, slower)')


def _StepCheck(args: argparse.Namespace, drive: Drive, endTime: float, stepSize: float, maxSteps: int) -> dict:
    """Whether the verdicts are checked at half the step, and why (--check-step, or the linear margin)."""
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.simulation.reelchanger import CheckRunSize
    from ..analysis.simulation.stepsize import SMALL_MARGIN, VERDICT_FACTOR, LinearMargin
    with BadInput():
        margin = LinearMargin(drive)
    check = {'checked': margin['small'] if args.check_step is None else args.check_step,
             'halfStepSize': 0.5 * stepSize, 'margin': margin['margin'], 'smallMargin': SMALL_MARGIN,
             'verdictFactor': VERDICT_FACTOR,
             'reason': _StepCheckReason.OPTION if args.check_step is not None else _StepCheckReason.DEFAULT}
    if check['checked']:
        try:
            CheckRunSize(endTime, 0.5 * stepSize, maxSteps, 'simulate',
                         ('--end-time', 'half the step (--check-step)', '--max-steps'))
        except ValueError as err:
            if args.check_step:
                raise UsageError(str(err)) from None
            check['checked'], check['reason'] = False, _StepCheckReason.MAX_STEPS      # said in the output (_StepCheckLine)
    return check


def _RunSettings(args: argparse.Namespace, drive: Drive) -> Tuple[float, float, int, List[Tuple[float, float]]]:
    """End time, step size, step limit and windows of a run, checked before anything is computed."""
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.simulation.reelchanger import MAX_STEPS, CheckRunSize, DefaultSimulatedTime, DefaultWindows
    from ..builders.oneangle import CheckReelChangerKeys
    from ..analysis.simulation.stepsize import CheckStepSize, CoarseStepWarning, RecommendedStepSize
    from ..params.plausibility import CheckWormRotation
    with BadInput():
        CheckReelChangerKeys(drive, 'simulate')
        stepSize = args.step_size if args.step_size is not None else RecommendedStepSize(drive)
    maxSteps = args.max_steps if args.max_steps is not None else MAX_STEPS
    with BadInput(), warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter('always', CoarseStepWarning)
        if args.step_size is not None:
            CheckStepSize(drive, args.step_size, 'simulate --step-size')
    for warning in caught:
        print(f"exudyn-worm: warning: {warning.message}", file=sys.stderr)
    CheckWormRotation(drive.parameters, stepSize, 'simulate')   # a step refused above stands alone; a run shorter than
    with BadInput():                                       # one step is refused below, after this warning says why
        userWindows = ParseWindows(args.windows) if args.windows is not None else None
        endTime = args.end_time
        if endTime is None:
            endTime = max([DefaultSimulatedTime(drive)] + [t1 for _, t1 in userWindows or []])
        CheckRunSize(endTime, stepSize, maxSteps, 'simulate',
                     ('--end-time', '--step-size' if args.step_size is not None else 'the recommended step size',
                      '--max-steps'))
        if userWindows is None:
            return endTime, stepSize, maxSteps, DefaultWindows(drive, endTime, minLength=2 * stepSize)
    for t0, t1 in userWindows:
        if t1 > endTime * (1 + 1e-12):
            raise UsageError(f"--windows: the window {t0:g}:{t1:g} ends after --end-time = {endTime:g} s")
        if t1 - t0 < 2 * stepSize:
            raise UsageError(f"--windows: the window {t0:g}:{t1:g} is shorter than two steps "
                             f"(2 x --step-size = {2 * stepSize:g} s)")
    return endTime, stepSize, maxSteps, userWindows


def _Write(what: str, path, write):
    try:
        return write()
    except OSError as err:
        raise UsageError(f"{what} {path}: cannot write: {err.strerror or err} (the results above are complete)") \
            from err


def _Run(args: argparse.Namespace) -> int:
    drive = WholeDriveFromArgs(args)
    csv = CheckOutputPath(args.csv, '--csv', overwrite=args.overwrite) if args.csv is not None else None
    plots = (CheckOutputPath(args.plot, '--plot', 'folder', overwrite=args.overwrite,
                             contents=[f'{kind}.png' for kind in _Figures(drive.isRigidBody)])
             if args.plot is not None else None)
    endTime, stepSize, maxSteps, windows = _RunSettings(args, drive)
    stepCheck = _StepCheck(args, drive, endTime, stepSize, maxSteps)
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.simulation.reelchanger import PhaseLabel, SimulateReelChanger, WindowPhases
    from ..items.solve import SolverDivergedError
    from ..analysis.simulation.stepsize import CloseVerdicts, CoarseStepWarning, CompareHalfStep, UNRESOLVED
    from ..items.results import ChatterVerdict, UNDECIDED
    from ..params.plausibility import ImplausibleValueWarning, UnresolvedRotationWarning

    def Simulate(h):
        try:
            with StdoutToStderr(args.json), warnings.catch_warnings():
                warnings.simplefilter('ignore', CoarseStepWarning)      # reported above
                warnings.simplefilter('ignore', UnresolvedRotationWarning)
                if h != stepSize:          # the run at half the step repeats what the run at the step said
                    warnings.simplefilter('ignore', ImplausibleValueWarning)
                return SimulateReelChanger(drive, endTime=endTime, stepSize=h, maxSteps=maxSteps,
                                           useSymbolic=not args.python_user_functions,
                                           progress=False if args.quiet else None)
        except SolverDivergedError as err:
            raise UsageError(f"simulation failed{' at half the step (--check-step)' if h != stepSize else ''}: "
                             f"{str(err).removeprefix('SimulateReelChanger: ')}") from err

    result = Simulate(stepSize)
    metrics = result.WindowMetrics(windows)
    if stepCheck['checked'] and stepCheck['reason'] is _StepCheckReason.DEFAULT:      # ... and only where a verdict is close
        stepCheck['closeWindows'] = CloseVerdicts(result, windows)
        if not stepCheck['closeWindows']:
            stepCheck['checked'], stepCheck['reason'] = False, _StepCheckReason.CLEAR_VERDICTS
    if stepCheck['checked']:
        metrics = CompareHalfStep(metrics, Simulate(0.5 * stepSize).WindowMetrics(windows))
    phases = WindowPhases(drive, windows, endTime)
    for m, phase in zip(metrics, phases):
        m['phase'] = phase
    source = SourceText(args)
    if args.json:
        PrintJson({'source': SourceInfo(args), 'endTime': result.endTime, 'stepSize': stepSize, 'steps': result.steps,
                   'solveSeconds': result.solveSeconds, 'stepCheck': stepCheck, 'windows': metrics})
    else:
        print(f"exudyn-worm simulate: {source}")
        print(f"simulated {result.endTime:g} s in {result.steps} steps of {stepSize:g} s, "
              f"solver time {result.solveSeconds:.3f} s")
        print(_StepCheckLine(stepCheck))
        print(_SIMULATE_HEADER)
        for m in metrics:
            verdict = {True: 'YES', False: 'no'}.get(m['chatter'], m['chatter'])
            if m['chatter'] != UNRESOLVED and m['chatterState'] != 'none':
                text = ChatterVerdict.FromMetrics(m).Describe()
                verdict = text if m['chatter'] == UNDECIDED else f"{verdict} ({text})"
            if m['chatter'] == UNRESOLVED:
                verdict += (f" (h: {_STATE_WORDS[m['chatterState']]}, h/2: {_STATE_WORDS[m['halfStep']['chatterState']]}"
                            f"; max|phi2''| at h/2 {m['halfStep']['maxAbsWheelAcceleration']:.1f})")
            print(f"{m['t0']:>5.2f} - {m['t1']:<5.2f} {PhaseLabel(drive, m['phase'], (m['t0'], m['t1'])):<22}"
                  f"{m['maxAbsWheelAcceleration']:>20.1f} {m['maxNormalForce'] / 1e3:>10.1f} "
                  f"{m['dominantFrequencyHz']:>7.1f} {100 * m['fractionSNegative']:>6.0f} {m['minWormSpeed']:>16.2f}  "
                  f"{verdict}")
        for line in _DivergenceLines(drive):
            print(line)
        if drive.isRigidBody:
            print(_BEARING_HEADER)
            for m in metrics:
                loads = m['bearingLoads']
                print(f"{m['t0']:>5.2f} - {m['t1']:<5.2f} " + ''.join(f"{loads[k] / 1e3:>14.2f}" for k in
                                                                     ('wormAxial', 'wormRadial', 'wheelAxial',
                                                                      'wheelRadial')))
        sys.stdout.flush()
    written = []
    if csv is not None:
        written.append(_Write('--csv', csv, lambda: WriteAtomically(csv, result.ToCsv)))
    if plots is not None:
        written += _Write('--plot', plots, lambda: _SaveFigures(result, plots, subtitle=source,
                                                                quiet=True if args.quiet else None))
    for path in written:
        print(f"wrote {Path(path).resolve()}", file=sys.stderr)
    return 0


def _DivergenceLines(drive) -> List[str]:
    """A line per operating point at which the linear analysis finds a divergence (a real eigenvalue grows: the drive
    runs away or creeps, which a window's chatter verdict does not describe)."""
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.stability.drivestability import DIVERGENCE, AnalyzeDrive
    try:
        points = AnalyzeDrive(drive).operatingPoints
    except ValueError:          # no linear analysis of this drive: nothing to add to the simulation
        return []
    return [f"note: the linear analysis at {p.point.Label()} finds a divergence, not chatter: {p.growthText}"
            for p in points if p.instability == DIVERGENCE]


#: a window's state in the step check's words (YES / no as in the chatter column)
_STATE_WORDS = {'chatter': 'YES', 'none': 'no', 'decaying': 'no (decaying)', 'undecided': 'undecided'}

COMMAND = Subcommand('simulate', 'time-domain simulation of the reel changer with the Exudyn worm-gear connector',
                     _AddArguments, _Run)
