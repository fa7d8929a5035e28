"""Chatter branches by shooting + continuation against brute-force long time simulations (issue 18, items 4, 6).

    python benchmarks/bench_chatter_branch.py                 # J1, kT of reel-P1; J1 with 0.5 mm backlash
    python benchmarks/bench_chatter_branch.py --json FILE     # also save every number

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
from exudyn_worm.analysis.chatter import LongSimulationAmplitude
from exudyn_worm.analysis.chatterbranch import AnalyzeChatterBranch

#: (parameter, low, high, changes to reel-P1)
BRANCHES = (('J1', 0.05, 0.3, {}), ('kT', 2000., 20000., {}), ('J1', 0.2, 0.3, {'backlash': 5e-4}))


def CheckBranch(name, low, high, changes, checks, duration, stepSize):
    p = {**ew.GetPreset('reel-P1'), **changes}
    t0 = time.perf_counter()
    branch = AnalyzeChatterBranch(p, name, low, high)
    branchSeconds = time.perf_counter() - t0
    chattering = [q for q in branch.points if q.info['forceFactor'] >= 2.]
    chattering.sort(key=lambda q: q.value)
    picks = [chattering[int(round(k))] for k in np.linspace(0, len(chattering) - 1, checks)]
    rows, bruteSeconds = [], 0.
    for q in picks:
        t1 = time.perf_counter()
        # where rest is stable too (coexistence), start the long run on the orbit with the worm speed kicked by 1 %
        coexisting = bool(branch.coexistence) and any(lo <= q.value <= hi for lo, hi in branch.coexistence)
        long = LongSimulationAmplitude({**p, name: q.value}, duration=duration, stepSize=stepSize,
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


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--checks', type=int, default=8)
    parser.add_argument('--duration', type=float, default=4.)
    parser.add_argument('--step', type=float, default=2e-4)
    parser.add_argument('--json', metavar='FILE')
    args = parser.parse_args(argv)
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores", file=sys.stderr)
    results = []
    for name, low, high, changes in BRANCHES:
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
