"""The ``exudyn-worm`` command line (also ``python -m exudyn_worm``).

This module holds what every subcommand shares (errors, the shared parameter options, JSON output);
each subcommand lives in its own module of :mod:`exudyn_worm.cli` and is listed in
:data:`COMMAND_MODULES`. A command module defines ``COMMAND``, a :class:`Subcommand` with a name, a
one-line help text, a function that adds its arguments to its ``argparse`` subparser and a function
that runs it and returns the exit status. To add a subcommand ``demo``, write
``exudyn_worm/cli/demo.py``::

    from .main import Subcommand, WholeDriveFromArgs

    def _AddArguments(parser):
        parser.add_argument('--duration', type=float, default=8., help='simulated time in s')

    def _Run(args):
        drive = WholeDriveFromArgs(args)      # --preset/--config/--set, bad input -> exit 2
        ...                                          # compute, then print (or JSON if args.json)
        return 0

    COMMAND = Subcommand('demo', 'one-line help', _AddArguments, _Run)

and add ``'demo'`` to :data:`COMMAND_MODULES`. Command modules import heavy packages (exudyn, scipy,
matplotlib) inside their run function, so that ``exudyn-worm --help`` and light subcommands start fast.
Extra subcommands (plugins, tests) can be appended to :data:`SUBCOMMANDS`.

With ``parameterOptions=True`` (the default) the subparser gets the shared options of
:func:`AddParameterOptions` (``--preset``, ``--config``, ``--set KEY=VALUE``, ``--json``). A run function
signals bad user input by raising :class:`UsageError` (or a ``ValueError``/``TypeError`` inside
``with BadInput():``); :func:`Main` prints it as one line ``exudyn-worm: error: ...`` on stderr and
returns 2. Other exceptions are internal errors and propagate with their traceback.

Exit status: 0 success (for ``stability`` whatever the verdict), 1 failed runs or an error of the system (a full
disk, a stdout that cannot be written: one line naming the file), 2 bad input, 130 interrupted
(Ctrl-C), 143 terminated (SIGTERM, handled as Ctrl-C): one line on stderr, no traceback; files are written with
:func:`~exudyn_worm._files.WriteAtomically`, so none is left half-written, and worker processes end with the
command (:mod:`exudyn_worm._workers`). An existing output file is refused unless ``--overwrite`` (:func:`CheckOutputPath`).
"""
from __future__ import annotations

import argparse
import contextlib
import importlib
import json
import math
import os
import re
import sys
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Callable, Dict, Iterator, List, Optional, Sequence, Tuple, Union

from .. import __version__
from .. import _files
from .._files import WriteAtomically
from .._workers import (INTERRUPTED_STATUS, TERMINATED_STATUS, ForgetSignals, InterruptStatus, ReceivedSignalStatus,
                        SigtermAsInterrupt)
from ..items.solve import IsInterrupt
from ..params.drives import ConfigArgument, DocPath, ShippedDrives

if TYPE_CHECKING:
    from ..drive.wholedrive import Drive

__all__ = ['PROG', 'UsageError', 'BadInput', 'Subcommand', 'COMMAND_MODULES', 'SUBCOMMANDS', 'Subcommands',
           'AddParameterOptions', 'ParametersFromArgs', 'WholeDriveFromArgs', 'WarnUnresolvedRotation',
           'SourceText', 'SourceInfo',
           'StdoutToStderr', 'PrintJson', 'CheckOutputPath', 'CheckFigurePath', 'FIGURE_SUFFIXES',
           'AddOverwriteOption', 'InterruptedLine', 'PositiveFloat', 'PositiveInt', 'BuildParser', 'Main']

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
    """ArgumentParser whose errors become one-line :class:`UsageError` instead of usage + exit.

    Negative numbers in any float notation (``-1e-3``, ``-.5``, ``-inf``) are read as values, not as
    options, so that ``--step-size -1e-3`` reaches the range check instead of "expected one argument".
    """

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(r'^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-inf(inity)?$',
                                                   re.IGNORECASE)

    def error(self, message: str):
        raise UsageError(f"{message} (see '{self.prog} --help')")


