"""Duty cycles: load and motor from a parameter set, in drive files and on the command line;
the evaluation windows follow the duty (lowering = the load drives the gear)."""
import json
import math

import numpy as np
import pytest

from exudyn_worm.drive.config import ResolveParameters
from exudyn_worm.model.friction import MATH_OPS, NUMPY_OPS
from exudyn_worm.model.profiles import ConstantTorque, SpeedTable, TorqueTable
from exudyn_worm.analysis.simulation.reelchanger import (DefaultPhases, DefaultSimulatedTime, PhaseLabel, RotationPeriod,
                                                         SimulateReelChanger)
from exudyn_worm.drive.duty import LoadFromParameters, MotorFromParameters, SteadyMotorSpeed
from exudyn_worm.cli.main import Main
from exudyn_worm.analysis.stability.drivestability import AnalyzeDrive
from exudyn_worm.drive.presets import ExtraComponents
from exudyn_worm.analysis.design.designconfirm import ChatterWhileLowering
from exudyn_worm.drive.wholedrive import ResolveDrive


def test_speed_table_angle_is_the_integral_of_its_speed():
    table = SpeedTable([(0., 0.), (0.5, 40.), (1.5, 40.), (2., -10.)])
    t = np.linspace(0., 3., 30001)
    angle, speed = table.AngleAndSpeed(t, NUMPY_OPS)
    integral = np.concatenate([[0.], np.cumsum(0.5 * (speed[1:] + speed[:-1]) * np.diff(t))])
    np.testing.assert_allclose(angle, integral, atol=1e-6)
    assert table.AngleAndSpeed(0.25, MATH_OPS)[1] == pytest.approx(20.)
    assert table.AngleAndSpeed(5., MATH_OPS)[1] == -10.             # constant beyond the last row


@pytest.mark.parametrize('points, message', [
    ([(0.1, 1.)], "SpeedTable: the first row of 'points' must be at time 0 s"),
    ([(0., 1.), (0., 2.)], "the time of 'points' must increase, got 0 then 0"),
    ([], "'points' must hold at least one row"),
    ([(0., 1., 2.)], "row 0 of 'points' must be (time, speed)"),
])
def test_bad_speed_table(points, message):
    with pytest.raises(ValueError) as info:
        SpeedTable(points)
    assert message in str(info.value)


def test_torque_table_interpolates_and_holds_its_ends():
    table = TorqueTable([(0., -100.), (2., 100.), (3., 100.)], over='angle')
    assert [table.Torque(x, 0., 0., MATH_OPS) for x in (-1., 0., 1., 2.5, 9.)] == [-100., -100., 0., 100., 100.]
    assert table.maximum == 100. and ConstantTorque(-7.).maximum == 7.
    with pytest.raises(ValueError, match="TorqueTable: 'over' must be 'time' or 'angle', got 'speed'"):
        TorqueTable([(0., 1.)], over='speed')


def test_reel_changer_phases_are_its_lift_lower_lift_quarters():
    p = ResolveParameters('reel-P1')
    T = RotationPeriod(ResolveDrive(parameters=p))
    phases = DefaultPhases(ResolveDrive(parameters=p), 1.5 * T)
    assert [ph for _, _, ph in phases] == ['lift', 'lower', 'lift', 'lift', 'lower']
    np.testing.assert_allclose([t for a, b, _ in phases for t in (a, b)],
                               np.array([0, .25, .25, .75, .75, 1, 1, 1.25, 1.25, 1.5]) * T, rtol=1e-12)


