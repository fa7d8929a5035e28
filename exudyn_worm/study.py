"""Parameter studies: many reel-changer simulations over a grid of parameters, on every core or a cluster.

A :class:`Study` varies keys of a flat parameter set (any key of
:data:`~exudyn_worm.presets.PARAMETER_UNITS`, e.g. ``J1``, ``kT``, ``backlash``, ``motorSpeed``,
``loadMass``) over grids or lists (:func:`ParseVariation`), as a full factorial or zipped. For every
point, :func:`RunPoint` runs :func:`~exudyn_worm.reelchanger.SimulateReelChanger`, takes the window
metrics and chatter verdicts of ``exudyn-worm simulate``
(:meth:`~exudyn_worm.results.SimulationResult.WindowMetrics`), adds the linear verdict of the same
parameter set (:func:`~exudyn_worm.linearization.DriveStability`, as ``exudyn-worm stability``: the analytical
two-mass model, or the linearized whole drive for a drive with a drive-side chain or a worm axial bearing) and
the run's times.

:func:`RunStudy` executes the points with an executor of the standard ``concurrent.futures`` interface:
a process pool on every core (Exudyn holds the GIL, threads do not help; each worker builds its own
model from a parameter dictionary, since symbolic user functions cannot be pickled) or
``mpi4py.futures.MPIPoolExecutor`` on a cluster. Results are handled as they finish (unordered) and
appended to a CSV file at once, so a failed run (recorded with its reason) never stops the others and an
interrupted study resumes with the same call without redoing finished runs. ``shard=(i, N)`` runs only
every N-th point, for job arrays that need no MPI.

Exudyn's ``ParameterVariation`` is not used: it aborts the whole study when one point raises, keeps no
partial results and cannot resume.

No matplotlib here: plots are in :mod:`exudyn_worm.plot_study`.
"""
from __future__ import annotations

import csv
import importlib
import itertools
import json
import math
import multiprocessing
import os
import platform
import signal
import subprocess
import sys
import time
import warnings
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field
from importlib import metadata
from pathlib import Path
from typing import Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from .config import ParseQuantity
from .parameters import PARAMETERS
from .presets import PARAMETER_UNITS, ApplyOverrides, CheckParameterKeys
from .results import CHATTER_TORQUE_FRACTION, CheckWindows
from .solve import IsInterrupt
from .studymap import ComputeChatterMap
from ._checks import CheckPositive
from .duty import IsReelChangerDuty
from .linearization import DriveStability
from .progress import ProgressBar
from .reelchanger import MAX_STEPS, DefaultPhases, DefaultSimulatedTime, DefaultWindows
from .stepsize import UNRESOLVED, CompareHalfStep, RecommendedStepSize, StepCheckByDefault
from . import reelchanger

__all__ = ['Variation', 'ParseVariation', 'StudyPoints', 'Study', 'ParseShard', 'ShardIndices', 'RunPoint',
           'StudyResult', 'RunStudy', 'ReadResults', 'StudySidecarPath', 'VibrationSeconds', 'WINDOW_METRICS',
           'RUN_COLUMNS', 'HALF_STEP_METRICS', 'ENGINES', 'DefaultWorkers']

#: metrics written per window (those of ``SimulationResult.WindowMetrics`` plus ``vibrationSeconds``)
WINDOW_METRICS = ('t0', 't1', 'maxAbsWheelAcceleration', 'maxNormalForce', 'dominantFrequencyHz',
                  'fractionSNegative', 'minWormSpeed', 'chatter', 'vibrationSeconds')
#: per-run columns of the results table, before the varied parameters and the window metrics
RUN_COLUMNS = ('run', 'status', 'error', 'seconds', 'solveSeconds', 'stepSize', 'analyticStable',
               'analyticStableLowering', 'loweringChatter', 'stepChecked')
#: metrics of the run at half the step written per window as ``w{i}.halfStep.{metric}`` (where the step is checked,
#: :func:`~exudyn_worm.stepsize.CompareHalfStep`; a window's ``chatter`` is then ``'unresolved'`` where they differ)
HALF_STEP_METRICS = ('maxAbsWheelAcceleration', 'dominantFrequencyHz', 'chatter')
#: execution engines of :func:`RunStudy`
ENGINES = ('process', 'mpi')

_BOOL_COLUMNS = {'analyticStable', 'analyticStableLowering', 'loweringChatter', 'chatter', 'stepChecked'}
_NUMBER_OF_DEFAULT_WINDOWS = 3          # DefaultWindows: lift, lower, lift


# ---------------------------------------------------------------------------------------------------------------
# study definition

@dataclass(frozen=True)
class Variation:
    """The values one parameter takes in a study.

    Attributes
    ----------
    key : str
        Parameter name (a key of :data:`~exudyn_worm.presets.PARAMETER_UNITS`).
    values : tuple of float
        Values in SI units, in study order.
    text : str
        The specification as given (for the record).
    """
    key: str
    values: Tuple[float, ...]
    text: str = ''

    def ToDict(self) -> Dict:
        """JSON-ready ``{'key', 'unit', 'values', 'text'}``."""
        return {'key': self.key, 'unit': PARAMETER_UNITS[self.key], 'values': list(self.values), 'text': self.text}


