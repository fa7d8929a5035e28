"""validation/chatter_corpus.py: agreement counted over the resolvable phases only, and the script end to end."""
import csv

import numpy as np
import pytest

from validation.chatter_corpus import FULL, QUICK, RESOLVABLE, DrawDrive, DutyWindows, Main, Summarize


def _Row(drive, phase, maxRealPart, chatter, plateau=1., state=None):
    growth = maxRealPart * plateau
    state = state or ('chatter' if chatter else 'none')
    return {'drive': drive, 'phase': phase, 'maxRealPart': maxRealPart, 'growthOverPhase': growth,
            'resolvable': abs(growth) >= RESOLVABLE, 'linearStable': maxRealPart < 0, 'simulatedChatter': chatter,
            'simulatedState': state, 'agree': chatter == (maxRealPart >= 0) if state != 'undecided' else None,
            'error': ''}


def test_agreement_counts_resolvable_points_and_lists_the_others_by_distance():
    rows = [_Row(0, 'lifting', -10., False), _Row(0, 'lowering', 20., True),      # resolvable, agree
            _Row(1, 'lifting', -5., True), _Row(1, 'lowering', -4., False),       # one disagreement
            _Row(2, 'lifting', -1., True), _Row(2, 'lowering', 0.5, False),       # not resolvable (|growth| < 3)
            dict(_Row(3, 'lifting', -9., False), error='simulation: diverged'),
            _Row(4, 'lifting', -8., False, state='undecided')]                   # resolvable, undecided: not counted
    s = Summarize(rows)
    assert [r['drive'] for r in s['undecided']] == [4]
    assert (s['points']['resolvable'], s['points']['agree']) == (4, 3)
    assert [(r['drive'], r['phase']) for r in s['disagree']] == [(1, 'lifting')]
    assert [r['growthOverPhase'] for r in s['others']] == [0.5, -1.]             # nearest the boundary first
    assert len(s['failed']) == 1
    # per drive: 0 unstable and chatters (agree), 1 stable but chatters (disagree); 2 decided by 0.5 1/s: not counted
    assert (s['drives']['resolvable'], s['drives']['agree']) == (2, 1)


def test_the_corpus_is_seeded_and_has_both_phases():
    first = [DrawDrive(np.random.default_rng(5)) for _ in range(2)]
    again = [DrawDrive(np.random.default_rng(5)) for _ in range(2)]
    assert first == again
    w = DutyWindows(first[0])
    assert w['lifting'][1] - w['lifting'][0] == pytest.approx(FULL['plateau'])
    assert w['lifting'][1] < w['lowering'][0] < w['lowering'][1] < w['end']
    table = dict(first[0]['motorSpeedOverTime'])
    assert table[w['lifting'][0]] > 0 > table[w['lowering'][0]] and first[0]['loadTorque'] < 0   # lift, then lower


def test_quick_run_writes_the_report_and_one_row_per_phase(tmp_path, capsys):
    report, table = tmp_path / 'corpus.md', tmp_path / 'corpus.csv'
    assert Main(['--quick', '--quiet', '--report', str(report), '--csv', str(table)]) in (0, 1)
    rows = list(csv.DictReader(table.open()))
    # the first group: lifting and lowering; the second: lifting, lowering after the load's reversal, lifting back
    assert len(rows) == 2 * QUICK['drives'] + 3 * QUICK['extra'] and {r['phase'] for r in rows} == {'lifting', 'lowering'}
    assert all(r['longState'] for r in rows if int(r['drive']) >= 1000)
    text = report.read_text()
    assert 'CHATTER_RULE.md' in text and f"{QUICK['drives'] + QUICK['extra']} drives" in text
    assert 'Short windows against the long simulations' in text
    assert sorted(p.name for p in tmp_path.iterdir()) == ['corpus.csv', 'corpus.md']


@pytest.mark.messages
def test_quick_needs_a_report_path(capsys):
    with pytest.raises(SystemExit) as exit:
        Main(['--quick'])
    assert exit.value.code == 2
    assert '--quick needs --report PATH' in capsys.readouterr().err
