"""The paper's paper-reel changer (section 3.2): simulate it and draw Figures 8-18.

The reel (m2 = 175 kg on a lever l2 = 1.2 m) is turned by a worm drive whose motor runs at 472.5 rpm,
so the frame makes one full rotation in 8 s: it starts horizontal, is lifted for 2 s, lowered for
4 s and lifted again for 2 s. Parameter set (28) is the chart point P1 (chatter while lowering),
P7 has ten times smaller J1 and kT (chatter also while lifting), P2 has J1 tripled (stable).

============  =================================  =========================================
figure        case                               file
============  =================================  =========================================
8, 9, 10, 11  ``--preset`` (P1), ``--backlash``  fig08_P1_acceleration.png, ...
12            ``--preset``, 0.25/0.5/0.75 mm     fig12_P1_backlash_normalForce.png
13-16         P7                                 fig13_P7_acceleration.png, ...
17            P7, 0.25/0.5/0.75 mm               fig17_P7_backlash_normalForce.png
18            P2                                 fig18_P2_driveTorque.png
============  =================================  =========================================

``--speed`` and ``--load`` change the operating point of every case; ``--backlash`` replaces the
paper's zero backlash of the single-case figures (the backlash studies keep 0.25, 0.5, 0.75 mm).
Every case runs one full rotation (8 s) except P7 (Figures 13-17), which runs 1.25 rotations (10 s)
to show the whole second lifting phase, 6-10 s, that the paper discusses; ``--end-time`` sets all.

Run ``python examples/paper_reel_changer.py`` (all figures) or e.g.
``python examples/paper_reel_changer.py --figures 8,9 --backlash 0.25 --out /tmp/reel``.
The computation (:func:`RunPaperCases`, :func:`Summary`) is importable and checked by
``tests/test_example_reel_changer.py``; only :func:`main` writes files.
"""
from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import Dict, Iterable, List, Mapping, Optional, Sequence

from exudyn_worm.drive.presets import REEL_KEYS, ApplyOverrides, ElasticDriveFromParameters, GetPreset
from exudyn_worm.analysis.simulation.reelchanger import DEFAULT_STEP_SIZE, RotationPeriod, SimulateReelChanger
from exudyn_worm.items.results import SimulationResult
from exudyn_worm.drive.wholedrive import ResolveDrive
from exudyn_worm.params.parameters import PARAMETERS

__all__ = ['PAPER_FIGURES', 'BACKLASH_STUDY', 'RPM', 'CaseParameters', 'RunPaperCases', 'Summary',
           'FormatSummary', 'WriteFigures', 'DifferenceFromP1', 'main']

#: rad/s per rpm
RPM = 2 * math.pi / 60
#: backlashes of the paper's Figures 12 and 17, m
BACKLASH_STUDY = (0.25e-3, 0.5e-3, 0.75e-3)
#: figure number -> (case group, what is drawn); groups: 'main' (the --preset, P1 in the paper),
#: 'mainBacklash', 'P7', 'P7Backlash', 'P2'
PAPER_FIGURES = {8: ('main', 'acceleration'), 9: ('main', 'zoom'), 10: ('main', 'speed'),
                 11: ('main', 'normalForce'), 12: ('mainBacklash', 'normalForce'),
                 13: ('P7', 'acceleration'), 14: ('P7', 'zoom'), 15: ('P7', 'speed'), 16: ('P7', 'zoom'),
                 17: ('P7Backlash', 'normalForce'), 18: ('P2', 'driveTorque')}

