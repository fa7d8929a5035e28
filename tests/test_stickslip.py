"""The stick/slip schedule's decisions (exudyn_worm.model.stickslip), on made-up worm motions, without Exudyn:
when a mesh is looked at, when it switches, where a reversal is placed, what a restart forgets."""
import math
from dataclasses import replace

import pytest

from exudyn_worm.model.contact import FrictionState, SlidingCoordinate
from exudyn_worm.model.stickslip import (CHECK_FRACTION, CHECK_INTERVAL, REVERSAL_WINDOW, CarrySchedule, IsDue,
                                         MeshReading, NextCheck, StartFrictionState, StartSchedule, StickSlipStep)
from exudyn_worm.drive.presets import ElasticDriveFromParameters, GetPreset

GEAR = ElasticDriveFromParameters(GetPreset('reel-P1')).gear
H = 1e-4                       # s: the made-up solver step


class Motion(MeshReading):
    """A worm turning with speed ``omega(t)`` (the wheel still); records what the policy asked for and when.
    ``breakAway(t)``: whether stuck flanks break away at t (they slide on in the direction +1)."""

    def __init__(self, omega, alpha, angle, breakAway=lambda t: False):
        self.omega, self.alpha, self.angle, self.breakAway = omega, alpha, angle, breakAway
        self.t, self.speedAsked, self.switchAsked = 0., [], []

    def At(self, t):
        self.t = t
        return self

    def WormSpeed(self):
        self.speedAsked.append(self.t)
        return self.omega(self.t)

    def WormAcceleration(self):
        return self.alpha(self.t)

    def SlidingCoordinate(self):
        return SlidingCoordinate(GEAR, self.angle(self.t), 0.)

    def Switch(self, state, reversalCoordinate):
        self.switchAsked.append((self.t, reversalCoordinate))
        if state.stuck < 0.5:             # the worm turned back: stuck where it turned
            s = self.SlidingCoordinate() if reversalCoordinate is None else reversalCoordinate
            return FrictionState(1., state.direction, s), 1.
        if self.breakAway(self.t):
            return FrictionState(0., 1., state.anchor), 2.
        return None, 0.


def Run(motion, schedule, t0, t1):
    """Step the schedule from t0 to t1 (steps of H); return the schedule and the times of the switches."""
    switches = []
    for k in range(1, int(round((t1 - t0) / H)) + 1):
        t = t0 + k * H
        if StickSlipStep(schedule, t, motion.At(t)) is not None:     # updates the schedule in place
            switches.append(t)
    return schedule, switches


def test_start_state_follows_the_worm_speed():
    assert StartFrictionState(GEAR, 0.3, 0.01, 2.) == FrictionState(0., 1., SlidingCoordinate(GEAR, 0.3, 0.01))
    assert StartFrictionState(GEAR, 0.3, 0.01, -2.).direction == -1.
    assert StartFrictionState(GEAR, 0.3, 0.01, 0.).stuck == 1.


def test_a_steady_worm_is_looked_at_less_and_less_often_up_to_the_longest_interval():
    motion = Motion(lambda t: 50., lambda t: 0., lambda t: 50. * t)
    schedule, switches = Run(motion, StartSchedule(FrictionState(0., 1., 0.)), 0., 0.2)
    assert switches == []
    asked = motion.speedAsked
    # the first steps after the start, then waits that double with the time run (no deceleration seen yet) ...
    assert asked[:3] == pytest.approx([H, 2 * H, 3 * H])
    waits = [b - a for a, b in zip(asked, asked[1:])]
    assert waits[2:6] == pytest.approx([2 * H, 4 * H, 8 * H, 16 * H])
    # ... up to CHECK_INTERVAL (the schedule's longest wait), then at that interval (one step of rounding)
    assert max(waits) == pytest.approx(CHECK_INTERVAL, abs=1.01 * H)
    assert waits[-1] >= CHECK_INTERVAL - 1e-12
    assert len(asked) < 0.2 / CHECK_INTERVAL + 15         # far fewer looks than the 2000 steps
    assert NextCheck(schedule) == schedule.nextCheck > 0.2 - H


