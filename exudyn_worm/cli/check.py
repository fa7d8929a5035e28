"""``exudyn-worm check``: the design check. The verdict of ``exudyn-worm stability`` (the drive's own operating
points), the self-locking verdicts at each of them, where a two-mass drive sits on its chart, and the smallest changes
of J1, J2, kT, the damping and the chains that make it stable with a margin
(:func:`exudyn_worm.analysis.design.designcheck.DesignCheck`)."""
from __future__ import annotations

import argparse
import sys
from .main import (_LazyHelp, AddOverwriteOption, BadInput, CheckFigurePath, PositiveFloat, PrintJson, SourceText, StdoutToStderr, Subcommand, UsageError, WarnUnresolvedRotation, WholeDriveFromArgs)
from .._files import WriteAtomically

__all__ = ['COMMAND']

def _AddArguments(parser: argparse.ArgumentParser) -> None:
    margin = parser.add_argument('--margin', type=float, default=None, metavar='DECADES',
                                 help='stability margin in decades of the changed parameter (default %(text)s)')
    margin.text = _LazyHelp(lambda: f'{_Defaults()[0]:g}: the drive stays stable if that parameter is off by a '
                                    f'factor {10 ** _Defaults()[0]:.2f}')
    span = parser.add_argument('--span', type=float, default=None, metavar='FACTOR',
                               help='search changes up to this factor in each direction (default %(text)s)')
    span.text = _LazyHelp(lambda: f'{_Defaults()[1]:g}')
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


def _Defaults():
    """The defaults of --margin and --span (the design rules' own)."""
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.design.designrules import DEFAULT_MARGIN, DEFAULT_SPAN
    return DEFAULT_MARGIN, DEFAULT_SPAN


def _Run(args: argparse.Namespace) -> int:
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.design import designcheck, designconfirm
    from ..analysis.design.designscan import DesignKeys
    from ..progress import ProgressBar
    from .formatcheck import FormatDesignCheck
    defaultMargin, defaultSpan = _Defaults()
    args.margin = defaultMargin if args.margin is None else args.margin
    args.span = defaultSpan if args.span is None else args.span
    plotPath = CheckFigurePath(args.plot, '--plot', args.overwrite) if args.plot is not None else None
    drive = WholeDriveFromArgs(args)              # resolved once: every analysis below takes this drive
    if not args.simulate:                         # a run checks the speed against its own step
        WarnUnresolvedRotation(drive, 'check')
    if args.simulate:
        # lazy: start-up (exudyn-worm --help imports every command module)
        from ..builders.oneangle import CheckReelChangerKeys
        with BadInput():
            CheckReelChangerKeys(drive, 'check --simulate')
    elif args.step_size is not None:
        raise UsageError(f"--step-size {args.step_size:g} only applies with --simulate")
    quiet = True if getattr(args, 'quiet', False) else None
    with BadInput(), StdoutToStderr(args.json):
        keys, _ = DesignKeys(drive)
        with ProgressBar(total=len(keys), desc='check', unit='parameter', quiet=quiet) as bar:
            result = designcheck.DesignCheck(drive, margin=args.margin, span=args.span, progress=bar.update)
    if args.simulate:
        runs = 1 + len(result.recommendations) + (result.bestPair is not None)
        with ProgressBar(total=runs, desc='check --simulate', unit='run', quiet=quiet) as bar:
            with BadInput(), StdoutToStderr(args.json):
                result = designconfirm.ConfirmBySimulation(result, stepSize=args.step_size, progress=bar.update)
    loadSide = None
    if drive.loadSideChain:          # as stability: may the driven machine be lumped into J2? which stage is not?
        # lazy: start-up (exudyn-worm --help imports every command module)
        from ..analysis.stability.loadside import DiagnoseLoadSide
        with StdoutToStderr(args.json), BadInput():
            loadSide = DiagnoseLoadSide(drive, args.margin)
    disturbance = _DisturbanceVerdict(args, drive, result)
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


def _DisturbanceVerdict(args: argparse.Namespace, drive, result):
    """:func:`~exudyn_worm.analysis.orbits.disturbance.ChattersAfterDisturbance` of the drive, or None where it is not asked
    for: ``--no-disturbance``; by default only for a drive with backlash that is linearly stable while lowering
    (S = -1) and has the reel changer's keys. ``--disturbance`` asks for it for any drive (missing keys: exit 2)."""
    if args.disturbance == 'no':
        return None
    if args.disturbance == 'auto':
        # lazy: start-up (exudyn-worm --help imports every command module)
        from ..drive.presets import REEL_KEYS
        lowering = result.ContactStates().get(-1)
        if not (drive.gear.backlash > 0. and lowering is not None and lowering.stable
                and all(k in drive.parameters for k in REEL_KEYS)):
            return None
    # lazy: start-up (exudyn-worm --help imports every command module)
    from ..analysis.orbits.disturbance import ChattersAfterDisturbance
    from ..builders.oneangle import CheckReelChangerKeys
    if args.disturbance == 'auto':
        try:
            with StdoutToStderr(args.json):
                return ChattersAfterDisturbance(drive)
        except ValueError:          # a drive the lowering model refuses (a motor on its characteristic): as before
            return None
    with BadInput():
        CheckReelChangerKeys(drive, 'check --disturbance')
        with StdoutToStderr(args.json):
            return ChattersAfterDisturbance(drive)


COMMAND = Subcommand('check', 'design check: stable or not, distance to the stability boundary and the smallest '
                     'changes that make the drive stable with a margin', _AddArguments, _Run)
