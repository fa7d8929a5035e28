"""Exudyn's implicit dynamic solver with a progress bar and clear failures.

:func:`SolveDynamicInChunks` does what ``mbs.SolveDynamic`` does for the implicit second-order solvers
(generalized-alpha, trapezoidal index 2) and turns a solver failure into :class:`SolverDivergedError`
carrying the simulated time reached. When a progress bar is shown (:func:`exudyn_worm.progress.ProgressBar`:
``progress=True``, or a terminal on stderr) it advances the solver in chunks of :data:`CHUNK_STEPS` steps,
so the bar follows a long run without a per-step Python callback; without a bar it runs Exudyn's own
``SolveSystem`` in one piece.

Costs and differences (benchmarks/bench_chunked_solve.py, CPU seconds, min of 5, idle 2-core machine):
with a bar the solve costs 0.94x (P1) and 1.006x (P7) of one ``SolveSystem`` call. ``SolveSystem`` switches
Exudyn's per-step solver timers off (unless ``show.computationTime``); ``InitializeSolver`` leaves them on,
which made a chunked run 7-16 % slower until the timers were switched off here as well. Chunking restarts the
modified-Newton Jacobian at each chunk start: with a bar the results agree with the one-piece run to the
Newton tolerance (P1 states 1e-5 relative before the chatter), not bit for bit: window peaks of P1 and P6 within
0.1 %, of P7 within 0.4 % (lowering) and 1.4 % (the wheel acceleration just after the load reverses in chatter,
set by the chatter's phase; docs/simulation.md); without a bar the run is exactly Exudyn's ``SolveSystem``.
"""
from __future__ import annotations

import contextlib
import math
import signal
from typing import Iterator

from .._workers import Terminated, TerminationRequested
from ..progress import ProgressBar, ProgressEnabled

__all__ = ['SolverDivergedError', 'IncompleteSolveError', 'SolveDynamicInChunks', 'CHUNK_STEPS', 'IsInterrupt', 'Interruptible']

#: solver steps per chunk: small enough for a live progress bar (a chunk of the slowest reel-changer run,
#: P7, takes about 0.3 s), large enough that the per-chunk restart costs nothing measurable
CHUNK_STEPS = 2000


class SolverDivergedError(RuntimeError):
    """The dynamic solver failed (Newton did not converge even with reduced steps).

    Parameters
    ----------
    message : str
        The error message.

    Attributes
    ----------
    timeReached : float
        Simulated time in s reached before the failure.
    endTime : float
        Simulated time in s that was asked for.
    stepSize : float
        Nominal time step in s.
    """

    def __init__(self, message: str, timeReached: float, endTime: float, stepSize: float):
        super().__init__(message)
        self.timeReached, self.endTime, self.stepSize = timeReached, endTime, stepSize


class IncompleteSolveError(SolverDivergedError):
    """The solver returned without failing, but before the end time (a user function stopped it, e.g. a pre-step
    function returning False or ``mbs.StopSimulation()``): its result would be a truncated run.

    The attributes are those of :class:`SolverDivergedError` (``timeReached`` < ``endTime``).
    """


#: set when Ctrl-C arrives during a solve (:func:`_NoticeInterrupt`): raised inside a Python user function, the
#: ``KeyboardInterrupt`` makes Exudyn stop the solve quietly, and the early end is then Ctrl-C, not a truncated run
_interrupted = [False]


@contextlib.contextmanager
def _NoticeInterrupt() -> Iterator[None]:
    """Within the block, SIGINT is recorded before the handler in force acts on it (restored on leaving). Outside
    the main thread, or with SIGINT ignored or at its default action, the block runs unchanged."""
    _interrupted[0] = False
    previous = signal.getsignal(signal.SIGINT)
    if not callable(previous):                  # ignored (a study's worker) or the default action: nothing to see
        yield
        return

    def Noticing(signum, frame):
        _interrupted[0] = True
        return previous(signum, frame)
    try:
        signal.signal(signal.SIGINT, Noticing)
    except ValueError:                          # not the main thread
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


def _CheckEndReached(solver, endTime: float, stepSize: float, until=None, where: str = 'SolveDynamicInChunks') -> None:
    """Raise :class:`IncompleteSolveError` if ``solver`` stopped before ``until`` (s; default the run's ``endTime``,
    a chunk's end in a chunked run) by more than a thousandth of the step ``stepSize`` (s; the solver's clock sums
    steps and may miss the end by round-off)."""
    reached = float(solver.it.currentTime)
    if not reached >= (endTime if until is None else until) - 1e-3 * stepSize:
        if TerminationRequested():       # SIGTERM in a user function: Exudyn stopped the solve and kept quiet
            raise Terminated()
        if _interrupted[0]:              # Ctrl-C in a user function: the same
            raise KeyboardInterrupt()
        raise IncompleteSolveError(f"{where}: the run ended at t = {reached:.6g} s, before its end time "
                                   f"{endTime:g} s (step size {stepSize:g} s), without a solver failure: a user "
                                   f"function or a stop request ended it early; its result would be truncated",
                                   reached, endTime, stepSize)


