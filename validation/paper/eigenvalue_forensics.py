"""Eigenvalue forensics for section 3.1 of the paper (reel changer, parameter set (28)).

The paper prints b1..b4 and the value of (19) for S = -1, and then eight eigenvalues (S = +1 and
S = -1). The b-coefficients follow from eq. (16) with the printed parameters, but the printed
eigenvalues are *not* the roots of that polynomial (they differ by up to 12 1/s). This script
finds out what the eigenvalue computation must have used.

Everything is computed with the package (:mod:`exudyn_worm`), except the reduced parametrization
of eq. (16) used for the model-class fits (:func:`ReducedCoefficients`, checked against the package
in ``tests/test_validation.py``)::

    b1 = a tauT + eta (x + y)        a = kT/J1, tauT = dT/kT, eta = dV/kV
    b2 = a + x + y + a tauT eta y    x = c1 kV/J1, y = u c3 kV/J2 (per S)
    b3 = a y (tauT + eta)
    b4 = a y

Findings (reproduced by ``python -m validation.paper.eigenvalue_forensics``):

* The best physical explanation is a mesh stiffness and damping referred to the wheel
  circumference (the worm's axial direction) instead of the tooth normal: every mesh term is
  larger by ``1/(cos(alphaN) cos(gamma))^2 = 1.1423``. It reproduces all eight printed eigenvalues
  to within 0.11 1/s (about one unit of the printed digit) with no fitted parameter; a fit of the
  scale factor and of rho on top of it lands on 1.0000 and 8.00 deg. It also predicts the P7
  natural frequencies of section 3.2.3 (21 and 81 Hz, the paper model gives 21.0 and 77.2 Hz).
* No parameter set of the paper's model (any J1, J2, kT, kV, dT, dV, r1, r2, u, alphaN, rho with
  gamma = 5.3228 deg) reproduces all eight printed eigenvalues within their rounding (+-0.05 1/s):
  the best possible max deviation is 0.061 1/s. The S-dependence is what fails: the ratio
  b4(S=-1)/b4(S=+1) = cos(gamma - rho)/cos(gamma + rho) of the printed eigenvalues needs
  rho <= 7.92 deg, the worm-side term needs rho >= 7.97 deg.
* A free 7-parameter family (a, tauT, eta, x+, y+, x-, y-) fits within rounding; its best point is
  the wheel-circumference model with mesh terms changed by < 0.5 % and dT/dV split differently.
"""
from __future__ import annotations

import csv
import math
import sys
from dataclasses import dataclass, field
from itertools import product
from pathlib import Path
from typing import Callable, Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np

from exudyn_worm.model.drive import ElasticDrive
from exudyn_worm.drive.presets import ApplyOverrides, ElasticDriveFromParameters, GetPreset
from exudyn_worm.model.stability import CharacteristicCoefficients, ContactStability, EigenvaluesFromPolynomial

# the friction coefficient the printed b1..b4 and (19) were computed with (see validation/REPORT.md)
from ..runner import PAPER_MU

__all__ = ['REFERENCE_CSV', 'PRINTED_DIGIT', 'HALF_DIGIT', 'PAPER_MU', 'EIGENVALUE_ROWS', 'PrintedEigenvalues',
           'BaseParameters', 'P7Parameters', 'WheelCircumferenceFactor', 'ScaleMesh', 'UpperEigenvalues',
           'EigenvalueDeviations', 'DriveDeviations', 'Hypothesis', 'HypothesisResult', 'Hypotheses',
           'EvaluateHypothesis', 'EvaluateHypotheses', 'ReducedCoefficients', 'ReducedParameters',
           'ImpliedCoefficients', 'B4RatioInterval', 'WheelSideFrictionBound', 'FitResult',
           'ModelClassMinimax', 'FreeFamilyMinimax', 'GlobalModelClassSearch', 'HypothesisTable', 'Main']

#: the reference data beside this script
REFERENCE_CSV = Path(__file__).with_name('reference.csv')
#: last printed digit of the eigenvalues of section 3.1, in 1/s
PRINTED_DIGIT = 0.1
#: rounding half-width of the printed eigenvalues, in 1/s
HALF_DIGIT = 0.5 * PRINTED_DIGIT

