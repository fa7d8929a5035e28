"""The reel changer with the worm driven by the shaft torque as a user-function load (benchmark lever).

Not part of the package. :func:`exudyn_worm.builders.oneangle.BuildReelChanger` prescribes the motor angle with a
``CoordinateConstraint``, which Exudyn's explicit and adaptive integrators (RK44, ODE23, DOPRI5) ignore.
Here the motor node and its constraint are left out: the prescribed motor enters only through the shaft
torque ``kT (phi0(t) - phi1) + dT (omega0(t) - omega1)`` (eq. (6)), applied to the worm with
:func:`CreateRotorTorque`. Equations (1)-(2) are unchanged (the motor's own inertia never mattered: its
motion is prescribed), so this is the same model; tests/test_torque_driven.py checks it against
:func:`SimulateReelChanger`.
"""
from __future__ import annotations

import time as _time
from typing import Any, Mapping, Optional

import exudyn as exu
from exudyn_worm.items.connector import CreateWormGear
from exudyn_worm.model.contact import ContactOptions
from exudyn_worm.model.friction import MATH_OPS
from exudyn_worm.items.drivetrain import CreateRotor, CreateRotorTorque
from exudyn_worm.drive.presets import ElasticDriveFromParameters
from exudyn_worm.model.profiles import ConstantSpeed, GravityLeverTorque
from exudyn_worm.analysis.simulation.reelchanger import RotationPeriod, SolverSettings
from exudyn_worm.items.equilibrium import SteadyInitialState
from exudyn_worm.items.results import SimulationResult
from exudyn_worm.drive.wholedrive import ResolveDrive

__all__ = ['SimulateTorqueDriven']


def SimulateTorqueDriven(parameters: Mapping[str, float], stepSize: float, endTime: Optional[float] = None,
                         solverType: str = 'GeneralizedAlpha', solverOptions: Optional[Mapping[str, Any]] = None,
                         contactOptions: ContactOptions = ContactOptions()) -> SimulationResult:
    """Simulate the reel changer with the motor acting through the shaft torque (no constraint).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set (e.g. ``GetPreset('reel-P1')``).
    stepSize : float
        Time step in s (the maximum step for the adaptive integrators), also the output period.
    endTime : float, optional
        Simulated time in s (default one wheel rotation).
    solverType : str
        Name of an ``exudyn.DynamicSolverType`` (``'GeneralizedAlpha'``, ``'RK44'``, ``'DOPRI5'``, ``'ODE23'``).
    solverOptions : mapping, optional
        Dotted ``SimulationSettings`` paths and values, applied after :data:`SOLVER_SETTINGS`.
    contactOptions : ContactOptions
        Options of the contact law.

    Returns
    -------
    SimulationResult
        With ``phi1, omega1, alpha1, phi2, omega2, alpha2`` and the mesh quantities; ``info['solver']`` holds
        the steps taken.
    """
    import exudyn as exu
    drive = ElasticDriveFromParameters(parameters)
    motorSpeed = parameters['motorSpeed']
    load = GravityLeverTorque(mass=parameters['loadMass'], leverArm=parameters['leverArm'])
    motor = ConstantSpeed(motorSpeed)
    init = SteadyInitialState(drive, load, motorSpeed, contactOptions)
    endTime = RotationPeriod(ResolveDrive(parameters=parameters)) if endTime is None else float(endTime)

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    worm = CreateRotor(mbs, drive.J1, initialAngle=init['phi1'], initialSpeed=init['omega1'], name='worm')
    wheel = CreateRotor(mbs, drive.J2, initialAngle=init['phi2'], initialSpeed=init['omega2'], name='wheel')
    kT, dT = drive.kT, drive.dT

    def ShaftTorque(phi, omega, t, ops):
        phi0, omega0 = motor.AngleAndSpeed(t, ops)
        return kT * (phi0 - phi) + dT * (omega0 - omega)

    CreateRotorTorque(mbs, worm, ShaftTorque, name='shaftTorque')
    connector = CreateWormGear(mbs, [worm['nodeNumber'], wheel['nodeNumber']], gear=drive.gear,
                               contactOptions=contactOptions, name='wormGear')
    CreateRotorTorque(mbs, wheel, load, name='reelLoad')
    connector.AddSensors(mbs)
    mbs.Assemble()

    ss, solver = SolverSettings(endTime, stepSize, {**(solverOptions or {}), 'solverType': solverType},
                                'SimulateTorqueDriven')
    printing = exu.config.printToConsole
    exu.config.printToConsole = False
    try:
        t0, c0 = _time.perf_counter(), _time.process_time()
        mbs.SolveDynamic(ss, solverType=solver)
        solveSeconds, solveCpuSeconds = _time.perf_counter() - t0, _time.process_time() - c0
    finally:
        exu.config.printToConsole = printing
    series = connector.StoredStates(mbs)
    time = series.pop('time')
    mesh = connector.Evaluate(series['phi1'], series['phi2'], series['omega1'], series['omega2'], time=time)
    series.update(deltaPhi=mesh.deltaPhi, deltaS=mesh.deltaS, normalForce=mesh.normalForce, S=mesh.S, sf=mesh.sf,
                  wormTorque=mesh.wormTorque, wheelTorque=mesh.wheelTorque)
    it = mbs.sys['dynamicSolver'].it
    info = {'solverType': solverType, 'stepSize': stepSize, 'solveCpuSeconds': solveCpuSeconds,
            'solver': {'steps': int(it.currentStepIndex) - 1, 'newtonIterations': int(it.newtonStepsCount),
                       'jacobians': int(it.newtonJacobiCount), 'rejectedSteps': int(it.rejectedModifiedNewtonSteps)},
            'shaftTorqueAtStart': ShaftTorque(init['phi1'], init['omega1'], 0., MATH_OPS)}
    return SimulationResult(time=time, series=series, J2=drive.J2, r2=drive.gear.r2, solveSeconds=solveSeconds,
                            steps=int(round(endTime / stepSize)), info=info)
