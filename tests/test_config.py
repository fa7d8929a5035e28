"""Tests of exudyn_worm.drive.config: quantities with units, --set options, TOML config files, resolution."""
import doctest
import math
import subprocess
import sys

import pytest
from hypothesis import given, strategies as st

from exudyn_worm.drive import config

from exudyn_worm.params import parameters
from exudyn_worm.drive.config import (DEFAULT_PRESET, LoadConfig, ParseQuantity, ParseSetOption,
                                ResolveParameters)
from exudyn_worm.drive.presets import PARAMETER_UNITS, GetPreset

RPM = 2 * math.pi / 60


# --- ParseQuantity ---------------------------------------------------------------------------------
@pytest.mark.parametrize('key, text, expected', [
    ('gamma', '8 deg', math.radians(8)),
    ('rho', '8deg', math.radians(8)),
    ('alphaN', '0.349 rad', 0.349),
    ('backlash', '0', 0.),                            # zero needs no unit
    ('J1', '0.3', 0.3),                               # plain numbers are SI where the SI unit is the printed one
    ('backlash', '0.5 mm', 0.5e-3),
    ('r1', '18.05 mm', 18.05e-3),
    ('kT', '7 kN*m', 7000.),                          # N*m accepted for N*m/rad
    ('kT', '7000 N*m/rad', 7000.),
    ('kT', '7000', 7000.),
    ('dT', '0.741 N*m*s', 0.741),
    ('motorSpeed', '472.5 rpm', 472.5 * RPM),
    ('motorSpeed', '49.48 rad/s', 49.48),
    ('J1', '0.1 kg*m^2', 0.1),
    ('J2', '33 kg m**2', 33.),
    ('kV', '2e8 N/m', 2e8),
    ('kV', '200 kN/mm', 2e8),
    ('dV', '21.47 kN*s/m', 21470.),
    ('DV', '1.4 %', 0.014),
    ('mu', '0.134', 0.134),
    ('loadMass', '175 kg', 175.),
    ('leverArm', '1200 mm', 1.2),
    ('J1', 0.1, 0.1),                                 # numbers (from TOML) pass through
    ('kT', 7000, 7000.),
])
def test_parse_quantity(key, text, expected):
    assert ParseQuantity(key, text) == pytest.approx(expected, rel=1e-12)


@pytest.mark.messages
@pytest.mark.parametrize('key, text, fragments', [
    ('kT', '7 kg', ["'kT'", 'N*m/rad', "'7 kg'", '[mass]']),
    ('r1', '5 s', ["'r1'", 'm', "'5 s'", '[time]']),
    ('J1', '0.1 kg*m', ["'J1'", 'kg*m^2', "'0.1 kg*m'"]),
    ('mu', '8 deg', ["'mu'", 'dimensionless', "'8 deg'", '[angle]']),   # angle for a plain ratio
    ('motorSpeed', '8 Hz', ["'motorSpeed'", 'rad/s', "'8 Hz'"]),       # would silently lose 2 pi
    ('alphaN', '20 %', ["'alphaN'", 'rad', "'20 %'"]),
    ('gamma', '2 rad/s', ["'gamma'", 'rad', '[time]']),
])
def test_parse_quantity_wrong_dimension(key, text, fragments):
    with pytest.raises(ValueError) as info:
        ParseQuantity(key, text)
    message = str(info.value)
    assert message.startswith('ParseQuantity:')
    for fragment in fragments:
        assert fragment in message


@pytest.mark.messages
@pytest.mark.parametrize('text', ['nan', 'inf', '-inf', 'NaN m', 'inf mm', '1e400', '1e400 mm',
                                  float('nan'), float('inf')])
def test_parse_quantity_non_finite(text):
    with pytest.raises(ValueError, match="'r1' must be finite"):
        ParseQuantity('r1', text)


@pytest.mark.messages
@pytest.mark.parametrize('text', ['', '   ', 'abc', 'mm', '1.2.3 m', '3 abc', '1/0 m', '3 m+', '0.5 mm mm x',
                                  '1,5 mm', '2 * 3 m', '__import__("os")'])
def test_parse_quantity_malformed(text):
    with pytest.raises(ValueError, match=r"^ParseQuantity: 'r1'"):
        ParseQuantity('r1', text)


@pytest.mark.messages
def test_parse_quantity_bad_key_and_type():
    with pytest.raises(ValueError, match="unknown parameter 'foo'; expected one of: alphaN"):
        ParseQuantity('foo', '1')
    with pytest.raises(TypeError, match="'r1'.*bool"):
        ParseQuantity('r1', True)
    with pytest.raises(TypeError, match="'r1'.*list"):
        ParseQuantity('r1', [1.])


