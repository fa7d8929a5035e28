"""One drive, one verdict: the Drive object, the operating points of the drive's own duty, AnalyzeDrive, and the
stability command on drives unlike the reel changer (the rope hoist of examples/drives/hoist.toml)."""
import json
import math
import subprocess
import sys
import types
from pathlib import Path

import numpy as np
import pytest

import exudyn_worm as ew
from exudyn_worm.analysis.stability import drivestability
from exudyn_worm.cli.main import Main
from exudyn_worm.analysis.design.designcheck import DesignCheck
from exudyn_worm.analysis.design.stabilityhint import StabilizingChanges
from exudyn_worm.drive import config, presets, wholedrive
from exudyn_worm.params import drivefile
from exudyn_worm.drive.config import ResolveParameters, SourceKind, ValueSource
from exudyn_worm.drive.operatingpoints import DutyOperatingPoints, SteadyPhases
from exudyn_worm.drive.presets import DriveFromParameters, GetPreset
from exudyn_worm.drive.wholedrive import Component, Drive, ResolveDrive
from exudyn_worm.cli import main
from exudyn_worm.analysis.orbits.lowering import LoweringPhaseDrive

import paper_model

ROOT = Path(__file__).resolve().parents[1]
HOIST = ROOT / 'examples' / 'drives' / 'hoist.toml'
HOIST_AGMA = ROOT / 'examples' / 'drives' / 'hoist-agma.toml'
RPM = 2 * math.pi / 60
G = 9.81                                    # m/s^2, the package's standard gravity (eq. (27): 175 kg, 1.2 m, 2060 N*m)


def _C4(gear, S, mu):
    """c4 of eq. (12) with eq. (13) written out: r2 (cos(alphaN) cos(gamma) - S mu sin(gamma))."""
    return gear.r2 * (math.cos(gear.alphaN) * math.cos(gear.gamma) - S * mu * math.sin(gear.gamma))


def _C2(gear, S, mu):
    """c2 of eq. (10) with eq. (13) written out: r1 (cos(alphaN) sin(gamma) + S mu cos(gamma))."""
    return gear.r1 * (math.cos(gear.alphaN) * math.sin(gear.gamma) + S * mu * math.cos(gear.gamma))


# --- the drive object -------------------------------------------------------------------------------------------
def test_drive_is_immutable_typed_and_knows_its_sources():
    drive = ResolveDrive(config=HOIST, sets=['kT=2500'])
    assert drive.components == (Component.LOAD_SIDE_CHAIN,) and not drive.isTwoMass
    assert drive.loadType == 'constant' and drive.motorType == 'speedTable'
    assert drive.loadSideChain == ((6.2, 8e4, 0.),) and drive.driveSideChain == () and drive.axialBearing is None
    assert drive.sources['kT'] == ValueSource(SourceKind.SET, '--set') and 'hoist.toml' in drive.sources['J1'].text
    assert drive.sources['J1'].kind == SourceKind.FILE
    with pytest.raises(TypeError):
        drive.parameters['J1'] = 1.                      # read-only
    with pytest.raises(Exception):
        drive.elastic = None                             # frozen
    changed = drive.Replace(J1=2e-3)
    assert changed.parameters['J1'] == 2e-3 and changed.sources['J1'].kind == SourceKind.CHANGED and drive.parameters['J1'] == 1.5e-3
    preset = ResolveDrive('reel-P1')
    assert preset.isTwoMass and preset.components == () and preset.sources['J1'] == ValueSource.Preset('reel-P1')


@pytest.mark.messages
def test_two_mass_builder_refuses_what_it_would_drop():
    """The README's old short form AnalyzeStability(DriveFromParameters(p)) dropped a chain without a word."""
    p = {**GetPreset('reel-P1'), 'J4': 0.5, 'k4': 2e3}
    with pytest.raises(ValueError, match=r"DriveFromParameters: the parameter set has a drive-side chain \(J4, \.\.\.\), "
                                         r"which the two-mass ElasticDrive of Figure 2 leaves out; use "
                                         r"exudyn_worm.ResolveDrive"):
        DriveFromParameters(p)


