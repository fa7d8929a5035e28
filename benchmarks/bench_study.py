"""Benchmark of parameter studies (exudyn_worm.analysis.studies.study): parallel speed-up, per-run overhead, the 144-point map.

Measures, in one process on this machine:

(a) a 16-run study (P1, J1 = 0.05 ... 0.2 kg*m^2, one rotation each) with 1 worker and with 2 workers, wall
    time of ``RunStudy`` including the pool start and the CSV writing; best of ``--repeat`` interleaved repetitions;
    the speed-up is 1-worker time / 2-worker time;
(b) the per-run overhead of a P1 run against its solve time (``mbs.SolveDynamic`` alone): model building with
    the symbolic user functions recorded (``BuildReelChanger``; the recording is the difference to Python user
    functions), ``Assemble`` and settings, post-processing (stored states, mesh evaluation, window metrics,
    analytical verdict) and writing one CSV row; best of ``--repeat`` each;
(c) the 144-point stability map of ``validation/studies.py`` (12 x 12 J1, kT at D_V = 0.014) with every core,
    wall time of the one call (skip with ``--no-map``).

Usage::

    python benchmarks/bench_study.py [--repeat 3] [--no-map] [--json FILE]

Nothing is written unless ``--json FILE`` is given (studies write into a temporary folder). The machine may be
shared: the load average is printed before and after; compare ratios measured in one run.
"""
from __future__ import annotations

import argparse
import csv
import json
import os
import platform
import resource
import sys
import tempfile
import time
from pathlib import Path
from typing import Dict

sys.dont_write_bytecode = True

import exudyn as exu
import numpy as np                                                  # noqa: E402

from exudyn_worm.drive.config import ResolveParameters                   # noqa: E402
from exudyn_worm.drive.presets import ElasticDriveFromParameters, GetPreset      # noqa: E402
from exudyn_worm.model.stability import AnalyzeStability                  # noqa: E402
from exudyn_worm.analysis.studies.study import RunStudy  # noqa: E402
from exudyn_worm.analysis.studies.studygrid import ParseVariation, Study
from exudyn_worm.analysis.studies.studypoint import VibrationSeconds
from exudyn_worm.drive.wholedrive import ResolveDrive  # noqa: E402

__all__ = ['SpeedUp', 'Overhead', 'MapWallTime', 'Main']

_STUDY16 = 'J1=0.05:0.2:16'


def _Load() -> str:
    try:
        return ' '.join(f'{x:.2f}' for x in os.getloadavg())
    except OSError:                                   # pragma: no cover
        return 'n/a'


def _ChildCpu() -> float:
    """CPU seconds of the finished child processes (the pool's workers, once shut down)."""
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def SpeedUp(repeat: int = 3) -> Dict:
    """Wall time of a 16-run study with 1 and with 2 workers (best of ``repeat``, interleaved)."""
    study = Study(ResolveParameters('reel-P1'), [ParseVariation(_STUDY16)])
    times = {1: [], 2: []}
    cores = {1: [], 2: []}
    inRun, solve, pool = [], [], []
    with tempfile.TemporaryDirectory() as folder:
        for k in range(repeat):
            for workers in (1, 2):
                t0, cpu0 = time.perf_counter(), _ChildCpu()
                result = RunStudy(study, Path(folder) / f'w{workers}_{k}.csv', workers=workers, quiet=True)
                wall = time.perf_counter() - t0
                times[workers].append(wall)
                cores[workers].append((_ChildCpu() - cpu0) / wall)     # CPUs the workers actually got
                assert len(result.finished) == 16
                if workers == 1:
                    seconds = result.Values('seconds')
                    solve.append(float(np.median(result.Values('solveSeconds'))))
                    inRun.append(float(np.median(seconds - result.Values('solveSeconds'))))
                    pool.append((wall - float(np.sum(seconds))) / 16)      # pool start, IPC, CSV, progress
    best = {w: min(t) for w, t in times.items()}
    return {'runs': 16, 'seconds1': best[1], 'seconds2': best[2], 'all1': times[1], 'all2': times[2],
            'speedUp': best[1] / best[2], 'coresUsed1': cores[1][int(np.argmin(times[1]))],
            'coresUsed2': cores[2][int(np.argmin(times[2]))], 'medianSolve': min(solve), 'medianInRunOverhead': min(inRun),
            'poolOverheadPerRun': min(pool)}


