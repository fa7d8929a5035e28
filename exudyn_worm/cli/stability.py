"""``exudyn-worm stability``: linear stability of a drive at the operating points of its duty, with a design hint."""
from __future__ import annotations

import argparse
import math
from typing import Dict, List, Union

from .main import BadInput, PrintJson, SourceText, StdoutToStderr, Subcommand, UsageError, WholeDriveFromArgs
from ..analysis.stabilityhint import StabilizingChanges
from ..analysis.drivestability import ANALYTICAL, LINEARIZED, AnalyzeDrive, DriveAnalysis
from ..model.geometry import DescribeGeometry, GeometryForm
from ..model.stability import CONTACT_STATES, StabilityAnalysis
from ..setups.wholedrive import Drive

__all__ = ['COMMAND', 'FormatStability', 'OperatingPointLines', 'VerdictLine', 'DangerLines', 'StabilityHint', 'StabilityHintData']


def _AddArguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument('--method', choices=('analytical', 'exudyn'), default=None,
                        help='analytical: eqs. (15)-(19) of the paper (default for the two-mass drive); exudyn: '
                             'eigenvalues of the linearized Exudyn model (default, and the only choice, for a '
                             'drive with a drive-side or load-side chain, a worm axial bearing or a motor on its '
                             'characteristic)')


_RPM = 60. / (2 * math.pi)


