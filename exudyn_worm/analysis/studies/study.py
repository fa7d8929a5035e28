"""Parameter studies: many reel-changer simulations over a grid of parameters, on every core or a cluster.

A :class:`~exudyn_worm.analysis.studies.studygrid.Study` varies keys of a flat parameter set (any key of
:data:`~exudyn_worm.drive.presets.PARAMETER_UNITS`, e.g. ``J1``, ``kT``, ``backlash``, ``motorSpeed``,
``loadMass``) over grids or lists (:func:`~exudyn_worm.analysis.studies.studygrid.ParseVariation`), as a full factorial or zipped. For every
point, :func:`~exudyn_worm.analysis.studies.studypoint.RunPoint` runs :func:`~exudyn_worm.analysis.simulation.reelchanger.SimulateReelChanger`, takes the window
metrics and chatter verdicts of ``exudyn-worm simulate``
(:meth:`~exudyn_worm.items.results.SimulationResult.WindowMetrics`), adds the linear verdict of the same
parameter set (:func:`~exudyn_worm.analysis.stability.drivestability.DriveStability`, as ``exudyn-worm stability``: the analytical
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

The study lives in four modules: :mod:`~exudyn_worm.analysis.studies.studygrid` (what it varies),
:mod:`~exudyn_worm.analysis.studies.studypoint` (one run, in a worker), :mod:`~exudyn_worm.analysis.studies.studyfiles` (the
results table, its sidecar and provenance, resuming) and this one (executors, progress, Ctrl-C and SIGTERM); each
name is imported from the module that defines it. No matplotlib here: plots are in
:mod:`exudyn_worm.plotting.plot_study`.
"""
from __future__ import annotations

import contextlib
import csv
import importlib
import json
import multiprocessing
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path
from typing import Callable, Dict, Optional, Tuple, Union

from ..._files import OutputLock
from ..._workers import CancelPool, SignalsHeld, SigtermAsInterrupt, WorkerInit
from ...progress import ProgressBar
from .studyfiles import (StudyResult, StudySidecarPath, _CheckOutput, _CheckOutputPath, _Columns, _CsvText, _SortByRun,
                         _Versions, _WriteSidecar)
from .studygrid import CheckStudySize, ParseShard, ShardIndices, Study
from . import studypoint

__all__ = ['ENGINES', 'DefaultWorkers', 'RunStudy']


#: execution engines of :func:`RunStudy`
ENGINES = ('process', 'mpi')


def DefaultWorkers() -> int:
    """CPUs this process may use (``os.sched_getaffinity`` where available, so a SLURM allocation counts)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:                    # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)


def _Executor(engine: str, workers: Optional[int]):
    if engine == 'mpi':
        try:
            from mpi4py.futures import MPIPoolExecutor  # lazy: optional dependency (the mpi extra) and an MPI runtime
        except ImportError as err:
            raise ValueError(f"RunStudy: engine 'mpi' needs mpi4py and an MPI runtime "
                             f"(pip install 'exudyn-worm[mpi]'): {err}") from None
        return MPIPoolExecutor(max_workers=workers, initializer=WorkerInit)
    for module in ('exudyn', 'exudyn_worm.analysis.simulation.reelchanger'):   # imported once here, inherited by forked workers
        importlib.import_module(module)
    if sys.platform.startswith('linux'):
        # fork: workers inherit the imported modules (no start-up per worker) and scripts need no
        # ``if __name__ == '__main__'`` guard; the pool is created before any thread of ours
        context = multiprocessing.get_context('fork')
    else:                                               # pragma: no cover - macOS, Windows
        context = multiprocessing.get_context('spawn')
    return ProcessPoolExecutor(max_workers=workers, mp_context=context, initializer=WorkerInit, initargs=(os.getpid(),))


def RunStudy(study: Study, output: Union[str, os.PathLike, None] = None, workers: Optional[int] = None,
             engine: str = 'process', shard: Union[str, Tuple[int, int], None] = None, quiet: Optional[bool] = None,
             overwrite: bool = False, onRow: Optional[Callable[[Dict], None]] = None,
             maxRuns: Optional[int] = None) -> StudyResult:
    """Run a study in parallel; write each run to ``output`` as it finishes; resume a study cut short.

    Parameters
    ----------
    study : Study
        The study.
    output : str or path-like, optional
        CSV results file (one row per run, written as runs finish) with a JSON sidecar
        (:func:`~exudyn_worm.analysis.studies.studyfiles.StudySidecarPath`: definition, versions, units, counts, ``wallSeconds`` summed over the
        invocations that computed it). If it exists with the sidecar of the same
        study (and shard), its finished runs are kept and only the others are run. Checked before computing.
    workers : int, optional
        Worker processes, >= 1 (default for ``'process'``: every CPU available, :func:`DefaultWorkers`; for
        ``'mpi'``: left to mpi4py, which under ``mpiexec -n N python -m mpi4py.futures`` uses the N - 1 worker
        ranks).
    engine : {'process', 'mpi'}
        ``concurrent.futures.ProcessPoolExecutor`` (default) or ``mpi4py.futures.MPIPoolExecutor``.
    shard : str or (int, int), optional
        ``'i/N'``: run only the runs i, i + N, i + 2N, ... (:func:`~exudyn_worm.analysis.studies.studygrid.ShardIndices`), for job arrays.
    quiet : bool, optional
        No progress bar (default: a bar on stderr if it is a terminal).
    overwrite : bool, optional
        Delete an existing ``output`` (and sidecar) instead of resuming it.
    onRow : callable, optional
        Called with each new row (flat dict) as it arrives.
    maxRuns : int, optional
        Runs this call may hold (the study's, or its shard's), >= 1; default
        :data:`~exudyn_worm.analysis.studies.studygrid.MAX_RUNS` (100,000: about 0.9 GB in the parent). A larger study is
        refused before any run, saying into how many shards to split it.

    Returns
    -------
    StudyResult
        All runs of the study (or shard), including those of a resumed file, ordered by run index.

    Raises
    ------
    ValueError
        For bad arguments, a study (or shard) of more than ``maxRuns`` runs, or an output file that cannot be
        written or belongs to another study.
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
    CheckStudySize(study, shard, maxRuns, where)          # before the list of runs is built
    indices = ShardIndices(len(study.points), shard)
    with contextlib.ExitStack() as stack:
        stack.enter_context(SigtermAsInterrupt())         # SIGTERM (a scheduler's limit) saves the runs as Ctrl-C
        lock = None
        if output is not None:
            _CheckOutputPath(output)
            # a second study on the same file (under any name) is refused at once
            lock = stack.enter_context(OutputLock(output, where))
        return _RunLocked(study, output, indices, workers, engine, shard, quiet, overwrite, onRow, lock)


