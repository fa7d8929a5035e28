"""``exudyn-worm validate``: a thin entry to the validation suite of the source checkout.

The suite (``validation/`` beside ``exudyn_worm/``, with the paper's reference data) is not part of the
installed package. This command finds it next to the package (editable install of a checkout) or in the
current directory and runs it exactly as ``python -m validation`` does; without a checkout it stops with
one line on stderr and exit status 2.
"""
from __future__ import annotations

import argparse
import importlib
import sys
from pathlib import Path
from types import ModuleType
from typing import Optional

from ..cli import CheckOutputPath, Subcommand, UsageError

__all__ = ['COMMAND', 'FindSuite', 'AddValidationArguments']


def FindSuite() -> Optional[Path]:
    """The repository root holding the validation suite, or None.

    Returns
    -------
    Path or None
        The directory containing ``validation/cli.py`` and ``validation/paper/reference.csv``: the
        checkout the package was installed from (editable install), else the current directory.
    """
    import exudyn_worm
    for root in (Path(exudyn_worm.__file__).resolve().parents[1], Path.cwd().resolve()):
        if (root / 'validation' / 'cli.py').is_file() and (root / 'validation' / 'paper' / 'reference.csv').is_file():
            return root
    return None


def _Suite(root: Path) -> ModuleType:
    if str(root) not in sys.path:
        sys.path.insert(0, str(root))
    return importlib.import_module('validation.cli')


def AddValidationArguments(parser: argparse.ArgumentParser) -> None:
    """Add the options of the validation (shared by ``python -m validation`` and ``exudyn-worm validate``).

    Parameters
    ----------
    parser : argparse.ArgumentParser
        Gets ``--report PATH``, ``--quick`` / ``--full`` and ``--quiet``.
    """
    parser.add_argument('--report', metavar='PATH', default=None,
                        help='write the Markdown report to PATH (nothing is written without it)')
    mode = parser.add_mutually_exclusive_group()
    mode.add_argument('--quick', action='store_true', help='skip the time-domain simulations')
    mode.add_argument('--full', action='store_true',
                      help='also run the slow forensic searches (about 9 min in all on an idle 2-core machine, 16-28 min '
                           'on a loaded one; the committed report uses it)')
    parser.add_argument('--quiet', action='store_true', default=None, help='no progress bar on stderr')


def _Run(args: argparse.Namespace) -> int:
    if args.report is not None:
        CheckOutputPath(args.report, '--report')          # before anything is computed
    root = FindSuite()
    if root is None:
        raise UsageError("validate: the validation suite is not installed with the package; run "
                         "'python -m validation' from the root of a source checkout (or this command "
                         "inside one)")
    try:
        return _Suite(root).Run(args)
    except ValueError as err:
        raise UsageError(str(err)) from err


COMMAND = Subcommand('validate', 'check the implementation against the numbers published in the paper '
                     '(needs the source checkout; same as python -m validation)',
                     AddValidationArguments, _Run, parameterOptions=False)
