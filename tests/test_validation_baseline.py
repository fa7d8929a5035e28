"""The validation's one way in (``python -m validation``, no ``exudyn-worm validate``, no ``sys.path`` edits, no
import cycle) and its regression mode: ``--baseline FILE`` reports every check whose verdict changed or whose value
moved by more than the row's tolerance and exits 0 when none did; ``--record-baseline FILE`` records one."""
import ast
import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

from validation.baseline import BaselineRecord, CompareWithBaseline, LoadBaseline, Tolerance
from validation.model import Check, ReferenceRow, ValidationSummary
from validation.runner import ReadingInterval
import validation.runner as runner
from validation.cli import Main
import exudyn_worm.cli.main as cli

ROOT = Path(__file__).resolve().parents[1]


def _Row(rowId, published='110', rule='printed', kind='value'):
    return ReferenceRow(rowId, 'g', 'a quantity', None, float(published) if published[0].isdigit() else 3.,
                        published, 'rad/s^2', 'Fig. 8', rule, kind, '', frozenset(), '', Path('reference.csv'))


def _Check(row, computed, verdict=None):
    interval = ReadingInterval(row.rule, row.publishedText)
    holds = interval[0] <= computed <= interval[1]
    return Check(row, computed, interval, verdict or ('PASS' if holds else 'FAIL'), holds)


def _Summary(*checks, mode='quick'):
    return ValidationSummary(list(checks), ['validation ...'], mode=mode)


ROWS = {'peak': _Row('peak', '110'), 'chatter': _Row('chatter', '1', 'yes-no'), 'many': _Row('many', 'many', 'many-times'),
        'about': _Row('about', '42', 'about')}


def _Base():
    return _Summary(_Check(ROWS['peak'], 112.), _Check(ROWS['chatter'], 1.), _Check(ROWS['many'], 2.5),
                    _Check(ROWS['about'], 44.))


def test_tolerance_is_the_rows():
    peak, chatter, many, about = _Base().checks
    assert Tolerance(peak) == pytest.approx(5.)           # "110": +- 5 (trailing zero is a placeholder)
    assert Tolerance(about) == pytest.approx(4.2)         # "about 42": +- 10 %
    assert Tolerance(chatter) == 0.5 and Tolerance(many) == 0.5     # exact and half-open rows: half a unit


def test_unchanged_run_reports_nothing():
    baseline = json.loads(json.dumps(BaselineRecord(_Base())))          # through JSON, as on disk
    assert CompareWithBaseline(_Base(), baseline) == []
    moved = _Summary(_Check(ROWS['peak'], 114.9), _Check(ROWS['chatter'], 1.), _Check(ROWS['many'], 2.9),
                     _Check(ROWS['about'], 40.))                        # all within the rows' tolerances
    assert CompareWithBaseline(moved, baseline) == []


def test_changed_verdict_and_value_are_reported():
    baseline = BaselineRecord(_Base())
    now = _Summary(_Check(ROWS['peak'], 117.5),                           # moved 5.5 > 5, verdict PASS -> FAIL
                   _Check(ROWS['chatter'], 0.),                           # yes -> no
                   _Check(ROWS['many'], 2.5, verdict='DIFFERS'),          # same value, other verdict
                   _Check(ROWS['about'], 30.))                            # moved 14 > 4.2, still... FAIL now
    lines = CompareWithBaseline(now, baseline)
    assert lines[0] == 'CHANGED peak: verdict PASS -> FAIL; computed 112 -> 117.5 (tolerance 5)'
    assert lines[1] == 'CHANGED chatter: verdict PASS -> FAIL; computed 1 -> 0 (tolerance 0.5)'
    assert lines[2] == 'CHANGED many: verdict FAIL -> DIFFERS; computed 2.5 -> 2.5'
    assert lines[3].startswith('CHANGED about: verdict PASS -> FAIL; computed 44 -> 30')
    assert len(lines) == 4


def test_value_moved_with_the_same_verdict_is_reported():
    baseline = BaselineRecord(_Summary(_Check(ROWS['many'], 1.)))      # FAIL ("many" needs >= 3)
    lines = CompareWithBaseline(_Summary(_Check(ROWS['many'], 2.)), baseline)
    assert lines == ['CHANGED many: computed 1 -> 2 (tolerance 0.5)']


def test_new_missing_and_non_finite_checks():
    baseline = BaselineRecord(_Summary(_Check(ROWS['peak'], 112.), _Check(ROWS['chatter'], math.nan, 'FAIL')))
    assert json.loads(json.dumps(baseline, allow_nan=False))['checks']['chatter']['computed'] is None
    same = _Summary(_Check(ROWS['peak'], 112.), _Check(ROWS['chatter'], math.nan, 'FAIL'))
    assert CompareWithBaseline(same, baseline) == []                   # NaN then and now: unchanged
    lines = CompareWithBaseline(_Summary(_Check(ROWS['chatter'], 1.), _Check(ROWS['about'], 42.)), baseline)
    assert lines == ['CHANGED chatter: verdict FAIL -> PASS; computed nan -> 1 (tolerance 0.5)',
                     'NEW     about: PASS, computed 42 (not in the baseline)',
                     'MISSING peak: PASS, computed 112 in the baseline, not in this run']


