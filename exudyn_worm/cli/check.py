"""``exudyn-worm check``: the design check. The verdict of ``exudyn-worm stability`` (the drive's own operating
points), the self-locking verdicts at each of them, where a two-mass drive sits on its chart, and the smallest changes
of J1, J2, kT, the damping and the chains that make it stable with a margin
(:func:`exudyn_worm.analysis.design.DesignCheck`)."""
from __future__ import annotations

import argparse
import math
import sys
from typing import TYPE_CHECKING, List

from .main import (AddOverwriteOption, BadInput, CheckFigurePath, PositiveFloat, PrintJson, SourceText, StdoutToStderr, Subcommand, UsageError, WholeDriveFromArgs)
from .._files import WriteAtomically
from .stability import DangerLines, OperatingPointLines

if TYPE_CHECKING:
    from ..analysis.drivestability import DriveAnalysis

__all__ = ['COMMAND', 'FormatDesignCheck', 'SelfLockingLines']

def _AddArguments(parser: argparse.ArgumentParser) -> None:
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.designrules import DEFAULT_MARGIN, DEFAULT_SPAN
    parser.add_argument('--margin', type=float, default=DEFAULT_MARGIN, metavar='DECADES',
                        help=f'stability margin in decades of the changed parameter (default {DEFAULT_MARGIN:g}: '
                             f'the drive stays stable if that parameter is off by a factor {10 ** DEFAULT_MARGIN:.2f})')
    parser.add_argument('--span', type=float, default=DEFAULT_SPAN, metavar='FACTOR',
                        help=f'search changes up to this factor in each direction (default {DEFAULT_SPAN:g})')
    parser.add_argument('--plot', default=None, metavar='FILE.png',
                        help='draw the check into FILE: for the two-mass drive its point on the chart that decides (at the '
                             'deciding operating point), the boundary and the recommended moves; for a drive with '
                             'chains, an axial bearing or a motor characteristic the stable range of each scanned '
                             'parameter and the moves')
    AddOverwriteOption(parser, 'the --plot file')
    parser.add_argument('--simulate', action='store_true',
                        help='confirm each recommendation with the time-domain reel-changer simulation '
                             '(chatter while lowering, as `exudyn-worm simulate` decides it); needs loadMass, '
                             'leverArm and motorSpeed')
    parser.add_argument('--step-size', type=PositiveFloat('s'), default=None, metavar='S',
                        help='time step of the --simulate runs in s (default: each drive\'s recommended step, as simulate)')
    group = parser.add_mutually_exclusive_group()
    group.add_argument('--disturbance', dest='disturbance', action='store_const', const='yes', default='auto',
                       help='also say whether a linearly stable drive chatters after a worm-speed disturbance '
                            '(steady chatter found by shooting, smallest kick by bisection on simulations; up to '
                            'about 10 s). Default: only for a drive with backlash, where rest and chatter can coexist; '
                            'needs loadMass, leverArm and motorSpeed')
    group.add_argument('--no-disturbance', dest='disturbance', action='store_const', const='no',
                       help='skip the disturbance verdict (also for a drive with backlash)')
    parser.add_argument('--quiet', action='store_true', help='no progress bar on stderr')


def _Factor(f: float) -> str:
    return f'x{f:.3g}' if f >= 1 else f'/{1 / f:.3g}'


def _G(x, digits: int = 4) -> str:
    return 'n/a' if x is None or (isinstance(x, float) and math.isnan(x)) else \
        'inf' if math.isinf(x) else f'{x:.{digits}g}'


def _Simulated(chatter) -> str:
    return '' if chatter is None else ('CHATTER' if chatter else 'no chatter')


#: a recommended Lehr damping ratio D_T or D_V from which the table adds a remark (half of critical damping)
HEAVY_DAMPING = 0.5


def SelfLockingLines(analysis: DriveAnalysis) -> List[str]:
    """Static and dynamic self-locking at every operating point of the drive's duty (at rest without one), with the
    gear makers' rating (grey zone) and a ``DANGER`` line where the load holds at rest but runs away once moving.

    Parameters
    ----------
    analysis : DriveAnalysis
        Result of :func:`~exudyn_worm.analysis.drivestability.AnalyzeDrive`.

    Returns
    -------
    list of str
    """
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..model.selflocking import GREY_ZONE
    state = lambda s: 'n/a (no speed)' if s is None else \
        f"{'yes' if s.selfLocking else 'no'} (mu {s.mu:.4g}, worm-driving efficiency {s.efficiencyWormDriving:.3g}: {s.rating})"
    low, high = GREY_ZONE
    lines = [f"Self-locking (static: at rest; dynamic: at the operating point's sliding speed; rated by the worm-driving "
             f"efficiency: self-locking below {low:g}, grey zone {low:g} to {high:g}, none above {high:g}):"]
    for label, v in analysis.selfLockingVerdicts.items():
        lines.append(f"  {label}: at rest {state(v.static)}; moving {state(v.dynamic)}")
    return lines + DangerLines(analysis)


