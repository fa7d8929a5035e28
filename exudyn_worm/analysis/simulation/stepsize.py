"""Time step of a simulation chosen from the drive itself, and the rule that refuses a step too coarse.

The reel changer is integrated with Exudyn's generalized-alpha method, a member of the Newmark /
trapezoidal family. For a linear mode of frequency f it is stable at any step h, but it stretches the
period by ``x / (2 atan(x/2)) - 1``, about ``x^2 / 12``, with ``x = 2 pi f h`` (the period error of the
trapezoidal rule, :func:`PeriodError`). A step that
is too coarse therefore does not fail: it reports a chatter frequency that is too low (28.8 Hz instead
of 40.5 Hz for P1 at h = 0.01 s) or steps over the vibration and reports no chatter at all (h = 0.05 s),
an answer that looks right. The rule below is written in terms of that period error of the highest
natural frequency of the linearized drive (eqs. (1)-(2) with S = +1 and S = -1, :func:`StateMatrix`; for a
drive with a drive-side chain or a worm axial bearing, the linearized whole drive of
:func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive`, as ``exudyn-worm stability`` reports it: the 116 Hz mode of
inertia4 in examples/drives/figure19.toml); it covers the chatter frequency, which is one of these modes:

==============  =====================  ==================================================
limit           period error of f_max  step
==============  =====================  ==================================================
recommended     0.5 %                  ``RECOMMENDED_CYCLES / f_max`` (0.039 / f_max)
soft (warn)     2 %                    ``SOFT_CYCLES / f_max`` (0.079 / f_max)
hard (refuse)   5 %                    ``HARD_CYCLES / f_max`` (0.126 / f_max)
==============  =====================  ==================================================

For the paper's P1 (f_max = 50.4 Hz) that is 7.8e-4 s, 1.6e-3 s and 2.5e-3 s; for P7 (77.2 Hz)
5.1e-4 s, 1.0e-3 s and 1.6e-3 s. Measured on P1 (generalized-alpha, spectral radius 0.9): the
chatter frequency is 40.3 Hz at h = 1e-3 s, 39.7 Hz at 2e-3 s, 37.5 Hz at 4e-3 s, 28.8 Hz at 0.01 s.

The friction regularization of ``ContactOptions(frictionModel='regularized')`` (``sf = phi1'/frictionSpeed``
for ``|phi1'| < frictionSpeed``; the default sticking model has none, docs/friction-sticking.md) acts on the
worm like a viscous damper ``d = |dc2/dS| Fn / frictionSpeed``. Its time constant ``J1/d`` is about
1e-5 s for P7 (it is returned by :func:`FrictionTimeConstant`), far below any affordable step; the
implicit solver does not need to resolve it (the mode is damped, not oscillating) as long as the
method damps stiff modes (spectral radius < 1), so it does not enter the step size. It matters for the
Newton iteration instead (see benchmarks/README.md).

The worm's own axial mode on its bearing (kA, mA; 1.2 kHz at kA = 1e8 N/m, 7 kHz at 1e10 N/m for mA = 5 kg,
Lehr damping 0.04-0.25 from the mesh damping) is left out for the same reason: it is a stiff mode of the
bearing in series with the mesh, not a mode the chatter or the load excites, and the method damps it where the
step does not resolve it. Resolving it would make the step fall with sqrt(kA) (5e-6 s at 1e10 N/m, more than
the run-size limit for one rotation) while the rigid worm, its limit, needs 7.8e-4 s. The bearing's effect on
the other modes (kV in series with kA) is included. The same holds for the bearings of the 3D model (worm and wheel
as rigid bodies, docs/mesh-3d.md): modes with more than half their kinetic energy in the bodies' translations and
tilts (:data:`BEARING_COORDINATES`; 0.9 to 2.3 kHz in examples/drives/reel-3d.toml) are left out. Measured on P1 with mA = 5 kg over 6 s: at kA = 1e9 N/m
(chatter while lowering) the recommended step 8.0e-4 s gives the peak ``|phi2''|`` and the chatter frequency within
0.1 % and 0.4 % of those at 1e-4 s; at kA = 5e8 N/m (stable) both steps give no chatter.

The rule bounds the period error of the linear modes, not the amplitudes that the nonlinear events of a run (load
reversal, contact flips, chatter ringing down into the next phase) leave behind. ``simulate`` and ``sweep`` therefore
check a run against the same run at half the step (:func:`CompareHalfStep`: a window whose chatter verdict changes is
:data:`UNRESOLVED`), by default where the linear margin is small (:func:`LinearMargin` below :data:`SMALL_MARGIN`)
and a window's own verdict is close (:func:`CloseVerdicts`).
Measured for J1 = 0.0247 kg m^2, kT = 1508 N m/rad on P1: the lift window after the lowering chatter peaks
at 11.7 rad/s^2 at the recommended step 6.4e-4 s and 22.9 rad/s^2 at 2e-5 s (converged within 5 % from 1e-4 s on);
the verdict (no chatter: the normal-force amplitude of its last quarter stays at 0.016-0.038 of the steady force
against 0.25, :meth:`~exudyn_worm.items.results.SimulationResult.Chatter`) holds at every step.

For the reel presets the accuracy of the recommended step is measured (benchmarks/step_convergence.py, table in
docs/simulation.md): every window peak within :data:`PEAK_ACCURACY` (1 %) of a converged step, except the wheel
acceleration in a window after chatter across a load reversal (and in the shipped drives with ringing load-side
modes), within :data:`TRANSIENT_PEAK_ACCURACY` (10 %). Tightening the rule would not buy the second cheaply: that
peak converges only at an eighth of the step or less.
"""
from __future__ import annotations