def test_duty_phases_follow_the_load_power():
    """Lowering where the load drives the gear (M omega > 0): with the speed reversed at 1.5 s a constant
    driving torque becomes a lifted one; the rigid kinematics put the switch where the speed passes zero."""
    p = ResolveParameters('reel-P1', sets=['loadType=constant', 'loadTorque=1500', 'motorType=speedTable',
                                           'motorSpeedOverTime=[[0, 0], [0.5, "50 rad/s"], [1.5, "50 rad/s"], [2, "-50 rad/s"]]'])
    assert DefaultSimulatedTime(ResolveDrive(parameters=p)) == 2.
    (t0, t1, a), (t2, t3, b) = DefaultPhases(ResolveDrive(parameters=p))
    assert (a, b) == ('lower', 'lift') and t0 == 0. and t3 == 2.
    assert t1 == t2 == pytest.approx(1.75, abs=1e-9)
    q = ResolveParameters('reel-P1', sets=['loadType=timeTable', 'loadTorqueOverTime=[[0, -1e3], [1, -1e3], [1.5, 1e3]]'])
    (_, s1, a), (s2, _, b) = DefaultPhases(ResolveDrive(parameters=q), 3.)
    assert (a, b) == ('lift', 'lower') and s1 == s2 == pytest.approx(1.25, abs=1e-9)
    assert DefaultPhases(ResolveDrive(parameters=ResolveParameters('reel-P1', sets=['loadType=none'])), 2.) == [(0., 2., 'idle')]


def test_drive_file_gives_the_duty(tmp_path):
    path = tmp_path / 'drive.toml'
    path.write_text('preset = "reel-P1"\n[load]\ntype = "angleTable"\ntorqueOverAngle = [[0, "-2 kN*m"], '
                    '["90 deg", 0], ["180 deg", "2 kN*m"]]\n[motor]\ntype = "startStop"\nspeed = "300 rpm"\n'
                    'rampTime = "0.5 s"\nbrakeTime = 3\n')
    p = ResolveParameters(config=path)
    load, motor = LoadFromParameters(p), MotorFromParameters(p)
    assert load.points == ((0., -2000.), (math.pi / 2, 0.), (math.pi, 2000.)) and load.over == 'angle'
    assert (motor.speed, motor.rampTime, motor.brakeTime) == (pytest.approx(10 * math.pi), 0.5, 3.)


def test_table_from_a_csv_file(tmp_path):
    (tmp_path / 'torque.csv').write_text('# time s, torque N*m\n0, -10\n1, 10\n')
    p = ResolveParameters('reel-P1', sets=['loadType=timeTable', f"loadTorqueOverTime={tmp_path / 'torque.csv'}"])
    assert LoadFromParameters(p).points == ((0., -10.), (1., 10.))


@pytest.mark.parametrize('sets, fragment', [
    (['loadType=constant'], "the load (loadType constant) needs loadTorque; missing loadTorque"),
    (['motorType=startStop'], "missing rampTime"),
    (['loadType=timeTable', 'loadTorqueOverTime=[[0, 1], [0, 2]]'], "the time must increase"),
    (['loadType=crane'], "'loadType' must be one of: lever, constant, timeTable, angleTable, none, got 'crane'"),
    (['motorType=startStop', 'rampTime=1', 'brakeTime=0.5'], "'brakeTime' must be >= rampTime = 1 s"),
])
def test_bad_duty_is_one_line_exit_2(capsys, tmp_path, monkeypatch, sets, fragment):
    monkeypatch.chdir(tmp_path)
    status = Main(['simulate', '--quiet', *[a for s in sets for a in ('--set', s)]])
    out, err = capsys.readouterr()
    assert status == 2 and out == '' and err.count('\n') == 1 and fragment in err, err
    assert 'Traceback' not in err and list(tmp_path.iterdir()) == []


def test_simulated_lowering_under_a_driving_torque_has_the_worm_braking(capsys, tmp_path, monkeypatch):
    """A constant torque that drives the gear (the reel changer's 2060 N*m at most, here 1500 N*m): the whole run
    is one lowering window, the contact is on the braking flank (S < 0) throughout; started and stopped by
    ramps, the run begins from rest."""
    monkeypatch.chdir(tmp_path)
    args = ['simulate', '--preset', 'reel-P2', '--quiet', '--json', '--set', 'loadType=constant', '--set',
            'loadTorque=1500', '--set', 'motorType=startStop', '--set', 'rampTime=0.1', '--set', 'brakeTime=0.2']
    assert Main(args) == 0
    data = json.loads(capsys.readouterr().out)
    assert data['endTime'] == pytest.approx(0.3)
    (window,) = data['windows']
    assert (window['t0'], window['t1']) == (0., pytest.approx(0.3)) and window['fractionSNegative'] > 0.99
    assert list(tmp_path.iterdir()) == []


