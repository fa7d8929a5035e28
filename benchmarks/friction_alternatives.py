"""Sticking at zero worm speed: the package's stick/slip switch against a LuGre bristle state.

Not part of the package: the measurements behind docs/friction-sticking.md. Three friction models of the mesh:

- ``regularized``: ``ContactOptions(frictionModel='regularized')``, the law of earlier versions (no state);
- ``sticking``: ``ContactOptions()``, the package's default: a stick/slip state switched by the post-Newton
  user function (Exudyn's discontinuous iteration), stick as a tangential spring-damper to an anchor;
- ``lugre``: a LuGre friction state (Canudas de Wit, Olsson, Astrom, Lischinsky, IEEE TAC 40(3), 1995, eqs.
  (1)-(3) with g(v) = mu Fn constant): the bristle deflection ``z`` (m) is an extra ODE2 coordinate,
  ``dz/dt = v - sigma0 |v| z / (mu Fn)``, friction ``Phi = sigma0 z + sigma1 dz/dt`` on the sliding coordinate
  (``contact.SlidingCoordinate``), everything in one symbolic (C++) user function, no Python during the solve.
  The first-order law is imposed on a coordinate with a small mass by a stiff damper
  (``m z'' = c (rate - z')``, relaxation time ``m/c``).

Cases: the hold test (reel-P1 gear, 175 kg at 1.2 m, no motor; from rest and after lowering at
-49.5 rad/s; drift of the wheel over 18 s after 5 s of settling) and the reel changer P1/P7 (motor through the
shaft torque, as benchmarks/torque_driven.py) with the peaks of benchmarks/bench_reel_changer.py.

    python benchmarks/friction_alternatives.py            # about 1 min on a quiet machine
"""
from __future__ import annotations

import sys
import time as _time
from pathlib import Path
from typing import Dict

import exudyn as exu
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from exudyn_worm import GetPreset                                           # noqa: E402
from exudyn_worm.items._userfunctions import AddGenericForce                      # noqa: E402
from exudyn_worm.items.connector import CreateWormGear                            # noqa: E402
from exudyn_worm.model.contact import ContactOptions, MeshContact, SlidingCoordinate  # noqa: E402
from exudyn_worm.model.friction import NUMPY_OPS
from exudyn_worm.items.drivetrain import CreateRotor, CreateRotorTorque           # noqa: E402
from exudyn_worm.drive.presets import ElasticDriveFromParameters                         # noqa: E402
from exudyn_worm.model.profiles import ConstantSpeed, GravityLeverTorque          # noqa: E402
from exudyn_worm.analysis.simulation.reelchanger import RotationPeriod, SolverSettings  # noqa: E402
from exudyn_worm.items.equilibrium import SteadyInitialState
from exudyn_worm.items.results import SimulationResult                            # noqa: E402
from exudyn_worm.analysis.simulation.stepsize import RecommendedStepSize                        # noqa: E402
from exudyn_worm.drive.wholedrive import ResolveDrive

#: bristle mass (kg-equivalent of the z equation) and damper: relaxation time 1e-5 s, below every step used
LUGRE_MASS, LUGRE_DAMPER = 1e-5, 1.


