"""Gear geometry from its designation: exudyn_worm/model/geometry.py and the [gear] forms."""
import json
import math
import subprocess
import sys

import pytest
from hypothesis import given, settings, strategies as st

from exudyn_worm.drive.config import ResolveParameters
from exudyn_worm.model.contact import ContactOptions, MeshContact
from exudyn_worm.model.geometry import (DescribeGeometry, DesignationFromRadii, GeometryFromParameters,
                                  MeshStiffnessFromWheelTorsion, RadiiFromCentreDistance, RadiiFromDesignation)
from exudyn_worm.drive.presets import ApplyOverrides, CheckParameterKeys, ElasticDriveFromParameters, GetPreset
from exudyn_worm.params.parameters import MissingParameterError

deg = math.radians
P1 = GetPreset('reel-P1')
_BASE = {k: v for k, v in P1.items() if k not in ('r1', 'r2', 'gamma')}


# -- published worked examples --------------------------------------------------------------------------------

def test_axial_module_example_worm_gear_formula_master():
    """The axial-module worm gear pair "Ref. Niemann / DIN" of the sheet "Worm Gear Formula-Master"
    (scribd document 418425143): z1 = 2, z2 = 30, mx = 3, a = 67, working PCD dm = 44 / 90, tooth profile factor
    (diameter quotient) 14.6666666667, ratio i = 15, lead angle 7.7651660184 deg. dm1 = 44 printed exactly gives
    q = 44/3; the lead angle is printed to 11 digits."""
    r1, r2, gamma = RadiiFromDesignation(3e-3, 2, 30, 44 / 3)
    assert (2 * r1 * 1e3, 2 * r2 * 1e3) == pytest.approx((44., 90.), rel=1e-12)
    assert math.degrees(gamma) == pytest.approx(7.7651660184, abs=5e-11)
    assert (r1 + r2) * 1e3 == pytest.approx(67., rel=1e-12)
    drive = ElasticDriveFromParameters({**_BASE, 'mx': 3e-3, 'z1': 2, 'z2': 30, 'q': 44 / 3})
    assert drive.gear.ratio == pytest.approx(15., rel=1e-12)          # eq. (3) gives z2/z1
    # the same gear from its centre distance, ratio and lead angle
    assert RadiiFromCentreDistance(0.067, 15., gamma) == pytest.approx((0.022, 0.045), rel=1e-12)


def test_axial_module_example_bolsover():
    """bolsover.com, "Axial Module Worm Gears" (utilitiesforalibre/axial-module-worm-gears.html): module 3,
    2 threads, 30 teeth, worm pitch diameter 23.719, gear pitch diameter 90, lead angle 14.196 deg, centre
    distance 56.859 (all printed to 3 decimals: tolerances half a unit of the last digit, plus the effect of
    the rounded 23.719 on the centre distance)."""
    r1, r2, gamma = RadiiFromDesignation(3e-3, 2, 30, 23.719 / 3)
    assert 2 * r2 * 1e3 == pytest.approx(90., rel=1e-12)
    assert math.degrees(gamma) == pytest.approx(14.196, abs=5e-4)
    assert (r1 + r2) * 1e3 == pytest.approx(56.859, abs=5e-4 + 2.5e-4)


# -- round trips ----------------------------------------------------------------------------------------------

@settings(max_examples=100, deadline=None)
@given(r1=st.floats(2e-3, 0.2), u=st.floats(1., 120.), gamma=st.floats(0.5, 40.), z1=st.integers(1, 6))
def test_radii_designation_radii_round_trip(r1, u, gamma, z1):
    gamma = deg(gamma)
    r2 = u * r1 * math.tan(gamma)
    d = DesignationFromRadii(r1, r2, gamma, z1=z1)
    assert d['z2'] / d['z1'] == pytest.approx(u, rel=1e-12)
    assert RadiiFromDesignation(d['mx'], d['z1'], d['z2'], d['q']) == pytest.approx((r1, r2, gamma), rel=1e-12)
    assert RadiiFromCentreDistance(d['a'], d['u'], gamma) == pytest.approx((r1, r2), rel=1e-10)


