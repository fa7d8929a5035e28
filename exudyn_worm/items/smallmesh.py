"""The small-displacement 3D model of a worm mesh between two shafts on linear bearings.

Worm and wheel have the twelve coordinates of the exact model's Tait-Bryan (``RotationRxyz``) nodes turning about
their last angle (:mod:`exudyn_worm.items.rigidmesh`): per shaft its displacement (3) and its angles (2 tilts, then
its turn, each from the reference rotation). For displacements and tilts that stay small (bearing deflections), the
mass matrix, the bearings' stiffness and damping and the gyroscopic matrix of a body spinning about its axis are
constant, and the four inputs of the contact law (worm angle, wheel angle, axial displacement, radial approach) are
linear in the coordinates, with the gradient rows of the exact model at its reference configuration
(:func:`~exudyn_worm.items.rigidmesh._MeshFrame`, the same kinematics). A constant change of coordinates
``z = C q`` makes the four inputs coordinates of their own (a ``NodeGenericODE2`` of 4), the other eight are node
coordinates of the shafts (a ``NodeGenericODE2`` of 8, the worm's turn among them); then

- one ``ObjectGenericODE2`` on both nodes carries the constant matrices ``C^-T M C^-1``, ``C^-T K C^-1``,
  ``C^-T D C^-1`` (no user function),
- the contact law is one symbolic (C++) user function of the 4 inputs, whose generalized forces are the law's
  [worm torque, wheel torque, axial force, radial force] as one vector expression, and
- no constraint is needed; the stick/slip state is switched by the same policy as for every mesh
  (:mod:`exudyn_worm.model.stickslip`), reading the 4 inputs.

The turns enter linearly and exactly (the last Tait-Bryan angle is the turn about the tilted axis), so the model
holds for any number of turns; what it leaves out are terms of second order in the displacements and tilts (the
exact model's rotation matrices) and the change of the gyroscopic matrix with the spin speed (it uses the speeds at
the start). The bearings are those of :func:`~exudyn_worm.items.bearings.CreateShaftBearings`: two radial bearings
``span`` apart, centred on the body's reference point, and an axial bearing there, each linear.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from .._checks import CheckName, CheckPositive, CheckSystem
from ._rigidnodes import RIGID_NODES
from ._userfunctions import SetGenericForceLaw
from .bearings import ShaftBearings
from .connector import _AddStickSlip, _StickSlip, _SwitchContactOptions
from .rigidmesh import MeshGeometry, _Law, _MeshFrame
from ..model.contact import ContactOptions, FrictionState, MeshState, SymbolicOps
from ..model.friction import MATH_OPS, NUMPY_OPS
from ..model.gear import WormGear
from ..model.stickslip import StartFrictionState

__all__ = ['SmallDisplacementBody', 'SmallWormGearConnector', 'CreateSmallDisplacementWormGear',
           'SMALL_CONNECTORS_KEY']

#: ``mbs.variables`` key of the list of small-displacement meshes built in a system
SMALL_CONNECTORS_KEY = 'exudynWorm.smallConnectors'
#: index of the turn among a shaft's six coordinates (the last Tait-Bryan angle)
_TURN = 5
_FOUR = np.eye(4)          # the law's forces on its own four coordinates


@dataclass(frozen=True)
class SmallDisplacementBody:
    """One shaft of the small-displacement model (SI units).

    Attributes
    ----------
    referencePosition : array_like
        The body's reference point (global, 3), on its axis; the bearings are centred on it.
    referenceRotation : array_like
        Rotation matrix (3 x 3, body to global) of the reference configuration; the body's local z is its axis
        (it turns about its last Tait-Bryan angle).
    mass : float
        Mass in kg (> 0).
    inertia : array_like
        Inertia tensor (3 x 3) in body coordinates about the reference point, symmetric about the local z axis.
    bearings : ShaftBearings
        The shaft's linear bearings.
    spinSpeed : float
        Speed in rad/s about the axis of the gyroscopic matrix (the speed at the start).
    shaftInertia : float
        Inertia in kg*m^2 that turns with the body without tilting with it (a motor rotor behind a coupling, a reel
        on its own bearings): a mass on the turn coordinate alone, outside the gyroscopic matrix.
    """
    referencePosition: Any
    referenceRotation: Any
    mass: float
    inertia: Any
    bearings: ShaftBearings
    spinSpeed: float = 0.
    shaftInertia: float = 0.


def _Skew(v) -> np.ndarray:
    return np.array([[0., -v[2], v[1]], [v[2], 0., -v[0]], [-v[1], v[0], 0.]])


def _RotationMass(inertia) -> Any:
    """The Tait-Bryan angles' mass matrix G(theta)^T J G(theta) as a function of the (total) angles."""
    G = RIGID_NODES['RigidBodyRxyz'].velocityMap
    return lambda theta: np.asarray(G(list(theta), MATH_OPS), dtype=float).T @ inertia @ \
        np.asarray(G(list(theta), MATH_OPS), dtype=float)


