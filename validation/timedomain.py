"""Time-domain checks of the paper's statements (section 3.2): the ``simulation`` group of the validation.

The published statements and the phrases they are read by are rows of ``validation/paper/reference.csv``
(``group = simulation``); this module computes our value for each row (yes/no statements as 1/0) from
reel-changer simulations, which are shared between rows, under both mesh readings (tooth normal and wheel
circumference).
"""
from __future__ import annotations

import math
from functools import lru_cache
from typing import Callable, Dict, List, Tuple

import numpy as np

from exudyn_worm.model.contact import ContactOptions
from exudyn_worm.drive.presets import ApplyOverrides, ElasticDriveFromParameters, GetPreset
from exudyn_worm.analysis.simulation.reelchanger import DEFAULT_STEP_SIZE, DefaultWindows, SimulateReelChanger
from exudyn_worm.model.stability import AnalyzeStability
from exudyn_worm.drive.wholedrive import ResolveDrive

from .paper.eigenvalue_forensics import WheelCircumferenceFactor
from .runner import READINGS, Fmt

__all__ = ['TIME_DOMAIN_CHECKS', 'Simulate', 'PaperMeshConvention', 'SimulationChecks']

_RPM = 2 * math.pi / 60
_FRICTION_SPEED = ContactOptions().frictionSpeed


def PaperMeshConvention(parameters):
    """Parameters with kV and dV referred to the wheel circumference, i.e. multiplied by
    1/(cos(alphaN) cos(gamma))^2: the mesh convention identified from the paper's printed eigenvalues
    (validation/REPORT.md, eigenvalue forensics).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set.
    """
    gear = ElasticDriveFromParameters(parameters).gear
    f = WheelCircumferenceFactor(gear)
    return ApplyOverrides(parameters, {'kV': gear.kV * f, 'dV': gear.dV * f})


@lru_cache(maxsize=None)
def Simulate(preset: str, overrides: Tuple = (), stepSize: float = DEFAULT_STEP_SIZE,
             frictionSpeed: float = _FRICTION_SPEED, paperMesh: bool = False, frictionModel: str = 'sticking'):
    """Cached simulation of one rotation of a reel preset with ``overrides`` ((key, value), ...)."""
    p = ApplyOverrides(GetPreset(preset), dict(overrides))
    if paperMesh:
        p = PaperMeshConvention(p)
    return SimulateReelChanger(ResolveDrive(parameters=p), stepSize=stepSize, contactOptions=ContactOptions(frictionSpeed=frictionSpeed,
                                                                                   frictionModel=frictionModel))


def _Metrics(preset, overrides=(), **kw):
    windows = DefaultWindows(ResolveDrive(parameters=ApplyOverrides(GetPreset(preset), dict(overrides))))
    return Simulate(preset, tuple(overrides), **kw).WindowMetrics(windows)


def _Lowering(preset, overrides=(), **kw):
    return _Metrics(preset, overrides, **kw)[1]


def _Window(r, t0, t1):
    return (r.time >= t0) & (r.time <= t1)


def _Ratio(preset, key, overrides):
    return lambda m: _Lowering(preset, overrides, paperMesh=m)[key] / _Lowering(preset, paperMesh=m)[key]


def _LinearFrequency(preset, paperMesh):
    p = GetPreset(preset)
    p = PaperMeshConvention(p) if paperMesh else p
    return float(np.mean(AnalyzeStability(ElasticDriveFromParameters(p)).contact[-1].frequenciesHz))


def _ChatterFrequencyVsLinear(m):
    return _Lowering('reel-P1', paperMesh=m)['dominantFrequencyHz'] / _LinearFrequency('reel-P1', m)


def _ForceFactor(m):
    static = abs(Simulate('reel-P1', paperMesh=m).series['normalForce'][0])
    return _Lowering('reel-P1', paperMesh=m)['maxNormalForce'] / static


def _BacklashFactor(backlash):
    def Compute(m):
        peak = [np.max(np.abs(r.series['normalForce'][_Window(r, 2, 3)]))
                for r in (Simulate('reel-P1', (('backlash', backlash),), paperMesh=m), Simulate('reel-P1', paperMesh=m))]
        return peak[0] / peak[1]
    return Compute


def _SignChangesPerPeriod(m):
    r = Simulate('reel-P7', paperMesh=m)
    s = np.sign(r.series['S'][_Window(r, 2, 6)])
    changes = np.count_nonzero(np.diff(s[s != 0]))
    return float(changes / (4. * _Lowering('reel-P7', paperMesh=m)['dominantFrequencyHz']) > 2)


def _ShareSNegativeLifting(m):
    r = Simulate('reel-P7', paperMesh=m)
    return 100. * float(np.mean(r.series['S'][_Window(r, 7.9, 8.0)] < 0))


