"""The chatter map of `exudyn-worm sweep --plot` has the stability charts' axes (a stiffness
across, an inertia up), whatever order the keys were varied in."""
import pytest

from exudyn_worm.cli.main import Main
from exudyn_worm.plotting.plot_study import ChartAxes
from exudyn_worm.plotting import plot

pytest.importorskip('matplotlib')


@pytest.mark.parametrize('keys, expected', [
    (('J1', 'kT'), ('kT', 'J1')),
    (('kT', 'J1'), ('kT', 'J1')),
    (('J2', 'kV'), ('kV', 'J2')),
    (('J1', 'backlash'), ('J1', 'backlash')),          # no stiffness: as given
    (('mu', 'kT'), ('mu', 'kT')),
])
def test_chart_axes(keys, expected):
    assert ChartAxes(*keys) == expected


@pytest.mark.parametrize('order', [('J1=0.1,0.2', 'kT=3000,7000'), ('kT=3000,7000', 'J1=0.1,0.2')])
def test_sweep_map_puts_kT_across_and_J1_up(order, monkeypatch, tmp_path, capsys):
    drawn = []
    monkeypatch.setattr(plot, 'SaveFigure', lambda fig, path, dpi=150: (drawn.append(fig), open(path, 'wb').close()))
    argv = ['sweep', '--vary', order[0], '--vary', order[1], '--windows', '0:0.5', '--end-time', '0.5', '--quiet',
            '--workers', '1', '--plot', str(tmp_path / 'map.png')]
    assert Main(argv) == 0, capsys.readouterr().err
    ax = drawn[0].axes[0]
    assert ax.get_xlabel().startswith('kT') and ax.get_ylabel().startswith('J1')
    lo, hi = ax.get_xlim()
    assert lo < 3000. and hi > 7000.
