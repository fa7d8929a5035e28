"""Parameter studies (exudyn_worm.analysis.studies.study): parsing, points, shards, failed runs, results files, resume."""
import csv
import json
import os
import signal
import subprocess
import sys
import textwrap
import time

import matplotlib
import numpy as np
import pytest
from hypothesis import given, strategies as st

from exudyn_worm.analysis.studies import studymap
from exudyn_worm.drive.config import ResolveParameters
from exudyn_worm.analysis.stability.linearization import LinearStabilityOfDrive
from exudyn_worm.drive.presets import ElasticDriveFromParameters
from exudyn_worm.model.stability import AnalyzeStability
from exudyn_worm.analysis.studies.study import RunStudy
from exudyn_worm.analysis.studies.studyfiles import ReadResults, StudyResult, StudySidecarPath
from exudyn_worm.analysis.studies.studygrid import ParseShard, ParseVariation, ShardIndices, Study, StudyPoints, Variation
from exudyn_worm.analysis.studies.studypoint import HALF_STEP_METRICS, RUN_COLUMNS, WINDOW_METRICS, RunPoint
from exudyn_worm.drive.wholedrive import ResolveDrive

# short runs: 1 s of the reel changer (lifting), two windows
SHORT = dict(windows=[(0., 0.5), (0.5, 1.)], endTime=1.)


def test_grid_linear_and_log():
    v = ParseVariation('J1=0.01:0.4:8')
    assert v.key == 'J1' and len(v.values) == 8
    np.testing.assert_allclose(v.values, np.linspace(0.01, 0.4, 8))
    v = ParseVariation('J1=0.01:0.4:8', log=True)
    np.testing.assert_allclose(v.values, np.geomspace(0.01, 0.4, 8))
    assert v.values[0] == 0.01 and v.values[-1] == 0.4            # exact ends
    np.testing.assert_allclose(np.diff(np.log(v.values)), np.log(40) / 7)
    # the fourth field overrides the flag
    np.testing.assert_allclose(ParseVariation('kT=700:14000:3:log').values, [700, 700 * 20 ** 0.5, 14000])
    np.testing.assert_allclose(ParseVariation('kT=700:14000:3:lin', log=True).values, [700, 7350, 14000])
    assert ParseVariation('J1=0.1:0.1:1').values == (0.1,)


def test_list_and_grid_with_units():
    np.testing.assert_allclose(ParseVariation('backlash=0,0.25mm,0.5 mm,0.75mm').values, [0, 2.5e-4, 5e-4, 7.5e-4])
    np.testing.assert_allclose(ParseVariation('backlash=0:1mm:5').values, [0, 2.5e-4, 5e-4, 7.5e-4, 1e-3])
    np.testing.assert_allclose(ParseVariation('motorSpeed=472.5rpm,945 rpm').values,
                               [472.5 * np.pi / 30, 945 * np.pi / 30])
    np.testing.assert_allclose(ParseVariation('kT=7 kN*m,14kN*m').values, [7000, 14000])


@pytest.mark.messages
@pytest.mark.parametrize('text, message', [
    ('J1', 'expected KEY='), ('J1=', 'expected KEY='), ('nope=1,2', "unknown parameter 'nope'"),
    ('J1=0.01:0.4', 'START:STOP:COUNT'), ('J1=0.01:0.4:0', 'COUNT must be >= 1'),
    ('J1=0.01:0.4:x', 'COUNT must be a whole number'), ('J1=0:0.4:5:log', 'log grid needs START and STOP > 0'),
    ('J1=0.1:0.1:3', 'must differ'), ('backlash=0,,1mm', 'empty value'), ('backlash=0,1 kg', "'backlash' must be"),
])
def test_bad_variations(text, message):
    with pytest.raises(ValueError, match=message):
        ParseVariation(text)


