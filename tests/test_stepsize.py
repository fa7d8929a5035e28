"""Step size from the drive (exudyn_worm.analysis.simulation.stepsize) and the coarse-step refusal."""
import json
import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from exudyn_worm.cli.main import Main
from exudyn_worm.drive.config import ResolveParameters
from exudyn_worm.analysis.stability.linearization import LinearStabilityOfDrive
from exudyn_worm.analysis.stability.drivestability import AnalyzeDrive
from exudyn_worm.drive.presets import ApplyOverrides, GetPreset
from exudyn_worm.analysis.simulation.reelchanger import SimulateReelChanger
from exudyn_worm.analysis.simulation.stepsize import (HARD_CYCLES, RECOMMENDED_CYCLES, SOFT_CYCLES, CheckStepSize, CoarseStepWarning,
                                  LinearizedFrequencies, PeriodError, RecommendedStepSize, StepSizeLimits)
from exudyn_worm.drive.wholedrive import ResolveDrive
from paper_model import AxialBearingEigenvalues, ChainEigenvalues, Eigenvalues


def _Frequencies(eigenvalues):
    """(highest undamped |lambda| / 2 pi, highest damped frequency of a growing mode or None) in Hz."""
    lam = np.concatenate(eigenvalues)
    growing = lam[lam.real > 0]
    return (np.abs(lam).max() / (2 * math.pi),
            np.abs(growing.imag).max() / (2 * math.pi) if growing.size else None)


@pytest.mark.physics
def test_frequencies_of_p1_are_those_of_the_linear_model():
    """The roots of the characteristic polynomial (15) with the b's of eq. (16) written out (tests/paper_model.py).
    The paper prints 52.2 Hz for the S = +1 second mode and 42.0 Hz for the growing one (section 3.1); our
    eq. (16) gives 50.4 and 40.5 Hz (a known difference, validation/REPORT.md)."""
    p1 = GetPreset('reel-P1')
    maxHz, chatterHz = _Frequencies([Eigenvalues(p1, S) for S in (+1, -1)])
    f = LinearizedFrequencies(ResolveDrive(parameters=p1))
    assert f['maxHz'] == pytest.approx(maxHz, rel=1e-9)          # S = +1, second mode
    assert f['chatterHz'] == pytest.approx(chatterHz, rel=1e-9)  # the growing mode of S = -1
    assert LinearizedFrequencies(ResolveDrive(parameters=GetPreset('reel-P2')))['chatterHz'] is None


def _TrapezoidalPeriodError(cycles):
    """The period error of the trapezoidal rule at f h = ``cycles``, by another route than the formula of the module:
    one step of the rule on x'' = -omega^2 x (f = 1 Hz, h = cycles) is the matrix (I - h A/2)^-1 (I + h A/2) of
    the state (x, x'); its eigenvalues exp(+-i theta) (|.| = 1: the rule keeps the energy) turn the state by
    theta per step, so the computed period is 2 pi h / theta against the true 1 s."""
    h, A = cycles, np.array([[0., 1.], [-(2 * math.pi)**2, 0.]])
    step = np.linalg.solve(np.eye(2) - 0.5 * h * A, np.eye(2) + 0.5 * h * A)
    lam = np.linalg.eigvals(step)
    assert np.abs(lam) == pytest.approx(1., abs=1e-12)
    return 2 * math.pi * h / abs(np.angle(lam[0])) - 1.


@pytest.mark.physics
def test_period_error_is_the_trapezoidal_one():
    assert PeriodError(40.5, 1e-4) == pytest.approx((2 * math.pi * 40.5e-4)**2 / 12, rel=1e-3)
    assert PeriodError(40.5, 0.01) == pytest.approx(_TrapezoidalPeriodError(0.405), rel=1e-9)
    # P1 at h = 0.01 s: 40.5 Hz comes out as 40.5 / 1.41 = 28.8 Hz (the chatter frequency simulated at this step,
    # the module's text)
    assert 40.5 / (1 + PeriodError(40.5, 0.01)) == pytest.approx(28.8, abs=0.1)
    for cycles, error in ((RECOMMENDED_CYCLES, 0.005), (SOFT_CYCLES, 0.02), (HARD_CYCLES, 0.05)):
        assert _TrapezoidalPeriodError(cycles) == pytest.approx(error, rel=1e-9)