def Overhead(repeat: int = 5) -> Dict:
    """Per-run overhead of a P1 run, by stage, against its solve time (best of ``repeat`` per stage)."""
    import exudyn as exu
    from exudyn_worm.analysis.simulation.reelchanger import DefaultWindows, RotationPeriod
    from exudyn_worm.builders.oneangle import BuildReelChanger
    p = GetPreset('reel-P1')
    stages = {k: [] for k in ('buildPython', 'buildSymbolic', 'assemble', 'solve', 'postProcess', 'writeRow')}
    for _ in range(repeat):
        t0 = time.perf_counter()
        BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=p), useSymbolic=False)
        stages['buildPython'].append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        model = BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=p), useSymbolic=True)
        stages['buildSymbolic'].append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        mbs = model.mbs
        mbs.Assemble()
        endTime, step = RotationPeriod(ResolveDrive(parameters=p)), 5e-4
        ss = exu.SimulationSettings()
        ss.solution.file.write = False
        ss.solution.sensors.writePeriod = step
        ss.timeIntegration.endTime = endTime
        ss.timeIntegration.numberOfSteps = int(round(endTime / step))
        ss.timeIntegration.verboseMode = 0
        ss.timeIntegration.newton.useModifiedNewton = True
        stages['assemble'].append(time.perf_counter() - t0)
        printing = exu.config.printToConsole
        exu.config.printToConsole = False
        t0 = time.perf_counter()
        mbs.SolveDynamic(ss, solverType=exu.DynamicSolverType.GeneralizedAlpha)
        stages['solve'].append(time.perf_counter() - t0)
        exu.config.printToConsole = printing
        # post-processing as SimulateReelChanger + RunPoint do it
        t0 = time.perf_counter()
        series = model.connector.StoredStates(mbs)
        series.pop('time')
        model.connector.Evaluate(series['phi1'], series['phi2'], series['omega1'], series['omega2'])
        stages['postProcess'].append(time.perf_counter() - t0)
    # window metrics, vibration durations and the analytical verdict on a finished result
    from exudyn_worm.analysis.simulation.reelchanger import SimulateReelChanger
    result = SimulateReelChanger(ResolveDrive(parameters=p))
    metrics = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        windows = DefaultWindows(ResolveDrive(parameters=p))
        result.WindowMetrics(windows)
        [VibrationSeconds(result, a, b) for a, b in windows]
        AnalyzeStability(ElasticDriveFromParameters(p))
        metrics.append(time.perf_counter() - t0)
    row = [repr(float(x)) for x in np.random.default_rng(0).random(35)]
    with tempfile.TemporaryDirectory() as folder:
        with open(Path(folder) / 'rows.csv', 'a', newline='') as f:
            w = csv.writer(f)
            for _ in range(repeat):
                t0 = time.perf_counter()
                w.writerow(row)
                f.flush()
                stages['writeRow'].append(time.perf_counter() - t0)
    best = {k: min(v) for k, v in stages.items()}
    best['buildSymbolicFirst'] = stages['buildSymbolic'][0]     # the first model of the process (a worker's first run)
    best['postProcess'] += min(metrics)
    best['symbolicRecording'] = best['buildSymbolic'] - best['buildPython']
    overhead = best['buildSymbolic'] + best['assemble'] + best['postProcess'] + best['writeRow']
    return {'stages': best, 'overhead': overhead, 'overheadPercent': 100 * overhead / best['solve']}


