"""Tests of whole-drive TOML files (exudyn_worm.params.drivefile through exudyn_worm.drive.config)."""
import doctest
import json
import math
import re
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import LoadScript
from exudyn_worm.params import drivefile
from exudyn_worm.drive.config import LoadConfig, ResolveParameters
from exudyn_worm.params.drivefile import DRIVE_FILE_TABLES, DRIVE_SIDE_KEYS, DriveSideKey
from exudyn_worm.drive.presets import AxialBearingFromParameters, DriveSideChain, GetPreset, PARAMETER_UNITS, PRESETS

ROOT = Path(__file__).resolve().parents[1]
DRIVES = ROOT / 'examples' / 'drives'


def _Write(tmp_path, text, name='drive.toml'):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_doctests():
    assert doctest.testmod(drivefile, raise_on_error=True).attempted > 0


def test_every_file_key_maps_to_a_parameter_key():
    for table, keys in DRIVE_FILE_TABLES.items():
        for fileKey, key in keys.items():
            assert key in PARAMETER_UNITS, (table, fileKey, key)
    for index in range(3):
        for fileKey in DRIVE_SIDE_KEYS:
            assert DriveSideKey(fileKey, index) in PARAMETER_UNITS


@pytest.mark.parametrize('name', sorted(PRESETS))
def test_example_file_per_preset_gives_the_preset(name):
    """examples/drives/NAME.toml describes the whole drive: it reproduces the preset without inheriting."""
    path = DRIVES / f'{name}.toml'
    cfg = LoadConfig(path)
    assert cfg['wholeDrive'] and cfg['preset'] is None
    expected = GetPreset(name)
    assert set(cfg['parameters']) == set(expected)
    for key, value in expected.items():
        assert cfg['parameters'][key] == pytest.approx(value, rel=1e-12, abs=0.), key
    assert ResolveParameters(config=path).keys() == expected.keys()


def test_whole_drive_file_inherits_nothing_unless_it_names_a_preset(tmp_path):
    path = _Write(tmp_path, '[worm]\ninertia = "0.3 kg*m^2"\n')
    assert ResolveParameters(config=path) == {'J1': 0.3}
    named = _Write(tmp_path, 'preset = "reel-P1"\n[worm]\ninertia = 0.3\n', 'named.toml')
    assert ResolveParameters(config=named) == {**GetPreset('reel-P1'), 'J1': 0.3}
    assert ResolveParameters('reel-P7', config=path) == {**GetPreset('reel-P7'), 'J1': 0.3}
    flat = _Write(tmp_path, '[parameters]\nJ1 = 0.3\n', 'flat.toml')      # the flat form keeps its default
    assert ResolveParameters(config=flat) == {**GetPreset('reel-P1'), 'J1': 0.3}


def test_units_and_alternative_forms(tmp_path):
    path = _Write(tmp_path, '[gear]\nfrictionAngle = "8 deg"\nmeshDamping = "21.47 kN*s/m"\n'
                            '[driveShaft]\ndamping = "0.741 N*m*s"\n[motor]\nspeed = "472.5 rpm"\n')
    p = LoadConfig(path)['parameters']
    assert p == {'rho': pytest.approx(math.radians(8)), 'dV': pytest.approx(21470.), 'dT': pytest.approx(0.741),
                 'motorSpeed': pytest.approx(472.5 * 2 * math.pi / 60)}


def test_drive_side_keys_are_numbered_from_four():
    assert [DriveSideKey(k, 0) for k in DRIVE_SIDE_KEYS] == ['J4', 'k4', 'd4']
    assert DriveSideKey('damping', 2) == 'd6'
    for bad in (-1, 1.5, True):
        with pytest.raises(ValueError, match="'index'"):
            DriveSideKey('inertia', bad)
    with pytest.raises(ValueError, match="'fileKey'"):
        DriveSideKey('mass', 0)


