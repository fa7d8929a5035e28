"""Worker processes that end with their parent, and SIGTERM handled like Ctrl-C.

Every process pool of the package (the study's, the chatter branch's) starts its workers with
:func:`WorkerInit`: Ctrl-C is left to the parent (no traceback from a worker), SIGTERM ends a worker at once,
and on Linux the kernel sends it SIGKILL when the parent dies, even by ``kill -9``
(``prctl(PR_SET_PDEATHSIG)``). :func:`CancelPool` stops a pool at once on Ctrl-C, SIGTERM or an error.
:func:`SigtermAsInterrupt` turns SIGTERM (a job scheduler's time limit, ``kill``) into :class:`Terminated`, a
``KeyboardInterrupt``, so that every path that cleans up after Ctrl-C (temporary files, a study's last record)
does so after SIGTERM too; :func:`InterruptStatus` gives the exit status (130 or 143).

A worker starts with the thread variables of BLAS and OpenMP at 1 (:func:`SingleThreadedBlas`): the pool already has
a worker per core, and a library that loads in the worker (a spawned worker's numpy, a child process) then starts
no more threads. The BLAS a forked worker inherits from its parent keeps its threads: limiting it there made a sweep
of 16 reel runs in 2 workers 5 % slower (benchmarks/README.md, "Worker processes and BLAS threads").
"""
from __future__ import annotations

import contextlib
import os
import signal
import sys
import threading
import weakref
from typing import Iterable, Iterator, Optional, Sequence

__all__ = ['Terminated', 'TerminationRequested', 'SigtermAsInterrupt', 'InterruptStatus', 'WorkerInit', 'CancelPool',
           'INTERRUPTED_STATUS', 'TERMINATED_STATUS', 'InstallSignalHandlers', 'RestoreSignalHandlers',
           'ReceivedSignalStatus', 'ForgetSignals', 'SignalsHeld', 'SingleThreadedBlas', 'THREAD_VARIABLES']

#: exit status after Ctrl-C (SIGINT): 128 + 2, the shell's convention
INTERRUPTED_STATUS = 130
#: exit status after SIGTERM: 128 + 15
TERMINATED_STATUS = 143

_PR_SET_PDEATHSIG = 1          # <linux/prctl.h>