@pytest.mark.physics
def test_recommended_step_follows_the_stiffest_mode():
    p1, p3 = GetPreset('reel-P1'), GetPreset('reel-P3')       # P3: J1 / 3 raises f_max from 50 to 81 Hz
    maxHz, _ = _Frequencies([Eigenvalues(p1, S) for S in (+1, -1)])
    assert RecommendedStepSize(ResolveDrive(parameters=p1)) == pytest.approx(RECOMMENDED_CYCLES / maxHz, rel=1e-9)
    assert RecommendedStepSize(ResolveDrive(parameters=p3)) < RecommendedStepSize(ResolveDrive(parameters=p1))
    stiff = ApplyOverrides(p1, {'kV': 4 * p1['kV'], 'kT': 4 * p1['kT']})
    assert RecommendedStepSize(ResolveDrive(parameters=stiff)) < RecommendedStepSize(ResolveDrive(parameters=p1))
    limits = StepSizeLimits(ResolveDrive(parameters=p1))
    assert limits['recommended'] < limits['soft'] < limits['hard']


@pytest.mark.messages
@pytest.mark.parametrize('stepSize', [0.05, 0.01, 3e-3])
def test_coarse_step_that_lowers_the_frequency_is_refused(stepSize):
    with pytest.raises(ValueError, match=r"CheckStepSize: 'stepSize' must be <= 0.0025 s .* got "):
        CheckStepSize(ResolveDrive(parameters=GetPreset('reel-P1')), stepSize)


@pytest.mark.messages
def test_soft_limit_warns_and_default_step_is_quiet():
    with pytest.warns(CoarseStepWarning, match='50.4 Hz'):
        assert CheckStepSize(ResolveDrive(parameters=GetPreset('reel-P1')), 2e-3) == 2e-3
    with warnings.catch_warnings():
        warnings.simplefilter('error')
        for name in ('reel-P1', 'reel-P3', 'reel-P7'):
            CheckStepSize(ResolveDrive(parameters=GetPreset(name)), 5e-4)


@pytest.mark.messages
def test_simulate_refuses_before_computing():
    with pytest.raises(ValueError, match="SimulateReelChanger: 'stepSize' must be <="):
        SimulateReelChanger(ResolveDrive(parameters=GetPreset('reel-P1')), stepSize=0.01)


