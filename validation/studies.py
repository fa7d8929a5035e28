"""Parameter studies for the validation report: the simulation-confirmed stability map and the backlash curves.

Run from the repository root::

    python -m validation.studies                 # all studies, every core; writes validation/STUDIES.md
    python -m validation.studies --workers 2 --quiet

It runs, with :func:`exudyn_worm.analysis.studies.study.RunStudy`,

* the stability map: a 12 x 12 log grid of J1 and kT of the reel changer around P1, spanning P2 ... P7, at
  D_V = 0.014 (Figure 4) and at D_V = 0.056 (Figure 5), both with D_TV = 1 (the chart line through P1). Each run
  is classified as chattering or not while lowering (the chatter rule of ``exudyn-worm simulate``) and compared
  with the analytical S = -1 verdict of the same parameter set; every disagreement is located relative to the
  analytical boundary and explained from its numbers;
* the backlash curves of P1 and P7 (0 ... 1 mm, 13 values including the paper's 0.25, 0.5 and 0.75 mm): peak
  normal force and peak wheel acceleration in the early lowering (2-3 s) and over the whole lowering (2-6 s), and
  how long P7's vibration lasts into the lifting phase (6-10 s, the interval of the paper's Figure 13).

The results tables are kept in ``validation/studies/`` (CSV + sidecar; an interrupted run resumes), the figures
go to ``validation/figures/`` and the report to ``validation/STUDIES.md``. Every conclusion sentence of the report
is generated from the numbers, with the reading rules of ``validation/README.md``.
"""
from __future__ import annotations

import argparse
import math
import json
from pathlib import Path
from typing import Dict, List, Optional

import numpy as np

from exudyn_worm.drive.config import ResolveParameters
from exudyn_worm.drive.presets import PRESETS, ApplyOverrides, ElasticDriveFromParameters
from exudyn_worm.model.stability import AnalyzeStability
from exudyn_worm.analysis.studies.study import RunStudy
from exudyn_worm.analysis.studies.studyfiles import StudyResult, StudySidecarPath
from exudyn_worm.analysis.studies.studygrid import ParseVariation, Study

__all__ = ['MAP_DV', 'MapStudy', 'BacklashStudy', 'RunStudies', 'MapAnalysis', 'BacklashAnalysis', 'WriteReport',
           'Main']

HERE = Path(__file__).resolve().parent
#: the two mesh damping measures of Figures 4 and 5
MAP_DV = (0.014, 0.056)
_MAP_J1 = 'J1=0.005:0.6:12:log'          # kg*m^2: P7 (0.01), P3 (0.033), P1 (0.1), P6 (0.2), P2 (0.3) inside
_MAP_KT = 'kT=350:28000:12:log'          # N*m/rad: P7 (700), P5 (1400), P1 (7000), P6 (12000), P4 (14000) inside
_BACKLASH = 'backlash=0,0.1mm,0.2mm,0.25mm,0.3mm,0.4mm,0.5mm,0.6mm,0.7mm,0.75mm,0.8mm,0.9mm,1mm'
_PAPER_BACKLASH = (0.25e-3, 0.5e-3, 0.75e-3)
# the vibration "does not die out" in a phase if it is still above the chatter threshold within the phase's last
# 0.08 s (about three periods of the ~40 Hz chatter; a duration is measured to the last sample above the threshold)
_PERSIST_SECONDS = 0.08
# lift (0-2 s), early lowering (2-3 s), whole lowering (2-6 s), lifting into the next rotation (6-10 s, Fig. 13)
_BACKLASH_WINDOWS = [(0., 2.), (2., 3.), (2., 6.), (6., 10.)]
_LOWERING_SECONDS = 4.                  # duration of the lowering phase at the paper's speed
_REPORT_POINTS = ('reel-P1', 'reel-P2', 'reel-P3', 'reel-P4', 'reel-P5', 'reel-P6', 'reel-P7')