import math
import warnings
from typing import Any, List, Mapping, Sequence

import numpy as np

from ..._checks import CheckPositive
from ..stability.drivestability import AnalyzeDrive
from ...model.stability import CONTACT_STATES, StabilityAnalysis, StateMatrix
from ...drive.wholedrive import CheckDrive, Drive

__all__ = ['RECOMMENDED_CYCLES', 'SOFT_CYCLES', 'HARD_CYCLES', 'PEAK_ACCURACY', 'TRANSIENT_PEAK_ACCURACY',
           'SMALL_MARGIN', 'UNRESOLVED', 'PeriodError',
           'LinearizedFrequencies', 'RecommendedStepSize', 'StepSizeLimits', 'CheckStepSize', 'FrictionTimeConstant',
           'CoarseStepWarning', 'LinearMargin', 'StepCheckByDefault', 'CompareHalfStep', 'BEARING_COORDINATES',
           'VERDICT_FACTOR', 'CloseVerdicts']


def _PeriodError(x: float) -> float:
    """Period elongation of the trapezoidal rule for a mode with omega*h = x: x / (2 atan(x/2)) - 1."""
    return x / (2. * math.atan(0.5 * x)) - 1. if x > 0 else 0.


def _CyclesForPeriodError(error: float) -> float:
    """f*h at which the trapezoidal period error equals ``error`` (bisection; about sqrt(12 error)/(2 pi))."""
    low, high = 0., 2 * math.pi
    for _ in range(60):
        mid = 0.5 * (low + high)
        low, high = (mid, high) if _PeriodError(2 * math.pi * mid) < error else (low, mid)
    return 0.5 * (low + high)


#: label of the worm's axial coordinate in the linearized whole drive (its mode is left out, see the module text)
AXIAL_COORDINATE = 'wormAxial'
#: labels of the coordinates by which the bearings of the 3D model (worm and wheel as rigid bodies on Tait-Bryan
#: nodes, exudyn_worm.analysis.simulation.reelchanger3d) let the bodies move besides their turn about their axes: the
#: translations and the tilts (both turn about their last angle); their modes are left out like the axial one
BEARING_COORDINATES = tuple(f'Node:{body}[{i}]' for body in ('worm', 'wheel') for i in range(5))