def test_p1_through_its_designation():
    """Set (28): r1 = 18.05 mm, r2 = 105.95 mm, gamma = 5.3228 deg is a single-start gear with u = 63."""
    d = DesignationFromRadii(P1['r1'], P1['r2'], P1['gamma'], z1=1)
    assert d['z2'] == pytest.approx(63., abs=5e-3)                    # the paper prints u = 63
    back = RadiiFromDesignation(d['mx'], d['z1'], d['z2'], d['q'])
    assert back == pytest.approx((P1['r1'], P1['r2'], P1['gamma']), rel=1e-12)
    centre = ElasticDriveFromParameters({**_BASE, 'a': d['a'], 'u': d['u'], 'gamma': P1['gamma']}).gear
    assert (centre.r1, centre.r2) == pytest.approx((P1['r1'], P1['r2']), rel=1e-12)


@pytest.mark.parametrize('form', [{'a': 0.04, 'u': 40., 'gamma': deg(3.5)},
                                  {'mx': 2e-3, 'z1': 1, 'z2': 40, 'q': 16.}])
def test_every_form_gives_the_same_drive_as_its_radii(form):
    r1, r2, gamma = GeometryFromParameters(form)
    a = ElasticDriveFromParameters({**_BASE, **form})
    b = ElasticDriveFromParameters({**_BASE, 'r1': r1, 'r2': r2, 'gamma': gamma})
    assert a == b
    assert a.gear.ratio == pytest.approx(form.get('u', form.get('z2', 0) / form.get('z1', 1)), rel=1e-12)


def test_overrides_change_the_form():
    p = ApplyOverrides(P1, {'a': 0.04, 'u': 40., 'gamma': deg(3.5)})
    assert 'r1' not in p and 'r2' not in p and p['a'] == 0.04
    p = ApplyOverrides(p, {'mx': 2e-3, 'z1': 1, 'z2': 40, 'q': 16.})
    assert not {'a', 'u', 'gamma', 'r1', 'r2'} & set(p)
    p = ApplyOverrides(p, {'r1': 0.016, 'r2': 0.04, 'gamma': deg(3.6)})
    assert not {'mx', 'z1', 'z2', 'q'} & set(p)


# -- refusals -------------------------------------------------------------------------------------------------

@pytest.mark.parametrize('mixed', [{'a': 0.04}, {'mx': 3e-3}, {'u': 40.}, {'q': 10.}])
def test_mixed_forms_are_refused(mixed):
    with pytest.raises(ValueError, match=r"different forms of the gear geometry; give one form: gamma, r1, r2 "
                                         r"\(radii\); or gamma, a, u \(centre distance\); or mx, z1, z2, q"):
        CheckParameterKeys({**P1, **mixed}, 'f')


@pytest.mark.parametrize('given, missing', [({'a': 0.04, 'u': 40.}, 'gamma'),
                                            ({'a': 0.04, 'gamma': deg(3.5)}, 'u'),
                                            ({'mx': 3e-3, 'z1': 2, 'z2': 30}, 'q'),
                                            ({'z2': 30, 'q': 10.}, 'mx, z1'),
                                            ({'r1': 0.02, 'gamma': deg(3.5)}, 'r2')])
def test_incomplete_forms_name_what_is_missing(given, missing):
    with pytest.raises(MissingParameterError, match=rf"missing parameter\(s\) {missing} \(.*gear geometry"):
        ElasticDriveFromParameters({**_BASE, **given})


@pytest.mark.parametrize('key, value, pattern', [('z1', 1.5, r"'z1' must be a whole number >= 1"),
                                                 ('z2', 0, r"'z2' must be >= 1"),
                                                 ('q', -3., r"'q' must be > 0")])
