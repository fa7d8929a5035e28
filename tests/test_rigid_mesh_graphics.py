"""Graphics of the rigid-body mesh for Exudyn's renderer: built on the bodies, the thread drawn with the mechanics'
hand, the force arrow follows the run where no body hides it, and a recorded run is what the viewer plays."""
import os

import exudyn as exu
import numpy as np
import pytest
from exudyn.rigidBodyUtilities import InertiaCylinder
from exudyn.utilities import LoadSolutionFile

from exudyn_worm.analysis.simulation.reelchanger import SolverSettings
from exudyn_worm.builders.rigidbody import BuildRigidBodyReelChanger
from exudyn_worm.items.meshgraphics import AddRigidMeshGraphics, ArrowStart, RecordSolution, ThreadHelix
from exudyn_worm.items.rigidmesh import CreateRigidBodyWormGear
from exudyn_worm.drive.presets import GetPreset
from exudyn_worm.drive.wholedrive import ResolveDrive

pytest.importorskip('exudyn')
GEAR = ResolveDrive('reel-P1').elastic.gear


def _Solved(endTime=0.01, record=None):
    model = BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=GetPreset('reel-P1')))
    mesh = model.connector
    mesh.AddSensors(model.mbs)
    graphics = AddRigidMeshGraphics(model.mbs, mesh, teeth=12)
    model.mbs.Assemble()
    ss, solverType = SolverSettings(endTime, 1e-3)
    path = None if record is None else RecordSolution(ss, folder=record, period=1e-3)
    model.mbs.SolveDynamic(ss, solverType=solverType)
    return model, graphics, path


def test_graphics_are_built_and_the_arrow_shows_the_stored_mesh_force():
    """Pitch cylinders, helix and tooth lines on the bodies; the arrow is the wheel's mesh force at the time shown
    (scaled to r2 for the largest normal force), from ArrowStart; nothing to draw before the solve."""
    model = BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=GetPreset('reel-P1')))
    mesh = model.connector
    mesh.AddSensors(model.mbs)
    graphics = AddRigidMeshGraphics(model.mbs, mesh, teeth=12)
    assert len(graphics['worm']) == 2 and len(graphics['wheel']) == 13
    for body in mesh.bodyNumbers:                    # Exudyn merges the lines into one item
        stored = model.mbs.GetObject(body, addGraphicsData=True)['VgraphicsData']
        assert {g['type'] for g in stored} >= {'TriangleList'} and {g['type'] for g in stored} & {'Line', 'Lines'}
    assert graphics['Arrow'](model.mbs, 0.) == []
    model, graphics, _ = _Solved()
    mesh = model.connector
    forces = mesh.StoredMeshForces(model.mbs)
    arrow = graphics['Arrow'](model.mbs, 0.005)
    assert len(arrow) == 1 and arrow[0]['type'] == 'TriangleList'
    k = int(np.argmin(np.abs(forces['time'] - 0.005)))
    F = np.asarray(forces['wheelForce'])[k]
    points = np.asarray(arrow[0]['points']).reshape(-1, 3)
    tip = points[np.argmax(points @ F)]              # the arrow's farthest point along the force
    expected = ArrowStart(mesh, 2. * mesh.gear.r1) + F * mesh.gear.r2 / np.max(forces['normalForceFlank1'])
    np.testing.assert_allclose(tip, expected, atol=1e-3 * mesh.gear.r2)


def _Outside(points, axisPoint, axis, radius, halfLength):
    """Which points lie outside a cylinder (radius and half length about the point on its axis)."""
    d = points - axisPoint
    along = d @ axis
    across = np.linalg.norm(d - np.outer(along, axis), axis=1)
    return (np.abs(along) > halfLength) | (across > radius)


def test_the_arrow_is_outside_both_bodies_and_faces_the_default_view():
    """Every point of the arrow lies outside the drawn worm (radius r1, length 8 r1) and wheel (radius r2, width 2 r1)
    and in front of the wheel's face seen from +z, where the renderer's default view looks from."""
    model, graphics, _ = _Solved()
    mesh, g = model.connector, model.connector.geometry
    r1, r2 = mesh.gear.r1, mesh.gear.r2
    for t in (0., 0.005, 0.01):
        points = np.asarray(graphics['Arrow'](model.mbs, t)[0]['points']).reshape(-1, 3)
        assert np.all(_Outside(points, g.wormAxisPoint, g.wormAxis, r1, 4. * r1))
        assert np.all(_Outside(points, g.wheelAxisPoint, g.wheelAxis, r2, r1))
        assert np.all(points[:, 2] > r1)                   # in front of the wheel's face z = r1


