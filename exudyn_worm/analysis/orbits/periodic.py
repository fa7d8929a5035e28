"""Periodic orbits by shooting, and their Floquet multipliers.

Any autonomous system whose one-period map ``flow(x0, T) -> x(T)`` can be evaluated (a scipy ODE, or an
Exudyn model simulated with ``mbs.SolveDynamic``, see :mod:`exudyn_worm.analysis.orbits.chatter`) has its periodic orbits
found here by Newton's method on the shooting equations

    x(T; x0) - x0 = 0,     f_ref . (x0 - x_ref) = 0     (phase condition),

with the period ``T`` as an unknown. ``f_ref`` is the velocity of the flow at the reference point ``x_ref``
(the start guess or the previous orbit of a continuation), so the orbit's start point is the point of the
orbit on the hyperplane through ``x_ref`` normal to the flow there. The Newton matrix (the monodromy matrix
``M = dx(T)/dx0`` and the velocity ``f = dx(T)/dT``) is taken by forward finite differences of the flow
(``n + 1`` extra flow evaluations), which only asks of the flow that it be piecewise smooth: the worm mesh
(contact loss, flank change, clipped normal force) and stick-slip friction are non-smooth, and integrating
variational equations through their switches would need the saltation matrices of every switch. It is then
corrected by Broyden's update after every step and computed again only when convergence slows
(:data:`SLOW_CONVERGENCE`). The converged orbit's monodromy matrix, for the multipliers, is taken by central
differences (step ``monodromyPerturbation``).

The Floquet multipliers are the eigenvalues of ``M``. One of them belongs to the shift along the orbit and
is 1 for an autonomous system (the trivial multiplier); the orbit is (orbitally) stable if every other
multiplier lies inside the unit circle.

Textbook checks (tests/test_orbits.py, docs/chatter-amplitude.md): the van der Pol oscillator and a mass on
a moving belt with static > kinetic friction (stick-slip, closed form).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Dict, Optional, Sequence, Tuple

import numpy as np

from ..._checks import CheckPositive

__all__ = ['PeriodicOrbit', 'ShootingError', 'NoSteadyChatter', 'FindPeriodicOrbit', 'FloquetMultipliers', 'ShootingJacobian',
           'Monodromy', 'FlowVelocity', 'BroydenUpdate', 'SHOOTING_TOLERANCE', 'SLOW_CONVERGENCE',
           'TRIVIAL_MULTIPLIER_TOLERANCE']

#: default tolerance of the shooting residual ``|x(T) - x0|``, relative to the state scale
SHOOTING_TOLERANCE = 1e-8
#: an orbit is accurate where its trivial Floquet multiplier (1 in exact arithmetic) is within this of 1: along the
#: chatter branches of docs/chatter-amplitude.md ("Accuracy and limits") the error was 0.005-0.007 in the median and
#: at most 0.05 (the 0.5 mm backlash branch); beyond it the monodromy matrix, and the orbit's stability, is not trusted
TRIVIAL_MULTIPLIER_TOLERANCE = 0.05


class ShootingError(ValueError):
    """Shooting did not converge; ``.lastOrbit`` holds the last iterate (a :class:`PeriodicOrbit` with
    ``converged = False``) so that callers can report what was found.

    Parameters
    ----------
    message : str
        The error message.
    lastOrbit : PeriodicOrbit or None
        The last iterate.
    """

    def __init__(self, message: str, lastOrbit: Optional['PeriodicOrbit'] = None):
        super().__init__(message)
        self.lastOrbit = lastOrbit


class NoSteadyChatter(ShootingError):
    """Not a failure of the method: the drive settles to rest, so there is no steady chatter to find (a result; the
    message says why). A :class:`ShootingError`, so that a caller that handles those handles this one too.

    Parameters
    ----------
    message : str
        What settles and why.
    lastOrbit : PeriodicOrbit or None
        None (no orbit was iterated).
    """


@dataclass
class PeriodicOrbit:
    """A periodic orbit found by shooting.

    Attributes
    ----------
    state : ndarray
        Start point ``x0`` of the orbit (on the phase-condition hyperplane).
    period : float
        Period ``T`` in the time unit of the flow (s).
    monodromy : ndarray
        ``dx(T)/dx0`` at the orbit (finite differences).
    velocity : ndarray
        ``dx(T)/dT``, the flow's velocity at ``x(T)`` (= at ``x0`` on a converged orbit).
    residual : float
        ``max |x(T) - x0| / scale`` at the returned point.
    iterations : int
        Newton iterations used.
    converged : bool
        Whether ``residual`` reached the tolerance.
    info : dict
        Anything the caller attaches (amplitudes, parameter value ...).
    """
    state: np.ndarray
    period: float
    monodromy: np.ndarray = field(repr=False)
    velocity: np.ndarray = field(repr=False)
    residual: float
    iterations: int
    converged: bool = True
    info: Dict = field(default_factory=dict)

    @property
    def frequencyHz(self) -> float:
        """1 / period, in Hz if the period is in s."""
        return 1. / self.period

    @property
    def multipliers(self) -> np.ndarray:
        """All Floquet multipliers (eigenvalues of the monodromy matrix), by decreasing modulus."""
        return FloquetMultipliers(self.monodromy)

    @property
    def nontrivialMultipliers(self) -> np.ndarray:
        """The multipliers without the trivial one (the one closest to 1), by decreasing modulus."""
        mu = self.multipliers
        return np.delete(mu, int(np.argmin(np.abs(mu - 1.)))) if mu.size else mu

    @property
    def trivialMultiplierError(self) -> float:
        """``|mu - 1|`` of the trivial multiplier (the one closest to 1): 0 in exact arithmetic, so a measure of the
        accuracy of the monodromy matrix; trust a verdict only if the other multipliers are farther from the unit
        circle than this."""
        mu = self.multipliers
        return float(np.min(np.abs(mu - 1.))) if mu.size else 0.

    @property
    def accurate(self) -> bool:
        """True where :attr:`trivialMultiplierError` is at most :data:`TRIVIAL_MULTIPLIER_TOLERANCE`."""
        return self.trivialMultiplierError <= TRIVIAL_MULTIPLIER_TOLERANCE

    @property
    def stabilityDecided(self) -> bool:
        """True where the orbit is :attr:`accurate` and its largest non-trivial multiplier lies farther from the unit
        circle than the trivial multiplier's error (else the monodromy matrix cannot tell stable from unstable)."""
        mu = self.nontrivialMultipliers
        distance = abs(float(np.max(np.abs(mu))) - 1.) if mu.size else math.inf
        return self.accurate and distance > self.trivialMultiplierError

    @property
    def stable(self) -> bool:
        """True if every non-trivial multiplier has modulus < 1 (orbitally stable)."""
        mu = self.nontrivialMultipliers
        return bool(mu.size == 0 or np.max(np.abs(mu)) < 1.)


