"""A seeded corpus of worm drives unlike the reel changer: the linear verdict at each operating point against the
simulated chatter verdict of the same phase.

Run from the repository root::

    python -m validation.chatter_corpus            # 240 drives: CHATTER_CORPUS.md and chatter_corpus.csv here
    python -m validation.chatter_corpus --quick    # 4 drives with short phases (a test of the script; --report/--csv)

Each drive is drawn from a seeded generator (:func:`DrawDrive`): a worm gear by its designation (axial module,
starts, wheel teeth, diameter quotient), mesh stiffness and damping, worm and wheel inertias, a drive shaft,
optionally a drive-side chain (J4, k4, d4), a load-side chain (JL1, kL1, dL1) and an axial bearing (kA, dA, mA),
a constant, Stribeck or AGMA friction law, a constant load torque and a speed-table motor that lifts, pauses
and lowers (the duty of a hoist). The linear verdict of each steady phase comes from the linear analysis at the
drive's own operating points (:func:`LinearOperatingPoints`, the one place that calls it); the simulated verdict
is :meth:`~exudyn_worm.items.results.SimulationResult.ChatterVerdict` over that phase's plateau, the rule fixed before
this corpus was run (validation/CHATTER_RULE.md). A phase counts where its growth or decay is resolvable within
it: |largest real part| x plateau length >= :data:`RESOLVABLE`, and where the simulated window is decided. A second
group (:func:`DrawLightlyDamped`) has a lightly damped load side, a load reversal and a restart, and each of its
drives is simulated again with long plateaus to check the short windows' verdicts.
"""
from __future__ import annotations

import argparse
import csv
import math
import sys
import time
from pathlib import Path
from typing import Dict, List, Mapping, Optional, Sequence

import numpy as np

__all__ = ['SEED', 'DRIVES', 'RESOLVABLE', 'TARGET', 'FULL', 'QUICK', 'EXTRA_FIRST', 'LINEAR_METHOD', 'DrawDrive',
           'DrawLightlyDamped', 'DutyWindows',
           'LinearOperatingPoints', 'RunDrive', 'RunCorpus', 'Summarize', 'WriteCsv', 'WriteReport', 'Main']

HERE = Path(__file__).resolve().parent
#: seed of the generator: the corpus is the same on every run (20261202 until the revised chatter rule of
#: 2026-12-05, whose defects were found on the drives of that seed; validation/CHATTER_RULE.md)
SEED = 20261205
#: number of drives of the full corpus
DRIVES = 200
#: a phase's growth or decay is resolvable within it when |largest real part| x plateau length >= this
RESOLVABLE = 3.
#: agreement required over the resolvable phases
TARGET = 0.95
#: duty of the full run and of --quick: drives, plateau length, ramp and pause in s; ``extra``: drives of the
#: second group (:func:`DrawLightlyDamped`: lightly damped load side, load reversal, stop and restart), each also
#: simulated with plateaus of ``long`` s (the long simulation its short verdicts are checked against)
FULL = {'drives': DRIVES, 'plateau': 1.0, 'ramp': 0.02, 'pause': 0.05, 'extra': 40, 'long': 5.0}
QUICK = {'drives': 3, 'plateau': 0.1, 'ramp': 0.01, 'pause': 0.02, 'extra': 1, 'long': 0.3}
#: the second group's drives are numbered from here
EXTRA_FIRST = 1000
#: largest number of solver steps of one long run (above it the long check is recorded as skipped)
_MAX_LONG_STEPS = 1_500_000
_RPM = 2 * math.pi / 60
#: largest number of solver steps of one drive's run (a drive needing more is recorded as skipped)
_MAX_STEPS = 400_000
CSV_COLUMNS = ('drive', 'phase', 'window', 'friction', 'components', 'mx', 'z1', 'z2', 'q', 'u', 'gammaDeg', 'motorSpeed',
               'loadTorque', 'maxRealPart', 'frequencyHz', 'linearStable', 'growthOverPhase', 'resolvable',
               'simulatedChatter', 'simulatedState', 'envelopeRate', 'rateOverPhase', 'chatterBy', 'agree',
               'normalA3', 'normalA4', 'slidingA3', 'slidingA4', 'normalRate', 'slidingRate', 'minWormSpeed',
               'lastQuarterMinWormSpeed', 'dominantFrequencyHz', 'stepSize',
               'longState', 'longRate', 'agreeLong', 'seconds', 'error')