@pytest.mark.parametrize('text, line, pattern', [
    ('[gear]\nwormRadius = "18 mm"\nmeshStifness = 2e8\n', 3,
     r"\[gear\]: unknown key 'meshStifness' \(did you mean 'meshStiffness'\?\); expected one of: pressureAngle"),
    ('[gaer]\nwormRadius = 1\n', 1, r"unknown top-level key or table 'gaer' \(did you mean 'gear'\?\)"),
    ('\n[worm]\ninertia = "0.1 kg"\n', 3, r"\[worm\] inertia: 'J1' must be in kg\*m\^2 \(plain numbers are SI\), got '0.1 kg'"),
    ('[driveShaft]\n\nstiffness = "lots"\n', 3, r"\[driveShaft\] stiffness: 'kT' must be a number optionally"),
    ('[load]\nmass = true\n', 2, r"\[load\] mass: must be a number \(SI\) or a string with units, got bool"),
    ('[gear]\nfrictionCoefficient = 0.13\nfrictionAngle = "8 deg"\n', None,
     r"both '(mu|rho)' and '(mu|rho)' are given \(line \d: \[gear\] \w+; line \d: \[gear\] \w+\)"),
    ('[worm]\ninertia = 0.1\n[parameters]\nJ1 = 0.2\n', 2,
     r"\[worm\] inertia: 'J1' is given a second time \(first at line 4: \[parameters\] J1\)"),
    ('[[driveSide]]\ninertia = 1\n[[driveSide]]\ninertia = 1\nspring = 3\n', 5,
     r"\[\[driveSide\]\] number 2: unknown key 'spring'; expected one of: inertia, stiffness, damping"),
    ('driveSide = 3\n', None, r"'driveSide' must be an array of tables"),
    ('worm = 3\n', 1, r"'worm' must be a table"),
    ('description = 3\n', 1, r"'description' must be a string"),
    # ranges (presets.CheckParameters) named by the file's line, table and key
    ('[gear]\nwormRadius = "18 mm"\n[worm]\ninertia = -0.1\n', 4,
     r"\[worm\] inertia: 'J1' must be > 0 kg\*m\^2, got -0.1"),
    ('[gear]\nbacklash = "-0.1 mm"\n', 2, r"\[gear\] backlash: 'backlash' must be >= 0 m"),
    ('[[driveSide]]\ninertia = 0.05\nstiffness = -1\n', 3,
     r"\[\[driveSide\]\] number 1 stiffness: 'k4' must be > 0 N\*m/rad, got -1"),
    ('[axialBearing]\nstiffness = 1e8\nmass = "0 kg"\n', 3, r"\[axialBearing\] mass: 'mA' must be > 0 kg"),
    # a file that gives nothing is refused, not taken as the reel-P1 preset
    ('', None, r"gives no parameters: a drive file must give the drive's values in component tables \(\[gear\]"),
    ('description = "my drive"\n[worm]\n', None, r"gives no parameters.*or name a preset"),
])
@pytest.mark.messages
def test_bad_drive_files_name_line_table_key_and_expectation(tmp_path, text, line, pattern):
    path = _Write(tmp_path, text)
    with pytest.raises(ValueError, match=pattern) as info:
        LoadConfig(path)
    message = str(info.value)
    assert message.startswith(f"LoadConfig: '{path}'")
    if line is not None:
        assert f"line {line}:" in message
    assert '\n' not in message


@pytest.mark.messages
def test_cli_bad_drive_file_one_line_exit_2(tmp_path):
    path = _Write(tmp_path, '[gear]\nwormRadius = "18 kg"\n')
    run = subprocess.run([sys.executable, '-m', 'exudyn_worm', 'stability', '--config', str(path)],
                         capture_output=True, text=True, cwd=tmp_path)
    assert run.returncode == 2
    assert run.stdout == ''
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith('exudyn-worm: error: ') and 'line 2: [gear] wormRadius' in lines[0]
    assert 'Traceback' not in run.stderr
    assert list(tmp_path.iterdir()) == [path]