def _NumberType(kind, unit: str, low: float, lowOpen: bool):
    name = 'an integer' if kind is int else 'a finite number'
    bound = f"{'>' if lowOpen else '>='} {low:g}{' ' + unit if unit else ''}"

    def Parse(text: str):
        try:
            value = float(text)
        except ValueError:
            value = math.nan
        if not math.isfinite(value) or (kind is int and not value.is_integer()):
            raise argparse.ArgumentTypeError(f"expected {name}{' in ' + unit if unit else ''}, got '{text}'")
        if value < low or (lowOpen and value == low):
            raise argparse.ArgumentTypeError(f"must be {bound}, got {text}{' ' + unit if unit else ''}")
        return kind(value)
    Parse.__name__ = f'{kind.__name__} {bound}'
    return Parse


def PositiveFloat(unit: str = ''):
    """An ``argparse`` type: a finite float > 0 (``--step-size``, ``--end-time``).

    Parameters
    ----------
    unit : str
        Unit named in the error message, e.g. ``'s'``.

    Returns
    -------
    callable
        ``type=`` argument of ``add_argument``; a bad value gives one line such as
        ``argument --step-size: must be > 0 s, got -1e-3 s``.
    """
    return _NumberType(float, unit, 0., True)


def PositiveInt(unit: str = ''):
    """An ``argparse`` type: an integer >= 1, also written as ``1e7``.

    Parameters
    ----------
    unit : str
        Unit named in the error message, e.g. ``'steps'``.

    Returns
    -------
    callable
        ``type=`` argument of ``add_argument``.
    """
    return _NumberType(int, unit, 1, False)


def CheckOutputPath(path, option: str, kind: str = 'file', overwrite: bool = False,
                    contents: Sequence[str] = ()) -> Path:
    """:func:`exudyn_worm._files.CheckOutputPath` for a subcommand: its error becomes a :class:`UsageError`.

    Parameters
    ----------
    path : str or os.PathLike
        The path given by the user.
    option : str
        The option that named it, for the message (e.g. ``'--csv'``).
    kind : {'file', 'folder'}
        What the path is to be.
    overwrite : bool, optional
        Allow replacing an existing file (for a folder: the files of ``contents`` in it).
    contents : sequence of str, optional
        For ``kind='folder'``: the names of the files that will be written into it.

    Returns
    -------
    pathlib.Path
        The path (unchanged).

    Raises
    ------
    UsageError
        As :func:`exudyn_worm._files.CheckOutputPath` describes.
    """
    try:
        return _files.CheckOutputPath(path, option, kind, overwrite, contents)
    except _files.OutputPathError as err:
        raise UsageError(str(err)) from None


#: file formats of the figure options (``--plot``, ``--output`` of ``chart``)
FIGURE_SUFFIXES = ('.png', '.pdf', '.svg')


def CheckFigurePath(path: Union[str, os.PathLike], option: str, overwrite: bool = False) -> Path:
    """:func:`CheckOutputPath` for a figure file: also its format (a suffix of :data:`FIGURE_SUFFIXES`).

    Parameters
    ----------
    path : str or os.PathLike
        The path given by the user.
    option : str
        The option that named it (e.g. ``'--plot'``).
    overwrite : bool, optional
        Allow replacing an existing file.

    Returns
    -------
    pathlib.Path

    Raises
    ------
    UsageError
        For another suffix, or what :func:`CheckOutputPath` refuses.
    """
    if Path(os.fspath(path)).suffix.lower() not in FIGURE_SUFFIXES:
        raise UsageError(f"{option}: expected a file ending in {', '.join(FIGURE_SUFFIXES)}, got '{os.fspath(path)}'")
    return CheckOutputPath(path, option, overwrite=overwrite)


def AddOverwriteOption(parser: argparse.ArgumentParser, what: str = 'the output files') -> None:
    """Add ``--overwrite``: the one switch that lets a subcommand replace existing output files.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The subcommand's parser.
    what : str, optional
        What is replaced, for the help text.
    """
    parser.add_argument('--overwrite', action='store_true',
                        help=f'replace {what} if they exist (without it an existing output file is refused)')


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


