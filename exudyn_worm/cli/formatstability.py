"""Text of ``exudyn-worm stability``: the verdict, the operating points, the danger lines and the analytical
model's table (the numbers come from :mod:`exudyn_worm.analysis.stability.drivestability` and
:mod:`exudyn_worm.model.stability`; this module only formats them).
"""
from __future__ import annotations

import math
from typing import Any, List

from ..analysis.stability.drivestability import (DIVERGENCE, AnalyzeDrive, DriveAnalysis, GrowthText, StateInstability,
                                                 VerdictWord)
from ..model.stability import CONTACT_STATES, StabilityAnalysis

__all__ = ['FormatStability', 'OperatingPointLines', 'VerdictLine', 'DangerLines', 'StateLine']

_RPM = 60. / (2 * math.pi)


def OperatingPointLines(analysis: DriveAnalysis) -> List[str]:
    """The table of a drive's operating points and the line naming the one that decides (``stability``, ``check``).

    Parameters
    ----------
    analysis : DriveAnalysis
        Result of :func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive`.

    Returns
    -------
    list of str
    """
    if not analysis.operatingPoints:
        return [f"Operating points: none ({analysis.decidingText})"]
    lines = ['Operating points of the duty (each steady phase in each direction of power flow, at the largest load '
             'torque of that direction in the phase)',
             f"  {'phase':<9} {'motor rpm':>9} {'load N*m':>10} {'v0 m/s':>8} {'mu(v0)':>7} {'dmu/dv s/m':>10} "
             f"{'Fn0 N':>10} {'S':>3} {'Re 1/s':>9} {'f Hz':>8}  verdict, self-locking while moving"]
    for p in analysis.operatingPoints:
        op = p.point.operatingPoint
        dynamic = p.selfLocking.dynamic
        lines.append(f"  {p.phase:<9} {p.point.motorSpeed * _RPM:9.4g} {p.point.loadTorque:10.4g} "
                     f"{op.slidingSpeed:8.4g} {op.mu:7.4g} {op.dmuDv:10.4g} {op.normalForce:10.4g} {op.S:+3d} "
                     f"{p.maxRealPart:9.4g} {p.frequencyHz:8.4g}  {VerdictWord(p.stable, p.instability)}, "
                     f"{dynamic.rating if dynamic is not None else 'n/a'}")
    lines.append(f"  ({', '.join(sorted({p.point.source for p in analysis.operatingPoints}))}; {analysis.decidingText})")
    return lines


def VerdictLine(analysis: DriveAnalysis) -> str:
    """The drive's one verdict, as every command prints it.

    Parameters
    ----------
    analysis : DriveAnalysis
        Result of :func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive`.

    Returns
    -------
    str
    """
    p = analysis.deciding
    if p is None:
        where = ' (at rest, every contact state: the duty has no steady phase)'
    elif p.instability == DIVERGENCE:
        where = (f" (decided by the {p.phase} phase, S = {p.S:+d}, at {p.point.motorSpeed * _RPM:.4g} rpm: a real "
                 f"eigenvalue grows at {p.maxRealPart:.4g} 1/s)")
    else:
        where = (f" (decided by the {p.phase} phase, S = {p.S:+d}, at {p.point.motorSpeed * _RPM:.4g} rpm: "
                 f"{p.maxRealPart:.4g} 1/s at {p.frequencyHz:.4g} Hz)")
    if analysis.stable:
        words = 'STABLE (no chatter predicted by the linear model)'
    elif analysis.instability == DIVERGENCE:
        words = 'DIVERGENT (not chatter: the drive runs away or creeps from its operating point)'
    else:
        words = 'UNSTABLE (chatter expected)'
    also = [q for q in analysis.operatingPoints if q is not p and q.instability is not None
            and q.instability != analysis.instability]
    also = ''.join(f"; also {'chatter expected' if q.instability != DIVERGENCE else 'DIVERGENT'} in the {q.phase} "
                   f"phase, S = {q.S:+d}, at {q.point.motorSpeed * _RPM:.4g} rpm ({q.growthText})" for q in also)
    return f"Verdict: {words}{where}{also}"


