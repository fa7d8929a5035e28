"""The worm mesh between two Exudyn rigid bodies: the mesh forces reach the bodies, their joints and bearings.

:func:`CreateRigidBodyWormGear` couples a worm body and a wheel body (``mbs.CreateRigidBody``, any of its rotation
parametrizations: Euler parameters, Tait-Bryan angles, rotation vector) with the contact law of
:mod:`exudyn_worm.model.contact`. The bodies are held by the user's own Exudyn items (revolute joints,
spring-dampers as bearings, :func:`~exudyn_worm.items.bearings.CreateShaftBearings`, a housing body ...).

Kinematics (docs/mesh-3d.md). The mesh frame is fixed in space and taken from the reference configuration: worm
axis ``e_a``, wheel axis ``e_b`` (perpendicular), centre line ``e_c`` from the worm axis to the wheel axis
(their common perpendicular, length a = r1 + r2), worm tangent ``t = e_a x e_c`` (the direction in which a
positive worm rotation moves the worm's surface at the pitch point, parallel to the wheel axis) and the thread's
hand ``h = t . e_b`` = +1 or -1 (the positive rotation directions are those in which a positive worm rotation
turns the wheel positively; the hand follows from the axes the user gives). The relative displacement
``worm - wheel`` of the two material points at the pitch point has the components

- ``T = r1 phi1 - dD.t - h r2 (e_c . b')`` along ``t``,
- ``A = -h dD.e_a - h r1 (e_c . a') - r2 phi2`` along ``h e_a`` (where the thread advances),
- ``C = -dD.e_c`` along ``e_c`` (the approach),

with ``phi1, phi2`` the bodies' rotations about their axes (unwrapped, see below), ``dD`` the change of the
vector between the two axis points and ``a', b'`` the current worm and wheel axes (their tilt; first order in the
tilt). The contact law receives ``phi1 + (T - r1 phi1)/r1`` as the worm angle, ``phi2`` as the wheel angle, the
rest of ``A`` as the worm's axial displacement and ``C`` as the radial approach
(:func:`~exudyn_worm.model.contact.MeshContact`), so worm and wheel on ideal revolute joints give exactly the
one-angle connector (:func:`~exudyn_worm.items.connector.CreateWormGear`) and a worm that moves only axially gives
:func:`~exudyn_worm.items.connector.CreateWormAxialBearing`. The law's generalized forces (worm torque, wheel
torque, axial force, radial force) act on the bodies' coordinates through the gradients of these four mesh
coordinates: the normal and friction forces at the pitch point on both bodies, to first order in the tilts.

Angles. A body's rotation about its axis is measured from its reference orientation by an ``atan`` relative to a
reference angle that the system's post-Newton function moves along with the body between time steps (a fifth
of a radian ahead at most), so no rotation parameter wraps and the angle grows over any number of turns. It starts
within +-pi from the bodies' initial rotations (the plain-Python law; the C++ law's inputs are coordinates, and no
reference needs moving). ``referenceAngles`` shift the tooth position: they are added to the
law's worm and wheel angles (not to the measured rotations), as the one-angle connector adds its nodes' references.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence

import numpy as np

from .._checks import CheckBool, CheckName, CheckReal, CheckSystem
from ._rigidnodes import RIGID_NODES
from ._userfunctions import CheckPlainForceLaw, SetGenericForceLaw
from .connector import _AddStickSlip, _StickSlip, _SwitchContactOptions
from ..model.contact import ContactOptions, FrictionState, MeshContact, MeshState
from ..model.friction import MATH_OPS, NUMPY_OPS
from ..model.gear import WormGear
from ..model.stickslip import StartFrictionState

__all__ = ['RigidBodyWormGearConnector', 'CreateRigidBodyWormGear', 'MeshGeometry', 'RIGID_CONNECTORS_KEY',
           'PERPENDICULAR_TOLERANCE', 'CENTRE_DISTANCE_TOLERANCE', 'LINEAR_ROWS_TOLERANCE']

#: ``mbs.variables`` key of the list of rigid-body worm meshes built in a system
RIGID_CONNECTORS_KEY = 'exudynWorm.rigidConnectors'
#: largest angle in rad between the axes' cross angle and 90 degrees (0.1 degree)
PERPENDICULAR_TOLERANCE = math.radians(0.1)
#: largest relative difference between the axes' distance and r1 + r2
CENTRE_DISTANCE_TOLERANCE = 0.01
#: largest rotation in rad of a body about its axis between two moves of its reference angle
_SPIN_STEP = 0.2


def _Unit(where: str, name: str, value) -> np.ndarray:
    try:
        v = np.asarray(value, dtype=float).ravel()
    except (TypeError, ValueError):
        raise TypeError(f"{where}: '{name}' must be a 3D vector (body coordinates), got {value!r}") from None
    if v.shape != (3,) or not np.all(np.isfinite(v)) or np.linalg.norm(v) == 0:
        raise ValueError(f"{where}: '{name}' must be a finite, non-zero 3D vector in body coordinates, got {value!r}")
    return v / np.linalg.norm(v)


@dataclass(frozen=True)
class MeshGeometry:
    """The mesh frame of a rigid-body worm mesh (global, from the reference configuration), SI units.

    Attributes
    ----------
    wormAxis, wheelAxis, centreLine, tangent : ndarray
        Unit vectors ``e_a``, ``e_b``, ``e_c`` (worm axis to wheel axis) and ``t = e_a x e_c``.
    hand : float
        ``t . e_b``: +1 or -1 (the thread's hand in the axes' directions as given).
    wormAxisPoint, wheelAxisPoint, meshPoint : ndarray
        The axes' feet of the common perpendicular and the pitch point ``wormAxisPoint + r1 e_c``.
    centreDistance : float
        Distance of the axes in m (= r1 + r2 within :data:`CENTRE_DISTANCE_TOLERANCE`).
    """
    wormAxis: np.ndarray
    wheelAxis: np.ndarray
    centreLine: np.ndarray
    tangent: np.ndarray
    hand: float
    wormAxisPoint: np.ndarray
    wheelAxisPoint: np.ndarray
    meshPoint: np.ndarray
    centreDistance: float

    @property
    def rightHanded(self) -> bool:
        """Whether the worm's thread is right-handed. A positive worm rotation moves the wheel's tooth at the pitch
        point along ``h e_a`` (the wheel's positive rotation there). A right-handed thread turned positively about
        its axis (held axially) moves its thread past a fixed point backwards along the axis, so the tooth in it
        along ``-e_a``: right-handed if ``h = -1``, left-handed if ``h = +1``."""
        return self.hand < 0.


@dataclass
class _Body:
    """What the law needs of one body: its node, the node type's kinematics and the body-fixed mesh data."""
    node: Any
    kinematics: Any
    size: int                      # ODE2 coordinates of the node
    referencePosition: np.ndarray
    referenceRotation: np.ndarray  # reference values of the rotation coordinates
    axis: np.ndarray               # rotation axis in body coordinates
    axisPoint: np.ndarray          # point on the axis in the mesh plane, body coordinates (from the node)
    radial: np.ndarray             # body-fixed vector along e_c in the reference configuration
    spinTangent: np.ndarray        # global axis x e_c: where the radial vector turns for a positive rotation


def _Cross(a, b) -> list:
    """a x b of two 3-lists (scalars or arrays of samples)."""
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _Dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _TransposeTimes(R, v) -> list:
    """R^T v for a 3x3 nested list R and a 3-list v."""
    return [R[0][j] * v[0] + R[1][j] * v[1] + R[2][j] * v[2] for j in range(3)]


class _Term:
    """A scalar function of both nodes' coordinates, with its gradient per body: the coefficients (3-lists) of the
    body's translational velocity and of its local angular velocity (None: zero). Entries are floats (one state)
    or arrays (many samples)."""

    def __init__(self, value, gradients):
        self.value, self.gradients = value, gradients

    def Combine(self, c: float, other: '_Term', d: float = 1.) -> '_Term':
        """d * self + c * other."""
        def Mix(a, b):
            if a is None:
                return None if b is None else [c * y for y in b]
            if b is None:
                return [d * x for x in a]
            return [d * x + c * y for x, y in zip(a, b)]
        return _Term(d * self.value + c * other.value,
                     [tuple(Mix(a, b) for a, b in zip(g, h)) for g, h in zip(self.gradients, other.gradients)])

    def Shift(self, c: float) -> '_Term':
        """self - c."""
        return _Term(self.value - c, self.gradients)


class _Kinematics:
    """The four mesh coordinates (law inputs) as functions of both nodes' coordinates (docstring of the module).

    Works on one state (coordinates as floats) or on many (each coordinate an array of samples)."""

    def __init__(self, gear: WormGear, geometry: MeshGeometry, bodies: Sequence[_Body]):
        self.gear, self.geometry, self.bodies = gear, geometry, list(bodies)
        self.size = sum(b.size for b in bodies)
        g = geometry
        self._const = {name: tuple(float(x) for x in getattr(g, name))
                       for name in ('tangent', 'wormAxis', 'centreLine')}
        self._local = [{name: tuple(float(x) for x in getattr(b, name)) for name in ('axis', 'axisPoint', 'radial',
                                                                                    'spinTangent')} for b in bodies]
        self._onAxis = [not np.any(b.axisPoint) for b in bodies]
        self._references = [([float(x) for x in b.referencePosition], [float(x) for x in b.referenceRotation])
                            for b in bodies]
        D0 = g.wheelAxisPoint - g.wormAxisPoint
        self._D0 = {name: float(D0 @ getattr(g, name)) for name in ('tangent', 'wormAxis', 'centreLine')}

    def Frames(self, q):
        """(position, R, G) of each body (3-list, nested lists) from the coordinates q (without references)."""
        frames, start = [], 0
        ops = MATH_OPS if np.ndim(q[0]) == 0 else NUMPY_OPS
        for b, (refPos, refRot) in zip(self.bodies, self._references):
            qk = q[start:start + b.size]
            start += b.size
            pos = [qk[i] + refPos[i] for i in range(3)]
            theta = [qk[3 + i] + refRot[i] for i in range(b.kinematics.rotationCoordinates)]
            R = b.kinematics.rotationMatrix(theta, ops)
            G = None if b.kinematics.velocityMap is None else b.kinematics.velocityMap(theta, ops)
            frames.append((pos, R, G))
        return frames

    def SpinComponents(self, frames, k: int):
        """Components (x, y) of body k's radial vector along e_c and along axis x e_c (its angle: atan2(y, x))."""
        local = self._local[k]
        R = frames[k][1]
        Rc = [_Dot(R[i], local['radial']) for i in range(3)]
        return _Dot(self._const['centreLine'], Rc), _Dot(local['spinTangent'], Rc)

    def Evaluate(self, q, spins):
        """Mesh coordinates ``[phi1, phi2, xA, C]`` as :class:`_Term`, and the frames; ``spins`` = [(phiRef, cos,
        sin)] per body."""
        frames = self.Frames(q)
        const = self._const

        def Only(k, p, w):
            return [(p, w), (None, None)] if k == 0 else [(None, None), (p, w)]

        def PointDot(k, v):                      # (x_k + R_k b_k) . v
            pos, R, _ = frames[k]
            if self._onAxis[k]:
                return _Term(_Dot(v, pos), Only(k, v, None))
            RTv = _TransposeTimes(R, v)
            b = self._local[k]['axisPoint']
            return _Term(_Dot(v, pos) + _Dot(RTv, b), Only(k, v, _Cross(b, RTv)))

        def AxisDot(k, u, local):                # u . R_k local
            RTu = _TransposeTimes(frames[k][1], u)
            return _Term(_Dot(RTu, local), Only(k, None, _Cross(local, RTu)))

        def Spin(k):
            local = self._local[k]
            x, y = AxisDot(k, const['centreLine'], local['radial']), AxisDot(k, local['spinTangent'], local['radial'])
            ref, c, s = spins[k]
            value = ref + (math.atan if np.ndim(x.value) == 0 else np.arctan)((y.value * c - x.value * s) / (x.value * c + y.value * s))
            norm = 1. / (x.value * x.value + y.value * y.value)
            w = [(x.value * wy - y.value * wx) * norm for wx, wy in zip(x.gradients[k][1], y.gradients[k][1])]
            return _Term(value, Only(k, None, w))

        def Relative(name):                       # (P2 - P1) . v - D0 . v
            v = const[name]
            return PointDot(1, v).Combine(-1., PointDot(0, v)).Shift(self._D0[name])

        r1, r2, h = self.gear.r1, self.gear.r2, self.geometry.hand
        wormTilt = AxisDot(0, const['centreLine'], self._local[0]['axis'])
        wheelTilt = AxisDot(1, const['centreLine'], self._local[1]['axis'])
        # phi1 + (T - r1 phi1) / r1 with T - r1 phi1 = -dD.t - h r2 (e_c . b')
        phi1 = Spin(0).Combine(-1. / r1, Relative('tangent')).Combine(-h * r2 / r1, wheelTilt)
        xA = Relative('wormAxis').Combine(-h * r1, wormTilt, -h)
        approach = Relative('centreLine')
        approach = _Term(-approach.value, [tuple(None if a is None else [-x for x in a] for a in gr)
                                           for gr in approach.gradients])
        return [phi1, Spin(1), xA, approach], frames

    def Rows(self, terms, frames):
        """The gradients of ``terms`` over both nodes' velocity coordinates: array (terms, coordinates[, samples])."""
        rows = []
        for term in terms:
            row = []
            for b, (p, w), (pos, R, G) in zip(self.bodies, term.gradients, frames):
                n = b.kinematics.rotationCoordinates
                row.extend([0.] * 3 if p is None else p)
                if w is None:
                    row.extend([0.] * n)
                elif G is None:
                    row.extend(w)
                else:
                    row.extend(G[0][j] * w[0] + G[1][j] * w[1] + G[2][j] * w[2] for j in range(n))
            rows.append(row)
        shape = np.shape(terms[0].value)
        if shape == ():
            return np.array(rows, dtype=float)
        return np.array([[np.broadcast_to(np.asarray(x, dtype=float), shape) for x in row] for row in rows])


class _SpinReference:
    """The reference angles about which the law measures the bodies' rotations (module docstring).

    Registered with the system's post-Newton function (shared with the stick/slip states of
    :mod:`.connector`); it moves the references to the bodies' angles before they have turned :data:`_SPIN_STEP`.
    """

    def __init__(self, kinematics: _Kinematics, nodes, angles: Sequence[float]):
        self.kinematics, self.nodes = kinematics, list(nodes)
        self.angles = [float(a) for a in angles]
        self.clock = None       # the system's post-Newton clock (set by _AddStickSlip)
        self._next, self._last, self._indices, self._data = -np.inf, None, None, None

    def LawSpins(self):
        """[(angle, cos, sin)] of both references."""
        return [(a, math.cos(a), math.sin(a)) for a in self.angles]

    def Angles(self, q) -> List[float]:
        """The bodies' angles (rad) at the nodes' coordinates q, continued from the references."""
        frames = self.kinematics.Frames(q)
        out = []
        for k, a in enumerate(self.angles):
            x, y = (float(v) for v in self.kinematics.SpinComponents(frames, k))
            c, s = math.cos(a), math.sin(a)
            out.append(a + math.atan2(y * c - x * s, x * c + y * s))
        return out

    def NodeCoordinates(self, mbs, vector) -> List[float]:
        """Both nodes' entries of a whole-system ODE2 vector (indices looked up once per solve)."""
        if self._indices is None:
            self._indices = [int(mbs.GetNodeODE2Index(n)) for n in self.nodes]
        out = []
        for start, b in zip(self._indices, self.kinematics.bodies):
            out.extend(float(x) for x in vector[start:start + b.size])
        return out

    def Restart(self, mbs, coordinates, initialAngles: Sequence[float]) -> None:
        """Move the references to the bodies' angles at the whole-system ODE2 ``coordinates`` (without the
        reference values), followed from ``initialAngles`` (those of the initial state, within a quarter turn of
        them): a new solve from a start near the initial state, after a solve that ended turns away."""
        self.angles = [float(a) for a in initialAngles]
        self._indices = None
        self.angles = self.Angles(self.NodeCoordinates(mbs, coordinates))
        self._next, self._last = -np.inf, None

    def NextCheck(self) -> float:
        """Time in s at which the references must be moved again."""
        return self._next

    def PostNewton(self, mbs, t: float) -> float:
        """Move the references to the bodies' present angles; schedule the next move; no discontinuity (0)."""
        if self._data is None:
            self._data = mbs.systemData
        angles = self.Angles(self.NodeCoordinates(mbs, self._data.GetODE2Coordinates()))
        last, self._last = self._last, (t, angles)
        self.angles = angles
        if last is None or t <= last[0]:
            self._next = -np.inf                    # next step: the speed is not known yet
            return 0.
        speed = max(abs(a - b) for a, b in zip(angles, last[1])) / (t - last[0])
        self._next = t + (min(_SPIN_STEP / speed, 0.005) if speed > 0 else 0.005)
        return 0.


class _RigidStickSlip(_StickSlip):
    """The stick/slip state of a rigid-body mesh: the connector's machinery with the law's inputs computed from the
    two rigid-body nodes (worm angle, wheel angle, axial displacement, radial approach, and their rates)."""

    def __init__(self, connector: 'RigidBodyWormGearConnector', initial: FrictionState):
        self._connector = connector
        nodes = connector.nodeNumbers if connector.compiled is None else connector.compiled['nodes']
        super().__init__(connector.gear, connector.options, nodes, [0., 0.], initial, False)

    def UseCompiledInputs(self, nodes) -> None:
        """Read the law's inputs from the compiled law's auxiliary nodes (worm's 3, wheel's 4): they are its
        coordinates, so no turn of the bodies needs to be followed."""
        self.nodes, self._indices, self._q = list(nodes), None, None

    def _LawInputs(self, q, v):
        if self._connector.compiled is not None:        # the auxiliary coordinates: worm's parts, wheel's parts
            i, k = self._indices
            return ([q[i] + q[k], q[k + 3], q[i + 1] + q[k + 1], q[i + 2] + q[k + 2]],
                    [v[i] + v[k], v[k + 3], v[i + 1] + v[k + 1], v[i + 2] + v[k + 2]])
        x, w, _ = self._connector._Inputs(self._Slice(q), self._Slice(v))
        return [float(a) for a in x], [float(a) for a in w]

    def _Slice(self, vector) -> List[float]:
        return np.concatenate([np.asarray(vector[start:start + b.size], dtype=float)
                               for start, b in zip(self._indices, self._connector._kinematics.bodies)]).tolist()

    def _WormSpeed(self, data, v) -> float:
        if self._connector.compiled is not None:
            i, k = self._indices
            return v[i] + v[k]
        return self._LawInputs(data.GetODE2Coordinates(), v)[1][0]

    def _WormAcceleration(self, data) -> float:
        if self._connector.compiled is not None:
            i, k = self._indices
            a = data.GetODE2Coordinates_tt()
            return float(a[i] + a[k])
        _, rate, _ = self._connector._Inputs(self._Slice(data.GetODE2Coordinates()),
                                             self._Slice(data.GetODE2Coordinates_tt()))   # the row times q_tt
        return float(rate[0])

    def _Forces(self, x, w):
        mesh = _Law(self.gear, self.options, x, w, MATH_OPS, self.state)
        return mesh.frictionForce, mesh.normalForce


def _Law(gear, options, x, w, ops, frictionState, forceMap=None) -> MeshState:
    """The contact law at the four mesh inputs ``x`` = (worm angle, wheel angle, axial, radial) and rates ``w``
    (``forceMap``: the generalized forces, :func:`~exudyn_worm.model.contact.MeshContact`)."""
    return MeshContact(gear, x[0], x[1], w[0], w[1], options, ops, axialDisplacement=x[2], axialSpeed=w[2],
                       frictionState=frictionState, radialApproach=x[3], radialSpeed=w[3], forceMap=forceMap)


#: the compiled law's generalized forces on its 7 auxiliary coordinates (:func:`_CompileLaw`) from [worm torque,
#: wheel torque, axial force, radial force]: the worm's and the wheel's parts of the worm angle, the axial
#: displacement and the radial approach, then the wheel angle
_COMPILED_FORCE_MAP = ((1., 0., 0., 0.), (0., 0., 1., 0.), (0., 0., 0., 1.),
                       (1., 0., 0., 0.), (0., 0., 1., 0.), (0., 0., 0., 1.), (0., 1., 0., 0.))


@dataclass
class RigidBodyWormGearConnector:
    """What :func:`CreateRigidBodyWormGear` created, and the law to post-process its results.

    Use :meth:`AddSensors` before ``mbs.Assemble()``, then :meth:`StoredMeshState` or :meth:`StoredMeshForces`
    after the solve.

    Attributes
    ----------
    objectNumber : exudyn.ObjectIndex
        The ``ObjectGenericODE2`` on both bodies' nodes that carries the mesh law.
    bodyNumbers, nodeNumbers : list
        Worm and wheel bodies and their nodes.
    gear : WormGear
        Mesh geometry, stiffness, damping, backlash and friction.
    options : ContactOptions
        The contact options the law was built with.
    geometry : MeshGeometry
        The mesh frame (global, reference configuration).
    name : str
        Name of the Exudyn object.
    referenceAngles : list of float
        Angles in rad added to the law's worm and wheel angles (the tooth position at the reference configuration).
    sensors : dict
        Sensors added by :meth:`AddSensors`, by name.
    stickSlip : object or None
        The stick/slip state of the sticking friction model; None with the regularized model or a fixed S.
    userFunction : callable or None
        The user function given to Exudyn (kept alive here).
    compiled : dict or None
        With ``useSymbolic``: the auxiliary nodes (``nodes``), their ties (``ties``) and the law's object
        (``objectNumber``); ``objectNumber`` above then carries no force. None: the plain-Python law.
    """
    objectNumber: Any
    bodyNumbers: List[Any]
    nodeNumbers: List[Any]
    gear: WormGear
    options: ContactOptions
    geometry: MeshGeometry
    name: str = ''
    referenceAngles: List[float] = field(default_factory=lambda: [0., 0.])
    sensors: Dict[str, Any] = field(default_factory=dict)
    stickSlip: Any = field(default=None, repr=False)
    userFunction: Any = field(default=None, repr=False)
    compiled: Optional[Dict[str, Any]] = field(default=None, repr=False)
    _kinematics: Any = field(default=None, repr=False)
    _spin: Any = field(default=None, repr=False)
    _initialAngles: List[float] = field(default_factory=lambda: [0., 0.], repr=False)

    @property
    def coordinates(self) -> int:
        """Number of ODE2 coordinates of the two nodes (the size of the law's q)."""
        return self._kinematics.size

    def _Inputs(self, q, v, spins=None):
        """Law inputs x (4), their rates w and the rows (4 x coordinates) at node coordinates q and velocities v (one
        state, or coordinates x samples)."""
        terms, frames = self._kinematics.Evaluate(q, self._spin.LawSpins() if spins is None else spins)
        rows = self._kinematics.Rows(terms, frames)
        x = [tm.value for tm in terms]
        # referenceAngles shift the law's worm and wheel angles (the tooth position), as the one-angle connector's
        # node references do; the spin references follow the bodies' measured rotations only
        for k, offset in enumerate(self.referenceAngles):
            if offset != 0.:
                x[k] = x[k] + offset
        return x, np.einsum('yj...,j...->y...', rows, np.asarray(v, dtype=float)), rows

    def _ForceLaw(self, options: ContactOptions):
        """The generalized forces on both nodes as ``law(t, q, q_t, ops)`` (plain Python)."""
        stickSlip = self.stickSlip if options.hasStickState else None

        def RigidBodyWormGearLaw(t, q, q_t, ops):
            """Generalized forces of the mesh on the worm's and the wheel's node coordinates."""
            x, w, rows = self._Inputs([float(a) for a in q], q_t)
            mesh = _Law(self.gear, options, [float(a) for a in x], [float(a) for a in w], MATH_OPS,
                        None if stickSlip is None else stickSlip.state)
            f = np.array([mesh.wormTorque, mesh.wheelTorque, mesh.axialForce, mesh.radialForce], dtype=float)
            return (f @ rows).tolist()
        return RigidBodyWormGearLaw

    def RestartAngles(self, mbs, coordinates) -> None:
        """Measure the turns of a new solve from the whole-system ODE2 ``coordinates`` (without the reference
        values; within a quarter turn of the initial state), not from where the previous solve ended (the orbit
        functions' flow, :class:`~exudyn_worm.analysis.orbits.exudynflow.ExudynFlow`).

        Parameters
        ----------
        mbs : exudyn.MainSystem
            The system the connector belongs to.
        coordinates : array_like
            The start's ODE2 coordinates.
        """
        self._spin.Restart(mbs, coordinates, self._initialAngles)

    def SetContactOptions(self, mbs, options: ContactOptions) -> None:
        """Replace the contact options (e.g. hold S for a linearization); re-records the law.

        Parameters
        ----------
        mbs : exudyn.MainSystem
            The system the connector belongs to.
        options : ContactOptions
            The new options.
        """
        _SwitchContactOptions('RigidBodyWormGearConnector', mbs, self, options,
                              lambda: _RigidStickSlip(self, self._StartState(mbs)))
        if self.compiled is not None:
            _RecordCompiledLaw(mbs, self, options)
            return
        self.userFunction = SetGenericForceLaw(mbs, self.objectNumber, self.coordinates, self._ForceLaw(options),
                                               useSymbolic=False)

    def _InitialVectors(self, mbs):
        q, v = [], []
        for node in self.nodeNumbers:
            info = mbs.GetNode(node)
            q.extend(float(x) for x in np.ravel(info['initialCoordinates']))
            v.extend(float(x) for x in np.ravel(info['initialVelocities']))
        return q, v

    def _StartState(self, mbs) -> FrictionState:
        q, v = self._InitialVectors(mbs)
        x, w, _ = self._Inputs(q, v)
        return StartFrictionState(self.gear, float(x[0]), float(x[1]), float(w[0]))

    def InitialMeshState(self, mbs) -> MeshState:
        """Mesh quantities at the system's initial state (the nodes' initial coordinates and velocities).

        Parameters
        ----------
        mbs : exudyn.MainSystem
            The system the connector belongs to.
        """
        q, v = self._InitialVectors(mbs)
        spins = [(a, math.cos(a), math.sin(a)) for a in self._initialAngles]
        x, w, _ = self._Inputs(q, v, spins)
        x, w = [float(a) for a in x], [float(a) for a in w]
        state = None if self.stickSlip is None or not self.options.hasStickState else self.stickSlip.history[0][1]
        return _Law(self.gear, self.options, x, w, MATH_OPS, state)

    def Evaluate(self, q, v, time=None) -> MeshState:
        """Mesh quantities for arrays of node states.

        Parameters
        ----------
        q, v : array_like
            Coordinates (without the reference values) and velocities of both nodes, one row per sample
            (worm node's coordinates first), samples in the order of a simulation (the bodies' angles are followed
            from the first sample, which must be the initial state or within a quarter turn of it).
        time : array_like, optional
            Times in s of the samples: with the sticking friction model the stick/slip states recorded during the
            solve are used (None: the exact Coulomb law).

        Returns
        -------
        MeshState
        """
        q, v = np.atleast_2d(np.asarray(q, dtype=float)), np.atleast_2d(np.asarray(v, dtype=float))
        frames = self._kinematics.Frames(q.T)
        angles = []
        for k, a0 in enumerate(self._initialAngles):
            x, y = self._kinematics.SpinComponents(frames, k)
            raw = np.unwrap(np.arctan2(y, x))
            angles.append(raw + (a0 - raw[0]))
        x, w, _ = self._Inputs(q.T, v.T, [(a, np.cos(a), np.sin(a)) for a in angles])
        state = None
        if time is not None and self.stickSlip is not None and self.options.hasStickState:
            state = self.stickSlip.StatesAt(np.asarray(time, dtype=float))
        return _Law(self.gear, self.options, x, w, NUMPY_OPS, state)

    def AddSensors(self, mbs) -> Dict[str, Any]:
        """Add internally stored sensors of both nodes' coordinates and velocities (nothing written to files).

        Parameters
        ----------
        mbs : exudyn.MainSystem
            The system, before ``mbs.Assemble()``.

        Returns
        -------
        dict
            Sensor numbers ``wormCoordinates``, ``wormVelocities``, ``wheelCoordinates``, ``wheelVelocities``.
        """
        import exudyn as exu
        from exudyn.itemInterface import SensorNode
        OVT = exu.OutputVariableType
        for body, node in zip(('worm', 'wheel'), self.nodeNumbers):
            for key, ovt in (('Coordinates', OVT.Coordinates), ('Velocities', OVT.Coordinates_t)):
                self.sensors[body + key] = mbs.AddSensor(SensorNode(nodeNumber=node, outputVariableType=ovt,
                                                                    storeInternal=True, writeToFile=False))
        return self.sensors

    def _Stored(self, mbs):
        where = f"RigidBodyWormGearConnector '{self.name}'" if self.name else 'RigidBodyWormGearConnector'
        CheckSystem(f"{where}.StoredMeshState", mbs)
        if not self.sensors:
            raise ValueError(f"{where}: call AddSensors(mbs) before mbs.Assemble()")
        data = {k: np.asarray(mbs.GetSensorStoredData(s)) for k, s in self.sensors.items()}
        if any(d.ndim != 2 or d.shape[0] == 0 for d in data.values()):
            raise ValueError(f"{where}: no stored sensor data: solve the system first (mbs.SolveDynamic(...) after "
                             f"mbs.Assemble()), then read the stored states")
        time = data['wormCoordinates'][:, 0]
        q = np.hstack([data['wormCoordinates'][:, 1:], data['wheelCoordinates'][:, 1:]])
        v = np.hstack([data['wormVelocities'][:, 1:], data['wheelVelocities'][:, 1:]])
        return time, q, v

    def StoredMeshState(self, mbs) -> MeshState:
        """Mesh quantities over the stored time steps (requires :meth:`AddSensors`), with their ``time`` in s.

        Parameters
        ----------
        mbs : exudyn.MainSystem
            The system, after a solve.

        Returns
        -------
        MeshState
            ``phi1``-like inputs are those of the law: ``deltaPhi``, ``deltaS``, the signed ``normalForce``, ``S``,
            ``sf``, torques, ``axialForce`` and ``radialForce``.

        Raises
        ------
        ValueError
            If :meth:`AddSensors` was not called or the system was not solved.
        """
        time, q, v = self._Stored(mbs)
        state = self.Evaluate(q, v, time)
        state.time = time
        return state

    def StoredMeshForces(self, mbs) -> Dict[str, np.ndarray]:
        """Per time step: the normal force on each flank, S, sf and the mesh force on each body in its own terms.

        Parameters
        ----------
        mbs : exudyn.MainSystem
            The system, after a solve (requires :meth:`AddSensors`).

        Returns
        -------
        dict of ndarray
            ``time`` (s), ``normalForceFlank1``, ``normalForceFlank2`` (N, >= 0), ``S``, ``sf`` and
            :func:`MeshForceComponents` of the stored states.
        """
        state = self.StoredMeshState(mbs)
        out = {'time': state.time}
        out['normalForceFlank1'], out['normalForceFlank2'] = state.normalForceFlanks
        out['S'], out['sf'] = np.asarray(state.S, dtype=float), np.asarray(state.sf, dtype=float)
        out.update(MeshForceComponents(self, state))
        return out


def MeshForceComponents(connector: RigidBodyWormGearConnector, state: MeshState) -> Dict[str, Any]:
    """The mesh force on each body in its own directions at the pitch point, from a mesh state, in N.

    Worm: ``wormTangential`` along the worm's positive rotation at the pitch point (``t``), ``wormAxial`` along
    ``wormAxis``, ``wormRadial`` outwards from the worm axis (``e_c``). Wheel: ``wheelTangential`` along its
    positive rotation (``h e_a``), ``wheelAxial`` along ``wheelAxis``, ``wheelRadial`` outwards from the wheel
    axis (``-e_c``). Also ``wormForce`` and ``wheelForce``: the global force vectors (samples x 3; the wheel's is
    the opposite of the worm's).

    Parameters
    ----------
    connector : RigidBodyWormGearConnector
        The mesh (radii and mesh frame).
    state : MeshState
        Law results, e.g. :meth:`RigidBodyWormGearConnector.StoredMeshState`.

    Returns
    -------
    dict
        The components (floats or arrays).
    """
    g, gear = connector.geometry, connector.gear
    tangential = np.asarray(state.wormTorque, dtype=float) / gear.r1           # on the worm, along t
    thrust = np.asarray(state.axialForce, dtype=float)                         # on the worm, along h e_a
    radial = np.asarray(state.radialForce, dtype=float)                        # on the worm, along e_c
    worm = (np.multiply.outer(tangential, g.tangent) + np.multiply.outer(thrust * g.hand, g.wormAxis)
            + np.multiply.outer(radial, g.centreLine))
    return {'wormTangential': tangential, 'wormAxial': g.hand * thrust, 'wormRadial': radial,
            'wheelTangential': -thrust, 'wheelAxial': -(worm @ g.wheelAxis), 'wheelRadial': radial,
            'wormForce': worm, 'wheelForce': -worm}


def _BodyOf(mbs, where: str, name: str, body):
    """(body number, object dict, node number, node dict) of a rigid body given by number or CreateRigidBody dict."""
    if isinstance(body, dict):
        body = body.get('bodyNumber', body.get('objectNumber'))
    if isinstance(body, (str, float, bool)) or body is None:
        raise TypeError(f"{where}: '{name}' must be a body number (mbs.CreateRigidBody) or its returnDict, "
                        f"got {type(body).__name__} {body!r}")
    try:
        info = mbs.GetObject(body)
    except Exception as err:      # exudyn raises its own error type for an invalid index
        raise ValueError(f"{where}: '{name}' is not an object of this system: {body!r} ({err})") from None
    if info.get('objectType') != 'RigidBody':
        raise ValueError(f"{where}: '{name}' must be a 3D rigid body (ObjectRigidBody, e.g. from mbs.CreateRigidBody), "
                         f"got object type '{info.get('objectType')}'")
    node = info['nodeNumber']
    nodeInfo = mbs.GetNode(node)
    if nodeInfo.get('nodeType') not in RIGID_NODES:
        raise ValueError(f"{where}: '{name}' has a node of type '{nodeInfo.get('nodeType')}'; supported are "
                         f"{', '.join(sorted(RIGID_NODES))} (mbs.CreateRigidBody's nodeType)")
    return body, info, node, nodeInfo


def _BodiesOfMarkers(mbs, where: str, markerNumbers):
    """Bodies and local points of [worm, wheel] markers (MarkerBodyRigid or MarkerBodyPosition)."""
    if isinstance(markerNumbers, (str, bytes, dict)) or not hasattr(markerNumbers, '__len__') or len(markerNumbers) != 2:
        raise ValueError(f"{where}: 'markerNumbers' must be [worm, wheel], two body markers, got {markerNumbers!r}")
    bodies, points = [], []
    for k, m in enumerate(markerNumbers):
        try:
            info = mbs.GetMarker(m)
        except Exception as err:      # exudyn raises its own error type for an invalid index
            raise ValueError(f"{where}: 'markerNumbers[{k}]' is not a marker of this system: {m!r} ({err})") from None
        if info.get('markerType') not in ('BodyRigid', 'BodyPosition'):
            raise ValueError(f"{where}: 'markerNumbers[{k}]' must be a MarkerBodyRigid or MarkerBodyPosition, got "
                             f"marker type '{info.get('markerType')}'")
        bodies.append(info['bodyNumber'])
        points.append(np.asarray(info.get('localPosition', [0., 0., 0.]), dtype=float))
    return bodies, points


def _CheckMass(where: str, name: str, info, axis: np.ndarray) -> None:
    mass = float(info.get('mass', info.get('physicsMass', 0.)))
    if not mass > 0:
        raise ValueError(f"{where}: '{name}' has no mass (mass = {mass!r} kg): give the body its mass and "
                         f"inertia (e.g. mbs.CreateRigidBody(inertia=InertiaCylinder(...)))")
    Jxx, Jyy, Jzz, Jyz, Jxz, Jxy = (float(x) for x in info.get('inertia', info.get('physicsInertia', [0.] * 6)))
    J = np.array([[Jxx, Jxy, Jxz], [Jxy, Jyy, Jyz], [Jxz, Jyz, Jzz]])
    if not float(axis @ J @ axis) > 0:
        raise ValueError(f"{where}: '{name}' has no moment of inertia about its axis ({float(axis @ J @ axis)!r} "
                         f"kg*m^2): give the body its inertia")


def _Rotation(body: _Body, theta) -> np.ndarray:
    return np.array(body.kinematics.rotationMatrix([float(x) for x in theta], MATH_OPS), dtype=float)


def _MeshFrame(w: str, gear: WormGear, nodes, nodeInfos, axes, linePoints):
    """The mesh frame (:class:`MeshGeometry`, checked), the law inputs' kinematics (:class:`_Kinematics`) and the
    bodies' initial angles about their axes, from the nodes' dictionaries (``mbs.GetNode``: node type, reference
    and initial coordinates), the axes and the axis points in body coordinates; errors name ``w``."""
    bodies, references, initial = [], [], []
    for node, nodeInfo, axis in zip(nodes, nodeInfos, axes):
        ref = np.asarray(nodeInfo['referenceCoordinates'], dtype=float)
        kin = RIGID_NODES[nodeInfo['nodeType']]
        b = _Body(node, kin, len(ref), ref[:3], ref[3:], axis, np.zeros(3), np.zeros(3), np.zeros(3))
        bodies.append(b)
        references.append((ref[:3], _Rotation(b, ref[3:])))
        initial.append(ref + np.asarray(nodeInfo['initialCoordinates'], dtype=float))
    (x1, R1), (x2, R2) = references
    p1, p2 = x1 + R1 @ linePoints[0], x2 + R2 @ linePoints[1]
    ea, eb = R1 @ axes[0], R2 @ axes[1]
    cross = math.degrees(math.acos(max(-1., min(1., abs(float(ea @ eb))))))
    if abs(float(ea @ eb)) > math.sin(PERPENDICULAR_TOLERANCE):
        raise ValueError(f"{w}: the worm axis and the wheel axis must cross at 90 deg (within "
                         f"{math.degrees(PERPENDICULAR_TOLERANCE):g} deg), got {cross:.4g} deg (global worm axis "
                         f"{np.round(ea, 6).tolist()}, wheel axis {np.round(eb, 6).tolist()})")
    d = p2 - p1
    F1, F2 = p1 + (d @ ea) * ea, p2 - (d @ eb) * eb
    D0 = F2 - F1
    a, target = float(np.linalg.norm(D0)), gear.r1 + gear.r2
    if abs(a - target) > CENTRE_DISTANCE_TOLERANCE * target:
        raise ValueError(f"{w}: the axes are {a:.6g} m apart in the reference configuration, but the gear's centre "
                         f"distance r1 + r2 is {target:.6g} m (more than {CENTRE_DISTANCE_TOLERANCE:.0%} off: positions "
                         f"and radii in m?)")
    for role, offset in (('worm', abs(float(d @ ea))), ('wheel', abs(float(d @ eb)))):
        if offset > 10. * target:
            raise ValueError(f"{w}: the pitch point is {offset:.6g} m along the {role} axis from the {role} body's "
                             f"reference point (more than ten centre distances, {10. * target:.6g} m): is the body "
                             f"placed in m?")
    ec = D0 / a
    t = np.cross(ea, ec)
    hand = 1. if float(t @ eb) > 0 else -1.
    geometry = MeshGeometry(ea, eb, ec, t, hand, F1, F2, F1 + gear.r1 * ec, a)
    for b, (x, R), F, e in zip(bodies, references, (F1, F2), (ea, eb)):
        b.axisPoint = R.T @ (F - x)
        b.radial = R.T @ ec
        b.spinTangent = np.cross(e, ec)
    kinematics = _Kinematics(gear, geometry, bodies)
    angles = []
    for b, q in zip(bodies, initial):
        R = _Rotation(b, q[3:])
        angles.append(math.atan2(float(b.spinTangent @ R @ b.radial), float(ec @ R @ b.radial)))

    return geometry, kinematics, angles


#: largest change of the law inputs' gradient rows with the bodies' turns for which :func:`CreateRigidBodyWormGear`
#: with ``useSymbolic`` takes them as linear in the node coordinates
LINEAR_ROWS_TOLERANCE = 1e-9


def _CompileLaw(mbs, where: str, connector: RigidBodyWormGearConnector, found) -> None:
    """The law in C++ on auxiliary coordinates (docs/mesh-3d.md, "Speed"): 3 tied to the worm's node (its parts of
    the worm angle, axial displacement and radial approach), 4 to the wheel's (its parts and its angle), each tie one
    linear ``ObjectConnectorCoordinateVector``; the law one symbolic ``ObjectGenericODE2`` on the 7."""
    from exudyn.itemInterface import MarkerNodeCoordinates, NodeGenericODE2, ObjectConnectorCoordinateVector, \
        ObjectGenericODE2
    types = [str(f[3]['nodeType']) for f in found]
    if any(t != 'RigidBodyRxyz' for t in types):
        raise ValueError(f"{where}: 'useSymbolic' needs Tait-Bryan (RotationRxyz) nodes turning about their last "
                         f"angle, got node types {', '.join(types)}; use useSymbolic=False (plain Python) for them")
    q0, v0 = connector._InitialVectors(mbs)
    spins = [(a, math.cos(a), math.sin(a)) for a in connector._initialAngles]
    x0, _, _ = connector._Inputs(q0, v0, spins)             # the inputs at the initial state, exact
    # the rows without tilts and translations (those of the linear map), and at other turns: they must be the same
    sizes = [b.size for b in connector._kinematics.bodies]
    untilted = np.zeros(len(q0))
    for start in (0, sizes[0]):
        untilted[start + 5] = q0[start + 5]
    _, _, rows = connector._Inputs(untilted.tolist(), v0, spins)
    rows = np.asarray(rows, dtype=float)
    turned, turns = untilted.copy(), (1., 0.3)
    for start, turn in zip((0, sizes[0]), turns):
        turned[start + 5] += turn
    _, _, rowsTurned = connector._Inputs(turned.tolist(), v0, [(a + d, math.cos(a + d), math.sin(a + d))
                                                               for a, d in zip(connector._initialAngles, turns)])
    change = float(np.max(np.abs(np.asarray(rowsTurned, dtype=float) - rows)))
    if change > LINEAR_ROWS_TOLERANCE * max(1., float(np.max(np.abs(rows)))) or np.any(rows[1, :sizes[0]]):
        raise ValueError(f"{where}: 'useSymbolic' needs Rxyz nodes whose turn about the axis is their last angle (a "
                         f"reference rotation puts the axis on the node's local z); here the law's inputs change with "
                         f"the turns (rows change by {change:.3g}); use useSymbolic=False (plain Python)")
    SU, SV = rows[[0, 2, 3], :sizes[0]], rows[[0, 2, 3, 1], sizes[0]:]
    q0, v0 = np.asarray(q0, dtype=float), np.asarray(v0, dtype=float)
    U0 = SU @ q0[:sizes[0]]
    V0 = np.asarray(x0, dtype=float)[[0, 2, 3, 1]] - np.concatenate([U0, [0.]])
    nodes, ties = [], []
    for (body, info, node, nodeInfo), S, X0, v, label in zip(found, (SU, SV), (U0, V0),
                                                             (v0[:sizes[0]], v0[sizes[0]:]), ('Worm', 'Wheel')):
        aux = mbs.AddNode(NodeGenericODE2(numberOfODE2Coordinates=len(X0), referenceCoordinates=[0.] * len(X0),
                                          initialCoordinates=list(X0), initialCoordinates_t=list(S @ v),
                                          name=f'{connector.name or "wormGear"}{label}Inputs'))
        # the tie reads S q_node - X - offset = 0 with q_node the node's coordinates including their reference values
        total = np.asarray(nodeInfo['referenceCoordinates'], dtype=float) + np.asarray(nodeInfo['initialCoordinates'],
                                                                                       dtype=float)
        ties.append(mbs.AddObject(ObjectConnectorCoordinateVector(
            markerNumbers=[mbs.AddMarker(MarkerNodeCoordinates(nodeNumber=aux)),
                           mbs.AddMarker(MarkerNodeCoordinates(nodeNumber=node))],
            scalingMarker0=np.eye(len(X0)), scalingMarker1=S, offset=list(S @ total - X0))))
        nodes.append(aux)
    zeros = np.zeros((7, 7))
    law = mbs.AddObject(ObjectGenericODE2(nodeNumbers=nodes, massMatrix=zeros, stiffnessMatrix=zeros,
                                          dampingMatrix=zeros, name=(connector.name + 'Law') if connector.name else ''))
    connector.compiled = {'nodes': nodes, 'ties': ties, 'objectNumber': law}
    if connector.stickSlip is not None:
        connector.stickSlip.UseCompiledInputs(nodes)
    _RecordCompiledLaw(mbs, connector, connector.options)


def _RecordCompiledLaw(mbs, connector: RigidBodyWormGearConnector, options: ContactOptions) -> None:
    """(Re)record the law on the 7 auxiliary coordinates as a C++ symbolic user function; the sticking model's state
    is read from named symbolic variables of the connector's stick/slip state."""
    import exudyn
    stickSlip = connector.stickSlip if options.hasStickState else None
    if stickSlip is not None and stickSlip.variables is None:
        esym = exudyn.symbolic
        stickSlip.variables = FrictionState(*(esym.Real(name, float(getattr(stickSlip.state, name)))
                                              for name in ('stuck', 'direction', 'anchor')))
    gear = connector.gear

    def CompiledLaw(t, q, q_t, ops):
        x = [q[0] + q[3], q[6], q[1] + q[4], q[2] + q[5]]
        w = [q_t[0] + q_t[3], q_t[6], q_t[1] + q_t[4], q_t[2] + q_t[5]]
        # [worm torque, axial, radial] on both nodes' parts, the wheel torque last: one vector expression
        return _Law(gear, options, x, w, ops, None if stickSlip is None else stickSlip.LawState(ops),
                    _COMPILED_FORCE_MAP).generalizedForces
    connector.userFunction = SetGenericForceLaw(mbs, connector.compiled['objectNumber'], 7, CompiledLaw,
                                                useSymbolic=True, where='CreateRigidBodyWormGear')


def CreateRigidBodyWormGear(mbs, bodyNumbers: Optional[Sequence[Any]] = None, gear: Optional[WormGear] = None,
                            wormAxis: Sequence[float] = (1., 0., 0.), wheelAxis: Sequence[float] = (0., 0., 1.),
                            name: str = '', contactOptions: ContactOptions = ContactOptions(),
                            referenceAngles: Sequence[float] = (0., 0.),
                            markerNumbers: Optional[Sequence[Any]] = None,
                            useSymbolic: bool = False) -> RigidBodyWormGearConnector:
    """Add a worm mesh between a worm body and a wheel body (3D rigid bodies on the user's joints or bearings).

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system.
    bodyNumbers : [worm, wheel]
        The two rigid bodies (``ObjectRigidBody``, e.g. from ``mbs.CreateRigidBody``, as body numbers or its
        ``returnDict``), with node type Euler parameters, Tait-Bryan angles (Rxyz) or rotation vector (Lie group).
        Their axes pass through the bodies' reference points; give ``markerNumbers`` instead for other points.
        With rotation-vector or Euler-parameter nodes use full Newton (docs/mesh-3d.md, "Node types").
    gear : WormGear
        Mesh geometry (r1, r2, alphaN, gamma), stiffness, damping, backlash and friction.
    wormAxis, wheelAxis : 3D vectors
        The rotation axes in body coordinates of the worm and of the wheel (normalized here). Their positive
        directions are the positive rotations; a positive worm rotation turns the wheel positively, and the
        thread's hand follows (:class:`MeshGeometry` ``hand``). In the reference configuration they must cross
        at 90 deg (within :data:`PERPENDICULAR_TOLERANCE`) at a distance r1 + r2 (within
        :data:`CENTRE_DISTANCE_TOLERANCE`), and the bodies' reference points must lie within ten centre
        distances of the pitch point.
    name : str
        Name of the Exudyn object.
    contactOptions : ContactOptions
        Friction model (default: sticking, with a stick/slip state), tension-free or linear law, fixed S.
    referenceAngles : (float, float)
        Angles in rad added to the law's worm and wheel angles, as :func:`~exudyn_worm.items.connector.CreateWormGear`
        adds its nodes' reference angles (default 0: no deflection of the mesh in the reference configuration;
        ``[0.01, 0]`` deflects the flank there by ``gear.normalLever * 0.01``).
    markerNumbers : [worm, wheel], optional
        Instead of ``bodyNumbers``: a ``MarkerBodyRigid`` or ``MarkerBodyPosition`` on each body, at a point of its
        rotation axis.
    useSymbolic : bool
        False (default): the law is a plain-Python user function on both nodes (every node type). True: the law runs
        in C++ (a symbolic user function) on 7 auxiliary coordinates tied to the nodes by linear constraints
        (docs/mesh-3d.md, "Speed"); needs Tait-Bryan (Rxyz) nodes whose turn about the axis is their *last* angle (a
        reference rotation can put any axis there), where the law's inputs are linear in the node coordinates to
        first order in the tilts; refused otherwise.

    Returns
    -------
    RigidBodyWormGearConnector

    Raises
    ------
    ValueError, TypeError
        For a body that is not a 3D rigid body of ``mbs`` or has no mass or inertia, axes that are not
        perpendicular, axes whose distance is not r1 + r2 (a unit slip?), a pitch point far from a body, or a bad
        gear, options or name; with ``useSymbolic``, nodes whose coordinates the law's inputs are not linear in.
    """
    w = 'CreateRigidBodyWormGear'
    CheckSystem(w, mbs)
    CheckBool(w, 'useSymbolic', useSymbolic)
    CheckName(w, 'name', name)
    if not isinstance(gear, WormGear):
        raise TypeError(f"{w}: 'gear' must be a WormGear, got {type(gear).__name__}")
    if (bodyNumbers is None) == (markerNumbers is None):
        raise ValueError(f"{w}: give either 'bodyNumbers' or 'markerNumbers' ([worm, wheel]), got "
                         f"bodyNumbers = {bodyNumbers!r}, markerNumbers = {markerNumbers!r}")
    linePoints = [np.zeros(3), np.zeros(3)]           # the axes' points in body coordinates
    if markerNumbers is not None:
        bodyNumbers, linePoints = _BodiesOfMarkers(mbs, w, markerNumbers)
    if not isinstance(contactOptions, ContactOptions):
        raise TypeError(f"{w}: 'contactOptions' must be a ContactOptions, got {type(contactOptions).__name__}")
    if isinstance(bodyNumbers, (str, bytes, dict)) or not hasattr(bodyNumbers, '__len__') or len(bodyNumbers) != 2:
        raise ValueError(f"{w}: 'bodyNumbers' must be [worm, wheel], two rigid bodies, got {bodyNumbers!r}")
    if isinstance(referenceAngles, (str, bytes, dict)) or not hasattr(referenceAngles, '__len__') \
            or len(referenceAngles) != 2:
        raise ValueError(f"{w}: 'referenceAngles' must be two angles in rad, got {referenceAngles!r}")
    offsets = [CheckReal(w, f'referenceAngles[{k}]', a, 'rad') for k, a in enumerate(referenceAngles)]
    axes = [_Unit(w, 'wormAxis', wormAxis), _Unit(w, 'wheelAxis', wheelAxis)]
    found = [_BodyOf(mbs, w, f'bodyNumbers[{k}] ({role})', b)
             for k, (role, b) in enumerate(zip(('worm', 'wheel'), bodyNumbers))]
    if int(found[0][2]) == int(found[1][2]):
        raise ValueError(f"{w}: worm and wheel must be different bodies, got {list(bodyNumbers)!r}")
    for (body, info, node, nodeInfo), axis, role in zip(found, axes, ('worm', 'wheel')):
        _CheckMass(w, f'{role} body {body}', info, axis)

    geometry, kinematics, angles = _MeshFrame(w, gear, [f[2] for f in found], [f[3] for f in found], axes,
                                              linePoints)

    from exudyn.itemInterface import ObjectGenericODE2
    nodes = [f[2] for f in found]
    connector = RigidBodyWormGearConnector(objectNumber=None, bodyNumbers=[f[0] for f in found], nodeNumbers=nodes,
                                           gear=gear, options=contactOptions, geometry=geometry, name=name,
                                           referenceAngles=offsets,
                                           _kinematics=kinematics, _spin=_SpinReference(kinematics, nodes, angles),
                                           _initialAngles=list(angles))
    if contactOptions.hasStickState:
        connector.stickSlip = _RigidStickSlip(connector, connector._StartState(mbs))
    law = connector._ForceLaw(contactOptions)
    n = kinematics.size
    CheckPlainForceLaw(w, n, law)          # before anything is added
    zeros = np.zeros((n, n))
    connector.objectNumber = mbs.AddObject(ObjectGenericODE2(nodeNumbers=nodes, massMatrix=zeros, stiffnessMatrix=zeros,
                                                             dampingMatrix=zeros, name=name))
    if useSymbolic:
        _CompileLaw(mbs, w, connector, found)
    else:
        connector.userFunction = SetGenericForceLaw(mbs, connector.objectNumber, n, law, useSymbolic=False,
                                                    check=False)
    if connector.compiled is None:     # the compiled law's inputs are coordinates: no turn to follow
        _AddStickSlip(mbs, connector._spin)
    if connector.stickSlip is not None:
        _AddStickSlip(mbs, connector.stickSlip)
    mbs.variables.setdefault(RIGID_CONNECTORS_KEY, []).append(connector)
    return connector