def AddLuGreMesh(mbs, worm, wheel, gear, sigma0: float, sigma1: float, omega1: float = 0., fn0: float = 0.):
    """The mesh with a LuGre friction state; returns the bristle node. ``omega1``, ``fn0``: initial worm speed
    and normal force (the bristle starts at its steady deflection ``sign(omega1) mu Fn / sigma0``)."""
    from exudyn.itemInterface import Node1D, ObjectMass1D
    z0 = float(np.sign(omega1)) * gear.mu * fn0 / sigma0
    nZ = mbs.AddNode(Node1D(referenceCoordinates=[0.], initialCoordinates=[z0], initialVelocities=[0.]))
    mbs.AddObject(ObjectMass1D(nodeNumber=nZ, mass=LUGRE_MASS))
    frictionless = gear.Replace(mu=0.)
    c1, c2 = SlidingCoordinate(gear, 1., 0.), SlidingCoordinate(gear, 0., 1.)

    def Law(t, q, q_t, ops):
        mesh = MeshContact(frictionless, q[0], q[1], q_t[0], q_t[1], ContactOptions(), ops)
        fn = ops.abs(mesh.normalForce)
        v = SlidingCoordinate(gear, q_t[0], q_t[1])
        rate = v - sigma0 * ops.abs(v) * q[2] / ops.max(gear.mu * fn, 1e-3)
        phi = sigma0 * q[2] + sigma1 * q_t[2]
        return [mesh.wormTorque - c1 * phi, mesh.wheelTorque - c2 * phi, LUGRE_DAMPER * (rate - q_t[2])]

    AddGenericForce(mbs, [worm['nodeNumber'], wheel['nodeNumber'], nZ], Law, name='lugreMesh')
    return nZ


def _Solve(mbs, endTime, h, sensors):
    import exudyn as exu
    from exudyn.itemInterface import SensorNode
    ids = {k: mbs.AddSensor(SensorNode(nodeNumber=n, outputVariableType=ovt, storeInternal=True, writeToFile=False))
           for k, (n, ovt) in sensors.items()}
    mbs.Assemble()
    ss, solverType = SolverSettings(endTime, h)
    printing, exu.config.printToConsole = exu.config.printToConsole, False
    try:
        c0 = _time.process_time()
        mbs.SolveDynamic(ss, solverType=solverType)
        cpu = _time.process_time() - c0
    finally:
        exu.config.printToConsole = printing
    data = {k: np.asarray(mbs.GetSensorStoredData(i)) for k, i in ids.items()}
    it = mbs.sys['dynamicSolver'].it
    return data, cpu, int(it.currentStepIndex) - 1


def HoldTest(model: str, omega1: float, endTime: float = 23., settle: float = 5., h: float = 5e-4,
             mu: float = None) -> Dict:
    """Wheel drift (rad) over ``endTime - settle`` s after ``settle`` s: reel-P1 gear, hanging load, no motor."""
    import exudyn as exu
    p = GetPreset('reel-P1')
    drive = ElasticDriveFromParameters(p)
    gear = drive.gear if mu is None else drive.gear.Replace(mu=mu)
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    worm = CreateRotor(mbs, drive.J1, initialSpeed=omega1)
    wheel = CreateRotor(mbs, drive.J2, initialSpeed=omega1 / gear.ratio)
    if model == 'lugre':
        AddLuGreMesh(mbs, worm, wheel, gear, gear.kV, gear.dV, omega1)
    else:
        CreateWormGear(mbs, [worm, wheel], gear=gear, contactOptions=ContactOptions(frictionModel=model))
    CreateRotorTorque(mbs, wheel, GravityLeverTorque(mass=p['loadMass'], leverArm=p['leverArm']))
    OVT = exu.OutputVariableType
    data, cpu, steps = _Solve(mbs, endTime, h, {'phi2': (wheel['nodeNumber'], OVT.Coordinates)})
    t, phi2 = data['phi2'][:, 0], data['phi2'][:, 1]
    k = int(np.searchsorted(t, settle))
    return {'drift': float(np.max(np.abs(phi2[k:] - phi2[k]))), 'phi2End': float(phi2[-1]), 'cpu': cpu}


