"""One run of a parameter study, executed in a worker process: the reel-changer simulation of one parameter set,
its window metrics and chatter verdicts, and the linear verdict of the same set. A failing run is a result: it is
recorded with its reason and never raises."""
from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from ..._checks import WarningText
from ...items.results import CHATTER_TORQUE_FRACTION, UNDECIDED
from ...items.solve import IsInterrupt
from ...params.plausibility import ImplausibleValueWarning
from ...drive.duty import IsReelChangerDuty
from ...drive.wholedrive import Drive
from ..stability.drivestability import AnalyzeDrive, DriveAnalysis, StateInstability
from ..simulation.reelchanger import MAX_STEPS, DefaultPhases, DefaultSimulatedTime
from ..simulation.stepsize import UNRESOLVED, CloseVerdicts, CompareHalfStep, RecommendedStepSize, StepCheckByDefault
from ..simulation import reelchanger

__all__ = ['WINDOW_METRICS', 'RUN_COLUMNS', 'HALF_STEP_METRICS', 'VibrationSeconds', 'LoweringVerdict', 'RunTask',
           'RunLabel', 'DecidingWindow', 'RunPoint']


#: metrics written per window (those of ``SimulationResult.WindowMetrics`` plus ``vibrationSeconds``)
WINDOW_METRICS = ('t0', 't1', 'maxAbsWheelAcceleration', 'maxNormalForce', 'dominantFrequencyHz',
                  'fractionSNegative', 'minWormSpeed', 'chatter', 'chatterState', 'chatterAmplitude', 'envelopeRate',
                  'vibrationSeconds')
#: per-run columns of the results table, before the varied parameters and the window metrics
RUN_COLUMNS = ('run', 'status', 'error', 'seconds', 'solveSeconds', 'stepSize', 'analyticStable',
               'analyticStableLowering', 'analyticInstability', 'analyticInstabilityLowering', 'loweringChatter',
               'stepChecked')
#: metrics of the run at half the step written per window as ``w{i}.halfStep.{metric}`` (where the step is checked,
#: :func:`~exudyn_worm.analysis.simulation.stepsize.CompareHalfStep`; a window's ``chatter`` is then ``'unresolved'`` where they differ)
HALF_STEP_METRICS = ('maxAbsWheelAcceleration', 'dominantFrequencyHz', 'chatter')
def VibrationSeconds(result, t0: float, t1: float) -> float:
    """How long into window [t0, t1] the wheel vibrates: the time after t0 of the last instant at which the
    wheel inertia torque J2*|phi2''| exceeds a fraction :data:`~exudyn_worm.items.results.CHATTER_TORQUE_FRACTION`
    of the largest mesh torque in the window (the wheel's measure; the chatter verdict itself is the mesh's,
    :meth:`~exudyn_worm.items.results.SimulationResult.Chatter`); 0 if never.

    Parameters
    ----------
    result : SimulationResult
        A simulation.
    t0, t1 : float
        The window in s.
    """
    t = result.time
    m = (t >= t0) & (t <= t1)
    if not m.any():
        return 0.
    threshold = CHATTER_TORQUE_FRACTION * np.max(np.abs(result.series['wheelTorque'][m]))
    above = np.nonzero(result.J2 * np.abs(result.series['alpha2'][m]) > threshold)[0]
    return float(t[m][above[-1]] - t0) if above.size else 0.


def LoweringVerdict(analysis: DriveAnalysis) -> Optional[bool]:
    """The linear verdict of the duty's lowering operating points (S = -1), the one the simulated chatter while
    lowering is compared with; None if the duty has no lowering point (it is not taken at rest instead).

    Parameters
    ----------
    analysis : DriveAnalysis
        From :func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive`.

    Returns
    -------
    bool or None
    """
    if analysis.operatingPoints and not any(op.S == -1 for op in analysis.operatingPoints):
        return None
    return bool(analysis.State(-1).stable)


def _WindowPhases(drive: Drive, windows, endTime: float) -> List[Tuple[float, float, str]]:
    """Given windows with the phase of the duty at their middle (``'idle'`` outside every phase)."""
    duty = DefaultPhases(drive, endTime)
    return [(t0, t1, next((ph for a, b, ph in duty if a <= 0.5 * (t0 + t1) <= b), 'idle')) for t0, t1 in windows]


#: window phase of :func:`~exudyn_worm.analysis.simulation.reelchanger.DefaultPhases` by operating-point phase
_WINDOW_PHASE = {'lifting': 'lift', 'lowering': 'lower'}