def test_factorial_and_zip():
    a, b = Variation('J1', (1., 2., 3.)), Variation('kT', (10., 20., 30.))
    points = StudyPoints([a, b])
    assert len(points) == 9
    assert points[:4] == [{'J1': 1., 'kT': 10.}, {'J1': 1., 'kT': 20.}, {'J1': 1., 'kT': 30.}, {'J1': 2., 'kT': 10.}]
    assert len({tuple(p.items()) for p in points}) == 9
    assert StudyPoints([a, b], zipped=True) == [{'J1': 1., 'kT': 10.}, {'J1': 2., 'kT': 20.}, {'J1': 3., 'kT': 30.}]
    assert StudyPoints([]) == [{}]
    with pytest.raises(ValueError, match='equal numbers'):
        StudyPoints([a, Variation('kT', (1., 2.))], zipped=True)
    with pytest.raises(ValueError, match='more than once'):
        StudyPoints([a, Variation('J1', (5.,))])


def test_shard_parsing():
    assert ParseShard('0/4') == (0, 4) and ParseShard('3/4') == (3, 4) and ParseShard(None) is None
    for bad in ('4/4', '-1/4', '1', 'a/b', '1/0'):
        with pytest.raises(ValueError, match='i/N'):
            ParseShard(bad)


@given(st.integers(0, 300), st.integers(1, 20))
def test_shards_cover_every_point_once(runs, n):
    seen = sorted(i for k in range(n) for i in ShardIndices(runs, (k, n)))
    assert seen == list(range(runs))
    sizes = [len(ShardIndices(runs, (k, n))) for k in range(n)]
    assert max(sizes) - min(sizes) <= 1


def _Study(*vary, **kw):
    return Study(ResolveParameters('reel-P1'), [ParseVariation(v) for v in vary], **{**SHORT, **kw})


def test_failed_run_is_recorded_and_others_finish(tmp_path):
    # loadMass = 1e20 kg: the Exudyn solver fails (1e9 kg runs through with the sticking friction);
    # J1 < 0: the model refuses it (a Variation built directly: ParseVariation refuses it at once); 175 kg: fine
    study = _Study('loadMass=175,1e20')
    with pytest.raises(ValueError, match=r"ParseVariation: 'J1=0.1,-0.1': 'J1' must be > 0 kg\*m\^2, got -0.1"):
        ParseVariation('J1=0.1,-0.1')
    study2 = Study(study.base, [Variation('J1', (0.1, -0.1))], **SHORT)
    r = RunStudy(study, tmp_path / 'a.csv', workers=2, quiet=True)
    assert [row['status'] for row in r.rows] == ['ok', 'failed']
    assert 'Solve' in r.rows[1]['error'] and r.rows[1]['w0.t0'] is None
    assert r.rows[0]['error'] == '' and r.rows[0]['w1.t1'] == 1.
    r2 = RunStudy(study2, tmp_path / 'b.csv', workers=1, quiet=True)
    assert [row['status'] for row in r2.rows] == ['ok', 'failed']
    assert "'J1' must be > 0" in r2.rows[1]['error']
    runs = r2.ToDict()['runs']
    assert runs[1]['windows'] == [] and runs[1]['analyticStable'] is None
    assert len(runs[0]['windows']) == 2