def StateLine(label: str, state: Any) -> str:
    """One contact state's verdict line of the whole drive's mode table (``stability``): ``label: stable, largest
    real part ...``, or for a divergence ``label: DIVERGENT, divergence: a real eigenvalue grows at ...``.

    Parameters
    ----------
    label : str
        The operating point and contact state.
    state : object
        A contact state's analysis (``stable``, ``maxRealPart``, ``eigenvalues``).
    """
    kind = StateInstability(state)
    if kind == DIVERGENCE:
        return f"{label}: {VerdictWord(False, kind)}, {GrowthText(float(state.maxRealPart), 0., kind)}"
    return f"{label}: {VerdictWord(bool(state.stable))}, largest real part {state.maxRealPart:.4g} 1/s"


def DangerLines(analysis: DriveAnalysis) -> List[str]:
    """One ``DANGER`` line per operating point at which the gear is self-locking at rest but not while moving
    (``stability``, ``check``).

    Parameters
    ----------
    analysis : DriveAnalysis
        Result of :func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive`.

    Returns
    -------
    list of str
    """
    return [f"DANGER at {label}: self-locking at rest (mu {v.static.mu:.4g}) but not while moving (mu {v.dynamic.mu:.4g}): "
            f"the load holds, but runs away once it moves" for label, v in analysis.selfLockingVerdicts.items()
            if v.dangerous]


def _G(x: float, digits: int = 5) -> str:
    return 'n/a' if x is None else ('inf' if math.isinf(x) and x > 0 else '-inf' if math.isinf(x)
                                    else f'{x:.{digits}g}')


def _Lehr(x: float, digits: int = 4) -> str:
    """A Lehr damping measure; a real mode (no frequency: the measure is infinite) reads ``real``."""
    return 'real' if x is not None and math.isinf(x) else _G(x, digits)


def _Complex(z: complex) -> str:
    return f"{z.real:.3f} {'+' if z.imag >= 0 else '-'} {abs(z.imag):.3f}i"


