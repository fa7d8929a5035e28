"""The paper's paper-reel changer (section 3.2) simulated: :func:`SimulateReelChanger` solves the system that
:func:`~exudyn_worm.builders.oneangle.BuildReelChanger` builds, and the phases and windows of its duty.

Motor (prescribed rotation phi0) -- elastic shaft kT, dT -- worm J1 -- worm-gear mesh -- wheel and
frame J2 -- load torque of the reel, M2 = -m2 g l2 cos(phi2) (eq. (27)). The frame is horizontal at
t = 0 and is lifted first; one full rotation of the wheel takes 2 pi u / motorSpeed (8 s in the paper).

Optional (see :mod:`exudyn_worm.drive.presets`): the drive-side chain of Figure 19 (``J4, k4, d4, J5, ...``:
worm --kT-- J4 --k4-- J5 ... -- motor), the load-side chain (``JL1, kL1, dL1, JL2, ...``: wheel --kL1-- JL1
--kL2-- JL2 ...; the reel's load torque then acts on the last inertia) and the worm's axial bearing
(``kA, dA, mA``).
"""
from __future__ import annotations

import math
import time as _time
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np

from ..._checks import CheckPositive
from ...items.results import SimulationResult
from ...items.solve import IncompleteSolveError, SolveDynamicInChunks, SolverDivergedError
from ...model.contact import ContactOptions
from ...model.friction import MATH_OPS
from ...model.drive import ElasticDrive
from ...params.plausibility import CheckWormRotation, CheckWormSpeed
from ...model.stability import CharacteristicCoefficients, EigenvaluesFromPolynomial
from ...builders.rigidbody import BuildRigidBodyReelChanger
from ...builders.oneangle import BuildReelChanger, CheckModelOptions, CheckReelChangerKeys
from ...drive.duty import DefaultEndTime, DutyPhases, IsReelChangerDuty, MotorMotion
from ...drive.wholedrive import CheckDrive, Drive
from .stepsize import CheckStepSize, RecommendedStepSize

__all__ = ['SimulateReelChanger', 'RotationPeriod', 'DefaultWindows',
           'DefaultPhases', 'DefaultSimulatedTime', 'WindowPhases', 'PhaseLabel',
           'CheckRunSize', 'RunSizeError', 'SolverSettings', 'DEFAULT_STEP_SIZE',
           'SOLVER_SETTINGS', 'SMALL_3D_SOLVER_SETTINGS', 'MAX_STEPS', 'STANDSTILL_TOLERANCE']

#: time step in s of the validation's simulations and the benchmark's output grid (the P1/P7 amplitudes change
#: < 1 % when it is halved, see validation/REPORT.md); SimulateReelChanger's default is the drive's own
#: RecommendedStepSize
DEFAULT_STEP_SIZE = 5e-4
#: generalized-alpha settings of :func:`SimulateReelChanger` (paths in ``exudyn.SimulationSettings``), chosen by
#: the lever measurements in benchmarks/README.md: modified Newton, at most 10 iterations before the Jacobian is
#: renewed or the step halved (Exudyn's 25 let a stuck iteration run on), relative tolerance 1e-6, spectral
#: radius 0.8 (damps the stiff friction-regularization mode; 0.9 made P1's peak 0.3 % high at 5e-4 s), and a new
#: Jacobian as soon as one modified-Newton iteration does not converge (the mesh's Jacobian changes with the
#: contact state S, eqs. (9)-(12): with the stale one the chattering phases took 2.7 iterations per step, with a
#: renewed one 1.1; P1 0.78x the instructions, peaks as with full Newton)
SOLVER_SETTINGS = {'timeIntegration.newton.useModifiedNewton': True, 'timeIntegration.newton.maxIterations': 10,
                   'timeIntegration.newton.maxModifiedNewtonIterations': 1,
                   'timeIntegration.newton.relativeTolerance': 1e-6,
                   'timeIntegration.generalizedAlpha.spectralRadius': 0.8}