def MapStudy(DV: float) -> Study:
    """The 12 x 12 map of J1 and kT around P1 at mesh damping measure ``DV`` (D_TV = 1).

    Parameters
    ----------
    DV : float
        Damping measure D_V of the mesh (eq. (23)).
    """
    sets = [f'DV={DV}', 'DTV=1']
    return Study(ResolveParameters('reel-P1', sets=sets), [ParseVariation(_MAP_J1), ParseVariation(_MAP_KT)],
                 source=f"preset reel-P1, --set {' '.join(sets)}")


def BacklashStudy(preset: str) -> Study:
    """Backlash 0 ... 1 mm for a reel preset, windows lift / early lowering / lowering / lifting to 10 s.

    Parameters
    ----------
    preset : str
        ``'reel-P1'`` or ``'reel-P7'``.
    """
    return Study(ResolveParameters(preset), [ParseVariation(_BACKLASH)], windows=_BACKLASH_WINDOWS, endTime=10.,
                 source=f'preset {preset}')


def RunStudies(dataDir: Path = HERE / 'studies', workers: Optional[int] = None, quiet: Optional[bool] = None,
               overwrite: bool = False) -> Dict[str, Dict]:
    """Run (or resume) every study; return ``{name: {'result': StudyResult, 'seconds': wall time, 'workers'}}``
    (the wall time summed over the invocations that computed the table, from its sidecar).

    Parameters
    ----------
    dataDir : Path
        Folder of the results tables (created).
    workers : int, optional
        Worker processes (default: every core).
    quiet : bool, optional
        No progress bars.
    overwrite : bool, optional
        Recompute everything instead of resuming the tables in ``dataDir``.
    """
    dataDir.mkdir(parents=True, exist_ok=True)
    studies = {f'map_DV{DV}': MapStudy(DV) for DV in MAP_DV}
    studies.update({f'backlash_{p[5:]}': BacklashStudy(p) for p in ('reel-P1', 'reel-P7')})
    out = {}
    for name, study in studies.items():
        path = dataDir / f'{name}.csv'
        result = RunStudy(study, path, workers=workers, quiet=quiet, overwrite=overwrite)
        meta = json.loads(StudySidecarPath(path).read_text())
        out[name] = {'result': result, 'seconds': meta['wallSeconds'], 'workers': meta['workers']}
    return out


# --------------------------------------------------------------------------------------------- stability map

def _Growth(base, J1, kT) -> float:
    """Largest real part (1/s) of the S = -1 eigenvalues at (J1, kT)."""
    drive = ElasticDriveFromParameters(ApplyOverrides(base, {'J1': J1, 'kT': kT}))
    return float(np.max(AnalyzeStability(drive).contact[-1].eigenvalues.real))


def _CrossingFactor(base, J1, kT, key, stable) -> Optional[float]:
    """Smallest factor (>1 up or <1 down, within 10) by which ``key`` must change for the analytical verdict to flip
    (a scan in 2 % steps, then bisection to 0.01 %)."""
    def Flips(factor):
        point = {'J1': J1, 'kT': kT}
        point[key] *= factor
        return (_Growth(base, point['J1'], point['kT']) < 0) != stable
    previous = 1.
    for f in np.geomspace(1.02, 10., 117):
        for sign in (1, -1):
            if Flips(f ** sign):
                lo, hi = math.log(previous), math.log(f)
                while hi - lo > 1e-4:
                    mid = 0.5 * (lo + hi)
                    lo, hi = (lo, mid) if Flips(math.exp(sign * mid)) else (mid, hi)
                return float(math.exp(sign * hi))
        previous = f
    return None


