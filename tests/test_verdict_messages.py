"""Divergence is not chatter, and messages that are right: a real growing eigenvalue is reported as a divergence with
its rate in every command; real modes print no infinite damping; warnings name the run and the drive's quantity, never
an internal function; a standstill is found with a tolerance of the drive's own speeds; an inaccurate orbit says so;
no steady chatter is a result; the load-side and chart notes name the cause that decides."""
import json
import math
import warnings
from pathlib import Path

import numpy as np
import pytest

import exudyn_worm as ew
import paper_model
from exudyn_worm.analysis.stability.drivestability import (CHATTER, DIVERGENCE, GrowthText, StateInstability, VerdictWord)
from exudyn_worm.analysis.orbits.periodic import TRIVIAL_MULTIPLIER_TOLERANCE
from exudyn_worm.analysis.stability.loadside import LoadSideDiagnosis, LoadSideStage
from exudyn_worm.analysis.simulation import reelchanger
from exudyn_worm.analysis.design.designconfirm import ChatterWhileLowering
from exudyn_worm.analysis.simulation.reelchanger import PhaseLabel, WindowPhases
from exudyn_worm.analysis.studies.study import Study
from exudyn_worm.analysis.studies.studypoint import RunPoint, RunTask
from exudyn_worm.analysis.studies.studygrid import Variation
from exudyn_worm.analysis.studies.studypoint import RunLabel
from exudyn_worm.analysis.studies.studyfiles import StudyResult
from exudyn_worm.cli.formatchatter import FormatSteadyChatter
from exudyn_worm.cli.formatsweep import FormatStudy
from exudyn_worm._checks import WarningText
from exudyn_worm.cli.main import Main
from exudyn_worm.params.plausibility import ImplausibleValueWarning, CheckWormSpeed

ROOT = Path(__file__).resolve().parents[1]
HOIST = str(ROOT / 'examples' / 'drives' / 'hoist.toml')
TRACKER = str(ROOT / 'examples' / 'drives' / 'solar-tracker.toml')
#: the hoist with a steep Stribeck fall (mu 0.6 at rest to 0.07 over 1 m/s) and a soft motor shaft: lowering, the
#: falling friction overdamps the worm's mode negatively, a real eigenvalue grows (the worm runs away or creeps)
DIVERGENT = ['--set', 'muStatic=0.6', '--set', 'stribeckVelocity=1', '--set', 'kT=100']


def _Run(capsys, *argv):
    status = Main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


class _State:
    """A contact state's analysis with given eigenvalues (what StateInstability reads)."""

    def __init__(self, eigenvalues):
        self.eigenvalues = np.asarray(eigenvalues, dtype=complex)
        self.maxRealPart = float(np.max(self.eigenvalues.real))
        self.stable = self.maxRealPart < 0


# --- divergence ---------------------------------------------------------------------------------------------------
def test_a_real_growing_eigenvalue_is_a_divergence_a_complex_one_chatter():
    assert StateInstability(_State([-1 + 10j, -1 - 10j, -5.])) is None
    assert StateInstability(_State([2 + 10j, 2 - 10j, -5.])) == CHATTER
    assert StateInstability(_State([-1 + 10j, -1 - 10j, 3.])) == DIVERGENCE
    assert VerdictWord(False, DIVERGENCE) == 'DIVERGENT' and VerdictWord(False, CHATTER) == 'UNSTABLE'
    assert GrowthText(3., 0., DIVERGENCE).startswith('a real eigenvalue grows at 3 1/s (divergence')
    assert 'Hz' not in GrowthText(3., 0., DIVERGENCE)


@pytest.mark.physics
@pytest.mark.slow
def test_the_divergent_hoist_against_the_matrices_written_out():
    """The lowering point's largest eigenvalue is real, as in the model of tests/paper_model.py, at its rate."""
    drive = ew.ResolveDrive(config=HOIST, sets=[s for s in DIVERGENT if s != '--set'])
    analysis = ew.AnalyzeDrive(drive)
    p = {**drive.parameters, 'r1': drive.gear.r1, 'r2': drive.gear.r2, 'gamma': drive.gear.gamma}
    lowering = next(q for q in analysis.operatingPoints if q.S == -1)
    op = lowering.point.operatingPoint
    expected = paper_model.FrictionSlopeEigenvalues(p, [(6.2, 8e4, 0.)], -1, op.mu, op.dmuDv, op.normalForce)
    top = expected[np.argmax(expected.real)]
    assert top.imag == 0. and top.real > 0.
    assert lowering.instability == DIVERGENCE and lowering.maxRealPart == pytest.approx(top.real, rel=1e-5)
    assert analysis.instability == DIVERGENCE


