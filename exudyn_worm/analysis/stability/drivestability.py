"""One stability entry point for every drive: :func:`AnalyzeDrive`, the linear verdict at the duty's operating points.

The drive (:class:`~exudyn_worm.drive.wholedrive.Drive`) is linearized at each operating point of its own duty
(:func:`~exudyn_worm.drive.operatingpoints.DutyOperatingPoints`: every steady phase in each direction of power
flow, with its sliding speed, mu(v), dmu/dv, static normal force and contact state S). The model is chosen by
what the drive contains, a typed property:

- the two-mass drive of Figure 2 (:attr:`~exudyn_worm.drive.wholedrive.Drive.isTwoMass`): the analytical model,
  eqs. (15)-(19) with the friction slope's damping (:func:`~exudyn_worm.model.stability.AnalyzeStability`);
- any other drive (chains, axial bearing, motor on its characteristic): the linearized Exudyn model of the whole
  drive at the same operating point (:func:`~exudyn_worm.analysis.stability.linearization.LinearizationModel`).

An operating point is stable when its own contact state S is (lifting: S = +1, lowering: S = -1); the drive's
verdict is the worst of its operating points, and the phase with the largest real part decides. A drive without a
steady phase (no motor, no load torque, only ramps) is analysed at rest in both contact states (the paper's
constant-mu model; the result says so). Each analysis is computed once per drive (cached on the drive).
"""
from __future__ import annotations

import enum
import math
from dataclasses import dataclass, replace
from typing import Any, Dict, Optional, Sequence, Tuple, Union

import numpy as np

from ..._checks import JsonNumber
from ...model.selflocking import SelfLocking
from ...model.stability import CONTACT_STATES, AnalyzeStability, OperatingPoint
from ...drive.operatingpoints import DutyOperatingPoints, DutyPoint
from ...drive.wholedrive import CheckDrive, Drive
from . import linearization
from ...builders.start import LinearizationPoint

__all__ = ['StabilityModel', 'OperatingPointStability', 'DriveAnalysis', 'AnalyzeDrive', 'StateGrowth',
           'StateInstability', 'GrowthText', 'VerdictWord', 'DIVERGENCE', 'CHATTER', 'REAL_EIGENVALUE_TOLERANCE']


class StabilityModel(str, enum.Enum):
    """The model of a drive's linear verdict (:attr:`DriveAnalysis.model`).

    Attributes
    ----------
    ANALYTICAL : StabilityModel
        Eqs. (15)-(19) of the two-mass drive of Figure 2 (value ``'analytical'``).
    LINEARIZED : StabilityModel
        The Exudyn model of the whole drive, linearized (value ``'linearized'``).
    """
    ANALYTICAL = 'analytical'
    LINEARIZED = 'linearized'


ANALYTICAL, LINEARIZED = StabilityModel.ANALYTICAL, StabilityModel.LINEARIZED


#: the kinds of a growing eigenvalue: a real one (divergence: the drive runs away or creeps from the operating point,
#: no vibration) and a complex one (a growing vibration: chatter)
DIVERGENCE, CHATTER = 'divergence', 'chatter'
#: a growing eigenvalue is real where abs(Im) <= this times abs(lambda) (numpy returns exactly 0 for a real eigenvalue
#: of a real matrix; this only absorbs round-off)
REAL_EIGENVALUE_TOLERANCE = 1e-9


def _Deciding(state: Any) -> complex:
    """The eigenvalue of the state's largest real part (its rigid-body modes left out, as StateGrowth)."""
    re = float(state.maxRealPart)
    lam = np.asarray(state.eigenvalues)
    return complex(lam[int(np.argmin(np.abs(lam.real - re)))])


def StateInstability(state: Any) -> Optional[str]:
    """How one contact state's analysis is unstable: None (stable), :data:`DIVERGENCE` (the eigenvalue with the
    largest real part is real: the drive runs away or creeps) or :data:`CHATTER` (it is complex: a growing vibration).

    Parameters
    ----------
    state : object
        ``OperatingPointStability.state`` or ``analysis.State(S)`` (``stable``, ``maxRealPart``, ``eigenvalues``).

    Returns
    -------
    str or None
    """
    if bool(state.stable):
        return None
    lam = _Deciding(state)
    return DIVERGENCE if abs(lam.imag) <= REAL_EIGENVALUE_TOLERANCE * abs(lam) else CHATTER