def test_csv_json_and_read_back(tmp_path):
    study = _Study('J1=0.01,0.1', 'backlash=0,0.5mm', source='preset reel-P1')
    out = tmp_path / 'runs.csv'
    result = RunStudy(study, out, workers=2, quiet=True)
    with out.open(newline='') as f:
        table = list(csv.DictReader(f))
    columns = list(RUN_COLUMNS) + ['J1', 'backlash'] + [f'w{i}.{m}' for i in range(2) for m in
                                                        WINDOW_METRICS + tuple(f'halfStep.{h}' for h in HALF_STEP_METRICS)]
    assert list(table[0]) == columns
    assert sorted(int(r['run']) for r in table) == [0, 1, 2, 3]
    assert {(float(r['J1']), float(r['backlash'])) for r in table} == {(0.01, 0.), (0.01, 5e-4), (0.1, 0.), (0.1, 5e-4)}
    assert all(r['status'] == 'ok' and float(r['seconds']) >= float(r['solveSeconds']) > 0 for r in table)
    meta = json.loads(StudySidecarPath(out).read_text())
    assert meta['study']['variations'][1] == {'key': 'backlash', 'unit': 'm', 'values': [0., 5e-4],
                                              'text': 'backlash=0,0.5mm'}
    assert meta['study']['base']['J2'] == 33. and meta['study']['windows'] == [[0., 0.5], [0.5, 1.]]
    assert meta['versions']['exudyn'] and meta['versions']['python']
    assert meta['counts'] == {'runs': 4, 'done': 4, 'failed': 0}
    d = result.ToDict()
    assert set(d) == {'runs', 'agreement'}
    assert d['runs'][1]['parameters'] == {'J1': 0.01, 'backlash': 5e-4}
    # P1's S = +1 margin 0.011 < 0.02, but the lifting windows' verdicts are clear: not checked at half the step
    assert d['runs'][0]['stepChecked'] is False and set(d['runs'][0]['windows'][0]) == set(WINDOW_METRICS)
    # the file holds exactly what the study returned (floats round-trip)
    assert ReadResults(out).ToDict() == d
    json.dumps(d, allow_nan=False)
    # no lowering window in [0, 1] s: no agreement can be judged
    assert d['agreement'] is None and all(r['loweringChatter'] is None for r in d['runs'])


def test_agreement_counts_finished_runs_only():
    study = Study(ResolveParameters('reel-P1'), [Variation('J1', (1., 2., 3., 4.))])
    row = lambda run, status, chatter, stable: {'run': run, 'status': status, 'loweringChatter': chatter,
                                                 'analyticStableLowering': stable}
    rows = [row(0, 'ok', True, False), row(1, 'ok', False, False), row(2, 'ok', False, True),
            row(3, 'failed', None, True)]
    assert StudyResult(study, rows).agreement == pytest.approx(2 / 3)


@pytest.mark.messages
def test_output_checked_before_computing(tmp_path):
    study = _Study('J1=0.1')
    with pytest.raises(ValueError, match='does not exist'):
        RunStudy(study, tmp_path / 'missing' / 'a.csv', quiet=True)
    with pytest.raises(ValueError, match='.csv'):
        RunStudy(study, tmp_path / 'a.txt', quiet=True)
    (tmp_path / 'b.csv').write_text('something else\n')
    with pytest.raises(ValueError, match='without its sidecar'):
        RunStudy(study, tmp_path / 'b.csv', quiet=True)
    RunStudy(study, tmp_path / 'c.csv', quiet=True, workers=1)
    with pytest.raises(ValueError, match='different study'):
        RunStudy(_Study('J1=0.2'), tmp_path / 'c.csv', quiet=True)
    with pytest.raises(ValueError, match='different study'):
        RunStudy(study, tmp_path / 'c.csv', quiet=True, shard='0/2')
    assert len(RunStudy(_Study('J1=0.2'), tmp_path / 'c.csv', quiet=True, overwrite=True, workers=1).rows) == 1
    for bad in (0, -1, 1.5, True):
        with pytest.raises(ValueError, match="'workers'"):
            RunStudy(study, workers=bad, quiet=True)
    with pytest.raises(ValueError, match="'engine'"):
        RunStudy(study, engine='dask', quiet=True)


def test_finished_study_resumed_keeps_its_record(tmp_path):
    """Reading a finished study again (e.g. to redraw its figures) with other workers leaves its sidecar alone:
    it records how the runs were computed."""
    study = _Study('J1=0.05,0.1')
    RunStudy(study, tmp_path / 'a.csv', workers=2, quiet=True)
    sidecar = StudySidecarPath(tmp_path / 'a.csv').read_text()
    assert json.loads(sidecar)['workers'] == 2
    assert len(RunStudy(study, tmp_path / 'a.csv', workers=1, quiet=True).rows) == 2
    assert StudySidecarPath(tmp_path / 'a.csv').read_text() == sidecar