#: reference.csv ids of the printed eigenvalues: S -> ((Re, Im) of lambda_1/2, (Re, Im) of lambda_3/4)
EIGENVALUE_ROWS = {+1: (('lam1_re_Sp', 'lam1_im_Sp'), ('lam2_re_Sp', 'lam2_im_Sp')),
                   -1: (('lam1_re_Sm', 'lam1_im_Sm'), ('lam2_re_Sm', 'lam2_im_Sm'))}

_LARGE = 1e3  # deviation reported when a model has no two oscillating modes


def PrintedEigenvalues(path: Path = REFERENCE_CSV) -> Dict[int, np.ndarray]:
    """The printed eigenvalues of section 3.1 read from ``reference.csv``.

    Parameters
    ----------
    path : Path, optional
        The reference table.

    Returns
    -------
    dict
        ``{S: array of the two eigenvalues with Im > 0}`` for S = +1 and S = -1, in 1/s.
    """
    with open(path, newline='') as f:
        wanted = {i for pairs in EIGENVALUE_ROWS.values() for pair in pairs for i in pair}
        rows = {r['id']: float(r['published']) for r in csv.DictReader(f) if r['id'] in wanted}
    return {S: np.array([complex(rows[re], rows[im]) for re, im in pairs]) for S, pairs in EIGENVALUE_ROWS.items()}


def BaseParameters(**overrides) -> Dict[str, float]:
    """Parameter set (28) as the paper computed it: preset ``reel-P1`` with mu = 0.132.

    ``overrides`` are applied with :func:`exudyn_worm.drive.presets.ApplyOverrides`.
    """
    return ApplyOverrides(GetPreset('reel-P1'), {'mu': PAPER_MU, **overrides})


def P7Parameters(**overrides) -> Dict[str, float]:
    """Parameter set P7 of section 3.2.3 (J1 and kT ten times smaller than (28)), mu = 0.132; ``overrides`` are
    applied with :func:`exudyn_worm.drive.presets.ApplyOverrides`."""
    return ApplyOverrides(GetPreset('reel-P7'), {'mu': PAPER_MU, **overrides})


def WheelCircumferenceFactor(drive) -> float:
    """Factor 1/(cos(alphaN) cos(gamma))^2 between a mesh spring acting along the wheel circumference
    (the worm axis) and one acting along the tooth normal, for the same spring constant.

    Parameters
    ----------
    drive : ElasticDrive or WormGear
        The drive (or its gear).
    """
    return 1. / getattr(drive, 'gear', drive).axialLever**2


def ScaleMesh(drive: ElasticDrive, stiffnessFactor: float, dampingFactor: Optional[float] = None) -> ElasticDrive:
    """Copy of ``drive`` with kV scaled by ``stiffnessFactor`` and dV by ``dampingFactor`` (default the same factor)."""
    dampingFactor = stiffnessFactor if dampingFactor is None else dampingFactor
    g = drive.gear
    return drive.Replace(gear=g.Replace(kV=g.kV * stiffnessFactor, dV=g.dV * dampingFactor))


def UpperEigenvalues(b: Sequence[float]) -> np.ndarray:
    """The eigenvalues with Im > 0 of the quartic (15) with coefficients ``b``, by increasing Im."""
    lam = EigenvaluesFromPolynomial(b)
    lam = lam[lam.imag > 0]
    return lam[np.argsort(lam.imag)]


def EigenvalueDeviations(eigenvalues: Mapping[int, np.ndarray], printed: Mapping[int, np.ndarray]) -> np.ndarray:
    """Signed deviations of ``eigenvalues`` from ``printed`` (both ``{S: two eigenvalues with Im > 0}``),
    ``[Re1, Im1, Re2, Im2]`` for S = +1 then S = -1 (8 values).

    Within each S the two computed modes are paired with the printed ones in the order that
    minimizes the total distance. A model without two oscillating modes gets deviations of 1e3.
    """
    out = []
    for S in (+1, -1):
        lam, pub = np.asarray(eigenvalues[S]), np.asarray(printed[S])
        if lam.size != 2:
            out += [_LARGE] * 4
            continue
        if abs(lam[0] - pub[0]) + abs(lam[1] - pub[1]) > abs(lam[1] - pub[0]) + abs(lam[0] - pub[1]):
            lam = lam[::-1]
        for z in lam - pub:
            out += [z.real, z.imag]
    return np.array(out)