#: f_max * h of the recommended step (0.5 % period error of the highest linearized mode)
RECOMMENDED_CYCLES = _CyclesForPeriodError(0.005)
#: f_max * h above which :func:`CheckStepSize` warns (2 % period error)
SOFT_CYCLES = _CyclesForPeriodError(0.02)
#: f_max * h above which :func:`CheckStepSize` raises (5 % period error)
HARD_CYCLES = _CyclesForPeriodError(0.05)


#: what the recommended step gives (measured, not implied by the rule): the window peaks (``max |phi2''|``,
#: ``max |Fn|`` of :meth:`~exudyn_worm.items.results.SimulationResult.WindowMetrics` in the default windows) within this
#: fraction of a converged step (halved until no peak changes by 0.05 %): ``max |Fn|`` in every window of the reel
#: presets and of the shipped drives figure19 and load-shaft, ``max |phi2''|`` in the reel presets' windows that do
#: not follow chatter across a load reversal (measured at most 0.43 %); the other windows:
#: :data:`TRANSIENT_PEAK_ACCURACY` (table in docs/simulation.md, benchmarks/step_convergence.py)
PEAK_ACCURACY = 0.01
#: the bound of ``max |phi2''|`` in the other windows: the lift after the lowering chatter of P1, P6, P7 (+2.4 %,
#: -8.1 %, +2.2 %), whose peak is the transient just after the load reverses, with an amplitude set by the phase of
#: the chatter at the reversal, which a fixed step resolves only to the period error accumulated over the chatter (at
#: half the step -8.5 %, -4.2 %, +0.16 %: halving does not bound it); and every window of figure19 and load-shaft,
#: whose lightly damped modes ring after each load reversal (load-shaft -4.3 %, without chatter)
TRANSIENT_PEAK_ACCURACY = 0.10


class CoarseStepWarning(UserWarning):
    """The time step resolves the drive's highest natural frequency only coarsely (see :func:`CheckStepSize`)."""


def PeriodError(frequency: float, stepSize: float) -> float:
    """Relative period elongation of a mode of ``frequency`` Hz at step ``stepSize`` s.

    The trapezoidal rule (generalized-alpha without numerical damping) turns a mode omega = 2 pi f into
    one of 2 atan(omega h / 2) / h: the period grows by x / (2 atan(x/2)) - 1 with x = omega h, about
    x^2 / 12 for small steps.

    Parameters
    ----------
    frequency : float
        Natural frequency in Hz.
    stepSize : float
        Time step in s.
    """
    return _PeriodError(2. * math.pi * frequency * stepSize)


def _WholeDriveEigenvalues(analysis, S: int) -> np.ndarray:
    """Eigenvalues of the linearized whole drive for contact state S that the step must resolve: every mode but
    the worm's own axial mode (see the module text) and rigid-body modes."""
    return np.array([m.eigenvalue for m in analysis.State(S).modes
                     if sum(m.energyShare.get(k, 0.) for k in (AXIAL_COORDINATE,) + BEARING_COORDINATES) <= 0.5],
                    dtype=complex)


def _Eigenvalues(drive: Drive) -> dict:
    """Eigenvalues per contact state S of the drive :func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive` analyses:
    eqs. (1)-(2) for the two-mass drive, else the linearized whole drive without the worm's axial mode, at the
    duty's operating points (at rest only for a duty without a steady phase: a speed-dependent friction law
    linearized at zero sliding speed has a slope there that no run sees, e.g. AGMA's: a spurious real
    eigenvalue of about 1e11 1/s that would ask for a step of 1e-11 s)."""
    analysis = AnalyzeDrive(CheckDrive('stepsize', drive))
    # once per drive (the step, its check and the linear margin of one run ask for the same set)
    return analysis.drive.Cached('stepSize.eigenvalues', lambda: _ComputeEigenvalues(analysis))


