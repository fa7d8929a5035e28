"""Command line of the validation: ``python -m validation`` (also ``exudyn-worm validate`` in a checkout).

Prints the summary line and one line per check on stdout; writes the Markdown report only with
``--report PATH``. Exit status 0 if no check failed, 1 if one failed, 2 for bad input.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Optional, Sequence

from exudyn_worm.commands.validate import AddValidationArguments

__all__ = ['Run', 'Main']

PROG = 'python -m validation'


def _CheckReportPath(path: Optional[str]) -> Optional[Path]:
    if path is None:
        return None
    p = Path(path)
    if p.is_dir() or not p.parent.is_dir():
        raise ValueError(f"--report: expected a file path in an existing directory, got '{path}'")
    return p


def Run(args: argparse.Namespace) -> int:
    """Run the validation for parsed ``args`` (options of :func:`exudyn_worm.commands.validate.AddValidationArguments`).

    Parameters
    ----------
    args : argparse.Namespace
        ``report`` (path or None), ``quick``, ``full`` and ``quiet``.

    Returns
    -------
    int
        0 if no check failed, 1 otherwise.

    Raises
    ------
    ValueError
        If ``--report`` names a directory or a file in a missing directory (checked before computing).
    """
    from .runner import RunValidation
    report = _CheckReportPath(args.report)
    summary = RunValidation(reportPath=report, quick=args.quick, full=getattr(args, 'full', False),
                            quiet=getattr(args, 'quiet', None))
    try:
        for line in summary.lines:
            print(line)
    except BrokenPipeError:      # output piped into e.g. `head`
        pass
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
        Exit status.
    """
    parser = argparse.ArgumentParser(prog=PROG, description='check exudyn-worm against the numbers published '
                                     'in the paper (run from the repository root)')
    AddValidationArguments(parser)
    args = parser.parse_args(argv)
    try:
        return Run(args)
    except ValueError as err:
        print(f'{PROG}: error: {err}', file=sys.stderr)
        return 2
