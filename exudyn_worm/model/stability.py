"""Analytical stability of the elastic worm drive: eqs. (14)-(21) of the paper.

Everything here is computed from :class:`~exudyn_worm.model.drive.ElasticDrive` and the coefficients of
:meth:`~exudyn_worm.model.gear.WormGear.Coefficients`; no formula is repeated elsewhere.

Speed-dependent friction (:mod:`exudyn_worm.model.friction`). Linearized at an :class:`OperatingPoint` (steady
lowering: sliding speed v0, mu0 = mu(v0), slope mu'(v0) = dmu/dv, static normal force Fn0), the coefficients
c1..c4 are taken at mu0 and the slope adds damping: the friction force on the flank is mu(v) Fn, and a change
of the worm speed changes v by r1/cos(gamma) per rad/s, so the worm torque -c2 sigma Fn and the wheel torque
c4 sigma Fn change with phi1' through mu (c2 = r1 (cos(alphaN) sin(gamma) + S mu cos(gamma)),
c4 = r2 (cos(alphaN) cos(gamma) - S mu sin(gamma)) for S = +-1, eqs. (10), (12) with (13)). With
sigma sign(phi1') = S this adds to the damping matrix of (1)-(2)

    e1 = Fn0 r1^2 mu'(v0)                 (worm row, phi1' column: D11 = dT + dV c1 + e1)
    e3 = Fn0 r1 r2 tan(gamma) mu'(v0)     (wheel row, phi1' column: D21 = -dV c3 + e3)

and to the coefficients of (16), with E = u (e1 c3 + e3 c1) / (J1 J2):
b1 += e1/J1, b2 += dV E, b3 += kV E (b4 unchanged). A friction that falls with speed (mu' < 0) gives
negative damping; load (Fn0) and speed (v0) now matter, which they do not with constant mu.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple

import numpy as np

from .drive import ElasticDrive
from .._checks import CheckNonNegative, CheckReal, JsonNumber
from .profiles import STANDARD_GRAVITY
from .selflocking import SelfLocking

__all__ = ['OperatingPoint', 'OperatingPointAt', 'OperatingPointFromParameters', 'FrictionSlopeDamping',
           'PolynomialCoefficients', 'CharacteristicCoefficients', 'HurwitzConditions', 'HurwitzStable',
           'LinearMatrices',
           'StateMatrix', 'EigenvaluesFromPolynomial', 'EigenvaluesFromStateMatrix', 'FuesgenLimit',
           'FirstCriterionLimit', 'ContactStability', 'StabilityAnalysis', 'AnalyzeStability', 'SortEigenvalues']

CONTACT_STATES = (+1, -1)


def _CheckS(S):
    if S not in CONTACT_STATES:
        raise ValueError(f"stability: contact parameter 'S' must be +1 or -1, got {S!r}")


@dataclass(frozen=True)
class OperatingPoint:
    """The steady state about which the drive is linearized (steady lowering at the motor speed).

    Attributes
    ----------
    slidingSpeed : float
        Sliding speed of the flanks ``v0 = r1 abs(phi1') / cos(gamma)`` in m/s.
    mu : float
        Friction coefficient mu(v0).
    dmuDv : float
        Slope dmu/dv of the friction law at v0 in s/m (0 for constant friction).
    normalForce : float
        Static normal force Fn0 in the mesh in N, >= 0.
    S : int
        Contact state of the steady motion, eq. (8): +1 while the worm drives the load (lifting), -1 while the load
        drives the gear (lowering, the default).
    """
    slidingSpeed: float
    mu: float
    dmuDv: float
    normalForce: float
    S: int = -1

    def __post_init__(self):
        w = 'OperatingPoint'
        object.__setattr__(self, 'slidingSpeed', CheckNonNegative(w, 'slidingSpeed', self.slidingSpeed, 'm/s'))
        object.__setattr__(self, 'mu', CheckNonNegative(w, 'mu', self.mu, ''))
        object.__setattr__(self, 'dmuDv', CheckReal(w, 'dmuDv', self.dmuDv, 's/m'))
        object.__setattr__(self, 'normalForce', CheckNonNegative(w, 'normalForce', self.normalForce, 'N'))
        _CheckS(self.S)

    def ToDict(self) -> Dict:
        """JSON-ready ``{slidingSpeed, mu, dmuDv, normalForce, S}`` (SI)."""
        return {'slidingSpeed': self.slidingSpeed, 'mu': self.mu, 'dmuDv': self.dmuDv, 'normalForce': self.normalForce,
                'S': self.S}


def OperatingPointAt(gear: 'WormGear', motorSpeed: float, loadTorque: float, S: int = -1) -> OperatingPoint:
    """Operating point of steady motion: worm speed ``motorSpeed``, wheel torque ``loadTorque``, contact state ``S``
    (-1, the default: lowering; +1: lifting).

    ``v0 = r1 abs(motorSpeed) / cos(gamma)``; mu0, slope from the gear's friction law; the static normal force follows
    from the wheel's balance c4(S, mu0) Fn0 = loadTorque (eq. (12); mesh damping does not act at steady
    speed).

    Parameters
    ----------
    gear : WormGear
        The mesh and its friction law.
    motorSpeed : float
        Worm speed in rad/s (the motor's, through the stiff shaft).
    loadTorque : float
        Magnitude of the load torque on the wheel in N*m, >= 0 (loadMass * g * leverArm for the reel changer).
    S : int, optional
        Contact state of the steady motion, +1 (lifting) or -1 (lowering).

    Returns
    -------
    OperatingPoint
    """
    w = 'OperatingPointAt'
    motorSpeed = CheckReal(w, 'motorSpeed', motorSpeed, 'rad/s')
    loadTorque = CheckNonNegative(w, 'loadTorque', loadTorque, 'N*m')
    _CheckS(S)
    v0 = gear.SlidingSpeed(motorSpeed)
    law = gear.frictionLaw
    mu0 = float(law.Mu(v0))
    _, _, _, c4 = gear.Coefficients(S, mu=mu0 if gear.speedDependentFriction else None)
    return OperatingPoint(slidingSpeed=v0, mu=mu0, dmuDv=float(law.Slope(v0)), normalForce=loadTorque / c4, S=S)


def OperatingPointFromParameters(parameters: Mapping[str, Any], gear: 'WormGear') -> Optional[OperatingPoint]:
    """:func:`OperatingPointAt` with ``motorSpeed`` and the load torque ``loadMass * g * leverArm`` of a flat
    parameter set; None if one of these keys is missing (no load or speed given).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set (see :mod:`exudyn_worm.drive.presets`).
    gear : WormGear
        The mesh built from it.

    Returns
    -------
    OperatingPoint or None
    """
    if any(k not in parameters for k in ('loadMass', 'leverArm', 'motorSpeed')):
        return None
    return OperatingPointAt(gear, parameters['motorSpeed'],
                            parameters['loadMass'] * STANDARD_GRAVITY * parameters['leverArm'])


def FrictionSlopeDamping(gear: 'WormGear', operatingPoint: OperatingPoint) -> Tuple[float, float]:
    """Damping (e1, e3) in N*m*s/rad that the friction slope adds to the worm row and to the wheel row (worm
    speed column) of the linearized eqs. (1)-(2): e1 = Fn0 r1^2 mu', e3 = Fn0 r1 r2 tan(gamma) mu' (module text).

    Parameters
    ----------
    gear : WormGear
        The mesh.
    operatingPoint : OperatingPoint
        Normal force and slope dmu/dv at the operating point.
    """
    k = operatingPoint.normalForce * operatingPoint.dmuDv * gear.r1
    return k * gear.r1, k * gear.r2 * math.tan(gear.gamma)


def _MuAt(gear, operatingPoint):
    """Friction coefficient for the coefficients c_k: None (the gear's own mu, exactly as always) unless an
    operating point gives another one."""
    return None if operatingPoint is None or operatingPoint.mu == gear.mu else operatingPoint.mu


def PolynomialCoefficients(gear, S: int, J1, J2, kT, dT, dV=None,
                           operatingPoint: Optional[OperatingPoint] = None) -> np.ndarray:
    """Coefficients b1..b4 of eq. (16) from the gear and the drive values; broadcasts over numpy arrays.

    The one implementation of eq. (16): :func:`CharacteristicCoefficients` (one drive) and the stability
    charts (:mod:`exudyn_worm.analysis.charts.stabilitychart`, a whole grid at once) both call it.

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
    operatingPoint : OperatingPoint, optional
        Linearize at this point: c1..c4 at its mu, plus the damping of its friction slope (module text).
        None (default): the paper's eq. (16) with the gear's constant mu.

    Returns
    -------
    ndarray
        Shape ``(4,) + broadcast shape`` of the arguments, in s^-1 .. s^-4.
    """
    _CheckS(S)
    c1, _, c3, _ = gear.Coefficients(S, mu=_MuAt(gear, operatingPoint))
    u, kV = gear.ratio, gear.kV
    dV = gear.dV if dV is None else dV
    b1 = (dT + c1 * dV) / J1 + u * c3 * dV / J2
    b2 = (kT + c1 * kV) / J1 + u * c3 * kV / J2 + u * c3 * dT * dV / (J1 * J2)
    b3 = u * c3 * (dT * kV + dV * kT) / (J1 * J2)
    b4 = u * c3 * kT * kV / (J1 * J2)
    if operatingPoint is not None and operatingPoint.dmuDv != 0:    # the friction slope's damping
        e1, e3 = FrictionSlopeDamping(gear, operatingPoint)
        E = u * (e1 * c3 + e3 * c1) / (J1 * J2)
        b1, b2, b3 = b1 + e1 / J1, b2 + dV * E, b3 + kV * E
    return np.array(np.broadcast_arrays(b1, b2, b3, b4), dtype=float)


def CharacteristicCoefficients(drive: ElasticDrive, S: int, operatingPoint: Optional[OperatingPoint] = None
                               ) -> np.ndarray:
    """Coefficients b1..b4 of the characteristic polynomial (15), eq. (16), in s^-1 .. s^-4.

    Parameters
    ----------
    drive : ElasticDrive
        The 2-DOF drive of Figure 2.
    S : int
        Contact parameter, +1 or -1 (eq. (8)).
    operatingPoint : OperatingPoint, optional
        Linearize at this point (speed-dependent friction); None: constant mu.
    """
    return PolynomialCoefficients(drive.gear, S, drive.J1, drive.J2, drive.kT, drive.dT,
                                  operatingPoint=operatingPoint)


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


def LinearMatrices(drive: ElasticDrive, S: int, operatingPoint: Optional[OperatingPoint] = None):
    """Mass, damping and stiffness matrices (M, D, K) of the linear system (1)-(2) in [phi1, phi2].

    Parameters
    ----------
    drive : ElasticDrive
        The 2-DOF drive of Figure 2.
    S : int
        Contact parameter, +1 or -1 (eq. (8)).
    operatingPoint : OperatingPoint, optional
        Linearize at this point: c_k at its mu, the friction slope's damping e1, e3 in D (module text).
    """
    _CheckS(S)
    g = drive.gear
    c1, _, c3, _ = g.Coefficients(S, mu=_MuAt(g, operatingPoint))
    u = g.ratio
    e1, e3 = (0., 0.) if operatingPoint is None else FrictionSlopeDamping(g, operatingPoint)
    M = np.diag([drive.J1, drive.J2])
    D = np.array([[drive.dT + g.dV * c1 + e1, -g.dV * c1 * u], [-g.dV * c3 + e3, g.dV * c3 * u]])
    K = np.array([[drive.kT + g.kV * c1, -g.kV * c1 * u], [-g.kV * c3, g.kV * c3 * u]])
    return M, D, K


def StateMatrix(drive: ElasticDrive, S: int, operatingPoint: Optional[OperatingPoint] = None) -> np.ndarray:
    """First-order state matrix A of x = [phi1, phi2, phi1', phi2'], with x' = A x.

    Parameters
    ----------
    drive : ElasticDrive
        The 2-DOF drive of Figure 2.
    S : int
        Contact parameter, +1 or -1 (eq. (8)).
    operatingPoint : OperatingPoint, optional
        Linearize at this point (speed-dependent friction); None: constant mu.
    """
    M, D, K = LinearMatrices(drive, S, operatingPoint)
    Minv = np.linalg.inv(M)
    return np.block([[np.zeros((2, 2)), np.eye(2)], [-Minv @ K, -Minv @ D]])


def SortEigenvalues(lam: Sequence[complex]) -> np.ndarray:
    """Eigenvalues in the paper's order: conjugate pairs (+Im first), pairs by increasing ``|Im|``, then real part.

    Parameters
    ----------
    lam : array_like of complex
        Eigenvalues in any order.

    Returns
    -------
    ndarray of complex
    """
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
    return SortEigenvalues(np.roots(np.concatenate([[1.], np.asarray(b, dtype=float)])))


def EigenvaluesFromStateMatrix(drive: ElasticDrive, S: int, operatingPoint: Optional[OperatingPoint] = None
                               ) -> np.ndarray:
    """Eigenvalues of :func:`StateMatrix` (must agree with :func:`EigenvaluesFromPolynomial`).

    Parameters
    ----------
    drive : ElasticDrive
        The 2-DOF drive of Figure 2.
    S : int
        Contact parameter, +1 or -1 (eq. (8)).
    operatingPoint : OperatingPoint, optional
        Linearize at this point (speed-dependent friction); None: constant mu.
    """
    return SortEigenvalues(np.linalg.eigvals(StateMatrix(drive, S, operatingPoint)))


def FuesgenLimit(drive: ElasticDrive, operatingPoint: Optional[OperatingPoint] = None) -> float:
    """Fuesgen / VDI 2158 limit of J1/J2, eq. (21): chatter is possible if J1/J2 is below it.

    Negative for a gear that is not self-locking (no chatter of this kind possible).

    Parameters
    ----------
    drive : ElasticDrive
        The 2-DOF drive of Figure 2.
    operatingPoint : OperatingPoint, optional
        Evaluate at its friction coefficient mu(v0) (the classic criterion knows no slope); None: the gear's mu.
    """
    g = drive.gear
    mu = _MuAt(g, operatingPoint)
    rho = g.rho if mu is None else math.atan(mu / math.cos(g.alphaN))
    return math.tan(rho - g.gamma) / (g.ratio**2 * math.tan(g.gamma))


def FirstCriterionLimit(drive: ElasticDrive, operatingPoint: Optional[OperatingPoint] = None) -> float:
    """Limit of J1/J2 of the first instability condition (20) (b1 < 0 for S = -1).

    J1/J2 below this value makes b1 negative. ``-inf`` if dV = 0 (b1 is then always positive).

    Parameters
    ----------
    drive : ElasticDrive
        The 2-DOF drive of Figure 2.
    operatingPoint : OperatingPoint, optional
        Linearize at this point: c_k at its mu, and the friction slope's damping e1 adds to dT in (20).
    """
    g = drive.gear
    c1, _, c3, _ = g.Coefficients(-1, mu=_MuAt(g, operatingPoint))
    u = g.ratio
    if g.dV == 0:
        return -math.inf
    dT = drive.dT if operatingPoint is None or operatingPoint.dmuDv == 0 else \
        drive.dT + FrictionSlopeDamping(g, operatingPoint)[0]
    return -c1 / (u * c3) - dT / (g.dV * u * c3)


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
        lam = SortEigenvalues(eigenvalues)
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
                'lehrDamping': [JsonNumber(x) for x in self.lehrDamping],
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
    operatingPoint : OperatingPoint or None
        The point the drive was linearized about (None: constant mu, the paper's model).
    """
    drive: ElasticDrive
    contact: Dict[int, ContactStability]
    operatingPoint: Optional[OperatingPoint] = None

    @property
    def stable(self) -> bool:
        """Stable iff both contact states S = +1 and S = -1 are stable."""
        return all(c.stable for c in self.contact.values())

    def State(self, S: int) -> ContactStability:
        """The result for contact state ``S`` (+1 or -1): ``contact[S]``, under the name
        :meth:`~exudyn_worm.analysis.stability.linearization.LinearStability.State` uses for the whole drive.

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
        """J1/J2 limit of eq. (21) (at the operating point's mu, if any)."""
        return FuesgenLimit(self.drive, self.operatingPoint)

    @property
    def firstCriterionLimit(self) -> float:
        """J1/J2 limit of eq. (20) (at the operating point, if any)."""
        return FirstCriterionLimit(self.drive, self.operatingPoint)

    @property
    def selfLockingVerdict(self):
        """Static and dynamic self-locking (:func:`~exudyn_worm.model.selflocking.SelfLocking`), the dynamic one at the
        operating point's sliding speed."""
        return SelfLocking(self.drive.gear, None if self.operatingPoint is None else self.operatingPoint.slidingSpeed)

    def plot(self, title: Optional[str] = None, ax=None):
        """Draw the eigenvalues of both contact states as growth rate against frequency
        (:func:`exudyn_worm.plotting.plot_stability.PlotEigenvalues`); returns the axes.

        Parameters
        ----------
        title : str, optional
            Title of the axes.
        ax : matplotlib.axes.Axes, optional
            Draw into this axes.
        """
        from ..plotting.plot_stability import PlotEigenvalues
        groups = {f'S = {S:+d}': self.contact[S].eigenvalues for S in CONTACT_STATES}
        S = max(CONTACT_STATES, key=lambda s: self.contact[s].maxRealPart)
        lam = np.asarray(self.contact[S].eigenvalues)
        return PlotEigenvalues(groups, (f'S = {S:+d}', complex(lam[int(np.argmax(lam.real))])), title, ax)

    def ToDict(self) -> Dict:
        """JSON-ready dictionary in the schema of ``exudyn-worm stability --json``."""
        g = self.drive.gear
        return {'ratio': g.ratio, 'frictionAngle': g.frictionAngle, 'selfLocking': g.selfLocking,
                'efficiency': {'wormDriving': g.efficiencyWormDriving, 'wheelDriving': g.efficiencyWheelDriving},
                'S': {f'{S:+d}': self.contact[S].ToDict() for S in CONTACT_STATES},
                'fuesgenLimit': JsonNumber(self.fuesgenLimit), 'firstCriterionLimit': JsonNumber(self.firstCriterionLimit),
                'stable': self.stable,
                'friction': g.frictionLaw.ToDict(),
                'selfLockingVerdict': self.selfLockingVerdict.ToDict(),
                'operatingPoint': None if self.operatingPoint is None else self.operatingPoint.ToDict()}


def AnalyzeStability(drive: ElasticDrive, operatingPoint: Optional[OperatingPoint] = None) -> StabilityAnalysis:
    """Analytical stability of ``drive`` for S = +1 and S = -1 from eqs. (15)-(16).

    Parameters
    ----------
    drive : ElasticDrive
        The 2-DOF drive of Figure 2.
    operatingPoint : OperatingPoint, optional
        Linearize about this point (:func:`OperatingPointAt`; speed-dependent friction: mu(v0) and the slope's
        damping, for both contact states). None (default): the paper's constant-mu model.

    Returns
    -------
    StabilityAnalysis
        Coefficients, Hurwitz values, eigenvalues, frequencies, Lehr damping, the limits of (20)
        and (21) and the overall verdict.
    """
    if not isinstance(drive, ElasticDrive):
        raise TypeError(f"AnalyzeStability: 'drive' must be an ElasticDrive, got {type(drive).__name__}")
    if operatingPoint is not None and not isinstance(operatingPoint, OperatingPoint):
        raise TypeError(f"AnalyzeStability: 'operatingPoint' must be an OperatingPoint or None, got "
                        f"{type(operatingPoint).__name__}")
    return StabilityAnalysis(drive, {S: ContactStability.FromCoefficients(
        S, CharacteristicCoefficients(drive, S, operatingPoint)) for S in CONTACT_STATES}, operatingPoint)
