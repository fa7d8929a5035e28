"""MeshState documents every field with unit and sign; flank magnitudes; stored states carry their time."""
import dataclasses
import inspect

import exudyn as exu
import numpy as np

import exudyn_worm as ew
from exudyn_worm.model.contact import MeshState, NormalForceFlanks
from exudyn_worm.items.solve import SolveDynamicInChunks
from exudyn_worm.drive.wholedrive import ResolveDrive


def test_every_field_documented_with_a_unit_or_sign():
    doc = inspect.getdoc(MeshState)
    for field in dataclasses.fields(MeshState):
        entry = doc.split(f'\n{field.name} :', 1)
        assert len(entry) == 2, f'{field.name} not documented'
        text = entry[1].split('\n\n')[0].split('\n', 2)[1]
        assert any(u in text for u in (' rad', ' m', ' N', 'N*m', ' s', 'dimensionless', '[-1, 1]')), field.name
    assert 'Signed' in doc


def test_flanks_are_magnitudes():
    first, second = NormalForceFlanks([3., -5., 0.])
    assert first.tolist() == [3., 0., 0.] and second.tolist() == [0., 5., 0.]


def test_result_and_stored_state_carry_time_and_flanks():
    result = ew.SimulateReelChanger(ResolveDrive(parameters=ew.GetPreset('reel-P1')), endTime=0.2, stepSize=5e-4, progress=False)
    first, second = result.normalForceFlanks
    assert np.all(first >= 0) and np.all(second >= 0)
    np.testing.assert_array_equal(first - second, result.normalForce)
    assert result.time.shape == result.normalForce.shape and result.time[-1] == result.endTime


def test_stored_mesh_state_has_time():
    drive = ew.ElasticDriveFromParameters(ew.GetPreset('reel-P1'))
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    worm, wheel = ew.CreateRotor(mbs, drive.J1, initialSpeed=1.), ew.CreateRotor(mbs, drive.J2)
    mesh = ew.CreateWormGear(mbs, [worm['nodeNumber'], wheel['nodeNumber']], gear=drive.gear)
    mesh.AddSensors(mbs)
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ss.solution.file.write = False
    ss.timeIntegration.endTime, ss.timeIntegration.numberOfSteps = 0.01, 20
    ss.solution.sensors.writePeriod = 0.01 / 20
    SolveDynamicInChunks(mbs, ss, progress=False)
    state = mesh.StoredMeshState(mbs)
    assert state.time.shape == state.normalForce.shape and state.time[0] == 0. and abs(state.time[-1] - 0.01) < 1e-12