def _LogUniform(rng, low: float, high: float) -> float:
    return float(math.exp(rng.uniform(math.log(low), math.log(high))))


def DrawDrive(rng: np.random.Generator, duty: Mapping[str, float] = FULL) -> Dict:
    """One random drive as a flat parameter set (a hoist's duty: constant load torque, speed table lift / pause / lower).

    Parameters
    ----------
    rng : numpy.random.Generator
        The seeded generator (draws in a fixed order, so the corpus depends on the seed only).
    duty : mapping
        ``plateau``, ``ramp``, ``pause`` in s (:data:`FULL` or :data:`QUICK`).

    Returns
    -------
    dict
        The parameter set, SI units.
    """
    mx = float(rng.choice([1e-3, 1.5e-3, 2e-3, 2.5e-3, 3e-3, 4e-3, 5e-3, 6e-3, 8e-3]))
    z1 = int(rng.choice([1, 1, 2]))
    z2 = int(rng.integers(20, 91))
    q = float(rng.choice([8., 10., 11., 12., 14., 16., 18., 20.]))
    r1, r2 = 0.5 * q * mx, 0.5 * z2 * mx
    gamma = math.atan(z1 / q)
    alphaN = math.radians(20.)
    p = {'alphaN': alphaN, 'mx': mx, 'z1': z1, 'z2': z2, 'q': q, 'backlash': 0.,
         'kV': mx * _LogUniform(rng, 1e10, 1e11), 'DV': _LogUniform(rng, 0.005, 0.05),
         'J1': _LogUniform(rng, 1e-4, 2e-2), 'kT': _LogUniform(rng, 200., 2e4), 'DT': _LogUniform(rng, 0.005, 0.05),
         'J2': r2 ** 4 * _LogUniform(rng, 2e3, 5e4)}
    law = str(rng.choice(['constant', 'stribeck', 'agma']))
    if law == 'constant':
        p['mu'] = rng.uniform(0.04, 0.12)
    elif law == 'stribeck':
        p.update(frictionLaw='stribeck', mu=rng.uniform(0.03, 0.08), stribeckVelocity=_LogUniform(rng, 0.05, 1.))
        p['muStatic'] = p['mu'] + rng.uniform(0.02, 0.08)
    else:                                        # mu: the gear's nominal value; the AGMA law replaces it in the mesh
        p.update(frictionLaw='agma', mu=0.05)
    if rng.uniform() < 0.35:                     # drive-side chain: worm --kT-- J4 --k4-- motor
        J4, k4 = p['J1'] * _LogUniform(rng, 0.3, 10.), p['kT'] * _LogUniform(rng, 0.3, 3.)
        p.update(J4=J4, k4=k4, d4=2 * rng.uniform(0.01, 0.1) * math.sqrt(k4 * J4))
    if rng.uniform() < 0.5:                      # load-side chain: wheel --kL1-- JL1 (the load acts on JL1)
        JL1, kL1 = p['J2'] * _LogUniform(rng, 1., 100.), _LogUniform(rng, 1e4, 3e6)
        p.update(JL1=JL1, kL1=kL1, dL1=2 * rng.uniform(0.01, 0.1) * math.sqrt(kL1 * JL1 * p['J2'] / (JL1 + p['J2'])))
    if rng.uniform() < 0.3:                      # axial bearing of the worm
        kA, mA = _LogUniform(rng, 1e8, 2e9), _LogUniform(rng, 0.5, 5.)
        p.update(kA=kA, mA=mA, dA=2 * rng.uniform(0.01, 0.05) * math.sqrt(kA * mA))
    normalForce = _LogUniform(rng, 500., 2e4)    # static normal force the load torque makes, N
    speed = _LogUniform(rng, 30. * _RPM, 1500. * _RPM)
    p.update(loadType='constant', loadTorque=-normalForce * r2 * math.cos(alphaN) * math.cos(gamma),
             motorType='speedTable', motorSpeedOverTime=_SpeedTable(speed, duty))
    return p


