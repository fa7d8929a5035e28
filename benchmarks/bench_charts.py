"""Benchmark of the stability charts: a 1000 x 1000 chart (mask), its largest real part, boundaries, ranges.

Run ``python benchmarks/bench_charts.py`` (about 30 s on a loaded 2-core machine); ``--repeat N`` sets the
repetitions (the minimum counts), ``--resolution N`` the grid. Prints one table; writes nothing.

Timed, on the gear of set (25) (preset 'chart'), D_V = 0.014, D_TV = 1, S = -1, the default domain:

- ``mask``: :func:`~exudyn_worm.analysis.charts.stabilitychart.ComputeStabilityChart` (coefficients (16) on the grid, Hurwitz (17)-(19),
  the margin field), the target is under 1 s;
- ``maxRealPart``: the largest real part of the eigenvalues on the whole grid (closed-form quartic + Newton
  polish, :func:`~exudyn_worm.analysis.charts.quartic.MaxRealPart`);
- ``eigvals``: numpy's batched ``eigvals`` of the companion matrices on a 100000-point subset, scaled to the
  grid (the straightforward alternative to ``maxRealPart``);
- ``boundaries``: marching squares and joining into curves; ``ranges``: the refined unstable x and y ranges.
"""
from __future__ import annotations

import argparse
import os
import platform
import sys
import time
from typing import Dict, Optional, Sequence

import numpy as np

from exudyn_worm.analysis.charts.stabilitychart import ComputeStabilityChart
from exudyn_worm.analysis.charts.quartic import MaxRealPart
from exudyn_worm.drive.presets import GearFromParameters, GetPreset

__all__ = ['TimeCharts', 'main']


def _Best(function, repeat: int) -> float:
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        function()
        best = min(best, time.perf_counter() - t0)
    return best


def TimeCharts(resolution: int = 1000, repeat: int = 3, DV: float = 0.014, DTV: float = 1.) -> Dict[str, float]:
    """Best-of-``repeat`` wall-clock seconds of the chart's parts (see the module docstring).

    Parameters
    ----------
    resolution : int, optional
        Grid points per axis.
    repeat : int, optional
        Repetitions; the minimum is reported.
    DV, DTV : float, optional
        Damping measure and ratio of the chart.

    Returns
    -------
    dict
        Seconds per part, plus ``points`` (grid size), ``fallback`` (points that needed ``eigvals``) and
        ``maxDeviation`` (largest |maxRealPart - eigvals| / omega on the subset).
    """
    parameters = GetPreset('chart')
    gear = GearFromParameters(parameters, meshDamping=False)
    J2 = parameters['J2']
    Make = lambda: ComputeStabilityChart(gear, J2, DV, DTV, resolution=resolution)
    out: Dict[str, float] = {'points': float(resolution**2)}
    out['mask'] = _Best(Make, repeat)
    chart = Make()
    b = chart.Coefficients()
    out['maxRealPart'] = _Best(lambda: MaxRealPart(b), repeat)
    value, fallback = MaxRealPart(b, returnFallback=True)
    out['fallback'] = float(fallback.sum())
    flat = b.reshape(4, -1)
    idx = np.random.default_rng(0).choice(flat.shape[1], size=min(100000, flat.shape[1]), replace=False)
    comp = np.zeros((idx.size, 4, 4))
    comp[:, 0, :] = -flat[:, idx].T
    comp[:, 1, 0] = comp[:, 2, 1] = comp[:, 3, 2] = 1.
    seconds = _Best(lambda: np.linalg.eigvals(comp), max(1, repeat - 1))
    out['eigvals'] = seconds * flat.shape[1] / idx.size
    ref = np.linalg.eigvals(comp).real.max(axis=1)
    omega = np.sqrt(np.sqrt(flat[3, idx]))
    out['maxDeviation'] = float(np.max(np.abs(value.reshape(-1)[idx] - ref) / omega))

    def Boundaries():
        c = Make()
        return c.boundaries
    out['boundaries'] = _Best(Boundaries, repeat) - out['mask']

    def Ranges():
        c = Make()
        return c.unstableXRange, c.unstableYRange
    out['ranges'] = _Best(Ranges, repeat) - out['mask']
    return out


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Run the benchmark and print the table. Returns the exit status.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments (default: ``sys.argv[1:]``).
    """
    parser = argparse.ArgumentParser(prog='bench_charts.py', description=__doc__.split('\n\n')[0])
    parser.add_argument('--resolution', type=int, default=1000, metavar='N', help='grid points per axis')
    parser.add_argument('--repeat', type=int, default=3, metavar='N', help='repetitions (minimum reported)')
    args = parser.parse_args(argv)
    if args.resolution < 2 or args.repeat < 1:
        print('bench_charts.py: error: --resolution must be >= 2 and --repeat >= 1', file=sys.stderr)
        return 2
    load = os.getloadavg() if hasattr(os, 'getloadavg') else (float('nan'),) * 3
    print(f'{time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())}, {platform.processor() or platform.machine()}, '
          f'{os.cpu_count()} cores, python {platform.python_version()}, numpy {np.__version__}, '
          f'load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}')
    r = TimeCharts(args.resolution, args.repeat)
    n = args.resolution
    print(f'{n} x {n} chart, set (25), D_V = 0.014, D_TV = 1, S = -1, best of {args.repeat}:')
    rows = [('mask (ComputeStabilityChart)', r['mask']),
            ('maxRealPart (closed form + Newton)', r['maxRealPart']),
            ('numpy eigvals of companion (scaled)', r['eigvals']),
            ('boundaries (marching squares)', r['boundaries']),
            ('unstable x, y ranges (refined)', r['ranges'])]
    for name, seconds in rows:
        print(f'  {name:<38} {seconds:8.3f} s   {seconds / r["points"] * 1e6:7.3f} us/point')
    print(f'  maxRealPart vs eigvals: {r["eigvals"] / r["maxRealPart"]:.1f}x faster, largest deviation '
          f'{r["maxDeviation"]:.1e} omega, eigvals fallback at {int(r["fallback"])} points')
    return 0


if __name__ == '__main__':
    sys.exit(main())