def test_cli_runs_a_drive_file(tmp_path):
    run = subprocess.run([sys.executable, '-m', 'exudyn_worm', 'stability', '--config',
                          str(DRIVES / 'reel-P2.toml'), '--json'], capture_output=True, text=True, cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    reference = subprocess.run([sys.executable, '-m', 'exudyn_worm', 'stability', '--preset', 'reel-P2', '--json'],
                               capture_output=True, text=True, cwd=tmp_path)
    a, b = json.loads(run.stdout), json.loads(reference.stdout)
    assert a['S'] == b['S'] and a['ratio'] == b['ratio']


def test_docs_list_every_file_key():
    text = (ROOT / 'docs' / 'drive-files.md').read_text()
    for table, keys in DRIVE_FILE_TABLES.items():
        assert f'[{table}]' in text, table
        for fileKey in keys:
            assert f'`{fileKey}`' in text, (table, fileKey)
    for fileKey in DRIVE_SIDE_KEYS:
        assert f'`{fileKey}`' in text


def test_drive_side_chain_and_axial_bearing_reach_the_model(tmp_path):
    """[[driveSide]] and [axialBearing] become the model's chain and bearing (presets.DriveSideChain, ...)."""
    path = _Write(tmp_path, 'preset = "reel-P1"\n'
                            '[[driveSide]]\ninertia = "0.05 kg*m^2"\nstiffness = "2 kN*m"\ndamping = 0.1\n'
                            '[[driveSide]]\ninertia = 0.2\nstiffness = 500\n'
                            '[axialBearing]\nstiffness = "500 kN/mm"\ndamping = "1 kN*s/m"\nmass = "5 kg"\n')
    p = ResolveParameters(config=path)
    assert (p['J4'], p['k4'], p['d4'], p['J5'], p['k5']) == (0.05, 2000., 0.1, 0.2, 500.)
    assert [tuple(stage) for stage in DriveSideChain(p)][0] == (0.05, 2000., 0.1)
    assert len(DriveSideChain(p)) == 2
    bearing = AxialBearingFromParameters(p)
    assert (bearing.stiffness, bearing.damping, bearing.mass) == (5e8, 1000., 5.)


def test_figure19_file_is_the_drive_side_inertia_example():
    """examples/drives/figure19.toml holds the values of examples/drive_side_inertia.py to its printed digits."""
    example = LoadScript('examples/drive_side_inertia.py', 'drive_side_inertia_for_files')
    expected = example.DriveSideParameters()
    p = ResolveParameters(config=DRIVES / 'figure19.toml')
    assert set(p) == set(expected)
    halfUnit = {'k4': 0.5, 'd4': 0.5e-4}      # the file prints k4 = 18.483 kN*m/rad and d4 = 0.8512 N*m*s/rad
    for key in expected:
        assert p[key] == pytest.approx(expected[key], rel=1e-12, abs=halfUnit.get(key, 0.)), key


@pytest.mark.messages
def test_incomplete_drive_side_chain_names_the_file(tmp_path):
    path = _Write(tmp_path, 'preset = "reel-P1"\n\n[[driveSide]]\ninertia = 0.05\ndamping = 1\n')
    with pytest.raises(ValueError, match=r"line 4: \[\[driveSide\]\] number 1 inertia: DriveSideChain: 'J4' needs "
                                         r"the stiffness 'k4'.*each \[\[driveSide\]\] table needs 'inertia' and "
                                         r"'stiffness'") as info:
        ResolveParameters(config=path)
    assert str(info.value).startswith(f"LoadConfig: '{path}', line 4")
    assert ResolveParameters(config=path, sets=['k4=2e4'])['k4'] == 2e4      # completed by --set: fine
    with pytest.raises(ValueError, match=r"^ResolveParameters: DriveSideChain: 'J4' needs the stiffness 'k4'"):
        ResolveParameters('reel-P1', sets=['J4=0.05'])
    with pytest.raises(ValueError, match=r"missing 'J4'"):
        ResolveParameters('reel-P1', sets=['k4=1e4'])


@pytest.mark.messages
def test_cli_missing_component_names_the_file_and_the_table(tmp_path):
    text = (DRIVES / 'reel-P1.toml').read_text()
    path = _Write(tmp_path, re.sub(r'\[wheel\]\ninertia = .*\n', '', text), 'nowheel.toml')
    assert '[wheel]' not in path.read_text()
    for command in ('stability', 'check', 'simulate', 'chart'):
        run = subprocess.run([sys.executable, '-m', 'exudyn_worm', command, '--config', str(path)],
                             capture_output=True, text=True, cwd=tmp_path)
        lines = run.stderr.strip().splitlines()
        assert run.returncode == 2 and run.stdout == '' and len(lines) == 1, (command, run.stderr)
        assert 'missing parameter' in lines[0] and 'J2' in lines[0], lines[0]
        assert f"to describe the drive in '{path}', add [wheel] inertia (J2)" in lines[0], lines[0]


_FIG19 = (DRIVES / 'figure19.toml').read_text()


def _Figure19Plus(tmp_path, extra):
    """figure19.toml with ``extra`` ('\n[[driveSide]]\n...') appended; returns the path and the line of its header."""
    assert _FIG19.endswith('\n') and extra.startswith('\n[[driveSide]]\n')
    return _Write(tmp_path, _FIG19 + extra), _FIG19.count('\n') + 2


@pytest.mark.messages
@pytest.mark.parametrize('where', ['last', 'first'])
def test_empty_drive_side_table_is_refused_at_its_line(tmp_path, where):
    """An empty trailing [[driveSide]] gave the same result as figure19.toml (silently ignored), an empty first one
    a message about a gap: every table is a stage, so an empty one is refused, named by its number and line."""
    if where == 'last':
        path, line = _Figure19Plus(tmp_path, '\n[[driveSide]]\n')
        number, expected = 2, 'J5, k5'
    else:
        header = _FIG19.index('[[driveSide]]')
        text = _FIG19[:header] + '[[driveSide]]\n\n' + _FIG19[header:]
        path, line = _Write(tmp_path, text), _FIG19[:header].count('\n') + 1
        number, expected = 1, 'J4, k4'
    with pytest.raises(ValueError) as info:
        ResolveParameters(config=path)
    assert str(info.value).startswith(f"LoadConfig: '{path}', line {line}: [[driveSide]] number {number}: the table "
                                      f"is empty; each [[driveSide]] table is one stage of the drive-side chain "
                                      f"({expected}) and needs 'inertia' and 'stiffness'")


@pytest.mark.messages
@pytest.mark.parametrize('key, message', [
    ('stiffness = 1000.0', "[[driveSide]] number 2 stiffness: DriveSideChain: the drive-side chain must be J4, J5, "
                           "... without gaps, each with its spring k<i>; got keys J4, k4, d4, k5 (missing 'J5')"),
    ('inertia = 0.01', "[[driveSide]] number 2 inertia: DriveSideChain: 'J5' needs the stiffness 'k5'"),
])
def test_incomplete_second_drive_side_table_is_named(tmp_path, key, message):
    """With two tables and the second incomplete, the error pointed at the first table ('line 36: [[driveSide]]
    number 1 inertia'); it names the second one, at its own line."""
    path, line = _Figure19Plus(tmp_path, f'\n[[driveSide]]\n{key}\n')
    with pytest.raises(ValueError) as info:
        ResolveParameters(config=path)
    assert str(info.value).startswith(f"LoadConfig: '{path}', line {line + 1}: {message}"), str(info.value)


def test_second_drive_side_table_completed_by_set(tmp_path):
    path, _ = _Figure19Plus(tmp_path, '\n[[driveSide]]\ninertia = 0.01\n')
    p = ResolveParameters(config=path, sets=['k5=2e4'])
    assert (p['J5'], p['k5']) == (0.01, 2e4) and p['J4'] == ResolveParameters(config=DRIVES / 'figure19.toml')['J4']
