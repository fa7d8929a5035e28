"""The step rule shared by simulate and sweep, and the step check: a verdict that changes at half the step is
'unresolved' (issue 16, item 7)."""
import json

import numpy as np
import pytest

from exudyn_worm.cli.main import Main
from exudyn_worm.setups.config import ResolveParameters
from exudyn_worm.setups.presets import ApplyOverrides, GetPreset
from exudyn_worm.items.results import SimulationResult
from exudyn_worm.model.stability import StateMatrix
from exudyn_worm.analysis.stepsize import (SMALL_MARGIN, UNRESOLVED, CompareHalfStep, LinearMargin, RecommendedStepSize,
                                  StepCheckByDefault)
from exudyn_worm.analysis.studygrid import Study, Variation
from exudyn_worm.analysis.studypoint import RunPoint

# the drive of issue 16: J1 = 0.0247 kg*m^2, kT = 1508 N*m/rad on P1's gear and load
ISSUE_SETS = ['J1=0.0247', 'kT=1508']
# short runs: 1 s of lifting in two windows
SHORT = ['--end-time', '1', '--windows', '0:0.5,0.5:1']


def _Run(capsys, *argv):
    status = Main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def _FlipWithStep(monkeypatch, threshold):
    """Make the chatter verdict depend on the step alone: chatter iff the run's step exceeds ``threshold``."""
    monkeypatch.setattr(SimulationResult, 'Chatter', lambda self, t0, t1: self.info['stepSize'] > threshold)


def test_simulate_and_sweep_use_the_same_step():
    """Both take the drive's RecommendedStepSize; for the issue's drive (6.4e-4 s) the sweep used to take 5e-4 s."""
    p = ResolveParameters('reel-P1', sets=ISSUE_SETS)
    h = RecommendedStepSize(p)
    assert h > 5e-4                       # the old sweep rule min(5e-4, recommended) would differ here
    row = RunPoint({'run': 0, 'parameters': p, 'varied': {}, 'windows': [(0., 0.5)], 'endTime': 0.5,
                    'stepSize': None, 'checkStep': False})
    assert row['status'] == 'ok' and row['stepSize'] == h and row['stepChecked'] is False