def DriveDeviations(drive: ElasticDrive, printed: Mapping[int, np.ndarray]) -> np.ndarray:
    """:func:`EigenvalueDeviations` of ``drive`` from ``printed``, eigenvalues from the package's eq. (16)."""
    return EigenvalueDeviations({S: UpperEigenvalues(CharacteristicCoefficients(drive, S)) for S in (+1, -1)},
                                printed)


# --- hypotheses ----------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Hypothesis:
    """One explanation of the printed eigenvalues.

    ``build(parameters, value)`` returns the drive for a parameter dictionary (set (28) or P7) and,
    for a fitted hypothesis, the value of its free parameter ``fitted`` searched in ``bounds``.
    """
    key: str
    description: str
    build: Callable[[Dict[str, float], Optional[float]], ElasticDrive]
    fitted: Optional[str] = None
    bounds: Tuple[float, float] = (0.7, 1.5)


@dataclass(frozen=True)
class HypothesisResult:
    """Outcome of :func:`EvaluateHypothesis`."""
    hypothesis: Hypothesis
    value: Optional[float]
    deviations: np.ndarray
    p7FrequenciesHz: np.ndarray

    @property
    def maxDeviation(self) -> float:
        """Largest |computed - printed| over the 8 eigenvalue components, 1/s."""
        return float(np.max(np.abs(self.deviations)))

    @property
    def digits(self) -> float:
        """:attr:`maxDeviation` in units of the printed digit (0.1 1/s)."""
        return self.maxDeviation / PRINTED_DIGIT

    @property
    def withinRounding(self) -> bool:
        """True if all 8 components are within +-0.05 1/s."""
        return self.maxDeviation <= HALF_DIGIT


def _Drive(parameters, **overrides) -> ElasticDrive:
    return ElasticDriveFromParameters(ApplyOverrides(parameters, overrides))


def _KeepDamping(parameters, **overrides) -> ElasticDrive:
    """Drive with ``overrides`` but the damping coefficients dT, dV of ``parameters`` unchanged."""
    d = ElasticDriveFromParameters(parameters)
    return _Drive(parameters, **{'dT': d.dT, 'dV': d.gear.dV, **overrides})


def _Circ(drive: ElasticDrive, damping: bool = True) -> ElasticDrive:
    k = WheelCircumferenceFactor(drive)
    return ScaleMesh(drive, k, k if damping else 1.)


def _cosA(p) -> float:
    return math.cos(p['alphaN'])


