"""Figures 19 and 20 (section 3.2.5): the reel changer with an extra inertia and spring-damper on the drive side.

This is also the worked example for building your own drivetrain around the worm-gear connector: every
item is added by hand with the public builders (``CreateRotor``, ``CreateShaft``, ``CreateWormGear``, ...),
the sensors record every time step, and the results are read as time, normal force and mesh state.

Model (Figure 19; keys of :mod:`exudyn_worm.drive.presets`; ``BuildReelChanger`` builds the same from ``J4, k4, d4``)::

    motor phi0(t) --spring-Damper4 (k4, d4)-- inertia4 J4 --spring-Damper1 (kT, dT)-- worm J1 --mesh-- wheel J2 -- reel

Parameter set (28) (point P1, chatter while lowering) plus inertia4 and spring-Damper4. The paper prints neither
value, only that inertia4 "introduces a third natural frequency of 116 Hz" and that the chatter continues
(Figure 20). The values chosen here:

- ``J4 = 0.05 kg*m^2``, half the worm-side inertia J1 (a motor rotor with its coupling is of this size). It must
  leave P1 unstable, as Figure 20 shows chatter; the scan below shows that it does.
- ``k4 = 18.47 kN*m/rad``: solved (:func:`StiffnessForThirdMode`) so that the linearized drive has its third
  natural frequency at 116.0 Hz in the contact state S = +1 (the state whose frequencies the paper calls the
  natural frequencies, 33 and 52 Hz in section 3.2.2). The mode is inertia4 swinging between k4 and kT,
  f ~ sqrt((k4 + kT)/J4)/(2 pi), so any J4 above kT/(2 pi 116 Hz)^2 = 0.013 kg*m^2 has a k4 for it.
- ``d4 = 2 D4 sqrt(k4 J4) = 0.85 N*m*s/rad`` with ``D4 = 0.014``, the damping measure of the drive shaft (eq. (22)).

What it shows (numbers from :func:`RunExample`, checked by tests/test_example_drive_side_inertia.py):

- Linear analysis (:func:`~exudyn_worm.analysis.stability.linearization.AnalyzeLinearStability`): S = +1: 29.0, 46.7, 116.0 Hz;
  S = -1: 36.9 Hz growing (largest real part 18.5 1/s against 19.8 1/s without inertia4): the extra inertia
  moves P1 towards stability but not into it. At this k4, P1 becomes stable for J4 between 0.20 and 0.76
  kg*m^2 (equivalent inertia ratio (J1 + J4)/J2 of 0.009 to 0.026, the region of P2 at 0.009); a much larger
  J4 acts like the motor itself and restores P1's instability. A softer spring-Damper4 widens the stable range
  (k4 = 10 kN*m/rad: 0.034 to 0.64), a stiffer one moves it to larger J4 and narrows it (30 kN*m/rad: 0.43 to
  0.93; 100 kN*m/rad: about 1.7 to 1.9) (:func:`StableInertiaRanges`): "if the additional inertia [...] is large
  enough and the stiffness of spring-Damper4 is small enough, the worm gear becomes stable".
- Simulation (one rotation, 8 s): chatter while lowering at 36.8 Hz, the frequency of the growing S = -1 mode.
  The acceleration of inertia4 is dominated by the chatter's third harmonic at 110.4 Hz, which the 116 Hz mode
  amplifies (in the worm's acceleration it is 10 % of the fundamental, in inertia4's 1.3 times it). The paper
  (chatter 42 Hz, third harmonic 126 Hz) sees the response at 122 Hz, between the mode and the harmonic. Ours is
  locked to the third harmonic (110.4 Hz: the chatter is periodic, so its forced response contains harmonics
  only); the mode's own free vibration shows as a weak peak at 116.0 Hz (0.5 % of the harmonic). Our chatter is
  slower (36.8 Hz, the growing S = -1 mode; 40.5 Hz without inertia4), so the harmonic lies below the mode,
  not above it as in the paper.

Run ``python examples/drive_side_inertia.py --out DIR``: prints the numbers and writes fig19_linear_scan.png,
fig20_accelerations.png and fig20_spectrum.png into DIR.
"""
from __future__ import annotations