def DrawLightlyDamped(rng: np.random.Generator, duty: Mapping[str, float] = FULL, plateau: Optional[float] = None) -> Dict:
    """One drive of the second group: a lightly damped load side (D <= 2 %), a load that reverses while the motor
    stands, and a stop and restart: speed table lift / stop (the load reverses) / run on in the same direction (now
    the load drives: lowering) / stop / run back (lifting against the reversed load).

    Parameters
    ----------
    rng : numpy.random.Generator
        The seeded generator of the second group.
    duty : mapping
        ``plateau``, ``ramp``, ``pause`` in s.
    plateau : float, optional
        Plateau length in s instead of ``duty['plateau']`` (the long simulation).

    Returns
    -------
    dict
        The parameter set, SI units.
    """
    p = DrawDrive(rng, duty)
    JL1, kL1 = p['J2'] * _LogUniform(rng, 1., 100.), _LogUniform(rng, 1e4, 3e6)
    D = rng.uniform(0.002, 0.02)
    p.update(JL1=JL1, kL1=kL1, dL1=2 * D * math.sqrt(kL1 * JL1 * p['J2'] / (JL1 + p['J2'])))
    torque = p['loadTorque']
    speed = p['motorSpeedOverTime'][2][1]
    r, L, P = duty['ramp'], duty['plateau'] if plateau is None else plateau, 2 * duty['pause']
    times = np.cumsum([0., r, L, r, P, r, L, r, P, r, L, r])
    speeds = (0., speed, speed, 0., 0., speed, speed, 0., 0., -speed, -speed, 0.)
    reverse = times[3] + 0.25 * P, times[3] + 0.75 * P
    p.update(motorSpeedOverTime=[(float(t), v) for t, v in zip(times, speeds)], loadType='timeTable',
             loadTorqueOverTime=[(0., torque), (float(reverse[0]), torque), (float(reverse[1]), -torque)])
    del p['loadTorque']
    return p


def _SpeedTable(speed: float, duty: Mapping[str, float]) -> List[tuple]:
    r, L, P = duty['ramp'], duty['plateau'], duty['pause']
    times = np.cumsum([0., r, L, r, P, r, L, r])
    return [(float(t), s) for t, s in zip(times, (0., speed, speed, 0., 0., -speed, -speed, 0.))]


def DutyWindows(parameters: Mapping) -> Dict[str, tuple]:
    """The plateaus of a corpus drive's speed table.

    Parameters
    ----------
    parameters : mapping
        A corpus drive (:func:`DrawDrive`).

    Returns
    -------
    dict
        ``{'lifting': (t0, t1), 'lowering': (t0, t1), 'end': t}`` in s (``end``: the end of the table).
    """
    t = [row[0] for row in parameters['motorSpeedOverTime']]
    return {'lifting': (t[1], t[2]), 'lowering': (t[5], t[6]), 'end': t[-1]}


#: how :func:`LinearOperatingPoints` gets its verdicts (named in the report)
LINEAR_METHOD = ('`exudyn_worm.AnalyzeDrive(ResolveDrive(parameters=...))` at the operating points of the duty '
                 '(each plateau of the speed table in its direction: sliding speed, mu(v) and its slope, static normal '
                 'force, contact state S = +1 lifting, -1 lowering; the two-mass drive analytically, any other drive '
                 'by the linearized whole drive)')


def LinearOperatingPoints(parameters: Mapping) -> List[Dict]:
    """The linear verdict at each steady phase of the drive: the one place this corpus asks the linear analysis.

    Parameters
    ----------
    parameters : mapping
        A corpus drive (:func:`DrawDrive`).

    Returns
    -------
    list of dict
        Per operating point ``phase`` ('lifting' / 'lowering'), ``window`` (t0, t1) in s, ``motorSpeed`` (rad/s),
        ``loadTorque`` (N*m), ``maxRealPart`` (1/s), ``frequencyHz``, ``stable``.
    """
    import exudyn_worm as ew
    analysis = ew.AnalyzeDrive(ew.ResolveDrive(parameters=dict(parameters)))
    return [{'phase': op.phase, 'window': tuple(op.point.window), 'motorSpeed': op.point.motorSpeed,
             'loadTorque': op.point.loadTorque, 'maxRealPart': op.maxRealPart, 'frequencyHz': op.frequencyHz,
             'stable': op.stable} for op in analysis.operatingPoints]


