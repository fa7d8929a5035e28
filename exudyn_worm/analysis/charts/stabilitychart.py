"""Stability charts of the elastic worm drive (paper section 2.3, Figures 4 and 5).

A chart fixes the gear and J2 and sweeps the two dimensionless ratios of the paper on a log grid:

- x = kT / (kV r1^2), the stiffness ratio (abscissa),
- y = J1 / J2, the inertia ratio (ordinate),

with the damping given by the measures D_V and D_T = D_TV D_V of eqs. (22)-(24), so that dT and dV follow
the swept J1 and kT as in the paper. Each grid point is classified with the Routh-Hurwitz conditions
(17)-(19) of the polynomial (15) (:func:`~exudyn_worm.model.stability.PolynomialCoefficients`,
:func:`~exudyn_worm.model.stability.HurwitzStable`: the same code as the single-drive analysis, evaluated on the
whole grid at once). The chart is dimensionless: scaling time by omega = (kV r1^2 / J1)^(1/2) makes the
scaled b-coefficients depend only on (x, y, D_V, D_TV) and on the gear's angles and r2/r1, so J2 only
scales :attr:`StabilityChart.maxRealPart` (in 1/s), never the verdict. A chart at a drive's operating point
(``operatingPoint``: mu(v0) and the damping of its friction slope, which depends on the normal force) is no
longer dimensionless: it belongs to that drive's J2 and load.

The largest real part of the four eigenvalues per point is computed by a vectorized closed-form quartic
solution (:func:`~exudyn_worm.analysis.charts.quartic.MaxRealPart`). Boundaries are traced by marching squares
(:func:`~exudyn_worm.analysis.charts.contours.ContourLines`, own code, no matplotlib) on a continuous margin field whose
sign is the Hurwitz verdict, interpolated linearly in log10 coordinates.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from ..._checks import CheckArray, CheckRange
from ...model.drive import ElasticDrive, MeshDampingFromMeasure, TorsionalDampingFromMeasure
from ...model.gear import WormGear
from ...model.stability import (CONTACT_STATES, FirstCriterionLimit, HurwitzConditions, HurwitzStable, OperatingPoint,
                                PolynomialCoefficients)
from ...drive.presets import PRESETS, ElasticDriveFromParameters, GetPreset
from .contours import ContourLines
from .quartic import MaxRealPart

__all__ = ['StabilityChart', 'ComputeStabilityChart', 'ChartCoordinates', 'ChartCoefficients',
           'UnstableGrid', 'MaxRealPartGrid',
           'ChartPoints', 'PresetChartPoints', 'FirstCriterionCurves', 'FirstCriterionChart', 'DEFAULT_X_RANGE', 'DEFAULT_Y_RANGE',
           'DEFAULT_RESOLUTION', 'MAX_CHART_POINTS']

#: default stiffness-ratio range kT/(kV r1^2) (validation/README.md fixes this chart domain)
DEFAULT_X_RANGE = (1e-4, 1e2)
#: default inertia-ratio range J1/J2
DEFAULT_Y_RANGE = (1e-6, 1.)
#: default number of grid points per axis
DEFAULT_RESOLUTION = 400
#: grid points of one chart (nx * ny) above which it is refused before any array is built: the coefficients, the
#: verdicts and the margin take about 120 bytes per point (measured: 2000 x 2000 peaks at 0.51 GB), so the limit
#: holds a chart below 0.5 GB
MAX_CHART_POINTS = 4_000_000
_BYTES_PER_CHART_POINT = 120

# --- evaluation at chart coordinates (broadcasting) ---------------------------------------------------------
def _CheckGear(where, gear, J2):
    if not isinstance(gear, WormGear):
        raise TypeError(f"{where}: 'gear' must be a WormGear, got {type(gear).__name__}")
    return CheckRange(where, 'J2', J2, low=0., unit='kg*m^2', lowOpen=True)


def _CheckS(where, S):
    if S not in CONTACT_STATES:
        raise ValueError(f"{where}: contact parameter 'S' must be +1 or -1, got {S!r}")


_GRID_PARAMETERS = """
    Parameters
    ----------
    gear : WormGear
        Geometry, friction and mesh stiffness; its own dV is not used.
    J2 : float
        Wheel-side inertia in kg*m^2, > 0.
    x : float or ndarray
        Stiffness ratio kT/(kV r1^2), > 0.
    y : float or ndarray
        Inertia ratio J1/J2, > 0.
    DV : float or ndarray
        Mesh damping measure D_V, >= 0 (eq. (23)).
    DTV : float or ndarray
        Damping ratio D_TV = D_T/D_V, >= 0 (eq. (24)).
    S : int, optional
        Contact parameter, -1 (default, load lowering) or +1.
    operatingPoint : OperatingPoint, optional
        Linearize at this point: mu(v0) and the damping of its friction slope
        (:func:`~exudyn_worm.model.stability.PolynomialCoefficients`); None (default): the gear's constant mu.