import argparse
import math
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple

import exudyn as exu
import numpy as np
from scipy.optimize import brentq
from scipy.signal import find_peaks

import exudyn_worm as ew
from exudyn_worm._checks import CheckOutputFolder
from exudyn_worm.model.drive import TorsionalDampingFromMeasure
from exudyn_worm.analysis.stability.linearization import AnalyzeLinearStability, LinearStability
from exudyn_worm.drive.presets import DriveSideChain
from exudyn_worm.analysis.simulation.reelchanger import RotationPeriod
from exudyn_worm.items.equilibrium import SteadyInitialState
from exudyn_worm.items.results import SimulationResult
from exudyn_worm.drive.wholedrive import ResolveDrive

__all__ = ['PRESET', 'J4', 'D4', 'MODE_HZ', 'STEP_SIZE', 'LOWERING', 'ZOOM', 'DriveSideParameters',
           'StiffnessForThirdMode', 'DriveSideModel', 'BuildDriveSideInertia', 'LinearAnalysis', 'MaxRealPart',
           'StableInertiaRanges', 'SimulateDriveSideInertia', 'Spectrum', 'SpectralPeaks', 'Figure20Summary',
           'RunExample', 'main']

PRESET = 'reel-P1'        #: parameter set (28), point P1
J4 = 0.05                 #: inertia4 in kg*m^2 (half of J1)
D4 = 0.014                #: damping measure of spring-Damper4 (= D_T of the drive shaft)
MODE_HZ = 116.            #: third natural frequency the paper names, Hz
STEP_SIZE = 2.5e-4        #: s; 34 steps per period of the 116 Hz mode (5e-4 s gives the same peaks within 0.1 Hz)
LOWERING = (2.5, 5.5)     #: s, spectrum window inside the lowering phase (2-6 s), away from the load reversal
ZOOM = (4.0, 4.1)         #: s, the zoomed window of Figure 20 (middle of the lowering, largest load)


def DriveSideParameters(J4: float = J4, k4: Optional[float] = None, D4: float = D4,
                        preset: str = PRESET) -> Dict[str, float]:
    """Flat parameter set: the preset plus ``J4``, ``k4`` and ``d4 = 2 D4 sqrt(k4 J4)``.

    Parameters
    ----------
    J4 : float
        Inertia of inertia4 in kg*m^2.
    k4 : float, optional
        Stiffness of spring-Damper4 in N*m/rad; default :func:`StiffnessForThirdMode` of ``J4``.
    D4 : float
        Damping measure of spring-Damper4 (eq. (22) form).
    preset : str
        Base parameter set.
    """
    if k4 is None:
        k4 = StiffnessForThirdMode(J4, MODE_HZ, D4, preset)
    return ew.ApplyOverrides(ew.GetPreset(preset), {'J4': J4, 'k4': k4,
                                                    'd4': TorsionalDampingFromMeasure(D4, k4, J4)})


def MaxRealPart(parameters: Mapping[str, float], S: int = -1) -> float:
    """Largest real part (1/s) of the linearized reel changer (``BuildReelChanger``) in contact state ``S``.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set.
    S : int
        Contact state held, +1 or -1.
    """
    model = ew.BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=parameters))
    return AnalyzeLinearStability(model.mbs, contactStates=[(S,)]).State(S).maxRealPart


def StiffnessForThirdMode(J4: float = J4, targetHz: float = MODE_HZ, D4: float = D4,
                          preset: str = PRESET) -> float:
    """The k4 in N*m/rad for which the third natural frequency (S = +1) equals ``targetHz``.

    Parameters
    ----------
    J4 : float
        Inertia of inertia4 in kg*m^2.
    targetHz : float
        Wanted third natural frequency in Hz.
    D4 : float
        Damping measure of spring-Damper4.
    preset : str
        Base parameter set.
    """
    def Third(k4):
        p = DriveSideParameters(J4, k4, D4, preset)
        return AnalyzeLinearStability(ew.BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=p)).mbs, contactStates=[(1,)]).State(1).frequenciesHz[2]

    guess = J4 * (2 * math.pi * targetHz)**2          # inertia4 between two springs, worm held
    return brentq(lambda k: Third(k) - targetHz, 0.2 * guess, 3 * guess, xtol=1e-3)


