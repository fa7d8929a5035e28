"""Steady chatter amplitudes by brute force: long time simulations of the lowering phase (the time simulations'
solver settings), measured over their last seconds; the check of the orbits found by shooting
(:mod:`exudyn_worm.analysis.orbits.chatter`) that the validation and the benchmarks run.
"""
from __future__ import annotations

import math
import time
from typing import Dict, Optional, Sequence

import numpy as np

from ..._checks import CheckPositive
from ...model.contact import ContactOptions
from ...drive.wholedrive import Drive
from .lowering import BuildLoweringModel, EquilibriumState, LoweringModel, _LoweringFlow, _MeshAt, _PeriodFromSignal
from ..simulation.reelchanger import SOLVER_SETTINGS

__all__ = ['LongSimulationAmplitude', 'SettledSimulationAmplitude']


def LongSimulationAmplitude(drive: Optional[Drive], duration: float = 3.0, stepSize: float = 1e-4,
                            kick: float = 0.01, window: float = 0.25,
                            contactOptions: ContactOptions = ContactOptions(),
                            initialState: Optional[Sequence[float]] = None,
                            model: Optional[LoweringModel] = None) -> Dict[str, float]:
    """Steady amplitude of the lowering phase by brute force: a long time simulation with the time simulations'
    solver settings (:data:`~exudyn_worm.analysis.simulation.reelchanger.SOLVER_SETTINGS`: modified Newton, tolerance 1e-6), measured
    over its last ``window`` seconds; the check of the orbits found by shooting.

    Parameters
    ----------
    drive : Drive or None
        A drive with the reel changer's duty (None with ``model``).
    duration : float
        Simulated time in s.
    stepSize : float
        Time step in s.
    kick : float
        Initial worm speed disturbance as a fraction of the motor speed.
    window : float
        Final part of the run in s over which the amplitude is measured.
    contactOptions : ContactOptions
        Options of the contact law.
    initialState : array_like, optional
        Flow state to start from (the worm-speed ``kick`` is added to it) instead of the equilibrium, e.g. a
        point of an orbit where rest and chatter coexist.
    model : LoweringModel, optional
        A model to simulate instead of one built from ``drive`` (e.g.
        :func:`~exudyn_worm.analysis.orbits.lowering.LoweringModelOfSystem`: then ``drive`` is not read).

    Returns
    -------
    dict
        ``forceFactor``, ``maxWheelAcceleration`` (rad/s^2), ``frequencyHz`` (nan at rest), ``seconds`` (solver time).
    """
    w = 'LongSimulationAmplitude'
    duration = CheckPositive(w, 'duration', duration, 's')
    stepSize = CheckPositive(w, 'stepSize', stepSize, 's')
    window = CheckPositive(w, 'window', window, 's')
    model = BuildLoweringModel(drive, contactOptions) if model is None else model
    steps = max(10, int(round(duration / stepSize)))
    flow = _LoweringFlow(model, steps, SOLVER_SETTINGS)
    x = EquilibriumState(model) if initialState is None else np.array(initialState, dtype=float)
    x[len(model.coordinates)] += kick * model.motorSpeed          # the worm's speed
    t0 = time.perf_counter()
    flow.Solve(x, duration, storeSensors=True)
    seconds = time.perf_counter() - t0
    return {**_TailAmplitude(model, window), 'seconds': seconds}


def _TailAmplitude(model: LoweringModel, window: float) -> Dict[str, float]:
    """Amplitude of the last ``window`` s of the stored run: force factor, largest |phi2''|, frequency, and the
    spread of the force factor's per-period peaks (relative to the largest: 0 for a periodic motion)."""
    s = model.connector.StoredStates(model.mbs)
    t = s['time']
    last = t >= t[-1] - window
    mesh = _MeshAt(model.connector, s, last)
    factor = np.abs(mesh.normalForce) / model.staticNormalForce
    period = _PeriodFromSignal(t[last], s['omega1'][last])
    spread = math.nan
    if np.isfinite(period):
        k = np.floor((t[last] - t[last][0]) / period).astype(int)
        peaks = [np.max(factor[k == j]) for j in range(int(k[-1]))]       # whole periods only
        spread = float(1. - min(peaks) / max(peaks)) if len(peaks) > 1 else math.nan
    return {'forceFactor': float(np.max(factor)), 'maxWheelAcceleration': float(np.max(np.abs(s['alpha2'][last]))),
            'frequencyHz': 1. / period, 'peakSpread': spread}


def SettledSimulationAmplitude(drive: Drive, maxDuration: float = 300., piece: float = 2.,
                               rate: float = 5e-4, stepSize: float = 2e-4, kick: float = 0.01, window: float = 0.25,
                               contactOptions: ContactOptions = ContactOptions()) -> Dict[str, float]:
    """Steady amplitude of the lowering phase by a time simulation from rest (worm speed kicked by ``kick``) that
    runs until it has settled: as :func:`LongSimulationAmplitude` (the time simulations' solver settings), but
    in pieces of ``piece`` s, stopped when the force factor and the largest ``|phi2''|`` over the last
    ``window`` s changed by less than ``rate`` (relative) per second since the previous piece, or at
    ``maxDuration``. Near a Hopf point the chatter grows and settles slowly (in proportion to the distance
    from it), so a run of fixed length may stop long before the steady state.

    Parameters
    ----------
    drive : Drive
        A drive with the reel changer's duty.
    maxDuration : float
        Longest simulated time in s.
    piece : float
        Simulated time in s between two looks at the amplitude (> ``window``).
    rate : float
        Settled when the amplitudes change by less than this fraction per second.
    stepSize : float
        Time step in s.
    kick : float
        Initial worm speed disturbance as a fraction of the motor speed.
    window : float
        Final part of each piece in s over which the amplitude is measured.
    contactOptions : ContactOptions
        Options of the contact law.

    Returns
    -------
    dict
        ``forceFactor``, ``maxWheelAcceleration`` (rad/s^2), ``frequencyHz``, ``peakSpread`` (1 - smallest /
        largest per-period peak of the force factor in the last window: 0 for a periodic motion),
        ``settled`` (bool), ``duration`` (simulated s), ``change`` (the last relative change per second),
        ``seconds`` (solver time).
    """
    w = 'SettledSimulationAmplitude'
    maxDuration = CheckPositive(w, 'maxDuration', maxDuration, 's')
    window = CheckPositive(w, 'window', window, 's')
    piece = CheckPositive(w, 'piece', piece, 's')
    rate = CheckPositive(w, 'rate', rate, '1/s')
    stepSize = CheckPositive(w, 'stepSize', stepSize, 's')
    if piece <= window:
        raise ValueError(f"{w}: 'piece' must be longer than 'window' ({window:g} s), got {piece:g} s")
    model = BuildLoweringModel(drive, contactOptions)
    steps = max(10, int(round(piece / stepSize)))
    flow = _LoweringFlow(model, steps, SOLVER_SETTINGS)
    x = EquilibriumState(model)
    x[len(model.coordinates)] += kick * model.motorSpeed          # the worm's speed
    t0, duration, before, change, settled = time.perf_counter(), 0., None, math.inf, False
    while duration < maxDuration and not settled:
        x = flow.Solve(x, piece, storeSensors=True, restart=duration == 0.)     # one run, in pieces
        duration += piece
        now = _TailAmplitude(model, window)
        if before is not None:
            change = max(abs(now[k] / before[k] - 1.) for k in ('forceFactor', 'maxWheelAcceleration')) / piece
            settled = change < rate
        before = now
    return {**now, 'settled': settled, 'duration': duration, 'change': change,
            'seconds': time.perf_counter() - t0}
