"""Friction that falls with sliding speed: where the reel changer chatters, and a load that runs away once moving.

Three pictures and one simulation, computed by importable functions (checked by
tests/test_example_friction_speed.py), drawn only when the file is run::

    python examples/friction_speed.py --out friction_speed      # writes PNG files into that folder

1. :func:`FrictionCurves`: mu(v) of the constant law (0.132, the paper's), the Stribeck law used here
   (reel-P3 with ``mu = 0.092``, ``muStatic = 0.2``, ``stribeckVelocity = 0.9 m/s``: mu = 0.132 at the paper's
   472.5 rpm, v0 = 0.897 m/s) and the AGMA 6034 curve.
2. :func:`SpeedChart`: the largest real part of the lowering state against motor speed, eq. (16) extended by the
   friction slope at each operating point (:func:`exudyn_worm.analysis.charts.speedchart.SpeedStabilityChart`). With constant mu
   it does not depend on speed; with the Stribeck law reel-P3 chatters while lowering between the boundaries near
   85 and 610 rpm (``exudyn-worm chart --speed``, docs/charts.md); the example prints the unstable speeds of its own
   grid, which lie inside them.
3. :func:`ChatterAmplitudes`: the simulated chatter amplitude against speed: J2 max abs(phi2'') in the lowering
   phase of the reel-changer simulation (one run per speed, ending with the lowering phase).
4. :func:`RunAway`, the dangerous case "statically but not dynamically self-locking": reel-P1's gear
   (gamma = 5.32 deg) with the AGMA curve is self-locking at rest (mu 0.150, rho = 9.1 deg) but not at the reel
   changer's sliding speed (mu 0.045, rho = 2.8 deg). The reel on its lever at the horizontal, lowering, the motor
   gone (worm free): with constant mu = 0.132 the worm brakes to (nearly) zero speed; with the AGMA law the load
   drives the worm faster and faster: it runs away once moving.

   :func:`HoldAtRest`, the other half: the same AGMA gear started at rest holds its load without creep (true
   sticking at zero sliding speed, the connector's default, ``docs/friction-sticking.md``): self-locking at rest
   (mu 0.150 > tan(gamma) cos(alphaN)). Both halves together are the dangerous case: the brake-free gear holds the
   reel while the drive stands, and lets it run away once it moves.
"""
from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Dict, Sequence

import exudyn as exu
import numpy as np

import exudyn_worm as ew
from exudyn_worm.model.friction import NUMPY_OPS, AgmaFriction, ConstantFriction, StribeckFriction
from exudyn_worm.analysis.simulation.reelchanger import RotationPeriod, SimulateReelChanger
from exudyn_worm.analysis.charts.speedchart import RPM, SpeedStabilityChart
from exudyn_worm.drive.wholedrive import ResolveDrive

#: reel-P3 with the Stribeck law of docs/friction.md: mu(v0) = 0.132 at 472.5 rpm
PARAMETERS = {**ew.GetPreset('reel-P3'), 'frictionLaw': 'stribeck', 'mu': 0.092, 'muStatic': 0.2,
              'stribeckVelocity': 0.9}
#: motor speeds of the simulated amplitudes (rpm)
SIMULATED_RPM = (60., 100., 160., 250., 400., 630., 1000., 1600.)


def FrictionCurves(v: Sequence[float]) -> Dict[str, np.ndarray]:
    """mu(v) of the three laws at the sliding speeds ``v`` (m/s).

    Parameters
    ----------
    v : sequence of float
        Sliding speeds in m/s, >= 0.

    Returns
    -------
    dict
        ``{'constant', 'stribeck', 'agma'}`` -> mu values.
    """
    v = np.asarray(v, dtype=float)
    laws = {'constant': ConstantFriction(0.132),
            'stribeck': StribeckFriction(PARAMETERS['mu'], PARAMETERS['muStatic'], PARAMETERS['stribeckVelocity']),
            'agma': AgmaFriction()}
    return {name: np.asarray(law.Mu(v, NUMPY_OPS), dtype=float) * np.ones_like(v)
            for name, law in laws.items()}


