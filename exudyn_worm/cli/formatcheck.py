"""Text of ``exudyn-worm check``: the design check's report and the self-locking lines (the numbers come from
:mod:`exudyn_worm.analysis.design.designcheck`; this module only formats them).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, List

from ..analysis.stability.drivestability import DIVERGENCE, StateInstability, VerdictWord
from .formatstability import DangerLines, OperatingPointLines

if TYPE_CHECKING:
    from ..analysis.stability.drivestability import DriveAnalysis

__all__ = ['FormatDesignCheck', 'SelfLockingLines', 'HEAVY_DAMPING']


def _Factor(f: float) -> str:
    return f'x{f:.3g}' if f >= 1 else f'/{1 / f:.3g}'


def _G(x, digits: int = 4) -> str:
    return 'n/a' if x is None or (isinstance(x, float) and math.isnan(x)) else \
        'inf' if math.isinf(x) else f'{x:.{digits}g}'


def _Simulated(chatter) -> str:
    if chatter == 'undecided':
        return 'undecided (a vibration that decays slower than the window; simulate says more)'
    return '' if chatter is None else ('CHATTER' if chatter else 'no chatter')


#: a recommended Lehr damping ratio D_T or D_V from which the table adds a remark (half of critical damping)
HEAVY_DAMPING = 0.5


def SelfLockingLines(analysis: DriveAnalysis) -> List[str]:
    """Static and dynamic self-locking at every operating point of the drive's duty (at rest without one), with the
    gear makers' rating (grey zone) and a ``DANGER`` line where the load holds at rest but runs away once moving.

    Parameters
    ----------
    analysis : DriveAnalysis
        Result of :func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive`.

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
    """Human-readable report of a :class:`~exudyn_worm.analysis.design.designcheck.DesignCheckResult` (the ``check`` output).

    Parameters
    ----------
    result : DesignCheckResult
        From :func:`~exudyn_worm.analysis.design.designcheck.DesignCheck` (optionally :func:`~exudyn_worm.analysis.design.designconfirm.ConfirmBySimulation`).
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
    states = '; '.join(f"S = {S:+d}: {VerdictWord(bool(s.stable), StateInstability(s))}, max Re(lambda) = "
                       f"{s.maxRealPart:.4g} 1/s" + (' (a real eigenvalue)' if StateInstability(s) == DIVERGENCE else '')
                       for S, s in result.ContactStates().items())
    verdict = ('STABLE with margin' if result.stableWithMargin else
               f"stable, but within the margin along {', '.join(result.marginShortBy)}" if result.stable else
               'DIVERGENT (not chatter: the drive runs away or creeps from its operating point)'
               if a.instability == DIVERGENCE else 'UNSTABLE (chatter expected)')
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
