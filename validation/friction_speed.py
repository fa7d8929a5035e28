"""Confirmed by simulation: stability over motor speed with a Stribeck law, reel-P2 and reel-P3.

Run from the repository root::

    python -m validation.friction_speed          # writes validation/studies/friction_speed.csv and FRICTION_SPEED.md

For each preset and each of 21 motor speeds (20 ... 2000 rpm, log-spaced) it compares

* the analytical verdict: the lowering state S = -1 of eq. (16) extended at the operating point of steady lowering
  (worm speed = motor speed, normal force from loadMass * g * leverArm, mu(v0) and dmu/dv(v0);
  :func:`exudyn_worm.analysis.charts.speedchart.SpeedStabilityChart`, the same verdict as the ``analyticStableLowering`` column of
  ``exudyn-worm sweep``), with
* the simulation's verdict: the chatter rule of ``exudyn-worm simulate`` in the lowering phase (T/4 ... 3T/4 of the
  wheel's rotation period T) of the reel-changer model with the friction law evaluated in the connector, run by
  :func:`exudyn_worm.analysis.studies.studypoint.RunPoint` (the one-run function of ``exudyn-worm sweep``) with the end time cut to the end
  of the lowering phase (3T/4), so that no lifting phase after it is simulated.

Law and rule, fixed before the agreement was looked at (only the analytical curves were used to choose them):
both laws pass through the preset's constant mu = 0.132 at the paper's 472.5 rpm (v0 = 0.897 m/s), so the kinetic
``mu`` follows from ``muStatic`` and ``stribeckVelocity``. reel-P3: muStatic = 0.2, stribeckVelocity = 0.9 m/s (the
law of docs/friction.md's reel-P3 check; analytical boundaries at about 85 and 609 rpm). reel-P2 (J1 nine times
larger) is stable at every speed with that law; of the grid muStatic in {0.2, 0.3, 0.4} x stribeckVelocity in
{0.5, 0.9, 1.2} m/s, the law with the largest growth rate, muStatic = 0.4, stribeckVelocity = 0.5 m/s (boundaries at
about 45 and 386 rpm, largest real part 3.7 1/s), so that an unstable lowering can grow visibly within the phase.
A point agrees when the simulated lowering chatters exactly where the analytical state is unstable. The
distance of a point to the boundary is |log10(n / n_b)| in decades to the nearest analytical boundary n_b (found
on a 400-point log grid).
"""
from __future__ import annotations

import argparse
import csv
import math
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Sequence

import numpy as np

from exudyn_worm.drive.presets import ApplyOverrides, GetPreset
from exudyn_worm.analysis.simulation.reelchanger import RotationPeriod
from exudyn_worm.analysis.charts.speedchart import RPM, SpeedStabilityChart
from exudyn_worm.analysis.studies.studygrid import ParseVariation, Study
from exudyn_worm.analysis.studies.studypoint import RunPoint
from exudyn_worm.drive.wholedrive import ResolveDrive

__all__ = ['PRESETS', 'LAWS', 'SPEEDS', 'LawParameters', 'AnalyticalBoundaries', 'RunSpeedStudy', 'Summary',
           'WriteReport', 'Main']

HERE = Path(__file__).resolve().parent
PRESETS = ('reel-P2', 'reel-P3')
#: (muStatic, stribeckVelocity in m/s) per preset; the kinetic mu passes the law through 0.132 at 472.5 rpm
LAWS = {'reel-P2': (0.4, 0.5), 'reel-P3': (0.2, 0.9)}
#: the motor speeds, as ``exudyn-worm sweep --vary`` takes them
SPEEDS = 'motorSpeed=20rpm:2000rpm:21:log'
_PAPER_SPEED = 472.5 * RPM
_CSV = HERE / 'studies' / 'friction_speed.csv'
_REPORT = HERE / 'FRICTION_SPEED.md'
_COLUMNS = ('preset', 'motorSpeedRpm', 'analyticMaxRealPart', 'analyticUnstable', 'sweepAnalyticStableLowering',
            'simulatedChatter', 'maxAbsWheelAcceleration', 'vibrationSeconds', 'distanceDecades', 'agree', 'status',
            'seconds')


