"""The worm-gear connector: one Exudyn item coupling the rotation coordinates of two nodes.

:func:`CreateWormGear` adds an ``ObjectGenericODE2`` on the worm and wheel nodes whose force user
function is the contact law of :mod:`exudyn_worm.contact`. By default the law is recorded as an
Exudyn symbolic user function and evaluated in C++; ``useSymbolic=False`` gives a plain-Python user
function for debugging (same law, same results, about 3 times slower on the reel changer;
see benchmarks/README.md).

Supported nodes: nodes with exactly one ODE2 coordinate that is a rotation angle, i.e. ``Node1D``
(with ``ObjectRotationalMass1D``) and ``NodeGenericODE2`` with one coordinate. 3D rigid-body nodes
are not supported: their rotation parameters wrap at +-pi (see docs/exudyn notes).

The worm's axial bearing (optional): :func:`CreateWormAxialBearing` adds the worm's axial degree of
freedom (mass ``mA`` on a spring-damper ``kA, dA`` to ground); pass its node as ``axialNodeNumber`` to
:func:`CreateWormGear` and the mesh displacement includes the worm's axial motion
(:func:`exudyn_worm.contact.MeshContact` documents the kinematics).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Sequence

import numpy as np

from ._checks import CheckBool, CheckName, CheckNonNegative, CheckPositive, CheckReal, CheckSystem
from ._userfunctions import AddGenericForce, SetGenericForceLaw
from .contact import NUMPY_OPS, ContactOptions, MeshContact, MeshState
from .gear import WormGear

__all__ = ['WormGearConnector', 'CreateWormGear', 'AxialBearing', 'CreateWormAxialBearing', 'CONNECTORS_KEY']

#: ``mbs.variables`` key of the list of worm-gear connectors built in a system (found by the linear analysis)
CONNECTORS_KEY = 'exudynWorm.connectors'


@dataclass(frozen=True)
class AxialBearing:
    """Axial bearing of the worm: the worm's axially moving mass on an axial spring-damper to the housing.

    Parameters
    ----------
    stiffness : float
        Axial stiffness kA in N/m, > 0.
    damping : float
        Axial damping dA in N*s/m, >= 0.
    mass : float
        Axially moving mass of the worm mA in kg, > 0 (worm, shaft and the bearing parts moving with it).
    """
    stiffness: float
    damping: float
    mass: float

    def __post_init__(self):
        w = 'AxialBearing'
        object.__setattr__(self, 'stiffness', CheckPositive(w, 'stiffness', self.stiffness, 'N/m'))
        object.__setattr__(self, 'damping', CheckNonNegative(w, 'damping', self.damping, 'N*s/m'))
        object.__setattr__(self, 'mass', CheckPositive(w, 'mass', self.mass, 'kg'))


def CreateWormAxialBearing(mbs, bearing: AxialBearing, initialDisplacement: float = 0., initialSpeed: float = 0.,
                           name: str = 'wormAxial') -> Dict[str, Any]:
    """Add the worm's axial degree of freedom: ``Node1D`` + ``ObjectMass1D`` + spring-damper to ground.

    Pass the returned ``nodeNumber`` as ``axialNodeNumber`` to :func:`CreateWormGear`.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system.
    bearing : AxialBearing
        Stiffness, damping and axially moving mass.
    initialDisplacement : float
        Initial axial displacement in m (positive where the thread advances for a positive worm rotation).
    initialSpeed : float
        Initial axial speed in m/s.
    name : str
        Name of the node, mass and spring-damper.

    Returns
    -------
    dict
        ``nodeNumber``, ``objectNumber`` (the mass), ``markerNumber``, ``springDamperNumber``.
    """
    from exudyn.itemInterface import (CoordinateSpringDamper, MarkerNodeCoordinate, Node1D, NodePointGround,
                                      ObjectMass1D)
    w = 'CreateWormAxialBearing'
    CheckSystem(w, mbs)
    CheckName(w, 'name', name)
    if not isinstance(bearing, AxialBearing):
        raise TypeError(f"{w}: 'bearing' must be an AxialBearing, got {type(bearing).__name__}")
    nNode = mbs.AddNode(Node1D(referenceCoordinates=[0.],
                               initialCoordinates=[CheckReal(w, 'initialDisplacement', initialDisplacement, 'm')],
                               initialVelocities=[CheckReal(w, 'initialSpeed', initialSpeed, 'm/s')], name=name))
    oMass = mbs.AddObject(ObjectMass1D(nodeNumber=nNode, mass=bearing.mass, name=name))
    mNode = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nNode, coordinate=0))
    nGround = mbs.AddNode(NodePointGround())
    mGround = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nGround, coordinate=0))
    oSpring = mbs.AddObject(CoordinateSpringDamper(markerNumbers=[mGround, mNode], stiffness=bearing.stiffness,
                                                   damping=bearing.damping, name=name + 'Bearing'))
    return {'nodeNumber': nNode, 'objectNumber': oMass, 'markerNumber': mNode, 'springDamperNumber': oSpring}


@dataclass
class WormGearConnector:
    """What :func:`CreateWormGear` created, and the law to post-process its results.

    Use :meth:`AddSensors` before ``mbs.Assemble()`` to record the worm and wheel states, then
    :meth:`StoredMeshState` after the solve for every mesh quantity over time.

    Attributes
    ----------
    objectNumber : exudyn.ObjectIndex
        The ``ObjectGenericODE2`` that carries the mesh law.
    nodeNumbers : list of exudyn.NodeIndex
        Worm and wheel nodes, ``[nWorm, nWheel]``.
    gear : WormGear
        Mesh geometry, stiffness, damping, backlash and friction.
    options : ContactOptions
        The contact options the law was built with.
    name : str
        Name of the Exudyn object.
    userFunction : callable or None
        The user function given to Exudyn (kept alive here).
    referenceAngles : list of float
        Reference coordinates in rad of the worm and wheel nodes, added to their stored displacements.
    sensors : dict
        Sensors added by :meth:`AddSensors`, by name.
    axialNodeNumber : exudyn.NodeIndex or None
        Node of the worm's axial coordinate in m; None: the worm is rigid axially.
    axialReference : float
        Reference coordinate of the axial node in m.
    useSymbolic : bool
        True: C++-evaluated symbolic user function; False: plain Python user function.
    """
    objectNumber: Any
    nodeNumbers: List[Any]
    gear: WormGear
    options: ContactOptions
    name: str = ''
    userFunction: Any = field(default=None, repr=False)
    referenceAngles: List[float] = field(default_factory=lambda: [0., 0.])
    sensors: Dict[str, Any] = field(default_factory=dict)
    axialNodeNumber: Any = None
    axialReference: float = 0.
    useSymbolic: bool = True

    @property
    def coordinateNodes(self) -> List[Any]:
        """Nodes of the connector's coordinates: worm, wheel (and the worm's axial node if present)."""
        return list(self.nodeNumbers) + ([] if self.axialNodeNumber is None else [self.axialNodeNumber])

    def SetContactOptions(self, mbs, options: ContactOptions) -> None:
        """Replace the contact options of the built connector (e.g. hold S for a linearization).

        Re-records the connector's user function; call ``mbs.Assemble()`` (or let Exudyn's solvers
        auto-assemble) before the next computation.

        Parameters
        ----------
        mbs : exudyn.MainSystem
            The system the connector belongs to.
        options : ContactOptions
            The new options.
        """
        if not isinstance(options, ContactOptions):
            raise TypeError(f"WormGearConnector.SetContactOptions: 'options' must be a ContactOptions, got "
                            f"{type(options).__name__}")
        law = _WormGearLaw(self.gear, options, self.referenceAngles, self.axialNodeNumber is not None,
                           self.axialReference)
        self.userFunction = SetGenericForceLaw(mbs, self.objectNumber, len(self.coordinateNodes), law,
                                               self.useSymbolic)
        self.options = options

    def InitialMeshState(self, mbs) -> MeshState:
        """Mesh quantities at the system's initial state (node initial coordinates and velocities).

        Parameters
        ----------
        mbs : exudyn.MainSystem
            The system the connector belongs to.
        """
        values = []
        for node in self.coordinateNodes:
            info = mbs.GetNode(node)
            values.append((float(np.ravel(info['initialCoordinates'])[0]), float(np.ravel(info['initialVelocities'])[0])))
        axial = values[2] if len(values) == 3 else (None, None)
        return self.Evaluate(values[0][0], values[1][0], values[0][1], values[1][1], *axial)

    def Evaluate(self, phi1, phi2, omega1, omega2, xA=None, vA=None) -> MeshState:
        """Mesh quantities (normal force, S, sf, torques, axial force, ...) for arrays of worm/wheel states.

        ``phi1, phi2`` (and ``xA``) are the node coordinates (the node reference values are added here);
        ``xA, vA``: the worm's axial displacement and speed, required if the connector has an axial node.
        """
        if (self.axialNodeNumber is None) != (xA is None):
            raise ValueError(f"WormGearConnector '{self.name}': give 'xA' (and 'vA') exactly when the connector has "
                             f"an axial node (axialNodeNumber = {self.axialNodeNumber!r})")
        axial = {} if xA is None else {'axialDisplacement': np.asarray(xA, dtype=float) + self.axialReference,
                                       'axialSpeed': np.asarray(vA, dtype=float)}
        return MeshContact(self.gear, np.asarray(phi1, dtype=float) + self.referenceAngles[0],
                           np.asarray(phi2, dtype=float) + self.referenceAngles[1],
                           np.asarray(omega1, dtype=float), np.asarray(omega2, dtype=float),
                           self.options, NUMPY_OPS, **axial)

    def AddSensors(self, mbs) -> Dict[str, Any]:
        """Add internally stored node sensors for the worm (1) and wheel (2): ``phi1, omega1, alpha1,
        phi2, omega2, alpha2``, and with an axial node the worm's axial ``xA, vA, aA``. Nothing is written
        to files. Returns the sensor numbers."""
        import exudyn as exu
        from exudyn.itemInterface import SensorNode
        OVT = exu.OutputVariableType
        nodes = [(('phi1', 'omega1', 'alpha1'), self.nodeNumbers[0]), (('phi2', 'omega2', 'alpha2'), self.nodeNumbers[1])]
        if self.axialNodeNumber is not None:
            nodes.append((('xA', 'vA', 'aA'), self.axialNodeNumber))
        for names, node in nodes:
            for key, ovt in zip(names, (OVT.Coordinates, OVT.Coordinates_t, OVT.Coordinates_tt)):
                self.sensors[key] = mbs.AddSensor(SensorNode(nodeNumber=node, outputVariableType=ovt,
                                                             storeInternal=True, writeToFile=False))
        return self.sensors

    def StoredStates(self, mbs) -> Dict[str, np.ndarray]:
        """Stored sensor data after a solve: ``time`` and the arrays of :meth:`AddSensors`.

        Parameters
        ----------
        mbs : exudyn.MainSystem
            The system the connector belongs to, after a solve.

        Returns
        -------
        dict of ndarray
            ``time`` in s and the node states of :meth:`AddSensors`.

        Raises
        ------
        ValueError
            If :meth:`AddSensors` was not called, or the sensors hold no data yet (the system was not solved).
        """
        where = f"WormGearConnector '{self.name}'" if self.name else 'WormGearConnector'
        CheckSystem(f"{where}.StoredStates", mbs)
        if not self.sensors:
            raise ValueError(f"{where}: call AddSensors(mbs) before mbs.Assemble()")
        data = {k: np.asarray(mbs.GetSensorStoredData(s)) for k, s in self.sensors.items()}
        if any(v.ndim != 2 or v.shape[0] == 0 or v.shape[1] < 2 for v in data.values()):
            raise ValueError(f"{where}: no stored sensor data: solve the system first (mbs.SolveDynamic(...) after "
                             f"mbs.Assemble()), then read the stored states")
        out = {'time': data['phi1'][:, 0]}
        out.update({k: v[:, 1] for k, v in data.items()})
        return out

    def StoredMeshState(self, mbs) -> MeshState:
        """Mesh quantities over the stored time steps (requires :meth:`AddSensors`), with their ``time`` in s.

        ``normalForce`` is signed (see :class:`~exudyn_worm.contact.MeshState`); ``normalForceFlanks`` gives
        the magnitudes on the two flanks. ``mbs`` and the errors (no sensors, not solved yet) are those of
        :meth:`StoredStates`.
        """
        s = self.StoredStates(mbs)
        state = self.Evaluate(s['phi1'], s['phi2'], s['omega1'], s['omega2'], s.get('xA'), s.get('vA'))
        state.time = s['time']
        return state


def _NodeOf(n):
    """A node number, or the ``nodeNumber`` of a dict from :func:`~exudyn_worm.drivetrain.CreateRotor` (or
    :func:`CreateWormAxialBearing`)."""
    return n['nodeNumber'] if isinstance(n, dict) and 'nodeNumber' in n else n


def _CheckNode(mbs, n, name, what='rotation'):
    if isinstance(n, (dict, str, float, bool)) or n is None:
        raise TypeError(f"CreateWormGear: '{name}' must be a node number or a dict with 'nodeNumber' (a rotor from "
                        f"CreateRotor), got {type(n).__name__} {n!r}")
    try:
        info = mbs.GetNode(n)
    except Exception as err:  # exudyn raises its own error type for an invalid index
        raise ValueError(f"CreateWormGear: '{name}' is not a node of this system: {n!r} ({err})") from None
    nodeType = info.get('nodeType', '')
    nCoords = len(info.get('referenceCoordinates', [0.]))
    if nodeType not in ('1D', 'GenericODE2') or nCoords != 1:
        raise ValueError(f"CreateWormGear: '{name}' must be a node with one {what} coordinate (Node1D or "
                         f"NodeGenericODE2 with 1 coordinate), got node type '{nodeType}' with {nCoords} coordinates")
    return float(np.asarray(info['referenceCoordinates']).ravel()[0])


def CreateWormGear(mbs, nodeNumbers: Sequence[Any], gear: WormGear, name: str = '',
                   contactOptions: ContactOptions = ContactOptions(), useSymbolic: bool = True,
                   axialNodeNumber: Any = None) -> WormGearConnector:
    """Add a worm-gear mesh between the rotation coordinates of a worm node and a wheel node.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system.
    nodeNumbers : [worm, wheel]
        Worm and wheel nodes (``Node1D`` or one-coordinate ``NodeGenericODE2``), each given as a node number
        or as a rotor dict from :func:`~exudyn_worm.drivetrain.CreateRotor` (its ``nodeNumber`` is used):
        ``[nWorm, nWheel]`` or ``[worm, wheel]``. Their coordinate is the rotation angle in rad, positive in the
        direction in which a positive worm rotation turns the wheel.
    gear : WormGear
        Mesh geometry, stiffness, damping, backlash and friction.
    name : str
        Name of the Exudyn object.
    contactOptions : ContactOptions
        Friction regularization, tension-free or linear law, fixed S for linearization.
    useSymbolic : bool
        True (default): C++-evaluated symbolic user function; False: plain Python user function.
    axialNodeNumber : optional
        Node of the worm's axial coordinate in m (a node number, or the dict from
        :func:`CreateWormAxialBearing`), positive in
        the direction in which the thread advances for a positive worm rotation. The mesh displacement
        then includes ``cos(alphaN) cos(gamma) xA`` and the mesh pushes this node with
        ``-wheelTorque / r2``. None (default): the worm is rigid axially.

    Returns
    -------
    WormGearConnector
        Object number, node numbers, gear, options; ``Evaluate`` post-processes stored states.

    Raises
    ------
    ValueError, TypeError
        For a ``mbs`` that is not an ``exudyn.MainSystem``, invalid nodes, gear or options.

    Examples
    --------
    With the rotors of :func:`~exudyn_worm.drivetrain.CreateRotor` (node numbers work as well)::

        worm, wheel = CreateRotor(mbs, 0.1), CreateRotor(mbs, 33.)
        mesh = CreateWormGear(mbs, [worm, wheel], gear=gear, name='mesh')
    """
    w = 'CreateWormGear'
    CheckSystem(w, mbs)
    CheckName(w, 'name', name)
    CheckBool(w, 'useSymbolic', useSymbolic)
    if isinstance(nodeNumbers, (str, bytes, dict)) or not hasattr(nodeNumbers, '__len__'):
        raise TypeError(f"{w}: 'nodeNumbers' must be a list [worm, wheel] of two node numbers or rotors from "
                        f"CreateRotor, got {type(nodeNumbers).__name__} {nodeNumbers!r}")
    if not isinstance(gear, WormGear):
        raise TypeError(f"CreateWormGear: 'gear' must be a WormGear, got {type(gear).__name__}")
    if not isinstance(contactOptions, ContactOptions):
        raise TypeError(f"CreateWormGear: 'contactOptions' must be a ContactOptions, got "
                        f"{type(contactOptions).__name__}")
    if len(nodeNumbers) != 2:
        raise ValueError(f"CreateWormGear: 'nodeNumbers' must be [nWorm, nWheel], got {list(nodeNumbers)!r}")
    nodeNumbers = [_NodeOf(n) for n in nodeNumbers]
    axialNodeNumber = _NodeOf(axialNodeNumber)
    ref1 = _CheckNode(mbs, nodeNumbers[0], 'nodeNumbers[0] (worm)')
    ref2 = _CheckNode(mbs, nodeNumbers[1], 'nodeNumbers[1] (wheel)')

    refA = 0. if axialNodeNumber is None else _CheckNode(mbs, axialNodeNumber, 'axialNodeNumber', 'axial displacement')
    nodes = list(nodeNumbers) + ([] if axialNodeNumber is None else [axialNodeNumber])
    if len({int(n) for n in nodes}) < len(nodes):     # nodes checked above
        raise ValueError(f"CreateWormGear: worm, wheel (and axial) nodes must be different nodes, got nodeNumbers = "
                         f"{list(nodeNumbers)!r}" + ('' if axialNodeNumber is None else
                                                    f", axialNodeNumber = {axialNodeNumber!r}"))
    law = _WormGearLaw(gear, contactOptions, [ref1, ref2], axialNodeNumber is not None, refA)
    oItem, userFunction = AddGenericForce(mbs, nodes, law, name=name, useSymbolic=useSymbolic, where='CreateWormGear')
    connector = WormGearConnector(objectNumber=oItem, nodeNumbers=list(nodeNumbers), gear=gear,
                                  options=contactOptions, name=name, userFunction=userFunction,
                                  referenceAngles=[ref1, ref2], axialNodeNumber=axialNodeNumber, axialReference=refA,
                                  useSymbolic=useSymbolic)
    mbs.variables.setdefault(CONNECTORS_KEY, []).append(connector)
    return connector


def _WormGearLaw(gear, options, referenceAngles, axial, axialReference):
    """The connector's generalized forces as ``law(t, q, q_t, ops)`` for AddGenericForce."""
    ref1, ref2 = referenceAngles
    Shifted = lambda x, ref: x + ref if ref != 0 else x      # no '+ 0' node in the recorded expression
    if not axial:
        def WormGearLaw(t, q, q_t, ops):
            """Generalized forces [worm torque, wheel torque] of the mesh."""
            state = MeshContact(gear, Shifted(q[0], ref1), Shifted(q[1], ref2), q_t[0], q_t[1], options, ops)
            return [state.wormTorque, state.wheelTorque]
    else:
        def WormGearLaw(t, q, q_t, ops):
            """Generalized forces [worm torque, wheel torque, worm axial force] of the mesh."""
            state = MeshContact(gear, Shifted(q[0], ref1), Shifted(q[1], ref2), q_t[0], q_t[1], options, ops,
                                axialDisplacement=Shifted(q[2], axialReference), axialSpeed=q_t[2])
            return [state.wormTorque, state.wheelTorque, state.axialForce]
    return WormGearLaw
