"""The worm-gear connector: one Exudyn item coupling the rotation coordinates of two nodes.

:func:`CreateWormGear` adds an ``ObjectGenericODE2`` on the worm and wheel nodes whose force user
function is the contact law of :mod:`exudyn_worm.model.contact`. By default the law is recorded as an
Exudyn symbolic user function and evaluated in C++; ``useSymbolic=False`` gives a plain-Python user
function for debugging (same law, same results, about 3 times slower on the reel changer;
see benchmarks/README.md).

Flank friction (:class:`~exudyn_worm.model.contact.ContactOptions` ``frictionModel``): by default the worm sticks
at zero sliding speed. The stick/slip state of each mesh lives in named symbolic variables read by the
recorded law and is switched between time steps by the system's post-Newton user function, which
:func:`CreateWormGear` installs (the decision is :func:`exudyn_worm.model.contact.StickSlipUpdate`;
docs/friction-sticking.md). ``frictionModel='regularized'`` gives the stateless law of earlier versions.

Supported nodes: nodes with exactly one ODE2 coordinate that is a rotation angle, i.e. ``Node1D``
(with ``ObjectRotationalMass1D``) and ``NodeGenericODE2`` with one coordinate. Worm and wheel as 3D rigid bodies
(``mbs.CreateRigidBody``, any rotation parametrization) take
:func:`~exudyn_worm.items.rigidmesh.CreateRigidBodyWormGear` instead, which measures each body's turn without
wrapping and gives the bearing reactions (docs/mesh-3d.md).

The worm's axial bearing (optional, :class:`~exudyn_worm.model.drive.AxialBearing`): :func:`CreateWormAxialBearing`
adds the worm's axial degree of freedom (mass ``mA`` on a spring-damper ``kA, dA`` to ground); pass its node as ``axialNodeNumber`` to
:func:`CreateWormGear` and the mesh displacement includes the worm's axial motion
(:func:`exudyn_worm.model.contact.MeshContact` documents the kinematics).
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any, Dict, List, Optional, Sequence

import numpy as np

from .._checks import CheckBool, CheckName, CheckReal, CheckSystem
from ._userfunctions import AddGenericForce, SetGenericForceLaw
from ..model.drive import AxialBearing
from ..model.contact import (ContactOptions, FrictionState, MeshContact, MeshState, SlidingCoordinate, StickSlipUpdate, SymbolicOps)
from ..model.friction import MATH_OPS, NUMPY_OPS
from ..model.gear import WormGear
from ..model.stickslip import (CarrySchedule, MeshReading, NextCheck, StartFrictionState, StartSchedule,
                               StickSlipSchedule, StickSlipStep)

__all__ = ['WormGearConnector', 'CreateWormGear', 'CreateWormAxialBearing', 'CONNECTORS_KEY']

#: ``mbs.variables`` key of the list of worm-gear connectors built in a system (found by the linear analysis)
CONNECTORS_KEY = 'exudynWorm.connectors'
#: ``mbs.variables`` key of the stick/slip states switched by the system's post-Newton user function
_STICK_SLIP_KEY = 'exudynWorm.stickSlip'


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


class _PostNewtonClock:
    """The system's post-Newton clock, shared by every item its post-Newton user function looks at.

    Attributes
    ----------
    lastTime : float
        Time in s of the last call.
    nextCheck : float
        Earliest time in s at which any item must be looked at (-inf: after the next step).
    """
    __slots__ = ('lastTime', 'nextCheck')

    def __init__(self):
        self.lastTime = self.nextCheck = -np.inf

    def Wake(self) -> None:
        """Look at every item after the next step."""
        self.nextCheck = -np.inf


class _StickSlip(MeshReading):
    """Stick/slip state of one connector with the sticking friction model, switched between time steps.

    The schedule (:class:`~exudyn_worm.model.stickslip.StickSlipSchedule`: the state and when to look again) is
    advanced by the pure policy :func:`~exudyn_worm.model.stickslip.StickSlipStep`, with this object as its
    :class:`~exudyn_worm.model.stickslip.MeshReading` of Exudyn's state. The state lives in Python (:attr:`state`,
    floats) and, for the symbolic (C++) law, in three named Exudyn symbolic variables that the recorded law reads;
    :meth:`_Apply` is the one place that writes both. The system's post-Newton user function calls
    :meth:`PostNewton` when the mesh is due; the switch rule is the contact law's
    :func:`~exudyn_worm.model.contact.StickSlipUpdate`, with the friction and normal force evaluated by a second
    recording of :func:`~exudyn_worm.model.contact.MeshContact` in C++ (symbolic connectors).
    """

    def __init__(self, gear: WormGear, options: ContactOptions, nodes, references, initial: FrictionState,
                 symbolic: bool):
        self.gear = gear
        self.options = options
        self.nodes, self.references = list(nodes), list(references)
        self.variables = self._probe = None
        if symbolic:
            self._Record(initial)
        self.schedule = StartSchedule(initial)
        self.history = [(-np.inf, initial)]     # (time from which a state holds, state)
        self.switches = 0
        self._indices = self._data = None
        # views of Exudyn's current coordinates and velocities (no copy: read in place after each step, taken
        # anew at the first step of each solve, see _View); the law's inputs, read once per call
        self._q = self._v = self._inputs = None
        self.clock = None                       # the system's _PostNewtonClock (set by _AddStickSlip)

    @property
    def options(self) -> ContactOptions:
        """The contact options of the law (setting them also sets whether the mesh has a stick state)."""
        return self._options

    @options.setter
    def options(self, options: ContactOptions) -> None:
        self._options, self._sticking = options, options.hasStickState

    def _Record(self, initial: FrictionState) -> None:
        """Named symbolic state variables, and (friction force, normal force) recorded in C++ for the checks."""
        import exudyn
        esym = exudyn.symbolic
        self.variables = FrictionState(*(esym.Real(name, float(getattr(initial, name)))
                                         for name in ('stuck', 'direction', 'anchor')))
        n = len(self.nodes)
        recording = esym.GetRecording()
        esym.SetRecording(True)
        try:
            x = esym.Vector('x', [0.] * (2 * n))        # coordinates (with references), then speeds
            axial = {} if n == 2 else {'axialDisplacement': x[2], 'axialSpeed': x[5]}
            mesh = MeshContact(self.gear, x[0], x[1], x[n], x[n + 1], self.options, SymbolicOps(),
                               frictionState=self.variables, **axial)
            self._probe = (x, mesh.frictionForce, mesh.normalForce)      # two scalars: each evaluates to a float
        finally:
            esym.SetRecording(recording)

    @property
    def state(self) -> FrictionState:
        """The stick/slip state in force (floats); setting it writes the law's variables too."""
        return self.schedule.state

    @state.setter
    def state(self, state: FrictionState) -> None:
        self._Apply(replace(self.schedule, state=state))

    def _Apply(self, schedule: StickSlipSchedule, t: Optional[float] = None, restart: bool = False) -> None:
        """Put ``schedule`` in force: its state into the law's symbolic variables, and into the history of the
        switches (a switch at time ``t``; ``restart``: the history starts anew with it)."""
        state = schedule.state
        self.schedule = schedule
        if restart:
            self._q = None                      # a new solve: the views are taken again at its first step
        if self.variables is not None:
            for name in ('stuck', 'direction', 'anchor'):
                getattr(self.variables, name).SetValue(float(getattr(state, name)))
        if restart:
            self.history = [(-np.inf, state)]
        elif t is not None:
            while len(self.history) > 1 and self.history[-1][0] >= t:    # a repeated step replaces its switch
                self.history.pop()
            self.history.append((t, state))
            self.switches += 1

    def Restart(self, mbs, coordinates, velocities) -> FrictionState:
        """Start a new solve from the ODE2 ``coordinates`` and ``velocities`` (whole-system vectors without the
        reference values, e.g. the initial configuration): the state becomes the one these imply
        (sliding in the direction of the worm's speed, stuck if it is at rest), the recorded switches and the
        check schedule are forgotten. Without it a solve starts from the state the previous one ended in.

        Returns
        -------
        FrictionState
            The start state.
        """
        self._indices = [mbs.GetNodeODE2Index(n) for n in self.nodes]
        x, w = self._LawInputs(*_Floats(coordinates, velocities))
        self._Apply(StartSchedule(StartFrictionState(self.gear, x[0], x[1], w[0])), restart=True)
        self.switches = 0
        if self.clock is not None:
            self.clock.Wake()                   # the system's post-Newton function looks at every mesh
        return self.state

    def Carry(self, mbs, fromCoordinates, toCoordinates) -> FrictionState:
        """Keep the state across a shift of the coordinates (a run continued in the coordinates relative to a
        steady rotation): the stuck flanks' anchor moves with the sliding coordinate, by its change from
        ``fromCoordinates`` (the end of the previous solve) to ``toCoordinates`` (the start of the next),
        whole-system ODE2 vectors without the reference values.

        Returns
        -------
        FrictionState
            The shifted state.
        """
        self._indices = [mbs.GetNodeODE2Index(n) for n in self.nodes]
        old, new = (self._LawInputs(*_Floats(q, q))[0] for q in (fromCoordinates, toCoordinates))
        shift = SlidingCoordinate(self.gear, new[0], new[1]) - SlidingCoordinate(self.gear, old[0], old[1])
        self._Apply(CarrySchedule(self.schedule, shift), restart=True)
        return self.state

    def LawState(self, ops):
        """The state as the law reads it: the symbolic variables, or the current floats in plain Python."""
        return self.state if ops is MATH_OPS or self.variables is None else self.variables

    def StatesAt(self, times) -> FrictionState:
        """The states in force at ``times`` (s), as arrays (from the recorded switches)."""
        starts = np.array([h[0] for h in self.history])
        k = np.searchsorted(starts, np.asarray(times, dtype=float), side='right') - 1
        return FrictionState(*(np.array([getattr(h[1], name) for h in self.history])[np.maximum(k, 0)]
                               for name in ('stuck', 'direction', 'anchor')))

    def _LawInputs(self, q, v):
        """The law's coordinates (with the node references) and speeds from whole-system ODE2 vectors ``q``, ``v``
        whose entries are floats (memoryviews or lists; a mesh of another kind, e.g. between rigid bodies, overrides
        this and the three methods below)."""
        indices, references = self._indices, self.references
        if len(indices) == 2:                       # worm and wheel (the common case): no loop
            i, k = indices
            return [q[i] + references[0], q[k] + references[1]], [v[i], v[k]]
        return [q[i] + ref for i, ref in zip(indices, references)], [v[i] for i in indices]

    def _WormSpeed(self, data, v) -> float:
        """The worm speed in rad/s that the friction law reads, from the whole-system ODE2 velocities ``v``."""
        return v[self._indices[0]]

    def _WormAcceleration(self, data) -> float:
        """The worm's angular acceleration in rad/s^2 (for the check schedule)."""
        return float(data.GetODE2Coordinates_tt()[self._indices[0]])

    def _Forces(self, x, w):
        """(friction force, normal force) in N of the law recorded in C++ at inputs ``x``, ``w``; None without it."""
        probe = self._probe
        if probe is None:
            return None
        probe[0].SetVector(x + w)
        return probe[1].Evaluate(), probe[2].Evaluate()

    def _View(self, mbs) -> None:
        """Take the node indices and views of Exudyn's current ODE2 coordinates and velocities (``copy=False``:
        reading them costs no call into Exudyn; as memoryviews, an entry is a float at a quarter of the cost of a
        numpy entry). Exudyn keeps these vectors in place while the system's size stays the same; a solve that
        starts anew (at an earlier time, or after :meth:`Restart` or :meth:`Carry`) takes them again, and so does
        a step after the system has grown (its number of ODE2 coordinates is compared at every step)."""
        import exudyn
        data = self._data = mbs.systemData
        self._indices = [mbs.GetNodeODE2Index(n) for n in self.nodes]
        current = exudyn.ConfigurationType.Current
        self._q = memoryview(data.GetODE2Coordinates(current, False))
        self._v = memoryview(data.GetODE2Coordinates_t(current, False))
        self._ode2Size = data.ODE2Size          # bound once: the size is compared at every step
        self._size = self._ode2Size()

    # the MeshReading of the policy, on the system's state after the step (read once per call)
    def _Inputs(self):
        if self._inputs is None:
            self._inputs = self._LawInputs(self._q, self._v)
        return self._inputs

    def WormSpeed(self) -> float:
        return self._WormSpeed(self._data, self._v)

    def WormAcceleration(self) -> float:
        return self._WormAcceleration(self._data)

    def SlidingCoordinate(self) -> float:
        x = self._Inputs()[0]
        return SlidingCoordinate(self.gear, x[0], x[1])

    def Switch(self, state, reversalCoordinate):
        inputs = self._inputs
        x, w = inputs if inputs is not None else self._Inputs()
        axial, axialSpeed = (x[2], w[2]) if len(x) == 3 else (None, None)
        return StickSlipUpdate(self.gear, self._options, state, x[0], x[1], w[0], w[1], axial, axialSpeed,
                               self._Forces(x, w), reversalCoordinate)

    def NextCheck(self) -> float:
        """Earliest time in s at which this mesh must be looked at again (-inf: after every step)."""
        if not self._sticking:
            return np.inf
        return NextCheck(self.schedule)

    def PostNewton(self, mbs, t: float) -> float:
        """Switch the state after a converged step; return the jump of the friction force in N (0: no switch)."""
        if not self._sticking:
            return 0.
        lastTime = self.schedule.lastTime
        if self._q is None or lastTime is None or t < lastTime or self._ode2Size() != self._size:
            self._View(mbs)                         # a new solve, or a system grown since: take the views again
        self._inputs = None
        jump = StickSlipStep(self.schedule, t, self)
        if jump is None:
            return 0.
        self._Apply(self.schedule, t)
        mbs.solverSignalJacobianUpdate = True       # the tangential stiffness changed: modified Newton renews it
        return jump