def _Sticking(m):
    r = Simulate('reel-P7', paperMesh=m)
    return float(np.any(np.abs(r.series['sf'][_Window(r, 2, 6)]) < 1))


def _PeakNormalForces(preset, m):
    return [np.max(np.abs(Simulate(preset, (('backlash', b),), paperMesh=m).series['normalForce']))
            for b in (0., 0.25e-3, 0.5e-3, 0.75e-3)]


def _RobustnessStudy(preset, m) -> List[Tuple[str, dict]]:
    return [('default (step 5e-4 s, sticking friction)', _Lowering(preset, paperMesh=m)),
            ('step halved', _Lowering(preset, stepSize=DEFAULT_STEP_SIZE / 2, paperMesh=m)),
            ('regularized friction, frictionSpeed / 10',
             _Lowering(preset, frictionSpeed=_FRICTION_SPEED / 10, paperMesh=m, frictionModel='regularized'))]


def _Robustness(preset):
    def Compute(m):
        (_, base), *variants = _RobustnessStudy(preset, m)
        return 100. * max(abs(v[k] / base[k] - 1.) for _, v in variants
                          for k in ('maxAbsWheelAcceleration', 'maxNormalForce'))
    return Compute


def _ChatterCount(preset, overrides=(), m=False):
    return float(sum(w['chatter'] is True for w in _Metrics(preset, overrides, paperMesh=m)))   # undecided: no


def _Lower(preset, key, scale=1.):
    return lambda m: _Lowering(preset, paperMesh=m)[key] / scale


#: row id of validation/paper/reference.csv (group simulation) -> function(paperMesh) computing our value
TIME_DOMAIN_CHECKS: Dict[str, Callable[[bool], float]] = {
    'P1_chatter_lowering': lambda m: float(_Lowering('reel-P1', paperMesh=m)['chatter'] is True),
    'P1_chatter_lifting': lambda m: float(_Metrics('reel-P1', paperMesh=m)[0]['chatter'] is True
                                          or _Metrics('reel-P1', paperMesh=m)[2]['chatter'] is True),
    'P1_chatter_frequency_band': lambda m: float(33. <= _Lowering('reel-P1', paperMesh=m)['dominantFrequencyHz'] <= 52.),
    'P1_chatter_frequency': _Lower('reel-P1', 'dominantFrequencyHz'),
    'P1_chatter_frequency_vs_linear': _ChatterFrequencyVsLinear,
    'P1_max_acceleration': _Lower('reel-P1', 'maxAbsWheelAcceleration'),
    'P1_force_factor': _ForceFactor,
    'P1_load_doubling': _Ratio('reel-P1', 'maxAbsWheelAcceleration', (('loadMass', 350.),)),
    'P1_speed_doubling': _Ratio('reel-P1', 'maxAbsWheelAcceleration', (('motorSpeed', 945. * _RPM),)),
    'P1_backlash_0.25': _BacklashFactor(0.25e-3),
    'P1_backlash_0.5': _BacklashFactor(0.5e-3),
    'P1_backlash_0.75': _BacklashFactor(0.75e-3),
    'P7_max_acceleration': _Lower('reel-P7', 'maxAbsWheelAcceleration'),
    'P7_to_P1_ratio': lambda m: (_Lowering('reel-P7', paperMesh=m)['maxAbsWheelAcceleration']
                                 / _Lowering('reel-P1', paperMesh=m)['maxAbsWheelAcceleration']),
    'P7_chatter_lifting': lambda m: float(_Metrics('reel-P7', paperMesh=m)[2]['chatter'] is True),
    'P7_worm_speed_zero': lambda m: float(_Lowering('reel-P7', paperMesh=m)['minWormSpeed'] <= 0.),
    'P7_S_sign_changes': _SignChangesPerPeriod,
    'P7_S_negative_lifting': _ShareSNegativeLifting,
    'P7_sticking': _Sticking,
    'P7_peak_normal_force': _Lower('reel-P7', 'maxNormalForce', 1e3),
    'P7_backlash_independence': lambda m: max(_PeakNormalForces('reel-P7', m)) / min(_PeakNormalForces('reel-P7', m)),
    'P7_speed_doubling': _Ratio('reel-P7', 'maxAbsWheelAcceleration', (('motorSpeed', 945. * _RPM),)),
    'P2_P5_chatter_windows': lambda m: sum(_ChatterCount(p, m=m) for p in ('reel-P2', 'reel-P3', 'reel-P4', 'reel-P5')),
    'P6_chatter_lowering': lambda m: float(_Lowering('reel-P6', paperMesh=m)['chatter'] is True),
    'P6_DV0.056_chatter_windows': lambda m: _ChatterCount('reel-P6', (('DV', 0.056),), m),
    'P1_numerical_robustness': _Robustness('reel-P1'),
    'P7_numerical_robustness': _Robustness('reel-P7'),
}