class _LazyHelp:
    """A part of a help text (``%(name)s`` of an option, set as an attribute of its action) computed when the help
    is printed, not when the parser is built: the defaults of the analyses load numpy, which ``exudyn-worm --help``
    and an argument error do without. The option's default is then None, and its run function puts the real one in."""

    def __init__(self, text: Callable[[], str]):
        self.text = text

    def __str__(self) -> str:
        return self.text()


class _PresetNames:
    """The preset names (or the default preset) for a help text, looked up only when the help is printed: the
    presets load numpy, which ``exudyn-worm --help`` and an argument error do without."""

    def __init__(self, default: bool = False):
        self.default = default

    def __str__(self) -> str:
        # lazy: start-up (numpy: the presets are read only when a help text is printed)
        from ..drive.config import DEFAULT_PRESET
        from ..drive.presets import PRESETS
        return DEFAULT_PRESET if self.default else ', '.join(PRESETS)


def AddParameterOptions(parser: argparse.ArgumentParser) -> None:
    """Add the options shared by every subcommand that works on a parameter set.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The subcommand's parser; it gets ``--preset NAME``, ``--config FILE.toml``, ``--set KEY=VALUE``
        (repeatable, stored as the list ``args.set``) and ``--json``. Read them back with
        :func:`ParametersFromArgs` / :func:`WholeDriveFromArgs`.
    """
    group = parser.add_argument_group('parameter set (preset, then config file, then --set)')
    preset = group.add_argument('--preset', metavar='NAME', default=None,
                                help="parameter preset, one of: %(presets)s "
                                     "(default: the config file's preset, else %(defaultPreset)s)")
    preset.presets, preset.defaultPreset = _PresetNames(), _PresetNames(default=True)   # read when help is printed
    group.add_argument('--config', metavar='FILE.toml', default=None, type=ConfigArgument,
                       help=f"whole-drive TOML file or one with a [parameters] table (format: "
                            f"{DocPath('drive-files.md')}), or the name of a shipped drive: "
                            f"{', '.join(ShippedDrives()) or 'none found'}")
    group.add_argument('--set', metavar='KEY=VALUE', action='append', default=[], dest='set',
                       help="override one parameter; VALUE has units or is SI, but an angle, a speed or a "
                            "length needs its unit (zero excepted), e.g. --set 'backlash=0.5 mm' --set 'kT=7 kN*m' "
                            "--set motorSpeed=472.5rpm; KEY= takes a key back (repeatable)")
    parser.add_argument('--json', action='store_true',
                        help='print exactly one JSON object on stdout instead of the table')


