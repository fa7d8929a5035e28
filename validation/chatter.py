"""Chatter branches of the validation report: steady chatter by shooting + continuation against long simulations.

Run from the repository root::

    python -m validation.chatter                 # writes validation/chatter/chatter.csv and validation/CHATTER.md
    python -m validation.chatter --checks 4      # fewer long simulations per study

It computes, with :mod:`exudyn_worm.analysis.orbits.chatterbranch` (docs/chatter-amplitude.md), for the reel changer P1

* the branch of steady chatter in J1 (0.05-0.3 kg m^2) and in kT (2000-20000 N m/rad), zero backlash: Hopf
  points against the linear boundaries, their type, folds, coexistence;
* the branch in J1 (0.2-0.3 kg m^2) with 0.5 mm backlash, where rest and chatter coexist, and the smallest
  worm-speed kick that ends in chatter in its middle; kick simulations from rest 5 % below and 5 % above that
  kick must end at rest and in chatter;
* the steady chatter over the backlash (0-1 mm) at P1 (single orbits, the backlash range crosses no boundary);
* reel-P3 with a Stribeck friction law over the motor speed: the branch of friction-limited chatter from the
  lower linear boundary (a smooth Hopf point) up to where the worm starts to turn back and stick in every period,
  and beyond it long runs and single orbits that show why no periodic orbit can be confirmed there.

At ``--checks`` orbits spread along each study a long time simulation
(:func:`~exudyn_worm.analysis.orbits.longsimulation.LongSimulationAmplitude`: 4 s, step 2e-4 s, the time simulations' solver settings;
where rest and chatter coexist it starts on the orbit with a 1 % worm-speed kick; for the friction branch
:func:`~exudyn_worm.analysis.orbits.longsimulation.SettledSimulationAmplitude`, from rest until settled, because near a smooth Hopf point
the chatter grows and settles slowly) gives the steady amplitude; the orbit must equal it within 2 % (our requirement).
Every sentence of the report is generated from the numbers.
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
from exudyn_worm.analysis.orbits.chatter import FindSteadyChatter
from exudyn_worm.analysis.orbits.longsimulation import LongSimulationAmplitude, SettledSimulationAmplitude
from exudyn_worm.analysis.orbits.chatterbranch import AnalyzeChatterBranch, LinearBoundaries
from exudyn_worm.analysis.orbits.smoothbranch import SMOOTH_OFFSETS, SMOOTH_SEED, SmoothHopfBranch
from exudyn_worm.analysis.orbits.periodic import ShootingError
from exudyn_worm.analysis.charts.speedchart import RPM, SpeedStabilityChart
from exudyn_worm.drive.wholedrive import ResolveDrive

__all__ = ['TOLERANCE', 'FOLD_DISTANCE', 'RunChatterStudies', 'WriteCsv', 'WriteReport', 'Main']

HERE = Path(__file__).resolve().parent
#: largest relative difference of orbit and long simulation (our requirement)
TOLERANCE = 0.02
_LONG = {'duration': 4., 'stepSize': 2e-4}
#: check points keep this fraction of the branch's range away from every fold. Added after a run (the shootfast
#: branch, 2026-12-02) in which a check point 0.04 % of the range from the fold of the 0.5 mm backlash branch ended on
#: the lower branch with the 1 % kick (force factor 4.20 against the orbit's 4.48), while runs started on that orbit
#: with kicks of 0 and 0.2 % stayed on it (4.449-4.469): docs/chatter-amplitude.md
FOLD_DISTANCE = 0.01
#: (study, parameter, low, high, changes to reel-P1)
_BRANCHES = (('J1', 'J1', 0.05, 0.3, {}), ('kT', 'kT', 2000., 20000., {}),
             ('J1, backlash 0.5 mm', 'J1', 0.2, 0.3, {'backlash': 5e-4}))
_BACKLASH = np.linspace(0., 1e-3, 8)
#: reel-P3 with a Stribeck law (linearly unstable between about 85 and 610 rpm); speeds in rpm
_FRICTION = {'frictionLaw': 'stribeck', 'mu': 0.092, 'muStatic': 0.2, 'stribeckVelocity': 0.9}
#: range in rpm searched for the lower linear boundary (the Hopf point of the friction branch)
_FRICTION_SEARCH = (70., 100.)
#: compared with a long simulation: the orbits at least this far from the boundary (closer ones settle too
#: slowly: the attraction rate goes to zero at a Hopf point; 0.8 % above it a run needs about 200 s)
_FRICTION_COMPARE_FROM = 0.008
#: beyond the branch's end the worm turns back in every period and sticks: single orbits and long runs there
_STICKING_RPM = (90., 95., 100., 140., 200., 300.)
#: settle rule of the long simulations of the friction studies, fixed before any comparison: pieces of 2 s,
#: settled when the force factor and the largest |phi2''| change by less than 0.05 % per second, at most 300 s
_SETTLE = {'piece': 2., 'rate': 5e-4, 'maxDuration': 300., 'stepSize': 2e-4}
_CSV_FIELDS = ('study', 'parameter', 'value', 'stable', 'orbitForceFactor', 'longForceFactor',
               'orbitWheelAcceleration', 'longWheelAcceleration', 'orbitFrequencyHz', 'longFrequencyHz',
               'settled', 'longSeconds', 'peakSpread')


def _Row(study: str, name: str, value: float, orbit, info: Dict, long: Dict) -> Dict:
    return {'study': study, 'parameter': name, 'value': float(value), 'stable': bool(orbit.stable),
            'orbitForceFactor': info['forceFactor'], 'longForceFactor': long['forceFactor'],
            'orbitWheelAcceleration': info['maxWheelAcceleration'],
            'longWheelAcceleration': long['maxWheelAcceleration'],
            'orbitFrequencyHz': orbit.frequencyHz, 'longFrequencyHz': long['frequencyHz']}


def _Branch(study: str, name: str, low: float, high: float, changes: Dict, checks: int) -> Dict:
    p = {**ew.GetPreset('reel-P1'), **changes}
    t0 = time.perf_counter()
    branch = AnalyzeChatterBranch(ResolveDrive(parameters=p), name, low, high)
    seconds = time.perf_counter() - t0
    # only stable orbits are steady states a long simulation can reach (the unstable ones between folds are not),
    # and only those at least FOLD_DISTANCE of the range from a fold: the basin of the stable orbit closes at the fold
    # (there it meets the unstable one), so a kick of fixed size leaves it next to a fold whatever the orbit
    margin = FOLD_DISTANCE * (high - low)
    chattering = sorted((q for q in branch.points if q.info['forceFactor'] >= 2. and q.stable
                         and all(abs(q.value - f) >= margin for f in branch.folds)), key=lambda q: q.value)
    picks = [chattering[int(round(k))] for k in np.linspace(0, len(chattering) - 1, min(checks, len(chattering)))]
    rows = []
    for q in picks:
        coexisting = any(lo <= q.value <= hi for lo, hi in branch.coexistence)
        long = LongSimulationAmplitude(ResolveDrive(parameters={**p, name: q.value}), **_LONG,
                                       initialState=q.orbit.state if coexisting else None)
        rows.append(_Row(study, name, q.value, q.orbit, q.info, long))
    kicks = []
    for d in branch.disturbances:
        for factor in (0.95, 1.05):
            kick = factor * d['wormSpeedFraction']
            long = LongSimulationAmplitude(ResolveDrive(parameters={**p, name: d['value']}), **_LONG, kick=kick)
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
            orbit = FindSteadyChatter(ResolveDrive(parameters=q), settleTime=settleTime, maxIterations=maxIterations)
        except ShootingError as err:
            failed.append((float(v), str(err).split(';')[0]))
            continue
        long = LongSimulationAmplitude(ResolveDrive(parameters=q), duration=duration, stepSize=_LONG['stepSize'])
        rows.append(_Row(study, name, v, orbit, orbit.info, long))
    keep = [rows[int(round(k))] for k in np.linspace(0, len(rows) - 1, min(checks, len(rows)))] if rows else []
    return {'study': study, 'parameter': name, 'seconds': time.perf_counter() - t0, 'rows': keep, 'failed': failed,
            'duration': duration}


def _FrictionBranch(study: str, base: Dict, checks: int) -> Dict:
    """The branch of friction-limited chatter from the lower linear boundary (a smooth Hopf point: the orbit
    stays in contact and its amplitude starts from zero), by the library's
    :func:`~exudyn_worm.analysis.orbits.smoothbranch.SmoothHopfBranch`: started from a settled time simulation at
    SMOOTH_SEED above the boundary, continued from orbit to orbit at SMOOTH_OFFSETS (the library's defaults) towards
    the boundary and away from it until the worm turns back within the orbit."""
    t0 = time.perf_counter()
    boundaries, _ = LinearBoundaries(ResolveDrive(parameters=base), 'motorSpeed', _FRICTION_SEARCH[0] * RPM, _FRICTION_SEARCH[1] * RPM)
    boundary = boundaries[0]
    branch = SmoothHopfBranch(ResolveDrive(parameters=base), 'motorSpeed', boundary, 1, offsets=SMOOTH_OFFSETS, seed=SMOOTH_SEED)
    orbits = {q.info['offset']: q.orbit for q in branch.points}
    failed = [(v / RPM, why) for v, why in branch.failed]
    messages = [f"branch ends at {e['value'] / RPM:.2f} rpm: the worm turns back within the orbit (smallest worm "
                f"speed {e['minWormSpeed']:.3f} rad/s), it sticks in every period from here on"
                for e in branch.ends if e['reason'] == 'reversal']
    offsets = sorted(orbits)
    hopfPoints = [{**branch.hopf, 'value': branch.hopf['value'] / RPM, 'linearBoundary': boundary / RPM}]
    compare = [f for f in offsets if f >= _FRICTION_COMPARE_FROM]
    picks = [compare[int(round(k))] for k in np.linspace(0, len(compare) - 1, min(checks, len(compare)))]
    rows, unsettled = [], []
    for f in sorted(set(picks)):
        v, orbit = boundary * (1. + f), orbits[f]
        long = SettledSimulationAmplitude(ResolveDrive(parameters={**base, 'motorSpeed': v}), **_SETTLE)
        row = _Row(study, 'motorSpeed', v / RPM, orbit, orbit.info, long)
        row.update(settled=long['settled'], longSeconds=long['duration'], peakSpread=long['peakSpread'])
        (rows if long['settled'] else unsettled).append(row)
    sticking = []
    for rpm in _STICKING_RPM:
        q = {**base, 'motorSpeed': rpm * RPM}
        long = SettledSimulationAmplitude(ResolveDrive(parameters=q), **_SETTLE)
        try:
            orbit = FindSteadyChatter(ResolveDrive(parameters=q), settleTime=3., maxIterations=40)
            found = {'forceFactor': orbit.info['forceFactor'], 'multipliers': np.abs(orbit.nontrivialMultipliers)}
        except ShootingError as err:
            found = {'error': str(err).split(';')[0]}
        sticking.append({'rpm': rpm, 'long': long, 'orbit': found})
    return {'study': study, 'parameter': 'motorSpeed', 'unit': 'rpm', 'seconds': time.perf_counter() - t0,
            'points': len(orbits), 'branchRange': (boundary * (1. + offsets[0]) / RPM,
                                                   boundary * (1. + offsets[-1]) / RPM),
            'linearBoundaries': [b / RPM for b in boundaries], 'hopf': hopfPoints, 'failed': failed,
            'messages': messages, 'unsettled': unsettled, 'sticking': sticking, 'rows': rows,
            'minimumRows': checks}


def RunChatterStudies(checks: int = 8, only: Optional[str] = None) -> List[Dict]:
    """Run every study of the module docstring.

    Parameters
    ----------
    checks : int
        Orbits per study compared with a long time simulation.
    only : str, optional
        Run only the studies whose title contains this text (e.g. ``'friction'``).

    Returns
    -------
    list of dict
        One per study: ``rows`` (orbit against long simulation) and, for the branches, Hopf points, folds,
        coexistence, disturbances and the kick simulations around the threshold.
    """
    Wanted = lambda title: only is None or only.lower() in title.lower()
    studies = [_Branch(s, n, lo, hi, ch, checks) for s, n, lo, hi, ch in _BRANCHES if Wanted(s)]
    if Wanted('backlash at P1'):
        studies.append(_Sweep('backlash at P1', 'backlash', ew.GetPreset('reel-P1'), _BACKLASH, checks))
    if Wanted('reel-P3, Stribeck friction'):
        friction = {**ew.GetPreset('reel-P3'), **_FRICTION}
        study = _FrictionBranch('reel-P3, Stribeck friction', friction, checks)
        chart = SpeedStabilityChart(ResolveDrive(parameters=friction), np.linspace(60., 700., 321) * RPM).Curve(-1)     # lowering
        study['unstableRanges'] = [(a / RPM, b / RPM) for a, b in chart.unstableRanges]
        studies.append(study)
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


def _Shown(path: Path) -> str:
    """``path`` relative to the repository if it lies in it, else as given."""
    path = Path(path)
    return str(path.relative_to(HERE.parent)) if path.is_relative_to(HERE.parent) else str(path)


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
    lines = ['# Chatter branches against long simulations', '',
             'Generated by `python -m validation.chatter` (docs/chatter-amplitude.md for the method). Each orbit '
             'found by shooting is compared with a long time simulation (4 s, step 2e-4 s, the time simulations\' '
             'solver settings; last 0.25 s; for the friction branch run until settled, see there); it must agree '
             f'within {TOLERANCE:.0%} (force factor = largest normal '
             'force over the static normal force, largest |phi2\'\'|, frequency).'
             + (f' Every compared point: `{_Shown(csvPath)}`.' if csvPath is not None else ''), '']
    verdicts = []
    for s in studies:
        worst = _Worst(s['rows'])
        ok = all(v <= TOLERANCE for v in worst.values()) and bool(s['rows'])
        verdicts.append(ok)
        lines += [f"## {s['study']} ({s['parameter']})", '']
        if 'sticking' in s:
            verdicts[-1] = ok = ok and len(s['rows']) >= s['minimumRows'] and all(
                h['relativeDifference'] <= 0.005 for h in s['hopf'])
            lines += _FrictionLines(s)
        elif 'hopf' in s:
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
            if s['folds']:
                lines.append(f"- Compared orbits keep {FOLD_DISTANCE:.0%} of the range from every fold (the stable "
                             f"orbit's basin closes at a fold, so a fixed kick leaves it there; rule added after a run "
                             f"in which a point 0.04 % of the range from the fold ended on the lower branch).")
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
        unit = f" [{s['unit']}]" if 'unit' in s else ''
        settled = 'settled' in (s['rows'][0] if s['rows'] else {})
        lines += ['', f"| {s['parameter']}{unit} | stable | force factor orbit / long | |phi2''| orbit / long "
                      f"[rad/s^2] | frequency orbit / long [Hz] |" + (' long run [s] |' if settled else ''),
                  '| --- | --- | --- | --- | --- |' + (' --- |' if settled else '')]
        for r in s['rows']:
            lines.append(f"| {r['value']:.5g} | {'yes' if r['stable'] else 'no'} | {r['orbitForceFactor']:.4f} / "
                         f"{r['longForceFactor']:.4f} | {r['orbitWheelAcceleration']:.2f} / "
                         f"{r['longWheelAcceleration']:.2f} | {r['orbitFrequencyHz']:.3f} / {r['longFrequencyHz']:.3f} |"
                         + (f" {r['longSeconds']:.0f} |" if settled else ''))
        lines += ['', f"Largest difference: force factor {worst['ForceFactor']:.2%}, |phi2''| "
                      f"{worst['WheelAcceleration']:.2%}, frequency {worst['FrequencyHz']:.2%}: "
                      f"{'PASS' if ok else 'FAIL'} (tolerance {TOLERANCE:.0%}"
                      + (f", at least {s['minimumRows']} settled points" if 'minimumRows' in s else '') + ').', '']
    lines.insert(4, f"**{sum(verdicts)} of {len(verdicts)} studies PASS.**")
    lines.insert(5, '')
    path.write_text('\n'.join(lines) + '\n')
    return path


def _FrictionLines(s: Dict) -> List[str]:
    """The report's lines on the friction branch (before its table)."""
    lo, hi = s['branchRange']
    lines = [f"Branch from the lower linear boundary: {s['points']} orbits on {lo:.2f}-{hi:.2f} rpm ({s['seconds']:.0f} s "
             f"with the long simulations); linear boundaries in {_FRICTION_SEARCH[0]:g}-{_FRICTION_SEARCH[1]:g} rpm: "
             f"{', '.join(f'{b:.6g}' for b in s['linearBoundaries'])} rpm."]
    if 'unstableRanges' in s:
        lines.append('- Linearly unstable (friction slope at the operating point, `speedchart`): '
                     + ', '.join(f'{a:.0f}-{b:.0f} rpm' for a, b in s['unstableRanges']) + '.')
    for h in s['hopf']:
        lines.append(f"- Hopf point {h['value']:.6g} rpm ({h['type']}; where the squared largest |phi2''| of the two "
                     f"orbits nearest the boundary extrapolates to zero) at the linear boundary "
                     f"{h['linearBoundary']:.6g} rpm: relative difference {h['relativeDifference']:.1e} "
                     f"({'within' if h['relativeDifference'] <= 0.005 else 'NOT within'} 0.5 %).")
    lines += [f"- {m}." for m in s['messages']]
    lines += [f"- no orbit at {v:.4g} rpm: {why}" for v, why in s['failed']]
    lines.append(f"- Long simulations from rest (1 % kick), run until settled: pieces of {_SETTLE['piece']:g} s, "
                 f"settled when the force factor and the largest |phi2''| change by less than {_SETTLE['rate']:.2%} per "
                 f"second, at most {_SETTLE['maxDuration']:g} s; orbits closer than {_FRICTION_COMPARE_FROM:.1%} to the "
                 f"boundary are not compared (they settle too slowly).")
    for r in s['unsettled']:
        lines.append(f"- not settled after {r['longSeconds']:g} s at {r['value']:.5g} rpm (not compared): force "
                     f"factor {r['orbitForceFactor']:.4f} / {r['longForceFactor']:.4f}")
    lines += ['', 'Beyond the branch the worm turns back and sticks in every period. Long simulations there '
                  '(settled as above) and single orbits by shooting (3 s settling):', '',
              '| motorSpeed [rpm] | long: force factor | long: per-period peaks vary by | long: settled '
              '| orbit: force factor | orbit: largest non-trivial multiplier |', '| --- | --- | --- | --- | --- | --- |']
    for k in s['sticking']:
        long, orbit = k['long'], k['orbit']
        found = (f"{orbit['forceFactor']:.4f} | {np.max(orbit['multipliers']):.4f}" if 'error' not in orbit
                 else f"none: {orbit['error']} | -")
        lines.append(f"| {k['rpm']:g} | {long['forceFactor']:.4f} | {long['peakSpread']:.1%} | "
                     f"{'yes' if long['settled'] else 'no'} ({long['duration']:g} s) | {found} |")
    lines.append('')
    lines.append('Per-period peaks that vary by more than the 2 % tolerance mean the steady motion is not periodic '
                 'with the chatter period: no single periodic orbit can equal it (docs/chatter-amplitude.md).')
    return lines


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
    parser.add_argument('--only', default=None, help="run only the studies whose title contains this text "
                                                     "(e.g. 'friction'); the report then holds only those")
    parser.add_argument('--report', default=str(HERE / 'CHATTER.md'), help='report path')
    parser.add_argument('--csv', default=str(HERE / 'chatter' / 'chatter.csv'), help='CSV path')
    args = parser.parse_args(argv)
    titles = [b[0] for b in _BRANCHES] + ['backlash at P1', 'reel-P3, Stribeck friction']
    if args.only is not None and not any(args.only.lower() in t.lower() for t in titles):
        parser.error(f"--only {args.only!r} matches no study; the studies are: {', '.join(titles)}")
    studies = RunChatterStudies(args.checks, args.only)
    csvPath = WriteCsv(studies, Path(args.csv).resolve())
    print(f"wrote {WriteReport(studies, Path(args.report).resolve(), csvPath)}")
    return 0


if __name__ == '__main__':
    raise SystemExit(Main())
