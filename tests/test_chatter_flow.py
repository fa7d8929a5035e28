"""The one-period map of the Exudyn model (exudyn_worm.analysis.orbits.exudynflow.ExudynFlow) with the sticking friction model:
its result must depend on the start state and the time alone, not on the calls before it (the stick/slip state
of the connector lives outside the ODE2 coordinates; before the fix it was left from the previous call, and a
call from the same start after a call that ended with the worm turning back differed by 1e-3 of the state
scale, which also polluted the finite-difference monodromy)."""
import numpy as np
import pytest

import exudyn_worm as ew
from exudyn_worm.analysis.orbits.chatter import (BuildLoweringModel, FindSteadyChatter, SettleLowering, StateScale, _LoweringFlow)
from exudyn_worm.analysis.orbits.lowering import EquilibriumState
from exudyn_worm.analysis.orbits.longsimulation import LongSimulationAmplitude, SettledSimulationAmplitude
from exudyn_worm.model.contact import FrictionState, SlidingCoordinate
from exudyn_worm.analysis.charts.speedchart import RPM
from exudyn_worm.drive.wholedrive import ResolveDrive

pytestmark = pytest.mark.usefixtures('emptyWorkingDirectory')


@pytest.fixture(scope='module')
def lowering():
    model = BuildLoweringModel(ResolveDrive(parameters=ew.GetPreset('reel-P1')))      # sticking friction model (the default)
    assert model.connector.stickSlip is not None
    return model, _LoweringFlow(model, 400)


def _Starts(model):
    forward = EquilibriumState(model)
    forward[2] = 0.05 * model.motorSpeed
    backward = EquilibriumState(model)
    backward[2] = -2. * model.motorSpeed          # the worm turns back: the stick/slip state switches
    return forward, backward


def test_flow_is_deterministic_after_a_call_that_ends_turned_back(lowering):
    model, flow = lowering
    forward, backward = _Starts(model)
    T = 0.002
    first = flow(forward, T)
    again = flow(forward, T)
    np.testing.assert_array_equal(first, again)
    flow(backward, T)
    assert model.connector.stickSlip.state.direction == -1.     # this call ended with the worm turned back
    after = flow(forward, T)
    assert np.max(np.abs(after - first) / StateScale(model)) <= 1e-12


def test_flow_restart_state_follows_the_start(lowering):
    model, flow = lowering
    forward, backward = _Starts(model)
    flow(forward, 1e-3)
    state = model.connector.stickSlip.state
    assert state.stuck == 0. and state.direction == 1.
    flow(backward, 1e-4)                            # starts sliding backward: no switch
    assert model.connector.stickSlip.state.direction == -1. and model.connector.stickSlip.switches == 0
    # restart=False goes on with the previous solve's state (sliding forward): the backward start is a reversal
    flow(forward, 1e-3)
    flow.Solve(backward, 1e-4, restart=False)
    assert model.connector.stickSlip.switches >= 1


def test_carry_keeps_the_stretch_of_the_stuck_flanks(lowering):
    """A run continued in pieces (restart=False) shifts the coordinates back by the steady rotation; the anchor
    of stuck flanks must move with them, else the sticking spring is stretched by the sliding of a whole piece
    (reel-P3 with a Stribeck law at 200 rpm then ran into a different motion, force factor 10.4 instead of 2.31)."""
    model, flow = lowering
    stickSlip = model.connector.stickSlip
    mbs = model.mbs
    n = mbs.systemData.ODE2Size()
    q0 = np.array(mbs.systemData.GetODE2Coordinates(), dtype=float)
    q1 = q0.copy()
    worm, wheel = (mbs.GetNodeODE2Index(k) for k in stickSlip.nodes[:2])
    q1[worm] -= 3.1
    q1[wheel] -= 0.4
    stickSlip.state = FrictionState(1., 1., 1e-4)
    Stretch = lambda q: SlidingCoordinate(model.drive.gear, *(q[i] + r for i, r in
                                                              zip((worm, wheel), stickSlip.references))) - \
        stickSlip.state.anchor
    before = Stretch(q0)
    state = stickSlip.Carry(mbs, q0, q1)
    assert state.stuck == 1. and state.direction == 1.
    assert abs(Stretch(q1) - before) <= 1e-12 and abs(state.anchor - 1e-4) > 1e-3
    stickSlip.Restart(mbs, q0, np.ones(n))


