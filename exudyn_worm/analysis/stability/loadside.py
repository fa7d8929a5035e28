"""When may the driven machine be lumped into the wheel's inertia J2? The load-side chain's check.

A load-side chain (``JL1, kL1, dL1, ...``, :func:`~exudyn_worm.drive.presets.LoadSideChain`) puts the driven machine
behind load shafts: ``wheel J2 --(kL1, dL1)-- JL1 --(kL2, dL2)-- JL2 ...``. The two-mass model of Figure 2 (and
the design check built on it) needs the load lumped into J2 (:func:`LumpedLoadSide`).

**Criterion.** Seen from the wheel, stage *i* with everything beyond it rigid (inertia ``J = JLi + JL(i+1) + ...``
on the shaft ``kLi``, wheel held) has the natural frequency ``fLi = sqrt(kLi / J) / (2 pi)``. At a frequency f
the stage acts on the wheel like the inertia ``J / (1 - (f / fLi)^2)`` (undamped single-stage impedance): J itself
for f << fLi, J 10^delta times too large at ``f = fLi sqrt(1 - 10^-delta)``, and a spring (negative inertia)
above fLi, where the load no longer follows the wheel. Lumping is therefore taken as safe when every stage
frequency is at least ``1 / sqrt(1 - 10^-delta)`` times the highest frequency at which the wheel moves (the modes
of the lumped drive in which the wheel has at least :data:`WHEEL_SHARE` of the kinetic energy), with the design
check's margin delta (default 0.1 decades: factor 2.2), *and* the lumped and the whole drive give the same
verdict. This is a derivation from the single-stage impedance, not a published rule; the whole drive's
linearization (:func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive`) is always the reference.

When lumping is not safe, the stage named as the cause is the first one from the wheel whose frequency is below
that limit at the frequency that matters: the whole drive's growing mode if it has one, else the highest wheel
mode. Below the stage frequency the driven machine follows the wheel; above it the wheel vibrates alone against
mesh and load shaft, a mode the lumped drive does not have (``examples/drives/load-shaft.toml``: 32 Hz load shaft,
chatter at 228 Hz).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple
from ..._checks import CheckRange
from .linearization import LinearStabilityOfDrive
from .drivestability import AnalyzeDrive, VerdictWord
from ...drive.wholedrive import CheckDrive, Drive
from ...params.parameters import PARAMETERS

__all__ = ['WHEEL_SHARE', 'LoadSideStage', 'LoadSideDiagnosis', 'LumpedLoadSide', 'DiagnoseLoadSide', 'LoadSideNotLumpable']

#: smallest kinetic-energy share of the wheel in a mode of the lumped drive for the mode to count as one in which
#: the wheel moves (the worm's own mode has < 1 % in the drives tested)
WHEEL_SHARE = 0.01


@dataclass(frozen=True)
class LoadSideStage:
    """One stage of the load-side chain as the wheel sees it.

    Attributes
    ----------
    number : int
        Stage number i (``JLi``, ``kLi``), from 1 at the wheel.
    inertia : float
        ``JLi`` in kg*m^2.
    inertiaBeyond : float
        ``JLi + JL(i+1) + ...`` in kg*m^2: what the shaft ``kLi`` carries.
    stiffness : float
        ``kLi`` in N*m/rad.
    """
    number: int
    inertia: float
    inertiaBeyond: float
    stiffness: float

    @property
    def frequencyHz(self) -> float:
        """``sqrt(kLi / inertiaBeyond) / (2 pi)`` in Hz: everything beyond the shaft rigid, the wheel held."""
        return math.sqrt(self.stiffness / self.inertiaBeyond) / (2 * math.pi)

    def StiffnessFor(self, frequencyHz: float) -> float:
        """The ``kLi`` in N*m/rad at which :attr:`frequencyHz` would equal ``frequencyHz``.

        Parameters
        ----------
        frequencyHz : float
            Frequency in Hz.
        """
        return (2 * math.pi * frequencyHz) ** 2 * self.inertiaBeyond


@dataclass(frozen=True)
class LoadSideDiagnosis:
    """Whether the load-side chain may be lumped into J2, and which stage is the cause if not.

    Attributes
    ----------
    stages : list of LoadSideStage
        Wheel side first.
    margin : float
        Margin in decades (the design check's).
    wheelModesHz : tuple of float
        Frequencies in Hz of the lumped drive's modes in which the wheel has at least :data:`WHEEL_SHARE` of the
        kinetic energy (both contact states).
    lumpedStable, wholeStable : bool
        Verdicts of the lumped drive and of the whole drive (every contact state).
    growingMode : dict or None
        The whole drive's fastest-growing mode if it is unstable: ``S``, ``frequencyHz``, ``realPart`` (1/s) and
        ``energyShare`` (coordinate -> share of the kinetic energy).
    cause : int or None
        Number of the stage named as the cause (None: lumping is safe, or no stage is below the limit).
    notes : list of str
        Remarks for the design check's table (e.g. that the lumped drive was checked).
    lumpedInstability, wholeInstability : str or None
        How the lumped and the whole drive are unstable (``DriveAnalysis.instability``): None (stable or not given),
        ``'divergence'`` (a real eigenvalue grows: the verdict reads DIVERGENT) or ``'chatter'`` (UNSTABLE).
    """
    stages: List[LoadSideStage]
    margin: float
    wheelModesHz: Tuple[float, ...]
    lumpedStable: bool
    wholeStable: bool
    growingMode: Optional[Dict] = None
    cause: Optional[int] = None
    notes: List[str] = field(default_factory=list)
    lumpedInstability: Optional[str] = None
    wholeInstability: Optional[str] = None

    @property
    def limitFactor(self) -> float:
        """``1 / sqrt(1 - 10^-margin)``: how far above a wheel frequency a stage frequency must lie."""
        return 1. / math.sqrt(1. - 10. ** -self.margin) if self.margin > 0 else 1.

    @property
    def frequencyHz(self) -> float:
        """The frequency that matters in Hz: the growing mode's, else (none grows, or it is real: a divergence) the
        highest wheel mode's (0 if none)."""
        if self.growingMode is not None and self.growingMode['frequencyHz'] > 0.:
            return self.growingMode['frequencyHz']
        return max(self.wheelModesHz, default=0.)

    @property
    def lumpingSafe(self) -> bool:
        """Every stage frequency >= limitFactor x every wheel mode, and lumped and whole drive agree."""
        highest = max(self.wheelModesHz, default=0.)
        return (self.lumpedStable == self.wholeStable and
                all(s.frequencyHz >= self.limitFactor * highest for s in self.stages))

    def Text(self) -> str:
        """One paragraph for reports and messages.

        Returns
        -------
        str
        """
        stages = '; '.join(f"stage {s.number}: JL{s.number} = {s.inertia:.4g} kg*m^2 behind kL{s.number} = "
                           f"{s.stiffness:.4g} N*m/rad, {s.frequencyHz:.4g} Hz" for s in self.stages)
        text = (f"load-side chain ({stages}); lumped into J2 the drive is "
                f"{VerdictWord(self.lumpedStable, self.lumpedInstability)}, the whole drive is "
                f"{VerdictWord(self.wholeStable, self.wholeInstability)}")
        if self.growingMode is not None:
            g = self.growingMode
            shares = ', '.join(f"{k} {v:.0%}" for k, v in sorted(g['energyShare'].items(), key=lambda kv: -kv[1])
                               if v >= 0.1)
            mode = (f"mode at {g['frequencyHz']:.4g} Hz grows" if g['frequencyHz'] > 0. else
                    'a real mode grows (divergence: the drive runs away or creeps, no vibration)')
            text += f" (S = {g['S']:+d}: {mode} at {g['realPart']:.3g} 1/s; kinetic energy {shares})"
        if self.lumpingSafe:
            return text + (f"; lumping is safe: every stage frequency is at least {self.limitFactor:.2f} times the "
                           f"highest wheel mode ({max(self.wheelModesHz, default=0.):.4g} Hz)")
        if self.cause is None:
            if self.lumpedStable != self.wholeStable:
                return text + '; lumping is not safe (the verdicts differ)'
            highest = max(self.wheelModesHz, default=0.)
            low = next(s for s in self.stages if s.frequencyHz < self.limitFactor * highest)
            return text + (f"; lumping is not safe although the verdicts agree: load-side stage {low.number}'s "
                           f"{low.frequencyHz:.4g} Hz lie below {self.limitFactor:.2f} x the lumped drive's highest "
                           f"wheel mode {highest:.4g} Hz, so the driven machine does not follow the wheel there")
        s = self.stages[self.cause - 1]
        highest = max(self.wheelModesHz, default=0.)
        return text + (f"; the cause is load-side stage {s.number}: its {s.frequencyHz:.4g} Hz lie below "
                       f"{self.limitFactor:.2f} x {self.frequencyHz:.4g} Hz, so the driven machine does not follow "
                       f"the wheel there" + (f" (lumping would hold from kL{s.number} >= "
                                             f"{s.StiffnessFor(self.limitFactor * highest):.3g} N*m/rad, "
                                             f"{self.limitFactor:.2f} x the lumped drive's highest wheel mode "
                                             f"{highest:.4g} Hz)" if highest > 0 else ''))

    def ToDict(self) -> Dict:
        """JSON-ready dictionary.

        Returns
        -------
        dict
        """
        return {'stages': [{'number': s.number, 'inertia': s.inertia, 'inertiaBeyond': s.inertiaBeyond,
                            'stiffness': s.stiffness, 'frequencyHz': s.frequencyHz} for s in self.stages],
                'margin': self.margin, 'limitFactor': self.limitFactor, 'wheelModesHz': list(self.wheelModesHz),
                'lumpedStable': self.lumpedStable, 'wholeStable': self.wholeStable,
                'lumpedInstability': self.lumpedInstability, 'wholeInstability': self.wholeInstability,
                'growingMode': self.growingMode,
                'lumpingSafe': self.lumpingSafe, 'cause': self.cause, 'text': self.Text()}


class LoadSideNotLumpable(ValueError):
    """The design check's two-mass model does not describe a drive with this load-side chain; ``diagnosis`` says
    why (:class:`LoadSideDiagnosis`).

    Parameters
    ----------
    message : str
        The error message.
    diagnosis : LoadSideDiagnosis
        The diagnosis of the load-side chain.
    """

    def __init__(self, message: str, diagnosis: LoadSideDiagnosis):
        super().__init__(message)
        self.diagnosis = diagnosis


def LumpedLoadSide(drive: Drive) -> Drive:
    """The drive with its load-side chain lumped into the wheel: J2 + JL1 + JL2 + ..., no chain.

    What the two-mass model assumes when the driven machine is counted in J2 (rigid load shafts); compare its
    verdict with the whole drive's (:func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive`) to see
    whether lumping is safe for a drive (docs/drive-files.md, "Load-side chain").

    Parameters
    ----------
    drive : Drive
        The drive.

    Returns
    -------
    Drive
        A new drive (:meth:`~exudyn_worm.drive.wholedrive.Drive.Replace`); ``drive`` itself without a load-side
        chain. The physical damping is kept: a damping given as a measure (``DV``, ``DT``, ``DTV``, which refer to
        J2) is replaced by the ``dV`` and ``dT`` it gives for the wheel's own J2.
    """
    drive = CheckDrive('LumpedLoadSide', drive)
    chain = drive.loadSideChain
    if not chain:
        return drive
    changes = {k: None for k in drive.parameters if (PARAMETERS.SeriesIndex(k) or ('',))[0] in ('JL', 'kL', 'dL')}
    changes.update(J2=drive.elastic.J2 + sum(J for J, _, _ in chain), dV=drive.gear.dV, dT=drive.elastic.dT)
    return drive.Replace(**changes)


def DiagnoseLoadSide(drive: Drive, margin: float = 0.1) -> LoadSideDiagnosis:
    """May the load-side chain of ``drive`` be lumped into J2? The criterion is in the module docstring.

    Parameters
    ----------
    drive : Drive
        The drive, with a load-side chain (``JL1``, ``kL1``, ...); its verdict is its own, cached analysis.
    margin : float, optional
        Margin in decades, in [0, 1] (default 0.1, the design check's).

    Returns
    -------
    LoadSideDiagnosis

    Raises
    ------
    ValueError
        For a parameter set without a load-side chain or with an invalid one, or a margin out of range.
    """
    w = 'DiagnoseLoadSide'
    margin = CheckRange(w, 'margin', margin, low=0., high=1., unit='decades')
    CheckDrive(w, drive)
    chain = drive.loadSideChain
    if not chain:
        raise ValueError(f"{w}: the drive has no load-side chain (JL1, kL1, ...)")
    stages = [LoadSideStage(i, J, sum(j for j, _, _ in chain[i - 1:]), k) for i, (J, k, _) in enumerate(chain, 1)]
    lumpedDrive = LumpedLoadSide(drive)
    lumped = LinearStabilityOfDrive(lumpedDrive)          # its modes: which ones move the wheel
    lumpedAnalysis = AnalyzeDrive(lumpedDrive)                # its verdict: at the duty's operating points
    lumpedStable = lumpedAnalysis.stable
    wheelModes = tuple(sorted({m.frequencyHz for s in lumped.states.values() for m in s.modes
                               if m.energyShare.get('wheel', 0.) >= WHEEL_SHARE and m.eigenvalue.imag != 0}))
    whole = AnalyzeDrive(drive)
    growing = None
    if not whole.stable:
        states = [p.state for p in whole.operatingPoints] or list(whole.atRest.states.values())
        S, mode = max(((s.S, m) for s in states for m in s.modes), key=lambda sm: sm[1].eigenvalue.real)
        growing = {'S': int(S[0]), 'frequencyHz': mode.frequencyHz, 'realPart': float(mode.eigenvalue.real),
                   'energyShare': dict(mode.energyShare)}
    kinds = {'lumpedInstability': lumpedAnalysis.instability, 'wholeInstability': whole.instability}
    diagnosis = LoadSideDiagnosis(stages, margin, wheelModes, lumpedStable, whole.stable, growing, **kinds)
    if not diagnosis.lumpingSafe:
        limit = diagnosis.limitFactor * diagnosis.frequencyHz
        cause = next((s.number for s in stages if s.frequencyHz < limit), None)
        diagnosis = LoadSideDiagnosis(stages, margin, wheelModes, lumpedStable, whole.stable, growing, cause, **kinds)
    return diagnosis