def MapAnalysis(result: StudyResult) -> Dict:
    """Agreement of a map study with the analytical chart and the location and reason of every disagreement.

    Parameters
    ----------
    result : StudyResult
        A :func:`MapStudy` result.

    Returns
    -------
    dict
        ``agreement``, ``counts`` (both unstable+chatter, both stable+quiet, unstable+quiet, stable+chatter,
        failed), ``disagreements`` (list of dicts with the numbers and a generated explanation), ``nearest`` (the
        six runs closest to the analytical boundary, in decades of J1 or kT), ``chartSame`` (runs where the
        stability chart of :mod:`exudyn_worm.analysis.charts.stabilitychart` gives the same verdict as eqs. (15)-(16)), ``chartDTV``.
    """
    base = result.study.base
    rows = result.finished
    J1s = sorted({r['J1'] for r in result.rows})
    kTs = sorted({r['kT'] for r in result.rows})
    verdict = {(r['J1'], r['kT']): r['analyticStableLowering'] for r in result.rows}
    counts = {'unstable, chatter': 0, 'stable, no chatter': 0, 'unstable, no chatter': 0, 'stable, chatter': 0,
              'failed': len(result.failed)}
    disagreements = []
    for r in rows:
        stable, chatter = r['analyticStableLowering'], r['loweringChatter']
        if chatter not in (True, False):        # 'undecided' or 'unresolved': no verdict to compare
            counts['undecided'] = counts.get('undecided', 0) + 1
            continue
        counts[f"{'stable' if stable else 'unstable'}, {'chatter' if chatter else 'no chatter'}"] += 1
        if chatter != stable:
            continue
        i, j = J1s.index(r['J1']), kTs.index(r['kT'])
        steps = min((max(abs(i - a), abs(j - b)) for (a, J1) in enumerate(J1s) for (b, kT) in enumerate(kTs)
                     if verdict[(J1, kT)] != stable), default=None)
        sigma = _Growth(base, r['J1'], r['kT'])
        d = {'J1': r['J1'], 'kT': r['kT'], 'analyticStable': stable, 'chatter': chatter, 'sigma': sigma,
             'gridSteps': steps,
             'J1Factor': _CrossingFactor(base, r['J1'], r['kT'], 'J1', stable),
             'kTFactor': _CrossingFactor(base, r['J1'], r['kT'], 'kT', stable),
             'fractionSNegative': r['w1.fractionSNegative'], 'maxAcceleration': r['w1.maxAbsWheelAcceleration'],
             'vibrationSeconds': r['w1.vibrationSeconds'], 'window': (r['w1.t0'], r['w1.t1'])}
        d['explanation'] = _Explain(d)
        disagreements.append(d)
    # the runs closest to the analytical boundary (smallest change of J1 or kT that flips the verdict), among
    # those next to a grid point of the other verdict: the test of the agreement is only as sharp as these
    nearest = []
    for r in rows:
        i, j = J1s.index(r['J1']), kTs.index(r['kT'])
        if not any(verdict[(J1s[a], kTs[b])] != r['analyticStableLowering']
                   for a in range(max(i - 1, 0), min(i + 2, len(J1s))) for b in range(max(j - 1, 0), min(j + 2, len(kTs)))):
            continue
        factors = [f for f in (_CrossingFactor(base, r['J1'], r['kT'], key, r['analyticStableLowering'])
                               for key in ('J1', 'kT')) if f is not None]
        if factors:
            decades = min(abs(math.log10(f)) for f in factors)
            nearest.append({'J1': r['J1'], 'kT': r['kT'], 'decades': decades,
                            'analyticStable': r['analyticStableLowering'], 'chatter': r['loweringChatter'],
                            'sigma': _Growth(base, r['J1'], r['kT'])})
    nearest.sort(key=lambda d: d['decades'])
    # the stability chart's own verdict (exudyn_worm.analysis.charts.stabilitychart, vectorized Hurwitz) at every run: the same chart?
    from exudyn_worm.analysis.charts.stabilitychart import ChartCoordinates, UnstableGrid
    drive = ElasticDriveFromParameters(base)
    c = ChartCoordinates(drive)
    x = np.array([r['kT'] for r in result.rows]) / (drive.gear.kV * drive.gear.r1**2)
    y = np.array([r['J1'] for r in result.rows]) / drive.J2
    chart = UnstableGrid(drive.gear, drive.J2, x, y, c['DV'], c['DTV'], S=-1)
    chartSame = int(sum(bool(u) != bool(r['analyticStableLowering']) for u, r in zip(chart, result.rows)))
    return {'agreement': result.agreement, 'counts': counts, 'disagreements': disagreements, 'nearest': nearest[:6],
            'chartSame': chartSame, 'chartDTV': c['DTV']}