def IsInterrupt(err: BaseException) -> bool:
    """Whether an exception is, or was caused by, Ctrl-C (a ``KeyboardInterrupt`` anywhere in its chain).

    Exudyn's C++ solver notices a pending Ctrl-C and returns with the ``KeyboardInterrupt`` set; Python then
    raises ``SystemError: ... returned a result with an exception set`` (or an ``ExudynError``) with the
    interrupt as its context. Such an error is an interrupt, not a failed run.

    Parameters
    ----------
    err : BaseException
        The exception.

    Returns
    -------
    bool
    """
    seen = set()
    while err is not None and id(err) not in seen:
        if isinstance(err, KeyboardInterrupt):
            return True
        seen.add(id(err))
        err = err.__cause__ or err.__context__
    return False


@contextlib.contextmanager
def Interruptible() -> Iterator[None]:
    """Context manager: an exception of the block caused by Ctrl-C (:func:`IsInterrupt`) becomes a plain
    ``KeyboardInterrupt``, so that callers stop instead of recording a failure."""
    try:
        yield
    except KeyboardInterrupt:
        raise
    except Exception as err:
        if IsInterrupt(err):
            raise KeyboardInterrupt() from None
        raise


def _ConstraintNames(mbs):
    """Names (or numbers) and types of the objects of the assembled ``mbs`` that add algebraic equations."""
    found = []
    for i in range(mbs.systemData.NumberOfObjects()):
        if len(mbs.systemData.GetObjectLTGAE(i)):
            item = mbs.GetObject(i)
            found.append(f"{item.get('name') or i} ({item['objectType']})")
    return found


def _SolveInOnePiece(mbs, ss, solverType):
    """Explicit solvers: one ``mbs.SolveDynamic`` call (no chunks, no progress), failures as SolverDivergedError.
    Refused for a system with constraints: Exudyn's explicit solvers ignore them (a prescribed motor would
    stand still and the run would look fine)."""
    import exudyn as exu
    constraints = _ConstraintNames(mbs)
    if constraints:
        raise ValueError(f"SolveDynamicInChunks: the explicit solver {solverType} ignores constraints, and this "
                         f"system has {', '.join(constraints[:3])}{' ...' if len(constraints) > 3 else ''} (e.g. a "
                         f"prescribed motor rotation, which would stand still); use GeneralizedAlpha or "
                         f"TrapezoidalIndex2, or drive the rotor by a torque (CreateRotorTorque)")
    ti = ss.timeIntegration
    try:
        with Interruptible():
            mbs.SolveDynamic(ss, solverType=solverType)
    except exu.ExudynError as err:
        solver = mbs.sys.get('dynamicSolver')
        reached = solver.it.currentTime if solver is not None else ti.startTime
        raise SolverDivergedError(f"the Exudyn solver ({solverType}) failed at t = {reached:.6g} s of "
                                  f"{ti.endTime:g} s ({err})", reached, ti.endTime,
                                  (ti.endTime - ti.startTime) / ti.numberOfSteps) from err
    solver = mbs.sys['dynamicSolver']
    _CheckEndReached(solver, ti.endTime, (ti.endTime - ti.startTime) / ti.numberOfSteps)
    return solver


def SolveDynamicInChunks(mbs, simulationSettings, solverType=None, progress=None, desc: str = 'simulate',
                         chunkSteps: int = CHUNK_STEPS):
    """Solve ``mbs`` dynamically like ``mbs.SolveDynamic``, in chunks, with an optional progress bar.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system (assembled here if it is not).
    simulationSettings : exudyn.SimulationSettings
        Settings of the run: ``timeIntegration.startTime``, ``endTime`` and ``numberOfSteps`` set the
        fixed step size. Not changed (the solver type is set for the run and restored).
    solverType : exudyn.DynamicSolverType, optional
        Default ``GeneralizedAlpha``. The implicit ``GeneralizedAlpha`` and ``TrapezoidalIndex2`` run in
        chunks; explicit solvers run in one ``mbs.SolveDynamic`` call, without progress.
    progress : bool or None
        Progress bar on stderr over simulated time: True shown, False never, None (default) shown when
        stderr is a terminal and the run takes longer than about 2 s. With a bar the run is chunked
        (as fast, results equal to the Newton tolerance); without one it is a single solve.
    desc : str
        Label of the progress bar.
    chunkSteps : int
        Solver steps per chunk, >= 1.

    Returns
    -------
    exudyn.MainSolverImplicitSecondOrder or exudyn.MainSolverExplicit
        The solver (also stored as ``mbs.sys['dynamicSolver']``); ``solver.it`` holds its statistics.

    Raises
    ------
    SolverDivergedError
        If the solver fails; the message gives the simulated time reached.
    IncompleteSolveError
        If the solver returns before the end time without failing (a user function stopped it): the message
        gives the time reached and the end time.
    ValueError, TypeError
        For ``chunkSteps < 1``, a ``solverType`` that is not an ``exudyn.DynamicSolverType``, or an explicit
        solver on a system with constraints.
    """
    import exudyn as exu
    w = 'SolveDynamicInChunks'
    DST = exu.DynamicSolverType
    solverType = DST.GeneralizedAlpha if solverType is None else solverType
    if not isinstance(solverType, DST):
        raise TypeError(f"{w}: 'solverType' must be an exudyn.DynamicSolverType, got {solverType!r}")
    if not (isinstance(chunkSteps, int) and chunkSteps >= 1):
        raise ValueError(f"{w}: 'chunkSteps' must be an integer >= 1, got {chunkSteps!r}")
    if not mbs.systemIsConsistent:
        mbs.Assemble()
    with _NoticeInterrupt():
        return _Solve(mbs, simulationSettings, solverType, progress, desc, chunkSteps)


