"""``exudyn-worm sweep``: options, errors, JSON, table, resume, plots."""
import json
import math
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from exudyn_worm.cli.main import Main
from exudyn_worm.drive.presets import GetPreset
from exudyn_worm.analysis.studies.studyfiles import ReadResults
from exudyn_worm.analysis.simulation.reelchanger import DefaultPhases
from exudyn_worm.analysis.studies.studypoint import DecidingWindow
from exudyn_worm.drive.config import ResolveParameters
from exudyn_worm.drive.wholedrive import ResolveDrive

SHORT = ['--windows', '0:0.5,0.5:1', '--end-time', '1', '--quiet']


def _Error(capsys, argv, text):
    assert Main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith('exudyn-worm: error:') and text in err[0], err


@pytest.mark.parametrize('argv, text', [
    (['sweep'], '--vary'),
    (['sweep', '--vary', 'J1=0.1:0.2'], 'START:STOP:COUNT'),
    (['sweep', '--vary', 'nope=1,2'], "unknown parameter 'nope'"),
    (['sweep', '--vary', 'J1=0.1,0.2', '--vary', 'kT=1,2,3', '--zip'], 'equal numbers'),
    (['sweep', '--vary', 'J1=0.1', '--shard', '2/2'], 'i/N'),
    (['sweep', '--vary', 'J1=0.1', '--workers', '0'], '--workers'),
    (['sweep', '--vary', 'J1=0.1', '--engine', 'dask'], 'invalid choice'),
    (['sweep', '--vary', 'J1=0.1', '--windows', '0:9', '--end-time', '8'], 'after --end-time'),
    (['sweep', '--vary', 'J1=0.1', '--plot', 'x.txt'], '--plot'),
    (['sweep', '--vary', 'J1=0.1', '--plot', 'x.png', '--metric', 'w7.nothing'], '--metric'),
    (['sweep', '--vary', 'J1=0.1', '--set', 'J2=1 m'], "'J2'"),
    (['sweep', '--vary', 'J1=0.1,0.2', '--set', 'J1=0.3'], "'J1' is both set (--set) and varied (--vary)"),
    (['sweep', '--vary', 'J1=0.1', '--metric', 'w0.maxNormalForce'], '--metric w0.maxNormalForce only applies with --plot'),
    (['sweep', '--vary', 'J1=0.1', '--overwrite'], '--overwrite only applies with --output'),
    (['sweep', '--preset', 'chart', '--vary', 'J1=0.001,0.002'], 'sweep: the reel-changer simulation needs'),
    (['sweep', '--vary', 'J1=0.1', '--output', 'nodir/a.csv'], '--output nodir/a.csv: the folder nodir does not exist'),
])
@pytest.mark.messages
def test_bad_input(capsys, argv, text):
    _Error(capsys, argv, text)


@pytest.mark.parametrize('argv, texts', [
    (['--vary', 'J9=1:2:2'], ["the drive-side chain must be J4, J5, ... without gaps", "missing 'J4'",
                              'every run would fail (varied: J9)']),
    (['--vary', 'J1=nan:0.3:3'], ["ParseVariation: 'J1=nan:0.3:3': START: 'J1' must be finite, got 'nan'"]),
    (['--vary', 'z1=1,1.5'], ["'z1' must be a whole number >= 1 (a count of teeth or starts), got 1.5"]),
    (['--vary', 'J1=0.01:0.4:10000', '--vary', 'kT=700:14000:10000'],
     ['the study has 100,000,000 runs (J1: 10,000 x kT: 10,000), above the limit of 100,000 runs per call',
      'split it into at least 1,000 shards', '--shard i/1000 for i = 0 ... 999', 'raise --max-runs']),
    (['--vary', 'J1=0.01:0.4:100000000'], ['100,000,000 values are above the limit of 1,000,000 values']),
    (['--vary', 'J1=0.1:0.2:10', '--max-runs', '4', '--shard', '0/2'],
     ["shard 0/2 has 5 of the study's 10 runs (J1: 10), above the limit of 4 runs", 'at least 3 shards']),
])
@pytest.mark.messages
def test_refused_before_any_run(capsys, tmp_path, argv, texts):
    """A study that would fail every run, or is too large for one call, is refused at once: one line, exit 2,
    nothing written (the 1e8-point grid grew to 11.5 GB before a MemoryError)."""
    assert Main(['sweep', *argv, '--output', str(tmp_path / 's.csv')] + SHORT) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith('exudyn-worm: error:'), err
    assert all(t in err[0] for t in texts), err
    assert list(tmp_path.iterdir()) == []


