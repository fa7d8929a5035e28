"""``exudyn-worm chatter``: how strong the steady chatter of the lowering phase gets along one parameter."""
from __future__ import annotations

import argparse
import sys
from typing import Tuple

from .main import (BadInput, CheckFigurePath, PositiveInt, PrintJson, SourceText, StdoutToStderr, Subcommand,
                   UsageError, WholeDriveFromArgs)

__all__ = ['COMMAND', 'ParseVary']

#: orbits in each direction of a branch of ``--vary`` unless ``--max-points`` says otherwise
_MAX_POINTS = 60


class _Once(argparse.Action):
    """An option given at most once: a second ``--vary`` is refused instead of replacing the first."""

    def __call__(self, parser, namespace, values, option_string=None):
        previous = getattr(namespace, self.dest, None)
        if previous is not None:
            raise argparse.ArgumentError(self, f"expected once (one parameter is continued), got {previous!r} and "
                                               f"{values!r}")
        setattr(namespace, self.dest, values)


def ParseVary(text: str) -> Tuple[str, float, float]:
    """``NAME=LOW:HIGH`` -> (name, low, high) in SI units; each bound a plain SI number or a number with a unit
    (``motorSpeed=80rpm:89rpm``, ``backlash=0.2mm:0.5mm``), as ``--set`` takes it.

    Parameters
    ----------
    text : str
        The ``--vary`` value, e.g. ``J1=0.05:0.3``.

    Raises
    ------
    UsageError
        If it is malformed, a bound has the wrong unit, or ``LOW >= HIGH``.
    """
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..drive.config import ParseQuantity
    name, sep, rest = text.partition('=')
    parts = rest.split(':')
    name = name.strip()
    if not sep or len(parts) != 2 or not name or not all(p.strip() for p in parts):
        raise UsageError(f"--vary must be NAME=LOW:HIGH in SI units or with units (e.g. J1=0.05:0.3, "
                         f"motorSpeed=80rpm:89rpm), got {text!r}")
    bounds = []
    for bound, part in zip(('LOW', 'HIGH'), parts):    # a unit, a finite number (nan is no bound), a known key
        try:
            bounds.append(float(ParseQuantity(name, part.strip())))
        except (ValueError, TypeError) as err:
            raise UsageError(f"--vary {text}: {bound}: {err}") from None
    low, high = bounds
    if not low < high:
        raise UsageError(f"--vary {text}: LOW must be below HIGH, got {low:g}:{high:g}")
    return name, low, high


def _AddArguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument('--vary', metavar='NAME=LOW:HIGH', default=None, action=_Once,
                        help='the parameter to continue and its range in SI units or with units, e.g. J1=0.05:0.3 '
                             'or motorSpeed=80rpm:89rpm (the output is in SI units; a drive with shaft bearings: '
                             'also their keys, e.g. wheelRadialStiffness=0.9e9:1.1e9); without it: the steady chatter '
                             'at the drive\'s own lowering operating point, one orbit')
    parser.add_argument('--plot', metavar='FILE.png', default=None,
                        help='draw the branch (stable solid, unstable dashed, linear boundary dotted) into FILE '
                             '(.png, .pdf or .svg)')
    parser.add_argument('--max-points', type=PositiveInt('orbits'), default=None, dest='max_points',
                        help=f'with --vary: largest number of orbits in each direction (default {_MAX_POINTS})')


def _Run(args: argparse.Namespace) -> int:
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.orbits.chatterbranch import AnalyzeChatterBranch
    from ..analysis.orbits.smoothbranch import ChatterBranchError
    from ..analysis.orbits.lowering import LoweringPhaseDrive
    from .formatchatter import FormatBranch
    name, low, high = ParseVary(args.vary) if args.vary is not None else (None, None, None)
    with BadInput():      # any drive: the periodic orbits of its lowering phase
        drive = WholeDriveFromArgs(args)
        loweringDrive = LoweringPhaseDrive(drive)
    if name is None:
        return _RunSteady(args, drive, loweringDrive)
    if args.plot:
        CheckFigurePath(args.plot, '--plot')
    try:
        with StdoutToStderr(args.json), BadInput():
            branch = AnalyzeChatterBranch(loweringDrive, name, low, high, maxPoints=args.max_points or _MAX_POINTS)
    except UsageError as err:
        partial = getattr(err.__cause__, 'branch', None)
        if partial is not None and partial.points:                 # keep the points computed so far
            if args.json:
                PrintJson(partial.ToDict())
            else:
                print('\n'.join(FormatBranch(partial, 'exudyn-worm chatter (incomplete)')))
        raise
    if args.plot:
        path = branch.plot(args.plot)
        print(f'wrote {args.plot}', file=sys.stderr)
    if args.json:
        PrintJson(branch.ToDict())
        return 0
    model = ', 3D model' if drive.isRigidBody else ''
    print('\n'.join(FormatBranch(branch, f"exudyn-worm chatter: {SourceText(args)}, {name} in [{low:g}, {high:g}], "
                                         f"lowering phase (constant load torque){model}")))
    return 0


def _RunSteady(args: argparse.Namespace, drive, loweringDrive) -> int:
    """The steady chatter at the lowering operating point: one periodic orbit of the one-angle model, or of the 3D
    model for a drive with shaft bearings (or, where no orbit converges, its settled long simulation)."""
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.orbits.chatter import SteadyChatterSummary
    from ..analysis.stability.drivestability import DIVERGENCE, AnalyzeDrive, GrowthText, StateInstability
    from ..analysis.orbits.periodic import NoSteadyChatter
    from .formatchatter import FormatSteadyChatter
    if args.plot:
        raise UsageError("chatter: --plot draws the branch of --vary; without --vary there is one orbit to report")
    if args.max_points is not None:
        raise UsageError(f"chatter: --max-points bounds the branch of --vary; without --vary there is one orbit to "
                         f"report, got --max-points {args.max_points}")
    with BadInput():
        lowering = AnalyzeDrive(drive).State(-1)
    divergence = None
    if StateInstability(lowering) == DIVERGENCE:      # a runaway or creep, which no chatter orbit describes
        divergence = (f"the lowering operating point diverges: {GrowthText(float(lowering.maxRealPart), 0., DIVERGENCE)}"
                      f"; what follows is the periodic orbit a time simulation settles on, if any")
        if not args.json:
            print(f"exudyn-worm chatter: note: {divergence}", file=sys.stderr)
    try:
        with StdoutToStderr(args.json), BadInput():
            summary = SteadyChatterSummary(loweringDrive)
    except UsageError as err:         # no steady chatter is a result, not an error
        if not isinstance(err.__cause__, NoSteadyChatter):
            raise
        reason = str(err.__cause__).split(': ', 1)[-1]
        if args.json:
            PrintJson({'steadyChatter': False, 'reason': reason, 'divergence': divergence})
        else:
            print(f"exudyn-worm chatter: {SourceText(args)}, lowering phase (constant load torque): {reason}")
        return 0
    if args.json:
        PrintJson({**summary, 'divergence': divergence})
        return 0
    print('\n'.join(FormatSteadyChatter(summary, f"exudyn-worm chatter: {SourceText(args)}, steady chatter of the "
                                                  f"lowering phase (constant load torque)")))
    return 0


COMMAND = Subcommand('chatter', 'steady chatter amplitude along one parameter: periodic orbits, Floquet stability, '
                     'continuation', _AddArguments, _Run)
