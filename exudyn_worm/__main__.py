"""``python -m exudyn_worm`` and the ``exudyn-worm`` console script: the command line, with Ctrl-C and SIGTERM
handled from its first line.

Loading the command line takes a moment (numpy, the parameter registry, every subcommand's module); a Ctrl-C or a
SIGTERM in that moment ends the command like one at any later moment: one line on stderr, no traceback, exit
status 130 (Ctrl-C) or 143 (SIGTERM). Only ``signal``, ``sys`` and :mod:`exudyn_worm._workers` (a few ms) are
loaded before the handlers are in place; they remember each signal, so that an interrupt that a module being
loaded swallows or turns into another error still ends the command as an interrupt. What comes before this
module's first line, Python's own start (about 0.1 s), is Python's: a signal then has its default effect.
"""
import signal
import sys
from typing import Optional, Sequence

from ._workers import InstallSignalHandlers, ReceivedSignalStatus, RestoreSignalHandlers, ForgetSignals

__all__ = ['Main', 'Run']


def _Interrupted(status: int) -> int:
    """Print the one line of an interrupt the command line could not report itself; return the exit status."""
    try:
        print(f"exudyn-worm: interrupted ({'SIGTERM' if status == 143 else 'Ctrl-C'}); no output file was left "
              f"half-written", file=sys.stderr)
    except (KeyboardInterrupt, OSError, ValueError):
        pass
    return status


def _Main(argv: Optional[Sequence[str]], exiting: bool) -> int:
    """:func:`Main`; with ``exiting``, Ctrl-C and SIGTERM are ignored afterwards instead of restored (the process
    exits: a late signal would only add a traceback or end it without a word)."""
    ForgetSignals()
    previous = InstallSignalHandlers()
    try:
        try:
            from .cli import main   # lazy: the signal handlers are in place before the command line loads
            if ReceivedSignalStatus():                    # swallowed while it loaded
                raise KeyboardInterrupt
            return main.Main(argv)
        finally:
            if exiting:
                RestoreSignalHandlers([(number, signal.SIG_IGN) for number, _ in previous])
            else:
                RestoreSignalHandlers(previous)
    except KeyboardInterrupt:
        return _Interrupted(ReceivedSignalStatus() or 130)
    except Exception:
        if not ReceivedSignalStatus():
            raise                   # an internal error: its traceback is for the bug report
        return _Interrupted(ReceivedSignalStatus())   # an error of a module interrupted while it loaded


def Main(argv: Optional[Sequence[str]] = None) -> int:
    """Run the command line (:func:`exudyn_worm.cli.main.Main`) with Ctrl-C and SIGTERM handled before it loads.

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
    return _Main(argv, exiting=False)


def Run() -> int:
    """The console script ``exudyn-worm``: :func:`Main`, after which Ctrl-C and SIGTERM are ignored while the process
    exits (the command has ended and said so).

    Returns
    -------
    int
        The exit status.
    """
    try:
        status = _Main(None, exiting=True)
    except KeyboardInterrupt:           # a second signal in the moment the first one's line is printed
        status = ReceivedSignalStatus() or 130
    _ForgetHandledInterrupt()
    return status


def _ForgetHandledInterrupt() -> None:
    """CPython remembers a Ctrl-C raised inside code that a C extension runs with ``PyRun_String`` (pybind11's
    ``exec`` while a module loads) even when it was handled, and then ends the process by SIGINT at exit instead of
    with the status returned (seen after a SIGTERM as much as after Ctrl-C): the interrupt was handled, forget it."""
    try:
        import ctypes               # lazy: only at the exit, and only CPython keeps this flag
        ctypes.c_int.in_dll(ctypes.pythonapi, '_Py_UnhandledKeyboardInterrupt').value = 0
    except (ImportError, AttributeError, ValueError, OSError):
        pass


if __name__ == '__main__':
    sys.exit(Run())
