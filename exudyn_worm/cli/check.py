"""``exudyn-worm check``: the design check. Stable or not, where the drive sits on its chart, and the smallest
changes of J1, J2, kT and the damping that make it stable with a margin (:func:`exudyn_worm.analysis.design.DesignCheck`)."""
from __future__ import annotations

import argparse
import math
import sys
from typing import List

from .main import (AddOverwriteOption, BadInput, CheckFigurePath, DriveFromArgs, PositiveFloat, PrintJson, SourceText,
                   StdoutToStderr, Subcommand, UsageError, WriteAtomically)

__all__ = ['COMMAND', 'FormatDesignCheck']

def _AddArguments(parser: argparse.ArgumentParser) -> None:
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.design import DEFAULT_MARGIN, DEFAULT_SPAN
    parser.add_argument('--margin', type=float, default=DEFAULT_MARGIN, metavar='DECADES',
                        help=f'stability margin in decades of the changed parameter (default {DEFAULT_MARGIN:g}: '
                             f'the drive stays stable if that parameter is off by a factor {10 ** DEFAULT_MARGIN:.2f})')
    parser.add_argument('--span', type=float, default=DEFAULT_SPAN, metavar='FACTOR',
                        help=f'search changes up to this factor in each direction (default {DEFAULT_SPAN:g})')
    parser.add_argument('--plot', default=None, metavar='FILE.png',
                        help='draw the drive\'s point, the stability boundary and the recommended moves into FILE')
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


def FormatDesignCheck(result, title: str = 'Design check') -> List[str]:
    """Human-readable report of a :class:`~exudyn_worm.analysis.design.DesignCheckResult` (the ``check`` output).

    Parameters
    ----------
    result : DesignCheckResult
        From :func:`~exudyn_worm.analysis.design.DesignCheck` (optionally :func:`~exudyn_worm.analysis.design.ConfirmBySimulation`).
    title : str, optional
        First line.

    Returns
    -------
    list of str
        The lines, without trailing newlines.
    """
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..model.stability import CONTACT_STATES
    a = result.analysis
    p = result.chartPoint
    lines = [title, '']
    states = '; '.join(f"S = {S:+d}: {'stable' if a.contact[S].stable else 'UNSTABLE'}, max Re(lambda) = "
                       f"{max(a.contact[S].eigenvalues.real):.4g} 1/s" for S in CONTACT_STATES)
    verdict = ('STABLE with margin' if result.stableWithMargin else
               f"stable, but within the margin along {', '.join(result.marginShortBy)}" if result.stable else
               'UNSTABLE (chatter expected)')
    lines.append(f"Verdict: {verdict} ({states})")
    if result.simulatedChatter is not None:
        lines.append(f"Simulation (reel changer, lowering): {_Simulated(result.simulatedChatter)}")
    lock = result.selfLockingVerdict
    state = lambda s: 'n/a (no motorSpeed)' if s is None else \
        f"{'yes' if s.selfLocking else 'no'} (mu {s.mu:.4g}, worm-driving efficiency {s.efficiencyWormDriving:.3g}: {s.rating})"
    lines.append(f"Self-locking: at rest {state(lock.static)}; moving {state(lock.dynamic)}"
                 + ('; DANGER: holds at rest but runs away once moving' if lock.dangerous else ''))
    distance = ('no boundary within 2 decades' if result.distanceToBoundary is None else
                f"{result.distanceToBoundary:.3g} decades to the stability boundary (at x = "
                f"{result.nearestBoundaryPoint['x']:.4g}, y = {result.nearestBoundaryPoint['y']:.4g})")
    lines.append(f"Chart point: x = kT/(kV r1^2) = {p['x']:.4g}, y = J1/J2 = {p['y']:.4g}, D_V = {_G(p['DV'])}, "
                 f"D_TV = {_G(p['DTV'])}; {distance}")
    lines.append(f"Margin: {result.margin:g} decades (factor {10 ** result.margin:.3g}): a recommended drive stays "
                 f"stable if the changed parameter is off by that factor either way")
    held = [k for k in result.scans if k not in ('J1', 'J2', 'kT')]
    if held:
        lines.append(f"Held while J1, J2, kT change: {', '.join(held)} (as the parameter set gives them)")
    lines += [f"Note: {n}" for n in result.notes]
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
            lines.append('No pair of parameters does either.')
        else:
            changes = ' and '.join(f"{k} {_Factor(f)} (to {v:.4g} {u})" for k, f, v, u in
                                   zip(pair.parameters, pair.factors, pair.newValues, pair.ToDict()['units']))
            lines.append(f"Best pair: {changes}; max Re after = {pair.maxRealPartAfter:.3g} 1/s"
                         + (f"; simulated: {_Simulated(pair.simulatedChatter)}" if pair.simulatedChatter is not None
                            else ''))
    return lines