def _BodyMatrices(where: str, name: str, body: SmallDisplacementBody, theta0: np.ndarray):
    """Mass, stiffness and damping (with the gyroscopic part) of one shaft on its 6 coordinates, and the bearing
    maps of :meth:`SmallWormGearConnector.BearingLoads` (list of (point map P, global matrices K, D, axis))."""
    J = np.asarray(body.inertia, dtype=float)
    if J.shape != (3, 3) or not np.allclose(J, J.T, atol=1e-12 * max(1., float(np.max(np.abs(J))))):
        raise ValueError(f"{where}: the {name}'s 'inertia' must be a symmetric 3 x 3 tensor in kg*m^2, got {J.tolist()!r}")
    Mr = _RotationMass(J)
    h = 1e-6
    shifted = theta0.copy()
    shifted[2] += 1.
    if not np.allclose(Mr(shifted), Mr(theta0), rtol=1e-9, atol=1e-12 * float(np.max(np.abs(J)))):
        raise ValueError(f"{where}: the small-displacement model needs the {name}'s inertia symmetric about its axis "
                         f"(local z: Jxx = Jyy, no products with z), got {J.tolist()!r}; use the exact model")
    M = np.zeros((6, 6))
    M[:3, :3] = np.eye(3) * CheckPositive(where, f'{name} mass', body.mass, 'kg')
    M[3:, 3:] = Mr(theta0)
    M[5, 5] += float(body.shaftInertia)        # the turn only (the last Tait-Bryan angle)
    # gyroscopic matrix of the steady spin Omega e_s (s: the turn) from the Lagrangian T = 1/2 theta'^T M(theta) theta':
    # D_ij = Omega (d_s M_ij + d_j M_is - d_i M_sj), the derivatives by central differences
    dM = []
    for k in range(3):
        e = np.zeros(3)
        e[k] = h
        dM.append((Mr(theta0 + e) - Mr(theta0 - e)) / (2. * h))
    s, Omega = 2, float(body.spinSpeed)
    gyro = np.array([[Omega * (dM[s][i, j] + dM[j][i, s] - dM[i][s, j]) for j in range(3)] for i in range(3)])
    R0 = np.asarray(body.referenceRotation, dtype=float)
    G0 = np.asarray(RIGID_NODES['RigidBodyRxyz'].velocityMap(list(theta0), MATH_OPS), dtype=float)
    T = np.zeros((6, 6))                       # coordinates -> (displacement, small rotation), global
    T[:3, :3] = np.eye(3)
    T[3:, 3:] = R0 @ G0
    axis = R0[:, 2]
    b = body.bearings
    K, D = np.zeros((6, 6)), np.zeros((6, 6))
    D[3:, 3:] = gyro
    across = np.eye(3) - np.outer(axis, axis)
    bearings = []
    for offset, k, d, key in ((-0.5 * b.span, b.radialStiffness, b.radialDamping, 'radial0'),
                              (0.5 * b.span, b.radialStiffness, b.radialDamping, 'radial1'),
                              (0., b.axialStiffness, b.axialDamping, 'axial')):
        direction = np.outer(axis, axis) if key == 'axial' else across
        P = np.hstack([np.eye(3), -_Skew(offset * axis)]) @ T     # coordinates -> the bearing point's displacement
        K += P.T @ (k * direction) @ P
        D += P.T @ (d * direction) @ P
        bearings.append((key, P, k * direction, d * direction))
    return M, K, D, (axis, bearings)