@pytest.mark.messages
def test_stability_reports_a_divergence_with_its_rate_and_no_infinite_damping(capsys):
    status, out, err = _Run(capsys, 'stability', '--config', HOIST, *DIVERGENT)
    assert status == 0 and 'Traceback' not in err
    verdict = next(line for line in out.splitlines() if line.startswith('Verdict:'))
    assert verdict.startswith('Verdict: DIVERGENT (not chatter: the drive runs away or creeps')
    assert 'a real eigenvalue grows at 603 1/s' in verdict and 'at 0 Hz' not in out
    assert 'also chatter expected in the lifting phase' in verdict           # the other point's growing vibration
    assert 'inf' not in out.replace('information', '')                         # no 'Lehr D -inf'
    assert any(line.split()[:2] == ['0.00', 'real'] for line in out.splitlines())
    assert 'lumping is not safe (the verdicts differ)' not in out               # both verdicts are unstable
    assert 'a real mode grows (divergence' in out
    load = next(line for line in out.splitlines() if line.startswith('Load side:'))
    assert 'lumped into J2 the drive is DIVERGENT, the whole drive is DIVERGENT' in load and 'UNSTABLE' not in load


@pytest.mark.messages
def test_the_load_side_verdicts_name_a_divergence_and_a_growing_vibration_apart():
    """The lumped and the whole drive's words are the drive verdict's: DIVERGENT for a real eigenvalue, UNSTABLE for
    a growing vibration, stable."""
    stages = [LoadSideStage(1, 6.2, 6.2, 8e4)]
    words = {(True, None): 'stable', (False, DIVERGENCE): 'DIVERGENT', (False, CHATTER): 'UNSTABLE'}
    for (lumped, kind), word in words.items():
        for whole, other in words.items():
            d = LoadSideDiagnosis(stages, 0.1, (8.9,), lumped, whole[0], lumpedInstability=kind,
                                  wholeInstability=whole[1])
            assert f"lumped into J2 the drive is {word}, the whole drive is {other}" in d.Text()
            assert (d.ToDict()['lumpedInstability'], d.ToDict()['wholeInstability']) == (kind, whole[1])


@pytest.mark.messages
@pytest.mark.slow
def test_check_and_chart_report_a_divergence(capsys):
    status, out, err = _Run(capsys, 'check', '--config', HOIST, *DIVERGENT, '--quiet')
    assert status == 0 and 'Traceback' not in err
    assert out.splitlines()[2].startswith('Verdict: DIVERGENT (not chatter')
    assert 'S = -1: DIVERGENT, max Re(lambda) = 603 1/s (a real eigenvalue)' in out
    status, out, err = _Run(capsys, 'chart', '--config', HOIST, *DIVERGENT, '--speed', '100 rad/s')
    assert status == 0 and 'Traceback' not in err
    assert 'DIVERGENT (a real eigenvalue grows at 603 1/s' in out and 'the drive is DIVERGENT' in out


@pytest.mark.messages
def test_the_chart_note_names_the_friction_slope_where_it_decides(capsys):
    """reel-P3 with a Stribeck law: the slope makes the lowering point unstable; with mu held at mu(v0) it is stable."""
    sets = ['--set', 'frictionLaw=stribeck', '--set', 'mu=0.07', '--set', 'muStatic=0.15', '--set',
            'stribeckVelocity=1']
    status, out, err = _Run(capsys, 'chart', '--config', 'reel-P3', *sets, '--resolution', '20')
    assert status == 0 and 'Traceback' not in err
    assert 'the speed-dependent friction decides: its slope dmu/dv = -0.064' in out
    assert 'with mu held at mu(v0) = 0.1058 it would be stable' in out


