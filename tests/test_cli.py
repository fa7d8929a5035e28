"""Tests of the exudyn-worm command line (exudyn_worm.cli.main), run in-process with Main([...])."""
import json
import os
import re
import subprocess
import sys
import types

import pytest
from numpy.testing import assert_allclose

import exudyn_worm
from exudyn_worm.cli import main as cli
from exudyn_worm.cli.main import Main
from exudyn_worm.model.stability import AnalyzeStability
import exudyn_worm.analysis.stability.linearization as linearization

S_KEYS = {'b', 'hurwitz', 'eigenvalues', 'frequenciesHz', 'lehrDamping', 'stable'}
# the speed-dependent friction added 'friction' (the law), 'selfLockingVerdict' (static/dynamic) and 'operatingPoint' (None without load/speed)
TOP_KEYS = {'ratio', 'frictionAngle', 'selfLocking', 'efficiency', 'S', 'fuesgenLimit', 'firstCriterionLimit', 'hint',
            'stable', 'instability', 'friction', 'selfLockingVerdict', 'operatingPoint',
            'geometry', 'method', 'model', 'components', 'maxRealPart', 'frequencyHz', 'operatingPoints', 'deciding',
            'decidingText', 'dangerous', 'selfLockingAtOperatingPoints'}


def Run(capsys, *argv):
    """Main(argv) in-process; returns (exit status, stdout, stderr)."""
    rc = Main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def RunJson(capsys, *argv):
    rc, out, err = Run(capsys, 'stability', '--json', *argv)
    assert rc == 0, err
    return json.loads(out)


# every test runs in an empty directory and checks that nothing was written to it (conftest)
pytestmark = pytest.mark.usefixtures('emptyWorkingDirectory')


# --- JSON output -----------------------------------------------------------------------------------
def test_json_schema(capsys):
    rc, out, err = Run(capsys, 'stability', '--preset', 'reel-P1', '--json')
    assert rc == 0 and err == ''
    data = json.loads(out)                      # stdout holds exactly one JSON object
    assert isinstance(data, dict)
    assert set(data) == TOP_KEYS
    assert set(data['efficiency']) == {'wormDriving', 'wheelDriving'}
    assert set(data['S']) == {'+1', '-1'}
    for entry in data['S'].values():
        assert set(entry) == S_KEYS
        assert len(entry['b']) == 4 and len(entry['hurwitz']) == 3
        assert len(entry['eigenvalues']) == 4 and all(len(ev) == 2 for ev in entry['eigenvalues'])
        assert len(entry['frequenciesHz']) == 2 and len(entry['lehrDamping']) == 2
        assert isinstance(entry['stable'], bool)
    assert isinstance(data['stable'], bool) and isinstance(data['selfLocking'], bool)
    for key in ('ratio', 'frictionAngle', 'fuesgenLimit', 'firstCriterionLimit'):
        assert isinstance(data[key], float)


def test_reel_p1_paper_section_3_1(capsys):
    data = RunJson(capsys, '--preset', 'reel-P1')
    assert data['S']['+1']['stable'] is True
    assert data['S']['-1']['stable'] is False
    assert data['stable'] is False and data['selfLocking'] is True
    assert data['ratio'] == pytest.approx(63., abs=0.01)                  # set (28): u = 63
    # paper section 3.1, set (28), S = -1: b1 = 13.615 s^-1, b2 = 1.279e5 s^-2, b3 = 9.004e5 s^-3,
    # b4 = 4.224e9 s^-4; tolerance: half a unit of the last printed digit
    b = data['S']['-1']['b']
    for value, printed, halfUnit in zip(b, (13.615, 1.279e5, 9.004e5, 4.224e9), (5e-4, 50., 50., 5e5)):
        assert_allclose(value, printed, rtol=0, atol=halfUnit)
    assert data['S']['-1']['hurwitz'][2] < 0                               # (19) violated: unstable
    assert data['S']['-1']['hurwitz'][0] > 0                               # (17) holds


