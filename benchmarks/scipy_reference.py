"""A straightforward scipy ``solve_ivp`` model of the reel changer: the benchmark's comparison baseline.

Not part of the package. It integrates the paper's equations (1)-(2) for the reel changer of section 3.2
as a first-order system with state ``y = [phi1, phi2, omega1, omega2]``:

    J1 phi1'' = kT (phi0 - phi1) + dT (omega0 - omega1) + M_worm(phi1, phi2, omega1, omega2)
    J2 phi2'' = M_wheel(phi1, phi2, omega1, omega2) + M2(phi2)

with the prescribed motor angle ``phi0(t) = motorSpeed * t`` (:class:`~exudyn_worm.model.profiles.ConstantSpeed`),
the mesh torques from :func:`exudyn_worm.model.contact.MeshContact` with the plain-Python backend ``MATH_OPS``
(the same law the Exudyn connector records; nothing is re-derived here), the load torque
``M2 = -m g l cos(phi2)`` from :meth:`GravityLeverTorque.Torque` and the same initial state as the
Exudyn model (:func:`exudyn_worm.items.equilibrium.SteadyInitialState`).

The result is a :class:`exudyn_worm.items.results.SimulationResult` with the same series names as
:func:`exudyn_worm.analysis.simulation.reelchanger.SimulateReelChanger`, so both are evaluated by the same
``WindowMetrics``. Accelerations are the right-hand side evaluated at the output points.
"""
from __future__ import annotations

import math
import time as _time
from typing import Callable, Mapping, Optional, Tuple

import numpy as np
from scipy.integrate import solve_ivp

from exudyn_worm.model.contact import ContactOptions, MeshContact
from exudyn_worm.model.friction import MATH_OPS, NUMPY_OPS
from exudyn_worm.model.drive import ElasticDrive
from exudyn_worm.drive.presets import ElasticDriveFromParameters
from exudyn_worm.model.profiles import ConstantSpeed, GravityLeverTorque
from exudyn_worm.analysis.simulation.reelchanger import DEFAULT_STEP_SIZE, RotationPeriod
from exudyn_worm.items.equilibrium import SteadyInitialState
from exudyn_worm.items.results import SimulationResult
from exudyn_worm.drive.wholedrive import ResolveDrive

#: the reference models have no stick state: they use the regularized friction law (docs/friction-sticking.md);
#: where the worm never stops (P1) it gives the same results as the package's default sticking law
REGULARIZED = ContactOptions(frictionModel='regularized')

__all__ = ['ReelChangerOde', 'SolveReelChangerScipy', 'ResultFromStates']


def ReelChangerOde(parameters: Mapping[str, float], contactOptions: ContactOptions = REGULARIZED
                   ) -> Tuple[Callable, np.ndarray, ElasticDrive, GravityLeverTorque, ConstantSpeed]:
    """Right-hand side ``f(t, y)`` of the reel changer, its initial state and the model pieces.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set (e.g. ``GetPreset('reel-P1')``).
    contactOptions : ContactOptions
        Options of the contact law (as for the Exudyn model).

    Returns
    -------
    (rhs, y0, drive, load, motor)
        ``rhs(t, y)`` returns ``[omega1, omega2, alpha1, alpha2]`` as a list of floats; ``y0`` is
        ``[phi1, phi2, omega1, omega2]`` at t = 0.
    """
    drive = ElasticDriveFromParameters(parameters)
    gear, J1, J2, kT, dT = drive.gear, drive.J1, drive.J2, drive.kT, drive.dT
    motorSpeed = parameters['motorSpeed']
    load = GravityLeverTorque(mass=parameters['loadMass'], leverArm=parameters['leverArm'])
    motor = ConstantSpeed(motorSpeed)

    def rhs(t, y):
        # plain Python floats: MATH_OPS.sign fails on numpy scalars (np.bool_ subtraction)
        phi1, phi2, omega1, omega2 = np.asarray(y, dtype=float).tolist()
        t = float(t)
        phi0, omega0 = motor.AngleAndSpeed(t, MATH_OPS)
        mesh = MeshContact(gear, phi1, phi2, omega1, omega2, contactOptions, MATH_OPS)
        shaft = kT * (phi0 - phi1) + dT * (omega0 - omega1)
        alpha1 = (shaft + mesh.wormTorque) / J1
        alpha2 = (mesh.wheelTorque + load.Torque(phi2, omega2, t, MATH_OPS)) / J2
        return [omega1, omega2, alpha1, alpha2]

    init = SteadyInitialState(drive, load, motorSpeed, contactOptions)
    y0 = np.array([init['phi1'], init['phi2'], init['omega1'], init['omega2']])
    return rhs, y0, drive, load, motor