# zoom intervals in s (the paper gives 7.9-8 s for Fig. 16; the others are not printed: 0.1 s in the
# middle of the lowering, where the load torque is largest); Fig. 15 shows the lowering
_ZOOM = {9: (4.0, 4.1), 14: (4.0, 4.1), 15: (4.0, 4.1), 16: (7.9, 8.0)}
_PAPER_PERIOD = 8.      # s, the rotation of the zoom times above (472.5 rpm; 8.0003 s with u = 63.002)
#: fewest solver steps in a quarter rotation (one lift phase) for the windows to mean something
MIN_STEPS_PER_PHASE = 100
_CAPTIONS = {
    8: r'wheel acceleration $\ddot\varphi_2$',
    9: r'$\ddot\varphi_2$ (zoom of Fig. 8) and contact parameter $S$',
    10: r'worm speed $\dot\varphi_1$ and friction state $s_f$',
    11: 'normal forces on the two tooth flanks',
    12: 'normal force for backlash 0.25, 0.5, 0.75 mm',
    13: r'wheel acceleration $\ddot\varphi_2$ (the paper: chatter also while lifting)',
    14: r'$\ddot\varphi_2$ and $S$ while lowering (zoom of Fig. 13)',
    15: r'worm speed $\dot\varphi_1$ and friction state $s_f$ while lowering',
    16: r'$\ddot\varphi_2$ and $S$ while lifting (zoom of Fig. 13)',
    17: 'normal force for backlash 0.25, 0.5, 0.75 mm',
    18: r'drive shaft torque $M_{an}$ and contact parameter $S$ (the paper: stable)',
}
_WINDOW_NAMES = ('lift', 'lower', 'lift')
# simulated rotations per case group (default 1): P7 keeps chattering while lifting, which the paper
# follows through the whole lifting phase 6-10 s
_ROTATIONS = {'P7': 1.25, 'P7Backlash': 1.25}


def _Short(preset: str) -> str:
    """'reel-P1' -> 'P1'."""
    return preset.split('-', 1)[-1] if preset.startswith('reel-') else preset


def _BacklashLabel(short: str, backlash: float) -> str:
    return f'{short} δ={backlash * 1e3:g}mm'


def _Groups(where: str, figures: Optional[Iterable[int]]) -> List[str]:
    figures = sorted(PAPER_FIGURES) if figures is None else list(figures)
    bad = [f for f in figures if f not in PAPER_FIGURES]
    if bad:
        raise ValueError(f"{where}: 'figures' must be among {min(PAPER_FIGURES)}..{max(PAPER_FIGURES)}, "
                         f"got {bad[0]!r}")
    groups = []
    for f in figures:
        g = PAPER_FIGURES[f][0]
        if g not in groups:
            groups.append(g)
    return groups