#: what the small-displacement 3D model (docs/mesh-3d.md) sets over :data:`SOLVER_SETTINGS`: an absolute floor of
#: 1e-6 (N, N*m) under the relative tolerance. Its bearings (1e8-1e9 N/m) make the residual's round-off about that
#: size; where a step starts near equilibrium (the steady lowering before a load reversal) the relative goal, 1e-6 of
#: that step's small initial residual, lies below it, Newton stalls and the step is halved again and again (P1 with
#: examples/drives/reel-3d.toml: 94 halvings down to 3e-6 s and 1040 Jacobians in the 25 ms before t = 6 s; with the
#: floor none and 16, peaks and RMS of the forces within 0.002 % of a run with tolerance 1e-8 and half the step,
#: benchmarks/README.md)
SMALL_3D_SOLVER_SETTINGS = {'timeIntegration.newton.absoluteTolerance': 1e-6}

#: default limit of solver steps (= stored samples, one per step) of one run: 1e6 steps is about 0.4 GB of
#: stored results and 15 s (P1) to 3.5 min (P7) of solving (780 s simulated of P1 at its recommended step);
#: raise it with ``maxSteps`` (``--max-steps``) for longer runs
MAX_STEPS = 1_000_000
#: solver time per step in s measured for the reel changer (P1 without chatter in most steps, P7 with the
#: worm speed through zero), used to say how long a refused run would take
_SECONDS_PER_STEP = (1.5e-5, 2e-4)
#: memory per stored step in bytes (8 sensors of 2 doubles in Exudyn, about 20 post-processed series)
_BYTES_PER_STEP = 400


def _Duration(seconds: float) -> str:
    for unit, size in (('h', 3600.), ('min', 60.), ('s', 1.)):
        if seconds >= size:
            return f"{seconds / size:.2g} {unit}"
    return f"{seconds:.2g} s"


class RunSizeError(ValueError):
    """A run refused before it starts because it needs more solver steps than its limit (:func:`CheckRunSize`)."""


def CheckRunSize(endTime: float, stepSize: float, maxSteps: int = MAX_STEPS, where: str = 'SimulateReelChanger',
                 names=('endTime', 'stepSize', 'maxSteps')) -> int:
    """Number of solver steps of a run; refuse runs longer than ``maxSteps`` before they start.

    Parameters
    ----------
    endTime : float
        Simulated time in s, > 0.
    stepSize : float
        Time step in s, > 0 and <= endTime.
    maxSteps : int
        Largest number of steps (and stored samples) allowed, >= 1 (default :data:`MAX_STEPS`).
    where : str
        Caller named in the messages.
    names : (str, str, str)
        How the caller calls end time, step size and step limit (``--end-time`` ... on the command line).

    Returns
    -------
    int
        ``round(endTime / stepSize)``.

    Raises
    ------
    ValueError
        For a bad value or a run above ``maxSteps``; the message says how long the run would take and how
        much memory its results would need.
    """
    nEnd, nStep, nMax = names
    endTime = CheckPositive(where, nEnd, endTime, 's')
    stepSize = CheckPositive(where, nStep, stepSize, 's')
    if isinstance(maxSteps, bool) or not isinstance(maxSteps, int) or maxSteps < 1:
        raise ValueError(f"{where}: '{nMax}' must be an integer >= 1, got {maxSteps!r}")
    if stepSize > endTime:
        raise ValueError(f"{where}: '{nStep}' must be <= {nEnd} = {endTime:g} s, got {stepSize:g} s")
    ratio = endTime / stepSize
    if not ratio <= maxSteps:           # also catches an overflow to inf
        fast, slow = (ratio * s for s in _SECONDS_PER_STEP)
        raise RunSizeError(f"{where}: {nEnd} {endTime:g} s at {nStep} {stepSize:g} s needs {ratio:.3g} solver steps, "
                         f"more than the limit {nMax} = {maxSteps:g}; it would take about {_Duration(fast)} to "
                         f"{_Duration(slow)} and store about {ratio * _BYTES_PER_STEP / 1e9:.2g} GB of results. "
                         f"Raise {nMax} to run it anyway")
    return max(1, int(round(ratio)))


def RotationPeriod(drive: Drive) -> float:
    """Duration in s of one full wheel rotation: 2 pi u / motorSpeed.

    Parameters
    ----------
    drive : Drive
        The drive, with ``motorSpeed`` in rad/s.
    """
    parameters = CheckDrive('RotationPeriod', drive).parameters
    if 'motorSpeed' not in parameters:
        CheckReelChangerKeys(drive, 'RotationPeriod')
    speed = CheckPositive('RotationPeriod', 'motorSpeed', parameters['motorSpeed'], 'rad/s')
    return 2 * math.pi * drive.gear.ratio / speed


