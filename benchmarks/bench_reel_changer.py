"""Benchmark: the paper's reel changer (section 3.2) with Exudyn against a straightforward scipy model.

Runs, in one process on this machine:

(a) ``SimulateReelChanger(GetPreset('reel-P1'))``: 8 s simulated, default step size, symbolic (C++) user
    functions;
(b) the same with Python user functions (``useSymbolic=False``);
(c) :func:`scipy_reference.SolveReelChangerScipy`: ``solve_ivp`` on equations (1)-(2) with the same
    contact law, at tolerances chosen for the same accuracy as (a) (see ``--scan`` and README.md);
(d) ``SimulateReelChanger(GetPreset('reel-P7'))`` with the default settings;

and a converged reference (``solve_ivp`` at rtol 1e-10) against which the accuracy of (a)-(c) is shown.
Reported per run: solve seconds (wall clock, best of ``--repeat`` repetitions, the solver call alone
without model building and post-processing), CPU seconds (best; of ``solve_ivp`` alone for the scipy
model, of the whole call for Exudyn, whose building and post-processing add about 4 ms), the
lowering-window (T/4..3T/4 = 2..6 s) maxima of |phi2''| and of the normal force, and their relative
differences to (a) and to the reference. Targets are judged on the wall-clock seconds; the CPU seconds
show how much of a slow run is due to other processes on a shared machine.

Usage::

    python benchmarks/bench_reel_changer.py [--repeat 5] [--repeat-p7 3] [--json FILE]
                                            [--no-reference] [--scan] [--profile]

Nothing is written unless ``--json FILE`` is given. Timings on a shared machine are noisy: runs of
(a), (b), (c) are interleaved and the best repetition counts.
"""
from __future__ import annotations

import argparse
import datetime
import json
import math
import os
import platform
import sys
import time
from pathlib import Path
from typing import Callable, Dict, List, Optional, Sequence

sys.dont_write_bytecode = True                       # leave no __pycache__ beside the benchmark
sys.path.insert(0, str(Path(__file__).resolve().parent))

import numpy as np                                   # noqa: E402
import scipy                                         # noqa: E402

import exudyn as exu                                 # noqa: E402
import exudyn_worm                                   # noqa: E402
from exudyn_worm.drive.presets import GetPreset            # noqa: E402
from exudyn_worm.analysis.simulation.reelchanger import DefaultWindows, RotationPeriod, SimulateReelChanger, SolverSettings
from exudyn_worm.builders.oneangle import BuildReelChanger
from exudyn_worm.analysis.simulation.stepsize import RecommendedStepSize  # noqa: E402
from scipy_reference import SolveReelChangerScipy    # noqa: E402
from compiled_reference import CompiledReelChanger   # noqa: E402
from torque_driven import SimulateTorqueDriven       # noqa: E402
from exudyn_worm.model.contact import ContactOptions       # noqa: E402
from exudyn_worm.drive.wholedrive import ResolveDrive

__all__ = ['SCIPY_SETTINGS', 'REFERENCE_SETTINGS', 'TARGETS', 'EnvironmentInfo', 'RunBenchmark',
           'ScanTolerances', 'ProfileExudyn', 'FormatReport', 'Main']

#: solve_ivp settings of run (c). ``--scan`` lists the settings that reach the accuracy of run (a) robustly
#: (they and every tighter rtol of the same method do); of those within 10 % of the fastest (LSODA rtol 2e-5
#: and 1e-5, in some runs RK45 rtol 2e-6: a tie within timing noise) this one has the largest margin (README.md)
SCIPY_SETTINGS = {'method': 'LSODA', 'rtol': 1e-5, 'atol': 1e-8}
#: converged reference: the compiled Dormand-Prince model at rtol 1e-10 on a 1e-4 s output grid (it agrees with
#: solve_ivp LSODA at rtol 1e-10 to 2e-6 in the P1 and P7 peaks; LSODA takes 10-40x longer)
REFERENCE_SETTINGS = {'method': 'C DOPRI5', 'rtol': 1e-10, 'atol': 1e-12, 'outputStep': 1e-4}
#: the sticking model's P7 reference: SimulateReelChanger at the default step divided by this (its P7 peaks at
#: h/4, h/8, h/16 agree within 0.6 %, docs/friction-sticking.md)
STICKING_REFERENCE_DIVISOR = 16
#: settings of the compiled limit (equal accuracy: within the P1 / P7 accuracy targets against the reference):
#: Dormand-Prince 5(4) (robust from rtol 1e-5 down) and generalized-alpha at our default step with step halving
COMPILED_DOPRI5 = {'rtol': 1e-5, 'atol': 1e-8}
COMPILED_GA_SPECTRAL_RADIUS = 0.8
#: the speed targets of the benchmark
TARGETS = {'p1SolveSeconds': 0.05, 'p1PeakError': 0.003, 'speedupOverScipy': 10., 'p7SolveSeconds': 0.2,
           'p7PeakError': 0.005, 'p7HalvedSteps': 0, 'compiledMultiple': 2.5, 'startupSeconds': 0.3}
#: the command whose whole-process time is the start-up target
STARTUP_COMMAND = ('exudyn-worm', 'stability', '--preset', 'reel-P1')
#: tolerance scan of ``--scan``
SCAN_METHODS = ('LSODA', 'RK45', 'DOP853', 'RK23', 'Radau', 'BDF')
SCAN_RTOLS = (1e-3, 1e-4, 5e-5, 2e-5, 1e-5, 5e-6, 2e-6, 1e-6)
SCAN_ATOL = 1e-8
_SLOW_METHODS = ('Radau', 'BDF')                      # timed once in the scan (several seconds per run)


