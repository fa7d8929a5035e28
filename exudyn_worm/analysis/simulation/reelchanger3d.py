"""The runs of the 3D model (:func:`~exudyn_worm.builders.rigidbody.BuildRigidBodyReelChanger`, worm and wheel as
rigid bodies): its sensors, the stored series, the shafts' loads and the mesh forces a simulation reports.
"""
from __future__ import annotations

from typing import Any, Dict, Optional

import numpy as np

from ...items.bearings import StoredBearingLoads
from ...items.rigidmesh import MeshForceComponents
from ...model.contact import MeshState
from ...builders.rigidbody import TURN, RigidBodyReelChanger, WORM_AXIS

__all__ = ['AddSeriesSensors', 'StoredSeries', 'StoredShaftLoads', 'ShaftLoadPeaks', 'StoredMeshState', 'MeshForceSeries', 'MESH_FORCE_SERIES']



def StoredShaftLoads(model: RigidBodyReelChanger) -> Dict[str, np.ndarray]:
    """The loads of both shafts' supports over the stored steps of a solved :class:`RigidBodyReelChanger`.

    Elastic bearings: :func:`~exudyn_worm.items.bearings.StoredBearingLoads`; an ideal revolute joint: its reaction
    force (along the shaft: the axial load; across: the radial load, the vector sum of the shaft's radial bearings);
    with the worm's axial bearing ``kA`` the axial load is its spring's force.

    Parameters
    ----------
    model : RigidBodyReelChanger
        The model, after a solve.

    Returns
    -------
    dict of ndarray
        ``time`` (s), ``wormAxialLoad``, ``wheelAxialLoad`` (N, along the shaft's axis, signed as the item reports
        it), ``wormRadialLoad``, ``wheelRadialLoad`` (N, magnitude of the radial force).
    """
    mbs = model.mbs
    out = {}
    if model.model == 'small':             # the bearings' forces from the shafts' stored states
        time, q, v = model.connector._Stored(mbs)
        loads = model.connector.BearingLoads(q, v)
        out['time'] = time
        for body in ('worm', 'wheel'):
            out[body + 'AxialLoad'], out[body + 'RadialLoad'] = loads[body]['axial'], loads[body]['radial']
        return out
    for body, items in model.bearings.items():
        if 'joint' not in items:
            loads = StoredBearingLoads(mbs, items)
            out['time'], axial, radial = loads['time'], loads['axial'], loads['radial']
        else:                      # the joint's forces on the held coordinates: translations first (global)
            force = np.asarray(mbs.GetSensorStoredData(items['sensors']['joint']))
            out['time'] = force[:, 0]
            along = int(np.argmax(np.abs(items['axis'])))
            translations = {k: force[:, 1 + i] for i, k in enumerate(items['heldCoordinates']) if k < 3}
            across = [translations[k] for k in range(3) if k != along]
            radial = np.hypot(across[0], across[1])
            axial = (np.asarray(mbs.GetSensorStoredData(items['sensors']['axialSpring']))[:, 1]
                     if 'axialSpring' in items['sensors'] else translations[along])
        out[body + 'AxialLoad'], out[body + 'RadialLoad'] = np.asarray(axial, float), np.asarray(radial, float)
    return out


def ShaftLoadPeaks(model: RigidBodyReelChanger, since: Optional[float] = None) -> Dict[str, float]:
    """The largest magnitudes in N of :func:`StoredShaftLoads` over the stored steps (from ``since`` s on, if given),
    by the keys of :data:`~exudyn_worm.items.bearings.BEARING_LOADS` (``maxWormAxialLoad``, ...).

    Parameters
    ----------
    model : RigidBodyReelChanger
        The model, after a solve.
    since : float, optional
        Only the steps at or after this time in s.

    Returns
    -------
    dict of float
    """
    loads = StoredShaftLoads(model)
    keep = slice(None) if since is None else loads['time'] >= since
    return {'max' + k[0].upper() + k[1:]: float(np.max(np.abs(v[keep]))) for k, v in loads.items() if k != 'time'}