def _ComputeEigenvalues(analysis) -> dict:
    """The eigenvalues of :func:`_Eigenvalues`, computed from the drive's analysis."""
    if analysis.drive.isTwoMass:                           # two-mass drive: eqs. (1)-(2)
        return {S: np.linalg.eigvals(StateMatrix(analysis.drive.elastic, S)) for S in CONTACT_STATES}
    if not analysis.operatingPoints:                       # chain or axial bearing, no steady phase
        return {S: _WholeDriveEigenvalues(analysis.atRest, S) for S in CONTACT_STATES}
    out: dict = {}
    for point in analysis.operatingPoints:                 # each point linearized in its own contact state
        out[point.S] = np.concatenate([out.get(point.S, np.zeros(0, complex)),
                                       _WholeDriveEigenvalues(point.analysis, point.S)])
    return out


def LinearizedFrequencies(drive: Drive) -> dict:
    """Natural frequencies of the linearized drive (S = +1 and S = -1).

    The drive is the one :func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive` analyses: for the two-mass drive of
    Figure 2 the state matrix of eqs. (1)-(2); for a drive with a drive-side chain or a worm axial bearing the
    linearized whole drive (Exudyn), without the worm's axial mode (see the module text).

    Parameters
    ----------
    drive : Drive
        The drive.

    Returns
    -------
    dict
        ``maxHz``: the highest undamped natural frequency ``|lambda|/(2 pi)`` over both contact states;
        ``chatterHz``: the highest damped frequency of a growing mode (None if the drive is stable).
    """
    fMax, fChatter = 0., None
    for lam in _Eigenvalues(drive).values():
        fMax = max(fMax, float(np.max(np.abs(lam))) / (2 * math.pi))
        growing = lam[lam.real > 0]
        if growing.size:
            f = float(np.max(np.abs(growing.imag))) / (2 * math.pi)
            fChatter = f if fChatter is None else max(fChatter, f)
    return {'maxHz': fMax, 'chatterHz': fChatter}


def RecommendedStepSize(drive: Drive) -> float:
    """Time step in s for the drive: ``RECOMMENDED_CYCLES / f_max`` (0.5 % period error of its highest mode).

    Parameters
    ----------
    drive : Drive
        The drive and its load (as for :func:`LinearizedFrequencies`).

    Returns
    -------
    float
        Step size in s (7.8e-4 s for the paper's P1, 5.1e-4 s for P7).
    """
    return RECOMMENDED_CYCLES / LinearizedFrequencies(drive)['maxHz']


def StepSizeLimits(drive: Drive) -> dict:
    """The recommended step and the soft and hard limits of :func:`CheckStepSize`, in s.

    Parameters
    ----------
    drive : Drive
        The drive.

    Returns
    -------
    dict
        ``recommended``, ``soft``, ``hard`` (s) and ``maxHz``, ``chatterHz`` of :func:`LinearizedFrequencies`.
    """
    f = LinearizedFrequencies(drive)
    return {'recommended': RECOMMENDED_CYCLES / f['maxHz'], 'soft': SOFT_CYCLES / f['maxHz'],
            'hard': HARD_CYCLES / f['maxHz'], **f}


def CheckStepSize(drive: Drive, stepSize: float, where: str = 'CheckStepSize') -> float:
    """Refuse a step that cannot resolve the drive's highest natural frequency; warn for a coarse one.

    Parameters
    ----------
    drive : Drive
        The drive.
    stepSize : float
        Time step in s, > 0.
    where : str
        Name of the calling function for the messages.

    Returns
    -------
    float
        ``stepSize``.

    Raises
    ------
    ValueError
        If ``stepSize`` exceeds the hard limit ``HARD_CYCLES / f_max`` (period error of the highest mode
        above 5 %: the chatter frequency and amplitude come out wrong, or the chatter is missed).

    Warns
    -----
    CoarseStepWarning
        If ``stepSize`` exceeds the soft limit ``SOFT_CYCLES / f_max`` (period error above 2 %).
    """
    stepSize = CheckPositive(where, 'stepSize', stepSize, 's')
    lim = StepSizeLimits(drive)
    text = (f"the drive's highest natural frequency is {lim['maxHz']:.1f} Hz"
            + (f" (chatter mode {lim['chatterHz']:.1f} Hz)" if lim['chatterHz'] else '')
            + f"; at stepSize = {stepSize:g} s its period comes out about "
              f"{100 * PeriodError(lim['maxHz'], stepSize):.1f} % too long")
    if stepSize > lim['hard']:
        raise ValueError(f"{where}: 'stepSize' must be <= {lim['hard']:.3g} s for this drive, got {stepSize:g} s: "
                         f"{text} (frequencies and chatter verdicts would be wrong); recommended "
                         f"{lim['recommended']:.3g} s")
    if stepSize > lim['soft']:
        warnings.warn(f"{where}: {text}; amplitudes and frequencies may be off by percents; recommended "
                      f"stepSize <= {lim['recommended']:.3g} s", CoarseStepWarning, stacklevel=2)
    return stepSize