def Hypotheses() -> List[Hypothesis]:
    """The hypotheses examined, in the order of the report table."""
    atan134 = math.atan(0.134)
    H = Hypothesis
    return [
        H('paper', 'eq. (16), set (28) with mu = 0.132 (reproduces the printed b1..b4 and (19))',
          lambda p, v: _Drive(p)),
        H('rho-8', 'rho = 8.000 deg exactly', lambda p, v: _Drive(p, rho=math.radians(8))),
        H('mu-0.134', 'mu = 0.134 as printed in (28), rho = 8.116 deg via (13)', lambda p, v: _Drive(p, mu=0.134)),
        H('rho-atan0.134', 'rho = atan(0.134) = 7.63 deg ((13) evaluated with alphaN = 0)',
          lambda p, v: _Drive(p, rho=atan134)),
        H('printed-damping', 'dT = 0.741 N*m*s, dV = 21470 N*s/m as printed (not from D_T, D_V)',
          lambda p, v: _Drive(p, dT=0.741, dV=21470.)),
        H('cosA-once', 'one cos(alphaN) dropped from (9), (11): kV, dV / cos(alphaN)',
          lambda p, v: ScaleMesh(_Drive(p), 1 / _cosA(p))),
        H('cosA-twice', 'cos^2(alphaN) dropped from (9), (11) (mesh stiffness tangential, not normal)',
          lambda p, v: ScaleMesh(_Drive(p), 1 / _cosA(p)**2)),
        H('alphaN-0', 'alphaN = 0 in (9)-(13) with mu = 0.134 (cos^2 dropped and rho = atan(0.134))',
          lambda p, v: ScaleMesh(_Drive(p, rho=atan134), 1 / _cosA(p)**2)),
        H('circ', 'kV, dV along the wheel circumference: mesh terms x 1/(cos(alphaN) cos(gamma))^2 = 1.1423',
          lambda p, v: _Circ(_Drive(p))),
        H('circ-stiffness-only', 'as circ, but dV in the normal direction (only kV scaled)',
          lambda p, v: _Circ(_Drive(p), damping=False)),
        H('circ+rho-8', 'circ with rho = 8.000 deg', lambda p, v: _Circ(_Drive(p, rho=math.radians(8)))),
        H('circ+mu-0.134', 'circ with mu = 0.134 via (13)', lambda p, v: _Circ(_Drive(p, mu=0.134))),
        H('circ+rho-atan0.134', 'circ with rho = atan(0.134)', lambda p, v: _Circ(_Drive(p, rho=atan134))),
        H('circ+printed-damping', 'circ with dT = 0.741, dV = 21470 as printed',
          lambda p, v: _Circ(_Drive(p, dT=0.741, dV=21470.))),
        H('fit-mesh', 'kV, dV x s, s fitted (e.g. stiffness per face width, any uniform convention)',
          lambda p, v: ScaleMesh(_Drive(p), v), fitted='s'),
        H('fit-J1', 'J1 x s, s fitted (dT kept)', lambda p, v: _KeepDamping(p, J1=p['J1'] * v), fitted='s'),
        H('fit-J2', 'J2 x s, s fitted (dV kept)', lambda p, v: _KeepDamping(p, J2=p['J2'] * v), fitted='s'),
        H('fit-kT', 'kT x s, s fitted (dT kept)', lambda p, v: _KeepDamping(p, kT=p['kT'] * v), fitted='s'),
        H('circ+fit-mesh', 'circ, then kV, dV x s, s fitted', lambda p, v: ScaleMesh(_Circ(_Drive(p)), v),
          fitted='s', bounds=(0.9, 1.1)),
        H('circ+fit-rho', 'circ with rho fitted (deg)', lambda p, v: _Circ(_Drive(p, rho=math.radians(v))),
          fitted='rho/deg', bounds=(7.0, 9.0)),
        H('circ+fit-dT', 'circ with dT x s, s fitted', lambda p, v: _Circ(_KeepDamping(p, dT=ElasticDriveFromParameters(p).dT * v)),
          fitted='s', bounds=(0.5, 1.5)),
        H('circ+fit-dV', 'circ with dV x s, s fitted',
          lambda p, v: _Circ(_KeepDamping(p, dV=ElasticDriveFromParameters(p).gear.dV * v)), fitted='s', bounds=(0.5, 1.5)),
    ]


def _FitScalar(objective: Callable[[float], float], bounds: Tuple[float, float]) -> float:
    """Minimize a non-smooth 1-D objective: grid, then bounded Brent around the best grid point."""
    from scipy.optimize import minimize_scalar
    grid = np.linspace(bounds[0], bounds[1], 201)
    values = np.array([objective(v) for v in grid])
    i = int(np.argmin(values))
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
    res = minimize_scalar(objective, bounds=(lo, hi), method='bounded', options={'xatol': 1e-10})
    return float(res.x) if res.fun <= values[i] else float(grid[i])


def _P7Frequencies(drive: ElasticDrive) -> np.ndarray:
    return ContactStability.FromCoefficients(+1, CharacteristicCoefficients(drive, +1)).frequenciesHz


def EvaluateHypothesis(hypothesis: Hypothesis, printed: Optional[Mapping[int, np.ndarray]] = None) -> HypothesisResult:
    """Deviations of one hypothesis from the printed eigenvalues (its free parameter fitted to them
    by minimizing the largest deviation) and its prediction of the P7 natural frequencies (S = +1)."""
    printed = PrintedEigenvalues() if printed is None else printed
    base = BaseParameters()
    value = None
    if hypothesis.fitted:
        value = _FitScalar(lambda v: float(np.max(np.abs(DriveDeviations(hypothesis.build(base, v), printed)))),
                           hypothesis.bounds)
    dev = DriveDeviations(hypothesis.build(base, value), printed)
    return HypothesisResult(hypothesis, value, dev, _P7Frequencies(hypothesis.build(P7Parameters(), value)))


def EvaluateHypotheses(fitted: bool = True, printed: Optional[Mapping[int, np.ndarray]] = None) -> List[HypothesisResult]:
    """:func:`EvaluateHypothesis` for every hypothesis against ``printed`` (default: the reference table;
    ``fitted=False`` skips the fitted ones)."""
    printed = PrintedEigenvalues() if printed is None else printed
    return [EvaluateHypothesis(h, printed) for h in Hypotheses() if fitted or not h.fitted]


