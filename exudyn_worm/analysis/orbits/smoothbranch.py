"""The smooth (friction-limited) branch of steady chatter from a linear boundary (:func:`SmoothHopfBranch`): with a
speed-dependent friction law the orbits near a Hopf point stay in contact, and the amplitude grows as the square
root of the distance from the boundary. Its points come by natural-parameter continuation from a settled time
simulation; :class:`ChatterBranchError` is the error of both branch analyses (this one and
:func:`~exudyn_worm.analysis.orbits.chatterbranch.AnalyzeChatterBranch`).
"""
from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field
from typing import Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np

from .chatter import FindSteadyChatter
from .continuation import BranchPoint
from .periodic import ShootingError
from ..._checks import CheckPositive
from ...drive.wholedrive import CheckDrive, Drive

__all__ = ['ChatterBranchError', 'SmoothBranch', 'SmoothHopfBranch', 'SMOOTH_OFFSETS', 'SMOOTH_SEED', 'SMOOTH_STEP',
           'SMOOTH_SETTLE_TIME', 'SMOOTH_MAX_ITERATIONS']
#: smooth (friction-limited) branch from a linear boundary (:func:`SmoothHopfBranch`): the distances from the boundary,
#: as fractions of its value into the linearly unstable side, at which orbits are computed; the amplitude grows as the
#: square root of the distance, so they are dense near it (reel-P3 with a Stribeck law, docs/chatter-amplitude.md)
SMOOTH_OFFSETS = (0.001, 0.002, 0.004, 0.006, 0.008, 0.011, 0.014, 0.017, 0.020, 0.023, 0.026, 0.029, 0.032,
                  0.035, 0.038, 0.041, 0.044, 0.047, 0.050)


class _Direction(enum.Enum):
    """Which way a smooth branch is followed from its seed (the value is the text of the messages)."""
    TOWARDS = 'towards the boundary'
    AWAY = 'away from the boundary'


class _End(enum.Enum):
    """Why one direction of a smooth branch ended."""
    OFFSETS = 'offsets'          # every offset looked at
    MAX_POINTS = 'maxPoints'     # the point limit
    FAILURES = 'failures'        # two points in a row without an orbit
    REVERSAL = 'reversal'        # the worm turns back within the orbit


#: beyond the last of :data:`SMOOTH_OFFSETS` the smooth branch goes on in steps of this fraction of the boundary
SMOOTH_STEP = 0.003


#: the smooth branch starts from a settled time simulation this fraction of the boundary into the unstable side
SMOOTH_SEED = 0.035


#: settling time in s of the start of a smooth branch: the chatter grows and settles slowly near a smooth Hopf point
#: (reel-P3, Stribeck, 3.5 % above the boundary: shooting after 10 s of settling did not converge, after 40 s in
#: 3 Newton steps; measured, docs/chatter-amplitude.md)
SMOOTH_SETTLE_TIME = 40.


#: Newton steps at most for each orbit of a smooth branch
SMOOTH_MAX_ITERATIONS = 40


class ChatterBranchError(ValueError):
    """The branch could not be computed; ``.branch`` holds what was computed so far (or None).

    Parameters
    ----------
    message : str
        The error message.
    branch : ChatterBranch or None
        What was computed so far.
    """

    def __init__(self, message: str, branch: Optional['ChatterBranch'] = None):
        super().__init__(message)
        self.branch = branch