def SpeedChart(rpm: Sequence[float] = tuple(np.geomspace(20., 2000., 60))):
    """The largest real part of the lowering state over motor speed, Stribeck law and constant mu.

    Parameters
    ----------
    rpm : sequence of float
        Motor speeds in rpm.

    Returns
    -------
    dict
        ``{'stribeck': SpeedChart, 'constant': SpeedChart}``.
    """
    speeds = np.asarray(rpm, dtype=float) * RPM
    constant = {k: v for k, v in PARAMETERS.items() if k not in ('frictionLaw', 'muStatic', 'stribeckVelocity')}
    return {'stribeck': SpeedStabilityChart(ResolveDrive(parameters=PARAMETERS), speeds),
            'constant': SpeedStabilityChart(ResolveDrive(parameters={**constant, 'mu': 0.132}), speeds)}


def ChatterAmplitudes(rpm: Sequence[float] = SIMULATED_RPM) -> Dict[str, np.ndarray]:
    """Simulated chatter amplitude in the lowering phase against motor speed (reel-changer model, Stribeck law).

    Parameters
    ----------
    rpm : sequence of float
        Motor speeds in rpm.

    Returns
    -------
    dict
        ``rpm``, ``amplitude`` (J2 max abs(phi2'') in the lowering phase T/4 ... 3T/4, rad/s^2), ``chatter`` (the
        chatter rule of ``exudyn-worm simulate`` in that phase).
    """
    amplitude, chatter = [], []
    for n in rpm:
        p = ew.ApplyOverrides(PARAMETERS, {'motorSpeed': n * RPM})
        T = RotationPeriod(ResolveDrive(parameters=p))
        result = SimulateReelChanger(ResolveDrive(parameters=p), endTime=0.75 * T, stepSize=min(5e-4, ew.RecommendedStepSize(ResolveDrive(parameters=p))),
                                     progress=False)
        window, = result.WindowMetrics([(0.25 * T, 0.75 * T)])
        amplitude.append(window['maxAbsWheelAcceleration'])
        chatter.append(window['chatter'])
    return {'rpm': np.asarray(rpm, dtype=float), 'amplitude': np.array(amplitude), 'chatter': np.array(chatter)}


def _FreeWorm(law: str, omega1: float, endTime: float, stepSize: float, where: str) -> Dict[str, np.ndarray]:
    """reel-P1's gear and inertias without drive shaft (the worm free), the reel's load torque on the wheel at
    phi2 = pi (horizontal, lowering: the load drives), both shafts starting at worm speed ``omega1`` (rad/s)."""
    import exudyn as exu
    p = ew.GetPreset('reel-P1')
    if law == 'agma':
        p = {**p, 'frictionLaw': 'agma'}
    elif law != 'constant':
        raise ValueError(f"{where}: 'law' must be 'agma' or 'constant', got {law!r}")
    drive = ew.ElasticDriveFromParameters(p)
    u = drive.gear.ratio
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    worm = ew.CreateRotor(mbs, inertia=drive.J1, initialAngle=u * math.pi, initialSpeed=omega1)
    wheel = ew.CreateRotor(mbs, inertia=drive.J2, initialAngle=math.pi, initialSpeed=omega1 / u)
    mesh = ew.CreateWormGear(mbs, [worm['nodeNumber'], wheel['nodeNumber']], gear=drive.gear, name='mesh')
    ew.CreateRotorTorque(mbs, wheel, ew.GravityLeverTorque(mass=p['loadMass'], leverArm=p['leverArm']))
    sensors = dict(mesh.AddSensors(mbs))
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ss.solution.file.write = False
    ss.timeIntegration.endTime, ss.timeIntegration.numberOfSteps = endTime, int(round(endTime / stepSize))
    ss.solution.sensors.writePeriod = stepSize
    ss.timeIntegration.verboseMode = 0
    printing = exu.config.printToConsole
    exu.config.printToConsole = False
    try:
        mbs.SolveDynamic(ss)
    finally:
        exu.config.printToConsole = printing
    speed = mbs.GetSensorStoredData(sensors['omega1'])
    angle = mbs.GetSensorStoredData(sensors['phi2'])
    verdict = ew.SelfLocking(drive.gear, drive.gear.SlidingSpeed(p['motorSpeed']))
    return {'time': speed[:, 0], 'omega1': speed[:, 1], 'phi2': angle[:, 1], 'verdict': verdict}


