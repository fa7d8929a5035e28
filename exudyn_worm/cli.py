"""The ``exudyn-worm`` command line (also ``python -m exudyn_worm``).

Subcommands live in the registry :data:`SUBCOMMANDS`: each entry is a :class:`Subcommand` with a
name, a one-line help text, a function that adds its arguments to its ``argparse`` subparser and a
function that runs it and returns the exit status. To add a subcommand (e.g. ``simulate``)::

    def _AddSimulateArguments(parser: argparse.ArgumentParser) -> None:
        parser.add_argument('--duration', type=float, default=8., help='simulated time in s')

    def _RunSimulate(args: argparse.Namespace) -> int:
        parameters, drive = DriveFromArgs(args)      # --preset/--config/--set, bad input -> exit 2
        ...                                          # compute, then print (or JSON if args.json)
        return 0

    SUBCOMMANDS.append(Subcommand('simulate', 'time-domain simulation of a preset',
                                  _AddSimulateArguments, _RunSimulate))

With ``parameterOptions=True`` (the default) the subparser gets the shared options of
:func:`AddParameterOptions` (``--preset``, ``--config``, ``--set KEY=VALUE``, ``--json``). A run function
signals bad user input by raising :class:`UsageError` (or a ``ValueError``/``TypeError`` inside
``with BadInput():``); :func:`Main` prints it as one line ``exudyn-worm: error: ...`` on stderr and
returns 2. Other exceptions are internal errors and propagate with their traceback.

Exit status: 0 success (for ``stability`` whatever the verdict), 1 failed validation, 2 bad input.
"""
from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Dict, Iterator, List, Optional, Sequence, Tuple

from .config import DEFAULT_PRESET, ResolveParameters
from .design import StabilizingChanges
from .drive import ElasticDrive
from .presets import PRESETS, DriveFromParameters
from .stability import CONTACT_STATES, AnalyzeStability, StabilityAnalysis

__all__ = ['PROG', 'UsageError', 'BadInput', 'Subcommand', 'SUBCOMMANDS', 'AddParameterOptions',
           'ParametersFromArgs', 'DriveFromArgs', 'BuildParser', 'FormatStability', 'StabilityHint', 'Main']

#: program name used in help and error messages
PROG = 'exudyn-worm'


class UsageError(Exception):
    """Bad user input: :func:`Main` prints it as one line on stderr and exits with status 2."""


@contextlib.contextmanager
def BadInput() -> Iterator[None]:
    """Context manager: a ``ValueError``/``TypeError`` raised inside the block becomes a :class:`UsageError`.

    Raises
    ------
    UsageError
        With the message of the original error (chained).
    """
    try:
        yield
    except (ValueError, TypeError) as err:
        raise UsageError(str(err)) from err


class _Parser(argparse.ArgumentParser):
    """ArgumentParser whose errors become one-line :class:`UsageError` instead of usage + exit."""

    def error(self, message: str):
        raise UsageError(f"{message} (see '{self.prog} --help')")


@dataclass(frozen=True)
class Subcommand:
    """One entry of the subcommand registry.

    Parameters
    ----------
    name : str
        Subcommand name on the command line.
    help : str
        One-line description for ``exudyn-worm --help``.
    addArguments : callable
        ``addArguments(parser)`` adds the subcommand's own options to its subparser.
    run : callable
        ``run(args) -> int`` runs it and returns the exit status.
    parameterOptions : bool, optional
        Add the shared options of :func:`AddParameterOptions` (default True).
    """
    name: str
    help: str
    addArguments: Callable[[argparse.ArgumentParser], None]
    run: Callable[[argparse.Namespace], int]
    parameterOptions: bool = True


def AddParameterOptions(parser: argparse.ArgumentParser) -> None:
    """Add the options shared by every subcommand that works on a parameter set.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The subcommand's parser; it gets ``--preset NAME``, ``--config FILE.toml``, ``--set KEY=VALUE``
        (repeatable, stored as the list ``args.set``) and ``--json``. Read them back with
        :func:`ParametersFromArgs` / :func:`DriveFromArgs`.
    """
    group = parser.add_argument_group('parameter set (preset, then config file, then --set)')
    group.add_argument('--preset', metavar='NAME', default=None,
                       help=f"parameter preset, one of: {', '.join(PRESETS)} "
                            f"(default: the config file's preset, else {DEFAULT_PRESET})")
    group.add_argument('--config', metavar='FILE.toml', default=None,
                       help="TOML file with optional preset = \"NAME\" and a [parameters] table")
    group.add_argument('--set', metavar='KEY=VALUE', action='append', default=[], dest='set',
                       help="override one parameter; VALUE is SI (angles in rad) or has units, "
                            "e.g. --set 'backlash=0.5 mm' --set 'kT=7 kN*m' (repeatable)")
    parser.add_argument('--json', action='store_true',
                        help='print exactly one JSON object on stdout instead of the table')


