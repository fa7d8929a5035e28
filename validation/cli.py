"""Command line of the validation: ``python -m validation``, run from the root of the source checkout.

The one way in: the suite lives beside its data in the checkout and is not part of the installed package.
Prints the summary line and one line per check on stdout; writes the Markdown report only with
``--report PATH``. With ``--baseline FILE`` it compares every check with a recorded baseline instead and
prints only what changed (``validation/baseline.py``); ``--record-baseline FILE`` records one.

Exit status: 0 if no check failed (with ``--baseline``: if no check changed), 1 otherwise, 2 for bad input,
130 after Ctrl-C, 143 after SIGTERM (one line on stderr; no report or baseline is left half-written).
"""
from __future__ import annotations

import argparse
import contextlib
import json
import sys
from pathlib import Path
from typing import Optional, Sequence

__all__ = ['PROG', 'AddValidationArguments', 'Run', 'Main']

PROG = 'python -m validation'


class _Parser(argparse.ArgumentParser):
    """Parse errors as one line (``ValueError``), like every other error of the command."""

    def error(self, message: str):
        raise ValueError(f"{message} (see '{PROG} --help')")


def AddValidationArguments(parser: argparse.ArgumentParser) -> None:
    """Add the options of ``python -m validation``.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        Gets ``--report PATH``, ``--quick`` / ``--full``, ``--baseline FILE`` / ``--record-baseline FILE``,
        ``--overwrite`` and ``--quiet``.
    """
    parser.add_argument('--report', metavar='PATH', default=None,
                        help='write the Markdown report to PATH (nothing is written without it)')
    mode = parser.add_mutually_exclusive_group()
    mode.add_argument('--quick', action='store_true', help='skip the time-domain simulations')
    mode.add_argument('--full', action='store_true',
                      help='also run the slow forensic searches (about 9 min in all on an idle 2-core machine, 16-28 min '
                           'on a loaded one; the committed report uses it)')
    regression = parser.add_mutually_exclusive_group()
    regression.add_argument('--baseline', metavar='FILE', default=None,
                            help='compare every check with the baseline FILE (recorded in the same mode): print the '
                                 'checks whose verdict changed or whose value moved by more than the row\'s '
                                 'tolerance; exit 0 when none did (e.g. validation/baseline-quick.json with --quick)')
    regression.add_argument('--record-baseline', metavar='FILE', default=None,
                            help='record this run as a baseline in FILE (JSON)')
    parser.add_argument('--overwrite', action='store_true',
                        help='replace an existing --report or --record-baseline file (refused without it)')
    parser.add_argument('--quiet', action='store_true', default=None, help='no progress bar on stderr')


def _CheckOutput(path: Optional[str], option: str, overwrite: bool) -> Optional[Path]:
    """The command line's one check of an output (a folder that exists and may be written, an existing file only
    with ``--overwrite``, unsearchable folders included), before any check runs."""
    from exudyn_worm._files import CheckOutputPath
    if path is None:
        return None
    return CheckOutputPath(path, option, overwrite=overwrite)          # a ValueError names the option


def _Mode(args: argparse.Namespace) -> str:
    return 'quick' if args.quick else 'full' if getattr(args, 'full', False) else 'default'


def Run(args: argparse.Namespace) -> int:
    """Run the validation for parsed ``args`` (the options of :func:`AddValidationArguments`).

    Parameters
    ----------
    args : argparse.Namespace
        ``report``, ``quick``, ``full``, ``baseline``, ``record_baseline``, ``overwrite`` and ``quiet``.

    Returns
    -------
    int
        0 if no check failed (with ``baseline``: if no check changed against it), 1 otherwise.

    Raises
    ------
    ValueError
        For an output path that cannot be written or exists without ``overwrite``, or a baseline that cannot be
        read or was recorded in another mode (all checked before computing).
    """
    from .baseline import BaselineRecord, CompareWithBaseline, LoadBaseline
    from .runner import RunValidation, WriteText
    overwrite = getattr(args, 'overwrite', False)
    report = _CheckOutput(args.report, '--report', overwrite)
    record = _CheckOutput(getattr(args, 'record_baseline', None), '--record-baseline', overwrite)
    baselinePath = getattr(args, 'baseline', None)
    baseline = LoadBaseline(baselinePath, _Mode(args)) if baselinePath is not None else None
    summary = RunValidation(reportPath=report, quick=args.quick, full=getattr(args, 'full', False),
                            quiet=getattr(args, 'quiet', None))
    if record is not None:
        WriteText(record, json.dumps(BaselineRecord(summary), indent=1, allow_nan=False) + '\n')
    try:
        if baseline is None:
            for line in summary.lines:
                print(line)
        else:
            changed = CompareWithBaseline(summary, baseline)
            print(summary.lines[0])
            print(f"against the baseline {baselinePath} ({baseline['mode']} mode, {len(baseline['checks'])} checks): "
                  + (f"{len(changed)} check(s) changed" if changed else 'no check changed'))
            for line in changed:
                print(line)
    except BrokenPipeError:      # output piped into e.g. `head`
        pass
    for path in (report, record):
        if path is not None:
            print(f"wrote {path.resolve()}", file=sys.stderr)
    if baseline is not None:
        return 1 if changed else 0
    return 0 if summary.passed else 1


def Main(argv: Optional[Sequence[str]] = None) -> int:
    """``python -m validation``: parse ``argv`` and run; bad input is one line on stderr and status 2.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments (default ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status (130 after Ctrl-C, 143 after SIGTERM: one line on stderr, no traceback).
    """
    from exudyn_worm._workers import SigtermAsInterrupt
    from exudyn_worm.items.solve import IsInterrupt
    try:
        parser = _Parser(prog=PROG, description='check exudyn-worm against the numbers published '
                                            'in the paper (run from the root of the source checkout)')
        AddValidationArguments(parser)
        args = parser.parse_args(argv)
        with SigtermAsInterrupt():              # SIGTERM stops it as Ctrl-C does (status 143)
            return Run(args)
    except ValueError as err:
        print(f'{PROG}: error: {err}', file=sys.stderr)
        return 2
    except OSError as err:                      # a full disk: one line (the report is complete or absent)
        with contextlib.suppress(OSError, ValueError):
            print(f"{PROG}: error: {err.filename or 'a file'}: {err.strerror or err}", file=sys.stderr)
        return 1
    except Exception as err:
        if not IsInterrupt(err):
            raise
        return _Interrupted(err)
    except KeyboardInterrupt as err:
        return _Interrupted(err)


def _Interrupted(err: BaseException) -> int:
    from exudyn_worm._workers import TERMINATED_STATUS, InterruptStatus
    status = InterruptStatus(err)
    with contextlib.suppress(KeyboardInterrupt, OSError, ValueError):
        print(f"{PROG}: interrupted ({'SIGTERM' if status == TERMINATED_STATUS else 'Ctrl-C'}); the validation "
              f"stopped, no check was recorded and no file written", file=sys.stderr)
    return status