def DefaultPhases(drive: Drive, endTime: Optional[float] = None,
                  minLength: float = 0.) -> List[Tuple[float, float, str]]:
    """The phases of the duty up to ``endTime`` as ``(t0, t1, phase)``, phase ``'lift'``, ``'lower'`` or ``'idle'``.

    The reel changer (a lever load at constant motor speed, the default duty): lift / lower / lift of every
    rotation, [kT, kT + T/4], [kT + T/4, kT + 3T/4], [kT + 3T/4, (k+1)T] for k = 0, 1, ..., clipped to ``endTime``.
    Any other duty (:mod:`exudyn_worm.drive.duty`): the phases in which the load opposes the motion (lift), drives the
    gear (lower) or is absent (idle), from the rigid kinematics (:func:`~exudyn_worm.drive.duty.DutyPhases`).

    Parameters
    ----------
    drive : Drive
        The drive with its duty (``motorSpeed`` in rad/s for the reel changer).
    endTime : float, optional
        Simulated time in s (default: :func:`DefaultSimulatedTime`, one rotation T for the reel changer).
    minLength : float
        Windows shorter than this (in s, after clipping) are dropped (another duty: merged into the one before);
        the first window is always kept.

    Returns
    -------
    list of (float, float, str)
        Phases in time order.
    """
    if not IsReelChangerDuty(CheckDrive('DefaultPhases', drive).parameters):
        CheckReelChangerKeys(drive, 'DefaultPhases')
        endTime = DefaultSimulatedTime(drive) if endTime is None else \
            CheckPositive('DefaultPhases', 'endTime', endTime, 's')
        return DutyPhases(drive.parameters, drive.gear.ratio, endTime, minLength)
    T = RotationPeriod(drive)
    endTime = T if endTime is None else CheckPositive('DefaultWindows', 'endTime', endTime, 's')
    windows = []
    for k in range(int(math.ceil(endTime / T - 1e-12))):
        for a, b, phase in ((0., .25, 'lift'), (.25, .75, 'lower'), (.75, 1., 'lift')):
            t0, t1 = (k + a) * T, min((k + b) * T, endTime)
            if t0 < endTime and (not windows or t1 - t0 >= minLength):
                windows.append((t0, t1, phase))
    return windows


def DefaultWindows(drive: Drive, endTime: Optional[float] = None,
                   minLength: float = 0.) -> List[Tuple[float, float]]:
    """The evaluation windows of ``simulate`` and ``sweep``: the phases of :func:`DefaultPhases` without their labels;
    for the reel changer lift / lower / lift of every rotation: [kT, kT + T/4], [kT + T/4, kT + 3T/4],
    [kT + 3T/4, (k+1)T] for k = 0, 1, ..., clipped to ``endTime``.

    Parameters
    ----------
    drive : Drive
        The drive with its duty (``motorSpeed`` in rad/s for the reel changer).
    endTime : float, optional
        Simulated time in s (default: one rotation T; another duty: :func:`DefaultSimulatedTime`).
    minLength : float
        Windows shorter than this (in s, after clipping) are dropped; the first window is always kept.

    Returns
    -------
    list of (float, float)
        Windows in s, in time order.
    """
    return [(t0, t1) for t0, t1, _ in DefaultPhases(drive, endTime, minLength)]


def WindowPhases(drive: Drive, windows: Sequence[Tuple[float, float]],
                 endTime: Optional[float] = None) -> List[str]:
    """The duty's phase in each window: ``'lift'``, ``'lower'`` (the load drives the gear) or ``'idle'``, or the
    phases a window spans joined by ``'+'`` (e.g. ``'lift+lower'``).

    Parameters
    ----------
    drive : Drive
        The drive with its duty (:func:`DefaultPhases`).
    windows : sequence of (float, float)
        Windows in s.
    endTime : float, optional
        Simulated time in s (default: the end of the last window or :func:`DefaultSimulatedTime`, the later).

    Returns
    -------
    list of str
        One label per window.
    """
    windows = [(float(t0), float(t1)) for t0, t1 in windows]
    if endTime is None:
        endTime = max([DefaultSimulatedTime(drive)] + [t1 for _, t1 in windows])
    phases = DefaultPhases(drive, max([endTime] + [t1 for _, t1 in windows]))
    labels = []
    for t0, t1 in windows:
        tol = 1e-9 * max(t1 - t0, 1e-300)
        inside = [ph for a, b, ph in phases if min(b, t1) - max(a, t0) > tol]
        labels.append('+'.join(dict.fromkeys(inside)) or phases[-1][2])
    return labels