def FrictionTimeConstant(drive: Drive, frictionSpeed: float, normalForce: float) -> float:
    """Time constant J1/d in s of the worm on the regularized friction law at normal force ``normalForce``.

    ``d = |dc2/dS| normalForce / frictionSpeed`` is the damping of the regularized law
    (``S = sigma phi1'/frictionSpeed``) on the worm (see the module text: it does not limit the step).

    Parameters
    ----------
    drive : Drive
        The drive.
    frictionSpeed : float
        Regularization speed in rad/s, > 0.
    normalForce : float
        Normal force in N, > 0.
    """
    core = CheckDrive('FrictionTimeConstant', drive).elastic
    g = core.gear
    frictionSpeed = CheckPositive('FrictionTimeConstant', 'frictionSpeed', frictionSpeed, 'rad/s')
    normalForce = CheckPositive('FrictionTimeConstant', 'normalForce', normalForce, 'N')
    dc2dS = g.r1 * math.cos(g.alphaN) / math.cos(g.rho) * g.rho * math.cos(g.gamma)   # d/dS r1 k sin(gamma + rho S) at S = 0
    return core.J1 * frictionSpeed / (dc2dS * normalForce)


# ---------------------------------------------------------------------------------------------------------------
# the step check: a verdict that changes when the step is halved is 'unresolved'

#: ``|Re lambda| / |lambda|`` of the least stable mode (the rightmost eigenvalue of either contact state) below which
#: the linear margin counts as small and ``simulate`` / ``sweep`` check their verdicts at half the step by default:
#: the mode then grows or decays by less than about 2 pi * 2 % = 12 % per cycle, so whether a window's second half
#: still vibrates depends on the amplitude that the nonlinear events before it (load reversal, contact flips,
#: lowering chatter ringing down into a lift) leave, and that amplitude changes with the step (see the module text)
SMALL_MARGIN = 0.02
#: the chatter verdict of a window whose verdict changes when the step is halved
UNRESOLVED = 'unresolved'


def LinearMargin(drive: Drive) -> dict:
    """The linear margin of the drive: how fast its least stable mode grows or decays per radian of its cycle.

    For each contact state S = +1 (the motor drives) and S = -1 (the load drives) the rightmost eigenvalue lambda
    of the linearized drive (as :func:`LinearizedFrequencies`; rigid-body modes left out) gives
    ``|Re lambda| / |lambda|``, the magnitude of its Lehr damping; the margin is the smaller of the two.

    Parameters
    ----------
    drive : Drive
        The drive.

    Returns
    -------
    dict
        ``margin`` (dimensionless), ``contactState`` (the S it comes from), ``realPart`` (1/s) and ``frequencyHz``
        of that eigenvalue, ``small`` (``margin < SMALL_MARGIN``).
    """
    best = None
    for S, lam in _Eigenvalues(drive).items():
        lam = lam[np.abs(lam) > 1e-9 * max(float(np.max(np.abs(lam), initial=0.)), 1e-300)]   # no rigid-body modes
        if not lam.size:
            continue
        right = lam[np.argmax(lam.real)]
        margin = abs(right.real) / abs(right)
        if best is None or margin < best['margin']:
            best = {'margin': float(margin), 'contactState': S, 'realPart': float(right.real),
                    'frequencyHz': float(abs(right.imag)) / (2 * math.pi)}
    if best is None:
        best = {'margin': math.inf, 'contactState': None, 'realPart': None, 'frequencyHz': None}
    best['small'] = best['margin'] < SMALL_MARGIN
    return best