def ParametersFromArgs(args: argparse.Namespace) -> Dict[str, float]:
    """Resolve the parameter set of the shared options with :func:`~exudyn_worm.config.ResolveParameters`.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed arguments of a subcommand with :func:`AddParameterOptions`.

    Returns
    -------
    dict
        Flat parameter dictionary, SI.

    Raises
    ------
    UsageError
        For any bad input (unknown preset or key, malformed value, wrong unit, bad config file).
    """
    with BadInput():
        return ResolveParameters(preset=args.preset, config=args.config, sets=args.set)


def DriveFromArgs(args: argparse.Namespace) -> Tuple[Dict[str, float], ElasticDrive]:
    """Resolve the parameter set and build its :class:`ElasticDrive`.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed arguments of a subcommand with :func:`AddParameterOptions`.

    Returns
    -------
    (dict, ElasticDrive)
        The flat parameter dictionary and the drive built from it.

    Raises
    ------
    UsageError
        For bad input or parameters the model rejects (its ``ValueError``/``TypeError``).
    """
    parameters = ParametersFromArgs(args)
    with BadInput():
        return parameters, DriveFromParameters(parameters)


@contextlib.contextmanager
def _StdoutToStderr(active: bool) -> Iterator[None]:
    """Send anything printed inside the block (Python and C level) to stderr, keeping stdout for JSON."""
    if not active:
        yield
        return
    sys.stdout.flush()
    try:
        saved = os.dup(1)
        os.dup2(2, 1)
    except OSError:
        saved = None
    try:
        with contextlib.redirect_stdout(sys.stderr):
            yield
    finally:
        sys.stderr.flush()
        if saved is not None:
            os.dup2(saved, 1)
            os.close(saved)


def _PrintJson(data) -> None:
    print(json.dumps(data, indent=2, allow_nan=False))


# ---------------------------------------------------------------------------------------------------
# stability
# ---------------------------------------------------------------------------------------------------
def _AddStabilityArguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument('--method', choices=('analytical', 'exudyn'), default='analytical',
                        help='analytical: eqs. (15)-(19) of the paper (default); exudyn: eigenvalues of '
                             'the linearized Exudyn model')


def _RunStability(args: argparse.Namespace) -> int:
    parameters, drive = DriveFromArgs(args)
    if args.method == 'exudyn':
        try:
            from .linearization import AnalyzeStabilityExudyn
        except ImportError as err:
            raise UsageError(f"--method exudyn is not available: cannot import "
                             f"exudyn_worm.linearization.AnalyzeStabilityExudyn ({err})") from err
        with _StdoutToStderr(args.json):
            analysis = AnalyzeStabilityExudyn(drive)
    else:
        analysis = AnalyzeStability(drive)
    if args.json:
        _PrintJson(analysis.ToDict())
        return 0
    lines = FormatStability(analysis, title=f"exudyn-worm stability: {_SourceText(args)}, method {args.method}")
    if not analysis.stable:
        lines.append(StabilityHint(parameters))
    print('\n'.join(lines))
    return 0


def _SourceText(args: argparse.Namespace) -> str:
    parts = [f"preset {args.preset}" if args.preset else None,
             f"config {args.config}" if args.config else None,
             f"--set {' '.join(args.set)}" if args.set else None]
    parts = [p for p in parts if p]
    if not args.preset and not args.config:
        parts.insert(0, f"preset {DEFAULT_PRESET} (default)")
    return ', '.join(parts)


def _G(x: float, digits: int = 5) -> str:
    return 'n/a' if x is None else ('inf' if math.isinf(x) and x > 0 else '-inf' if math.isinf(x)
                                    else f'{x:.{digits}g}')


def _Complex(z: complex) -> str:
    return f"{z.real:.3f} {'+' if z.imag >= 0 else '-'} {abs(z.imag):.3f}i"