def test_readme_short_form_and_cli_give_one_verdict_with_a_chain(capsys):
    p = {**GetPreset('reel-P1'), 'J4': 0.5, 'k4': 2e3}
    api = ew.AnalyzeDrive(ew.ResolveDrive('reel-P1', sets=['J4=0.5', 'k4=2e3']))
    assert ew.AnalyzeDrive(ResolveDrive(parameters=p)).stable is api.stable
    assert Main(['stability', '--preset', 'reel-P1', '--set', 'J4=0.5', '--set', 'k4=2e3', '--json']) == 0
    data = json.loads(capsys.readouterr().out)
    assert data['stable'] is api.stable and data['model'] == 'linearized'
    # the chain's own eigenvalues (tests/paper_model.py): the lowering point decides with constant mu
    expected = paper_model.ChainEigenvalues(p, [(0.5, 2e3, 0.)], -1)
    assert api.State(-1).maxRealPart == pytest.approx(max(expected.real), rel=1e-6, abs=1e-6)


@pytest.mark.messages
@pytest.mark.parametrize('sets, missing', [(['motorType=characteristic'], 'stallTorque, noLoadSpeed, motorInertia'),
                                           (['loadType=angleTable'], 'loadTorqueOverAngle')])
@pytest.mark.parametrize('command', ['stability', 'check', 'simulate', 'sweep'])
def test_incomplete_duty_is_one_line_for_every_command(capsys, tmp_path, monkeypatch, command, sets, missing):
    """A duty without its keys (the motor on its characteristic without motorInertia once raised a KeyError)."""
    monkeypatch.chdir(tmp_path)
    extra = {'simulate': ['--quiet'], 'sweep': ['--vary', 'kT=7000,8000', '--quiet'], 'check': ['--quiet']}.get(command, [])
    status = Main([command, '--preset', 'reel-P1', *[a for s in sets for a in ('--set', s)], *extra])
    out, err = capsys.readouterr()
    assert status == 2 and f'missing {missing}' in err and err.count('\n') == 1 and 'Traceback' not in err, err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.messages
def test_motor_speed_on_a_speed_table_is_refused(capsys):
    status = Main(['stability', '--config', str(HOIST), '--set', 'motorSpeed=50 rad/s'])
    err = capsys.readouterr().err
    assert status == 2 and err.count('\n') == 1
    assert "'motorSpeed' (--set) is not used by motorType = 'speedTable' (" in err
    assert "which takes motorSpeedOverTime; 'motorSpeed' belongs to motorType constantSpeed or startStop" in err


def test_a_presets_motor_speed_gives_way_to_another_motor_type():
    drive = ResolveDrive('reel-P1', sets=['motorType=speedTable', 'motorSpeedOverTime=[[0, "10 rad/s"], [1, "10 rad/s"]]'])
    assert 'motorSpeed' not in drive.parameters and drive.motorType == 'speedTable'


# --- operating points of the duty ---------------------------------------------------------------------------------
@pytest.mark.physics
def test_reel_changer_points_are_lifting_and_lowering_at_m_g_l():
    """Constant speed, a lever over one rotation: the largest torque of each power direction is m g l (eq. (27))."""
    drive = ResolveDrive('reel-P1')
    p, gear = drive.parameters, drive.gear
    points = DutyOperatingPoints(drive)
    assert [q.phase for q in points] == ['lifting', 'lowering'] and [q.S for q in points] == [1, -1]
    mgl = p['loadMass'] * G * p['leverArm']
    for q in points:
        assert abs(q.loadTorque) == pytest.approx(mgl, rel=1e-5)         # 721 samples of a rotation
        assert q.motorSpeed == p['motorSpeed'] and q.window == (0., pytest.approx(2 * math.pi * gear.ratio / p['motorSpeed']))
        op = q.operatingPoint
        assert op.slidingSpeed == pytest.approx(gear.r1 * p['motorSpeed'] / math.cos(gear.gamma), rel=1e-14)
        assert op.normalForce == pytest.approx(abs(q.loadTorque) / _C4(gear, q.S, p['mu']), rel=1e-12)
        assert op.mu == p['mu'] and op.dmuDv == 0.