def StepCheckByDefault(drive: Drive) -> bool:
    """Whether ``simulate`` and ``sweep`` may check their verdicts at half the step when not told: the linear margin
    (:func:`LinearMargin`) is below :data:`SMALL_MARGIN`. They then run at half the step only if a window's own
    verdict is close (:func:`CloseVerdicts`).

    Parameters
    ----------
    drive : Drive
        The drive.
    """
    return LinearMargin(drive)['small']


def CompareHalfStep(metrics: Sequence[Mapping], halfStepMetrics: Sequence[Mapping]) -> List[dict]:
    """The window metrics of a run with the verdicts checked against the same run at half the step.

    Parameters
    ----------
    metrics : sequence of mapping
        Window metrics of the run (:meth:`~exudyn_worm.items.results.SimulationResult.WindowMetrics`).
    halfStepMetrics : sequence of mapping
        The same windows of the run at half the step.

    Returns
    -------
    list of dict
        ``metrics`` with ``chatter`` set to :data:`UNRESOLVED` where the two verdicts (True, False or
        ``'undecided'``) differ, and ``halfStep``: the
        half-step run's metrics of the window.

    Raises
    ------
    ValueError
        If the two runs have different windows.
    """
    if len(metrics) != len(halfStepMetrics) or any(
            (a['t0'], a['t1']) != (b['t0'], b['t1']) for a, b in zip(metrics, halfStepMetrics)):
        raise ValueError(f"CompareHalfStep: 'halfStepMetrics' must have the windows of 'metrics', got "
                         f"{[(b['t0'], b['t1']) for b in halfStepMetrics]} against {[(a['t0'], a['t1']) for a in metrics]}")
    out = []
    for a, b in zip(metrics, halfStepMetrics):
        chatter = a['chatter'] if a['chatter'] == b['chatter'] else UNRESOLVED
        out.append(dict(a, chatter=chatter, halfStep={k: v for k, v in b.items() if k not in ('t0', 't1')}))
    return out


#: a window's chatter verdict counts as close, and is checked at half the step by default, when its
#: :meth:`~exudyn_worm.items.results.SimulationResult.ChatterRatio` is within this factor of 1 (between 1/2 and 2).
#: Halving the recommended step moved the ratio of every window of reel-P1, P6 and P7 by 6 % at most (P7's
#: lowering 5.08 -> 4.79, its chattering lift 2.02 -> 1.96; h/4 within 1 % of h/2); in the drive of the module text
#: the lift window's peak doubled while its ratio stayed below 0.16: a factor 2 covers a doubling of the amplitude
VERDICT_FACTOR = 2.


def CloseVerdicts(result: Any, windows: Sequence) -> List[int]:
    """The windows whose chatter verdict is close: the
    :meth:`~exudyn_worm.items.results.SimulationResult.ChatterRatio` of the run is within :data:`VERDICT_FACTOR` of 1.

    By default ``simulate`` and ``sweep`` run at half the step only where the linear margin is small
    (:func:`StepCheckByDefault`) and some window's verdict is close; a verdict far from its threshold does not change
    when the step is halved (see :data:`VERDICT_FACTOR`).

    Parameters
    ----------
    result : SimulationResult
        The run at the chosen step.
    windows : sequence of (float, float)
        The evaluation windows in s.

    Returns
    -------
    list of int
        Indices into ``windows``.
    """
    return [i for i, (t0, t1) in enumerate(windows)
            if 1. / VERDICT_FACTOR < result.ChatterRatio(t0, t1) < VERDICT_FACTOR]
