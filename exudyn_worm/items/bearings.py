"""Elastic shaft bearings for rigid bodies: two radial bearings and an axial bearing, as ordinary Exudyn items.

:func:`CreateShaftBearings` holds a rigid body (a worm or a wheel shaft from ``mbs.CreateRigidBody``) on two radial
bearings, ``span`` apart and centred on the body's reference point along the shaft axis, and one axial bearing at
the reference point, each an ``ObjectConnectorRigidBodySpringDamper`` to ground (or to a housing body) whose
frame's x axis is the shaft axis: the radial bearings are springs and dampers across the axis, the axial one along
it; the body turns freely about the axis (no rotational stiffness). Their forces are Exudyn outputs
(``ForceLocal``: x along the axis) and stored by the sensors made here, so the bearing loads of a run are read from
:func:`StoredBearingLoads`.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Dict, Optional, Sequence

import numpy as np

from .._checks import CheckName, CheckNonNegative, CheckPositive, CheckSystem
from ..model.bodies import BodyInertia

__all__ = ['ShaftBearings', 'ShaftSupports', 'WORM_MASS', 'WHEEL_MASS', 'CreateShaftBearings', 'StoredBearingLoads',
           'BEARING_LOADS']

#: the largest loads of the shafts' supports that the 3D analyses report (orbits, settled runs, branch points), by
#: their key and a label: the key of each is ``'max'`` and the shaft's ``...AxialLoad`` / ``...RadialLoad`` series
BEARING_LOADS = (('maxWormAxialLoad', 'worm axial'), ('maxWormRadialLoad', 'worm radial'),
                 ('maxWheelAxialLoad', 'wheel axial'), ('maxWheelRadialLoad', 'wheel radial'))


@dataclass(frozen=True)
class ShaftBearings:
    """Stiffness and damping of a shaft's bearings (SI units).

    Parameters
    ----------
    radialStiffness : float
        Stiffness of each radial bearing in N/m (> 0), the same in every direction across the axis.
    axialStiffness : float
        Stiffness of the axial bearing in N/m (> 0).
    radialDamping, axialDamping : float
        Damping in N*s/m (>= 0) of each radial bearing and of the axial bearing.
    span : float
        Distance in m (> 0) of the two radial bearings along the axis, centred on the body's reference point.
    """
    radialStiffness: float
    axialStiffness: float
    radialDamping: float = 0.
    axialDamping: float = 0.
    span: float = 0.1

    def __post_init__(self):
        w = 'ShaftBearings'
        for name in ('radialStiffness', 'axialStiffness'):
            object.__setattr__(self, name, CheckPositive(w, name, getattr(self, name), 'N/m'))
        for name in ('radialDamping', 'axialDamping'):
            object.__setattr__(self, name, CheckNonNegative(w, name, getattr(self, name), 'N*s/m'))
        object.__setattr__(self, 'span', CheckPositive(w, 'span', self.span, 'm'))


#: default mass in kg of the worm body (a steel worm shaft of the reel changer's size; only the bearings feel it)
WORM_MASS = 5.
#: default mass in kg of the wheel body
WHEEL_MASS = 30.


@dataclass(frozen=True)
class ShaftSupports:
    """How the 3D model holds its two bodies: each shaft's bearings (None: an ideal revolute joint) and the masses.

    Parameters
    ----------
    wormBearings, wheelBearings : ShaftBearings or None
        The shafts' elastic bearings; None: the shaft turns on an ideal revolute joint (with the worm's axial
        bearing ``kA, dA, mA`` of the parameter set, the worm slides along its joint on it).
    wormMass, wheelMass : float
        Masses in kg (> 0) of the worm and the wheel body.
    wormInertia, wheelInertia : BodyInertia or None
        The body's own mass, polar and tilt inertia (:class:`~exudyn_worm.model.bodies.BodyInertia`, its mass the
        one above); a shaft on elastic bearings needs it. Its polar inertia is at most the shaft's J1 (J2): the rest
        turns with the body without tilting with it (a motor rotor, a reel on its own bearings). None: a body on an
        ideal revolute joint, which holds its tilt (docs/mesh-3d.md, "Inertia").
    """
    wormBearings: Optional[ShaftBearings]
    wheelBearings: Optional[ShaftBearings]
    wormMass: float
    wheelMass: float
    wormInertia: Optional[BodyInertia] = None
    wheelInertia: Optional[BodyInertia] = None

    def __post_init__(self):
        w = 'ShaftSupports'
        for name in ('wormBearings', 'wheelBearings'):
            value = getattr(self, name)
            if value is not None and not isinstance(value, ShaftBearings):
                raise TypeError(f"{w}: '{name}' must be a ShaftBearings or None, got {type(value).__name__}")
        for name in ('wormMass', 'wheelMass'):
            object.__setattr__(self, name, CheckPositive(w, name, getattr(self, name), 'kg'))
        for body in ('worm', 'wheel'):
            inertia, bearings = getattr(self, body + 'Inertia'), getattr(self, body + 'Bearings')
            if inertia is not None and not isinstance(inertia, BodyInertia):
                raise TypeError(f"{w}: '{body}Inertia' must be a BodyInertia or None, got {type(inertia).__name__}")
            if inertia is None and bearings is not None:
                raise ValueError(f"{w}: the {body} on elastic bearings needs its tilt inertia: give '{body}Inertia' "
                                 f"(a BodyInertia), got None")
            if inertia is not None and inertia.mass != getattr(self, body + 'Mass'):
                raise ValueError(f"{w}: '{body}Inertia' has the mass {inertia.mass:g} kg, '{body}Mass' is "
                                 f"{getattr(self, body + 'Mass'):g} kg; give one mass")


def _AxisFrame(axis: np.ndarray) -> np.ndarray:
    """A rotation matrix whose first column is ``axis`` (unit)."""
    helper = np.array([0., 0., 1.]) if abs(axis[2]) < 0.9 else np.array([1., 0., 0.])
    y = np.cross(helper, axis)
    y /= np.linalg.norm(y)
    return np.column_stack([axis, y, np.cross(axis, y)])


def CreateShaftBearings(mbs, body, axis: Sequence[float], bearings: ShaftBearings, name: str = '',
                        housing: Optional[Any] = None) -> Dict[str, Any]:
    """Hold a rigid body on two radial bearings and an axial bearing (module docstring).

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system.
    body : body number or dict
        The rigid body (``mbs.CreateRigidBody``, its number or ``returnDict``).
    axis : 3D vector
        The shaft axis in global coordinates (reference configuration).
    bearings : ShaftBearings
        Stiffness, damping and span.
    name : str
        Prefix of the connectors' and sensors' names.
    housing : body number, optional
        The body the bearings sit in (default: a new ground object at the body's reference point).

    Returns
    -------
    dict
        ``radial`` (two connectors, at -span/2 and +span/2 along the axis), ``axial`` (connector), ``sensors``
        (``ForceLocal`` of each, by the names ``radial0``, ``radial1``, ``axial``), ``axis`` (unit, global).

    Raises
    ------
    TypeError, ValueError
        For ``bearings`` that is not a :class:`ShaftBearings`, a zero axis or a bad name.
    """
    import exudyn as exu
    from exudyn.itemInterface import MarkerBodyRigid, ObjectConnectorRigidBodySpringDamper, ObjectGround, SensorObject
    w = 'CreateShaftBearings'
    CheckSystem(w, mbs)
    CheckName(w, 'name', name)
    if not isinstance(bearings, ShaftBearings):
        raise TypeError(f"{w}: 'bearings' must be a ShaftBearings, got {type(bearings).__name__}")
    axis = np.asarray(axis, dtype=float).ravel()
    if axis.shape != (3,) or not np.all(np.isfinite(axis)) or np.linalg.norm(axis) == 0:
        raise ValueError(f"{w}: 'axis' must be a finite, non-zero 3D vector (global), got {axis!r}")
    axis = axis / np.linalg.norm(axis)
    number = body['bodyNumber'] if isinstance(body, dict) else body
    node = mbs.GetNode(mbs.GetObject(number)['nodeNumber'])
    position = np.asarray(node['referenceCoordinates'][:3], dtype=float)
    A = _AxisFrame(axis)
    # the body's reference rotation, to put its markers on the same points
    R = np.asarray(mbs.GetNodeOutput(mbs.GetObject(number)['nodeNumber'], exu.OutputVariableType.RotationMatrix,
                                     configuration=exu.ConfigurationType.Reference), dtype=float).reshape(3, 3)
    if housing is None:
        housing = mbs.AddObject(ObjectGround(referencePosition=list(position)))
        housingOrigin = position
    else:
        housingOrigin = np.asarray(mbs.GetNode(mbs.GetObject(housing)['nodeNumber'])['referenceCoordinates'][:3], dtype=float)
    out = {'radial': [], 'sensors': {}, 'axis': axis}
    OVT = exu.OutputVariableType

    def Add(offset: float, stiffness, damping, key: str):
        point = position + offset * axis
        m0 = mbs.AddMarker(MarkerBodyRigid(bodyNumber=housing, localHT=exu.HT(rotation=A, translation=point - housingOrigin)))
        m1 = mbs.AddMarker(MarkerBodyRigid(bodyNumber=number, localHT=exu.HT(rotation=R.T @ A,
                                                                              translation=R.T @ (point - position))))
        o = mbs.AddObject(ObjectConnectorRigidBodySpringDamper(markerNumbers=[m0, m1], stiffness=np.diag(stiffness),
                                                               damping=np.diag(damping), name=f'{name}{key}'))
        out['sensors'][key] = mbs.AddSensor(SensorObject(objectNumber=o, outputVariableType=OVT.ForceLocal,
                                                         storeInternal=True, writeToFile=False))
        return o

    kR, dR = bearings.radialStiffness, bearings.radialDamping
    for k, offset in enumerate((-0.5 * bearings.span, 0.5 * bearings.span)):
        out['radial'].append(Add(offset, [0., kR, kR, 0., 0., 0.], [0., dR, dR, 0., 0., 0.], f'radial{k}'))
    out['axial'] = Add(0., [bearings.axialStiffness, 0., 0., 0., 0., 0.], [bearings.axialDamping, 0., 0., 0., 0., 0.],
                       'axial')
    return out


def StoredBearingLoads(mbs, bearingItems: Dict[str, Any]) -> Dict[str, np.ndarray]:
    """Bearing forces per stored time step, from the sensors of :func:`CreateShaftBearings` (after a solve).

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system, solved.
    bearingItems : dict
        What :func:`CreateShaftBearings` returned.

    Returns
    -------
    dict of ndarray
        ``time`` (s); ``axial`` (N, along the axis, the force of the spring on the body side); ``radial0``,
        ``radial1`` (N, magnitude across the axis of each radial bearing); ``radial`` (N, the magnitude of their
        vector sum).
    """
    data = {k: np.asarray(mbs.GetSensorStoredData(s)) for k, s in bearingItems['sensors'].items()}
    out = {'time': data['axial'][:, 0], 'axial': data['axial'][:, 1]}
    across = [data[f'radial{k}'][:, 2:4] for k in range(2)]
    for k in range(2):
        out[f'radial{k}'] = np.hypot(across[k][:, 0], across[k][:, 1])
    total = across[0] + across[1]
    out['radial'] = np.hypot(total[:, 0], total[:, 1])
    return out