def CaseParameters(preset: str = 'reel-P1', backlash: float = 0., motorSpeed: Optional[float] = None,
                   loadMass: Optional[float] = None,
                   figures: Optional[Iterable[int]] = None) -> Dict[str, Dict[str, float]]:
    """Parameter sets of the cases the requested figures need, keyed by case label.

    The P7 cases (Figures 13-17) carry ``rotations = 1.25``: they are simulated to 10 s at the paper's
    speed, so the whole second lifting phase (6-10 s in the paper's text on Fig. 13) is shown; all
    other cases run one full rotation (8 s). The key ``rotations`` is not a model parameter; it is
    removed before the parameters reach the simulation.

    Parameters
    ----------
    preset : str
        Preset of Figures 8-12 (the paper: ``'reel-P1'``, parameter set (28)).
    backlash : float
        Backlash in m of the single-case figures 8-11, 13-16, 18 (paper: 0). >= 0.
    motorSpeed : float, optional
        Motor speed in rad/s for every case (paper: 472.5 rpm).
    loadMass : float, optional
        Reel mass in kg for every case (paper: 175 kg).
    figures : iterable of int, optional
        Paper figure numbers 8-18 (default: all).

    Returns
    -------
    dict
        Label (``'P1'``, ``'P1 δ=0.25mm'``, ``'P7'``, ...) -> flat parameter dict.

    Raises
    ------
    ValueError, TypeError
        For an unknown preset or figure, or a bad backlash, speed or mass.
    """
    w = 'CaseParameters'
    if isinstance(backlash, bool) or not isinstance(backlash, (int, float)):
        raise TypeError(f"{w}: 'backlash' must be a number in m, got {type(backlash).__name__} {backlash!r}")
    if not backlash >= 0:
        raise ValueError(f"{w}: 'backlash' must be >= 0 m, got {backlash:g} m")
    operating = {}
    if motorSpeed is not None:
        operating['motorSpeed'] = motorSpeed
    if loadMass is not None:
        operating['loadMass'] = loadMass
    main = _Short(preset)
    base = {'main': GetPreset(preset), 'P7': GetPreset('reel-P7'), 'P2': GetPreset('reel-P2')}
    missing = [k for k in REEL_KEYS if k not in base['main']]
    if missing:
        raise ValueError(f"{w}: preset {preset!r} is not a reel-changer preset (it has no "
                         f"{', '.join(missing)}); use one of reel-P1 ... reel-P7")
    cases = {}
    for group in _Groups(w, figures):
        rotations = _ROTATIONS.get(group, 1.)
        if group in ('main', 'P7', 'P2'):
            label = main if group == 'main' else group
            cases[label] = {**ApplyOverrides(base[group], {**operating, 'backlash': float(backlash)}),
                            'rotations': max(rotations, cases.get(label, {}).get('rotations', 1.))}
        else:
            short = main if group == 'mainBacklash' else 'P7'
            params = base['main' if group == 'mainBacklash' else 'P7']
            for b in BACKLASH_STUDY:
                label = _BacklashLabel(short, b)
                cases[label] = {**ApplyOverrides(params, {**operating, 'backlash': b}),
                                'rotations': max(rotations, cases.get(label, {}).get('rotations', 1.))}
    for case in cases.values():                    # validate now: bad input fails before any simulation
        params = {k: v for k, v in case.items() if k != 'rotations'}     # not a model parameter
        RotationPeriod(ResolveDrive(parameters=params))
        ElasticDriveFromParameters(params)
        if params['loadMass'] < 0 or not math.isfinite(params['loadMass']):
            raise ValueError(f"{w}: 'loadMass' must be >= 0 kg, got {params['loadMass']:g} kg")
    return cases


def RunPaperCases(preset: str = 'reel-P1', backlash: float = 0., motorSpeed: Optional[float] = None,
                  loadMass: Optional[float] = None, figures: Optional[Iterable[int]] = None,
                  endTime: Optional[float] = None, stepSize: float = DEFAULT_STEP_SIZE,
                  progress: Optional[bool] = None) -> Dict[str, SimulationResult]:
    """Simulate the reel-changer cases of the paper's Figures 8-18.

    Parameters
    ----------
    preset, backlash, motorSpeed, loadMass, figures
        See :func:`CaseParameters` (SI units: m, rad/s, kg).
    endTime : float, optional
        Simulated time in s for every case (default: one full rotation, 8 s at the paper's speed;
        1.25 rotations, 10 s, for P7, see :func:`CaseParameters`).
    stepSize : float
        Time step in s.
    progress : bool or None
        Progress bar over the cases on stderr: True shown, False never, None (default) when stderr is a
        terminal and the cases take longer than about 2 s.

    Returns
    -------
    dict
        Case label -> :class:`SimulationResult`; ``result.info['parameters']`` holds the parameter set
        and ``result.info['windows']`` the lift / lower / lift windows (lift 0-T/4, lower T/4-3T/4,
        lift 3T/4-5T/4, cut at the end time, T the rotation period).

    Raises
    ------
    ValueError, TypeError
        For bad input (see :func:`CaseParameters`, :func:`SimulateReelChanger`).
    """
    from exudyn_worm.progress import ProgressBar
    results = {}
    cases = CaseParameters(preset, backlash, motorSpeed, loadMass, figures)
    bar = ProgressBar(total=len(cases), desc='paper cases', unit='case', delay=2.,
                      quiet=None if progress is None else not progress)
    for label, case in cases.items():
        bar.set_postfix_str(label)
        params = {k: v for k, v in case.items() if k != 'rotations'}
        drive = ResolveDrive(parameters=params)        # the case's drive, resolved once
        period = RotationPeriod(drive)
        if period / 4 < MIN_STEPS_PER_PHASE * stepSize:
            fastest = params['motorSpeed'] * period / (4 * MIN_STEPS_PER_PHASE * stepSize) / RPM
            raise ValueError(f"--speed: at {params['motorSpeed'] / RPM:g} rpm a quarter rotation (one lift or "
                             f"lowering phase) takes {period / 4:.3g} s, fewer than {MIN_STEPS_PER_PHASE} steps of "
                             f"{stepSize:g} s; at most {fastest:.4g} rpm")
        result = SimulateReelChanger(drive, endTime=case['rotations'] * period if endTime is None else endTime,
                                     stepSize=stepSize, progress=False)
        bar.update(1)
        edges = (0., period / 4, 3 * period / 4, 5 * period / 4)
        windows = [(a, min(b, result.endTime)) for a, b in zip(edges[:-1], edges[1:]) if a < result.endTime]
        result.info.update(parameters=params, windows=windows)
        results[label] = result
    bar.close()
    return results