"""


def _GridDoc(summary: str, returns: str):
    """Decorator: a docstring made of ``summary``, the shared chart-coordinate parameters and ``returns``."""
    def Decorate(function):
        function.__doc__ = f"{summary}\n{_GRID_PARAMETERS}\n    Returns\n    -------\n{returns}"
        return function
    return Decorate


@_GridDoc("""b1..b4 of eq. (16) at chart coordinates; broadcasts over numpy arrays.

    J1 = y J2, kT = x kV r1^2, dV from D_V by eq. (23), dT from D_T = D_TV D_V by eq. (22).""",
          """    ndarray
        Shape ``(4,) + broadcast shape`` of the arguments, in s^-1 .. s^-4.
""")
def ChartCoefficients(gear: WormGear, J2: float, x, y, DV, DTV, S: int = -1,
                      operatingPoint: Optional[OperatingPoint] = None) -> np.ndarray:
    w = 'ChartCoefficients'
    J2 = _CheckGear(w, gear, J2)
    _CheckS(w, S)
    x = CheckArray(w, 'x', x)
    y = CheckArray(w, 'y', y)
    DV = CheckArray(w, 'DV', DV, lowOpen=False)
    DTV = CheckArray(w, 'DTV', DTV, lowOpen=False)
    J1 = y * J2
    kT = x * gear.kV * gear.r1**2
    dT = TorsionalDampingFromMeasure(DTV * DV, kT, J1)                  # eq. (22)
    dV = MeshDampingFromMeasure(DV, gear.kV, gear.r2, J2)               # eq. (23)
    return PolynomialCoefficients(gear, S, J1, J2, kT, dT, dV, operatingPoint=operatingPoint)


@_GridDoc("Hurwitz verdict (17)-(19) at chart coordinates: True where unstable; broadcasts over arrays.",
          """    ndarray of bool
        Broadcast shape of the arguments.
""")
def UnstableGrid(gear: WormGear, J2: float, x, y, DV, DTV, S: int = -1,
                 operatingPoint: Optional[OperatingPoint] = None) -> np.ndarray:
    return ~np.asarray(HurwitzStable(ChartCoefficients(gear, J2, x, y, DV, DTV, S, operatingPoint)), dtype=bool)


@_GridDoc("""Largest real part of the four eigenvalues in 1/s at chart coordinates; broadcasts over arrays.

    Positive: unstable (growth rate of the chatter), negative: stable (decay rate of the slowest mode).
    See :func:`MaxRealPart` for the method.""",
          """    ndarray
        Broadcast shape of the arguments.
