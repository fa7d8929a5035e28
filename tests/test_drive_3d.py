"""Drive files and the command line with the shafts' bearings: the 3D model (worm and wheel as rigid bodies) is
simulated and linearized, simulate reports the bearing loads; bad bearing tables give one line; [axialBearing]
files keep the one-angle model."""
import csv
import json

import exudyn as exu
import numpy as np
import pytest

from exudyn_worm.analysis.stability.drivestability import AnalyzeDrive
from exudyn_worm.analysis.simulation.reelchanger import SolverSettings
from exudyn_worm.analysis.simulation.reelchanger3d import StoredShaftLoads
from exudyn_worm.builders.rigidbody import BuildRigidBodyReelChanger
from exudyn_worm.analysis.simulation.stepsize import RecommendedStepSize
from exudyn_worm.cli.main import Main
from exudyn_worm.items.bearings import ShaftBearings
from exudyn_worm.drive.presets import GetPreset
from exudyn_worm.drive.wholedrive import Component, ResolveDrive

pytest.importorskip('exudyn')
DRIVE_3D = 'examples/drives/reel-3d.toml'
LOAD_KEYS = {'wormAxial', 'wormRadial', 'wheelAxial', 'wheelRadial'}
#: the bearings of examples/drives/reel-3d.toml
WORM, WHEEL = ShaftBearings(5e8, 5e8, 1e3, 1e3, span=0.12), ShaftBearings(1e9, 1e9, 1e3, 1e3, span=0.15)


def _Run(capsys, *argv):
    status = Main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def test_bearing_tables_make_the_drive_the_3d_model():
    drive = ResolveDrive(config=DRIVE_3D)
    assert drive.isRigidBody and Component.SHAFT_BEARINGS in drive.components and not drive.isTwoMass
    supports = drive.shaftSupports
    assert (supports.wormBearings, supports.wheelBearings) == (WORM, WHEEL)
    assert (supports.wormMass, supports.wheelMass) == (5., 30.)
    # the bodies as solid cylinders (the file's radius and length): polar m r^2 / 2, tilt m (3 r^2 + L^2) / 12
    for inertia, m, r, L in ((supports.wormInertia, 5., 0.021, 0.46), (supports.wheelInertia, 30., 0.11, 0.1)):
        assert (inertia.mass, inertia.polar, inertia.tilt) == pytest.approx((m, m * r**2 / 2, m * (3 * r**2 + L**2) / 12),
                                                                            rel=1e-12)
    assert drive.sources['wormRadialStiffness'].text.endswith('[wormBearing] radialStiffness')


def _File(tmp_path, text):
    path = tmp_path / 'drive.toml'
    path.write_text('preset = "reel-P1"\n' + text)
    return str(path)


