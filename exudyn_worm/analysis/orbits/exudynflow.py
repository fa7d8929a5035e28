"""The one-period map of any Exudyn system relative to a steady rotation (:class:`ExudynFlow`): set the initial
state, ``mbs.SolveDynamic`` over time T with a fixed number of steps, read the end state; with the helpers that
find a system's ODE2 coordinates, the nodes that own them and the ones a coordinate constraint holds.
"""
from __future__ import annotations

from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np

from ...items.connector import CONNECTORS_KEY
from ...items.rigidmesh import RIGID_CONNECTORS_KEY
from ...items.solve import SolverDivergedError
from ..simulation.reelchanger import SolverSettings

__all__ = ['ExudynFlow', 'STEPS_PER_PERIOD', 'ORBIT_SOLVER_SETTINGS']

#: solver steps per chatter period of the shooting runs: at P1 the force factor, largest ``|phi2''|`` and frequency
#: change by less than 0.04 % between 150 and 1600 steps (2.6157/102.29/40.525 at 150, 2.6149/102.28/40.535 at
#: 800), but with 0.5 mm backlash (J1 = 0.25, the worm crosses the gap) shooting does not converge at 200 or 300
#: steps (the map is too rough); measured, docs/chatter-amplitude.md
STEPS_PER_PERIOD = 400


#: generalized-alpha settings of the shooting runs: Newton with a tight tolerance, so that the one-period map is
#: smooth enough for finite differences of 1e-6; modified Newton (the Jacobian kept while it converges) gives the
#: same end state to 4e-12 of the state scale in half the time of full Newton (P1, measured)
ORBIT_SOLVER_SETTINGS = {'timeIntegration.newton.useModifiedNewton': True,
                         'timeIntegration.newton.relativeTolerance': 1e-11,
                         'timeIntegration.newton.absoluteTolerance': 1e-11,
                         'timeIntegration.newton.maxIterations': 12,
                         'timeIntegration.generalizedAlpha.spectralRadius': 0.8}


def _Configuration():
    import exudyn as exu
    return exu.ConfigurationType


def _AddFlowSensors(mbs, coordinates: Sequence[int]) -> Tuple[Tuple[int, int, int], ...]:
    """Node sensors (positions, velocities; stored, not written) for the nodes of the ODE2 ``coordinates``;
    per coordinate ``(positionSensor, velocitySensor, column)``. Call ``mbs.Assemble()`` afterwards."""
    import exudyn as exu
    from exudyn.itemInterface import SensorNode
    OVT = exu.OutputVariableType
    owner = _CoordinateOwners(mbs)
    made, out = {}, []
    for i in coordinates:
        node, column = owner[int(i)]
        if node not in made:
            made[node] = tuple(mbs.AddSensor(SensorNode(nodeNumber=node, outputVariableType=ovt, storeInternal=True,
                                                        writeToFile=False))
                               for ovt in (OVT.Coordinates, OVT.Coordinates_t))
        out.append((int(made[node][0]), int(made[node][1]), column))
    return tuple(out)


def _CoordinateOwners(mbs) -> Dict[int, Tuple[int, int]]:
    """ODE2 coordinate index -> (node number, coordinate of the node), for the nodes with ODE2 coordinates."""
    import exudyn as exu
    owner = {}
    for n in range(mbs.systemData.NumberOfNodes()):
        try:
            count = np.size(mbs.GetNodeOutput(n, exu.OutputVariableType.Coordinates_t))   # a float for a 1D node
        except Exception:          # a node without velocities (ground, data node) has no ODE2 coordinates
            count = 0
        if count:
            first = int(mbs.GetNodeODE2Index(n))
            owner.update({first + k: (n, k) for k in range(count)})
    return owner


