"""Memory of a study worker over many runs: ``RunPoint`` (the linear verdict, the simulation and, by default for the
reel presets, the run at half the step) of one preset, repeated in one process.

Prints the resident memory (``VmRSS``, Linux) after ``--warm-up`` runs and after ``--runs`` more, and the growth per
run. Run: ``python benchmarks/bench_memory.py [--preset reel-P7] [--runs 64] [--end-time 8]`` (P7, 64 runs of one
rotation: about 25 s); nothing is written. The plain-Exudyn cause of the growth this guards against is
``benchmarks/exudyn_symbolic_leak.py``.
"""
from __future__ import annotations

import argparse
import gc
import time

from exudyn_symbolic_leak import Rss

__all__ = ['WorkerGrowth', 'main']


def WorkerGrowth(preset: str = 'reel-P7', runs: int = 64, endTime=None, warmUp: int = 3, checkStep=True) -> dict:
    """Resident memory in MB before and after ``runs`` study points of ``preset``, and seconds per run.

    ``checkStep``: the half-step check of each point (True: forced, so that every point builds and frees three
    systems; None: the study's default, which checks only close verdicts).
    """
    from exudyn_worm import ResolveDrive
    from exudyn_worm.analysis.studies.studypoint import RunPoint, RunTask
    task = RunTask(0, ResolveDrive(preset), endTime=endTime, checkStep=checkStep)
    for _ in range(warmUp):
        RunPoint(task)
    gc.collect()
    before, start = Rss(), time.perf_counter()
    for _ in range(runs):
        row = RunPoint(task)
    seconds = (time.perf_counter() - start) / runs
    gc.collect()
    return {'before': before, 'after': Rss(), 'secondsPerRun': seconds, 'status': row['status'],
            'stepChecked': row['stepChecked']}


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--preset', default='reel-P7')
    parser.add_argument('--runs', type=int, default=64)
    parser.add_argument('--end-time', type=float, default=None, help='simulated s per run (default one rotation)')
    parser.add_argument('--warm-up', type=int, default=3)
    args = parser.parse_args(argv)
    g = WorkerGrowth(args.preset, args.runs, args.end_time, args.warm_up)
    print(f"{args.preset}, {args.runs} study points (status {g['status']}, half-step check {g['stepChecked']}, "
          f"{g['secondsPerRun']:.2f} s per run): resident memory {g['before']:.1f} -> {g['after']:.1f} MB, "
          f"{(g['after'] - g['before']) * 1024. / args.runs:.1f} kB per run")


if __name__ == '__main__':
    main()