def _Where(d) -> str:
    moves = []
    for key, unit in (('J1', 'kg*m^2'), ('kT', 'N*m/rad')):
        f = d[f'{key}Factor']
        if f is not None:
            moves.append(f"{key} {'x' if f > 1 else '/'} {f if f > 1 else 1 / f:.2f}")
    near = ('next to the boundary (the neighbouring grid point has the other analytical verdict)'
            if d['gridSteps'] == 1 else f"{d['gridSteps']} grid steps from the boundary"
            if d['gridSteps'] is not None else 'far from any boundary on this grid')
    return near + ('; the analytical verdict flips with ' + ' or '.join(moves) if moves else
                   '; no change of J1 or kT within a factor 10 flips the analytical verdict')


def _Explain(d) -> str:
    """One generated sentence: where the point sits and which number explains the difference."""
    sigma, t0, t1 = d['sigma'], d['window'][0], d['window'][1]
    where = _Where(d)
    if not d['analyticStable']:        # linear model unstable, simulation quiet
        growth = math.exp(sigma * (t1 - t0))
        if growth < 10:
            why = (f"the growth rate is only sigma = {sigma:.3g} 1/s: over the {t1 - t0:.1f} s of lowering a "
                   f"linear oscillation grows {growth:.3g}-fold, too little to reach the chatter threshold")
        elif d['fractionSNegative'] < 0.9:
            why = (f"the contact is in the state S = -1 only {100 * d['fractionSNegative']:.0f} % of the lowering "
                   f"(the linear S = -1 model applies only then), although sigma = {sigma:.3g} 1/s")
        else:
            why = (f"sigma = {sigma:.3g} 1/s would grow a linear oscillation {growth:.3g}-fold, but the nonlinear "
                   f"contact limits it: max |phi2''| = {d['maxAcceleration']:.3g} rad/s^2 stays below the chatter "
                   f"threshold in the second half of the window")
        return f"Analytically unstable, simulated without chatter: {where}; {why}."
    decay = math.exp(sigma * 0.5 * (t1 - t0))          # left of a transient at the window's midpoint
    if decay > 0.1:
        why = (f"it is weakly damped (sigma = {sigma:.3g} 1/s): the vibration excited at the load reversal decays "
               f"only to {100 * decay:.0f} % by the second half of the lowering, where the chatter rule looks "
               f"(it lasts {d['vibrationSeconds']:.2f} s into the window)")
    else:
        why = (f"sigma = {sigma:.3g} 1/s would damp a small vibration to {100 * decay:.2g} % by the second half of "
               f"the window, yet the simulation keeps vibrating ({d['vibrationSeconds']:.2f} s, max |phi2''| = "
               f"{d['maxAcceleration']:.3g} rad/s^2): a finite-amplitude (nonlinear) instability of the contact, "
               f"which alternates between the flanks (S = -1 only {100 * d['fractionSNegative']:.0f} % of the time)")
    return f"Analytically stable, simulated with chatter: {where}; {why}."


def _PaperPoints(DV: float) -> Dict[str, tuple]:
    """(kT, J1) of P1 ... P7 for the map figure (P6 belongs to D_TV = 2, marked for orientation)."""
    return {name[5:]: (PRESETS[name]['kT'], PRESETS[name]['J1']) for name in _REPORT_POINTS}


def _PaperPointVerdicts(result: StudyResult) -> List[str]:
    """The analytical verdict at P1 ... P7 (D_TV = 1 of the map; P6 also at its own D_TV = 2)."""
    lines = []
    base = result.study.base
    for name in _REPORT_POINTS:
        p = PRESETS[name]
        s = _Growth(base, p['J1'], p['kT'])
        lines.append(f"{name[5:]} (J1 = {p['J1']:g}, kT = {p['kT']:g}): {'unstable' if s > 0 else 'stable'} "
                     f"(sigma = {s:.3g} 1/s)")
    return lines


# --------------------------------------------------------------------------------------------- backlash

