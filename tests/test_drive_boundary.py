"""The drive boundary: units that cannot slip, one-line refusals that name where a value came from, keys taken back
from the command line, and decisions on typed sources (docs/drive-files.md, "Values" and "Where a value comes
from"; docs/command-line.md)."""
import json
import math
from pathlib import Path

import pytest

from exudyn_worm.analysis.stability.drivestability import AnalyzeDrive
from exudyn_worm.cli.main import Main
from exudyn_worm.model.geometry import GeometryForm, GeometryFormKind
from exudyn_worm.params.parameters import PARAMETERS, UNIT_REQUIRED, ParameterError
from exudyn_worm.drive.config import (LoadConfig, ParseQuantity, ParseSetOption, ResolveParameters,
                                      ResolveParametersWithSources, SourceKind, ValueSource)
from exudyn_worm.drive.wholedrive import ResolveDrive

ROOT = Path(__file__).resolve().parents[1]
DRIVES = ROOT / 'examples' / 'drives'
HOIST = DRIVES / 'hoist.toml'
RPM = math.pi / 30.
#: the Stribeck law of docs/chatter-amplitude.md's speed range (a speed-dependent friction makes the verdict depend
#: on the motor speed)
STRIBECK = ['frictionLaw=stribeck', 'mu=0.092', 'muStatic=0.2', 'stribeckVelocity=0.9 m/s']


def _Write(folder, text, name='drive.toml'):
    path = folder / name
    path.write_text(text)
    return path


def _Cli(capsys, *argv):
    status = Main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


# --- 1. units that cannot slip ------------------------------------------------------------------------------------
def test_why_a_plain_speed_is_refused():
    """60 meant as rpm but taken as rad/s (573 rpm) changes the verdict of reel-P3 with a Stribeck law: a speed
    typed as on a nameplate must not pass silently."""
    asRpm = ResolveDrive('reel-P3', sets=STRIBECK + ['motorSpeed=60 rpm'])
    asRadS = ResolveDrive('reel-P3', sets=STRIBECK + ['motorSpeed=60 rad/s'])
    assert asRadS.parameters['motorSpeed'] == pytest.approx(asRpm.parameters['motorSpeed'] / RPM, rel=1e-12)
    assert AnalyzeDrive(asRpm).stable != AnalyzeDrive(asRadS).stable


@pytest.mark.messages
@pytest.mark.parametrize('key, text, units, readings', [
    ('motorSpeed', '60', '"472.5 rpm"', '60 rpm = 6.283 rad/s; in rad/s: 60 rad/s = 573 rpm'),
    ('noLoadSpeed', '150', '"472.5 rpm"', '150 rpm = 15.71 rad/s'),
    ('gamma', '5.3228', '"20 deg"', '5.3228 deg = 0.0929 rad'),
    ('alphaN', '20', '"20 deg"', '20 deg = 0.3491 rad'),
    ('rho', '8', '"20 deg"', '8 deg = 0.1396 rad'),
    ('r1', '18.05', '"18.05 mm"', '18.05 mm = 0.01805 m'),
    ('backlash', '0.5', '"18.05 mm"', '0.5 mm = 0.0005 m'),
    ('leverArm', '1200', '"18.05 mm"', '1200 mm = 1.2 m'),
    ('wormBearingSpan', '100', '"18.05 mm"', '100 mm = 0.1 m'),
])
def test_set_refuses_a_plain_angle_speed_or_length(key, text, units, readings):
    with pytest.raises(ValueError, match=f"ParseSetOption: '{key}={text}': '{key}' is .* and needs its unit, e.g. "
                                         f"{units}.*got the plain number '{text}' \\(meant in .*{readings}"):
        ParseSetOption(f'{key}={text}')


@pytest.mark.parametrize('text, value', [('motorSpeed=0', 0.), ('backlash=0', 0.), ('gamma=0.0', 0.),
                                         ('backlash=0.5mm', 5e-4), ('motorSpeed=60rpm', 60 * RPM),
                                         ('gamma=0.09 rad', 0.09), ('J2=23', 23.), ('kT=7000', 7000.),
                                         ('stribeckVelocity=0.9', 0.9), ('rampTime=0.5', 0.5)])
def test_set_takes_zero_units_and_the_plain_numbers_of_other_quantities(text, value):
    assert ParseSetOption(text)[1] == pytest.approx(value, rel=1e-12)