def _Floats(q, v):
    """Whole-system ODE2 vectors (arrays or sequences) as lists of floats, for ``_StickSlip._LawInputs``."""
    return np.asarray(q, dtype=float).tolist(), np.asarray(v, dtype=float).tolist()


def _SwitchContactOptions(where: str, mbs, connector, options: ContactOptions, NewStickSlip) -> None:
    """The part of a mesh's ``SetContactOptions`` that every mesh shares: check ``options``, give a sticking mesh its
    stick/slip state (``NewStickSlip()``, registered here unless it registered itself), hand it the options and wake
    the post-Newton function; the caller then re-records its law."""
    if not isinstance(options, ContactOptions):
        raise TypeError(f"{where}.SetContactOptions: 'options' must be a ContactOptions, got {type(options).__name__}")
    if options.hasStickState and connector.stickSlip is None:
        connector.stickSlip = NewStickSlip()
        if connector.stickSlip.clock is None:
            _AddStickSlip(mbs, connector.stickSlip)
    if connector.stickSlip is not None:
        connector.stickSlip.options = options
        connector.stickSlip.clock.Wake()            # look at every mesh after the next step
    connector.options = options


def _AddStickSlip(mbs, item) -> None:
    """Register a connector's stick/slip state (or another item with ``PostNewton`` and ``NextCheck``) with the
    system's post-Newton user function (one per system)."""
    items = mbs.variables.get(_STICK_SLIP_KEY)
    if items is None:
        items = mbs.variables[_STICK_SLIP_KEY] = []
        noSwitch = [0., -1.]
        clock = mbs.variables[_STICK_SLIP_KEY + '.clock'] = _PostNewtonClock()

        def PostNewtonUserFunction(mbs, t):
            """Exudyn's discontinuous iteration: [friction force jump in N, no step size recommendation]."""
            if clock.lastTime <= t < clock.nextCheck:    # every mesh slides and none is due: most steps' call
                clock.lastTime = t
                return noSwitch
            clock.lastTime = t
            if len(items) == 1:                     # one mesh (the common case): no loop
                item = items[0]
                error = item.PostNewton(mbs, t)
                clock.nextCheck = item.NextCheck()
            else:
                error = 0.
                for item in items:
                    error += item.PostNewton(mbs, t)
                clock.nextCheck = min(item.NextCheck() for item in items)
            return [error, -1.] if error else noSwitch

        mbs.SetPostNewtonUserFunction(PostNewtonUserFunction)
    item.clock = mbs.variables[_STICK_SLIP_KEY + '.clock']
    items.append(item)