class _SmallStickSlip(_StickSlip):
    """The stick/slip state of a small-displacement mesh: the connector's machinery on the law's own four
    coordinates (worm angle, wheel angle, axial displacement, radial approach; plus their constant offsets)."""

    def __init__(self, gear: WormGear, options: ContactOptions, node, offsets, initial: FrictionState,
                 symbolic: bool):
        self._offsets = [float(x) for x in offsets]
        super().__init__(gear, options, [node], [0.], initial, symbolic)

    def _Record(self, initial: FrictionState) -> None:
        import exudyn
        esym = exudyn.symbolic
        self.variables = FrictionState(*(esym.Real(name, float(getattr(initial, name)))
                                         for name in ('stuck', 'direction', 'anchor')))
        recording = esym.GetRecording()
        esym.SetRecording(True)
        try:
            # the four inputs and their rates as two vectors (Exudyn 1.13.6: a vector of 8 entries corrupts the heap)
            x, w = esym.Vector('x', [0.] * 4), esym.Vector('w', [0.] * 4)
            mesh = _Law(self.gear, self.options, [x[k] for k in range(4)], [w[k] for k in range(4)],
                        SymbolicOps(), self.variables)
            self._probe = (x, mesh.frictionForce, mesh.normalForce, w)
        finally:
            esym.SetRecording(recording)

    def _LawInputs(self, q, v):
        i = self._indices[0]
        o = self._offsets
        return ([q[i] + o[0], q[i + 1] + o[1], q[i + 2] + o[2], q[i + 3] + o[3]],
                [v[i], v[i + 1], v[i + 2], v[i + 3]])

    def _Forces(self, x, w):
        probe = self._probe
        if probe is None:
            mesh = _Law(self.gear, self.options, x, w, MATH_OPS, self.state)
            return mesh.frictionForce, mesh.normalForce
        probe[0].SetVector(x)
        probe[3].SetVector(w)
        return probe[1].Evaluate(), probe[2].Evaluate()