""")
def MaxRealPartGrid(gear: WormGear, J2: float, x, y, DV, DTV, S: int = -1,
                    operatingPoint: Optional[OperatingPoint] = None) -> np.ndarray:
    return MaxRealPart(ChartCoefficients(gear, J2, x, y, DV, DTV, S, operatingPoint))


def ChartCoordinates(drive: ElasticDrive) -> Dict[str, float]:
    """Where a drive lies on its stability chart.

    Parameters
    ----------
    drive : ElasticDrive
        The 2-DOF drive.

    Returns
    -------
    dict
        ``{'x': kT/(kV r1^2), 'y': J1/J2, 'DV': D_V, 'DTV': D_TV}`` (eqs. (22)-(24); D_TV is inf if
        D_V = 0). ``ComputeStabilityChart(drive.gear, drive.J2, DV, DTV)`` is the chart the drive lies on.
    """
    if not isinstance(drive, ElasticDrive):
        raise TypeError(f"ChartCoordinates: 'drive' must be an ElasticDrive, got {type(drive).__name__}")
    return {'x': float(drive.stiffnessRatio), 'y': float(drive.inertiaRatio), 'DV': float(drive.DV),
            'DTV': float(drive.DTV)}


def ChartPoints(points: Union[Mapping, Sequence[str], None], where: str = 'ChartPoints') -> Dict[str, Tuple[float, float]]:
    """Points to mark on a chart as ``{label: (x, y)}`` chart coordinates, for the plotting functions of
    :mod:`exudyn_worm.plotting.plot_charts` (which only draw).

    Parameters
    ----------
    points : mapping or list of str or None
        ``{label: point}`` with a point as (x, y), as a dict with 'x' and 'y' (e.g. from
        :func:`ChartCoordinates`) or as an ElasticDrive; or a list of preset names (``['reel-P1', 'P7']``;
        ``'P1'`` stands for ``'reel-P1'``), at their chart coordinates (:func:`PresetChartPoints`).
    where : str, optional
        Name of the caller in error messages.

    Returns
    -------
    dict
        ``{label: (x, y)}`` (empty for None).

    Raises
    ------
    TypeError, ValueError
        For ``points`` of another form or with an unknown preset name.
    """
    if points is None:
        return {}
    if not isinstance(points, Mapping):
        if isinstance(points, str) or not isinstance(points, (list, tuple)) or \
                not all(isinstance(p, str) for p in points):
            raise TypeError(f"{where}: 'points' must be a mapping {{label: (x, y), a dict with 'x' and 'y', or an "
                            f"ElasticDrive}} or a list of preset names (e.g. ['reel-P1', 'reel-P7']), got "
                            f"{type(points).__name__} {points!r}")
        names = []
        for p in points:
            name = p if p in PRESETS else f'reel-{p}' if f'reel-{p}' in PRESETS else None
            if name is None:
                raise ValueError(f"{where}: 'points': unknown preset {p!r}; expected preset names: "
                                 f"{', '.join(PRESETS)} (or P1 ... P7 for reel-P1 ... reel-P7)")
            names.append(name)
        points = PresetChartPoints(names)
    out = {}
    for label, value in points.items():
        if isinstance(value, ElasticDrive):
            value = ChartCoordinates(value)
        if isinstance(value, Mapping):
            out[label] = (float(value['x']), float(value['y']))
        else:
            x, y = value
            out[label] = (float(x), float(y))
    return out


def PresetChartPoints(names: Sequence[str]) -> Dict[str, Dict[str, float]]:
    """Chart coordinates of presets, e.g. the paper's points P1-P7 (presets 'reel-P1' ... 'reel-P7').

    Parameters
    ----------
    names : sequence of str
        Preset names (see :data:`~exudyn_worm.drive.presets.PRESETS`); each needs a complete drive (J1, kT and
        the damping). A 'reel-' prefix is dropped from the label.

    Returns
    -------
    dict
        ``{label: {'x', 'y', 'DV', 'DTV'}}`` in the order given.
    """
    return {name.replace('reel-', ''): ChartCoordinates(ElasticDriveFromParameters(GetPreset(name))) for name in names}


def _Margin(b) -> np.ndarray:
    """Continuous stability margin: min of b1 and of (19), each made dimensionless with omega = b4^(1/4).

    Positive exactly where :func:`HurwitzStable` holds (b3, b4 > 0 on a chart; (18) follows from (19)).
    """
    omega = np.sqrt(np.sqrt(np.abs(b[3])))
    omega = np.where(omega > 0, omega, 1.)
    o2 = omega * omega
    h = HurwitzConditions(b)
    return np.minimum(h[0] / omega, h[2] / (o2 * o2 * o2))


# --- the chart ------------------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class StabilityChart:
    """A stability chart: the Hurwitz verdict on a log grid of x = kT/(kV r1^2) and y = J1/J2.

    Built by :func:`ComputeStabilityChart`. ``unstable[i, j]`` belongs to ``(x[j], y[i])``.

    Parameters
    ----------
    gear : WormGear
        The gear (its dV is replaced by the one of ``DV``).
    J2 : float
        Wheel-side inertia in kg*m^2.
    DV : float
        Mesh damping measure D_V.
    DTV : float
        Damping ratio D_TV = D_T/D_V.
    S : int
        Contact parameter of the chart.
    x : ndarray
        Stiffness ratios (log grid), shape (nx,).
    y : ndarray
        Inertia ratios (log grid), shape (ny,).
    unstable : ndarray of bool
        Shape (ny, nx).
    margin : ndarray
        Shape (ny, nx): a continuous field, > 0 exactly where stable (b1 and (19) made dimensionless,
        their minimum); the boundaries are its zero level set.
    operatingPoint : OperatingPoint or None
        The chart is linearized at this point (mu(v0) and its slope; then J2 and the normal force matter);
        None: the gear's constant mu (the paper's charts).
    """
    gear: WormGear
    J2: float
    DV: float
    DTV: float
    S: int
    x: np.ndarray
    y: np.ndarray
    unstable: np.ndarray
    margin: np.ndarray
    operatingPoint: Optional[OperatingPoint] = None
    _cache: dict = field(default_factory=dict, repr=False)

    def Coefficients(self) -> np.ndarray:
        """b1..b4 of eq. (16) on the grid, shape (4, ny, nx)."""
        return ChartCoefficients(self.gear, self.J2, self.x[None, :], self.y[:, None], self.DV, self.DTV, self.S,
                                 self.operatingPoint)

    @property
    def maxRealPart(self) -> np.ndarray:
        """Largest real part of the eigenvalues in 1/s on the grid, shape (ny, nx) (computed on first use)."""
        if 'maxRealPart' not in self._cache:
            self._cache['maxRealPart'] = MaxRealPart(self.Coefficients())
        return self._cache['maxRealPart']

    @property
    def boundaries(self) -> List[np.ndarray]:
        """Boundary curves between stable and unstable points: list of (N, 2) arrays of (x, y).

        Marching squares on :attr:`margin` in log10 coordinates; curves end where they leave the domain.
        """
        if 'boundaries' not in self._cache:
            lines = ContourLines(np.log10(self.x), np.log10(self.y), self.margin, self.unstable)
            self._cache['boundaries'] = [10.**line for line in lines]
        return self._cache['boundaries']

    def _MarginAt(self, x, y) -> np.ndarray:
        """The margin field (see :attr:`margin`) at arbitrary chart coordinates (broadcasting)."""
        return _Margin(ChartCoefficients(self.gear, self.J2, x, y, self.DV, self.DTV, self.S, self.operatingPoint))

    def _RidgeMin(self, axis: int, values: np.ndarray, coarse: Optional[np.ndarray] = None) -> np.ndarray:
        """For each value of coordinate ``axis`` (0: x, 1: y): the minimum of the margin over the other
        coordinate. Coarse minimum on the chart's grid (``coarse``: the margin there, shape (n, m), else
        computed), then three passes of 41 points within +-1 step of the current minimum."""
        other = self.y if axis == 0 else self.x
        At = (lambda v, o: self._MarginAt(v, o)) if axis == 0 else (lambda v, o: self._MarginAt(o, v))
        v = np.asarray(values, dtype=float)[:, None]
        if coarse is None:
            coarse = At(v, other[None, :])
        j = np.argmin(coarse, axis=1)
        lo = np.log10(other[np.maximum(j - 1, 0)])
        hi = np.log10(other[np.minimum(j + 1, other.size - 1)])
        best = coarse[np.arange(v.shape[0]), j]
        t = np.linspace(0., 1., 41)[None, :]
        for _ in range(3):
            o = 10.**(lo[:, None] + (hi - lo)[:, None] * t)
            m = At(v, o)
            k = np.argmin(m, axis=1)
            best = np.minimum(best, m[np.arange(v.shape[0]), k])
            step = (hi - lo) / 40.
            centre = lo + k * step
            lo, hi = centre - step, centre + step
        return best

    def _End(self, axis: int, side: int) -> float:
        """One end of the unstable set along ``axis`` (0: x, 1: y), ``side`` -1 (min) or +1 (max).

        The unstable set can end in a thin tip (a needle thinner than a grid step), so the end is found on
        the ridge: for each grid value of this coordinate the margin is minimized over the other coordinate
        (coarse grid, then three refinements), the extreme value with a negative minimum is taken and the end
        is bisected (40 steps, in log) between it and the next grid value. At a side of the domain that the
        unstable set touches, the domain's end.
        """
        grid = self.x if axis == 0 else self.y
        coarse = self.margin.T if axis == 0 else self.margin                 # (len(grid), len(other))
        ridge = self._RidgeMin(axis, grid, coarse)
        inside = (ridge <= 0) | (self.unstable.any(axis=0) if axis == 0 else self.unstable.any(axis=1))
        idx = np.nonzero(inside)[0]
        k = int(idx[-1] if side > 0 else idx[0])
        if (side > 0 and k == grid.size - 1) or (side < 0 and k == 0):
            return float(grid[k])
        a, b = math.log10(grid[k]), math.log10(grid[k + side])               # a unstable, b stable
        for _ in range(40):
            mid = 0.5 * (a + b)
            if self._RidgeMin(axis, np.array([10.**mid]))[0] <= 0:
                a = mid
            else:
                b = mid
        return float(10.**a)

    def _Range(self, axis: int) -> Optional[Tuple[float, float]]:
        if not self.unstable.any():
            return None
        key = f'range{axis}'
        if key not in self._cache:
            self._cache[key] = (self._End(axis, -1), self._End(axis, +1))
        return self._cache[key]

    @property
    def unstableXRange(self) -> Optional[Tuple[float, float]]:
        """(min, max) stiffness ratio of the unstable set, None if there is none.

        Each end follows the ridge of the unstable set beyond the grid and is bisected with the exact margin
        (see ``_End``), so a thin tip is not cut at the last grid column; where the unstable set touches the
        domain's edge the end is the domain's (:attr:`clippedSides` says where).
        """
        return self._Range(0)

    @property
    def unstableYRange(self) -> Optional[Tuple[float, float]]:
        """(min, max) inertia ratio of the unstable set, None if there is none (as :attr:`unstableXRange`)."""
        return self._Range(1)

    @property
    def unstableFraction(self) -> float:
        """Fraction of grid points that are unstable (= fraction of the log-log chart area)."""
        return float(self.unstable.mean())

    @property
    def unstableArea(self) -> float:
        """Unstable area in log10-log10 coordinates (decades^2): the fraction times the domain's area."""
        return self.unstableFraction * float(np.log10(self.x[-1] / self.x[0]) * np.log10(self.y[-1] / self.y[0]))

    @property
    def clippedSides(self) -> List[str]:
        """Sides of the domain ('left', 'right', 'bottom', 'top') that unstable points touch: there the
        unstable region continues beyond the chart and the ranges are clipped."""
        u = self.unstable
        return [side for side, edge in (('left', u[:, 0]), ('right', u[:, -1]), ('bottom', u[0, :]),
                                        ('top', u[-1, :])) if edge.any()]

    def UnstableYExtent(self) -> np.ndarray:
        """Per grid column x[j]: the log10 extent (decades) of the unstable y values, 0 where none.

        Extent = log10(max y / min y) over the unstable points of the column plus one grid step in
        log10 y, so a single unstable point counts one grid step.
        """
        logy = np.log10(self.y)
        step = float(np.mean(np.diff(logy))) if logy.size > 1 else 0.
        any_ = self.unstable.any(axis=0)
        masked = np.where(self.unstable, logy[:, None], np.nan)
        with np.errstate(all='ignore'):
            lo = np.nanmin(np.where(any_[None, :], masked, 0.), axis=0)
            hi = np.nanmax(np.where(any_[None, :], masked, 0.), axis=0)
        return np.where(any_, hi - lo + step, 0.)

    def IsUnstable(self, x, y) -> np.ndarray:
        """Hurwitz verdict at arbitrary (x, y) of this chart (exact, not read off the grid).

        Parameters
        ----------
        x, y : float or ndarray
            Stiffness and inertia ratios, > 0.
        """
        return UnstableGrid(self.gear, self.J2, x, y, self.DV, self.DTV, self.S, self.operatingPoint)

    def NearestBoundary(self, point: Tuple[float, float]) -> float:
        """Distance in decades (Euclidean in log10 x, log10 y) from a point to the nearest boundary vertex of
        this chart; inf for a chart without boundary.

        Parameters
        ----------
        point : (float, float)
            Stiffness and inertia ratios (x, y), > 0.

        Returns
        -------
        float
        """
        x, y = point
        return min((float(np.min(np.hypot(np.log10(line[:, 0] / x), np.log10(line[:, 1] / y))))
                    for line in self.boundaries), default=math.inf)

    def ToDict(self, boundaries: bool = False) -> Dict:
        """JSON-ready summary (the entries of ``exudyn-worm chart --json``).

        Parameters
        ----------
        boundaries : bool, optional
            Also include the boundary curves as lists of [x, y] pairs.
        """
        r = lambda t: None if t is None else [t[0], t[1]]
        d = {'DV': float(self.DV), 'DTV': float(self.DTV), 'S': int(self.S),
             'unstableXRange': r(self.unstableXRange), 'unstableYRange': r(self.unstableYRange),
             'unstableFraction': self.unstableFraction, 'unstableArea': self.unstableArea,
             'clippedSides': self.clippedSides,
             'xRange': [float(self.x[0]), float(self.x[-1])], 'yRange': [float(self.y[0]), float(self.y[-1])],
             'resolution': [int(self.x.size), int(self.y.size)], 'J2': float(self.J2)}
        if boundaries:
            d['boundaries'] = [line.tolist() for line in self.boundaries]
        return d

    def plot(self, ax=None, points=None, **kwargs):
        """Draw the chart with :func:`exudyn_worm.plotting.plot_charts.PlotStabilityChart` (imports matplotlib).

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw into (default: a new figure).
        points : mapping or list of str, optional
            ``{label: (x, y)}`` or ``{label: ElasticDrive}`` points to mark, or a list of preset names
            (``['reel-P1', 'P7']``) marked at their chart coordinates (resolved by :func:`ChartPoints`).
        **kwargs
            Passed on to :func:`~exudyn_worm.plotting.plot_charts.PlotStabilityChart`.

        Returns
        -------
        matplotlib.axes.Axes
        """
        from ...plotting.plot_charts import PlotStabilityChart   # lazy: matplotlib only when drawing
        return PlotStabilityChart(self, ax=ax, points=ChartPoints(points, 'PlotStabilityChart'), **kwargs)


