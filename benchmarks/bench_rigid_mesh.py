"""Benchmark: the reel changer P1 with worm and wheel as rigid bodies on ideal joints against the one-angle connector.

Runs once each, in one process: ``BuildReelChanger(GetPreset('reel-P1'))`` (one-angle connector, symbolic C++ law),
``BuildRigidBodyReelChanger(mbs, ResolveDrive('reel-P1'))`` (the mesh between rigid bodies on ideal joints that are linear
coordinate constraints, its law in C++ on auxiliary coordinates) and the same with ``useSymbolic=False`` (the law a
plain-Python user function),
8 s simulated at the drive's recommended step with the same solver settings; reports the solver call's wall and CPU
seconds, their ratio, and the largest difference of the normal force between the two (relative to its peak).

Usage::

    python benchmarks/bench_rigid_mesh.py [--end-time 8] [--model oneAngle|rigid|rigidPython]

``--model`` runs that model alone and prints nothing (for timing each as a whole process).

Nothing is written.
"""
from __future__ import annotations

import argparse
import sys
import time

import numpy as np

from exudyn_worm.analysis.simulation.reelchanger import SolverSettings
import exudyn as exu
from exudyn_worm.builders.oneangle import BuildReelChanger
from exudyn_worm.builders.rigidbody import BuildRigidBodyReelChanger
from exudyn_worm.analysis.simulation.stepsize import RecommendedStepSize
from exudyn_worm.drive.presets import GetPreset
from exudyn_worm.drive.wholedrive import ResolveDrive

__all__ = ['RunOnce', 'Main']


def RunOnce(build, parameters, endTime: float, **kwargs):
    """Build, solve and return (wall s, CPU s, stored mesh state) of one model."""
    drive = ResolveDrive(parameters=parameters)
    model = build(exu.SystemContainer().AddSystem(), drive, **kwargs)
    if build is BuildRigidBodyReelChanger:
        model.connector.AddSensors(model.mbs)
    model.mbs.Assemble()
    ss, solverType = SolverSettings(endTime, RecommendedStepSize(drive))
    wall, cpu = time.perf_counter(), time.process_time()
    model.mbs.SolveDynamic(ss, solverType=solverType)
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    return wall, cpu, model.connector.StoredMeshState(model.mbs)


def Main(argv=None) -> int:
    """Run the benchmark and print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--end-time', type=float, default=8.)
    parser.add_argument('--model', choices=('oneAngle', 'rigid', 'rigidPython'),
                        help='run this model alone and print nothing')
    args = parser.parse_args(argv)
    p1 = GetPreset('reel-P1')
    if args.model is not None:
        build = BuildReelChanger if args.model == 'oneAngle' else BuildRigidBodyReelChanger
        RunOnce(build, p1, args.end_time, **({'useSymbolic': False} if args.model == 'rigidPython' else {}))
        return 0
    one = RunOnce(BuildReelChanger, p1, args.end_time)
    rigid = RunOnce(BuildRigidBodyReelChanger, p1, args.end_time)
    python = RunOnce(BuildRigidBodyReelChanger, p1, args.end_time, useSymbolic=False)
    diff = np.max(np.abs(np.asarray(rigid[2].normalForce) - one[2].normalForce)) / np.max(np.abs(one[2].normalForce))
    print(f"{'model':44s} {'wall s':>8s} {'CPU s':>8s}")
    print(f"{'P1 one-angle connector (symbolic C++)':44s} {one[0]:8.3f} {one[1]:8.3f}")
    print(f"{'P1 rigid bodies on joints (C++ law)':44s} {rigid[0]:8.3f} {rigid[1]:8.3f}")
    print(f"{'P1 rigid bodies on joints (Python law)':44s} {python[0]:8.3f} {python[1]:8.3f}")
    print(f"ratio rigid/one-angle: wall {rigid[0] / one[0]:.1f}x, CPU {rigid[1] / one[1]:.1f}x (target <= 3x; Python "
          f"law: CPU {python[1] / one[1]:.1f}x); normal force differs by {diff:.2g} of its peak")
    return 0


if __name__ == '__main__':
    sys.exit(Main())