def test_output_checked_before_computing(capsys, tmp_path):
    _Error(capsys, ['sweep', '--vary', 'J1=0.1', '--output', str(tmp_path / 'no' / 'a.csv')] + SHORT, 'does not exist')
    (tmp_path / 'other.csv').write_text('x\n')
    _Error(capsys, ['sweep', '--vary', 'J1=0.1', '--output', str(tmp_path / 'other.csv')] + SHORT, 'sidecar')


def test_json_and_files(capsys, tmp_path):
    out = tmp_path / 'runs.csv'
    argv = ['sweep', '--vary', 'J1=0.05,0.1', '--vary', 'loadMass=175,1e20', '--workers', '2',
            '--output', str(out), '--json'] + SHORT
    assert Main(argv) == 1                          # two runs failed: exit status 1, as documented
    captured = capsys.readouterr()
    data = json.loads(captured.out)
    assert set(data) == {'runs', 'agreement'} and data['agreement'] is None
    assert [r['parameters'] for r in data['runs']] == [{'J1': 0.05, 'loadMass': 175.}, {'J1': 0.05, 'loadMass': 1e20},
                                                        {'J1': 0.1, 'loadMass': 175.}, {'J1': 0.1, 'loadMass': 1e20}]
    assert [r['status'] for r in data['runs']] == ['ok', 'failed', 'ok', 'failed']
    assert data['runs'][1]['error'] and data['runs'][1]['windows'] == []
    assert [len(r['windows']) for r in data['runs']] == [2, 0, 2, 0]
    assert set(data['runs'][0]['windows'][0]) >= {'t0', 't1', 'maxAbsWheelAcceleration', 'maxNormalForce', 'chatter'}
    assert isinstance(data['runs'][0]['analyticStable'], bool)
    assert ReadResults(out).ToDict() == data
    assert 'wrote' in captured.err
    # the same command again: everything is resumed from the file (nothing recomputed), same JSON
    table = out.read_text()
    assert Main(argv) == 1
    assert json.loads(capsys.readouterr().out) == data and out.read_text() == table
    assert Main(argv[:-1]) == 1                     # without --quiet: says that it resumes
    assert 'resuming: 4 of 4' in capsys.readouterr().err


def test_table_agreement_and_plots(capsys, tmp_path):
    # one rotation, so the lowering window exists: the agreement is judged
    assert Main(['sweep', '--vary', 'J1=0.1', '--vary', 'kT=700,7000', '--quiet', '--workers', '2',
                 '--plot', str(tmp_path / 'map.png')]) == 0
    text = capsys.readouterr().out
    assert 'agreement of chatter while lowering' in text and '2 runs: 2 ok, 0 failed' in text
    assert (tmp_path / 'map.png').stat().st_size > 1000
    assert Main(['sweep', '--vary', 'backlash=0,0.5mm', '--plot', str(tmp_path / 'b.png'), '--metric',
                 'w0.maxNormalForce'] + SHORT) == 0
    assert (tmp_path / 'b.png').stat().st_size > 1000