def ParseVariation(text: str, log: bool = False) -> Variation:
    """Parse one ``--vary`` specification.

    Parameters
    ----------
    text : str
        ``KEY=START:STOP:COUNT`` for a grid of COUNT values from START to STOP (both included; optional
        fourth field ``lin`` or ``log``), or ``KEY=V1,V2,...`` for a list. Every value is a plain SI number
        or has units, as ``--set`` accepts (:func:`~exudyn_worm.config.ParseQuantity`), e.g.
        ``'J1=0.01:0.4:8'``, ``'kT=700:14000:12:log'``, ``'backlash=0,0.25mm,0.5 mm'``,
        ``'backlash=0:1mm:9'``.
    log : bool, optional
        Space a grid logarithmically (default linear; a fourth field ``lin``/``log`` wins).

    Returns
    -------
    Variation

    Raises
    ------
    ValueError
        For a malformed specification, an unknown key, a bad value or unit, COUNT < 1, a grid with
        COUNT > 1 and START = STOP, or a log grid with START or STOP <= 0.
    """
    where = 'ParseVariation'
    if not isinstance(text, str):
        raise TypeError(f"{where}: expected a string 'KEY=START:STOP:COUNT' or 'KEY=V1,V2,...', "
                        f"got {type(text).__name__} {text!r}")
    key, sep, spec = text.partition('=')
    key, spec = key.strip(), spec.strip()
    if not sep or not key or not spec:
        raise ValueError(f"{where}: expected KEY=START:STOP:COUNT or KEY=V1,V2,... "
                         f"(e.g. 'J1=0.01:0.4:8' or 'backlash=0,0.25mm,0.5mm'), got {text!r}")
    if key not in PARAMETERS:
        raise ValueError(PARAMETERS.UnknownKeyMessage(f"{where}: {text!r}", key))
    if PARAMETERS[key].kind != 'number':
        raise ValueError(f"{where}: {text!r}: a study sweeps numbers; {key!r} takes a {PARAMETERS[key].kind} "
                         f"({PARAMETERS[key].rangeText}): set it with --set or in the base set instead")
    context = f"{where}: {text!r}"
    if ':' in spec:
        fields = [f.strip() for f in spec.split(':')]
        if len(fields) == 4 and fields[3].lower() in ('lin', 'log'):
            log = fields[3].lower() == 'log'
            fields = fields[:3]
        if len(fields) != 3:
            raise ValueError(f"{context}: a grid is START:STOP:COUNT[:lin|log], e.g. 'J1=0.01:0.4:8'")
        start, stop = (ParseQuantity(key, f) if f else _Raise(context, 'START and STOP must be given')
                       for f in fields[:2])
        try:
            count = int(fields[2])
        except ValueError:
            raise ValueError(f"{context}: COUNT must be a whole number >= 1, got {fields[2]!r}") from None
        if count < 1:
            raise ValueError(f"{context}: COUNT must be >= 1, got {count}")
        if count > 1 and start == stop:
            raise ValueError(f"{context}: START and STOP must differ for COUNT > 1")
        if log:
            if start <= 0 or stop <= 0:
                raise ValueError(f"{context}: a log grid needs START and STOP > 0 "
                                 f"(in {PARAMETER_UNITS[key] or 'SI'}), got {start:g} and {stop:g}")
            values = np.geomspace(start, stop, count) if count > 1 else np.array([start])
        else:
            values = np.linspace(start, stop, count)
        values = [float(v) for v in values]
        values[0] = start                                  # exact ends, no rounding from exp/log
        values[-1] = stop if count > 1 else start
    else:
        items = [item.strip() for item in spec.split(',')]
        if any(not item for item in items):
            raise ValueError(f"{context}: empty value in the list (V1,V2,...)")
        values = [ParseQuantity(key, item) for item in items]
    return Variation(key, tuple(values), text)


def _Raise(context, message):
    raise ValueError(f"{context}: {message}")


def StudyPoints(variations: Sequence[Variation], zipped: bool = False) -> List[Dict[str, float]]:
    """The points of a study: the full factorial of the variations (the first varies slowest), or zipped.

    Parameters
    ----------
    variations : sequence of Variation
        One per varied key; keys must be distinct.
    zipped : bool, optional
        Pair the i-th values of all variations (they must have equal lengths) instead of the full factorial.

    Returns
    -------
    list of dict
        One ``{key: value}`` per point; ``[{}]`` for no variation (one run of the base set).

    Raises
    ------
    ValueError
        For a key varied twice, or zipped variations of different lengths.
    """
    keys = [v.key for v in variations]
    repeated = sorted({k for k in keys if keys.count(k) > 1})
    if repeated:
        raise ValueError(f"StudyPoints: parameter(s) {', '.join(repeated)} varied more than once")
    if zipped and len({len(v.values) for v in variations}) > 1:
        lengths = ', '.join(f"{v.key}: {len(v.values)}" for v in variations)
        raise ValueError(f"StudyPoints: zipped variations need equal numbers of values, got {lengths}")
    combos = zip(*(v.values for v in variations)) if zipped else itertools.product(*(v.values for v in variations))
    return [dict(zip(keys, combo)) for combo in combos]