def SimulateReel(parameters, model: str, stepSize: float = None) -> SimulationResult:
    """The reel changer (motor through the shaft torque) with the mesh of ``model``."""
    import exudyn as exu
    drive = ElasticDriveFromParameters(parameters)
    h = RecommendedStepSize(ResolveDrive(parameters=parameters)) if stepSize is None else stepSize
    motor = ConstantSpeed(parameters['motorSpeed'])
    load = GravityLeverTorque(mass=parameters['loadMass'], leverArm=parameters['leverArm'])
    init = SteadyInitialState(drive, load, parameters['motorSpeed'], ContactOptions(frictionModel='regularized'))
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    worm = CreateRotor(mbs, drive.J1, initialAngle=init['phi1'], initialSpeed=init['omega1'])
    wheel = CreateRotor(mbs, drive.J2, initialAngle=init['phi2'], initialSpeed=init['omega2'])
    kT, dT = drive.kT, drive.dT
    CreateRotorTorque(mbs, worm, lambda phi, omega, t, ops: kT * (motor.AngleAndSpeed(t, ops)[0] - phi)
                      + dT * (motor.AngleAndSpeed(t, ops)[1] - omega))
    g = drive.gear
    fn0 = abs(MeshContact(g, init['phi1'], init['phi2'], init['omega1'], init['omega2']).normalForce)
    if model == 'lugre':
        AddLuGreMesh(mbs, worm, wheel, g, g.kV, g.dV, init['omega1'], fn0)
    else:
        CreateWormGear(mbs, [worm, wheel], gear=g, contactOptions=ContactOptions(frictionModel=model))
    CreateRotorTorque(mbs, wheel, load)
    OVT = exu.OutputVariableType
    sensors = {k: (r['nodeNumber'], o) for k, r, o in (('phi1', worm, OVT.Coordinates), ('omega1', worm, OVT.Coordinates_t),
                                                        ('phi2', wheel, OVT.Coordinates), ('omega2', wheel, OVT.Coordinates_t),
                                                        ('alpha2', wheel, OVT.Coordinates_tt))}
    T = RotationPeriod(ResolveDrive(parameters=parameters))
    data, cpu, steps = _Solve(mbs, T, h, sensors)
    series = {k: v[:, 1] for k, v in data.items()}
    mesh = MeshContact(g, series['phi1'], series['phi2'], series['omega1'], series['omega2'],
                       ContactOptions(frictionModel='regularized'), NUMPY_OPS)
    # normal force from the law; S and the wheel torque only feed WindowMetrics' counters, not judged here
    series.update(normalForce=mesh.normalForce, S=mesh.S, wheelTorque=mesh.wheelTorque)
    return SimulationResult(time=data['phi1'][:, 0], series=series, J2=drive.J2, r2=g.r2, solveSeconds=cpu,
                            steps=steps, info={'solveCpuSeconds': cpu, 'solver': {'steps': steps}})


def Main() -> None:
    from bench_reel_changer import _Peaks2
    print('hold test (reel-P1 gear, 175 kg at 1.2 m, no motor): wheel drift over 18 s after 5 s settling')
    for model in ('regularized', 'sticking', 'lugre'):
        rest, lowering = HoldTest(model, 0.), HoldTest(model, -49.5)
        print(f"  {model:12s} from rest {rest['drift']:.3g} rad ({rest['cpu']:.2f} s CPU), after lowering "
              f"{lowering['drift']:.3g} rad ({lowering['cpu']:.2f} s CPU)")
    runaway = HoldTest('sticking', 0., endTime=3., settle=0., mu=0.03)
    print(f"  sticking, mu 0.03: wheel turns {runaway['drift']:.3g} rad in 3 s (runs away)")
    print('reel changer (motor through the shaft torque), peaks in the lowering window:')
    for name in ('reel-P1', 'reel-P7'):
        p = GetPreset(name)
        for model in ('regularized', 'sticking', 'lugre'):
            r = SimulateReel(p, model)
            pk = _Peaks2(r, p)
            print(f"  {name} {model:12s} max|phi2''| {pk['maxAbsAlpha2']:9.3f}  max Fn {pk['maxNormalForce']:10.1f}  "
                  f"CPU {r.info['solveCpuSeconds']:.3f} s  steps {r.steps}")


if __name__ == '__main__':
    Main()