def FormatStability(analysis: StabilityAnalysis, title: str = 'Stability') -> List[str]:
    """Human-readable table of a :class:`StabilityAnalysis` (the ``stability`` subcommand's output).

    Parameters
    ----------
    analysis : StabilityAnalysis
        Result of :func:`~exudyn_worm.stability.AnalyzeStability` (or of the Exudyn linearization).
    title : str, optional
        First line.

    Returns
    -------
    list of str
        The lines, without trailing newlines.
    """
    d = analysis.drive
    g = d.gear
    w = 36
    row = lambda label, *cells: f"  {label:<{w}}" + ''.join(f"{c:>22}" for c in cells)
    lines = [title, '', 'Gear and drive']
    lines += [row('transmission ratio u', _G(g.ratio)),
              row('pitch angle gamma [deg]', _G(math.degrees(g.gamma))),
              row('friction angle rho [deg]', _G(math.degrees(g.frictionAngle))),
              row('friction coefficient mu', _G(g.mu)),
              row('self-locking (gamma < rho)', 'yes' if g.selfLocking else 'no'),
              row('efficiency, worm driving', _G(g.efficiencyWormDriving, 4)),
              row('efficiency, wheel driving', _G(g.efficiencyWheelDriving, 4)),
              row('J1, J2 [kg*m^2]', _G(d.J1), _G(d.J2)),
              row('kT [N*m/rad], kV [N/m]', _G(d.kT), _G(g.kV)),
              row('dT [N*m*s/rad], dV [N*s/m]', _G(d.dT), _G(g.dV)),
              row('D_T, D_V, D_TV (eqs. 22-24)', _G(d.DT, 4), _G(d.DV, 4), _G(d.DTV, 4)),
              row('J1/J2', _G(d.inertiaRatio, 4)),
              row('kT/(kV r1^2)', _G(d.stiffnessRatio, 4))]
    c = {S: analysis.contact[S] for S in CONTACT_STATES}
    lines += ['', 'Linear stability per contact state S (eqs. (15)-(19))',
              row('', *(f'S = {S:+d}' for S in CONTACT_STATES))]
    for i, unit in enumerate(('1/s', '1/s^2', '1/s^3', '1/s^4')):
        lines.append(row(f'b{i + 1} [{unit}]', *(_G(c[S].b[i]) for S in CONTACT_STATES)))
    for label, i in (('(17) b1 > 0', 0), ('(18) b1 b2 - b3 > 0', 1), ('(19) (b1 b2 - b3) b3 - b1^2 b4 > 0', 2)):
        lines.append(row(label, *(f"{_G(c[S].hurwitz[i], 4)} {'ok' if c[S].hurwitz[i] > 0 else 'NO'}"
                                  for S in CONTACT_STATES)))
    for i in range(4):
        lines.append(row(f'eigenvalue {i + 1} [1/s]', *(_Complex(c[S].eigenvalues[i]) for S in CONTACT_STATES)))
    for i in range(2):
        lines.append(row(f'frequency f{i + 1} [Hz]', *(_G(c[S].frequenciesHz[i], 4) for S in CONTACT_STATES)))
    for i in range(2):
        lines.append(row(f'Lehr damping D{i + 1} = -delta/omega', *(_G(float(c[S].lehrDamping[i]), 3)
                                                                    for S in CONTACT_STATES)))
    lines.append(row('stable (all Re(lambda) < 0)', *('yes' if c[S].stable else 'NO' for S in CONTACT_STATES)))

    ratio = d.inertiaRatio
    fuesgen, first = analysis.fuesgenLimit, analysis.firstCriterionLimit
    classicChatter = ratio < fuesgen or ratio < first
    verdict = lambda limit: 'chatter predicted' if ratio < limit else 'no chatter predicted'
    lines += ['', 'Classic criteria: chatter if J1/J2 is below the limit',
              row('actual J1/J2', _G(ratio, 4)),
              row('Fuesgen limit (21), d_T = 0', _G(fuesgen, 4), verdict(fuesgen)),
              row('first criterion limit (20)', _G(first, 4), verdict(first)),
              '']
    if analysis.stable:
        lines.append('Verdict: STABLE for S = +1 and S = -1 (no chatter predicted by the linear model)')
    else:
        bad = [f'S = {S:+d}' for S in CONTACT_STATES if not c[S].stable]
        violated = sorted({n for S in CONTACT_STATES for n, v in zip(('(17)', '(18)', '(19)'), c[S].hurwitz)
                           if v <= 0})
        lines.append(f"Verdict: UNSTABLE for {' and '.join(bad)} (chatter expected); Hurwitz conditions violated: "
                     f"{', '.join(violated) if violated else 'none of (17)-(19) (b3 or b4 <= 0)'}")
        if not classicChatter:
            lines.append('Note: the classic criteria (20) and (21) predict no chatter here; they alone are '
                         'insufficient (paper section 3.1)')
    return lines