def FormatDesignCheck(result, title: str = 'Design check') -> List[str]:
    """Human-readable report of a :class:`~exudyn_worm.analysis.design.DesignCheckResult` (the ``check`` output).

    Parameters
    ----------
    result : DesignCheckResult
        From :func:`~exudyn_worm.analysis.design.DesignCheck` (optionally :func:`~exudyn_worm.analysis.designconfirm.ConfirmBySimulation`).
    title : str, optional
        First line.

    Returns
    -------
    list of str
        The lines, without trailing newlines.
    """
    a = result.analysis
    p = result.chartPoint
    lines = [title, '']
    states = '; '.join(f"S = {S:+d}: {'stable' if s.stable else 'UNSTABLE'}, max Re(lambda) = {s.maxRealPart:.4g} 1/s"
                       for S, s in result.ContactStates().items())
    verdict = ('STABLE with margin' if result.stableWithMargin else
               f"stable, but within the margin along {', '.join(result.marginShortBy)}" if result.stable else
               'UNSTABLE (chatter expected)')
    lines.append(f"Verdict: {verdict} ({states})")
    lines.append(a.decidingText[0].upper() + a.decidingText[1:])
    drive = result.drive
    lines.append('Model: ' + ('eqs. (15)-(19), the two-mass drive of Figure 2' if drive.isTwoMass else
                              f"linearized Exudyn model of the whole drive (it has {drive.ComponentsText()})"))
    if result.simulatedChatter is not None:
        lines.append(f"Simulation (reel changer, lowering): {_Simulated(result.simulatedChatter)}")
    lines += SelfLockingLines(a)
    if result.chartApplies:
        distance = ('no boundary within 2 decades' if result.distanceToBoundary is None else
                    f"{result.distanceToBoundary:.3g} decades to the stability boundary (at x = "
                    f"{result.nearestBoundaryPoint['x']:.4g}, y = {result.nearestBoundaryPoint['y']:.4g})")
        atPoint = ' (charts at mu(v0) and slope of the deciding operating points)' \
            if drive.gear.speedDependentFriction and a.operatingPoints else ''
        lines.append(f"Chart point: x = kT/(kV r1^2) = {p['x']:.4g}, y = J1/J2 = {p['y']:.4g}, D_V = {_G(p['DV'])}, "
                     f"D_TV = {_G(p['DTV'])}; {distance}{atPoint}")
    else:
        lines.append(f"Chart point: none; the stability chart (eqs. (15)-(19)) describes the two-mass drive, this "
                     f"drive has {drive.ComponentsText()}")
    lines.append(f"Margin: {result.margin:g} decades (factor {10 ** result.margin:.3g}): a recommended drive stays "
                 f"stable if the changed parameter is off by that factor either way")
    held = [k for k in result.scans if k not in ('J1', 'J2', 'kT')]
    if held:
        lines.append(f"Held while J1, J2, kT change: {', '.join(held)} (as the parameter set gives them)")
    lines += [f"Note: {n}" for n in result.notes]
    lines += [''] + OperatingPointLines(a)
    if result.stableWithMargin:
        lines += ['', 'No change needed.']
        return lines
    simulated = any(r.simulatedChatter is not None for r in result.recommendations)
    header = f"  {'parameter':<10}{'change':>10}{'new value':>14}  {'unit':<10}{'max Re after [1/s]':>20}"
    if simulated:
        header += '  simulated'
    if result.recommendations:
        lines += ['', f"Smallest single changes that make the drive stable with margin (within a factor "
                      f"{result.span:g}):", header]
        for r in result.recommendations:
            row = (f"  {r.parameter:<10}{_Factor(r.factor):>10}{r.newValue:>14.4g}  {r.unit:<10}"
                   f"{r.maxRealPartAfter:>20.3g}")
            lines.append(row + (f"  {_Simulated(r.simulatedChatter)}" if simulated else ''))
    heavy = [r for r in result.recommendations if r.parameter in ('DT', 'DV') and r.newValue >= HEAVY_DAMPING]
    if heavy:
        lines.append('Note: ' + ' and '.join(f"{r.parameter} = {r.newValue:.3g}" for r in heavy)
                     + " are damping ratios near or above critical damping (1); the paper's largest are D_V = 0.056 "
                       "and D_T = 0.35 (D_TV = 25 at D_V = 0.014): reachable only with a dedicated damper")
    missing = result.Missing()
    if missing and result.recommendations:
        lines.append('No ' + ', '.join(f"{'increase' if d > 0 else 'decrease'} of {k}" for k, d in missing)
                     + f" within a factor {result.span:g} gives stability with margin.")
    if not result.recommendations:
        lines += ['', f"No single parameter within a factor {result.span:g} makes the drive stable with margin."]
        pair = result.bestPair
        if pair is None:
            lines.append('No pair of parameters does either.' if drive.isTwoMass else
                         'Pairs of parameters are not searched for a whole drive.')
        else:
            changes = ' and '.join(f"{k} {_Factor(f)} (to {v:.4g} {u})" for k, f, v, u in
                                   zip(pair.parameters, pair.factors, pair.newValues, pair.ToDict()['units']))
            lines.append(f"Best pair: {changes}; max Re after = {pair.maxRealPartAfter:.3g} 1/s"
                         + (f"; simulated: {_Simulated(pair.simulatedChatter)}" if pair.simulatedChatter is not None
                            else ''))
    return lines