def _Components(p: Mapping) -> str:
    parts = [name for key, name in (('J4', 'drive chain'), ('JL1', 'load chain'), ('kA', 'axial bearing')) if key in p]
    return '+'.join(parts) or 'two-mass'


def _Plateaus(parameters: Mapping) -> List[tuple]:
    """The plateaus (t0, t1) of a speed table: consecutive rows with the same non-zero speed."""
    rows = parameters['motorSpeedOverTime']
    return [(a[0], b[0]) for a, b in zip(rows, rows[1:]) if a[1] == b[1] != 0.]


def _Simulate(p: Mapping, maxSteps: int):
    """One run of the whole duty at the recommended step (raises where it needs more than ``maxSteps``)."""
    from exudyn_worm.analysis.simulation.reelchanger import SimulateReelChanger
    from exudyn_worm.analysis.simulation.stepsize import RecommendedStepSize
    from exudyn_worm.drive.wholedrive import ResolveDrive
    drive = ResolveDrive(parameters=p)
    stepSize = RecommendedStepSize(drive)
    endTime = DutyWindows(p)['end']
    if endTime / stepSize > maxSteps:
        raise ValueError(f"needs {endTime / stepSize:.3g} steps at the recommended {stepSize:.3g} s, above the "
                         f"corpus' budget of {maxSteps}")
    result = SimulateReelChanger(drive, endTime=endTime, stepSize=stepSize, progress=False, maxSteps=maxSteps)
    if not all(np.all(np.isfinite(result.series[k])) for k in ('omega1', 'omega2', 'normalForce')):
        raise FloatingPointError('diverged: non-finite state')
    return result, stepSize


def RunDrive(index: int, parameters: Mapping, longParameters: Optional[Mapping] = None) -> List[Dict]:
    """Linear verdicts and the simulation of one drive: one row per operating point (never raises: a failure is
    recorded in ``error``).

    Parameters
    ----------
    index : int
        The drive's number in the corpus.
    parameters : mapping
        The drive (:func:`DrawDrive` or :func:`DrawLightlyDamped`).
    longParameters : mapping, optional
        The same drive with long plateaus: its verdict on the same plateau is recorded (``longState``, ``longRate``)
        and compared with the short one where both are decided (``agreeLong``).

    Returns
    -------
    list of dict
        Rows with the columns :data:`CSV_COLUMNS`.
    """
    from exudyn_worm.drive.presets import ElasticDriveFromParameters
    from exudyn_worm.drive.wholedrive import ResolveDrive
    start = time.perf_counter()
    p = dict(parameters)
    gear = ElasticDriveFromParameters(p).gear
    friction = p.get('frictionLaw', 'constant')
    base = {'drive': index, 'friction': friction, 'components': _Components(p), 'mx': p['mx'], 'z1': p['z1'],
            'z2': p['z2'], 'q': p['q'], 'u': gear.ratio, 'gammaDeg': math.degrees(gear.gamma), 'error': ''}
    if 'loadTorqueOverTime' in p:
        base['components'] += ', reversal+restart'
    try:
        points = LinearOperatingPoints(p)
    except Exception as err:                    # a failing drive is a result, not the end of the corpus
        return [dict(base, phase='-', error=f"linear analysis: {type(err).__name__}: {err}",
                     seconds=time.perf_counter() - start)]
    rows = [dict(base, phase=op['phase'], window=op['window'], motorSpeed=op['motorSpeed'],
                 loadTorque=op['loadTorque'], maxRealPart=op['maxRealPart'], frequencyHz=op['frequencyHz'],
                 linearStable=op['stable']) for op in points]
    for row in rows:
        t0, t1 = row['window']
        row['growthOverPhase'] = row['maxRealPart'] * (t1 - t0)
        row['resolvable'] = abs(row['growthOverPhase']) >= RESOLVABLE
    try:
        result, stepSize = _Simulate(p, _MAX_STEPS)
        for row in rows:
            t0, t1 = row['window']
            a = result.MeshOscillation(t0, t1)
            v = result.ChatterVerdict(t0, t1)
            rates = result.EnvelopeRates(t0, t1)
            row.update(simulatedChatter=v.chatter, simulatedState=v.state, envelopeRate=v.rate,
                       rateOverPhase=v.rate * (t1 - t0), chatterBy='+'.join(v.measures) if v.chatter else '',
                       agree=(v.chatter == (not row['linearStable'])) if v.decided else None,
                       normalA3=a['normal'][2], normalA4=a['normal'][3], slidingA3=a['sliding'][2],
                       slidingA4=a['sliding'][3], normalRate=rates['normal'], slidingRate=rates['sliding'],
                       minWormSpeed=result.MinWormSpeed(t0, t1),
                       lastQuarterMinWormSpeed=result.MinWormSpeed(t0 + 0.75 * (t1 - t0), t1),
                       dominantFrequencyHz=result.DominantFrequency(0.5 * (t0 + t1), t1, 'normalForce'),
                       stepSize=stepSize)
    except Exception as err:                    # a failing run is recorded, the others go on
        for row in rows:
            row['error'] = f"simulation: {' '.join(f'{type(err).__name__}: {err}'.split())}"
    if longParameters is not None and not any(r.get('error') for r in rows):
        try:
            long, _ = _Simulate(longParameters, _MAX_LONG_STEPS)
            short, longPlateaus = _Plateaus(p), _Plateaus(longParameters)
            for row in rows:
                k = min(range(len(short)), key=lambda i: abs(short[i][0] - row['window'][0]))
                v = long.ChatterVerdict(*longPlateaus[k])
                row.update(longState=v.state, longRate=v.rate,
                           agreeLong=(v.chatter == row['simulatedChatter'])
                           if v.decided and row['simulatedState'] != 'undecided' else None)
        except Exception as err:                # a long run that fails leaves the short verdicts standing
            for row in rows:
                row['longState'] = f"failed: {' '.join(f'{type(err).__name__}: {err}'.split())}"
    seconds = time.perf_counter() - start
    for row in rows:
        row['seconds'] = seconds / len(rows)
    return rows


