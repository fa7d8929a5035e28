"""``python -m exudyn_worm`` and the ``exudyn-worm`` console script: the command line, with Ctrl-C and SIGTERM
handled from its first line.

Loading the command line takes a moment (numpy, the parameter registry, every subcommand's module); a Ctrl-C or a
SIGTERM in that moment ends the command like one at any later moment: one line on stderr, no traceback, exit
status 130 (Ctrl-C) or 143 (SIGTERM). Only ``sys`` and ``signal`` are loaded before the handlers are in place.
What comes before this module's first line, Python's own start (about 0.1 s), is Python's: a signal then has its
default effect.
"""
from __future__ import annotations    # the annotations below name typing, which is loaded after the handlers

import signal
import sys

__all__ = ['Main', 'Run']

#: the signals (SIGINT, SIGTERM) that arrived while this entry point's handlers were in place
_RECEIVED: list = []


def _OnSignal(signum, frame):
    """Ctrl-C or SIGTERM while the command line loads (or between its own handlers): a ``KeyboardInterrupt``,
    remembered, so that an error it causes in a module being loaded (numpy's ImportError) counts as the interrupt."""
    _RECEIVED.append(signum)
    raise KeyboardInterrupt


def _Install() -> list:
    """Install :func:`_OnSignal` for SIGTERM, and for SIGINT unless it is ignored; return what to restore."""
    restore = []
    for number in (signal.SIGINT, signal.SIGTERM):
        try:
            previous = signal.getsignal(number)
            if number == signal.SIGINT and previous is not signal.default_int_handler:
                continue                                  # ignored (a background job) or the caller's own: kept
            signal.signal(number, _OnSignal)
            restore.append((number, previous))
        except (ValueError, OSError):                     # not the main thread: nothing to handle
            pass
    return restore


def _Interrupted() -> int:
    """Print the one line of an interrupt the command line could not report itself; return the exit status."""
    terminated = signal.SIGTERM in _RECEIVED
    try:
        print(f"exudyn-worm: interrupted ({'SIGTERM' if terminated else 'Ctrl-C'}); no output file was left "
              f"half-written", file=sys.stderr)
    except (KeyboardInterrupt, OSError, ValueError):
        pass
    return 143 if terminated else 130


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
    del _RECEIVED[:]
    restore = _Install()
    try:
        try:
            from .cli import main   # lazy: the signal handlers are in place before the command line loads
            return main.Main(argv)
        finally:
            for number, previous in restore:
                signal.signal(number, previous)
    except KeyboardInterrupt:
        return _Interrupted()
    except Exception:
        if not _RECEIVED:
            raise                   # an internal error: its traceback is for the bug report
        return _Interrupted()       # an error of a module interrupted while it loaded


def Run() -> int:
    """The console script ``exudyn-worm``: :func:`Main`, then Ctrl-C and SIGTERM are ignored while the process
    exits (the command has ended and said so; a late signal would only add a traceback).

    Returns
    -------
    int
        The exit status.
    """
    try:
        status = Main()
    except KeyboardInterrupt:           # a second signal in the moment the first one's line is printed
        status = 143 if signal.SIGTERM in _RECEIVED else 130
    for number in (signal.SIGINT, signal.SIGTERM):
        try:
            signal.signal(number, signal.SIG_IGN)
        except (ValueError, OSError):
            pass
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
