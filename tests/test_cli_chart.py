"""`exudyn-worm chart`: JSON shape and numbers, the chart preset without damping, points, plot file checked
before computing, one-line errors with exit status 2."""
import json
from pathlib import Path

import pytest
from numpy.testing import assert_allclose

import exudyn_worm.analysis.charts.stabilitychart as charts
from exudyn_worm.analysis.charts.stabilitychart import ComputeStabilityChart
from exudyn_worm.cli.main import Main
from exudyn_worm.drive.presets import GearFromParameters, GetPreset

ENTRY_KEYS = {'DV', 'DTV', 'unstableXRange', 'unstableYRange', 'unstableFraction'}


def _Run(capsys, *argv):
    status = Main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


pytestmark = pytest.mark.usefixtures('emptyWorkingDirectory')   # nothing written to the cwd


def test_json_of_the_paper_charts(capsys):
    status, out, err = _Run(capsys, 'chart', '--preset', 'chart', '--DV', '0.014', '--DTV', '1', '5', '25',
                            '--resolution', '120', '--json')
    assert status == 0 and err == ''
    data = json.loads(out)
    assert set(data) == {'charts'}
    assert [c['DTV'] for c in data['charts']] == [1., 5., 25.]
    gear = GearFromParameters(GetPreset('chart'), meshDamping=False)
    for entry in data['charts']:
        assert ENTRY_KEYS <= set(entry) and entry['DV'] == 0.014
        chart = ComputeStabilityChart(gear, 0.1, 0.014, entry['DTV'], resolution=120)
        assert_allclose(entry['unstableXRange'], chart.unstableXRange, rtol=1e-12)
        assert_allclose(entry['unstableYRange'], chart.unstableYRange, rtol=1e-12)
        assert entry['unstableFraction'] == pytest.approx(chart.unstableFraction)


def test_stable_charts_give_null_ranges(capsys):
    status, out, _ = _Run(capsys, 'chart', '--preset', 'chart', '--DV', '0.014', '--DTV', '1', '--S', '1',
                          '--resolution', '60', '--json')
    entry = json.loads(out)['charts'][0]
    assert status == 0 and entry['S'] == 1
    assert entry['unstableXRange'] is None and entry['unstableYRange'] is None and entry['unstableFraction'] == 0.


def test_chart_preset_needs_no_damping_and_takes_its_DV(capsys):
    # preset 'chart' has neither J1, kT nor shaft damping; its dV = 1250 N*s/m is D_V = 0.028 (set (25))
    status, out, err = _Run(capsys, 'chart', '--preset', 'chart', '--DTV', '5', '--resolution', '40', '--json')
    assert status == 0, err
    assert json.loads(out)['charts'][0]['DV'] == pytest.approx(0.028, abs=5e-4)


def test_points_and_table(capsys):
    status, out, err = _Run(capsys, 'chart', '--preset', 'chart', '--DV', '0.014', '--DTV', '1',
                            '--resolution', '60', '--points', 'P1', 'reel-P2', '--json')
    data = json.loads(out)
    assert status == 0 and set(data['points']) == {'P1', 'P2'}
    # section 3.2: P1 chatters, P2 does not (both D_TV = 1, D_V = 0.014)
    assert data['charts'][0]['pointsUnstable'] == {'P1': True, 'P2': False}
    status, out, err = _Run(capsys, 'chart', '--preset', 'chart', '--DV', '0.014', '--resolution', '40',
                            '--points', 'P1')
    assert status == 0 and 'unstable kT/(kV r1^2)' in out and len(out.splitlines()) == 6


def test_output_png(capsys, tmp_path):
    target = tmp_path / 'chart.png'
    status, out, err = _Run(capsys, 'chart', '--preset', 'chart', '--DV', '0.014', '--resolution', '40',
                            '--points', 'P1', '--output', str(target))
    assert status == 0 and target.read_bytes()[:4] == b'\x89PNG' and 'wrote' in err