def StoredSeries(model: RigidBodyReelChanger) -> Dict[str, np.ndarray]:
    """The series of a solved :class:`RigidBodyReelChanger` by the names of
    :class:`~exudyn_worm.items.results.SimulationResult` (before the mesh quantities are added).

    Parameters
    ----------
    model : RigidBodyReelChanger
        The model, after a solve; needs :func:`AddSeriesSensors` before ``mbs.Assemble()``.

    Returns
    -------
    dict of ndarray
        ``time``; ``phi0, omega0`` (motor), ``phi1, omega1, alpha1`` (worm: its turn about its axis, the last
        Tait-Bryan coordinate), ``phi2, omega2, alpha2`` (wheel: the same), with the worm's axial bearing
        ``xA, vA`` (the worm's axial displacement); the bearing loads of :func:`StoredShaftLoads`.
    """
    mbs = model.mbs
    data = {k: np.asarray(mbs.GetSensorStoredData(s)) for k, s in model.sensors.items()}
    if model.model == 'small':             # the shafts' coordinates from the model's nodes
        shafts = model.connector.StoredShaftStates(mbs)
        data.update({k: np.column_stack([shafts['time'], v]) for k, v in shafts.items() if k != 'time'})
    out = {'time': data['motorAngle'][:, 0], 'phi0': data['motorAngle'][:, 1], 'omega0': data['motorSpeed'][:, 1]}
    for body, prefix in (('worm', '1'), ('wheel', '2')):
        for name, key in (('phi', 'Coordinates'), ('omega', 'Velocities'), ('alpha', 'Accelerations')):
            out[name + prefix] = data[body + key][:, 1 + TURN]
    if model.axialBearing is not None:          # along the worm's axis, -y
        along = 1 + int(np.argmax(np.abs(WORM_AXIS)))
        out['xA'], out['vA'] = (float(WORM_AXIS[along - 1]) * data['worm' + key][:, along]
                                for key in ('Coordinates', 'Velocities'))
    loads = StoredShaftLoads(model)
    loads.pop('time')
    out.update(loads)
    return out


def StoredMeshState(model: RigidBodyReelChanger, keep: Optional[np.ndarray] = None) -> MeshState:
    """The mesh quantities over the stored steps of a solved :class:`RigidBodyReelChanger` (those selected by the
    boolean array ``keep``, default all), as :meth:`~exudyn_worm.items.rigidmesh.RigidBodyWormGearConnector.Evaluate`.

    Parameters
    ----------
    model : RigidBodyReelChanger
        The model, after a solve (with :func:`AddSeriesSensors`).
    keep : ndarray of bool, optional
        The stored steps to evaluate.

    Returns
    -------
    MeshState
    """
    time, q, v = model.connector._Stored(model.mbs)
    if keep is not None:
        time, q, v = time[keep], q[keep], v[keep]
    state = model.connector.Evaluate(q, v, time)
    state.time = time
    return state


def MeshForceSeries(model: RigidBodyReelChanger, state: MeshState) -> Dict[str, np.ndarray]:
    """The mesh force on each body in its own terms (worm and wheel: tangential, axial, radial, N) per step of
    ``state``, as :func:`~exudyn_worm.items.rigidmesh.MeshForceComponents` gives them.

    Parameters
    ----------
    model : RigidBodyReelChanger
        The model.
    state : MeshState
        Its mesh quantities (:func:`StoredMeshState`).

    Returns
    -------
    dict of ndarray
        ``meshWormTangential``, ``meshWormAxial``, ..., ``meshWheelRadial`` (:data:`MESH_FORCE_SERIES`).
    """
    components = MeshForceComponents(model.connector, state)
    return {name: np.asarray(components[key], dtype=float) for key, name in MESH_FORCE_SERIES.items()}


#: the mesh-force series of a run of the 3D model (:func:`MeshForceSeries`) by their
#: :func:`~exudyn_worm.items.rigidmesh.MeshForceComponents` key
MESH_FORCE_SERIES = {key: 'mesh' + key[0].upper() + key[1:] for key in
                     ('wormTangential', 'wormAxial', 'wormRadial', 'wheelTangential', 'wheelAxial', 'wheelRadial')}


def AddSeriesSensors(model: RigidBodyReelChanger) -> Dict[str, Any]:
    """Add the internally stored sensors that :func:`StoredSeries` reads (before ``mbs.Assemble()``).

    Parameters
    ----------
    model : RigidBodyReelChanger
        The model, not yet assembled.

    Returns
    -------
    dict
        The sensors by name (also in ``model.sensors``).
    """
    import exudyn as exu
    from exudyn.itemInterface import SensorNode
    OVT = exu.OutputVariableType
    mbs = model.mbs
    for name, node, ovt in (('motorAngle', model.motor['nodeNumber'], OVT.Coordinates),
                            ('motorSpeed', model.motor['nodeNumber'], OVT.Coordinates_t)):
        model.sensors[name] = mbs.AddSensor(SensorNode(nodeNumber=node, outputVariableType=ovt, storeInternal=True,
                                                       writeToFile=False))
    if model.model == 'small':             # the connector's sensors of its nodes (StoredShaftStates)
        model.connector.AddSensors(mbs)
        return model.sensors
    for body, info in model.bodies.items():
        for key, ovt in (('Coordinates', OVT.Coordinates), ('Velocities', OVT.Coordinates_t),
                         ('Accelerations', OVT.Coordinates_tt)):
            model.sensors[body + key] = mbs.AddSensor(SensorNode(nodeNumber=info['nodeNumber'], outputVariableType=ovt,
                                                                 storeInternal=True, writeToFile=False))
    model.connector.sensors.update({k: model.sensors[k] for k in ('wormCoordinates', 'wormVelocities',
                                                                   'wheelCoordinates', 'wheelVelocities')})
    return model.sensors
