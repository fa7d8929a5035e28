"""The benchmark's scipy baseline (benchmarks/scipy_reference.py) integrates the same model as Exudyn.

Three seconds of the reel changer P1: lifting (0 to T/4 = 2 s, quasi-static, no chatter) and the onset of
the chatter after the load reverses at 2 s. Only results are compared, never wall-clock times.
"""

import numpy as np
import pytest

from exudyn_worm.drive.presets import GetPreset
from exudyn_worm.analysis.simulation.reelchanger import DEFAULT_STEP_SIZE, SimulateReelChanger
from exudyn_worm.drive.wholedrive import ResolveDrive

from conftest import LoadScript

END_TIME = 3.


def _LoadReference():
    return LoadScript('benchmarks/scipy_reference.py', 'scipy_reference')


@pytest.fixture(scope='module')
def reference():
    return _LoadReference()


@pytest.fixture(scope='module')
def runs(reference):
    p1 = GetPreset('reel-P1')
    ours = SimulateReelChanger(ResolveDrive(parameters=p1), endTime=END_TIME, stepSize=DEFAULT_STEP_SIZE)    # 5e-4 s: scipy's output grid
    # tight tolerances: this run stands for the exact solution of eqs. (1)-(2)
    scipy = reference.SolveReelChangerScipy(p1, endTime=END_TIME, method='LSODA', rtol=1e-8, atol=1e-11)
    return ours, scipy


def _Window(result, t0, t1):
    return (result.time >= t0) & (result.time <= t1)


@pytest.mark.physics
def test_starts_in_equilibrium(reference):
    # the scipy model starts from SteadyInitialState as the Exudyn model does: no initial acceleration
    rhs, y0, *_ = reference.ReelChangerOde(GetPreset('reel-P1'))
    omega1, omega2, alpha1, alpha2 = rhs(0., y0)
    assert abs(alpha1) < 1e-8 and abs(alpha2) < 1e-8
    assert omega1 == pytest.approx(y0[2]) and omega2 == pytest.approx(y0[3])


@pytest.mark.physics
def test_same_output_grid(runs):
    ours, scipy = runs
    np.testing.assert_allclose(scipy.time, ours.time, rtol=0, atol=1e-12)


@pytest.mark.physics
def test_lifting_phase_agrees_pointwise(runs):
    # 0..2 s: smooth quasi-static lifting. The solutions differ only by the integration errors (Exudyn's
    # generalized-alpha at h = 5e-4 s, LSODA at rtol 1e-8): measured 4e-7 of the force and 5e-10 rad.
    # The tolerances leave a margin of 25x and 200x, yet a 0.1 % change of the load mass, of kT or of the
    # friction angle in one model already exceeds one of them (checked by hand).
    ours, scipy = runs
    m = _Window(ours, 0., 2.)
    forceScale = np.max(np.abs(scipy.normalForce[m]))
    np.testing.assert_allclose(ours.normalForce[m], scipy.normalForce[m], rtol=0, atol=1e-5 * forceScale)
    np.testing.assert_allclose(ours.phi2[m], scipy.phi2[m], rtol=0, atol=1e-7)
    np.testing.assert_allclose(ours.phi1[m], scipy.phi1[m], rtol=0, atol=1e-6)
    assert np.max(np.abs(ours.alpha2[m])) < 0.1 and np.max(np.abs(scipy.alpha2[m])) < 0.1   # no chatter yet


@pytest.mark.physics
def test_chatter_onset_agrees(runs):
    # 2.5..3 s: the chatter has built up (the paper's P1 chatters in the lowering phase). Self-excited
    # oscillations drift in phase, so the amplitudes are compared, not the samples: peak |phi2''| and peak
    # normal force within 1 % (the required agreement; measured 0.07 % and 0.34 %, from the sampling
    # of the ~40 Hz oscillation and its harmonics at 2 kHz and Exudyn's step-size error), and the dominant
    # frequency within 2 Hz, the frequency resolution of a 0.5 s window.
    ours, scipy = runs
    window = (2.5, END_TIME)
    a, b = ours.WindowMetrics([window])[0], scipy.WindowMetrics([window])[0]
    assert a['maxAbsWheelAcceleration'] > 10. and b['maxAbsWheelAcceleration'] > 10.      # chatter present
    assert a['maxAbsWheelAcceleration'] == pytest.approx(b['maxAbsWheelAcceleration'], rel=0.01)
    assert a['maxNormalForce'] == pytest.approx(b['maxNormalForce'], rel=0.01)
    assert a['dominantFrequencyHz'] == pytest.approx(b['dominantFrequencyHz'], abs=2.)
