"""``exudyn-worm validate``: the checks against the numbers published in the paper."""
from __future__ import annotations

import argparse
import sys

from ..cli import PROG, CheckOutputPath, Subcommand, UsageError

__all__ = ['COMMAND']


def _AddArguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument('--report', metavar='PATH', default=None,
                        help='write the Markdown report here (default: validation/REPORT.md of the source tree)')
    parser.add_argument('--no-report', action='store_true', dest='noReport', help='write no report')
    parser.add_argument('--quick', action='store_true', help='skip the slow checks')


def _Run(args: argparse.Namespace) -> int:
    try:
        from ..validation import DEFAULT_REPORT_PATH, RunValidation
    except ImportError as err:
        raise UsageError(f"validate is not available: cannot import exudyn_worm.validation.RunValidation "
                         f"({err})") from err
    if args.noReport and args.report:
        raise UsageError("give either --report PATH or --no-report, not both")
    if args.noReport:
        report = None
    elif args.report is not None:
        report = CheckOutputPath(args.report, '--report')
    else:
        report = DEFAULT_REPORT_PATH if DEFAULT_REPORT_PATH.parent.is_dir() else None
        if report is None:
            print(f"{PROG}: note: no source tree found; no report written (use --report PATH)", file=sys.stderr)
    summary = RunValidation(reportPath=report, quick=args.quick)
    for line in summary.lines:
        print(line)
    return 0 if summary.passed else 1


COMMAND = Subcommand('validate', 'check the implementation against the numbers published in the paper',
                     _AddArguments, _Run, parameterOptions=False)