def _RobustnessTable() -> str:
    lines = ['| preset | mesh reading | run | max \\|phi2\'\'\\| (rad/s^2) | change | peak normal force (kN) | change |',
             '|---|---|---|---|---|---|---|']
    for preset in ('reel-P1', 'reel-P7'):
        for m in (False, True):
            (_, base), *_ = study = _RobustnessStudy(preset, m)
            for label, w in study:
                a, f = w['maxAbsWheelAcceleration'], w['maxNormalForce']
                lines.append(f"| {preset} | {READINGS[m]} | {label} | {a:.2f} | "
                             f"{100 * (a / base['maxAbsWheelAcceleration'] - 1):+.2f} % | "
                             f"{f / 1e3:.2f} | {100 * (f / base['maxNormalForce'] - 1):+.2f} % |")
    return '\n'.join(lines)


def _Ids(checks) -> str:
    return ', '.join(f'`{c.row.id}`' for c in checks) or 'none'


def SimulationChecks(ctx):
    """Check group ``simulation`` of :func:`validation.RunValidation`: every row under both mesh readings."""
    from exudyn_worm.progress import ProgressBar
    rows = ctx.Rows('simulation')
    checks = []
    with ProgressBar(total=2 * len(rows), desc='time-domain rows', unit='check', quiet=ctx.quiet, leave=False) as bar:
        for row in rows:
            for m in (False, True):
                checks.append(ctx.Compare(row.id, TIME_DOMAIN_CHECKS[row.id](m), reading=READINGS[m],
                                          uses=('mu', 'circ') if m else ('mu',)))
                bar.update(1)
    normal = {c.row.id: c for c in checks if c.reading == 'normal'}
    paper = {c.row.id: c for c in checks if c.reading == 'paperMesh'}
    ok = lambda c: c.holds
    both = [normal[i] for i in normal if ok(normal[i]) and ok(paper[i])]
    onlyPaper = [paper[i] for i in normal if not ok(normal[i]) and ok(paper[i])]
    onlyNormal = [normal[i] for i in normal if ok(normal[i]) and not ok(paper[i])]
    neither = [normal[i] for i in normal if not ok(normal[i]) and not ok(paper[i])]
    confirm = [c for c in onlyPaper if not c.inSample]
    notCounted = [c for c in onlyPaper if c.inSample]
    table = ['| row | published | rule | accepted | tooth normal | verdict | wheel circumference | verdict | in-sample (circ) |',
             '|---|---|---|---|---|---|---|---|---|']
    for i in normal:
        n, p = normal[i], paper[i]
        table.append(f'| `{i}` | {n.row.publishedText} | {n.row.rule} | {n.IntervalText()} | '
                     f'{Fmt(n.computed, n.row.publishedText)} | {n.verdict} | '
                     f'{Fmt(p.computed, p.row.publishedText)} | {p.verdict} | {"yes" if p.inSample else "no"} |')
    ctx.AddSection('Time domain: both mesh readings side by side', f'''
All runs: the reel changer of `exudyn_worm.analysis.simulation.reelchanger` (motor with prescribed constant speed, elastic shaft
kT/dT, worm J1, the worm-gear connector, wheel J2, load -m2 g l2 cos(phi2)), one full rotation starting in the
static equilibrium at full speed, generalized-alpha with step 5e-4 s, the worm sticking at zero sliding speed (the
default friction model).
"Chatter" in a window: in its second half the wheel inertia torque J2 max|phi2''| exceeds 10 % of the largest
mesh torque on the wheel in the window (docs/command-line.md). Each row is computed with the mesh stiffness and damping along
the tooth normal (eq. (5), the package's model) and referred to the wheel circumference (kV, dV times
1/(cos alphaN cos gamma)^2, the reading the printed eigenvalues imply):

{chr(10).join(table)}

Generated from the comparisons (known differences counted as not holding): {len(both)} of {len(normal)} rows hold
under both readings; {len(onlyPaper)} hold only under the wheel-circumference reading ({_Ids(onlyPaper)}), of which
{len(confirm)} are out-of-sample and count as confirmation of that reading ({_Ids(confirm)}) and {len(notCounted)}
are in-sample and do not ({_Ids(notCounted)}); {len(onlyNormal)} hold only under the tooth-normal reading
({_Ids(onlyNormal)}), evidence against the wheel-circumference reading; {len(neither)} hold under neither
({_Ids(neither)}).

**Numerical knobs** (our own requirement: results must not hinge on them). Lowering window, max |phi2''| and peak normal
force:

{_RobustnessTable()}
''')
    return checks
