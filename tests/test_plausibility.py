"""Plausibility of a worm gear: refusals and warnings naming the likely unit slip."""
import math
import re
import subprocess
import sys
import warnings

import pytest

from exudyn_worm.model.gear import WormGear
from exudyn_worm.params.plausibility import ImplausibleValueWarning
from exudyn_worm.setups.presets import PRESETS, ElasticDriveFromParameters, GearFromParameters, GetPreset

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
    run = _Run('check', '--set', 'mu=0.8', '--set', 'r1=0.2', cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 2, run.stderr
    assert lines[0].startswith('exudyn-worm: warning: WormGear: flank friction mu = 0.8')
    assert lines[1].startswith('exudyn-worm: warning: WormGear: the worm radius r1 = 0.2 m')
    assert 'Verdict' in run.stdout


def test_api_refusal_from_a_parameter_set():
    with pytest.raises(ValueError, match=r"mm given as m\? 18.05 mm = 0.01805 m"):
        ElasticDriveFromParameters({**GetPreset('reel-P1'), 'r1': 18.05})
