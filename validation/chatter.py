"""Chatter branches of the validation report: steady chatter by shooting + continuation against long simulations.

Run from the repository root::

    python -m validation.chatter                 # writes validation/chatter/chatter.csv and validation/CHATTER.md
    python -m validation.chatter --checks 4      # fewer long simulations per study

It computes, with :mod:`exudyn_worm.analysis.chatterbranch` (docs/chatter-amplitude.md), for the reel changer P1

* the branch of steady chatter in J1 (0.05-0.3 kg m^2) and in kT (2000-20000 N m/rad), zero backlash: Hopf
  points against the linear boundaries, their type, folds, coexistence;
* the branch in J1 (0.2-0.3 kg m^2) with 0.5 mm backlash, where rest and chatter coexist, and the smallest
  worm-speed kick that ends in chatter in its middle; kick simulations from rest 5 % below and 5 % above that
  kick must end at rest and in chatter;
* the steady chatter over the backlash (0-1 mm) at P1 (single orbits, the backlash range crosses no boundary);
* reel-P3 with a Stribeck friction law over the motor speed (single orbits, see the report for why no branch).

At ``--checks`` orbits spread along each study a long time simulation
(:func:`~exudyn_worm.analysis.chatter.LongSimulationAmplitude`: 4 s, step 2e-4 s, the time simulations' solver settings;
where rest and chatter coexist it starts on the orbit with a 1 % worm-speed kick) gives the steady amplitude; the
orbit must equal it within 2 % (issue 18). Every sentence of the report is generated from the numbers.
"""
from __future__ import annotations

import argparse
import csv
import math
import time
from pathlib import Path
from typing import Dict, List, Optional

import numpy as np

import exudyn_worm as ew
from exudyn_worm.analysis.chatter import FindSteadyChatter, LongSimulationAmplitude
from exudyn_worm.analysis.chatterbranch import AnalyzeChatterBranch
from exudyn_worm.analysis.orbits import ShootingError
from exudyn_worm.analysis.speedchart import RPM, SpeedStabilityChart

__all__ = ['TOLERANCE', 'RunChatterStudies', 'WriteCsv', 'WriteReport', 'Main']

HERE = Path(__file__).resolve().parent
#: largest relative difference of orbit and long simulation (issue 18, item 4)
TOLERANCE = 0.02
_LONG = {'duration': 4., 'stepSize': 2e-4}
#: (study, parameter, low, high, changes to reel-P1)
_BRANCHES = (('J1', 'J1', 0.05, 0.3, {}), ('kT', 'kT', 2000., 20000., {}),
             ('J1, backlash 0.5 mm', 'J1', 0.2, 0.3, {'backlash': 5e-4}))
_BACKLASH = np.linspace(0., 1e-3, 8)
#: reel-P3 with a Stribeck law (linearly unstable between about 85 and 610 rpm); speeds in rpm
_FRICTION = {'frictionLaw': 'stribeck', 'mu': 0.092, 'muStatic': 0.2, 'stribeckVelocity': 0.9}
_FRICTION_RPM = (92., 140., 200., 300., 450.)
#: the friction-limited orbits grow slowly: their long simulations run longer (at 140 rpm the force factor is
#: 1.905 after 4 s, 1.909 after 6 s, 1.913 after 10 s)
_FRICTION_SECONDS = 8.
_CSV_FIELDS = ('study', 'parameter', 'value', 'stable', 'orbitForceFactor', 'longForceFactor',
               'orbitWheelAcceleration', 'longWheelAcceleration', 'orbitFrequencyHz', 'longFrequencyHz')


def _Row(study: str, name: str, value: float, orbit, info: Dict, long: Dict) -> Dict:
    return {'study': study, 'parameter': name, 'value': float(value), 'stable': bool(orbit.stable),
            'orbitForceFactor': info['forceFactor'], 'longForceFactor': long['forceFactor'],
            'orbitWheelAcceleration': info['maxWheelAcceleration'],
            'longWheelAcceleration': long['maxWheelAcceleration'],
            'orbitFrequencyHz': orbit.frequencyHz, 'longFrequencyHz': long['frequencyHz']}


