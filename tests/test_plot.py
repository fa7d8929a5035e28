"""exudyn_worm.plotting.plot: every kind draws a Figure without a display; bad arguments raise named errors."""
import subprocess
import sys

import numpy as np
import pytest

pytest.importorskip('matplotlib')

from matplotlib.figure import Figure                                  # noqa: E402

from exudyn_worm.plotting import plot                                          # noqa: E402
from exudyn_worm.items.results import SimulationResult                      # noqa: E402


@pytest.fixture(scope='module')
def result():
    """A synthetic reel-changer-like record (no simulation needed): 2 s, wheel turning a quarter turn per s."""
    t = np.linspace(0., 2., 2001)
    phi2 = 0.25 * np.pi * 2 * t
    chatter = np.where(np.cos(phi2) < 0, np.sin(2 * np.pi * 40 * t), 0.)
    series = {'phi0': 50 * t, 'omega0': 50 + 0 * t, 'phi1': 50 * t, 'omega1': 50 + chatter,
              'alpha1': chatter, 'phi2': phi2, 'omega2': np.pi / 2 + 0 * t, 'alpha2': 100 * chatter,
              'deltaPhi': chatter, 'deltaS': 1e-6 * chatter, 'normalForce': 2e4 * np.cos(phi2) + 3e4 * chatter,
              'S': np.sign(chatter) + (chatter == 0), 'sf': 1 + 0 * t, 'wormTorque': 0 * t, 'wheelTorque': 0 * t,
              'driveTorque': -80 * np.cos(phi2), 'tangentialForce': 0 * t,
              # the bearing loads of a run of the 3D model (the 'bearingLoads' kind)
              'wormAxialLoad': 2e4 * np.cos(phi2), 'wormRadialLoad': 8e3 + 3e3 * chatter,
              'wheelAxialLoad': 5e3 * np.cos(phi2), 'wheelRadialLoad': 2e4 + 3e3 * chatter}
    return SimulationResult(time=t, series=series, J2=33., r2=0.106, info={'maxLoadTorque': 2060.})


@pytest.mark.parametrize('kind', plot.PLOT_KINDS)
def test_every_kind_returns_a_figure(result, kind, tmp_path):
    fig = plot.PlotSimulation(result, kind=kind, title=f'Fig. 0: {kind}')
    assert isinstance(fig, Figure)
    path = plot.SaveFigure(fig, tmp_path / 'sub' / f'{kind}.png')
    assert path.read_bytes()[:4] == b'\x89PNG'


def test_result_plot_method_and_zoom(result):
    fig = result.plot('zoom', tZoom=(1.2, 1.3))
    ax = fig.axes[0]
    assert ax.get_xlim() == pytest.approx((1.2, 1.3))
    assert 'rad/s²' in ax.get_ylabel()


def test_comparison_stacks_one_panel_per_result(result):
    fig = plot.PlotComparison({'a': result, 'b': result, 'c': result}, quantity='normalForce', title='Fig. 12')
    panels = [ax for ax in fig.axes if ax.get_title(loc='left')]
    assert [ax.get_title(loc='left') for ax in panels] == ['a', 'b', 'c']


@pytest.mark.messages
@pytest.mark.parametrize('call, error, fragment', [
    (lambda r: plot.PlotSimulation(r, kind='spectrum'), ValueError, "'kind'"),
    (lambda r: plot.PlotSimulation(r, kind='zoom', tZoom=(1.3, 1.2)), ValueError, 't0 < t1'),
    (lambda r: plot.PlotSimulation(r, kind='zoom', tZoom=(5., 6.)), ValueError, 'tZoom'),
    (lambda r: plot.PlotSimulation(r, kind='zoom', tZoom=3.), TypeError, 'tZoom'),
    (lambda r: plot.PlotSimulation({'time': 0}), TypeError, 'SimulationResult'),
    (lambda r: plot.PlotComparison({}), ValueError, 'empty'),
    (lambda r: plot.PlotComparison({'a': r}, quantity='nothing'), ValueError, 'nothing'),
    (lambda r: plot.SaveFigure(None, 'x.png'), TypeError, 'Figure'),
])
def test_bad_arguments_raise_named_errors(result, call, error, fragment):
    with pytest.raises(error, match=fragment):
        call(result)


def test_package_import_does_not_import_matplotlib():
    code = "import sys, exudyn_worm, exudyn_worm.items.results, exudyn_worm.plotting.plot; print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == 'False'