@dataclass
class DriveSideModel:
    """The hand-built Exudyn system of Figure 19 and the handles to read its results."""
    systemContainer: Any
    mbs: Any
    drive: ew.ElasticDrive
    load: ew.GravityLeverTorque
    rotors: Dict[str, Dict]
    mesh: ew.WormGearConnector
    inertia4Sensor: Any


def BuildDriveSideInertia(parameters: Mapping[str, float], useSymbolic: bool = True) -> DriveSideModel:
    """Build Figure 19 item by item (the worked example: copy this for your own drivetrain).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set with ``J4, k4, d4`` (one drive-side inertia) and the reel changer's keys.
    useSymbolic : bool
        Symbolic (C++) user functions (default) or plain Python.
    """
    import exudyn as exu
    from exudyn.itemInterface import SensorNode
    drive = ew.ElasticDriveFromParameters(parameters)                 # gear + J1, J2, kT, dT
    (J4_, k4, d4), = DriveSideChain(parameters)                # exactly one extra inertia here
    load = ew.GravityLeverTorque(mass=parameters['loadMass'], leverArm=parameters['leverArm'])
    speed = parameters['motorSpeed']
    # start in the static equilibrium under the initial load: every spring pre-twisted, the mesh in contact
    # (also what the linear analysis linearizes about)
    init = SteadyInitialState(drive, load, speed, chain=[(J4_, k4, d4)])

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    motor = ew.CreateRotor(mbs, 1e-3, initialSpeed=speed, name='motor')       # prescribed: inertia irrelevant
    inertia4 = ew.CreateRotor(mbs, J4_, initialAngle=init['phi4'], initialSpeed=init['omega4'], name='inertia4')
    worm = ew.CreateRotor(mbs, drive.J1, initialAngle=init['phi1'], initialSpeed=init['omega1'], name='worm')
    wheel = ew.CreateRotor(mbs, drive.J2, initialAngle=init['phi2'], initialSpeed=init['omega2'], name='wheel')
    ew.CreatePrescribedRotation(mbs, motor, ew.ConstantSpeed(speed), name='motorDrive', useSymbolic=useSymbolic)
    ew.CreateShaft(mbs, [motor, inertia4], stiffness=k4, damping=d4, name='springDamper4')
    ew.CreateShaft(mbs, [inertia4, worm], stiffness=drive.kT, damping=drive.dT, name='springDamper1')
    mesh = ew.CreateWormGear(mbs, [worm['nodeNumber'], wheel['nodeNumber']], gear=drive.gear, name='wormGear',
                             useSymbolic=useSymbolic)
    ew.CreateRotorTorque(mbs, wheel, load, name='reelLoad', useSymbolic=useSymbolic)
    mesh.AddSensors(mbs)                # worm and wheel angle, speed, acceleration, stored in memory
    sensor = mbs.AddSensor(SensorNode(nodeNumber=inertia4['nodeNumber'], storeInternal=True, writeToFile=False,
                                      outputVariableType=exu.OutputVariableType.Coordinates_tt))
    return DriveSideModel(SC, mbs, drive, load, {'motor': motor, 'inertia4': inertia4, 'worm': worm, 'wheel': wheel},
                          mesh, sensor)


def LinearAnalysis(parameters: Mapping[str, float]) -> LinearStability:
    """Linear stability of the hand-built model for S = +1 and S = -1 (modes, frequencies, shapes).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set with ``J4, k4, d4``.
    """
    return AnalyzeLinearStability(BuildDriveSideInertia(parameters).mbs)


