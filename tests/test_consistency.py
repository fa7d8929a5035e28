"""Consistency of the subcommands: ``sweep --max-steps`` as ``simulate`` has it; a refused resume
names the option that differs with its old and new values; one policy for existing output files (refused unless
``--overwrite``) in every subcommand and in ``python -m validation``."""
import json

import pytest

from exudyn_worm.cli.main import Main
from exudyn_worm.drive.config import ResolveParameters
from exudyn_worm.analysis.studies.studygrid import ParseVariation
from exudyn_worm.analysis.studies.study import RunStudy, Study
import exudyn_worm.analysis.design.designcheck as design
import exudyn_worm.analysis.simulation.reelchanger as reelchanger
import exudyn_worm.analysis.charts.stabilitychart as charts
import validation.runner as runner
from validation.cli import Main as ValidationMain

pytestmark = pytest.mark.usefixtures('emptyWorkingDirectory')   # nothing written to the cwd

SHORT = dict(windows=[(0., 0.1), (0.1, 0.2)], endTime=0.2)


def _Run(capsys, *argv):
    status = Main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return status, out, err


# --- sweep --max-steps -------------------------------------------------------------------------------------
def test_sweep_max_steps_limits_each_run(capsys):
    argv = ['sweep', '--vary', 'J1=0.1,0.2', '--windows', '0:0.1,0.1:0.2', '--end-time', '0.2', '--step-size', '5e-4',
            '--workers', '1', '--quiet', '--json']
    status, out, err = _Run(capsys, *argv, '--max-steps', '100')         # 0.2 s / 5e-4 s = 400 steps > 100
    runs = json.loads(out)['runs']
    assert status == 1 and [r['status'] for r in runs] == ['failed', 'failed']
    assert all('more than the limit maxSteps = 100' in r['error'] for r in runs)
    assert err.strip().endswith('runs longer than the step limit are refused: raise it with --max-steps N')
    status, out, err = _Run(capsys, *argv, '--max-steps', '400')
    assert status == 0 and [r['status'] for r in json.loads(out)['runs']] == ['ok', 'ok']


@pytest.mark.parametrize('value, text', [('0', 'must be >= 1 steps, got 0'), ('1.5', 'expected an integer'),
                                         ('x', 'expected an integer')])
def test_sweep_max_steps_bad_input(capsys, value, text):
    status, out, err = _Run(capsys, 'sweep', '--vary', 'J1=0.1', '--max-steps', value)
    assert status == 2 and out == '' and err.count('\n') == 1 and '--max-steps' in err and text in err, err


def test_study_max_steps_is_checked():
    with pytest.raises(ValueError, match="Study: 'maxSteps' must be a whole number >= 1"):
        Study(ResolveParameters('reel-P1'), [ParseVariation('J1=0.1')], maxSteps=0)


# --- a refused resume names what differs ---------------------------------------------------------------------
def _Study(**kw):
    base = ResolveParameters('reel-P1')
    options = {**SHORT, **kw}
    if 'base' in options:
        base.update(options.pop('base'))
    vary = options.pop('vary', 'J1=0.1')
    return Study(base, [ParseVariation(vary)], **options)


@pytest.fixture(scope='module')
def recorded(tmp_path_factory):
    """A finished one-run study on disk (the resume check reads only its sidecar)."""
    path = tmp_path_factory.mktemp('resume') / 'runs.csv'
    RunStudy(_Study(), path, workers=1, quiet=True)
    return path


@pytest.mark.parametrize('change, shard, expected', [
    (dict(stepSize=4e-4), None, 'stepSize (--step-size): default in the file, 0.0004 now'),
    (dict(maxSteps=5000), None, 'maxSteps (--max-steps): default in the file, 5000 now'),
    (dict(endTime=0.3), None, 'endTime (--end-time): 0.2 in the file, 0.3 now'),
    (dict(windows=[(0., 0.2)]), None, 'windows (--windows): [[0.0, 0.1], [0.1, 0.2]] in the file, [[0.0, 0.2]] now'),
    (dict(base={'J2': 1.5}), None, 'parameter J2 (--preset/--config/--set): '),
    (dict(vary='J1=0.2'), None, 'varied values (--vary): J1=0.1 in the file, J1=0.2 now'),
    (dict(), '0/2', 'shard (--shard): default in the file, [0, 2] now'),
])
def test_refused_resume_names_the_option(recorded, change, shard, expected):
    with pytest.raises(ValueError, match='different study') as info:
        RunStudy(_Study(**change), recorded, quiet=True, shard=shard)
    assert expected in str(info.value) and str(info.value).count(';') >= 1
    if 'base' in change:
        assert ', 1.5 now' in str(info.value)


