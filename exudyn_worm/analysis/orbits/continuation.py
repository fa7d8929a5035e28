"""Pseudo-arclength continuation of periodic orbits in one parameter.

The unknowns are ``y = (x0, T, p)``: a point of the orbit, its period and the parameter. The equations are the
shooting equations of :mod:`exudyn_worm.analysis.orbits.periodic` at parameter ``p`` (``x(T; x0, p) - x0 = 0`` and the phase
condition against the previous point) and the arclength condition ``t . (y - y_pred) = 0``, in scaled variables
(state / stateScale, T / T0, p / parameterScale). The first step changes the parameter alone; after it the
predictor follows the secant through the last two points (robust to the errors of the finite-difference
Jacobian through the mesh's switches), so the branch is followed through folds (turning points in ``p``, where
the parameter component of the secant changes sign). The step length adapts: halved when
the corrector fails, grown by 1.5 after an easy step.

The corrector is Newton's method with Broyden updates: it starts from the previous orbit's Jacobian (its
monodromy matrix, velocity and parameter derivative, computed there anyway) and renews it by finite differences
only when convergence slows, so a step costs a few flow runs instead of ``n + 2`` per Newton step.

The flow at parameter ``p`` comes from ``flowAt(p)``, which may change the model in place or build a new one.
"""
from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np

from .periodic import (SLOW_CONVERGENCE, BroydenUpdate, FlowVelocity, Monodromy, PeriodicOrbit,
                       ShootingJacobian)

__all__ = ['StopKind', 'BranchPoint', 'Branch', 'ContinueOrbits']


class StopKind(enum.Enum):
    """Why a run of the continuation stopped (:attr:`Branch.stopKinds`; the words are in :attr:`Branch.stopReason`).

    Attributes
    ----------
    CORRECTOR_FAILED, RANGE_END, STOPPED, MAX_POINTS : StopKind
        The corrector did not converge at the smallest step length; the branch left the range; the caller's
        ``stop`` function ended it; the point limit was reached.
    """
    CORRECTOR_FAILED = 'corrector failed'
    RANGE_END = 'end of range'
    STOPPED = 'stopped'
    MAX_POINTS = 'point limit'


@dataclass
class BranchPoint:
    """One orbit of a branch: parameter ``value``, the :class:`~exudyn_worm.analysis.orbits.periodic.PeriodicOrbit` and what the
    caller's ``measure`` returned (``info``).

    Parameters
    ----------
    value : float
        The parameter value.
    orbit : PeriodicOrbit
        The orbit there.
    info : dict
        What the caller's ``measure`` returned for the orbit.
    """
    value: float
    orbit: PeriodicOrbit
    info: Dict = field(default_factory=dict)

    @property
    def stable(self) -> bool:
        """Floquet stability of the orbit."""
        return self.orbit.stable


@dataclass
class Branch:
    """A continued branch of periodic orbits, in the order computed (a run in each direction is joined, sorted
    along the arclength).

    Parameters
    ----------
    parameter : str
        Name of the continued parameter.
    points : list of BranchPoint
        The orbits of the branch.
    folds : list of float
        Parameter values of the folds (turning points) found.
    stopReason : list of str
        Why each run of the continuation stopped, in words.
    stopKinds : list of StopKind
        The same as kinds, one per entry of ``stopReason`` (what code decides on).
    """
    parameter: str
    points: List[BranchPoint]
    folds: List[float] = field(default_factory=list)
    stopReason: List[str] = field(default_factory=list)
    stopKinds: List[StopKind] = field(default_factory=list)

    def Stopped(self, kind: StopKind, reason: str) -> None:
        """Record why a run stopped.

        Parameters
        ----------
        kind : StopKind
            The kind of stop.
        reason : str
            The words for the user.
        """
        self.stopKinds.append(kind)
        self.stopReason.append(reason)


#: a corrector that converged in at most this many Broyden steps from the previous orbit's Jacobian, without
#: renewing it, made an easy step: the next step is 1.5 times longer (as after at most 2 Newton steps)
EASY_BROYDEN_STEPS = 5
#: the corrector gives up after this many slow steps with a freshly computed Jacobian (stuck at a kink of the map:
#: a shorter continuation step is cheaper than more Newton steps)
MAX_STALLS = 3