@dataclass
class SmallWormGearConnector:
    """What :func:`CreateSmallDisplacementWormGear` created, and what reads its results.

    Attributes
    ----------
    objectNumber : exudyn.ObjectIndex
        The ``ObjectGenericODE2`` of the contact law (on the inputs' node).
    linearObjectNumber : exudyn.ObjectIndex
        The ``ObjectGenericODE2`` with the constant mass, stiffness and damping matrices (both nodes).
    nodeNumbers : list
        ``[inputs, shafts]``: the node of the law's 4 inputs and the node of the other 8 coordinates.
    gear : WormGear
        The mesh.
    options : ContactOptions
        The contact options the law was built with.
    geometry : MeshGeometry
        The mesh frame (global, reference configuration).
    name : str
        Name of the law's object.
    rows : ndarray
        The law inputs' gradient rows (4 x 12) over the shafts' coordinates (worm's 6, wheel's 6).
    offsets : ndarray
        The law inputs at zero coordinates (4; the reference angles included).
    toShafts : ndarray
        ``C^-1`` (12 x 12): the shafts' coordinates from the nodes' (inputs' 4, then the other 8).
    bearings : dict
        Per shaft (``worm``, ``wheel``): its axis and its bearings' maps, for :meth:`BearingLoads`.
    sensors : dict
        Sensors of :meth:`AddSensors`, by name.
    stickSlip : object or None
        The stick/slip state of the sticking friction model; None with the regularized model or a fixed S.
    userFunction : callable or None
        The law's user function (kept alive here).
    useSymbolic : bool
        The law in C++ (a symbolic user function) or in plain Python.
    """
    objectNumber: Any
    linearObjectNumber: Any
    nodeNumbers: List[Any]
    gear: WormGear
    options: ContactOptions
    geometry: MeshGeometry
    name: str
    rows: np.ndarray
    offsets: np.ndarray
    toShafts: np.ndarray
    bearings: Dict[str, Any] = field(default_factory=dict, repr=False)
    sensors: Dict[str, Any] = field(default_factory=dict)
    stickSlip: Any = field(default=None, repr=False)
    userFunction: Any = field(default=None, repr=False)
    useSymbolic: bool = True

    def CoordinateMarker(self, mbs: Any, body: str, coordinate: int) -> Tuple[Any, Any]:
        """A ``MarkerNodeCoordinate`` on shaft coordinate ``coordinate`` (0..5) of ``body`` ('worm' or 'wheel'),
        if that coordinate is one node coordinate of the model (the turns are).

        Parameters
        ----------
        mbs : exudyn.MainSystem
            The system.
        body : str
            'worm' or 'wheel'.
        coordinate : int
            0..5 (displacement x, y, z, then the Tait-Bryan angles, the turn last).

        Returns
        -------
        (marker number, node number)
        """
        from exudyn.itemInterface import MarkerNodeCoordinate
        k, j = self._NodeCoordinate(body, coordinate)
        node = self.nodeNumbers[k]
        return mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=node, coordinate=j)), node

    def _NodeCoordinate(self, body: str, coordinate: int) -> Tuple[int, int]:
        """(node index 0 or 1, coordinate of that node) that equals the shaft coordinate, else ValueError."""
        row = self.toShafts[6 * ('worm', 'wheel').index(body) + coordinate]
        j = int(np.argmax(np.abs(row)))
        if abs(row[j] - 1.) > 1e-12 or np.count_nonzero(np.abs(row) > 1e-12) != 1:
            raise ValueError(f"SmallWormGearConnector: the {body}'s coordinate {coordinate} is not a coordinate of "
                             f"the model's nodes")
        return (0, j) if j < 4 else (1, j - 4)

    def TurnIndices(self, mbs: Any) -> Tuple[int, int]:
        """The ODE2 indices (assembled system) of the worm's and the wheel's turn.

        Parameters
        ----------
        mbs : exudyn.MainSystem
            The system, assembled.

        Returns
        -------
        (int, int)
        """
        out = []
        for body in ('worm', 'wheel'):
            k, j = self._NodeCoordinate(body, _TURN)
            out.append(int(mbs.GetNodeODE2Index(self.nodeNumbers[k])) + j)
        return out[0], out[1]

    def Evaluate(self, q: Any, v: Any, time: Optional[Any] = None) -> MeshState:
        """Mesh quantities for arrays of the shafts' states.

        Parameters
        ----------
        q, v : array_like
            The shafts' coordinates and velocities (worm's 6, wheel's 6), one row per sample.
        time : array_like, optional
            Times in s of the samples: with the sticking model the recorded stick/slip states (None: the exact
            Coulomb law).

        Returns
        -------
        MeshState
        """
        q, v = np.atleast_2d(np.asarray(q, dtype=float)), np.atleast_2d(np.asarray(v, dtype=float))
        x = (q @ self.rows.T + self.offsets).T
        w = (v @ self.rows.T).T
        state = None
        if time is not None and self.stickSlip is not None and self.options.hasStickState:
            state = self.stickSlip.StatesAt(np.asarray(time, dtype=float))
        return _Law(self.gear, self.options, list(x), list(w), NUMPY_OPS, state)

    def InitialMeshState(self, mbs: Any) -> MeshState:
        """Mesh quantities at the system's initial state.

        Parameters
        ----------
        mbs : exudyn.MainSystem
            The system the connector belongs to.
        """
        z, zt = ([float(x) for node in self.nodeNumbers for x in np.ravel(mbs.GetNode(node)[key])]
                 for key in ('initialCoordinates', 'initialCoordinates_t'))
        x = [a + b for a, b in zip(z[:4], self.offsets)]
        state = None if self.stickSlip is None or not self.options.hasStickState else self.stickSlip.history[0][1]
        return _Law(self.gear, self.options, x, zt[:4], MATH_OPS, state)

    def RestartAngles(self, mbs: Any, coordinates: Any) -> None:
        """Nothing to do: the turns are coordinates (the exact model's method of the same name moves its angle
        references).

        Parameters
        ----------
        mbs : exudyn.MainSystem
            The system.
        coordinates : array_like
            The start's ODE2 coordinates (not used).
        """

    def SetContactOptions(self, mbs: Any, options: ContactOptions) -> None:
        """Replace the contact options (e.g. hold S); re-records the law.

        Parameters
        ----------
        mbs : exudyn.MainSystem
            The system the connector belongs to.
        options : ContactOptions
            The new options.
        """
        def NewStickSlip():
            z, zt = ([float(x) for x in np.ravel(mbs.GetNode(self.nodeNumbers[0])[key])]
                     for key in ('initialCoordinates', 'initialCoordinates_t'))
            start = StartFrictionState(self.gear, z[0] + self.offsets[0], z[1] + self.offsets[1], zt[0])
            return _SmallStickSlip(self.gear, options, self.nodeNumbers[0], self.offsets, start, self.useSymbolic)
        _SwitchContactOptions('SmallWormGearConnector', mbs, self, options, NewStickSlip)
        _SetLaw(mbs, self)

    def AddSensors(self, mbs: Any) -> Dict[str, Any]:
        """Add internally stored sensors of both nodes' coordinates, velocities and accelerations.

        Parameters
        ----------
        mbs : exudyn.MainSystem
            The system, before ``mbs.Assemble()``.

        Returns
        -------
        dict
        """
        import exudyn as exu
        from exudyn.itemInterface import SensorNode
        OVT = exu.OutputVariableType
        for k, node in enumerate(self.nodeNumbers):
            for key, ovt in (('Coordinates', OVT.Coordinates), ('Velocities', OVT.Coordinates_t),
                             ('Accelerations', OVT.Coordinates_tt)):
                self.sensors[f'node{k}{key}'] = mbs.AddSensor(SensorNode(nodeNumber=node, outputVariableType=ovt,
                                                                         storeInternal=True, writeToFile=False))
        return self.sensors

    def StoredShaftStates(self, mbs: Any) -> Dict[str, np.ndarray]:
        """The shafts' coordinates, velocities and accelerations over the stored steps (after :meth:`AddSensors`).

        Parameters
        ----------
        mbs : exudyn.MainSystem
            The system, after a solve.

        Returns
        -------
        dict of ndarray
            ``time`` (s); ``wormCoordinates``, ``wormVelocities``, ``wormAccelerations``, ``wheel...`` (samples x 6).
        """
        if not self.sensors:
            raise ValueError("SmallWormGearConnector: call AddSensors(mbs) before mbs.Assemble()")
        data = {k: np.asarray(mbs.GetSensorStoredData(s)) for k, s in self.sensors.items()}
        out = {'time': data['node0Coordinates'][:, 0]}
        for key in ('Coordinates', 'Velocities', 'Accelerations'):
            shafts = np.hstack([data[f'node0{key}'][:, 1:], data[f'node1{key}'][:, 1:]]) @ self.toShafts.T
            out['worm' + key], out['wheel' + key] = shafts[:, :6], shafts[:, 6:]
        return out

    def _Stored(self, mbs: Any):
        s = self.StoredShaftStates(mbs)
        return (s['time'], np.hstack([s['wormCoordinates'], s['wheelCoordinates']]),
                np.hstack([s['wormVelocities'], s['wheelVelocities']]))

    def StoredMeshState(self, mbs: Any) -> MeshState:
        """Mesh quantities over the stored time steps (requires :meth:`AddSensors`), with their ``time`` in s.

        Parameters
        ----------
        mbs : exudyn.MainSystem
            The system, after a solve.

        Returns
        -------
        MeshState
        """
        time, q, v = self._Stored(mbs)
        state = self.Evaluate(q, v, time)
        state.time = time
        return state

    def BearingLoads(self, q: Any, v: Any) -> Dict[str, Dict[str, np.ndarray]]:
        """The bearings' forces for arrays of the shafts' states, as
        :func:`~exudyn_worm.items.bearings.StoredBearingLoads` gives them for the exact model.

        Parameters
        ----------
        q, v : array_like
            The shafts' coordinates and velocities (worm's 6, wheel's 6), one row per sample.

        Returns
        -------
        dict
            Per shaft (``worm``, ``wheel``): ``axial`` (N, along the axis, signed), ``radial0``, ``radial1``
            (N, magnitudes across the axis) and ``radial`` (N, the magnitude of their vector sum).
        """
        q, v = np.atleast_2d(np.asarray(q, dtype=float)), np.atleast_2d(np.asarray(v, dtype=float))
        out = {}
        for k, body in enumerate(('worm', 'wheel')):
            axis, bearings = self.bearings[body]
            qb, vb = q[:, 6 * k:6 * k + 6], v[:, 6 * k:6 * k + 6]
            loads, total = {}, 0.
            for key, P, K, D in bearings:
                force = qb @ (K @ P).T + vb @ (D @ P).T          # the spring-damper's force, global
                if key == 'axial':
                    loads[key] = force @ axis
                else:
                    loads[key] = np.linalg.norm(force, axis=1)
                    total = total + force
            loads['radial'] = np.linalg.norm(total, axis=1)
            out[body] = loads
        return out


