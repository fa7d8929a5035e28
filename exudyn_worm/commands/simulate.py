"""``exudyn-worm simulate``: time-domain simulation of the reel changer with the worm-gear connector."""
from __future__ import annotations

import argparse
import math
import sys
import warnings
from pathlib import Path
from typing import List, Tuple

from ..cli import BadInput, DriveFromArgs, PrintJson, StdoutToStderr, Subcommand

__all__ = ['COMMAND', 'ParseWindows']


def ParseWindows(text: str) -> List[Tuple[float, float]]:
    """Parse ``'0:2,2:6,6:8'`` into [(0, 2), (2, 6), (6, 8)] (seconds).

    Parameters
    ----------
    text : str
        Comma-separated windows ``T0:T1`` in s.

    Raises
    ------
    ValueError
        For a malformed list or a window with t1 <= t0 or t0 < 0.
    """
    windows = []
    for part in text.split(','):
        try:
            t0, t1 = (float(x) for x in part.split(':'))
        except ValueError:
            raise ValueError(f"--windows: expected T0:T1[,T0:T1...] in s, e.g. 0:2,2:6,6:8, got '{text}'") from None
        if not (0 <= t0 < t1) or not all(map(math.isfinite, (t0, t1))):
            raise ValueError(f"--windows: each window needs 0 <= T0 < T1 (s), got '{part}'")
        windows.append((t0, t1))
    return windows


_SIMULATE_HEADER = '{:>12} {:>20} {:>10} {:>7} {:>6} {:>16}  chatter'.format(
    'window [s]', "max|phi2''| rad/s^2", 'max Fn kN', 'f Hz', 'S<0 %', "min phi1' rad/s")
_SIMULATE_FIGURES = ('overview', 'acceleration', 'speed', 'normalForce', 'driveTorque')


def _SaveFigures(result, folder: Path) -> List[Path]:
    """Write the standard figures of a simulation as PNG files into ``folder``."""
    from .. import plot
    folder.mkdir(parents=True, exist_ok=True)
    paths = []
    for kind in _SIMULATE_FIGURES:
        path = folder / f'{kind}.png'
        plot.SaveFigure(plot.PlotSimulation(result, kind=kind), path)
        paths.append(path)
    return paths


def _AddArguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument('--end-time', type=float, default=None, metavar='S',
                        help='simulated time in s (default: one full rotation, 8 s at the paper\'s speed)')
    parser.add_argument('--step-size', type=float, default=None, metavar='S',
                        help='time step in s (default: from the drive, 0.039 / its highest natural frequency); refused '
                             'if it cannot resolve that frequency (rule in exudyn_worm/stepsize.py)')
    parser.add_argument('--windows', default=None, metavar='T0:T1,...',
                        help='evaluation windows in s (default: the lift / lower / lift phases of one rotation)')
    parser.add_argument('--plot', default=None, metavar='DIR', help='write PNG figures into DIR')
    parser.add_argument('--csv', default=None, metavar='FILE', help='write the time series to FILE (CSV)')
    parser.add_argument('--python-user-functions', action='store_true',
                        help='evaluate the connector in Python instead of C++ (debugging; same results, slower)')


def _Run(args: argparse.Namespace) -> int:
    from ..reelchanger import DefaultWindows, SimulateReelChanger
    from ..stepsize import CheckStepSize, CoarseStepWarning
    parameters, drive = DriveFromArgs(args)
    with BadInput(), warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter('always', CoarseStepWarning)
        if args.step_size is not None:
            CheckStepSize(parameters, args.step_size, 'simulate --step-size')
    for warning in caught:
        print(f"exudyn-worm: warning: {warning.message}", file=sys.stderr)
    with BadInput():
        windows = ParseWindows(args.windows) if args.windows else DefaultWindows(parameters)
        endTime = args.end_time if args.end_time is not None else max(
            DefaultWindows(parameters)[-1][1], max(t1 for _, t1 in windows))
        if max(t1 for _, t1 in windows) > endTime:
            raise ValueError(f"--windows: a window ends after --end-time = {endTime:g} s")
        with StdoutToStderr(args.json), warnings.catch_warnings():
            warnings.simplefilter('ignore', CoarseStepWarning)      # reported above
            result = SimulateReelChanger(parameters, endTime=endTime,
                                         stepSize=args.step_size,
                                         useSymbolic=not args.python_user_functions)
        metrics = result.WindowMetrics(windows)
    written = []
    if args.csv:
        written.append(result.ToCsv(args.csv))
    if args.plot:
        written += _SaveFigures(result, Path(args.plot))
    if args.json:
        PrintJson({'endTime': result.endTime, 'steps': result.steps, 'solveSeconds': result.solveSeconds,
                    'windows': metrics})
    else:
        print(f"simulated {result.endTime:g} s in {result.steps} steps, solver time {result.solveSeconds:.3f} s")
        print(_SIMULATE_HEADER)
        for m in metrics:
            print(f"{m['t0']:>5.2f} - {m['t1']:<5.2f}{m['maxAbsWheelAcceleration']:>20.1f} {m['maxNormalForce'] / 1e3:>10.1f} "
                  f"{m['dominantFrequencyHz']:>7.1f} {100 * m['fractionSNegative']:>6.0f} {m['minWormSpeed']:>16.2f}  "
                  f"{'YES' if m['chatter'] else 'no'}")
    for path in written:
        print(f"wrote {Path(path).resolve()}", file=sys.stderr)
    return 0


COMMAND = Subcommand('simulate', 'time-domain simulation of the reel changer with the Exudyn worm-gear connector',
                     _AddArguments, _Run)
