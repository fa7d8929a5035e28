"""The lowering phase settled by a long time simulation, watched on a Poincare section: the start of the 3D
model's orbit search, and its steady vibration where no periodic orbit is found.

The 3D model with elastic shaft bearings settles slowly: at the lowering point of ``examples/drives/reel-3d-chatter.toml``
the linearization has a wheel-tilt mode at 30.97 Hz with a damping ratio of 7e-5 beside the chatter (31.0 Hz, locked
to the tilt modes), and the orbit's largest nontrivial Floquet multiplier is 0.994 per period. One second of
settling leaves the state 13 state scales from the orbit, and the worm speed, dominated by the second harmonic,
gives a wrong period (docs/chatter-amplitude.md, "The 3D model"). :func:`SettleOnSection` therefore simulates in
pieces until the state on the section (upward crossings of the wheel speed through its mean) stops moving.
"""
from __future__ import annotations

import math
import time
from typing import Any, Dict, Optional, Sequence

import numpy as np

from ..._checks import CheckPositive
from .lowering import (EquilibriumState, LoweringModel, StateScale, _LoweringFlow, _MeshAt, _StoredFlowStates,
                       _StoredStates)
from ..simulation.reelchanger import SOLVER_SETTINGS

__all__ = ['SettleOnSection', 'SECTION_TOLERANCE']

#: the section point may move by at most this fraction of the state scale (:func:`~exudyn_worm.analysis.orbits.lowering.StateScale`)
#: over one piece for the run to count as settled: from the states reached so (0.2-0.3 of the state scale from the
#: orbit, reel-3d-chatter.toml after 14-16 s) shooting converges in a few Newton steps, from 1 state scale (10 s) in 30 s,
#: from 13 (1 s) it stalls (measured, docs/chatter-amplitude.md); the bearings' kHz modes leave a jitter of up to
#: 0.13 on the section (a contact switch resolved to a solver step)
SECTION_TOLERANCE = 0.3


def _SectionPoints(model: LoweringModel):
    """Times and flow states at the upward crossings of the wheel speed through its mean in the last stored
    solve (with hysteresis: a crossing counts after the signal was a quarter of its half swing below the mean)."""
    t, X = _StoredFlowStates(model)
    n = len(model.coordinates)
    y = X[:, n + 1] - np.mean(X[:, n + 1])
    band = 0.25 * 0.5 * np.ptp(y)
    times, points, armed = [], [], False
    for k in range(1, y.size):
        if y[k] < -band:
            armed = True
        elif armed and y[k - 1] < 0 <= y[k]:
            a = -y[k - 1] / (y[k] - y[k - 1])
            times.append(t[k - 1] + a * (t[k] - t[k - 1]))
            points.append((1. - a) * X[k - 1] + a * X[k])
            armed = False
    return np.asarray(times), np.asarray(points), float(np.ptp(y))


def _TailVibration(model: LoweringModel, window: float) -> Dict[str, float]:
    """The largest loads and speeds over the last ``window`` s of the stored solve."""
    s = _StoredStates(model)
    t = s['time']
    last = t >= t[-1] - window
    normal = np.abs(_MeshAt(model.connector, s, last).normalForce)
    out = {'forceFactor': float(np.max(normal) / model.staticNormalForce),
           'maxWheelAcceleration': float(np.max(np.abs(s['alpha2'][last]))),
           'minWormSpeed': float(np.min(s['omega1'][last])), 'maxWormSpeed': float(np.max(s['omega1'][last]))}
    if model.rigidBody is not None:
        # lazy: the 3D model's module is loaded only for drives with shaft bearings
        from ..simulation.reelchanger3d import ShaftLoadPeaks
        out.update(ShaftLoadPeaks(model.rigidBody, since=t[-1] - window))
    return out