def test_settled_simulation_stops_when_the_amplitude_stops_changing():
    p1 = ew.GetPreset('reel-P1')
    settled = SettledSimulationAmplitude(ResolveDrive(parameters=p1), maxDuration=20.)
    assert settled['settled'] and settled['duration'] < 20. and settled['change'] < 5e-4
    assert settled['peakSpread'] < 0.01                  # P1's chatter is periodic
    fixed = LongSimulationAmplitude(ResolveDrive(parameters=p1), duration=settled['duration'], stepSize=2e-4)
    for key in ('forceFactor', 'maxWheelAcceleration'):
        assert settled[key] == pytest.approx(fixed[key], rel=1e-3)
    short = SettledSimulationAmplitude(ResolveDrive(parameters=p1), maxDuration=1., piece=0.5)       # chatter still growing at 1 s
    assert not short['settled'] and short['duration'] == pytest.approx(1.)


def test_settled_simulation_rejects_a_piece_shorter_than_the_window():
    with pytest.raises(ValueError, match=r"SettledSimulationAmplitude: 'piece' must be longer than 'window'"):
        SettledSimulationAmplitude(ResolveDrive(parameters=ew.GetPreset('reel-P1')), piece=0.2, window=0.25)


@pytest.mark.slow
def test_friction_limited_orbit_near_the_hopf_point_equals_a_settled_run():
    """reel-P3 with a Stribeck law, 3.5 % above the lower linear boundary (85.08 rpm): the orbit stays in contact
    and its amplitude is set by the falling friction. Shot from a settled run and continued one step towards the
    boundary, it equals a time simulation from rest run until settled within 2 % (the required agreement)."""
    base = {**ew.GetPreset('reel-P3'), 'frictionLaw': 'stribeck', 'mu': 0.092, 'muStatic': 0.2,
            'stribeckVelocity': 0.9}
    orbit = FindSteadyChatter(ResolveDrive(parameters={**base, 'motorSpeed': 88. * RPM}), settleTime=40., maxIterations=40)
    assert orbit.info['forceFactor'] < 2. and orbit.info['minWormSpeed'] > 0.       # in contact, sliding forward
    assert orbit.stable
    closer = FindSteadyChatter(ResolveDrive(parameters={**base, 'motorSpeed': 87. * RPM}), start=(orbit.state, orbit.period),
                               maxIterations=40)
    # towards the Hopf point the amplitude shrinks and the amplitude's multiplier approaches 1
    assert closer.info['maxWheelAcceleration'] < orbit.info['maxWheelAcceleration']
    assert 1. - max(abs(closer.nontrivialMultipliers)) < 1. - max(abs(orbit.nontrivialMultipliers))
    long = SettledSimulationAmplitude(ResolveDrive(parameters={**base, 'motorSpeed': 88. * RPM}))
    assert long['settled'] and long['peakSpread'] < 0.01
    for key in ('forceFactor', 'maxWheelAcceleration'):
        assert orbit.info[key] == pytest.approx(long[key], rel=0.02)


def test_one_period_run_started_at_the_largest_worm_speed_sees_the_reversal():
    """A one-period run that starts where the worm is fastest sees no acceleration at its first look; the check of
    a sliding worm was then put off by CHECK_INTERVAL (0.02 s), longer than a chatter period of reel-P3 (0.015 s),
    and the worm turned back without sticking (no switch, the friction still pushing it forward)."""
    p = {**ew.GetPreset('reel-P3'), 'frictionLaw': 'stribeck', 'mu': 0.092, 'muStatic': 0.2,
         'stribeckVelocity': 0.9, 'motorSpeed': 140. * RPM}
    model = BuildLoweringModel(ResolveDrive(parameters=p))
    x, _ = SettleLowering(model, 5.)
    probe = _LoweringFlow(model, 4000)
    probe.Solve(x, 0.4, storeSensors=True)
    s = model.connector.StoredStates(model.mbs)
    t, period = s['time'], 1. / 68.7
    last = np.nonzero(t >= t[-1] - period)[0]
    k = last[np.argmax(s['omega1'][last])]
    assert np.min(s['omega1'][last]) < 0.                  # the worm turns back in every period
    w1, w2 = model.motorSpeed, model.motorSpeed / model.drive.gear.ratio
    x0 = np.array([s['phi1'][k] - w1 * t[k], s['phi2'][k] - w2 * t[k], s['omega1'][k] - w1, s['omega2'][k] - w2])
    _LoweringFlow(model, 400).Solve(x0, period, storeSensors=True)
    assert model.connector.stickSlip.switches >= 2         # stuck at the reversal, sliding again later
    assert np.any(model.connector.stickSlip.StatesAt(model.connector.StoredStates(model.mbs)['time']).stuck > 0.5)