def SolveReelChangerScipy(parameters: Mapping[str, float], endTime: Optional[float] = None,
                          method: str = 'LSODA', rtol: float = 1e-6, atol: float = 1e-9,
                          outputStep: float = DEFAULT_STEP_SIZE, maxStep: float = math.inf,
                          contactOptions: ContactOptions = REGULARIZED) -> SimulationResult:
    """Integrate the reel changer with :func:`scipy.integrate.solve_ivp`.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set (e.g. ``GetPreset('reel-P1')``).
    endTime : float, optional
        Simulated time in s (default: one full wheel rotation, as the Exudyn model).
    method : str
        ``solve_ivp`` method ('LSODA', 'Radau', 'BDF', 'RK45', 'DOP853', ...).
    rtol, atol : float
        ``solve_ivp`` tolerances; ``atol`` applies to all states (rad and rad/s).
    outputStep : float
        Spacing of the output points in s (``t_eval``); default the Exudyn default step, so both
        results are sampled on the same grid.
    maxStep : float
        ``max_step`` of ``solve_ivp``.
    contactOptions : ContactOptions
        Options of the contact law.

    Returns
    -------
    SimulationResult
        ``solveSeconds`` is the wall time of the ``solve_ivp`` call alone; ``info`` holds the
        method, the tolerances, the CPU time of that call (``solveCpuSeconds``) and the work counters
        of ``solve_ivp`` (``nfev``, ``njev``, ``nlu``).

    Raises
    ------
    RuntimeError
        If ``solve_ivp`` fails.
    """
    endTime = RotationPeriod(ResolveDrive(parameters=parameters)) if endTime is None else float(endTime)
    rhs, y0, drive, load, motor = ReelChangerOde(parameters, contactOptions)
    n = int(round(endTime / outputStep))
    tEval = np.linspace(0., n * outputStep, n + 1)
    tEval = tEval[tEval <= endTime]
    t0, c0 = _time.perf_counter(), _time.process_time()
    sol = solve_ivp(rhs, (0., endTime), y0, method=method, t_eval=tEval, rtol=rtol, atol=atol,
                    max_step=maxStep)
    solveSeconds, solveCpuSeconds = _time.perf_counter() - t0, _time.process_time() - c0
    if not sol.success:
        raise RuntimeError(f"SolveReelChangerScipy: solve_ivp({method}, rtol={rtol:g}, atol={atol:g}) failed: "
                           f"{sol.message}")

    accel = np.array([rhs(t, y)[2:] for t, y in zip(sol.t, sol.y.T)])   # phi'' from the RHS at output points
    info = {'method': method, 'rtol': rtol, 'atol': atol, 'solveCpuSeconds': solveCpuSeconds, 'nfev': int(sol.nfev),
            'njev': int(sol.njev), 'nlu': int(sol.nlu), 'outputStep': outputStep}
    return ResultFromStates(sol.t, sol.y, accel, drive, motor, contactOptions, solveSeconds, info)


def ResultFromStates(time, y, accel, drive: ElasticDrive, motor, contactOptions: ContactOptions, solveSeconds: float,
                     info: dict) -> SimulationResult:
    """The :class:`SimulationResult` of states ``y`` (4 x n: phi1, phi2, omega1, omega2) and accelerations
    ``accel`` (n x 2) on ``time``: the series of :func:`SimulateReelChanger`, post-processed with the contact law.

    Parameters
    ----------
    time : ndarray
        Output times in s.
    y : ndarray
        States, shape (4, n).
    accel : ndarray
        Worm and wheel accelerations, shape (n, 2).
    drive : ElasticDrive
        The drive.
    motor : ConstantSpeed
        The motor motion.
    contactOptions : ContactOptions
        Options of the contact law.
    solveSeconds : float
        Wall time of the solve.
    info : dict
        Solver information (``frictionSpeed`` is added).
    """
    phi1, phi2, omega1, omega2 = y
    phi0, omega0 = motor.AngleAndSpeed(time, NUMPY_OPS)
    mesh = MeshContact(drive.gear, phi1, phi2, omega1, omega2, contactOptions, NUMPY_OPS)
    series = {'phi0': phi0, 'omega0': omega0, 'phi1': phi1, 'omega1': omega1, 'alpha1': accel[:, 0],
              'phi2': phi2, 'omega2': omega2, 'alpha2': accel[:, 1],
              'deltaPhi': mesh.deltaPhi, 'deltaS': mesh.deltaS, 'normalForce': mesh.normalForce, 'S': mesh.S,
              'sf': mesh.sf, 'wormTorque': mesh.wormTorque, 'wheelTorque': mesh.wheelTorque,
              'driveTorque': drive.kT * (phi1 - phi0) + drive.dT * (omega1 - omega0),
              'tangentialForce': mesh.wheelTorque / drive.gear.r2}
    return SimulationResult(time=time, series=series, J2=drive.J2, r2=drive.gear.r2, solveSeconds=solveSeconds,
                            steps=0, info={**info, 'frictionSpeed': contactOptions.frictionSpeed})