def test_sigterm_saves_and_says_how_to_resume(tmp_path):
    # a job scheduler's time limit (SIGTERM) ends the study like Ctrl-C: exit 143 (128 + 15), finished runs kept,
    # hint on stderr, no lock or temporary file left
    out = tmp_path / 'runs.csv'
    argv = [sys.executable, '-m', 'exudyn_worm', 'sweep', '--vary', 'J1=0.02:0.3:12:log', '--workers', '1',
            '--output', str(out)] + SHORT
    proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=tmp_path)
    deadline = time.time() + 240
    while time.time() < deadline and proc.poll() is None and not (out.exists() and out.read_text().count('\n') >= 2):
        time.sleep(0.05)
    proc.send_signal(signal.SIGTERM)
    stdout, stderr = proc.communicate(timeout=240)
    assert proc.returncode == 143, stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ['runs.csv', 'runs.study.json']
    assert 'interrupted (SIGTERM)' in stderr and 'run the same command again to resume' in stderr and stdout == ''
    assert 'Traceback' not in stderr
    done = out.read_text().count('\n') - 1
    assert 1 <= done < 12
    assert Main(argv[3:]) == 0                                   # the same command finishes the study
    assert ReadResults(out).ToDict()['runs'][-1]['run'] == 11 and len(ReadResults(out).rows) == 12


def test_default_windows_follow_a_short_end_time(capsys, tmp_path):
    """Half a rotation (P1: 4 of 8 s): lift 0-2 s and the lowering 2-4 s are judged, the missing third window's
    columns stay empty; before, every run failed on a window beyond the end."""
    out = tmp_path / 'half.csv'
    assert Main(['sweep', '--vary', 'backlash=0,0.5mm', '--end-time', '4', '--quiet', '--output', str(out),
                 '--json']) == 0
    data = json.loads(capsys.readouterr().out)
    assert [r['status'] for r in data['runs']] == ['ok', 'ok']
    # a quarter rotation of the wheel: T/4 = (pi/2) u / motorSpeed with u = r2 / (r1 tan gamma), eq. (3)
    p1 = GetPreset('reel-P1')
    quarter = math.pi / 2 * p1['r2'] / (p1['r1'] * math.tan(p1['gamma'])) / p1['motorSpeed']
    windows = [[(w['t0'], w['t1']) for w in r['windows']] for r in data['runs']]
    assert windows == [[(0., pytest.approx(quarter, rel=1e-12)), (pytest.approx(quarter, rel=1e-12), 4.)]] * 2
    # P1 chatters while lowering; with 0.5 mm backlash the chatter settles from its first overshoot within the 2 s
    # left of the lowering: its envelope falls at 0.39 1/s over 3-4 s, slower than the window (undecided; over the
    # whole lowering, 2-6 s, it is steady at the saturated amplitude: chatter)
    assert [r['loweringChatter'] for r in data['runs']] == [True, 'undecided']


def test_failed_runs_are_reported_and_any_failed_is_exit_1(capsys):
    assert Main(['sweep', '--vary', 'J1=0.1', '--vary', 'loadMass=175,1e20'] + SHORT) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert err[-1].startswith('exudyn-worm: warning: 1 of 2 runs failed') and "'error' column" in err[-1]
    assert Main(['sweep', '--vary', 'loadMass=1e20'] + SHORT) == 1
    assert 'warning: 1 of 1 runs failed' in capsys.readouterr().err


def test_default_metric_belongs_to_the_deciding_phase():
    """The default --metric window is the first of the phase that decides the linear verdict: the reel changer at
    P1 chatters while lowering (section 3.2), its window 1; the hoist's lifting point decides (its file), a lifting
    window."""
    assert DecidingWindow(ResolveDrive(parameters=GetPreset('reel-P1'))) == 1
    hoist = ResolveParameters(config=Path(__file__).resolve().parents[1] / 'examples' / 'drives' / 'hoist.toml')
    i = DecidingWindow(ResolveDrive(parameters=hoist))
    phases = DefaultPhases(ResolveDrive(parameters=hoist), None, minLength=1e-3)
    assert phases[i][2] == 'lift' and all(ph != 'lift' for _, _, ph in phases[:i])