class ExudynFlow:
    """One-period map of an Exudyn system relative to a steady rotation: ``flow(x, T) -> x(T)``.

    The state ``x`` holds, for the ODE2 coordinates ``coordinates``, the positions minus ``steadySpeeds * t``,
    then the velocities minus ``steadySpeeds``. Coordinates not in ``coordinates`` (e.g. a prescribed motor)
    start at their position ``fixedPositions`` (default: the system's initial values) and steady speed.
    The discrete state is not part of ``x``: every solve starts with the data coordinates the system had when
    the flow was made and with the stick/slip state of each worm-gear connector that the start implies
    (sliding in the direction of the worm's speed, :meth:`~exudyn_worm.items.connector._StickSlip.Restart`; a
    rigid-body connector's reference angles of the turns from the start state as well), so
    ``flow(x, T)`` depends on ``x`` and ``T`` alone, not on the previous call.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        An assembled system.
    coordinates : sequence of int
        ODE2 coordinate indices of the state.
    steadySpeeds : sequence of float
        Steady speed of every ODE2 coordinate (rad/s or m/s); 0 for a coordinate at rest.
    stepsPerPeriod : int
        Solver steps per call (the step is ``T / stepsPerPeriod``).
    solverSettings : mapping, optional
        Dotted ``SimulationSettings`` paths applied over :data:`ORBIT_SOLVER_SETTINGS`.
    dependent : (sequence of int, ndarray), optional
        Coordinates outside the state that linear constraints tie to the others (a rigid-body mesh law's auxiliary
        coordinates, :func:`~exudyn_worm.items.rigidmesh.CreateRigidBodyWormGear`): their indices and the matrix
        ``D`` (rows: these coordinates, columns: all ODE2 coordinates) with which each start sets them consistent,
        ``q = q0 + D (q - q0)``, ``q' = D q'``; massless, they would otherwise start off their constraint.
    """

    def __init__(self, mbs: Any, coordinates: Sequence[int], steadySpeeds: Sequence[float],
                 stepsPerPeriod: int = STEPS_PER_PERIOD, solverSettings: Optional[Mapping[str, Any]] = None,
                 dependent: Optional[Tuple[Sequence[int], Any]] = None):
        import exudyn as exu
        self.mbs = mbs
        self.coordinates = np.asarray(coordinates, dtype=int)
        self.speeds = np.asarray(steadySpeeds, dtype=float)
        if isinstance(stepsPerPeriod, bool) or not isinstance(stepsPerPeriod, int) or stepsPerPeriod < 10:
            raise ValueError(f"ExudynFlow: 'stepsPerPeriod' must be an integer >= 10, got {stepsPerPeriod!r}")
        self.steps = stepsPerPeriod
        self.settings = {**ORBIT_SOLVER_SETTINGS, **(solverSettings or {})}
        self._ss, self._solver = SolverSettings(1., 1. / stepsPerPeriod, self.settings, 'ExudynFlow')
        self._ss.solution.sensors.writePeriod = 1e10         # sensors off in shooting runs
        self._ss.timeIntegration.verboseMode = 0
        C = exu.ConfigurationType
        self._C = C
        self.q0 = np.array(mbs.systemData.GetODE2Coordinates(configuration=C.Initial), dtype=float)
        #: data coordinates every solve starts from (Exudyn keeps the last solve's in the system otherwise)
        self.data0 = (np.array(mbs.systemData.GetDataCoordinates(configuration=C.Initial), dtype=float)
                      if mbs.systemData.DataSize() else None)
        self.dependent = None if dependent is None else (np.asarray(dependent[0], dtype=int),
                                                         np.asarray(dependent[1], dtype=float))
        self.calls = 0

    def StartState(self) -> np.ndarray:
        """The system's initial state in flow coordinates."""
        C = self._C
        q = np.array(self.mbs.systemData.GetODE2Coordinates(configuration=C.Initial), dtype=float)
        v = np.array(self.mbs.systemData.GetODE2Coordinates_t(configuration=C.Initial), dtype=float)
        i = self.coordinates
        return np.concatenate([q[i], v[i] - self.speeds[i]])

    def _SetInitial(self, x, restart: bool = True):
        C, i, n = self._C, self.coordinates, self.coordinates.size
        q, v = self.q0.copy(), self.speeds.copy()
        q[i], v[i] = x[:n], x[n:] + self.speeds[i]
        if self.dependent is not None:
            d, D = self.dependent
            q[d], v[d] = self.q0[d] + D @ (q - self.q0), D @ v
        self.mbs.systemData.SetODE2Coordinates(q.tolist(), configuration=C.Initial)
        self.mbs.systemData.SetODE2Coordinates_t(v.tolist(), configuration=C.Initial)
        # the discrete state must follow from x alone, else the map depends on the previous call (and the
        # finite-difference monodromy on the order of its columns): data coordinates back to their start
        # values, the worm-gear connectors' stick/slip state to the one the start implies
        for connector in self.mbs.variables.get(RIGID_CONNECTORS_KEY, []):
            connector.RestartAngles(self.mbs, q)       # the turns' reference angles from the start, not the end
        if not restart:             # go on from the previous solve's end (a long run in pieces)
            if self.data0 is not None:
                data = self.mbs.systemData.GetDataCoordinates(configuration=C.Current)
                self.mbs.systemData.SetDataCoordinates(data, configuration=C.Initial)
            end = np.array(self.mbs.systemData.GetODE2Coordinates(configuration=C.Current), dtype=float)
            for connector in self._Connectors():
                if connector.stickSlip is not None:      # the stuck flanks' anchor shifts with the coordinates
                    connector.stickSlip.Carry(self.mbs, end, q)
            return
        if self.data0 is not None:
            self.mbs.systemData.SetDataCoordinates(self.data0.tolist(), configuration=C.Initial)
        for connector in self._Connectors():
            if connector.stickSlip is not None:
                connector.stickSlip.Restart(self.mbs, q, v)

    def Solve(self, x, T: float, storeSensors: bool = False, restart: bool = True):
        """Simulate time ``T`` from flow state ``x``; returns the end state (flow coordinates).

        Parameters
        ----------
        x : array_like
            Start state (flow coordinates).
        T : float
            Simulated time in s.
        storeSensors : bool
            Keep the sensors' samples of every step.
        restart : bool
            True (default): the discrete state (data coordinates, stick/slip state of the worm-gear connectors)
            starts from the one ``x`` implies, so the result depends on ``x`` and ``T`` alone. False: it goes on
            from where the previous solve ended (``x`` must then be that solve's end state; the anchor of stuck
            flanks is shifted with the coordinates).
        """
        import exudyn as exu
        x = np.asarray(x, dtype=float)
        self._SetInitial(x, restart)
        ss = self._ss
        ss.timeIntegration.endTime = T
        ss.timeIntegration.numberOfSteps = self.steps
        ss.solution.sensors.writePeriod = T / self.steps * (1. - 1e-9) if storeSensors else 10. * T
        printing = exu.config.printToConsole
        exu.config.printToConsole = False
        try:
            ok = self.mbs.SolveDynamic(ss, solverType=self._solver)
        except Exception as err:         # Exudyn raises a RuntimeError-like error on a failed step
            raise SolverDivergedError(f"ExudynFlow: the solver failed over T = {T:g} s: {err}", float('nan'), T,
                                      T / self.steps) from err
        finally:
            exu.config.printToConsole = printing
        if ok is False:
            raise SolverDivergedError(f"ExudynFlow: the solver failed over T = {T:g} s", float('nan'), T,
                                      T / self.steps)
        self.calls += 1
        C, i = self._C, self.coordinates
        q = np.array(self.mbs.systemData.GetODE2Coordinates(configuration=C.Current), dtype=float)
        v = np.array(self.mbs.systemData.GetODE2Coordinates_t(configuration=C.Current), dtype=float)
        return np.concatenate([q[i] - self.speeds[i] * T, v[i] - self.speeds[i]])

    __call__ = Solve

    def _Connectors(self) -> list:
        """The system's worm-gear connectors, one-angle and rigid-body."""
        return list(self.mbs.variables.get(CONNECTORS_KEY, [])) + list(self.mbs.variables.get(RIGID_CONNECTORS_KEY, []))


def _HeldCoordinates(mbs) -> List[int]:
    """ODE2 coordinates held by a coordinate constraint (``ObjectConnectorCoordinate``, e.g. a motor prescribed by
    :func:`~exudyn_worm.items.drivetrain.CreatePrescribedRotation`)."""
    owner = {node: first for first, (node, column) in _CoordinateOwners(mbs).items() if column == 0}
    held = []
    for i in range(mbs.systemData.NumberOfObjects()):
        item = mbs.GetObject(i)
        if item.get('objectType') != 'ConnectorCoordinate':
            continue
        for m in item['markerNumbers']:
            marker = mbs.GetMarker(m)
            if marker.get('markerType') == 'NodeCoordinate' and int(marker['nodeNumber']) in owner:
                held.append(owner[int(marker['nodeNumber'])] + int(marker['coordinate']))
    return sorted(set(held))
