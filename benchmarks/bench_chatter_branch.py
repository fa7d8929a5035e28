"""Chatter branches by shooting + continuation against brute-force long time simulations.

    python benchmarks/bench_chatter_branch.py                 # J1, kT of reel-P1; J1 with 0.5 mm backlash
    python benchmarks/bench_chatter_branch.py --json FILE     # also save every number
    python benchmarks/bench_chatter_branch.py --fifty-only    # only the 50-point timing

First a branch of about 50 orbits (reel-P1, kT in 2000-20000 N m/rad, a shorter continuation step) timed
serially with its breakdown (flow runs and their cost, linear scan, first orbit and restarts) and with the two
directions in two processes, and the same parameter values by brute force: one long time simulation per value
(LongSimulationAmplitude, 4 s, step 2e-4 s), timed, and their ratio (to the serial time).

For each branch: its wall time and number of orbits; then at ``--checks`` points spread along it (orbits that lose
contact, force factor >= 2) a long time simulation (LongSimulationAmplitude: 4 s from the steady state with a 1 %
worm-speed kick, the time simulations' solver settings, step 2e-4 s; where rest and chatter coexist the run
starts on the orbit with the 1 % kick, as a kick from rest need not reach the chatter) and the relative difference of the force
factor, the largest |phi2''| and the frequency; the brute-force time of the same points is the sum of those runs.
Nothing is written unless ``--json`` is given.
"""
import argparse
import json
import os
import sys
import time

import numpy as np

import exudyn_worm as ew
from exudyn_worm.analysis.orbits import chatterbranch, exudynflow
from exudyn_worm.analysis.orbits.longsimulation import LongSimulationAmplitude
from exudyn_worm.analysis.orbits.chatterbranch import AnalyzeChatterBranch
from exudyn_worm.drive.wholedrive import ResolveDrive

#: (parameter, low, high, changes to reel-P1)
BRANCHES = (('J1', 0.05, 0.3, {}), ('kT', 2000., 20000., {}), ('J1', 0.2, 0.3, {'backlash': 5e-4}))


def CheckBranch(name, low, high, changes, checks, duration, stepSize):
    p = {**ew.GetPreset('reel-P1'), **changes}
    t0 = time.perf_counter()
    branch = AnalyzeChatterBranch(ResolveDrive(parameters=p), name, low, high)
    branchSeconds = time.perf_counter() - t0
    chattering = [q for q in branch.points if q.info['forceFactor'] >= 2.]
    chattering.sort(key=lambda q: q.value)
    picks = [chattering[int(round(k))] for k in np.linspace(0, len(chattering) - 1, checks)]
    rows, bruteSeconds = [], 0.
    for q in picks:
        t1 = time.perf_counter()
        # where rest is stable too (coexistence), start the long run on the orbit with the worm speed kicked by 1 %
        coexisting = bool(branch.coexistence) and any(lo <= q.value <= hi for lo, hi in branch.coexistence)
        long = LongSimulationAmplitude(ResolveDrive(parameters={**p, name: q.value}), duration=duration, stepSize=stepSize,
                                       initialState=q.orbit.state if coexisting else None)
        bruteSeconds += time.perf_counter() - t1
        rows.append({'value': float(q.value), 'orbitForceFactor': q.info['forceFactor'],
                     'longForceFactor': long['forceFactor'],
                     'orbitWheelAcceleration': q.info['maxWheelAcceleration'],
                     'longWheelAcceleration': long['maxWheelAcceleration'],
                     'orbitFrequencyHz': q.orbit.frequencyHz, 'longFrequencyHz': long['frequencyHz']})
    return {'parameter': name, 'changes': changes, 'coexistence': branch.coexistence, 'folds': branch.folds,
            'disturbances': branch.disturbances, 'points': len(branch.points), 'branchSeconds': branchSeconds,
            'bruteForceSecondsForChecks': bruteSeconds, 'hopf': branch.hopf, 'checks': rows,
            'messages': branch.messages}


#: the 50-orbit branch: reel-P1 in kT over 2000-20000 N m/rad with the continuation step that gives about 50 orbits
FIFTY = ('kT', 2000., 20000., 0.045)


class _Timers:
    """Wall time and calls of the flow runs, the linear scan and the settling + first shooting, by wrapping them."""

    def __init__(self):
        self.seconds = {'flow': 0., 'linearScan': 0., 'settleAndFirstOrbit': 0.}
        self.calls = {'flow': 0, 'settleAndFirstOrbit': 0}
        self._saved = []

    def _Wrap(self, owner, attribute, key):
        original = getattr(owner, attribute)
        self._saved.append((owner, attribute, original))

        def Timed(*args, **kwargs):
            t0 = time.perf_counter()
            try:
                return original(*args, **kwargs)
            finally:
                self.seconds[key] += time.perf_counter() - t0
                if key in self.calls:
                    self.calls[key] += 1
        setattr(owner, attribute, Timed)

    def __enter__(self):
        self._Wrap(exudynflow.ExudynFlow, 'Solve', 'flow')
        exudynflow.ExudynFlow.__call__ = exudynflow.ExudynFlow.Solve
        self._Wrap(chatterbranch, 'LinearBoundaries', 'linearScan')
        self._Wrap(chatterbranch, 'FindSteadyChatter', 'settleAndFirstOrbit')
        return self

    def __exit__(self, *exc):
        for owner, attribute, original in reversed(self._saved):
            setattr(owner, attribute, original)
        exudynflow.ExudynFlow.__call__ = exudynflow.ExudynFlow.Solve