def test_the_rule_covers_every_angle_speed_and_length_of_the_registry():
    required = {p.key for p in PARAMETERS if p.kind == 'number' and p.unit in UNIT_REQUIRED}
    assert {'alphaN', 'gamma', 'rho', 'r1', 'r2', 'a', 'mx', 'backlash', 'leverArm', 'motorSpeed',
            'noLoadSpeed', 'wormBearingSpan', 'wheelBearingSpan', 'wormRadius', 'wormInnerRadius', 'wormLength',
            'wheelRadius', 'wheelInnerRadius', 'wheelLength'} == required
    assert all(PARAMETERS.UnitRequired(k) for k in required) and not PARAMETERS.UnitRequired('J2')


def test_python_numbers_stay_si():
    """The API is SI (a parameters dictionary, a (key, value) pair): the rule is for text and drive files."""
    assert ParseQuantity('motorSpeed', 60.) == 60.
    assert ResolveParameters('reel-P1', sets=[('motorSpeed', 60.)])['motorSpeed'] == 60.
    drive = ResolveDrive(parameters=dict(ResolveDrive('reel-P1').parameters), sets=[('motorSpeed', 60.)])
    assert drive.parameters['motorSpeed'] == 60. and drive.sources['motorSpeed'].kind == SourceKind.SET


@pytest.mark.messages
@pytest.mark.parametrize('table, entry, line, key', [
    ('motor', 'speed = 60', 3, "'motorSpeed' is an angular speed"),
    ('gear', 'pitchAngle = 0.0929', 3, "'gamma' is an angle"),
    ('gear', 'backlash = 0.0002', 3, "'backlash' is a length"),
    ('motor', 'type = "speedTable"\nspeedOverTime = [[0, 0], [1, 50]]', 4,
     r"'motorSpeedOverTime\[1\] speed' is an angular speed"),
    ('load', 'type = "angleTable"\ntorqueOverAngle = [[0, -100], [3, 100]]', 4,
     r"'loadTorqueOverAngle\[1\] angle' is an angle"),
])
def test_drive_file_refuses_a_plain_number_at_its_line(tmp_path, table, entry, line, key):
    path = _Write(tmp_path, f'preset = "reel-P1"\n[{table}]\n{entry}\n')
    with pytest.raises(ValueError, match=f"^LoadConfig: '.*drive.toml', line {line}: .*{key} and needs its unit"):
        LoadConfig(path)


def test_drive_file_takes_zero_and_units(tmp_path):
    path = _Write(tmp_path, 'preset = "reel-P1"\n[gear]\nbacklash = 0\n[motor]\ntype = "speedTable"\n'
                            'speedOverTime = [[0, 0], [1, "50 rad/s"], [2, "60 rpm"]]\n')
    p = LoadConfig(path)['parameters']
    assert p['backlash'] == 0. and p['motorSpeedOverTime'] == ((0., 0.), (1., 50.), (2., pytest.approx(60 * RPM)))


@pytest.mark.parametrize('path', sorted(DRIVES.glob('*.toml')), ids=lambda p: p.name)
def test_shipped_drive_files_follow_the_rule(path):
    LoadConfig(path)                # a plain angle, speed or length would be refused here