def _Branch(study: str, name: str, low: float, high: float, changes: Dict, checks: int) -> Dict:
    p = {**ew.GetPreset('reel-P1'), **changes}
    t0 = time.perf_counter()
    branch = AnalyzeChatterBranch(p, name, low, high)
    seconds = time.perf_counter() - t0
    # only stable orbits are steady states a long simulation can reach (the unstable ones between folds are not)
    chattering = sorted((q for q in branch.points if q.info['forceFactor'] >= 2. and q.stable), key=lambda q: q.value)
    picks = [chattering[int(round(k))] for k in np.linspace(0, len(chattering) - 1, min(checks, len(chattering)))]
    rows = []
    for q in picks:
        coexisting = any(lo <= q.value <= hi for lo, hi in branch.coexistence)
        long = LongSimulationAmplitude({**p, name: q.value}, **_LONG,
                                       initialState=q.orbit.state if coexisting else None)
        rows.append(_Row(study, name, q.value, q.orbit, q.info, long))
    kicks = []
    for d in branch.disturbances:
        for factor in (0.95, 1.05):
            kick = factor * d['wormSpeedFraction']
            long = LongSimulationAmplitude({**p, name: d['value']}, **_LONG, kick=kick)
            kicks.append({'value': d['value'], 'kick': kick, 'threshold': d['wormSpeedFraction'],
                          'forceFactor': long['forceFactor']})
    return {'study': study, 'parameter': name, 'range': (low, high), 'points': len(branch.points),
            'seconds': seconds, 'unstableOrbits': sum(not q.stable for q in branch.points),
            'linearBoundaries': branch.linearBoundaries, 'hopf': branch.hopf,
            'folds': branch.folds, 'coexistence': branch.coexistence, 'disturbances': branch.disturbances,
            'kicks': kicks, 'rows': rows}


def _Sweep(study: str, name: str, base: Dict, values, checks: int, settleTime: float = 1.0,
           maxIterations: int = 30, duration: float = _LONG['duration']) -> Dict:
    rows, failed = [], []
    t0 = time.perf_counter()
    for v in values:
        q = {**base, name: float(v)}
        try:
            orbit = FindSteadyChatter(q, settleTime=settleTime, maxIterations=maxIterations)
        except ShootingError as err:
            failed.append((float(v), str(err).split(';')[0]))
            continue
        long = LongSimulationAmplitude(q, duration=duration, stepSize=_LONG['stepSize'])
        rows.append(_Row(study, name, v, orbit, orbit.info, long))
    keep = [rows[int(round(k))] for k in np.linspace(0, len(rows) - 1, min(checks, len(rows)))] if rows else []
    return {'study': study, 'parameter': name, 'seconds': time.perf_counter() - t0, 'rows': keep, 'failed': failed,
            'duration': duration}


def RunChatterStudies(checks: int = 8) -> List[Dict]:
    """Run every study of the module docstring.

    Parameters
    ----------
    checks : int
        Orbits per study compared with a long time simulation.

    Returns
    -------
    list of dict
        One per study: ``rows`` (orbit against long simulation) and, for the branches, Hopf points, folds,
        coexistence, disturbances and the kick simulations around the threshold.
    """
    studies = [_Branch(s, n, lo, hi, ch, checks) for s, n, lo, hi, ch in _BRANCHES]
    studies.append(_Sweep('backlash at P1', 'backlash', ew.GetPreset('reel-P1'), _BACKLASH, checks))
    friction = {**ew.GetPreset('reel-P3'), **_FRICTION}
    sweep = _Sweep('reel-P3, Stribeck friction', 'motorSpeed', friction, np.array(_FRICTION_RPM) * RPM, checks,
                   settleTime=3.0, maxIterations=60, duration=_FRICTION_SECONDS)
    chart = SpeedStabilityChart(friction, np.linspace(60., 700., 321) * RPM)
    sweep['unstableRanges'] = [(a / RPM, b / RPM) for a, b in chart.unstableRanges]
    studies.append(sweep)
    return studies


def _Difference(a: float, b: float) -> float:
    return abs(a / b - 1.) if b else math.inf


def _Worst(rows: List[Dict]) -> Dict[str, float]:
    return {k: max((_Difference(r[f'orbit{k}'], r[f'long{k}']) for r in rows), default=math.nan)
            for k in ('ForceFactor', 'WheelAcceleration', 'FrequencyHz')}


def WriteCsv(studies: List[Dict], path: Path) -> Path:
    """Write every orbit-against-long-simulation row to ``path``.

    Parameters
    ----------
    studies : list of dict
        From :func:`RunChatterStudies`.
    path : Path
        CSV file.

    Returns
    -------
    Path
    """
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, 'w', newline='') as f:
        w = csv.DictWriter(f, fieldnames=_CSV_FIELDS)
        w.writeheader()
        for s in studies:
            for r in s['rows']:
                w.writerow({k: (f'{v:.6g}' if isinstance(v, float) else v) for k, v in r.items()})
    return path


