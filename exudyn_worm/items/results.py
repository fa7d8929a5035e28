"""Simulation results of a worm drive: time series, mesh quantities, window metrics, saving.

Mesh quantities are post-processed from the stored node states with the same contact law the
connector uses (:func:`exudyn_worm.model.contact.MeshContact` on numpy arrays).
"""
from __future__ import annotations

import csv
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np
from .._checks import JsonNumber
from ..model.contact import NormalForceFlanks

__all__ = ['SimulationResult', 'SeriesUnit', 'SERIES_UNITS', 'BEARING_LOADS', 'CheckWindows', 'ChatterVerdict',
           'SteadyMotorStretch', 'STEADY_MOTOR_TOLERANCE',
           'CHATTER_AMPLITUDE', 'CHATTER_STEADY_EXPONENT', 'CHATTER_GROWTH_EXPONENT', 'CHATTER_DECAY_EXPONENT',
           'CHATTER_SATURATION', 'CHATTER_MIN_PERIODS', 'CHATTER_STATES', 'UNDECIDED', 'CHATTER_MIN_MESH_TORQUE',
           'CHATTER_TORQUE_FRACTION']

# The chatter rule of SimulationResult.Chatter, fixed with its reasons in validation/CHATTER_RULE.md: the mesh's
# normal force and its sliding (worm speed against the motor), each as an amplitude relative to its steady value
# in the window's last quarter, and the growth or decay rate of that relative amplitude's envelope over the
# window's second half.
#: a vibration counts: the relative amplitude of the mesh's normal force or sliding in the window's last quarter is
#: at least this (a self-excited vibration of a zero-backlash mesh saturates only where the flanks unload or the
#: sliding stops, at a relative amplitude of about 1; speed ramps and slow duty changes move the mesh by a few per cent)
CHATTER_AMPLITUDE = 0.25
#: steady: the envelope's rate sigma (1/s) times the window length L is at least -this (it loses less than
#: 1 - exp(-0.2) = 18 % over the window); below it the vibration decays
CHATTER_STEADY_EXPONENT = 0.2
#: growing: sigma L is at least this (it gains more than a factor exp(0.2) over the window)
CHATTER_GROWTH_EXPONENT = 0.2
#: decided decaying: sigma L <= -this, the decay time 1/abs(sigma) is at most the window; between this and
#: -:data:`CHATTER_STEADY_EXPONENT` the decay time is longer than the window and the window is undecided
CHATTER_DECAY_EXPONENT = 1.
#: a steady (neither growing nor decaying) vibration is chatter only where it saturates: its relative amplitude is
#: at least this (the flanks unload or the sliding stops or reverses); a steady vibration below it may be a lightly
#: damped free vibration whose decay the window cannot resolve: undecided
CHATTER_SATURATION = 1.
#: the envelope is measured over sliding spans of one period of the dominant frequency; at least this many periods
#: must fit in the window's second half, else its rate is not measured (undecided where the amplitude counts)
CHATTER_MIN_PERIODS = 2.
#: the states of a window's :class:`ChatterVerdict`; ``chatter`` and ``undecided`` are the strings of a window's
#: ``chatter`` metric beside True / False
CHATTER_STATES = ('chatter', 'none', 'decaying', 'undecided')
UNDECIDED = 'undecided'
#: ... and only where the mesh carries a load: below this mesh torque on the wheel (N*m) a window has no load
#: to chatter against; what moves there is round-off (about 1e-7 N*m in P1 without load, 1e-3 N*m is 1e4 times that)
CHATTER_MIN_MESH_TORQUE = 1e-3
#: wheel inertia torque J2*|phi2''| against this fraction of the largest mesh torque on the wheel: the chatter rule
#: before the mesh-based one, kept for the wheel's vibration time of a study
#: (:func:`~exudyn_worm.analysis.studies.studypoint.VibrationSeconds`)
CHATTER_TORQUE_FRACTION = 0.1