def GrowthText(maxRealPart: float, frequencyHz: float, instability: Optional[str]) -> str:
    """The deciding eigenvalue in words: ``largest real part -0.25 1/s at 2.4 Hz``, or for a divergence
    ``a real eigenvalue grows at 603 1/s (divergence: the drive runs away or creeps ...; no vibration)``.

    Parameters
    ----------
    maxRealPart : float
        Largest real part in 1/s.
    frequencyHz : float
        Frequency of that eigenvalue in Hz.
    instability : str or None
        :func:`StateInstability`.
    """
    if instability == DIVERGENCE:
        return (f"a real eigenvalue grows at {maxRealPart:.4g} 1/s (divergence: the drive runs away or creeps from "
                f"the operating point; no vibration)")
    return f"largest real part {maxRealPart:.4g} 1/s at {frequencyHz:.4g} Hz"


def VerdictWord(stable: bool, instability: Optional[str] = None) -> str:
    """``stable``, ``UNSTABLE`` (a growing vibration) or ``DIVERGENT`` (a real eigenvalue grows).

    Parameters
    ----------
    stable : bool
        The verdict.
    instability : str or None
        :func:`StateInstability`.
    """
    return 'stable' if stable else 'DIVERGENT' if instability == DIVERGENCE else 'UNSTABLE'


def StateGrowth(state: Any) -> Tuple[float, float]:
    """(largest real part in 1/s, frequency in Hz of that eigenvalue) of one contact state's analysis, with its own
    verdict's eigenvalues: the rigid-body modes of the linearized whole drive (a free motor rotor) left out.

    Parameters
    ----------
    state : object
        ``OperatingPointStability.state`` or ``analysis.State(S)`` (``maxRealPart``, ``eigenvalues``).

    Returns
    -------
    (float, float)
    """
    re = float(state.maxRealPart)
    lam = np.asarray(state.eigenvalues)
    k = int(np.argmin(np.abs(lam.real - re)))       # the eigenvalue of that real part
    return re, abs(float(lam[k].imag)) / (2 * math.pi)


@dataclass(frozen=True)
class OperatingPointStability:
    """The linear analysis of a drive at one operating point of its duty.

    Attributes
    ----------
    point : DutyPoint
        The operating point (phase, motor speed, load torque, sliding speed, mu, slope, normal force, S).
    analysis : StabilityAnalysis or LinearStability
        The analytical model (both contact states at the point's mu and slope) or the linearized whole drive
        (the point's own contact state).
    gear : WormGear
        The drive's gear (for the self-locking verdict at the point's sliding speed).
    """
    point: DutyPoint
    analysis: Any
    gear: Any

    @property
    def phase(self) -> str:
        """``'lifting'`` or ``'lowering'``."""
        return self.point.phase

    @property
    def S(self) -> int:
        """The point's contact state, +1 lifting, -1 lowering."""
        return self.point.S

    @property
    def state(self):
        """The analysis of the point's own contact state (``stable``, ``maxRealPart``, ``eigenvalues``)."""
        return self.analysis.State(self.S)

    @property
    def eigenvalues(self) -> np.ndarray:
        """Eigenvalues in 1/s of the point's contact state."""
        return np.asarray(self.state.eigenvalues)

    @property
    def maxRealPart(self) -> float:
        """Largest real part in 1/s (> 0: vibrations grow at this point)."""
        return StateGrowth(self.state)[0]

    @property
    def frequencyHz(self) -> float:
        """Frequency in Hz of the eigenvalue with the largest real part."""
        return StateGrowth(self.state)[1]

    @property
    def stable(self) -> bool:
        """True iff every eigenvalue of the point's contact state has a negative real part."""
        return bool(self.state.stable)

    @property
    def instability(self) -> Optional[str]:
        """None (stable), :data:`DIVERGENCE` or :data:`CHATTER` (:func:`StateInstability`)."""
        return StateInstability(self.state)

    @property
    def growthText(self) -> str:
        """The deciding eigenvalue in words (:func:`GrowthText`)."""
        return GrowthText(self.maxRealPart, self.frequencyHz, self.instability)

    @property
    def selfLocking(self):
        """Static and dynamic self-locking at this point's sliding speed
        (:class:`~exudyn_worm.model.selflocking.SelfLockingVerdict`)."""
        return SelfLocking(self.gear, self.point.operatingPoint.slidingSpeed)

    def ToDict(self) -> Dict:
        """JSON-ready: the point (:meth:`DutyPoint.ToDict`) with ``maxRealPart``, ``frequencyHz``, ``stable``,
        ``instability``."""
        return {**self.point.ToDict(), 'maxRealPart': JsonNumber(self.maxRealPart),
                'frequencyHz': JsonNumber(self.frequencyHz), 'stable': self.stable, 'instability': self.instability}