class _QuietExudyn:
    """Silence Exudyn's console output (its per-run 'memory allocations' warning) inside the block."""

    def __enter__(self):
        self.previous = exu.config.printToConsole
        exu.config.printToConsole = False

    def __exit__(self, *exc):
        exu.config.printToConsole = self.previous


def _CpuModel() -> str:
    try:
        for line in Path('/proc/cpuinfo').read_text().splitlines():
            if line.startswith('model name'):
                return line.split(':', 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def EnvironmentInfo() -> Dict:
    """Versions, CPU and load of this machine."""
    return {'date': datetime.datetime.now().astimezone().isoformat(timespec='seconds'),
            'python': platform.python_version(), 'exudyn': exu.__version__, 'exudynWorm': exudyn_worm.__version__,
            'numpy': np.__version__, 'scipy': scipy.__version__, 'platform': platform.platform(),
            'cpu': _CpuModel(), 'cores': os.cpu_count(),
            'loadAverage': [round(x, 2) for x in os.getloadavg()] if hasattr(os, 'getloadavg') else None}


def _Peaks(result, window) -> Dict[str, float]:
    m = result.WindowMetrics([window])[0]
    return {'maxAbsAlpha2': m['maxAbsWheelAcceleration'], 'maxNormalForce': m['maxNormalForce'],
            'dominantFrequencyHz': m['dominantFrequencyHz']}


def _Timed(fn: Callable) -> Dict:
    """Call fn(); return its result, its solve seconds (wall), the wall/CPU seconds of the whole call and the
    solve CPU seconds: those of solve_ivp alone for the scipy model, those of the whole call for Exudyn (its
    model building and post-processing add about 4 ms to the solver)."""
    w0, c0 = time.perf_counter(), time.process_time()
    result = fn()
    cpu = time.process_time() - c0
    return {'result': result, 'solve': result.solveSeconds, 'wall': time.perf_counter() - w0, 'cpu': cpu,
            'solveCpu': result.info.get('solveCpuSeconds', cpu)}


def _RelDiff(x: float, ref: float) -> float:
    return x / ref - 1. if ref != 0 else math.nan


def _Peaks2(result, parameters) -> Dict[str, float]:
    """Peaks judged by the targets: max |phi2''| and max |Fn| in the lowering window, max |Fn| in the first
    lifting window (|phi2''| is about 0.004 rad/s^2 there, quasi-static: its relative error means nothing)."""
    lift, lower = DefaultWindows(ResolveDrive(parameters=parameters))[:2]
    m = result.WindowMetrics([lower, lift])
    return {'maxAbsAlpha2': m[0]['maxAbsWheelAcceleration'], 'maxNormalForce': m[0]['maxNormalForce'],
            'liftMaxNormalForce': m[1]['maxNormalForce'], 'dominantFrequencyHz': m[0]['dominantFrequencyHz']}


_PEAK_KEYS = ('maxAbsAlpha2', 'maxNormalForce', 'liftMaxNormalForce')


def StartupSeconds(repeat: int = 5) -> Dict:
    """Whole-process wall and CPU seconds of :data:`STARTUP_COMMAND` (best of ``repeat``), as a user's
    installation starts: with Python's bytecode cache (a warm-up run writes it; ``PYTHONDONTWRITEBYTECODE``, set on
    this project's machines, is removed for the child, otherwise every start compiles every module: 0.30 s
    instead of 0.24 s measured once)."""
    import resource
    import shutil
    import subprocess
    command = list(STARTUP_COMMAND)
    exe = shutil.which(command[0])
    if exe is None:
        command = [sys.executable, '-m', 'exudyn_worm'] + command[1:]
    env = {k: v for k, v in os.environ.items() if k != 'PYTHONDONTWRITEBYTECODE'}
    subprocess.run(command, check=True, capture_output=True, env=env)          # warm-up: writes the bytecode cache
    walls, cpus = [], []
    for _ in range(repeat):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        subprocess.run(command, check=True, capture_output=True, env=env)
        walls.append(time.perf_counter() - t0)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpus.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    return {'command': ' '.join(STARTUP_COMMAND), 'wallSecondsBest': min(walls), 'cpuSecondsBest': min(cpus),
            'wallSeconds': walls, 'cpuSeconds': cpus, 'bytecodeCache': True}


def RunBenchmark(repeat: int = 5, repeatP7: int = 3, scipySettings: Optional[Dict] = None,
                 reference: bool = True, log: Callable[[str], None] = print) -> Dict:
    """Run P1 and P7 with our defaults, the Python-UF variant, the tuned scipy model and the compiled limit
    (interleaved, best of ``repeat``), the converged reference and the CLI start-up; return all numbers and
    the targets' verdicts as a JSON-serializable dict."""
    settings = dict(SCIPY_SETTINGS if scipySettings is None else scipySettings)
    p1, p7 = GetPreset('reel-P1'), GetPreset('reel-P7')
    log('  compiling the C models ...')
    c1, c7 = CompiledReelChanger(p1), CompiledReelChanger(p7)
    h1, h7 = RecommendedStepSize(ResolveDrive(parameters=p1)), RecommendedStepSize(ResolveDrive(parameters=p7))
    regularized = ContactOptions(frictionModel='regularized')
    runs = {
        'exudynSymbolic': lambda: SimulateReelChanger(ResolveDrive(parameters=p1)),
        'exudynRegularized': lambda: SimulateReelChanger(ResolveDrive(parameters=p1), contactOptions=regularized),
        'exudynPython': lambda: SimulateReelChanger(ResolveDrive(parameters=p1), useSymbolic=False),
        'scipy': lambda: SolveReelChangerScipy(p1, **settings),
        'compiledDopri5': lambda: c1.Solve(**COMPILED_DOPRI5),
        'compiledGA': lambda: c1.SolveGeneralizedAlpha(h1, spectralRadius=COMPILED_GA_SPECTRAL_RADIUS),
    }
    runsP7 = {
        'p7': lambda: SimulateReelChanger(ResolveDrive(parameters=p7)),
        'p7Regularized': lambda: SimulateReelChanger(ResolveDrive(parameters=p7), contactOptions=regularized),
        'p7CompiledGA': lambda: c7.SolveGeneralizedAlpha(h7, spectralRadius=COMPILED_GA_SPECTRAL_RADIUS),
    }
    timings: Dict[str, List[Dict]] = {k: [] for k in list(runs) + list(runsP7)}
    with _QuietExudyn():
        for i in range(repeat):                      # interleaved, so load bursts hit all runs alike
            for key, fn in runs.items():
                timings[key].append(_Timed(fn))
            log(f'  repetition {i + 1}/{repeat}: ' + ', '.join(f'{k} {timings[k][-1]["solve"]:.4f} s' for k in runs))
        for i in range(repeatP7):
            for key, fn in runsP7.items():
                timings[key].append(_Timed(fn))
            log(f'  P7 repetition {i + 1}/{repeatP7}: ' + ', '.join(f'{k} {timings[k][-1]["solve"]:.4f} s'
                                                                   for k in runsP7))
        refs = {}
        if reference:
            for name, model, p in (('reference', c1, p1), ('p7Reference', c7, p7)):
                refs[name] = _Timed(lambda: model.Solve(rtol=REFERENCE_SETTINGS['rtol'], atol=REFERENCE_SETTINGS['atol'],
                                                        outputStep=REFERENCE_SETTINGS['outputStep']))
                log(f'  {name} (compiled DOPRI5, rtol {REFERENCE_SETTINGS["rtol"]:g}): {refs[name]["solve"]:.3f} s')
            # the compiled model has the regularized friction: the sticking model's P7 (the worm stops in the
            # chatter) is judged against itself at a sixteenth of the step (docs/friction-sticking.md)
            refs['p7StickingReference'] = _Timed(lambda: SimulateReelChanger(ResolveDrive(parameters=p7), stepSize=h7 / STICKING_REFERENCE_DIVISOR,
                                                                             maxSteps=10 ** 7))
            log(f"  p7StickingReference (Exudyn, step / {STICKING_REFERENCE_DIVISOR}): "
                f"{refs['p7StickingReference']['solve']:.3f} s")
    log('  CLI start-up ...')
    startup = StartupSeconds(repeat)

    def Summary(ts, parameters):
        last = ts[-1]['result']
        out = {'solveSecondsBest': min(t['solve'] for t in ts), 'solveSeconds': [t['solve'] for t in ts],
               'cpuSecondsBest': min(t['solveCpu'] for t in ts), 'cpuSeconds': [t['solveCpu'] for t in ts],
               'callCpuSecondsBest': min(t['cpu'] for t in ts), 'callWallSecondsBest': min(t['wall'] for t in ts),
               **_Peaks2(last, parameters)}
        out.update({k: last.info[k] for k in ('method', 'rtol', 'atol', 'nfev', 'njev', 'nlu', 'steps', 'rejectedSteps',
                                              'halvedSteps', 'stepSize', 'spectralRadius') if k in last.info})
        if 'solver' in last.info:
            out['solver'] = last.info['solver']
        return out

    res = {k: Summary(v, p7 if k.startswith('p7') else p1) for k, v in timings.items()}
    res.update({k: Summary([v], p7 if k.startswith('p7') else p1) for k, v in refs.items()})
    for key, r in res.items():
        ref = res.get('p7Reference' if key.startswith('p7') else 'reference')
        if key == 'p7' and 'p7StickingReference' in res:
            ref = res['p7StickingReference']
        if ref is not None and ref is not r:
            r['relErrToReference'] = {q: _RelDiff(r[q], ref[q]) for q in _PEAK_KEYS}
            r['worstPeakError'] = max(abs(r['relErrToReference'][q]) for q in
                                      (_PEAK_KEYS if key.startswith('p7') else _PEAK_KEYS[:2]))
    a, p7r = res['exudynSymbolic'], res['p7']
    compiledP1 = min(('compiledDopri5', 'compiledGA'), key=lambda k: res[k]['solveSecondsBest'])
    ratios = {'scipyOverOurs': res['scipy']['solveSecondsBest'] / a['solveSecondsBest'],
              'pythonUFOverOurs': res['exudynPython']['solveSecondsBest'] / a['solveSecondsBest'],
              'scipyOverOursCpu': res['scipy']['cpuSecondsBest'] / a['cpuSecondsBest'],
              'oursOverCompiledP1': a['solveSecondsBest'] / res[compiledP1]['solveSecondsBest'],
              'oursOverCompiledGAP1': a['solveSecondsBest'] / res['compiledGA']['solveSecondsBest'],
              'oursOverCompiledP7': p7r['solveSecondsBest'] / res['p7CompiledGA']['solveSecondsBest'],
              'compiledP1': compiledP1,
              'stickingOverRegularizedP1': a['solveSecondsBest'] / res['exudynRegularized']['solveSecondsBest'],
              'stickingOverRegularizedP1Cpu': a['cpuSecondsBest'] / res['exudynRegularized']['cpuSecondsBest'],
              'stickingOverRegularizedP7': p7r['solveSecondsBest'] / res['p7Regularized']['solveSecondsBest'],
              'stickingOverRegularizedP7Cpu': p7r['cpuSecondsBest'] / res['p7Regularized']['cpuSecondsBest']}
    cpuP1 = min(res[k]['cpuSecondsBest'] for k in ('compiledDopri5', 'compiledGA'))
    ratios.update(oursOverCompiledP1Cpu=a['cpuSecondsBest'] / max(cpuP1, 1e-9),
                  oursOverCompiledP7Cpu=p7r['cpuSecondsBest'] / max(res['p7CompiledGA']['cpuSecondsBest'], 1e-9))
    T = TARGETS
    nominal = int(round(RotationPeriod(ResolveDrive(parameters=p7)) / h7))
    halved = p7r['solver']['steps'] - nominal

    def Verdict(target, measured, met, unit=''):
        return {'target': target, 'measured': measured, 'met': bool(met), 'unit': unit}

    targets = {
        'p1SolveSeconds': Verdict(f"<= {T['p1SolveSeconds']} s", a['solveSecondsBest'],
                                  a['solveSecondsBest'] <= T['p1SolveSeconds'], 's'),
        'p1PeakError': Verdict(f"<= {T['p1PeakError']:.1%} (lowering |phi2''|, Fn)", a.get('worstPeakError', math.nan),
                               a.get('worstPeakError', math.inf) <= T['p1PeakError'], '%'),
        'scipyAtEqualAccuracy': Verdict(f"scipy peaks within {T['p1PeakError']:.1%} too",
                                        res['scipy'].get('worstPeakError', math.nan),
                                        res['scipy'].get('worstPeakError', math.inf) <= T['p1PeakError'], '%'),
        'speedupOverScipy': Verdict(f">= {T['speedupOverScipy']:g}x", ratios['scipyOverOurs'],
                                    ratios['scipyOverOurs'] >= T['speedupOverScipy'], 'x'),
        'p7SolveSeconds': Verdict(f"<= {T['p7SolveSeconds']} s", p7r['solveSecondsBest'],
                                  p7r['solveSecondsBest'] <= T['p7SolveSeconds'], 's'),
        'p7PeakError': Verdict(f"<= {T['p7PeakError']:.1%} (lowering |phi2''|, Fn; lifting Fn)",
                               p7r.get('worstPeakError', math.nan), p7r.get('worstPeakError', math.inf) <= T['p7PeakError'],
                               '%'),
        'p7HalvedSteps': Verdict('no rejected or halved steps', halved, halved <= T['p7HalvedSteps'], 'n'),
        'compiledMultipleP1': Verdict(f"<= {T['compiledMultiple']}x the compiled limit", ratios['oursOverCompiledP1'],
                                      ratios['oursOverCompiledP1'] <= T['compiledMultiple'], 'x'),
        'compiledMultipleP7': Verdict(f"<= {T['compiledMultiple']}x the compiled limit", ratios['oursOverCompiledP7'],
                                      ratios['oursOverCompiledP7'] <= T['compiledMultiple'], 'x'),
        'startupSeconds': Verdict(f"<= {T['startupSeconds']} s whole process", startup['wallSecondsBest'],
                                  startup['wallSecondsBest'] <= T['startupSeconds'], 's'),
    }
    targets['startupSeconds']['measuredCpu'] = startup['cpuSecondsBest']
    targets['startupSeconds']['metCpu'] = startup['cpuSecondsBest'] <= T['startupSeconds']
    for key, run in (('p1SolveSeconds', a), ('p7SolveSeconds', p7r)):
        targets[key]['measuredCpu'] = run['cpuSecondsBest']
        targets[key]['metCpu'] = run['cpuSecondsBest'] <= T[key]
    for key, cpu, ok in (('speedupOverScipy', ratios['scipyOverOursCpu'], lambda x: x >= T['speedupOverScipy']),
                         ('compiledMultipleP1', ratios['oursOverCompiledP1Cpu'], lambda x: x <= T['compiledMultiple']),
                         ('compiledMultipleP7', ratios['oursOverCompiledP7Cpu'], lambda x: x <= T['compiledMultiple'])):
        targets[key]['measuredCpu'] = cpu
        targets[key]['metCpu'] = ok(cpu)
    return {'environment': EnvironmentInfo(), 'endTime': RotationPeriod(ResolveDrive(parameters=p1)), 'repeat': repeat, 'repeatP7': repeatP7,
            'stepSizes': {'p1': h1, 'p7': h7, 'p7NominalSteps': nominal},
            'scipySettings': settings, 'referenceSettings': REFERENCE_SETTINGS if reference else None,
            'runs': res, 'ratios': ratios, 'startup': startup, 'targets': targets}


#: SimulateReelChanger's earlier settings, before the speed tuning (Exudyn's Newton defaults, spectral radius 0.9, h = 5e-4 s)
OLD_SETTINGS = {'timeIntegration.newton.maxIterations': 25, 'timeIntegration.newton.relativeTolerance': 1e-8,
                'timeIntegration.generalizedAlpha.spectralRadius': 0.9}
_N10 = {'timeIntegration.newton.maxIterations': 10, 'timeIntegration.newton.relativeTolerance': 1e-6}


class _MotorAngleByUserFunction:
    """The default constant motor speed, but not a ConstantSpeed: prescribed on position level by symbolic
    offset user functions (how the motor was driven before the velocity-level constraint)."""

    def __init__(self, speed: float):
        from exudyn_worm.model.profiles import ConstantSpeed
        self.AngleAndSpeed = ConstantSpeed(speed).AngleAndSpeed


def _Levers(p, h):
    """(label, run) of every lever of ``--levers`` for parameter set ``p`` with our default step ``h``."""
    rho = lambda r: {**_N10, 'timeIntegration.generalizedAlpha.spectralRadius': r}
    Sim = lambda **kw: (lambda: SimulateReelChanger(ResolveDrive(parameters=p), **kw))
    return [
        ('earlier settings: h 5e-4, rho 0.9, Newton 25 it. rtol 1e-8', Sim(stepSize=5e-4, solverOptions=OLD_SETTINGS)),
        ('Newton 10 it., rtol 1e-6 (h 5e-4, rho 0.9)', Sim(stepSize=5e-4, solverOptions=rho(0.9))),
        ('full Newton (10 it., rtol 1e-6, rho 0.9)', Sim(stepSize=5e-4, solverOptions={
            **rho(0.9), 'timeIntegration.newton.useModifiedNewton': False})),
        ('Newton rtol 1e-4 (10 it., rho 0.8)', Sim(stepSize=5e-4, solverOptions={
            **rho(0.8), 'timeIntegration.newton.relativeTolerance': 1e-4})),
        ('spectral radius 1.0 (h 5e-4)', Sim(stepSize=5e-4, solverOptions=rho(1.))),
        ('spectral radius 0.8 (h 5e-4)', Sim(stepSize=5e-4, solverOptions=rho(0.8))),
        ('spectral radius 0.6 (h 5e-4)', Sim(stepSize=5e-4, solverOptions=rho(0.6))),
        (f'NEW DEFAULT: step from the drive h {h:.3g}, rho 0.8, Newton 10/1e-6', Sim()),
        ('motor angle by offset user functions (before the velocity-level motor constraint)',
         Sim(profile=_MotorAngleByUserFunction(p['motorSpeed']))),
        ('Newton rtol 1e-5 (drive step, rho 0.8, 10 it.)', Sim(solverOptions={
            'timeIntegration.newton.relativeTolerance': 1e-5})),
        ('step 1e-3 (new settings)', Sim(stepSize=1e-3)),
        ('sensors every 10th step (new default)', Sim(solverOptions={'solution.sensors.writePeriod': 10 * h})),
        ('frictionSpeed 0.2 rad/s instead of 0.05 (law change)', Sim(contactOptions=ContactOptions(frictionSpeed=0.2))),
        ('torque-driven worm, generalized-alpha (new settings)', lambda: SimulateTorqueDriven(p, h)),
        ('torque-driven worm, explicit RK44 h 2e-3', lambda: SimulateTorqueDriven(p, 2e-3, solverType='RK44')),
        ('torque-driven worm, explicit RK44 h 1e-3', lambda: SimulateTorqueDriven(p, 1e-3, solverType='RK44')),
    ]


def RunLevers(references: Dict[str, Dict], repeat: int = 2, log: Callable[[str], None] = print) -> List[Dict]:
    """Each lever on P1 and P7: solve CPU seconds (best of ``repeat``), work counters and peak errors against
    the converged references (``references['reel-P1']``, ``['reel-P7']``: peak dicts of :func:`_Peaks2`)."""
    rows = []
    for name in ('reel-P1', 'reel-P7'):
        p = GetPreset(name)
        h = RecommendedStepSize(ResolveDrive(parameters=p))
        with _QuietExudyn():
            for label, run in _Levers(p, h):
                ts = [_Timed(run) for _ in range(repeat if name == 'reel-P1' else 1)]
                r = ts[-1]['result']
                peaks = _Peaks2(r, p)
                err = {q: _RelDiff(peaks[q], references[name][q]) for q in _PEAK_KEYS}
                keys = _PEAK_KEYS if name == 'reel-P7' else _PEAK_KEYS[:2]
                row = {'preset': name, 'lever': label, 'cpuSecondsBest': min(t['solveCpu'] for t in ts),
                       'solveSecondsBest': min(t['solve'] for t in ts), 'solver': r.info.get('solver', {}),
                       'relErrToReference': err, 'worstPeakError': max(abs(err[q]) for q in keys)}
                rows.append(row)
                log(f"  {name} {label:58s} {row['cpuSecondsBest']:7.3f} s CPU, worst peak error "
                    f"{row['worstPeakError']:.3%}, steps {row['solver'].get('steps', '-')}")
    return rows


def FormatLevers(rows: List[Dict]) -> str:
    """Markdown table of :func:`RunLevers`."""
    lines = ["| preset | lever | CPU s | x before | steps | Newton it. | rejected | err max\\|phi2''\\| | err max Fn "
             "| worst |", '| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |']
    before = {}
    for r in rows:
        before.setdefault(r['preset'], r['cpuSecondsBest'])
        c, e = r['solver'], r['relErrToReference']
        lines.append(f"| {r['preset'][5:]} | {r['lever']} | {r['cpuSecondsBest']:.3f} | "
                     f"{r['cpuSecondsBest'] / before[r['preset']]:.2f} | {c.get('steps', '-')} | "
                     f"{c.get('newtonIterations', '-')} | {c.get('rejectedSteps', '-')} | {_Pct(e['maxAbsAlpha2'])} | "
                     f"{_Pct(e['maxNormalForce'])} | {r['worstPeakError']:.2%} |")
    return '\n'.join(lines)


def ScanTolerances(exudynPeaks: Dict[str, float], reference: Dict[str, float], methods: Sequence[str] = SCAN_METHODS,
                   rtols: Sequence[float] = SCAN_RTOLS, atol: float = SCAN_ATOL, repeat: int = 2,
                   log: Callable[[str], None] = print) -> Dict:
    """Time solve_ivp methods over a tolerance grid and compare their P1 peaks with the reference.

    A setting *passes* if both its peak errors are within the P1 accuracy target (0.3 %, which our default
    run must meet too) against the converged reference; it is *robust* if it and every
    tighter rtol of the same method pass (the peak errors do not fall monotonically with rtol).
    """
    p1 = GetPreset('reel-P1')
    window = DefaultWindows(ResolveDrive(parameters=p1))[1]
    level = TARGETS['p1PeakError']                  # equal accuracy: the accuracy target ours must meet too
    rows = []
    for method in methods:
        for rtol in rtols:
            n = 1 if method in _SLOW_METHODS else repeat
            ts = [_Timed(lambda: SolveReelChangerScipy(p1, method=method, rtol=rtol, atol=atol)) for _ in range(n)]
            r = ts[-1]['result']
            peaks = _Peaks(r, window)
            err = {q: _RelDiff(peaks[q], reference[q]) for q in ('maxAbsAlpha2', 'maxNormalForce')}
            row = {'method': method, 'rtol': rtol, 'atol': atol, 'solveSecondsBest': min(t['solve'] for t in ts),
                   'cpuSecondsBest': min(t['solveCpu'] for t in ts),
                   'nfev': r.info['nfev'], **peaks, 'relErrToReference': err,
                   'pass': max(abs(e) for e in err.values()) <= level,
                   'missesChatter': peaks['maxAbsAlpha2'] < 0.5 * reference['maxAbsAlpha2']}
            rows.append(row)
            log(f"  {method:6s} rtol {rtol:7.0e}: {row['cpuSecondsBest']:7.3f} s CPU, errors "
                f"{err['maxAbsAlpha2']:+.3%} / {err['maxNormalForce']:+.3%}" + ('  PASS' if row['pass'] else ''))
    for row in rows:                                  # robust: this and all tighter rtols of the method pass
        row['robust'] = all(o['pass'] for o in rows if o['method'] == row['method'] and o['rtol'] <= row['rtol'])
    robust = [r for r in rows if r['robust']]
    keys = ('method', 'rtol', 'atol', 'solveSecondsBest', 'cpuSecondsBest', 'relErrToReference')
    best = min(robust, key=lambda r: r['cpuSecondsBest']) if robust else None     # CPU: less sensitive to load
    near = sorted((r for r in robust if r['cpuSecondsBest'] <= 1.1 * best['cpuSecondsBest']),
                  key=lambda r: r['cpuSecondsBest']) if robust else []
    return {'accuracyLevel': level, 'atol': atol, 'rows': rows,
            'fastestRobust': None if best is None else {k: best[k] for k in keys},
            'withinTenPercentOfFastest': [{k: r[k] for k in keys} for r in near]}


def ProfileExudyn(presetName: str) -> Dict:
    """Solve one reel-changer preset as :func:`SimulateReelChanger` does, with Exudyn's timers and counters.

    The settings mirror ``SimulateReelChanger`` (generalized-alpha, SOLVER_SETTINGS, the drive's step); the
    returned ``sameAsSimulate`` says whether the lowering-window peak equals that of SimulateReelChanger.
    """
    p = GetPreset(presetName)
    endTime = RotationPeriod(ResolveDrive(parameters=p))
    model = BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=p))
    mbs = model.mbs
    mbs.Assemble()
    ss, solverType = SolverSettings(endTime, RecommendedStepSize(ResolveDrive(parameters=p)), where='ProfileExudyn')
    ss.show.computationTime = True                    # fills solver.timer (and prints the CPU-time table)
    with _QuietExudyn():
        t0 = time.perf_counter()
        mbs.SolveDynamic(ss, solverType=solverType)
        seconds = time.perf_counter() - t0
        check = SimulateReelChanger(ResolveDrive(parameters=p))
    solver = mbs.sys['dynamicSolver']
    it, timer = solver.it, solver.timer
    names = ('factorization', 'newtonIncrement', 'integrationFormula', 'ODE2RHS', 'ODE1RHS', 'AERHS',
             'totalJacobian', 'jacobianODE2', 'jacobianAE', 'massMatrix', 'reactionForces', 'python',
             'writeSolution', 'overhead', 'visualization')
    timers = {n: float(getattr(timer, n)) for n in names if hasattr(timer, n)}
    total = float(getattr(timer, 'total', 0.)) or sum(timers.values())
    a2 = mbs.GetSensorStoredData(model.sensors['alpha2'])
    w0, w1 = DefaultWindows(ResolveDrive(parameters=p))[1]
    m = (a2[:, 0] >= w0) & (a2[:, 0] <= w1)
    peak = float(np.max(np.abs(a2[m, 1])))
    return {'preset': presetName, 'solveSecondsWithTimers': seconds,
            'steps': int(it.currentStepIndex) - 1, 'nominalSteps': int(ss.timeIntegration.numberOfSteps),
            'newtonIterations': int(it.newtonStepsCount), 'newtonJacobians': int(it.newtonJacobiCount),
            'rejectedModifiedNewtonSteps': int(it.rejectedModifiedNewtonSteps),
            'timerSeconds': timers, 'timerTotalSeconds': total,
            'sameAsSimulate': bool(np.isclose(peak, check.WindowMetrics([(w0, w1)])[0]['maxAbsWheelAcceleration'],
                                              rtol=1e-12))}


