"""Plausibility of a worm gear: refusals and warnings naming the likely unit slip."""
import math
import re
import subprocess
import sys
import warnings

import pytest

from exudyn_worm.model.gear import WormGear
from exudyn_worm.analysis.simulation.stepsize import RecommendedStepSize
from exudyn_worm.params.plausibility import (MAX_WORM_SPEED_RATIO, MIN_STEPS_PER_ROTATION, CheckWormRotation,
                                             CheckWormSpeed, ImplausibleValueWarning, UnresolvedRotationWarning)
from exudyn_worm.drive.presets import PRESETS, ElasticDriveFromParameters, GearFromParameters, GetPreset
from exudyn_worm.drive.wholedrive import ResolveDrive

deg = math.radians
GEAR = dict(alphaN=deg(20), gamma=deg(5.3228), r1=0.01805, r2=0.10595, kV=2e8, dV=21470., mu=0.132)


@pytest.mark.parametrize('name', list(PRESETS))
def test_presets_are_plausible(name):
    with warnings.catch_warnings():
        warnings.simplefilter('error')
        GearFromParameters(GetPreset(name), meshDamping=False)


def test_radius_in_mm_given_as_m_is_refused():
    """A user's case: r1 = 18.05 (mm typed as m) gives u = 0.063."""
    with pytest.raises(ValueError, match=r"WormGear: the transmission ratio u = r2/\(r1 tan\(gamma\)\) of eq. \(3\) "
                                         r"must be >= 1 .*got u = 0.063 .*mm given as m\? 18.05 mm = 0.01805 m"):
        WormGear(**{**GEAR, 'r1': 18.05})


def test_lead_angle_in_degrees_given_as_rad_is_named():
    with pytest.raises(ValueError, match=r"must be >= 1 .*degrees given as rad\? 1.2 deg = 0.02094 rad"):
        WormGear(**{**GEAR, 'r2': 0.02, 'gamma': 1.2})


def test_worm_that_cannot_drive_is_refused():
    """mu = 12 (12 % meant): rho = 85.5 deg, gamma + rho > 90 deg, efficiency with the worm driving < 0."""
    with pytest.raises(ValueError, match=r"gamma \+ rho must be < 90 deg .*efficiency .*<= 0.*percent given as a "
                                         r"number\? 12 % = 0.12"):
        WormGear(**{**GEAR, 'mu': 12.})
    below = WormGear(**{**GEAR, 'mu': 0.132})
    assert below.efficiencyWormDriving > 0


@pytest.mark.parametrize('mu, slip', [(0.8, False), (5., True)])
def test_large_friction_is_warned(mu, slip):
    with pytest.warns(ImplausibleValueWarning, match=rf"flank friction mu = {mu:g} .*warned above 0.5") as record:
        gear = WormGear(**{**GEAR, 'mu': mu})
    assert gear.mu == mu
    assert ('percent given as a number? 5 % = 0.05' in str(record[0].message)) == slip


def test_mu_at_the_limit_is_not_warned():
    with warnings.catch_warnings():
        warnings.simplefilter('error')
        WormGear(**{**GEAR, 'mu': 0.5})


@pytest.mark.parametrize('r1, r2, slip', [(0.2, 0.10595, "check 'r1' and its unit"),
                                           (0.6, 0.5, "mm given as m? 0.6 mm = 0.0006 m")])
def test_worm_larger_than_wheel_is_warned(r1, r2, slip):
    with pytest.warns(ImplausibleValueWarning, match=rf"worm radius r1 = {r1:g} m is larger than the wheel radius "
                                                     rf"r2 = {r2:g} m .*{re.escape(slip)}"):
        gear = WormGear(**{**GEAR, 'r1': r1, 'r2': r2, 'gamma': deg(1.)})
    assert gear.ratio >= 1


def _Run(*args, cwd):
    return subprocess.run([sys.executable, '-m', 'exudyn_worm', *args], capture_output=True, text=True, cwd=cwd)


@pytest.mark.parametrize('sets, text', [(['r1=18.05'], '18.05 mm = 0.01805 m'),
                                        (['mu=12'], 'gamma + rho must be < 90 deg')])
def test_cli_refusal_one_line_exit_2(tmp_path, sets, text):
    run = _Run('stability', *(a for s in sets for a in ('--set', s)), cwd=tmp_path)
    assert run.returncode == 2 and run.stdout == ''
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith('exudyn-worm: error: ') and text in lines[0], run.stderr