@dataclass
class Study:
    """A parameter study of the reel changer.

    Parameters
    ----------
    base : mapping
        The flat parameter set every point starts from (e.g. :func:`~exudyn_worm.config.ResolveParameters`).
    variations : sequence of Variation
        The varied parameters (:func:`ParseVariation`).
    zipped : bool, optional
        Pair the variations instead of the full factorial.
    windows : sequence of (float, float), optional
        Evaluation windows in s (default: the lift / lower / lift phases of each point's first rotation,
        :func:`~exudyn_worm.reelchanger.DefaultWindows`, clipped to ``endTime`` when that is shorter; the
        columns of a window that does not exist stay empty). For a duty other than the reel changer's
        (:mod:`exudyn_worm.duty`) the default is the phases of the first point's duty up to ``endTime`` (or its
        :func:`~exudyn_worm.reelchanger.DefaultSimulatedTime`), the same windows for every run (the columns of a
        study are fixed); a window counts as lowering if its middle lies in a lowering phase of the run's duty.
    endTime : float, optional
        Simulated time in s (default: one rotation of each point, at least up to the last window).
    stepSize : float, optional
        Time step in s (default, per run: the drive's :func:`~exudyn_worm.stepsize.RecommendedStepSize`, the
        step ``simulate`` and ``check --simulate`` use, so a run and ``simulate`` of the same drive agree).
    source : str, optional
        Where the base set came from (for the record).
    maxSteps : int, optional
        Refuse (record as failed) runs of more solver steps than this (default, None:
        :data:`~exudyn_worm.reelchanger.MAX_STEPS`, as ``simulate``).
    checkStep : bool, optional
        Run each point again at half the step and record a window whose chatter verdict changes as
        ``'unresolved'`` (True), never (False), or (None, default) where the point's linear margin is small
        (:func:`~exudyn_worm.stepsize.StepCheckByDefault`), as ``simulate``.
    """
    base: Mapping[str, float]
    variations: Sequence[Variation] = ()
    zipped: bool = False
    windows: Optional[Sequence[Tuple[float, float]]] = None
    endTime: Optional[float] = None
    stepSize: Optional[float] = None
    source: str = ''
    maxSteps: Optional[int] = None
    checkStep: Optional[bool] = None
    points: List[Dict[str, float]] = field(init=False, repr=False)

    def __post_init__(self):
        CheckParameterKeys(self.base, 'Study', 'base')
        self.base = dict(self.base)
        self.variations = list(self.variations)
        for v in self.variations:
            if not isinstance(v, Variation):
                raise TypeError(f"Study: 'variations' must hold Variation objects (ParseVariation), "
                                f"got {type(v).__name__}")
        if self.endTime is not None:
            self.endTime = CheckPositive('Study', 'endTime', self.endTime, 's')
        if self.maxSteps is not None and (isinstance(self.maxSteps, bool) or not isinstance(self.maxSteps, int)
                                          or self.maxSteps < 1):
            raise ValueError(f"Study: 'maxSteps' must be a whole number >= 1 (solver steps), got {self.maxSteps!r}")
        if self.windows is not None:      # a window beyond endTime would be judged on its missing part
            self.windows = CheckWindows(self.windows, self.endTime, 'Study')
        if self.checkStep is not None and not isinstance(self.checkStep, bool):
            raise TypeError(f"Study: 'checkStep' must be True, False or None (by the linear margin), "
                            f"got {self.checkStep!r}")
        self.points = StudyPoints(self.variations, self.zipped)
        first = ApplyOverrides(self.base, self.points[0])          # unknown keys raise here
        if self.windows is None and not IsReelChangerDuty(first):   # the phases of the first point's duty
            self.windows = DefaultWindows(first, self.endTime, minLength=1e-3)

    @property
    def keys(self) -> List[str]:
        """The varied keys, in order."""
        return [v.key for v in self.variations]

    @property
    def numberOfWindows(self) -> int:
        """Windows evaluated per run."""
        return _NUMBER_OF_DEFAULT_WINDOWS if self.windows is None else len(self.windows)

    def Parameters(self, run: int) -> Dict[str, float]:
        """The full parameter set of point ``run`` (0-based)."""
        return ApplyOverrides(self.base, self.points[run])

    def Task(self, run: int) -> Dict:
        """The picklable work item of point ``run`` for :func:`RunPoint` (plain data only)."""
        return {'run': run, 'parameters': self.Parameters(run), 'varied': dict(self.points[run]),
                'windows': self.windows, 'endTime': self.endTime, 'stepSize': self.stepSize,
                'maxSteps': self.maxSteps, 'checkStep': self.checkStep}

    def ToDict(self) -> Dict:
        """JSON-ready definition: base set, variations, pairing, windows, times, number of runs."""
        return {'base': dict(self.base), 'source': self.source,
                'variations': [v.ToDict() for v in self.variations], 'zipped': self.zipped,
                'windows': None if self.windows is None else [list(w) for w in self.windows],
                'endTime': self.endTime, 'stepSize': self.stepSize, 'maxSteps': self.maxSteps,
                'checkStep': self.checkStep, 'runs': len(self.points)}

    def Identity(self) -> Dict:
        """What must match for a results file to be resumed: the definition without its free-text parts."""
        return _Identity(self.ToDict())


def ParseShard(text: Union[str, Tuple[int, int], None]) -> Optional[Tuple[int, int]]:
    """Parse ``'i/N'`` (0 <= i < N), e.g. ``'$SLURM_ARRAY_TASK_ID/4'`` expanded to ``'2/4'``.

    Parameters
    ----------
    text : str, (int, int) or None
        The shard; None means the whole study.

    Returns
    -------
    (int, int) or None

    Raises
    ------
    ValueError
        Unless 0 <= i < N.
    """
    if text is None:
        return None
    if isinstance(text, str):
        i, sep, n = text.partition('/')
        try:
            i, n = int(i), int(n)
        except ValueError:
            raise ValueError(f"ParseShard: expected 'i/N' with whole numbers 0 <= i < N (e.g. '0/4'), "
                             f"got {text!r}") from None
    else:
        i, n = text
    if not (isinstance(i, int) and isinstance(n, int) and 0 <= i < n):
        raise ValueError(f"ParseShard: a shard i/N needs whole numbers 0 <= i < N, got {text!r}")
    return i, n


def ShardIndices(numberOfRuns: int, shard: Optional[Tuple[int, int]]) -> List[int]:
    """Run indices of one shard: every N-th run starting at i (round robin, so shards get similar mixes).

    Parameters
    ----------
    numberOfRuns : int
        Runs in the whole study.
    shard : (int, int) or None
        ``(i, N)`` from :func:`ParseShard`; None for all runs.
    """
    if shard is None:
        return list(range(numberOfRuns))
    i, n = shard
    return list(range(i, numberOfRuns, n))