def BacklashAnalysis(result: StudyResult) -> Dict:
    """The backlash curves of one preset and the numbers behind the paper's statements.

    Parameters
    ----------
    result : StudyResult
        A :func:`BacklashStudy` result.

    Returns
    -------
    dict
        Arrays ``backlash`` (m), ``forceEarly``, ``forceLowering``, ``forceRotation`` (N), ``accelerationEarly``,
        ``accelerationLowering`` (rad/s^2), ``liftingVibration`` (s), ``liftingChatter`` (bool), ``failed``.
    """
    rows = sorted(result.finished, key=lambda r: r['backlash'])
    col = lambda name: np.array([r[name] for r in rows], float)
    return {'backlash': col('backlash'), 'forceEarly': col('w1.maxNormalForce'),
            'forceLowering': col('w2.maxNormalForce'),
            'forceRotation': np.max([col(f'w{i}.maxNormalForce') for i in (0, 2, 3)], axis=0),
            'accelerationEarly': col('w1.maxAbsWheelAcceleration'),
            'accelerationLowering': col('w2.maxAbsWheelAcceleration'),
            'liftingVibration': col('w3.vibrationSeconds'),
            'liftingChatter': np.array([r['w3.chatter'] is True for r in rows]),     # undecided: no
            'failed': len(result.failed)}


def _At(a, key, backlash):
    i = int(np.argmin(np.abs(a['backlash'] - backlash)))
    return a[key][i] if abs(a['backlash'][i] - backlash) < 1e-9 else math.nan


def _BacklashConclusions(p1: Dict, p7: Dict) -> List[str]:
    """Generated sentences beside the paper's statements (reading rules of validation/README.md)."""
    lines = []
    # P1, Figure 12: "2-4 times bigger" peak normal force in the early lowering with backlash
    ratios = [_At(p1, 'forceEarly', b) / _At(p1, 'forceEarly', 0.) for b in _PAPER_BACKLASH]
    inside = all(2 <= r <= 4 for r in ratios)
    lines.append(
        "P1 (paper, Fig. 12: with backlash the peak normal force early in the lowering is \"2-4 times bigger\", "
        "read as the interval [2, 4]): our ratios for 0.25 / 0.5 / 0.75 mm are "
        + ' / '.join(f'{r:.2f}' for r in ratios) + f" -> {'all inside' if inside else 'not all inside'} [2, 4]. "
        f"Over 0 ... 1 mm the early peak goes from {p1['forceEarly'][0] / 1e3:.1f} kN to "
        f"{p1['forceEarly'][-1] / 1e3:.1f} kN (largest {np.max(p1['forceEarly']) / 1e3:.1f} kN at "
        f"{1e3 * p1['backlash'][np.argmax(p1['forceEarly'])]:.2f} mm); over the whole lowering from "
        f"{p1['forceLowering'][0] / 1e3:.1f} kN to {p1['forceLowering'][-1] / 1e3:.1f} kN.")
    # P7, Figure 17: "about 280 kN", "virtually independent of the backlash in the interval from 0 to 0.75 mm"
    sel = p7['backlash'] <= 0.75e-3 + 1e-12
    force = p7['forceRotation'][sel]
    spread = float(np.max(force) / np.min(force))
    lines.append(
        f"P7 (paper, Fig. 17: the maximum normal force, \"about 280 kN\", is \"virtually independent\" of the "
        f"backlash from 0 to 0.75 mm, read as largest / smallest <= 1.10): our peak over the rotation is "
        f"{np.min(force) / 1e3:.0f} ... {np.max(force) / 1e3:.0f} kN, largest / smallest = {spread:.3f} -> "
        f"{'independent within the reading' if spread <= 1.10 else 'NOT independent within the reading'}; "
        f"{'inside' if all(abs(f / 280e3 - 1) <= 0.10 for f in force) else 'not all inside'} 280 kN +- 10 % "
        f"(\"about\"). Over the whole lowering the peak is {np.min(p7['forceLowering'][sel]) / 1e3:.0f} ... "
        f"{np.max(p7['forceLowering'][sel]) / 1e3:.0f} kN, in the early lowering "
        f"{np.min(p7['forceEarly'][sel]) / 1e3:.0f} ... {np.max(p7['forceEarly'][sel]) / 1e3:.0f} kN.")
    # P7: "the bigger the backlash, the earlier the vibration dies out in the lifting phase"
    whole = p7['liftingVibration']
    phase = _BACKLASH_WINDOWS[-1][1] - _BACKLASH_WINDOWS[-1][0]
    persists = whole >= phase - _PERSIST_SECONDS
    paper = [_At(p7, 'liftingVibration', b) for b in (0.,) + _PAPER_BACKLASH]
    decreasing = all(a > b for a, b in zip(paper, paper[1:]))
    dying = whole[~persists]
    bDying = p7['backlash'][~persists]
    orderedDying = bool(np.all(np.diff(dying) < 0))
    upper = bool(np.all(persists[:np.argmin(persists)] if not persists.all() else persists)
                 and not np.any(persists[np.argmin(persists):]))
    sentence = ("P7 (paper: \"the bigger the backlash, the earlier the vibration dies out in the lifting phase\", "
                "read as a strictly decreasing duration): the vibration lasts "
                + ' / '.join(f'{s:.2f}' for s in paper) + f" s into the lifting phase (6-10 s, {phase:.0f} s long) for "
                "0 / 0.25 / 0.5 / 0.75 mm -> " + ('strictly decreasing, as the paper says. ' if decreasing else
                                                  'NOT strictly decreasing. '))
    if persists.any():
        sentence += (f"The vibration does not die out at all in the lifting phase (still above the chatter threshold "
                     f"within its last {_PERSIST_SECONDS:g} s) for backlash "
                     + ', '.join(f'{1e3 * b:g}' for b in p7['backlash'][persists]) + ' mm. ')
    if dying.size:
        sentence += ("It dies out for " + ', '.join(f'{1e3 * b:g}' for b in bDying) + " mm after "
                     + ', '.join(f'{s:.2f}' for s in dying) + " s: "
                     + ('the bigger the backlash, the earlier, as the paper says, ' if orderedDying and dying.size > 1
                        else '') + ('and only above a backlash threshold' if upper and persists.any() else '')
                     + '.')
    else:
        sentence += 'It dies out for no backlash value up to 1 mm.'
    lines.append(sentence.replace(', .', '.').replace(': .', '.'))
    return lines