# --- messages -----------------------------------------------------------------------------------------------------
@pytest.mark.messages
def test_a_worm_vibration_is_no_runaway_a_runaway_is_warned_without_a_function_name():
    """Stick-slip at 200 Hz with peaks 20 times the motor speed averages to the motor speed: no warning. A worm
    that the load drives at 30 times the motor speed for 0.2 s is warned, naming the load, not a function."""
    t = np.linspace(0., 1., 10001)
    motor = np.full_like(t, 5.)
    p = {'motorSpeed': 5., 'loadTorque': -4000.}
    with warnings.catch_warnings():
        warnings.simplefilter('error')
        CheckWormSpeed(5. + 100. * np.sin(2 * np.pi * 200. * t), motor, p, 'simulation', t)
    runaway = np.where(t > 0.8, -150., 5.)
    with pytest.warns(ImplausibleValueWarning) as caught:
        CheckWormSpeed(runaway, motor, p, 'simulation', t)
    message = str(caught[0].message)
    assert message.startswith('simulation: the worm turned at -150 rad/s on average over 0.1 s, 30 times the motor')
    assert 'loadTorque = -4000 N*m' in message and 'SimulateReelChanger' not in message


def test_a_run_of_a_study_is_named_in_its_warnings():
    task = RunTask(3, None, {'J1': 0.0125, 'frictionLaw': 'agma'})
    assert RunLabel(task) == 'run 3 (J1 = 0.0125, frictionLaw = agma)'


def test_a_standstill_under_load_is_found_with_a_tolerance():
    """The tracker's speed table interpolates its two rows of zero speed to round-off (8.9e-16 rad/s), not 0: the
    pause under the wind torque is a standstill under load, not idle."""
    drive = ew.ResolveDrive(config=TRACKER)
    windows = [(3.0, 3.8)]
    phase = WindowPhases(drive, windows, 7.6)[0]
    assert PhaseLabel(drive, phase, windows[0]) == 'standstill under load'


def _Summary(trivial, largest=1.3):
    return {'model': 'one-angle', 'motorSpeed': 10., 'loadTorque': -100., 'periodS': 0.01, 'frequencyHz': 100.,
            'maxNormalForce': 2000., 'staticNormalForce': 1000., 'multipliers': [largest, 0.5],
            'trivialMultiplierError': trivial, 'stable': largest < 1., 'accurate': trivial <= TRIVIAL_MULTIPLIER_TOLERANCE,
            'stabilityDecided': trivial <= TRIVIAL_MULTIPLIER_TOLERANCE and abs(largest - 1.) > trivial,
            'amplitude': {'forceFactor': 2., 'maxWheelAcceleration': 5., 'minWormSpeed': -1.}}


@pytest.mark.messages
def test_an_orbit_off_in_its_trivial_multiplier_is_labelled_inaccurate():
    """The Stribeck drive's orbit with the trivial multiplier off by 0.37: INACCURATE, no stability verdict."""
    line = next(l for l in FormatSteadyChatter(_Summary(0.37), 't') if 'Floquet' in l)
    assert 'trivial one off by 0.37, above the tolerance 0.05): INACCURATE orbit' in line
    assert 'unstable orbit' not in line
    line = next(l for l in FormatSteadyChatter(_Summary(0.01), 't') if 'Floquet' in l)
    assert line.endswith('trivial one off by 0.01): unstable orbit')
    line = next(l for l in FormatSteadyChatter(_Summary(0.02, 1.01), 't') if 'Floquet' in l)
    assert "the orbit's stability is not decided" in line


@pytest.mark.messages
def test_chatter_on_a_stable_drive_is_a_result(capsys):
    """reel-P2 is stable while lowering: 'no steady chatter' on stdout, exit 0, nothing on stderr."""
    status, out, err = _Run(capsys, 'chatter', '--preset', 'reel-P2')
    assert status == 0 and err == '', err
    assert out.startswith('exudyn-worm chatter: preset reel-P2, lowering phase (constant load torque): the lowering '
                          'phase settles to rest') and 'no steady chatter at these parameters' in out
    status, out, err = _Run(capsys, 'chatter', '--preset', 'reel-P2', '--json')
    assert status == 0 and json.loads(out)['steadyChatter'] is False


