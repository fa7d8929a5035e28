"""Cost of the chunked solve that makes the progress bar possible (exudyn_worm.items.solve.SolveDynamicInChunks).

Compares, for the reel changer's P1 and P7 (one rotation, SimulateReelChanger's settings and recommended step):
(a) one ``mbs.SolveDynamic`` call, (b) ``SolveDynamicInChunks`` with the bar off, (c) with the bar drawn (into
a buffer). CPU seconds of the solve alone, minimum of interleaved repetitions. Run:
``python benchmarks/bench_chunked_solve.py [--repeats 5]`` (about 1 min); nothing is written.
"""
from __future__ import annotations

import argparse
import contextlib
import io
import sys
import time

__all__ = ['Solve', 'main']


def Solve(preset: str, mode: str):
    """CPU seconds and Newton statistics of one solve of ``preset`` in ``mode`` ('one', 'chunks', 'bar')."""
    import exudyn as exu
    from exudyn_worm import GetPreset
    from exudyn_worm.analysis.simulation.reelchanger import RotationPeriod, SolverSettings
    from exudyn_worm.builders.oneangle import BuildReelChanger
    from exudyn_worm.items.solve import SolveDynamicInChunks
    from exudyn_worm.analysis.simulation.stepsize import RecommendedStepSize
    from exudyn_worm.drive.wholedrive import ResolveDrive
    p = GetPreset(preset)
    drive = ResolveDrive(parameters=p)
    endTime, h = RotationPeriod(drive), RecommendedStepSize(drive)
    model = BuildReelChanger(exu.SystemContainer().AddSystem(), drive)
    mbs = model.mbs
    mbs.Assemble()
    ss, solverType = SolverSettings(endTime, h, where='bench')
    printing, exu.config.printToConsole = exu.config.printToConsole, False
    buffer = io.StringIO()
    try:
        with contextlib.redirect_stderr(buffer):
            c0 = time.process_time()
            if mode == 'one':
                mbs.SolveDynamic(ss, solverType=solverType)
            else:
                SolveDynamicInChunks(mbs, ss, solverType, progress=(mode == 'bar'))
            cpu = time.process_time() - c0
    finally:
        exu.config.printToConsole = printing
    it = mbs.sys['dynamicSolver'].it
    return cpu, int(it.newtonJacobiCount), int(it.newtonStepsCount), len(buffer.getvalue())


def main(argv=None) -> int:
    """Print the CPU seconds per mode and their ratios to the one-piece solve."""
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--repeats', type=int, default=5)
    args = parser.parse_args(argv)
    for preset in ('reel-P1', 'reel-P7'):
        best, stats = {}, {}
        for _ in range(args.repeats):
            for mode in ('one', 'chunks', 'bar'):
                cpu, jac, newton, drawn = Solve(preset, mode)
                best[mode] = min(best.get(mode, cpu), cpu)
                stats[mode] = (jac, newton, drawn)
        print(f"{preset}: CPU s (min of {args.repeats}): " + ', '.join(f"{m} {best[m]:.3f}" for m in best)
              + f"; chunks/one {best['chunks'] / best['one']:.3f}, bar/one {best['bar'] / best['one']:.3f}; "
              + 'Jacobians/Newton iterations ' + ', '.join(f"{m} {j}/{n}" for m, (j, n, _) in stats.items())
              + f"; bar output {stats['bar'][2]} characters")
    return 0


if __name__ == '__main__':
    sys.exit(main())