def MapWallTime(workers=None) -> Dict:
    """Wall time of the 144-point map (J1 x kT, 12 x 12 log grid, D_V = 0.014) in one call on every core."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from validation.studies import MapStudy
    study = MapStudy(0.014)
    with tempfile.TemporaryDirectory() as folder:
        t0 = time.perf_counter()
        result = RunStudy(study, Path(folder) / 'map.csv', workers=workers, quiet=True)
        seconds = time.perf_counter() - t0
    return {'runs': len(result.rows), 'failed': len(result.failed), 'seconds': seconds,
            'workers': workers or os.cpu_count(), 'meanRunSeconds': float(np.mean([r['seconds'] for r in result.rows]))}


def _ReportOverhead(out: Dict, repeat: int) -> None:
    o = Overhead(max(repeat, 3))
    out['overhead'] = o
    s = o['stages']
    print(f"(b) P1 run, best of {max(repeat, 3)}: solve {s['solve']:.3f} s; build {s['buildSymbolic']:.4f} s "
          f"(of which symbolic recording {s['symbolicRecording']:.4f} s; the first model of a process "
          f"{s['buildSymbolicFirst']:.4f} s), assemble+settings {s['assemble']:.4f} s, "
          f"post-processing {s['postProcess']:.4f} s, CSV row {1e3 * s['writeRow']:.3f} ms -> overhead "
          f"{o['overhead']:.4f} s = {o['overheadPercent']:.1f} % of the solve time")


def Main(argv=None) -> int:
    """Command line; prints the report (and writes ``--json FILE``).

    Parameters
    ----------
    argv : list of str, optional
        Arguments (default ``sys.argv[1:]``).
    """
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--repeat', type=int, default=3)
    parser.add_argument('--no-map', action='store_true')
    parser.add_argument('--only-speed-up', action='store_true', help='measure (a) only')
    parser.add_argument('--json', default=None)
    args = parser.parse_args(argv)
    import exudyn
    out = {'date': time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime()), 'cpus': os.cpu_count(),
           'python': platform.python_version(), 'exudyn': exudyn.__version__, 'loadBefore': _Load()}
    print(f"{out['date']}, {out['cpus']} CPUs, python {out['python']}, exudyn {out['exudyn']}, "
          f"load average before: {out['loadBefore']}")
    if not args.only_speed_up:
        _ReportOverhead(out, args.repeat)
    sp = SpeedUp(args.repeat)
    out['speedUp'] = sp
    print(f"(a) 16-run study: 1 worker {sp['seconds1']:.2f} s, 2 workers {sp['seconds2']:.2f} s (best of "
          f"{args.repeat}) -> speed-up {sp['speedUp']:.2f}x; CPUs the workers got on average: "
          f"{sp['coresUsed1']:.2f} (1 worker), {sp['coresUsed2']:.2f} (2 workers)")
    print(f"    inside the study (1 worker): median solve {sp['medianSolve']:.3f} s, median run overhead (RunPoint "
          f"time - solve) {sp['medianInRunOverhead']:.4f} s = {100 * sp['medianInRunOverhead'] / sp['medianSolve']:.1f} %, "
          f"pool + result writing per run {sp['poolOverheadPerRun']:.4f} s = "
          f"{100 * sp['poolOverheadPerRun'] / sp['medianSolve']:.1f} %")
    if not (args.no_map or args.only_speed_up):
        m = MapWallTime()
        out['map'] = m
        print(f"(c) 144-point map: {m['seconds']:.1f} s wall with {m['workers']} workers, {m['failed']} failed, "
              f"mean run {m['meanRunSeconds']:.2f} s")
    out['loadAfter'] = _Load()
    print(f"load average after: {out['loadAfter']}")
    if args.json:
        Path(args.json).write_text(json.dumps(out, indent=2))
        print(f'wrote {Path(args.json).resolve()}')
    return 0


if __name__ == '__main__':
    raise SystemExit(Main())