def _Pct(x: float) -> str:
    return f'{x:+.3%}' if x == x else 'n/a'


def FormatReport(data: Dict) -> str:
    """Human-readable report of :func:`RunBenchmark` (plus scan/profile if present)."""
    env, runs = data['environment'], data['runs']
    h = data['stepSizes']
    lines = [f"date {env['date']}; python {env['python']}, exudyn {env['exudyn']}, exudyn-worm {env['exudynWorm']}, "
             f"numpy {env['numpy']}, scipy {env['scipy']}",
             f"CPU: {env['cpu']}, {env['cores']} cores; {env['platform']}; load average at end {env['loadAverage']}",
             f"one wheel rotation ({data['endTime']:.4f} s simulated); our default step: P1 {h['p1']:.3g} s, "
             f"P7 {h['p7']:.3g} s (RecommendedStepSize); best of {data['repeat']} (P7: {data['repeatP7']})",
             '']
    s = data['scipySettings']
    labels = {'exudynSymbolic': 'P1 ours (Exudyn, symbolic UF, defaults)',
              'exudynRegularized': 'P1 ours, regularized friction',
              'exudynPython': 'P1 ours, Python UF',
              'scipy': f"P1 solve_ivp {s['method']} rtol={s['rtol']:g} atol={s['atol']:g}",
              'compiledDopri5': f"P1 compiled C DOPRI5 rtol={COMPILED_DOPRI5['rtol']:g}",
              'compiledGA': f"P1 compiled C gen.-alpha h={h['p1']:.3g} rho={COMPILED_GA_SPECTRAL_RADIUS}",
              'reference': 'P1 reference (C DOPRI5 rtol=1e-10)',
              'p7': 'P7 ours (Exudyn, defaults)',
              'p7Regularized': 'P7 ours, regularized friction',
              'p7CompiledGA': f"P7 compiled C gen.-alpha h={h['p7']:.3g} rho={COMPILED_GA_SPECTRAL_RADIUS}",
              'p7Reference': 'P7 reference (C DOPRI5 rtol=1e-10)',
              'p7StickingReference': f"P7 reference, sticking (ours h/{STICKING_REFERENCE_DIVISOR})"}
    header = (f"{'run':46s} {'solve s':>8s} {'CPU s':>7s} {'max|phi2dd|':>11s} {'max Fn N':>9s} {'lift Fn N':>9s} "
              f"{'err phi2dd':>10s} {'err Fn':>9s} {'err liftFn':>10s}  work")
    lines += [header, '-' * len(header)]
    for key, label in labels.items():
        if key not in runs:
            continue
        r = runs[key]
        e = r.get('relErrToReference', {})
        work = ''
        if 'solver' in r:
            c = r['solver']
            work = f"{c['steps']} steps, {c['newtonIterations']} Newton it., {c['jacobians']} Jac., {c['rejectedSteps']} rej."
        elif 'nfev' in r:
            work = f"nfev {r['nfev']}, njev {r['njev']}"
        elif 'halvedSteps' in r:
            work = f"{r['steps']} steps, {r['halvedSteps']} halved"
        elif 'rejectedSteps' in r:
            work = f"{r['steps']} steps, {r['rejectedSteps']} rejected"
        lines.append(f"{label:46s} {r['solveSecondsBest']:8.4f} {r['cpuSecondsBest']:7.4f} {r['maxAbsAlpha2']:11.3f} "
                     f"{r['maxNormalForce']:9.0f} {r['liftMaxNormalForce']:9.0f} "
                     + ' '.join(f"{_Pct(e[q]) if e else '':>{w}s}" for q, w in zip(_PEAK_KEYS, (10, 9, 10)))
                     + f"  {work}")
    lines += ['', 'solve s: wall-clock seconds of the solver call alone (best); CPU s: CPU seconds of the same call (best);',
              "phi2dd = phi2'' in rad/s^2, Fn = |normal force|; maxima in the lowering window, lift Fn in the first "
              'lifting window; err: relative difference to the converged reference of the same preset']
    ra = data['ratios']
    st = data['startup']
    lines += ['', f"ratios (solve s): scipy/ours = {ra['scipyOverOurs']:.2f}, pythonUF/ours = {ra['pythonUFOverOurs']:.2f}, "
              f"ours/compiled P1 = {ra['oursOverCompiledP1']:.1f} (vs {ra['compiledP1']}; vs compiled gen.-alpha "
              f"{ra['oursOverCompiledGAP1']:.1f}), ours/compiled P7 = {ra['oursOverCompiledP7']:.1f}",
              f"ratios (CPU s):   scipy/ours = {ra['scipyOverOursCpu']:.2f}, ours/compiled P1 = "
              f"{ra['oursOverCompiledP1Cpu']:.1f}, ours/compiled P7 = {ra['oursOverCompiledP7Cpu']:.1f}",
              f"sticking/regularized friction (solve s, same run): P1 {ra['stickingOverRegularizedP1']:.3f}, "
              f"P7 {ra['stickingOverRegularizedP7']:.3f}; CPU s: P1 {ra['stickingOverRegularizedP1Cpu']:.3f}, "
              f"P7 {ra['stickingOverRegularizedP7Cpu']:.3f}",
              f"CLI start-up `{st['command']}`: {st['wallSecondsBest']:.3f} s wall, {st['cpuSecondsBest']:.3f} s CPU "
              f"(best of {len(st['wallSeconds'])})", '',
              'speed targets (time targets judged on wall-clock seconds; on CPU seconds in brackets):']
    fmt = {'s': '{:.3f} s', 'x': '{:.2f}x', '%': '{:.3%}', 'n': '{:d}'}
    for key, t in data['targets'].items():
        f = fmt[t['unit']]
        measured = f.format(t['measured']) if t['measured'] == t['measured'] else 'n/a'
        cpu = (f"   [CPU {f.format(t['measuredCpu'])}: {'met' if t['metCpu'] else 'not met'}]"
               if 'measuredCpu' in t else '')
        lines.append(f"  {key:22s} {t['target']:48s} measured {measured:>10s}   {'MET' if t['met'] else 'NOT MET':7s}{cpu}")
    if 'scan' in data:
        sc = data['scan']
        lines += ['', f"tolerance scan (P1, atol {sc['atol']:g}; pass: both peak errors <= the accuracy target "
                      f"{sc['accuracyLevel']:.3%}; robust: this and all tighter rtols pass)",
                  f"{'method':7s} {'rtol':>7s} {'solve s':>8s} {'CPU s':>7s} {'nfev':>7s} {'err phi2dd':>10s} "
                  f"{'err Fn':>9s}  verdict"]
        for r in sc['rows']:
            e = r['relErrToReference']
            verdict = ('robust' if r['robust'] else 'pass' if r['pass'] else
                       'misses the chatter' if r['missesChatter'] else '-')
            lines.append(f"{r['method']:7s} {r['rtol']:7.0e} {r['solveSecondsBest']:8.3f} {r['cpuSecondsBest']:7.3f} "
                         f"{r['nfev']:7d} "
                         f"{_Pct(e['maxAbsAlpha2']):>10s} {_Pct(e['maxNormalForce']):>9s}  {verdict}")
        lines.append('robust settings within 10 % of the fastest (CPU s): ' + ('none' if not sc['fastestRobust'] else
                     '; '.join(f"{r['method']} rtol={r['rtol']:g} ({r['cpuSecondsBest']:.3f} s, worst error "
                               f"{max(abs(e) for e in r['relErrToReference'].values()):.3%})"
                               for r in sc['withinTenPercentOfFastest'])))
        lines.append(f"run (c) uses {SCIPY_SETTINGS['method']} rtol={SCIPY_SETTINGS['rtol']:g} "
                     f"atol={SCIPY_SETTINGS['atol']:g} (see README.md)")
    for prof in data.get('profile', []):
        tm = prof['timerSeconds']
        total = prof['timerTotalSeconds'] or 1.
        subTimers = ('jacobianODE2', 'jacobianAE')          # parts of totalJacobian
        top = sorted(((v, k) for k, v in tm.items() if v > 0 and k not in subTimers), reverse=True)[:6]
        lines += ['', f"Exudyn profile {prof['preset']}: {prof['steps']} steps (nominal {prof['nominalSteps']}), "
                      f"{prof['newtonIterations']} Newton iterations, {prof['newtonJacobians']} Jacobians, "
                      f"{prof['rejectedModifiedNewtonSteps']} rejected modified-Newton steps; "
                      f"{prof['solveSecondsWithTimers']:.3f} s with timers"
                      + ('' if prof['sameAsSimulate'] else ' (WARNING: differs from SimulateReelChanger)'),
                  '  share of the solver time: ' + ', '.join(f'{k} {v / total:.0%}' for v, k in top)
                  + (f" (jacobianODE2 {tm['jacobianODE2'] / total:.0%})" if tm.get('jacobianODE2', 0) > 0.01 * total
                     else '')]
    return '\n'.join(lines)