@pytest.mark.physics
def test_hoist_points_are_its_plus_minus_100_rpm_phases():
    drive = ResolveDrive(config=HOIST)
    gear = drive.gear
    assert [(ph.t0, ph.t1, ph.source) for ph in SteadyPhases(drive)] == [(0.2, 1.2, 'speed table'),
                                                                         (1.8, 2.8, 'speed table')]
    lift, lower = DutyOperatingPoints(drive)
    assert (lift.phase, lift.S, lower.phase, lower.S) == ('lifting', 1, 'lowering', -1)
    assert lift.motorSpeed == pytest.approx(100 * RPM) and lower.motorSpeed == pytest.approx(-100 * RPM)
    assert lift.loadTorque == lower.loadTorque == -367.875
    # geometry of mx 3 mm, z1 1, z2 50, q 16: r1 = q mx / 2, tan(gamma) = z1 / q
    v0 = 0.024 * 100 * RPM / math.cos(math.atan(1 / 16))
    mu = 0.07 + 0.05 * math.exp(-(v0 / 0.3)**2)                    # the Stribeck law written out
    slope = -0.05 * 2 * v0 / 0.3**2 * math.exp(-(v0 / 0.3)**2)
    for q in (lift, lower):
        op = q.operatingPoint
        assert op.slidingSpeed == pytest.approx(v0, rel=1e-12)
        assert op.mu == pytest.approx(mu, rel=1e-12) and op.mu == pytest.approx(0.0947, abs=5e-5)   # the value the
        assert op.dmuDv == pytest.approx(slope, rel=1e-9)                                          # hoist.toml states
        assert op.normalForce == pytest.approx(367.875 / _C4(gear, q.S, mu), rel=1e-12)


@pytest.mark.physics
def test_start_stop_plateau_and_characteristic_equilibrium():
    plateau = ResolveDrive('reel-P1', sets=['motorType=startStop', 'rampTime=0.5', 'brakeTime=3'])
    (phase,) = SteadyPhases(plateau)
    assert (phase.t0, phase.t1, phase.source) == (0.5, 3., 'start/stop plateau')
    motor = ['motorType=characteristic', 'stallTorque=400', 'noLoadSpeed=55 rad/s', 'motorInertia=0.01']
    drive = ResolveDrive('reel-P1', sets=motor)
    gear, p = drive.gear, drive.parameters
    mgl = p['loadMass'] * G * p['leverArm']
    for q in DutyOperatingPoints(drive):
        S = q.S
        torque = S * _C2(gear, S, p['mu']) * mgl / _C4(gear, S, p['mu'])     # the worm's torque along the motion
        assert q.motorSpeed == pytest.approx(55 * (1 - torque / 400), rel=1e-4)   # 1e-5 of m g l in the samples
    with pytest.raises(ValueError, match=r"the motor on its characteristic cannot carry the lifting load of 2060 N\*m"):
        DutyOperatingPoints(ResolveDrive('reel-P1', sets=motor[:1] + ['stallTorque=5', *motor[2:]]))


def test_drive_without_a_duty_is_analysed_at_rest():
    drive = ResolveDrive('chart', sets=['J1=0.1', 'kT=7000', 'DT=0.01'])
    analysis = ew.AnalyzeDrive(drive)
    assert not drive.hasDuty and analysis.operatingPoints == ()
    assert analysis.stable is analysis.atRest.stable and 'no steady phase' in analysis.decidingText


# --- the verdict at the operating points --------------------------------------------------------------------------
@pytest.mark.physics
def test_hoist_is_unstable_at_both_phases_by_its_own_linearization():
    """The whole drive linearized by Exudyn at each point against the matrices written out (tests/paper_model.py)."""
    drive = ResolveDrive(config=HOIST)
    analysis = ew.AnalyzeDrive(drive)
    assert analysis.model == 'linearized' and not analysis.stable
    p = {**drive.parameters, 'r1': drive.gear.r1, 'r2': drive.gear.r2, 'gamma': drive.gear.gamma}
    for point in analysis.operatingPoints:
        op = point.point.operatingPoint
        expected = paper_model.FrictionSlopeEigenvalues(p, [(6.2, 8e4, 0.)], point.S, op.mu, op.dmuDv, op.normalForce)
        got = point.eigenvalues
        key = lambda lam: (round(abs(lam.imag), 3), lam.real)
        for a, b in zip(sorted(got, key=key), sorted(expected, key=key)):
            assert a == pytest.approx(b, rel=1e-5, abs=1e-3)
        assert not point.stable and point.maxRealPart > 50. and 170. < point.frequencyHz < 200.