def _Run(args: argparse.Namespace) -> int:
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.design import ConfirmBySimulation, DesignCheck
    plotPath = CheckFigurePath(args.plot, '--plot', args.overwrite) if args.plot is not None else None
    parameters, _ = DriveFromArgs(args)
    if args.simulate:
        # lazy: start-up (exudyn-worm --help imports every command module)
        from ..analysis.reelchanger import CheckReelChangerKeys
        with BadInput():
            CheckReelChangerKeys(parameters, 'check --simulate')
    elif args.step_size is not None:
        raise UsageError(f"--step-size {args.step_size:g} only applies with --simulate")
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.loadside import LoadSideNotLumpable
    with BadInput():
        try:
            result = DesignCheck(parameters, margin=args.margin, span=args.span)
        except LoadSideNotLumpable as err:       # a valid drive that the two-mass check does not describe
            diagnosis = err.diagnosis
        else:
            diagnosis = None
    if diagnosis is not None:
        return _ReportWholeDrive(args, diagnosis, plotPath)
    if args.simulate:
        # lazy: start-up (exudyn-worm --help imports every command module)
        from ..progress import ProgressBar
        runs = 1 + len(result.recommendations) + (result.bestPair is not None)
        with ProgressBar(total=runs, desc='check --simulate', unit='run',
                         quiet=True if getattr(args, 'quiet', False) else None) as bar:
            with BadInput(), StdoutToStderr(args.json):
                result = ConfirmBySimulation(result, stepSize=args.step_size, progress=bar.update)
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
        data = result.ToDict()
        if disturbance is not None:
            data['disturbance'] = disturbance.ToDict()
        PrintJson(data)
    else:
        lines = FormatDesignCheck(result, title=f"exudyn-worm check: {SourceText(args)}")
        if disturbance is not None:
            lines.insert(3, f"After a disturbance (lowering, nonlinear mesh): {disturbance.text}")
        print('\n'.join(lines))
    if plotPath is not None:
        print(f"wrote {plotPath.resolve()}", file=sys.stderr)
    return 0


def _DisturbanceVerdict(args: argparse.Namespace, parameters, result):
    """:func:`~exudyn_worm.analysis.chatterbranch.ChattersAfterDisturbance` of the drive, or None where it is not asked
    for: ``--no-disturbance``; by default only for a drive with backlash that is linearly stable while lowering
    (S = -1) and has the reel changer's keys. ``--disturbance`` asks for it for any drive (missing keys: exit 2)."""
    if args.disturbance == 'no':
        return None
    if args.disturbance == 'auto':
        # lazy: start-up (exudyn-worm --help imports every command module)
        from ..analysis.reelchanger import REEL_KEYS
        if not (float(parameters.get('backlash', 0.)) > 0. and result.analysis.contact[-1].stable
                and all(k in parameters for k in REEL_KEYS)):
            return None
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.chatterbranch import ChattersAfterDisturbance
    from ..analysis.reelchanger import CheckReelChangerKeys
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


def _ReportWholeDrive(args: argparse.Namespace, diagnosis, plotPath) -> int:
    """A drive whose load-side chain may not be lumped into J2: the whole drive's verdict and the stage that is the
    cause; the two-mass recommendations, chart and simulations do not apply."""
    if plotPath is not None or args.simulate:
        raise UsageError(f"{'--plot' if plotPath is not None else '--simulate'}: the design chart and its "
                         f"recommendations need the two-mass drive; {diagnosis.Text()}")
    if args.json:
        PrintJson({'stable': diagnosis.wholeStable, 'method': 'exudyn', 'loadSide': diagnosis.ToDict(),
                   'recommendations': []})
        return 0
    verdict = 'STABLE' if diagnosis.wholeStable else 'UNSTABLE (chatter expected)'
    lines = [f"exudyn-worm check: {SourceText(args)}", '',
             f"Verdict (linearized whole drive): {verdict}",
             f"Load side: {diagnosis.Text()}.",
             '', "No recommendations: they come from the two-mass model (eqs. (15)-(19)), which does not describe "
                 "this drive; `exudyn-worm stability` lists the whole drive's modes, `exudyn-worm sweep --vary "
                 "kL1=...` scans the load shaft."]
    print('\n'.join(lines))
    return 0


COMMAND = Subcommand('check', 'design check: stable or not, distance to the stability boundary and the smallest '
                     'changes that make the drive stable with a margin', _AddArguments, _Run)