@dataclass
class SmoothBranch:
    """Result of :func:`SmoothHopfBranch`: the friction-limited branch from one linear boundary.

    Attributes
    ----------
    parameter : str
        The continued parameter.
    boundary : float
        The linear boundary the branch starts from.
    side : int
        +1 if the drive is linearly unstable above the boundary, -1 if below (the branch lies on that side).
    points : list of BranchPoint
        The orbits, from the boundary outwards; ``info`` holds ``forceFactor``, ``maxWheelAcceleration`` (rad/s^2),
        ``minWormSpeed`` (rad/s) and ``offset`` (distance from the boundary as a fraction of it).
    hopf : dict or None
        ``value``, ``type`` ('supercritical' if the two orbits nearest the boundary are stable, else
        'subcritical'), ``linearBoundary`` and ``relativeDifference``; None with fewer than two orbits.
    failed : list of (float, str)
        Parameter values at which no orbit was found, and why.
    ends : list of dict
        Why each direction stopped: ``direction`` ('towards the boundary' or 'away from the boundary'), ``reason``
        ('reversal': the worm turns back within the orbit, 'failures': two failed points in a row or a failed last
        one, 'offsets': the last distance was reached, 'maxPoints'), ``value`` (the parameter value where it stopped) and ``minWormSpeed`` (rad/s,
        for 'reversal').
    messages : list of str
        The ends in words.
    """
    parameter: str
    boundary: float
    side: int
    points: List[BranchPoint] = field(default_factory=list)
    hopf: Optional[Dict] = None
    failed: List[Tuple[float, str]] = field(default_factory=list)
    ends: List[Dict] = field(default_factory=list)
    messages: List[str] = field(default_factory=list)


def _SmoothOffsets(reach: float, count: int) -> List[float]:
    """:data:`SMOOTH_OFFSETS` up to ``reach`` (fraction of the boundary), then steps of :data:`SMOOTH_STEP` (or
    wider, so that at most ``count`` distances are used in all)."""
    offsets = [f for f in SMOOTH_OFFSETS if f <= reach]
    if reach > SMOOTH_OFFSETS[-1]:
        room = max(count - len(offsets), 1)
        step = max(SMOOTH_STEP, (reach - SMOOTH_OFFSETS[-1]) / room)
        offsets += list(SMOOTH_OFFSETS[-1] + step * np.arange(1, int((reach - SMOOTH_OFFSETS[-1]) / step + 1e-9) + 1))
    return offsets[:count]