@pytest.mark.physics
def test_agma_hoist_is_dangerous_with_and_without_its_load_side_chain():
    """mu 0.15 at rest (self-locking: rho > gamma) but about 0.024 at 3.65 m/s (not): the load runs away."""
    for lumped in (False, True):
        params = ResolveParameters(config=HOIST_AGMA)
        if lumped:        # without the chain: the drum's inertia on the wheel
            params = {k: v for k, v in params.items() if k not in ('JL1', 'kL1')}
            params['J2'] += 6.2
        analysis = ew.AnalyzeDrive(ResolveDrive(parameters=params))
        assert analysis.dangerous
        for point in analysis.operatingPoints:
            verdict = point.selfLocking
            assert point.point.operatingPoint.slidingSpeed == pytest.approx(3.65, abs=5e-3)
            assert verdict.static.selfLocking and not verdict.dynamic.selfLocking and verdict.dangerous
            gamma = math.atan(1 / 16)                     # z1 / q
            assert math.atan(verdict.dynamic.mu / math.cos(math.radians(20))) < gamma < \
                math.atan(0.15 / math.cos(math.radians(20)))


def test_stability_command_names_the_phase_that_decides(capsys):
    assert Main(['stability', '--config', str(HOIST)]) == 0
    out = capsys.readouterr().out
    assert 'Verdict: UNSTABLE (chatter expected) (decided by the lifting phase, S = +1, at 100 rpm' in out
    assert Main(['stability', '--config', str(HOIST), '--json']) == 0
    data = json.loads(capsys.readouterr().out)
    keys = {'phase', 'motorSpeed', 'loadTorque', 'slidingSpeed', 'mu', 'dmuDv', 'normalForce', 'S', 'maxRealPart',
            'frequencyHz', 'stable'}
    assert data['stable'] is False and len(data['operatingPoints']) == 2
    assert all(keys <= set(p) for p in data['operatingPoints'])
    assert [p['phase'] for p in data['operatingPoints']] == ['lifting', 'lowering']
    assert Main(['stability', '--config', str(HOIST_AGMA)]) == 0
    assert 'DANGER at lifting at 1450 rpm' in capsys.readouterr().out


# --- cost ---------------------------------------------------------------------------------------------------------
def test_a_command_resolves_its_drive_once_and_analyses_each_point_once(capsys, monkeypatch):
    """The drive file is resolved once, the drive built once, and no operating point is analysed twice (the load
    side's lumped drive, another drive, has its own points)."""
    built, analysed, resolved = [], [], []
    build, atPoint, resolve = wholedrive.Drive.FromParameters.__func__, drivestability._AtPoint, \
        config.ResolveParametersWithSources

    def CountedBuild(cls, parameters, *args, **kwargs):
        built.append(dict(parameters))
        return build(cls, parameters, *args, **kwargs)

    def CountedPoint(drive, point, model):
        analysed.append((id(drive), repr(point), model))
        return atPoint(drive, point, model)

    def CountedResolve(*args, **kwargs):
        resolved.append(args)
        return resolve(*args, **kwargs)
    monkeypatch.setattr(wholedrive.Drive, 'FromParameters', classmethod(CountedBuild))
    monkeypatch.setattr(drivestability, '_AtPoint', CountedPoint)
    monkeypatch.setattr(config, 'ResolveParametersWithSources', CountedResolve)
    assert Main(['stability', '--config', str(HOIST), '--set', 'kT=2100', '--json']) == 0
    data = json.loads(capsys.readouterr().out)
    assert len(resolved) == 1 and sum(1 for p in built if p.get('kT') == 2100 and 'JL1' in p) == 1
    assert len(analysed) == len(set(analysed)) and len(data['operatingPoints']) == 2


