"""Plain Exudyn (no exudyn_worm): a system with a symbolic user function is never freed.

A mass on a spring whose force is a symbolic (C++) user function made by Exudyn's own
``exudyn.advancedUtilities.CreateSymbolicUserFunction``, a sensor that stores its position in memory
(``storeInternal=True``), 10,000 steps; the system is built and solved in a function and then dropped. The
process's resident memory (``VmRSS`` of ``/proc/self/status``, Linux) is read after a warm-up and after
``--runs`` more runs. Variants (``--variant``):

``exudyn``
    as Exudyn's documentation shows it: the memory grows by the whole system per run (its sensor data, four
    numbers per step, time and position: 320 kB per 10,000 steps, plus the items and the solver).
``reset``
    the same, with ``mbs.Reset()`` after the results are read: flat.
``noMainSystem``
    the user function recorded by hand with ``None`` in place of the MainSystem in the recording's argument list
    (``fnDict['argList'][0]``, which the recording never evaluates): flat, without a reset.
``python``
    a plain-Python user function: flat.

Why: the symbolic user function keeps its recording dictionary, whose argument list starts with ``mbs``; the
Python ``mbs`` keeps its ``SystemContainer`` alive, and the container owns the item that holds the user
function. The cycle runs through C++ objects that Python's garbage collector cannot traverse, so
``gc.collect()`` does not free it. Run: ``python benchmarks/exudyn_symbolic_leak.py [--runs 30] [--variant
exudyn]`` (a few seconds); nothing is written.
"""
from __future__ import annotations

import argparse
import gc

__all__ = ['Rss', 'RunOnce', 'Growth', 'main']

VARIANTS = ('exudyn', 'reset', 'noMainSystem', 'python')


def Rss() -> float:
    """Resident memory of this process in MB (Linux)."""
    with open('/proc/self/status') as f:
        for line in f:
            if line.startswith('VmRSS:'):
                return int(line.split()[1]) / 1024.
    raise RuntimeError('Rss: no VmRSS line in /proc/self/status (Linux only)')


def _SpringForce(mbs, t, itemNumber, u, v, k, d, F0):
    return -k * u - d * v


def RunOnce(variant: str = 'exudyn', steps: int = 10000) -> None:
    """Build, solve and drop one system of the given variant (see the module docstring)."""
    import exudyn as exu
    from exudyn.advancedUtilities import CreateSymbolicUserFunction
    from exudyn.itemInterface import (CoordinateSpringDamper, MarkerNodeCoordinate, MassPoint, NodePoint,
                                      NodePointGround, SensorNode)
    esym = exu.symbolic
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddNode(NodePointGround())
    node = mbs.AddNode(NodePoint(referenceCoordinates=[0., 0., 0.], initialCoordinates=[0.01, 0., 0.]))
    mass = mbs.AddObject(MassPoint(nodeNumber=node, mass=1.))
    m0 = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground, coordinate=0))
    m1 = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=node, coordinate=0))
    spring = mbs.AddObject(CoordinateSpringDamper(markerNumbers=[m0, m1], stiffness=100., damping=0.1))
    del mass
    keep = None
    if variant in ('exudyn', 'reset'):
        keep = CreateSymbolicUserFunction(mbs, _SpringForce, 'springForceUserFunction', spring)
    elif variant == 'noMainSystem':
        esym.SetRecording(True)
        args = [None] + [esym.Real(name, 0.) for name in ('t', 'itemNumber', 'u', 'v', 'k', 'd', 'F0')]
        fnDict = {'functionName': 'springForceUserFunction', 'argList': args,
                  'argTypeList': ['MainSystem', 'Real', 'Index', 'Real', 'Real', 'Real', 'Real', 'Real'],
                  'returnValue': _SpringForce(*args), 'returnType': 'Real'}
        keep = esym.UserFunction()
        keep.SetUserFunctionFromDict(mbs, fnDict, 'springForceUserFunction', spring, 'None')
        esym.SetRecording(False)
    else:
        keep = _SpringForce
    mbs.SetObjectParameter(spring, 'springForceUserFunction', keep)
    sensor = mbs.AddSensor(SensorNode(nodeNumber=node, outputVariableType=exu.OutputVariableType.Position,
                                      storeInternal=True, writeToFile=False))
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ss.solution.file.write = False
    ss.timeIntegration.endTime = 1.
    ss.timeIntegration.numberOfSteps = steps
    ss.solution.sensors.writePeriod = 1. / steps * (1. - 1e-9)
    ss.timeIntegration.verboseMode = 0
    printing, exu.config.printToConsole = exu.config.printToConsole, False
    try:
        mbs.SolveDynamic(ss)
    finally:
        exu.config.printToConsole = printing
    mbs.GetSensorStoredData(sensor)          # the results, copied out
    if variant == 'reset':
        mbs.Reset()


def Growth(variant: str = 'exudyn', runs: int = 30, steps: int = 10000) -> float:
    """Growth of the resident memory in kB per run over ``runs`` runs, after 3 warm-up runs."""
    for _ in range(3):
        RunOnce(variant, steps)
    gc.collect()
    before = Rss()
    for _ in range(runs):
        RunOnce(variant, steps)
    gc.collect()
    return (Rss() - before) * 1024. / runs


def main(argv=None) -> None:
    import exudyn as exu
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--runs', type=int, default=30, help='runs measured after the warm-up (default 30)')
    parser.add_argument('--steps', type=int, default=10000, help='solver steps per run (default 10000)')
    parser.add_argument('--variant', choices=VARIANTS + ('all',), default='all', help='default: all')
    args = parser.parse_args(argv)
    print(f"exudyn {exu.__version__}: memory kept per run of {args.steps} steps ({args.runs} runs)")
    for variant in VARIANTS if args.variant == 'all' else (args.variant,):
        print(f"  {variant:13s} {Growth(variant, args.runs, args.steps):8.1f} kB per run")


if __name__ == '__main__':
    main()
