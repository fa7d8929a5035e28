"""``exudyn-worm stability``: linear stability of a drive at the operating points of its duty, with a design hint."""
from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Dict, Union

from .main import (BadInput, PrintJson, SourceText, StdoutToStderr, Subcommand, UsageError, WarnUnresolvedRotation,
                   WholeDriveFromArgs)

if TYPE_CHECKING:
    from ..analysis.stability.drivestability import DriveAnalysis
    from ..drive.wholedrive import Drive

__all__ = ['COMMAND', 'StabilityHintData']


def _AddArguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument('--method', choices=('analytical', 'exudyn'), default=None,
                        help='analytical: eqs. (15)-(19) of the paper (default for the two-mass drive); exudyn: '
                             'eigenvalues of the linearized Exudyn model (default, and the only choice, for a '
                             'drive with a drive-side or load-side chain, a worm axial bearing or a motor on its '
                             'characteristic)')


def _RunWholeDrive(args: argparse.Namespace, analysis: DriveAnalysis) -> int:
    """A drive beyond two masses (or --method exudyn): the linearized Exudyn model at each operating point."""
    # lazy: start-up (exudyn-worm --help imports every command module)
    from .formatstability import DangerLines, OperatingPointLines, StateLine, VerdictLine, _G, _Lehr
    drive = analysis.drive
    loadSide = None
    if drive.loadSideChain:          # may the driven machine be lumped into J2? which stage is not?
        # lazy: start-up (exudyn-worm --help imports every command module)
        from ..analysis.stability.loadside import DiagnoseLoadSide
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
        lines.append(StateLine(label, state))
        lines.append(f"  {'f (Hz)':>9} {'Lehr D':>9} {'Re (1/s)':>10}  coordinates taking part (kinetic energy share)")
        for mode in state.modes:
            parts = ', '.join(f"{k} {mode.energyShare[k]:.0%}" for k in mode.Participants())
            lines.append(f"  {mode.frequencyHz:9.2f} {_Lehr(mode.lehrDamping):>9} {mode.eigenvalue.real:10.4g}  {parts}")
    lines += [''] + DangerLines(analysis) + [VerdictLine(analysis)]
    if loadSide is not None:
        lines.append(f"Load side: {loadSide.Text()}.")
    print('\n'.join(lines))
    return 0


def _Run(args: argparse.Namespace) -> int:
    # lazy: start-up (exudyn-worm --help imports every command module)
    from .formatstability import DangerLines, FormatStability, OperatingPointLines, VerdictLine
    from ..analysis.stability.drivestability import ANALYTICAL, LINEARIZED, AnalyzeDrive
    from ..model.geometry import DescribeGeometry
    drive = WholeDriveFromArgs(args)
    if drive.components and args.method == 'analytical':
        raise UsageError(f"--method analytical: eqs. (15)-(19) describe the two-mass drive of Figure 2; this "
                         f"drive has {drive.ComponentsText()}; use --method exudyn (the default for such a drive)")
    WarnUnresolvedRotation(drive, 'stability')
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
        geometry = {'form': drive.geometryForm, 'r1': g.r1, 'r2': g.r2, 'gamma': g.gamma, 'u': g.ratio}
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


def StabilityHintData(drive: Drive, span: float = 100.) -> Dict:
    """The design hint of an unstable drive as data: the nearest stable J1 and kT
    (:func:`~exudyn_worm.analysis.design.stabilityhint.StabilizingChanges`), other parameters as given; the table's hint line
    and the ``--json`` key ``hint`` both come from here.

    Parameters
    ----------
    drive : Drive
        The drive (:class:`~exudyn_worm.drive.wholedrive.Drive`).
    span : float, optional
        Search range factor, > 1.

    Returns
    -------
    dict
        ``text`` (the one-line hint), ``span`` and ``nearestStable``: per parameter ``parameter``,
        ``given``, ``below``, ``above`` (None where there is none within the span), ``unit``, ``ratioName``,
        ``ratioBelow``, ``ratioAbove``.
    """
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.design.stabilityhint import StabilizingChanges
    ranges = StabilizingChanges(drive, span)
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


COMMAND = Subcommand('stability', 'linear stability (chatter) analysis of a parameter set', _AddArguments, _Run)