def RunCorpus(duty: Mapping[str, float] = FULL, seed: int = SEED, quiet: Optional[bool] = None) -> List[Dict]:
    """Draw and run the corpus (one core, in order).

    Parameters
    ----------
    duty : mapping
        :data:`FULL` or :data:`QUICK` (``drives``, ``plateau``, ``ramp``, ``pause``).
    seed : int
        Seed of the generator.
    quiet : bool or None
        Progress bar on stderr (None: when stderr is a terminal).

    Returns
    -------
    list of dict
        All rows (:data:`CSV_COLUMNS`).
    """
    from exudyn_worm.progress import ProgressBar
    rng = np.random.default_rng(seed)
    drives = [DrawDrive(rng, duty) for _ in range(int(duty['drives']))]
    extra = [(DrawLightlyDamped(np.random.default_rng([seed, 1, i]), duty),
              DrawLightlyDamped(np.random.default_rng([seed, 1, i]), duty, plateau=duty['long']))
             for i in range(int(duty.get('extra', 0)))]
    rows = []
    with ProgressBar(total=len(drives) + len(extra), desc='corpus', unit='drive', quiet=quiet) as bar:
        for i, p in enumerate(drives):
            rows += RunDrive(i, p)
            bar.update(1)
        for i, (p, long) in enumerate(extra):
            rows += RunDrive(EXTRA_FIRST + i, p, long)
            bar.update(1)
    return rows