def test_refused_resume_on_the_command_line(capsys, tmp_path):
    output = tmp_path / 'out' / 'runs.csv'
    output.parent.mkdir()
    argv = ['sweep', '--vary', 'J1=0.1', '--windows', '0:0.1,0.1:0.2', '--end-time', '0.2', '--workers', '1', '--quiet',
            '--output', output]
    assert _Run(capsys, *argv)[0] == 0
    status, out, err = _Run(capsys, *argv, '--step-size', '4e-4')
    assert status == 2 and err.count('\n') == 1
    assert 'stepSize (--step-size): default in the file, 0.0004 now' in err
    assert _Run(capsys, *argv)[0] == 0                     # the same options: resumed (nothing left to run)


def test_sidecar_without_max_steps_still_resumes(tmp_path):
    """Results files written before --max-steps existed have no 'maxSteps': they are studies at the default."""
    path = tmp_path / 'runs.csv'
    RunStudy(_Study(), path, workers=1, quiet=True)
    sidecar = tmp_path / 'runs.study.json'
    meta = json.loads(sidecar.read_text())
    del meta['study']['maxSteps']
    sidecar.write_text(json.dumps(meta))
    assert len(RunStudy(_Study(), path, quiet=True).rows) == 1


# --- one policy for existing output files ------------------------------------------------------------------
def _OutputCases(folder):
    """name -> (argv, the existing file that must be refused and left unchanged)."""
    figs = folder / 'figs'
    return {
        'simulate --csv': (['simulate', '--end-time', '0.1', '--quiet', '--csv', folder / 'a.csv'], folder / 'a.csv'),
        'simulate --plot': (['simulate', '--end-time', '0.1', '--quiet', '--plot', figs], figs / 'speed.png'),
        'chart --output': (['chart', '--preset', 'chart', '--DV', '0.014', '--resolution', '5', '--output',
                            folder / 'c.png'], folder / 'c.png'),
        'check --plot': (['check', '--preset', 'reel-P1', '--plot', folder / 'k.png'], folder / 'k.png'),
        'sweep --plot': (['sweep', '--vary', 'J1=0.1,0.2', '--plot', folder / 's.png'], folder / 's.png'),
    }


OUTPUT_CASES = ['simulate --csv', 'simulate --plot', 'chart --output', 'check --plot', 'sweep --plot']


@pytest.mark.parametrize('case', OUTPUT_CASES)
def test_existing_output_is_refused_without_overwrite(capsys, tmp_path, monkeypatch, case):
    for module, name in ((design, 'DesignCheck'), (reelchanger, 'SimulateReelChanger'),
                         (charts, 'ComputeStabilityChart')):     # refused before anything is computed
        monkeypatch.setattr(module, name, lambda *a, **k: pytest.fail('computed before the output check'))
    folder = tmp_path / 'out'
    (folder / 'figs').mkdir(parents=True)
    cases = _OutputCases(folder)
    assert set(cases) == set(OUTPUT_CASES)
    argv, existing = cases[case]
    existing.write_text('precious')
    status, out, err = _Run(capsys, *argv)
    assert status == 2 and out == '' and err.count('\n') == 1 and 'Traceback' not in err
    assert err.startswith('exudyn-worm: error: ') and 'give --overwrite to replace it' in err, err
    assert existing.read_text() == 'precious'


@pytest.mark.parametrize('argv, written', [
    (['simulate', '--end-time', '0.1', '--quiet', '--csv', 'a.csv'], 'a.csv'),
    (['chart', '--preset', 'chart', '--DV', '0.014', '--DTV', '5', '--resolution', '5', '--quiet', '--output', 'c.png'],
     'c.png'),
])
def test_overwrite_replaces_the_file(capsys, tmp_path, argv, written):
    folder = tmp_path / 'out'
    folder.mkdir()
    target = folder / written
    target.write_text('old')
    argv = [folder / a if a == written else a for a in argv]
    status, out, err = _Run(capsys, *argv, '--overwrite')
    assert status == 0 and target.read_bytes() != b'old' and sorted(p.name for p in folder.iterdir()) == [written]


def test_new_output_needs_no_overwrite(capsys, tmp_path):
    folder = tmp_path / 'out'
    folder.mkdir()
    status, out, err = _Run(capsys, 'simulate', '--end-time', '0.1', '--quiet', '--csv', folder / 'a.csv')
    assert status == 0 and (folder / 'a.csv').is_file()


@pytest.mark.parametrize('option', ['--report', '--record-baseline'])
def test_validation_refuses_an_existing_file(capsys, tmp_path, monkeypatch, option):
    monkeypatch.setattr(runner, 'RunValidation', lambda **kw: pytest.fail('computed before the output check'))
    path = tmp_path / 'existing'
    path.write_text('precious')
    status = ValidationMain(['--quick', option, str(path)])
    out, err = capsys.readouterr()
    assert status == 2 and err.count('\n') == 1 and 'give --overwrite to replace it' in err
    assert path.read_text() == 'precious'