def ParametersFromArgs(args: argparse.Namespace) -> Dict[str, float]:
    """Resolve the parameter set of the shared options with :func:`~exudyn_worm.drive.config.ResolveParameters`.

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
    # lazy: start-up (numpy: exudyn-worm --help and argument errors)
    from ..drive.config import ResolveParametersWithSources
    resolved = getattr(args, '_resolved', None)
    if resolved is None:                   # resolved once per command: the file is read once
        with BadInput():
            resolved = ResolveParametersWithSources(preset=args.preset, config=_DriveFile(args), sets=args.set)
        args._resolved = resolved
    return dict(resolved[0])


def _DriveFile(args: argparse.Namespace):
    """The drive file of ``--config`` as :func:`~exudyn_worm.drive.config.LoadConfig` reads it, read once per
    command (None without ``--config``)."""
    if not args.config:
        return None
    if getattr(args, '_driveFile', None) is None:
        # lazy: start-up (numpy: exudyn-worm --help and argument errors)
        from ..drive.config import LoadConfig
        with BadInput():
            args._driveFile = LoadConfig(args.config)
    return args._driveFile


def WholeDriveFromArgs(args: argparse.Namespace) -> Drive:
    """The :class:`~exudyn_worm.drive.wholedrive.Drive` of the shared options, resolved and checked once per
    command (a second call returns the same object, so its analyses are computed once).

    Parameters
    ----------
    args : argparse.Namespace
        Parsed arguments of a subcommand with :func:`AddParameterOptions`.

    Returns
    -------
    Drive

    Raises
    ------
    UsageError
        For any bad input (also a drive the model rejects).
    """
    # lazy: start-up (numpy: exudyn-worm --help and argument errors)
    from ..drive.wholedrive import Drive
    drive = getattr(args, '_drive', None)
    if drive is None:
        ParametersFromArgs(args)
        parameters, sources = args._resolved
        with BadInput():
            drive = Drive.FromParameters(parameters, sources, name=SourceText(args))
        args._drive = drive
    return drive


def WarnUnresolvedRotation(drive: Drive, where: str) -> None:
    """Warn, for a command that does not simulate, if any simulation of ``drive`` at its own recommended time step
    (:func:`~exudyn_worm.analysis.simulation.stepsize.RecommendedStepSize`) would turn the worm once in fewer than
    :data:`~exudyn_worm.params.plausibility.MIN_STEPS_PER_ROTATION` steps (a speed in rpm given as rad/s):
    the linear verdict holds for that speed, but no run of the drive could check it.

    Parameters
    ----------
    drive : Drive
        The resolved drive.
    where : str
        The command, the prefix of the warning.
    """
    # lazy: start-up (numpy: exudyn-worm --help and argument errors)
    from ..analysis.simulation.stepsize import RecommendedStepSize
    from ..params.plausibility import CheckWormRotation
    with BadInput():       # the drive itself: its linear analysis is the command's own, not computed again
        CheckWormRotation(dict(drive.parameters), RecommendedStepSize(drive),
                          f"{where} (at the drive's recommended step)")


@contextlib.contextmanager
def StdoutToStderr(active: bool) -> Iterator[None]:
    """Send anything printed inside the block (Python and C level) to stderr, keeping stdout for JSON.

    Parameters
    ----------
    active : bool
        Redirect only if True (e.g. ``args.json``).
    """
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


def PrintJson(data) -> None:
    """Print ``data`` as one JSON object on stdout (no NaN or infinity: JSON has none).

    Parameters
    ----------
    data : dict
        JSON-ready data.
    """
    print(json.dumps(data, indent=2, allow_nan=False))


def SourceInfo(args: argparse.Namespace) -> Dict:
    """Which parameter set a run used, for JSON output: the preset, the config file and the overrides.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed arguments of a subcommand with :func:`AddParameterOptions` (already resolved once, so
        the config file is known to be valid).

    Returns
    -------
    dict
        ``preset`` (the name used, None for a whole-drive file that names none), ``presetFrom``
        (``'--preset'``, ``'config'``, ``'default'`` or None), ``config`` (path or None) and ``overrides``
        (the ``--set`` texts, in order).
    """
    # lazy: start-up (numpy: exudyn-worm --help and argument errors)
    from ..drive.config import DEFAULT_PRESET
    known = getattr(args, '_sourceInfo', None)
    if known is not None:
        return dict(known)
    if args.preset:
        preset, source = args.preset, '--preset'
    else:
        preset, wholeDrive = None, False
        if args.config:
            config = _DriveFile(args)
            preset, wholeDrive = config['preset'], config['wholeDrive']
        if preset:
            source = 'config'
        elif wholeDrive:                 # a whole-drive file inherits no preset
            source = None
        else:
            preset, source = DEFAULT_PRESET, 'default'
    args._sourceInfo = {'preset': preset, 'presetFrom': source, 'config': os.fspath(args.config) if args.config
                        else None, 'overrides': list(args.set)}
    return dict(args._sourceInfo)


def SourceText(args: argparse.Namespace) -> str:
    """Which parameter set a run used: preset, config file and ``--set`` overrides, as one phrase.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed arguments of a subcommand with :func:`AddParameterOptions`.

    Returns
    -------
    str
        E.g. ``preset reel-P1 (default), --set J1=0.3``.
    """
    info = SourceInfo(args)
    parts = [None if info['preset'] is None else
             f"preset {info['preset']}" + {'--preset': '', 'config': ' (from the config)',
                                           'default': ' (default)'}[info['presetFrom']],
             f"config {info['config']}" if info['config'] else None,
             f"--set {' '.join(info['overrides'])}" if info['overrides'] else None]
    return ', '.join(p for p in parts if p)


#: built-in subcommands: modules of :mod:`exudyn_worm.cli`, in the order of ``exudyn-worm --help``
COMMAND_MODULES: Tuple[str, ...] = ('stability', 'check', 'chart', 'simulate', 'sweep', 'chatter')
#: further subcommands registered at run time (plugins, tests), after the built-in ones
SUBCOMMANDS: List[Subcommand] = []


def Subcommands() -> List[Subcommand]:
    """All subcommands: the ``COMMAND`` of each module in :data:`COMMAND_MODULES`, then :data:`SUBCOMMANDS`.

    Returns
    -------
    list of Subcommand
    """
    return [importlib.import_module(f'{__package__}.{name}').COMMAND
            for name in COMMAND_MODULES] + list(SUBCOMMANDS)


def BuildParser() -> argparse.ArgumentParser:
    """Build the argument parser: one subparser per entry of :data:`SUBCOMMANDS`.

    Returns
    -------
    argparse.ArgumentParser
        Parse errors raise :class:`UsageError` instead of printing usage and exiting.
    """
    parser = _Parser(prog=PROG, description='Chatter analysis of self-locking worm gears with Exudyn.')
    parser.add_argument('--version', action='version', version=f'%(prog)s {__version__}')
    sub = parser.add_subparsers(dest='command', metavar='COMMAND', required=True, parser_class=_Parser)
    for command in Subcommands():
        p = sub.add_parser(command.name, help=command.help, description=command.help)
        if command.parameterOptions:
            AddParameterOptions(p)
        command.addArguments(p)
        p.set_defaults(run=command.run)
    return parser


#: the warnings printed in this run of :func:`Main` (each message once, however often it is issued)
_SHOWN: set = set()


def _ShowWarning(message, category, filename, lineno, file=None, line=None) -> None:
    """Print a Python warning as one line ``exudyn-worm: warning: ...`` on stderr (no source path), once per run."""
    # lazy: start-up (numpy: a warning comes from a command that has loaded it)
    from .._checks import WarningText
    text = f"{PROG}: warning: {WarningText(message)}"
    if text not in _SHOWN:
        _SHOWN.add(text)
        print(text, file=sys.stderr)


def _WhereToAdd(err: BaseException, args: Optional[argparse.Namespace]) -> str:
    """For parameters missing from a run with a drive file: the file and the tables to add them to."""
    config = getattr(args, 'config', None)
    if not config:                     # also an argument error: no args
        return ''
    # lazy: start-up (numpy: exudyn-worm --help and argument errors)
    from ..params.drivefile import FileKeyOf
    from ..params.parameters import MissingParameterError
    cause = err.__cause__
    while cause is not None and not isinstance(cause, MissingParameterError):
        cause = cause.__cause__
    if cause is None:
        return ''
    return (f"; to describe the drive in '{config}', add " + ', '.join(f"{FileKeyOf(k)} ({k})" for k in cause.keys)
            + (' (a file with component tables inherits no preset unless it names one)'
               if not getattr(args, 'preset', None) else ''))


def InterruptedLine(err: BaseException, what: str = 'no output file was left half-written') -> int:
    """Print the one line after Ctrl-C or SIGTERM on stderr (a second signal while printing it is ignored).

    Parameters
    ----------
    err : BaseException
        The interrupt (or an error around it, see :func:`~exudyn_worm.items.solve.IsInterrupt`).
    what : str, optional
        What became of the outputs, after the semicolon.

    Returns
    -------
    int
        The exit status: 130 after Ctrl-C, 143 after SIGTERM.
    """
    status = InterruptStatus(err)
    with contextlib.suppress(KeyboardInterrupt, OSError, ValueError):
        sys.stderr.flush()
        print(f"{PROG}: interrupted ({'SIGTERM' if status == TERMINATED_STATUS else 'Ctrl-C'}); {what}",
              file=sys.stderr)
    return status


#: the file name of an error in writing stdout (:class:`_NamedStdout`)
_STDOUT = 'standard output'


class _NamedStdout:
    """sys.stdout whose write errors (a full disk, ``> /dev/full``) name it, so that :func:`Main` can say so."""

    def __init__(self, stream):
        self._stream = stream
        self.error: Optional[OSError] = None     # kept: argparse's --help and --version swallow it

    def _Named(self, method, *args):
        try:
            return method(*args)
        except OSError as err:
            self.error = OSError(err.errno, err.strerror, _STDOUT)
            raise self.error from None

    def write(self, text):
        return self._Named(self._stream.write, text)

    def flush(self):
        return self._Named(self._stream.flush)

    def __getattr__(self, name):
        return getattr(self._stream, name)


def _OSErrorLine(err: OSError) -> int:
    """Print the one line of an error of the system (a full disk, a name too long) on stderr; return the exit
    status 1. After a stdout that cannot be written, what is still buffered for it is dropped (a quiet exit)."""
    if err.filename == _STDOUT:
        with contextlib.suppress(OSError, ValueError, AttributeError):
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    what = f'cannot write {_STDOUT}' if err.filename == _STDOUT else err.filename or 'a file'
    with contextlib.suppress(OSError, ValueError):
        print(f"{PROG}: error: {what}: {err.strerror or err}", file=sys.stderr)
    return 1


def Main(argv: Optional[Sequence[str]] = None) -> int:
    """Run the command line; return the exit status.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments without the program name (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        0 on success, 1 if a validation failed or an output could not be written (a full disk, a stdout that
        cannot be written: one line), 2 for bad input (one line ``exudyn-worm: error: ...``
        on stderr), 130 after Ctrl-C and 143 after SIGTERM (one line ``exudyn-worm: interrupted ...`` on stderr, no
        traceback).
    """
    args = None
    _SHOWN.clear()
    ForgetSignals()
    stdout = _NamedStdout(sys.stdout)
    try:
        with SigtermAsInterrupt(), contextlib.redirect_stdout(stdout):  # SIGTERM: as Ctrl-C, with status 143
            args = BuildParser().parse_args(argv)
            # lazy: start-up (numpy: exudyn-worm --help and argument errors end above)
            from ..params.plausibility import ImplausibleValueWarning
            with warnings.catch_warnings():
                warnings.showwarning = _ShowWarning      # a warning of any subcommand reads like our errors
                warnings.simplefilter('always', ImplausibleValueWarning)  # shown once per run by _ShowWarning
                status = int(args.run(args) or 0)
            if ReceivedSignalStatus() and status not in (INTERRUPTED_STATUS, TERMINATED_STATUS):
                return InterruptedLine(KeyboardInterrupt())   # swallowed by a library: its results are not trusted
            sys.stdout.flush()                        # a stdout that cannot be written fails here, not at exit
            if stdout.error is not None:              # ... or failed before, and the error was swallowed
                raise stdout.error
            return status
    except UsageError as err:
        if IsInterrupt(err) or ReceivedSignalStatus():   # also an interrupt a library turned into another error
            return InterruptedLine(err)
        message = ' '.join((str(err) + _WhereToAdd(err, args)).split())
        print(f"{PROG}: error: {message}", file=sys.stderr)
        return 2
    except KeyboardInterrupt as err:   # Ctrl-C, SIGTERM: one line, no traceback; outputs are written atomically
        return InterruptedLine(err)
    except BrokenPipeError:            # output piped into e.g. `head`: stop quietly
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except PermissionError as err:     # a file or folder of the user's that this user may not read or write
        print(f"{PROG}: error: {err.filename or 'a file'}: {err.strerror or 'permission denied'}", file=sys.stderr)
        return 2
    except OSError as err:             # a full disk, a name too long, a stdout that cannot be written: one line
        return InterruptedLine(err) if ReceivedSignalStatus() else _OSErrorLine(err)
    except SystemExit as err:          # --help, --version
        try:
            sys.stdout.flush()             # what they printed: a stdout that cannot be written is said
        except OSError as failed:
            stdout.error = OSError(failed.errno, failed.strerror, _STDOUT)
        if stdout.error is not None:
            return _OSErrorLine(stdout.error)
        return err.code if isinstance(err.code, int) else 0 if err.code is None else 2
    except Exception as err:           # e.g. Exudyn's SystemError around a pending Ctrl-C
        if not (IsInterrupt(err) or ReceivedSignalStatus()):
            raise                      # an internal error: its traceback is for the bug report
        return InterruptedLine(err)