@given(st.floats(allow_nan=False, allow_infinity=False))
def test_parse_quantity_plain_numbers_round_trip(x):
    assert ParseQuantity('J1', repr(x)) == x


@given(st.floats(min_value=-1e6, max_value=1e6, allow_nan=False))
def test_parse_quantity_millimetre(x):
    assert ParseQuantity('backlash', f'{x!r} mm') == pytest.approx(x * 1e-3, rel=1e-12, abs=1e-300)


def test_unit_registry_lazy_and_single():
    code = ("import sys; from exudyn_worm.drive.config import ParseQuantity, ResolveParameters; "
            "ParseQuantity('J1', '0.1'); ResolveParameters(sets=['J1=0.2']); print('pint' in sys.modules)")
    out = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == 'False'
    assert parameters._UnitRegistry() is parameters._UnitRegistry()


def test_config_doctests():
    result = doctest.testmod(config)
    assert result.attempted > 0 and result.failed == 0


# --- ParseSetOption --------------------------------------------------------------------------------
def test_parse_set_option():
    assert ParseSetOption('J1=0.3') == ('J1', 0.3)
    assert ParseSetOption(' backlash = 0.5 mm ') == ('backlash', pytest.approx(5e-4))
    assert ParseSetOption('kT=7 kN*m') == ('kT', 7000.)
    assert ParseSetOption('gamma=5.3228 deg') == ('gamma', pytest.approx(math.radians(5.3228)))


@pytest.mark.messages
@pytest.mark.parametrize('text, pattern', [
    ('J1', 'expected KEY=VALUE'),
    ('=0.3', 'expected KEY=VALUE'),
    ('foo=1', "unknown parameter 'foo'; expected one of: " + ' '.join(PARAMETER_UNITS)),
    ('J1=', "'J1' must be a number"),
    ('J1=abc', "'J1' must be a number"),
    ('kT=7 kg', r"'kT' must be in N\*m/rad"),
])
def test_parse_set_option_errors(text, pattern):
    with pytest.raises(ValueError, match=pattern):
        ParseSetOption(text)


# --- LoadConfig ------------------------------------------------------------------------------------
def _Write(tmp_path, text, name='drive.toml'):
    path = tmp_path / name
    path.write_text(text, encoding='utf-8')
    return path


def test_load_config(tmp_path):
    path = _Write(tmp_path, 'preset = "reel-P6"\n[parameters]\nJ1 = "0.3 kg*m^2"\nkT = 12000\n'
                            'backlash = "0.25 mm"\nDV = 0.056\ngamma = "5.3228 deg"\n')
    cfg = LoadConfig(path)
    assert cfg['preset'] == 'reel-P6'
    assert cfg['parameters'] == {'J1': 0.3, 'kT': 12000., 'backlash': pytest.approx(2.5e-4), 'DV': 0.056,
                                 'gamma': pytest.approx(math.radians(5.3228))}
    with pytest.raises(ValueError, match="empty.toml': the file gives no parameters"):     # not silently reel-P1
        LoadConfig(str(_Write(tmp_path, '', 'empty.toml')))
    assert LoadConfig(str(_Write(tmp_path, 'preset = "reel-P7"\n', 'named.toml')))['preset'] == 'reel-P7'


@pytest.mark.parametrize('text, pattern', [
    ('preset = "reel-P1"\n[parameters\nJ1 = 1\n', 'not valid TOML'),
    ('J1 = 0.1\n', "line 1: unknown top-level key or table 'J1'.*preset, description, parameters, gear"),
    ('preset = "nope"\n', "unknown preset 'nope'; expected one of: chart, reel-P1"),
    ('preset = 3\n', "'preset' must be a string"),
    ('parameters = 3\n', "'parameters' must be a table"),
    ('[parameters]\nfoo = 1\n', "unknown parameter 'foo'"),
    ('[parameters]\nJ1 = true\n', r'line 2: \[parameters\] J1: must be a number'),
    ('[parameters]\nJ1 = [1, 2]\n', r'line 2: \[parameters\] J1: must be a number'),
    ('[parameters]\nJ1 = "0.1 kg"\n', r"'J1' must be in kg\*m\^2"),
    ('[parameters]\nJ1 = nan\n', "'J1' must be finite"),
    ('[parameters]\nmu = 0.134\nrho = "8 deg"\n', "both 'mu' and 'rho'"),
    ('[parameters]\ndT = 0.7\nDT = 0.014\n', "both 'dT' and 'DT'"),
])
@pytest.mark.messages
def test_load_config_errors(tmp_path, text, pattern):
    path = _Write(tmp_path, text)
    with pytest.raises(ValueError, match=pattern) as info:
        LoadConfig(path)
    assert str(path) in str(info.value)