def StableInertiaRanges(k4: float, J4Grid: Sequence[float] = tuple(np.geomspace(0.005, 3., 25)), D4: float = D4,
                        preset: str = PRESET) -> Dict[str, Any]:
    """Scan J4 at fixed k4: largest real part for S = -1 and the J4 intervals in which the drive is stable.

    Parameters
    ----------
    k4 : float
        Stiffness of spring-Damper4 in N*m/rad.
    J4Grid : sequence of float
        Inertias in kg*m^2 (increasing); interval ends are refined between grid points.
    D4 : float
        Damping measure of spring-Damper4.
    preset : str
        Base parameter set.

    Returns
    -------
    dict
        ``k4``, ``J4`` (the grid), ``maxRealPart`` (1/s, per grid point), ``stableRanges`` ([(J4min, J4max)];
        an end at the grid's edge is the grid value).
    """
    def F(J):
        return MaxRealPart(DriveSideParameters(J, k4, D4, preset))

    grid = np.asarray(J4Grid, dtype=float)
    values = np.array([F(J) for J in grid])
    edges = [brentq(F, grid[i], grid[i + 1], xtol=1e-5 * grid[i]) for i in range(grid.size - 1)
             if (values[i] < 0) != (values[i + 1] < 0)]
    starts = ([grid[0]] if values[0] < 0 else []) + edges
    bounds = sorted(starts + ([grid[-1]] if values[-1] < 0 else []))
    return {'k4': k4, 'J4': grid, 'maxRealPart': values,
            'stableRanges': [(bounds[i], bounds[i + 1]) for i in range(0, len(bounds) - 1, 2)]}


def SimulateDriveSideInertia(parameters: Mapping[str, float], stepSize: float = STEP_SIZE,
                             endTime: Optional[float] = None) -> SimulationResult:
    """Simulate the hand-built model (one wheel rotation by default) and read its results.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set with ``J4, k4, d4``.
    stepSize : float
        Time step in s; the sensors record every step.
    endTime : float, optional
        Simulated time in s (default: one rotation, 8 s).

    Returns
    -------
    SimulationResult
        Series ``phi1, omega1, alpha1, phi2, omega2, alpha2, alpha4``, the signed ``normalForce`` (N), ``S``,
        ``sf``, ``wormTorque``, ``wheelTorque``.
    """
    import exudyn as exu
    model = BuildDriveSideInertia(parameters)
    mbs = model.mbs
    mbs.Assemble()
    endTime = RotationPeriod(ResolveDrive(parameters=parameters)) if endTime is None else endTime
    steps = int(round(endTime / stepSize))
    ss = exu.SimulationSettings()
    ss.solution.file.write = False                  # Exudyn writes ./solution/ by default
    ss.solution.sensors.writePeriod = stepSize      # a sample every step: coarser sampling cuts the peaks
    ss.timeIntegration.endTime = steps * stepSize   # a whole number of steps: a sample at every step
    ss.timeIntegration.numberOfSteps = steps
    ss.timeIntegration.verboseMode = 0
    ss.timeIntegration.newton.useModifiedNewton = True
    printing, exu.config.printToConsole = exu.config.printToConsole, False   # Exudyn's note on user functions
    try:
        if not mbs.SolveDynamic(ss):
            raise RuntimeError(f"SimulateDriveSideInertia: the solver failed with stepSize = {stepSize:g} s")
    finally:
        exu.config.printToConsole = printing
    series = model.mesh.StoredStates(mbs)           # time and worm/wheel phi, omega, alpha
    time = series.pop('time')
    series['alpha4'] = mbs.GetSensorStoredData(model.inertia4Sensor)[:, 1]
    # mesh quantities from the stored states with the connector's own contact law:
    # normalForce is signed: > 0 on the flank a leading worm pushes (Delta s > 0, lifting), < 0 on the
    # second flank (Delta s < 0: the load drives the wheel while lowering); S = sign(Delta s) sf, eq. (8)
    mesh = model.mesh.StoredMeshState(mbs)
    series.update(normalForce=mesh.normalForce, S=mesh.S, sf=mesh.sf, wormTorque=mesh.wormTorque,
                  wheelTorque=mesh.wheelTorque, deltaS=mesh.deltaS)
    return SimulationResult(time=time, series=series, J2=model.drive.J2, r2=model.drive.gear.r2, steps=steps,
                            info={'stepSize': stepSize})


