"""Steady chatter of the reel changer's lowering phase as a periodic orbit of the Exudyn model itself.

The lowering phase is modelled as the linear analysis sees it: the motor turns at constant speed
``motorSpeed`` and the wheel carries the constant load torque ``loadMass * g * leverArm`` that drives it
forward (the reel changer's load -m g l cos(phi2) at phi2 = pi, the middle of the lowering phase). With the
angles taken relative to the steady rotation (``phi - omega t``) and the speeds relative to the steady speeds,
the drive is then autonomous, and the steady chatter is a periodic orbit in the state
``(phi1 - omega1 t, phi2 - omega2 t, phi1' - omega1, phi2' - omega2)``, extended by every other free coordinate
of the drive (drive-side and load-side chain rotors, the worm's axial coordinate: :func:`BuildLoweringModel`).
:func:`SteadyChatterOfSystem` does the same for your own Exudyn system with a worm-gear connector.

:class:`ExudynFlow` is the one-period map of any Exudyn system: set the initial state, ``mbs.SolveDynamic``
over time T (fixed number of steps), read the end state. :func:`FindSteadyChatter` starts from a short time
simulation that has settled (or from the unstable eigenvector of the linearization) and shoots
(:func:`~exudyn_worm.analysis.orbits.FindPeriodicOrbit`). :func:`OrbitAmplitude` simulates the converged orbit once and
reports the largest normal-force factor (largest normal force / static normal force) and the largest
``|phi2''|``.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np

from ..model.contact import ContactOptions
from ..model.friction import MATH_OPS
from .orbits import FindPeriodicOrbit, PeriodicOrbit, ShootingError
from ..model.profiles import STANDARD_GRAVITY, ConstantSpeed, ConstantTorque, GravityLeverTorque
from .._checks import CheckPositive, CheckReal, CheckSystem
from ..items.connector import CONNECTORS_KEY, WormGearConnector
from .linearization import AnalyzeLinearStability
from .drivestability import DriveStability
from ..setups.wholedrive import Component
from ..setups.duty import IsReelChangerDuty
from ..setups.presets import (DUTY_KEYS, REEL_KEYS, AxialBearingFromParameters, ElasticDriveFromParameters,
                              DriveSideChain, LoadSideChain)
from .reelchanger import SOLVER_SETTINGS, SolverSettings
from ..setups.build import BuildReelChanger, CheckReelChangerKeys
from ..items.equilibrium import SteadyInitialState
from ..items.solve import SolverDivergedError

__all__ = ['LoweringModel', 'BuildLoweringModel', 'ExudynFlow', 'FindSteadyChatter',
           'OrbitAmplitude', 'SettleLowering', 'EquilibriumState', 'StateScale', 'LongSimulationAmplitude', 'UpdateLoweringModel', 'IN_PLACE_KEYS', 'STEPS_PER_PERIOD', 'ORBIT_SOLVER_SETTINGS',
           'LoweringModelOfSystem', 'SteadyChatterOfSystem', 'MONODROMY_PERTURBATION',
           'SettledSimulationAmplitude', 'LoweringPhaseParameters', 'LOWERING_LEVER_ARM']

#: solver steps per chatter period of the shooting runs: at P1 the force factor, largest ``|phi2''|`` and frequency
#: change by less than 0.04 % between 150 and 1600 steps (2.6157/102.29/40.525 at 150, 2.6149/102.28/40.535 at
#: 800), but with 0.5 mm backlash (J1 = 0.25, the worm crosses the gap) shooting does not converge at 200 or 300
#: steps (the map is too rough); measured, docs/chatter-amplitude.md
STEPS_PER_PERIOD = 400
#: relative step (of :func:`StateScale`) of the central differences for an orbit's monodromy matrix: the fixed-step
#: integrator resolves the force jump where the mesh changes flank only to a step, which leaves a sawtooth on the
#: one-period map; steps of 1e-6 see its slope (trivial multiplier 1.005-1.03 at P1 for 150-1600 steps per
#: period), 0.05 spans a few solver steps and averages it out (1.001-1.003), 0.1 and more see the map's curvature
#: (measured, docs/chatter-amplitude.md)
MONODROMY_PERTURBATION = 0.05
#: generalized-alpha settings of the shooting runs: Newton with a tight tolerance, so that the one-period map is
#: smooth enough for finite differences of 1e-6; modified Newton (the Jacobian kept while it converges) gives the
#: same end state to 4e-12 of the state scale in half the time of full Newton (P1, measured)
ORBIT_SOLVER_SETTINGS = {'timeIntegration.newton.useModifiedNewton': True,
                         'timeIntegration.newton.relativeTolerance': 1e-11,
                         'timeIntegration.newton.absoluteTolerance': 1e-11,
                         'timeIntegration.newton.maxIterations': 12,
                         'timeIntegration.generalizedAlpha.spectralRadius': 0.8}


@dataclass
class LoweringModel:
    """The Exudyn model of the lowering phase and what the shooting needs to know about it.

    Parameters
    ----------
    systemContainer : exudyn.SystemContainer
        Keeps the system alive.
    mbs : exudyn.MainSystem
        The system.
    drive : ElasticDrive
        The two-mass drive of the parameter set.
    connector : WormGearConnector
        The mesh.
    rotors : dict of str to dict
        Motor, worm and wheel rotors (:func:`~exudyn_worm.items.drivetrain.CreateRotor`).
    steady : dict of str to float
        The steady state of lowering (:func:`~exudyn_worm.items.equilibrium.SteadyInitialState`).
    motorSpeed : float
        Motor speed in rad/s.
    loadTorque : float
        Constant load torque on the wheel in N*m (loadMass g leverArm, lowering).
    staticNormalForce : float
        Normal force of the steady state in N.
    contactOptions : ContactOptions
        Options of the contact law.
    parameters : dict of str to float
        The flat parameter set the model was built from (empty for :func:`LoweringModelOfSystem`).
    coordinates : tuple of int
        ODE2 coordinate indices of the flow state: the worm's, the wheel's, then every other free coordinate
        (drive-side and load-side chain rotors, the worm's axial coordinate, ...).
    steadySpeeds : ndarray
        Steady speed of every ODE2 coordinate of ``mbs`` (rad/s or m/s; 0 for a coordinate at rest).
    stateKeys : tuple of str
        Key of ``steady`` that holds the equilibrium position of each coordinate of ``coordinates``.
    initialCoordinates : ndarray
        ODE2 coordinates of the steady state at t = 0 (a prescribed motor's angle among them).
    nodeSensors : tuple of (int, int, int)
        Per coordinate of ``coordinates``: the node sensors of its node's positions and velocities and the
        coordinate's column in them.
    """
    systemContainer: Any
    mbs: Any
    drive: Any
    connector: Any
    rotors: Dict[str, Dict]
    steady: Dict[str, float]
    motorSpeed: float
    loadTorque: float
    staticNormalForce: float
    contactOptions: ContactOptions
    parameters: Dict[str, float]
    coordinates: Tuple[int, ...] = ()
    steadySpeeds: Any = None
    stateKeys: Tuple[str, ...] = ()
    initialCoordinates: Any = None
    nodeSensors: Tuple[Tuple[int, int, int], ...] = ()


#: lever arm in m with which :func:`LoweringPhaseParameters` writes a drive's lowering load torque as the reel keys
#: (the periodic-orbit analysis takes only their product ``loadMass * g * leverArm``, a constant torque)
LOWERING_LEVER_ARM = 1.


def LoweringPhaseParameters(parameters: Mapping[str, float]) -> Dict[str, float]:
    """The parameter set of the periodic-orbit analysis for any drive: the lowering phase of its own duty.

    The analysis follows the chatter of steady lowering: the motor at constant speed, a constant load torque that
    drives the gear (the reel keys ``motorSpeed``, ``loadMass``, ``leverArm``). The reel changer's duty is taken as it
    is. Any other duty is replaced by its lowering operating point
    (:func:`~exudyn_worm.setups.operatingpoints.DutyOperatingPoints`, S = -1; of several, the one with the largest
    real part at which the linear analysis, :func:`~exudyn_worm.analysis.drivestability.AnalyzeDrive`, puts it): the
    speed's magnitude as ``motorSpeed`` and its load torque as ``loadMass * g * leverArm`` with
    ``leverArm`` = :data:`LOWERING_LEVER_ARM` (a drive turning backwards while lowering is its mirror image).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set of the drive.

    Returns
    -------
    dict
        A flat parameter set with the reel changer's duty keys.

    Raises
    ------
    ValueError
        If the drive has no lowering phase, or a motor on its characteristic (the analysis holds the motor).
    """
    w = 'LoweringPhaseParameters'
    if parameters.get('motorType') == 'characteristic':
        raise ValueError(f"{w}: the periodic-orbit analysis holds the motor at constant speed (the lowering phase of "
                         f"the linear analysis); this parameter set has {Component.MOTOR_CHARACTERISTIC.text} (not "
                         f"supported); leave those keys out")
    if IsReelChangerDuty(parameters) and all(k in parameters for k in REEL_KEYS):
        return dict(parameters)
    analysis = DriveStability(parameters)
    lowering = [p for p in analysis.operatingPoints if p.S == -1]
    if not lowering:
        raise ValueError(f"{w}: the drive's duty has no lowering phase at a steady speed (no phase in which the load "
                         f"drives the gear; {analysis.decidingText}); the periodic-orbit analysis follows the chatter "
                         f"of lowering")
    point = max(lowering, key=lambda p: p.maxRealPart).point
    out = {k: v for k, v in parameters.items() if k not in DUTY_KEYS}
    out.update(motorSpeed=abs(point.motorSpeed), leverArm=LOWERING_LEVER_ARM,
               loadMass=abs(point.loadTorque) / (STANDARD_GRAVITY * LOWERING_LEVER_ARM))
    return out


def BuildLoweringModel(parameters: Mapping[str, float], contactOptions: ContactOptions = ContactOptions(),
                       useSymbolic: bool = True) -> LoweringModel:
    """Exudyn model of the reel changer's lowering phase: motor at constant speed, constant load torque
    ``loadMass * g * leverArm`` driving the wheel (the last rotor of a load-side chain), starting in the steady
    state (static mesh deflection, every shaft of the chains pre-twisted by the torque it carries).

    The system is the time simulation's own (:func:`~exudyn_worm.setups.build.BuildReelChanger` with the duty
    ``loadType = constant``, ``loadTorque = loadMass * g * leverArm`` and the motor at ``motorSpeed``), so the
    drive-side chain (``J4, k4, d4, ...``), the load-side chain (``JL1, kL1, dL1, ...``) and the worm's axial
    bearing (``kA, dA, mA``) are built as a simulation builds them. The flow state holds every free ODE2
    coordinate (``LoweringModel.coordinates``).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set with the reel changer's keys (e.g. ``GetPreset('reel-P1')``), with or without the
        chains and the axial bearing; a motor on its characteristic (``motorType = characteristic``) is refused.
    contactOptions : ContactOptions
        Options of the contact law.
    useSymbolic : bool
        Symbolic (C++) user functions (default) or plain Python.

    Returns
    -------
    LoweringModel

    Raises
    ------
    ValueError, TypeError
        For a bad parameter set, or one with a component the lowering model does not have (a motor on its
        characteristic: the lowering phase holds the motor at constant speed).
    """
    w = 'BuildLoweringModel'
    CheckReelChangerKeys(parameters, w)
    if parameters.get('motorType') == 'characteristic':
        raise ValueError(f"{w}: the periodic-orbit analysis holds the motor at constant speed 'motorSpeed' (the "
                         f"lowering phase of the linear analysis); this parameter set has "
                         f"{Component.MOTOR_CHARACTERISTIC.text} (not supported); leave those keys out")
    if not isinstance(contactOptions, ContactOptions):
        raise TypeError(f"{w}: 'contactOptions' must be a ContactOptions, got {type(contactOptions).__name__}")
    drive = ElasticDriveFromParameters(parameters)
    motorSpeed = CheckPositive(w, 'motorSpeed', parameters['motorSpeed'], 'rad/s')
    loadTorque = GravityLeverTorque(mass=parameters['loadMass'], leverArm=parameters['leverArm']).maximum
    # the time simulation's builder, with the lowering phase as its duty: one assembly of the chains
    reel = BuildReelChanger({**parameters, 'loadType': 'constant', 'loadTorque': loadTorque}, contactOptions,
                            useSymbolic, startFromEquilibrium=True, profile=ConstantSpeed(motorSpeed))
    mbs = reel.mbs
    mbs.Assemble()                                  # coordinate indices and sizes exist from here on
    steady = _SteadyState(drive, parameters, loadTorque, motorSpeed, contactOptions)
    # the flow state: worm, wheel, then the chains' rotors and the worm's axial coordinate, each with the key of
    # its equilibrium position in ``steady`` (SteadyInitialState's names) and of its steady speed
    nodes = [(reel.rotors['worm'], 'phi1', 'omega1'), (reel.rotors['wheel'], 'phi2', 'omega2')]
    nodes += [(reel.rotors[f'inertia{i}'], f'phi{i}', f'omega{i}') for i in range(4, 4 + len(reel.chain))]
    nodes += [(reel.rotors[f'loadInertia{i}'], f'phiL{i}', f'omegaL{i}') for i in range(1, 1 + len(reel.loadChain))]
    if reel.axialBearing is not None:
        nodes.append((reel.axialBearing, 'xA', 'vA'))
    index = [mbs.GetNodeODE2Index(node['nodeNumber']) for node, _, _ in nodes]
    speeds = np.zeros(mbs.systemData.ODE2Size())
    speeds[mbs.GetNodeODE2Index(reel.rotors['motor']['nodeNumber'])] = motorSpeed
    speeds[index] = [steady[v] for _, _, v in nodes]
    sensors = _AddFlowSensors(mbs, index)
    mbs.Assemble()
    static = _MeshAt(reel.connector, steady)
    rotors = {**reel.rotors, 'driveShaft': {'objectNumber': mbs.GetObjectNumber('driveShaft')}}
    initial = np.array(mbs.systemData.GetODE2Coordinates(configuration=_Configuration().Initial), dtype=float)
    return LoweringModel(reel.systemContainer, mbs, drive, reel.connector, rotors, steady, motorSpeed, loadTorque,
                         abs(float(static.normalForce)), contactOptions, dict(parameters), tuple(index), speeds,
                         tuple(p for _, p, _ in nodes), initial, sensors)


def _Configuration():
    import exudyn as exu
    return exu.ConfigurationType


def _SteadyState(drive, parameters: Mapping[str, float], loadTorque: float, motorSpeed: float,
                 contactOptions: ContactOptions) -> Dict[str, float]:
    """The steady state of lowering with the parameter set's chains and axial bearing, as
    :func:`~exudyn_worm.setups.build.BuildReelChanger` starts its system."""
    return SteadyInitialState(drive, ConstantTorque(loadTorque), motorSpeed, contactOptions,
                              AxialBearingFromParameters(parameters), tuple(DriveSideChain(parameters)),
                              loadSide=tuple(LoadSideChain(parameters)))


def _MeshAt(connector, state: Mapping[str, Any], mask=None):
    """The connector's mesh quantities for the states in ``state`` (keys ``phi1, phi2, omega1, omega2`` and, with
    an axial node, ``xA, vA``: a steady state or stored sensor series), at ``mask`` (None: all)."""
    keys = ('phi1', 'phi2', 'omega1', 'omega2') + (() if connector.axialNodeNumber is None else ('xA', 'vA'))
    values = [np.asarray(state[k]) if mask is None else np.asarray(state[k])[mask] for k in keys]
    return connector.Evaluate(*values)


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


def _StoredFlowStates(model: LoweringModel) -> Tuple[np.ndarray, np.ndarray]:
    """Times (s, from the start of the last solve) and flow states (one row per stored step) of the last solve
    with stored sensors."""
    data = {s: np.asarray(model.mbs.GetSensorStoredData(s)) for sensors in model.nodeSensors for s in sensors[:2]}
    t = data[model.nodeSensors[0][0]][:, 0]
    q = np.column_stack([data[p][:, 1 + c] for p, _, c in model.nodeSensors])
    v = np.column_stack([data[u][:, 1 + c] for _, u, c in model.nodeSensors])
    speeds = model.steadySpeeds[np.asarray(model.coordinates)]
    return t, np.hstack([q - np.outer(t, speeds), v - speeds])


#: parameters that :func:`UpdateLoweringModel` changes in the built system (others rebuild it)
IN_PLACE_KEYS = ('J1', 'J2', 'kT', 'DT', 'dT', 'DTV')


def UpdateLoweringModel(model: LoweringModel, parameters: Mapping[str, float]) -> LoweringModel:
    """The lowering model for ``parameters``: ``model`` changed in place if only :data:`IN_PLACE_KEYS` differ
    (inertias, shaft stiffness and damping), else a new model.

    Parameters
    ----------
    model : LoweringModel
    parameters : mapping
        The new flat parameter set.

    Returns
    -------
    LoweringModel
    """
    changed = {k for k in set(parameters) | set(model.parameters) if parameters.get(k) != model.parameters.get(k)}
    if not changed:
        return model
    if not changed <= set(IN_PLACE_KEYS):
        return BuildLoweringModel(parameters, model.contactOptions)
    drive = ElasticDriveFromParameters(parameters)
    mbs = model.mbs
    mbs.SetObjectParameter(model.rotors['worm']['objectNumber'], 'inertia', drive.J1)
    mbs.SetObjectParameter(model.rotors['wheel']['objectNumber'], 'inertia', drive.J2)
    mbs.SetObjectParameter(model.rotors['driveShaft']['objectNumber'], 'stiffness', drive.kT)
    mbs.SetObjectParameter(model.rotors['driveShaft']['objectNumber'], 'damping', drive.dT)
    mbs.Assemble()
    model.drive, model.parameters = drive, dict(parameters)
    model.steady = _SteadyState(drive, parameters, model.loadTorque, model.motorSpeed, model.contactOptions)
    return model


class ExudynFlow:
    """One-period map of an Exudyn system relative to a steady rotation: ``flow(x, T) -> x(T)``.

    The state ``x`` holds, for the ODE2 coordinates ``coordinates``, the positions minus ``steadySpeeds * t``,
    then the velocities minus ``steadySpeeds``. Coordinates not in ``coordinates`` (e.g. a prescribed motor)
    start at their position ``fixedPositions`` (default: the system's initial values) and steady speed.
    The discrete state is not part of ``x``: every solve starts with the data coordinates the system had when
    the flow was made and with the stick/slip state of each worm-gear connector that the start implies
    (sliding in the direction of the worm's speed, :meth:`~exudyn_worm.items.connector._StickSlip.Restart`), so
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
    """

    def __init__(self, mbs: Any, coordinates: Sequence[int], steadySpeeds: Sequence[float],
                 stepsPerPeriod: int = STEPS_PER_PERIOD, solverSettings: Optional[Mapping[str, Any]] = None):
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
        self.mbs.systemData.SetODE2Coordinates(q.tolist(), configuration=C.Initial)
        self.mbs.systemData.SetODE2Coordinates_t(v.tolist(), configuration=C.Initial)
        # the discrete state must follow from x alone, else the map depends on the previous call (and the
        # finite-difference monodromy on the order of its columns): data coordinates back to their start
        # values, the worm-gear connectors' stick/slip state to the one the start implies
        if not restart:             # go on from the previous solve's end (a long run in pieces)
            if self.data0 is not None:
                data = self.mbs.systemData.GetDataCoordinates(configuration=C.Current)
                self.mbs.systemData.SetDataCoordinates(data, configuration=C.Initial)
            end = np.array(self.mbs.systemData.GetODE2Coordinates(configuration=C.Current), dtype=float)
            for connector in self.mbs.variables.get(CONNECTORS_KEY, []):
                if connector.stickSlip is not None:      # the stuck flanks' anchor shifts with the coordinates
                    connector.stickSlip.Carry(self.mbs, end, q)
            return
        if self.data0 is not None:
            self.mbs.systemData.SetDataCoordinates(self.data0.tolist(), configuration=C.Initial)
        for connector in self.mbs.variables.get(CONNECTORS_KEY, []):
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
            raise SolverDivergedError(f"ExudynFlow: the solver failed over T = {T:g} s: {err}") from err
        finally:
            exu.config.printToConsole = printing
        if ok is False:
            raise SolverDivergedError(f"ExudynFlow: the solver failed over T = {T:g} s")
        self.calls += 1
        C, i = self._C, self.coordinates
        q = np.array(self.mbs.systemData.GetODE2Coordinates(configuration=C.Current), dtype=float)
        v = np.array(self.mbs.systemData.GetODE2Coordinates_t(configuration=C.Current), dtype=float)
        return np.concatenate([q[i] - self.speeds[i] * T, v[i] - self.speeds[i]])

    __call__ = Solve


def _LoweringFlow(model: LoweringModel, stepsPerPeriod: int,
                  solverSettings: Optional[Mapping[str, Any]] = None) -> ExudynFlow:
    flow = ExudynFlow(model.mbs, model.coordinates, model.steadySpeeds, stepsPerPeriod, solverSettings=solverSettings)
    flow.q0 = np.array(model.initialCoordinates, dtype=float)     # coordinates outside the state (the motor)
    return flow


def SettleLowering(model: LoweringModel, duration: float, kick: float = 0.01, stepSize: float = 1e-4,
                   store: bool = False) -> Tuple[np.ndarray, 'ExudynFlow']:
    """Time simulation of the lowering phase from the steady state with the worm speed kicked by ``kick``
    (relative to the motor speed); returns the flow state at the end and the flow used.

    Parameters
    ----------
    model : LoweringModel
    duration : float
        Simulated time in s.
    kick : float
        Initial worm speed disturbance as a fraction of the motor speed.
    stepSize : float
        Time step in s.
    store : bool
        Keep the sensors' samples of every step (read them with ``model.connector.StoredStates(model.mbs)``).

    Returns
    -------
    (ndarray, ExudynFlow)
    """
    steps = max(10, int(round(duration / stepSize)))
    flow = _LoweringFlow(model, steps)
    x = EquilibriumState(model)
    x[len(model.coordinates)] += kick * model.motorSpeed          # the worm's speed
    return flow.Solve(x, duration, storeSensors=store), flow


def EquilibriumState(model: LoweringModel) -> np.ndarray:
    """The static equilibrium of the lowering phase in flow coordinates (relative angles, speed deviations 0).

    Parameters
    ----------
    model : LoweringModel
    """
    return np.concatenate([[model.steady[k] for k in model.stateKeys], np.zeros(len(model.coordinates))])


def _PeriodFromSignal(t, y) -> float:
    """Median time between upward mean crossings of ``y``, with hysteresis (a crossing counts only after the
    signal has been below the mean by a quarter of its half swing), so that harmonics add no crossings."""
    y = y - np.mean(y)
    band = 0.25 * 0.5 * np.ptp(y)
    crossings, armed = [], False
    for k in range(1, y.size):
        if y[k] < -band:
            armed = True
        elif armed and y[k - 1] < 0 <= y[k]:
            crossings.append(t[k - 1] - y[k - 1] * (t[k] - t[k - 1]) / (y[k] - y[k - 1]))
            armed = False
    if len(crossings) < 3:
        return math.nan
    return float(np.median(np.diff(crossings[-6:])))


def OrbitAmplitude(model: LoweringModel, flow: ExudynFlow, state: Sequence[float], period: float) -> Dict[str, float]:
    """Simulate one period of the orbit and measure it.

    Parameters
    ----------
    model : LoweringModel
    flow : ExudynFlow
    state : array_like
        Orbit start in flow coordinates.
    period : float
        Period in s.

    Returns
    -------
    dict
        ``forceFactor`` (largest normal force over the static normal force), ``maxWheelAcceleration`` (largest
        ``|phi2''|`` in rad/s^2), ``minWormSpeed`` (rad/s).
    """
    flow.Solve(state, period, storeSensors=True)
    s = model.connector.StoredStates(model.mbs)
    mesh = _MeshAt(model.connector, s)
    return {'forceFactor': float(np.max(np.abs(mesh.normalForce)) / model.staticNormalForce),
            'maxWheelAcceleration': float(np.max(np.abs(s['alpha2']))),
            'minWormSpeed': float(np.min(s['omega1']))}


def FindSteadyChatter(parameters: Mapping[str, float], settleTime: float = 1.0, stepsPerPeriod: int = STEPS_PER_PERIOD,
                      contactOptions: ContactOptions = ContactOptions(), start: Optional[Any] = None, maxIterations: int = 30,
                      tolerance: float = 1e-8, model: Optional[LoweringModel] = None, kick: float = 0.01,
                      initialState: Optional[Sequence[float]] = None) -> PeriodicOrbit:
    """Steady chatter of the lowering phase: the periodic orbit of the Exudyn model, by shooting.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set with the reel changer's keys (e.g. ``GetPreset('reel-P1')``).
    settleTime : float
        Duration in s of the time simulation (from the steady state, worm speed kicked by 1 %) whose end is
        the first guess, if ``start`` is not given.
    stepsPerPeriod : int
        Solver steps per period in the shooting runs.
    contactOptions : ContactOptions
        Options of the contact law.
    start : (array_like, float), optional
        Start guess ``(state, period)`` in flow coordinates (e.g. the previous orbit of a continuation).
    maxIterations : int
        Newton steps at most.
    tolerance : float
        Shooting tolerance (relative to the state scale).
    model : LoweringModel, optional
        A model already built from ``parameters``.
    kick : float
        Initial worm-speed disturbance of the settling simulation, as a fraction of the motor speed (a large one
        finds chatter that coexists with a stable rest).
    initialState : array_like, optional
        Flow state the settling simulation starts from instead of the kicked equilibrium (e.g. an orbit of a
        neighbouring parameter value).

    Returns
    -------
    PeriodicOrbit
        ``info`` holds ``forceFactor``, ``maxWheelAcceleration``, ``minWormSpeed``, ``model`` and ``flow``.

    Raises
    ------
    ShootingError
        If the settled simulation does not oscillate (the drive is at rest: no chatter to find) or Newton fails.
    """
    model = BuildLoweringModel(parameters, contactOptions) if model is None else model
    return _FindChatter(model, 'FindSteadyChatter', 'the lowering phase', settleTime, stepsPerPeriod, start,
                        maxIterations, tolerance, kick, initialState)


def _LinearlyStable(model: LoweringModel) -> bool:
    """The linear verdict at the model's steady state: :func:`~exudyn_worm.analysis.drivestability.DriveStability` (S = -1,
    lowering) for a parameter set; for a user's system its own linearization in the contact state of its steady
    state (False if it cannot be linearized there, so that a drive is never called at rest on that ground)."""
    if model.parameters:
        return bool(DriveStability(model.parameters).State(-1).stable)
    S = int(np.sign(float(_MeshAt(model.connector, model.steady).S))) or -1
    mbs, C = model.mbs, _Configuration()
    mbs.systemData.SetODE2Coordinates(model.initialCoordinates.tolist(), configuration=C.Initial)
    mbs.systemData.SetODE2Coordinates_t(model.steadySpeeds.tolist(), configuration=C.Initial)
    try:
        return bool(AnalyzeLinearStability(mbs, [model.connector], contactStates=[(S,)]).State(S).stable)
    except ValueError:              # e.g. the mesh is not in contact at the steady state
        return False


def _FindChatter(model: LoweringModel, where: str, what: str, settleTime: float, stepsPerPeriod: int,
                 start: Optional[Any], maxIterations: int, tolerance: float, kick: float,
                 initialState: Optional[Sequence[float]]) -> PeriodicOrbit:
    """:func:`FindSteadyChatter` on a built model (``what`` names the system in messages)."""
    w = where
    scale = StateScale(model)
    if start is None:
        CheckPositive(w, 'settleTime', settleTime, 's')
        # settle, then record a few periods to estimate the period
        if initialState is None:
            x, _ = SettleLowering(model, settleTime, kick=kick)
        else:
            x = _LoweringFlow(model, max(10, int(round(settleTime / 1e-4)))).Solve(np.asarray(initialState, float),
                                                                               settleTime)
        probe = _LoweringFlow(model, 4000)
        x = probe.Solve(x, 0.4, storeSensors=True)
        s = model.connector.StoredStates(model.mbs)
        quarter = len(s['omega1']) // 4
        first, swing = np.ptp(s['omega1'][:quarter]), np.ptp(s['omega1'][-quarter:])
        tail = _MeshAt(model.connector, s, slice(-quarter, None))
        inContact = float(np.max(np.abs(tail.normalForce))) < 2. * model.staticNormalForce
        # rest: no swing left, or a linearly stable drive whose swing shrinks while the mesh stays in contact
        if not swing > 1e-4 * model.motorSpeed or (inContact and swing < 0.95 * first and _LinearlyStable(model)):
            raise ShootingError(f"{w}: {what} settles to rest (after {settleTime:g} s the worm speed swing "
                                f"still shrinks, {first:.3g} -> {swing:.3g} rad/s in 0.3 s, the mesh stays in contact): "
                                f"no steady chatter at these parameters (a larger disturbance may still start one "
                                f"where rest and chatter coexist)")
        period = _PeriodFromSignal(s['time'], s['omega1'])
        # start where the mesh is deepest in contact in the last period: far from the switches of the law
        # (contact loss, clipped force), so the finite-difference monodromy does not straddle one
        t = s['time']
        last = np.nonzero(t >= t[-1] - period)[0]
        if np.min(s['omega1'][last]) <= 0.:
            # the worm turns back (and may stick) within the period: start where it clearly slides forward, since
            # every shooting run starts sliding in the direction of the worm's speed (ExudynFlow)
            last = last[s['omega1'][last] >= 0.5 * np.max(s['omega1'][last])]
        mesh = _MeshAt(model.connector, s, last)
        k = last[int(np.argmax(np.abs(mesh.normalForce)))]
        x = _StoredFlowStates(model)[1][k]
    else:
        x, period = np.asarray(start[0], dtype=float), float(start[1])
    flow = _LoweringFlow(model, stepsPerPeriod)
    orbit = FindPeriodicOrbit(flow, x, period, stateScale=scale, maxIterations=maxIterations, tolerance=tolerance,
                              monodromyPerturbation=MONODROMY_PERTURBATION, where=w)
    orbit.info.update(OrbitAmplitude(model, flow, orbit.state, orbit.period), model=model, flow=flow)
    return orbit


def StateScale(model: LoweringModel) -> np.ndarray:
    """Typical size of the flow state's components: the static mesh deflection as angles (each coordinate's in
    proportion to its steady speed: the worm's, the wheel's divided by the ratio; a coordinate at rest, such as
    the worm's axial one, the deflection as a length), times the chatter angular frequency (2 pi 40 Hz) as speeds.

    Parameters
    ----------
    model : LoweringModel
        The lowering model (its gear, static normal force and steady speeds).
    """
    g = model.connector.gear
    deflection = max(model.staticNormalForce / g.kV, 1e-9) / g.normalLever         # worm angle of the deflection
    speeds = np.abs(model.steadySpeeds[np.asarray(model.coordinates)])
    angles = np.where(speeds > 0, deflection * speeds / speeds[0], deflection * g.normalLever)
    return np.concatenate([angles, angles * 2 * math.pi * 40.])


def LongSimulationAmplitude(parameters: Mapping[str, float], duration: float = 3.0, stepSize: float = 1e-4,
                            kick: float = 0.01, window: float = 0.25,
                            contactOptions: ContactOptions = ContactOptions(),
                            initialState: Optional[Sequence[float]] = None,
                            model: Optional[LoweringModel] = None) -> Dict[str, float]:
    """Steady amplitude of the lowering phase by brute force: a long time simulation with the time simulations'
    solver settings (:data:`~exudyn_worm.analysis.reelchanger.SOLVER_SETTINGS`: modified Newton, tolerance 1e-6), measured
    over its last ``window`` seconds; the check of the orbits found by shooting.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set with the reel changer's keys.
    duration : float
        Simulated time in s.
    stepSize : float
        Time step in s.
    kick : float
        Initial worm speed disturbance as a fraction of the motor speed.
    window : float
        Final part of the run in s over which the amplitude is measured.
    contactOptions : ContactOptions
        Options of the contact law.
    initialState : array_like, optional
        Flow state to start from (the worm-speed ``kick`` is added to it) instead of the equilibrium, e.g. a
        point of an orbit where rest and chatter coexist.
    model : LoweringModel, optional
        A model to simulate instead of one built from ``parameters`` (e.g. :func:`LoweringModelOfSystem`: then
        ``parameters`` is not read).

    Returns
    -------
    dict
        ``forceFactor``, ``maxWheelAcceleration`` (rad/s^2), ``frequencyHz`` (nan at rest), ``seconds`` (solver time).
    """
    w = 'LongSimulationAmplitude'
    duration = CheckPositive(w, 'duration', duration, 's')
    stepSize = CheckPositive(w, 'stepSize', stepSize, 's')
    window = CheckPositive(w, 'window', window, 's')
    model = BuildLoweringModel(parameters, contactOptions) if model is None else model
    steps = max(10, int(round(duration / stepSize)))
    flow = _LoweringFlow(model, steps, SOLVER_SETTINGS)
    x = EquilibriumState(model) if initialState is None else np.array(initialState, dtype=float)
    x[len(model.coordinates)] += kick * model.motorSpeed          # the worm's speed
    t0 = time.perf_counter()
    flow.Solve(x, duration, storeSensors=True)
    seconds = time.perf_counter() - t0
    return {**_TailAmplitude(model, window), 'seconds': seconds}


def _TailAmplitude(model: LoweringModel, window: float) -> Dict[str, float]:
    """Amplitude of the last ``window`` s of the stored run: force factor, largest |phi2''|, frequency, and the
    spread of the force factor's per-period peaks (relative to the largest: 0 for a periodic motion)."""
    s = model.connector.StoredStates(model.mbs)
    t = s['time']
    last = t >= t[-1] - window
    mesh = _MeshAt(model.connector, s, last)
    factor = np.abs(mesh.normalForce) / model.staticNormalForce
    period = _PeriodFromSignal(t[last], s['omega1'][last])
    spread = math.nan
    if np.isfinite(period):
        k = np.floor((t[last] - t[last][0]) / period).astype(int)
        peaks = [np.max(factor[k == j]) for j in range(int(k[-1]))]       # whole periods only
        spread = float(1. - min(peaks) / max(peaks)) if len(peaks) > 1 else math.nan
    return {'forceFactor': float(np.max(factor)), 'maxWheelAcceleration': float(np.max(np.abs(s['alpha2'][last]))),
            'frequencyHz': 1. / period, 'peakSpread': spread}


def SettledSimulationAmplitude(parameters: Mapping[str, float], maxDuration: float = 300., piece: float = 2.,
                               rate: float = 5e-4, stepSize: float = 2e-4, kick: float = 0.01, window: float = 0.25,
                               contactOptions: ContactOptions = ContactOptions()) -> Dict[str, float]:
    """Steady amplitude of the lowering phase by a time simulation from rest (worm speed kicked by ``kick``) that
    runs until it has settled: as :func:`LongSimulationAmplitude` (the time simulations' solver settings), but
    in pieces of ``piece`` s, stopped when the force factor and the largest ``|phi2''|`` over the last
    ``window`` s changed by less than ``rate`` (relative) per second since the previous piece, or at
    ``maxDuration``. Near a Hopf point the chatter grows and settles slowly (in proportion to the distance
    from it), so a run of fixed length may stop long before the steady state.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set with the reel changer's keys.
    maxDuration : float
        Longest simulated time in s.
    piece : float
        Simulated time in s between two looks at the amplitude (> ``window``).
    rate : float
        Settled when the amplitudes change by less than this fraction per second.
    stepSize : float
        Time step in s.
    kick : float
        Initial worm speed disturbance as a fraction of the motor speed.
    window : float
        Final part of each piece in s over which the amplitude is measured.
    contactOptions : ContactOptions
        Options of the contact law.

    Returns
    -------
    dict
        ``forceFactor``, ``maxWheelAcceleration`` (rad/s^2), ``frequencyHz``, ``peakSpread`` (1 - smallest /
        largest per-period peak of the force factor in the last window: 0 for a periodic motion),
        ``settled`` (bool), ``duration`` (simulated s), ``change`` (the last relative change per second),
        ``seconds`` (solver time).
    """
    w = 'SettledSimulationAmplitude'
    maxDuration = CheckPositive(w, 'maxDuration', maxDuration, 's')
    window = CheckPositive(w, 'window', window, 's')
    piece = CheckPositive(w, 'piece', piece, 's')
    rate = CheckPositive(w, 'rate', rate, '1/s')
    stepSize = CheckPositive(w, 'stepSize', stepSize, 's')
    if piece <= window:
        raise ValueError(f"{w}: 'piece' must be longer than 'window' ({window:g} s), got {piece:g} s")
    model = BuildLoweringModel(parameters, contactOptions)
    steps = max(10, int(round(piece / stepSize)))
    flow = _LoweringFlow(model, steps, SOLVER_SETTINGS)
    x = EquilibriumState(model)
    x[len(model.coordinates)] += kick * model.motorSpeed          # the worm's speed
    t0, duration, before, change, settled = time.perf_counter(), 0., None, math.inf, False
    while duration < maxDuration and not settled:
        x = flow.Solve(x, piece, storeSensors=True, restart=duration == 0.)     # one run, in pieces
        duration += piece
        now = _TailAmplitude(model, window)
        if before is not None:
            change = max(abs(now[k] / before[k] - 1.) for k in ('forceFactor', 'maxWheelAcceleration')) / piece
            settled = change < rate
        before = now
    return {**now, 'settled': settled, 'duration': duration, 'change': change,
            'seconds': time.perf_counter() - t0}


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


def LoweringModelOfSystem(mbs: Any, connector: WormGearConnector,
                          coordinates: Optional[Sequence[int]] = None) -> LoweringModel:
    """The model the orbit functions work on, for your own Exudyn system with a worm-gear connector.

    The system must be autonomous relative to its steady rotation, as the lowering phase is: motors held at
    constant speed, loads constant (not depending on angles or time), and it must start in that steady state:
    every coordinate at its steady speed (its initial velocity), the mesh deflected by the load and every shaft
    pre-twisted by the torque it carries (:func:`~exudyn_worm.items.equilibrium.SteadyInitialState`). The flow state
    is then ``(q - v0 t, q' - v0)`` over ``coordinates`` (:class:`ExudynFlow`).

    Node sensors for the state's coordinates (and the connector's own, :meth:`WormGearConnector.AddSensors`, if it
    has none) are added to ``mbs`` and the system is assembled again; its initial state is kept.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The assembled system, in its steady state.
    connector : WormGearConnector
        The mesh of ``mbs`` (:func:`~exudyn_worm.items.connector.CreateWormGear`) whose chatter is looked for; its worm
        must turn (initial worm speed != 0).
    coordinates : sequence of int, optional
        ODE2 coordinate indices of the flow state; default: every ODE2 coordinate not held by a coordinate
        constraint (``ObjectConnectorCoordinate``, e.g. the motor of ``CreatePrescribedRotation``). The worm's
        and the wheel's come first.

    Returns
    -------
    LoweringModel
        ``drive`` is None, ``parameters`` empty, ``motorSpeed`` the worm's steady speed (kicks are fractions of
        it), ``loadTorque`` nan.

    Raises
    ------
    TypeError
        If ``mbs`` is not an ``exudyn.MainSystem`` or ``connector`` not a WormGearConnector of ``mbs``.
    ValueError
        If the system is not assembled, the worm does not turn, the mesh carries no load at the initial state, or
        ``coordinates`` is not a set of ODE2 indices with the worm's and the wheel's.
    """
    w = 'LoweringModelOfSystem'
    CheckSystem(w, mbs)
    if not isinstance(connector, WormGearConnector) or connector not in mbs.variables.get(CONNECTORS_KEY, []):
        raise TypeError(f"{w}: 'connector' must be a WormGearConnector built in 'mbs' by CreateWormGear, got "
                        f"{type(connector).__name__}")
    size = mbs.systemData.ODE2Size()
    if not size:
        raise ValueError(f"{w}: 'mbs' has no ODE2 coordinates: call mbs.Assemble() first")
    C = _Configuration()
    q0 = np.array(mbs.systemData.GetODE2Coordinates(configuration=C.Initial), dtype=float)
    v0 = np.array(mbs.systemData.GetODE2Coordinates_t(configuration=C.Initial), dtype=float)
    worm, wheel = (int(mbs.GetNodeODE2Index(n)) for n in connector.nodeNumbers)
    if v0[worm] == 0.:
        raise ValueError(f"{w}: the worm's initial speed must be its steady speed (!= 0 rad/s): start the system in "
                         f"the steady rotation (SteadyInitialState), got 0 rad/s")
    if coordinates is None:
        held = set(_HeldCoordinates(mbs))
        coordinates = [i for i in range(size) if i not in held]
    if isinstance(coordinates, (str, bytes)) or not hasattr(coordinates, '__iter__'):
        raise TypeError(f"{w}: 'coordinates' must be a sequence of ODE2 indices, got {type(coordinates).__name__}")
    chosen = list(coordinates)
    if (any(isinstance(i, bool) or not isinstance(i, (int, np.integer)) or not 0 <= i < size for i in chosen)
            or len(set(chosen)) != len(chosen) or worm not in chosen or wheel not in chosen):
        raise ValueError(f"{w}: 'coordinates' must be distinct ODE2 indices in [0, {size - 1}] including the worm's "
                         f"({worm}) and the wheel's ({wheel}), got {chosen!r}")
    index = [worm, wheel] + sorted(int(i) for i in chosen if i not in (worm, wheel))
    sensors = _AddFlowSensors(mbs, index)               # first: it reads the assembled system's nodes
    if not connector.sensors:
        connector.AddSensors(mbs)
    mbs.Assemble()
    mbs.systemData.SetODE2Coordinates(q0.tolist(), configuration=C.Initial)
    mbs.systemData.SetODE2Coordinates_t(v0.tolist(), configuration=C.Initial)
    keys = ['phi1', 'phi2'] + [f'q{i}' for i in index[2:]]
    steady = {k: float(q0[i]) for k, i in zip(keys, index)}
    steady.update(omega1=float(v0[worm]), omega2=float(v0[wheel]))
    if connector.axialNodeNumber is not None:
        a = int(mbs.GetNodeODE2Index(connector.axialNodeNumber))
        steady.update(xA=float(q0[a]), vA=float(v0[a]))
    force = abs(float(_MeshAt(connector, steady).normalForce))
    if not force > 0:
        raise ValueError(f"{w}: the mesh carries no load at the initial state (normal force 0 N): start the system "
                         f"in the static equilibrium under its load (SteadyInitialState)")
    return LoweringModel(None, mbs, None, connector, {}, steady, abs(float(v0[worm])), math.nan, force,
                         connector.options, {}, tuple(index), v0, tuple(keys), q0, sensors)


def SteadyChatterOfSystem(mbs: Any, connector: WormGearConnector, coordinates: Optional[Sequence[int]] = None,
                          settleTime: float = 1.0, stepsPerPeriod: int = STEPS_PER_PERIOD, kick: float = 0.01,
                          start: Optional[Any] = None, maxIterations: int = 30, tolerance: float = 1e-8,
                          initialState: Optional[Sequence[float]] = None) -> PeriodicOrbit:
    """Steady chatter of your own Exudyn system with a worm-gear connector: its periodic orbit, by shooting on the
    system itself, with Floquet multipliers (as :func:`FindSteadyChatter` for a parameter set).

    The system must run in a steady rotation and start in it (:func:`LoweringModelOfSystem` says what that
    means); the chatter is looked for after a time simulation from that state with the worm speed kicked by
    ``kick`` times its steady speed.

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The assembled system, in its steady state.
    connector : WormGearConnector
        Its mesh.
    coordinates : sequence of int, optional
        ODE2 indices of the flow state (default: every coordinate not held by a coordinate constraint).
    settleTime : float
        Duration in s of the settling simulation, > 0.
    stepsPerPeriod : int
        Solver steps per period in the shooting runs.
    kick : float
        Initial worm-speed disturbance as a fraction of the worm's steady speed.
    start : (array_like, float), optional
        Start guess ``(state, period)`` in flow coordinates instead of the settling simulation.
    maxIterations : int
        Newton steps at most.
    tolerance : float
        Shooting tolerance (relative to the state scale).
    initialState : array_like, optional
        Flow state the settling simulation starts from instead of the kicked steady state.

    Returns
    -------
    PeriodicOrbit
        ``state`` is ``(q - v0 t, q' - v0)`` over ``info['model'].coordinates`` (worm, wheel, the others);
        ``info`` holds ``forceFactor`` (largest normal force over the steady one), ``maxWheelAcceleration``
        (rad/s^2), ``minWormSpeed`` (rad/s), ``model`` and ``flow``.

    Raises
    ------
    TypeError, ValueError
        For a system or connector that does not fit (:func:`LoweringModelOfSystem`).
    ShootingError
        If the system settles to rest (no chatter to find) or Newton fails.

    Examples
    --------
    A three-mass drive built by hand (motor, shaft, worm, mesh, wheel, load shaft, load) in
    ``tests/test_chatter_chains.py``; in short::

        state = SteadyInitialState(drive, load=M, motorSpeed=w, loadSide=[(JL, kL)])
        # ... CreateRotor / CreatePrescribedRotation / CreateShaft / CreateWormGear / CreateRotorTorque at state
        mbs.Assemble()
        orbit = SteadyChatterOfSystem(mbs, connector)
        orbit.frequencyHz, orbit.info['forceFactor'], orbit.stable
    """
    model = LoweringModelOfSystem(mbs, connector, coordinates)
    return _FindChatter(model, 'SteadyChatterOfSystem', 'the system', settleTime, stepsPerPeriod, start,
                        maxIterations, tolerance, kick, initialState)
