"""Figures a reader can read: S drawn as the paper's +-1 in its own panel over a whole run, one panel per flank
with the mean the chatter exceeds, titles naming the run."""
import numpy as np
import pytest

import exudyn_worm as ew


@pytest.fixture(scope='module')
def result():
    return ew.SimulateReelChanger(ew.GetPreset('reel-P1'), endTime=3., stepSize=5e-4, progress=False)


def test_drive_torque_and_S_in_separate_panels(result):
    from exudyn_worm.plot import PlotSimulation
    fig = PlotSimulation(result, kind='driveTorque', subtitle='preset reel-P1, --set J1=0.1')
    top, bottom = fig.axes
    assert len(fig.axes) == 2 and 'preset reel-P1, --set J1=0.1' in top.get_title()
    S = bottom.lines[0].get_ydata()
    assert set(np.unique(S)) <= {-1., 0., 1.} and set(np.unique(S)) >= {-1., 1.}     # the paper's S = +-1
    assert 'regularized' in bottom.get_title(loc='left')


def test_normal_force_one_panel_per_flank_with_mean(result):
    from exudyn_worm.plot import MEAN_WINDOW, PlotSimulation
    fig = PlotSimulation(result, kind='normalForce')
    assert len(fig.axes) == 2
    for flank, ax in enumerate(fig.axes, start=1):
        force, mean = (line.get_ydata() for line in ax.lines[:2])
        assert np.all(force >= 0) and f'mean over {MEAN_WINDOW:g} s' in ax.get_legend_handles_labels()[1]
        if flank == 2:                       # lowering with chatter: peaks far above the mean
            assert force.max() > 1.3 * mean.max()