def Summarize(rows: Sequence[Mapping]) -> Dict:
    """Agreement of linear and simulated verdicts, per operating point and per drive.

    Parameters
    ----------
    rows : sequence of mapping
        Rows of :func:`RunDrive`.

    Returns
    -------
    dict
        ``points``: ``resolvable``, ``agree`` (counts over the resolvable operating points that ran), ``fraction``;
        ``drives``: the same per drive (its verdict: unstable at any point / chatters in any phase; resolvable when
        its deciding point is: the one with the largest real part); ``failed`` rows; ``undecided`` (resolvable points
        whose simulated window is undecided: not counted); ``others`` (the rows not counted: unresolvable, sorted by
        their distance |growthOverPhase| to the boundary); ``long``: the short verdicts against the long simulations
        (``compared``, ``agree``, ``disagree`` rows, ``undecided`` rows whose short window is undecided).
    """
    ran = [r for r in rows if not r.get('error')]
    undecided = [r for r in ran if r['resolvable'] and r['simulatedState'] == 'undecided']
    resolvable = [r for r in ran if r['resolvable'] and r['simulatedState'] != 'undecided']
    byDrive: Dict[int, List[Mapping]] = {}
    for r in ran:
        byDrive.setdefault(r['drive'], []).append(r)
    drives = []
    for index, rs in sorted(byDrive.items()):
        deciding = max(rs, key=lambda r: r['maxRealPart'])
        drives.append({'drive': index, 'resolvable': deciding['resolvable']
                       and all(r['simulatedState'] != 'undecided' for r in rs),
                       'agree': any(r['simulatedChatter'] for r in rs) == (not all(r['linearStable'] for r in rs))})
    counted = [d for d in drives if d['resolvable']]

    def Fraction(n, total):
        return n / total if total else float('nan')
    agreePoints = sum(bool(r['agree']) for r in resolvable)
    agreeDrives = sum(d['agree'] for d in counted)
    return {'points': {'total': len(rows), 'ran': len(ran), 'resolvable': len(resolvable), 'agree': agreePoints,
                       'fraction': Fraction(agreePoints, len(resolvable))},
            'drives': {'total': len({r['drive'] for r in rows}), 'ran': len(drives), 'resolvable': len(counted),
                       'agree': agreeDrives, 'fraction': Fraction(agreeDrives, len(counted))},
            'failed': [r for r in rows if r.get('error')],
            'disagree': [r for r in resolvable if not r['agree']],
            'undecided': undecided,
            'long': {'compared': [r for r in ran if r.get('agreeLong') is not None],
                     'disagree': [r for r in ran if r.get('agreeLong') is False],
                     'undecided': [r for r in ran if r.get('longState') and r['simulatedState'] == 'undecided']},
            'others': sorted((r for r in ran if not r['resolvable']), key=lambda r: abs(r['growthOverPhase']))}


def _Count(values) -> Dict[str, int]:
    out: Dict[str, int] = {}
    for v in values:
        key = 'failed' if str(v).startswith('failed') else str(v)
        out[key] = out.get(key, 0) + 1
    return out


def _Cell(value) -> str:
    if isinstance(value, bool):
        return 'yes' if value else 'no'
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, tuple):
        return ':'.join(f"{v:.6g}" for v in value)
    return '' if value is None else str(value)


def WriteCsv(rows: Sequence[Mapping], path: Path) -> Path:
    """Write the rows (:data:`CSV_COLUMNS`) to ``path``.

    Parameters
    ----------
    rows : sequence of mapping
        Rows of :func:`RunDrive`.
    path : pathlib.Path
        The CSV file (its folder must exist).
    """
    with Path(path).open('w', newline='') as f:
        w = csv.writer(f)
        w.writerow(CSV_COLUMNS)
        for r in rows:
            w.writerow([_Cell(r.get(c)) for c in CSV_COLUMNS])
    return Path(path)


def _Line(r: Mapping) -> str:
    return (f"| {r['drive']} | {r['phase']} | {r['friction']} | {r['components']} | {r['u']:.3g} | "
            f"{r['maxRealPart']:.3g} | {r['growthOverPhase']:+.2f} | {r['frequencyHz']:.0f} | "
            f"{'stable' if r['linearStable'] else 'unstable'} | {r['simulatedState']} | {r['envelopeRate']:.3g} | "
            f"{max(r['normalA4'], r['slidingA4']):.3g} | {r['minWormSpeed']:.3g} |"
            + (f" {r.get('longState', '')} |" if r.get('longState') else ' |'))


_HEADER = ('| drive | phase | friction | components | u | max Re [1/s] | Re x phase | f [Hz] | linear | simulated | '
           'envelope rate [1/s] | largest a4 | min worm speed [rad/s] | long simulation |\n'
           '|---|---|---|---|---|---|---|---|---|---|---|---|---|---|')


