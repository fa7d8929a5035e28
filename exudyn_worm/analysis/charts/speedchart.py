"""Stability over motor speed: the speed range in which a drive chatters, at the load of its own duty.

With a constant mu the linear model does not depend on speed or load. With a friction law mu(v)
(:mod:`exudyn_worm.model.friction`) it does: the drive is linearized at steady motion at each motor speed, with the
load torque of its own duty. The curves come from the drive's operating points
(:func:`~exudyn_worm.drive.operatingpoints.DutyOperatingPoints`): one curve per direction of power flow and load
torque of the duty (lifting, S = +1; lowering, S = -1), each evaluated at every speed of the chart with the
static normal force, mu(v0) and dmu/dv of that speed (:func:`~exudyn_worm.model.stability.OperatingPointAt`). The
model is the one :func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive` takes for the drive: eq. (16) extended
by the friction slope for the two-mass drive, the linearized Exudyn model of the whole drive otherwise (chains,
axial bearing, a motor on its characteristic, which the chart holds at each speed). At the drive's own speed a
curve is the verdict of ``exudyn-worm stability`` at that operating point.

:func:`SpeedStabilityChart` returns a :class:`SpeedChart` (the curves, mu and its slope, the unstable speed ranges,
and the drive's verdict at its own operating points); its ``plot()`` draws it
(:func:`exudyn_worm.plotting.plot_charts.PlotSpeedChart`). ``exudyn-worm chart --speed SPEC`` prints or draws it.

No matplotlib here.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np
from ..._checks import CheckPositive
from ...model.stability import OperatingPointAt
from ...params.parameters import MissingParameterError
from ...drive.operatingpoints import PHASE_NAMES, DutyOperatingPoints, DutyPoint
from ...drive.wholedrive import CheckDrive, Drive
from ..stability.drivestability import ANALYTICAL, LINEARIZED, AnalyzeDrive, StateGrowth

__all__ = ['RPM', 'SpeedCurve', 'SpeedChart', 'SpeedStabilityChart']

#: one revolution per minute in rad/s
RPM = 2 * math.pi / 60


def _UnstableRanges(speeds: np.ndarray, maxRealPart: np.ndarray) -> List[Tuple[float, float]]:
    """(first unstable, last unstable) speed of each run of consecutive unstable speeds."""
    ranges, start, bad = [], None, maxRealPart > 0
    for i, b in enumerate(bad):
        if b and start is None:
            start = i
        if start is not None and (not b or i == len(bad) - 1):
            end = i if b else i - 1
            ranges.append((float(speeds[start]), float(speeds[end])))
            start = None
    return ranges


def _Boundaries(speeds: np.ndarray, maxRealPart: np.ndarray) -> List[float]:
    """Speeds where the largest real part changes sign (linear interpolation in log speed)."""
    out = []
    s, r = np.log(speeds), maxRealPart
    for i in range(len(r) - 1):
        if (r[i] > 0) != (r[i + 1] > 0):
            t = r[i] / (r[i] - r[i + 1])
            out.append(float(math.exp(s[i] + t * (s[i + 1] - s[i]))))
    return out


def _RangesDict(speeds: np.ndarray, maxRealPart: np.ndarray) -> Dict:
    ranges, bounds = _UnstableRanges(speeds, maxRealPart), _Boundaries(speeds, maxRealPart)
    return {'maxRealPart': maxRealPart.tolist(), 'unstable': (maxRealPart > 0).tolist(),
            'unstableRanges': [list(r) for r in ranges], 'unstableRangesRpm': [[a / RPM, b / RPM] for a, b in ranges],
            'boundaries': bounds, 'boundariesRpm': [b / RPM for b in bounds]}


@dataclass(frozen=True)
class SpeedCurve:
    """One direction of power flow of the duty over motor speed.

    Attributes
    ----------
    phase : str
        ``'lifting'`` (S = +1, the load opposes the motion) or ``'lowering'`` (S = -1, the load drives).
    S : int
        Contact state, +1 or -1.
    loadTorque : float
        Magnitude of the load torque in N*m (that of the duty's operating points in this direction).
    motorSpeeds : ndarray
        Motor speeds in rad/s (those of the chart).
    maxRealPart : ndarray
        Largest real part in 1/s of the eigenvalues of contact state S at each speed (> 0: chatter).
    frequencyHz : ndarray
        Frequency in Hz of that eigenvalue.
    normalForce : ndarray
        Static normal force Fn0 in N (it changes with mu(v0) through c4).
    """
    phase: str
    S: int
    loadTorque: float
    motorSpeeds: np.ndarray
    maxRealPart: np.ndarray
    frequencyHz: np.ndarray
    normalForce: np.ndarray

    @property
    def unstable(self) -> np.ndarray:
        """Boolean per speed: this direction is unstable."""
        return self.maxRealPart > 0

    @property
    def unstableRanges(self) -> List[Tuple[float, float]]:
        """Speed ranges (rad/s) of consecutive unstable speeds: (first unstable, last unstable) of each run."""
        return _UnstableRanges(self.motorSpeeds, self.maxRealPart)

    def Boundaries(self) -> List[float]:
        """Motor speeds in rad/s where the largest real part changes sign (linear interpolation in log speed)."""
        return _Boundaries(self.motorSpeeds, self.maxRealPart)

    def ToDict(self) -> Dict:
        """JSON-ready: phase, S, load torque, normal force, frequencies and the ranges (SI and rpm)."""
        return {'phase': self.phase, 'S': self.S, 'loadTorque': self.loadTorque,
                'normalForce': self.normalForce.tolist(), 'frequencyHz': self.frequencyHz.tolist(),
                **_RangesDict(self.motorSpeeds, self.maxRealPart)}


@dataclass(frozen=True)
class SpeedChart:
    """The drive's stability over motor speed (the result of :func:`SpeedStabilityChart`).

    Attributes
    ----------
    motorSpeeds : ndarray
        Motor speeds in rad/s, increasing.
    slidingSpeeds : ndarray
        Sliding speeds v0 in m/s at these motor speeds.
    mu, dmuDv : ndarray
        Friction coefficient mu(v0) and slope dmu/dv in s/m.
    curves : tuple of SpeedCurve
        One per direction of power flow and load torque of the duty (lifting first).
    frictionLaw : str
        The law's name (``constant``, ``stribeck``, ...).
    model : str
        ``'analytical'`` (eq. (16) extended by the friction slope) or ``'linearized'`` (the whole drive).
    ownPoints : tuple
        The drive's own operating points with their verdict
        (:class:`~exudyn_worm.analysis.stability.drivestability.OperatingPointStability`, as ``exudyn-worm stability``);
        empty for a drive without a motor (the chart then takes the load at every speed).
    components : tuple of str
        The drive's parts beyond the two-mass drive, as named in messages (empty: two-mass).
    """
    motorSpeeds: np.ndarray
    slidingSpeeds: np.ndarray
    mu: np.ndarray
    dmuDv: np.ndarray
    curves: Tuple[SpeedCurve, ...]
    frictionLaw: str
    model: str = ANALYTICAL
    ownPoints: Tuple[Any, ...] = ()
    components: Tuple[str, ...] = ()

    @property
    def maxRealPart(self) -> np.ndarray:
        """Largest real part in 1/s over every curve at each speed (> 0: the drive chatters in some direction)."""
        return np.max(np.array([c.maxRealPart for c in self.curves]), axis=0)

    @property
    def unstable(self) -> np.ndarray:
        """Boolean per speed: some direction of the duty is unstable."""
        return self.maxRealPart > 0

    @property
    def unstableRanges(self) -> List[Tuple[float, float]]:
        """Speed ranges (rad/s) in which some direction is unstable (of :attr:`maxRealPart`)."""
        return _UnstableRanges(self.motorSpeeds, self.maxRealPart)

    def Boundaries(self) -> List[float]:
        """Motor speeds in rad/s where :attr:`maxRealPart` changes sign (linear interpolation in log speed)."""
        return _Boundaries(self.motorSpeeds, self.maxRealPart)

    def Curve(self, S: int) -> SpeedCurve:
        """The curve of contact state ``S`` with the largest load torque.

        Parameters
        ----------
        S : int
            +1 (lifting) or -1 (lowering).

        Returns
        -------
        SpeedCurve

        Raises
        ------
        ValueError
            If the duty has no operating point in that direction.
        """
        mine = [c for c in self.curves if c.S == S]
        if not mine:
            raise ValueError(f"SpeedChart.Curve: the duty has no {PHASE_NAMES.get(S, S)} operating point "
                             f"(S = {S}); its curves: {', '.join(c.phase for c in self.curves)}")
        return max(mine, key=lambda c: c.loadTorque)

    @property
    def stable(self) -> Optional[bool]:
        """The drive's verdict at its own operating points (as ``exudyn-worm stability``); None without them."""
        return all(p.stable for p in self.ownPoints) if self.ownPoints else None

    def ToDict(self) -> Dict:
        """JSON-ready: speeds (SI and rpm), mu, slope, the envelope's ranges, ``curves`` and ``operatingPoints``."""
        return {'frictionLaw': self.frictionLaw, 'model': self.model, 'components': list(self.components),
                'motorSpeed': self.motorSpeeds.tolist(), 'motorSpeedRpm': (self.motorSpeeds / RPM).tolist(),
                'slidingSpeed': self.slidingSpeeds.tolist(), 'mu': self.mu.tolist(), 'dmuDv': self.dmuDv.tolist(),
                **_RangesDict(self.motorSpeeds, self.maxRealPart),
                'curves': [c.ToDict() for c in self.curves],
                'stable': self.stable,
                'operatingPoints': [{**p.ToDict(), 'motorSpeedRpm': p.point.motorSpeed / RPM} for p in self.ownPoints]}

    def plot(self, ax=None, **kwargs):
        """Draw the chart (:func:`exudyn_worm.plotting.plot_charts.PlotSpeedChart`); returns the axes."""
        from ...plotting.plot_charts import PlotSpeedChart
        return PlotSpeedChart(self, ax=ax, **kwargs)


def _LoadsOfTheDuty(drive: Drive, speed: float, where: str) -> Tuple[Tuple[Any, ...], List[Tuple[int, float]]]:
    """(the drive's own operating points, [(S, |load torque|), ...] of the curves, lifting first, no repeats)."""
    if drive.load is None:
        raise MissingParameterError(f"{where}: the drive has no load torque (the load sets the normal force of the "
                                    f"operating point): give [load] in the drive file (mass and leverArm, or a "
                                    f"type and its torque) or --set loadMass=... --set leverArm=...",
                                    ['loadMass', 'leverArm'])
    own: Tuple[Any, ...] = ()
    if drive.hasDuty:
        own = AnalyzeDrive(drive).operatingPoints
        points = [p.point for p in own]
    else:                           # no motor: the load of a constant-speed duty at the chart's speed
        points = list(DutyOperatingPoints(drive.Replace(motorSpeed=speed)))
    if not points:
        raise ValueError(f"{where}: the drive's duty has no steady phase with a load torque (the motor never runs "
                         f"at a constant speed other than 0), so there is no load to take over speed")
    loads: List[Tuple[int, float]] = []
    for p in sorted(points, key=lambda p: -p.S):
        key = (p.S, abs(p.loadTorque))
        if not any(S == key[0] and math.isclose(T, key[1], rel_tol=1e-9) for S, T in loads):
            loads.append(key)
    return own, loads


def SpeedStabilityChart(drive: Drive, motorSpeeds: Sequence[float],
                        progress: Optional[Callable[[int], Any]] = None) -> SpeedChart:
    """Largest real part over motor speed of each direction of the drive's duty, at the load torque of its duty.

    Parameters
    ----------
    drive : Drive
        The drive (:func:`~exudyn_worm.drive.wholedrive.ResolveDrive`), with a load
        (any load type) and usually a friction law (with constant mu the result does not depend on speed). A
        drive without a motor is taken at the load of a constant-speed duty.
    motorSpeeds : sequence of float
        Motor speeds in rad/s, > 0 (sorted here); each direction is evaluated at the speed of its sign.
    progress : callable, optional
        Called with 1 after each linear analysis (e.g. a progress bar's ``update``).

    Returns
    -------
    SpeedChart

    Raises
    ------
    ValueError
        For a bad drive, a drive without a load or without a steady phase, or a speed that is not > 0.
    """
    w = 'SpeedStabilityChart'
    if isinstance(motorSpeeds, (str, bytes)) or not hasattr(motorSpeeds, '__len__') or len(motorSpeeds) == 0:
        raise ValueError(f"{w}: 'motorSpeeds' must be a non-empty sequence of speeds in rad/s, got {motorSpeeds!r}")
    speeds = np.sort(np.array([CheckPositive(w, f'motorSpeeds[{i}]', s, 'rad/s') for i, s in enumerate(motorSpeeds)]))
    CheckDrive(w, drive)
    own, loads = _LoadsOfTheDuty(drive, float(speeds[0]), w)
    model = ANALYTICAL if drive.isTwoMass else LINEARIZED
    gear = drive.gear
    curves = []
    for S, torque in loads:
        rows = []
        for speed in speeds:
            op = OperatingPointAt(gear, float(speed), torque, S)
            # the chart's speed (> 0) and a load torque whose power has the phase's sign (lifting: < 0)
            point = DutyPoint(PHASE_NAMES[S], float(speed), -S * torque, None, 'speed chart', op)
            rows.append((*StateGrowth(AnalyzeDrive(drive, model, [point]).operatingPoints[0].state), op.normalForce))
            if progress is not None:
                progress(1)
        re, f, fn = (np.array(c) for c in zip(*rows))
        curves.append(SpeedCurve(PHASE_NAMES[S], S, torque, speeds, re, f, fn))
    ops = [OperatingPointAt(gear, float(s), 0., -1) for s in speeds]
    return SpeedChart(speeds, np.array([o.slidingSpeed for o in ops]), np.array([o.mu for o in ops]),
                      np.array([o.dmuDv for o in ops]), tuple(curves), gear.frictionLaw.kind, model, tuple(own),
                      tuple(c.text for c in drive.components))