def test_simulation_with_each_duty_records_its_laws():
    """Every duty builds with symbolic user functions (recorded laws are checked against Python at build time)."""
    for sets in (['loadType=angleTable', 'loadTorqueOverAngle=[[0, -2000], ["3 rad", 2000]]', 'motorType=speedTable',
                  'motorSpeedOverTime=[[0, 0], [0.05, "49.5 rad/s"]]'],
                 ['loadType=timeTable', 'loadTorqueOverTime=[[0, -2000], [0.1, 0]]'],
                 ['loadType=none']):
        p = ResolveParameters('reel-P2', sets=sets)
        result = SimulateReelChanger(ResolveDrive(parameters=p), endTime=0.1)
        assert np.all(np.isfinite(result.series['phi2'])), sets
        assert result.info['loadType'] == p['loadType']


# a load torque going linearly from lifting (-1500 N*m, against the motion) to lowering (+1500 N*m) over 0.3 s
RAMPED_LOAD = ['loadType=timeTable', 'loadTorqueOverTime=[[0, -1500], [0.3, 1500]]']


def test_sweep_of_another_duty_takes_its_phases_as_windows(capsys, tmp_path, monkeypatch):
    """Without --windows a sweep of a non-reel duty evaluates the duty's own phases (the sign change of the load
    power at 0.15 s), as simulate does, and judges the lowering in the phase where the load drives."""
    monkeypatch.chdir(tmp_path)
    p = ResolveParameters('reel-P2', sets=RAMPED_LOAD)
    phases = DefaultPhases(ResolveDrive(parameters=p))
    assert [ph for _, _, ph in phases] == ['lift', 'lower'] and phases[0][1] == pytest.approx(0.15, rel=1e-6)
    args = ['sweep', '--preset', 'reel-P2', '--quiet', '--json', '--workers', '1', '--no-check-step',
            '--vary', 'J1=0.1,0.2', *[a for s in RAMPED_LOAD for a in ('--set', s)]]
    assert Main(args) == 0
    runs = json.loads(capsys.readouterr().out)['runs']
    for run in runs:
        assert run['status'] == 'ok', run['error']
        assert [(w['t0'], w['t1']) for w in run['windows']] == [pytest.approx((t0, t1)) for t0, t1, _ in phases]
        assert run['loweringChatter'] is not None          # the second window is a lowering one (judged or undecided)
    assert list(tmp_path.iterdir()) == []


def test_simulate_labels_each_window_with_its_phase(capsys, tmp_path, monkeypatch):
    """The text table names the phase of each window: lift / lower for the reel changer, lifting / lowering for
    another duty; a window over two phases names both."""
    monkeypatch.chdir(tmp_path)
    assert Main(['simulate', '--preset', 'reel-P2', '--quiet', '--no-check-step',
                 *[a for s in RAMPED_LOAD for a in ('--set', s)]]) == 0
    rows = [line for line in capsys.readouterr().out.splitlines() if line.strip()[:1].isdigit()]
    assert [r.split()[3] for r in rows] == ['lifting', 'lowering']
    assert Main(['simulate', '--quiet', '--no-check-step', '--end-time', '3', '--windows', '0:1,1:3']) == 0
    rows = [line for line in capsys.readouterr().out.splitlines() if line.strip()[:1].isdigit()]
    assert [r.split()[3] for r in rows] == ['lift', 'lift+lower']          # P1: lowering from T/4 = 2 s


def test_idle_window_is_a_standstill_under_load_or_no_load():
    """A hoist that pauses with its load on the drum stands still under load; a duty without load torque has none."""
    hoist = ['loadType=constant', 'loadTorque=-1500', 'motorType=speedTable',
             'motorSpeedOverTime=[[0, 0], [0.1, "50 rad/s"], [0.5, "50 rad/s"], [0.6, 0], [1, 0], [1.1, "-50 rad/s"], [1.5, "-50 rad/s"], [1.6, 0]]']
    p = ResolveParameters('reel-P1', sets=hoist)
    phases = DefaultPhases(ResolveDrive(parameters=p), 1.6)
    assert [ph for _, _, ph in phases] == ['lift', 'idle', 'lower']
    assert [PhaseLabel(ResolveDrive(parameters=p), ph, (t0, t1)) for t0, t1, ph in phases] == ['lifting', 'standstill under load', 'lowering']
    unloaded = ResolveParameters('reel-P1', sets=['loadType=none', 'motorType=speedTable',
                                                   'motorSpeedOverTime=[[0, 0], [0.1, "50 rad/s"]]'])
    assert PhaseLabel(ResolveDrive(parameters=unloaded), 'idle', (0., 1.)) == 'no load'
    assert PhaseLabel(ResolveDrive(parameters=p), 'idle') == 'idle'                       # without its window it cannot tell