def test_default_preset_is_reel_p1(capsys):
    assert RunJson(capsys) == RunJson(capsys, '--preset', 'reel-P1')


@pytest.mark.parametrize('preset, stable', [
    ('reel-P1', False), ('reel-P2', True), ('reel-P3', True), ('reel-P4', True), ('reel-P5', True),
    ('reel-P6', False), ('reel-P7', False)])
def test_presets_classified_as_in_the_paper(capsys, preset, stable):
    # Figure 4 and sections 3.2.2-3.2.4: P1, P6, P7 chatter; P2-P5 do not
    data = RunJson(capsys, '--preset', preset)
    assert data['stable'] is stable
    assert data['S']['+1']['stable'] is True


def test_p6_with_higher_mesh_damping_is_stable(capsys):
    # paper section 3.2.4: P6 (J1 = 0.2, kT = 12000, D_TV = 2) moves to the stable region for D_V = 0.056
    assert RunJson(capsys, '--preset', 'reel-P6', '--set', 'DV=0.056')['stable'] is True


@pytest.mark.parametrize('option', ['kT=7 kN*m', 'kT=7000 N*m/rad', 'gamma=5.3228 deg', 'mu=0.132',
                                    'alphaN=20 deg', 'J1=100 g*m^2', 'r1=18.05 mm', 'DV=1.4 %'])
def test_units_reproduce_the_preset(capsys, option):
    a, b = RunJson(capsys, '--set', option), RunJson(capsys)
    assert a['S']['-1']['b'] == pytest.approx(b['S']['-1']['b'], rel=1e-12)
    assert a['stable'] == b['stable']


def test_units_that_do_not_change_stability(capsys):
    reference = RunJson(capsys)
    for option in ('backlash=0.5 mm', 'motorSpeed=472.5 rpm', 'loadMass=175 kg', 'leverArm=1200 mm'):
        assert RunJson(capsys, '--set', option) == reference


def test_set_changes_the_result(capsys):
    assert RunJson(capsys, '--set', 'J1=0.3')['stable'] is True          # = reel-P2
    assert RunJson(capsys, '--set', 'kT=14 kN*m')['stable'] is True      # = reel-P4


def test_config_file(capsys, tmp_path):
    path = tmp_path / 'p6.toml'
    path.write_text('preset = "reel-P6"\n[parameters]\nDV = "5.6 %"\n')
    assert RunJson(capsys, '--config', str(path))['stable'] is True
    assert RunJson(capsys, '--config', str(path), '--set', 'DV=0.014')['stable'] is False
    assert RunJson(capsys, '--config', str(path), '--preset', 'reel-P1') == \
        RunJson(capsys, '--preset', 'reel-P1', '--set', 'DV=0.056')


# --- human output ----------------------------------------------------------------------------------
def test_table_unstable(capsys):
    rc, out, err = Run(capsys, 'stability', '--preset', 'reel-P1')
    assert rc == 0 and err == ''
    for text in ('transmission ratio u', 'friction angle rho [deg]', 'self-locking', 'efficiency, worm driving',
                 'efficiency, wheel driving', 'S = +1', 'S = -1', 'b1 [1/s]', 'b4 [1/s^4]', '(17)', '(18)',
                 '(19)', 'eigenvalue 4', 'frequency f2 [Hz]', 'Lehr damping D2', 'Fuesgen limit (21)',
                 'first criterion limit (20)', 'actual J1/J2', 'Contact states: UNSTABLE for S = -1',
                 'Verdict: UNSTABLE (chatter expected) (decided by the lowering phase', '13.615'):
        assert text in out, text
    hints = [line for line in out.splitlines() if line.startswith('Hint:')]
    assert len(hints) == 1 and 'J1' in hints[0] and 'kT' in hints[0]