def SmoothHopfBranch(drive: Drive, name: str, boundary: float, side: int,
                     limit: Optional[float] = None, offsets: Optional[Sequence[float]] = None,
                     seed: float = SMOOTH_SEED, settleTime: float = SMOOTH_SETTLE_TIME,
                     maxIterations: int = SMOOTH_MAX_ITERATIONS, maxPoints: int = 60,
                     maxSeedForceFactor: float = math.inf, onPoint: Optional[Callable] = None) -> SmoothBranch:
    """The branch of steady chatter from a smooth Hopf point at the linear boundary ``boundary``: chatter whose
    amplitude starts from zero there and is limited by a friction law that falls with the sliding speed (the
    mesh stays in contact), followed until the worm turns back within the orbit.

    Started from a settled time simulation ``seed`` (a fraction of the boundary) into the linearly unstable side
    (:func:`~exudyn_worm.analysis.orbits.chatter.FindSteadyChatter` after ``settleTime`` s), then natural-parameter
    continuation from orbit to orbit at the distances ``offsets``, towards the boundary and away from it; each
    orbit is shot from the previous one (towards the boundary from the larger orbit: started below its amplitude,
    Newton would head for the rest state, which solves the shooting equations too). A failed point does not end a
    direction, two in a row do; away from the boundary the branch ends where the worm turns back within the orbit
    (it then sticks in every period and the steady chatter is no longer periodic with the chatter period,
    docs/chatter-amplitude.md). The Hopf point is where the line through the squared largest ``|phi2''|`` of the
    two orbits nearest the boundary meets zero (near a smooth Hopf point the squared amplitude is linear in the
    parameter).

    Parameters
    ----------
    drive : Drive
        A drive with the reel changer's duty (e.g. reel-P3 with ``frictionLaw = 'stribeck'``).
    name : str
        The continued parameter (see :data:`~exudyn_worm.analysis.orbits.chatterbranch.CONTINUABLE`).
    boundary : float
        The linear boundary in the parameter's SI unit (:func:`~exudyn_worm.analysis.orbits.chatterbranch.LinearBoundaries`), != 0.
    side : int
        +1 if the drive is linearly unstable above ``boundary``, -1 if below.
    limit : float, optional
        Farthest parameter value on that side (the end of the range or the next boundary); default: the last of
        ``offsets``.
    offsets : sequence of float, optional
        Distances from the boundary as fractions of it (> 0); default :data:`SMOOTH_OFFSETS`, then steps of
        :data:`SMOOTH_STEP` up to ``limit``.
    seed : float
        Distance of the start (fraction of the boundary, > 0); moved to three quarters of the way to ``limit`` if
        that is nearer.
    settleTime : float
        Settling time in s of the start, > 0.
    maxIterations : int
        Newton steps at most per orbit.
    maxPoints : int
        Largest number of orbits.
    maxSeedForceFactor : float
        Refuse the branch if the start orbit's force factor is not below this (it loses contact: not a smooth branch).
    onPoint : callable, optional
        Called with each new :class:`~exudyn_worm.analysis.orbits.continuation.BranchPoint`.

    Returns
    -------
    SmoothBranch

    Raises
    ------
    ValueError
        For a bad ``side``, ``boundary``, ``seed`` or ``limit``.
    ShootingError
        If no orbit is found at the start.
    ChatterBranchError
        If the start orbit's force factor is ``maxSeedForceFactor`` or more.
    """
    w = 'SmoothHopfBranch'
    drive = CheckDrive(w, drive)
    if side not in (-1, 1):
        raise ValueError(f"{w}: 'side' must be +1 or -1 (the linearly unstable side of the boundary), got {side!r}")
    boundary = float(boundary)
    if not (math.isfinite(boundary) and boundary != 0.):
        raise ValueError(f"{w}: 'boundary' must be a finite non-zero value of {name}, got {boundary!r}")
    seed = CheckPositive(w, 'seed', seed)
    Value = lambda f: boundary * (1. + side * f)
    given = offsets is not None
    reach = max(offsets) if given else SMOOTH_OFFSETS[-1]
    if limit is not None:
        reach = side * (float(limit) / boundary - 1.) if boundary > 0 else side * (1. - float(limit) / boundary)
        if not reach > 0:
            raise ValueError(f"{w}: 'limit' must lie on the unstable side ({'above' if side > 0 else 'below'}) of the "
                             f"boundary {name} = {boundary:g}, got {limit!r}")
    offsets = sorted(f for f in offsets if 0 < f <= reach) if given else _SmoothOffsets(reach, maxPoints)
    seed = seed if seed < reach else 0.75 * reach
    start = FindSteadyChatter(drive.Replace(**{name: Value(seed)}), settleTime=settleTime, maxIterations=maxIterations)
    if start.info['forceFactor'] >= maxSeedForceFactor:
        raise ChatterBranchError(f"{w}: the orbit at {name} = {Value(seed):.6g} ({seed:.1%} from the linear boundary "
                                 f"{boundary:.6g}) loses contact (force factor {start.info['forceFactor']:.3f}): the "
                                 f"branch there is limited by the mesh, not a smooth one")
    result = SmoothBranch(name, boundary, side)
    kept = ('forceFactor', 'maxWheelAcceleration', 'minWormSpeed')    # the orbits keep no model or flow
    start.info = {k: start.info[k] for k in kept}
    orbits = {seed: start}
    directions = ((_Direction.TOWARDS, sorted((f for f in offsets if f < seed), reverse=True)),
                  (_Direction.AWAY, sorted(f for f in offsets if f > seed)))
    for direction, todo in directions:
        last, misses, end = start, 0, {'direction': direction, 'reason': _End.OFFSETS, 'value': Value(seed)}
        for f in todo:
            if len(orbits) >= maxPoints:
                end = {'direction': direction, 'reason': _End.MAX_POINTS, 'value': end['value']}
                break
            v = Value(f)
            try:
                orbit = FindSteadyChatter(drive.Replace(**{name: v}), start=(last.state, last.period),
                                          maxIterations=maxIterations)
            except ShootingError as err:
                result.failed.append((v, str(err).split(';')[0]))
                misses += 1
                if misses == 2:
                    end = {'direction': direction, 'reason': _End.FAILURES, 'value': v}
                    break
                continue
            misses = 0
            if orbit.info['minWormSpeed'] <= 0.:
                end = {'direction': direction, 'reason': _End.REVERSAL, 'value': v,
                       'minWormSpeed': float(orbit.info['minWormSpeed'])}
                break
            orbit.info = {k: orbit.info[k] for k in kept}
            orbits[f] = last = orbit
            end['value'] = v
            if onPoint is not None:
                onPoint(BranchPoint(v, orbit, {**orbit.info, 'offset': f}))
        else:
            if misses:                      # the last value tried found no orbit
                end = {'direction': direction, 'reason': _End.FAILURES, 'value': v}
        result.ends.append(end)
    near = sorted(orbits)
    result.points = [BranchPoint(Value(f), orbits[f], {**orbits[f].info, 'offset': f}) for f in near]
    for e in result.ends:
        if e['reason'] is _End.REVERSAL:
            result.messages.append(f"the branch ends at {name} = {e['value']:.6g}: the worm turns back within the orbit "
                                   f"(smallest worm speed {e['minWormSpeed']:.3f} rad/s); from there on it sticks in "
                                   f"every period and the steady chatter is not periodic with the chatter period, "
                                   f"so no orbit is followed beyond")
        elif e['reason'] is _End.FAILURES and e['direction'] is _Direction.AWAY and len(orbits) >= 2:
            # the smallest worm speed of the last two orbits, extrapolated to zero: where the worm would turn back
            (fa, oa), (fb, ob) = [(f, orbits[f]) for f in sorted(orbits)[-2:]]
            sa, sb = oa.info['minWormSpeed'], ob.info['minWormSpeed']
            turn = Value(fb) + (Value(fb) - Value(fa)) * sb / (sa - sb) if sa > sb else math.nan
            result.messages.append(
                f"the branch ends at {name} = {Value(fb):.6g}: no orbit found beyond it (tried up to "
                f"{name} = {e['value']:.6g}); the last orbit's smallest worm speed is {sb:.3g} rad/s"
                + (f", which extrapolates to zero (the worm turns back within the orbit and sticks) at about "
                   f"{name} = {turn:.6g}" if math.isfinite(turn) else ''))
        elif e['reason'] is _End.FAILURES:
            result.messages.append(f"{e['direction'].value}: two points in a row found no orbit, the branch ends at {name} = "
                                   f"{e['value']:.6g}")
        elif e['reason'] is _End.MAX_POINTS:
            result.messages.append(f"{e['direction'].value}: stopped after {maxPoints} orbits at {name} = {e['value']:.6g}")
        elif e['direction'] is _Direction.AWAY:
            result.messages.append(f"the branch reaches {name} = {e['value']:.6g}, the end of the range looked at, "
                                   f"with the worm still sliding forward")
    if len(near) >= 2:
        (f1, o1), (f2, o2) = [(f, orbits[f]) for f in near[:2]]
        a1, a2 = o1.info['maxWheelAcceleration'] ** 2, o2.info['maxWheelAcceleration'] ** 2
        v1, v2 = Value(f1), Value(f2)
        hopf = v1 - a1 * (v2 - v1) / (a2 - a1)
        result.hopf = {'value': float(hopf), 'type': 'supercritical' if o1.stable and o2.stable else 'subcritical',
                       'linearBoundary': boundary, 'relativeDifference': float(abs(hopf / boundary - 1.))}
    else:
        result.messages.append(f"fewer than two orbits near the linear boundary {name} = {boundary:.6g}: no Hopf point "
                               f"estimated")
    return result