def _Resolution(where, resolution) -> Tuple[int, int]:
    values = resolution if isinstance(resolution, (tuple, list)) else (resolution, resolution)
    if len(values) != 2:
        raise ValueError(f"{where}: 'resolution' must be an int or a pair (nx, ny), got {resolution!r}")
    out = []
    for n in values:
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)):
            raise TypeError(f"{where}: 'resolution' must be an integer number of grid points in [2, 20000], "
                            f"got {n!r}")
        if not 2 <= n <= 20000:
            raise ValueError(f"{where}: 'resolution' must be in [2, 20000] grid points per axis, got {n}")
        out.append(int(n))
    if out[0] * out[1] > MAX_CHART_POINTS:     # refused before any array: about 120 bytes per grid point
        raise ValueError(f"{where}: 'resolution' {out[0]} x {out[1]} = {out[0] * out[1]:,} grid points is above the "
                         f"limit of {MAX_CHART_POINTS:,} (about {_BYTES_PER_CHART_POINT} bytes of memory each: "
                         f"{out[0] * out[1] * _BYTES_PER_CHART_POINT / 1e9:.3g} GB); give a coarser resolution, or "
                         f"split 'xRange' / 'yRange' into several charts")
    return out[0], out[1]


def _LogRange(where, name, rng) -> Tuple[float, float]:
    try:
        lo, hi = rng
    except (TypeError, ValueError):
        raise TypeError(f"{where}: '{name}' must be a pair (min, max), got {rng!r}") from None
    lo = CheckRange(where, f'{name}[0]', lo, low=0., lowOpen=True)
    hi = CheckRange(where, f'{name}[1]', hi, low=0., lowOpen=True)
    if not hi > lo:
        raise ValueError(f"{where}: '{name}' must have min < max, got ({lo:g}, {hi:g})")
    return lo, hi