@pytest.mark.parametrize('argv', [
    ['stability'], ['check'], ['simulate', '--end-time', '0.02'],
    ['chart', '--resolution', '20'],
], ids=lambda a: a[0])
def test_each_command_reads_its_drive_file_once_and_builds_its_drive_once(argv, capsys, monkeypatch, tmp_path):
    """One boundary: the drive file is parsed once per command and the user's drive built once (a drive the
    command derives from it, as the load side's lumped drive, is another drive)."""
    parsed, built = [], []
    loads, build = drivefile.tomllib.loads, wholedrive.Drive.FromParameters.__func__

    def CountedLoads(text, *args, **kwargs):
        parsed.append(len(text))
        return loads(text, *args, **kwargs)

    def CountedBuild(cls, parameters, sources=None, *args, **kwargs):
        if not any(v.kind == SourceKind.CHANGED for v in (sources or {}).values()):       # a trial of the design check is another drive
            built.append(dict(parameters))
        return build(cls, parameters, sources, *args, **kwargs)
    monkeypatch.setattr(drivefile.tomllib, 'loads', CountedLoads)
    monkeypatch.setattr(wholedrive.Drive, 'FromParameters', classmethod(CountedBuild))
    path = tmp_path / 'p1.toml'
    path.write_text('preset = "reel-P1"\n[parameters]\nkT = 7001.0\n')
    assert Main([*argv, '--config', str(path), '--json']) == 0, capsys.readouterr().err
    capsys.readouterr()
    assert len(parsed) == 1
    assert sum(1 for p in built if p.get('kT') == 7001.) <= 1


def test_trial_drives_of_the_hint_and_the_design_check_do_not_go_through_the_resolver(monkeypatch):
    """The hint scan and the design check make their trial drives with Drive.Replace: no trial is a flat set
    resolved again (ApplyOverrides, the resolver of presets, files and --set), and a trial that changes an inertia,
    the shaft stiffness or a damping keeps the drive's gear."""
    calls = []
    for module, name in ((presets, 'ApplyOverrides'), (config, 'ResolveParametersWithSources'),
                         (wholedrive, 'ResolveParametersWithSources')):
        original = getattr(module, name)
        monkeypatch.setattr(module, name, lambda *a, _o=original, _n=name, **k: calls.append(_n) or _o(*a, **k))
    drive = ResolveDrive('reel-P1')
    calls.clear()
    StabilizingChanges(drive)
    DesignCheck(drive)
    assert calls == []
    changed = drive.Replace(J1=0.3, DT=0.02)
    assert changed.gear is drive.gear and changed.elastic.J1 == 0.3 and changed.sources['J1'].kind == SourceKind.CHANGED
    assert changed.elastic.dT == pytest.approx(2 * 0.02 * math.sqrt(drive.elastic.kT * 0.3), rel=1e-12)   # eq. (22)
    with pytest.raises(ValueError, match=r"'J1' must be > 0 kg\*m\^2, got -1 kg\*m\^2"):
        drive.Replace(J1=-1.)


# --- the periodic-orbit analysis follows the drive's own lowering phase -------------------------------------------
def test_chatter_analysis_takes_the_lowering_point_of_any_duty():
    p = LoweringPhaseDrive(ResolveDrive(config=HOIST)).parameters
    assert p['motorSpeed'] == pytest.approx(100 * RPM) and 'motorSpeedOverTime' not in p and 'loadType' not in p
    assert p['loadMass'] * G * p['leverArm'] == pytest.approx(367.875, rel=1e-14)
    reel = ResolveDrive('reel-P1')
    assert LoweringPhaseDrive(reel) is reel
    lifting = reel.Replace(loadType='constant', loadTorque=-500.)      # the load only ever opposes the motion
    with pytest.raises(ValueError, match="LoweringPhaseDrive: the drive's duty has no lowering phase"):
        LoweringPhaseDrive(lifting)