def test_hint_values_are_stable_and_unstable_inside(capsys):
    rc, out, _ = Run(capsys, 'stability')
    hint = next(line for line in out.splitlines() if line.startswith('Hint:'))
    # the paper's P2 (J1 = 0.3), P3 (0.033), P4 (kT = 14000), P5 (1400) lie beyond the reported limits
    j1Low, j1High = (float(x) for x in re.findall(r'J1 [<>]= ([0-9.e+-]+) kg', hint))
    kTLow, kTHigh = (float(x) for x in re.findall(r'kT [<>]= ([0-9.e+-]+) N', hint))
    assert 0.033 < j1Low < 0.1 < j1High < 0.3
    assert 1400 < kTLow < 7000 < kTHigh < 14000
    for option, stable in ((f'J1={j1Low * 0.98}', True), (f'J1={j1Low * 1.02}', False),
                           (f'J1={j1High * 1.02}', True), (f'J1={j1High * 0.98}', False),
                           (f'kT={kTLow * 0.98}', True), (f'kT={kTHigh * 1.02}', True)):
        assert RunJson(capsys, '--set', option)['stable'] is stable, option


def test_table_stable(capsys):
    rc, out, err = Run(capsys, 'stability', '--preset', 'reel-P2')
    assert rc == 0 and 'Verdict: STABLE' in out and 'Hint:' not in out


def test_help(capsys):
    rc, out, _ = Run(capsys, '--help')
    assert rc == 0 and 'stability' in out and 'sweep' in out
    assert 'validate' not in out          # removed: the validation runs from the checkout, python -m validation
    rc, out, _ = Run(capsys, 'stability', '--help')
    assert rc == 0 and '--preset' in out and '--config' in out and '--set' in out and '--json' in out
    rc, out, _ = Run(capsys, '--version')
    assert rc == 0 and exudyn_worm.__version__ in out


# --- errors: one line on stderr, exit status 2 -----------------------------------------------------
# case: the words that say it is this error and not another one (a stale case that fails on 'unrecognized
# arguments' instead of its own error would pass the exit-2 checks alone)
BAD_CASES = {
    'no command': 'the following arguments are required: COMMAND',
    'unknown command': "invalid choice: 'bogus'",
    'unknown option': 'unrecognized arguments: --bogus',
    'bad method': "argument --method: invalid choice: 'fem'",
    'unknown preset': "unknown preset 'reel-P9'",
    'unknown key': "unknown parameter 'foo'",
    'no equals sign': "expected KEY=VALUE",
    'malformed value': "'J1=0.1.2'",
    'non-finite value': "'J1' must be finite, got 'nan'",
    'wrong unit': "'kT' must be in N*m/rad",
    'angle for a ratio': "'mu' must be a dimensionless number",
    'negative inertia': "'J1' must be > 0 kg*m^2, got -0.1",
    'zero stiffness': "'kT' must be > 0 N*m/rad, got 0",
    'pitch angle out of range': "'gamma' must be in (0, pi/2) rad",
    'missing parameters': 'missing parameter(s) J1, kT',
    'conflicting overrides': "both 'mu' and 'rho' are given",
    'missing config': 'missing.toml',
    'config is a directory': 'is a folder, expected a TOML drive file',
    'malformed config': 'not valid TOML',
    'unknown key in config': "unknown parameter 'foo'",
    'wrong unit in config': "'kT' must be in N*m/rad",
    'missing --set value': 'argument --set: expected one argument',
    'removed validate command': "invalid choice: 'validate'",
    # the messages of the fault corpus: an empty preset name was taken as the default, J1 = 1e308 blamed dT,
    # z1 = 1.5 asked for the other keys of its geometry form
    'empty preset': "'preset' must name a preset, got an empty name ''; expected one of: chart, reel-P1",
    'huge inertia': "'J1' = 1e+308 kg*m^2 is out of range (it must be > 0 kg*m^2 and of a size a drive can have)",
    'fractional starts': "'z1' must be a whole number >= 1 (a count of teeth or starts), got 1.5",
}