def StabilityHint(parameters: Dict[str, float], span: float = 100.) -> str:
    """One-line design hint for an unstable drive: the nearest stable J1 and kT
    (:func:`~exudyn_worm.design.StabilizingChanges`), other parameters as given.

    Parameters
    ----------
    parameters : dict
        Flat parameter dictionary (see :func:`~exudyn_worm.presets.DriveFromParameters`).
    span : float, optional
        Search range factor, > 1.

    Returns
    -------
    str
        One line starting with ``Hint:``.
    """
    parts = []
    for r in StabilizingChanges(parameters, span):
        options = [f"{r.key} {op} {value:.3g} {r.unit} ({r.ratioName} {op} {value * r.ratioScale:.3g})"
                   for op, value in (('<=', r.below), ('>=', r.above)) if value is not None]
        parts.append(' or '.join(options) if options else
                     f"no {r.key} within 1/{span:g} to {span:g} times the given value")
    return ('Hint: with all other parameters as given, the analytical model is stable for '
            + '; or for '.join(parts) + ' (nearest stable values found by a scan)')


# ---------------------------------------------------------------------------------------------------
# validate
# ---------------------------------------------------------------------------------------------------
def _AddValidateArguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument('--report', metavar='PATH', default=None,
                        help='write the Markdown report here (default: validation/REPORT.md of the source tree)')
    parser.add_argument('--no-report', action='store_true', dest='noReport', help='write no report')
    parser.add_argument('--quick', action='store_true', help='skip the slow checks')


def _RunValidate(args: argparse.Namespace) -> int:
    try:
        from .validation import DEFAULT_REPORT_PATH, RunValidation
    except ImportError as err:
        raise UsageError(f"validate is not available: cannot import exudyn_worm.validation.RunValidation "
                         f"({err})") from err
    if args.noReport and args.report:
        raise UsageError("give either --report PATH or --no-report, not both")
    if args.noReport:
        report = None
    elif args.report:
        report = Path(args.report)
    else:
        report = DEFAULT_REPORT_PATH if DEFAULT_REPORT_PATH.parent.is_dir() else None
        if report is None:
            print(f"{PROG}: note: no source tree found; no report written (use --report PATH)", file=sys.stderr)
    summary = RunValidation(reportPath=report, quick=args.quick)
    for line in summary.lines:
        print(line)
    return 0 if summary.passed else 1


# ---------------------------------------------------------------------------------------------------
# simulate
# ---------------------------------------------------------------------------------------------------
def ParseWindows(text: str) -> List[Tuple[float, float]]:
    """Parse ``'0:2,2:6,6:8'`` into [(0, 2), (2, 6), (6, 8)] (seconds).

    Raises
    ------
    ValueError
        For a malformed list or a window with t1 <= t0 or t0 < 0.
    """
    windows = []
    for part in text.split(','):
        try:
            t0, t1 = (float(x) for x in part.split(':'))
        except ValueError:
            raise ValueError(f"--windows: expected T0:T1[,T0:T1...] in s, e.g. 0:2,2:6,6:8, got '{text}'") from None
        if not (0 <= t0 < t1) or not all(map(math.isfinite, (t0, t1))):
            raise ValueError(f"--windows: each window needs 0 <= T0 < T1 (s), got '{part}'")
        windows.append((t0, t1))
    return windows


_SIMULATE_HEADER = '{:>12} {:>20} {:>10} {:>7} {:>6} {:>16}  chatter'.format(
    'window [s]', "max|phi2''| rad/s^2", 'max Fn kN', 'f Hz', 'S<0 %', "min phi1' rad/s")
_SIMULATE_FIGURES = ('overview', 'acceleration', 'speed', 'normalForce', 'driveTorque')


def _SaveFigures(result, folder: Path) -> List[Path]:
    """Write the standard figures of a simulation as PNG files into ``folder``."""
    from . import plot
    folder.mkdir(parents=True, exist_ok=True)
    paths = []
    for kind in _SIMULATE_FIGURES:
        path = folder / f'{kind}.png'
        plot.SaveFigure(plot.PlotSimulation(result, kind=kind), path)
        paths.append(path)
    return paths