BAD = [('[wormBearing]\nradialStiffness = "5e8 N/m"\naxialStiffness = "5e8 N/m"\n',
        "the worm's bearings ([wormBearing]) need its radialStiffness, axialStiffness (N/m) and the worm's mass "
        "([worm] mass, kg); missing wormMass"),
       ('[worm]\nmass = "5 kg"\n[wormBearing]\nradialStiffness = "5e8 N/m"\n', 'missing wormAxialStiffness'),
       ('[wheel]\nmass = "30 kg"\n', "'wheelMass' (the wheel's mass, kg) is used only by the 3D model"),
       ('[wheel]\ntiltInertia = "1 kg*m^2"\n', "'wheelTiltInertia' (the wheel's tilt inertia, kg*m^2) is used only "
        "by the 3D model"),
       # the tilt inertia is required with elastic bearings, never taken from the polar one
       ('[wheel]\nmass = 30\n[wheelBearing]\nradialStiffness = 1e9\naxialStiffness = 1e9\n',
        "the wheel on elastic bearings ([wheelBearing]) needs its tilt inertia: missing wheelTiltInertia"),
       # the perpendicular-axis bound: without polarInertia the wheel body carries all of J2 = 33 kg*m^2
       ('[wheel]\nmass = 30\ntiltInertia = 16\n[wheelBearing]\nradialStiffness = 1e9\naxialStiffness = 1e9\n',
        "'wheelTiltInertia' must be >= half the wheel's polar inertia (J2, all of the shaft's inertia in the wheel "
        "body without wheelPolarInertia: 33 kg*m^2)"),
       ('[wheel]\nmass = 30\ntiltInertia = 0.05\npolarInertia = 0.2\n[wheelBearing]\nradialStiffness = 1e9\n'
        'axialStiffness = 1e9\n', "'wheelTiltInertia' must be >= half the wheel's polar inertia (wheelPolarInertia: "
        "0.2 kg*m^2)"),
       ('[wheel]\nmass = 30\ntiltInertia = 20\npolarInertia = 34\n[wheelBearing]\nradialStiffness = 1e9\n'
        'axialStiffness = 1e9\n', "must be <= J2 = 33 kg*m^2"),
       ('[wheel]\nmass = 30\nradius = "0.1 m"\n[wheelBearing]\nradialStiffness = 1e9\naxialStiffness = 1e9\n',
        "the wheel's shape (a cylinder) needs its radius and length ([wheel] radius, length in m); missing "
        "wheelLength"),
       ('[wheel]\nmass = 30\nradius = "0.1 m"\nlength = "0.1 m"\ninnerRadius = "0.1 m"\n[wheelBearing]\n'
        'radialStiffness = 1e9\naxialStiffness = 1e9\n', "'wheelInnerRadius' must be < wheelRadius = 0.1 m, got 0.1 m"),
       ('[wheel]\nmass = 30\nradius = "0.1 m"\nlength = "0.1 m"\ntiltInertia = 20\n[wheelBearing]\n'
        'radialStiffness = 1e9\naxialStiffness = 1e9\n', "belong to different forms of the wheel inertia"),
       ('[worm]\nmass = "5 kg"\n[wormBearing]\nradialStiffness = 5e8\naxialStiffness = 5e8\n'
        '[axialBearing]\nstiffness = 1e8\nmass = 5\n', "the worm's axial bearing is given twice"),
       ('[wheel]\nmass = 30\ntiltInertia = 20\n[wheelBearing]\nradialStiffness = 1e9\naxialStiffness = 1e9\n'
        '[[driveSide]]\ninertia = 0.5\nstiffness = 2e4\n', 'which has no drive-side chain'),
       ('[wheel]\nmass = 30\n[wheelBearing]\nradialStiffness = -1e9\naxialStiffness = 1e9\n',
        "'wheelRadialStiffness' must be > 0 N/m, got -1e+09")]


@pytest.mark.parametrize('text, message', BAD)
def test_bad_bearing_tables_give_one_line(capsys, tmp_path, text, message):
    status, out, err = _Run(capsys, 'simulate', '--config', _File(tmp_path, text), '--end-time', '0.1')
    assert status == 2
    assert message in err and len(err.strip().splitlines()) == 1 and 'Traceback' not in err


@pytest.mark.slow
def test_simulate_reports_bearing_loads_as_the_python_builder(capsys, tmp_path):
    """simulate on the drive file: exit 0, windows with bearingLoads, the series in the CSV; the same peaks (1e-6)
    as the Python builder with the same bearings, masses and step, run as one solve."""
    path = tmp_path / 'run.csv'
    status, out, err = _Run(capsys, 'simulate', '--config', DRIVE_3D, '--end-time', '0.4', '--windows',
                            '0:0.2,0.2:0.4', '--no-check-step', '--json', '--csv', str(path), '--quiet')
    assert status == 0, err
    data = json.loads(out)
    assert all(set(w['bearingLoads']) == LOAD_KEYS for w in data['windows'])
    with path.open() as f:
        header = next(csv.reader(f))
    assert {'wormAxialLoad [N]', 'wormRadialLoad [N]', 'wheelAxialLoad [N]', 'wheelRadialLoad [N]',
            'meshWheelTangential [N]'} <= set(header)

    model = BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(config=DRIVE_3D))
    model.connector.AddSensors(model.mbs)
    model.mbs.Assemble()
    ss, solverType = SolverSettings(0.4, data['stepSize'])
    model.mbs.SolveDynamic(ss, solverType=solverType)
    loads = StoredShaftLoads(model)
    for window in data['windows']:
        # the windows' own rule (SimulationResult._Window, no tolerance: a sample 6e-16 s before t0 = 0.2 s, at the
        # 238th step, is not in the second window; the load falls monotonically there, so it would be its peak)
        inside = (loads['time'] >= window['t0']) & (loads['time'] <= window['t1'])
        for key in LOAD_KEYS:
            expected = np.max(np.abs(loads[key + 'Load'][inside]))
            assert window['bearingLoads'][key] == pytest.approx(expected, rel=1e-6), key
    # lifting in steady state: the worm's axial bearing carries the wheel's tangential force
    assert data['windows'][0]['bearingLoads']['wormAxial'] == pytest.approx(
        data['windows'][0]['maxNormalForce'] * 0.9234, rel=0.01)


