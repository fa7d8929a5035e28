"""Figures a reader can read: S drawn as the paper's +-1 in its own panel over a whole run, one panel per flank
with the mean the chatter exceeds, titles naming the run."""
import dataclasses
import sys

import numpy as np
import pytest

import exudyn_worm as ew
from exudyn_worm.plotting.plot import (DENSE_SWITCHES_PER_INCH, MEAN_WINDOW, S_SIGN_NOTE, FrictionStateDrawn,
                                       MergePhases, PhaseMeans, PlotSimulation, TorqueSignNote, _RunningMean)
from exudyn_worm.plotting.plot_charts import PlotSpeedChart
from exudyn_worm.items.results import SimulationResult
from exudyn_worm.drive.wholedrive import ResolveDrive
from exudyn_worm.analysis.charts.speedchart import RPM, SpeedStabilityChart
from exudyn_worm.drive.presets import GetPreset


@pytest.fixture(scope='module')
def result():
    return ew.SimulateReelChanger(ResolveDrive(parameters=ew.GetPreset('reel-P1')), endTime=3., stepSize=5e-4, progress=False)


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


# --- readable figures: labels outside the data, the first time tick, the sign of M_an, a readable sign(S) -------

@pytest.fixture(autouse=True)
def _CloseFigures():
    """Figures go through pyplot once another test imported it: close them (pyplot keeps them)."""
    yield
    if 'matplotlib.pyplot' in sys.modules:
        sys.modules['matplotlib.pyplot'].close('all')


def _Record(seconds=2., chatterHz=40., omegaSign=1.):
    """Synthetic reel-changer-like record: a quarter turn of the wheel per s, chatter while lowering."""
    t = np.linspace(0., seconds, int(1000 * seconds) + 1)
    phi2 = 0.5 * np.pi * t
    chatter = np.where(np.cos(phi2) < 0, np.sin(2 * np.pi * chatterHz * t), 0.)
    series = {'phi0': 50 * t, 'omega0': 50 + 0 * t, 'phi1': 50 * t, 'omega1': omegaSign * (50 + chatter),
              'alpha1': chatter, 'phi2': phi2, 'omega2': np.pi / 2 + 0 * t, 'alpha2': 100 * chatter,
              'deltaPhi': chatter, 'deltaS': 1e-6 * chatter, 'normalForce': 2e4 * np.abs(np.cos(phi2)),
              'S': np.sign(chatter) + (chatter == 0), 'sf': 1 + 0 * t, 'wormTorque': 0 * t, 'wheelTorque': 0 * t,
              'driveTorque': -80 * np.cos(phi2) ** 2 - 10, 'tangentialForce': 0 * t}
    # the phases a reel-changer simulation records (info['phases']): lifting while the load opposes the motion
    lifting = np.cos(phi2) > 0
    edges = np.concatenate([[0], np.flatnonzero(np.diff(lifting.astype(int))) + 1, [t.size - 1]])
    phases = [(t[a], t[b], 'lift' if lifting[a] else 'lower') for a, b in zip(edges[:-1], edges[1:])]
    return SimulationResult(time=t, series=series, J2=33., r2=0.106, info={'maxLoadTorque': 2060., 'phases': phases})


@pytest.mark.parametrize('kind', ['acceleration', 'speed', 'normalForce', 'driveTorque', 'zoom'])
def test_phase_names_lie_outside_the_data(kind):
    """No curve can run through 'lift' / 'lower': the names sit above the axes, where the data is clipped."""
    fig = PlotSimulation(_Record(), kind=kind, tZoom=(0.9, 1.4) if kind == 'zoom' else None)
    fig.draw_without_rendering()
    renderer = fig._get_renderer()
    names = [(ax, t) for ax in fig.axes for t in ax.texts if t.get_gid() == 'phase label']
    assert {t.get_text() for _, t in names} >= ({'lower'} if kind == 'zoom' else {'lift', 'lower'})
    for ax, text in names:
        box, frame = text.get_window_extent(renderer), ax.get_window_extent(renderer)
        assert box.y0 >= frame.y1 - 0.5, (kind, text.get_text())
        title = ax.title.get_window_extent(renderer)
        assert title.y0 >= box.y1 - 0.5 or not ax.get_title()


def test_zoom_starting_just_after_a_round_time_keeps_its_first_tick():
    """A zoom from 1.20015 s (the paper's 4.0 s at the simulated rotation period) shows the tick 1.2."""
    fig = PlotSimulation(_Record(), kind='zoom', tZoom=(1.20015, 1.30015))
    ax = fig.axes[0]
    lo, hi = ax.get_xlim()
    visible = [v for v in ax.get_xticks() if lo <= v <= hi]
    assert visible[0] == pytest.approx(1.2) and lo == pytest.approx(1.2)
    assert visible[-1] == pytest.approx(1.3)
    fig = PlotSimulation(_Record(), kind='zoom', tZoom=(1.205, 1.305))      # 5 % off a tick: not widened
    assert fig.axes[0].get_xlim() == pytest.approx((1.205, 1.305))