@pytest.mark.messages
@pytest.mark.parametrize('argv, message', [
    (['--DV', '-1'], "'DV' must be >= 0, got -1"),
    (['--DTV', '1', 'nan'], "'DTV' must be finite"),
    (['--x-range', '1', '0.1'], "'xRange' must have min < max"),
    (['--y-range', '0', '1'], "'yRange[0]' must be > 0, got 0"),
    (['--resolution', '1'], "'resolution' must be in [2, 20000]"),
    (['--points', 'P9'], "--points: 'P9' is not a drive to mark; expected one of: reel-P1"),
    (['--points', 'chart'], "--points: 'chart' is not a drive to mark ('chart' is the gear of the chart"),
    (['--S', '0'], "argument --S: invalid choice"),
    (['--output', 'chart.txt'], "--output: expected a file ending in .png, .pdf, .svg, got 'chart.txt'"),
    (['--set', 'J2=-1'], "'J2' must be > 0"),
    (['--DTV'], "argument --DTV: expected at least one argument"),
])
def test_bad_input_one_line_exit_2(capsys, argv, message):
    status, out, err = _Run(capsys, 'chart', '--preset', 'chart', '--resolution', '20', *argv)
    assert status == 2 and out == ''
    assert err.startswith('exudyn-worm: error: ') and err.count('\n') == 1 and message in err


@pytest.mark.messages
def test_output_checked_before_computing(capsys, tmp_path, monkeypatch):
    monkeypatch.setattr(charts, 'ComputeStabilityChart', lambda *a, **k: pytest.fail('computed'))
    (tmp_path / 'adir.png').mkdir()
    for path, message in ((tmp_path / 'adir.png', 'is a folder'),
                          (tmp_path / 'nofolder' / 'x.png', 'does not exist'),
                          (tmp_path / 'x.txt', 'expected a file ending in')):
        status, _, err = _Run(capsys, 'chart', '--preset', 'chart', '--output', str(path))
        assert status == 2 and message in err


@pytest.mark.parametrize('dV, DV', [(625., 0.014), (2500., 0.056)])
def test_mesh_damping_given_as_dV(capsys, dV, DV):
    """Section 2.3: D_V = 0.014 is d_V = 625 N*s/m and D_V = 0.056 is 2500 N*s/m (printed digits)."""
    status, out, err = _Run(capsys, 'chart', '--preset', 'chart', '--set', f'dV={dV}', '--DTV', '1',
                            '--resolution', '20', '--json')
    assert status == 0, err
    assert json.loads(out)['charts'][0]['DV'] == pytest.approx(DV, abs=5e-4)


def test_drive_side_chain_is_noted_not_used(capsys):
    status, out, err = _Run(capsys, 'chart', '--preset', 'chart', '--DV', '0.014', '--DTV', '1', '--resolution', '30',
                            '--set', 'J4=0.5', '--set', 'k4=1e4', '--set', 'd4=1', '--json')
    plain = _Run(capsys, 'chart', '--preset', 'chart', '--DV', '0.014', '--DTV', '1', '--resolution', '30', '--json')
    assert status == 0 and 'drive-side chain' in err and 'not in it' in err
    assert json.loads(out) == json.loads(plain[1])


def test_own_drive_is_marked_with_its_verdict(capsys):
    """A whole drive from --config is marked at its chart coordinates: reel-P1 with the Figure 19 chain lies at P1's
    x = kT/(kV r1^2) = 7000 / (2e8 * 0.01805^2) and y = J1/J2 = 0.1/33 (set (28)), in the unstable region of
    D_TV = 1 (section 3.2: P1 chatters)."""
    config = str(Path(__file__).resolve().parents[1] / 'examples' / 'drives' / 'figure19.toml')
    status, out, err = _Run(capsys, 'chart', '--config', config, '--DTV', '1', '--resolution', '60', '--json')
    assert status == 0, err
    data = json.loads(out)
    point = data['points']['figure19']
    assert point['x'] == pytest.approx(7000 / (2e8 * 0.01805 ** 2), rel=1e-12)
    assert point['y'] == pytest.approx(0.1 / 33, rel=1e-12)
    assert data['charts'][0]['pointsUnstable'] == {'figure19': True}
    assert data['drive']['stable'] is False and data['drive']['components'] == ['a drive-side chain (J4, ...)']
    assert 'drive-side chain' in err and 'not in it' in err
    status, out, err = _Run(capsys, 'chart', '--config', config, '--DTV', '1', '--resolution', '40', '--points', 'P2')
    assert status == 0 and 'this drive (figure19) is marked at x = 0.1074' in out and 'UNSTABLE' in out
