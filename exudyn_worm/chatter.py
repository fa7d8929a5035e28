"""Steady chatter of the reel changer's lowering phase as a periodic orbit of the Exudyn model itself.

The lowering phase is modelled as the linear analysis sees it: the motor turns at constant speed
``motorSpeed`` and the wheel carries the constant load torque ``loadMass * g * leverArm`` that drives it
forward (the reel changer's load -m g l cos(phi2) at phi2 = pi, the middle of the lowering phase). With the
angles taken relative to the steady rotation (``phi - omega t``) and the speeds relative to the steady speeds,
the drive is then autonomous, and the steady chatter is a periodic orbit in the state
``(phi1 - omega1 t, phi2 - omega2 t, phi1' - omega1, phi2' - omega2)``.

:class:`ExudynFlow` is the one-period map of any Exudyn system: set the initial state, ``mbs.SolveDynamic``
over time T (fixed number of steps), read the end state. :func:`FindSteadyChatter` starts from a short time
simulation that has settled (or from the unstable eigenvector of the linearization) and shoots
(:func:`~exudyn_worm.orbits.FindPeriodicOrbit`). :func:`OrbitAmplitude` simulates the converged orbit once and
reports the largest normal-force factor (largest normal force / static normal force) and the largest
``|phi2''|``.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple

import numpy as np

from .contact import MATH_OPS, ContactOptions
from .orbits import FindPeriodicOrbit, PeriodicOrbit, ShootingError
from .profiles import ConstantSpeed, ConstantTorque, GravityLeverTorque
from ._checks import CheckPositive, CheckReal
from .connector import CONNECTORS_KEY, CreateWormGear
from .drivetrain import CreatePrescribedRotation, CreateRotor, CreateRotorTorque, CreateShaft
from .linearization import DriveStability
from .presets import DriveFromParameters, ExtraComponents
from .reelchanger import SOLVER_SETTINGS, CheckReelChangerKeys, SolverSettings, SteadyInitialState
from .solve import SolverDivergedError

__all__ = ['LoweringModel', 'BuildLoweringModel', 'ExudynFlow', 'FindSteadyChatter',
           'OrbitAmplitude', 'SettleLowering', 'EquilibriumState', 'StateScale', 'LongSimulationAmplitude', 'SettledSimulationAmplitude', 'UpdateLoweringModel', 'IN_PLACE_KEYS', 'STEPS_PER_PERIOD', 'ORBIT_SOLVER_SETTINGS']

#: solver steps per chatter period of the shooting runs (about 2 % change in the P1 amplitude to 800 steps,
#: measured, see docs/chatter-amplitude.md)
STEPS_PER_PERIOD = 400
#: generalized-alpha settings of the shooting runs: full Newton with a tight tolerance, so that the one-period
#: map is smooth enough for finite differences of 1e-6 (the time simulations use modified Newton at 1e-6)
ORBIT_SOLVER_SETTINGS = {'timeIntegration.newton.useModifiedNewton': False,
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
        Motor, worm and wheel rotors (:func:`~exudyn_worm.drivetrain.CreateRotor`).
    steady : dict of str to float
        The steady state of lowering (:func:`~exudyn_worm.equilibrium.SteadyInitialState`).
    motorSpeed : float
        Motor speed in rad/s.
    loadTorque : float
        Constant load torque on the wheel in N*m (loadMass g leverArm, lowering).
    staticNormalForce : float
        Normal force of the steady state in N.
    contactOptions : ContactOptions
        Options of the contact law.
    parameters : dict of str to float
        The flat parameter set the model was built from.
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


def BuildLoweringModel(parameters: Mapping[str, float], contactOptions: ContactOptions = ContactOptions(),
                       useSymbolic: bool = True) -> LoweringModel:
    """Exudyn model of the reel changer's lowering phase: motor at constant speed, constant load torque
    ``loadMass * g * leverArm`` driving the wheel, starting in the steady state (static mesh deflection).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set with the reel changer's keys (e.g. ``GetPreset('reel-P1')``); the two-mass drive of
        Figure 2 (a drive-side chain or an axial bearing is refused).
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
        For a bad parameter set, or one with components beyond the two-mass drive.
    """
    import exudyn as exu
    w = 'BuildLoweringModel'
    CheckReelChangerKeys(parameters, w)
    extra = ExtraComponents(parameters)
    if extra:
        raise ValueError(f"{w}: the periodic-orbit analysis covers the two-mass drive of Figure 2; this parameter set "
                         f"also has {' and '.join(extra)} (not supported yet); leave those keys out")
    if not isinstance(contactOptions, ContactOptions):
        raise TypeError(f"{w}: 'contactOptions' must be a ContactOptions, got {type(contactOptions).__name__}")
    drive = DriveFromParameters(parameters)
    motorSpeed = CheckPositive(w, 'motorSpeed', parameters['motorSpeed'], 'rad/s')
    loadTorque = GravityLeverTorque(mass=parameters['loadMass'], leverArm=parameters['leverArm']).maximum
    load = ConstantTorque(loadTorque)
    steady = SteadyInitialState(drive, load, motorSpeed, contactOptions)
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    motor = CreateRotor(mbs, 1e-3, initialAngle=0., initialSpeed=motorSpeed, name='motor')
    worm = CreateRotor(mbs, drive.J1, initialAngle=steady['phi1'], initialSpeed=steady['omega1'], name='worm')
    wheel = CreateRotor(mbs, drive.J2, initialAngle=steady['phi2'], initialSpeed=steady['omega2'], name='wheel')
    CreatePrescribedRotation(mbs, motor, ConstantSpeed(motorSpeed), name='motorDrive', useSymbolic=useSymbolic)
    shaft = CreateShaft(mbs, [motor, worm], stiffness=drive.kT, damping=drive.dT, name='driveShaft')
    connector = CreateWormGear(mbs, [worm['nodeNumber'], wheel['nodeNumber']], gear=drive.gear, name='wormGear',
                               contactOptions=contactOptions, useSymbolic=useSymbolic)
    CreateRotorTorque(mbs, wheel, load, name='lowerLoad', useSymbolic=useSymbolic)
    connector.AddSensors(mbs)
    mbs.Assemble()
    static = connector.Evaluate(steady['phi1'], steady['phi2'], steady['omega1'], steady['omega2'])
    return LoweringModel(SC, mbs, drive, connector, {'motor': motor, 'worm': worm, 'wheel': wheel,
                                                      'driveShaft': shaft}, steady,
                         motorSpeed, loadTorque, abs(float(static.normalForce)), contactOptions, dict(parameters))


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
    drive = DriveFromParameters(parameters)
    mbs = model.mbs
    mbs.SetObjectParameter(model.rotors['worm']['objectNumber'], 'inertia', drive.J1)
    mbs.SetObjectParameter(model.rotors['wheel']['objectNumber'], 'inertia', drive.J2)
    mbs.SetObjectParameter(model.rotors['driveShaft']['objectNumber'], 'stiffness', drive.kT)
    mbs.SetObjectParameter(model.rotors['driveShaft']['objectNumber'], 'damping', drive.dT)
    mbs.Assemble()
    model.drive, model.parameters = drive, dict(parameters)
    model.steady = SteadyInitialState(drive, ConstantTorque(model.loadTorque), model.motorSpeed, model.contactOptions)
    return model


class ExudynFlow:
    """One-period map of an Exudyn system relative to a steady rotation: ``flow(x, T) -> x(T)``.

    The state ``x`` holds, for the ODE2 coordinates ``coordinates``, the positions minus ``steadySpeeds * t``,
    then the velocities minus ``steadySpeeds``. Coordinates not in ``coordinates`` (e.g. a prescribed motor)
    start at their position ``fixedPositions`` (default: the system's initial values) and steady speed.
    The discrete state is not part of ``x``: every solve starts with the data coordinates the system had when
    the flow was made and with the stick/slip state of each worm-gear connector that the start implies
    (sliding in the direction of the worm's speed, :meth:`~exudyn_worm.connector._StickSlip.Restart`), so
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


def _LoweringFlow(model: LoweringModel, stepsPerPeriod: int) -> ExudynFlow:
    mbs = model.mbs
    nodes = [model.rotors[k]['nodeNumber'] for k in ('motor', 'worm', 'wheel')]
    index = [mbs.GetNodeODE2Index(n) for n in nodes]
    speeds = np.zeros(mbs.systemData.ODE2Size())
    u = model.drive.gear.ratio
    speeds[index] = [model.motorSpeed, model.motorSpeed, model.motorSpeed / u]
    flow = ExudynFlow(mbs, index[1:], speeds, stepsPerPeriod)
    flow.q0[index[0]] = 0.
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
    x[2] += kick * model.motorSpeed
    return flow.Solve(x, duration, storeSensors=store), flow


def EquilibriumState(model: LoweringModel) -> np.ndarray:
    """The static equilibrium of the lowering phase in flow coordinates (relative angles, speed deviations 0).

    Parameters
    ----------
    model : LoweringModel
    """
    return np.array([model.steady['phi1'], model.steady['phi2'], 0., 0.])


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
    mesh = model.connector.Evaluate(s['phi1'], s['phi2'], s['omega1'], s['omega2'])
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
    w = 'FindSteadyChatter'
    model = BuildLoweringModel(parameters, contactOptions) if model is None else model
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
        tail = model.connector.Evaluate(s['phi1'][-quarter:], s['phi2'][-quarter:], s['omega1'][-quarter:],
                                        s['omega2'][-quarter:])
        inContact = float(np.max(np.abs(tail.normalForce))) < 2. * model.staticNormalForce
        linearlyStable = DriveStability(model.parameters).State(-1).stable
        # rest: no swing left, or a linearly stable drive whose swing shrinks while the mesh stays in contact
        if not swing > 1e-4 * model.motorSpeed or (linearlyStable and inContact and swing < 0.95 * first):
            raise ShootingError(f"{w}: the lowering phase settles to rest (after {settleTime:g} s the worm speed swing "
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
        mesh = model.connector.Evaluate(s['phi1'][last], s['phi2'][last], s['omega1'][last], s['omega2'][last])
        k = last[int(np.argmax(np.abs(mesh.normalForce)))]
        u = model.drive.gear.ratio
        w1, w2 = model.motorSpeed, model.motorSpeed / u
        x = np.array([s['phi1'][k] - w1 * t[k], s['phi2'][k] - w2 * t[k], s['omega1'][k] - w1, s['omega2'][k] - w2])
    else:
        x, period = np.asarray(start[0], dtype=float), float(start[1])
    flow = _LoweringFlow(model, stepsPerPeriod)
    orbit = FindPeriodicOrbit(flow, x, period, stateScale=scale, maxIterations=maxIterations, tolerance=tolerance,
                              where=w)
    orbit.info.update(OrbitAmplitude(model, flow, orbit.state, orbit.period), model=model, flow=flow)
    return orbit


def StateScale(model: LoweringModel) -> np.ndarray:
    """Typical size of the flow state's components: the static mesh deflection as angles, times the chatter
    angular frequency (2 pi 40 Hz) as speeds.

    Parameters
    ----------
    model : LoweringModel
        The lowering model (its gear and static normal force).
    """
    g = model.drive.gear
    deflection = max(model.staticNormalForce / g.kV, 1e-9) / g.normalLever         # worm angle of the deflection
    angles = np.array([deflection, deflection / g.ratio])
    return np.concatenate([angles, angles * 2 * math.pi * 40.])


def LongSimulationAmplitude(parameters: Mapping[str, float], duration: float = 3.0, stepSize: float = 1e-4,
                            kick: float = 0.01, window: float = 0.25,
                            contactOptions: ContactOptions = ContactOptions(),
                            initialState: Optional[Sequence[float]] = None) -> Dict[str, float]:
    """Steady amplitude of the lowering phase by brute force: a long time simulation with the time simulations'
    solver settings (:data:`~exudyn_worm.reelchanger.SOLVER_SETTINGS`: modified Newton, tolerance 1e-6), measured
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

    Returns
    -------
    dict
        ``forceFactor``, ``maxWheelAcceleration`` (rad/s^2), ``frequencyHz`` (nan at rest), ``seconds`` (solver time).
    """
    w = 'LongSimulationAmplitude'
    duration = CheckPositive(w, 'duration', duration, 's')
    stepSize = CheckPositive(w, 'stepSize', stepSize, 's')
    window = CheckPositive(w, 'window', window, 's')
    model = BuildLoweringModel(parameters, contactOptions)
    steps = max(10, int(round(duration / stepSize)))
    flow = _LoweringFlow(model, steps)
    flow = ExudynFlow(model.mbs, flow.coordinates, flow.speeds, steps, solverSettings=SOLVER_SETTINGS)
    flow.q0[model.mbs.GetNodeODE2Index(model.rotors['motor']['nodeNumber'])] = 0.
    x = EquilibriumState(model) if initialState is None else np.array(initialState, dtype=float)
    x[2] += kick * model.motorSpeed
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
    mesh = model.connector.Evaluate(s['phi1'][last], s['phi2'][last], s['omega1'][last], s['omega2'][last])
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
    flow = _LoweringFlow(model, steps)
    flow = ExudynFlow(model.mbs, flow.coordinates, flow.speeds, steps, solverSettings=SOLVER_SETTINGS)
    flow.q0[model.mbs.GetNodeODE2Index(model.rotors['motor']['nodeNumber'])] = 0.
    x = EquilibriumState(model)
    x[2] += kick * model.motorSpeed
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