def _Detrended(t: np.ndarray, x: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """``x`` minus a quadratic fitted over ``t`` (the slow, quasi-static part), and that quadratic."""
    if x.size < 3:
        return np.zeros_like(x), x.astype(float)
    tc = t - t.mean()
    scale = max(float(np.max(np.abs(tc))), 1e-300)
    trend = np.polyval(np.polyfit(tc / scale, x, 2), tc / scale)
    return x - trend, trend


def _FastFftLength(n: int) -> int:
    """The smallest length >= ``n`` whose prime factors are 2, 3 and 5 only (a fast length of numpy's real FFT;
    the same as ``scipy.fft.next_fast_len(n, real=True)``, without importing SciPy in a simulation's process).
    A window's own length can have a large prime factor (1289), and the FFT of such a length is 25-45 times
    slower than of a fast one."""
    best = 1 << max(int(n) - 1, 0).bit_length()          # the next power of 2
    p5 = 1
    while p5 < best:
        p35 = p5
        while p35 < best:
            p235 = p35                     # then the smallest power of 2 times p35 that reaches n
            if p235 < n:
                p235 <<= (-(-n // p235) - 1).bit_length()
            best = min(best, p235)
            p35 *= 3
        p5 *= 5
    return best


def _HalfRange(x: np.ndarray) -> float:
    return 0.5 * float(np.max(x) - np.min(x)) if x.size else 0.


def _DominantFrequency(t: np.ndarray, rest: np.ndarray) -> float:
    """Frequency in Hz of the largest spectral peak of ``rest`` (mean removed, Hann window, zero-padded 4 times);
    0 where it holds fewer than 16 samples or does not move."""
    n = rest.size
    if n < 16 or not np.any(rest):
        return 0.
    dt = float(t[-1] - t[0]) / (n - 1)
    spectrum = np.abs(np.fft.rfft((rest - rest.mean()) * np.hanning(n), n=4 * n))
    freq = np.fft.rfftfreq(4 * n, dt)
    return float(freq[1:][np.argmax(spectrum[1:])])


def _SteadyValueLeak(rest: np.ndarray, steady: np.ndarray, periods: float, window: float, stretch: float) -> float:
    """Bound on what a swing can add to sigma L through a steady value fitted as a quadratic over the stretch.

    A least-squares quadratic over ``periods`` whole periods of a tone of amplitude A takes up a line whose range over
    the stretch is 6 A / (pi N) (closed form: the Legendre coefficient of the linear term is 3 A cos(phase) / (pi N)),
    so the fitted steady value m may change by 6 a / (pi N) of itself, a = half the range of ``rest`` over the mean
    of ``steady``; over the stretch of length T that is a rate of at most that over T, and sigma L up to
    (6 / pi) (a / N) (L / T). The revised chatter rule (validation/CHATTER_RULE.md) divides the envelope by the fitted
    steady value only where this is at most :data:`CHATTER_STEADY_EXPONENT`.

    Parameters
    ----------
    rest : numpy.ndarray
        The measure's signal over the stretch, its quadratic removed.
    steady : numpy.ndarray
        The magnitude of that quadratic (the fitted steady value), per sample.
    periods : float
        Periods N of the dominant frequency in the stretch, > 0.
    window : float
        The window's length L in s.
    stretch : float
        The stretch's length T in s, > 0.

    Returns
    -------
    float
        The bound on sigma L (inf where the steady value is 0).
    """
    mean = float(np.mean(np.abs(steady))) if steady.size else 0.
    if mean <= 0. or periods <= 0. or stretch <= 0.:
        return float('inf')
    return 6. / np.pi * _HalfRange(rest) / mean / periods * window / stretch


def _EnvelopeRate(t: np.ndarray, rest: np.ndarray, steady: np.ndarray, fitted: bool, window: float) -> float:
    """Robust slope (1/s, Theil-Sen: the median of the slopes between all pairs of points) of the log of the envelope
    of ``rest`` (half its range over sliding spans of one dominant period), divided span by span by the span's mean
    |steady| unless that steady value is ``fitted`` and not resolved against the swing (:func:`_SteadyValueLeak` above
    :data:`CHATTER_STEADY_EXPONENT`: then the half range's own rate); NaN where fewer than CHATTER_MIN_PERIODS
    periods fit."""
    n = rest.size
    f = _DominantFrequency(t, rest)
    if f <= 0.:
        return float('nan')
    dt = float(t[-1] - t[0]) / (n - 1)
    span = max(3, int(round(1. / (f * dt))))
    if CHATTER_MIN_PERIODS * span > n:
        return float('nan')
    stretch = float(t[-1] - t[0])
    divide = not fitted or _SteadyValueLeak(rest, steady, f * stretch, window, stretch) <= CHATTER_STEADY_EXPONENT
    starts = np.unique(np.linspace(0, n - span, min(64, n - span + 1)).astype(int))
    env = np.array([_HalfRange(rest[i:i + span])
                    / (max(float(np.mean(np.abs(steady[i:i + span]))), 1e-300) if divide else 1.) for i in starts])
    centres = t[starts + span // 2]
    if np.any(env <= 0.):
        return float('nan')
    i, j = np.triu_indices(env.size, 1)          # Theil-Sen: the median of the slopes between all pairs of points
    return float(np.median((np.log(env[j]) - np.log(env[i])) / (centres[j] - centres[i])))


#: the motor holds its speed where it stays within this fraction of its largest speed in the window of the median
STEADY_MOTOR_TOLERANCE = 1e-6


def SteadyMotorStretch(result: 'SimulationResult', t0: float, t1: float) -> Tuple[float, float]:
    """The longest stretch (a, b) of [t0, t1] in which the motor speed stays within :data:`STEADY_MOTOR_TOLERANCE` of
    its largest magnitude from its median in [t0, t1] ([t0, t1] itself without a motor series or where it holds).

    Parameters
    ----------
    result : SimulationResult
        The run.
    t0, t1 : float
        The span in s.

    Returns
    -------
    (float, float)
    """
    m = result._Window(t0, t1)
    if 'omega0' not in result.series or np.count_nonzero(m) < 2:
        return t0, t1
    t, w = result.time[m], result.series['omega0'][m]
    scale = float(np.max(np.abs(w)))
    held = np.abs(w - np.median(w)) <= STEADY_MOTOR_TOLERANCE * scale
    if held.all() or not held.any():
        return t0, t1
    edges = np.diff(np.concatenate(([0], held.astype(int), [0])))
    starts, ends = np.nonzero(edges == 1)[0], np.nonzero(edges == -1)[0]
    k = int(np.argmax(ends - starts))
    return float(t[starts[k]]), float(t[ends[k] - 1])


def _MeasureState(amplitude: float, rate: float, length: float, fewPeriods: bool = False,
                  reversal: bool = False) -> str:
    """One measure's state by the rule of SimulationResult.ChatterVerdict (``fewPeriods``: fewer than
    CHATTER_MIN_PERIODS periods in the last quarter; ``reversal``: the worm turns back in it)."""
    if amplitude < CHATTER_AMPLITUDE:
        return 'none'
    if fewPeriods or not np.isfinite(rate):
        return UNDECIDED
    exponent = rate * length
    if exponent <= -CHATTER_DECAY_EXPONENT:
        return 'decaying'
    if exponent < -CHATTER_STEADY_EXPONENT:
        return UNDECIDED
    if exponent >= CHATTER_GROWTH_EXPONENT:
        return 'chatter'
    return 'chatter' if amplitude >= CHATTER_SATURATION or reversal else UNDECIDED


@dataclass(frozen=True)
class ChatterVerdict:
    """The chatter verdict of one window (:meth:`SimulationResult.ChatterVerdict`).

    Attributes
    ----------
    state : str
        ``'chatter'``, ``'none'`` (no vibration of :data:`CHATTER_AMPLITUDE`), ``'decaying'`` (a vibration that
        decays within the window) or ``'undecided'`` (a vibration whose decay time is longer than the window, a
        steady one below :data:`CHATTER_SATURATION` without the worm turning back, or too few periods).
    measures : tuple of str
        The measures (``'normal'``, ``'sliding'``) in that state.
    window : float
        The window's length L in s.
    amplitude : float
        The deciding measure's relative amplitude in the window's last quarter.
    rate : float
        Its envelope's growth (> 0) or decay (< 0) rate in 1/s over the window's second half (NaN: not measured, or
        fewer than :data:`CHATTER_MIN_PERIODS` periods in the last quarter).
    """
    state: str
    measures: Tuple[str, ...]
    window: float
    amplitude: float
    rate: float

    @property
    def chatter(self) -> bool:
        """True where the window chatters."""
        return self.state == 'chatter'

    @property
    def decided(self) -> bool:
        """False where the window is undecided."""
        return self.state != UNDECIDED

    @property
    def value(self):
        """The window's ``chatter`` metric: True, False or ``'undecided'``."""
        return UNDECIDED if self.state == UNDECIDED else self.chatter

    @classmethod
    def FromMetrics(cls, metrics: Dict) -> 'ChatterVerdict':
        """The verdict of a window from its metrics (:meth:`SimulationResult.WindowMetrics`, JSON or a study's row).

        Parameters
        ----------
        metrics : dict
            ``t0``, ``t1``, ``chatterState``, ``chatterAmplitude``, ``envelopeRate`` (None: not measured).
        """
        rate = metrics.get('envelopeRate')
        return cls(state=metrics['chatterState'], measures=(), window=float(metrics['t1']) - float(metrics['t0']),
                   amplitude=float(metrics['chatterAmplitude']), rate=float('nan') if rate is None else float(rate))

    def Describe(self) -> str:
        """The verdict in words, e.g. ``'decaying, rate -2.5 1/s (amplitude 0.6)'``."""
        rate = 'rate not measured' if not np.isfinite(self.rate) else f"rate {self.rate:+.3g} 1/s"
        if self.state == 'none':
            return f"no vibration of {CHATTER_AMPLITUDE:g} of the steady value (amplitude {self.amplitude:.3g})"
        if self.state == 'decaying':
            return f"decaying, {rate} (amplitude {self.amplitude:.3g})"
        if self.state == 'chatter':
            how = ('growing' if self.rate * self.window >= CHATTER_GROWTH_EXPONENT
                   else 'steady at the saturated amplitude' if self.amplitude >= CHATTER_SATURATION
                   else 'steady, the worm turning back')
            return f"{how}, {rate} (amplitude {self.amplitude:.3g})"
        if not np.isfinite(self.rate):
            why = (f"fewer than {CHATTER_MIN_PERIODS:g} periods of its dominant frequency in the window's last quarter "
                   f"(its amplitude) or second half (its rate, where the motor holds its speed); a longer window "
                   f"decides")
        elif self.rate * self.window >= -CHATTER_STEADY_EXPONENT:
            why = (f"steady, {rate}, below the saturated amplitude {CHATTER_SATURATION:g} and without the worm "
                   f"turning back: a lightly damped free vibration looks the same; a longer window or the linear "
                   f"verdict decides")
        else:
            why = (f"decaying, {rate}: its decay time {-1. / self.rate:.3g} s is longer than the window "
                   f"{self.window:.3g} s")
        return f"undecided: amplitude {self.amplitude:.3g}, {why}"


def _VerdictMetrics(verdict: ChatterVerdict) -> Dict:
    """The window metrics of a verdict (SimulationResult.WindowMetrics; ChatterVerdict.FromMetrics reads them)."""
    return {'chatter': verdict.value, 'chatterState': verdict.state, 'chatterAmplitude': verdict.amplitude,
            'envelopeRate': JsonNumber(verdict.rate)}


@dataclass
class SimulationResult:
    """Time series of one simulation (SI units) plus the metadata needed to judge chatter.

    Attributes hold arrays over ``time`` (s): motor angle/speed ``phi0, omega0`` (rad, rad/s); worm and wheel
    angles, speeds, accelerations ``phi1, omega1, alpha1, phi2, omega2, alpha2`` (rad, rad/s, rad/s^2); mesh
    quantities ``deltaPhi`` (rad), ``deltaS`` (m), ``normalForce`` (N, **signed**: < 0 on the second flank; use
    :attr:`normalForceFlanks` for magnitudes), ``S``, ``sf`` (see :class:`~exudyn_worm.model.contact.MeshState`),
    ``wormTorque, wheelTorque`` (N*m); ``driveTorque`` M_an (eq. (6), N*m) and ``tangentialForce`` F_V
    (eq. (7), N). Units of every series: :meth:`ToCsv`'s header.

    Attributes
    ----------
    time : numpy.ndarray
        Output times in s.
    series : dict of str to numpy.ndarray
        The time series above by name, each over ``time`` (also readable as attributes).
    J2 : float
        Wheel-side inertia in kg*m^2.
    r2 : float
        Wheel radius in m.
    solveSeconds : float
        Wall-clock time of the solve in s.
    steps : int
        Number of time steps.
    info : dict
        Metadata of the run (step size, maximum load torque, ...); :meth:`Chatter` reads ``frictionSpeed`` (m/s)
        and ``slidingRadius`` (r1/cos(gamma) in m, sliding speed per worm speed) where given.
    """
    time: np.ndarray
    series: Dict[str, np.ndarray]
    J2: float
    r2: float
    solveSeconds: float = 0.
    steps: int = 0
    info: Dict = field(default_factory=dict)

    def __getattr__(self, name):
        series = self.__dict__.get('series', {})
        if name in series:
            return series[name]
        raise AttributeError(name)

    @property
    def endTime(self) -> float:
        return float(self.time[-1])

    @property
    def normalForceFlanks(self) -> Tuple[np.ndarray, np.ndarray]:
        """Normal force magnitudes in N (both >= 0) on the flank pushed by a leading worm (Delta s > 0) and on
        the other flank (:func:`~exudyn_worm.model.contact.NormalForceFlanks`); ``normalForce`` itself is signed."""
        return NormalForceFlanks(self.series['normalForce'])

    def _Window(self, t0, t1):
        return (self.time >= t0) & (self.time <= t1)

    def DominantFrequency(self, t0: float, t1: float, signal: str = 'alpha2') -> float:
        """Frequency in Hz of the largest spectral peak of ``signal`` in [t0, t1] (mean removed, Hann window,
        zero-padded to at least 4 times the window's samples: a frequency step of at most a quarter of
        1 / (t1 - t0); the padded length is the next one whose prime factors are 2, 3 and 5, for speed)."""
        m = self._Window(t0, t1)
        x = self.series[signal][m]
        if x.size < 8:
            return 0.
        dt = float(np.mean(np.diff(self.time[m])))
        x = (x - x.mean()) * np.hanning(x.size)
        n = _FastFftLength(4 * x.size)
        spectrum = np.abs(np.fft.rfft(x, n=n))
        freq = np.fft.rfftfreq(n, dt)
        return float(freq[1:][np.argmax(spectrum[1:])])

    def MeshOscillation(self, t0: float, t1: float) -> Dict[str, List[float]]:
        """Relative amplitudes of the mesh's motion in each quarter of [t0, t1] (the measures of :meth:`Chatter`).

        ``normal``: half the range of the normal force after a quadratic over time (the quasi-static force) is
        removed, over the mean magnitude of that quadratic. ``sliding``: half the range of the worm speed minus
        the motor speed (the sliding speed r1 phi1'/cos(gamma) is proportional to the worm speed; steady sliding
        follows the motor), a quadratic removed, over the mean motor speed magnitude, but at least the worm speed
        of the friction law's regularization speed (``info['frictionSpeed'] / info['slidingRadius']``); without
        a motor series the worm speed's own quadratic is the steady part. A sliding amplitude above 1 with the
        motor at speed means the worm turns back.

        Parameters
        ----------
        t0, t1 : float
            The window in s.

        Returns
        -------
        dict
            ``normal`` and ``sliding``: four dimensionless amplitudes each, one per quarter (0 where a quarter
            holds fewer than 3 samples or the steady value is 0).
        """
        out = {'normal': [], 'sliding': []}
        for k in range(4):
            for name, a in self._QuarterAmplitudes(t0 + k * (t1 - t0) / 4, t0 + (k + 1) * (t1 - t0) / 4).items():
                out[name].append(a)
        return out

    def _SlidingFloor(self) -> float:
        """The worm speed of the friction law's regularization speed in rad/s (0 where the run does not say)."""
        return (self.info['frictionSpeed'] / self.info['slidingRadius']
                if 'frictionSpeed' in self.info and 'slidingRadius' in self.info else 0.)

    def _QuarterAmplitudes(self, a: float, b: float, fitFrom: Optional[float] = None) -> Dict[str, float]:
        """The relative amplitudes of :meth:`MeshOscillation` over [a, b]; with ``fitFrom`` the quadratic removed from
        the signal is fitted over [fitFrom, b] instead (the steady value stays that of [a, b])."""
        s, t = self.series, self.time
        m = self._Window(a, b)
        if np.count_nonzero(m) < 3:
            return {'normal': 0., 'sliding': 0.}
        fit = m if fitFrom is None else self._Window(fitFrom, b)
        inner = m[fit]

        def Rest(x):
            rest, trend = _Detrended(t[fit], x[fit])
            return rest[inner], (trend[inner] if fitFrom is None else _Detrended(t[m], x[m])[1])
        out = {}
        rest, trend = Rest(s['normalForce'])
        steady = float(np.mean(np.abs(trend)))
        out['normal'] = _HalfRange(rest) / steady if steady > 0. else 0.
        if 'omega0' in s:
            rest, _ = Rest(s['omega1'] - s['omega0'])
            steady = float(np.mean(np.abs(s['omega0'][m])))
        else:
            rest, trend = Rest(s['omega1'])
            steady = float(np.mean(np.abs(trend)))
        steady = max(steady, self._SlidingFloor())
        out['sliding'] = _HalfRange(rest) / steady if steady > 0. else 0.
        return out

    def _Relative(self, t0: float, t1: float) -> Dict[str, Tuple[np.ndarray, np.ndarray, np.ndarray, bool]]:
        """Per measure of :meth:`MeshOscillation`, over [t0, t1]: time, the signal with its quadratic removed, its
        steady value (positive, per sample) and whether that steady value is fitted (the quadratic's magnitude) rather
        than given (the motor speed)."""
        s, t = self.series, self.time
        m = self._Window(t0, t1)
        floor = self._SlidingFloor()
        tm = t[m]
        rest, trend = _Detrended(tm, s['normalForce'][m])
        out = {'normal': (tm, rest, np.abs(trend), True)}
        if 'omega0' in s:
            rest, _ = _Detrended(tm, s['omega1'][m] - s['omega0'][m])
            out['sliding'] = (tm, rest, np.maximum(np.abs(s['omega0'][m]), floor), False)
        else:
            rest, steady = _Detrended(tm, s['omega1'][m])
            out['sliding'] = (tm, rest, np.maximum(np.abs(steady), floor), True)
        return out

    def _RatesAndFrequencies(self, t0: float, t1: float) -> Dict[str, Tuple[float, float]]:
        """Per measure: the rate of :meth:`EnvelopeRates` and the dominant frequency in Hz over the same stretch."""
        a, b = SteadyMotorStretch(self, 0.5 * (t0 + t1), t1)
        return {name: (_EnvelopeRate(tm, rest, steady, fitted, float(t1 - t0)), _DominantFrequency(tm, rest))
                for name, (tm, rest, steady, fitted) in self._Relative(a, b).items()}

    def EnvelopeRates(self, t0: float, t1: float) -> Dict[str, float]:
        """Growth (> 0) or decay (< 0) rate in 1/s of each mesh measure's relative vibration amplitude over the
        second half of [t0, t1] (the measures of :meth:`MeshOscillation`).

        The measure's signal, a quadratic over the second half removed, has its envelope taken as half the range
        over sliding spans of one period of its dominant frequency (a span's steady value, the mean magnitude of the
        quadratic or of the motor speed, at least the friction law's regularization speed, divides it, except where
        the steady value is the fitted quadratic and the swing could move it across the steady band: then the half
        range itself, see validation/CHATTER_RULE.md); the rate is
        the slope of the logarithm of that envelope over time, fitted robustly (Theil-Sen: the median of the
        slopes between all pairs of envelope points, so that a stop at the window's end, a speed ramp to rest, does
        not read as a decay of the whole window). Only the longest stretch of the second half in which the motor
        holds its speed is fitted (:func:`SteadyMotorStretch`: a ramp within the window, which starts a transient of
        the drive, is left out). NaN where fewer than :data:`CHATTER_MIN_PERIODS` periods of the dominant frequency
        fit in that stretch, or where the signal does not move.

        Parameters
        ----------
        t0, t1 : float
            The window in s.

        Returns
        -------
        dict
            ``normal`` and ``sliding``: rates in 1/s.
        """
        return {name: rate for name, (rate, _) in self._RatesAndFrequencies(t0, t1).items()}

    def ChatterVerdict(self, t0: float, t1: float) -> 'ChatterVerdict':
        """The chatter verdict of [t0, t1] from the amplitude and the growth or decay rate of the mesh's vibration.

        For each measure of :meth:`MeshOscillation` (the normal force, the sliding), with its relative amplitude a4
        in the last quarter and the rate sigma of :meth:`EnvelopeRates` over the window's second half, L = t1 - t0:

        - a4 < :data:`CHATTER_AMPLITUDE`: ``none`` (small); where the last quarter holds fewer than
          :data:`CHATTER_MIN_PERIODS` periods of the measure's dominant frequency, a4 is also read with the whole
          window's quadratic removed and the larger reading counts;
        - fewer than :data:`CHATTER_MIN_PERIODS` periods in the last quarter, or sigma not measured: ``undecided``;
        - sigma L <= -:data:`CHATTER_DECAY_EXPONENT`: ``decaying`` (its decay time is at most the window), at any
          amplitude;
        - -:data:`CHATTER_DECAY_EXPONENT` < sigma L < -:data:`CHATTER_STEADY_EXPONENT`: ``undecided`` (the decay time
          is longer than the window);
        - sigma L >= :data:`CHATTER_GROWTH_EXPONENT`: ``chatter`` (growing);
        - steady between: ``chatter`` where it saturates, a4 >= :data:`CHATTER_SATURATION` (the flanks unload or
          change) or, for the sliding, the worm turns back in the last quarter with the motor at speed; else
          ``undecided`` (a lightly damped free vibration looks the same).

        The window's state: ``chatter`` if any measure chatters, else ``undecided`` if any is undecided, else
        ``decaying`` if any decays, else ``none``; ``none`` for an unloaded mesh (its torque on the wheel never above
        :data:`CHATTER_MIN_MESH_TORQUE`). The rule and its reasons: validation/CHATTER_RULE.md.

        Parameters
        ----------
        t0, t1 : float
            The window in s.

        Returns
        -------
        ChatterVerdict
        """
        length = float(t1 - t0)
        loaded = self._LoadedOscillation(t0, t1)
        measured = self._RatesAndFrequencies(t0, t1) if loaded else {}
        amplitudes, rates, states = {}, {}, {}
        for name, a in loaded.items():
            rate, f = measured[name]
            few = f * length / 4 < CHATTER_MIN_PERIODS
            amplitudes[name] = (max(a[3], self._QuarterAmplitudes(t0 + 0.75 * length, t1, fitFrom=t0)[name])
                                if few else a[3])
            rates[name] = float('nan') if few else rate
            states[name] = _MeasureState(amplitudes[name], rates[name], length, few,
                                         name == 'sliding' and self._WormTurnsBack(t0 + 0.75 * length, t1))
        state = next((x for x in ('chatter', UNDECIDED, 'decaying') if x in states.values()), 'none')
        measures = tuple(name for name, x in states.items() if x == state) if state != 'none' else ()
        pick = max(measures or tuple(loaded), key=lambda name: amplitudes[name], default=None)
        return ChatterVerdict(state=state, measures=measures, window=length,
                              amplitude=float(amplitudes[pick]) if pick else 0.,
                              rate=float(rates[pick]) if pick else float('nan'))

    def _WormTurnsBack(self, a: float, b: float) -> bool:
        """The worm turns back in [a, b] (:meth:`MinWormSpeed` <= 0) while the motor's mean speed magnitude there
        exceeds the worm speed of the friction law's regularization speed; False without a motor series."""
        m = self._Window(a, b)
        if 'omega0' not in self.series or not m.any():
            return False
        return (abs(float(np.mean(self.series['omega0'][m]))) > self._SlidingFloor()
                and self.MinWormSpeed(a, b) <= 0.)

    def Chatter(self, t0: float, t1: float) -> bool:
        """Chatter in [t0, t1]: :meth:`ChatterVerdict`'s state is ``chatter`` (a vibration of the mesh that grows,
        or keeps a saturated amplitude, over the window's second half; a decaying or undecided window is not).

        Parameters
        ----------
        t0, t1 : float
            The window in s.

        Returns
        -------
        bool
        """
        return self.ChatterVerdict(t0, t1).chatter

    def ChatterMeasures(self, t0: float, t1: float) -> List[str]:
        """The measures of :meth:`MeshOscillation` by which [t0, t1] chatters (:meth:`ChatterVerdict`): ``'normal'``,
        ``'sliding'``, both or none (none also for an unloaded mesh).

        Parameters
        ----------
        t0, t1 : float
            The window in s.

        Returns
        -------
        list of str
        """
        v = self.ChatterVerdict(t0, t1)
        return list(v.measures) if v.chatter else []

    def _LoadedOscillation(self, t0: float, t1: float) -> Dict[str, List[float]]:
        """:meth:`MeshOscillation` of [t0, t1], empty for an unloaded mesh (its torque on the wheel never above
        :data:`CHATTER_MIN_MESH_TORQUE`)."""
        m = self._Window(t0, t1)
        meshTorque = np.max(np.abs(self.series['wheelTorque'][m])) if m.any() else 0.
        return self.MeshOscillation(t0, t1) if meshTorque > CHATTER_MIN_MESH_TORQUE else {}

    def ChatterRatio(self, t0: float, t1: float) -> float:
        """How clearly the amplitude of [t0, t1] counts: for each measure of :meth:`MeshOscillation`, the last
        quarter's amplitude over :data:`CHATTER_AMPLITUDE`; the largest over the measures (0 for an unloaded mesh).
        Near 1 the verdict is close (the step check of :mod:`exudyn_worm.analysis.simulation.stepsize` looks there).

        Parameters
        ----------
        t0, t1 : float
            The window in s.

        Returns
        -------
        float
            Dimensionless, >= 0.
        """
        return max((a[3] / CHATTER_AMPLITUDE for a in self._LoadedOscillation(t0, t1).values()), default=0.)

    def MinWormSpeed(self, t0: float, t1: float) -> float:
        """Smallest worm speed in [t0, t1] in rad/s, counted in the direction the motor turns in the window
        (the sign of its mean speed; forward where it stands or without a motor series): negative where the
        worm turns back, also while lowering with the motor reversed.

        Parameters
        ----------
        t0, t1 : float
            The window in s.
        """
        m = self._Window(t0, t1)
        if not m.any():
            return float('nan')
        mean = float(np.mean(self.series['omega0'][m])) if 'omega0' in self.series else 0.
        return float(np.min((-1. if mean < 0. else 1.) * self.series['omega1'][m]))

    def WindowMetrics(self, windows: Sequence[Tuple[float, float]]) -> List[Dict]:
        """Per window: t0, t1, maxAbsWheelAcceleration (rad/s^2), maxNormalForce (N), dominantFrequencyHz,
        fractionSNegative, minWormSpeed (rad/s, in the motor's direction: :meth:`MinWormSpeed`), chatter (True, False
        or ``'undecided'``: :meth:`ChatterVerdict`), chatterState (its state), chatterAmplitude (relative) and
        envelopeRate (1/s, None where not measured) of its deciding measure; for a run
        of the 3D model (worm and wheel as rigid bodies) also ``bearingLoads``: the peak magnitudes in N of
        :data:`BEARING_LOADS` (``wormAxial``, ``wormRadial``, ``wheelAxial``, ``wheelRadial``; radial: the vector sum
        over the shaft's radial bearings)."""
        out = []
        for t0, t1 in CheckWindows(windows, self.endTime, 'SimulationResult.WindowMetrics'):
            m = self._Window(t0, t1)
            if not m.any():
                raise ValueError(f"window {t0:g}:{t1:g} s holds no output time (simulated 0:{self.endTime:g} s)")
            out.append({'t0': float(t0), 't1': float(t1),
                        'maxAbsWheelAcceleration': float(np.max(np.abs(self.series['alpha2'][m]))),
                        'maxNormalForce': float(np.max(np.abs(self.series['normalForce'][m]))),
                        'dominantFrequencyHz': self.DominantFrequency(t0, t1),
                        'fractionSNegative': float(np.mean(self.series['S'][m] < 0)),
                        'minWormSpeed': self.MinWormSpeed(t0, t1),
                        **_VerdictMetrics(self.ChatterVerdict(t0, t1))})
            if all(name in self.series for name in BEARING_LOADS.values()):     # the 3D model
                out[-1]['bearingLoads'] = {key: float(np.max(np.abs(self.series[name][m])))
                                           for key, name in BEARING_LOADS.items()}
        return out

    def ToCsv(self, path) -> Path:
        """Write all time series to a CSV file (header with SI units). Returns the path.

        Raises
        ------
        ValueError
            If ``path`` is a folder or its folder does not exist.
        """
        path = Path(path)
        if path.is_dir() or not path.parent.is_dir():
            raise ValueError(f"SimulationResult.ToCsv: 'path' must be a file in an existing folder, got '{path}'"
                             + (' (a folder)' if path.is_dir() else f" (no folder '{path.parent}')"))
        names = list(self.series)
        with path.open('w', newline='') as f:
            w = csv.writer(f)
            w.writerow(['time [s]'] + [f'{n} [{SeriesUnit(n)}]' for n in names])
            data = np.column_stack([self.time] + [self.series[n] for n in names])
            w.writerows(data.tolist())
        return path

    def plot(self, kind: str = 'overview', **kwargs):
        """Plot with :func:`exudyn_worm.plotting.plot.PlotSimulation` (matplotlib is imported only there).

        Parameters
        ----------
        kind : str, optional
            Kind of figure, as for :func:`~exudyn_worm.plotting.plot.PlotSimulation`.
        **kwargs
            Passed on to :func:`~exudyn_worm.plotting.plot.PlotSimulation`.

        Returns
        -------
        matplotlib.figure.Figure
        """
        from ..plotting import plot                         # lazy: matplotlib only when drawing
        return plot.PlotSimulation(self, kind=kind, **kwargs)


#: SI units of the mesh and bearing series of a :class:`SimulationResult` (rotor series: :func:`SeriesUnit`)
#: the bearing loads of a run of the 3D model: key of the peak in :meth:`SimulationResult.WindowMetrics` -> series
BEARING_LOADS = {'wormAxial': 'wormAxialLoad', 'wormRadial': 'wormRadialLoad', 'wheelAxial': 'wheelAxialLoad',
                 'wheelRadial': 'wheelRadialLoad'}
SERIES_UNITS = {'deltaPhi': 'rad', 'deltaS': 'm', 'normalForce': 'N', 'S': '-', 'sf': '-', 'wormTorque': 'N*m',
                'wheelTorque': 'N*m', 'driveTorque': 'N*m', 'tangentialForce': 'N',
                'xA': 'm', 'vA': 'm/s', 'aA': 'm/s^2', 'axialForce': 'N',
                # the 3D model (worm and wheel as rigid bodies): bearing loads and the mesh force on each body
                **{f'{body}{d}Load': 'N' for body in ('worm', 'wheel') for d in ('Axial', 'Radial')},
                **{f'mesh{body}{d}': 'N' for body in ('Worm', 'Wheel') for d in ('Tangential', 'Axial', 'Radial')}}
#: angle, speed and acceleration of rotor i (0 motor, 1 worm, 2 wheel, 4, 5, ... the drive-side chain)
_ROTOR_UNITS = {'phi': 'rad', 'omega': 'rad/s', 'alpha': 'rad/s^2'}


def CheckWindows(windows, endTime: Optional[float], where: str) -> List[Tuple[float, float]]:
    """Evaluation windows as a list of (t0, t1) in s with 0 <= t0 < t1 <= endTime: a window beyond the
    simulated end would be judged on the part that exists (its second half, which decides chatter, may be empty).

    Parameters
    ----------
    windows : sequence of (float, float)
        Windows in s.
    endTime : float or None
        Simulated end time in s (None: not checked against it).
    where : str
        Caller, first in the messages.

    Returns
    -------
    list of (float, float)

    Raises
    ------
    TypeError, ValueError
        For anything else.
    """
    try:
        pairs = [(float(a), float(b)) for a, b in windows]
    except (TypeError, ValueError) as err:
        raise TypeError(f"{where}: 'windows' must be a sequence of (t0, t1) pairs in s, e.g. [(2., 6.)], "
                        f"got {windows!r}") from err
    for t0, t1 in pairs:
        if not (0. <= t0 < t1):
            raise ValueError(f"{where}: a window must have 0 <= t0 < t1 (s), got {t0:g}:{t1:g}")
        if endTime is not None and t1 > endTime * (1. + 1e-9):
            raise ValueError(f"{where}: the window {t0:g}:{t1:g} s ends after the simulated end {endTime:g} s")
    return pairs


def SeriesUnit(name: str) -> str:
    """SI unit of a series of :class:`SimulationResult` (``'-'`` for dimensionless ones).

    Parameters
    ----------
    name : str
        Series name, e.g. ``'phi4'`` or ``'axialForce'``.

    Raises
    ------
    KeyError
        For a series name without a known unit (a new series must get one here).
    """
    if name in SERIES_UNITS:
        return SERIES_UNITS[name]
    for prefix, unit in _ROTOR_UNITS.items():
        rest = name[len(prefix):]
        if name.startswith(prefix) and (rest.isdigit() or (rest[:1] == 'L' and rest[1:].isdigit())):
            return unit                                  # phi4, ... (drive side), phiL1, ... (load side)
    raise KeyError(f"SeriesUnit: no unit known for the series '{name}'")