def test_axial_bearing_file_keeps_the_one_angle_model(capsys, tmp_path):
    path = _File(tmp_path, '[axialBearing]\nstiffness = "1e9 N/m"\nmass = "5 kg"\n')
    drive = ResolveDrive(config=path)
    assert not drive.isRigidBody and drive.components == (Component.AXIAL_BEARING,)
    status, out, err = _Run(capsys, 'simulate', '--config', path, '--end-time', '0.2', '--no-check-step', '--json',
                            '--quiet')
    assert status == 0, err
    assert all('bearingLoads' not in w for w in json.loads(out)['windows'])


def test_stiff_bearings_give_the_verdict_of_the_one_angle_drive():
    """AnalyzeDrive linearizes the 3D model for a drive with shaft bearings: with bearings of 1e13 N/m the deciding
    eigenvalue of P1 is the two-mass drive's (1e-3); with the file's bearings the step rule leaves the bearings'
    own modes (above 900 Hz) out."""
    stiff = {f'{b}{k}': 1e13 for b in ('worm', 'wheel') for k in ('RadialStiffness', 'AxialStiffness')}
    stiff.update(wormMass=5., wheelMass=30., wormBearingSpan=0.5, wheelBearingSpan=0.5, wormTiltInertia=0.1,
                 wheelTiltInertia=33.)
    rigid, reference = AnalyzeDrive(ResolveDrive(parameters={**GetPreset('reel-P1'), **stiff})), AnalyzeDrive(ResolveDrive(parameters=GetPreset('reel-P1')))
    assert rigid.drive.isRigidBody and rigid.model == 'linearized' and rigid.stable == reference.stable
    assert rigid.maxRealPart == pytest.approx(reference.maxRealPart, rel=1e-3)
    assert rigid.frequencyHz == pytest.approx(reference.frequencyHz, rel=1e-3)
    elastic = dict(ResolveDrive(config=DRIVE_3D).parameters)
    assert RecommendedStepSize(ResolveDrive(parameters=elastic)) > 0.5 * RecommendedStepSize(ResolveDrive(parameters=GetPreset('reel-P1')))


def test_ideal_joint_loads_are_the_statics_of_the_mesh_force():
    """On ideal joints the bearing loads are the joints' reactions: at the start (static equilibrium) the worm's
    axial load is the wheel's tangential force, its radial load the worm's tangential and separating forces together,
    and the wheel's loads the same forces seen from the wheel (to 1e-6)."""
    model = BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=GetPreset('reel-P1')))
    model.connector.AddSensors(model.mbs)
    model.mbs.Assemble()
    ss, solverType = SolverSettings(0.01, 1e-3)
    model.mbs.SolveDynamic(ss, solverType=solverType)
    loads = StoredShaftLoads(model)
    forces = model.connector.StoredMeshForces(model.mbs)
    assert abs(loads['wormAxialLoad'][0]) == pytest.approx(abs(forces['wormAxial'][0]), rel=1e-6)
    assert loads['wormRadialLoad'][0] == pytest.approx(np.hypot(forces['wormTangential'][0], forces['wormRadial'][0]),
                                                       rel=1e-6)
    assert abs(loads['wheelAxialLoad'][0]) == pytest.approx(abs(forces['wheelAxial'][0]), rel=1e-6)
    assert loads['wheelRadialLoad'][0] == pytest.approx(np.hypot(forces['wheelTangential'][0],
                                                                 forces['wheelRadial'][0]), rel=1e-6)
    assert abs(forces['wormAxial'][0]) > 1e4