def WriteReport(rows: Sequence[Mapping], path: Path, duty: Mapping[str, float], seed: int, csvPath: Path,
                seconds: float) -> Path:
    """Write the Markdown report: the numbers, the disagreements, every phase not counted with its distance to the
    boundary, and every failure.

    Parameters
    ----------
    rows : sequence of mapping
        Rows of :func:`RunDrive`.
    path : pathlib.Path
        The report file.
    duty : mapping
        The duty the corpus was run with.
    seed : int
        Its seed.
    csvPath : pathlib.Path
        The CSV written beside it (named in the report).
    seconds : float
        Wall-clock time of the run.
    """
    s = Summarize(rows)
    pts, drv = s['points'], s['drives']
    verdict = 'PASS' if pts['resolvable'] and pts['fraction'] >= TARGET else 'FAIL'
    friction = {law: len({r['drive'] for r in rows if r['friction'] == law}) for law in ('constant', 'stribeck', 'agma')}
    components = {c: len({r['drive'] for r in rows if c in r['components']})
                  for c in ('drive chain', 'load chain', 'axial bearing')}
    lines = [f"# Chatter rule on a seeded corpus of drives",
             '',
             f"Generated by `python -m validation.chatter_corpus` (seed {seed}, {drv['total']} drives, "
             f"{time.strftime('%Y-%m-%d')}, {seconds / 60:.1f} min on one core); every row: `{csvPath.name}`. "
             f"The chatter rule was fixed before this run: [CHATTER_RULE.md](CHATTER_RULE.md).",
             '',
             f"Drives: gears by designation (module 1-8 mm, 1 or 2 starts, 20-90 teeth, diameter quotient 8-20), "
             f"friction constant {friction['constant']}, Stribeck {friction['stribeck']}, AGMA {friction['agma']}; "
             f"with a drive-side chain {components['drive chain']}, a load-side chain {components['load chain']}, "
             f"an axial bearing {components['axial bearing']}. Duty: constant load torque, speed table "
             f"ramp {duty['ramp']:g} s, lifting plateau {duty['plateau']:g} s, pause {duty['pause']:g} s, lowering "
             f"plateau {duty['plateau']:g} s. Linear verdict at the operating point of each plateau: "
             f"{LINEAR_METHOD}; simulated verdict: `SimulationResult.ChatterVerdict` over the plateau (chatter, none, decaying or undecided; undecided windows are not counted). A phase counts when "
             f"|largest real part| x plateau >= {RESOLVABLE:g}.",
             '',
             f"**Agreement over the resolvable operating points: {pts['agree']} of {pts['resolvable']} "
             f"({100 * pts['fraction']:.1f} %; target {100 * TARGET:.0f} %): {verdict}.**",
             '',
             f"Per drive (unstable at any operating point / chatters in any phase; counted when the deciding point, "
             f"the largest real part, is resolvable): {drv['agree']} of {drv['resolvable']} "
             f"({100 * drv['fraction']:.1f} %).",
             '',
             f"Operating points: {pts['total']}, simulated {pts['ran']}, resolvable {pts['resolvable']}, "
             f"not resolvable {len(s['others'])}, failed {len(s['failed'])}.",
             '', '## Agreement by kind (resolvable points)', '',
             '| group | points | agree | linear unstable | simulated chatter (normal / sliding measure) |',
             '|---|---|---|---|---|']
    resolvable = [r for r in rows if not r.get('error') and r['resolvable']]
    groups = [('lifting', lambda r: r['phase'] == 'lifting'), ('lowering', lambda r: r['phase'] == 'lowering')]
    groups += [(f'friction {law}', lambda r, law=law: r['friction'] == law) for law in ('constant', 'stribeck', 'agma')]
    groups += [(f'with {c}', lambda r, c=c: c in r['components']) for c in ('drive chain', 'load chain', 'axial bearing')]
    groups += [('two-mass', lambda r: r['components'] == 'two-mass'),
               ('lightly damped, reversal, restart', lambda r: 'reversal' in r['components']), ('all', lambda r: True)]
    for name, member in groups:
        rs = [r for r in resolvable if member(r) and r['simulatedState'] != 'undecided']
        chatter = [r for r in rs if r['simulatedChatter']]
        normal, sliding = (sum(name in r['chatterBy'].split('+') for r in chatter) for name in ('normal', 'sliding'))
        lines.append(f"| {name} | {len(rs)} | {sum(bool(r['agree']) for r in rs)} | "
                     f"{sum(not r['linearStable'] for r in rs)} | {len(chatter)} ({normal} / {sliding}) |")
    lines += ['', '## Resolvable points where the verdicts differ', '']
    lines += [_HEADER] + [_Line(r) for r in s['disagree']] if s['disagree'] else ['None.']
    lines += ['', '## Resolvable points whose simulated window is undecided (not counted)', '',
              'The window holds a vibration of at least a quarter of the steady value that decays slower than the window, '
              'a steady one below saturation without the worm turning back, or fewer than 2 periods of its vibration in '
              "the window's last quarter or second half (CHATTER_RULE.md; `largest a4` is the last quarter's own reading).", '']
    lines += [_HEADER] + [_Line(r) for r in s['undecided']] if s['undecided'] else ['None.']
    lg = s['long']
    lines += ['', f"## Short windows against the long simulations (second group, plateaus of {duty.get('long', 0):g} s)",
              '', f"Decided in both: {len(lg['compared'])}, the verdicts agree in "
              f"{len(lg['compared']) - len(lg['disagree'])}; short windows undecided: {len(lg['undecided'])} "
              f"(their long verdicts: "
              + (', '.join(f"{k} {v}" for k, v in sorted(_Count(r['longState'] for r in lg['undecided']).items()))
                 or 'none') + ').', '', 'Disagreements:', '']
    lines += [_HEADER] + [_Line(r) for r in lg['disagree']] if lg['disagree'] else ['None.']
    lines += ['', 'Short windows undecided, with the long verdict:', '']
    lines += [_HEADER] + [_Line(r) for r in lg['undecided']] if lg['undecided'] else ['None.']
    lines += ['', '## Points not counted (growth or decay not resolvable within the phase), nearest the boundary first',
              '', "Distance to the boundary: `Re x phase` (the growth exponent over the plateau; 0 on the boundary).",
              '']
    lines += [_HEADER] + [_Line(r) for r in s['others']] if s['others'] else ['None.']
    lines += ['', '## Failed', '']
    lines += ([f"- drive {r['drive']} {r['phase']}: {r['error']}" for r in s['failed']] or ['None.'])
    Path(path).write_text('\n'.join(lines) + '\n')
    return Path(path)