def Summary(results: Mapping[str, SimulationResult]) -> List[Dict]:
    """One row per case and lift / lower / lift window with the chatter metrics.

    Returns
    -------
    list of dict
        Keys: case, window ('lift' / 'lower'), t0, t1, maxAbsWheelAcceleration (rad/s^2),
        maxNormalForce (N), dominantFrequencyHz, fractionSNegative, minWormSpeed (rad/s), chatter.
    """
    rows = []
    for label, result in results.items():
        windows = result.info.get('windows')
        if windows is None:
            quarter = result.endTime / 4           # a result not from RunPaperCases: one rotation assumed
            windows = [(0., quarter), (quarter, 3 * quarter), (3 * quarter, result.endTime)]
        for name, metrics in zip(_WINDOW_NAMES, result.WindowMetrics(windows)):
            rows.append({'case': label, 'window': name, **metrics})
    return rows


def FormatSummary(rows: Sequence[Mapping]) -> str:
    """The rows of :func:`Summary` as a fixed-width text table."""
    head = (f"{'case':<13} {'window':<6} {'t [s]':>9}  {'max|phi2dd|':>11} {'max Fn':>9} "
            f"{'f_dom':>7} {'S<0':>5} {'chatter':>7}")
    units = f"{'':<13} {'':<6} {'':>9}  {'[rad/s^2]':>11} {'[kN]':>9} {'[Hz]':>7} {'[%]':>5}"
    lines = [head, units, '-' * len(head)]
    for r in rows:
        lines.append(f"{r['case']:<13} {r['window']:<6} {r['t0']:4.1f}-{r['t1']:<4.1f}  "
                     f"{r['maxAbsWheelAcceleration']:11.1f} {r['maxNormalForce'] * 1e-3:9.1f} "
                     f"{r['dominantFrequencyHz']:7.1f} {100 * r['fractionSNegative']:5.0f} "
                     f"{'yes' if r['chatter'] else 'no':>7}")
    return '\n'.join(lines)


#: keys the subtitle gives as the run's conditions, not as a difference from P1
_CONDITION_KEYS = ('backlash', 'motorSpeed', 'loadMass')


def DifferenceFromP1(params: Mapping[str, float]) -> str:
    """What a case's parameter set changes of P1 (set (28)), e.g. ``'J1 = 0.01 kg·m² (P1: 0.1), kT = 700 N·m/rad
    (P1: 7000)'``; empty for P1 itself. The operating conditions (backlash, speed, reel mass) are left out: the
    subtitles give them.

    Parameters
    ----------
    params : mapping
        The case's flat parameter set (SI units).

    Returns
    -------
    str
    """
    reference = GetPreset('reel-P1')
    parts = []
    for key in params:
        if key in _CONDITION_KEYS or key == 'rotations' or reference.get(key) == params[key]:
            continue
        unit = PARAMETERS.Get(key).unit.replace('*', '·').replace('^2', '²') if key in PARAMETERS else ''
        value = f'{key} = {params[key]:g}' + (f' {unit}' if unit else '')
        parts.append(value + (f' (P1: {reference[key]:g})' if key in reference else ''))
    parts += [f'no {key} (P1: {reference[key]:g})' for key in reference
              if key not in params and key not in _CONDITION_KEYS]
    return ', '.join(parts)


