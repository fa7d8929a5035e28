"""Simulation results of a worm drive: time series, mesh quantities, window metrics, saving.

Mesh quantities are post-processed from the stored node states with the same contact law the
connector uses (:func:`exudyn_worm.model.contact.MeshContact` on numpy arrays).
"""
from __future__ import annotations

import csv
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np
from ..model.contact import NormalForceFlanks

__all__ = ['SimulationResult', 'SeriesUnit', 'SERIES_UNITS', 'CheckWindows', 'CHATTER_TORQUE_FRACTION', 'CHATTER_MIN_MESH_TORQUE']

#: chatter criterion: wheel inertia torque J2*|phi2''| in the second half of a window above this
#: fraction of the largest mesh torque on the wheel in the window
CHATTER_TORQUE_FRACTION = 0.1
#: ... and only where the mesh carries a load: below this mesh torque on the wheel (N*m) a window has no load
#: to chatter against; what moves there is round-off (about 1e-7 N*m in P1 without load, 1e-3 N*m is 1e4 times that)
CHATTER_MIN_MESH_TORQUE = 1e-3


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
        Wheel-side inertia in kg*m^2 (chatter criterion: wheel inertia torque).
    r2 : float
        Wheel radius in m.
    solveSeconds : float
        Wall-clock time of the solve in s.
    steps : int
        Number of time steps.
    info : dict
        Metadata of the run (step size, maximum load torque, ...).
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
        """Frequency in Hz of the largest spectral peak of ``signal`` in [t0, t1] (mean removed, Hann window)."""
        m = self._Window(t0, t1)
        x = self.series[signal][m]
        if x.size < 8:
            return 0.
        dt = float(np.mean(np.diff(self.time[m])))
        x = (x - x.mean()) * np.hanning(x.size)
        spectrum = np.abs(np.fft.rfft(x, n=4 * x.size))
        freq = np.fft.rfftfreq(4 * x.size, dt)
        return float(freq[1:][np.argmax(spectrum[1:])])

    def Chatter(self, t0: float, t1: float) -> bool:
        """Chatter in [t0, t1]: in the window's second half the wheel inertia torque J2*max|phi2''| exceeds
        :data:`CHATTER_TORQUE_FRACTION` of the largest mesh torque on the wheel in the window (a decaying
        transient after a load reversal does not count; a self-excited vibration does), and that mesh torque
        exceeds :data:`CHATTER_MIN_MESH_TORQUE` (an unloaded mesh, e.g. ``loadMass = 0``, does not chatter)."""
        m = self._Window(t0, t1)
        late = self._Window(0.5 * (t0 + t1), t1)
        meshTorque = np.max(np.abs(self.series['wheelTorque'][m])) if m.any() else 0.
        inertiaTorque = self.J2 * np.max(np.abs(self.series['alpha2'][late])) if late.any() else 0.
        return bool(meshTorque > CHATTER_MIN_MESH_TORQUE and inertiaTorque > CHATTER_TORQUE_FRACTION * meshTorque)

    def WindowMetrics(self, windows: Sequence[Tuple[float, float]]) -> List[Dict]:
        """Per window: t0, t1, maxAbsWheelAcceleration (rad/s^2), maxNormalForce (N), dominantFrequencyHz,
        fractionSNegative, minWormSpeed (rad/s), chatter."""
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
                        'minWormSpeed': float(np.min(self.series['omega1'][m])),
                        'chatter': self.Chatter(t0, t1)})
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

    def Plot(self, *args, **kwargs):
        """Deprecated spelling of :meth:`plot` (warns; removed in the next release).

        Parameters
        ----------
        *args, **kwargs
            As for :meth:`plot`.

        Returns
        -------
        matplotlib.figure.Figure
        """
        warnings.warn("SimulationResult.Plot is deprecated; use SimulationResult.plot", DeprecationWarning,
                      stacklevel=2)
        return self.plot(*args, **kwargs)


#: SI units of the mesh and bearing series of a :class:`SimulationResult` (rotor series: :func:`SeriesUnit`)
SERIES_UNITS = {'deltaPhi': 'rad', 'deltaS': 'm', 'normalForce': 'N', 'S': '-', 'sf': '-', 'wormTorque': 'N*m',
                'wheelTorque': 'N*m', 'driveTorque': 'N*m', 'tangentialForce': 'N',
                'xA': 'm', 'vA': 'm/s', 'aA': 'm/s^2', 'axialForce': 'N'}
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
