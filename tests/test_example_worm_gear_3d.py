"""examples/worm_gear_3d.py: the rigid-body reel changer in elastic bearings, its numbers checked."""
import exudyn as exu
import numpy as np
import pytest

from exudyn_worm.builders.oneangle import BuildReelChanger
from exudyn_worm.drive.presets import GetPreset
from exudyn_worm.drive.wholedrive import ResolveDrive

from conftest import LoadScript

pytest.importorskip('exudyn')


@pytest.fixture(scope='module')
def example():
    return LoadScript('examples/worm_gear_3d.py', 'worm_gear_3d')


@pytest.mark.physics
def test_axial_bearing_stiffness_moves_the_boundary_as_in_the_one_angle_model(example):
    """With stiff radial bearings (1e11 N/m) the 3D drive's chatter mode has the one-angle model's real part (with
    the worm's axial degree of freedom) within 0.1 1/s (the radial compliance and the tilt are left in series), and
    P1's boundary lies between 7.0e8 and 7.2e8 N/m in both (examples/worm_axial_bearing.py: 7.12e8 N/m)."""
    rows = example.AxialStiffnessScan((2e9, 7.2e8, 7e8, 5e8))
    for row in rows:
        assert row['rigidBodies'] == pytest.approx(row['oneAngle'], abs=0.1)
    signs = [np.sign(r['rigidBodies']) for r in rows]
    assert signs == [1., 1., -1., -1.] == [np.sign(r['oneAngle']) for r in rows]


@pytest.mark.physics
def test_bearing_loads_start_from_the_static_mesh_force(example):
    """A short run starts in the static equilibrium with the bearings deflected: the normal force is the one-angle
    model's static force (to 1e-5: the bodies' tilts in their bearings shift it by 1e-6), every bearing is loaded from
    the first step, and nothing rings (the loads stay within 1e-4 of their start over 0.05 s; started with undeflected
    bearings the worm's axial load peaked 32 % above it)."""
    series = example.BearingLoadSeries(endTime=0.05)
    loads = example.BearingLoads(series=series)
    reference = BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=GetPreset('reel-P1')))
    static = abs(float(reference.connector.InitialMeshState(reference.mbs).normalForce))
    assert loads['initialNormalForce'] == pytest.approx(static, rel=1e-5)
    for key in ('wormAxial', 'wormRadial', 'wheelAxial', 'wheelRadial'):
        assert series[key][0] > 100.
        assert loads[key] == pytest.approx(series[key][0], rel=1e-4), key


def test_without_a_display_the_frame_says_why(example, tmp_path, monkeypatch):
    """--out without a display and without xvfb-run: the frame's file is a picture that says why, and the line
    printed says so too (no window is opened)."""
    monkeypatch.delenv('DISPLAY', raising=False)
    monkeypatch.setattr(example.shutil, 'which', lambda name: None)
    line = example.WriteFrame(str(tmp_path))
    assert line == (f"wrote {tmp_path / example.FRAME} without a rendered frame: no display is set and xvfb-run "
                    f"(Debian package xvfb) is not installed")
    assert (tmp_path / example.FRAME).read_bytes()[:8] == b'\x89PNG\r\n\x1a\n'