@pytest.mark.slow
def test_cli_warns_once_on_stderr(tmp_path):
    """`check` builds the gear many times (the stabilizing changes): each warning is printed once."""
    run = _Run('check', '--set', 'mu=0.8', '--set', 'r1=0.2 m', cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 2, run.stderr
    assert lines[0].startswith('exudyn-worm: warning: the gear: flank friction mu = 0.8')       # no function's name
    assert lines[1].startswith('exudyn-worm: warning: the gear: the worm radius r1 = 0.2 m')
    assert 'Verdict' in run.stdout


def test_api_refusal_from_a_parameter_set():
    with pytest.raises(ValueError, match=r"mm given as m\? 18.05 mm = 0.01805 m"):
        ElasticDriveFromParameters({**GetPreset('reel-P1'), 'r1': 18.05})


# --- speeds and loads of a simulation --------------------------------------------------------------------------
REEL_PRESETS = [name for name in PRESETS if name.startswith('reel-')]


@pytest.mark.parametrize('name', REEL_PRESETS)
def test_preset_speeds_are_plausible(name):
    p = GetPreset(name)
    with warnings.catch_warnings():
        warnings.simplefilter('error')
        CheckWormRotation(p, RecommendedStepSize(ResolveDrive(parameters=p)))
        CheckWormSpeed([0., p['motorSpeed'], -2. * p['motorSpeed']], [p['motorSpeed']], p)   # chatter: a few times


def test_a_worm_rotation_in_fewer_than_a_few_steps_is_warned():
    """The corpus's case: motorSpeed = 1e6 rad/s turns the worm once in 6.3 us, far less than one step."""
    p = {**GetPreset('reel-P1'), 'motorSpeed': 1e6}
    with pytest.warns(UnresolvedRotationWarning, match=r"'motorSpeed' = 1e\+06 rad/s \(9.549e\+06 rpm\) turns the worm "
                                                       r"once in 6.28e-06 s, fewer than 10 time steps of 0.000776 s"):
        CheckWormRotation(p, 7.76e-4, 'SimulateReelChanger')
    assert issubclass(UnresolvedRotationWarning, ImplausibleValueWarning)
    # at the limit: 10 steps per rotation are not warned about, 9.9 are
    with warnings.catch_warnings():
        warnings.simplefilter('error')
        CheckWormRotation({'motorSpeed': 2 * math.pi / (MIN_STEPS_PER_ROTATION * 1e-3)}, 1e-3)
    with pytest.warns(UnresolvedRotationWarning):
        CheckWormRotation({'motorSpeed': 2 * math.pi / (MIN_STEPS_PER_ROTATION * 0.99e-3)}, 1e-3)
    with pytest.warns(UnresolvedRotationWarning, match="'noLoadSpeed' = 5000 rad/s"):
        CheckWormRotation({'motorType': 'characteristic', 'noLoadSpeed': 5000.}, 1e-3)


def test_a_worm_far_faster_than_the_motor_is_warned():
    p = {**GetPreset('reel-P1'), 'loadMass': 1e9}
    with pytest.warns(ImplausibleValueWarning, match=r"^simulation: the worm turned at -3.4e\+06 rad/s, 6.87e\+04 times "
                                                     r"the motor's largest speed 49.48 rad/s .*loadMass = 1e\+09 kg, "
                                                     r"leverArm = 1.2 m\); check the load values"):
        CheckWormSpeed([49.48, -3.4e6], [49.48, 49.48], p, 'simulation')
    with warnings.catch_warnings():          # ten times the motor's speed is the limit
        warnings.simplefilter('error')
        CheckWormSpeed([MAX_WORM_SPEED_RATIO * 49.48], [49.48], p)


def test_cli_warns_of_a_load_that_drives_the_worm(tmp_path):
    """loadMass = 1e9 kg ran through without a word, the worm at millions of rad/s; now one warning line."""
    run = _Run('simulate', '--set', 'loadMass=1e9', '--end-time', '0.1', '--windows', '0:0.05,0.05:0.1', '--quiet',
               '--no-check-step', cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith('exudyn-worm: warning: simulation: the worm turned at '), lines
    assert 'SimulateReelChanger' not in run.stderr
    assert 'loadMass = 1e+09 kg' in lines[0] and 'Traceback' not in run.stderr
    assert list(tmp_path.iterdir()) == []


def test_cli_names_a_rotation_shorter_than_a_step(tmp_path):
    """motorSpeed = 1e6 rad/s: the warning says why before the refusal of a run shorter than one step."""
    run = _Run('simulate', '--set', 'motorSpeed=1e6 rad/s', cwd=tmp_path)
    assert run.returncode == 2 and run.stdout == ''
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 2 and 'Traceback' not in run.stderr, run.stderr
    assert lines[0].startswith("exudyn-worm: warning: simulate: 'motorSpeed' = 1e+06 rad/s (9.549e+06 rpm) turns the "
                               "worm once in 6.28e-06 s")
    assert lines[1].startswith('exudyn-worm: error: ')
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize('command', ['stability', 'check'])
def test_linear_commands_warn_of_a_speed_no_run_could_resolve(tmp_path, command):
    """stability and check simulate nothing, yet motorSpeed = 1e6 (rpm typed as rad/s) passed them without a word:
    they warn at the drive's own recommended step, once, and still give their verdict."""
    run = _Run(command, '--set', 'motorSpeed=1e6 rad/s', *(['--quiet'] if command == 'check' else []), cwd=tmp_path)
    assert run.returncode in (0, 1), run.stderr
    warned = [line for line in run.stderr.splitlines() if 'turns the worm once' in line]
    assert len(warned) == 1, run.stderr
    assert warned[0].startswith(f"exudyn-worm: warning: {command} (at the drive's recommended step): 'motorSpeed' = "
                                f"1e+06 rad/s (9.549e+06 rpm) turns the worm once in 6.28e-06 s, fewer than 10 time "
                                f"steps of 0.000776 s"), warned[0]
    assert 'Traceback' not in run.stderr and run.stdout.strip()
    assert list(tmp_path.iterdir()) == []


def test_linear_commands_are_quiet_at_a_plausible_speed(tmp_path):
    run = _Run('stability', cwd=tmp_path)
    assert run.returncode in (0, 1) and 'turns the worm once' not in run.stderr, run.stderr