@pytest.mark.messages
def test_cli_refuses_the_coarse_step_in_one_line(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    status = Main(['simulate', '--preset', 'reel-P1', '--step-size', '0.05'])
    out, err = capsys.readouterr()
    assert status == 2 and out == ''
    assert err.startswith('exudyn-worm: error: ') and err.count('\n') == 1 and '50.4 Hz' in err
    assert 'Traceback' not in err and list(tmp_path.iterdir()) == []


def test_cli_warns_for_a_coarse_step_and_runs(capsys):
    status = Main(['simulate', '--preset', 'reel-P1', '--step-size', '2e-3', '--end-time', '2', '--windows', '0:2'])
    out, err = capsys.readouterr()
    assert status == 0 and 'chatter' in out
    assert err.startswith('exudyn-worm: warning: ') and 'recommended' in err


FIGURE19 = Path(__file__).resolve().parents[1] / 'examples' / 'drives' / 'figure19.toml'


@pytest.mark.physics
def test_a_drive_beyond_two_masses_gets_the_frequencies_of_its_whole_drive():
    """Figure 19's drive: the 116 Hz mode of inertia4 and the 36.96 Hz chatter mode that `stability` reports,
    not the two-mass model's 50.4 Hz and 40.5 Hz."""
    p = ResolveParameters(config=FIGURE19)
    f = LinearizedFrequencies(ResolveDrive(parameters=p))
    points = AnalyzeDrive(ResolveDrive(parameters=p)).operatingPoints              # the whole drive at its duty's operating points
    # the mass, damping and stiffness matrices of motor --k4-- J4 --kT-- J1 --mesh (14)-- J2 written out in
    # tests/paper_model.py; Exudyn's numerical linearization agrees to about 1e-10
    maxHz, chatterHz = _Frequencies([ChainEigenvalues(p, [(p['J4'], p['k4'], p['d4'])], S) for S in (+1, -1)])
    assert f['maxHz'] == pytest.approx(maxHz, rel=1e-8) and f['maxHz'] == pytest.approx(116.0, abs=0.05)  # toml
    growing = [m.frequencyHz for op in points for m in op.state.modes if m.eigenvalue.real > 0]
    assert f['chatterHz'] == pytest.approx(max(growing), rel=1e-12)
    assert f['chatterHz'] == pytest.approx(chatterHz, rel=1e-8)
    assert RecommendedStepSize(ResolveDrive(parameters=p)) == pytest.approx(RECOMMENDED_CYCLES / maxHz, rel=1e-8)
    assert RecommendedStepSize(ResolveDrive(parameters=p)) < 0.5 * RecommendedStepSize(ResolveDrive(parameters=GetPreset('reel-P1')))
    with pytest.raises(ValueError, match=r"'stepSize' must be <= 0.00108 s .* got 0.0015 s: the drive's highest "
                                         r"natural frequency is 116.0 Hz \(chatter mode 37.0 Hz\)"):
        CheckStepSize(ResolveDrive(parameters=p), 0.0015)


@pytest.mark.physics
def test_axial_bearing_enters_the_modes_but_its_own_mode_is_left_out():
    p = ApplyOverrides(GetPreset('reel-P1'), {'kA': 1e9, 'mA': 5.})
    f = LinearizedFrequencies(ResolveDrive(parameters=p))
    # the 3-DOF matrices [phi1, phi2, xA] written out in tests/paper_model.py; the bearing's own mode (about
    # 2440 Hz) is not resolved by the step, so it is left out of both frequencies
    lam = np.concatenate([AxialBearingEigenvalues(p, S) for S in (+1, -1)])
    drive = lam[np.abs(lam) / (2 * math.pi) < 1000.]
    maxHz, chatterHz = _Frequencies([drive])
    assert f['chatterHz'] == pytest.approx(chatterHz, rel=1e-8)       # the whole drive's growing mode
    assert f['maxHz'] == pytest.approx(maxHz, rel=1e-8)
    rigid, _ = _Frequencies([Eigenvalues(p, S) for S in (+1, -1)])
    assert f['maxHz'] < rigid                                         # kV in series with kA: below the rigid drive
    axial = [m.frequencyHz for s in LinearStabilityOfDrive(ResolveDrive(parameters=p)).states.values() for m in s.modes
             if m.energyShare['wormAxial'] > 0.5]
    assert axial and min(axial) > 2000.                               # the bearing's own stiff mode, not resolved


@pytest.mark.messages
def test_cli_step_rule_of_a_whole_drive_file(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    status = Main(['simulate', '--config', str(FIGURE19), '--step-size', '0.0015'])
    out, err = capsys.readouterr()
    assert status == 2 and out == '' and err.count('\n') == 1
    assert '116.0 Hz (chatter mode 37.0 Hz)' in err and 'Traceback' not in err and list(tmp_path.iterdir()) == []
    status = Main(['simulate', '--config', str(FIGURE19), '--end-time', '0.02', '--windows', '0:0.02', '--json',
                   '--quiet'])
    out, err = capsys.readouterr()
    p = ResolveParameters(config=FIGURE19)
    maxHz, _ = _Frequencies([ChainEigenvalues(p, [(p['J4'], p['k4'], p['d4'])], S) for S in (+1, -1)])
    assert status == 0 and json.loads(out)['stepSize'] == pytest.approx(RECOMMENDED_CYCLES / maxHz, rel=1e-8)
