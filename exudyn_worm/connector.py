"""The worm-gear connector: one Exudyn item coupling the rotation coordinates of two nodes.

:func:`CreateWormGear` adds an ``ObjectGenericODE2`` on the worm and wheel nodes whose force user
function is the contact law of :mod:`exudyn_worm.contact`. By default the law is recorded as an
Exudyn symbolic user function and evaluated in C++; ``useSymbolic=False`` gives a plain-Python user
function for debugging (same law, same results, about 3 times slower on the reel changer;
see benchmarks/README.md).

Supported nodes: nodes with exactly one ODE2 coordinate that is a rotation angle, i.e. ``Node1D``
(with ``ObjectRotationalMass1D``) and ``NodeGenericODE2`` with one coordinate. 3D rigid-body nodes
are not supported: their rotation parameters wrap at +-pi (see docs/exudyn notes).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Sequence

import numpy as np

from ._userfunctions import AddGenericForce
from .contact import NUMPY_OPS, ContactOptions, MeshContact, MeshState
from .gear import WormGear

__all__ = ['WormGearConnector', 'CreateWormGear']


@dataclass
class WormGearConnector:
    """What :func:`CreateWormGear` created, and the law to post-process its results.

    Use :meth:`AddSensors` before ``mbs.Assemble()`` to record the worm and wheel states, then
    :meth:`StoredMeshState` after the solve for every mesh quantity over time.
    """
    objectNumber: Any
    nodeNumbers: List[Any]
    gear: WormGear
    options: ContactOptions
    name: str = ''
    userFunction: Any = field(default=None, repr=False)
    referenceAngles: List[float] = field(default_factory=lambda: [0., 0.])
    sensors: Dict[str, Any] = field(default_factory=dict)

    def Evaluate(self, phi1, phi2, omega1, omega2) -> MeshState:
        """Mesh quantities (normal force, S, sf, torques, ...) for arrays of worm/wheel states.

        ``phi1, phi2`` are the node coordinates (the node reference angles are added here).
        """
        return MeshContact(self.gear, np.asarray(phi1, dtype=float) + self.referenceAngles[0],
                           np.asarray(phi2, dtype=float) + self.referenceAngles[1],
                           np.asarray(omega1, dtype=float), np.asarray(omega2, dtype=float),
                           self.options, NUMPY_OPS)

    def AddSensors(self, mbs) -> Dict[str, Any]:
        """Add internally stored node sensors for the worm (1) and wheel (2): ``phi1, omega1, alpha1,
        phi2, omega2, alpha2``. Nothing is written to files. Returns the sensor numbers."""
        import exudyn as exu
        from exudyn.itemInterface import SensorNode
        OVT = exu.OutputVariableType
        for index, node in zip('12', self.nodeNumbers):
            for prefix, ovt in (('phi', OVT.Coordinates), ('omega', OVT.Coordinates_t), ('alpha', OVT.Coordinates_tt)):
                self.sensors[prefix + index] = mbs.AddSensor(SensorNode(nodeNumber=node, outputVariableType=ovt,
                                                                        storeInternal=True, writeToFile=False))
        return self.sensors

    def StoredStates(self, mbs) -> Dict[str, np.ndarray]:
        """Stored sensor data after a solve: ``time`` and the arrays of :meth:`AddSensors`."""
        if not self.sensors:
            raise ValueError(f"WormGearConnector '{self.name}': call AddSensors(mbs) before mbs.Assemble()")
        data = {k: mbs.GetSensorStoredData(s) for k, s in self.sensors.items()}
        out = {'time': data['phi1'][:, 0]}
        out.update({k: v[:, 1] for k, v in data.items()})
        return out

    def StoredMeshState(self, mbs) -> MeshState:
        """Mesh quantities over the stored time steps (requires :meth:`AddSensors`)."""
        s = self.StoredStates(mbs)
        return self.Evaluate(s['phi1'], s['phi2'], s['omega1'], s['omega2'])


def _CheckNode(mbs, n, name):
    try:
        info = mbs.GetNode(n)
    except Exception as err:  # exudyn raises its own error type for an invalid index
        raise ValueError(f"CreateWormGear: '{name}' is not a node of this system: {n!r} ({err})") from None
    nodeType = info.get('nodeType', '')
    nCoords = len(info.get('referenceCoordinates', [0.]))
    if nodeType not in ('1D', 'GenericODE2') or nCoords != 1:
        raise ValueError(f"CreateWormGear: '{name}' must be a node with one rotation coordinate (Node1D or "
                         f"NodeGenericODE2 with 1 coordinate), got node type '{nodeType}' with {nCoords} coordinates")
    return float(np.asarray(info['referenceCoordinates']).ravel()[0])


def CreateWormGear(mbs, nodeNumbers: Sequence[Any], gear: WormGear, name: str = '',
                   contactOptions: ContactOptions = ContactOptions(), useSymbolic: bool = True
                   ) -> WormGearConnector:
    """Add a worm-gear mesh between the rotation coordinates of a worm node and a wheel node.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system.
    nodeNumbers : [nWorm, nWheel]
        Worm and wheel nodes (``Node1D`` or one-coordinate ``NodeGenericODE2``); their coordinate is
        the rotation angle in rad, positive in the direction in which a positive worm rotation turns
        the wheel.
    gear : WormGear
        Mesh geometry, stiffness, damping, backlash and friction.
    name : str
        Name of the Exudyn object.
    contactOptions : ContactOptions
        Friction regularization, tension-free or linear law, fixed S for linearization.
    useSymbolic : bool
        True (default): C++-evaluated symbolic user function; False: plain Python user function.

    Returns
    -------
    WormGearConnector
        Object number, nodes, gear, options; ``Evaluate`` post-processes stored states.

    Raises
    ------
    ValueError, TypeError
        For invalid nodes, gear or options.
    """
    if not isinstance(gear, WormGear):
        raise TypeError(f"CreateWormGear: 'gear' must be a WormGear, got {type(gear).__name__}")
    if not isinstance(contactOptions, ContactOptions):
        raise TypeError(f"CreateWormGear: 'contactOptions' must be a ContactOptions, got "
                        f"{type(contactOptions).__name__}")
    if len(nodeNumbers) != 2:
        raise ValueError(f"CreateWormGear: 'nodeNumbers' must be [nWorm, nWheel], got {list(nodeNumbers)!r}")
    ref1 = _CheckNode(mbs, nodeNumbers[0], 'nodeNumbers[0] (worm)')
    ref2 = _CheckNode(mbs, nodeNumbers[1], 'nodeNumbers[1] (wheel)')

    def WormGearLaw(t, q, q_t, ops):
        """Generalized forces [worm torque, wheel torque] of the mesh."""
        state = MeshContact(gear, q[0] + ref1, q[1] + ref2, q_t[0], q_t[1], contactOptions, ops)
        return [state.wormTorque, state.wheelTorque]

    oItem, userFunction = AddGenericForce(mbs, nodeNumbers, WormGearLaw, name=name, useSymbolic=useSymbolic)
    return WormGearConnector(objectNumber=oItem, nodeNumbers=list(nodeNumbers), gear=gear,
                             options=contactOptions, name=name, userFunction=userFunction,
                             referenceAngles=[ref1, ref2])