def _CaseLine(label: str, params: Mapping[str, float]) -> str:
    """The subtitle's case: ``'P7 = P1 with J1 = 0.01 kg·m² (P1: 0.1), ...'``, or the label for P1."""
    differences = DifferenceFromP1(params)
    return f'{label} = P1 with {differences}' if differences else f"{label}: the paper's set (28)"


def _Conditions(params: Mapping[str, float]) -> str:
    return (f"$\\delta$ = {params.get('backlash', 0.) * 1e3:g} mm, $n_0$ = {params['motorSpeed'] / RPM:.4g} rpm, "
            f"$m_2$ = {params['loadMass']:g} kg")


def WriteFigures(results: Mapping[str, SimulationResult], outDir, figures: Optional[Iterable[int]] = None,
                 preset: str = 'reel-P1') -> List[Path]:
    """Draw the requested paper figures from ``results`` of :func:`RunPaperCases` and save them as PNG.

    Returns
    -------
    list of Path
        The files written, in figure order.
    """
    from exudyn_worm.plotting.plot import PlotComparison, PlotSimulation, SaveFigure

    outDir = Path(outDir)
    main = _Short(preset)
    written = []
    for number in (sorted(PAPER_FIGURES) if figures is None else sorted(figures)):
        group, kind = PAPER_FIGURES[number]
        caption = f'Fig. {number}: {_CAPTIONS[number]}'
        if number == 8:                   # what the figure spans: a rotation, or the --end-time given
            result = results[main]
            period = RotationPeriod(ResolveDrive(parameters=result.info['parameters']))
            caption += (' (one full rotation)' if abs(result.endTime - period) < 1e-6 * period
                        else f' ({result.endTime / period:.3g} rotations, {result.endTime:g} s)')
        if group in ('mainBacklash', 'P7Backlash'):
            short = main if group == 'mainBacklash' else 'P7'
            subset = {_BacklashLabel(short, b).replace('δ=', 'δ = ').replace('mm', ' mm'):
                      results[_BacklashLabel(short, b)] for b in BACKLASH_STUDY}
            params = next(iter(subset.values())).info['parameters']
            fig = PlotComparison(subset, quantity=kind,
                                 title=f'{caption}\n{_CaseLine(short, params)}\n$n_0$ = '
                                       f'{params["motorSpeed"] / RPM:.4g} rpm, $m_2$ = {params["loadMass"]:g} kg')
            name = f'fig{number:02d}_{short}_backlash_{kind}.png'
        else:
            label = main if group == 'main' else group
            result = results[label]
            tZoom = _ZOOM.get(number)
            if tZoom is not None:         # the same phase of the rotation at another speed (0.1 s wide)
                start = tZoom[0] * RotationPeriod(ResolveDrive(parameters=result.info['parameters'])) / _PAPER_PERIOD
                tZoom = (start, start + tZoom[1] - tZoom[0])
            if tZoom is not None and tZoom[0] >= result.endTime:
                tZoom = None if kind != 'zoom' else (max(0., result.endTime - 0.1), result.endTime)
            fig = PlotSimulation(result, kind=kind, tZoom=tZoom,
                                 title=f"{caption}\n{_CaseLine(label, result.info['parameters'])}\n"
                                       f"{_Conditions(result.info['parameters'])}")
            suffix = {14: '_lowering', 15: '_lowering', 16: '_lifting'}.get(number, '')
            name = f'fig{number:02d}_{label}_{kind}{suffix}.png'
        written.append(SaveFigure(fig, outDir / name))
    return written


