"""Where P1's solver time goes: the reel changer's P1 with parts of its work taken out, one variant per process.

Each variant builds ``BuildReelChanger(GetPreset('reel-P1'), motorConstraint=False)`` (the model of
``SimulateReelChanger``: the motor a flywheel), changes it as below, and solves
P1's 8 s at the drive's recommended step with ``SOLVER_SETTINGS`` (only the variant ``default`` is the real model;
the others answer "what would the solve cost if this part cost nothing"):

``default``
    the model as ``SimulateReelChanger`` solves it.
``noPostNewton``
    without the Python post-Newton function of the sticking friction (P1's worm never stops, so its motion is the
    same).
``zeroLaw``
    the mesh's symbolic user function replaced by one that returns zeros (the call path of Exudyn's
    ``ObjectGenericODE2`` user function stays, the law's arithmetic is gone).
``zeroLawNoLoadNoPostNewton``
    the same, also without the load's user function (a spring-damper from ground, ``CreateRotorTorque``) and the
    post-Newton function: the floor of a model whose mesh is one symbolic ``ObjectGenericODE2`` user function that
    does no work.
``noUserFunctions``
    no user function at all: the mesh a constant stiffness matrix ``kV a a^T`` (``a`` the normal
    displacement per worm and wheel angle), no load, no post-Newton function: Exudyn's solver with the nodes (the
    motor a flywheel), the drive shaft and the sensors.

Run under callgrind to count the instructions of the solve alone (the counts repeat exactly, whatever else the
machine does)::

    valgrind --tool=callgrind --callgrind-out-file=/tmp/p1.cg --toggle-collect='CSolverBase::SolveSystem*' \\
        python benchmarks/p1_floor.py zeroLaw

Without valgrind it prints the solve's CPU seconds (best of ``--repeat``) and Exudyn's work counters. Nothing is
written.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.dont_write_bytecode = True                       # leave no __pycache__ beside the benchmark

import numpy as np                                   # noqa: E402
import exudyn as exu                                 # noqa: E402

from exudyn_worm.analysis.simulation.reelchanger import DefaultSimulatedTime, SolverSettings   # noqa: E402
from exudyn_worm.analysis.simulation.stepsize import RecommendedStepSize                        # noqa: E402
from exudyn_worm.builders.oneangle import BuildReelChanger                                # noqa: E402
from exudyn_worm.drive.presets import ElasticDriveFromParameters, GetPreset         # noqa: E402
from exudyn_worm.drive.wholedrive import ResolveDrive

__all__ = ['VARIANTS', 'SolveVariant', 'Main']

VARIANTS = ('default', 'noPostNewton', 'zeroLaw', 'zeroLawNoLoadNoPostNewton', 'noUserFunctions')


def _ZeroLaw(mbs, objectNumber, keep: list) -> None:
    """Replace the mesh's user function by a symbolic one that returns [0, 0] (recorded as the package does)."""
    esym = exu.symbolic
    recording = esym.GetRecording()
    esym.SetRecording(True)
    try:
        args = [None, esym.Real('t', 0.), esym.Real('itemNumber', 0.), esym.Vector('q', [0., 0.]),
                esym.Vector('q_t', [0., 0.])]
        value = esym.Vector([0. * args[3][0], 0. * args[3][1]])
        fnDict = {'functionName': 'forceUserFunction', 'argList': args,
                  'argTypeList': ['MainSystem', 'Real', 'Index', 'StdVector', 'StdVector'],
                  'returnValue': value, 'returnType': 'StdVector'}
        uf = esym.UserFunction()
        uf.SetUserFunctionFromDict(mbs, fnDict, 'forceUserFunction', objectNumber, 'None')
    finally:
        esym.SetRecording(recording)
    keep.append((uf, fnDict))                        # the expression tree must outlive the solve
    mbs.SetObjectParameter(objectNumber, 'forceUserFunction', uf)


def SolveVariant(variant: str):
    """Build P1, apply ``variant`` (one of :data:`VARIANTS`), solve; return (CPU seconds, work counters)."""
    if variant not in VARIANTS:
        raise ValueError(f"p1_floor: variant must be one of {', '.join(VARIANTS)}, got {variant!r}")
    p = GetPreset('reel-P1')
    model = BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=p), motorConstraint=False)
    mbs, keep = model.mbs, []
    mesh = model.connector.objectNumber
    if variant in ('noPostNewton', 'zeroLawNoLoadNoPostNewton', 'noUserFunctions'):
        mbs.SetPostNewtonUserFunction(0)
    if variant in ('zeroLaw', 'zeroLawNoLoadNoPostNewton'):
        _ZeroLaw(mbs, mesh, keep)
    if variant in ('zeroLawNoLoadNoPostNewton', 'noUserFunctions'):
        mbs.SetObjectParameter(mbs.GetObjectNumber('reelLoad'), 'springForceUserFunction', 0)
    if variant == 'noUserFunctions':
        drive = ElasticDriveFromParameters(p)
        g = drive.gear
        a = np.array([g.r2 / g.ratio, -g.r2])          # normal displacement per worm and wheel angle, about
        mbs.SetObjectParameter(mesh, 'forceUserFunction', 0)
        mbs.SetObjectParameter(mesh, 'stiffnessMatrix', g.kV * np.outer(a, a))
    mbs.Assemble()
    ss, solverType = SolverSettings(DefaultSimulatedTime(ResolveDrive(parameters=p)), RecommendedStepSize(ResolveDrive(parameters=p)))
    printing = exu.config.printToConsole
    exu.config.printToConsole = False
    try:
        c0 = time.process_time()
        mbs.SolveDynamic(ss, solverType=solverType)
        seconds = time.process_time() - c0
    finally:
        exu.config.printToConsole = printing
    it = mbs.sys['dynamicSolver'].it
    return seconds, {'newtonIterations': int(it.newtonStepsCount), 'jacobians': int(it.newtonJacobiCount)}


def Main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('variant', choices=VARIANTS)
    parser.add_argument('--repeat', type=int, default=1, help='solves; the best CPU time is printed')
    args = parser.parse_args(argv)
    runs = [SolveVariant(args.variant) for _ in range(max(1, args.repeat))]
    seconds = min(r[0] for r in runs)
    print(f"{args.variant}: {seconds * 1e3:.1f} ms CPU (best of {len(runs)}), {runs[-1][1]}")
    return 0


if __name__ == '__main__':
    sys.exit(Main())
