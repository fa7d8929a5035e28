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
from ..model.contact import NormalForceFlanks

__all__ = ['SimulationResult', 'SeriesUnit', 'SERIES_UNITS', 'BEARING_LOADS', 'CheckWindows', 'CHATTER_AMPLITUDE', 'CHATTER_SUSTAIN',
           'CHATTER_MIN_MESH_TORQUE', 'CHATTER_TORQUE_FRACTION']

# The chatter rule of SimulationResult.Chatter, fixed with its reasons in validation/CHATTER_RULE.md: the mesh's
# normal force and its sliding (worm speed against the motor), each as an amplitude relative to its steady value
# in the third and last quarter of a window.
#: chatter: the relative amplitude of the mesh's normal force or sliding in the window's last quarter is at least
#: this (a self-excited vibration of a zero-backlash mesh saturates only where the flanks unload or the sliding
#: stops, at a relative amplitude of about 1; speed ramps and slow duty changes move the mesh by a few per cent)
CHATTER_AMPLITUDE = 0.25
#: ... and at least this fraction of the third quarter's (a decay resolvable within the window, sigma L >= 3,
#: loses the factor exp(-3/4) = 0.47 per quarter; a sustained or growing vibration keeps about 1 or more)
CHATTER_SUSTAIN = 0.5
#: ... and only where the mesh carries a load: below this mesh torque on the wheel (N*m) a window has no load
#: to chatter against; what moves there is round-off (about 1e-7 N*m in P1 without load, 1e-3 N*m is 1e4 times that)
CHATTER_MIN_MESH_TORQUE = 1e-3
#: wheel inertia torque J2*|phi2''| against this fraction of the largest mesh torque on the wheel: the chatter rule
#: before the mesh-based one, kept for the wheel's vibration time of a study
#: (:func:`~exudyn_worm.analysis.studypoint.VibrationSeconds`)
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
        s, t = self.series, self.time
        floor = (self.info['frictionSpeed'] / self.info['slidingRadius']
                 if 'frictionSpeed' in self.info and 'slidingRadius' in self.info else 0.)
        out = {'normal': [], 'sliding': []}
        for k in range(4):
            m = self._Window(t0 + k * (t1 - t0) / 4, t0 + (k + 1) * (t1 - t0) / 4)
            if np.count_nonzero(m) < 3:
                out['normal'].append(0.)
                out['sliding'].append(0.)
                continue
            rest, trend = _Detrended(t[m], s['normalForce'][m])
            steady = float(np.mean(np.abs(trend)))
            out['normal'].append(_HalfRange(rest) / steady if steady > 0. else 0.)
            if 'omega0' in s:
                rest, _ = _Detrended(t[m], s['omega1'][m] - s['omega0'][m])
                steady = float(np.mean(np.abs(s['omega0'][m])))
            else:
                rest, trend = _Detrended(t[m], s['omega1'][m])
                steady = float(np.mean(np.abs(trend)))
            steady = max(steady, floor)
            out['sliding'].append(_HalfRange(rest) / steady if steady > 0. else 0.)
        return out

    def Chatter(self, t0: float, t1: float) -> bool:
        """Chatter in [t0, t1]: a vibration of the mesh that keeps its amplitude over the window's second half.

        For the normal force or the sliding of the mesh (:meth:`MeshOscillation`, relative amplitudes), the
        last quarter's amplitude is at least :data:`CHATTER_AMPLITUDE` and at least :data:`CHATTER_SUSTAIN`
        times the third quarter's (a decaying transient, e.g. after a load reversal, does not count; a
        self-excited vibration does, wherever in the drive it lives: the wheel and load side show in the normal
        force, the worm and drive side in the sliding, stick-slip with worm reversal in both), and the mesh
        torque on the wheel exceeds :data:`CHATTER_MIN_MESH_TORQUE` somewhere in the window (an unloaded mesh,
        e.g. ``loadMass = 0``, does not chatter). The rule and its reasons: validation/CHATTER_RULE.md.

        Parameters
        ----------
        t0, t1 : float
            The window in s.

        Returns
        -------
        bool
        """
        return bool(self.ChatterMeasures(t0, t1))

    def ChatterMeasures(self, t0: float, t1: float) -> List[str]:
        """The measures of :meth:`MeshOscillation` by which [t0, t1] chatters (:meth:`Chatter`): ``'normal'``,
        ``'sliding'``, both or none (none also for an unloaded mesh).

        Parameters
        ----------
        t0, t1 : float
            The window in s.

        Returns
        -------
        list of str
        """
        return [name for name, a in self._LoadedOscillation(t0, t1).items()
                if a[3] >= CHATTER_AMPLITUDE and a[3] >= CHATTER_SUSTAIN * a[2]]

    def _LoadedOscillation(self, t0: float, t1: float) -> Dict[str, List[float]]:
        """:meth:`MeshOscillation` of [t0, t1], empty for an unloaded mesh (its torque on the wheel never above
        :data:`CHATTER_MIN_MESH_TORQUE`)."""
        m = self._Window(t0, t1)
        meshTorque = np.max(np.abs(self.series['wheelTorque'][m])) if m.any() else 0.
        return self.MeshOscillation(t0, t1) if meshTorque > CHATTER_MIN_MESH_TORQUE else {}

    def ChatterRatio(self, t0: float, t1: float) -> float:
        """How clearly [t0, t1] chatters or not: for each measure of :meth:`MeshOscillation`, the last quarter's
        amplitude over the larger of its two thresholds in :meth:`Chatter` (:data:`CHATTER_AMPLITUDE`, and
        :data:`CHATTER_SUSTAIN` times the third quarter's amplitude); the largest over the measures. At least 1
        where the window chatters (the mesh loaded), below 1 where it does not; 0 for an unloaded mesh. Near 1 the
        verdict is close (the step check of :mod:`exudyn_worm.analysis.stepsize` looks there).

        Parameters
        ----------
        t0, t1 : float
            The window in s.

        Returns
        -------
        float
            Dimensionless, >= 0.
        """
        return max((a[3] / max(CHATTER_AMPLITUDE, CHATTER_SUSTAIN * a[2])
                    for a in self._LoadedOscillation(t0, t1).values()), default=0.)

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
        fractionSNegative, minWormSpeed (rad/s, in the motor's direction: :meth:`MinWormSpeed`), chatter; for a run
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
                        'chatter': self.Chatter(t0, t1)})
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