def Spectrum(time: np.ndarray, signal: np.ndarray, t0: float, t1: float) -> Tuple[np.ndarray, np.ndarray]:
    """Amplitude spectrum of ``signal`` in [t0, t1]: mean removed, Hann window, zero-padded 4 times.

    Parameters
    ----------
    time, signal : ndarray
        Uniformly sampled series.
    t0, t1 : float
        Window in s.

    Returns
    -------
    (ndarray, ndarray)
        Frequencies in Hz and amplitudes (in the signal's unit, Hann-corrected for a pure tone).
    """
    m = (time >= t0) & (time <= t1)
    x = signal[m] - np.mean(signal[m])
    window = np.hanning(x.size)
    amplitude = 2 * np.abs(np.fft.rfft(x * window, n=4 * x.size)) / np.sum(window)
    return np.fft.rfftfreq(4 * x.size, float(np.mean(np.diff(time[m])))), amplitude


def SpectralPeaks(frequency: np.ndarray, amplitude: np.ndarray, fMax: float = 200.,
                  relativeHeight: float = 0.05) -> List[Tuple[float, float]]:
    """Peaks below ``fMax`` higher than ``relativeHeight`` times the largest: [(Hz, amplitude)], by frequency.

    Parameters
    ----------
    frequency, amplitude : ndarray
        From :func:`Spectrum`.
    fMax : float
        Highest frequency in Hz.
    relativeHeight : float
        Smallest peak as a fraction of the largest.
    """
    keep = frequency <= fMax
    f, a = frequency[keep], amplitude[keep]
    peaks, _ = find_peaks(a, height=relativeHeight * np.max(a), distance=max(1, int(5. / (f[1] - f[0]))))
    return [(float(f[i]), float(a[i])) for i in peaks]


def _AmplitudeAt(frequency, amplitude, f, halfWidth=1.):
    band = np.abs(frequency - f) <= halfWidth
    return float(np.max(amplitude[band]))


def Figure20Summary(result: SimulationResult, linear: LinearStability) -> Dict[str, Any]:
    """The numbers behind Figure 20: chatter frequency, harmonics, the response of inertia4, linear frequencies.

    Parameters
    ----------
    result : SimulationResult
        From :func:`SimulateDriveSideInertia`.
    linear : LinearStability
        From :func:`LinearAnalysis` of the same parameters.
    """
    t0, t1 = LOWERING
    f, a1 = Spectrum(result.time, result.series['alpha1'], t0, t1)
    _, a4 = Spectrum(result.time, result.series['alpha4'], t0, t1)
    chatter = float(f[np.argmax(a1)])
    band = (f >= 90.) & (f <= 150.)
    modeBand = (f >= 3 * chatter + 2.) & (f <= 125.)
    lowering = (result.time >= 2.) & (result.time <= 6.)
    return {
        'linearHz': {f'{S[0]:+d}': [float(x) for x in state.frequenciesHz] for S, state in linear.states.items()},
        'maxRealPart': {f'{S[0]:+d}': state.maxRealPart for S, state in linear.states.items()},
        'chatterHz': chatter,
        'thirdHarmonicHz': 3 * chatter,
        'alpha4DominantHz': float(f[np.argmax(a4)]),
        'alpha4PeakHz90to150': float(f[band][np.argmax(a4[band])]),
        # the mode's own (not harmonic-locked) response: the largest peak between the harmonic and 125 Hz
        'alpha4ModePeakHz': float(f[modeBand][np.argmax(a4[modeBand])]),
        'alpha4ModePeakToThirdHarmonic': float(np.max(a4[modeBand])) / _AmplitudeAt(f, a4, 3 * chatter),
        'alpha1Peaks': SpectralPeaks(f, a1),
        'alpha4Peaks': SpectralPeaks(f, a4),
        'alpha1ThirdToFundamental': _AmplitudeAt(f, a1, 3 * chatter) / _AmplitudeAt(f, a1, chatter),
        'alpha4ThirdToFundamental': _AmplitudeAt(f, a4, 3 * chatter) / _AmplitudeAt(f, a4, chatter),
        'maxAbsAlpha1': float(np.max(np.abs(result.series['alpha1'][lowering]))),
        'maxAbsAlpha4': float(np.max(np.abs(result.series['alpha4'][lowering]))),
        'maxAbsAlpha2': float(np.max(np.abs(result.series['alpha2'][lowering]))),
        'chatterWhileLowering': result.Chatter(2., 6.),
        'fractionSNegativeLowering': float(np.mean(result.series['S'][lowering] < 0)),
    }