def LawParameters(preset: str) -> Dict[str, object]:
    """The preset with its Stribeck law (:data:`LAWS`), kinetic mu such that mu(v0 at 472.5 rpm) = 0.132.

    Parameters
    ----------
    preset : str
        ``'reel-P2'`` or ``'reel-P3'``.

    Returns
    -------
    dict
    """
    base = GetPreset(preset)
    muStatic, vs = LAWS[preset]
    from exudyn_worm.drive.presets import ElasticDriveFromParameters
    v0 = ElasticDriveFromParameters(base).gear.SlidingSpeed(_PAPER_SPEED)
    x = math.exp(-(v0 / vs) ** 2)
    mu = (base['mu'] - muStatic * x) / (1. - x)
    return ApplyOverrides(base, {'mu': mu, 'frictionLaw': 'stribeck', 'muStatic': muStatic, 'stribeckVelocity': vs})


def AnalyticalBoundaries(parameters: Mapping[str, Any], low: float = 10 * RPM, high: float = 4000 * RPM) -> List[float]:
    """Motor speeds in rad/s where the lowering state changes stability (400-point log grid, interpolated).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set with a friction law.
    low, high : float
        Speed range in rad/s.

    Returns
    -------
    list of float
    """
    return SpeedStabilityChart(ResolveDrive(parameters=parameters), np.geomspace(low, high, 400)).Curve(-1).Boundaries()


def RunSpeedStudy(preset: str) -> List[Dict]:
    """Analytical and simulated verdict at every speed of :data:`SPEEDS` for ``preset`` (rows of the CSV).

    Parameters
    ----------
    preset : str
        ``'reel-P2'`` or ``'reel-P3'``.

    Returns
    -------
    list of dict
    """
    parameters = LawParameters(preset)
    study = Study(parameters, [ParseVariation(SPEEDS)], source=f'{preset} with a Stribeck law')
    speeds = [p['motorSpeed'] for p in study.points]
    chart = SpeedStabilityChart(ResolveDrive(parameters=parameters), speeds).Curve(-1)           # lowering, as the simulated phase
    boundaries = AnalyticalBoundaries(parameters)
    rows = []
    for run, speed in enumerate(speeds):
        task = study.Task(run)
        task.endTime = 0.75 * RotationPeriod(task.base.Replace(**task.varied))     # to the end of the lowering phase
        row = RunPoint(task)
        analyticUnstable = bool(chart.maxRealPart[run] > 0)
        chatter = row['loweringChatter']
        distance = min((abs(math.log10(speed / b)) for b in boundaries), default=math.inf)
        rows.append({'preset': preset, 'motorSpeedRpm': speed / RPM, 'analyticMaxRealPart': float(chart.maxRealPart[run]),
                     'analyticUnstable': analyticUnstable,
                     'sweepAnalyticStableLowering': row['analyticStableLowering'], 'simulatedChatter': chatter,
                     'maxAbsWheelAcceleration': row.get('w1.maxAbsWheelAcceleration'),
                     'vibrationSeconds': row.get('w1.vibrationSeconds'), 'distanceDecades': distance,
                     'agree': None if chatter is None else chatter == analyticUnstable, 'status': row['status'],
                     'seconds': row['seconds']})
        print(f"{preset} {speed / RPM:8.1f} rpm: analytical {'unstable' if analyticUnstable else 'stable  '} "
              f"(max Re {chart.maxRealPart[run]:+.3f} 1/s), simulated {'chatter' if chatter else 'no chatter'} "
              f"[{row['status']}] {row['seconds']:.1f} s", flush=True)
    return rows


def Summary(rows: List[Dict]) -> Dict:
    """Agreement over the finished rows: count, share, the disagreements.

    Parameters
    ----------
    rows : list of dict
        Rows of :func:`RunSpeedStudy`.

    Returns
    -------
    dict
    """
    done = [r for r in rows if r['agree'] is not None]
    agree = [r for r in done if r['agree']]
    return {'points': len(rows), 'finished': len(done), 'agree': len(agree),
            'share': len(agree) / len(done) if done else float('nan'),
            'disagreements': [r for r in done if not r['agree']], 'failed': [r for r in rows if r['agree'] is None]}


def _Fmt(x, digits=4):
    return 'n/a' if x is None else f'{x:.{digits}g}'


