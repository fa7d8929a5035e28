"""``python -m exudyn_worm`` and the ``exudyn-worm`` console script: the command line, with Ctrl-C and SIGTERM
handled from its first line.

Loading the command line takes a moment (numpy, the parameter registry, every subcommand's module); a Ctrl-C or a
SIGTERM in that moment ends the command like one at any later moment: one line on stderr, no traceback, exit
status 130 (Ctrl-C) or 143 (SIGTERM). Only the standard library and :mod:`exudyn_worm._workers` are loaded before
the handlers are in place.
"""
import contextlib
import signal
import sys
from typing import Optional, Sequence

from ._workers import InterruptStatus, SigtermAsInterrupt, TERMINATED_STATUS

__all__ = ['Main', 'Run']


def Main(argv: Optional[Sequence[str]] = None) -> int:
    """Run the command line (:func:`exudyn_worm.cli.main.Main`) with SIGTERM handled as Ctrl-C before it loads.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments without the program name (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        The exit status of :func:`exudyn_worm.cli.main.Main`; 130 (Ctrl-C) or 143 (SIGTERM) if interrupted while
        it loads.
    """
    try:
        with SigtermAsInterrupt():
            from .cli import main   # lazy: the signal handlers are in place before the command line loads
            return main.Main(argv)
    except KeyboardInterrupt as err:
        status = InterruptStatus(err)
        with contextlib.suppress(KeyboardInterrupt, OSError, ValueError):
            print(f"exudyn-worm: interrupted ({'SIGTERM' if status == TERMINATED_STATUS else 'Ctrl-C'}); "
                  f"no output file was written", file=sys.stderr)
        return status


def Run() -> int:
    """The console script ``exudyn-worm``: :func:`Main`, then Ctrl-C and SIGTERM are ignored while the process
    exits (the command has ended and said so; a late signal would only add a traceback).

    Returns
    -------
    int
        The exit status.
    """
    status = Main()
    for number in (signal.SIGINT, signal.SIGTERM):
        with contextlib.suppress(ValueError, OSError, AttributeError):
            signal.signal(number, signal.SIG_IGN)
    return status


if __name__ == '__main__':
    sys.exit(Run())
