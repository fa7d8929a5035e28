"""Steady chatter of the reel changer's lowering phase as a periodic orbit of the Exudyn model itself.

The lowering phase relative to its steady rotation is autonomous (:mod:`exudyn_worm.analysis.orbits.lowering` builds
that model), and the steady chatter is a periodic orbit of its one-period map
(:class:`~exudyn_worm.analysis.orbits.exudynflow.ExudynFlow`). :func:`FindSteadyChatter` starts from a short time
simulation that has settled (or from the unstable eigenvector of the linearization) and shoots
(:func:`~exudyn_worm.analysis.orbits.periodic.FindPeriodicOrbit`); :func:`SteadyChatterOfSystem` does the same for your own
Exudyn system with a worm-gear connector. :func:`OrbitAmplitude` simulates the converged orbit once and reports
the largest normal-force factor (largest normal force / static normal force) and the largest ``|phi2''|``. The
brute-force check by long time simulations is :mod:`exudyn_worm.analysis.orbits.longsimulation`.
"""
from __future__ import annotations

from typing import Any, Dict, Optional, Sequence

import numpy as np

from ...model.contact import ContactOptions
from .periodic import FindPeriodicOrbit, NoSteadyChatter, PeriodicOrbit, ShootingError
from ..._checks import CheckPositive
from ...items.connector import WormGearConnector
from ..stability.linearization import AnalyzeLinearStability
from ...drive.wholedrive import CheckDrive, Drive
from ..stability.drivestability import AnalyzeDrive
from .exudynflow import STEPS_PER_PERIOD, ExudynFlow, _Configuration
from .lowering import (BuildLoweringModel, BuildRigidBodyLoweringModel, LoweringModel, LoweringModelOfSystem,
                       SettleLowering, StateScale,
                       _LoweringFlow, _MeshAt, _PeriodFromSignal, _StoredFlowStates, _StoredStates)
from .settling import SettleOnSection

__all__ = ['FindSteadyChatter', 'OrbitAmplitude', 'SteadyChatterOfSystem', 'SteadyChatterSummary',
           'MONODROMY_PERTURBATION']

#: relative step (of :func:`~exudyn_worm.analysis.orbits.lowering.StateScale`) of the central differences for an orbit's monodromy matrix: the fixed-step
#: integrator resolves the force jump where the mesh changes flank only to a step, which leaves a sawtooth on the
#: one-period map; steps of 1e-6 see its slope (trivial multiplier 1.005-1.03 at P1 for 150-1600 steps per
#: period), 0.05 spans a few solver steps and averages it out (1.001-1.003), 0.1 and more see the map's curvature
#: (measured, docs/chatter-amplitude.md)
MONODROMY_PERTURBATION = 0.05


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
        ``|phi2''|`` in rad/s^2), ``minWormSpeed`` (rad/s); for the 3D model (``model.rigidBody``) also the largest
        bearing loads in N over the orbit, ``maxWormAxialLoad``, ``maxWormRadialLoad``, ``maxWheelAxialLoad``,
        ``maxWheelRadialLoad`` (:func:`~exudyn_worm.analysis.simulation.reelchanger3d.ShaftLoadPeaks`).
    """
    flow.Solve(state, period, storeSensors=True)
    s = _StoredStates(model)
    mesh = _MeshAt(model.connector, s)
    out = {'forceFactor': float(np.max(np.abs(mesh.normalForce)) / model.staticNormalForce),
           'maxWheelAcceleration': float(np.max(np.abs(s['alpha2']))),
           'minWormSpeed': float(np.min(s['omega1']))}
    if model.rigidBody is not None:            # the 3D model: the shafts' bearing loads over the orbit
        # lazy: the 3D model's module is loaded only for drives with shaft bearings
        from ..simulation.reelchanger3d import ShaftLoadPeaks
        out.update(ShaftLoadPeaks(model.rigidBody))
    return out


def FindSteadyChatter(drive: Drive, settleTime: float = 1.0, stepsPerPeriod: int = STEPS_PER_PERIOD,
                      contactOptions: ContactOptions = ContactOptions(), start: Optional[Any] = None, maxIterations: int = 30,
                      tolerance: float = 1e-8, model: Optional[LoweringModel] = None, kick: float = 0.01,
                      initialState: Optional[Sequence[float]] = None) -> PeriodicOrbit:
    """Steady chatter of the lowering phase: the periodic orbit of the Exudyn model, by shooting.

    Parameters
    ----------
    drive : Drive
        A drive with the reel changer's duty (e.g. ``ResolveDrive('reel-P1')``; any other duty through
        :func:`~exudyn_worm.analysis.orbits.lowering.LoweringPhaseDrive`).
    settleTime : float
        Duration in s of the time simulation (from the steady state, worm speed kicked by 1 %) whose end is
        the first guess, if ``start`` is not given. For the 3D model (``model`` from
        :func:`~exudyn_worm.analysis.orbits.lowering.BuildRigidBodyLoweringModel`) with elastic shaft bearings the guess
        is instead taken from a run that has settled on its Poincare section (:func:`~exudyn_worm.analysis.orbits.settling.SettleOnSection`,
        15-20 s for ``examples/drives/reel-3d-chatter.toml``: its tilt modes are barely damped).
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
        A model already built from ``drive``.
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
    model = BuildLoweringModel(drive, contactOptions) if model is None else model
    return _FindChatter(model, 'FindSteadyChatter', 'the lowering phase', settleTime, stepsPerPeriod, start,
                        maxIterations, tolerance, kick, initialState)