def WriteReport(rows: List[Dict], path: Path = _REPORT) -> str:
    """The markdown report (every sentence from the numbers); returns its text.

    Parameters
    ----------
    rows : list of dict
        Rows of :func:`RunSpeedStudy`.
    path : Path
        Where to write it.

    Returns
    -------
    str
    """
    lines = ['# Stability over motor speed with a Stribeck law, confirmed by simulation', '',
             '<!-- generated by python -m validation.friction_speed; do not edit -->', '',
             'The rule and the laws are in the docstring of `validation/friction_speed.py` (fixed '
             'before the agreement was looked at): analytical verdict = lowering state S = -1 of eq. (16) extended at '
             'the operating point; simulated verdict = the chatter rule of `exudyn-worm simulate` in the lowering '
             'phase (T/4 to 3T/4) of the reel-changer model, one run per speed with `exudyn_worm.analysis.studies.studypoint.RunPoint`, '
             'ending at 3T/4.', '']
    for preset in PRESETS:
        sub = [r for r in rows if r['preset'] == preset]
        if not sub:
            continue
        s = Summary(sub)
        muStatic, vs = LAWS[preset]
        p = LawParameters(preset)
        bounds = ', '.join(f'{b / RPM:.0f}' for b in AnalyticalBoundaries(p))
        lines += [f'## {preset}: mu = {p["mu"]:.4f}, muStatic = {muStatic}, stribeckVelocity = {vs} m/s', '',
                  f'Analytical boundaries at {bounds} rpm. Agreement: **{s["agree"]} of {s["finished"]} points '
                  f'({100 * s["share"]:.0f} %)**' + (f'; {len(s["failed"])} runs failed' if s['failed'] else '') + '.',
                  '', '| motor speed [rpm] | analytical max Re [1/s] | analytical | simulated (lowering) | '
                  'J2 max abs(phi2\'\') [rad/s^2] | vibration [s] | distance to boundary [decades] | agree |',
                  '|---|---|---|---|---|---|---|---|']
        for r in sub:
            lines.append(f"| {r['motorSpeedRpm']:.1f} | {r['analyticMaxRealPart']:+.3f} | "
                         f"{'unstable' if r['analyticUnstable'] else 'stable'} | "
                         f"{'n/a' if r['simulatedChatter'] is None else 'chatter' if r['simulatedChatter'] else 'no chatter'}"
                         f" | {_Fmt(r['maxAbsWheelAcceleration'])} | {_Fmt(r['vibrationSeconds'], 3)} | "
                         f"{r['distanceDecades']:.3f} | {'yes' if r['agree'] else 'n/a' if r['agree'] is None else '**no**'} |")
        if s['disagreements']:
            lines += ['', 'Disagreements: ' + '; '.join(
                f"{r['motorSpeedRpm']:.1f} rpm ({r['distanceDecades']:.3f} decades from the boundary, analytical max Re "
                f"{r['analyticMaxRealPart']:+.3f} 1/s)" for r in s['disagreements']) + '.']
        lines.append('')
    total = Summary(rows)
    lines += [f'Both presets: {total["agree"]} of {total["finished"]} points agree '
              f'({100 * total["share"]:.1f} %; our target is >= 95 %).', '']
    text = '\n'.join(lines)
    path.write_text(text)
    return text


def _WriteCsv(rows: List[Dict], path: Path = _CSV) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, 'w', newline='') as file:
        writer = csv.DictWriter(file, fieldnames=_COLUMNS)
        writer.writeheader()
        for r in rows:
            writer.writerow(r)


def Main(argv: Optional[Sequence[str]] = None) -> int:
    """Command line: run the studies, write the CSV and the report.

    Parameters
    ----------
    argv : list of str, optional
        Arguments (default: sys.argv).

    Returns
    -------
    int
        Exit status.
    """
    parser = argparse.ArgumentParser(prog='python -m validation.friction_speed', description=__doc__.splitlines()[0])
    parser.add_argument('--presets', nargs='+', default=list(PRESETS), choices=PRESETS)
    args = parser.parse_args(argv)
    rows = []
    for preset in args.presets:
        rows += RunSpeedStudy(preset)
        _WriteCsv(rows)
    print(WriteReport(rows))
    return 0


if __name__ == '__main__':
    raise SystemExit(Main())