def _Bad(tmp_path):
    """Argument lists of bad input, keyed by BAD_CASES; config files are written to ``tmp_path``."""
    malformed = tmp_path / 'malformed.toml'
    malformed.write_text('[parameters\nJ1 = 1\n')
    unknown = tmp_path / 'unknown.toml'
    unknown.write_text('[parameters]\nfoo = 1\n')
    wrongUnit = tmp_path / 'unit.toml'
    wrongUnit.write_text('[parameters]\nkT = "7 kg"\n')
    return {
        'no command': [],
        'unknown command': ['bogus'],
        'unknown option': ['stability', '--bogus'],
        'bad method': ['stability', '--method', 'fem'],
        'unknown preset': ['stability', '--preset', 'reel-P9'],
        'unknown key': ['stability', '--set', 'foo=1'],
        'no equals sign': ['stability', '--set', 'J1'],
        'malformed value': ['stability', '--set', 'J1=0.1.2'],
        'non-finite value': ['stability', '--set', 'J1=nan'],
        'wrong unit': ['stability', '--set', 'kT=7 kg'],
        'angle for a ratio': ['stability', '--set', 'mu=8 deg'],
        'negative inertia': ['stability', '--set', 'J1=-0.1'],
        'zero stiffness': ['stability', '--set', 'kT=0'],
        'pitch angle out of range': ['stability', '--set', 'gamma=95 deg'],
        'missing parameters': ['stability', '--preset', 'chart'],
        'conflicting overrides': ['stability', '--set', 'mu=0.13', '--set', 'rho=8 deg'],
        'missing config': ['stability', '--config', str(tmp_path / 'missing.toml')],
        'config is a directory': ['stability', '--config', str(tmp_path)],
        'malformed config': ['stability', '--config', str(malformed)],
        'unknown key in config': ['stability', '--config', str(unknown)],
        'wrong unit in config': ['stability', '--config', str(wrongUnit)],
        'missing --set value': ['stability', '--set'],
        'removed validate command': ['validate', '--quick'],
        'empty preset': ['stability', '--preset', ''],
        'huge inertia': ['stability', '--set', 'J1=1e308'],
        'fractional starts': ['stability', '--set', 'z1=1.5'],
    }


@pytest.mark.messages
@pytest.mark.parametrize('case', BAD_CASES)
@pytest.mark.parametrize('json_', [False, True])
def test_errors_one_line_exit_2(capsys, tmp_path, case, json_):
    bad = _Bad(tmp_path)
    assert set(bad) == set(BAD_CASES)
    argv = bad[case]
    if json_ and argv[:1] == ['stability']:
        argv = ['stability', '--json'] + argv[1:]
    rc, out, err = Run(capsys, *argv)
    assert rc == 2
    assert out == ''
    assert err.startswith('exudyn-worm: error: ') and err.endswith('\n')
    assert BAD_CASES[case] in err, (case, err)
    assert err.count('\n') == 1, err
    assert 'Traceback' not in err


@pytest.mark.messages
def test_error_messages_are_specific(capsys, tmp_path):
    expected = {'unknown preset': ['reel-P9', 'reel-P1'],
                'unknown key': ["'foo'", 'alphaN', 'motorSpeed'],
                'wrong unit': ["'kT'", 'N*m/rad', '7 kg', '[mass]'],
                'negative inertia': ["'J1'", '> 0', 'kg*m^2', '-0.1'],
                'pitch angle out of range': ["'gamma'", '(0, pi/2) rad'],
                'missing config': ['missing.toml'],
                'malformed config': ['malformed.toml', 'not valid TOML'],
                'missing parameters': ['J1', 'kT']}
    bad = _Bad(tmp_path)
    for case, fragments in expected.items():
        _, _, err = Run(capsys, *bad[case])
        for fragment in fragments:
            assert fragment in err, (case, fragment, err)


