"""The orbit functions on the 3D model (worm and wheel as rigid bodies): on ideal revolute joints its steady chatter is
the one-angle model's; the flow sets the C++ mesh law's auxiliary coordinates from the bodies'; ``chatter`` without
``--vary`` reports the steady chatter at the lowering operating point, also of a drive with elastic shaft bearings
(shooting from a run settled on the Poincare section); ``--vary`` on such a drive is tests/test_chatter_vary_3d.py."""
import json

import numpy as np
import pytest

import exudyn_worm.analysis.orbits.chatter as chatter
from exudyn_worm.analysis.orbits.chatter import FindSteadyChatter, SteadyChatterSummary
from exudyn_worm.analysis.stability.drivestability import AnalyzeDrive
from exudyn_worm.analysis.orbits.lowering import BuildRigidBodyLoweringModel, LoweringPhaseDrive
from exudyn_worm.analysis.orbits.periodic import PeriodicOrbit, ShootingError
from exudyn_worm.cli.formatchatter import FormatSteadyChatter
from exudyn_worm.cli.main import Main
from exudyn_worm.drive.presets import GetPreset
from exudyn_worm.drive.wholedrive import ResolveDrive

pytest.importorskip('exudyn')
DRIVE_3D = 'examples/drives/reel-3d-chatter.toml'


def _Run(capsys, *argv):
    status = Main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def test_rigid_body_lowering_model_leaves_the_auxiliary_coordinates_to_the_flow():
    model = BuildRigidBodyLoweringModel(ResolveDrive(parameters=GetPreset('reel-P1')))
    auxiliary, D = model.dependent
    assert auxiliary.size == 7 and not set(auxiliary.tolist()) & set(model.coordinates)
    assert len(model.coordinates) == 12                      # both bodies' six coordinates, the motor held
    # the ties hold at the steady start: X = X0 + D (q - q0) with q = q0 is the start itself
    speeds = model.steadySpeeds
    assert np.allclose(D @ speeds, speeds[auxiliary], rtol=1e-12, atol=1e-12 * np.max(np.abs(speeds)))
    assert model.staticNormalForce == pytest.approx(20513.1, rel=1e-5)


@pytest.mark.slow
def test_3d_model_on_ideal_joints_chatters_as_the_one_angle_model():
    # ideal revolute joints give the one-angle mesh exactly (docs/mesh-3d.md): the converged orbits (shooting
    # tolerance 1e-8 of the state scale) must agree to that order, not only to the digits of a time simulation
    drive = ResolveDrive('reel-P1')
    one = FindSteadyChatter(drive)
    model = BuildRigidBodyLoweringModel(drive)
    rigid = FindSteadyChatter(drive, model=model)
    assert rigid.converged and one.converged
    assert rigid.period == pytest.approx(one.period, rel=1e-8)
    for key in ('forceFactor', 'maxWheelAcceleration', 'minWormSpeed'):
        assert rigid.info[key] == pytest.approx(one.info[key], rel=1e-7), key
    assert sorted(np.abs(rigid.nontrivialMultipliers))[-1] == pytest.approx(
        sorted(np.abs(one.nontrivialMultipliers))[-1], rel=1e-7)
    assert rigid.stable == one.stable
    summary = chatter._OrbitSummary(model, rigid, '3D')      # as SteadyChatterSummary gives it for such a drive
    assert summary['model'] == '3D' and summary['periodS'] == pytest.approx(one.period, rel=1e-8)
    loads = {'maxWormAxialLoad', 'maxWormRadialLoad', 'maxWheelAxialLoad', 'maxWheelRadialLoad'}
    assert loads <= set(summary['amplitude'])
    # the joint carries the mesh force's axial component on the worm: above the static normal force's share
    assert summary['amplitude']['maxWormAxialLoad'] > 0.5 * summary['maxNormalForce']


def test_chatter_without_vary_reports_the_steady_orbit(capsys):
    status, out, err = _Run(capsys, 'chatter', '--preset', 'reel-P1')
    assert status == 0, err
    assert 'one-angle model' in out and 'period' in out and 'Floquet multipliers' in out and 'stable orbit' in out
    status, out, err = _Run(capsys, 'chatter', '--preset', 'reel-P1', '--json')
    assert status == 0, err
    summary = json.loads(out)
    assert summary['model'] == 'one-angle' and summary['stable'] is True
    assert 1. / summary['periodS'] == pytest.approx(summary['frequencyHz'], rel=1e-12)
    assert 35. < summary['frequencyHz'] < 45.                # P1 chatters near 40 Hz (docs/chatter-amplitude.md)
    amplitude = summary['amplitude']
    assert summary['maxNormalForce'] == pytest.approx(amplitude['forceFactor'] * summary['staticNormalForce'])
    assert summary['amplitude']['forceFactor'] > 1.


def test_chatter_plot_needs_vary(capsys):
    status, out, err = _Run(capsys, 'chatter', '--preset', 'reel-P1', '--plot', 'x.png')
    assert status == 2 and len(err.strip().splitlines()) == 1 and '--plot' in err