def test_a_decelerating_worm_is_looked_at_before_it_could_stop_and_sticks_at_the_first_step_after_it_turned():
    a, w0 = 400., 20.                            # rad/s^2, rad/s: the worm turns back at t = 0.05 s
    tTurn = w0 / a
    motion = Motion(lambda t: w0 - a * t, lambda t: -a, lambda t: w0 * t - 0.5 * a * t * t)
    schedule, switches = Run(motion, StartSchedule(FrictionState(0., 1., 0.)), 0., 0.06)
    assert len(switches) == 1
    assert tTurn < switches[0] <= tTurn + H + 1e-12                        # the first step with omega1 < 0
    # while sliding, each wait is at most the fraction CHECK_FRACTION of the time to stop at the deceleration seen
    asked = [t for t in motion.speedAsked if t < tTurn]
    for before, after in zip(asked[5:], asked[6:]):
        assert after - before <= max(CHECK_FRACTION * (w0 - a * before) / a, 0.) + H + 1e-12
    # the reversal is placed where the worm turned (interpolated between the last two looks), not at the step's end
    t, reversal = motion.switchAsked[0]                                    # then asked every step: stuck
    assert t == switches[0]
    sTurn = SlidingCoordinate(GEAR, w0 * tTurn - 0.5 * a * tTurn ** 2, 0.)
    sEnd = SlidingCoordinate(GEAR, motion.angle(t), 0.)
    assert reversal is not None and abs(reversal - sTurn) < 0.05 * abs(sEnd - sTurn)
    assert schedule.state == FrictionState(1., 1., reversal)
    assert NextCheck(schedule) == -math.inf                                # stuck: looked at after every step


def test_a_late_first_look_places_no_reversal():
    """A worm found turned back at the first look after more than REVERSAL_WINDOW: no interpolation."""
    motion = Motion(lambda t: -1., lambda t: 0., lambda t: -t)
    schedule = StartSchedule(FrictionState(0., 1., 0.))
    jump = StickSlipStep(schedule, 10 * REVERSAL_WINDOW, motion.At(10 * REVERSAL_WINDOW))
    assert motion.switchAsked == [(10 * REVERSAL_WINDOW, None)]
    assert jump == 1. and schedule.state.stuck == 1.


def test_stuck_flanks_are_looked_at_every_step_until_they_break_away():
    tBreak = 0.0105
    motion = Motion(lambda t: 0., lambda t: 0., lambda t: 0., breakAway=lambda t: t >= tBreak)
    schedule, switches = Run(motion, StartSchedule(FrictionState(1., 1., 0.)), 0., 0.02)
    stuckSteps = [t for t, _ in motion.switchAsked if t < tBreak]
    assert len(stuckSteps) == pytest.approx(tBreak / H, abs=1)            # every step while stuck
    assert switches == [pytest.approx(tBreak + 0.5 * H, abs=0.51 * H)]
    assert schedule.state.stuck == 0. and schedule.state.direction == 1.


def test_a_repeated_step_is_looked_at_and_an_earlier_time_starts_a_new_solve():
    motion = Motion(lambda t: 50., lambda t: 100., lambda t: 50. * t)
    schedule, _ = Run(motion, StartSchedule(FrictionState(0., 1., 0.)), 0., 0.1)
    assert schedule.maxRate > 0 and schedule.startTime == pytest.approx(H)
    t = schedule.lastTime
    assert not IsDue(schedule, t + H)             # sliding, the next look is later
    assert IsDue(schedule, t)                     # the same step again (the solver repeats it after a switch)
    assert IsDue(schedule, 0.5 * t)               # an earlier time: a new solve
    restarted = replace(schedule)
    assert StickSlipStep(restarted, 0.01, motion.At(0.01)) is None
    assert restarted.startTime == 0.01 and restarted.maxRate == 100.     # what the old solve learnt is forgotten
    assert restarted.nextCheck == 0.01            # a new solve's first look: after the next step again


def test_carrying_a_schedule_moves_the_anchor_with_the_shift():
    schedule = replace(StartSchedule(FrictionState(1., -1., 2e-4)), maxRate=7., startTime=0.5, lastTime=0.9)
    carried = CarrySchedule(schedule, -0.03)
    assert carried.state == FrictionState(1., -1., 2e-4 - 0.03)
    assert replace(carried, state=schedule.state) == schedule
    assert schedule.state.anchor == 2e-4                      # the schedule carried is left as it was