# --- the model class of eq. (16) in reduced parameters ---------------------------------------------

def ReducedCoefficients(a: float, tauT: float, eta: float, x: float, y: float) -> np.ndarray:
    """b1..b4 of eq. (16) written in a = kT/J1, tauT = dT/kT, eta = dV/kV, x = c1 kV/J1, y = u c3 kV/J2."""
    return np.array([a * tauT + eta * (x + y), a + x + y + a * tauT * eta * y, a * y * (tauT + eta), a * y])


def ReducedParameters(drive: ElasticDrive) -> Dict[str, float]:
    """a, tauT, eta and x, y for S = +1 and S = -1 of ``drive`` (keys ``x+ y+ x- y-``)."""
    g = drive.gear
    out = {'a': drive.kT / drive.J1, 'tauT': drive.dT / drive.kT, 'eta': g.dV / g.kV}
    for S, s in ((+1, '+'), (-1, '-')):
        c1, _, c3, _ = g.Coefficients(S)
        out['x' + s] = c1 * g.kV / drive.J1
        out['y' + s] = g.ratio * c3 * g.kV / drive.J2
    return out


def ImpliedCoefficients(printed: Mapping[int, np.ndarray], S: int) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """b1..b4 of the printed eigenvalues of contact state ``S`` (nominal) and their range over the rounding box
    (+-0.05 1/s).

    Each b is monotonic in every eigenvalue component over the box, so the range is attained at
    its corners.
    """
    lam = np.asarray(printed[S])
    nominal = ContactStability.FromEigenvalues(S, np.r_[lam, lam.conj()]).b
    corners = []
    for s in product((-HALF_DIGIT, HALF_DIGIT), repeat=4):
        l = lam + np.array([s[0] + 1j * s[1], s[2] + 1j * s[3]])
        corners.append(ContactStability.FromEigenvalues(S, np.r_[l, l.conj()]).b)
    corners = np.array(corners)
    return nominal, corners.min(axis=0), corners.max(axis=0)


def B4RatioInterval(printed: Mapping[int, np.ndarray]) -> Tuple[float, float, float]:
    """b4(S=-1)/b4(S=+1) of the printed eigenvalues: (nominal, lowest, highest) over the rounding.

    In eq. (16) this ratio is c3(-1)/c3(+1) = cos(gamma - rho)/cos(gamma + rho), independent of every
    other parameter (kT, kV, J1, J2, r1, r2, u, alphaN, any scaling of the mesh terms).
    """
    nm, lm, hm = ImpliedCoefficients(printed, -1)
    npl, lp, hp = ImpliedCoefficients(printed, +1)
    return nm[3] / npl[3], lm[3] / hp[3], hm[3] / lp[3]


def WheelSideFrictionBound(printed: Mapping[int, np.ndarray], gamma: float) -> Tuple[float, float]:
    """Interval of rho in rad for which cos(gamma - rho)/cos(gamma + rho) lies in :func:`B4RatioInterval` of
    ``printed``."""
    _, lo, hi = B4RatioInterval(printed)
    tg = math.tan(gamma)
    rho = lambda R: math.atan((R - 1) / ((R + 1) * tg))  # (1 + tg t)/(1 - tg t) = R
    return rho(lo), rho(hi)


@dataclass(frozen=True)
class FitResult:
    """A minimax fit of reduced parameters to the printed eigenvalues."""
    names: Tuple[str, ...]
    values: np.ndarray
    deviations: np.ndarray
    extra: Dict[str, float] = field(default_factory=dict)

    @property
    def maxDeviation(self) -> float:
        """Largest |computed - printed| over the 8 components, 1/s."""
        return float(np.max(np.abs(self.deviations)))

    def AsDict(self) -> Dict[str, float]:
        """``{name: value}``."""
        return dict(zip(self.names, (float(v) for v in self.values)))


def _Minimax(deviations: Callable[[np.ndarray], np.ndarray], q0: np.ndarray, bounds=None) -> np.ndarray:
    """min_q max_i |dev_i(q)| as the epigraph problem min s subject to -s <= dev_i <= s (SLSQP),
    in variables scaled by ``q0``."""
    from scipy.optimize import minimize
    q0 = np.asarray(q0, dtype=float)
    z0 = np.r_[np.ones(q0.size), np.max(np.abs(deviations(q0)))]
    cons = [{'type': 'ineq', 'fun': lambda z: z[-1] - deviations(z[:-1] * q0)},
            {'type': 'ineq', 'fun': lambda z: z[-1] + deviations(z[:-1] * q0)}]
    res = minimize(lambda z: z[-1], z0, constraints=cons, method='SLSQP', bounds=bounds,
                   options={'maxiter': 1000, 'ftol': 1e-13})
    q = res.x[:-1] * q0
    return q if np.max(np.abs(deviations(q))) <= np.max(np.abs(deviations(q0))) else q0


