"""The speed targets against the tuned scipy model, the cost of the default step check, and meshes per system.

In one process, interleaved, best of ``--repeat``:

(a) ``SimulateReelChanger(GetPreset('reel-P1'))`` and ``reel-P7`` with the defaults (the drive's recommended step,
    ``SOLVER_SETTINGS``, symbolic user functions, the sticking friction) against
    ``scipy_reference.SolveReelChangerScipy(..., method='LSODA', rtol=1e-5, atol=1e-8)`` (the tuned reference of
    ``bench_reel_changer.py``); wall-clock seconds of the solver call alone, and CPU seconds;
(b) a default sweep of the seven reel presets: :func:`exudyn_worm.analysis.studies.studypoint.RunPoint` of each preset with the
    default step check (``checkStep`` None), without it (False) and with it forced (True, what the default did when
    every preset's small linear margin sent it to half the step); whole-run seconds summed over the presets;
(c) N = 1, 2, 4, 8 independent reel-P1 meshes in one Exudyn system (each a worm and wheel on the sticking
    connector, the worm started at the motor speed, the lever load on the wheel; 0.5 s), solve seconds per mesh;
(d) with ``--instructions``: the instructions of the same solver calls of (a), ours and LSODA, counted by callgrind
    (``count_instructions.py``; four more processes under valgrind, 5-10 min), and their ratios.

Usage::

    python benchmarks/bench_speed.py [--repeat 5] [--instructions] [--json FILE]

Nothing is written unless ``--json FILE`` is given.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path
from typing import Dict, List, Optional, Sequence

sys.dont_write_bytecode = True                       # leave no __pycache__ beside the benchmark
sys.path.insert(0, str(Path(__file__).resolve().parent))

import exudyn as exu                                 # noqa: E402
from exudyn_worm.drive.presets import ElasticDriveFromParameters, GetPreset   # noqa: E402
from exudyn_worm.analysis.simulation.reelchanger import SimulateReelChanger, SolverSettings   # noqa: E402
from exudyn_worm.analysis.studies.studypoint import RunPoint, RunTask     # noqa: E402
from exudyn_worm.drive.wholedrive import ResolveDrive
from scipy_reference import SolveReelChangerScipy    # noqa: E402
import count_instructions                            # noqa: E402

__all__ = ['SCIPY_SETTINGS', 'TARGETS', 'PRESETS', 'SpeedRatios', 'SweepCost', 'MeshScaling', 'Main']

#: the tuned scipy model of bench_reel_changer.py (its README: the same accuracy as our P1 run)
SCIPY_SETTINGS = {'method': 'LSODA', 'rtol': 1e-5, 'atol': 1e-8}
#: the targets: ratio scipy / ours of P1 and P7, default sweep / sweep without the check
TARGETS = {'p1Ratio': 12., 'p7Ratio': 25., 'sweepCheckCost': 1.3}
PRESETS = tuple(f'reel-P{i}' for i in range(1, 8))


def _Best(times: List[float]) -> float:
    return min(times)


def SpeedRatios(repeat: int) -> Dict:
    """(a): best solve seconds (wall and CPU) of ours and of scipy for P1 and P7, interleaved, and the ratios."""
    out = {}
    for name in ('reel-P1', 'reel-P7'):
        p = GetPreset(name)
        ours, oursCpu, scipy, scipyCpu = [], [], [], []
        for _ in range(repeat):
            r = SimulateReelChanger(ResolveDrive(parameters=p), progress=False)
            ours.append(r.solveSeconds)
            oursCpu.append(r.info['solveCpuSeconds'])
            s = SolveReelChangerScipy(p, **SCIPY_SETTINGS)
            scipy.append(s.solveSeconds)
            scipyCpu.append(s.info.get('solveCpuSeconds', s.solveSeconds))
        out[name] = {'ours': _Best(ours), 'oursCpu': _Best(oursCpu), 'scipy': _Best(scipy), 'scipyCpu': _Best(scipyCpu),
                     'ratio': _Best(scipy) / _Best(ours), 'ratioCpu': _Best(scipyCpu) / _Best(oursCpu),
                     'solver': r.info['solver']}
    return out


def _Sweep(checkStep) -> Dict:
    total, checked = 0., 0
    for k, name in enumerate(PRESETS):
        row = RunPoint(RunTask(k, ResolveDrive(name), checkStep=checkStep))
        if row['status'] != 'ok':
            raise RuntimeError(f"bench_speed: {name} failed: {row['error']}")
        total += row['seconds']
        checked += bool(row['stepChecked'])
    return {'seconds': total, 'checked': checked}


def SweepCost(repeat: int) -> Dict:
    """(b): the seven presets as study runs with the default check, without it and with it forced."""
    runs: Dict[str, List[Dict]] = {'default': [], 'off': [], 'forced': []}
    for _ in range(repeat):
        for key, check in (('default', None), ('off', False), ('forced', True)):
            runs[key].append(_Sweep(check))
    out = {k: {'seconds': _Best([r['seconds'] for r in v]), 'checkedRuns': v[-1]['checked']} for k, v in runs.items()}
    out['defaultOverOff'] = out['default']['seconds'] / out['off']['seconds']
    out['forcedOverOff'] = out['forced']['seconds'] / out['off']['seconds']
    return out


def _Meshes(n: int, endTime: float = 0.5) -> float:
    """Solve seconds of ``n`` independent reel-P1 meshes in one system over ``endTime``."""
    from exudyn_worm.items.connector import CreateWormGear
    from exudyn_worm.items.drivetrain import CreateRotor, CreateRotorTorque
    from exudyn_worm.items.solve import SolveDynamicInChunks
    from exudyn_worm.analysis.simulation.stepsize import RecommendedStepSize
    from exudyn_worm.model.profiles import GravityLeverTorque
    p = GetPreset('reel-P1')
    drive = ElasticDriveFromParameters(p)
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    for k in range(n):
        worm = CreateRotor(mbs, drive.J1, initialSpeed=p['motorSpeed'], name=f'worm{k}')
        wheel = CreateRotor(mbs, drive.J2, initialSpeed=p['motorSpeed'] / drive.gear.ratio, name=f'wheel{k}')
        CreateWormGear(mbs, [worm, wheel], gear=drive.gear, name=f'mesh{k}')
        CreateRotorTorque(mbs, wheel, GravityLeverTorque(mass=p['loadMass'], leverArm=p['leverArm']))
    mbs.Assemble()
    ss, solverType = SolverSettings(endTime, RecommendedStepSize(ResolveDrive(parameters=p)), where='bench_speed')
    t0 = time.perf_counter()
    SolveDynamicInChunks(mbs, ss, solverType, progress=False)
    return time.perf_counter() - t0


def MeshScaling(repeat: int, counts: Sequence[int] = (1, 2, 4, 8)) -> Dict:
    """(c): best solve seconds of N meshes in one system, and per mesh."""
    times = {n: [] for n in counts}
    for _ in range(repeat):
        for n in counts:
            times[n].append(_Meshes(n))
    return {str(n): {'seconds': _Best(v), 'perMesh': _Best(v) / n} for n, v in times.items()}


def Main(argv: Optional[Sequence[str]] = None) -> Dict:
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--repeat', type=int, default=5, help='repetitions, best counts (default 5)')
    parser.add_argument('--instructions', action='store_true',
                        help='also count the instructions of the solver calls of (a) under callgrind (needs valgrind)')
    parser.add_argument('--json', metavar='FILE', help='save every number to FILE (JSON)')
    args = parser.parse_args(argv)
    printing, exu.config.printToConsole = exu.config.printToConsole, False
    try:
        data = {'loadAverage': list(os.getloadavg()), 'ratios': SpeedRatios(args.repeat),
                'sweep': SweepCost(max(1, args.repeat // 2)), 'meshes': MeshScaling(max(1, args.repeat // 2))}
    finally:
        exu.config.printToConsole = printing
    data['loadAverageAfter'] = list(os.getloadavg())
    if args.instructions:
        for name in ('reel-P1', 'reel-P7'):
            counts = {model: count_instructions.CountInstructions(model, name) for model in ('ours', 'lsoda')}
            data['ratios'][name].update(oursInstructions=counts['ours'], scipyInstructions=counts['lsoda'],
                                        ratioInstructions=counts['lsoda'] / counts['ours'])
    for name, target in (('reel-P1', 'p1Ratio'), ('reel-P7', 'p7Ratio')):
        r = data['ratios'][name]
        counted = (f", instructions {r['oursInstructions'] / 1e6:.0f} M / {r['scipyInstructions'] / 1e6:.0f} M "
                   f"(x{r['ratioInstructions']:.1f})" if 'ratioInstructions' in r else '')
        print(f"{name}: ours {r['ours'] * 1e3:.1f} ms (CPU {r['oursCpu'] * 1e3:.1f}), scipy LSODA {r['scipy'] * 1e3:.0f} ms "
              f"(CPU {r['scipyCpu'] * 1e3:.0f}): x{r['ratio']:.1f} (CPU x{r['ratioCpu']:.1f}{counted}); target >= "
              f"{TARGETS[target]:g} in CPU time: {'MET' if r['ratioCpu'] >= TARGETS[target] else 'NOT MET'}; "
              f"{r['solver']}")
    s = data['sweep']
    print(f"sweep of the seven presets: default {s['default']['seconds']:.3f} s ({s['default']['checkedRuns']} runs "
          f"checked), without the check {s['off']['seconds']:.3f} s, forced {s['forced']['seconds']:.3f} s: default / "
          f"off = {s['defaultOverOff']:.2f} (target <= {TARGETS['sweepCheckCost']:g}: "
          f"{'MET' if s['defaultOverOff'] <= TARGETS['sweepCheckCost'] else 'NOT MET'}), forced / off = "
          f"{s['forcedOverOff']:.2f}")
    print('meshes in one system (0.5 s of reel-P1 each): ' + ', '.join(
        f"N={n}: {m['seconds'] * 1e3:.1f} ms ({m['perMesh'] * 1e3:.1f} ms per mesh)" for n, m in data['meshes'].items()))
    print(f"load average before {data['loadAverage'][0]:.2f}, after {data['loadAverageAfter'][0]:.2f}")
    if args.json:
        Path(args.json).write_text(json.dumps(data, indent=1, default=str))
        print(f"wrote {Path(args.json).resolve()}", file=sys.stderr)
    return data


if __name__ == '__main__':
    Main()