def test_load_baseline_checks_file_and_mode(tmp_path):
    path = tmp_path / 'b.json'
    path.write_text(json.dumps(BaselineRecord(_Base())))
    assert LoadBaseline(path, 'quick')['mode'] == 'quick'
    with pytest.raises(ValueError, match=r"recorded in quick mode, this run is in default mode; run 'python -m "
                                         r"validation --quick --baseline"):
        LoadBaseline(path, 'default')
    (tmp_path / 'x.json').write_text('{"checks": 1}')
    for bad, text in ((tmp_path / 'missing.json', 'cannot read it'), (tmp_path / 'x.json', 'not a validation baseline')):
        with pytest.raises(ValueError, match=text):
            LoadBaseline(bad)


# --- the command line --------------------------------------------------------------------------------------
@pytest.fixture
def fakeRun(monkeypatch):
    """python -m validation with a stand-in run: returns the summary set in fakeRun['summary']."""
    state = {'summary': _Base()}

    def Fake(reportPath=None, quick=False, full=False, quiet=None):
        state['mode'] = 'quick' if quick else 'full' if full else 'default'
        return state['summary']
    monkeypatch.setattr(runner, 'RunValidation', Fake)
    return state


def _Main(capsys, *argv):
    status = Main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return status, out, err


def test_record_then_compare_on_the_command_line(capsys, tmp_path, fakeRun):
    path = tmp_path / 'baseline.json'
    status, out, err = _Main(capsys, '--quick', '--record-baseline', path)
    assert status == 1 and path.is_file() and f'wrote {path}' in err           # recording: the plain run's status
    assert set(json.loads(path.read_text())['checks']) == set(ROWS)
    status, out, err = _Main(capsys, '--quick', '--baseline', path)
    assert status == 0 and out.splitlines()[1].endswith('no check changed')
    fakeRun['summary'] = _Summary(_Check(ROWS['peak'], 112.), _Check(ROWS['chatter'], 0.), _Check(ROWS['many'], 2.5),
                                  _Check(ROWS['about'], 44.))
    status, out, err = _Main(capsys, '--quick', '--baseline', path)
    lines = out.splitlines()
    assert status == 1 and lines[1].endswith('1 check(s) changed') and lines[2].startswith('CHANGED chatter:')
    assert len(lines) == 3                                                   # only the rows that changed


def test_baseline_of_another_mode_is_refused_before_computing(capsys, tmp_path, fakeRun):
    path = tmp_path / 'baseline.json'
    path.write_text(json.dumps(BaselineRecord(_Base())))
    status, out, err = _Main(capsys, '--baseline', path)
    assert status == 2 and 'mode' not in fakeRun and err.count('\n') == 1
    assert err.startswith('python -m validation: error: --baseline') and '--quick' in err
    status, out, err = _Main(capsys, '--quick', '--baseline', path, '--record-baseline', tmp_path / 'b2.json')
    assert status == 2 and 'not allowed with argument' in err


def test_committed_quick_baseline_is_a_quick_baseline():
    data = LoadBaseline(ROOT / 'validation' / 'baseline-quick.json', 'quick')
    assert len(data['checks']) > 50 and all(set(c) == {'verdict', 'computed', 'tolerance'} for c in data['checks'].values())


# --- one way in ----------------------------------------------------------------------------------------------
def _Imports(path: Path):
    names = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            names.add(('.' * node.level) + (node.module or ''))
        elif isinstance(node, ast.Import):
            names.update(a.name for a in node.names)
    return names


def test_package_does_not_reach_into_the_checkout():
    """No subcommand imports the validation or edits sys.path (it could not work in an installed package)."""
    assert 'validate' not in cli.COMMAND_MODULES
    for path in (ROOT / 'exudyn_worm').rglob('*.py'):
        text = path.read_text()
        assert 'sys.path' not in text and not any(n.startswith('validation') for n in _Imports(path)), path


def test_validation_layers_have_no_cycle():
    """model <- runner <- report? No: model <- report <- runner <- baseline <- cli; nothing imports upwards."""
    imports = {p.stem: _Imports(p) for p in (ROOT / 'validation').glob('*.py')}
    assert not any(n.startswith('.') for n in imports['model'])                 # the lowest layer
    assert not {'.runner', '.baseline', '.cli'} & imports['report']
    assert not {'.baseline', '.cli'} & imports['runner']
    assert '.cli' not in imports['baseline']
    assert not any('exudyn_worm.cli' in n for n in imports['cli'])        # no options from the package


def test_python_m_validation_runs_from_the_checkout(tmp_path):
    result = subprocess.run([sys.executable, '-m', 'validation', '--help'], cwd=ROOT, capture_output=True, text=True,
                            timeout=120)
    assert result.returncode == 0 and '--baseline' in result.stdout and '--record-baseline' in result.stdout