@pytest.mark.physics
@pytest.mark.parametrize('wheelAxis, right', [([0., 0., 1.], False), ([0., 0., -1.], True)])
def test_the_drawn_thread_has_the_hand_of_the_mechanics(wheelAxis, right):
    """The drawn helix turns positively about the worm's axis while it advances along it for a right-handed thread
    (against it for a left-handed one). Turned positively, a thread moves past a fixed point against the axis if
    right-handed: the wheel's tooth at the pitch point must move so, and a positive worm rotation turns the wheel
    positively, so the wheel's positive direction at the pitch point, e_b x (P - wheel axis point), has along the worm's
    axis the sign -1 for a right-handed thread, +1 for a left-handed one. Worm along x, wheel at +y; the wheel's axis
    +z and -z give both hands."""
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    worm = mbs.CreateRigidBody(inertia=InertiaCylinder(7800., 0.1, GEAR.r1, axis=0), returnDict=True)
    wheel = mbs.CreateRigidBody(inertia=InertiaCylinder(7800., 0.03, GEAR.r2, axis=2),
                                referencePosition=[0., GEAR.r1 + GEAR.r2, 0.], returnDict=True)
    mesh = CreateRigidBodyWormGear(mbs, [worm, wheel], gear=GEAR, wormAxis=[1, 0, 0], wheelAxis=wheelAxis)
    g = mesh.geometry
    helix = ThreadHelix(mesh, 8. * GEAR.r1)                 # body coordinates: the worm's are the global ones here
    axis = np.array([1., 0., 0.])
    d = np.diff(helix, axis=0)
    radial = helix[:-1] - (helix[:-1] @ axis)[:, None] * axis
    turning = np.cross(radial, d) @ axis                    # > 0: turns positively about the axis
    advance = d @ axis
    drawnRight = bool(np.all(turning * advance > 0.))
    assert drawnRight or np.all(turning * advance < 0.)
    toothMoves = np.cross(g.wheelAxis, g.meshPoint - g.wheelAxisPoint) @ g.wormAxis
    assert drawnRight == (toothMoves < 0.) == right == g.rightHanded


def test_the_builders_reel_layout_is_left_handed_and_drawn_so():
    """The reel changer's layout (worm axis -y, wheel axis +z, centre line +x) has h = +1: left-handed, and its helix
    advances against the worm's axis while turning positively."""
    model = BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=GetPreset('reel-P1')))
    mesh = model.connector
    assert mesh.geometry.hand == 1. and not mesh.geometry.rightHanded
    worm = mesh._kinematics.bodies[0]
    helix = ThreadHelix(mesh, 8. * mesh.gear.r1)
    d = np.diff(helix, axis=0)
    radial = helix[:-1] - worm.axisPoint - ((helix[:-1] - worm.axisPoint) @ worm.axis)[:, None] * worm.axis
    assert np.all((np.cross(radial, d) @ worm.axis) * (d @ worm.axis) < 0.)


def test_a_recorded_run_is_what_the_solution_viewer_plays(tmp_path):
    """RecordSolution: the solve writes its coordinates where mbs.SolutionViewer() reads them (the system's last
    simulation settings), up to the end time, not into the current directory."""
    before = set(os.listdir('.'))
    model, graphics, path = _Solved(endTime=0.02, record=str(tmp_path))
    assert set(os.listdir('.')) == before
    settings = model.mbs.sys['simulationSettings']
    assert settings.solution.file.write and os.path.abspath(settings.solution.file.name) == path
    solution = LoadSolutionFile(path, verbose=False)
    times = np.asarray(solution['data'])[:, 0]
    assert times[-1] == pytest.approx(0.02, abs=1e-9) and len(times) > 10
    assert solution['nColumns'] - 1 >= model.mbs.systemData.ODE2Size()