@dataclass(frozen=True)
class DriveAnalysis:
    """The linear verdict of a drive at its own operating points (:func:`AnalyzeDrive`).

    Attributes
    ----------
    drive : Drive
        The drive analysed.
    model : StabilityModel
        ``ANALYTICAL`` (eqs. (15)-(19), the two-mass drive) or ``LINEARIZED`` (the Exudyn model of the whole
        drive).
    operatingPoints : tuple of OperatingPointStability
        One per operating point of the duty (empty: the drive has no steady phase; see :attr:`atRest`).
    """
    drive: Drive
    model: StabilityModel
    operatingPoints: Tuple[OperatingPointStability, ...]

    @property
    def atRest(self):
        """The analysis at rest in both contact states (constant mu; the paper's model): what decides for a drive
        without a steady phase, and the reference of the classic criteria. Computed once, on first use."""
        return _AtRest(self.drive, self.model)

    @property
    def deciding(self) -> Optional[OperatingPointStability]:
        """The operating point with the largest real part (None without operating points)."""
        if not self.operatingPoints:
            return None
        return max(self.operatingPoints, key=lambda p: p.maxRealPart)

    @property
    def stable(self) -> bool:
        """The drive's verdict: every operating point stable (without one: both contact states at rest)."""
        if self.operatingPoints:
            return all(p.stable for p in self.operatingPoints)
        return bool(self.atRest.stable)

    @property
    def maxRealPart(self) -> float:
        """Largest real part in 1/s of the deciding point (at rest: of both contact states)."""
        if self.operatingPoints:
            return self.deciding.maxRealPart
        return max(float(self.atRest.State(S).maxRealPart) for S in CONTACT_STATES)

    @property
    def frequencyHz(self) -> float:
        """Frequency in Hz of the deciding eigenvalue."""
        if self.operatingPoints:
            return self.deciding.frequencyHz
        S = max(CONTACT_STATES, key=lambda s: float(self.atRest.State(s).maxRealPart))
        return StateGrowth(self.atRest.State(S))[1]

    @property
    def instability(self) -> Optional[str]:
        """How the drive is unstable: None (stable), :data:`DIVERGENCE` or :data:`CHATTER`, by the deciding point's
        eigenvalue (at rest: the contact state with the largest real part)."""
        if self.operatingPoints:
            return self.deciding.instability
        if self.stable:
            return None
        S = max(CONTACT_STATES, key=lambda s: float(self.atRest.State(s).maxRealPart))
        return StateInstability(self.atRest.State(S))

    @property
    def growthText(self) -> str:
        """The deciding eigenvalue in words (:func:`GrowthText`)."""
        return GrowthText(self.maxRealPart, self.frequencyHz, self.instability)

    def State(self, S: int):
        """The result for contact state ``S``: the operating point in that state with the largest real part, or,
        if the duty has none in it, the analysis at rest (for callers that follow one contact state, as the
        lowering phase's chatter).

        Parameters
        ----------
        S : int
            +1 or -1.
        """
        mine = [p for p in self.operatingPoints if p.S == S]
        if mine:
            return max(mine, key=lambda p: p.maxRealPart).state
        return self.atRest.State(S)

    @property
    def decidingText(self) -> str:
        """One line that names what decides the verdict."""
        if not self.operatingPoints:
            return (f"no steady phase in the drive's duty: analysed at rest in both contact states "
                    f"(constant mu = {self.drive.gear.mu:g})")
        p = self.deciding
        return f"deciding: {p.point.Label()}: {VerdictWord(p.stable, p.instability)}, {p.growthText}"

    def CauseText(self) -> str:
        """What decides the verdict at the deciding point, in words: the friction slope where the point's verdict
        with mu held at mu(v0) (dmu/dv = 0) differs; else the drive's components where the two-mass drive at the same
        point (eqs. (15)-(19) with the slope) has another verdict; else '' (the two-mass drive with constant mu
        already has this verdict).

        Returns
        -------
        str
        """
        p = self.deciding
        if p is None:
            return ''
        op = p.point.operatingPoint
        word = VerdictWord(p.stable, p.instability)
        if op.dmuDv != 0.:
            flat = _AtPoint(self.drive, replace(op, dmuDv=0.), self.model).State(p.S)
            if bool(flat.stable) != p.stable:
                return (f"the speed-dependent friction decides: its slope dmu/dv = {op.dmuDv:.4g} s/m at "
                        f"v0 = {op.slidingSpeed:.4g} m/s makes the {p.phase} point {word}; with mu held at "
                        f"mu(v0) = {op.mu:.4g} it would be {VerdictWord(bool(flat.stable), StateInstability(flat))}")
        if self.drive.components:
            two = AnalyzeStability(self.drive.elastic, op).State(p.S)
            if bool(two.stable) != p.stable:
                return (f"what the two-mass drive lacks decides ({' and '.join(c.text for c in self.drive.components)}): the two-mass "
                        f"drive at the same {p.phase} point would be "
                        f"{VerdictWord(bool(two.stable), StateInstability(two))}, the whole drive is {word}")
        return ''

    @property
    def selfLockingVerdicts(self) -> Dict[str, Any]:
        """Static and dynamic self-locking at every operating point, keyed by its label (at rest: ``'at rest'``)."""
        gear = self.drive.gear
        if not self.operatingPoints:
            return {'at rest': SelfLocking(gear)}
        return {p.point.Label(): SelfLocking(gear, p.point.operatingPoint.slidingSpeed) for p in self.operatingPoints}

    @property
    def dangerous(self) -> bool:
        """True if the gear is self-locking at rest but not while moving at one of the operating points (the load
        holds, but runs away once it moves)."""
        return any(v.dangerous for v in self.selfLockingVerdicts.values())

    def plot(self, title: Optional[str] = None, ax=None):
        """Draw the eigenvalues at each operating point (in its own contact state; without one, of both contact
        states at rest) as growth rate against frequency, the deciding one circled
        (:func:`exudyn_worm.plotting.plot_stability.PlotEigenvalues`); returns the axes.

        Parameters
        ----------
        title : str, optional
            Title of the axes (default: the verdict and what decides it).
        ax : matplotlib.axes.Axes, optional
            Draw into this axes.
        """
        from ...plotting.plot_stability import PlotEigenvalues
        if not self.operatingPoints:
            return self.atRest.plot(title=title or self.decidingText, ax=ax)
        groups = {p.point.Label(): p.eigenvalues for p in self.operatingPoints}
        p = self.deciding
        return PlotEigenvalues(groups, (p.point.Label(), _Deciding(p.state)), title or self.decidingText, ax)

    def ToDict(self) -> Dict:
        """JSON-ready: ``stable``, ``instability``, ``model``, ``components``, ``maxRealPart``, ``frequencyHz``,
        ``operatingPoints``,
        ``deciding``, ``decidingText``, ``dangerous``, ``selfLockingAtOperatingPoints``."""
        deciding = self.deciding
        return {'stable': self.stable, 'instability': self.instability, 'model': self.model.value, 'components': [c.text for c in self.drive.components],
                'maxRealPart': JsonNumber(self.maxRealPart), 'frequencyHz': JsonNumber(self.frequencyHz),
                'operatingPoints': [p.ToDict() for p in self.operatingPoints],
                'deciding': None if deciding is None else {'phase': deciding.phase,
                                                           'label': deciding.point.Label()},
                'decidingText': self.decidingText,
                'dangerous': self.dangerous,
                'selfLockingAtOperatingPoints': {k: v.ToDict() for k, v in self.selfLockingVerdicts.items()}}