def WriteReport(studies: List[Dict], path: Path = HERE / 'CHATTER.md', csvPath: Optional[Path] = None) -> Path:
    """Write the chatter-branch report (markdown) from the studies' numbers.

    Parameters
    ----------
    studies : list of dict
        From :func:`RunChatterStudies`.
    path : Path
        The report.
    csvPath : Path, optional
        The CSV beside it (named in the report).

    Returns
    -------
    Path
    """
    lines = ['# Chatter branches against long simulations (issue 18)', '',
             'Generated by `python -m validation.chatter` (docs/chatter-amplitude.md for the method). Each orbit '
             'found by shooting is compared with a long time simulation (4 s, step 2e-4 s, the time simulations\' '
             f'solver settings; last 0.25 s); it must agree within {TOLERANCE:.0%} (force factor = largest normal '
             'force over the static normal force, largest |phi2\'\'|, frequency).'
             + (f' Every compared point: `{csvPath.relative_to(HERE.parent)}`.' if csvPath is not None else ''), '']
    verdicts = []
    for s in studies:
        worst = _Worst(s['rows'])
        ok = all(v <= TOLERANCE for v in worst.values()) and bool(s['rows'])
        verdicts.append(ok)
        lines += [f"## {s['study']} ({s['parameter']})", '']
        if 'hopf' in s:
            lo, hi = s['range']
            lines.append(f"Range {lo:g}-{hi:g}: {s['points']} orbits in {s['seconds']:.0f} s; linear boundaries "
                         f"{', '.join(f'{b:.7g}' for b in s['linearBoundaries']) or 'none'}.")
            for h in s['hopf']:
                lines.append(f"- Hopf point {h['value']:.7g} ({h['type']}) at the linear boundary "
                             f"{h['linearBoundary']:.7g}: relative difference {h['relativeDifference']:.1e} "
                             f"({'within' if h['relativeDifference'] <= 0.005 else 'NOT within'} 0.5 %).")
            lines.append(f"- Unstable orbits on the branch (not compared: a long simulation cannot stay on them): "
                         f"{s['unstableOrbits']}.")
            lines.append(f"- Folds: {', '.join(f'{x:.5g}' for x in s['folds']) or 'none'}; rest and chatter "
                         f"coexist on: {', '.join(f'{a:.4g}-{b:.4g}' for a, b in s['coexistence']) or 'nowhere'}.")
            for d in s['disturbances']:
                lines.append(f"- At {s['parameter']} = {d['value']:.4g} the smallest worm-speed kick that ends in "
                             f"chatter is {d['wormSpeedFraction']:.1%} of the motor speed ({d['wormSpeed']:.3g} rad/s).")
            for k in s['kicks']:
                end = 'chatter' if k['forceFactor'] >= 2. else 'rest' if k['forceFactor'] < 1.01 else 'undecided'
                expected = 'chatter' if k['kick'] > k['threshold'] else 'rest'
                lines.append(f"  - kick {k['kick']:.1%} from rest: ends in {end} (force factor "
                             f"{k['forceFactor']:.3f}); expected {expected}: {'PASS' if end == expected else 'FAIL'}")
                verdicts[-1] = verdicts[-1] and end == expected
        else:
            lines.append(f"{len(s['rows'])} orbits compared ({s['seconds']:.0f} s with the long simulations, "
                         f"{s['duration']:g} s each).")
            for v, why in s.get('failed', []):
                lines.append(f"- no orbit at {s['parameter']} = {v:.4g}: {why}")
            if 'unstableRanges' in s:
                lines.append('- Linearly unstable (friction slope at the operating point, `speedchart`): '
                             + ', '.join(f'{a:.0f}-{b:.0f} rpm' for a, b in s['unstableRanges']) + '.')
        lines += ['', f"| {s['parameter']} | stable | force factor orbit / long | |phi2''| orbit / long [rad/s^2] "
                      f"| frequency orbit / long [Hz] |", '| --- | --- | --- | --- | --- |']
        for r in s['rows']:
            lines.append(f"| {r['value']:.5g} | {'yes' if r['stable'] else 'no'} | {r['orbitForceFactor']:.4f} / "
                         f"{r['longForceFactor']:.4f} | {r['orbitWheelAcceleration']:.2f} / "
                         f"{r['longWheelAcceleration']:.2f} | {r['orbitFrequencyHz']:.3f} / {r['longFrequencyHz']:.3f} |")
        lines += ['', f"Largest difference: force factor {worst['ForceFactor']:.2%}, |phi2''| "
                      f"{worst['WheelAcceleration']:.2%}, frequency {worst['FrequencyHz']:.2%}: "
                      f"{'PASS' if ok else 'FAIL'} (tolerance {TOLERANCE:.0%}).", '']
    lines.insert(4, f"**{sum(verdicts)} of {len(verdicts)} studies PASS.**")
    lines.insert(5, '')
    path.write_text('\n'.join(lines) + '\n')
    return path


def Main(argv: Optional[List[str]] = None) -> int:
    """Command line: run the studies, write the CSV and ``validation/CHATTER.md``.

    Parameters
    ----------
    argv : list of str, optional
        Arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status.
    """
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--checks', type=int, default=8, help='orbits per study compared with a long simulation')
    parser.add_argument('--report', default=str(HERE / 'CHATTER.md'), help='report path')
    parser.add_argument('--csv', default=str(HERE / 'chatter' / 'chatter.csv'), help='CSV path')
    args = parser.parse_args(argv)
    studies = RunChatterStudies(args.checks)
    csvPath = WriteCsv(studies, Path(args.csv).resolve())
    print(f"wrote {WriteReport(studies, Path(args.report).resolve(), csvPath)}")
    return 0


if __name__ == '__main__':
    raise SystemExit(Main())
