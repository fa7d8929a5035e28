"""Parameter checks name the user's key, reject values that overflow the model, and catch unit mistakes."""
import math
from pathlib import Path

import pytest

from exudyn_worm import ApplyOverrides, DriveFromParameters, GetPreset, SimulateReelChanger, WormGear
from exudyn_worm.cli.main import Main
from exudyn_worm.drive.config import ResolveParameters
from exudyn_worm.analysis.design.designcheck import DesignCheck
from exudyn_worm.drive.presets import CheckParameterKeys, GearFromParameters, PRESETS
from exudyn_worm.analysis.studies.studygrid import Study
from exudyn_worm.drive.wholedrive import ResolveDrive


@pytest.mark.messages
@pytest.mark.parametrize('key, value, message', [
    ('kT', -5., "parameter set: 'kT' must be > 0 N*m/rad, got -5 N*m/rad"),
    ('J2', 0., "parameter set: 'J2' must be > 0 kg*m^2, got 0 kg*m^2"),
    ('DTV', -1., "parameter set: 'DTV' must be >= 0, got -1"),
    ('DV', -0.1, "parameter set: 'DV' must be >= 0, got -0.1"),
    ('gamma', 5.3, "parameter set: 'gamma' must be in (0, pi/2) rad"),
    ('r2', math.nan, "parameter set: 'r2' must be finite"),
])
def test_messages_name_the_key(key, value, message):
    with pytest.raises(ValueError) as info:
        DriveFromParameters(ApplyOverrides(GetPreset('reel-P6' if key == 'DTV' else 'reel-P1'), {key: value}))
    assert str(info.value).startswith(message)


@pytest.mark.messages
@pytest.mark.parametrize('overrides', [{'kT': 1e300}, {'J1': 1e-300}, {'kV': 1e300}, {'dT': 1e300}])
def test_overflowing_parameters_rejected(overrides):
    with pytest.raises(ValueError, match=r"parameter set: out of range: the drive's rates .* check these values"):
        DriveFromParameters(ApplyOverrides(GetPreset('reel-P1'), overrides))


@pytest.mark.messages
@pytest.mark.parametrize('overrides', [{'J1': 1e100}, {'kT': 1e-100}])
def test_frequencies_far_apart_rejected(overrides):
    """J1 = 1e100 kg*m^2 passed and gave 'Hurwitz conditions ok' next to 'Verdict: UNSTABLE': the slow mode
    was round-off. Frequencies more than 1e12 apart are refused; 1e6 kg*m^2 still works."""
    with pytest.raises(ValueError, match=r"out of range: its two natural frequencies lie more than 1e12 apart"):
        DriveFromParameters(ApplyOverrides(GetPreset('reel-P1'), overrides))
    DriveFromParameters(ApplyOverrides(GetPreset('reel-P1'), {'J1': 1e6}))


def test_every_preset_is_within_range():
    for name in PRESETS:
        DriveFromParameters(ApplyOverrides(GetPreset(name), {'J1': 0.01, 'kT': 10., 'DT': 0.01}) if name == 'chart'
                            else GetPreset(name))


@pytest.mark.messages
@pytest.mark.parametrize('value', ['kT=1e300', 'J1=1e-300'])
def test_stability_cli_overflow_is_one_line(capsys, value):
    status = Main(['stability', '--set', value])
    out, err = capsys.readouterr()
    assert status == 2 and err.count('\n') == 1 and 'out of range' in err and 'Traceback' not in err


@pytest.mark.messages
def test_backlash_above_the_worm_radius_suggests_the_unit():
    gear = DriveFromParameters(GetPreset('reel-P1')).gear
    with pytest.raises(ValueError, match=r"WormGear: 'backlash' must be <= the worm radius r1 = 0.01805 m, got 0.5 m; "
                                         r"backlash is in m: for 0.5 mm give 0.0005"):
        gear.Replace(backlash=0.5)
    assert gear.Replace(backlash=0.5e-3).backlash == 0.5e-3
    assert isinstance(gear.Replace(backlash=gear.r1), WormGear)


# --- keys of a parameter set: typos and two forms of one quantity (found by a QA pass) ---------------------------
P1 = GetPreset('reel-P1')
_KNOWN = ("expected one of: alphaN gamma mu rho r1 r2 a u mx z1 z2 q kV dV DV backlash frictionLaw muStatic "
          "stribeckVelocity frictionTable J1 J2 kT")


def _Resolve(p):
    return ResolveDrive(parameters=p)


def _Study(p):
    return Study(p)


@pytest.mark.messages
@pytest.mark.parametrize('call, where', [
    (DriveFromParameters, 'DriveFromParameters'), (_Resolve, 'ResolveDrive'),
    (_Study, "Study: 'base'"),
])
@pytest.mark.parametrize('key, suggestion', [('Kt', " (did you mean 'kT'?)"), ('kt', " (did you mean 'kT'?)"),
                                             ('J_1', " (did you mean 'J1'?)"), ('rotations', '')])
