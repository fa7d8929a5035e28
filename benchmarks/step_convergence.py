"""Window peaks of every reel preset at the default step against a converged step.

For each preset (``reel-P1`` ... ``reel-P7``), one rotation with :func:`~exudyn_worm.SimulateReelChanger`'s defaults,
then the same run at half the step, a quarter, ... until no window peak (max |phi2''|, max |Fn|) changes by more
than ``--tolerance`` (0.05 %) from one halving to the next, or ``--max-halvings`` is reached. Prints per preset and
window the peaks at the default step, at the finest step and their relative difference; ``--json FILE`` also saves
every number. Run: ``python benchmarks/step_convergence.py [--presets reel-P7 figure19] [--json /tmp/c.json]`` (a
few minutes for all seven; P7 alone about 1 min); nothing is written unless ``--json`` is given. A halving that
would exceed the run-size limit of ``SimulateReelChanger`` is not run (the preset is then reported as not
converged).
"""
from __future__ import annotations

import argparse
import json
import sys

__all__ = ['PEAKS', 'WindowPeaks', 'Converge', 'main']

#: the window peaks judged: those the paper's figures show
PEAKS = ('maxAbsWheelAcceleration', 'maxNormalForce')


def _Parameters(preset: str) -> dict:
    """A preset (``reel-P1``, ...), a shipped drive (``figure19``, ...) or a drive file (``*.toml``)."""
    from exudyn_worm.params.drives import ConfigPath
    from exudyn_worm.drive.config import ResolveParameters
    return ResolveParameters(preset) if preset.startswith('reel-') else ResolveParameters(config=ConfigPath(preset))


def WindowPeaks(preset: str, divisor: int = 1) -> dict:
    """Peaks per default window of one rotation of ``preset`` (see :func:`_Parameters`; a drive file: its duty's
    windows) at the recommended step / ``divisor``."""
    from exudyn_worm import SimulateReelChanger
    from exudyn_worm.analysis.simulation.reelchanger import DefaultWindows
    from exudyn_worm.analysis.simulation.stepsize import RecommendedStepSize
    from exudyn_worm.drive.wholedrive import ResolveDrive
    p = _Parameters(preset)
    drive = ResolveDrive(parameters=p)
    h = RecommendedStepSize(drive) / divisor
    result = SimulateReelChanger(drive, stepSize=h, progress=False)
    metrics = result.WindowMetrics(DefaultWindows(drive))
    return {'stepSize': h, 'solveSeconds': result.solveSeconds, 'chatter': [m['chatter'] for m in metrics],
            'windows': [[m[k] for k in PEAKS] for m in metrics]}


def _Change(a: dict, b: dict) -> float:
    return max(abs(x / y - 1.) for wa, wb in zip(a['windows'], b['windows']) for x, y in zip(wa, wb))


def Converge(preset: str, tolerance: float = 5e-4, maxHalvings: int = 6) -> list:
    """Runs of ``preset`` at the default step and halved steps until the peaks change by less than ``tolerance``."""
    from exudyn_worm.analysis.simulation.reelchanger import MAX_STEPS, DefaultSimulatedTime
    from exudyn_worm.analysis.simulation.stepsize import RecommendedStepSize
    from exudyn_worm.drive.wholedrive import ResolveDrive
    drive = ResolveDrive(parameters=_Parameters(preset))
    runs = [WindowPeaks(preset)]
    for k in range(1, maxHalvings + 1):
        if DefaultSimulatedTime(drive) * 2 ** k / RecommendedStepSize(drive) > MAX_STEPS:
            break                       # the run-size limit of SimulateReelChanger: not converged
        runs.append(WindowPeaks(preset, 2 ** k))
        if _Change(runs[-2], runs[-1]) < tolerance:
            break
    return runs


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--presets', nargs='+', default=[f'reel-P{i}' for i in range(1, 8)],
                        help='presets, shipped drives (figure19, ...) or drive files (*.toml); default reel-P1 ... reel-P7')
    parser.add_argument('--tolerance', type=float, default=5e-4, help='converged: change below this (0.05 %%)')
    parser.add_argument('--max-halvings', type=int, default=6)
    parser.add_argument('--json', help='also save every number to this file')
    args = parser.parse_args(argv)
    out = {}
    for preset in args.presets:
        runs = out[preset] = Converge(preset, args.tolerance, args.max_halvings)
        last = runs[-1]
        change = _Change(runs[-2], last) if len(runs) > 1 else float('nan')
        print(f"{preset}: default step {runs[0]['stepSize']:.3g} s, finest {last['stepSize']:.3g} s "
              f"({'converged' if change < args.tolerance else 'NOT converged'}: last change {change:.3%})")
        for i, (w0, w1) in enumerate(zip(runs[0]['windows'], last['windows'])):
            cells = '  '.join(f"{name} {a:.5g} / {b:.5g} ({a / b - 1.:+.2%})" for name, a, b in zip(PEAKS, w0, w1))
            print(f"  window {i} ({runs[0]['chatter'][i]}): {cells}")
        sys.stdout.flush()
    if args.json:
        with open(args.json, 'w') as f:
            json.dump(out, f, indent=1)
        print(f"saved {args.json}")


if __name__ == '__main__':
    main()