def _ClassDeviations(q, tg, printed):
    a, tauT, eta, K1, K2, t = q
    b = {S: ReducedCoefficients(a, tauT, eta, K1 * (tg + S * t), K2 * (1 - S * tg * t)) for S in (+1, -1)}
    return EigenvalueDeviations({S: UpperEigenvalues(b[S]) for S in b}, printed)


def ModelClassMinimax(printed: Optional[Mapping[int, np.ndarray]] = None,
                      start: Optional[ElasticDrive] = None) -> FitResult:
    """Best max deviation from ``printed`` reachable by eq. (16) with any parameters and gamma fixed.

    In (16) with (9)-(12), x(S) = K1 (tan(gamma) + S tan(rho)) and y(S) = K2 (1 - S tan(gamma) tan(rho)),
    with K1 = kV r1^2 cos^2(alphaN) sin(gamma) cos(gamma)/J1 and K2 = u kV r1 r2 cos^2(alphaN) sin(gamma)
    cos(gamma)/J2. The six free parameters (a, tauT, eta, K1, K2, t = tan rho) therefore cover every
    choice of J1, J2, kT, kV, dT, dV, r1, r2, u, alphaN and rho. Local minimax from ``start`` (default:
    the wheel-circumference hypothesis); :func:`GlobalModelClassSearch` confirms it is global.
    """
    printed = PrintedEigenvalues() if printed is None else printed
    start = _Circ(_Drive(BaseParameters())) if start is None else start
    g = start.gear
    tg, t = math.tan(g.gamma), math.tan(g.rho)
    r = ReducedParameters(start)
    q0 = np.array([r['a'], r['tauT'], r['eta'], r['x+'] / (tg + t), r['y+'] / (1 - tg * t), t])
    q = _Minimax(lambda q: _ClassDeviations(q, tg, printed), q0)
    return FitResult(('a', 'tauT', 'eta', 'K1', 'K2', 'tanRho'), q, _ClassDeviations(q, tg, printed),
                     {'rhoDeg': math.degrees(math.atan(q[5]))})


def _FreeDeviations(q, printed):
    a, tauT, eta, xp, yp, xm, ym = q
    return EigenvalueDeviations({+1: UpperEigenvalues(ReducedCoefficients(a, tauT, eta, xp, yp)),
                                 -1: UpperEigenvalues(ReducedCoefficients(a, tauT, eta, xm, ym))}, printed)


def FreeFamilyMinimax(printed: Optional[Mapping[int, np.ndarray]] = None,
                      start: Optional[ElasticDrive] = None) -> FitResult:
    """Minimax fit to ``printed`` of the free 7-parameter family (a, tauT, eta, x+, y+, x-, y-), local from ``start``
    (default: the wheel-circumference hypothesis); the mesh terms are not tied to one friction angle."""
    printed = PrintedEigenvalues() if printed is None else printed
    start = _Circ(_Drive(BaseParameters())) if start is None else start
    r = ReducedParameters(start)
    names = ('a', 'tauT', 'eta', 'x+', 'y+', 'x-', 'y-')
    q0 = np.array([r[n] for n in names])
    q = _Minimax(lambda q: _FreeDeviations(q, printed), q0, bounds=[(0.8, 1.2)] * 7 + [(0, None)])
    return FitResult(names, q, _FreeDeviations(q, printed), {f'{n}/start': float(v / v0) for n, v, v0 in zip(names, q, q0)})