def Main(argv: Optional[Sequence[str]] = None) -> Dict:
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--repeat', type=int, default=5, help='repetitions of the P1 runs (a)-(c) (default 5)')
    parser.add_argument('--repeat-p7', type=int, default=3, help='repetitions of the P7 run (d) (default 3)')
    parser.add_argument('--method', default=SCIPY_SETTINGS['method'], help='solve_ivp method of run (c)')
    parser.add_argument('--rtol', type=float, default=SCIPY_SETTINGS['rtol'], help='rtol of run (c)')
    parser.add_argument('--atol', type=float, default=SCIPY_SETTINGS['atol'], help='atol of run (c)')
    parser.add_argument('--no-reference', action='store_true',
                        help='skip the converged references (about 10 s; the accuracy verdicts need them)')
    parser.add_argument('--scan', action='store_true',
                        help='also scan solve_ivp methods and tolerances (about 2 min; needs the reference)')
    parser.add_argument('--profile', action='store_true', help="also print Exudyn's timers and Newton counters")
    parser.add_argument('--levers', action='store_true',
                        help='also measure each solver/model lever on P1 and P7 (about 1 min CPU; needs the reference)')
    parser.add_argument('--json', metavar='FILE', help='save all results to FILE (JSON)')
    args = parser.parse_args(argv)
    if args.repeat < 1 or args.repeat_p7 < 1:
        parser.error('--repeat and --repeat-p7 must be >= 1')
    if (args.scan or args.levers) and args.no_reference:
        parser.error('--scan and --levers need the reference; drop --no-reference')

    log = lambda msg: print(msg, flush=True)
    log('running the benchmark ...')
    data = RunBenchmark(args.repeat, args.repeat_p7, {'method': args.method, 'rtol': args.rtol, 'atol': args.atol},
                        reference=not args.no_reference, log=log)
    if args.scan:
        log('tolerance scan ...')
        data['scan'] = ScanTolerances(data['runs']['exudynSymbolic'], data['runs']['reference'], log=log)
    if args.levers:
        log('levers ...')
        data['levers'] = RunLevers({'reel-P1': data['runs']['reference'], 'reel-P7': data['runs']['p7Reference']},
                                   log=log)
    if args.profile:
        data['profile'] = [ProfileExudyn(name) for name in ('reel-P1', 'reel-P7')]
    data['environment']['loadAverage'] = EnvironmentInfo()['loadAverage']
    print()
    print(FormatReport(data))
    if args.levers:
        print('\nlevers (CPU seconds of the solve; errors against the converged reference; worst: lowering '
              "|phi2''| and Fn, for P7 also the lifting Fn):")
        print(FormatLevers(data['levers']))
    if args.json:
        path = Path(args.json).resolve()
        path.write_text(json.dumps(data, indent=2))
        print(f'\nresults saved to {path}')
    return data


if __name__ == '__main__':
    Main()
