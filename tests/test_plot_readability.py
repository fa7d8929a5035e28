"""Figures a reader can read: S drawn as the paper's +-1 in its own panel over a whole run, one panel per flank
with the mean the chatter exceeds, titles naming the run."""
import numpy as np
import pytest

import exudyn_worm as ew
from exudyn_worm.plot import MEAN_WINDOW, PlotSimulation, _RunningMean


@pytest.fixture(scope='module')
def result():
    return ew.SimulateReelChanger(ew.GetPreset('reel-P1'), endTime=3., stepSize=5e-4, progress=False)


def test_drive_torque_and_S_in_separate_panels(result):
    fig = PlotSimulation(result, kind='driveTorque', subtitle='preset reel-P1, --set J1=0.1')
    top, bottom = fig.axes
    assert len(fig.axes) == 2 and 'preset reel-P1, --set J1=0.1' in top.get_title()
    S = bottom.lines[0].get_ydata()
    assert set(np.unique(S)) <= {-1., 0., 1.} and set(np.unique(S)) >= {-1., 1.}     # the paper's S = +-1
    assert 'regularized' in bottom.get_title(loc='left')


def test_normal_force_one_panel_per_flank_with_mean(result):
    fig = PlotSimulation(result, kind='normalForce')
    assert len(fig.axes) == 2
    for flank, ax in enumerate(fig.axes, start=1):
        force, mean = (line.get_ydata() for line in ax.lines[:2])
        assert np.all(force >= 0) and f'mean over {MEAN_WINDOW:g} s' in ax.get_legend_handles_labels()[1]
        if flank == 2:                       # lowering with chatter: peaks far above the mean
            assert force.max() > 1.3 * mean.max()


def test_running_mean_of_an_oscillation_does_not_drift_at_the_ends():
    """The mean over 0.25 s of a force oscillating between 0 and 2 kN about 1 kN is 1 kN up to the last sample
    (it dropped at the end when the window was padded with the last, oscillating value)."""
    t = np.arange(0., 4., 5e-4)
    force = 1000. * (1. + np.sin(2 * np.pi * 40. * (t - t[-1]) + np.pi / 2))      # ends on a 2 kN peak
    mean = _RunningMean(t, force, 0.25)
    assert mean.shape == force.shape
    inner = (t > 0.125) & (t < t[-1] - 0.125)
    np.testing.assert_allclose(mean[inner], 1000., rtol=1e-9)                      # whole periods
    assert np.max(np.abs(mean - 1000.)) < 70.             # half a window at the ends: >= 5 periods (was 500 N off)
    np.testing.assert_allclose(_RunningMean(t, np.full_like(t, 7.), 0.25), 7.)
