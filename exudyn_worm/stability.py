"""Analytical stability of the elastic worm drive: eqs. (14)-(21) of the paper.

Everything here is computed from :class:`~exudyn_worm.drive.ElasticDrive` and the coefficients of
:meth:`~exudyn_worm.gear.WormGear.Coefficients`; no formula is repeated elsewhere.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Dict, Sequence

import numpy as np

from .drive import ElasticDrive

__all__ = ['PolynomialCoefficients', 'CharacteristicCoefficients', 'HurwitzConditions', 'HurwitzStable', 'LinearMatrices',
           'StateMatrix', 'EigenvaluesFromPolynomial', 'EigenvaluesFromStateMatrix', 'FuesgenLimit',
           'FirstCriterionLimit', 'ContactStability', 'StabilityAnalysis', 'AnalyzeStability']

CONTACT_STATES = (+1, -1)


def _CheckS(S):
    if S not in CONTACT_STATES:
        raise ValueError(f"stability: contact parameter 'S' must be +1 or -1, got {S!r}")


def PolynomialCoefficients(gear, S: int, J1, J2, kT, dT, dV=None) -> np.ndarray:
    """Coefficients b1..b4 of eq. (16) from the gear and the drive values; broadcasts over numpy arrays.

    The one implementation of eq. (16): :func:`CharacteristicCoefficients` (one drive) and the stability
    charts (:mod:`exudyn_worm.charts`, a whole grid at once) both call it.

    Parameters
    ----------
    gear : WormGear
        The mesh (geometry, friction, kV; its dV unless ``dV`` is given).
    S : int
        Contact parameter, +1 or -1 (eq. (8)).
    J1, J2 : float or ndarray
        Inertias in kg*m^2.
    kT : float or ndarray
        Shaft stiffness in N*m/rad.
    dT : float or ndarray
        Shaft damping in N*m*s/rad.
    dV : float or ndarray, optional
        Mesh damping in N*s/m (default ``gear.dV``).

    Returns
    -------
    ndarray
        Shape ``(4,) + broadcast shape`` of the arguments, in s^-1 .. s^-4.
    """
    _CheckS(S)
    c1, _, c3, _ = gear.Coefficients(S)
    u, kV = gear.ratio, gear.kV
    dV = gear.dV if dV is None else dV
    b1 = (dT + c1 * dV) / J1 + u * c3 * dV / J2
    b2 = (kT + c1 * kV) / J1 + u * c3 * kV / J2 + u * c3 * dT * dV / (J1 * J2)
    b3 = u * c3 * (dT * kV + dV * kT) / (J1 * J2)
    b4 = u * c3 * kT * kV / (J1 * J2)
    return np.array(np.broadcast_arrays(b1, b2, b3, b4), dtype=float)


def CharacteristicCoefficients(drive: ElasticDrive, S: int) -> np.ndarray:
    """Coefficients b1..b4 of the characteristic polynomial (15), eq. (16), in s^-1 .. s^-4.

    Parameters
    ----------
    drive : ElasticDrive
        The 2-DOF drive of Figure 2.
    S : int
        Contact parameter, +1 or -1 (eq. (8)).
    """
    return PolynomialCoefficients(drive.gear, S, drive.J1, drive.J2, drive.kT, drive.dT)


def HurwitzConditions(b: Sequence[float]) -> np.ndarray:
    """Left-hand sides of the Routh-Hurwitz conditions (17), (18), (19); all > 0 for stability.

    Parameters
    ----------
    b : array_like
        Coefficients b1..b4 of eq. (16), shape ``(4,)`` or ``(4, ...)``.

    Returns
    -------
    numpy.ndarray
        ``[b1, b1 b2 - b3, (b1 b2 - b3) b3 - b1^2 b4]``, shape ``(3,)`` or ``(3, ...)``.
    """
    b1, b2, b3, b4 = b
    return np.array([b1, b1 * b2 - b3, (b1 * b2 - b3) * b3 - b1**2 * b4])


def HurwitzStable(b: Sequence[float]):
    """Routh-Hurwitz classification of the quartic (15): b1, b3, b4 > 0 and (18), (19) > 0.

    Parameters
    ----------
    b : array_like
        Coefficients b1..b4 of eq. (16), shape ``(4,)`` or ``(4, ...)``.

    Returns
    -------
    bool or numpy.ndarray
        A bool for one polynomial; for ``b`` of shape ``(4, ...)`` a bool array of shape ``(...)``.
    """
    b = np.asarray(b, dtype=float)
    stable = (b[0] > 0) & (b[2] > 0) & (b[3] > 0) & np.all(HurwitzConditions(b) > 0, axis=0)
    return bool(stable) if b.ndim == 1 else stable


def LinearMatrices(drive: ElasticDrive, S: int):
    """Mass, damping and stiffness matrices (M, D, K) of the linear system (1)-(2) in [phi1, phi2].

    Parameters
    ----------
    drive : ElasticDrive
        The 2-DOF drive of Figure 2.
    S : int
        Contact parameter, +1 or -1 (eq. (8)).
    """
    _CheckS(S)
    g = drive.gear
    c1, _, c3, _ = g.Coefficients(S)
    u = g.ratio
    M = np.diag([drive.J1, drive.J2])
    D = np.array([[drive.dT + g.dV * c1, -g.dV * c1 * u], [-g.dV * c3, g.dV * c3 * u]])
    K = np.array([[drive.kT + g.kV * c1, -g.kV * c1 * u], [-g.kV * c3, g.kV * c3 * u]])
    return M, D, K


def StateMatrix(drive: ElasticDrive, S: int) -> np.ndarray:
    """First-order state matrix A of x = [phi1, phi2, phi1', phi2'], with x' = A x.

    Parameters
    ----------
    drive : ElasticDrive
        The 2-DOF drive of Figure 2.
    S : int
        Contact parameter, +1 or -1 (eq. (8)).
    """
    M, D, K = LinearMatrices(drive, S)
    Minv = np.linalg.inv(M)
    return np.block([[np.zeros((2, 2)), np.eye(2)], [-Minv @ K, -Minv @ D]])


def _SortEigenvalues(lam) -> np.ndarray:
    """Order as the paper does: conjugate pairs (+Im first), pairs by increasing |Im|, then real part."""
    lam = np.asarray(lam, dtype=complex)
    return lam[np.lexsort((-np.sign(lam.imag), lam.real, np.round(np.abs(lam.imag), 9)))]


def EigenvaluesFromPolynomial(b: Sequence[float]) -> np.ndarray:
    """The four roots of P(lambda) = lambda^4 + b1 lambda^3 + b2 lambda^2 + b3 lambda + b4, eq. (15).

    Parameters
    ----------
    b : array_like
        Coefficients b1..b4 of eq. (16), shape ``(4,)``.

    Returns
    -------
    numpy.ndarray
        The four (complex) roots in 1/s.
    """
    return _SortEigenvalues(np.roots(np.concatenate([[1.], np.asarray(b, dtype=float)])))


def EigenvaluesFromStateMatrix(drive: ElasticDrive, S: int) -> np.ndarray:
    """Eigenvalues of :func:`StateMatrix` (must agree with :func:`EigenvaluesFromPolynomial`).

    Parameters
    ----------
    drive : ElasticDrive
        The 2-DOF drive of Figure 2.
    S : int
        Contact parameter, +1 or -1 (eq. (8)).
    """
    return _SortEigenvalues(np.linalg.eigvals(StateMatrix(drive, S)))


def FuesgenLimit(drive: ElasticDrive) -> float:
    """Fuesgen / VDI 2158 limit of J1/J2, eq. (21): chatter is possible if J1/J2 is below it.

    Negative for a gear that is not self-locking (no chatter of this kind possible).

    Parameters
    ----------
    drive : ElasticDrive
        The 2-DOF drive of Figure 2.
    """
    g = drive.gear
    return math.tan(g.rho - g.gamma) / (g.ratio**2 * math.tan(g.gamma))


def FirstCriterionLimit(drive: ElasticDrive) -> float:
    """Limit of J1/J2 of the first instability condition (20) (b1 < 0 for S = -1).

    J1/J2 below this value makes b1 negative. ``-inf`` if dV = 0 (b1 is then always positive).

    Parameters
    ----------
    drive : ElasticDrive
        The 2-DOF drive of Figure 2.
    """
    g = drive.gear
    c1, _, c3, _ = g.Coefficients(-1)
    u = g.ratio
    if g.dV == 0:
        return -math.inf
    return -c1 / (u * c3) - drive.dT / (g.dV * u * c3)


def _Finite(x):
    """JSON has no inf/nan: non-finite values become None."""
    x = float(x)
    return x if math.isfinite(x) else None


@dataclass(frozen=True)
class ContactStability:
    """Linear stability for one contact state S: coefficients, Hurwitz values, eigenvalues.

    Build it with :meth:`FromCoefficients` (analytical) or :meth:`FromEigenvalues` (e.g. from an
    Exudyn linearization); the other quantities are derived the same way in both cases.

    Attributes
    ----------
    S : int
        Contact parameter, +1 or -1 (eq. (8)).
    b : numpy.ndarray
        Coefficients b1..b4 of the characteristic polynomial (15), eq. (16).
    eigenvalues : numpy.ndarray
        The four eigenvalues in 1/s.
    """
    S: int
    b: np.ndarray
    eigenvalues: np.ndarray

    @classmethod
    def FromCoefficients(cls, S: int, b) -> 'ContactStability':
        """From the coefficients b1..b4; eigenvalues are the polynomial roots."""
        b = np.asarray(b, dtype=float)
        return cls(S, b, EigenvaluesFromPolynomial(b))

    @classmethod
    def FromEigenvalues(cls, S: int, eigenvalues) -> 'ContactStability':
        """From four eigenvalues; b1..b4 are the coefficients of prod(lambda - lambda_i)."""
        lam = _SortEigenvalues(eigenvalues)
        if lam.size != 4:
            raise ValueError(f"ContactStability.FromEigenvalues: expected 4 eigenvalues, got {lam.size}")
        return cls(S, np.real(np.poly(lam))[1:], lam)

    @property
    def hurwitz(self) -> np.ndarray:
        """Left-hand sides of (17), (18), (19)."""
        return HurwitzConditions(self.b)

    @property
    def oscillating(self) -> np.ndarray:
        """The eigenvalue of each mode with Im >= 0, ordered by frequency (two modes)."""
        return self.eigenvalues[::2]

    @property
    def frequenciesHz(self) -> np.ndarray:
        """Damped natural frequencies f_i = omega_i / (2 pi) in Hz (section 3.1)."""
        return np.abs(self.oscillating.imag) / (2 * math.pi)

    @property
    def lehrDamping(self) -> np.ndarray:
        """Lehr damping D_i = -delta_i / omega_i as the paper defines it (section 3.1); negative: growing."""
        lam = self.oscillating
        with np.errstate(divide='ignore', invalid='ignore'):
            return np.where(lam.imag != 0, -lam.real / np.abs(lam.imag), np.inf * -np.sign(lam.real))

    @property
    def stable(self) -> bool:
        """True iff every eigenvalue has a negative real part."""
        return bool(np.all(self.eigenvalues.real < 0))

    @property
    def maxRealPart(self) -> float:
        """Largest real part of the eigenvalues in 1/s; > 0: unstable."""
        return float(np.max(self.eigenvalues.real))

    def ToDict(self) -> Dict:
        """JSON-ready dictionary (see the ``exudyn-worm stability --json`` schema)."""
        return {'b': [float(x) for x in self.b],
                'hurwitz': [float(x) for x in self.hurwitz],
                'eigenvalues': [[float(l.real), float(l.imag)] for l in self.eigenvalues],
                'frequenciesHz': [float(x) for x in self.frequenciesHz],
                'lehrDamping': [_Finite(x) for x in self.lehrDamping],
                'stable': self.stable}


@dataclass(frozen=True)
class StabilityAnalysis:
    """Stability of an elastic worm drive for both contact states, plus the classic criteria.

    Attributes
    ----------
    drive : ElasticDrive
        The drive analysed.
    contact : dict of int to ContactStability
        The result of each contact state, keyed by S = +1 and -1.
    """
    drive: ElasticDrive
    contact: Dict[int, ContactStability]

    @property
    def stable(self) -> bool:
        """Stable iff both contact states S = +1 and S = -1 are stable."""
        return all(c.stable for c in self.contact.values())

    def State(self, S: int) -> ContactStability:
        """The result for contact state ``S`` (+1 or -1): ``contact[S]``, under the name
        :meth:`~exudyn_worm.linearization.LinearStability.State` uses for the whole drive.

        Parameters
        ----------
        S : int
            Contact parameter, +1 or -1.

        Returns
        -------
        ContactStability
        """
        _CheckS(S)
        return self.contact[S]

    @property
    def fuesgenLimit(self) -> float:
        """J1/J2 limit of eq. (21)."""
        return FuesgenLimit(self.drive)

    @property
    def firstCriterionLimit(self) -> float:
        """J1/J2 limit of eq. (20)."""
        return FirstCriterionLimit(self.drive)

    def ToDict(self) -> Dict:
        """JSON-ready dictionary in the schema of ``exudyn-worm stability --json``."""
        g = self.drive.gear
        return {'ratio': g.ratio, 'frictionAngle': g.frictionAngle, 'selfLocking': g.selfLocking,
                'efficiency': {'wormDriving': g.efficiencyWormDriving, 'wheelDriving': g.efficiencyWheelDriving},
                'S': {f'{S:+d}': self.contact[S].ToDict() for S in CONTACT_STATES},
                'fuesgenLimit': _Finite(self.fuesgenLimit), 'firstCriterionLimit': _Finite(self.firstCriterionLimit),
                'stable': self.stable}


def AnalyzeStability(drive: ElasticDrive) -> StabilityAnalysis:
    """Analytical stability of ``drive`` for S = +1 and S = -1 from eqs. (15)-(16).

    Parameters
    ----------
    drive : ElasticDrive
        The 2-DOF drive of Figure 2.

    Returns
    -------
    StabilityAnalysis
        Coefficients, Hurwitz values, eigenvalues, frequencies, Lehr damping, the limits of (20)
        and (21) and the overall verdict.
    """
    if not isinstance(drive, ElasticDrive):
        raise TypeError(f"AnalyzeStability: 'drive' must be an ElasticDrive, got {type(drive).__name__}")
    return StabilityAnalysis(drive, {S: ContactStability.FromCoefficients(S, CharacteristicCoefficients(drive, S))
                                     for S in CONTACT_STATES})
