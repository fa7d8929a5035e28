"""Rotation kinematics of Exudyn's rigid-body nodes, written once for every arithmetic backend.

For each rotation parametrization that ``mbs.CreateRigidBody`` offers, :data:`RIGID_NODES` gives the rotation
matrix ``R(theta)`` (body to global) and the matrix ``G`` that maps the node's rotation velocity coordinates to
the local angular velocity, ``omega_local = G theta_t``; a generalized force on the rotation coordinates is
then ``G^T tau_local``. Matrices are nested lists of scalars, so the same code runs on floats and on Exudyn
symbolic expressions (recorded user functions).

- ``RigidBodyEP`` (Euler parameters p0..p3): ``G = 2 [[-p1, p0, p3, -p2], [-p2, -p3, p0, p1], [-p3, p2, -p1, p0]]``;
- ``RigidBodyRxyz`` (Tait-Bryan angles, ``R = Rx(a) Ry(b) Rz(c)``): ``G = [[cb cc, sc, 0], [-cb sc, cc, 0], [sb, 0, 1]]``;
- ``RigidBodyRotVecLG`` (rotation vector, Lie group): the velocity coordinates are ``omega_local`` (``G = I``).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Optional

__all__ = ['RigidNodeKinematics', 'RIGID_NODES']

_TINY = 1e-300      # keeps sqrt(v.v) of a zero rotation vector finite (sin(x)/x and (1-cos x)/x^2 stay exact)


@dataclass(frozen=True)
class RigidNodeKinematics:
    """Rotation matrix and velocity map of one rigid-body node type.

    Attributes
    ----------
    nodeType : str
        Exudyn's node type name (``mbs.GetNode(n)['nodeType']``).
    rotationCoordinates : int
        Number of rotation coordinates (after the 3 position coordinates).
    rotationMatrix : callable
        ``rotationMatrix(theta, ops) -> 3x3 nested list``.
    velocityMap : callable or None
        ``velocityMap(theta, ops) -> 3 x n nested list`` G with ``omega_local = G theta_t``; None: identity.
    """
    nodeType: str
    rotationCoordinates: int
    rotationMatrix: Callable[[Any, Any], List[List[Any]]]
    velocityMap: Optional[Callable[[Any, Any], List[List[Any]]]]


def _EPMatrix(p, ops):
    p0, p1, p2, p3 = p
    return [[p0 * p0 + p1 * p1 - p2 * p2 - p3 * p3, 2. * (p1 * p2 - p0 * p3), 2. * (p1 * p3 + p0 * p2)],
            [2. * (p1 * p2 + p0 * p3), p0 * p0 - p1 * p1 + p2 * p2 - p3 * p3, 2. * (p2 * p3 - p0 * p1)],
            [2. * (p1 * p3 - p0 * p2), 2. * (p2 * p3 + p0 * p1), p0 * p0 - p1 * p1 - p2 * p2 + p3 * p3]]


def _EPMap(p, ops):
    p0, p1, p2, p3 = p
    return [[-2. * p1, 2. * p0, 2. * p3, -2. * p2],
            [-2. * p2, -2. * p3, 2. * p0, 2. * p1],
            [-2. * p3, 2. * p2, -2. * p1, 2. * p0]]


def _RxyzMatrix(theta, ops):
    a, b, c = theta
    ca, sa, cb, sb, cc, sc = ops.cos(a), ops.sin(a), ops.cos(b), ops.sin(b), ops.cos(c), ops.sin(c)
    return [[cb * cc, -(cb * sc), sb],
            [ca * sc + sa * sb * cc, ca * cc - sa * sb * sc, -(sa * cb)],
            [sa * sc - ca * sb * cc, sa * cc + ca * sb * sc, ca * cb]]


def _RxyzMap(theta, ops):
    a, b, c = theta
    cb, sb, cc, sc = ops.cos(b), ops.sin(b), ops.cos(c), ops.sin(c)
    return [[cb * cc, sc, 0.], [-(cb * sc), cc, 0.], [sb, 0., 1.]]


def _RotVecMatrix(v, ops):
    x, y, z = v
    angle = (x * x + y * y + z * z + _TINY) ** 0.5
    s = ops.sin(angle) / angle
    half = ops.sin(0.5 * angle) / angle
    c = 2. * half * half                   # (1 - cos(angle)) / angle^2 without cancellation
    return [[1. - c * (y * y + z * z), c * x * y - s * z, c * x * z + s * y],
            [c * x * y + s * z, 1. - c * (x * x + z * z), c * y * z - s * x],
            [c * x * z - s * y, c * y * z + s * x, 1. - c * (x * x + y * y)]]


#: the rigid-body node types the rigid-body mesh supports, by Exudyn's node type name
RIGID_NODES: Dict[str, RigidNodeKinematics] = {
    'RigidBodyEP': RigidNodeKinematics('RigidBodyEP', 4, _EPMatrix, _EPMap),
    'RigidBodyRxyz': RigidNodeKinematics('RigidBodyRxyz', 3, _RxyzMatrix, _RxyzMap),
    'RigidBodyRotVecLG': RigidNodeKinematics('RigidBodyRotVecLG', 3, _RotVecMatrix, None),
}