def _AtRest(drive: Drive, model: StabilityModel = ANALYTICAL):
    def Compute():
        if drive.isTwoMass:
            return AnalyzeStability(drive.elastic) if model == ANALYTICAL else \
                linearization.ExudynStabilityAnalysis(drive.elastic)
        return linearization.AnalyzeLinearStability(linearization.LinearizationModel(drive).mbs)
    return drive.Cached(f'stabilityAtRest.{model.value}', Compute)


def _AtPoint(drive: Drive, operatingPoint: OperatingPoint, model: StabilityModel) -> Any:
    """The linear analysis of ``drive`` at one operating point with ``model``: a
    :class:`~exudyn_worm.model.stability.StabilityAnalysis` (two-mass drive, both contact states) or a
    :class:`~exudyn_worm.analysis.stability.linearization.LinearStability` (whole drive, the point's contact state)."""
    op = operatingPoint
    if model == ANALYTICAL:
        return AnalyzeStability(drive.elastic, op)
    if drive.isTwoMass:             # the same result type as the analytical model, from Exudyn's eigenvalues
        return linearization.ExudynStabilityAnalysis(drive.elastic, operatingPoint=op)
    model = linearization.LinearizationModel(drive, LinearizationPoint(op.S, op))
    return linearization.AnalyzeLinearStability(model.mbs, contactStates=[(op.S,)])