def DecidingWindow(drive: Drive, windows: Optional[Sequence[Tuple[float, float]]] = None,
                   endTime: Optional[float] = None) -> Optional[int]:
    """The index of the first evaluation window in the phase that decides the drive's linear verdict (lifting or
    lowering: the operating point with the largest real part), with the windows a study run takes.

    Parameters
    ----------
    drive : Drive
        The drive of one run.
    windows : sequence of (float, float), optional
        Given windows in s; None: the duty's phases (as :func:`RunPoint`).
    endTime : float, optional
        Simulated time in s (None: as :func:`RunPoint`).

    Returns
    -------
    int or None
        None if the duty has no operating point or no window in its deciding phase.
    """
    deciding = AnalyzeDrive(drive).deciding
    if deciding is None:
        return None
    period = DefaultSimulatedTime(drive)
    if windows is None:
        phases = DefaultPhases(drive, None if endTime is None else min(endTime, period), minLength=1e-3)
    else:
        phases = _WindowPhases(drive, windows, endTime if endTime is not None else
                               max(period, max(t1 for _, t1 in windows)))
    return next((i for i, (_, _, ph) in enumerate(phases) if ph == _WINDOW_PHASE[deciding.phase]), None)


def _OneLine(err: BaseException) -> str:
    return ' '.join(f"{type(err).__name__}: {err}".split())


@dataclass
class RunTask:
    """One point of a study as a worker runs it (:meth:`~exudyn_worm.analysis.studies.studygrid.Study.Task`);
    picklable (the drive travels by its values).

    Attributes
    ----------
    run : int
        The run's index.
    base : Drive or None
        The drive the point changes (the study's base drive); None if the point's drive could not be made (then
        ``error`` says why and the run is recorded as failed).
    varied : dict
        The point's varied values by parameter key (SI), applied with
        :meth:`~exudyn_worm.drive.wholedrive.Drive.Replace` in the worker.
    windows : list of (float, float) or None
        Evaluation windows in s; None: the duty's phases.
    endTime, stepSize : float or None
        Simulated time and time step in s; None: one rotation, the drive's recommended step.
    maxSteps : int or None
        Largest number of solver steps; None: the default limit.
    checkStep : bool or None
        Run again at half the step (True), never (False), or by the linear margin (None,
        :func:`~exudyn_worm.analysis.simulation.stepsize.StepCheckByDefault`).
    error : str
        Why the point's drive could not be made ('' if it could).
    """
    run: int
    base: Optional[Drive]
    varied: Dict[str, Any] = field(default_factory=dict)
    windows: Optional[Sequence[Tuple[float, float]]] = None
    endTime: Optional[float] = None
    stepSize: Optional[float] = None
    maxSteps: Optional[int] = None
    checkStep: Optional[bool] = None
    error: str = ''


def RunLabel(task: RunTask) -> str:
    """A run of a study in words, for its warnings: ``run 3 (J1 = 0.01, kT = 2000)``.

    Parameters
    ----------
    task : RunTask
        The run.
    """
    return f"run {task.run} (" + ', '.join(f"{k} = {v:.4g}" if isinstance(v, float) else f"{k} = {v}"
                                           for k, v in task.varied.items()) + ')'