@pytest.mark.messages
def test_load_config_unreadable(tmp_path):
    with pytest.raises(ValueError, match='cannot read it'):
        LoadConfig(tmp_path / 'missing.toml')
    with pytest.raises(ValueError, match=r"^LoadConfig: '.*': is a folder, expected a TOML drive file$"):
        LoadConfig(tmp_path)                                   # a directory
    path = tmp_path / 'latin1.toml'
    path.write_bytes('[parameters]\n# M\xfcller\nJ1 = 0.1\n'.encode('latin-1'))
    with pytest.raises(ValueError, match='not valid TOML'):
        LoadConfig(path)


# --- ResolveParameters -----------------------------------------------------------------------------
def test_resolve_default_is_reel_p1():
    assert DEFAULT_PRESET == 'reel-P1'
    assert ResolveParameters() == GetPreset('reel-P1')


def test_resolve_preset_precedence(tmp_path):
    path = _Write(tmp_path, 'preset = "reel-P2"\n[parameters]\nbacklash = "0.5 mm"\n')
    fromConfig = ResolveParameters(config=path)
    assert fromConfig['J1'] == 0.3 and fromConfig['backlash'] == pytest.approx(5e-4)     # config's preset
    explicit = ResolveParameters(preset='reel-P3', config=path)
    assert explicit['J1'] == 0.033 and explicit['backlash'] == pytest.approx(5e-4)      # explicit preset wins
    noPreset = _Write(tmp_path, '[parameters]\nJ1 = 0.2\n', 'nopreset.toml')
    assert ResolveParameters(config=noPreset) == {**GetPreset('reel-P1'), 'J1': 0.2}


def test_resolve_layers_in_order(tmp_path):
    path = _Write(tmp_path, '[parameters]\nJ1 = 0.2\nkT = 8000\n')
    p = ResolveParameters(config=path, sets=['J1=0.25'])
    assert p['J1'] == 0.25 and p['kT'] == 8000.
    assert ResolveParameters(config={'parameters': {'J1': '200 g*m^2'}})['J1'] == pytest.approx(0.2)
    assert ResolveParameters(sets=[('J1', '0.3 kg*m^2')])['J1'] == pytest.approx(0.3)
    assert ResolveParameters(sets=['J1=0.2', 'J1=0.4'])['J1'] == 0.4                      # last wins


def test_resolve_alternatives_are_replaced(tmp_path):
    p = ResolveParameters(sets=['dT=1.5'])
    assert p['dT'] == 1.5 and 'DT' not in p and 'DTV' not in p
    p = ResolveParameters(sets=['mu=0.134'])
    assert p['mu'] == 0.134 and 'rho' not in p
    p = ResolveParameters('reel-P6', sets=['DT=0.02'])
    assert 'DTV' not in p and p['DT'] == 0.02
    p = ResolveParameters(config=_Write(tmp_path, '[parameters]\ndV = 20000\n'))
    assert p['dV'] == 20000. and 'DV' not in p
    p = ResolveParameters('reel-P6', sets=['DV=0.056'])        # paper section 3.2.4
    assert p['DV'] == 0.056 and p['DTV'] == 2. and p['J1'] == 0.2 and p['kT'] == 12000.


@pytest.mark.messages
@pytest.mark.parametrize('kwargs, error, pattern', [
    (dict(preset='nope'), ValueError, "unknown preset 'nope'"),
    (dict(sets=['foo=1']), ValueError, "unknown parameter 'foo'"),
    (dict(sets=['mu=0.1', 'rho=0.1 rad']), ValueError, "both 'mu' and 'rho'"),
    (dict(sets=['dT=1', 'DTV=2']), ValueError, "both 'dT' and 'DTV'"),
    (dict(sets='J1=0.2'), TypeError, 'single string'),
    (dict(sets=[3.]), TypeError, "'KEY=VALUE' or \\(key, value\\)"),
    (dict(config=3), TypeError, "'config' must be a path or a dict"),
    (dict(config={'preset': 'nope'}), ValueError, "unknown preset 'nope'"),
])
def test_resolve_errors(kwargs, error, pattern):
    with pytest.raises(error, match=pattern):
        ResolveParameters(**kwargs)