def _Solve(mbs, ss, solverType, progress, desc: str, chunkSteps: int):
    """The solve of :func:`SolveDynamicInChunks` (arguments checked)."""
    import exudyn as exu
    DST = exu.DynamicSolverType
    if solverType not in (DST.GeneralizedAlpha, DST.TrapezoidalIndex2):
        return _SolveInOnePiece(mbs, ss, solverType)
    ti, ga = ss.timeIntegration, ss.timeIntegration.generalizedAlpha
    saved = (ti.solverType, ga.useNewmark, ga.useIndex2Constraints)
    ti.solverType = solverType
    if solverType == DST.TrapezoidalIndex2:              # as mbs.SolveDynamic does
        ga.useNewmark, ga.useIndex2Constraints = True, True
    t0, T, n = ti.startTime, ti.endTime, ti.numberOfSteps
    h = (T - t0) / n
    chunks = max(1, math.ceil(n / chunkSteps))
    solver = exu.MainSolverImplicitSecondOrder()
    mbs.sys['dynamicSolver'] = solver

    def Diverged(err=None):
        reached = solver.it.currentTime
        detail = f" ({err})" if err is not None and str(err) else ''
        return SolverDivergedError(f"the Exudyn solver failed at t = {reached:.6g} s of {T:g} s (step size "
                                   f"{h:g} s): Newton did not converge even with reduced steps{detail}",
                                   reached, T, h)
    quiet = None if progress is None else not progress
    with Interruptible():       # Ctrl-C in the C++ solver: a KeyboardInterrupt, not a diverged run
        try:
            if not ProgressEnabled(quiet):           # no bar: Exudyn's own loop, bit for bit as before
                try:
                    ok = solver.SolveSystem(mbs, ss)
                except exu.ExudynError as err:
                    raise Diverged(err) from err
                if not ok:
                    raise Diverged()
                _CheckEndReached(solver, T, h)
                return solver
            with ProgressBar(total=T - t0, desc=desc, unit='s', quiet=quiet, delay=2. if progress is None else 0.,
                             bar_format='{desc}: {percentage:3.0f}%|{bar}| {n:.3g}/{total:.3g} s simulated '
                                        '[{elapsed}<{remaining}]') as bar:
                try:
                    ok = solver.InitializeSolver(mbs, ss)
                    # SolveSystem switches Exudyn's per-step timers off unless asked for; InitializeSolver leaves
                    # them on, and their clock reads made a chunked run 7-16 % slower
                    timer = solver.timer
                    timer.Reset(ss.show.computationTime)
                    solver.timer = timer
                    mbs.sys['dynamicSolverSteps'] = 0        # steps taken in all chunks (it.currentStepIndex restarts)
                    for k in range(1, chunks + 1):
                        if not ok:
                            raise Diverged()
                        solver.it.endTime = chunkEnd = T if k == chunks else t0 + h * round(n * k / chunks)
                        ok = solver.SolveSteps(mbs, ss)
                        mbs.sys['dynamicSolverSteps'] += int(solver.it.currentStepIndex) - 1
                        bar.update(solver.it.currentTime - t0 - bar.n)
                        if ok:
                            _CheckEndReached(solver, T, h, chunkEnd)   # stopped early: T is not reached either
                    if not ok:
                        raise Diverged()
                except exu.ExudynError as err:    # SolverError and others raised by the C++ solver
                    raise Diverged(err) from err
                solver.FinalizeSolver(mbs, ss)
        finally:
            ti.solverType, ga.useNewmark, ga.useIndex2Constraints = saved
    return solver
