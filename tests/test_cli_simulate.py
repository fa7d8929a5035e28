"""`exudyn-worm simulate`: JSON schema, the paper's chatter verdicts, files only where asked, clean errors."""
import json
import os

import pytest

from exudyn_worm.cli import Main
from exudyn_worm.commands.simulate import ParseWindows

WINDOW_KEYS = {'t0', 't1', 'maxAbsWheelAcceleration', 'maxNormalForce', 'dominantFrequencyHz',
               'fractionSNegative', 'minWormSpeed', 'chatter'}


def _Run(capsys, *argv):
    status = Main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def test_simulate_json_p1(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    status, out, err = _Run(capsys, 'simulate', '--preset', 'reel-P1', '--json')
    assert status == 0
    data = json.loads(out)                                    # exactly one JSON object on stdout
    assert set(data) == {'endTime', 'steps', 'solveSeconds', 'windows'}
    assert [set(w) for w in data['windows']] == [WINDOW_KEYS] * 3
    assert [w['chatter'] for w in data['windows']] == [False, True, False]   # paper section 3.2.2
    assert os.listdir(tmp_path) == []                         # nothing written unless asked


def test_simulate_writes_csv_and_plots_where_asked(capsys, tmp_path):
    csv, plots = tmp_path / 'p1.csv', tmp_path / 'figs'
    status, out, err = _Run(capsys, 'simulate', '--end-time', '3', '--windows', '0:2,2:3',
                            '--csv', str(csv), '--plot', str(plots))
    assert status == 0
    assert 'chatter' in out and csv.exists() and (plots / 'overview.png').exists()
    header = csv.read_text().splitlines()[0]
    assert header.startswith('time [s],') and 'normalForce [N]' in header


@pytest.mark.parametrize('argv, fragment', [
    (['--windows', '0:2,2:x'], '--windows'),
    (['--windows', '3:2'], '0 <= T0 < T1'),
    (['--end-time', '2', '--windows', '0:3'], 'after --end-time'),
    (['--set', 'loadMass=-3'], "'mass' must be >= 0 kg"),
    (['--set', 'motorSpeed=0'], "'motorSpeed' must be > 0 rad/s"),
    (['--step-size', '-1'], "'stepSize' must be > 0 s"),
    (['--set', 'backlash=2 kg'], 'backlash'),
])
def test_simulate_bad_input(capsys, argv, fragment):
    status, out, err = _Run(capsys, 'simulate', *argv)
    assert status == 2
    assert err.count('\n') == 1 and fragment in err and 'Traceback' not in err


def test_parse_windows():
    assert ParseWindows('0:2,2:6,6:8') == [(0., 2.), (2., 6.), (6., 8.)]