def test_exudyn_method_uses_linearization(capsys, monkeypatch):
    calls = []

    def Fake(drive, useSymbolic=True, operatingPoint=None):
        calls.append(operatingPoint)
        print('noise from the solver')              # must not reach stdout with --json
        return AnalyzeStability(drive, operatingPoint)

    monkeypatch.setattr(linearization, 'ExudynStabilityAnalysis', Fake)
    rc, out, err = Run(capsys, 'stability', '--method', 'exudyn', '--json')
    assert rc == 0 and [op.S for op in calls] == [1, -1]          # one linearization per operating point
    assert json.loads(out) == {**RunJson(capsys), 'method': 'exudyn', 'model': 'linearized'}
    assert 'noise from the solver' in err


def test_exudyn_method_real(capsys):
    for preset in ('reel-P1', 'reel-P2'):
        exu = RunJson(capsys, '--method', 'exudyn', '--preset', preset)
        ana = RunJson(capsys, '--preset', preset)
        assert exu['stable'] == ana['stable']
        assert_allclose(exu['S']['-1']['b'], ana['S']['-1']['b'], rtol=1e-6)


# --- registry --------------------------------------------------------------------------------------
def test_registry_adds_a_subcommand(capsys, monkeypatch):
    def Add(parser):
        parser.add_argument('--duration', type=float, default=8.)

    def RunDemo(args):
        drive = cli.WholeDriveFromArgs(args)
        print(f"{args.duration} {drive.elastic.J1} {args.json}")
        return 0

    monkeypatch.setattr(cli, 'SUBCOMMANDS', cli.SUBCOMMANDS + [cli.Subcommand('demo', 'demo', Add, RunDemo)])
    assert Run(capsys, 'demo', '--duration', '2', '--set', 'J1=0.3', '--json') == (0, '2.0 0.3 True\n', '')
    rc, out, err = Run(capsys, 'demo', '--set', 'J1=-1')
    assert rc == 2 and err.startswith('exudyn-worm: error: ')


# --- the console entry in a subprocess -------------------------------------------------------------
def _Subprocess(*argv):
    env = dict(os.environ, PYTHONWARNINGS='ignore')
    return subprocess.run([sys.executable, '-m', 'exudyn_worm', *argv], capture_output=True, text=True,
                          cwd=os.getcwd(), env=env, timeout=300)


def test_python_m_exudyn_worm_json():
    result = _Subprocess('stability', '--preset', 'reel-P1', '--json')
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    assert set(data) == TOP_KEYS and data['stable'] is False
    assert 'Traceback' not in result.stderr


@pytest.mark.messages
def test_python_m_exudyn_worm_error():
    result = _Subprocess('stability', '--set', 'kT=7 kg')
    assert result.returncode == 2 and result.stdout == ''
    assert result.stderr.startswith('exudyn-worm: error: ') and result.stderr.count('\n') == 1


@pytest.mark.parametrize('command', ['stability', 'check'])
def test_drive_at_the_edge_of_the_ranges_gets_an_answer(capsys, command):
    """J1 = 1e-12 is accepted; the hint's and the check's scans probed J1 / 10 and ended in a traceback
    (stability) or an error about J1 = 1e-13, a value the user never gave (check)."""
    assert Main([command, '--set', 'J1=1e-12']) == 0
    captured = capsys.readouterr()
    assert 'Traceback' not in captured.err and '1e-13' not in captured.out + captured.err
    # J1 = 1e-12: eigenvalue 2 of S = -1 is real and positive (the paper's table: 2.7e10 + 0i 1/s): a divergence
    assert ('Verdict: DIVERGENT' in captured.out) if command == 'stability' else ('No single parameter' in captured.out)


def test_wide_table_cells_keep_a_gap(capsys):
    assert Main(['stability', '--set', 'J1=1e-6']) == 0
    rows = [line for line in capsys.readouterr().out.splitlines() if line.strip().startswith('eigenvalue 3')]
    assert rows and 'i ' in rows[0].split('[1/s]')[1].strip()           # '... + 60344.930i 12322.547 + ...'