def _Run(args: argparse.Namespace) -> int:
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis import design, designconfirm
    from ..analysis.designscan import DesignKeys
    from ..progress import ProgressBar
    plotPath = CheckFigurePath(args.plot, '--plot', args.overwrite) if args.plot is not None else None
    drive = WholeDriveFromArgs(args)              # resolved once: every analysis below takes this drive
    parameters = dict(drive.parameters)
    if args.simulate:
        # lazy: start-up (exudyn-worm --help imports every command module)
        from ..setups.build import CheckReelChangerKeys
        with BadInput():
            CheckReelChangerKeys(parameters, 'check --simulate')
    elif args.step_size is not None:
        raise UsageError(f"--step-size {args.step_size:g} only applies with --simulate")
    quiet = True if getattr(args, 'quiet', False) else None
    with BadInput(), StdoutToStderr(args.json):
        keys, _ = DesignKeys(drive)
        with ProgressBar(total=len(keys), desc='check', unit='parameter', quiet=quiet) as bar:
            result = design.DesignCheck(drive, margin=args.margin, span=args.span, progress=bar.update)
    if args.simulate:
        runs = 1 + len(result.recommendations) + (result.bestPair is not None)
        with ProgressBar(total=runs, desc='check --simulate', unit='run', quiet=quiet) as bar:
            with BadInput(), StdoutToStderr(args.json):
                result = designconfirm.ConfirmBySimulation(result, stepSize=args.step_size, progress=bar.update)
    loadSide = None
    if drive.loadSideChain:          # as stability: may the driven machine be lumped into J2? which stage is not?
        # lazy: start-up (exudyn-worm --help imports every command module)
        from ..analysis.loadside import DiagnoseLoadSide
        with StdoutToStderr(args.json), BadInput():
            loadSide = DiagnoseLoadSide(parameters, args.margin)
    disturbance = _DisturbanceVerdict(args, parameters, result)
    if plotPath is not None:
        # lazy: start-up (exudyn-worm --help imports every command module)
        from ..plotting.plot import SaveFigure
        try:
            figure = result.plot(title=f'exudyn-worm check: {SourceText(args)}')
            WriteAtomically(plotPath, lambda tmp: SaveFigure(figure, tmp))
        except OSError as err:
            raise UsageError(f"--plot {plotPath}: cannot write: {err.strerror or err}") from err
    if args.json:
        data = {**result.ToDict(), 'method': 'analytical' if result.analysis.model == 'analytical' else 'exudyn'}
        if disturbance is not None:
            data['disturbance'] = disturbance.ToDict()
        if loadSide is not None:
            data['loadSide'] = loadSide.ToDict()
        PrintJson(data)
    else:
        lines = FormatDesignCheck(result, title=f"exudyn-worm check: {SourceText(args)}")
        if disturbance is not None:
            lines.insert(3, f"After a disturbance (lowering, nonlinear mesh): {disturbance.text}")
        if loadSide is not None:
            lines.insert(5, f"Load side: {loadSide.Text()}.")
        print('\n'.join(lines))
    if plotPath is not None:
        print(f"wrote {plotPath.resolve()}", file=sys.stderr)
    return 0


def _DisturbanceVerdict(args: argparse.Namespace, parameters, result):
    """:func:`~exudyn_worm.analysis.disturbance.ChattersAfterDisturbance` of the drive, or None where it is not asked
    for: ``--no-disturbance``; by default only for a drive with backlash that is linearly stable while lowering
    (S = -1) and has the reel changer's keys. ``--disturbance`` asks for it for any drive (missing keys: exit 2)."""
    if args.disturbance == 'no':
        return None
    if args.disturbance == 'auto':
        # lazy: start-up (exudyn-worm --help imports every command module)
        from ..setups.presets import REEL_KEYS
        lowering = result.ContactStates().get(-1)
        if not (float(parameters.get('backlash', 0.)) > 0. and lowering is not None and lowering.stable
                and all(k in parameters for k in REEL_KEYS)):
            return None
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.disturbance import ChattersAfterDisturbance
    from ..setups.build import CheckReelChangerKeys
    if args.disturbance == 'auto':
        try:
            with StdoutToStderr(args.json):
                return ChattersAfterDisturbance(parameters)
        except ValueError:          # a drive the lowering model refuses (a motor on its characteristic): as before
            return None
    with BadInput():
        CheckReelChangerKeys(parameters, 'check --disturbance')
        with StdoutToStderr(args.json):
            return ChattersAfterDisturbance(parameters)


COMMAND = Subcommand('check', 'design check: stable or not, distance to the stability boundary and the smallest '
                     'changes that make the drive stable with a margin', _AddArguments, _Run)