def _AddSimulateArguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument('--end-time', type=float, default=None, metavar='S',
                        help='simulated time in s (default: one full rotation, 8 s at the paper\'s speed)')
    parser.add_argument('--step-size', type=float, default=None, metavar='S',
                        help='time step in s (default 5e-4)')
    parser.add_argument('--windows', default=None, metavar='T0:T1,...',
                        help='evaluation windows in s (default: the lift / lower / lift phases of one rotation)')
    parser.add_argument('--plot', default=None, metavar='DIR', help='write PNG figures into DIR')
    parser.add_argument('--csv', default=None, metavar='FILE', help='write the time series to FILE (CSV)')
    parser.add_argument('--python-user-functions', action='store_true',
                        help='evaluate the connector in Python instead of C++ (debugging; same results, slower)')


def _RunSimulate(args: argparse.Namespace) -> int:
    from .reelchanger import DEFAULT_STEP_SIZE, DefaultWindows, SimulateReelChanger
    parameters, drive = DriveFromArgs(args)
    with BadInput():
        windows = ParseWindows(args.windows) if args.windows else DefaultWindows(parameters)
        endTime = args.end_time if args.end_time is not None else max(
            DefaultWindows(parameters)[-1][1], max(t1 for _, t1 in windows))
        if max(t1 for _, t1 in windows) > endTime:
            raise ValueError(f"--windows: a window ends after --end-time = {endTime:g} s")
        with _StdoutToStderr(args.json):
            result = SimulateReelChanger(parameters, endTime=endTime,
                                         stepSize=args.step_size if args.step_size is not None else DEFAULT_STEP_SIZE,
                                         useSymbolic=not args.python_user_functions)
        metrics = result.WindowMetrics(windows)
    written = []
    if args.csv:
        written.append(result.ToCsv(args.csv))
    if args.plot:
        written += _SaveFigures(result, Path(args.plot))
    if args.json:
        _PrintJson({'endTime': result.endTime, 'steps': result.steps, 'solveSeconds': result.solveSeconds,
                    'windows': metrics})
    else:
        print(f"simulated {result.endTime:g} s in {result.steps} steps, solver time {result.solveSeconds:.3f} s")
        print(_SIMULATE_HEADER)
        for m in metrics:
            print(f"{m['t0']:>5.2f} - {m['t1']:<5.2f}{m['maxAbsWheelAcceleration']:>20.1f} {m['maxNormalForce'] / 1e3:>10.1f} "
                  f"{m['dominantFrequencyHz']:>7.1f} {100 * m['fractionSNegative']:>6.0f} {m['minWormSpeed']:>16.2f}  "
                  f"{'YES' if m['chatter'] else 'no'}")
    for path in written:
        print(f"wrote {Path(path).resolve()}", file=sys.stderr)
    return 0


#: the subcommand registry, in the order of ``exudyn-worm --help``
SUBCOMMANDS: List[Subcommand] = [
    Subcommand('stability', 'linear stability (chatter) analysis of a parameter set',
               _AddStabilityArguments, _RunStability),
    Subcommand('validate', 'check the implementation against the numbers published in the paper',
               _AddValidateArguments, _RunValidate, parameterOptions=False),
    Subcommand('simulate', 'time-domain simulation of the reel changer with the Exudyn worm-gear connector',
               _AddSimulateArguments, _RunSimulate),
]


def BuildParser() -> argparse.ArgumentParser:
    """Build the argument parser: one subparser per entry of :data:`SUBCOMMANDS`.

    Returns
    -------
    argparse.ArgumentParser
        Parse errors raise :class:`UsageError` instead of printing usage and exiting.
    """
    from . import __version__
    parser = _Parser(prog=PROG, description='Chatter analysis of self-locking worm gears with Exudyn.')
    parser.add_argument('--version', action='version', version=f'%(prog)s {__version__}')
    sub = parser.add_subparsers(dest='command', metavar='COMMAND', required=True, parser_class=_Parser)
    for command in SUBCOMMANDS:
        p = sub.add_parser(command.name, help=command.help, description=command.help)
        if command.parameterOptions:
            AddParameterOptions(p)
        command.addArguments(p)
        p.set_defaults(run=command.run)
    return parser


def Main(argv: Optional[Sequence[str]] = None) -> int:
    """Run the command line; return the exit status.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments without the program name (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        0 on success, 1 if a validation failed, 2 for bad input (one line ``exudyn-worm: error: ...``
        on stderr).
    """
    try:
        args = BuildParser().parse_args(argv)
        return int(args.run(args) or 0)
    except UsageError as err:
        message = ' '.join(str(err).split())
        print(f"{PROG}: error: {message}", file=sys.stderr)
        return 2
    except BrokenPipeError:            # output piped into e.g. `head`: stop quietly
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except SystemExit as err:          # --help, --version
        return err.code if isinstance(err.code, int) else 0 if err.code is None else 2