def RunAway(law: str = 'agma', endTime: float = 0.6, stepSize: float = 1e-4) -> Dict[str, np.ndarray]:
    """The reel at the horizontal while lowering, the motor gone: does the load stop or run away?

    reel-P1's gear and inertias, no drive shaft (the worm is free), the reel's load torque on the wheel at
    phi2 = pi (horizontal, lowering: the load drives), both shafts starting at the lowering speed of 472.5 rpm.

    Parameters
    ----------
    law : str
        ``'agma'`` (statically, not dynamically self-locking) or ``'constant'`` (mu = 0.132 at every speed).
    endTime : float
        Simulated time in s.
    stepSize : float
        Time step in s.

    Returns
    -------
    dict
        ``time`` (s), ``omega1`` (worm speed, rad/s), ``phi2`` (wheel angle, rad), ``verdict`` of the gear (static
        and dynamic self-locking).
    """
    return _FreeWorm(law, ew.GetPreset('reel-P1')['motorSpeed'], endTime, stepSize, 'RunAway')


def HoldAtRest(law: str = 'agma', endTime: float = 8., stepSize: float = 1e-3) -> Dict[str, np.ndarray]:
    """The same drive as :func:`RunAway`, started at rest: does the brake-free gear hold the reel?

    Parameters
    ----------
    law : str
        ``'agma'`` or ``'constant'``.
    endTime : float
        Simulated time in s.
    stepSize : float
        Time step in s.

    Returns
    -------
    dict
        As :func:`RunAway`; the wheel angle ``phi2`` stays at pi (to the mesh's elastic deflection) when the gear
        holds.
    """
    return _FreeWorm(law, 0., endTime, stepSize, 'HoldAtRest')


def _Plot(out: Path) -> None:
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    out.mkdir(parents=True, exist_ok=True)
    v = np.linspace(0., 3., 400)
    fig, ax = plt.subplots(figsize=(8.5, 4), layout='constrained')
    for name, mu in FrictionCurves(v).items():
        ax.plot(v, mu, label=name)
    ax.set_xlabel('sliding speed v [m/s]')
    ax.set_ylabel(r'friction coefficient $\mu$')
    ax.legend(loc='upper left', bbox_to_anchor=(1.01, 1.), frameon=False)
    fig.savefig(out / 'mu_of_v.png', dpi=120)
    charts = SpeedChart()
    ax = charts['stribeck'].plot()
    ax.plot(charts['constant'].motorSpeeds / RPM, charts['constant'].Curve(-1).maxRealPart, color='0.5',
            label=fr"largest real part, lowering, constant $\mu$ = {charts['constant'].mu[0]:.3g}")
    for legend in list(ax.figure.legends):        # the legend below the axes, with the line just drawn
        legend.remove()
    lines = [line for a in ax.figure.axes for line in a.get_lines() if not line.get_label().startswith('_')]
    ax.figure.legend(lines, [line.get_label() for line in lines], loc='outside lower center', ncols=2, fontsize=8,
                     frameon=False)
    ax.figure.savefig(out / 'max_real_part_over_speed.png', dpi=120)
    sim = ChatterAmplitudes()
    fig, ax = plt.subplots(figsize=(7, 4), layout='constrained')
    ax.semilogy(sim['rpm'], sim['amplitude'], 'o-')
    ax.set_xscale('log')
    ax.set_xlabel('motor speed [rpm]')
    ax.set_ylabel("lowering: J2 max |phi2''| [rad/s^2]")
    fig.savefig(out / 'chatter_amplitude_over_speed.png', dpi=120)
    fig, ax = plt.subplots(figsize=(8.5, 4), layout='constrained')
    for law in ('constant', 'agma'):
        r = RunAway(law)
        ax.plot(r['time'], r['omega1'] / RPM, label=f'{law}')
    ax.set_xlabel('time [s]')
    ax.set_ylabel('worm speed [rpm]')
    hold = HoldAtRest('agma')
    ax.plot(hold['time'], hold['omega1'] / RPM, label='agma, from rest (holds)')
    ax.set_title('reel at the horizontal, lowering, motor gone', loc='left', fontsize=10)
    ax.legend(loc='upper left', bbox_to_anchor=(1.01, 1.), frameon=False)
    fig.savefig(out / 'run_away.png', dpi=120)
    for n, a, c in zip(sim['rpm'], sim['amplitude'], sim['chatter']):
        print(f"{n:7.1f} rpm: lowering J2 max|phi2''| = {a:.4g} rad/s^2{' (chatter)' if c else ''}")
    print('chatter while lowering (linear):', ', '.join(f'{a / RPM:.0f} to {b / RPM:.0f} rpm'
                                                       for a, b in charts['stribeck'].Curve(-1).unstableRanges))


if __name__ == '__main__':
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--out', default='friction_speed', help='folder for the PNG files')
    _Plot(Path(parser.parse_args().out))