def Main(argv: Optional[List[str]] = None) -> int:
    """Command line: run the corpus, write the CSV and the report.

    Parameters
    ----------
    argv : list of str, optional
        Arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status: 0 when the agreement meets :data:`TARGET`, 1 otherwise, 2 for bad arguments.
    """
    parser = argparse.ArgumentParser(prog='python -m validation.chatter_corpus', description=__doc__.splitlines()[0])
    parser.add_argument('--quick', action='store_true', help=f"{QUICK['drives']} drives with short phases "
                                                             "(a test of the script, not of the rule)")
    parser.add_argument('--seed', type=int, default=SEED, help=f'seed of the generator (default {SEED})')
    parser.add_argument('--report', default=None, help='report path (default validation/CHATTER_CORPUS.md; '
                                                       '--quick: required)')
    parser.add_argument('--csv', default=None, help='CSV path (default beside the report, chatter_corpus.csv)')
    parser.add_argument('--quiet', action='store_true', help='no progress bar')
    args = parser.parse_args(argv)
    if args.quick and args.report is None:
        parser.error('--quick needs --report PATH (the committed report is the full corpus)')
    report = Path(args.report).resolve() if args.report else HERE / 'CHATTER_CORPUS.md'
    csvPath = Path(args.csv).resolve() if args.csv else report.parent / 'chatter_corpus.csv'
    for path, option in ((report, '--report'), (csvPath, '--csv')):
        if path.is_dir() or not path.parent.is_dir():
            parser.error(f"{option}: must be a file in an existing folder, got '{path}'")
    duty = QUICK if args.quick else FULL
    start = time.perf_counter()
    rows = RunCorpus(duty, args.seed, quiet=True if args.quiet else None)
    seconds = time.perf_counter() - start
    WriteCsv(rows, csvPath)
    WriteReport(rows, report, duty, args.seed, csvPath, seconds)
    s = Summarize(rows)['points']
    print(f"agreement {s['agree']} of {s['resolvable']} resolvable operating points; wrote {report} and {csvPath}",
          file=sys.stderr)
    return 0 if s['resolvable'] and s['fraction'] >= TARGET else 1


if __name__ == '__main__':
    raise SystemExit(Main())