def GlobalModelClassSearch(seeds: Sequence[int] = (0, 1, 2), printed: Optional[Mapping[int, np.ndarray]] = None
                           ) -> List[FitResult]:
    """Differential evolution (one run per seed of ``seeds``) against ``printed`` over the six parameters of
    :func:`ModelClassMinimax`, each within +-15 % of the local optimum (slow: minutes per seed)."""
    from scipy.optimize import differential_evolution
    printed = PrintedEigenvalues() if printed is None else printed
    start = _Circ(_Drive(BaseParameters()))
    tg = math.tan(start.gear.gamma)
    ref = ModelClassMinimax(printed).values
    bounds = [(0.85 * v, 1.15 * v) for v in ref]
    out = []
    for seed in seeds:
        res = differential_evolution(lambda q: float(np.max(np.abs(_ClassDeviations(q, tg, printed)))), bounds,
                                     seed=seed, tol=1e-12, maxiter=3000, popsize=40, polish=False)
        q = _Minimax(lambda q: _ClassDeviations(q, tg, printed), res.x)
        out.append(FitResult(('a', 'tauT', 'eta', 'K1', 'K2', 'tanRho'), q, _ClassDeviations(q, tg, printed),
                             {'rhoDeg': math.degrees(math.atan(q[5])), 'seed': seed}))
    return out


# --- output ------------------------------------------------------------------------------------------

def HypothesisTable(results: Sequence[HypothesisResult]) -> str:
    """Markdown table of hypothesis results."""
    lines = ['| hypothesis | fitted | max dev. (1/s) | printed digits | within +-0.05? | P7 f1, f2 (S=+1) Hz |',
             '|---|---|---|---|---|---|']
    for r in results:
        fit = '' if r.value is None else f'{r.hypothesis.fitted} = {r.value:.5g}'
        f1, f2 = r.p7FrequenciesHz
        lines.append(f'| `{r.hypothesis.key}`: {r.hypothesis.description} | {fit} | {r.maxDeviation:.3f} | '
                     f'{r.digits:.2f} | {"yes" if r.withinRounding else "no"} | {f1:.2f}, {f2:.2f} |')
    return '\n'.join(lines)


def DeviationTable(result: HypothesisResult, printed: Optional[Mapping[int, np.ndarray]] = None) -> str:
    """Markdown table of the eight printed eigenvalue components against one hypothesis."""
    printed = PrintedEigenvalues() if printed is None else printed
    lines = ['| S | component | printed | computed | deviation |', '|---|---|---|---|---|']
    i = 0
    for S in (+1, -1):
        for k, lam in enumerate(printed[S]):
            for part, v in (('Re', lam.real), ('Im', lam.imag)):
                dev = result.deviations[i]
                flag = '' if abs(dev) <= HALF_DIGIT + 1e-12 else ' (outside +-0.05)'
                lines.append(f'| {S:+d} | {part} lambda_{2 * k + 1}/{2 * k + 2} | {v:.1f} | {v + dev:.3f} | {dev:+.3f}{flag} |')
                i += 1
    return '\n'.join(lines)


def Main(argv: Optional[Sequence[str]] = None) -> int:
    """Print the hypothesis table and the model-class fits (``--global`` in ``argv`` adds the global search)."""
    argv = list(sys.argv[1:] if argv is None else argv)
    printed = PrintedEigenvalues()
    np.set_printoptions(linewidth=140)
    results = EvaluateHypotheses(printed=printed)
    print(HypothesisTable(results))
    circ = next(r for r in results if r.hypothesis.key == 'circ')
    print('\nWheel-circumference hypothesis, per component:\n' + DeviationTable(circ, printed))
    ratio = B4RatioInterval(printed)
    lo, hi = WheelSideFrictionBound(printed, BaseParameters()['gamma'])
    print(f'\nb4(-1)/b4(+1) of the printed eigenvalues: {ratio[0]:.5f} in [{ratio[1]:.5f}, {ratio[2]:.5f}] '
          f'-> rho in [{math.degrees(lo):.3f}, {math.degrees(hi):.3f}] deg')
    cls = ModelClassMinimax(printed)
    print(f'model class (16), gamma fixed: max deviation {cls.maxDeviation:.4f} 1/s at rho = {cls.extra["rhoDeg"]:.4f} deg,',
          cls.AsDict())
    free = FreeFamilyMinimax(printed)
    print(f'free 7-parameter family: max deviation {free.maxDeviation:.4f} 1/s,', free.AsDict())
    if '--global' in argv:
        for r in GlobalModelClassSearch(printed=printed):
            print(f'global search seed {r.extra["seed"]}: max deviation {r.maxDeviation:.5f} 1/s at rho = '
                  f'{r.extra["rhoDeg"]:.4f} deg')
    return 0


if __name__ == '__main__':
    raise SystemExit(Main())