CHARACTERISTIC = ['motorType=characteristic', 'stallTorque=300', 'noLoadSpeed=500 rpm', 'motorInertia=0.05']


def test_motor_characteristic_starts_where_its_line_carries_the_load():
    """The steady speed: M(omega) = stallTorque (1 - omega / noLoadSpeed) equals the drive-shaft torque of the
    equilibrium; the run starts there without a jump and the speed follows the lever's load."""
    p = ResolveParameters('reel-P2', sets=CHARACTERISTIC)
    speed = SteadyMotorSpeed(p)
    result = SimulateReelChanger(ResolveDrive(parameters=p), endTime=0.2)
    torque = 300. * (1 - speed / p['noLoadSpeed'])
    shaft = result.series['driveTorque'][0]
    assert torque == pytest.approx(-shaft, rel=1e-6)            # the shaft pulls the worm with the motor's torque
    assert result.series['omega0'][0] == pytest.approx(speed, rel=1e-12)
    assert np.max(np.abs(np.diff(result.series['omega0'][:20]))) < 1e-3   # no start transient
    with pytest.raises(ValueError, match='the motor cannot carry the load'):
        SteadyMotorSpeed({**p, 'stallTorque': 20.})


def test_motor_characteristic_in_the_linear_analysis():
    """The free motor rotor is in the linearized drive: its inertia adds a mode, the line's slope damps the
    drive's free rotation (a real eigenvalue -slope / (J0 + J1 + ...) reflected), one rigid-body angle remains."""
    p = ResolveParameters('reel-P2', sets=CHARACTERISTIC)
    assert ExtraComponents(p) == ['a motor on its characteristic (motorType characteristic)']
    state = AnalyzeDrive(ResolveDrive(parameters=p)).State(1)
    assert state.rigidBodyModes == 1
    assert len(state.frequenciesHz) == 2 and any(m.eigenvalue.imag == 0 and m.eigenvalue.real < 0 for m in state.modes)


def test_check_simulate_judges_the_lowering_phases_of_a_duty():
    """check --simulate on another duty: chatter is looked for where the load drives the gear; a duty that only
    lifts has no lowering to chatter in."""
    lifting = ResolveParameters('reel-P7', sets=['loadType=constant', 'loadTorque=-2000', 'motorType=speedTable',
                                                 'motorSpeedOverTime=[[0, "49.5 rad/s"], [1, "49.5 rad/s"]]'])
    assert ChatterWhileLowering(ResolveDrive(parameters=lifting)) is False
    lowering = {**lifting, 'loadTorque': 2000.}
    assert ChatterWhileLowering(ResolveDrive(parameters=lowering)) is True          # P7 chatters while lowering (the paper's Figure 14)


@pytest.mark.parametrize('preset', ['reel-P1', 'reel-P2', 'reel-P7'])
def test_check_of_a_characteristic_motor_is_the_whole_drives(capsys, tmp_path, monkeypatch, preset):
    """A motor on its characteristic: the check analyses the whole drive with the free motor and gives its verdict
    (P1: the whole drive is stable while lowering where the two-mass model, motor holding its speed, is not)."""
    monkeypatch.chdir(tmp_path)
    p = ResolveParameters(preset, sets=CHARACTERISTIC)
    status = Main(['check', '--quiet', '--preset', preset, '--json', *[a for s in CHARACTERISTIC for a in ('--set', s)]])
    out, err = capsys.readouterr()
    assert status == 0, err
    data = json.loads(out)
    assert data['stable'] is AnalyzeDrive(ResolveDrive(parameters=p)).stable and data['model'] == 'linearized'
    assert 'a motor on its characteristic (motorType characteristic)' in data['components']
    assert list(tmp_path.iterdir()) == []