def test_simulate_default_step_is_the_recommended_one(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    status, out, err = _Run(capsys, 'simulate', '--quiet', '--json', '--no-check-step', *SHORT,
                            *[a for s in ISSUE_SETS for a in ('--set', s)])
    assert status == 0, err
    assert json.loads(out)['stepSize'] == RecommendedStepSize(ResolveParameters('reel-P1', sets=ISSUE_SETS))


def test_linear_margin_is_the_least_damped_rightmost_mode():
    """P1: the rightmost eigenvalue of S = +1 (eqs. (1)-(2)) has |Re|/|lambda| = 0.011 (printed by 'stability' as
    Lehr damping 0.0108), below SMALL_MARGIN; raising both damping measures to 0.1 takes it to 0.09."""
    from exudyn_worm.setups.presets import ElasticDriveFromParameters
    p = GetPreset('reel-P1')
    lam = np.linalg.eigvals(StateMatrix(ElasticDriveFromParameters(p), +1))
    right = lam[np.argmax(lam.real)]
    m = LinearMargin(p)
    assert m['contactState'] == 1 and m['margin'] == pytest.approx(abs(right.real) / abs(right), rel=1e-12)
    assert m['margin'] == pytest.approx(0.0108, abs=5e-5) and StepCheckByDefault(p)
    damped = ApplyOverrides(GetPreset('reel-P2'), {'DV': 0.1, 'DT': 0.1})
    assert LinearMargin(damped)['margin'] > SMALL_MARGIN and not StepCheckByDefault(damped)


def test_a_verdict_that_flips_with_the_step_is_unresolved_in_simulate(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    p = GetPreset('reel-P1')
    h = RecommendedStepSize(p)
    _FlipWithStep(monkeypatch, 0.75 * h)            # chatter at h, none at h/2
    status, out, err = _Run(capsys, 'simulate', '--quiet', '--json', '--check-step', *SHORT)
    assert status == 0, err
    data = json.loads(out)
    assert data['stepCheck']['checked'] and data['stepCheck']['halfStepSize'] == pytest.approx(h / 2)
    for w in data['windows']:
        assert w['chatter'] == UNRESOLVED and w['halfStep']['chatter'] is False
        assert w['halfStep']['maxAbsWheelAcceleration'] >= 0 and 'maxNormalForce' in w['halfStep']
    status, out, err = _Run(capsys, 'simulate', '--quiet', '--check-step', *SHORT)
    assert status == 0 and out.count('unresolved (h: YES, h/2: no;') == 2
    # without the check the same run reports chatter
    status, out, err = _Run(capsys, 'simulate', '--quiet', '--json', '--no-check-step', *SHORT)
    data = json.loads(out)
    assert not data['stepCheck']['checked'] and [w['chatter'] for w in data['windows']] == [True, True]
    assert all('halfStep' not in w for w in data['windows'])
    assert list(tmp_path.iterdir()) == []


def test_a_verdict_that_holds_at_half_the_step_stays(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    _FlipWithStep(monkeypatch, 0.)                  # chatter at both steps
    status, out, err = _Run(capsys, 'simulate', '--quiet', '--json', '--check-step', *SHORT)
    assert status == 0 and [w['chatter'] for w in json.loads(out)['windows']] == [True, True]


def test_step_check_follows_the_margin_by_default(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    status, out, err = _Run(capsys, 'simulate', '--quiet', *SHORT, '--set', 'DV=0.1', '--set', 'DT=0.1',
                            '--preset', 'reel-P2')
    assert status == 0 and 'step check: off (linear margin |Re lambda|/|lambda| = 0.09' in out


def test_explicit_step_check_beyond_the_step_limit_is_refused(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    h = RecommendedStepSize(GetPreset('reel-P1'))
    limit = str(int(1. / h) + 10)                   # the run fits, the run at half the step does not
    status, out, err = _Run(capsys, 'simulate', '--quiet', '--check-step', *SHORT, '--max-steps', limit)
    assert status == 2 and err.count('\n') == 1 and 'half the step (--check-step)' in err and 'Traceback' not in err
    status, out, err = _Run(capsys, 'simulate', '--quiet', *SHORT, '--max-steps', limit)   # default: skipped, said
    assert status == 0 and err == '' and 'step check: off (the run at half the step would exceed' in out
    status, out, err = _Run(capsys, 'simulate', '--quiet', '--json', *SHORT, '--max-steps', limit)
    assert json.loads(out)['stepCheck']['reason'] == 'maxSteps' and not json.loads(out)['stepCheck']['checked']


def test_a_verdict_that_flips_with_the_step_is_unresolved_in_sweep(monkeypatch):
    p = GetPreset('reel-P1')
    _FlipWithStep(monkeypatch, 0.75 * RecommendedStepSize(p))
    study = Study(p, [Variation('J1', (0.2,))], windows=[(0., 0.5), (0.5, 1.)], endTime=1., checkStep=True)
    row = RunPoint(study.Task(0))
    assert row['status'] == 'ok', row['error']
    assert row['stepChecked'] is True
    assert [row[f'w{i}.chatter'] for i in range(2)] == [UNRESOLVED] * 2
    assert [row[f'w{i}.halfStep.chatter'] for i in range(2)] == [False] * 2
    assert all(row[f'w{i}.halfStep.maxAbsWheelAcceleration'] >= 0 for i in range(2))
    off = RunPoint(Study(p, [Variation('J1', (0.2,))], windows=[(0., 0.5)], endTime=1., checkStep=False).Task(0))
    assert off['w0.chatter'] is True and 'w0.halfStep.chatter' not in off


def test_unresolved_survives_the_csv_and_stays_out_of_the_agreement(tmp_path, monkeypatch):
    from exudyn_worm.cli.formatsweep import FormatStudy
    from exudyn_worm.analysis.study import RunStudy
    from exudyn_worm.analysis.studyfiles import ReadResults
    p = GetPreset('reel-P1')
    _FlipWithStep(monkeypatch, 0.75 * RecommendedStepSize(p))
    study = Study(p, [Variation('J1', (0.2,))], windows=[(3.8, 4.0), (4.0, 4.2)], endTime=4.2, checkStep=True)
    out = tmp_path / 'runs.csv'
    result = RunStudy(study, out, workers=1, quiet=True)
    assert result.rows[0]['loweringChatter'] == UNRESOLVED and result.agreement is None
    assert ReadResults(out).ToDict() == result.ToDict()
    table = '\n'.join(FormatStudy(result))
    assert 'UNR UNR' in table and '1 with an unresolved verdict' in table


def test_compare_half_step_needs_the_same_windows():
    a = [{'t0': 0., 't1': 1., 'chatter': True}]
    assert CompareHalfStep(a, [{'t0': 0., 't1': 1., 'chatter': True}])[0]['chatter'] is True
    with pytest.raises(ValueError, match="CompareHalfStep: 'halfStepMetrics' must have the windows"):
        CompareHalfStep(a, [{'t0': 0., 't1': 2., 'chatter': True}])
