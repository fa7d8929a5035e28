"""The orbit functions on the 3D model (worm and wheel as rigid bodies): on ideal revolute joints its steady chatter is
the one-angle model's; the flow sets the C++ mesh law's auxiliary coordinates from the bodies'; ``chatter`` without
``--vary`` reports the steady chatter at the lowering operating point, and refuses a drive with shaft bearings in one
line."""
import json

import numpy as np
import pytest

from exudyn_worm.analysis.chatter import FindSteadyChatter, SteadyChatterSummary
from exudyn_worm.analysis.lowering import BuildRigidBodyLoweringModel
from exudyn_worm.cli.main import Main
from exudyn_worm.setups.presets import GetPreset

pytest.importorskip('exudyn')
DRIVE_3D = 'examples/drives/reel-3d.toml'


def _Run(capsys, *argv):
    status = Main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def test_rigid_body_lowering_model_leaves_the_auxiliary_coordinates_to_the_flow():
    model = BuildRigidBodyLoweringModel(GetPreset('reel-P1'))
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
    parameters = GetPreset('reel-P1')
    one = FindSteadyChatter(parameters)
    model = BuildRigidBodyLoweringModel(parameters)
    rigid = FindSteadyChatter(parameters, model=model)
    assert rigid.converged and one.converged
    assert rigid.period == pytest.approx(one.period, rel=1e-8)
    for key in ('forceFactor', 'maxWheelAcceleration', 'minWormSpeed'):
        assert rigid.info[key] == pytest.approx(one.info[key], rel=1e-7), key
    assert sorted(np.abs(rigid.nontrivialMultipliers))[-1] == pytest.approx(
        sorted(np.abs(one.nontrivialMultipliers))[-1], rel=1e-7)
    assert rigid.stable == one.stable
    summary = SteadyChatterSummary(parameters, rigidBody=True)
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


@pytest.mark.parametrize('vary', [(), ('--vary', 'J1=0.05:0.3')])
def test_chatter_refuses_a_drive_with_shaft_bearings_in_one_line(capsys, vary):
    status, out, err = _Run(capsys, 'chatter', '--config', DRIVE_3D, *vary)
    assert status == 2 and len(err.strip().splitlines()) == 1 and not out
    assert 'shaft bearings' in err and '3D model' in err