@pytest.mark.messages
def test_a_warning_of_a_study_run_names_the_run(monkeypatch):
    """The worm-speed warning of one run of a sweep says which run it comes from, not which function."""
    real = reelchanger.SimulateReelChanger

    def Warning(p, **kw):
        warnings.warn('simulation: the worm turned at -150 rad/s', ImplausibleValueWarning)
        warnings.warn("SimulateReelChanger: the drive's highest natural frequency is 900 Hz", ImplausibleValueWarning)
        return real(p, **kw)
    monkeypatch.setattr(reelchanger, 'SimulateReelChanger', Warning)
    s = Study(ew.GetPreset('reel-P1'), [Variation('J1', (0.2,))], windows=[(0., 0.2)], endTime=0.2, checkStep=False)
    with pytest.warns(ImplausibleValueWarning) as caught:
        row = RunPoint(s.Task(0))
    assert row['status'] == 'ok', row['error']
    assert [str(w.message) for w in caught] == ['run 0 (J1 = 0.2): the worm turned at -150 rad/s',
                                                "run 0 (J1 = 0.2): the drive's highest natural frequency is 900 Hz"]


def test_a_warning_for_the_command_line_has_no_python_name():
    assert WarningText("SimulateReelChanger: the drive's highest") == "the drive's highest"
    assert WarningText('SimulationResult.WindowMetrics: the window') == 'the window'
    assert WarningText('the gear: flank friction mu = 0.6') == 'the gear: flank friction mu = 0.6'
    assert WarningText("simulate --step-size: the drive's") == "simulate --step-size: the drive's"


@pytest.mark.messages
@pytest.mark.slow
def test_simulate_the_solar_tracker(capsys, tmp_path, monkeypatch):
    """The tracker's windows hold the table's swing after each start and stop, decaying over seconds: undecided, not
    chatter (its swing of about 1.7 Hz leaves 1.6 periods in the last window's last quarter of 0.9 s: fewer than
    the 2 the amplitude needs); its pause under the wind is a standstill under load; no warning of an overpowering
    load."""
    monkeypatch.chdir(tmp_path)
    status, out, err = _Run(capsys, 'simulate', '--config', TRACKER, '--no-check-step', '--quiet')
    assert status == 0 and err == '', err
    rows = out.splitlines()[4:]
    assert [r[14:36].strip() for r in rows] == ['lifting', 'standstill under load', 'lowering', 'lifting']
    assert 'YES' not in out and 'undecided: amplitude' in out
    assert "fewer than 2 periods of its dominant frequency in the window's last quarter" in rows[3]
    assert list(tmp_path.iterdir()) == []


@pytest.mark.messages
def test_sweep_agreement_counts_decided_windows_and_says_what_it_left_out():
    """Four runs: two decided and judged (one agrees), one undecided, one whose lowering points diverge."""
    study = Study(ew.GetPreset('reel-P1'), [Variation('J1', (1., 2., 3., 4.))])

    def Row(run, chatter, stable, kind=None):
        row = {'run': run, 'status': 'ok', 'error': '', 'seconds': 1., 'J1': float(run + 1), 'stepChecked': False,
               'analyticStable': stable, 'analyticStableLowering': stable, 'analyticInstability': kind,
               'analyticInstabilityLowering': kind, 'loweringChatter': chatter}
        row.update({f'w{i}.chatter': chatter if i == 1 else False for i in range(study.numberOfWindows)})
        return row
    rows = [Row(0, True, False, CHATTER), Row(1, True, True), Row(2, 'undecided', True),
            Row(3, True, False, DIVERGENCE)]
    result = StudyResult(study, rows)
    assert result.agreement == pytest.approx(0.5) and len(result.judged) == 2 and len(result.divergent) == 1
    table = '\n'.join(FormatStudy(result))
    assert 'no UND no' in table and 'DIVERGENT' in table
    assert '50 % of 2 runs with a decided lowering window' in table
    assert '1 run left out, lowering undecided (UND' in table
    assert '1 left out whose lowering points diverge' in table


def test_check_simulate_says_undecided_for_the_tracker():
    """The tracker's lowering window holds the table's swing, not decided within it: 'undecided', not False."""
    assert ChatterWhileLowering(ew.ResolveDrive(config=TRACKER)) == 'undecided'
