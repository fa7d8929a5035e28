"""The friction-law parameter keys: one declaration in the registry, usable with --set, in
parameter dicts and in drive files; a gear built from parameters carries its law; bad input names key, range,
unit and value."""
import math
import subprocess
import sys

import pytest

from exudyn_worm.drive.config import LoadConfig, ResolveParameters
from exudyn_worm.model.friction import AgmaFriction, StribeckFriction, TableFriction
from exudyn_worm.params.parameters import PARAMETERS
from exudyn_worm.drive.presets import ApplyOverrides, ElasticDriveFromParameters, GearFromParameters, GetPreset
from exudyn_worm.params.parameters import MissingParameterError
from exudyn_worm.model.stability import OperatingPointFromParameters

STRIBECK = {'frictionLaw': 'stribeck', 'muStatic': 0.15, 'stribeckVelocity': 0.1}


def test_keys_are_declared_once_with_kind_unit_and_drive_file_place():
    assert PARAMETERS['frictionLaw'].kind == 'choice'
    assert PARAMETERS['frictionLaw'].choices == ('constant', 'stribeck', 'agma', 'table')
    assert PARAMETERS['muStatic'].unit == '' and PARAMETERS['muStatic'].range == 'nonNegative'
    assert PARAMETERS['stribeckVelocity'].unit == 'm/s' and PARAMETERS['stribeckVelocity'].range == 'positive'
    assert PARAMETERS['frictionTable'].kind == 'table'
    assert all(PARAMETERS.FileKeyOf(k).startswith('[gear] ')
               for k in ('frictionLaw', 'muStatic', 'stribeckVelocity', 'frictionTable'))


def test_constant_is_the_default_and_leaves_the_gear_unchanged():
    gear = GearFromParameters(GetPreset('reel-P1'))
    assert gear.friction is None
    assert GearFromParameters({**GetPreset('reel-P1'), 'frictionLaw': 'constant'}) == gear


def test_parameter_dict_carries_the_stribeck_law_into_the_gear():
    drive = ElasticDriveFromParameters({**GetPreset('reel-P3'), **STRIBECK})
    assert drive.gear.friction == StribeckFriction(mu=0.132, muStatic=0.15, stribeckVelocity=0.1)
    # the kinetic mu of a set that gives the friction angle: rho -> mu by eq. (13)
    p = ApplyOverrides({**GetPreset('reel-P3'), **STRIBECK}, {'rho': math.radians(8)})
    assert drive.gear.friction.mu != ElasticDriveFromParameters(p).gear.friction.mu
    assert math.isclose(ElasticDriveFromParameters(p).gear.friction.mu, math.tan(math.radians(8)) * math.cos(math.radians(20)))


def test_set_options_with_units_and_inline_table():
    p = ResolveParameters('reel-P3', sets=['frictionLaw=stribeck', 'muStatic=0.15', 'stribeckVelocity=10 cm/s'])
    assert p['stribeckVelocity'] == pytest.approx(0.1)
    assert ElasticDriveFromParameters(p).gear.friction.stribeckVelocity == pytest.approx(0.1)
    p = ResolveParameters('reel-P3', sets=['frictionLaw=table', 'frictionTable=[[0, 0.15], [1, 0.05]]'])
    assert ElasticDriveFromParameters(p).gear.friction == TableFriction(((0., 0.15), (1., 0.05)))
    p = ResolveParameters('reel-P3', sets=['frictionLaw=agma'])
    assert isinstance(ElasticDriveFromParameters(p).gear.friction, AgmaFriction)
    assert ElasticDriveFromParameters(p).gear.mu == 0.132                # the nominal mu stays


