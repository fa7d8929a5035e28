"""The step rule shared by simulate and sweep, and the step check: a verdict that changes at half the step is
'unresolved'."""
import json

import numpy as np
import pytest

from exudyn_worm.cli.main import Main
from exudyn_worm.drive.config import ResolveParameters
from exudyn_worm.drive.presets import ApplyOverrides, GetPreset
from exudyn_worm.items.results import ChatterVerdict, SimulationResult
from exudyn_worm.analysis.simulation.stepsize import (SMALL_MARGIN, UNRESOLVED, CompareHalfStep, LinearMargin, RecommendedStepSize,
                                  StepCheckByDefault)
from exudyn_worm.analysis.studies.studyfiles import ReadResults
from exudyn_worm.analysis.studies.study import RunStudy, Study
from exudyn_worm.analysis.studies.studypoint import RunPoint, RunTask
from exudyn_worm.analysis.studies.studygrid import Variation
from exudyn_worm.analysis.simulation.reelchanger import SimulateReelChanger
from exudyn_worm.analysis.simulation.stepsize import VERDICT_FACTOR, CloseVerdicts
from exudyn_worm.cli.formatsweep import FormatStudy
from exudyn_worm.drive.wholedrive import ResolveDrive
from paper_model import Eigenvalues

# a user's drive: J1 = 0.0247 kg*m^2, kT = 1508 N*m/rad on P1's gear and load
USER_SETS = ['J1=0.0247', 'kT=1508']
# short runs: 1 s of lifting in two windows
SHORT = ['--end-time', '1', '--windows', '0:0.5,0.5:1']


def _Run(capsys, *argv):
    status = Main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def _FlipWithStep(monkeypatch, threshold):
    """Make the chatter verdict depend on the step alone: chatter iff the run's step exceeds ``threshold``."""
    monkeypatch.setattr(SimulationResult, 'ChatterVerdict', lambda self, t0, t1: ChatterVerdict(
        'chatter' if self.info['stepSize'] > threshold else 'none', ('normal',), t1 - t0, 1., 0.))


def test_simulate_and_sweep_use_the_same_step():
    """Both take the drive's RecommendedStepSize; for that drive (6.4e-4 s) the sweep used to take 5e-4 s."""
    p = ResolveParameters('reel-P1', sets=USER_SETS)
    h = RecommendedStepSize(ResolveDrive(parameters=p))
    assert h > 5e-4                       # the old sweep rule min(5e-4, recommended) would differ here
    row = RunPoint(RunTask(0, ResolveDrive(parameters=p), windows=[(0., 0.5)], endTime=0.5, checkStep=False))
    assert row['status'] == 'ok' and row['stepSize'] == h and row['stepChecked'] is False