def _LinearlyStable(model: LoweringModel) -> bool:
    """The linear verdict at the model's steady state: :func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive` (S = -1,
    lowering) for a drive; for a user's system its own linearization in the contact state of its steady
    state (False if it cannot be linearized there, so that a drive is never called at rest on that ground)."""
    if model.whole is not None:
        return bool(AnalyzeDrive(model.whole).State(-1).stable)
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
    if start is None and initialState is None and _ElasticBearings(model):
        # the 3D model on elastic bearings settles slowly (barely damped tilt modes): a long run watched on the
        # Poincare section
        start = _SettledStart(model, w, what)
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
        s = _StoredStates(model)
        quarter = len(s['omega1']) // 4
        first, swing = np.ptp(s['omega1'][:quarter]), np.ptp(s['omega1'][-quarter:])
        tail = _MeshAt(model.connector, s, slice(-quarter, None))
        inContact = float(np.max(np.abs(tail.normalForce))) < 2. * model.staticNormalForce
        # rest: no swing left, or a linearly stable drive whose swing shrinks while the mesh stays in contact
        if not swing > 1e-4 * model.motorSpeed or (inContact and swing < 0.95 * first and _LinearlyStable(model)):
            raise NoSteadyChatter(f"{w}: {what} settles to rest (after {settleTime:g} s the worm speed swing "
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


def _ElasticBearings(model: LoweringModel) -> bool:
    """Whether ``model`` is the 3D model with a shaft on elastic bearings (not on an ideal revolute joint)."""
    return model.rigidBody is not None and any('joint' not in items for items in model.rigidBody.bearings.values())


def _SettledStart(model: LoweringModel, where: str, what: str, settled: Optional[Dict[str, Any]] = None):
    """(state, period) on the Poincare section of a settled long run (:func:`~exudyn_worm.analysis.orbits.settling.SettleOnSection`)."""
    settled = SettleOnSection(model) if settled is None else settled
    if not np.isfinite(settled['period']):
        raise NoSteadyChatter(f"{where}: {what} does not oscillate after {settled['duration']:g} s: no steady chatter "
                            f"at these parameters")
    return settled['state'], settled['period']


def SteadyChatterOfSystem(mbs: Any, connector: WormGearConnector, coordinates: Optional[Sequence[int]] = None,
                          settleTime: float = 1.0, stepsPerPeriod: int = STEPS_PER_PERIOD, kick: float = 0.01,
                          start: Optional[Any] = None, maxIterations: int = 30, tolerance: float = 1e-8,
                          initialState: Optional[Sequence[float]] = None) -> PeriodicOrbit:
    """Steady chatter of your own Exudyn system with a worm-gear connector: its periodic orbit, by shooting on the
    system itself, with Floquet multipliers (as :func:`FindSteadyChatter` for a parameter set).

    The system must run in a steady rotation and start in it (:func:`~exudyn_worm.analysis.orbits.lowering.LoweringModelOfSystem` says what that
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
        For a system or connector that does not fit (:func:`~exudyn_worm.analysis.orbits.lowering.LoweringModelOfSystem`).
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


def SteadyChatterSummary(drive: Drive, stepsPerPeriod: int = STEPS_PER_PERIOD) -> Dict[str, Any]:
    """The steady chatter of the lowering phase (:func:`FindSteadyChatter`) as a JSON-ready dictionary, on the
    model the drive needs: the one-angle model, or the 3D model for a drive with shaft bearings
    (:func:`~exudyn_worm.analysis.orbits.lowering.BuildRigidBodyLoweringModel`: worm and wheel as rigid bodies).

    Parameters
    ----------
    drive : Drive
        A drive with the reel changer's duty (:func:`~exudyn_worm.analysis.orbits.lowering.LoweringPhaseDrive`).
    stepsPerPeriod : int
        Solver steps per period in the shooting runs.

    Returns
    -------
    dict
        ``model`` ('3D' or 'one-angle'), ``periodS``, ``frequencyHz``, ``stable``, ``multipliers`` (the nontrivial
        Floquet multipliers' moduli, largest first), ``trivialMultiplierError``, ``staticNormalForce`` and
        ``maxNormalForce`` (N), ``amplitude`` (:func:`OrbitAmplitude`: ``forceFactor``, ``maxWheelAcceleration``,
        ``minWormSpeed``, and for the 3D model the largest bearing loads), ``motorSpeed`` (rad/s), ``loadTorque``
        (N*m). The 3D model's summary also holds ``method``, ``settledS`` (the simulated time after which the
        state on the Poincare section stopped moving, :func:`~exudyn_worm.analysis.orbits.settling.SettleOnSection`),
        ``sectionChange`` (its last move in state scales) and ``reason`` (how the result was found). Its
        ``method`` is 'shooting' (the orbit, started from that state), or 'long simulation' where shooting does not
        converge from there: then the values are those of the settled run's last 0.5 s (``amplitude`` with
        ``maxWormSpeed`` too), ``stable`` and ``trivialMultiplierError`` are None and ``multipliers`` is empty, and
        ``reason`` says why no orbit is given.

    Raises
    ------
    ShootingError
        If the lowering phase settles to rest (no chatter) or, on the one-angle model, shooting does not converge.
    """
    drive = CheckDrive('SteadyChatterSummary', drive)
    if drive.isRigidBody:
        return _SteadyChatterSummary3D(drive, stepsPerPeriod)
    model = BuildLoweringModel(drive)
    orbit = FindSteadyChatter(drive, stepsPerPeriod=stepsPerPeriod, model=model)
    return _OrbitSummary(model, orbit, 'one-angle')


def _OrbitSummary(model: LoweringModel, orbit: PeriodicOrbit, name: str) -> Dict[str, Any]:
    """The JSON-ready summary of a converged orbit."""
    amplitude = {k: float(v) for k, v in orbit.info.items() if k not in ('model', 'flow')}
    multipliers = sorted((abs(complex(m)) for m in orbit.nontrivialMultipliers), reverse=True)
    return {'model': name, 'periodS': float(orbit.period),
            'frequencyHz': float(orbit.frequencyHz), 'stable': bool(orbit.stable), 'multipliers': multipliers,
            'trivialMultiplierError': float(orbit.trivialMultiplierError), 'accurate': orbit.accurate,
            'stabilityDecided': orbit.stabilityDecided,
            'staticNormalForce': float(model.staticNormalForce),
            'maxNormalForce': float(amplitude['forceFactor'] * model.staticNormalForce), 'amplitude': amplitude,
            'motorSpeed': float(model.motorSpeed), 'loadTorque': float(model.loadTorque)}


def _SteadyChatterSummary3D(drive: Drive, stepsPerPeriod: int) -> Dict[str, Any]:
    """:func:`SteadyChatterSummary` on the 3D model: shooting from a run settled on the Poincare section, or, where
    shooting does not converge from there, the settled run's vibration (``method`` 'long simulation')."""
    w = 'SteadyChatterSummary'
    model = BuildRigidBodyLoweringModel(drive)
    if not _ElasticBearings(model):                  # ideal joints: the one-angle model's dynamics, its start
        summary = _OrbitSummary(model, FindSteadyChatter(drive, stepsPerPeriod=stepsPerPeriod, model=model), '3D')
        summary.update(method='shooting', reason='periodic orbit by shooting (shafts on ideal joints)')
        return summary
    settled = SettleOnSection(model)
    start = _SettledStart(model, w, 'the lowering phase', settled)
    settledText = (f"started on the Poincare section of a {settled['duration']:g} s time simulation (the section "
                   f"point moved by {settled['change']:.2g} of the state scale over its last 2 s)")
    try:
        orbit = FindSteadyChatter(drive, stepsPerPeriod=stepsPerPeriod, model=model, start=start)
    except ShootingError as err:
        residual = getattr(err.lastOrbit, 'residual', float('nan'))
        vibration = settled['vibration']
        return {'model': '3D', 'method': 'long simulation', 'periodS': float(settled['period']),
                'frequencyHz': float(1. / settled['period']), 'stable': None, 'multipliers': [],
                'trivialMultiplierError': None, 'accurate': None, 'stabilityDecided': False,
                'staticNormalForce': float(model.staticNormalForce),
                'maxNormalForce': float(vibration['forceFactor'] * model.staticNormalForce), 'amplitude': vibration,
                'motorSpeed': float(model.motorSpeed), 'loadTorque': float(model.loadTorque),
                'settledS': float(settled['duration']), 'sectionChange': float(settled['change']),
                'reason': f"no periodic orbit: shooting {settledText} did not converge (residual {residual:.2g} of "
                          f"the state scale); the values are the largest over the run's last 0.5 s"}
    summary = _OrbitSummary(model, orbit, '3D')
    summary.update(method='shooting', settledS=float(settled['duration']), sectionChange=float(settled['change']),
                   reason=f"periodic orbit by shooting, {settledText}")
    return summary