def test_lowering_point_of_the_bearing_drive_has_a_barely_damped_tilt_mode_beside_the_chatter():
    # the measured reason why the 3D model settles slowly (docs/chatter-amplitude.md, "The 3D model"): at the lowering
    # point of reel-3d-chatter.toml a mode at 30.97 Hz has Re = -0.014 1/s (damping ratio 7e-5, decay time 70 s), and the
    # unstable (chatter) mode is at 31.8 Hz beside it, not the one-angle model's 40 Hz
    state = AnalyzeDrive(ResolveDrive(config=DRIVE_3D)).State(-1)
    ev = np.asarray(state.eigenvalues)
    ev = ev[ev.imag > 0]
    f, zeta = np.abs(ev) / (2 * np.pi), -ev.real / np.abs(ev)
    slow = (f > 30.5) & (f < 31.5) & (np.abs(zeta) < 2e-4)
    assert np.count_nonzero(slow) == 1 and zeta[slow][0] > 0
    growing = ev.real > 0
    assert np.count_nonzero(growing) == 1 and f[growing][0] == pytest.approx(31.79, abs=0.1)


@pytest.mark.slow
@pytest.mark.usefixtures('sharedChatterAnalyses')      # computed once for --json, the text and test_chatter_vary_3d.py
def test_chatter_reports_the_steady_chatter_of_a_drive_with_shaft_bearings(capsys):
    # measured on reel-3d-chatter.toml: a 20 s time simulation (step 1e-4 s) settles to a motion of period 32.224 ms on the
    # Poincare section (wheel-speed crossings, period spread 1 us), force factor 2.741, |phi2''| 112.6 rad/s^2, worm
    # speed down to 48.20 rad/s over its last 2 s; shooting from the section point of a 14-16 s run converges to it
    status, out, err = _Run(capsys, 'chatter', '--config', DRIVE_3D, '--json')
    assert status == 0, err
    summary = json.loads(out)
    assert summary['model'] == '3D' and summary['method'] == 'shooting' and summary['stable'] is True
    assert summary['frequencyHz'] == pytest.approx(1. / 32.224e-3, rel=1e-3)
    amplitude = summary['amplitude']
    assert amplitude['forceFactor'] == pytest.approx(2.741, rel=0.01)
    assert amplitude['maxWheelAcceleration'] == pytest.approx(112.6, rel=0.01)
    assert amplitude['minWormSpeed'] == pytest.approx(48.20, abs=0.05)
    # the multipliers near 1 come from a non-smooth map (0.987-0.994 for two starts): a slowly settling orbit
    assert 0.95 < summary['multipliers'][0] < 1.
    assert 10. <= summary['settledS'] <= 24. and summary['sectionChange'] < 0.3
    loads = {k: amplitude[k] for k in ('maxWormAxialLoad', 'maxWormRadialLoad', 'maxWheelAxialLoad',
                                       'maxWheelRadialLoad')}
    assert all(v > 0. for v in loads.values())
    # the worm's axial bearing and the wheel's radial bearings carry the mesh force's large components
    assert loads['maxWormAxialLoad'] > 0.8 * summary['maxNormalForce']
    assert loads['maxWheelRadialLoad'] > 0.8 * summary['maxNormalForce']
    status, out, err = _Run(capsys, 'chatter', '--config', DRIVE_3D)
    assert status == 0, err
    assert '3D model' in out and 'method: shooting' in out and 'Poincare section' in out and 'stable orbit' in out
    assert 'bearing loads over the orbit' in out and 'worm axial' in out and 'wheel radial' in out
    assert f"{amplitude['maxWheelRadialLoad'] / 1e3:.3f} kN" in out


def test_chatter_on_a_bearing_drive_with_a_bad_option_prints_one_line(capsys):
    status, out, err = _Run(capsys, 'chatter', '--config', DRIVE_3D, '--plot', 'x.png')
    assert status == 2 and len(err.strip().splitlines()) == 1 and not out and '--plot' in err


def test_bearing_drive_without_a_converged_orbit_reports_the_settled_long_simulation(monkeypatch):
    # where shooting does not converge from the settled state, the summary is the settled run's vibration, labelled
    # as such, with the reason (the settling run and the shooting are replaced here: the labelling is under test)
    vibration = {'forceFactor': 2.7, 'maxWheelAcceleration': 110., 'minWormSpeed': 48.2, 'maxWormSpeed': 50.8,
                 'maxWormAxialLoad': 5.3e4, 'maxWormRadialLoad': 1.9e4, 'maxWheelAxialLoad': 4.5e3,
                 'maxWheelRadialLoad': 5.7e4}
    monkeypatch.setattr(chatter, 'SettleOnSection', lambda model: {
        'state': np.zeros(24), 'period': 0.032224, 'settled': False, 'duration': 40., 'change': 0.5,
        'vibration': vibration, 'seconds': 0.})

    def Stall(*args, **kwargs):
        last = PeriodicOrbit(state=np.zeros(24), period=0.032, monodromy=np.eye(24), velocity=np.zeros(24),
                             residual=0.21, iterations=30, converged=False)
        raise ShootingError('stalled', last)

    monkeypatch.setattr(chatter, 'FindSteadyChatter', Stall)
    summary = chatter.SteadyChatterSummary(LoweringPhaseDrive(ResolveDrive(config=DRIVE_3D)))
    json.dumps(summary)
    assert summary['method'] == 'long simulation' and summary['stable'] is None and summary['multipliers'] == []
    assert 'no periodic orbit' in summary['reason'] and 'residual 0.21' in summary['reason']
    assert summary['amplitude'] == vibration and summary['frequencyHz'] == pytest.approx(1. / 0.032224)
    assert summary['maxNormalForce'] == pytest.approx(2.7 * summary['staticNormalForce'])
    text = '\n'.join(FormatSteadyChatter(summary, 'title'))
    assert 'method: long simulation' in text and 'no periodic orbit' in text and 'stable orbit' not in text
    assert 'worm speed                  48.200 to 50.800 rad/s' in text and 'bearing loads over the last 0.5 s' in text