def _Newton(F, Jacobian, y, tol, maxIterations, A=None):
    """Newton's method with Broyden updates: the Jacobian ``A`` (e.g. the previous orbit's) is corrected by every
    step (:func:`~exudyn_worm.analysis.orbits.periodic.BroydenUpdate`) and renewed by finite differences (``Jacobian(y)``) only
    when a step lowers the residual by less than :data:`~exudyn_worm.analysis.orbits.periodic.SLOW_CONVERGENCE` or finds no
    descent; it gives up after :data:`MAX_STALLS` slow steps with fresh Jacobians. A step that does not lower the
    residual is halved (up to 6 times), which stops the two-cycle Newton falls into across a kink of the non-smooth
    one-period map. Returns ``(y, iterations, converged, renewals)`` (renewals: finite-difference Jacobians
    computed)."""
    r = F(y)
    fresh, stalls, renewals = False, 0, 0
    for k in range(maxIterations):
        norm = float(np.max(np.abs(r)))
        if norm <= tol:
            return y, k, True, renewals
        if A is None:
            A, fresh = Jacobian(y), True
            renewals += 1
        dy = np.linalg.lstsq(A, -r, rcond=None)[0]
        dy /= max(1., float(np.max(np.abs(dy))) / 0.5)
        improved = False
        for _ in range(7):
            yTrial = y + dy
            rTrial = F(yTrial)
            trial = float(np.max(np.abs(rTrial)))
            if trial < norm:
                improved = True
                break
            dy *= 0.5
        if not improved and not fresh:
            A = None                    # renew the Jacobian at the same point
            continue
        A = BroydenUpdate(A, yTrial - y, rTrial - r)
        if trial > SLOW_CONVERGENCE * norm:
            stalls += fresh
            if stalls >= MAX_STALLS:    # stuck at a kink even with fresh Jacobians: let the caller shorten the step
                return yTrial, k + 1, trial <= tol, renewals
            A = None
        y, r, fresh = yTrial, rTrial, False
    return y, maxIterations, float(np.max(np.abs(r))) <= tol, renewals