def FormatStability(analysis: StabilityAnalysis, title: str = 'Stability', where: str = '') -> List[str]:
    """Human-readable table of a :class:`StabilityAnalysis` (the ``stability`` subcommand's output).

    Parameters
    ----------
    analysis : StabilityAnalysis
        Result of :func:`~exudyn_worm.model.stability.AnalyzeStability` (or of the Exudyn linearization).
    title : str, optional
        First line.
    where : str, optional
        Where the drive was linearized (named in the heading of the per-state table).

    Returns
    -------
    list of str
        The lines, without trailing newlines.
    """
    d = analysis.drive
    g = d.gear
    w = 36
    row = lambda label, *cells: f"  {label:<{w}}" + ''.join(f"{' ' + c:>22}" for c in cells)   # a wide cell keeps a gap
    lines = [title, '', 'Gear and drive']
    lines += [row('reference radii r1, r2 [mm]', _G(g.r1 * 1e3), _G(g.r2 * 1e3)),
              row('transmission ratio u', _G(g.ratio)),
              row('pitch angle gamma [deg]', _G(math.degrees(g.gamma))),
              row('friction angle rho [deg]', _G(math.degrees(g.frictionAngle))),
              row('friction coefficient mu', _G(g.mu)),
              row('self-locking (gamma < rho)', 'yes' if g.selfLocking else 'no'),
              row('friction law', g.frictionLaw.kind)]
    verdict = analysis.selfLockingVerdict
    for label, state in (('at rest (static)', verdict.static), ('moving (dynamic)',
                                                                   verdict.dynamic)):
        lines.append(row(f'self-locking, {label}', 'n/a (no speed)' if state is None else
                         f"{'yes' if state.selfLocking else 'no'} (mu {_G(state.mu, 4)})",
                         '' if state is None else f"eta {_G(state.efficiencyWormDriving, 3)}, {state.rating}"))
    if verdict.dangerous:
        lines.append('  DANGER: self-locking at rest but not while moving: the load holds, but runs away once it moves')
    op = analysis.operatingPoint
    if op is not None:
        lines.append(row('operating point v0 [m/s], Fn0 [N]', _G(op.slidingSpeed, 4), _G(op.normalForce, 4)))
        lines.append(row('mu(v0), dmu/dv(v0) [s/m]', _G(op.mu, 4), _G(op.dmuDv, 4)))
    lines += [row('efficiency, worm driving', _G(g.efficiencyWormDriving, 4)),
              row('efficiency, wheel driving', _G(g.efficiencyWheelDriving, 4)),
              row('J1, J2 [kg*m^2]', _G(d.J1), _G(d.J2)),
              row('kT [N*m/rad], kV [N/m]', _G(d.kT), _G(g.kV)),
              row('dT [N*m*s/rad], dV [N*s/m]', _G(d.dT), _G(g.dV)),
              row('D_T, D_V, D_TV (eqs. 22-24)', _G(d.DT, 4), _G(d.DV, 4), _G(d.DTV, 4)),
              row('J1/J2', _G(d.inertiaRatio, 4)),
              row('kT/(kV r1^2)', _G(d.stiffnessRatio, 4))]
    c = {S: analysis.contact[S] for S in CONTACT_STATES}
    lines += ['', f"Linear stability per contact state S (eqs. (15)-(19)){', ' + where if where else ''}",
              row('', *(f'S = {S:+d}' for S in CONTACT_STATES))]
    for i, unit in enumerate(('1/s', '1/s^2', '1/s^3', '1/s^4')):
        lines.append(row(f'b{i + 1} [{unit}]', *(_G(c[S].b[i]) for S in CONTACT_STATES)))
    for label, i in (('(17) b1 > 0', 0), ('(18) b1 b2 - b3 > 0', 1), ('(19) (b1 b2 - b3) b3 - b1^2 b4 > 0', 2)):
        lines.append(row(label, *(f"{_G(c[S].hurwitz[i], 4)} {'ok' if c[S].hurwitz[i] > 0 else 'NO'}"
                                  for S in CONTACT_STATES)))
    for i in range(4):
        lines.append(row(f'eigenvalue {i + 1} [1/s]', *(_Complex(c[S].eigenvalues[i]) for S in CONTACT_STATES)))
    for i in range(2):
        lines.append(row(f'frequency f{i + 1} [Hz]', *(_G(c[S].frequenciesHz[i], 4) for S in CONTACT_STATES)))
    for i in range(2):
        lines.append(row(f'Lehr damping D{i + 1} = -delta/omega',
                         *(_Lehr(float(c[S].lehrDamping[i]), 3) + (' (grows)' if c[S].lehrDamping[i] == -math.inf else
                                                                   ' (decays)' if c[S].lehrDamping[i] == math.inf
                                                                   else '') for S in CONTACT_STATES)))
    lines.append(row('stable (all Re(lambda) < 0)', *('yes' if c[S].stable else 'NO' for S in CONTACT_STATES)))

    ratio = d.inertiaRatio
    fuesgen, first = analysis.fuesgenLimit, analysis.firstCriterionLimit
    classicChatter = ratio < fuesgen or ratio < first
    verdict = lambda limit: 'chatter predicted' if ratio < limit else 'no chatter predicted'
    lines += ['', 'Classic criteria: chatter if J1/J2 is below the limit',
              row('actual J1/J2', _G(ratio, 4)),
              row('Fuesgen limit (21), d_T = 0', _G(fuesgen, 4), verdict(fuesgen)),
              row('first criterion limit (20)', _G(first, 4), verdict(first)),
              '']
    if analysis.stable:
        lines.append('Both contact states: STABLE for S = +1 and S = -1')
    else:
        bad = [f'S = {S:+d}' for S in CONTACT_STATES if not c[S].stable]
        violated = sorted({n for S in CONTACT_STATES for n, v in zip(('(17)', '(18)', '(19)'), c[S].hurwitz)
                           if v <= 0})
        lines.append(f"Contact states: UNSTABLE for {' and '.join(bad)}; Hurwitz conditions violated: "
                     f"{', '.join(violated) if violated else 'none of (17)-(19) (b3 or b4 <= 0)'}")
        if not classicChatter:
            lines.append('Note: the classic criteria (20) and (21) predict no chatter here; they alone are '
                         'insufficient (paper section 3.1)')
    return lines