def ComputeStabilityChart(gear: WormGear, J2: float, DV: float, DTV: float,
                          xRange: Sequence[float] = DEFAULT_X_RANGE, yRange: Sequence[float] = DEFAULT_Y_RANGE,
                          resolution=DEFAULT_RESOLUTION, S: int = -1,
                          operatingPoint: Optional[OperatingPoint] = None) -> StabilityChart:
    """Stability chart of Figures 4 and 5: the Hurwitz verdict on a log grid of the two ratios.

    Parameters
    ----------
    gear : WormGear
        Geometry, friction and mesh stiffness (e.g. the gear of preset 'chart', set (25)); its dV is not
        used: the mesh damping follows from ``DV`` by eq. (23).
    J2 : float
        Wheel-side inertia in kg*m^2, > 0 (it scales time only: the verdict does not depend on it).
    DV : float
        Mesh damping measure D_V, >= 0, eq. (23).
    DTV : float
        Damping ratio D_TV = D_T/D_V, >= 0, eq. (24); dT = 2 D_TV D_V sqrt(kT J1), eq. (22).
    xRange : (float, float), optional
        Stiffness-ratio range kT/(kV r1^2), 0 < min < max.
    yRange : (float, float), optional
        Inertia-ratio range J1/J2, 0 < min < max.
    resolution : int or (int, int), optional
        Grid points per axis, or (nx, ny); each in [2, 20000].
    S : int, optional
        Contact parameter: -1 (default; self-locking lowering, the paper's charts) or +1.
    operatingPoint : OperatingPoint, optional
        Linearize at this point (mu(v0), the damping of its friction slope; its contact state should be ``S``),
        e.g. a drive's operating point of its duty; then J2 and the normal force enter the verdict. None
        (default): the gear's constant mu.

    Returns
    -------
    StabilityChart

    Raises
    ------
    ValueError, TypeError
        For out-of-range or wrongly typed arguments.

    Examples
    --------
    >>> from exudyn_worm.drive.presets import DriveFromParameters, GetPreset
    >>> p = GetPreset('chart'); p.update(J1=1e-4, kT=1., DTV=1.)
    >>> gear = DriveFromParameters(p).gear
    >>> chart = ComputeStabilityChart(gear, 0.1, DV=0.014, DTV=1., resolution=50)
    >>> chart.unstable.shape
    (50, 50)
    """
    w = 'ComputeStabilityChart'
    J2 = _CheckGear(w, gear, J2)
    DV = CheckRange(w, 'DV', DV, low=0.)
    DTV = CheckRange(w, 'DTV', DTV, low=0.)
    _CheckS(w, S)
    x0, x1 = _LogRange(w, 'xRange', xRange)
    y0, y1 = _LogRange(w, 'yRange', yRange)
    nx, ny = _Resolution(w, resolution)
    x = np.geomspace(x0, x1, nx)
    y = np.geomspace(y0, y1, ny)
    if operatingPoint is not None and not isinstance(operatingPoint, OperatingPoint):
        raise TypeError(f"{w}: 'operatingPoint' must be an OperatingPoint or None, got {type(operatingPoint).__name__}")
    b = ChartCoefficients(gear, J2, x[None, :], y[:, None], DV, DTV, S, operatingPoint)
    unstable = ~HurwitzStable(b)
    return StabilityChart(gear=gear, J2=J2, DV=DV, DTV=DTV, S=S, x=x, y=y, unstable=unstable, margin=_Margin(b),
                          operatingPoint=operatingPoint)