def RunExample(scanStiffnesses: Sequence[float] = (1e4, None, 3e4, 1e5), simulate: bool = True) -> Dict[str, Any]:
    """Everything the example shows: chosen parameters, linear analysis, J4 scans, simulation and its summary.

    Parameters
    ----------
    scanStiffnesses : sequence
        k4 values in N*m/rad for :func:`StableInertiaRanges`; None stands for the chosen k4.
    simulate : bool
        Also run the time-domain simulation (about 2 s) and :func:`Figure20Summary`.
    """
    parameters = DriveSideParameters()
    k4 = parameters['k4']
    out = {'parameters': parameters, 'linear': LinearAnalysis(parameters),
           'P1maxRealPart': MaxRealPart(ew.GetPreset(PRESET)),
           'scans': [StableInertiaRanges(k4 if k is None else k) for k in scanStiffnesses]}
    if simulate:
        out['result'] = SimulateDriveSideInertia(parameters)
        out['summary'] = Figure20Summary(out['result'], out['linear'])
    return out


def _Print(run: Dict[str, Any]) -> None:
    p = run['parameters']
    print(f"J4 = {p['J4']:g} kg*m^2, k4 = {p['k4']:.6g} N*m/rad, d4 = {p['d4']:.4g} N*m*s/rad")
    for S, state in run['linear'].states.items():
        modes = ', '.join(f'{m.frequencyHz:.2f} Hz (D = {m.lehrDamping:+.4f}, {"/".join(m.Participants(0.1))})'
                          for m in state.modes)
        print(f'S = {S[0]:+d}: {"stable" if state.stable else "unstable"}; {modes}')
    print(f"largest real part for S = -1: {run['linear'].State(-1).maxRealPart:.3f} 1/s "
          f"(P1 without inertia4: {run['P1maxRealPart']:.3f} 1/s)")
    for scan in run['scans']:
        ranges = ', '.join(f'{a:.4g}..{b:.4g}' for a, b in scan['stableRanges']) or 'none'
        print(f"k4 = {scan['k4']:.6g} N*m/rad: stable for J4 in [{ranges}] kg*m^2")
    if 'summary' in run:
        s = run['summary']
        print(f"simulation: chatter while lowering {s['chatterWhileLowering']} at {s['chatterHz']:.2f} Hz, third harmonic "
              f"{s['thirdHarmonicHz']:.2f} Hz; inertia4 dominated by {s['alpha4DominantHz']:.2f} Hz "
              f"(peak in 90-150 Hz: {s['alpha4PeakHz90to150']:.2f} Hz); third/fundamental amplitude worm "
              f"{s['alpha1ThirdToFundamental']:.3f}, inertia4 {s['alpha4ThirdToFundamental']:.3f}; weak free response of the "
              f"mode at {s['alpha4ModePeakHz']:.2f} Hz ({s['alpha4ModePeakToThirdHarmonic']:.4f} of the harmonic); max |alpha1| "
              f"{s['maxAbsAlpha1']:.0f}, |alpha4| {s['maxAbsAlpha4']:.0f}, |alpha2| {s['maxAbsAlpha2']:.1f} rad/s^2")