def PhaseLabel(drive: Drive, phase: str, window: Optional[Tuple[float, float]] = None) -> str:
    """The words for a phase of :func:`WindowPhases` in a table: ``lift`` / ``lower`` for the reel changer; for
    another duty ``lifting`` / ``lowering`` (the load opposes the motion / drives the gear) and, for ``idle``,
    ``standstill under load`` where the motor stands while a load torque acts, ``no load`` where none acts.

    Parameters
    ----------
    drive : Drive
        The drive.
    phase : str
        A label of :func:`WindowPhases`.
    window : (float, float), optional
        The window in s (its middle tells a standstill under load from no load; without it ``idle`` reads ``idle``).
    """
    if IsReelChangerDuty(CheckDrive('PhaseLabel', drive).parameters):
        return phase
    words = {'lift': 'lifting', 'lower': 'lowering', 'idle': 'idle'}
    if window is not None:
        words['idle'] = _IdleWords(drive, 0.5 * (float(window[0]) + float(window[1])))
    return '+'.join(words.get(part, part) for part in phase.split('+'))


def _IdleWords(drive: Drive, t: float) -> str:
    """``standstill under load`` or ``no load`` at time t of the rigid kinematics (a phase without load power)."""
    load = drive.load
    if load is None:
        return 'no load'
    ratio = drive.gear.ratio
    motion = MotorMotion(drive.parameters, 'PhaseLabel')
    angle, speed = motion.AngleAndSpeed(t, MATH_OPS)
    torque = load.Torque(angle / ratio, speed / ratio, t, MATH_OPS)
    if abs(torque) <= 1e-9 * max(load.maximum, 1e-300):
        return 'no load'
    return 'standstill under load' if abs(speed) <= STANDSTILL_TOLERANCE * _LargestSpeed(motion) else 'idle'


#: the motor stands where its speed is at most this fraction of its own largest speed (a speed table interpolated
#: between rows of zero speed returns round-off, e.g. 8.9e-16 rad/s, not an exact 0)
STANDSTILL_TOLERANCE = 1e-9


def _LargestSpeed(motion) -> float:
    """The motor's largest speed in rad/s: a speed table's largest row, a constant or start-stop motor's speed (a
    motor on its characteristic: its no-load speed)."""
    if hasattr(motion, 'points'):
        return max((abs(float(w)) for _, w in motion.points), default=0.)
    return abs(float(getattr(motion, 'speed', getattr(motion, 'noLoadSpeed', 0.))))


def DefaultSimulatedTime(drive: Drive) -> float:
    """Simulated time in s when none is given: one wheel rotation for the reel changer (:func:`RotationPeriod`),
    else the end of the duty's tables and ramps (:func:`~exudyn_worm.drive.duty.DefaultEndTime`).

    Parameters
    ----------
    drive : Drive
        The drive.
    """
    if IsReelChangerDuty(CheckDrive('DefaultSimulatedTime', drive).parameters):
        return RotationPeriod(drive)
    CheckReelChangerKeys(drive, 'DefaultSimulatedTime')
    return DefaultEndTime(drive.parameters, drive.gear.ratio)


def _SolverCounters(mbs) -> Dict[str, Any]:
    """Work counters of the last solve: steps taken, Newton iterations, Jacobians, rejected (halved) steps."""
    it = mbs.sys['dynamicSolver'].it
    steps = mbs.sys['dynamicSolverSteps'] if 'dynamicSolverSteps' in mbs.sys else int(it.currentStepIndex) - 1
    return {'steps': steps, 'newtonIterations': int(it.newtonStepsCount),
            'jacobians': int(it.newtonJacobiCount), 'rejectedSteps': int(it.rejectedModifiedNewtonSteps),
            'minStepSize': float(it.minStepSize)}