# --- Figure 3: the first criterion (20) with dT = 0 -----------------------------------------------------------
@dataclass(frozen=True)
class FirstCriterionCurves:
    """Limits of J1/J2 of the first instability condition (20) with dT = 0 (Figure 3).

    Below a curve (J1/J2 smaller than the limit) the drive is unstable; where the limit is <= 0 (gamma >= rho,
    not self-locking) there is no instability of this kind.

    Parameters
    ----------
    gamma : ndarray
        Pitch angles in rad, shape (n,).
    rho : ndarray
        Friction angles in rad, shape (m,).
    ratio : float
        Transmission ratio u, held fixed (r2 = u r1 tan(gamma)).
    limit : ndarray
        J1/J2 limit, shape (m, n); NaN where not self-locking.
    """
    gamma: np.ndarray
    rho: np.ndarray
    ratio: float
    limit: np.ndarray

    def ToDict(self) -> Dict:
        """JSON-ready dictionary (angles in degrees, NaN as None)."""
        return {'ratio': self.ratio, 'gammaDeg': np.degrees(self.gamma).tolist(),
                'rhoDeg': np.degrees(self.rho).tolist(),
                'limit': [[None if not np.isfinite(v) else float(v) for v in row] for row in self.limit]}

    def plot(self, ax=None, **kwargs):
        """Draw with :func:`exudyn_worm.plotting.plot_charts.PlotFirstCriterion` (imports matplotlib).

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw into (default: a new figure).
        **kwargs
            Passed on to :func:`~exudyn_worm.plotting.plot_charts.PlotFirstCriterion`.
        """
        from ...plotting.plot_charts import PlotFirstCriterion
        return PlotFirstCriterion(self, ax=ax, **kwargs)