def ContinueOrbits(flowAt: Callable[[float], Callable], start: PeriodicOrbit, value: float, bounds: Tuple[float, float],
                   stateScale: Sequence[float], parameterScale: float, parameter: str = 'p', direction: int = 1,
                   stepLength: float = 0.05, maxStepLength: float = 0.3, minStepLength: float = 1e-3,
                   maxPoints: int = 50, tolerance: float = 1e-8, perturbation: float = 1e-6,
                   monodromyPerturbation: Optional[float] = None, measure: Optional[Callable] = None,
                   stop: Optional[Callable] = None, onPoint: Optional[Callable] = None) -> Branch:
    """Follow a branch of periodic orbits from ``start`` at parameter ``value`` in one direction.

    Parameters
    ----------
    flowAt : callable
        ``flowAt(p)`` returns ``flow(x0, T) -> x(T)`` at parameter value ``p``.
    start : PeriodicOrbit
        A converged orbit at ``value``.
    value : float
        Parameter value of ``start``.
    bounds : (float, float)
        The branch is followed while the parameter stays in ``[low, high]``.
    stateScale : array_like
        Typical size of each state component (> 0).
    parameterScale : float
        Typical size of a parameter change (> 0); the step length is measured in these units.
    parameter : str
        Name of the parameter (for the result).
    direction : int
        +1: start towards increasing parameter, -1: decreasing.
    stepLength, maxStepLength, minStepLength : float
        First, largest and smallest arclength step (scaled units).
    maxPoints : int
        Largest number of points after ``start``.
    tolerance : float
        Corrector tolerance on the scaled residual.
    perturbation : float
        Relative forward-difference step of the corrector's Jacobian.
    monodromyPerturbation : float, optional
        Relative step of the central differences for each orbit's monodromy matrix (default ``perturbation``;
        see :func:`~exudyn_worm.analysis.orbits.periodic.FindPeriodicOrbit`).
    measure : callable, optional
        ``measure(p, orbit) -> dict`` stored as the point's ``info`` (amplitudes ...).
    stop : callable, optional
        ``stop(point) -> str or None``: a reason to end the branch at this point (kept).
    onPoint : callable, optional
        Called with every new point (progress, partial results).

    Returns
    -------
    Branch
        ``points`` from ``start`` on, ``folds`` (parameter values where the branch turns), ``stopReason``.
    """
    scale = np.asarray(stateScale, dtype=float)
    n = scale.size
    T0 = start.period
    low, high = bounds

    def Unscale(y):
        return y[:n] * scale, y[n] * T0, y[n + 1] * parameterScale

    def Matrix(M, velocity, dxdp, referenceVelocity):
        """Rows of the shooting equations and the phase condition, in scaled unknowns."""
        W = referenceVelocity * scale
        A = np.zeros((n + 1, n + 2))
        A[:n, :n] = (M - np.eye(n)) * scale / scale[:, None]
        A[:n, n] = velocity * T0 / scale
        A[:n, n + 1] = dxdp * parameterScale / scale
        A[n, :n] = W / np.linalg.norm(W)
        return A

    def ParameterDerivative(x, T, p, xT):
        dp = perturbation * parameterScale
        dxdp = (np.asarray(flowAt(p + dp)(x, T), dtype=float) - xT) / dp
        flowAt(p)
        return dxdp

    def Shooting(y, reference, withJacobian):
        x, T, p = Unscale(y)
        flow = flowAt(p)
        xRef, fRef = reference
        wn = np.linalg.norm(fRef * scale)
        if not withJacobian:
            xT = np.asarray(flow(x, T), dtype=float)
            return np.concatenate([(xT - x) / scale, [fRef @ (x - xRef) / wn]]), None
        xT, M, velocity = ShootingJacobian(flow, x, T, scale, perturbation)
        A = Matrix(M, velocity, ParameterDerivative(x, T, p, xT), fRef)
        r = np.concatenate([(xT - x) / scale, [fRef @ (x - xRef) / wn]])
        return r, (A, M, velocity)

    y = np.concatenate([start.state / scale, [1., value / parameterScale]])
    reference = (start.state.copy(), start.velocity.copy())
    # first step: parameter changed alone (natural continuation), then the secant through the two points
    tangent = np.zeros(n + 2)
    tangent[n + 1] = 1. if direction > 0 else -1.
    first = True
    jacobian = None                 # the corrector's first Jacobian: the previous orbit's (none for the first step)
    points = [BranchPoint(value, start, measure(value, start) if measure else {})]
    branch = Branch(parameter, points)
    h = stepLength
    while len(points) <= maxPoints:
        yPred = y + h * tangent
        cache = {}
        row = tangent
        pPred = yPred[n + 1] * parameterScale
        if first:
            row = np.zeros(n + 2)
            row[n + 1] = 1.
        if not low <= pPred <= high and abs(tangent[n + 1]) > 1e-3:
            # the step would leave the range: land on its end instead (parameter fixed there)
            end = low if pPred < low else high
            yPred = y + (end / parameterScale - y[n + 1]) / tangent[n + 1] * tangent
            yPred[n + 1] = end / parameterScale
            row = np.zeros(n + 2)
            row[n + 1] = 1.

        def F(z):
            r, _ = Shooting(z, reference, False)
            cache['last'] = (z, r)
            return np.concatenate([r, [row @ (z - yPred)]])

        def J(z):
            return np.vstack([Shooting(z, reference, True)[1][0], row])

        try:
            yNew, iterations, ok, renewals = _Newton(F, J, yPred, tolerance, 12,
                                           None if jacobian is None else np.vstack([jacobian, row]))
        except Exception as err:            # a solver failure on the way counts as a failed step
            ok, iterations, yNew, renewals = False, 8, yPred, 1
            cache['error'] = str(err)
        if ok and yNew[n] <= 0:
            ok = False
        if not ok:
            h *= 0.5
            if h < minStepLength:
                branch.Stopped(StopKind.CORRECTOR_FAILED, f"the corrector did not converge at step length {h:.2g}"
                               + (f" ({cache['error']})" if 'error' in cache else ''))
                break
            continue
        x, T, p = Unscale(yNew)
        # at the orbit: its monodromy (central differences, for the multipliers), velocity and parameter
        # derivative, which are also the next corrector's first Jacobian
        flow = flowAt(p)
        z, r = cache['last']
        if not np.array_equal(z, yNew):
            r = Shooting(yNew, reference, False)[0]
        xT = x + r[:n] * scale
        M = Monodromy(flow, x, T, scale, monodromyPerturbation or perturbation, central=True)
        velocity = FlowVelocity(flow, x, T, perturbation, xT)
        jacobian = Matrix(M, velocity, ParameterDerivative(x, T, p, xT), velocity)
        # secant predictor: robust to the errors of the finite-difference Jacobian through the mesh's switches
        secant = yNew - y
        newTangent = secant / np.linalg.norm(secant)
        if newTangent[n + 1] * tangent[n + 1] < 0:
            branch.folds.append(p)
        orbit = PeriodicOrbit(state=x, period=T, monodromy=M, velocity=velocity,
                              residual=float(np.max(np.abs(r[:n]))), iterations=iterations)
        point = BranchPoint(p, orbit, measure(p, orbit) if measure else {})
        points.append(point)
        if onPoint is not None:
            onPoint(point)
        y, tangent, reference, first = yNew, newTangent, (x.copy(), velocity.copy()), False
        if not low < p < high:
            branch.Stopped(StopKind.RANGE_END, f"reached the end of the range at {parameter} = {p:.6g}")
            break
        reason = stop(point) if stop else None
        if reason:
            branch.Stopped(StopKind.STOPPED, reason)
            break
        if iterations <= 2 or (renewals == 0 and iterations <= EASY_BROYDEN_STEPS):
            h = min(maxStepLength, 1.5 * h)
    else:
        branch.Stopped(StopKind.MAX_POINTS, f"reached {maxPoints} points")
    return branch