def _ApplySolverOptions(ss, options: Mapping[str, Any], where: str):
    """Set dotted ``SimulationSettings`` paths of ``options`` on ``ss``; return the solver type."""
    import exudyn as exu
    options = dict(options)
    name = options.pop('solverType', 'GeneralizedAlpha')
    if not hasattr(exu.DynamicSolverType, str(name)):
        raise ValueError(f"{where}: solverOptions['solverType'] must name an exudyn.DynamicSolverType, got {name!r}")
    for path, value in options.items():
        *parents, leaf = path.split('.')
        target = ss
        for part in parents:
            target = getattr(target, part, None)
        if target is None or not hasattr(target, leaf):
            raise ValueError(f"{where}: solverOptions key {path!r} is not a SimulationSettings path")
        setattr(target, leaf, value)
    return getattr(exu.DynamicSolverType, str(name))


def SolverSettings(endTime: float, stepSize: float, solverOptions: Optional[Mapping[str, Any]] = None,
                   where: str = 'SolverSettings'):
    """The ``exudyn.SimulationSettings`` of :func:`SimulateReelChanger`: one place for the run settings.

    Nothing is written to disk, sensors store every step, Exudyn is silent, and :data:`SOLVER_SETTINGS`
    (overridden by ``solverOptions``) is applied.

    Parameters
    ----------
    endTime : float
        Simulated time in s, > 0.
    stepSize : float
        Time step in s, > 0 (the number of steps is ``round(endTime / stepSize)``, at least 1).
    solverOptions : mapping, optional
        Dotted ``SimulationSettings`` paths and values, and optionally ``'solverType'`` (the name of an
        ``exudyn.DynamicSolverType``), applied over :data:`SOLVER_SETTINGS`.
    where : str, optional
        Name used in error messages.

    Returns
    -------
    (exudyn.SimulationSettings, exudyn.DynamicSolverType)

    Raises
    ------
    ValueError
        For a ``solverOptions`` key that is not a settings path or an unknown solver type.
    """
    import exudyn as exu
    ss = exu.SimulationSettings()
    ss.solution.file.write = False                 # never litter the user's current directory
    ss.timeIntegration.endTime = endTime
    ss.timeIntegration.numberOfSteps = max(1, int(round(endTime / stepSize)))
    # a sample every step: a hair below the solver's step (endTime / numberOfSteps), or round-off skips the
    # sample at t = h (the sensor is written once t - tLastWrite >= writePeriod)
    ss.solution.sensors.writePeriod = endTime / ss.timeIntegration.numberOfSteps * (1. - 1e-9)
    ss.timeIntegration.verboseMode = 0
    return ss, _ApplySolverOptions(ss, {**SOLVER_SETTINGS, **(solverOptions or {})}, where)


def _LikelyCause(drive: ElasticDrive, stepSize: float) -> str:
    """Why a run of ``drive`` at ``stepSize`` may have failed, from the linearized drive's fastest eigenvalue."""
    rate = max(float(np.max(np.abs(EigenvaluesFromPolynomial(CharacteristicCoefficients(drive, S)))))
               for S in (1, -1))
    if stepSize * rate > 0.5:
        return (f"likely cause: the stiffest mode of the linearized drive (|lambda|max = {rate:.3g} 1/s) is far "
                f"faster than the step resolves (step * |lambda|max = {stepSize * rate:.2g}); resolving it needs a "
                f"step below about {0.1 / rate:.2g} s; if that is unreasonably small, a parameter is out of a "
                f"physical range (check values and units)")
    return (f"likely cause: parameters out of a physical range or a contact too stiff for the step "
            f"(step * |lambda|max = {stepSize * rate:.2g} of the linearized drive); check the parameters, "
            f"then try a smaller step size")


