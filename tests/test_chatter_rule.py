"""The chatter rule of SimulationResult.ChatterVerdict: a mesh vibration (normal force or sliding) of at least a
quarter of its steady value whose envelope grows, or keeps a saturated amplitude, over the window's second half is
chatter; one that decays within the window is not; one that decays slower than the window (or stays steady below
saturation) is undecided; never on an unloaded mesh (validation/CHATTER_RULE.md)."""
import math

import numpy as np
import pytest

from exudyn_worm import GetPreset, SimulateReelChanger
from exudyn_worm.items.results import (CHATTER_AMPLITUDE, CHATTER_DECAY_EXPONENT, CHATTER_GROWTH_EXPONENT,
                                       CHATTER_MIN_MESH_TORQUE, CHATTER_SATURATION, CHATTER_STEADY_EXPONENT,
                                       ChatterVerdict, SimulationResult)
from exudyn_worm.analysis.simulation.reelchanger import DefaultPhases
from exudyn_worm.drive.wholedrive import ResolveDrive

_T = np.linspace(0., 1., 20001)
#: frequency in Hz of the test tones: 100 periods in each quarter of the window [0, 1] s
_F = 400.
#: the quadratic removed from a pure tone of N whole periods per quarter tilts it by at most 6/(2 pi N) of its
#: amplitude (its least-squares slope 12/(omega T^2) times T/2), so the measure reads that much high at most
_TILT = 6. / (2 * np.pi * _F / 4)


def _Result(force=5000., forceWave=0., motorSpeed=10., wormWave=0., meshTorque=368., info=None, time=_T):
    """A window [0, time[-1]]: the normal force ``force (1 + forceWave(t))``, the worm speed ``motorSpeed + wormWave(t)``."""
    def Wave(w):
        return w(time) if callable(w) else w * np.sin(2 * np.pi * _F * time)
    series = {'normalForce': force * (1. + Wave(forceWave)), 'wheelTorque': meshTorque + 0. * time,
              'omega0': motorSpeed + 0. * time, 'omega1': motorSpeed + Wave(wormWave), 'alpha2': 0. * time,
              'S': 1. + 0. * time}
    return SimulationResult(time=time, series=series, J2=0.02, r2=0.075, info=info or {})


def _Decaying(amplitude, rate, frequency=_F):
    return lambda t: amplitude * np.exp(-rate * t) * np.sin(2 * np.pi * frequency * t)


def test_the_thresholds_of_the_rule():
    """The values fixed in validation/CHATTER_RULE.md before the corpus was run."""
    assert (CHATTER_AMPLITUDE, CHATTER_STEADY_EXPONENT, CHATTER_GROWTH_EXPONENT, CHATTER_DECAY_EXPONENT,
            CHATTER_SATURATION) == (0.25, 0.2, 0.2, 1., 1.)


def test_normal_force_amplitude_against_its_threshold():
    """A steady tone of 1.5 times the steady force (the flanks unload: saturated) is chatter; 0.3 keeps its amplitude
    but does not saturate (a free vibration looks the same): undecided; 0.2 is small motion."""
    assert _Result(forceWave=1.5).Chatter(0., 1.)
    steady = _Result(forceWave=0.3).ChatterVerdict(0., 1.)
    assert steady.state == 'undecided' and not steady.chatter and not steady.decided
    assert 'steady' in steady.Describe() and 'below the saturated amplitude 1' in steady.Describe()
    assert _Result(forceWave=0.2).ChatterVerdict(0., 1.).state == 'none'
    amplitudes = _Result(forceWave=0.3).MeshOscillation(0., 1.)
    assert all(0.3 <= a <= 0.3 * (1 + _TILT) for a in amplitudes['normal'])  # half the range over the steady force
    assert amplitudes['sliding'] == [0.] * 4


@pytest.mark.parametrize('rate', [-3., -0.25, 3.])
def test_the_envelope_rate_of_a_decaying_or_growing_tone(rate):
    """exp(rate t) sin(2 pi f t): the envelope's rate over the second half is ``rate`` (closed form); the removed
    quadratic tilts each period's half range by at most _TILT of the amplitude, which leaves the slope of its log
    within 1 % of the rate's magnitude here, or 0.01 1/s. The largest amplitude is 0.5 (the quadratic fitted to the
    force stays at its steady 5000 N)."""
    result = _Result(forceWave=_Decaying(0.5 * min(1., math.exp(-rate)), -rate))
    measured = result.EnvelopeRates(0., 1.)['normal']
    assert measured == pytest.approx(rate, rel=0.01, abs=0.01)


