"""`exudyn-worm simulate`: JSON schema, the paper's chatter verdicts, files only where asked, clean errors."""
import json
import os

import pytest

import exudyn_worm.analysis.simulation.reelchanger as reelchanger
from exudyn_worm import GetPreset, SimulateReelChanger
from exudyn_worm.cli.main import Main
from exudyn_worm.cli.simulate import ParseWindows
from exudyn_worm.analysis.simulation.reelchanger import DefaultWindows, RotationPeriod
from exudyn_worm.items.solve import SolverDivergedError
from exudyn_worm.drive.wholedrive import ResolveDrive

WINDOW_KEYS = {'t0', 't1', 'maxAbsWheelAcceleration', 'maxNormalForce', 'dominantFrequencyHz',
               'fractionSNegative', 'minWormSpeed', 'chatter', 'chatterState', 'chatterAmplitude', 'envelopeRate'}


def _Run(capsys, *argv):
    status = Main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def test_simulate_json_p1(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    status, out, err = _Run(capsys, 'simulate', '--preset', 'reel-P1', '--json')
    assert status == 0
    data = json.loads(out)                                    # exactly one JSON object on stdout
    assert set(data) == {'source', 'endTime', 'stepSize', 'steps', 'solveSeconds', 'stepCheck', 'windows'}
    assert data['source'] == {'preset': 'reel-P1', 'presetFrom': '--preset', 'config': None, 'overrides': []}
    # P1's S = +1 mode has |Re lambda|/|lambda| = 0.011 < SMALL_MARGIN, but no window's verdict is close (chatter
    # measures 0.01, 3.3, 0.002 of the threshold): not checked at half the step by default
    assert not data['stepCheck']['checked'] and data['stepCheck']['reason'] == 'clearVerdicts'
    assert data['stepCheck']['closeWindows'] == []
    assert [set(w) for w in data['windows']] == [WINDOW_KEYS | {'phase'}] * 3
    assert [w['phase'] for w in data['windows']] == ['lift', 'lower', 'lift']
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


# bad input: (argument list, fragment of the one-line message); '{tmp}' is the test's tmp_path
BAD_INPUT = [
    (['--preset', 'chart', '--set', 'J1=0.001', '--set', 'kT=10', '--set', 'DTV=1'],
     'simulate: the reel-changer simulation needs loadMass, leverArm, motorSpeed; missing loadMass'),
    (['--windows', '0:2,2:x'], '--windows'),
    (['--windows', '3:2'], '0 <= T0 < T1'),
    (['--windows', ''], "--windows: expected T0:T1"),
    (['--windows', '0:1e-4'], 'shorter than two steps'),
    (['--end-time', '2', '--windows', '0:3'], 'after --end-time'),
    (['--set', 'loadMass=-3'], "ParseSetOption: 'loadMass=-3': 'loadMass' must be >= 0 kg"),
    (['--set', 'motorSpeed=0'], "ParseSetOption: 'motorSpeed=0': 'motorSpeed' must be > 0 rad/s"),
    (['--set', 'kT=-5'], "ParseSetOption: 'kT=-5': 'kT' must be > 0 N*m/rad, got -5"),
    (['--set', 'J2=0'], "ParseSetOption: 'J2=0': 'J2' must be > 0 kg*m^2, got 0"),
    (['--set', 'DTV=-1'], "ParseSetOption: 'DTV=-1': 'DTV' must be >= 0, got -1"),
    (['--set', 'kT=1e300'], "out of range"),
    (['--set', 'J1=1e-300'], "out of range"),
    (['--set', 'backlash=0.5'], "'backlash' is a length and needs its unit, e.g. \"18.05 mm\""),
    (['--set', 'backlash=2 kg'], 'backlash'),
    (['--step-size', '-1'], "argument --step-size: must be > 0 s, got -1 s"),
    (['--step-size', '-1e-3'], "argument --step-size: must be > 0 s, got -1e-3 s"),
    (['--step-size', '1e-300'], "Raise --max-steps to run it anyway"),
    (['--end-time', '1e7'], "would take about"),
    (['--end-time', '1e4'], 'solver steps, more than the limit --max-steps = 1e+06'),
    (['--end-time', '0.1', '--max-steps', '10'], "more than the limit --max-steps = 10"),
    (['--max-steps', '1.5'], "argument --max-steps: expected an integer"),
    (['--csv', '/nonexistent/dir/x.csv'], 'the folder /nonexistent/dir does not exist'),
    (['--csv', 'newdir/x.csv'], 'the folder newdir does not exist'),
    (['--csv', '.'], '--csv .: is a folder'),
    (['--csv', ''], "--csv: expected a file name"),
    (['--csv', '{tmp}/afile/x.csv'], 'is not a folder'),
    (['--plot', '{tmp}/afile'], 'is a file, expected a folder'),
    (['--plot', 'newdir/figs'], 'the folder newdir does not exist'),
    (['--set', 'kT=1e16', '--end-time', '0.01'], 'at the recommended step size 7.76'),
    (['--set', 'kT=1e16', '--end-time', '0.01', '--step-size', '1e-4'], 'simulate --step-size'),   # stepsize.py
]


@pytest.mark.messages
@pytest.mark.parametrize('argv, fragment', BAD_INPUT, ids=[' '.join(a) for a, _ in BAD_INPUT])
def test_simulate_bad_input(capsys, tmp_path, monkeypatch, argv, fragment):
    """One line on stderr, exit 2, no traceback, nothing written (checked before anything is computed)."""
    work = tmp_path / 'cwd'
    work.mkdir()
    (tmp_path / 'afile').write_text('keep')
    monkeypatch.chdir(work)
    status, out, err = _Run(capsys, 'simulate', '--quiet', *[a.replace('{tmp}', str(tmp_path)) for a in argv])
    assert status == 2
    assert err.count('\n') == 1 and err.startswith('exudyn-worm: error: ') and fragment in err, err
    assert 'Traceback' not in err and out == ''
    assert os.listdir(work) == [] and sorted(os.listdir(tmp_path)) == ['afile', 'cwd']
    assert (tmp_path / 'afile').read_text() == 'keep'


@pytest.mark.messages
def test_simulate_divergence_is_one_line(capsys, monkeypatch):

    def Fail(mbs, ss, *args, **kwargs):
        raise SolverDivergedError('the Exudyn solver failed at t = 0.25 s of 1 s (step size 0.0005 s)', 0.25, 1., 5e-4)
    monkeypatch.setattr(reelchanger, 'SolveDynamicInChunks', Fail)
    status, out, err = _Run(capsys, 'simulate', '--end-time', '1')
    assert status == 2 and out == '' and err.count('\n') == 1
    assert err.startswith('exudyn-worm: error: simulation failed: the Exudyn solver failed at t = 0.25 s of 1 s')
    assert 'likely cause' in err


def test_output_rule_is_the_same_for_csv_and_plot(capsys, tmp_path):
    """The output you name is created (file or folder); the folder holding it must exist."""
    status, out, err = _Run(capsys, 'simulate', '--quiet', '--end-time', '0.5', '--csv', str(tmp_path / 'r.csv'),
                            '--plot', str(tmp_path / 'figs'))
    assert status == 0 and (tmp_path / 'r.csv').is_file() and (tmp_path / 'figs' / 'speed.png').is_file()


def test_end_time_below_one_rotation_and_default_windows(capsys):
    status, out, err = _Run(capsys, 'simulate', '--quiet', '--end-time', '1', '--json')
    assert status == 0
    assert [(w['t0'], w['t1']) for w in json.loads(out)['windows']] == [(0., 1.)]


def test_default_windows_follow_the_end_time():
    p = GetPreset('reel-P1')
    T = RotationPeriod(ResolveDrive(parameters=p))
    assert DefaultWindows(ResolveDrive(parameters=p)) == [(0., T / 4), (T / 4, 3 * T / 4), (3 * T / 4, T)]
    w = DefaultWindows(ResolveDrive(parameters=p), 1.5 * T)
    assert w[3:] == [(T, 1.25 * T), (1.25 * T, 1.5 * T)] and len(w) == 5
    assert DefaultWindows(ResolveDrive(parameters=p), 0.3 * T) == [(0., T / 4), (T / 4, 0.3 * T)]
    assert DefaultWindows(ResolveDrive(parameters=p), T / 4 + 1e-4, minLength=1e-3) == [(0., T / 4)]


def test_run_size_limit_api():
    with pytest.raises(ValueError, match=r"SimulateReelChanger: endTime 10 s at stepSize 0.0005 s needs 2e\+04 "
                                         r"solver steps, more than the limit maxSteps = 1000"):
        SimulateReelChanger(ResolveDrive(parameters=GetPreset('reel-P1')), endTime=10., stepSize=5e-4, maxSteps=1000)


def test_simulate_states_its_source(capsys, tmp_path):
    config = tmp_path / 'c.toml'
    config.write_text('preset = "reel-P2"\n')
    status, out, err = _Run(capsys, 'simulate', '--quiet', '--end-time', '0.2', '--config', str(config),
                            '--set', 'J1=0.25')
    assert status == 0 and out.splitlines()[0] == (f'exudyn-worm simulate: preset reel-P2 (from the config), '
                                                   f'config {config}, --set J1=0.25')
    status, out, err = _Run(capsys, 'simulate', '--quiet', '--end-time', '0.2', '--set', 'J1=0.25', '--json')
    assert json.loads(out)['source'] == {'preset': 'reel-P1', 'presetFrom': 'default', 'config': None,
                                         'overrides': ['J1=0.25']}


def test_parse_windows():
    assert ParseWindows('0:2,2:6,6:8') == [(0., 2.), (2., 6.), (6., 8.)]