# --------------------------------------------------------------------------------------------- report

def _Figures(results, figures: Path) -> Dict[str, Path]:
    from exudyn_worm.plotting import plot
    from exudyn_worm.plotting import plot_study
    from exudyn_worm.plotting.plot import _NewFigure
    figures.mkdir(parents=True, exist_ok=True)
    paths = {}
    for DV in MAP_DV:
        result = results[f'map_DV{DV}']['result']
        fig = result.plot('kT', 'J1', labels=_PaperPoints(DV),
                          title=f'D_V = {DV}, D_TV = 1: simulated chatter while lowering\nover the '
                                f'analytical S = -1 region (agreement {100 * result.agreement:.0f} %)')
        paths[f'map_DV{DV}'] = plot.SaveFigure(fig, figures / f'stability_map_DV{DV}.png')
    fig, axes = _NewFigure(2, 2, figsize=(10., 7.), sharex=True)
    for ax, metric in zip(axes.flat, ('w1.maxNormalForce', 'w2.maxNormalForce', 'w1.maxAbsWheelAcceleration',
                                      'w2.maxAbsWheelAcceleration')):
        for name in ('P1', 'P7'):
            plot_study.PlotMetric(results[f'backlash_{name}']['result'], 'backlash', metric, ax=ax, label=name,
                                  title={'w1': 'early lowering (2-3 s)', 'w2': 'whole lowering (2-6 s)'}[metric[:2]])
        ax.legend(fontsize='small')
    paths['backlash'] = plot.SaveFigure(fig, figures / 'backlash_curves.png')
    fig = plot_study.PlotMetric(results['backlash_P7']['result'], 'backlash', 'w3.vibrationSeconds', label='P7',
                                title='P7: how long the vibration lasts into the lifting phase (6-10 s)')
    paths['lifting'] = plot.SaveFigure(fig, figures / 'backlash_lifting_P7.png')
    return paths


