"""The design check confirmed in the time domain: the reel changer simulated for the given drive and every
recommended drive, with the chatter rule of ``exudyn-worm simulate`` on the lowering phases.
"""
from __future__ import annotations

from dataclasses import replace
from typing import Optional, Union

from ...items.results import UNDECIDED
from ...builders.oneangle import CheckReelChangerKeys
from ...drive.wholedrive import Drive
from ..simulation import reelchanger
from .designcheck import DesignCheckResult
from ..simulation.reelchanger import DefaultPhases

__all__ = ['ChatterWhileLowering', 'ConfirmBySimulation']


def ChatterWhileLowering(drive: Drive, stepSize: Optional[float] = None) -> Union[bool, str]:
    """Time-domain verdict: does the reel changer chatter while lowering the load?

    One rotation with :func:`~exudyn_worm.analysis.simulation.reelchanger.SimulateReelChanger`; the verdict is
    :meth:`~exudyn_worm.items.results.SimulationResult.ChatterVerdict` on the lowering window of
    :func:`~exudyn_worm.analysis.simulation.reelchanger.DefaultWindows` (the rule of ``exudyn-worm simulate``); for another duty
    (:mod:`exudyn_worm.drive.duty`) on each of its lowering phases (False if it has none).

    Parameters
    ----------
    drive : Drive
        The drive with the reel-changer keys ``loadMass``, ``leverArm``, ``motorSpeed`` (or another duty's).
    stepSize : float, optional
        Time step in s. Default: the simulation's default, the drive's own
        :func:`~exudyn_worm.analysis.simulation.stepsize.RecommendedStepSize` (a recommended drive can have a higher natural
        frequency than the given one).

    Returns
    -------
    bool or str
        True where a lowering window chatters, ``'undecided'`` where none does but one is undecided (a vibration
        that decays slower than the window), else False.

    Raises
    ------
    ValueError
        For a drive without the reel-changer keys, or a ``stepSize`` the simulation refuses.
    """
    CheckReelChangerKeys(drive, 'ChatterWhileLowering')
    lowering = [(t0, t1) for t0, t1, phase in DefaultPhases(drive) if phase == 'lower']   # the load drives
    if not lowering:
        return False
    result = reelchanger.SimulateReelChanger(drive, stepSize=stepSize)          # the default time the phases cover
    verdicts = [result.ChatterVerdict(t0, t1) for t0, t1 in lowering]
    if any(v.chatter for v in verdicts):
        return True
    return UNDECIDED if any(not v.decided for v in verdicts) else False


def ConfirmBySimulation(result: DesignCheckResult, stepSize: Optional[float] = None,
                        progress=None) -> DesignCheckResult:
    """Simulate the given drive and every recommended drive; return the result with the simulated verdicts.

    Parameters
    ----------
    result : DesignCheckResult
        From :func:`~exudyn_worm.analysis.design.designcheck.DesignCheck`; its drive must hold ``loadMass``, ``leverArm``, ``motorSpeed``.
    stepSize : float, optional
        Time step in s (default: see :func:`ChatterWhileLowering`).
    progress : callable, optional
        Called with no argument after each simulation (e.g. a progress bar's ``update``).

    Returns
    -------
    DesignCheckResult
        A copy with ``simulatedChatter`` set on the result, each recommendation and the best pair.
    """
    if not isinstance(result, DesignCheckResult):
        raise TypeError(f"ConfirmBySimulation: 'result' must be a DesignCheckResult, got {type(result).__name__}")
    drive = result.drive

    def Verdict(changes):
        chatter = ChatterWhileLowering(drive.Replace(**changes), stepSize)
        if progress is not None:
            progress()
        return chatter

    base = Verdict({})
    recommendations = [replace(r, simulatedChatter=Verdict(r.changes)) for r in result.recommendations]
    pair = replace(result.bestPair, simulatedChatter=Verdict(result.bestPair.changes)) if result.bestPair else None
    return replace(result, recommendations=recommendations, bestPair=pair, simulatedChatter=base)