def FloquetMultipliers(monodromy: np.ndarray) -> np.ndarray:
    """Eigenvalues of a monodromy matrix, by decreasing modulus.

    Parameters
    ----------
    monodromy : array_like, shape (n, n)
        The one-period map's Jacobian ``dx(T)/dx0``.

    Returns
    -------
    ndarray of complex
    """
    mu = np.linalg.eigvals(np.atleast_2d(np.asarray(monodromy, dtype=float)))
    return mu[np.argsort(-np.abs(mu), kind='stable')]


def _Scale(where: str, stateScale, x0: np.ndarray) -> np.ndarray:
    if stateScale is None:
        return np.maximum(np.abs(x0), 1e-3 * max(1., float(np.max(np.abs(x0)))))
    scale = np.broadcast_to(np.asarray(stateScale, dtype=float), x0.shape).copy()
    if not np.all(np.isfinite(scale)) or np.any(scale <= 0):
        raise ValueError(f"{where}: 'stateScale' must hold positive finite values (one per state or one for all), "
                         f"got {stateScale!r}")
    return scale


def Monodromy(flow: Callable, x0: Sequence[float], period: float, scale: Sequence[float],
              perturbation: float = 1e-6, xT: Optional[Sequence[float]] = None, central: bool = False) -> np.ndarray:
    """Monodromy matrix ``dx(T)/dx0`` of the one-period map by finite differences.

    Parameters
    ----------
    flow : callable
        ``flow(x0, T) -> x(T)`` (arrays of shape (n,)).
    x0 : array_like
        Start state.
    period : float
        Integration time T.
    scale : array_like
        Typical size of each state component; the step of component j is ``perturbation * scale[j]``.
    perturbation : float
        Relative finite-difference step.
    xT : array_like, optional
        ``flow(x0, period)`` if already known (forward differences only).
    central : bool
        Central differences (2 n flow runs) instead of forward differences (n runs, plus one without ``xT``).
        With a step spanning a few solver steps, central differences average out the error a fixed-step
        integrator makes where a force jumps (see docs/chatter-amplitude.md).

    Returns
    -------
    ndarray, shape (n, n)
    """
    x0 = np.asarray(x0, dtype=float)
    n = x0.size
    if not central and xT is None:
        xT = flow(x0, period)
    M = np.empty((n, n))
    for j in range(n):
        h = perturbation * scale[j]
        x = x0.copy()
        x[j] += h
        plus = np.asarray(flow(x, period), dtype=float)
        if central:
            x[j] = x0[j] - h
            M[:, j] = (plus - np.asarray(flow(x, period), dtype=float)) / (2. * h)
        else:
            M[:, j] = (plus - np.asarray(xT, dtype=float)) / h
    return M