def SimulateReelChanger(drive: Drive, endTime: Optional[float] = None,
                        stepSize: Optional[float] = None, contactOptions: ContactOptions = ContactOptions(),
                        useSymbolic: bool = True, startFromEquilibrium: bool = True, profile=None,
                        solverOptions: Optional[Mapping[str, Any]] = None, maxSteps: int = MAX_STEPS,
                        progress: Optional[bool] = None) -> SimulationResult:
    """Build and simulate the reel changer with Exudyn's generalized-alpha solver.

    Parameters
    ----------
    drive : Drive
        The drive with its duty (e.g. ``ResolveDrive('reel-P1')``).
    endTime : float, optional
        Simulated time in s (default: one full rotation, 8 s for the paper's speed; another duty:
        :func:`DefaultSimulatedTime`).
    stepSize : float, optional
        Time step in s, > 0; refused above the hard limit and warned about above the soft limit of
        :func:`exudyn_worm.analysis.simulation.stepsize.CheckStepSize`. Default: the drive's own
        :func:`~exudyn_worm.analysis.simulation.stepsize.RecommendedStepSize` (7.8e-4 s for P1, 5.1e-4 s for P7).
    contactOptions : ContactOptions
        Options of the worm-gear contact law (see :func:`~exudyn_worm.builders.oneangle.BuildReelChanger`).
    useSymbolic : bool
        C++ symbolic user functions (default) or plain Python.
    startFromEquilibrium : bool
        Start in the static equilibrium under the initial load (default); see :func:`~exudyn_worm.builders.oneangle.BuildReelChanger`.
    profile : optional
        Motor motion with ``AngleAndSpeed(t, ops)`` (default: constant ``motorSpeed``); see
        :func:`~exudyn_worm.builders.oneangle.BuildReelChanger`.
    solverOptions : mapping, optional
        Changes to the solver settings, keyed by their path in ``exudyn.SimulationSettings`` (e.g.
        ``{'timeIntegration.newton.maxIterations': 10}``), and ``'solverType'`` (a name of
        ``exudyn.DynamicSolverType``, default ``'GeneralizedAlpha'``), applied over :data:`SOLVER_SETTINGS` (and, for
        the small-displacement 3D model, :data:`SMALL_3D_SOLVER_SETTINGS`). For benchmarks and studies.
    maxSteps : int
        Refuse a run of more than this many steps (:func:`CheckRunSize`, default :data:`MAX_STEPS`).
    progress : bool or None
        Progress bar on stderr: True shown, False never, None (default) shown when stderr is a terminal
        and the run takes longer than about 2 s (:func:`~exudyn_worm.items.solve.SolveDynamicInChunks`). The
        numbers do not depend on it.

    Returns
    -------
    SimulationResult
        Nothing is written to disk.

    Raises
    ------
    ValueError
        For bad arguments or parameters, or a run above ``maxSteps``.
    TypeError
        If ``drive`` is not a :class:`~exudyn_worm.drive.wholedrive.Drive`, ``contactOptions`` is not a
        :class:`~exudyn_worm.model.contact.ContactOptions` or ``profile`` has no ``AngleAndSpeed``.
    SolverDivergedError
        If the solver fails; the message gives the simulated time reached and the likely cause.
    """
    import exudyn as exu
    w = 'SimulateReelChanger'
    CheckReelChangerKeys(drive, w)
    parameters = drive.parameters
    CheckModelOptions(w, contactOptions, profile, useSymbolic, startFromEquilibrium)
    endTime = DefaultSimulatedTime(drive) if endTime is None else CheckPositive(w, 'endTime', endTime, 's')
    stepSize = RecommendedStepSize(drive) if stepSize is None else CheckPositive(w, 'stepSize', stepSize, 's')
    steps = CheckRunSize(endTime, stepSize, maxSteps, w)
    CheckStepSize(drive, stepSize, w)          # refuses a step that cannot resolve the drive's modes
    CheckWormRotation(parameters, stepSize, 'simulation')     # warns: a worm rotation in fewer than a few steps
    rigid = drive.isRigidBody                       # the 3D model (docs/mesh-3d.md)
    if rigid:
        # lazy: the 3D model's module builds on this one's helpers
        from . import reelchanger3d
        # a constant-speed motor is a flywheel, as in the one-angle model below (the small model; the exact one keeps
        # the constraint)
        model = BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), drive, contactOptions, useSymbolic, profile=profile,
                                          startFromEquilibrium=startFromEquilibrium, motorConstraint=False)
        reelchanger3d.AddSeriesSensors(model)
        if model.model == 'small':
            solverOptions = {**SMALL_3D_SOLVER_SETTINGS, **(solverOptions or {})}
    else:
        # the motor at constant speed as a flywheel: the constraint's numbers bit for bit, 12 % fewer instructions
        model = BuildReelChanger(exu.SystemContainer().AddSystem(), drive, contactOptions, useSymbolic,
                                 startFromEquilibrium, profile, motorConstraint=False)
    mbs = model.mbs
    mbs.Assemble()
    ss, solverType = SolverSettings(endTime, stepSize, solverOptions, w)
    printing = exu.config.printToConsole
    exu.config.printToConsole = False   # silences Exudyn's note on ObjectGenericODE2 allocations per step
    try:
        t0, c0 = _time.perf_counter(), _time.process_time()
        SolveDynamicInChunks(mbs, ss, solverType, progress=progress, desc=w)
        solveSeconds, solveCpuSeconds = _time.perf_counter() - t0, _time.process_time() - c0
    except IncompleteSolveError:           # stopped, not diverged: no likely cause of a divergence
        raise
    except SolverDivergedError as err:
        raise SolverDivergedError(f"{w}: {err}; {_LikelyCause(model.drive, stepSize)}",
                                  err.timeReached, err.endTime, err.stepSize) from err
    finally:
        exu.config.printToConsole = printing

    if rigid:
        series = reelchanger3d.StoredSeries(model)
    else:
        series = model.connector.StoredStates(mbs)
        for key in [k for k in model.sensors if k not in model.connector.sensors]:
            series[key] = mbs.GetSensorStoredData(model.sensors[key])[:, 1]
        if model.motorFlywheel:                     # its speed is motorSpeed to the last bit (FLYWHEEL_INERTIA)
            series['omega0'] = np.full(len(series['phi0']), model.motorSpeed)
    time = series.pop('time')
    # each chunk of the solve stores its start once more: keep one sample per time
    keep = np.concatenate([[True], np.diff(time) > 1e-6 * stepSize])
    time = time[keep]
    series = {k: v[keep] for k, v in series.items()}
    if rigid:
        mesh = reelchanger3d.StoredMeshState(model, keep)
    else:
        mesh = model.connector.Evaluate(series['phi1'], series['phi2'], series['omega1'], series['omega2'],
                                        series.get('xA'), series.get('vA'), time)
    core = model.drive
    motorSide = '4' if not rigid and model.chain else '0'   # the drive shaft (spring-Damper1) ends at inertia4 or the motor
    series.update(deltaPhi=mesh.deltaPhi, deltaS=mesh.deltaS, normalForce=mesh.normalForce, S=mesh.S, sf=mesh.sf,
                  wormTorque=mesh.wormTorque, wheelTorque=mesh.wheelTorque,
                  # eq. (6): torque in the drive shaft; eq. (7): tangential force at the wheel
                  driveTorque=core.kT * (series['phi1'] - series['phi' + motorSide])
                  + core.dT * (series['omega1'] - series['omega' + motorSide]),
                  tangentialForce=mesh.wheelTorque / core.gear.r2)
    if model.axialBearing is not None:
        series['axialForce'] = mesh.axialForce
    if rigid:
        series.update(reelchanger3d.MeshForceSeries(model, mesh))
    CheckWormSpeed(series['omega1'], series.get('omega0', ()), parameters, 'simulation', time)  # the load drives the worm
    return SimulationResult(time=time, series=series, J2=core.J2, r2=core.gear.r2, solveSeconds=solveSeconds,
                            steps=steps, info={'stepSize': stepSize,
                                               'maxLoadTorque': model.load.maximum if model.load is not None else 0.,
                                               'loadType': parameters.get('loadType', 'lever'),
                                               'frictionSpeed': contactOptions.frictionSpeed,
                                               # sliding speed per worm speed (the chatter rule's sliding floor)
                                               'slidingRadius': core.gear.r1 / math.cos(core.gear.gamma),
                                               'frictionModel': contactOptions.frictionModel,
                                               'useSymbolic': useSymbolic, 'solver': _SolverCounters(mbs),
                                               'solveCpuSeconds': solveCpuSeconds,
                                               # the duty's lift / lower / idle phases, shaded by the plots
                                               'phases': DefaultPhases(drive, float(time[-1]))})