def FirstCriterionChart(gear: WormGear, gamma: Sequence[float], rho: Sequence[float]) -> FirstCriterionCurves:
    """J1/J2 limit of the first instability condition (20) with dT = 0 over pitch and friction angles.

    With dT = 0, (20) is Fuesgen's condition (21), tan(rho - gamma) / (u^2 tan(gamma)); it is evaluated by
    :func:`~exudyn_worm.model.stability.FirstCriterionLimit` on gears that keep ``gear``'s transmission ratio u,
    pressure angle and r1 (r2 = u r1 tan(gamma)) with the given gamma and rho.

    Parameters
    ----------
    gear : WormGear
        Template gear (e.g. set (25)): its ratio u, alphaN, r1 and kV are kept.
    gamma : sequence of float
        Pitch angles in rad, each in (0, pi/2).
    rho : sequence of float
        Friction angles in rad, each in [0, pi/2).

    Returns
    -------
    FirstCriterionCurves
    """
    w = 'FirstCriterionChart'
    if not isinstance(gear, WormGear):
        raise TypeError(f"{w}: 'gear' must be a WormGear, got {type(gear).__name__}")
    gamma = np.atleast_1d(np.asarray(gamma, dtype=float))
    rho = np.atleast_1d(np.asarray(rho, dtype=float))
    u = gear.ratio
    limit = np.full((rho.size, gamma.size), np.nan)
    for i, r in enumerate(rho):
        for j, g in enumerate(gamma):
            if g >= r:
                continue
            # Figure 3 varies a constant rho: the gear's own friction law (if any) does not apply
            mesh = gear.Replace(gamma=g, rho=r, r2=u * gear.r1 * math.tan(g), dV=1., friction=None)
            limit[i, j] = FirstCriterionLimit(ElasticDrive(mesh, J1=1., J2=1., kT=1., dT=0.))
    return FirstCriterionCurves(gamma=gamma, rho=rho, ratio=u, limit=limit)
