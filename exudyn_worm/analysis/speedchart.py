"""Stability over motor speed: the speed range in which a drive with speed-dependent friction chatters.

With a constant mu the linear model (eqs. (15)-(19)) does not depend on speed or load. With a friction law
mu(v) (:mod:`exudyn_worm.model.friction`) it does: the drive is linearized at steady lowering (worm speed = motor
speed, static normal force from ``loadMass * g * leverArm``, :func:`~exudyn_worm.model.stability.OperatingPointAt`) and
the slope dmu/dv adds damping to eq. (16) (:mod:`exudyn_worm.model.stability`). :func:`SpeedStabilityChart` evaluates
the extended eq. (16) at every speed of a list and returns a :class:`SpeedChart` (largest real part of the lowering
state S = -1, mu and its slope, the unstable speed ranges); its ``plot()`` draws it
(:func:`exudyn_worm.plotting.plot_charts.PlotSpeedChart`). ``exudyn-worm chart --speed SPEC`` prints or draws it.

No matplotlib here.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Dict, List, Mapping, Sequence, Tuple

import numpy as np
from .._checks import CheckPositive
from ..setups.presets import ApplyOverrides, ElasticDriveFromParameters, ExtraComponents, MissingParameterError
from ..model.profiles import STANDARD_GRAVITY
from ..model.stability import AnalyzeStability, OperatingPointAt

__all__ = ['RPM', 'SpeedChart', 'SpeedStabilityChart']

#: one revolution per minute in rad/s
RPM = 2 * math.pi / 60


@dataclass(frozen=True)
class SpeedChart:
    """The lowering state's stability over motor speed (the result of :func:`SpeedStabilityChart`).

    Attributes
    ----------
    motorSpeeds : ndarray
        Motor speeds in rad/s, increasing.
    slidingSpeeds : ndarray
        Sliding speeds v0 in m/s at these motor speeds.
    mu, dmuDv : ndarray
        Friction coefficient mu(v0) and slope dmu/dv in s/m.
    maxRealPart : ndarray
        Largest real part in 1/s of the eigenvalues of the lowering state S = -1 (extended eq. (16)); > 0:
        unstable, the drive chatters while lowering at this speed.
    frictionLaw : str
        The law's name (``constant``, ``stribeck``, ...).
    normalForce : float
        Static normal force Fn0 in N at the first speed (it changes with mu(v0) through c4).
    """
    motorSpeeds: np.ndarray
    slidingSpeeds: np.ndarray
    mu: np.ndarray
    dmuDv: np.ndarray
    maxRealPart: np.ndarray
    frictionLaw: str
    normalForce: float

    @property
    def unstable(self) -> np.ndarray:
        """Boolean per speed: the lowering state is unstable."""
        return self.maxRealPart > 0

    @property
    def unstableRanges(self) -> List[Tuple[float, float]]:
        """Speed ranges (rad/s) of consecutive unstable speeds: (first unstable, last unstable) of each run."""
        ranges, start = [], None
        for i, bad in enumerate(self.unstable):
            if bad and start is None:
                start = i
            if start is not None and (not bad or i == len(self.unstable) - 1):
                end = i if bad else i - 1
                ranges.append((float(self.motorSpeeds[start]), float(self.motorSpeeds[end])))
                start = None
        return ranges

    def Boundaries(self) -> List[float]:
        """Motor speeds in rad/s where the largest real part changes sign (linear interpolation in log speed)."""
        out = []
        s, r = np.log(self.motorSpeeds), self.maxRealPart
        for i in range(len(r) - 1):
            if (r[i] > 0) != (r[i + 1] > 0):
                t = r[i] / (r[i] - r[i + 1])
                out.append(float(math.exp(s[i] + t * (s[i + 1] - s[i]))))
        return out

    def ToDict(self) -> Dict:
        """JSON-ready: the arrays (SI; speeds also in rpm), the unstable ranges and the boundaries."""
        return {'frictionLaw': self.frictionLaw, 'contactState': -1, 'normalForce': self.normalForce,
                'motorSpeed': self.motorSpeeds.tolist(), 'motorSpeedRpm': (self.motorSpeeds / RPM).tolist(),
                'slidingSpeed': self.slidingSpeeds.tolist(), 'mu': self.mu.tolist(), 'dmuDv': self.dmuDv.tolist(),
                'maxRealPart': self.maxRealPart.tolist(), 'unstable': self.unstable.tolist(),
                'unstableRanges': [list(r) for r in self.unstableRanges],
                'unstableRangesRpm': [[a / RPM, b / RPM] for a, b in self.unstableRanges],
                'boundaries': self.Boundaries(), 'boundariesRpm': [b / RPM for b in self.Boundaries()]}

    def plot(self, ax=None, **kwargs):
        """Draw the chart (:func:`exudyn_worm.plotting.plot_charts.PlotSpeedChart`); returns the axes."""
        from ..plotting.plot_charts import PlotSpeedChart
        return PlotSpeedChart(self, ax=ax, **kwargs)


def SpeedStabilityChart(parameters: Mapping[str, object], motorSpeeds: Sequence[float]) -> SpeedChart:
    """Largest real part of the lowering state over motor speed, from eq. (16) extended at each operating point.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set of a two-mass drive with ``loadMass`` and ``leverArm`` (its ``motorSpeed`` is replaced),
        and usually a friction law (``frictionLaw`` ...; with constant mu the result does not depend on speed).
    motorSpeeds : sequence of float
        Motor speeds in rad/s, > 0 (sorted here).

    Returns
    -------
    SpeedChart

    Raises
    ------
    ValueError
        For a bad parameter set, a set without ``loadMass``/``leverArm``, one with components beyond the
        two-mass drive, or a speed that is not > 0.
    """
    w = 'SpeedStabilityChart'
    if isinstance(motorSpeeds, (str, bytes)) or not hasattr(motorSpeeds, '__len__') or len(motorSpeeds) == 0:
        raise ValueError(f"{w}: 'motorSpeeds' must be a non-empty sequence of speeds in rad/s, got {motorSpeeds!r}")
    speeds = np.sort(np.array([CheckPositive(w, f'motorSpeeds[{i}]', s, 'rad/s') for i, s in enumerate(motorSpeeds)]))
    missing = [k for k in ('loadMass', 'leverArm') if k not in parameters]
    if missing:
        raise MissingParameterError(f"{w}: missing parameter(s) {', '.join(missing)} (the load sets the normal force "
                                    f"of the operating point); give them with --set KEY=VALUE", missing)
    extra = ExtraComponents(parameters)
    if extra:
        raise ValueError(f"{w}: the chart over speed uses the two-mass model of eq. (16); this parameter set has "
                         f"{' and '.join(extra)}")
    drive = ElasticDriveFromParameters(ApplyOverrides(parameters, {'motorSpeed': float(speeds[0])}))
    torque = parameters['loadMass'] * STANDARD_GRAVITY * parameters['leverArm']
    rows = []
    for speed in speeds:
        op = OperatingPointAt(drive.gear, float(speed), torque)
        analysis = AnalyzeStability(drive, op)
        rows.append((op.slidingSpeed, op.mu, op.dmuDv, float(np.max(analysis.contact[-1].eigenvalues.real)),
                     op.normalForce))
    v, mu, slope, re, fn = (np.array(c) for c in zip(*rows))
    return SpeedChart(speeds, v, mu, slope, re, drive.gear.frictionLaw.kind, float(fn[0]))
