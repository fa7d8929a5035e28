"""The stick/slip schedule of the sticking friction model: when a mesh is looked at, and what it becomes.

The sticking model's state (:class:`~exudyn_worm.model.contact.FrictionState`: stuck, sliding direction, anchor) is
switched between time steps, after a converged step (Exudyn's discontinuous iteration). The switch rule itself is
the contact law's :func:`~exudyn_worm.model.contact.StickSlipUpdate`; this module decides *when* to apply it and
keeps what the decision needs:

- a stuck mesh is looked at after every step (it may break away at any step);
- a sliding mesh whose worm still turns in its sliding direction is looked at again only after a fraction
  :data:`CHECK_FRACTION` of the time it would need to stop at the largest deceleration seen in the solve, at
  most :data:`CHECK_INTERVAL` later, and, early in a solve, at most as long after as the solve has run;
- when a check falls within :data:`REVERSAL_WINDOW` of a possible reversal, the sliding coordinate is kept, so
  that a reversal found at the next check is placed where the worm turned back (interpolated in time);
- a repeated step (the same time again: the solver repeats a step after a switch) is always looked at; a step
  at an earlier time than the last starts a new solve and forgets what the checks learnt.

Everything here is plain Python on floats and has no Exudyn in it: :class:`StickSlipSchedule` is the named
state, :func:`StickSlipStep` the one update, :func:`StartSchedule` and :func:`CarrySchedule` the two ways a
solve starts (from given coordinates, or continued across a shift of the coordinates). The connector
(:mod:`exudyn_worm.items.connector`) reads the mesh through a :class:`MeshReading` and writes the state where the
recorded law reads it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import NamedTuple, Optional, Tuple

from .contact import FrictionState, SlidingCoordinate
from .gear import WormGear

__all__ = ['CHECK_FRACTION', 'CHECK_INTERVAL', 'REVERSAL_WINDOW', 'CheckPoint', 'StickSlipSchedule', 'MeshReading',
           'StartFrictionState', 'StartSchedule', 'CarrySchedule', 'IsDue', 'NextCheck',
           'StickSlipStep']

#: fraction of the time to stop (``|omega1| / |alpha1|``) after which a sliding worm is checked again
CHECK_FRACTION = 0.2
#: longest time in s between two checks of a sliding worm (reel-P7: 0.005 and 0.02 s give the same peaks as a
#: check after every step; 0.05 s saw a reversal late and moved them by -1.2 %, docs/friction-sticking.md)
CHECK_INTERVAL = 0.02
#: a check at most this many s before a possible reversal also keeps the sliding coordinate, to locate the reversal
REVERSAL_WINDOW = 0.002


class CheckPoint(NamedTuple):
    """What a check of a sliding worm saw.

    Attributes
    ----------
    time : float
        Time of the check in s.
    wormSpeed : float
        Worm speed in rad/s.
    slidingCoordinate : float or None
        Sliding coordinate in m (:func:`~exudyn_worm.model.contact.SlidingCoordinate`), kept only when a reversal may
        come before the next check (:data:`REVERSAL_WINDOW`); None otherwise.
    """
    time: float
    wormSpeed: float
    slidingCoordinate: Optional[float] = None


@dataclass(slots=True)
class StickSlipSchedule:
    """Named state of one mesh's stick/slip schedule. :func:`StickSlipStep` updates it in place after every step
    (it runs after each converged step of a solve, so it allocates nothing when nothing switches); copy it with
    :func:`dataclasses.replace`.

    Attributes
    ----------
    state : FrictionState
        The stick/slip state in force (floats).
    nextCheck : float
        Earliest time in s at which a sliding mesh must be looked at again (-inf: after the next step).
    lastCheck : CheckPoint or None
        The last check of the sliding worm since the last switch (None: none yet).
    maxRate : float
        Largest worm deceleration in rad/s^2 seen in this solve (a worm that once decelerated hard may again).
    startTime : float or None
        Time in s of the solve's first step (None: no step yet).
    lastTime : float or None
        Time in s of the last step looked at (None: none yet).
    """
    state: FrictionState
    nextCheck: float = -math.inf
    lastCheck: Optional[CheckPoint] = None
    maxRate: float = 0.
    startTime: Optional[float] = None
    lastTime: Optional[float] = None


class MeshReading:
    """How :func:`StickSlipStep` reads a mesh after a step (an interface: the connector implements it on Exudyn's
    state, tests on plain numbers). Only what a decision needs is asked for, so a sliding worm that keeps its
    direction costs one speed.

    Methods
    -------
    WormSpeed() -> float
        Worm speed in rad/s, as the friction law reads it.
    WormAcceleration() -> float
        Worm angular acceleration in rad/s^2 (for the first check of a solve).
    SlidingCoordinate() -> float
        Sliding coordinate of the flanks in m.
    Switch(state, reversalCoordinate) -> (FrictionState or None, float)
        The contact law's switch rule at the present state
        (:func:`~exudyn_worm.model.contact.StickSlipUpdate`): the new state (None: unchanged) and the jump of the
        friction force in N.
    """

    def WormSpeed(self) -> float:  # pragma: no cover - interface
        raise NotImplementedError

    def WormAcceleration(self) -> float:  # pragma: no cover - interface
        raise NotImplementedError

    def SlidingCoordinate(self) -> float:  # pragma: no cover - interface
        raise NotImplementedError

    def Switch(self, state: FrictionState,
               reversalCoordinate: Optional[float]) -> Tuple[Optional[FrictionState], float]:  # pragma: no cover
        raise NotImplementedError


def StartFrictionState(gear: WormGear, phi1: float, phi2: float, omega1: float) -> FrictionState:
    """The state a solve starts in: sliding in the direction of the worm speed ``omega1`` (rad/s), stuck (without
    force: the anchor at the present sliding coordinate) if the worm is at rest.

    Parameters
    ----------
    gear : WormGear
        The mesh.
    phi1, phi2 : float
        Worm and wheel angles in rad (with the node reference values).
    omega1 : float
        Worm speed in rad/s.

    Returns
    -------
    FrictionState
    """
    s = SlidingCoordinate(gear, phi1, phi2)
    if omega1 != 0:
        return FrictionState(0., 1. if omega1 > 0 else -1., s)
    return FrictionState(1., 1., s)


def StartSchedule(state: FrictionState) -> StickSlipSchedule:
    """A schedule that starts a new solve in ``state``: nothing learnt, the mesh looked at after the first step.

    Parameters
    ----------
    state : FrictionState
        The start state (e.g. :func:`StartFrictionState`).

    Returns
    -------
    StickSlipSchedule
    """
    return StickSlipSchedule(state)


def CarrySchedule(schedule: StickSlipSchedule, shift: float) -> StickSlipSchedule:
    """The schedule continued across a shift of the coordinates (a run continued in coordinates relative to a
    steady rotation): stuck and direction are kept, the anchor moves with the sliding coordinate by ``shift``
    (m), so the stuck flanks keep their force; what the checks learnt is kept.

    Parameters
    ----------
    schedule : StickSlipSchedule
        The schedule at the end of the previous solve.
    shift : float
        Change of the sliding coordinate in m from the end of the previous solve to the start of the next.

    Returns
    -------
    StickSlipSchedule
    """
    state = schedule.state
    return replace(schedule, state=FrictionState(state.stuck, state.direction, state.anchor + shift))


def IsDue(schedule: StickSlipSchedule, t: float) -> bool:
    """Whether the mesh must be looked at after the step that ended at ``t`` (s): stuck, a repeated or earlier
    step, or a sliding mesh whose next check has come.

    Parameters
    ----------
    schedule : StickSlipSchedule
        The schedule.
    t : float
        Time of the step in s.
    """
    return schedule.state.stuck >= 0.5 or t == schedule.lastTime or t >= schedule.nextCheck or \
        (schedule.lastTime is not None and t < schedule.lastTime)


def NextCheck(schedule: StickSlipSchedule) -> float:
    """Earliest time in s at which the mesh must be looked at again (-inf: after every step, as while stuck).

    Parameters
    ----------
    schedule : StickSlipSchedule
        The schedule.
    """
    return schedule.nextCheck if schedule.state.stuck < 0.5 else -math.inf


def _Interval(startTime: Optional[float], t: float, omega1: float, rate: float) -> float:
    """Time in s to the next check of a worm sliding at ``omega1`` that decelerates at ``rate``, in a solve that
    started at ``startTime`` (see the module)."""
    horizon = CHECK_FRACTION * abs(omega1)
    interval = min(horizon / rate, CHECK_INTERVAL) if rate > 0 else CHECK_INTERVAL
    # early in a solve the largest acceleration is not known yet (a start at the worm's largest speed sees none):
    # wait at most as long as the solve has run, so the waits double until it is (a chatter period of reel-P3,
    # 0.015 s, is shorter than CHECK_INTERVAL: a one-period run otherwise missed the reversal)
    if startTime is not None:
        interval = min(interval, t - startTime)
    return interval


def _ReversalCoordinate(last: Optional[CheckPoint], t: float, omega1: float, s: float) -> Optional[float]:
    """Sliding coordinate at which the worm turned back, interpolated linearly in time between the last check (if
    it kept the coordinate and was at most :data:`REVERSAL_WINDOW` ago) and now; None if unknown."""
    if last is None or last.slidingCoordinate is None or not 0. < t - last.time <= REVERSAL_WINDOW \
            or last.wormSpeed == omega1:
        return None
    return last.slidingCoordinate + (s - last.slidingCoordinate) * last.wormSpeed / (last.wormSpeed - omega1)


def StickSlipStep(schedule: StickSlipSchedule, t: float, reading: MeshReading) -> Optional[float]:
    """One update of the schedule after a converged step that ended at ``t``: look at the mesh if it is due,
    switch its state by the contact law's rule, and plan the next check. ``schedule`` is updated in place.

    Parameters
    ----------
    schedule : StickSlipSchedule
        The schedule before the step was looked at; after the call, the schedule after it (its ``state`` is the
        new state if the mesh switched).
    t : float
        Time in s at the end of the step.
    reading : MeshReading
        The mesh after the step (asked only for what the decision needs).

    Returns
    -------
    float or None
        None if the state did not switch; else the jump of the friction force in N that the switch causes: the
        discontinuous error, compared with Exudyn's ``timeIntegration.discontinuous.iterationTolerance``.
    """
    lastTime = schedule.lastTime
    if lastTime is None:                                      # the first step looked at
        schedule.startTime = t
    elif t < lastTime:                                        # a new solve from an earlier time: forget the schedule
        schedule.nextCheck, schedule.lastCheck, schedule.maxRate, schedule.startTime = -math.inf, None, 0., t
    state = schedule.state
    stuck = state.stuck >= 0.5
    if not stuck and not IsDue(schedule, t):                  # sliding and not due (asked before the time is kept)
        schedule.lastTime = t
        return None
    schedule.lastTime = t
    if stuck:                                                 # stuck flanks may break away at any step
        new, jump = reading.Switch(state, None)
        if new is None:                                       # the flanks hold
            return None
    else:
        omega1 = reading.WormSpeed()
        if omega1 * state.direction >= 0.:                    # still sliding the same way: plan the next check
            last = schedule.lastCheck
            if last is not None and t > last.time:            # mean deceleration since the last check
                rate = abs(omega1 - last.wormSpeed) / (t - last.time)
            else:
                rate = abs(reading.WormAcceleration())
            if rate < schedule.maxRate:
                rate = schedule.maxRate
            interval = _Interval(schedule.startTime, t, omega1, rate)
            s = reading.SlidingCoordinate() if interval < REVERSAL_WINDOW else None   # a reversal may come: keep s
            schedule.nextCheck, schedule.lastCheck, schedule.maxRate = t + interval, CheckPoint(t, omega1, s), rate
            return None
        reversal = _ReversalCoordinate(schedule.lastCheck, t, omega1, reading.SlidingCoordinate())
        new, jump = reading.Switch(state, reversal)
    # after a reversal has been looked at, or a switch, the mesh is looked at after the next step again
    schedule.nextCheck, schedule.lastCheck = t, None
    if new is None:
        return None
    schedule.state = new
    return jump