def test_a_decay_within_the_window_is_not_chatter_a_growth_is():
    """sigma L = -3 (decay time a third of the window): decaying, decided, not chatter, even where the last quarter is
    still far above the amplitude threshold; sigma L = +3: chatter, growing, from 5 % to 1.0."""
    decaying = _Result(forceWave=_Decaying(3., 3.)).ChatterVerdict(0., 1.)
    assert decaying.amplitude > CHATTER_AMPLITUDE and decaying.state == 'decaying' and decaying.decided
    assert decaying.Describe().startswith('decaying, rate -') and decaying.rate == pytest.approx(-3., rel=0.01)
    growing = _Result(forceWave=_Decaying(0.05, -3.)).ChatterVerdict(0., 1.)
    assert growing.chatter and growing.Describe().startswith('growing, rate +') and growing.rate > 2.


def test_a_swing_that_decays_slower_than_the_window_is_undecided():
    """The solar tracker's swing: 2.4 Hz decaying at 0.25 1/s (D = 0.25 / (2 pi 2.4) = 1.7 %) in a window of 4 s
    (2.4 periods in the last quarter, 4.8 in the second half): the decay time 4 s is not shorter than the window; the
    verdict says so and is never chatter. The rate's tolerance is the measure's own limit with few periods
    (validation/CHATTER_RULE.md)."""
    time = np.linspace(0., 4., 40001)
    verdict = _Result(forceWave=_Decaying(0.8, 0.25, 2.4), time=time).ChatterVerdict(0., 4.)
    assert verdict.state == 'undecided' and not verdict.chatter
    assert verdict.rate == pytest.approx(-0.25, rel=0.05)
    assert ', decaying, rate -0.' in verdict.Describe()
    assert "longer than the window 4 s" in verdict.Describe()


def test_a_window_of_few_periods_is_undecided_even_where_its_rate_is_measured():
    """The same swing in the tracker's window of 1.8 s: 1.08 periods in the last quarter (fewer than 2), although the
    second half holds 2.2 (enough for a rate): the amplitude is not trusted, the window is undecided and says why."""
    time = np.linspace(0., 1.8, 18001)
    verdict = _Result(forceWave=_Decaying(0.8, 0.25, 2.4), time=time).ChatterVerdict(0., 1.8)
    assert verdict.state == 'undecided' and math.isnan(verdict.rate)
    assert "fewer than 2 periods of its dominant frequency in the window's last quarter" in verdict.Describe()


def test_a_slow_swing_the_last_quarter_cannot_see_is_undecided_not_none():
    """A swing of 2 times the mean force at 1.27 Hz in a window of 1 s (the last quarter holds a third of a period):
    the quadratic over that quarter follows the swing, but with the window's quadratic removed the last quarter
    still swings by more than CHATTER_AMPLITUDE: undecided, not none. The same swing at 0.05 of the mean reads small
    both ways: none. The closed form of the first: the tone's range over the quarter (0.32 of a period, from its
    phase 2 pi 1.27 0.75 on) exceeds half its amplitude, so the reading is far above 0.25 at amplitude 2."""
    large = _Result(forceWave=_Decaying(2., 0., 1.27)).ChatterVerdict(0., 1.)
    assert large.state == 'undecided' and large.amplitude >= CHATTER_AMPLITUDE
    assert _Result(forceWave=_Decaying(2., 0., 1.27)).MeshOscillation(0., 1.)['normal'][3] < large.amplitude
    assert _Result(forceWave=_Decaying(0.05, 0., 1.27)).ChatterVerdict(0., 1.).state == 'none'


def test_the_rate_of_a_swing_much_larger_than_its_mean():
    """A tone of 200 times the mean force decaying at 3 1/s (it changes flanks in every period): the fitted steady value
    cannot be told from the swing (its bound (6 / pi) (a / N) (L / T), a = 200 exp(-1.5) = 44.6 at the second half's
    start, N = 200 periods, is 0.8 > 0.2), so the rate is the half range's own: the closed form's -3 1/s within the
    tolerance of the decaying tone above (the half range does not depend on the mean)."""
    result = _Result(force=25., forceWave=_Decaying(200., 3.))
    assert result.EnvelopeRates(0., 1.)['normal'] == pytest.approx(-3., rel=0.01, abs=0.01)
    assert result.ChatterVerdict(0., 1.).state == 'decaying'


def test_a_chatter_under_a_falling_load_keeps_its_relative_amplitude():
    """The reel changer's case: the mean force falls linearly to half over the window and the vibration keeps half of
    it, 5000 (1 - t/2) (1 + 0.5 sin(2 pi 400 t)): the half range itself decays (its log falls by ln 1.5 = 0.41 over
    the second half), the relative envelope does not. The quadratic fits the linear mean exactly and 200 periods make
    the swing's leak small (bound 0.01), so the envelope is divided: rate 0 within 0.01 1/s."""
    result = _Result()
    result.series['normalForce'] = 5000. * (1. - 0.5 * _T) * (1. + 0.5 * np.sin(2 * np.pi * _F * _T))
    assert abs(result.EnvelopeRates(0., 1.)['normal']) <= 0.01