def test_simulate_default_step_is_the_recommended_one(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    status, out, err = _Run(capsys, 'simulate', '--quiet', '--json', '--no-check-step', *SHORT,
                            *[a for s in USER_SETS for a in ('--set', s)])
    assert status == 0, err
    assert json.loads(out)['stepSize'] == RecommendedStepSize(ResolveDrive(parameters=ResolveParameters('reel-P1', sets=USER_SETS)))


def _PaperMargins(p):
    """|Re lambda| / |lambda| of the rightmost root of eq. (15) per contact state S (tests/paper_model.py)."""
    margins = {}
    for S in (+1, -1):
        lam = Eigenvalues(p, S)
        right = lam[np.argmax(lam.real)]
        margins[S] = abs(right.real) / abs(right)
    return margins


def test_linear_margin_is_the_least_damped_rightmost_mode():
    """P1: the rightmost root of the characteristic polynomial (15) of each contact state, with the b's of eq. (16)
    written out from the paper (tests/paper_model.py), gives |Re|/|lambda|; the smaller one, that of S = +1, is the
    margin, below SMALL_MARGIN, so the step check runs by default; raising both damping measures to 0.1 lifts it
    above."""
    p = GetPreset('reel-P1')
    margins = _PaperMargins(p)
    m = LinearMargin(ResolveDrive(parameters=p))
    assert m['contactState'] == 1 and margins[+1] < margins[-1]
    assert m['margin'] == pytest.approx(margins[+1], rel=1e-9)
    assert m['margin'] < SMALL_MARGIN and StepCheckByDefault(ResolveDrive(parameters=p))
    damped = ApplyOverrides(GetPreset('reel-P2'), {'DV': 0.1, 'DT': 0.1})
    assert LinearMargin(ResolveDrive(parameters=damped))['margin'] > SMALL_MARGIN and not StepCheckByDefault(ResolveDrive(parameters=damped))


def test_a_verdict_that_flips_with_the_step_is_unresolved_in_simulate(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    p = GetPreset('reel-P1')
    h = RecommendedStepSize(ResolveDrive(parameters=p))
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
    margin = min(_PaperMargins(ApplyOverrides(GetPreset('reel-P2'), {'DV': 0.1, 'DT': 0.1})).values())
    assert margin > SMALL_MARGIN
    assert status == 0 and f'step check: off (linear margin |Re lambda|/|lambda| = {margin:.3g}' in out


def test_explicit_step_check_beyond_the_step_limit_is_refused(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    h = RecommendedStepSize(ResolveDrive(parameters=GetPreset('reel-P1')))
    limit = str(int(1. / h) + 10)                   # the run fits, the run at half the step does not
    status, out, err = _Run(capsys, 'simulate', '--quiet', '--check-step', *SHORT, '--max-steps', limit)
    assert status == 2 and err.count('\n') == 1 and 'half the step (--check-step)' in err and 'Traceback' not in err
    status, out, err = _Run(capsys, 'simulate', '--quiet', *SHORT, '--max-steps', limit)   # default: skipped, said
    assert status == 0 and err == '' and 'step check: off (the run at half the step would exceed' in out
    status, out, err = _Run(capsys, 'simulate', '--quiet', '--json', *SHORT, '--max-steps', limit)
    assert json.loads(out)['stepCheck']['reason'] == 'maxSteps' and not json.loads(out)['stepCheck']['checked']


def test_a_verdict_that_flips_with_the_step_is_unresolved_in_sweep(monkeypatch):
    p = GetPreset('reel-P1')
    _FlipWithStep(monkeypatch, 0.75 * RecommendedStepSize(ResolveDrive(parameters=p)))
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
    p = GetPreset('reel-P1')
    _FlipWithStep(monkeypatch, 0.75 * RecommendedStepSize(ResolveDrive(parameters=p)))
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


def test_the_chatter_ratio_decides_as_the_chatter_rule():
    """ChatterRatio >= 1 where the amplitude counts, which it must where Chatter says yes (reel-P7: lift, lowering
    chatter, chattering lift), and CloseVerdicts picks the windows within VERDICT_FACTOR of the threshold."""
    p = GetPreset('reel-P7')
    result = SimulateReelChanger(ResolveDrive(parameters=p), endTime=4.4, progress=False)
    windows = [(0., 1.8), (2.2, 3.8), (3.8, 4.4)]
    ratios = [result.ChatterRatio(t0, t1) for t0, t1 in windows]
    assert [r >= 1. for r in ratios] == [result.ChatterVerdict(t0, t1).state != 'none' for t0, t1 in windows]
    assert all(r >= 1. for r, (t0, t1) in zip(ratios, windows) if result.Chatter(t0, t1))
    assert ratios[0] < 0.1 and ratios[1] > 1.
    assert CloseVerdicts(result, windows) == [i for i, r in enumerate(ratios) if 1 / VERDICT_FACTOR < r < VERDICT_FACTOR]


def _RatioOfWindow(monkeypatch, ratio):
    """Make every window's chatter ratio ``ratio`` (the verdicts themselves stay those of the run)."""
    monkeypatch.setattr(SimulationResult, 'ChatterRatio', lambda self, t0, t1: ratio)


@pytest.mark.parametrize('ratio, checked', [(0.3, False), (0.7, True), (1.5, True), (3., False)])
def test_by_default_the_step_is_checked_only_where_a_verdict_is_close(ratio, checked, capsys, tmp_path, monkeypatch):
    """P1 has a small linear margin; the run at half the step follows only where a window's verdict is close."""
    monkeypatch.chdir(tmp_path)
    _RatioOfWindow(monkeypatch, ratio)
    status, out, err = _Run(capsys, 'simulate', '--quiet', '--json', *SHORT)
    assert status == 0, err
    check = json.loads(out)['stepCheck']
    assert check['checked'] is checked and check['closeWindows'] == ([0, 1] if checked else [])
    assert check['reason'] == ('default' if checked else 'clearVerdicts')
    status, out, err = _Run(capsys, 'simulate', '--quiet', *SHORT)
    assert ('step check: verdicts compared' in out) is checked
    assert ("every window's verdict is clear" in out) is not checked
    row = RunPoint(Study(GetPreset('reel-P1'), [Variation('J1', (0.2,))], windows=[(0., 0.5), (0.5, 1.)],
                         endTime=1.).Task(0))
    assert row['status'] == 'ok' and row['stepChecked'] is checked
    assert ('w0.halfStep.chatter' in row) is checked


def test_an_explicit_step_check_ignores_clear_verdicts(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    _RatioOfWindow(monkeypatch, 100.)
    status, out, err = _Run(capsys, 'simulate', '--quiet', '--json', '--check-step', *SHORT)
    assert json.loads(out)['stepCheck']['checked'] is True
    row = RunPoint(Study(GetPreset('reel-P1'), [Variation('J1', (0.2,))], windows=[(0., 0.5)], endTime=1.,
                         checkStep=True).Task(0))
    assert row['stepChecked'] is True and 'w0.halfStep.chatter' in row