def AnalyzeDrive(drive: Drive, model: Optional[Union[StabilityModel, str]] = None,
                 operatingPoints: Optional[Sequence[DutyPoint]] = None) -> DriveAnalysis:
    """Linear stability of a drive at the operating points of its own duty (or at given ones): the one entry point
    of every command.

    Parameters
    ----------
    drive : Drive
        The drive (:func:`~exudyn_worm.drive.wholedrive.ResolveDrive`).
    model : StabilityModel or str, optional
        ``ANALYTICAL`` (eqs. (15)-(19); only for the two-mass drive) or ``LINEARIZED`` (the Exudyn model of the
        whole drive), or their values ``'analytical'``, ``'linearized'``; None (default): analytical for the
        two-mass drive, linearized for any other.
    operatingPoints : sequence of DutyPoint, optional
        Analyse at these points instead of the duty's own (e.g. other motor speeds, as the chart over speed does;
        :class:`~exudyn_worm.drive.operatingpoints.DutyPoint`).

    Returns
    -------
    DriveAnalysis
        ``stable`` (the worst operating point), ``operatingPoints``, ``deciding``, ``State(S)``, ``ToDict()``.

    Raises
    ------
    ValueError, TypeError
        For a bad drive (see :class:`~exudyn_worm.drive.wholedrive.Drive`), a drive that is not a
        :class:`~exudyn_worm.drive.wholedrive.Drive`, or a motor that cannot carry its load.

    Examples
    --------
    >>> from exudyn_worm.drive.wholedrive import ResolveDrive
    >>> analysis = AnalyzeDrive(ResolveDrive('reel-P1'))
    >>> [(p.phase, p.stable) for p in analysis.operatingPoints], analysis.stable
    ([('lifting', True), ('lowering', False)], False)
    """
    w = 'AnalyzeDrive'
    CheckDrive(w, drive)
    if model is None:
        model = ANALYTICAL if drive.isTwoMass else LINEARIZED
    else:
        try:
            model = StabilityModel(model)
        except ValueError:
            raise ValueError(f"{w}: 'model' must be None, {ANALYTICAL.value!r} or {LINEARIZED.value!r}, "
                             f"got {model!r}") from None
    if model == ANALYTICAL and not drive.isTwoMass:
        raise ValueError(f"{w}: the analytical model (eqs. (15)-(19)) describes the two-mass drive of "
                         f"Figure 2; this drive has {drive.ComponentsText()}: use model {LINEARIZED.value!r} "
                         f"(the default)")
    if operatingPoints is not None:
        points = tuple(operatingPoints)
        for i, p in enumerate(points):
            if not isinstance(p, DutyPoint):
                raise TypeError(f"{w}: 'operatingPoints[{i}]' must be a DutyPoint, got {type(p).__name__}")
        return DriveAnalysis(drive=drive, model=model, operatingPoints=tuple(
            OperatingPointStability(p, _AtPoint(drive, p.operatingPoint, model), drive.gear) for p in points))

    def Compute():
        points = tuple(OperatingPointStability(p, drive.Cached(f'stabilityAt{i}.{model.value}',
                                                               lambda p=p: _AtPoint(drive, p.operatingPoint, model)),
                                               drive.gear)
                       for i, p in enumerate(DutyOperatingPoints(drive)))
        return DriveAnalysis(drive=drive, model=model, operatingPoints=points)
    return drive.Cached(f'driveAnalysis.{model.value}', Compute)