#: environment variables that BLAS and OpenMP libraries read when they load: the number of threads they start
THREAD_VARIABLES = ('OMP_NUM_THREADS', 'OPENBLAS_NUM_THREADS', 'MKL_NUM_THREADS', 'BLIS_NUM_THREADS')
#: the thread setters of OpenBLAS builds: its own, the 64-bit-integer build, and the one numpy's wheels bundle
_OPENBLAS_SETTERS = ('openblas_set_num_threads', 'openblas_set_num_threads64_', 'scipy_openblas_set_num_threads64_',
                     'scipy_openblas_set_num_threads')


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised like Ctrl-C by the handler of :func:`SigtermAsInterrupt`."""


#: set when SIGTERM arrives inside :func:`SigtermAsInterrupt` (a solver that swallowed the exception of its user
#: function and stopped early learns from it that it was terminated, :func:`TerminationRequested`)
_terminated = [False]
#: the signals (SIGINT, SIGTERM) received by the handlers of this module since :func:`ForgetSignals`
_received: list = []


def _RaiseTerminated(signum, frame):
    _terminated[0] = True
    _received.append(signum)
    raise Terminated()


def _RaiseInterrupt(signum, frame):
    _received.append(signum)
    raise KeyboardInterrupt()


def InstallSignalHandlers() -> list:
    """Handle Ctrl-C (unless it is ignored, as in a background job) and SIGTERM as :func:`SigtermAsInterrupt` does,
    remembering each signal (:func:`ReceivedSignalStatus`): the entry point of the command line calls it first.

    Returns
    -------
    list of (int, handler)
        The previous handlers, for :func:`RestoreSignalHandlers`.
    """
    previous = []
    for number, handler in ((signal.SIGINT, _RaiseInterrupt), (signal.SIGTERM, _RaiseTerminated)):
        try:
            old = signal.getsignal(number)
            if number == signal.SIGINT and old is not signal.default_int_handler:
                continue                                  # ignored, or the caller's own: kept
            signal.signal(number, handler)
            previous.append((number, old))
        except (ValueError, OSError, AttributeError):      # not the main thread
            pass
    return previous


def RestoreSignalHandlers(previous: Sequence) -> None:
    """Put back the handlers that :func:`InstallSignalHandlers` replaced.

    Parameters
    ----------
    previous : sequence of (int, handler)
        What :func:`InstallSignalHandlers` returned.
    """
    for number, handler in previous:
        with contextlib.suppress(ValueError, OSError, TypeError):
            signal.signal(number, handler)


def ReceivedSignalStatus() -> Optional[int]:
    """The exit status of a signal received by this module's handlers since :func:`ForgetSignals`: 143 after
    SIGTERM, 130 after Ctrl-C, None if none came. A library that swallows the ``KeyboardInterrupt`` (or turns it
    into another error) cannot hide the signal from it.

    Returns
    -------
    int or None
    """
    if not _received:
        return None
    return TERMINATED_STATUS if signal.SIGTERM in _received else INTERRUPTED_STATUS


def ForgetSignals() -> None:
    """Start a command afresh for :func:`ReceivedSignalStatus`."""
    del _received[:]


def TerminationRequested() -> bool:
    """Whether SIGTERM arrived inside the current :func:`SigtermAsInterrupt` block.

    Returns
    -------
    bool
    """
    return _terminated[0]


@contextlib.contextmanager
def SigtermAsInterrupt() -> Iterator[None]:
    """Within the block, SIGTERM raises :class:`Terminated` (a ``KeyboardInterrupt``) in the main thread.

    Outside the main thread (where Python cannot set a handler) the block runs unchanged. The previous handler
    is restored on leaving.
    """
    _terminated[0] = False
    try:
        previous = signal.signal(signal.SIGTERM, _RaiseTerminated)
    except (ValueError, AttributeError):      # not the main thread, or no SIGTERM
        yield
        return
    interrupt = signal.getsignal(signal.SIGINT)
    if interrupt is signal.default_int_handler:   # Ctrl-C as before, but remembered (ReceivedSignalStatus)
        signal.signal(signal.SIGINT, _RaiseInterrupt)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)
        if interrupt is signal.default_int_handler:
            signal.signal(signal.SIGINT, interrupt)


#: the signals that :func:`SignalsHeld` holds back
_HELD = (signal.SIGINT, signal.SIGTERM)


@contextlib.contextmanager
def SignalsHeld() -> Iterator[None]:
    """Within the block, Ctrl-C and SIGTERM wait (they are blocked) and arrive as the block ends: for a pool's
    first ``submit``, which forks its workers. A ``KeyboardInterrupt`` raised inside ``os.fork``'s handlers (those
    of ``logging`` release a lock there) is printed by Python as 'Exception ignored' and lost; held, it is raised
    after the fork, where the pool is cancelled. The workers let them through again (:func:`WorkerInit`).
    """
    try:
        previous = signal.pthread_sigmask(signal.SIG_BLOCK, _HELD)
    except (AttributeError, OSError, ValueError):         # no pthread_sigmask (Windows)
        yield
        return
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


def InterruptStatus(err: BaseException) -> int:
    """The exit status of an interrupt: 143 if SIGTERM (a :class:`Terminated` in the chain of ``err``), else 130.

    Parameters
    ----------
    err : BaseException
        A ``KeyboardInterrupt``, or an error raised around one (Exudyn's ``SystemError``).

    Returns
    -------
    int
    """
    seen = set()
    while err is not None and id(err) not in seen:
        if isinstance(err, Terminated):
            return TERMINATED_STATUS
        seen.add(id(err))
        err = err.__cause__ or err.__context__
    return ReceivedSignalStatus() or INTERRUPTED_STATUS


def _DieWithParent(parent: int) -> None:
    """Linux: ask the kernel for SIGKILL when the parent ends; if it has ended already, end now."""
    if not sys.platform.startswith('linux'):
        return
    try:
        # lazy: only a worker needs them, and the command line's entry point loads this module before all others
        import ctypes
        import ctypes.util
        libc = ctypes.CDLL(ctypes.util.find_library('c') or 'libc.so.6', use_errno=True)
        libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    except (OSError, AttributeError):
        return
    if os.getppid() != parent:                # the parent died before the request: nobody would kill us
        os._exit(1)


def WorkerInit(parent: Optional[int] = None) -> None:
    """Initializer of a pool's worker process (``initializer=WorkerInit, initargs=(os.getpid(),)``).

    stdout goes to stderr (stdout may carry the parent's JSON); Ctrl-C is ignored (the parent stops the pool
    and reports it once); SIGTERM has its default action (the parent's handler is not inherited by a forked
    worker); on Linux the worker gets SIGKILL when the parent ends.

    Parameters
    ----------
    parent : int, optional
        Process id of the parent (default ``os.getppid()`` at the worker's start).
    """
    try:
        os.dup2(2, 1)
    except OSError:
        pass
    for number, handler in ((signal.SIGINT, signal.SIG_IGN), (signal.SIGTERM, signal.SIG_DFL)):
        with contextlib.suppress(ValueError, OSError, AttributeError):
            signal.signal(number, handler)
    with contextlib.suppress(ValueError, OSError, AttributeError):   # forked where they were held (SignalsHeld)
        signal.pthread_sigmask(signal.SIG_UNBLOCK, _HELD)
    _DieWithParent(os.getppid() if parent is None else parent)
    SingleThreadedBlas(loaded=False)


def SingleThreadedBlas(loaded: bool = True) -> str:
    """Run BLAS (numpy's linear algebra) on one thread in this process, for a worker of a pool with a worker per core.

    Sets :data:`THREAD_VARIABLES` to 1 (libraries loaded later, also by the process's children, read them) and, with
    ``loaded``, limits the libraries already loaded too (a forked worker inherits numpy's BLAS from its parent, with
    its threads): with ``threadpoolctl`` where it is installed, else through OpenBLAS's own setter where OpenBLAS is
    loaded (the BLAS of numpy's wheels).

    Parameters
    ----------
    loaded : bool, optional
        Also limit the libraries already loaded (default True). :func:`WorkerInit` passes False: limiting the
        OpenBLAS of numpy's wheels in a forked worker made a sweep 5 % slower, measured.

    Returns
    -------
    str
        How the loaded libraries were limited: ``'threadpoolctl'``, ``'openblas'``, or ``'environment'`` (only
        the variables: ``loaded`` False, no BLAS loaded yet, or one that neither way reaches).
    """
    for name in THREAD_VARIABLES:
        os.environ[name] = '1'
    if not loaded:
        return 'environment'
    try:
        from threadpoolctl import threadpool_limits  # lazy: optional package, not a dependency
    except ImportError:
        pass
    else:
        threadpool_limits(limits=1)
        return 'threadpoolctl'
    # lazy: only a worker needs it, and the command line's entry point loads this module before all others
    import ctypes
    limited = False
    for path in _LoadedLibraries('openblas'):
        try:
            library = ctypes.CDLL(path)          # already loaded: the same library, not a second copy
        except OSError:
            continue
        for symbol in _OPENBLAS_SETTERS:
            setter = getattr(library, symbol, None)
            if setter is not None:
                setter.argtypes = [ctypes.c_int]
                setter(1)
                limited = True
                break
    return 'openblas' if limited else 'environment'


def _LoadedLibraries(word: str) -> list:
    """Paths of the shared libraries loaded in this process whose file name contains ``word`` (Linux: from
    ``/proc/self/maps``; elsewhere none)."""
    try:
        with open('/proc/self/maps') as maps:
            paths = {line.split(None, 5)[5].strip() for line in maps if line.count(' ') >= 5 and '.so' in line}
    except (OSError, IndexError):
        return []
    return sorted(p for p in paths if word in os.path.basename(p).lower())


def CancelPool(executor, futures: Iterable) -> None:
    """Stop a pool at once (Ctrl-C, SIGTERM, an error): cancel the queued jobs and end the running ones.

    A ``ProcessPoolExecutor``'s workers are terminated and joined (their jobs are lost); another executor (an
    MPI pool) can only cancel what has not started.

    Parameters
    ----------
    executor : concurrent.futures.Executor
        The pool.
    futures : iterable of concurrent.futures.Future
        Its jobs.
    """
    manager = getattr(executor, '_executor_manager_thread', None)              # ProcessPoolExecutor only
    if manager is not None:
        _QuietAboutCancelledJobs(manager)
    for future in futures:
        future.cancel()
    processes = list((getattr(executor, '_processes', None) or {}).values())   # ProcessPoolExecutor only
    for process in processes:
        with contextlib.suppress(OSError, ValueError, AttributeError):
            process.terminate()
    executor.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        with contextlib.suppress(OSError, ValueError, AttributeError, AssertionError):
            process.join(timeout=5.)


#: pool manager threads whose complaint about a cancelled job is not printed (see _QuietAboutCancelledJobs)
_QUIET_THREADS: 'weakref.WeakSet[threading.Thread]' = weakref.WeakSet()


def _QuietAboutCancelledJobs(thread: threading.Thread) -> None:
    """Let ``thread``, a ``ProcessPoolExecutor``'s manager thread, fail silently on a job :func:`CancelPool`
    cancelled. When the terminated workers break the pool, the thread marks every job it still holds as failed;
    for a job cancelled just before, Python 3.11 raises ``InvalidStateError`` in that thread and prints its
    traceback below our one line (seen once in the SIGTERM test of ``sweep`` in CI). Other exceptions, and those
    of other threads, are printed as before."""
    _QUIET_THREADS.add(thread)
    if getattr(threading.excepthook, '_exudynWorm', False):
        return
    previous = threading.excepthook
    # lazy: only a cancelled pool needs it, and the command line's entry point loads this module before all others
    from concurrent.futures import InvalidStateError

    def ExceptHook(args):
        if args.thread in _QUIET_THREADS and args.exc_type is not None and issubclass(args.exc_type, InvalidStateError):
            return
        previous(args)

    ExceptHook._exudynWorm = True
    threading.excepthook = ExceptHook