def _WriteFigures(run: Dict[str, Any], outDir: Path) -> List[Path]:
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    from exudyn_worm.plotting.plot import S_SIGN_LABEL, S_SIGN_NOTE
    paths = []
    fig, ax = plt.subplots(figsize=(8.5, 4), layout='constrained')
    for scan in run['scans']:
        ax.semilogx(scan['J4'], scan['maxRealPart'], marker='.', label=f"k4 = {scan['k4'] / 1e3:.3g} kN·m/rad")
    ax.axhline(0, color='k', lw=0.8)
    ax.axvline(run['parameters']['J4'], color='gray', ls='--', lw=0.8, label='chosen J4')
    ax.set(xlabel='J4 (inertia4) [kg·m²]', ylabel='largest real part, S = -1 [1/s]',
           title='Figure 19 drive: P1 with inertia4 (stable below 0)')
    ax.legend(fontsize=8, loc='upper left', bbox_to_anchor=(1.01, 1.), frameon=False)          # beside the axes, over no data
    paths.append(outDir / 'fig19_linear_scan.png')
    fig.savefig(paths[-1], dpi=120), plt.close(fig)

    r = run['result']
    m = (r.time >= ZOOM[0]) & (r.time <= ZOOM[1])
    fig, axes = plt.subplots(3, 1, sharex=True, figsize=(8.5, 6), layout='constrained')
    for ax, key, label in ((axes[0], 'alpha1', r'$\ddot\varphi_1$ (worm) [rad/s²]'),
                           (axes[1], 'alpha4', r'$\ddot\varphi_4$ (inertia4) [rad/s²]')):
        ax.plot(r.time[m], r.series[key][m], lw=1.)
        ax.set_ylabel(label)
    # the paper's S = +-1: the sign of the regularized S, as in Figures 9, 14 and 16
    axes[2].plot(r.time[m], np.sign(r.series['S'][m]), color='tab:red', lw=1.2, drawstyle='steps-post')
    axes[2].set(ylabel=S_SIGN_LABEL, yticks=[-1, 0, 1], ylim=(-1.4, 1.4), xlabel='time [s]')
    axes[2].set_title(S_SIGN_NOTE, loc='left', fontsize=7, color='0.3')
    for ax in axes:
        ax.grid(True, color='0.85', lw=0.5)
    axes[0].set_title(f"Figure 20: worm, inertia4 and S while lowering (P1, J4 = {run['parameters']['J4']:g} kg·m², "
                      f"k4 = {run['parameters']['k4'] / 1e3:.3g} kN·m/rad)", fontsize=10)
    paths.append(outDir / 'fig20_accelerations.png')
    fig.savefig(paths[-1], dpi=120), plt.close(fig)

    s = run['summary']
    fig, ax = plt.subplots(figsize=(8.5, 4), layout='constrained')
    for key, label in (('alpha1', 'worm'), ('alpha4', 'inertia4')):
        f, a = Spectrum(r.time, r.series[key], *LOWERING)
        keep = f <= 200
        ax.semilogy(f[keep], a[keep], label=label)
    ax.axvline(s['linearHz']['+1'][2], color='k', ls='--', lw=0.8, label=f"third mode {s['linearHz']['+1'][2]:.1f} Hz")
    ax.axvline(s['thirdHarmonicHz'], color='r', ls=':', lw=0.8, label=f"3 x chatter {s['thirdHarmonicHz']:.1f} Hz")
    ax.set(xlabel='frequency [Hz]', ylabel='amplitude [rad/s²]',
           title=f'spectra while lowering ({LOWERING[0]:g}-{LOWERING[1]:g} s)')
    ax.legend(fontsize=8, loc='upper left', bbox_to_anchor=(1.01, 1.), frameon=False)
    paths.append(outDir / 'fig20_spectrum.png')
    fig.savefig(paths[-1], dpi=120), plt.close(fig)
    return paths


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Command line: compute, print the numbers, write the figures into ``--out``. Returns the exit status.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments (default: ``sys.argv[1:]``).
    """
    parser = argparse.ArgumentParser(prog='drive_side_inertia.py', description=__doc__.split('\n')[0])
    parser.add_argument('--out', required=True, help='folder for the PNG figures (created if missing)')
    args = parser.parse_args(argv)
    try:                                                   # check the output folder before computing
        outDir = CheckOutputFolder(parser.prog, '--out', args.out)
    except ValueError as error:
        print(f'{parser.prog}: error: {str(error).split(": ", 1)[1]}', file=sys.stderr)
        return 2
    run = RunExample()
    _Print(run)
    print(f'\nwriting figures to {outDir}')
    for path in _WriteFigures(run, outDir):
        print(f'  {path.name}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