def OperatingPointLines(analysis: DriveAnalysis) -> List[str]:
    """The table of a drive's operating points and the line naming the one that decides (``stability``, ``check``).

    Parameters
    ----------
    analysis : DriveAnalysis
        Result of :func:`~exudyn_worm.analysis.drivestability.AnalyzeDrive`.

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
                     f"{p.maxRealPart:9.4g} {p.frequencyHz:8.4g}  {'stable' if p.stable else 'UNSTABLE'}, "
                     f"{dynamic.rating if dynamic is not None else 'n/a'}")
    lines.append(f"  ({', '.join(sorted({p.point.source for p in analysis.operatingPoints}))}; {analysis.decidingText})")
    return lines


def VerdictLine(analysis: DriveAnalysis) -> str:
    """The drive's one verdict, as every command prints it.

    Parameters
    ----------
    analysis : DriveAnalysis
        Result of :func:`~exudyn_worm.analysis.drivestability.AnalyzeDrive`.

    Returns
    -------
    str
    """
    p = analysis.deciding
    where = '' if p is None else f" (decided by the {p.phase} phase, S = {p.S:+d}, at {p.point.motorSpeed * _RPM:.4g} rpm: " \
                                  f"{p.maxRealPart:.4g} 1/s at {p.frequencyHz:.4g} Hz)"
    if p is None:
        where = ' (at rest, every contact state: the duty has no steady phase)'
    return f"Verdict: {'STABLE (no chatter predicted by the linear model)' if analysis.stable else 'UNSTABLE (chatter expected)'}{where}"


def DangerLines(analysis: DriveAnalysis) -> List[str]:
    """One ``DANGER`` line per operating point at which the gear is self-locking at rest but not while moving
    (``stability``, ``check``).

    Parameters
    ----------
    analysis : DriveAnalysis
        Result of :func:`~exudyn_worm.analysis.drivestability.AnalyzeDrive`.

    Returns
    -------
    list of str
    """
    return [f"DANGER at {label}: self-locking at rest (mu {v.static.mu:.4g}) but not while moving (mu {v.dynamic.mu:.4g}): "
            f"the load holds, but runs away once it moves" for label, v in analysis.selfLockingVerdicts.items()
            if v.dangerous]


def _RunWholeDrive(args: argparse.Namespace, analysis: DriveAnalysis) -> int:
    """A drive beyond two masses (or --method exudyn): the linearized Exudyn model at each operating point."""
    drive = analysis.drive
    loadSide = None
    if drive.loadSideChain:          # may the driven machine be lumped into J2? which stage is not?
        # lazy: start-up (exudyn-worm --help imports every command module)
        from ..analysis.loadside import DiagnoseLoadSide
        with StdoutToStderr(args.json), BadInput():
            loadSide = DiagnoseLoadSide(drive)
    if args.json:
        PrintJson({**analysis.ToDict(), 'method': 'exudyn', 'components': [c.text for c in drive.components],
                   'coordinates': list((analysis.operatingPoints[0].analysis if analysis.operatingPoints
                                        else analysis.atRest).coordinates),
                   'states': [p.state.ToDict() for p in analysis.operatingPoints] or
                             [s.ToDict() for s in analysis.atRest.states.values()],
                   **({'loadSide': loadSide.ToDict()} if loadSide is not None else {})})
        return 0
    what = f"it has {drive.ComponentsText()}" if drive.components else 'chosen with --method exudyn'
    lines = [f"exudyn-worm stability: {SourceText(args)}, method exudyn (linearized Exudyn model of the whole "
             f"drive: {what})", '']
    lines += OperatingPointLines(analysis) + ['']
    states = [(f"{p.point.Label()}, S = {p.S:+d}", p.state) for p in analysis.operatingPoints] or \
        [(f"at rest, S = {', '.join(f'{s:+d}' for s in state.S)}", state) for state in analysis.atRest.states.values()]
    for label, state in states:
        lines.append(f"{label}: {'stable' if state.stable else 'UNSTABLE'}, largest real part {state.maxRealPart:.4g} 1/s")
        lines.append(f"  {'f (Hz)':>9} {'Lehr D':>9} {'Re (1/s)':>10}  coordinates taking part (kinetic energy share)")
        for mode in state.modes:
            parts = ', '.join(f"{k} {mode.energyShare[k]:.0%}" for k in mode.Participants())
            lines.append(f"  {mode.frequencyHz:9.2f} {_G(mode.lehrDamping, 4):>9} {mode.eigenvalue.real:10.4g}  {parts}")
    lines += [''] + DangerLines(analysis) + [VerdictLine(analysis)]
    if loadSide is not None:
        lines.append(f"Load side: {loadSide.Text()}.")
    print('\n'.join(lines))
    return 0


def _Run(args: argparse.Namespace) -> int:
    drive = WholeDriveFromArgs(args)
    if drive.components and args.method == 'analytical':
        raise UsageError(f"--method analytical: eqs. (15)-(19) describe the two-mass drive of Figure 2; this "
                         f"drive has {drive.ComponentsText()}; use --method exudyn (the default for such a drive)")
    model = LINEARIZED if drive.components or args.method == 'exudyn' else ANALYTICAL
    with StdoutToStderr(args.json), BadInput():
        analysis = AnalyzeDrive(drive, model)
        analysis.stable
    if drive.components:
        return _RunWholeDrive(args, analysis)
    parameters = dict(drive.parameters)
    method = 'analytical' if model == ANALYTICAL else 'exudyn'
    deciding = analysis.deciding
    table = analysis.atRest if deciding is None else deciding.analysis     # both contact states at the deciding point
    hint = None if analysis.stable else StabilityHintData(drive)     # the same drive: nothing resolved again
    if args.json:
        g = drive.gear
        geometry = {'form': GeometryForm(parameters), 'r1': g.r1, 'r2': g.r2, 'gamma': g.gamma, 'u': g.ratio}
        PrintJson({**table.ToDict(), **analysis.ToDict(), 'method': method, 'geometry': geometry, 'hint': hint})
        return 0
    where = 'at rest' if deciding is None else f"at the deciding operating point, {deciding.point.Label()}"
    lines = FormatStability(table, title=f"exudyn-worm stability: {SourceText(args)}, method {method}", where=where)
    geometry = DescribeGeometry(parameters)
    if geometry:                  # given as a designation: say how r1, r2, gamma, u were derived
        lines.insert(1, geometry[0].upper() + geometry[1:])
    lines += [''] + OperatingPointLines(analysis) + [''] + DangerLines(analysis) + [VerdictLine(analysis)]
    if hint is not None:
        lines.append(hint['text'])
    print('\n'.join(lines))
    return 0


def _G(x: float, digits: int = 5) -> str:
    return 'n/a' if x is None else ('inf' if math.isinf(x) and x > 0 else '-inf' if math.isinf(x)
                                    else f'{x:.{digits}g}')


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
        lines.append(row(f'Lehr damping D{i + 1} = -delta/omega', *(_G(float(c[S].lehrDamping[i]), 3)
                                                                    for S in CONTACT_STATES)))
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


def StabilityHintData(parameters: Union[Drive, Dict[str, float]], span: float = 100.) -> Dict:
    """The design hint of an unstable drive as data: the nearest stable J1 and kT
    (:func:`~exudyn_worm.analysis.stabilityhint.StabilizingChanges`), other parameters as given; the table's hint line
    and the ``--json`` key ``hint`` both come from here.

    Parameters
    ----------
    parameters : Drive or dict
        The drive (:class:`~exudyn_worm.setups.wholedrive.Drive`) or its flat parameter dictionary.
    span : float, optional
        Search range factor, > 1.

    Returns
    -------
    dict
        ``text`` (the one-line hint), ``span`` and ``nearestStable``: per parameter ``parameter``,
        ``given``, ``below``, ``above`` (None where there is none within the span), ``unit``, ``ratioName``,
        ``ratioBelow``, ``ratioAbove``.
    """
    ranges = StabilizingChanges(parameters, span)
    parts = []
    for r in ranges:
        options = [f"{r.key} {op} {value:.3g} {r.unit} ({r.ratioName} {op} {value * r.ratioScale:.3g})"
                   for op, value in (('<=', r.below), ('>=', r.above)) if value is not None]
        parts.append(' or '.join(options) if options else
                     f"no {r.key} within 1/{span:g} to {span:g} times the given value")
    text = ('Hint: with all other parameters as given, the analytical model is stable for '
            + '; or for '.join(parts) + ' (nearest stable values found by a scan; '
            'exudyn-worm check recommends changes with a margin)')
    return {'text': text, 'span': span, 'nearestStable': [r.ToDict() for r in ranges]}


def StabilityHint(parameters: Dict[str, float], span: float = 100.) -> str:
    """One-line design hint for an unstable drive (the ``text`` of :func:`StabilityHintData`).

    Parameters
    ----------
    parameters : dict
        Flat parameter dictionary (see :func:`~exudyn_worm.setups.presets.DriveFromParameters`).
    span : float, optional
        Search range factor, > 1.

    Returns
    -------
    str
        One line starting with ``Hint:``.
    """
    return StabilityHintData(parameters, span)['text']


COMMAND = Subcommand('stability', 'linear stability (chatter) analysis of a parameter set', _AddArguments, _Run)