@pytest.mark.parametrize('shift, state', [(-0.15, 'chatter'), (0.15, 'undecided')])
def test_the_worm_turning_back_saturates_the_sliding(shift, state):
    """A steady stick-slip whose half range is 0.9 of the motor speed, the worm speed 10.5 (1 + shift + 0.9 sin):
    shifted down by 0.15 the worm turns back (smallest speed -0.05 of the motor's): chatter, steady, although the
    amplitude is below CHATTER_SATURATION; shifted up it does not (smallest 0.25): undecided, steady below saturation."""
    wave = lambda t: 10.5 * (shift + 0.9 * np.sin(2 * np.pi * 184. * t))
    result = _Result(motorSpeed=10.5, wormWave=wave)
    verdict = result.ChatterVerdict(0., 1.)
    assert verdict.amplitude == pytest.approx(0.9, rel=6. / (2 * np.pi * 46))
    assert result.MinWormSpeed(0.75, 1.) == pytest.approx(10.5 * (1 + shift - 0.9), rel=1e-3)
    assert verdict.state == state and verdict.measures == ('sliding',)
    if state == 'chatter':
        assert verdict.Describe().startswith('steady, the worm turning back')


def test_a_worm_ringing_at_rest_is_no_reversal():
    """With the motor at rest (below the friction law's regularization worm speed, 2 rad/s here) a worm swinging
    around zero by 1.6 rad/s (0.8 of that speed) is not turning back: undecided, not chatter."""
    info = {'frictionSpeed': 0.05, 'slidingRadius': 0.025}
    verdict = _Result(motorSpeed=0., wormWave=1.6, info=info).ChatterVerdict(0., 1.)
    assert verdict.state == 'undecided'


def test_fewer_than_two_periods_in_the_second_half_is_undecided():
    """A 3 Hz swing of amplitude 1 in a window of 1 s: 1.5 periods in the second half, no rate."""
    verdict = _Result(forceWave=_Decaying(1., 0., 3.)).ChatterVerdict(0., 1.)
    assert verdict.state == 'undecided' and math.isnan(verdict.rate)
    assert 'fewer than 2 periods' in verdict.Describe()


def test_stick_slip_that_stops_at_the_window_end_is_still_steady():
    """A saturated stick-slip (sliding 1.1) that stops in the window's last 5 % (the motor ramps to rest): the robust
    fit reads it as steady, chatter, where a least-squares fit of all spans would read a decay."""
    wave = lambda t: np.where(t < 0.95, 11.5, 0.) * np.sin(2 * np.pi * 184. * t)
    verdict = _Result(motorSpeed=10.5, wormWave=wave).ChatterVerdict(0., 1.)
    assert verdict.chatter and abs(verdict.rate) < CHATTER_STEADY_EXPONENT


def test_the_verdict_from_window_metrics():
    """ChatterVerdict.FromMetrics reads what WindowMetrics (and the JSON of simulate) stores."""
    result = _Result(forceWave=_Decaying(3., 3.))
    metrics = result.WindowMetrics([(0., 1.)])[0]
    assert metrics['chatter'] is False and metrics['chatterState'] == 'decaying'
    again = ChatterVerdict.FromMetrics(metrics)
    assert again.Describe() == result.ChatterVerdict(0., 1.).Describe()
    undecided = _Result(forceWave=0.3).WindowMetrics([(0., 1.)])[0]
    assert undecided['chatter'] == 'undecided'


def test_worm_stick_slip_with_reversal_is_chatter_in_both_directions():
    """The worm oscillates by 1.1 times the motor speed at 184 Hz (it turns back), the normal force stays steady:
    chatter by the sliding measure, lifting (motor forward) and lowering (motor reversed)."""
    for motorSpeed in (10.5, -10.5):                   # 46 periods in a quarter
        wave = lambda t: 1.1 * abs(motorSpeed) * np.sin(2 * np.pi * 184. * t)
        result = _Result(motorSpeed=motorSpeed, wormWave=wave)
        assert all(1.1 <= a <= 1.1 * (1 + 6. / (2 * np.pi * 46)) for a in result.MeshOscillation(0., 1.)['sliding'])
        assert result.Chatter(0., 1.)
        assert result.MinWormSpeed(0., 1.) == pytest.approx(-0.1 * 10.5, rel=1e-3)   # turned back by 1.05 rad/s
    assert _Result(motorSpeed=-10.5).MinWormSpeed(0., 1.) == pytest.approx(10.5)   # lowering without reversal