def WriteReport(results: Dict[str, Dict], path: Path = HERE / 'STUDIES.md', figures: Path = HERE / 'figures') -> Path:
    """Write the Markdown report of the studies (and its figures).

    Parameters
    ----------
    results : dict
        Output of :func:`RunStudies`.
    path : Path
        The report file.
    figures : Path
        Folder of the PNG figures.

    Returns
    -------
    Path
        ``path``.
    """
    figurePaths = _Figures(results, figures)
    rel = lambda p: Path(p).resolve().relative_to(path.resolve().parent).as_posix()
    L = ['# Parameter studies: the simulation-confirmed stability map and the backlash curves', '',
         'Generated by `python -m validation.studies` (see `validation/README.md`); every sentence with a number is '
         'computed from the study tables in `validation/studies/`. Chatter is the rule of `exudyn-worm simulate` '
         '(`SimulationResult.Chatter`); the analytical verdict is the S = -1 stability of eqs. (15)-(16) for the '
         'same parameter set.', '']
    L += ['## The stability map (Figures 4 and 5, confirmed by simulation)', '',
          'The paper: "the conclusions drawn from the stability charts can be confirmed by numerical simulation". '
          'Grid: J1 = 0.005 ... 0.6 kg*m^2 and kT = 350 ... 28000 N*m/rad, 12 log-spaced values each (144 runs per '
          'map, one rotation each), around P1 and spanning P2 ... P7; D_TV = 1 (the chart line through P1; P6 lies '
          'on the D_TV = 2 line and is marked for orientation only).', '']
    for DV in MAP_DV:
        entry = results[f'map_DV{DV}']
        result = entry['result']
        a = MapAnalysis(result)
        c = a['counts']
        judged = sum(v for k, v in c.items() if k != 'failed')
        L += [f'### D_V = {DV}', '',
              f"![stability map D_V = {DV}]({rel(figurePaths[f'map_DV{DV}'])})", '',
              f"{len(result.rows)} runs ({c['failed']} failed), wall time {entry['seconds']:.0f} s with {entry['workers']} "
              f"worker processes on a 2-core machine. "
              f"Agreement of the simulated chatter while lowering with the analytical S = -1 verdict: "
              f"**{100 * a['agreement']:.1f} %** ({judged - len(a['disagreements'])} of {judged} runs).", '',
              '| | simulation: chatter | simulation: no chatter |', '|---|---|---|',
              f"| analytical: unstable | {c['unstable, chatter']} | {c['unstable, no chatter']} |",
              f"| analytical: stable | {c['stable, chatter']} | {c['stable, no chatter']} |", '',
              f"The stability chart of `exudyn_worm.analysis.charts.stabilitychart` (D_V = {DV}, D_TV = {a['chartDTV']:g}, x = kT/(kV r1^2), "
              f"y = J1/J2) gives the same verdict as eqs. (15)-(16) at {a['chartSame']} of the {len(result.rows)} runs; "
              f"its boundary is the line in the figure.", '',
              'Analytical verdicts at the paper\'s points on this map: '
              + '; '.join(_PaperPointVerdicts(result)) + '.', '']
        if a['disagreements']:
            L += [f"Every disagreement ({len(a['disagreements'])}):", '',
                  '| J1 [kg*m^2] | kT [N*m/rad] | analytical | simulated | sigma [1/s] | explanation |',
                  '|---|---|---|---|---|---|']
            for d in a['disagreements']:
                L.append(f"| {d['J1']:.4g} | {d['kT']:.4g} | {'stable' if d['analyticStable'] else 'unstable'} | "
                         f"{'chatter' if d['chatter'] else 'no chatter'} | {d['sigma']:.3g} | {d['explanation']} |")
            near = sum(d['gridSteps'] == 1 for d in a['disagreements'])
            L += ['', f"{near} of the {len(a['disagreements'])} disagreements sit next to the analytical boundary "
                      f"(a neighbouring grid point has the other verdict); "
                      f"{len(a['disagreements']) - near} lie further inside a region.", '']
        else:
            L += ['No disagreement: every run chatters while lowering exactly where the linear model is unstable.', '']
        agreeNear = sum(d['chatter'] != d['analyticStable'] for d in a['nearest'])
        L += [f"The runs closest to the analytical boundary (the change of J1 or kT alone that flips the analytical "
              f"verdict, in decades; the grid step is {math.log10(result.study.variations[0].values[1] / result.study.variations[0].values[0]):.3f} "
              f"decades in J1 and {math.log10(result.study.variations[1].values[1] / result.study.variations[1].values[0]):.3f} in kT): "
              f"the simulation agrees for {agreeNear} of these {len(a['nearest'])}.", '',
              '| J1 [kg*m^2] | kT [N*m/rad] | decades to the boundary | sigma [1/s] | analytical | simulated |',
              '|---|---|---|---|---|---|']
        L += [f"| {d['J1']:.4g} | {d['kT']:.4g} | {d['decades']:.3f} | {d['sigma']:.3g} | "
              f"{'stable' if d['analyticStable'] else 'unstable'} | {'chatter' if d['chatter'] else 'no chatter'} |"
              for d in a['nearest']]
        L.append('')
    p1, p7 = (BacklashAnalysis(results[f'backlash_{n}']['result']) for n in ('P1', 'P7'))
    L += ['## The backlash curves (Figures 12 and 17 as curves)', '',
          f"Backlash 0 ... 1 mm ({len(p1['backlash'])} values, with the paper's 0.25 / 0.5 / 0.75 mm), P1 and P7, "
          f"simulated to 10 s (windows: lift 0-2 s, early lowering 2-3 s, lowering 2-6 s, lifting 6-10 s). "
          f"Failed runs: P1 {p1['failed']}, P7 {p7['failed']}.", '',
          f"![backlash curves]({rel(figurePaths['backlash'])})", '',
          f"![P7 lifting]({rel(figurePaths['lifting'])})", '',
          '| backlash [mm] | P1 Fn 2-3 s [kN] | P1 Fn 2-6 s [kN] | P1 max phi2\'\' 2-3 s | P1 max phi2\'\' 2-6 s | '
          'P7 Fn 2-3 s [kN] | P7 Fn 2-6 s [kN] | P7 max phi2\'\' 2-3 s | P7 max phi2\'\' 2-6 s | '
          'P7 vibration into lifting [s] |', '|' + '---|' * 10]
    for i, b in enumerate(p1['backlash']):
        j = int(np.argmin(np.abs(p7['backlash'] - b)))
        L.append(f"| {1e3 * b:.2f} | {p1['forceEarly'][i] / 1e3:.1f} | {p1['forceLowering'][i] / 1e3:.1f} | "
                 f"{p1['accelerationEarly'][i]:.0f} | {p1['accelerationLowering'][i]:.0f} | "
                 f"{p7['forceEarly'][j] / 1e3:.1f} | {p7['forceLowering'][j] / 1e3:.1f} | "
                 f"{p7['accelerationEarly'][j]:.0f} | {p7['accelerationLowering'][j]:.0f} | "
                 f"{p7['liftingVibration'][j]:.2f} |")
    L += ['', 'Beside the paper\'s statements:', '']
    L += [f'- {line}' for line in _BacklashConclusions(p1, p7)]
    L.append('')
    path.write_text('\n'.join(L))
    return path


def Main(argv=None) -> int:
    """Command line: run or resume the studies, write the figures and ``validation/STUDIES.md``.

    Parameters
    ----------
    argv : list of str, optional
        Arguments (default: ``sys.argv[1:]``).
    """
    parser = argparse.ArgumentParser(prog='python -m validation.studies', description=__doc__.split('\n')[0])
    parser.add_argument('--workers', type=int, default=None, help='worker processes (default: every core)')
    parser.add_argument('--quiet', action='store_true', help='no progress bars')
    parser.add_argument('--overwrite', action='store_true', help='recompute instead of resuming the tables')
    parser.add_argument('--report', default=str(HERE / 'STUDIES.md'), help='report path')
    args = parser.parse_args(argv)
    results = RunStudies(workers=args.workers, quiet=True if args.quiet else None, overwrite=args.overwrite)
    path = WriteReport(results, Path(args.report))
    print(f'wrote {path}')
    return 0


if __name__ == '__main__':
    raise SystemExit(Main())