def test_designation_values_out_of_range(key, value, pattern):
    with pytest.raises(ValueError, match=pattern):
        ElasticDriveFromParameters({**_BASE, 'mx': 3e-3, 'z1': 2, 'z2': 30, 'q': 10., key: value})


# -- files and command line -----------------------------------------------------------------------------------

def test_drive_file_designation(tmp_path):
    path = tmp_path / 'drive.toml'
    path.write_text('preset = "reel-P1"\n[gear]\naxialModule = "3 mm"\nstarts = 2\nwheelTeeth = 30\n'
                    'diameterQuotient = 14.666666666666666\n')
    p = ResolveParameters(config=path)
    assert ElasticDriveFromParameters(p).gear.r1 == pytest.approx(0.022, rel=1e-12)
    assert 'r1' not in p and 'gamma' not in p


def _Run(*args, cwd):
    return subprocess.run([sys.executable, '-m', 'exudyn_worm', *args], capture_output=True, text=True, cwd=cwd)


def test_cli_stability_prints_the_derived_geometry(tmp_path):
    run = _Run('stability', '--set', 'a=40 mm', '--set', 'u=40', '--set', 'gamma=3.5 deg', cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    r1 = 40. / (1 + 40 * math.tan(deg(3.5)))
    assert (f"r1 = {r1:.6g} mm, r2 = {40 - r1:.6g} mm, gamma = 3.5 deg, u = r2/(r1 tan(gamma)) = 40"
            in run.stdout)
    row = next(line for line in run.stdout.splitlines() if 'reference radii r1, r2 [mm]' in line)
    assert [float(x) for x in row.split()[-2:]] == pytest.approx([r1, 40 - r1], rel=1e-4)
    assert DescribeGeometry(P1) == ''
    data = json.loads(_Run('stability', '--json', '--set', 'mx=3 mm', '--set', 'z1=2', '--set', 'z2=30',
                           '--set', 'q=14.666666666666666', cwd=tmp_path).stdout)
    assert data['geometry']['form'] == 'designation'
    assert (data['geometry']['r1'], data['geometry']['r2'], data['geometry']['u']) == pytest.approx((0.022, 0.045, 15.),
                                                                                                    rel=1e-12)


@pytest.mark.parametrize('args, text', [
    (['--set', 'mx=3 mm', '--set', 'z1=2', '--set', 'z2=30'], "missing parameter(s) q"),
    (['--set', 'mx=3 mm', '--set', 'z1=2', '--set', 'z2=30', '--set', 'q=10', '--set', 'r1=3 mm'],
     "different forms of the gear geometry"),
    (['--set', 'mx=3 mm', '--set', 'z1=2.5', '--set', 'z2=30', '--set', 'q=10'], "'z1' must be a whole number >= 1"),
])
def test_cli_bad_geometry_one_line_exit_2(tmp_path, args, text):
    run = _Run('stability', *args, cwd=tmp_path)
    assert run.returncode == 2 and run.stdout == ''
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and text in lines[0], run.stderr


def test_mesh_stiffness_from_wheel_torsion_inverts_the_contact_law():
    """The torque the contact law puts on the wheel per wheel angle, worm held, frictionless gear (mu = 0):
    k_phi2 = -d(wheelTorque)/d(phi2); MeshStiffnessFromWheelTorsion(k_phi2) must give back kV."""
    gear = ElasticDriveFromParameters({**P1, 'mu': 0.}).gear
    phi2 = -1e-6                                         # wheel turned against the worm: the flank is loaded
    torque = MeshContact(gear, 0., phi2, 0., 0., ContactOptions()).wheelTorque
    kPhi2 = -torque / phi2
    assert MeshStiffnessFromWheelTorsion(kPhi2, gear.r2, gear.alphaN, gear.gamma) == pytest.approx(gear.kV, rel=1e-9)