def test_standstill_sliding_is_measured_against_the_regularization_speed():
    """With the motor at rest the sliding amplitude is relative to frictionSpeed / slidingRadius (here 2 rad/s):
    a ringing of 0.1 rad/s is not chatter, one of 3 rad/s (1.5 of it, sustained) is."""
    info = {'frictionSpeed': 0.05, 'slidingRadius': 0.025}
    assert not _Result(motorSpeed=0., wormWave=0.1, info=info).Chatter(0., 1.)
    assert all(0.5 <= a <= 0.5 * (1 + _TILT) for a in _Result(motorSpeed=0., wormWave=1., info=info)
               .MeshOscillation(0., 1.)['sliding'])
    assert _Result(motorSpeed=0., wormWave=3., info=info).Chatter(0., 1.)


def test_no_load_no_chatter():
    """The same proportions at round-off level of the mesh torque: no load, no chatter."""
    assert _Result(force=2e-7 / 0.075, forceWave=1.5, meshTorque=2e-7).ChatterVerdict(0., 1.).state == 'none'
    assert _Result(force=10 * CHATTER_MIN_MESH_TORQUE / 0.075, forceWave=1.5,
                   meshTorque=10 * CHATTER_MIN_MESH_TORQUE).Chatter(0., 1.)


@pytest.mark.physics
def test_unloaded_reel_changer_does_not_chatter():
    """loadMass = 0: the mesh carries only round-off (|phi2''| about 1e-9 rad/s^2), which a relative rule alone
    would call chatter in both windows."""
    p = dict(GetPreset('reel-P1'), loadMass=0.)
    result = SimulateReelChanger(ResolveDrive(parameters=p), endTime=4., progress=False)
    metrics = result.WindowMetrics([(0., 2.), (2., 4.)])
    assert max(m['maxAbsWheelAcceleration'] for m in metrics) < 1e-6
    assert [m['chatter'] for m in metrics] == [False, False]


#: a rope hoist (gear mx 3 mm, z1 1, z2 50, q 16; Stribeck 0.07 / 0.12 / 0.3 m/s; motor shaft 2000 N m/rad; wheel
#: 0.02 kg m^2 behind which a load shaft of 8e4 N m/rad carries drum and load, 6.2 kg m^2; 300 kg on a 125 mm drum
#: as a constant torque; lift, pause, lower at 100 rpm). J1, kV, DV, DT are chosen values.
_RPM = 2 * math.pi / 60
HOIST = {'alphaN': math.radians(20), 'mx': 3e-3, 'z1': 1, 'z2': 50, 'q': 16, 'mu': 0.07, 'muStatic': 0.12,
         'stribeckVelocity': 0.3, 'frictionLaw': 'stribeck', 'kV': 1e8, 'DV': 0.014, 'backlash': 0.,
         'J1': 2e-3, 'kT': 2000., 'DT': 0.014, 'J2': 0.02, 'JL1': 6.2, 'kL1': 8e4, 'dL1': 0.,
         'loadType': 'constant', 'loadTorque': -300 * 9.80665 * 0.125, 'motorType': 'speedTable',
         'motorSpeedOverTime': [(0, 0), (0.1, 100 * _RPM), (1.0, 100 * _RPM), (1.1, 0), (1.5, 0),
                                (1.6, -100 * _RPM), (2.5, -100 * _RPM), (2.6, 0), (3.0, 0)]}


def test_worm_side_stick_slip_of_a_hoist_is_chatter():
    """The worm vibrates against its soft shaft and turns back while lifting and lowering; the wheel barely
    moves, so its inertia torque stays far below a tenth of the mesh torque (the wheel's measure misses it),
    while the mesh's sliding measure exceeds 1 (the worm turns back). Standing still under load, no chatter."""
    result = SimulateReelChanger(ResolveDrive(parameters=HOIST), progress=False)
    phases = DefaultPhases(ResolveDrive(parameters=HOIST), result.endTime)
    assert [ph for _, _, ph in phases] == ['lift', 'idle', 'lower', 'idle']
    for t0, t1, phase in phases:
        late = (result.time >= 0.5 * (t0 + t1)) & (result.time <= t1)
        wheel = result.J2 * np.max(np.abs(result.series['alpha2'][late]))
        assert wheel < 0.1 * np.max(np.abs(result.series['wheelTorque'][late]))
        sliding = result.MeshOscillation(t0, t1)['sliding'][3]
        if phase == 'idle':
            assert not result.Chatter(t0, t1)
        else:
            assert sliding > 1. and result.ChatterMeasures(t0, t1)[-1] == 'sliding'
            assert result.MinWormSpeed(t0, t1) < 0.                      # turned back, in either direction