def _RunLocked(study, output, indices, workers, engine, shard, quiet, overwrite, onRow, lock) -> StudyResult:
    """The body of :func:`RunStudy`, with ``output`` checked and locked."""
    previous = _CheckOutput(output, study, shard, overwrite) if output is not None else []
    shardRuns = set(indices)
    done = {r['run']: r for r in previous if r['run'] in shardRuns}
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
        created = not output.exists()
        new = created or output.stat().st_size == 0
        csvFile = output.open('a', newline='')
        try:
            writer = csv.writer(csvFile)
            if new:
                writer.writerow(columns)
                csvFile.flush()
            lock.HoldFile()                               # the file itself, now that it exists (or was replaced)
        except BaseException as err:                      # e.g. a full disk: no empty or half a header left
            with contextlib.suppress(OSError):
                csvFile.close()
            if created:
                for path in (output, StudySidecarPath(output)):
                    with contextlib.suppress(OSError):
                        path.unlink()
            if isinstance(err, OSError) and err.filename is None:
                raise OSError(err.errno, err.strerror, os.fspath(output)) from None
            raise

    def Record(row):
        nonlocal failed
        row = {c: row.get(c) for c in columns}          # the same keys as a row read back from the file
        rows[row['run']] = row
        failed += row['status'] != 'ok'
        if writer is not None:
            try:
                writer.writerow([_CsvText(row.get(c)) for c in columns])
                csvFile.flush()
            except OSError as err:                        # a full disk: the message names the results file
                raise OSError(err.errno, err.strerror, os.fspath(output)) from None
        if onRow is not None:
            onRow(row)

    if done and quiet is not True:
        print(f"resuming: {len(done)} of {len(indices)} runs already in '{output}'", file=sys.stderr)
    completed = False
    try:
        if todo:
            executor = _Executor(engine, None if workers is None else min(workers, len(todo)))
            futures = []
            try:
                with SignalsHeld():                       # the first submit forks the workers
                    futures.append(executor.submit(studypoint.RunPoint, study.Task(todo[0])))
                futures += [executor.submit(studypoint.RunPoint, study.Task(i)) for i in todo[1:]]
                with ProgressBar(total=len(todo), desc='sweep', unit='run', quiet=quiet) as bar:
                    for future in as_completed(futures):
                        Record(future.result())
                        bar.set_postfix(failed=failed, refresh=False)
                        bar.update(1)
            except BaseException:
                CancelPool(executor, futures)
                raise
            else:
                executor.shutdown(wait=True)
        completed = True
    finally:
        # each row was flushed: closing fails only after a failed flush, which was raised (a full disk)
        if csvFile is not None:
            with contextlib.suppress(OSError):
                csvFile.close()
            _SortByRun(output)                     # written as the runs finished: in run order on finishing
        if record:
            # the last record; after an interrupt or an error, its own failure (a full disk) does not replace them
            with contextlib.suppress(*(() if completed else (OSError,))):
                _WriteSidecar(StudySidecarPath(output), study, shard, engine, workers, started, versions,
                              counts={'runs': len(indices), 'done': len(rows), 'failed': failed},
                              wallSeconds=wallBefore + time.perf_counter() - startTime)
    return StudyResult(study, [rows[i] for i in sorted(rows)])