@pytest.mark.parametrize('omegaSign', [1., -1.])
def test_drive_torque_says_what_its_sign_means(omegaSign):
    result = _Record(omegaSign=omegaSign)
    fig = PlotSimulation(result, kind='driveTorque')
    legend = next(legend for legend in fig.legends if legend.get_gid() == 'torque sign')     # below the axes
    text = '\n'.join(t.get_text() for t in legend.get_texts())
    assert 'eq. 6' in text
    drives = '$M_{an}$ < 0 = the motor drives' if omegaSign > 0 else '$M_{an}$ > 0 = the motor drives'
    assert drives in text
    # the record's torque is negative throughout: with the worm turning forward, the motor drives also while
    # lowering (the self-locking remark); turning backward it would be the worm that drives
    assert ('self-locking' in text) == (omegaSign > 0)
    assert 'lifting: mean' in text and 'lowering: mean' in text
    assert TorqueSignNote(result).count('\n') == 1                 # without phases: no means


def test_dense_contact_sign_is_drawn_as_share_of_time_and_zoom():
    """P7's sign(S) over a whole run switches about a thousand times: a step line would be a solid block."""
    result = _Record(seconds=8., chatterHz=60.)
    sign = np.sign(result.series['S'])
    assert np.count_nonzero(np.diff(sign)) > DENSE_SWITCHES_PER_INCH * 8
    fig = PlotSimulation(result, kind='driveTorque')
    assert len(fig.axes) == 3
    share, zoom = fig.axes[1], fig.axes[2]
    fills = {c.get_gid(): c for c in share.collections if c.get_gid()}
    assert set(fills) == {'share S=-1', 'share S=+1'}
    top = fills['share S=+1'].get_paths()[0].vertices
    assert top[:, 1].max() <= 1. + 1e-12 and top[:, 1].min() >= 0.
    minus = fills['share S=-1'].get_paths()[0].vertices
    t = minus[:, 0]
    lowering = (t > 1.2) & (t < 2.8)                               # sin(2 pi 60 t): half the time below zero
    assert np.median(minus[lowering, 1][minus[lowering, 1] > 0]) == pytest.approx(0.5, abs=0.06)
    assert minus[(t > 3.2) & (t < 4.8), 1].max() == 0.             # lifting: S = +1 all the time
    line = next(l for l in zoom.lines if l.get_gid() == 'sign zoom')
    steps = np.count_nonzero(np.diff(line.get_ydata()))
    assert 5 <= steps <= 40                                        # readable steps
    width = np.diff(zoom.get_xlim())[0]
    assert width < 8. / 10


def test_sparse_contact_sign_keeps_its_step_line():
    fig = PlotSimulation(_Record(seconds=2., chatterHz=5.), kind='driveTorque')
    assert len(fig.axes) == 2 and fig.axes[1].lines[0].get_drawstyle() == 'steps-post'


# --- boxes and legends over no data, one entry per line, means per direction, one band per window, states ----------

def _Legends(fig):
    return list(fig.legends) + [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None]


def _LegendsOverData(fig):
    """(legend title or first label, axes label) of every legend or explanation box that overlaps an axes (or the
    figure's title)."""
    fig.draw_without_rendering()
    renderer = fig._get_renderer()
    hits = []
    frames = [(ax.get_ylabel(), ax.get_window_extent(renderer)) for ax in fig.axes]
    if fig._suptitle is not None:
        frames.append(('figure title', fig._suptitle.get_window_extent(renderer)))
    for legend in _Legends(fig):
        box = legend.get_window_extent(renderer)
        for name, frame in frames:
            overlap = min(box.x1, frame.x1) - max(box.x0, frame.x0), min(box.y1, frame.y1) - max(box.y0, frame.y0)
            if overlap[0] > 0.5 and overlap[1] > 0.5:
                hits.append((legend.get_title().get_text() or legend.get_texts()[0].get_text(), name))
    return hits


@pytest.mark.parametrize('kind', ['driveTorque', 'normalForce', 'overview', 'speed', 'zoom'])
def test_no_legend_or_explanation_box_lies_over_the_data(kind):
    fig = PlotSimulation(_Record(), kind=kind, tZoom=(0.9, 1.4) if kind == 'zoom' else None)
    assert _LegendsOverData(fig) == []
    for legend in _Legends(fig):                      # one entry per line
        labels = [t.get_text() for t in legend.get_texts()]
        assert len(labels) == len(set(labels)), labels


def test_the_legend_of_the_flanks_names_each_line_once():
    fig = PlotSimulation(_Record(), kind='normalForce')
    (legend,) = _Legends(fig)
    assert sorted(t.get_text() for t in legend.get_texts()) == sorted(
        [r'flank 1 ($\Delta s > 0$, worm drives)', r'flank 2 ($\Delta s < 0$)', f'mean over {MEAN_WINDOW:g} s'])