def _SetLaw(mbs: Any, connector: SmallWormGearConnector) -> None:
    """(Re)set the law's user function on the inputs' node."""
    stickSlip = connector.stickSlip if connector.options.hasStickState else None
    gear, options = connector.gear, connector.options
    offsets = [float(x) for x in connector.offsets]

    def SmallMeshLaw(t, q, q_t, ops):
        """[worm torque, wheel torque, axial force, radial force] on the law's own four coordinates."""
        x = [q[k] + offsets[k] if offsets[k] != 0. else q[k] for k in range(4)]
        w = [q_t[k] for k in range(4)]
        mesh = _Law(gear, options, x, w, ops, None if stickSlip is None else stickSlip.LawState(ops), _FOUR)
        return mesh.generalizedForces
    connector.userFunction = SetGenericForceLaw(mbs, connector.objectNumber, 4, SmallMeshLaw,
                                                useSymbolic=connector.useSymbolic, check=False)


def CreateSmallDisplacementWormGear(mbs: Any, bodies: Sequence[SmallDisplacementBody], gear: WormGear,
                                    contactOptions: ContactOptions = ContactOptions(),
                                    initialCoordinates: Optional[Sequence[float]] = None,
                                    initialVelocities: Optional[Sequence[float]] = None,
                                    referenceAngles: Sequence[float] = (0., 0.), name: str = '',
                                    useSymbolic: bool = True) -> SmallWormGearConnector:
    """Add worm and wheel on their linear bearings, meshing, as the small-displacement model (module docstring).

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system.
    bodies : [worm, wheel]
        The two shafts (:class:`SmallDisplacementBody`); their axes (local z) must cross at 90 deg at the distance
        r1 + r2, as for :func:`~exudyn_worm.items.rigidmesh.CreateRigidBodyWormGear`.
    gear : WormGear
        The mesh.
    contactOptions : ContactOptions
        Options of the contact law (default: sticking friction with its stick/slip state).
    initialCoordinates, initialVelocities : sequence of 12 floats, optional
        The shafts' coordinates (worm's 6, wheel's 6: displacement, tilts, turn, from the reference configuration)
        and velocities at the start (default 0).
    referenceAngles : (float, float)
        Angles in rad added to the law's worm and wheel angles (the tooth position), as in
        :func:`~exudyn_worm.items.rigidmesh.CreateRigidBodyWormGear`.
    name : str
        Name of the law's object (and prefix of the nodes' names).
    useSymbolic : bool
        The law in C++ (a symbolic user function, default) or plain Python.

    Returns
    -------
    SmallWormGearConnector

    Raises
    ------
    ValueError, TypeError
        For bodies that are not two :class:`SmallDisplacementBody`, axes that do not cross at 90 deg at r1 + r2,
        an inertia not symmetric about the axis, or initial states that are not 12 numbers.
    """
    from exudyn.itemInterface import NodeGenericODE2, ObjectGenericODE2
    from exudyn.rigidBodyUtilities import RotationMatrix2RotXYZ
    w = 'CreateSmallDisplacementWormGear'
    CheckSystem(w, mbs)
    CheckName(w, 'name', name)
    if not isinstance(gear, WormGear):
        raise TypeError(f"{w}: 'gear' must be a WormGear, got {type(gear).__name__}")
    if not isinstance(contactOptions, ContactOptions):
        raise TypeError(f"{w}: 'contactOptions' must be a ContactOptions, got {type(contactOptions).__name__}")
    if len(bodies) != 2 or not all(isinstance(b, SmallDisplacementBody) for b in bodies):
        raise TypeError(f"{w}: 'bodies' must be [worm, wheel], two SmallDisplacementBody, got {bodies!r}")
    states = []
    for label, value in (('initialCoordinates', initialCoordinates), ('initialVelocities', initialVelocities)):
        array = np.zeros(12) if value is None else np.asarray(value, dtype=float).ravel()
        if array.shape != (12,) or not np.all(np.isfinite(array)):
            raise ValueError(f"{w}: '{label}' must be 12 finite numbers (worm's 6, wheel's 6), got {value!r}")
        states.append(array)
    q0, v0 = states
    infos, thetas = [], []
    for b in bodies:
        theta = np.asarray(RotationMatrix2RotXYZ(np.asarray(b.referenceRotation, dtype=float)), dtype=float)
        thetas.append(theta)
        infos.append({'nodeType': 'RigidBodyRxyz', 'initialCoordinates': np.zeros(6),
                      'referenceCoordinates': np.concatenate([np.asarray(b.referencePosition, dtype=float), theta])})
    axes = [np.array([0., 0., 1.])] * 2
    geometry, kinematics, angles = _MeshFrame(w, gear, [None, None], infos, axes, [np.zeros(3), np.zeros(3)])
    terms, frames = kinematics.Evaluate([0.] * 12, [(a, math.cos(a), math.sin(a)) for a in angles])
    rows = np.asarray(kinematics.Rows(terms, frames), dtype=float)
    offsets = np.array([float(t.value) for t in terms]) + np.array([float(referenceAngles[0]),
                                                                    float(referenceAngles[1]), 0., 0.])
    # the other eight coordinates: the shafts' own, worm's first, each kept if it is independent of those before
    C = list(rows)
    kept = []
    for k in range(12):
        trial = np.vstack(C + [np.eye(12)[k]])
        if np.linalg.matrix_rank(trial, tol=1e-9) == len(trial):
            C.append(np.eye(12)[k])
            kept.append(k)
        if len(C) == 12:
            break
    C = np.array(C)
    Cinv = np.linalg.inv(C)
    M, K, D = (np.zeros((12, 12)) for _ in range(3))
    maps = {}
    for k, (b, theta, label) in enumerate(zip(bodies, thetas, ('worm', 'wheel'))):
        Mb, Kb, Db, maps[label] = _BodyMatrices(w, label, b, theta)
        block = slice(6 * k, 6 * k + 6)
        M[block, block], K[block, block], D[block, block] = Mb, Kb, Db
    Mz, Kz, Dz = (Cinv.T @ A @ Cinv for A in (M, K, D))
    z0, zt0 = C @ q0, C @ v0
    prefix = name or 'wormGear'
    inputs = mbs.AddNode(NodeGenericODE2(numberOfODE2Coordinates=4, referenceCoordinates=[0.] * 4,
                                         initialCoordinates=list(z0[:4]), initialCoordinates_t=list(zt0[:4]),
                                         name=prefix + 'Inputs'))
    shafts = mbs.AddNode(NodeGenericODE2(numberOfODE2Coordinates=8, referenceCoordinates=[0.] * 8,
                                         initialCoordinates=list(z0[4:]), initialCoordinates_t=list(zt0[4:]),
                                         name=prefix + 'Shafts'))
    linear = mbs.AddObject(ObjectGenericODE2(nodeNumbers=[inputs, shafts], massMatrix=Mz, stiffnessMatrix=Kz,
                                             dampingMatrix=Dz, name=prefix + 'Shafts'))
    zeros = np.zeros((4, 4))
    law = mbs.AddObject(ObjectGenericODE2(nodeNumbers=[inputs], massMatrix=zeros, stiffnessMatrix=zeros,
                                          dampingMatrix=zeros, name=name))
    connector = SmallWormGearConnector(objectNumber=law, linearObjectNumber=linear, nodeNumbers=[inputs, shafts],
                                       gear=gear, options=contactOptions, geometry=geometry, name=name, rows=rows,
                                       offsets=offsets, toShafts=Cinv, bearings=maps, useSymbolic=bool(useSymbolic))
    if contactOptions.hasStickState:
        x, rate = rows @ q0 + offsets, rows @ v0
        connector.stickSlip = _SmallStickSlip(gear, contactOptions, inputs, offsets,
                                              StartFrictionState(gear, float(x[0]), float(x[1]), float(rate[0])),
                                              bool(useSymbolic))
    _SetLaw(mbs, connector)
    if connector.stickSlip is not None:
        _AddStickSlip(mbs, connector.stickSlip)
    mbs.variables.setdefault(SMALL_CONNECTORS_KEY, []).append(connector)
    return connector