# ---------------------------------------------------------------------------------------------------------------
# one run (executed in a worker process)

def VibrationSeconds(result, t0: float, t1: float) -> float:
    """How long into window [t0, t1] the wheel vibrates: the time after t0 of the last instant at which the
    wheel inertia torque J2*|phi2''| exceeds the chatter threshold of
    :meth:`~exudyn_worm.results.SimulationResult.Chatter` (a fraction
    :data:`~exudyn_worm.results.CHATTER_TORQUE_FRACTION` of the largest mesh torque in the window); 0 if never.

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


def _OneLine(err: BaseException) -> str:
    return ' '.join(f"{type(err).__name__}: {err}".split())


def RunPoint(task: Mapping) -> Dict:
    """Run one point of a study; never raises for a failing run (it is recorded as failed with its reason).

    Parameters
    ----------
    task : mapping
        A work item of :meth:`Study.Task`: ``run`` (index), ``parameters`` (full set), ``varied``,
        ``windows`` (None: default), ``endTime`` (None: one rotation), ``stepSize`` (None: the drive's
        recommended step), ``maxSteps`` (optional; None: the default limit), ``checkStep`` (optional; None: by
        the linear margin, :func:`~exudyn_worm.stepsize.StepCheckByDefault`).

    Returns
    -------
    dict
        A flat row of the results table: the columns :data:`RUN_COLUMNS`, the varied keys and
        ``w{i}.{metric}`` for each window i and each metric of :data:`WINDOW_METRICS` (None where a run
        failed before computing them), and ``w{i}.halfStep.{metric}`` (:data:`HALF_STEP_METRICS`) where the
        step was checked (``stepChecked``).
    """
    start = time.perf_counter()
    p = dict(task['parameters'])
    row = {'run': int(task['run']), 'status': 'failed', 'error': '', 'seconds': None, 'solveSeconds': None,
           'stepSize': None, 'analyticStable': None, 'analyticStableLowering': None, 'loweringChatter': None,
           'stepChecked': None}
    row.update(task['varied'])
    try:
        analysis = DriveStability(p)            # two-mass: eqs. (15)-(19); with a chain or bearing: the whole drive
        row['analyticStable'] = analysis.stable
        row['analyticStableLowering'] = analysis.State(-1).stable
        period = DefaultSimulatedTime(p)      # one rotation of the reel changer; another duty: its tables' end
        if task['windows'] is not None:
            windows, phases = task['windows'], None
        else:        # the first rotation's lift / lower / lift (or the duty's phases), clipped to a shorter end time
            phases = DefaultPhases(p, None if task['endTime'] is None else min(task['endTime'], period),
                                   minLength=1e-3)
            windows = [(t0, t1) for t0, t1, _ in phases]
        endTime = task['endTime'] if task['endTime'] is not None else max(period, max(t1 for _, t1 in windows))
        stepSize = task['stepSize'] or RecommendedStepSize(p)       # the rule of simulate
        row['stepSize'] = stepSize
        maxSteps = MAX_STEPS if task.get('maxSteps') is None else task['maxSteps']
        check = task.get('checkStep')
        if check is None:      # by the linear margin, unless the run at half the step would exceed the limit
            check = StepCheckByDefault(p) and 2 * endTime / stepSize <= maxSteps
        row['stepChecked'] = bool(check)

        def Simulate(h):       # no bar per run: the study draws one bar for all runs
            result = reelchanger.SimulateReelChanger(p, endTime=endTime, stepSize=h, progress=False, maxSteps=maxSteps)
            if not all(np.all(np.isfinite(result.series[k])) for k in ('phi1', 'phi2', 'omega1', 'omega2')):
                raise FloatingPointError('diverged: non-finite state in the solution'
                                         + (' at half the step' if h != stepSize else ''))
            return result
        result = Simulate(stepSize)
        row['solveSeconds'] = result.solveSeconds
        metrics = result.WindowMetrics(windows)
        if check:
            half = Simulate(0.5 * stepSize)
            row['solveSeconds'] += half.solveSeconds
            metrics = CompareHalfStep(metrics, half.WindowMetrics(windows))
        for i, (m, (t0, t1)) in enumerate(zip(metrics, windows)):
            m = dict(m, vibrationSeconds=VibrationSeconds(result, t0, t1))
            for name in WINDOW_METRICS:
                value = m[name]
                if not isinstance(value, (bool, str)) and not math.isfinite(value):
                    raise FloatingPointError(f"diverged: window {i} metric {name} = {value}")
                row[f'w{i}.{name}'] = value
            for name in HALF_STEP_METRICS if check else ():
                row[f'w{i}.halfStep.{name}'] = m['halfStep'][name]
        if phases is None and not IsReelChangerDuty(p):     # given windows: lowering where the duty lowers
            duty = DefaultPhases(p, endTime)
            phases = [(t0, t1, next((ph for a, b, ph in duty if a <= 0.5 * (t0 + t1) <= b), 'idle'))
                      for t0, t1 in windows]
        lowering = ([i for i, (t0, t1) in enumerate(windows) if t0 <= period / 2 <= t1] if phases is None
                    else [i for i, (_, _, phase) in enumerate(phases) if phase == 'lower'])   # the load drives
        verdict = metrics[lowering[0]]['chatter'] if lowering else None
        row['loweringChatter'] = verdict if verdict in (None, UNRESOLVED) else bool(verdict)
        row['status'] = 'ok'
    except Exception as err:            # a failing run is a result, not the end of the study
        if IsInterrupt(err):            # ... but Ctrl-C is the end of it
            raise KeyboardInterrupt() from None
        row['error'] = _OneLine(err)
        for key in [k for k in row if k.startswith('w') and '.' in k]:
            del row[key]
    row['seconds'] = time.perf_counter() - start
    return row


def _WorkerInit() -> None:
    """Worker start: stdout goes to stderr (stdout may carry the study's JSON); Ctrl-C is left to the parent."""
    try:
        os.dup2(2, 1)
    except OSError:
        pass
    try:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    except (ValueError, OSError):
        pass


# ---------------------------------------------------------------------------------------------------------------
# results table

def _Columns(study: Study) -> List[str]:
    return list(RUN_COLUMNS) + study.keys + [f'w{i}.{name}' for i in range(study.numberOfWindows)
                                             for name in WINDOW_METRICS + tuple(f'halfStep.{m}' for m in
                                                                                HALF_STEP_METRICS)]


def _CsvText(value) -> str:
    if value is None:
        return ''
    if isinstance(value, float):
        return repr(value)
    return str(value)


def _FromCsv(column: str, text: str):
    if column in ('status', 'error'):
        return text
    if text == '':
        return None
    if column == 'run':
        return int(text)
    if column in _BOOL_COLUMNS or column.endswith('.chatter'):
        verdict = column == 'loweringChatter' or column.endswith('.chatter')
        if text not in ('True', 'False') and not (verdict and text == 'unresolved'):
            raise ValueError(f"column {column}: expected True or False{' or unresolved' if verdict else ''}, "
                             f"got {text!r}")
        return text if text == 'unresolved' else text == 'True'
    return float(text)


def StudySidecarPath(output: Union[str, os.PathLike]) -> Path:
    """The JSON sidecar of a results file: ``runs.csv`` -> ``runs.study.json``.

    Parameters
    ----------
    output : str or path-like
        The CSV results file.
    """
    output = Path(output)
    return output.with_name(output.stem + '.study.json')


def _ReadCsv(path: Path, repair: bool = False) -> Tuple[List[str], List[Dict]]:
    """Rows of a results file; a last line cut off by a killed job is dropped (and removed with ``repair``)."""
    with path.open(newline='') as f:
        text = f.read()
    lines = text.splitlines(keepends=True)
    if lines and not lines[-1].endswith('\n'):
        lines = lines[:-1]                                # partial last line of a killed job
    reader = csv.reader(lines)
    header = next(reader, None)
    if header is None:
        return [], []
    rows, good = [], len(lines)
    for n, values in enumerate(reader, start=1):
        if len(values) != len(header):
            good = n
            break
        try:
            rows.append({c: _FromCsv(c, v) for c, v in zip(header, values)})
        except ValueError:
            good = n
            break
    if repair and (good < len(lines) or ''.join(lines) != text):
        with path.open('w', newline='') as f:
            f.write(''.join(lines[:good]))
    return header, rows


def ReadResults(*paths: Union[str, os.PathLike]) -> 'StudyResult':
    """Read one or more results files of one study (e.g. the shards of a job array) into one result.

    Parameters
    ----------
    *paths : str or path-like
        CSV files written by :func:`RunStudy`, each with its JSON sidecar (:func:`StudySidecarPath`).

    Returns
    -------
    StudyResult
        The runs of all files, by run index (a run present twice is taken once, the last read).

    Raises
    ------
    ValueError
        If a file or sidecar is missing or the files belong to different studies.
    """
    if not paths:
        raise ValueError("ReadResults: give at least one results file")
    definition, rows = None, {}
    for path in map(Path, paths):
        sidecar = StudySidecarPath(path)
        if not path.is_file() or not sidecar.is_file():
            raise ValueError(f"ReadResults: '{path}' and its sidecar '{sidecar}' must both exist")
        meta = json.loads(sidecar.read_text())
        if definition is None:
            definition = meta['study']
        elif _Identity(meta['study']) != _Identity(definition):
            raise ValueError(f"ReadResults: '{path}' belongs to a different study than '{paths[0]}'")
        for row in _ReadCsv(path)[1]:
            rows[row['run']] = row
    study = _StudyFromDict(definition)
    return StudyResult(study, [rows[k] for k in sorted(rows)])


def _Identity(definition: Mapping) -> Dict:
    d = json.loads(json.dumps(definition))
    d.pop('source', None)
    d.setdefault('maxSteps', None)           # files written before the option existed: the default limit
    d.setdefault('checkStep', None)
    for v in d.get('variations', []):
        v.pop('text', None)
    return d


#: the option of ``exudyn-worm sweep`` behind each entry of a study definition (for messages)
_DEFINITION_OPTIONS = {'base': '--preset/--config/--set', 'variations': '--vary', 'zipped': '--zip',
                       'windows': '--windows', 'endTime': '--end-time', 'stepSize': '--step-size',
                       'maxSteps': '--max-steps', 'checkStep': '--check-step/--no-check-step', 'runs': '--vary',
                       'shard': '--shard'}


def _Text(value) -> str:
    if value is None:
        return 'default'
    if isinstance(value, float):
        return f'{value:g}'
    return json.dumps(value)


def _DefinitionDifferences(old: Mapping, new: Mapping) -> List[str]:
    """What differs between two study identities (plus ``shard``), one phrase per entry: the entry, the
    option of ``sweep`` that sets it, the old and the new value."""
    out = []
    for name in dict.fromkeys(list(new) + list(old)):
        a, b = old.get(name), new.get(name)
        if a == b:
            continue
        option = _DEFINITION_OPTIONS.get(name, name)
        if name == 'base' and isinstance(a, Mapping) and isinstance(b, Mapping):
            for key in dict.fromkeys(list(b) + list(a)):
                if a.get(key) != b.get(key):
                    out.append(f"parameter {key} ({option}): {_Text(a.get(key))} in the file, {_Text(b.get(key))} now")
        elif name == 'variations' and isinstance(a, list) and isinstance(b, list):
            spell = lambda vs: '; '.join(f"{v.get('key')}={','.join(f'{x:g}' for x in v.get('values', []))}"
                                         for v in vs)
            out.append(f"varied values ({option}): {spell(a) or 'none'} in the file, {spell(b) or 'none'} now")
        elif name == 'runs' and old.get('variations') != new.get('variations'):
            continue                                      # the number of runs follows from the variations
        else:
            out.append(f"{name} ({option}): {_Text(a)} in the file, {_Text(b)} now")
    return out


def _StudyFromDict(d: Mapping) -> Study:
    return Study(base=d['base'], variations=[Variation(v['key'], tuple(v['values']), v.get('text', ''))
                                             for v in d['variations']],
                 zipped=d['zipped'], windows=d['windows'], endTime=d['endTime'], stepSize=d['stepSize'],
                 source=d.get('source', ''), checkStep=d.get('checkStep'))


@dataclass
class StudyResult:
    """The runs of a study, ordered by run index.

    Attributes
    ----------
    study : Study
        The definition.
    rows : list of dict
        Flat rows as in the CSV file (see :func:`RunPoint`).
    """
    study: Study
    rows: List[Dict]

    @property
    def finished(self) -> List[Dict]:
        """The rows of runs that succeeded (status ``ok``)."""
        return [r for r in self.rows if r['status'] == 'ok']

    @property
    def failed(self) -> List[Dict]:
        """The rows of failed runs."""
        return [r for r in self.rows if r['status'] != 'ok']

    @property
    def agreement(self) -> Optional[float]:
        """Fraction of finished runs whose chatter while lowering matches the analytical S = -1 verdict
        (chatter iff unstable); None if no finished run has a lowering window. Runs whose verdict is
        ``'unresolved'`` (it changes at half the step) are left out."""
        judged = [r for r in self.finished if r['loweringChatter'] in (True, False)
                  and r['analyticStableLowering'] is not None]
        if not judged:
            return None
        return sum(r['loweringChatter'] == (not r['analyticStableLowering']) for r in judged) / len(judged)

    def Run(self, row: Mapping) -> Dict:
        """One row in the JSON form of ``exudyn-worm sweep --json``.

        Parameters
        ----------
        row : mapping
            A flat row of :attr:`rows`.
        """
        windows = []
        for i in range(self.study.numberOfWindows):
            if row.get(f'w{i}.t0') is None:
                break
            windows.append({name: row[f'w{i}.{name}'] for name in WINDOW_METRICS})
            if row.get('stepChecked'):
                windows[-1]['halfStep'] = {name: row.get(f'w{i}.halfStep.{name}') for name in HALF_STEP_METRICS}
        return {'run': row['run'], 'parameters': {k: row[k] for k in self.study.keys},
                'status': row['status'], 'error': row['error'] or None, 'seconds': row['seconds'],
                'solveSeconds': row['solveSeconds'], 'stepSize': row['stepSize'], 'windows': windows,
                'analyticStable': row['analyticStable'], 'analyticStableLowering': row['analyticStableLowering'],
                'loweringChatter': row['loweringChatter'], 'stepChecked': row.get('stepChecked')}

    def ToDict(self) -> Dict:
        """``{"runs": [...], "agreement": float or None}`` (the schema of ``exudyn-worm sweep --json``)."""
        return {'runs': [self.Run(r) for r in self.rows], 'agreement': self.agreement}

    def Values(self, column: str) -> np.ndarray:
        """One column over all rows as a float array (NaN where missing), e.g. ``'J1'`` or
        ``'w1.maxNormalForce'``.

        Parameters
        ----------
        column : str
            A column of the results table.
        """
        return np.array([np.nan if r.get(column) is None else float(r[column]) for r in self.rows])

    def plot(self, x: str, y: Optional[str] = None, metric: str = 'w1.maxAbsWheelAcceleration',
             resolution: int = 60, **kwargs):
        """Plot with :mod:`exudyn_worm.plot_study` (matplotlib is imported only there): ``metric`` against
        parameter ``x``, or, with ``y``, the chatter map over ``x`` and ``y`` over the analytical region of
        :func:`~exudyn_worm.studymap.ComputeChatterMap`.

        Parameters
        ----------
        x : str
            Varied key on the horizontal axis.
        y : str, optional
            Second varied key: draw the 2-D chatter map.
        metric : str, optional
            Column for the 1-D plot.
        resolution : int, optional
            Points per axis of the chatter map's analytical grid (the stability chart gets at least 300).
        **kwargs
            Passed on to the plotting function.

        Returns
        -------
        matplotlib.figure.Figure
        """
        from . import plot_study                   # lazy: matplotlib only when drawing
        if y is None:
            return plot_study.PlotMetric(self, x, metric, **kwargs)
        return plot_study.PlotChatterMap(self, ComputeChatterMap(self, x, y, resolution), **kwargs)

    def Plot(self, *args, **kwargs):
        """Deprecated spelling of :meth:`plot` (warns; removed in the next release).

        Parameters
        ----------
        *args, **kwargs
            As for :meth:`plot`.

        Returns
        -------
        matplotlib.figure.Figure
        """
        warnings.warn("StudyResult.Plot is deprecated; use StudyResult.plot", DeprecationWarning, stacklevel=2)
        return self.plot(*args, **kwargs)


# ---------------------------------------------------------------------------------------------------------------
# execution

def DefaultWorkers() -> int:
    """CPUs this process may use (``os.sched_getaffinity`` where available, so a SLURM allocation counts)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:                    # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)


def _Versions(engine: str) -> Dict[str, str]:
    versions = {'python': platform.python_version(), 'platform': platform.platform()}
    for name in ('exudyn-worm', 'exudyn', 'numpy', 'scipy') + (('mpi4py',) if engine == 'mpi' else ()):
        try:
            versions[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            versions[name] = None
    try:                                                  # a source checkout: which commit computed the table
        git = ['git', '-C', str(Path(__file__).resolve().parent)]
        head = subprocess.run(git + ['rev-parse', 'HEAD'], capture_output=True, text=True, timeout=10)
        if head.returncode == 0:
            dirty = subprocess.run(git + ['status', '--porcelain', '--untracked-files=no'], capture_output=True,
                                   text=True, timeout=10)
            versions['gitCommit'] = head.stdout.strip()
            versions['gitModified'] = bool(dirty.stdout.strip())
    except (OSError, ValueError, subprocess.SubprocessError):
        pass
    return versions


def _Executor(engine: str, workers: Optional[int]):
    if engine == 'mpi':
        try:
            from mpi4py.futures import MPIPoolExecutor  # lazy: optional dependency (the mpi extra) and an MPI runtime
        except ImportError as err:
            raise ValueError(f"RunStudy: engine 'mpi' needs mpi4py and an MPI runtime "
                             f"(pip install 'exudyn-worm[mpi]'): {err}") from None
        return MPIPoolExecutor(max_workers=workers, initializer=_WorkerInit)
    for module in ('exudyn', f'{__package__}.reelchanger'):   # imported once here, inherited by forked workers
        importlib.import_module(module)
    if sys.platform.startswith('linux'):
        # fork: workers inherit the imported modules (no start-up per worker) and scripts need no
        # ``if __name__ == '__main__'`` guard; the pool is created before any thread of ours
        context = multiprocessing.get_context('fork')
    else:                                               # pragma: no cover - macOS, Windows
        context = multiprocessing.get_context('spawn')
    return ProcessPoolExecutor(max_workers=workers, mp_context=context, initializer=_WorkerInit)


class _Terminated(KeyboardInterrupt):
    """SIGTERM (e.g. a job scheduler's time limit) handled like Ctrl-C."""


def _CheckOutput(output: Path, study: Study, shard, overwrite: bool) -> List[Dict]:
    """Check the results file before computing; return the rows of a study to resume (else [])."""
    where = 'RunStudy'
    sidecar = StudySidecarPath(output)
    if output.suffix.lower() != '.csv':
        raise ValueError(f"{where}: 'output' must be a .csv file, got '{output}'")
    if output.is_dir():
        raise ValueError(f"{where}: 'output' is a directory: '{output}'")
    if not output.parent.is_dir():
        raise ValueError(f"{where}: the folder of 'output' does not exist: '{output.parent}'")
    if not os.access(output.parent, os.W_OK):
        raise ValueError(f"{where}: cannot write into '{output.parent}'")
    if overwrite or not output.exists():
        for p in (output, sidecar):
            if p.exists():
                p.unlink()
        return []
    if not sidecar.is_file():
        raise ValueError(f"{where}: '{output}' exists without its sidecar '{sidecar.name}', so it cannot be "
                         f"resumed; choose another output file or start it afresh (--overwrite; overwrite=True)")
    try:
        meta = json.loads(sidecar.read_text())
        old = dict(_Identity(meta['study']), shard=meta.get('shard') and list(meta['shard']))
        differences = _DefinitionDifferences(old, dict(study.Identity(), shard=shard and list(shard)))
    except (ValueError, KeyError, TypeError, AttributeError):
        differences = [f"its sidecar '{sidecar.name}' cannot be read"]
    if differences:
        raise ValueError(f"{where}: '{output}' holds results of a different study ({'; '.join(differences)}); "
                         f"give the same options to resume it, or choose another output file or start it afresh "
                         f"(--overwrite; overwrite=True)")
    header, rows = _ReadCsv(output, repair=True)
    if header and header != _Columns(study):
        raise ValueError(f"{where}: '{output}' has other columns than this study; choose another output file")
    return rows


def _WriteSidecar(path: Path, study: Study, shard, engine, workers, started, versions, counts=None,
                  wallSeconds=None) -> None:
    meta = {'study': study.ToDict(), 'shard': list(shard) if shard else None, 'engine': engine, 'workers': workers,
            'versions': versions,
            'units': {k: PARAMETER_UNITS[k] for k in study.keys},
            'windowMetricUnits': {'t0': 's', 't1': 's', 'maxAbsWheelAcceleration': 'rad/s^2', 'maxNormalForce': 'N',
                                  'dominantFrequencyHz': 'Hz', 'fractionSNegative': '-', 'minWormSpeed': 'rad/s',
                                  'chatter': 'bool', 'vibrationSeconds': 's'},
            'columns': _Columns(study), 'started': started, 'updated': time.strftime('%Y-%m-%dT%H:%M:%S%z'),
            'counts': counts, 'wallSeconds': wallSeconds}
    tmp = path.with_name(path.name + '.tmp')
    tmp.write_text(json.dumps(meta, indent=2, allow_nan=False))
    os.replace(tmp, path)


def RunStudy(study: Study, output: Union[str, os.PathLike, None] = None, workers: Optional[int] = None,
             engine: str = 'process', shard: Union[str, Tuple[int, int], None] = None, quiet: Optional[bool] = None,
             overwrite: bool = False, onRow: Optional[Callable[[Dict], None]] = None) -> StudyResult:
    """Run a study in parallel; write each run to ``output`` as it finishes; resume a study cut short.

    Parameters
    ----------
    study : Study
        The study.
    output : str or path-like, optional
        CSV results file (one row per run, written as runs finish) with a JSON sidecar
        (:func:`StudySidecarPath`: definition, versions, units, counts, ``wallSeconds`` summed over the
        invocations that computed it). If it exists with the sidecar of the same
        study (and shard), its finished runs are kept and only the others are run. Checked before computing.
    workers : int, optional
        Worker processes, >= 1 (default for ``'process'``: every CPU available, :func:`DefaultWorkers`; for
        ``'mpi'``: left to mpi4py, which under ``mpiexec -n N python -m mpi4py.futures`` uses the N - 1 worker
        ranks).
    engine : {'process', 'mpi'}
        ``concurrent.futures.ProcessPoolExecutor`` (default) or ``mpi4py.futures.MPIPoolExecutor``.
    shard : str or (int, int), optional
        ``'i/N'``: run only the runs i, i + N, i + 2N, ... (:func:`ShardIndices`), for job arrays.
    quiet : bool, optional
        No progress bar (default: a bar on stderr if it is a terminal).
    overwrite : bool, optional
        Delete an existing ``output`` (and sidecar) instead of resuming it.
    onRow : callable, optional
        Called with each new row (flat dict) as it arrives.

    Returns
    -------
    StudyResult
        All runs of the study (or shard), including those of a resumed file, ordered by run index.

    Raises
    ------
    ValueError
        For bad arguments or an output file that cannot be written or belongs to another study.
    KeyboardInterrupt
        On Ctrl-C or SIGTERM, after the finished runs are saved (rerun the same call to resume); the queued
        runs are cancelled and the running ones stopped at once (a process pool's workers are terminated).
    """
    where = 'RunStudy'
    if not isinstance(study, Study):
        raise TypeError(f"{where}: 'study' must be a Study, got {type(study).__name__}")
    if engine not in ENGINES:
        raise ValueError(f"{where}: 'engine' must be one of {', '.join(ENGINES)}, got {engine!r}")
    shard = ParseShard(shard)
    if workers is None and engine == 'process':
        workers = DefaultWorkers()
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise ValueError(f"{where}: 'workers' must be a whole number >= 1, got {workers!r}")
    output = Path(output) if output is not None else None
    indices = ShardIndices(len(study.points), shard)
    previous = _CheckOutput(output, study, shard, overwrite) if output is not None else []
    done = {r['run']: r for r in previous if r['run'] in set(indices)}
    startTime = time.perf_counter()
    started = time.strftime('%Y-%m-%dT%H:%M:%S%z')
    wallBefore = 0.
    if previous:                                          # resumed: keep the start and add up the wall time
        try:
            meta = json.loads(StudySidecarPath(output).read_text())
            started, wallBefore = meta.get('started') or started, float(meta.get('wallSeconds') or 0.)
        except (OSError, ValueError, TypeError, AttributeError):
            pass
    todo = [i for i in indices if i not in done]
    columns = _Columns(study)
    rows = dict(done)
    failed = sum(r['status'] != 'ok' for r in done.values())

    csvFile = writer = None
    # a resumed study with nothing left to run keeps its record (engine, workers, versions, wall time of the runs)
    record = output is not None and (bool(todo) or not previous or not StudySidecarPath(output).exists())
    if record:
        versions = _Versions(engine)       # once: the final record after Ctrl-C runs no subprocess
        _WriteSidecar(StudySidecarPath(output), study, shard, engine, workers, started, versions)
        new = not output.exists() or output.stat().st_size == 0
        csvFile = output.open('a', newline='')
        writer = csv.writer(csvFile)
        if new:
            writer.writerow(columns)
            csvFile.flush()

    def Record(row):
        nonlocal failed
        row = {c: row.get(c) for c in columns}          # the same keys as a row read back from the file
        rows[row['run']] = row
        failed += row['status'] != 'ok'
        if writer is not None:
            writer.writerow([_CsvText(row.get(c)) for c in columns])
            csvFile.flush()
        if onRow is not None:
            onRow(row)

    if done and quiet is not True:
        print(f"resuming: {len(done)} of {len(indices)} runs already in '{output}'", file=sys.stderr)
    previousHandler = None
    try:
        if todo:
            try:
                previousHandler = signal.signal(signal.SIGTERM, _RaiseTerminated)
            except ValueError:                        # not the main thread
                previousHandler = None
            executor = _Executor(engine, None if workers is None else min(workers, len(todo)))
            try:
                futures = [executor.submit(RunPoint, study.Task(i)) for i in todo]
                with ProgressBar(total=len(todo), desc='sweep', unit='run', quiet=quiet) as bar:
                    for future in as_completed(futures):
                        Record(future.result())
                        bar.set_postfix(failed=failed, refresh=False)
                        bar.update(1)
            except BaseException:
                _Cancel(executor, futures)
                raise
            else:
                executor.shutdown(wait=True)
    finally:
        if previousHandler is not None:
            signal.signal(signal.SIGTERM, previousHandler)
        if csvFile is not None:
            csvFile.close()
        if record:
            _WriteSidecar(StudySidecarPath(output), study, shard, engine, workers, started, versions,
                          counts={'runs': len(indices), 'done': len(rows), 'failed': failed},
                          wallSeconds=wallBefore + time.perf_counter() - startTime)
    return StudyResult(study, [rows[i] for i in sorted(rows)])


def _Cancel(executor, futures) -> None:
    """Stop a study at once (Ctrl-C, SIGTERM, an error): cancel the queued runs and end the running ones.

    A process pool's workers are terminated (their runs are lost, the finished ones are already recorded);
    an MPI pool can only cancel what has not started.
    """
    for future in futures:
        future.cancel()
    processes = list((getattr(executor, '_processes', None) or {}).values())   # ProcessPoolExecutor only
    for process in processes:
        try:
            process.terminate()
        except (OSError, ValueError, AttributeError):
            pass
    executor.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        try:
            process.join(timeout=5.)
        except (OSError, ValueError, AttributeError, AssertionError):
            pass


def _RaiseTerminated(signum, frame):
    raise _Terminated()