def test_unknown_keys_are_refused_with_a_suggestion(call, where, key, suggestion):
    """{**P1, 'kt': 1.} ran SimulateReelChanger, DesignCheck and Study with the typo ignored; a flat set is now
    resolved (and refused) once, by ResolveDrive, before any analysis takes it."""
    with pytest.raises(ValueError) as info:
        call({**P1, key: 1.})
    assert str(info.value).startswith(f"{where}: unknown parameter {key!r}{suggestion}; {_KNOWN}")


@pytest.mark.messages
def test_unknown_key_message_is_the_cli_one():
    with pytest.raises(ValueError, match=r"^ParseSetOption: unknown parameter 'Kt' \(did you mean 'kT'\?\); "):
        ResolveParameters('reel-P1', sets=['Kt=5'])
    with pytest.raises(ValueError, match=r"^chart: unknown parameter 'Dv' \(did you mean 'dV' or 'DV'\?\)"):
        GearFromParameters({**GetPreset('chart'), 'Dv': 1.}, meshDamping=False, where='chart')


@pytest.mark.messages
@pytest.mark.parametrize('added, group, quantity, dropped', [
    ({'dV': 1.}, "'DV' and 'dV'", 'mesh damping', "'DV'"),
    ({'DTV': 5.}, "'DT' and 'DTV'", 'drive-shaft damping', "'DT'"),
    ({'dT': 100.}, "'DT' and 'dT'", 'drive-shaft damping', "'DT'"),
    ({'rho': math.radians(8)}, "'mu' and 'rho'", 'flank friction', "'mu'"),
    ({'dT': 1., 'DTV': 2.}, "'DT' and 'dT' and 'DTV'", 'drive-shaft damping', "'DT' and 'dT'"),
])
def test_two_forms_of_one_quantity_are_refused(added, group, quantity, dropped):
    """{**P1, 'dV': 1.} used dV = 1 and ignored DV = 0.014; {**P1, 'DTV': 5.} kept DT; {**P1, 'dT': 100.} used dT."""
    last = list(added)[-1]
    with pytest.raises(ValueError) as info:
        DriveFromParameters({**P1, **added})
    assert str(info.value) == (f"DriveFromParameters: {group} are given together, which describe the same quantity "
                               f"({quantity}); give only one of them (to replace one form by another, use "
                               f"ApplyOverrides(parameters, {{{last!r}: {added[last]!r}}}), which sets {last!r} and "
                               f"drops {dropped})")


@pytest.mark.parametrize('override, dropped', [({'dV': 21470.}, 'DV'), ({'DTV': 1.}, 'DT'), ({'dT': 0.741}, 'DT'),
                                               ({'rho': math.radians(8)}, 'mu')])
def test_apply_overrides_replaces_the_other_form(override, dropped):
    """The CLI's --set and the design scans change one form of a quantity with ApplyOverrides: still accepted."""
    p = ApplyOverrides(P1, override)
    assert dropped not in p and DriveFromParameters(p)


@pytest.mark.messages
def test_apply_overrides_checks_both_mappings():
    with pytest.raises(ValueError, match=r"^ApplyOverrides: 'overrides': unknown parameter 'Kt' \(did you mean 'kT'"):
        ApplyOverrides(P1, {'Kt': 1.})
    with pytest.raises(ValueError, match=r"^ApplyOverrides: 'DV' and 'dV' are given together"):
        ApplyOverrides({**P1, 'dV': 1.}, {'J1': 0.2})
    # overrides apply in order: the later form wins (validation/analytical.py sets mu, then rho)
    assert ApplyOverrides(P1, {'mu': 0.1, 'rho': 0.14})['rho'] == 0.14 and 'mu' not in ApplyOverrides(P1, {'rho': 0.1})
    with pytest.raises(TypeError, match=r"^ApplyOverrides: 'overrides' must be a mapping .*e.g. \{'J1': 0.3\}, got str"):
        ApplyOverrides(P1, 'J1=0.3')


def test_every_example_and_preset_set_passes_the_key_check():
    """Internal code carries no extra keys into a parameter set: presets, drive files, design recommendations."""
    for name in PRESETS:
        CheckParameterKeys(GetPreset(name))
    for path in sorted((Path(__file__).resolve().parents[1] / 'examples' / 'drives').glob('*.toml')):
        CheckParameterKeys(ResolveParameters(config=path))
    result = DesignCheck(ResolveDrive(parameters=P1))
    for r in result.recommendations:
        CheckParameterKeys(ApplyOverrides(P1, r.changes))
