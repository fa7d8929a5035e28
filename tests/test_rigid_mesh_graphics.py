"""Graphics of the rigid-body mesh for Exudyn's renderer: built on the bodies, the force arrow follows the run."""
import exudyn as exu
import numpy as np
import pytest

from exudyn_worm.analysis.simulation.reelchanger import SolverSettings
from exudyn_worm.builders.rigidbody import BuildRigidBodyReelChanger
from exudyn_worm.items.meshgraphics import AddRigidMeshGraphics
from exudyn_worm.drive.presets import GetPreset
from exudyn_worm.drive.wholedrive import ResolveDrive

pytest.importorskip('exudyn')


def test_graphics_are_built_and_the_arrow_shows_the_stored_mesh_force():
    """Pitch cylinders, helix and tooth lines on the bodies; the arrow at the pitch point is the wheel's mesh force
    at the time shown (scaled to r2 for the largest normal force); nothing to draw before the solve."""
    model = BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=GetPreset('reel-P1')))
    mesh = model.connector
    mesh.AddSensors(model.mbs)
    graphics = AddRigidMeshGraphics(model.mbs, mesh, teeth=12)
    assert len(graphics['worm']) == 2 and len(graphics['wheel']) == 13
    for body in mesh.bodyNumbers:                    # Exudyn merges the lines into one item
        stored = model.mbs.GetObject(body, addGraphicsData=True)['VgraphicsData']
        assert {g['type'] for g in stored} >= {'TriangleList'} and {g['type'] for g in stored} & {'Line', 'Lines'}
    assert graphics['Arrow'](model.mbs, 0.) == []
    model.mbs.Assemble()
    ss, solverType = SolverSettings(0.01, 1e-3)
    model.mbs.SolveDynamic(ss, solverType=solverType)
    forces = mesh.StoredMeshForces(model.mbs)
    arrow = graphics['Arrow'](model.mbs, 0.005)
    assert len(arrow) == 1 and arrow[0]['type'] == 'TriangleList'
    k = int(np.argmin(np.abs(forces['time'] - 0.005)))
    F = np.asarray(forces['wheelForce'])[k]
    points = np.asarray(arrow[0]['points']).reshape(-1, 3)
    tip = points[np.argmax(points @ F)]              # the arrow's farthest point along the force
    expected = mesh.geometry.meshPoint + F * mesh.gear.r2 / np.max(forces['normalForceFlank1'])
    np.testing.assert_allclose(tip, expected, atol=1e-3 * mesh.gear.r2)