def test_shards_together_give_the_whole_study(tmp_path):
    study = _Study('J1=0.05,0.1,0.2')
    whole = RunStudy(study, tmp_path / 'all.csv', workers=2, quiet=True)
    parts = [RunStudy(study, tmp_path / f's{k}.csv', workers=1, quiet=True, shard=f'{k}/2') for k in range(2)]
    assert [r['run'] for r in parts[0].rows] == [0, 2] and [r['run'] for r in parts[1].rows] == [1]
    merged = ReadResults(tmp_path / 's0.csv', tmp_path / 's1.csv')
    strip = lambda runs: [{k: v for k, v in r.items() if 'econds' not in k} for r in runs]
    assert strip(merged.ToDict()['runs']) == strip(whole.ToDict()['runs'])


_KILLABLE = textwrap.dedent('''
    import sys
    from exudyn_worm.drive.config import ResolveParameters
    from exudyn_worm.analysis.studies.study import RunStudy
    from exudyn_worm.analysis.studies.studygrid import ParseVariation, Study
    study = Study(ResolveParameters('reel-P1'), [ParseVariation('J1=0.02:0.3:12:log')],
                  windows=[(0., 0.5), (0.5, 1.)], endTime=1.)
    RunStudy(study, sys.argv[1], workers=1, quiet=True)
''')