def FiftyPoints():
    """A branch of about 50 orbits by shooting, and the same parameter values by long time simulations."""
    name, low, high, step = FIFTY
    p = ew.GetPreset('reel-P1')
    load0 = os.getloadavg()[0]
    with _Timers() as timers:
        # serial, so that the timers see every flow run (the settling + first orbit runs are counted in both)
        t0 = time.perf_counter()
        branch = AnalyzeChatterBranch(ResolveDrive(parameters=p), name, low, high, stepLength=step, maxPoints=60, processes=1)
        seconds = time.perf_counter() - t0
    t0 = time.perf_counter()
    parallel = AnalyzeChatterBranch(ResolveDrive(parameters=p), name, low, high, stepLength=step, maxPoints=60, processes=2)
    parallelSeconds = time.perf_counter() - t0
    if [q.value for q in parallel.points] != [q.value for q in branch.points]:
        print('warning: the branch in two processes differs from the serial one', file=sys.stderr)
    values = [float(q.value) for q in branch.points]
    t1 = time.perf_counter()
    for v in values:
        LongSimulationAmplitude(ResolveDrive(parameters={**p, name: v}), duration=4., stepSize=2e-4)
    brute = time.perf_counter() - t1
    trivial = np.array([q.orbit.trivialMultiplierError for q in branch.points if q.info['forceFactor'] >= 2.])
    return {'parameter': name, 'range': [low, high], 'stepLength': step, 'points': len(values),
            'seconds': seconds, 'parallelSeconds': parallelSeconds, 'flowRuns': timers.calls['flow'],
            'flowSeconds': timers.seconds['flow'],
            'linearScanSeconds': timers.seconds['linearScan'],
            'settleAndFirstOrbitSeconds': timers.seconds['settleAndFirstOrbit'],
            'settleAndFirstOrbitCalls': timers.calls['settleAndFirstOrbit'],
            'bruteForceSeconds': brute, 'ratio': brute / seconds, 'messages': branch.messages,
            'trivialMultiplierError': {'median': float(np.median(trivial)), 'max': float(np.max(trivial))},
            'loadAverage': [load0, os.getloadavg()[0]]}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--checks', type=int, default=8)
    parser.add_argument('--duration', type=float, default=4.)
    parser.add_argument('--step', type=float, default=2e-4)
    parser.add_argument('--json', metavar='FILE')
    parser.add_argument('--fifty-only', action='store_true', help='only the 50-point timing')
    args = parser.parse_args(argv)
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores", file=sys.stderr)
    f = FiftyPoints()
    print(f"50-point branch: {f['parameter']} in {f['range']}, step {f['stepLength']}: {f['points']} orbits in "
          f"{f['seconds']:.1f} s serial ({f['seconds'] / f['points']:.2f} s per orbit), "
          f"{f['parallelSeconds']:.1f} s in "
          f"two processes; {f['flowRuns']} flow runs in "
          f"{f['flowSeconds']:.1f} s ({1e3 * f['flowSeconds'] / f['flowRuns']:.1f} ms each, "
          f"{f['flowRuns'] / f['points']:.0f} per orbit), linear scan {f['linearScanSeconds']:.1f} s, settling + "
          f"first orbits {f['settleAndFirstOrbitSeconds']:.1f} s ({f['settleAndFirstOrbitCalls']}x); trivial "
          f"multiplier error median {f['trivialMultiplierError']['median']:.4f}, largest "
          f"{f['trivialMultiplierError']['max']:.4f}")
    print(f"  the same {f['points']} values by brute force (4 s long runs, step 2e-4 s): "
          f"{f['bruteForceSeconds']:.1f} s; "
          f"brute force / shooting = {f['ratio']:.2f}; load average {f['loadAverage'][0]:.1f} -> "
          f"{f['loadAverage'][1]:.1f}")
    print(f"  {f['messages']}")
    results = [{'fifty': f}]
    if args.fifty_only:
        BRANCHES_RUN = ()
    else:
        BRANCHES_RUN = BRANCHES
    for name, low, high, changes in BRANCHES_RUN:
        r = CheckBranch(name, low, high, changes, args.checks, args.duration, args.step)
        results.append(r)
        print(f"\n{name} in [{low:g}, {high:g}] {changes or ''}: {r['points']} orbits in {r['branchSeconds']:.1f} s; "
              f"{len(r['checks'])} long simulations in {r['bruteForceSecondsForChecks']:.1f} s")
        print(f"  folds {r['folds']}, coexistence {r['coexistence']}, disturbances {r['disturbances']}")
        for h in r['hopf']:
            print(f"  Hopf {h['value']:.7g} ({h['type']}), linear boundary {h['linearBoundary']:.7g}, "
                  f"difference {h['relativeDifference']:.1e}")
        print(f"  {'value':>10} {'FF orbit':>9} {'FF long':>9} {'diff':>7} {'a2 orbit':>9} {'a2 long':>9} {'diff':>7} "
              f"{'f orbit':>8} {'f long':>8}")
        for c in r['checks']:
            d1 = c['orbitForceFactor'] / c['longForceFactor'] - 1
            d2 = c['orbitWheelAcceleration'] / c['longWheelAcceleration'] - 1
            print(f"  {c['value']:10.5g} {c['orbitForceFactor']:9.4f} {c['longForceFactor']:9.4f} {d1:7.2%} "
                  f"{c['orbitWheelAcceleration']:9.2f} {c['longWheelAcceleration']:9.2f} {d2:7.2%} "
                  f"{c['orbitFrequencyHz']:8.3f} {c['longFrequencyHz']:8.3f}")
    print(f"load average {os.getloadavg()[0]:.1f} at the end", file=sys.stderr)
    if args.json:
        with open(args.json, 'w') as f:
            json.dump(results, f, indent=1, default=float)
        print(f"wrote {args.json}", file=sys.stderr)


if __name__ == '__main__':
    main()