@pytest.mark.messages
def test_cli_refuses_a_plain_speed_in_one_line(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    status, out, err = _Cli(capsys, 'stability', '--preset', 'reel-P1', '--set', 'motorSpeed=60')
    assert status == 2 and out == '' and 'Traceback' not in err and err.count('\n') == 1
    assert err.startswith("exudyn-worm: error: ParseSetOption: 'motorSpeed=60': 'motorSpeed' is an angular speed")
    assert '60 rpm = 6.283 rad/s' in err and list(tmp_path.iterdir()) == []


@pytest.mark.messages
def test_cli_refuses_a_plain_speed_in_vary(capsys):
    status, out, err = _Cli(capsys, 'sweep', '--preset', 'reel-P1', '--vary', 'motorSpeed=40:60:3')
    assert status == 2 and 'Traceback' not in err and err.count('\n') == 1
    assert "'motorSpeed' is an angular speed and needs its unit" in err


# --- 2. one line naming the file and line, the key, the range and unit, the value -------------------------------
def test_sets_none_means_no_overrides():
    assert ResolveDrive('reel-P1', sets=None).parameters == ResolveDrive('reel-P1').parameters
    assert ResolveParameters('reel-P1', sets=None) == ResolveParameters('reel-P1')


@pytest.mark.messages
@pytest.mark.parametrize('kwargs, error, pattern', [
    (dict(preset='reel-P1', sets=5), TypeError, r"ResolveParameters: 'sets' must be a list .*, got int 5"),
    (dict(preset='reel-P1', sets='J1=0.3'), TypeError, r"got a single string 'J1=0.3'; write sets=\['J1=0.3'\]"),
    (dict(parameters=[1]), TypeError, r"ResolveDrive: 'parameters' must be a mapping .*, got list \[1\]"),
    (dict(preset='reel-P9'), ValueError, r"ResolveParameters: 'preset': unknown preset 'reel-P9' \(did you mean "
                                         r"'reel-P7'\?\); expected one of: chart"),
    (dict(preset='reel-P1', sets=[('J1', -1.)]), ValueError,
     r"ResolveParameters: sets item \('J1', -1.0\): 'J1' must be > 0 kg\*m\^2, got -1 kg\*m\^2"),
    (dict(preset='reel-P1', sets=['kA=1e8']), ValueError,
     r"^Drive \(reel-P1\): 'kA' = 1e\+08 N/m > 0 needs the worm's axially moving mass 'mA' \(kg\)"),
    (dict(preset='reel-P1', sets=['mu=12']), ParameterError, r"^Drive \(reel-P1\): gamma \+ rho must be < 90 deg"),
])
def test_api_refusals_name_the_argument_and_the_value(kwargs, error, pattern):
    with pytest.raises(error, match=pattern):
        ResolveDrive(**kwargs)


@pytest.mark.messages
@pytest.mark.parametrize('base, old, new, pattern', [
    ('hoist', 'staticFrictionCoefficient = 0.12', 'staticFrictionCoefficient = 0.05',
     r"line 17: \[gear\] staticFrictionCoefficient: 'muStatic' \(friction at rest, frictionLaw = stribeck\) must be "
     r">= the kinetic 'mu' = 0.07, got 0.05"),
    ('reel-P1', 'frictionCoefficient = 0.132', 'frictionCoefficient = 12',
     r"line 8: \[gear\] frictionCoefficient: gamma \+ rho must be < 90 deg .* \(mu = 12\)"),
    ('reel-P1', 'wheelRadius = "105.95 mm"', 'wheelRadius = "1.5 mm"',
     r"line 9: \[gear\] wormRadius: the transmission ratio .* must be >= 1 .*got u = 0.892"),
    ('reel-P1', 'speed = "472.5 rpm"', 'type = "startStop"\nspeed = "472.5 rpm"\nrampTime = "1 s"\nbrakeTime = "0.5 s"',
     r"line 33: \[motor\] brakeTime: 'brakeTime' must be >= rampTime = 1 s \(motorType startStop\), got 0.5 s"),
    ('hoist', 'type = "constant"\ntorque = "-367.875 N*m"', 'type = "timeTable"\ntorqueOverTime = "nofile.csv"',
     r"line 39: \[load\] torqueOverTime: 'loadTorqueOverTime': the table file '.*nofile.csv': cannot read it"),
    ('reel-P1', 'inertia = "33 kg*m^2"', 'inertia = "33 kg*m^2"\nmass = "30 kg"',
     r"line 20: \[wheel\] mass: 'wheelMass' \(the wheel's mass, kg\) is used only by the 3D model, .* got 30 kg"),
    ('reel-P1', 'description', 'preset = "reel-P9"\ndescription',
     r"line 3: preset: unknown preset 'reel-P9' \(did you mean 'reel-P7'\?\); expected one of: chart"),
    ('reel-P1', 'leverArm = "1.2 m"', 'leverArm = "1.2 m"\ntype = "constant"\ntorque = "-100 N*m"',
     r"line 26: \[load\] mass: 'loadMass' is not used by loadType = 'constant' \(line 28: \[load\] type\), which "
     r"takes loadTorque; 'loadMass' belongs to loadType lever"),
    ('reel-P1', 'leverArm = "1.2 m"', 'leverArm = "1.2 m"\ntorque = "5 N*m"',
     r"line 28: \[load\] torque: 'loadTorque' is not used by loadType = 'lever' \(the default\)"),
])
def test_drive_file_refusals_name_the_file_and_line(tmp_path, base, old, new, pattern):
    """Checks that need several keys (the friction law, the gear's plausibility, the duty) are made when the drive is
    built; their message still names the file and the line of the value at fault."""
    text = (DRIVES / f'{base}.toml').read_text()
    assert old in text
    path = _Write(tmp_path, text.replace(old, new))
    with pytest.raises(ValueError, match=f"^LoadConfig: '{path}', " + pattern):
        ResolveDrive(config=path)


@pytest.mark.messages
@pytest.mark.parametrize('text, pattern', [
    ('driveSide = 5\n', r"line 1: 'driveSide' must be an array of tables \(\[\[driveSide\]\]\), got int 5"),
    ('[driveSide]\ninertia = 1\n', r"line 1: 'driveSide' must be an array of tables .*, got dict \{'inertia': 1\}"),
    ('parameters = 5\n', r"line 1: 'parameters' must be a table \(\[parameters\]\), got int 5"),
    ('gear = "x"\n', r"line 1: 'gear' must be a table \(\[gear\]\), got str 'x'"),
])
def test_drive_file_tables_of_the_wrong_type_are_named_at_their_line(tmp_path, text, pattern):
    path = _Write(tmp_path, text)
    with pytest.raises(ValueError, match=f"^LoadConfig: '{path}', " + pattern):
        LoadConfig(path)


@pytest.mark.messages
def test_a_chain_on_the_3d_model_is_named_at_its_line(tmp_path):
    text = (DRIVES / 'reel-3d.toml').read_text().rstrip('\n') + '\n\n[[driveSide]]\ninertia = "0.05 kg*m^2"\n' \
        'stiffness = "2000 N*m/rad"\n'
    line = text.splitlines().index('inertia = "0.05 kg*m^2"') + 1
    path = _Write(tmp_path, text)
    with pytest.raises(ValueError, match=f"^LoadConfig: '{path}', line {line}: \\[\\[driveSide\\]\\] number 1 inertia: "
                                         f"the shafts' bearings .* which has no drive-side chain"):
        ResolveDrive(config=path)


@pytest.mark.messages
def test_cli_names_the_file_line_of_a_value_checked_with_others(capsys, tmp_path):
    text = HOIST.read_text().replace('staticFrictionCoefficient = 0.12', 'staticFrictionCoefficient = 0.05')
    path = _Write(tmp_path, text)
    status, out, err = _Cli(capsys, 'stability', '--config', str(path))
    assert status == 2 and out == '' and 'Traceback' not in err and err.count('\n') == 1
    assert err.startswith(f"exudyn-worm: error: LoadConfig: '{path}', line 17: [gear] staticFrictionCoefficient: "
                          f"'muStatic'")


# --- 3. a key taken back from the command line ----------------------------------------------------------------------
def test_set_law_drops_the_keys_of_the_replaced_law():
    drive = ResolveDrive(config=HOIST, sets=['frictionLaw=constant'])
    assert 'muStatic' not in drive.parameters and 'stribeckVelocity' not in drive.parameters
    assert drive.gear.friction is None and drive.parameters['mu'] == 0.07


def test_set_empty_value_takes_a_key_back():
    p, sources = ResolveParametersWithSources(config=HOIST, sets=['muStatic=', 'stribeckVelocity=',
                                                                  'frictionLaw=constant'])
    assert 'muStatic' not in p and 'stribeckVelocity' not in p and sources['frictionLaw'].kind == SourceKind.SET
    # the last of a repeated key wins: taken back, then given again
    assert ResolveParameters('reel-P1', sets=['backlash=', 'backlash=0.1 mm'])['backlash'] == pytest.approx(1e-4)
    assert 'backlash' not in ResolveParameters('reel-P1', sets=['backlash=0.1 mm', 'backlash='])


@pytest.mark.messages
def test_a_key_taken_back_that_the_law_needs_is_reported_missing():
    with pytest.raises(ValueError, match=r"frictionLaw = 'stribeck' needs 'muStatic'"):
        ResolveDrive(config=HOIST, sets=['muStatic='])


def test_set_load_type_drops_the_presets_lever():
    drive = ResolveDrive('reel-P1', sets=['loadType=constant', 'loadTorque=-100 N*m'])
    assert 'loadMass' not in drive.parameters and 'leverArm' not in drive.parameters
    assert drive.loadType == 'constant' and drive.parameters['motorSpeed'] == pytest.approx(472.5 * RPM)


@pytest.mark.messages
def test_a_key_given_with_the_choice_that_it_does_not_fit_is_refused():
    with pytest.raises(ValueError, match=r"ResolveParameters: 'loadMass' \(--set\) is not used by loadType = "
                                         r"'constant' \(--set\), which takes loadTorque"):
        ResolveDrive('reel-P1', sets=['loadType=constant', 'loadTorque=-100 N*m', 'loadMass=100'])
    with pytest.raises(ValueError, match=r"'muStatic' is used only with frictionLaw = stribeck, got frictionLaw = "
                                         r"'constant'; set frictionLaw=stribeck or remove 'muStatic' \(on the command "
                                         r"line --set muStatic=\)"):
        ResolveDrive(config=HOIST, sets=['frictionLaw=constant', 'muStatic=0.2'])


@pytest.mark.messages
def test_a_dictionary_key_gives_way_to_a_choice_made_not_to_the_default():
    base = dict(ResolveDrive('reel-P1').parameters)
    lifted = ResolveDrive(parameters={**base, 'loadType': 'constant', 'loadTorque': -100.})
    assert 'loadMass' not in lifted.parameters and lifted.loadType == 'constant'
    with pytest.raises(ValueError, match=r"^ResolveDrive: 'muStatic' is used only with frictionLaw = stribeck, got "
                                         r"frictionLaw = 'constant' \(the default\)"):
        ResolveDrive(parameters={**base, 'muStatic': 0.2})
    with pytest.raises(ValueError, match=r"^ResolveDrive: 'loadTorque' \(API\) is not used by loadType = 'lever' \(the "
                                         r"default\), which takes loadMass, leverArm"):
        ResolveDrive(parameters={**base, 'loadTorque': -100.})


def test_cli_switches_the_law_of_a_file(capsys):
    status, out, err = _Cli(capsys, 'stability', '--config', str(HOIST), '--set', 'frictionLaw=constant', '--json')
    assert status in (0, 1) and err == '', err
    assert all(p['mu'] == 0.07 and p['dmuDv'] == 0. for p in json.loads(out)['operatingPoints'])


# --- 4. decisions on types ------------------------------------------------------------------------------------------
def test_sources_are_typed_and_print_as_before():
    drive = ResolveDrive(config=HOIST, sets=['kT=2500'])
    kinds = {k: s.kind for k, s in drive.sources.items()}
    assert kinds['kT'] == SourceKind.SET and kinds['J1'] == SourceKind.FILE
    assert drive.ToDict()['sources']['kT'] == '--set' and 'hoist.toml' in drive.ToDict()['sources']['J1']
    assert ResolveDrive('reel-P1').sources['J1'] == ValueSource(SourceKind.PRESET, 'preset reel-P1')
    assert str(ValueSource.Preset('reel-P1')) == 'preset reel-P1'
    with pytest.raises(TypeError, match=r"Drive: 'sources' must map each key to a ValueSource .*, got str "
                                        r"'preset reel-P1' for 'J1'"):
        type(drive).FromParameters(drive.parameters, {'J1': 'preset reel-P1'})


def test_a_source_text_decides_nothing():
    """A file location that reads like a preset is still a file's value: motorSpeed given in a file with a speed-table
    motor is refused, whatever the file is called."""
    drive = ResolveDrive('reel-P1')
    parameters = {**drive.parameters, 'motorType': 'speedTable', 'motorSpeedOverTime': ((0., 0.), (1., 10.))}
    fromFile = {k: ValueSource.File('preset reel-P1') for k in parameters}
    with pytest.raises(ValueError, match=r"'motorSpeed' is not used by motorType = 'speedTable'"):
        type(drive).FromParameters(parameters, fromFile)
    kept = type(drive).FromParameters(parameters, {k: ValueSource.Preset('x') for k in parameters})
    assert 'motorSpeed' not in kept.parameters


@pytest.mark.parametrize('sets, form', [([], GeometryFormKind.RADII),
                                        (['a=40 mm', 'u=40', 'gamma=3.5 deg'], GeometryFormKind.CENTRE_DISTANCE),
                                        (['mx=3 mm', 'z1=2', 'z2=30', 'q=10'], GeometryFormKind.DESIGNATION)])
def test_geometry_form_is_an_enum_printed_by_name(sets, form):
    drive = ResolveDrive('reel-P1', sets=sets)
    assert drive.geometryForm is form and GeometryForm(drive.parameters) is form
    assert json.dumps(form) == json.dumps(form.value) and f'{form}' == str(form) == form.value


def test_stability_json_prints_the_geometry_form_by_name(capsys):
    status, out, err = _Cli(capsys, 'stability', '--preset', 'reel-P1', '--set', 'a=40 mm', '--set', 'u=40',
                            '--set', 'gamma=3.5 deg', '--json')
    assert status in (0, 1), err
    assert json.loads(out)['geometry']['form'] == 'centre distance'