def test_resume_after_kill(tmp_path):
    out = tmp_path / 'runs.csv'
    script = tmp_path / 'study.py'
    script.write_text(_KILLABLE)
    proc = subprocess.Popen([sys.executable, str(script), str(out)], start_new_session=True,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    try:
        deadline = time.time() + 240
        while time.time() < deadline and proc.poll() is None:
            if out.exists() and out.read_text().count('\n') >= 3:      # header + 2 runs
                break
            time.sleep(0.05)
        assert proc.poll() is None, proc.stderr.read().decode()
    finally:
        os.killpg(proc.pid, signal.SIGKILL)                # the study and its worker, like a killed job
        proc.wait()
    before = out.read_text()
    doneRuns = {int(line.split(',')[0]) for line in _Complete(before)}
    assert 2 <= len(doneRuns) < 12
    newRows = []
    study = Study(ResolveParameters('reel-P1'), [ParseVariation('J1=0.02:0.3:12:log')], **SHORT)
    result = RunStudy(study, out, workers=2, quiet=True, onRow=newRows.append)
    assert [r['run'] for r in result.rows] == list(range(12))
    assert all(r['status'] == 'ok' for r in result.rows)
    # finished runs were not redone: only the others were computed, the old lines stay as they were
    assert sorted(r['run'] for r in newRows) == sorted(set(range(12)) - doneRuns)
    after = out.read_text()
    assert after.startswith(''.join(_Complete(before, header=True)))
    assert sorted(int(line.split(',')[0]) for line in after.splitlines()[1:]) == list(range(12))


def _Complete(text, header=False):
    """Complete lines of a CSV text (a killed writer may leave a partial last line)."""
    lines = text.splitlines(keepends=True)
    if lines and not lines[-1].endswith('\n'):
        lines = lines[:-1]
    return lines if header else lines[1:]


def test_chatter_map_axes_follow_the_grid():
    """Two kT values 80x apart: the map's analytical grid is log-spaced, so the axis must be logarithmic too
    (it was linear from 0 to 250000 N*m/rad); the outer runs lie inside the axes by 15 % of the span."""
    matplotlib.use('Agg')
    result = RunStudy(_Study('J1=0.05,0.1', 'kT=350,28000'), workers=1, quiet=True)
    ax = result.plot('J1', 'kT').axes[0]
    assert ax.get_yscale() == 'log' and ax.get_xscale() == 'linear'
    low, high = ax.get_ylim()
    assert low == pytest.approx(350. / 80. ** 0.15) and high == pytest.approx(28000. * 80. ** 0.15)
    lo, hi = ax.get_xlim()
    assert 0 < lo < 0.05 and hi > 0.1


@pytest.mark.parametrize('base, varied', [
    ({'kA': 5e8, 'mA': 5.}, 'J1=0.1,0.2'),                                  # worm axial bearing
    ({'J4': 0.05, 'k4': 18483., 'd4': 0.8512}, 'J4=0.05,0.4'),              # Figure 19's drive-side chain
])
def test_verdict_of_a_drive_beyond_two_masses_is_that_of_stability(base, varied):
    """The verdict columns come from the linearized whole drive, as `exudyn-worm stability` gives them, not from the
    two-mass model (which disagrees here at one of the two points); the simulation agrees with them."""
    study = Study(ResolveParameters('reel-P1', sets=list(base.items())), [ParseVariation(varied)], endTime=6.)
    rows = [RunPoint(study.Task(i)) for i in range(2)]
    twoMassDiffers = False
    for i, row in enumerate(rows):
        p = study.Parameters(i)
        whole = LinearStabilityOfDrive(ResolveDrive(parameters=p))
        assert row['status'] == 'ok', row['error']
        assert row['analyticStable'] is whole.stable
        assert row['analyticStableLowering'] is whole.State(-1).stable
        twoMass = AnalyzeStability(ElasticDriveFromParameters({k: v for k, v in p.items() if k not in base}))
        twoMassDiffers |= twoMass.contact[-1].stable != whole.State(-1).stable
        assert row['loweringChatter'] is (not whole.State(-1).stable)
    assert twoMassDiffers                      # the test would catch the two-mass verdict
    assert sorted(r['analyticStableLowering'] for r in rows) == [False, True]
    assert StudyResult(study, rows).agreement == 1.


def test_chatter_map_of_a_drive_beyond_two_masses_uses_the_whole_drive():
    """studymap: the stability-chart shortcut only for the two-mass drive; the map's linear model is the whole
    drive's (the two-mass model says the opposite at both J1 here)."""
    pytest.importorskip('matplotlib')
    bearing = ResolveParameters('reel-P1', sets=['kA=5e8', 'mA=5'])
    growth = studymap.AnalyticalMap(ResolveDrive(parameters=bearing), 'J1', [0.1, 0.2], 'kT', [7000.])
    assert growth.shape == (1, 2) and growth[0, 0] < 0 < growth[0, 1]       # as `stability`: J1 = 0.1 stable
    twoMass = studymap.AnalyticalMap(ResolveDrive(parameters=ResolveParameters('reel-P1')), 'J1', [0.1, 0.2], 'kT', [7000.])
    assert twoMass[0, 0] > 0 > twoMass[0, 1]
    grid = np.geomspace(0.05, 0.4, 5), np.geomspace(3000., 20000., 5)
    assert studymap._Chart(ResolveDrive('reel-P1'), 'J1', grid[0], 'kT', grid[1], 50) is not None
    assert studymap._Chart(ResolveDrive(parameters=bearing), 'J1', grid[0], 'kT', grid[1], 50) is None
    study = Study(bearing, [ParseVariation('J1=0.1,0.2'), ParseVariation('kT=7000,8000')])
    rows = [{'run': i, 'status': 'ok', 'loweringChatter': p['J1'] > 0.15, 'analyticStableLowering': p['J1'] < 0.15,
             **p} for i, p in enumerate(study.points)]
    fig = StudyResult(study, rows).plot('J1', 'kT', resolution=8)
    labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert any('linearized whole drive' in t for t in labels), labels


@pytest.mark.messages
def test_study_names_itself_for_a_typo_in_the_base_set():
    with pytest.raises(ValueError, match=r"Study: 'base': unknown parameter 'Kt' \(did you mean 'kT'\?\)"):
        Study({**ResolveParameters('reel-P1'), 'Kt': 1.}, [ParseVariation('J1=0.1')])