def RunPoint(task: RunTask) -> Dict:
    """Run one point of a study; never raises for a failing run (it is recorded as failed with its reason).

    Parameters
    ----------
    task : RunTask
        A work item of :meth:`~exudyn_worm.analysis.studies.studygrid.Study.Task`.

    Returns
    -------
    dict
        A flat row of the results table: the columns :data:`RUN_COLUMNS`, the varied keys and
        ``w{i}.{metric}`` for each window i and each metric of :data:`WINDOW_METRICS` (None where a run
        failed before computing them), and ``w{i}.halfStep.{metric}`` (:data:`HALF_STEP_METRICS`) where the
        step was checked (``stepChecked``).
    """
    start = time.perf_counter()
    row = {'run': int(task.run), 'status': 'failed', 'error': '', 'seconds': None, 'solveSeconds': None,
           'stepSize': None, 'analyticStable': None, 'analyticStableLowering': None, 'analyticInstability': None,
           'analyticInstabilityLowering': None, 'loweringChatter': None, 'stepChecked': None}
    row.update(task.varied)
    try:
        if task.base is None:
            raise ValueError(task.error)
        drive = task.base.Replace(**task.varied)    # the run's drive, made once in its worker
        analysis = AnalyzeDrive(drive)          # at the duty's operating points: two-mass or the whole drive
        row['analyticStable'] = analysis.stable
        row['analyticStableLowering'] = LoweringVerdict(analysis)
        row['analyticInstability'] = analysis.instability
        if row['analyticStableLowering'] is not None:
            row['analyticInstabilityLowering'] = StateInstability(analysis.State(-1))
        period = DefaultSimulatedTime(drive)      # one rotation of the reel changer; another duty: its tables' end
        if task.windows is not None:
            windows, phases = task.windows, None
        else:        # the first rotation's lift / lower / lift (or the duty's phases), clipped to a shorter end time
            phases = DefaultPhases(drive, None if task.endTime is None else min(task.endTime, period),
                                   minLength=1e-3)
            windows = [(t0, t1) for t0, t1, _ in phases]
        endTime = task.endTime if task.endTime is not None else max(period, max(t1 for _, t1 in windows))
        stepSize = task.stepSize or RecommendedStepSize(drive)       # the rule of simulate
        row['stepSize'] = stepSize
        maxSteps = MAX_STEPS if task.maxSteps is None else task.maxSteps
        check = task.checkStep
        byDefault = check is None
        if byDefault:          # by the linear margin, unless the run at half the step would exceed the limit
            check = StepCheckByDefault(drive) and 2 * endTime / stepSize <= maxSteps

        def Simulate(h):       # no bar per run: the study draws one bar for all runs
            with warnings.catch_warnings(record=True) as caught:
                if h != stepSize:      # the run at half the step repeats what the run at the step said
                    warnings.simplefilter('ignore', ImplausibleValueWarning)
                result = reelchanger.SimulateReelChanger(drive, endTime=endTime, stepSize=h, progress=False,
                                                         maxSteps=maxSteps)
            for caughtWarning in caught:       # each warning says which run it comes from
                text = WarningText(caughtWarning.message).removeprefix('simulation: ')
                warnings.warn(f"{RunLabel(task)}: {text}", caughtWarning.category, stacklevel=1)
            if not all(np.all(np.isfinite(result.series[k])) for k in ('phi1', 'phi2', 'omega1', 'omega2')):
                raise FloatingPointError('diverged: non-finite state in the solution'
                                         + (' at half the step' if h != stepSize else ''))
            return result
        result = Simulate(stepSize)
        row['solveSeconds'] = result.solveSeconds
        metrics = result.WindowMetrics(windows)
        if check and byDefault:         # ... and only where a window's own verdict is close
            check = bool(CloseVerdicts(result, windows))
        row['stepChecked'] = bool(check)
        if check:
            half = Simulate(0.5 * stepSize)
            row['solveSeconds'] += half.solveSeconds
            metrics = CompareHalfStep(metrics, half.WindowMetrics(windows))
        for i, (m, (t0, t1)) in enumerate(zip(metrics, windows)):
            m = dict(m, vibrationSeconds=VibrationSeconds(result, t0, t1))
            for name in WINDOW_METRICS:
                value = m[name]
                if value is not None and not isinstance(value, (bool, str)) and not math.isfinite(value):
                    raise FloatingPointError(f"diverged: window {i} metric {name} = {value}")
                row[f'w{i}.{name}'] = value
            for name in HALF_STEP_METRICS if check else ():
                row[f'w{i}.halfStep.{name}'] = m['halfStep'][name]
        if phases is None and not IsReelChangerDuty(drive.parameters):     # given windows: lowering where the duty lowers
            phases = _WindowPhases(drive, windows, endTime)
        lowering = ([i for i, (t0, t1) in enumerate(windows) if t0 <= period / 2 <= t1] if phases is None
                    else [i for i, (_, _, phase) in enumerate(phases) if phase == 'lower'])   # the load drives
        verdict = metrics[lowering[0]]['chatter'] if lowering else None
        row['loweringChatter'] = verdict if verdict in (None, UNRESOLVED, UNDECIDED) else bool(verdict)
        row['status'] = 'ok'
    except Exception as err:            # a failing run is a result, not the end of the study
        if IsInterrupt(err):            # ... but Ctrl-C is the end of it
            raise KeyboardInterrupt() from None
        row['error'] = _OneLine(err)
        for key in [k for k in row if k.startswith('w') and '.' in k]:
            del row[key]
    row['seconds'] = time.perf_counter() - start
    return row