def test_drive_file_table_path_is_relative_to_the_drive_file(tmp_path, monkeypatch):
    folder = tmp_path / 'rig'
    folder.mkdir()
    (folder / 'mu.csv').write_text('v, mu\n0, 0.14\n0.5, 0.08\n2, 0.05\n')
    (folder / 'drive.toml').write_text('preset = "reel-P3"\n[gear]\nfrictionLaw = "table"\nfrictionTable = "mu.csv"\n')
    monkeypatch.chdir(tmp_path)                                    # the table is not in the current directory
    gear = ElasticDriveFromParameters(ResolveParameters(config=str(folder / 'drive.toml'))).gear
    assert gear.friction.points == ((0., 0.14), (0.5, 0.08), (2., 0.05))
    (folder / 'inline.toml').write_text('preset = "reel-P3"\n[gear]\nfrictionLaw = "stribeck"\n'
                                        'staticFrictionCoefficient = 0.15\nstribeckVelocity = "100 mm/s"\n')
    gear = ElasticDriveFromParameters(ResolveParameters(config=str(folder / 'inline.toml'))).gear
    assert gear.friction == StribeckFriction(mu=0.132, muStatic=0.15, stribeckVelocity=0.1)


def test_the_law_reaches_the_operating_point():
    p = {**GetPreset('reel-P3'), **STRIBECK, 'stribeckVelocity': 1.}
    op = OperatingPointFromParameters(p, ElasticDriveFromParameters(p).gear)
    v0 = op.slidingSpeed
    assert op.mu == pytest.approx(0.132 + 0.018 * math.exp(-v0**2))
    assert op.dmuDv == pytest.approx(-2 * 0.018 * v0 * math.exp(-v0**2))


@pytest.mark.parametrize('sets, match', [
    (['frictionLaw=stribek'], r"'frictionLaw' must be one of: constant, stribeck, agma, table, got 'stribek' "
                              r"\(did you mean 'stribeck'\?\)"),
    (['frictionLaw=stribeck', 'muStatic=0.1', 'stribeckVelocity=0.1'],
     r"'muStatic' .* must be >= the kinetic 'mu' = 0.132, got 0.1"),
    (['frictionLaw=stribeck', 'muStatic=0.2', 'stribeckVelocity=-0.1'], r"'stribeckVelocity' must be > 0 m/s, got -0.1"),
    (['frictionLaw=stribeck', 'muStatic=-0.2', 'stribeckVelocity=0.1'], r"'muStatic' must be >= 0, got -0.2"),
    (['frictionLaw=stribeck', 'muStatic=0.2', 'stribeckVelocity=2 rpm'], r"'stribeckVelocity' must be in m/s"),
    (['muStatic=0.2'], r"'muStatic' is used only with frictionLaw = stribeck, got frictionLaw = 'constant'"),
    (['frictionLaw=stribeck'], r"frictionLaw = 'stribeck' needs 'muStatic', 'stribeckVelocity'"),
    (['frictionLaw=table', 'frictionTable=[[1, 0.15], [0, 0.05]]'], r"'frictionTable': the speed must increase"),
    (['frictionLaw=table', 'frictionTable=[[1, 0.15]]'], r"'frictionTable': .*at least 2"),
    (['frictionLaw=table', 'frictionTable=[[0, -0.15], [1, 0.1]]'], r"'frictionTable\[0\] mu' must be >= 0"),
    (['frictionLaw=table', 'frictionTable=no-such-file.csv'], r"'frictionTable': .*cannot read"),
])
def test_bad_input_names_key_range_and_value(sets, match):
    with pytest.raises(ValueError, match=match):
        ElasticDriveFromParameters(ResolveParameters('reel-P3', sets=sets))


def test_missing_law_values_are_a_missing_parameter_error():
    with pytest.raises(MissingParameterError) as info:
        GearFromParameters({**GetPreset('reel-P3'), 'frictionLaw': 'table'})
    assert info.value.keys == ('frictionTable',)


def test_cli_prints_one_line_and_exits_2():
    run = subprocess.run([sys.executable, '-m', 'exudyn_worm', 'stability', '--preset', 'reel-P3', '--set',
                          'frictionLaw=stribeck', '--set', 'muStatic=0.1', '--set', 'stribeckVelocity=0.1'],
                         capture_output=True, text=True)
    assert run.returncode == 2
    assert run.stderr.strip().count('\n') == 0 and 'Traceback' not in run.stderr
    assert "'muStatic'" in run.stderr and '0.132' in run.stderr and '0.1' in run.stderr
