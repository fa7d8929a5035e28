"""Scans of the design check: where a drive stays stable when one design parameter alone is multiplied by 10**t.

The verdict of every scanned drive is that of :func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive`: each
operating point of the drive's duty in its own contact state, with its mu(v0) and slope (without a steady phase:
both contact states at rest, constant mu). Two ways to compute it, chosen by what the drive contains:

- **the two-mass drive** (:attr:`~exudyn_worm.drive.wholedrive.Drive.isTwoMass`): the Hurwitz conditions
  (17)-(19) of all candidate drives at once on a fine grid (:data:`SCAN_STEP` decades), boundaries refined by
  bisection to 1e-10 decades. The candidates are built from the probed scaling of J1, J2, kT, dT and dV with each
  design parameter (all are monomials of the parameters, eqs. (22)-(24)), so no formula of the model is repeated
  here. J1, J2, kT and the damping do not move the operating points (sliding speed, static normal force).
- **any other drive** (chains, axial bearing, motor on its characteristic): the linearized Exudyn model of the
  whole drive at each operating point, one drive per scan point (:meth:`~exudyn_worm.drive.wholedrive.Drive.Replace`
  and ``AnalyzeDrive``). Measured on this machine: 6 ms (drive-side chain, two operating points) to 16 ms (the
  hoist's speed table) per scan point, so the grid is coarser (:data:`WHOLE_DRIVE_STEP` decades), boundaries are
  bisected to :data:`WHOLE_DRIVE_TOLERANCE` decades, and each recommended change is confirmed at 9 points across
  its margin (a band narrower than the grid step could hide between two grid points).

The motor speed is a design parameter where the friction depends on speed and the motor runs at ``motorSpeed``:
each scanned speed is a drive with its own operating points.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np

from ..._checks import CheckRange
from ...model.stability import CONTACT_STATES, CharacteristicCoefficients, HurwitzStable, PolynomialCoefficients
from ...drive.operatingpoints import DutyOperatingPoints
from ...drive.presets import PARAMETER_UNITS
from ...drive.wholedrive import CheckDrive, Drive
from ..charts.stabilitychart import ChartCoordinates
from ..stability.drivestability import AnalyzeDrive, DriveAnalysis

__all__ = ['SCAN_STEP', 'WHOLE_DRIVE_STEP', 'WHOLE_DRIVE_TOLERANCE', 'SPEED_KEY', 'Conditions',
           'DesignParameters', 'DesignKeys', 'AxisScan', 'ScanParameter', 'ScanMotorSpeed', 'Scanner']

#: grid step of the two-mass drive's 1-D scans in decades (boundaries are then refined by bisection)
SCAN_STEP = 0.005
#: grid step of a whole drive's scans in decades (each point: a linearized Exudyn model per operating point)
WHOLE_DRIVE_STEP = 0.1
#: bisection tolerance of a whole drive's boundaries in decades
WHOLE_DRIVE_TOLERANCE = 1e-3
#: the motor speed, a design parameter when the friction depends on speed (:func:`ScanMotorSpeed`)
SPEED_KEY = 'motorSpeed'
_SPEED_STEP = 0.01          # grid step of the two-mass speed scan in decades (each point has its own operating points)
_REFINE_TOLERANCE = 1e-10   # bisection tolerance in decades (two-mass drive)
_CONFIRM_POINTS = 9         # a whole drive's recommendation is confirmed at this many points across its margin

_SHAFT_DAMPING_FORMS = ('dT', 'DT', 'DTV')      # precedence as in ElasticDriveFromParameters
_MESH_DAMPING_FORMS = ('dV', 'DV')
_QUANTITIES = ('J1', 'J2', 'kT', 'dT', 'dV')    # the two-mass drive's quantities a design parameter acts on
_AXIAL_DESIGN_KEYS = ('kA', 'dA')


def Conditions(drive: Drive) -> Tuple[Tuple[int, object], ...]:
    """The (contact state, operating point) pairs the drive's verdict takes: each operating point of the duty in
    its own contact state; without one, both contact states at rest (operating point None: constant mu).

    Parameters
    ----------
    drive : Drive
        The drive.

    Returns
    -------
    tuple of (int, OperatingPoint or None)
    """
    points = DutyOperatingPoints(drive)
    if points:
        return tuple(dict.fromkeys((p.S, p.operatingPoint) for p in points))
    return tuple((S, None) for S in CONTACT_STATES)


def DesignParameters(drive: Drive) -> List[str]:
    """The design parameters of a drive: J1, J2, kT and the damping keys in the form it holds them, then the
    drive-side chain (J4, k4, d4, ...), the load-side chain (JL1, kL1, dL1, ...) and the axial bearing (kA, dA)
    where the drive has them.

    Parameters
    ----------
    drive : Drive
        The drive.

    Returns
    -------
    list of str
        ``['J1', 'J2', 'kT', <dT|DT|DTV>, <dV|DV>, ...]`` (a key only if present).
    """
    CheckDrive('DesignParameters', drive)
    parameters = drive.parameters
    keys = ['J1', 'J2', 'kT']
    for forms in (_SHAFT_DAMPING_FORMS, _MESH_DAMPING_FORMS):
        key = next((k for k in forms if k in parameters), None)
        if key is not None:
            keys.append(key)
    for i in range(len(drive.driveSideChain)):
        keys += [k for k in (f'J{4 + i}', f'k{4 + i}', f'd{4 + i}') if k in parameters]
    for i in range(len(drive.loadSideChain)):
        keys += [k for k in (f'JL{1 + i}', f'kL{1 + i}', f'dL{1 + i}') if k in parameters]
    if drive.axialBearing is not None:
        keys += [k for k in _AXIAL_DESIGN_KEYS if k in parameters]
    return keys


def _SpeedIsDesignParameter(drive: Drive) -> bool:
    """The friction depends on speed and the motor runs at ``motorSpeed`` with a steady phase: the speed is a remedy."""
    return drive.gear.speedDependentFriction and SPEED_KEY in drive.parameters and bool(DutyOperatingPoints(drive))


def DesignKeys(drive: Drive) -> Tuple[List[str], List[str]]:
    """The keys the design check scans and the notes on those it cannot.

    Parameters
    ----------
    drive : Drive
        The drive.

    Returns
    -------
    keys : list of str
        :func:`DesignParameters` with a value > 0, then :data:`SPEED_KEY` where the speed is a design parameter.
    notes : list of str
        One per design parameter that is 0 (it cannot be changed by a factor).
    """
    keys, notes = [], []
    for key in DesignParameters(drive):
        if drive.parameters[key] > 0:
            keys.append(key)
        else:
            notes.append(f"{key} = 0 cannot be changed by a factor; give it a value > 0 to include it")
    if _SpeedIsDesignParameter(drive):
        keys.append(SPEED_KEY)
    return keys, notes


@dataclass(frozen=True)
class AxisScan:
    """Where the drive is stable when one design parameter alone is multiplied by 10**t.

    Attributes
    ----------
    parameter : str
        The parameter key.
    value : float
        Its given value.
    stableIntervals : tuple of (float, float)
        Intervals of t (decades) with a stable drive, boundaries refined by bisection; an interval that
        reaches ``limit`` may continue beyond it.
    limit : float
        The scan covered -limit <= t <= limit.
    """
    parameter: str
    value: float
    stableIntervals: Tuple[Tuple[float, float], ...]
    limit: float

    def Move(self, direction: int, margin: float, span: float) -> Optional[float]:
        """Smallest change t (decades, sign of ``direction``, ``|t| <= log10(span)``) after which every
        t' with ``|t' - t| <= margin`` is stable; 0 if the given value already is; None if there is none.

        Parameters
        ----------
        direction : int
            +1 (increase) or -1 (decrease).
        margin : float
            Margin in decades, >= 0.
        span : float
            Largest factor, > 1.
        """
        L = math.log10(span)
        moves = []
        for a, b in self.stableIntervals:
            if direction > 0:
                t = max(0., a + margin)
                if t <= L and b - t >= margin:
                    moves.append(t)
            else:
                t = min(0., b - margin)
                if t >= -L and t - a >= margin:
                    moves.append(t)
        return min(moves, key=abs) if moves else None

    def Boundaries(self) -> List[float]:
        """The refined stability boundaries (decades) inside the scanned range."""
        return sorted(t for ab in self.stableIntervals for t in ab if abs(t) < self.limit)


def _SymmetricGrid(limit, step):
    n = int(math.ceil(limit / step))
    return np.linspace(-limit, limit, 2 * n + 1)


def _Bisect(stableAt: Callable[[float], bool], tUnstable: float, tStable: float, tolerance: float) -> float:
    """Bisection between an unstable and a stable log factor; returns the stable end."""
    while abs(tStable - tUnstable) > tolerance:
        mid = 0.5 * (tUnstable + tStable)
        if stableAt(mid):
            tStable = mid
        else:
            tUnstable = mid
    return tStable


def _Intervals(key: str, value: float, t: np.ndarray, stable: Sequence[bool], stableAt, tolerance) -> AxisScan:
    """The stable intervals of a grid verdict, each inner boundary bisected."""
    intervals, start = [], None
    for i, s in enumerate(stable):
        if s and start is None:
            start = t[0] if i == 0 else _Bisect(stableAt, t[i - 1], t[i], tolerance)
        if not s and start is not None:
            intervals.append((start, _Bisect(stableAt, t[i], t[i - 1], tolerance)))
            start = None
    if start is not None:
        intervals.append((start, t[-1]))
    return AxisScan(key, float(value), tuple((float(a), float(b)) for a, b in intervals), float(t[-1]))


class _ScaledDrives:
    """Stability of many two-mass drives at once: the drive with design parameters multiplied by 10**t.

    J1, J2, kT, dT and dV are monomials of the parameters (eqs. (22)-(24)); their exponents are probed once
    per design parameter with :meth:`~exudyn_worm.drive.wholedrive.Drive.Replace` (and checked at a second
    factor), so the model's formulas stay in :mod:`presets`, :mod:`drive` and :mod:`stability`.
    """

    def __init__(self, whole: Drive, keys: Sequence[str], conditions):
        self.drive = whole.elastic
        self.conditions = conditions        # J1, J2, kT, dT, dV do not move the operating points
        self.q0 = self._Quantities(self.drive)
        self.exponents = {}
        probe = 0.05       # decades: a small factor, so a drive at the edge of the allowed ranges is not refused
        for key in keys:
            up, down = (self._Quantities(whole.Replace(**{key: whole.parameters[key] * 10. ** s}).elastic)
                        for s in (probe, -probe))
            with np.errstate(divide='ignore', invalid='ignore'):
                e = np.where(self.q0 > 0, np.log10(up / self.q0) / probe, 0.)
            if not np.allclose(down, self.q0 * 10. ** (-e * probe), rtol=1e-9, atol=0.):
                raise RuntimeError(f"design: the drive does not scale as a power of '{key}' (internal error)")
            self.exponents[key] = e

    @staticmethod
    def _Quantities(drive) -> np.ndarray:
        return np.array([drive.J1, drive.J2, drive.kT, drive.dT, drive.gear.dV])

    def Stable(self, logFactors: Mapping[str, np.ndarray]) -> np.ndarray:
        """Boolean array: stable at every condition (Hurwitz (17)-(19) with b3, b4 > 0)."""
        shape = np.broadcast(*logFactors.values()).shape
        q = [self.q0[i] * 10. ** (np.zeros(shape) + sum(self.exponents[k][i] * np.asarray(t)
                                                         for k, t in logFactors.items()))
             for i in range(len(_QUANTITIES))]
        stable = np.ones(shape, dtype=bool)
        for S, op in self.conditions:
            stable &= HurwitzStable(PolynomialCoefficients(self.drive.gear, S, *q, operatingPoint=op))
        return stable


class Scanner:
    """The stability of a drive with design parameters multiplied by 10**t, as the design check asks it.

    Parameters
    ----------
    drive : Drive
        The drive (two-mass: analytical scans; otherwise the linearized whole drive, module text).

    Attributes
    ----------
    evaluations : int
        Linear analyses of changed drives made so far (the cost of a whole drive's check).
    """

    def __init__(self, drive: Drive):
        self.drive = drive
        self.parameters = dict(drive.parameters)
        self.twoMass = drive.isTwoMass
        self.conditions = Conditions(drive)
        self.evaluations = 0

    @property
    def step(self) -> float:
        """Grid step of the 1-D scans in decades."""
        return SCAN_STEP if self.twoMass else WHOLE_DRIVE_STEP

    def Changed(self, changes: Mapping[str, float]) -> Drive:
        """The drive with ``key`` multiplied by 10**t for each item of ``changes`` (a checked, new drive).

        Parameters
        ----------
        changes : mapping
            Log factors (decades) by key.
        """
        changed = self.drive.Replace(**{k: self.parameters[k] * 10. ** t for k, t in changes.items()})
        if SPEED_KEY not in changes:   # inertias, stiffnesses and dampings do not move the operating points
            changed.Cached('dutyOperatingPoints', lambda: DutyOperatingPoints(self.drive))
        return changed

    def Analysis(self, changes: Mapping[str, float]) -> DriveAnalysis:
        """:func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive` of the changed drive.

        Parameters
        ----------
        changes : mapping
            Log factors (decades) by key.
        """
        self.evaluations += 1
        return AnalyzeDrive(self.Changed(changes))

    def StableAt(self, changes: Mapping[str, float]) -> bool:
        """The changed drive's verdict (every condition stable).

        Parameters
        ----------
        changes : mapping
            Log factors (decades) by key.
        """
        if not self.twoMass:
            return bool(self.Analysis(changes).stable)
        # Routh-Hurwitz on (16) is the verdict of AnalyzeStability(...) without the polynomial roots (10x faster)
        changed = self.Changed(changes)
        conditions = self.conditions if SPEED_KEY not in changes else Conditions(changed)
        return all(HurwitzStable(CharacteristicCoefficients(changed.elastic, S, op)) for S, op in conditions)

    def After(self, changes: Mapping[str, float]) -> Tuple[float, Dict[str, float]]:
        """(largest real part in 1/s at the deciding operating point, chart point of the two-mass core) of the
        changed drive.

        Parameters
        ----------
        changes : mapping
            Log factors (decades) by key.
        """
        analysis = self.Analysis(changes)
        return float(analysis.maxRealPart), ChartCoordinates(analysis.drive.elastic)

    def Scan(self, key: str, limit: float, step: Optional[float] = None) -> AxisScan:
        """Scan ``key`` multiplied by 10**t for ``|t| <= limit``.

        Parameters
        ----------
        key : str
            A design parameter (or :data:`SPEED_KEY`) with a value > 0.
        limit : float
            Scanned range in decades, > 0.
        step : float, optional
            Grid step in decades (default :attr:`step`; the two-mass speed scan: 0.01).
        """
        w = 'ScanParameter' if key != SPEED_KEY else 'ScanMotorSpeed'
        if key not in self.parameters:
            raise ValueError(f"{w}: 'key' must be a key of the parameter set, got {key!r}")
        CheckRange(w, key, self.parameters[key], low=0., lowOpen=True, unit=PARAMETER_UNITS.get(key, ''))
        CheckRange(w, 'limit', limit, low=0., lowOpen=True)
        if step is None:
            step = _SPEED_STEP if (self.twoMass and key == SPEED_KEY) else self.step
        CheckRange(w, 'step', step, low=0., high=limit, lowOpen=True)
        t = _SymmetricGrid(limit, step)
        if self.twoMass and key != SPEED_KEY:
            stable = _ScaledDrives(self.drive, (key,), self.conditions).Stable({key: t})
        else:
            stable = [self.StableAt({key: ti}) for ti in t]
        tolerance = _REFINE_TOLERANCE if self.twoMass else WHOLE_DRIVE_TOLERANCE
        return _Intervals(key, self.parameters[key], t, stable, lambda s: self.StableAt({key: s}), tolerance)

    def Confirmed(self, key: str, t: float, margin: float) -> bool:
        """Whether the change ``key`` x 10**t is stable at :data:`_CONFIRM_POINTS` points across its margin (the
        check of a whole drive's recommendation, whose grid is coarse; the two-mass grid needs none).

        Parameters
        ----------
        key : str
            The changed key.
        t : float
            The change in decades.
        margin : float
            Margin in decades.
        """
        if self.twoMass:
            return True
        return all(self.StableAt({key: t + d}) for d in np.linspace(-margin, margin, _CONFIRM_POINTS))


def ScanParameter(drive: Drive, key: str, limit: float,
                  step: Optional[float] = None) -> AxisScan:
    """Scan the stability of the drive with ``key`` multiplied by 10**t for ``|t| <= limit``.

    Parameters
    ----------
    drive : Drive
        The drive.
    key : str
        A design parameter present in the drive with a value > 0.
    limit : float
        Scanned range in decades, > 0.
    step : float, optional
        Grid step in decades (default :data:`SCAN_STEP` for the two-mass drive, :data:`WHOLE_DRIVE_STEP` for a
        whole drive); boundaries are refined by bisection.

    Returns
    -------
    AxisScan
    """
    return Scanner(CheckDrive('ScanParameter', drive)).Scan(key, limit, step)


def ScanMotorSpeed(drive: Drive, limit: float, step: Optional[float] = None) -> AxisScan:
    """Scan the stability of the drive with ``motorSpeed`` multiplied by 10**t for ``|t| <= limit``.

    With a speed-dependent friction law the operating points (mu(v0), its slope, the normal force) move with the
    speed, so every point is a drive with its own operating points.

    Parameters
    ----------
    drive : Drive
        The drive, with ``motorSpeed`` and a load.
    limit : float
        Scanned range in decades, > 0.
    step : float, optional
        Grid step in decades (default 0.01 for the two-mass drive, :data:`WHOLE_DRIVE_STEP` for a whole drive).

    Returns
    -------
    AxisScan
    """
    drive = CheckDrive('ScanMotorSpeed', drive)
    CheckRange('ScanMotorSpeed', SPEED_KEY, drive.parameters.get(SPEED_KEY, 0.), low=0., lowOpen=True, unit='rad/s')
    return Scanner(drive).Scan(SPEED_KEY, limit, step)