def _InitialFrictionState(gear: WormGear, mbs, nodes, references) -> FrictionState:
    """The start state (:func:`~exudyn_worm.model.stickslip.StartFrictionState`) of the nodes' initial values."""
    x, v = [], []
    for node, ref in zip(nodes[:2], references[:2]):
        info = mbs.GetNode(node)
        x.append(float(np.ravel(info['initialCoordinates'])[0]) + ref)
        v.append(float(np.ravel(info['initialVelocities'])[0]))
    return StartFrictionState(gear, x[0], x[1], v[0])


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
    stickSlip : object or None
        The stick/slip machinery of the sticking friction model (its state and the switches recorded during a
        solve); None with the regularized model or a fixed S.
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
    stickSlip: Any = field(default=None, repr=False)

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
        _SwitchContactOptions('WormGearConnector', mbs, self, options, lambda: _CreateStickSlip(
            mbs, self.gear, options, self.coordinateNodes, self._References(), self.useSymbolic))
        law = _WormGearLaw(self.gear, options, self.referenceAngles, self.axialNodeNumber is not None,
                           self.axialReference, self.stickSlip)
        self.userFunction = SetGenericForceLaw(mbs, self.objectNumber, len(self.coordinateNodes), law,
                                               self.useSymbolic)

    def _References(self) -> List[float]:
        return list(self.referenceAngles) + ([] if self.axialNodeNumber is None else [self.axialReference])

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

    def Evaluate(self, phi1, phi2, omega1, omega2, xA=None, vA=None, time=None) -> MeshState:
        """Mesh quantities (normal force, S, sf, torques, axial force, ...) for arrays of worm/wheel states.

        ``phi1, phi2`` (and ``xA``) are the node coordinates (the node reference values are added here);
        ``xA, vA``: the worm's axial displacement and speed, required if the connector has an axial node.
        ``time``: the simulated times in s of the states; with the sticking friction model the stick/slip
        state recorded during the solve at these times is used (None: the exact Coulomb law without a stick
        state, which differs from the simulation only where the flanks stuck).
        """
        if (self.axialNodeNumber is None) != (xA is None):
            raise ValueError(f"WormGearConnector '{self.name}': give 'xA' (and 'vA') exactly when the connector has "
                             f"an axial node (axialNodeNumber = {self.axialNodeNumber!r})")
        axial = {} if xA is None else {'axialDisplacement': np.asarray(xA, dtype=float) + self.axialReference,
                                       'axialSpeed': np.asarray(vA, dtype=float)}
        state = None
        if time is not None and self.stickSlip is not None and self.options.hasStickState:
            state = self.stickSlip.StatesAt(np.broadcast_to(np.asarray(time, dtype=float), np.shape(phi1)))
        return MeshContact(self.gear, np.asarray(phi1, dtype=float) + self.referenceAngles[0],
                           np.asarray(phi2, dtype=float) + self.referenceAngles[1],
                           np.asarray(omega1, dtype=float), np.asarray(omega2, dtype=float),
                           self.options, NUMPY_OPS, frictionState=state, **axial)

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

        ``normalForce`` is signed (see :class:`~exudyn_worm.model.contact.MeshState`); ``normalForceFlanks`` gives
        the magnitudes on the two flanks. ``mbs`` and the errors (no sensors, not solved yet) are those of
        :meth:`StoredStates`.
        """
        s = self.StoredStates(mbs)
        state = self.Evaluate(s['phi1'], s['phi2'], s['omega1'], s['omega2'], s.get('xA'), s.get('vA'), s['time'])
        state.time = s['time']
        return state


def _NodeOf(n):
    """A node number, or the ``nodeNumber`` of a dict from :func:`~exudyn_worm.items.drivetrain.CreateRotor` (or
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
        or as a rotor dict from :func:`~exudyn_worm.items.drivetrain.CreateRotor` (its ``nodeNumber`` is used):
        ``[nWorm, nWheel]`` or ``[worm, wheel]``. Their coordinate is the rotation angle in rad, positive in the
        direction in which a positive worm rotation turns the wheel.
    gear : WormGear
        Mesh geometry, stiffness, damping, backlash and friction.
    name : str
        Name of the Exudyn object.
    contactOptions : ContactOptions
        Friction model (default: sticking, with a stick/slip state), tension-free or linear law, fixed S for
        linearization. With the sticking model (and no fixed S) this installs the system's post-Newton user
        function (``mbs.SetPostNewtonUserFunction``, one per system, shared by all sticking meshes), which
        switches the stick/slip state between time steps; a post-Newton function set before is replaced.
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
    With the rotors of :func:`~exudyn_worm.items.drivetrain.CreateRotor` (node numbers work as well)::

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
    stickSlip = None
    if contactOptions.hasStickState:
        stickSlip = _CreateStickSlip(mbs, gear, contactOptions, nodes, [ref1, ref2, refA][:len(nodes)], useSymbolic)
    law = _WormGearLaw(gear, contactOptions, [ref1, ref2], axialNodeNumber is not None, refA, stickSlip)
    oItem, userFunction = AddGenericForce(mbs, nodes, law, name=name, useSymbolic=useSymbolic, where='CreateWormGear')
    connector = WormGearConnector(objectNumber=oItem, nodeNumbers=list(nodeNumbers), gear=gear,
                                  options=contactOptions, name=name, userFunction=userFunction,
                                  referenceAngles=[ref1, ref2], axialNodeNumber=axialNodeNumber, axialReference=refA,
                                  useSymbolic=useSymbolic, stickSlip=stickSlip)
    mbs.variables.setdefault(CONNECTORS_KEY, []).append(connector)
    return connector


def _CreateStickSlip(mbs, gear, options, nodes, references, useSymbolic) -> _StickSlip:
    """The stick/slip state of a new sticking connector, registered with the system's post-Newton function."""
    stickSlip = _StickSlip(gear, options, nodes, references, _InitialFrictionState(gear, mbs, nodes, references),
                           useSymbolic)
    _AddStickSlip(mbs, stickSlip)
    return stickSlip


def _WormGearLaw(gear, options, referenceAngles, axial, axialReference, stickSlip=None):
    """The connector's generalized forces as ``law(t, q, q_t, ops)`` for AddGenericForce."""
    ref1, ref2 = referenceAngles
    Shifted = lambda x, ref: x + ref if ref != 0 else x      # no '+ 0' node in the recorded expression
    StateOf = (lambda ops: None) if stickSlip is None or not options.hasStickState else stickSlip.LawState
    if not axial:
        def WormGearLaw(t, q, q_t, ops):
            """Generalized forces [worm torque, wheel torque] of the mesh."""
            return MeshContact(gear, Shifted(q[0], ref1), Shifted(q[1], ref2), q_t[0], q_t[1], options, ops,
                               frictionState=StateOf(ops)).generalizedForces
    else:
        def WormGearLaw(t, q, q_t, ops):
            """Generalized forces [worm torque, wheel torque, worm axial force] of the mesh."""
            return MeshContact(gear, Shifted(q[0], ref1), Shifted(q[1], ref2), q_t[0], q_t[1], options, ops,
                               axialDisplacement=Shifted(q[2], axialReference), axialSpeed=q_t[2],
                               frictionState=StateOf(ops)).generalizedForces
    return WormGearLaw
