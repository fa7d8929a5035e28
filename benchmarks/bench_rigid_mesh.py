"""Benchmark: the reel changer P1 with worm and wheel as 3D bodies against the one-angle connector.

Runs in one process: ``BuildReelChanger(GetPreset('reel-P1'))`` (one-angle connector, symbolic C++ law); the 3D model
of P1 with the elastic bearings of ``examples/drives/reel-3d.toml``, as the small-displacement model (the default of a
drive with both shafts' bearings, ``exudyn_worm/items/smallmesh.py``) and as the exact rigid-body model
(``model='exact'``); and ``BuildRigidBodyReelChanger(mbs, ResolveDrive('reel-P1'))`` on ideal joints (linear coordinate
constraints, the law in C++ on auxiliary coordinates) and the same with ``useSymbolic=False`` (the law a plain-Python
user function). Each is 8 s simulated at the drive's recommended step with the settings of ``SimulateReelChanger``
(``SOLVER_SETTINGS``, for the small-displacement model with ``SMALL_3D_SOLVER_SETTINGS``; the constant-speed motor a
flywheel in the one-angle and the small-displacement model, the exact models hold it by a constraint); reports the
solver call's wall and CPU seconds (best of ``--repeat``), their ratio to the one-angle connector's, and the largest
difference of the peak normal force from the one-angle model's (on joints) or from the exact model's (bearings).

Usage::

    python benchmarks/bench_rigid_mesh.py [--end-time 8] [--repeat 3]
    python benchmarks/bench_rigid_mesh.py --model small --repeat 20    # one model only, for a whole-process timer

Nothing is written.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

from exudyn_worm.analysis.simulation.reelchanger import SMALL_3D_SOLVER_SETTINGS, SolverSettings
import exudyn as exu
from exudyn_worm.analysis.simulation import reelchanger3d
from exudyn_worm.builders.oneangle import BuildReelChanger
from exudyn_worm.builders.rigidbody import BuildRigidBodyReelChanger
from exudyn_worm.analysis.simulation.stepsize import RecommendedStepSize
from exudyn_worm.drive.presets import GetPreset
from exudyn_worm.drive.wholedrive import ResolveDrive

__all__ = ['RunOnce', 'Main', 'MODELS']

DRIVE_3D = Path(__file__).resolve().parent.parent / 'examples' / 'drives' / 'reel-3d.toml'


def _Bearings():
    """The bearing keys that examples/drives/reel-3d.toml adds to reel-P1."""
    return {k: v for k, v in ResolveDrive(config=str(DRIVE_3D)).parameters.items() if k not in GetPreset('reel-P1')}


#: the models by name: (label, builder, parameters, keyword arguments)
MODELS = {
    'one-angle': ('P1 one-angle connector (symbolic C++)', BuildReelChanger, lambda: GetPreset('reel-P1'),
                  {'motorConstraint': False}),
    'small': ('P1 3D, elastic bearings: small-displacement', BuildRigidBodyReelChanger,
              lambda: {**GetPreset('reel-P1'), **_Bearings()}, {'model': 'small', 'motorConstraint': False}),
    'exact': ('P1 3D, elastic bearings: exact rigid bodies', BuildRigidBodyReelChanger,
              lambda: {**GetPreset('reel-P1'), **_Bearings()}, {'model': 'exact'}),
    'joints': ('P1 rigid bodies on joints (C++ law)', BuildRigidBodyReelChanger, lambda: GetPreset('reel-P1'), {}),
    'joints-python': ('P1 rigid bodies on joints (Python law)', BuildRigidBodyReelChanger, lambda: GetPreset('reel-P1'),
                      {'useSymbolic': False}),
}


def RunOnce(build, parameters, endTime: float, **kwargs):
    """Build, solve and return (wall s, CPU s, peak normal force in N) of one model."""
    drive = ResolveDrive(parameters=parameters)
    model = build(exu.SystemContainer().AddSystem(), drive, **kwargs)
    if build is BuildRigidBodyReelChanger:
        reelchanger3d.AddSeriesSensors(model)
    model.mbs.Assemble()
    ss, solverType = SolverSettings(endTime, RecommendedStepSize(drive),
                                    SMALL_3D_SOLVER_SETTINGS if kwargs.get('model') == 'small' else None)
    wall, cpu = time.perf_counter(), time.process_time()
    model.mbs.SolveDynamic(ss, solverType=solverType)
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    if build is BuildRigidBodyReelChanger:
        state = reelchanger3d.StoredMeshState(model)
    else:
        state = model.connector.StoredMeshState(model.mbs)
    return wall, cpu, float(np.max(np.abs(state.normalForce)))


def Main(argv=None) -> int:
    """Run the benchmark and print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--end-time', type=float, default=8.)
    parser.add_argument('--repeat', type=int, default=3, help='solves of each model; the best is reported')
    parser.add_argument('--model', choices=sorted(MODELS), help='run this model only')
    args = parser.parse_args(argv)
    exu.config.printToConsole = False
    names = [args.model] if args.model else list(MODELS)
    results = {}
    for name in names:
        label, build, parameters, kwargs = MODELS[name]
        runs = [RunOnce(build, parameters(), args.end_time, **kwargs) for _ in range(max(1, args.repeat))]
        results[name] = (min(r[0] for r in runs), min(r[1] for r in runs), runs[0][2])
    print(f"{'model':48s} {'wall s':>8s} {'CPU s':>8s} {'peak Fn N':>10s}")
    for name, (wall, cpu, peak) in results.items():
        print(f"{MODELS[name][0]:48s} {wall:8.4f} {cpu:8.4f} {peak:10.1f}")
    if 'one-angle' in results:
        one = results['one-angle']
        for name in [n for n in results if n != 'one-angle']:
            print(f"{name}/one-angle: wall x{results[name][0] / one[0]:.2f}, CPU x{results[name][1] / one[1]:.2f}")
    if 'small' in results and 'exact' in results:
        print(f"peak normal force, small-displacement against exact: "
              f"{results['small'][2] / results['exact'][2] - 1.:+.2%}")
    return 0


if __name__ == '__main__':
    sys.exit(Main())