def _BothWays():
    """Lifting forward for 1 s (the motor drives: M_an = -50 N m), then lifting backward for 1 s (the motor turns the
    other way and still drives: M_an = +30 N m), then lowering backward (M_an = +10 N m)."""
    t = np.linspace(0., 3., 3001)
    omega = np.where(t < 1., 50., -50.)
    torque = np.where(t < 1., -50., np.where(t < 2., 30., 10.))
    series = {'omega1': omega, 'driveTorque': torque, 'S': np.ones_like(t), 'alpha2': 0 * t}
    phases = [(0., 1., 'lift'), (1., 2., 'lift'), (2., 3., 'lower')]
    return SimulationResult(time=t, series=series, J2=33., r2=0.106, info={'phases': phases}), phases


def test_phase_means_are_taken_per_direction():
    """A forward and a backward lift have drive torques of opposite sign: averaged together they would give a
    mean (-50 + 30) / 2 = -10 N m that neither lift has."""
    result, phases = _BothWays()
    means = {(kind, d): round(m, 6) for kind, d, m in PhaseMeans(result, phases)}
    assert means == {('lift', 1): -50., ('lift', -1): 30., ('lower', -1): 10.}
    note = TorqueSignNote(result, phases=phases)
    assert 'lifting forward: mean -50 N·m' in note and 'lifting backward: mean +30 N·m' in note
    assert 'lowering backward: mean +10 N·m (self-locking' in note       # turning backward, M_an > 0: the motor drives
    assert 'worm turning forward' in note and 'worm turning backward' in note
    one = TorqueSignNote(_Record(), phases=_Record().info['phases'])   # one direction: no direction named
    assert 'lifting: mean' in one and 'forward:' not in one.split('\n', 2)[2]


def test_adjoining_phases_of_one_kind_are_one_window():
    """The lift at the end of a rotation and the lift at the start of the next (6-8 s and 8-10 s of P7) are one."""
    phases = [(0., 2., 'lift'), (2., 6., 'lower'), (6., 8., 'lift'), (8., 10., 'lift')]
    assert MergePhases(phases) == [(0., 2., 'lift'), (2., 6., 'lower'), (6., 10., 'lift')]
    assert MergePhases([(0., 1., 'lift'), (1.5, 2., 'lift')]) == [(0., 1., 'lift'), (1.5, 2., 'lift')]
    record = _Record(seconds=2.)
    split = [(0., 0.5, 'lift'), (0.5, 1., 'lift'), (1., 2., 'lower')]
    fig = PlotSimulation(record, kind='acceleration', phases=split)
    ax = fig.axes[0]
    assert len([p for p in ax.patches if p.get_x() is not None]) == 2
    assert sorted(t.get_text() for t in ax.texts if t.get_gid() == 'phase label') == ['lift', 'lower']


def test_friction_state_is_drawn_within_its_range_one_value_per_step():
    """While stuck, s_f is the sticking force over mu |F_n|, which may pass 1 in the step before the flanks slide."""
    record = _Record(seconds=1.)
    sf = np.where(np.arange(record.time.size) % 50 == 0, 1.12, 0.3)
    record.series['sf'] = sf
    drawn = FrictionStateDrawn(record)
    assert drawn.min() >= -1. and drawn.max() <= 1. and drawn.max() == 1.
    fig = PlotSimulation(record, kind='speed')
    line = next(l for l in fig.axes[1].lines if l.get_gid() == 'sf')
    assert line.get_drawstyle() == 'steps-post' and line.get_ydata().size == record.time.size
    assert np.abs(line.get_ydata()).max() <= 1.
    assert 'time step of 1 ms' in fig.axes[1].get_title(loc='left')


def test_notes_use_the_users_words():
    assert 'frictionSpeed' not in S_SIGN_NOTE and 'N*m' not in TorqueSignNote(_Record(), phases=_Record().info['phases'])


def test_speed_chart_names_each_kind_of_point_once_beside_the_axes():
    p3 = {**GetPreset('reel-P3'), 'frictionLaw': 'stribeck', 'mu': 0.092, 'muStatic': 0.2, 'stribeckVelocity': 0.9}
    chart = SpeedStabilityChart(ResolveDrive(parameters=p3), np.geomspace(50, 1500, 8) * RPM)
    twice = dataclasses.replace(chart, ownPoints=chart.ownPoints * 2)       # e.g. a duty that lifts twice
    fig = PlotSpeedChart(twice).figure
    (legend,) = _Legends(fig)
    labels = [t.get_text() for t in legend.get_texts()]
    assert len(labels) == len(set(labels)) == 2 + 2 + 1             # two curves, two kinds of star, mu(v0)
    assert not any('N*m' in label for label in labels)
    assert _LegendsOverData(fig) == []