def ShootingJacobian(flow: Callable, x0: Sequence[float], period: float, scale: Sequence[float],
                     perturbation: float = 1e-6, xT: Optional[Sequence[float]] = None
                     ) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One-period map, monodromy matrix and velocity by forward finite differences.

    Parameters
    ----------
    flow : callable
        ``flow(x0, T) -> x(T)`` (arrays of shape (n,)).
    x0 : array_like
        Start state.
    period : float
        Integration time T.
    scale : array_like
        Typical size of each state component; the step of component j is ``perturbation * scale[j]``.
    perturbation : float
        Relative finite-difference step.
    xT : array_like, optional
        ``flow(x0, period)`` if already known.

    Returns
    -------
    (xT, monodromy, velocity)
        ``x(T)``, ``dx(T)/dx0`` (n x n) and ``dx(T)/dT`` (n).
    """
    x0 = np.asarray(x0, dtype=float)
    xT = np.asarray(flow(x0, period), dtype=float) if xT is None else np.asarray(xT, dtype=float)
    M = Monodromy(flow, x0, period, scale, perturbation, xT)
    return xT, M, FlowVelocity(flow, x0, period, perturbation, xT)


def FlowVelocity(flow: Callable, x0: Sequence[float], period: float, perturbation: float = 1e-6,
                 xT: Optional[Sequence[float]] = None) -> np.ndarray:
    """``dx(T)/dT`` by a forward difference in T (one flow run, two without ``xT``).

    Parameters
    ----------
    flow : callable
        ``flow(x0, T) -> x(T)``.
    x0 : array_like
        Start state.
    period : float
        Integration time T.
    perturbation : float
        Relative step of T.
    xT : array_like, optional
        ``flow(x0, period)`` if already known.

    Returns
    -------
    ndarray, shape (n,)
    """
    x0 = np.asarray(x0, dtype=float)
    xT = np.asarray(flow(x0, period), dtype=float) if xT is None else np.asarray(xT, dtype=float)
    dT = perturbation * period
    return (np.asarray(flow(x0, period + dT), dtype=float) - xT) / dT


def BroydenUpdate(A: np.ndarray, step: np.ndarray, change: np.ndarray) -> np.ndarray:
    """Broyden's rank-one update of a Jacobian ``A`` after a step ``step`` that changed the residual by ``change``
    (``A + (change - A step) step^T / |step|^2``): the secant condition ``A_new step = change`` with the least
    change of ``A``. Rows of exactly linear equations (phase and arclength conditions) stay as they are.

    Parameters
    ----------
    A : ndarray, shape (m, k)
    step : ndarray, shape (k,)
    change : ndarray, shape (m,)

    Returns
    -------
    ndarray, shape (m, k)
    """
    ss = float(step @ step)
    if not ss > 0:
        return A
    return A + np.outer(change - A @ step, step) / ss


#: a Newton step after which the residual is above this fraction of the one before renews the finite-difference
#: Jacobian (the Broyden-updated one has stopped paying)
SLOW_CONVERGENCE = 0.3


def FindPeriodicOrbit(flow: Callable, x0: Sequence[float], period: float, stateScale: Optional[Sequence[float]] = None,
                      referenceState: Optional[Sequence[float]] = None, referenceVelocity: Optional[Sequence[float]] = None,
                      tolerance: float = SHOOTING_TOLERANCE, maxIterations: int = 30, perturbation: float = 1e-6,
                      monodromyPerturbation: Optional[float] = None, where: str = 'FindPeriodicOrbit'
                      ) -> PeriodicOrbit:
    """Periodic orbit of an autonomous system by Newton's method on the one-period map (shooting).

    Parameters
    ----------
    flow : callable
        ``flow(x0, T) -> x(T)``: the state after integrating time ``T`` from ``x0`` (shape (n,)).
    x0 : sequence of float
        Guess of a point on the orbit (e.g. the end state of a time simulation that has settled).
    period : float
        Guess of the period, > 0 (same time unit as ``flow``).
    stateScale : float or sequence of float, optional
        Typical size of each state component (> 0), used for the finite-difference steps and the residual
        norm; default ``|x0|`` (at least 1e-3 of the largest component).
    referenceState, referenceVelocity : sequence of float, optional
        Point and flow velocity defining the phase condition ``referenceVelocity . (x0 - referenceState) = 0``;
        default ``x0`` and its velocity, estimated from the flow.
    tolerance : float
        Converged when ``max |x(T) - x0| / stateScale`` is below this (default :data:`SHOOTING_TOLERANCE`).
    maxIterations : int
        Largest number of Newton steps, >= 1.
    perturbation : float
        Relative forward-difference step of the Newton matrix.
    monodromyPerturbation : float, optional
        Relative step of the central differences for the monodromy matrix returned with the converged orbit
        (2 n flow runs; default ``perturbation``). For a fixed-step integration of a force that jumps, a step
        spanning a few solver steps averages out the integrator's error at the jump (docs/chatter-amplitude.md).
    where : str
        Caller named in messages.

    Returns
    -------
    PeriodicOrbit
        With the monodromy matrix at the returned orbit (Floquet multipliers, stability).

    Raises
    ------
    ValueError
        For bad arguments.
    ShootingError
        If Newton does not converge in ``maxIterations`` steps or the period collapses; ``.lastOrbit`` holds
        the last iterate.
    """
    x = np.array(x0, dtype=float).ravel()
    if x.size == 0 or not np.all(np.isfinite(x)):
        raise ValueError(f"{where}: 'x0' must be a non-empty sequence of finite numbers, got {x0!r}")
    T = CheckPositive(where, 'period', period, 's')
    CheckPositive(where, 'tolerance', tolerance)
    CheckPositive(where, 'perturbation', perturbation)
    if monodromyPerturbation is not None:
        CheckPositive(where, 'monodromyPerturbation', monodromyPerturbation)
    if isinstance(maxIterations, bool) or not isinstance(maxIterations, int) or maxIterations < 1:
        raise ValueError(f"{where}: 'maxIterations' must be an integer >= 1, got {maxIterations!r}")
    scale = _Scale(where, stateScale, x)
    xRef = x.copy() if referenceState is None else np.asarray(referenceState, dtype=float).ravel()
    fRef = None if referenceVelocity is None else np.asarray(referenceVelocity, dtype=float).ravel()
    n = x.size
    T0 = T
    xT = np.asarray(flow(x, T), dtype=float)
    A, M, velocity, fresh = None, None, None, False

    def Residual(x, xT):
        return np.concatenate([(xT - x) / scale, [(fRef @ (x - xRef)) / np.linalg.norm(fRef * scale)]])

    def Result(x, T, xT, iteration, residual, converged):
        if converged:                 # the monodromy at the orbit itself, for the multipliers: central differences
            Mx = Monodromy(flow, x, T, scale, monodromyPerturbation or perturbation, central=True)
        elif M is None:
            Mx = Monodromy(flow, x, T, scale, perturbation, xT)
        else:                                           # not converged: the last Jacobian's, for a report
            Mx = M
        v = FlowVelocity(flow, x, T, perturbation, xT) if converged or velocity is None else velocity
        return PeriodicOrbit(state=x.copy(), period=T, monodromy=Mx, velocity=v, residual=residual,
                             iterations=iteration, converged=converged)

    residual = float(np.max(np.abs(xT - x) / scale))
    for iteration in range(maxIterations + 1):
        if residual <= tolerance:
            return Result(x, T, xT, iteration, residual, True)
        if iteration == maxIterations:
            break
        if A is None:
            # Newton matrix from forward differences, in scaled unknowns (x / scale, T / T0): well balanced
            _, M, velocity = ShootingJacobian(flow, x, T, scale, perturbation, xT)
            if fRef is None:
                fRef = velocity.copy()
            W = fRef * scale
            A = np.zeros((n + 1, n + 1))
            A[:n, :n] = (M - np.eye(n)) * scale / scale[:, None]
            A[:n, n] = velocity * T0 / scale
            A[n, :n] = W / np.linalg.norm(W)
            fresh = True
        r = Residual(x, xT)
        try:
            dy = np.linalg.solve(A, -r)
        except np.linalg.LinAlgError:
            dy = np.linalg.lstsq(A, -r, rcond=None)[0]
        # damped step: at most half the state scale per component and 30 % of the period; halved while it does
        # not lower the residual (stops Newton's two-cycle across a kink of a non-smooth map)
        dy /= max(1., float(np.max(np.abs(dy[:n]))) / 0.5, abs(dy[n]) * T0 / T / 0.3)
        improved, xTTrial = False, None
        for _ in range(7):
            xTrial, TTrial, xTTrial = x + dy[:n] * scale, T + dy[n] * T0, None
            if TTrial > 0 and np.all(np.isfinite(xTrial)):
                xTTrial = np.asarray(flow(xTrial, TTrial), dtype=float)
                trial = float(np.max(np.abs(xTTrial - xTrial) / scale))
                if trial < residual:
                    improved = True
                    break
            dy *= 0.5
        if not improved and not fresh:
            A = None                # an updated Jacobian that finds no descent: renew it at the same point
            continue
        if xTTrial is None:
            raise ShootingError(f"{where}: the shooting iteration diverged (period {TTrial:g} s) after "
                                f"{iteration + 1} Newton steps; start closer to the orbit (e.g. from a longer time "
                                f"simulation)", Result(x, T, xT, iteration, residual, False))
        # Broyden: the next step reuses the Jacobian, corrected by what this step taught about the map
        A = BroydenUpdate(A, dy, Residual(xTrial, xTTrial) - r)
        slow = trial > SLOW_CONVERGENCE * residual
        x, T, xT, residual = xTrial, TTrial, xTTrial, trial
        fresh = False
        if slow:
            A = None
    raise ShootingError(f"{where}: shooting did not converge in {maxIterations} Newton steps (residual {residual:.3g}, "
                        f"tolerance {tolerance:g}, period {T:g} s); start closer to the orbit (e.g. from a longer "
                        f"time simulation), or raise maxIterations", Result(x, T, xT, maxIterations, residual, False))