def SettleOnSection(model: LoweringModel, maxDuration: float = 40., piece: float = 2., stepSize: float = 1e-4,
                    tolerance: float = SECTION_TOLERANCE, kick: float = 0.01, window: float = 0.5,
                    initialState: Optional[Sequence[float]] = None) -> Dict[str, Any]:
    """Simulate the lowering phase from its kicked steady state in pieces of ``piece`` s (the time simulations'
    solver settings, :data:`~exudyn_worm.analysis.simulation.reelchanger.SOLVER_SETTINGS`) until its state on the Poincare
    section (the upward crossings of the wheel speed through its mean) moved by less than ``tolerance`` state
    scales over the last piece, or for ``maxDuration`` s.

    Parameters
    ----------
    model : LoweringModel
        The lowering model (:func:`~exudyn_worm.analysis.orbits.lowering.BuildRigidBodyLoweringModel` or another).
    maxDuration : float
        Longest simulated time in s.
    piece : float
        Simulated time in s between two looks at the section (> ``window``).
    stepSize : float
        Time step in s.
    tolerance : float
        Settled when the section point moved by less than this (relative to the state scale) over a piece.
    kick : float
        Initial worm speed disturbance as a fraction of the motor speed.
    window : float
        Final part of the run in s over which ``vibration`` is measured.
    initialState : array_like, optional
        Flow state to start from instead of the kicked steady state (``kick`` is then not used), e.g. a state of
        the chatter at a neighbouring parameter value.

    Returns
    -------
    dict
        ``state`` (the flow state in the last period where the mesh is deepest in contact: the start of an orbit
        search), ``period`` (s, the median time between the
        crossings of the last piece; nan if the wheel speed does not oscillate), ``settled`` (bool), ``duration``
        (simulated s), ``change`` (the section point's last move in state scales), ``vibration`` (over the last
        ``window`` s: ``forceFactor``, ``maxWheelAcceleration``, ``minWormSpeed``, ``maxWormSpeed``, and for the 3D
        model the largest bearing loads in N, ``maxWormAxialLoad``, ...), ``seconds`` (solver time).
    """
    w = 'SettleOnSection'
    maxDuration = CheckPositive(w, 'maxDuration', maxDuration, 's')
    piece = CheckPositive(w, 'piece', piece, 's')
    stepSize = CheckPositive(w, 'stepSize', stepSize, 's')
    tolerance = CheckPositive(w, 'tolerance', tolerance)
    window = CheckPositive(w, 'window', window, 's')
    if piece <= window:
        raise ValueError(f"{w}: 'piece' must be longer than 'window' ({window:g} s), got {piece:g} s")
    scale = StateScale(model)
    flow = _LoweringFlow(model, max(10, int(round(piece / stepSize))), SOLVER_SETTINGS)
    if initialState is None:
        x = EquilibriumState(model)
        x[len(model.coordinates)] += kick * model.motorSpeed          # the worm's speed
    else:
        x = np.array(initialState, dtype=float)
        if x.shape != EquilibriumState(model).shape or not np.all(np.isfinite(x)):
            raise ValueError(f"{w}: 'initialState' must hold {2 * len(model.coordinates)} finite flow coordinates, "
                             f"got {initialState!r}")
    t0, duration, before, change, settled = time.perf_counter(), 0., None, math.inf, False
    state, period = x, math.nan
    while duration < maxDuration and not settled:
        x = flow.Solve(x, piece, storeSensors=True, restart=duration == 0.)     # one run, in pieces
        duration += piece
        times, points, swing = _SectionPoints(model)
        if times.size < 3 or not swing > 1e-6 * model.motorSpeed:
            state, period, before = x, math.nan, None                   # no oscillation (yet)
            continue
        section, period = points[-1], float(np.median(np.diff(times)))
        state = _DeepestContact(model, period)
        if before is not None:
            change = float(np.max(np.abs(section - before) / scale))
            settled = change < tolerance
        before = section
    return {'state': np.array(state, dtype=float), 'period': period, 'settled': settled, 'duration': duration,
            'change': change, 'vibration': _TailVibration(model, window), 'seconds': time.perf_counter() - t0}


def _DeepestContact(model: LoweringModel, period: float) -> np.ndarray:
    """The flow state of the last stored period's step where the mesh is deepest in contact, among the steps where
    the worm clearly slides forward: far from the contact law's switches, as the orbit search starts
    (:func:`~exudyn_worm.analysis.orbits.chatter.FindSteadyChatter`)."""
    s = _StoredStates(model)
    t = s['time']
    last = np.nonzero(t >= t[-1] - period)[0]
    if np.min(s['omega1'][last]) <= 0.:
        last = last[s['omega1'][last] >= 0.5 * np.max(s['omega1'][last])]
    k = last[int(np.argmax(np.abs(_MeshAt(model.connector, s, last).normalForce)))]
    return _StoredFlowStates(model)[1][k]