def _ParseFigures(text: str) -> List[int]:
    if text.strip().lower() == 'all':
        return sorted(PAPER_FIGURES)
    try:
        numbers = sorted({int(part) for part in text.replace(',', ' ').split()})
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected figure numbers like '8,9,12' or 'all', got {text!r}") from None
    bad = [n for n in numbers if n not in PAPER_FIGURES]
    if bad or not numbers:
        raise argparse.ArgumentTypeError(f"figures must be among {min(PAPER_FIGURES)}..{max(PAPER_FIGURES)}, "
                                         f"got {text!r}")
    return numbers


class _Parser1Line(argparse.ArgumentParser):
    """Argument errors as one line on stderr (exit status 2), without the usage block."""

    def error(self, message):
        self.exit(2, f'{self.prog}: error: {message} (see --help)\n')


def _Parser() -> argparse.ArgumentParser:
    p = _Parser1Line(prog='paper_reel_changer.py', description=__doc__.split('\n\n')[0])
    p.add_argument('--preset', default='reel-P1', help='parameter set of Figures 8-12, reel-P1 ... reel-P7 (default: reel-P1)')
    p.add_argument('--backlash', type=float, default=0., metavar='MM',
                   help='backlash in mm of the single-case figures 8-11, 13-16, 18 (default: 0)')
    p.add_argument('--speed', type=float, default=None, metavar='RPM', help="motor speed in rpm (default: the preset's, the paper's 472.5)")
    p.add_argument('--load', type=float, default=None, metavar='KG', help="reel mass in kg (default: the preset's, the paper's 175)")
    p.add_argument('--end-time', type=float, default=None, metavar='S',
                   help='simulated time in s (default: one full rotation)')
    p.add_argument('--out', default='reel_changer_output', metavar='DIR',
                   help='folder for the PNG files, created if missing (default: reel_changer_output)')
    p.add_argument('--figures', type=_ParseFigures, default=None, metavar='LIST',
                       help="paper figures to draw, e.g. '8,9,12' or 'all' (default: all, 8-18)")
    p.add_argument('--quiet', action='store_true', help='no progress bar on stderr')
    p.add_argument('--no-figures', action='store_true',
                       help='only simulate and print the summary (cases of all figures or of --figures)')
    return p


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Command line: simulate, print the summary table, write the figures. Returns the exit status."""
    parser = _Parser()
    args = parser.parse_args(argv)
    figures = args.figures if args.figures is not None else sorted(PAPER_FIGURES)
    prog = parser.prog
    for option, value, ok, what in (('--backlash', args.backlash, args.backlash >= 0, '>= 0 mm'),
                                    ('--speed', args.speed, args.speed is None or args.speed > 0, '> 0 rpm'),
                                    ('--load', args.load, args.load is None or args.load >= 0, '>= 0 kg'),
                                    ('--end-time', args.end_time, args.end_time is None or args.end_time > 0,
                                     '> 0 s')):
        if not ok or (value is not None and not math.isfinite(value)):
            print(f"{prog}: error: {option} must be {what}, got {value:g}", file=sys.stderr)
            return 2
    try:
        CaseParameters(args.preset, args.backlash * 1e-3, None if args.speed is None else args.speed * RPM,
                       args.load, figures)
    except (ValueError, TypeError) as error:          # bad input: one line, no traceback
        print(f"{prog}: error: {error}", file=sys.stderr)
        return 2
    try:
        results = RunPaperCases(args.preset, args.backlash * 1e-3,
                                None if args.speed is None else args.speed * RPM, args.load, figures,
                                endTime=args.end_time, progress=False if args.quiet else None)
    except ValueError as error:
        print(f"{prog}: error: {error}", file=sys.stderr)
        return 2
    print(FormatSummary(Summary(results)))
    if args.no_figures:
        return 0
    outDir = Path(args.out).resolve()
    print(f'\nwriting figures to {outDir}')
    for path in WriteFigures(results, outDir, figures, preset=args.preset):
        print(f'  {path.name}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
