"""The 3D model's chatter branch where the pseudo-arclength continuation fails: natural-parameter points, each
from its own settled time simulation.

On the 3D model with elastic shaft bearings the continuation of the chatter orbit
(:func:`~exudyn_worm.analysis.orbits.chatterbranch.AnalyzeChatterBranch`) covers only a few per mille of a bearing
stiffness before its corrector fails: the one-period map jumps (by 0.01-0.05 of the state scale within 1e-3 state
scales of the orbit at ``wheelRadialStiffness`` = 1.112e9 N/m of ``examples/drives/reel-3d.toml``, with 400, 800 and
1600 solver steps per period alike; measured, docs/chatter-amplitude.md) where a contact switch of the mesh changes
with the start state. :func:`SettledBranchPoints` therefore computes each further point on its own: the lowering
phase simulated from its kicked steady state until it settles on its Poincare section
(:func:`~exudyn_worm.analysis.orbits.settling.SettleOnSection`), then shooting from there. A point is

- an orbit (``info['method']`` 'shooting') where Newton reached the shooting tolerance, or stopped with a residual
  below :data:`SETTLED_ORBIT_TOLERANCE` (a tenth of the map's jumps: the iterate closes to the resolution of the map
  itself; ``converged`` is then False and ``info['residual']`` says how closely it closes);
- 'rest' where the drive is linearly stable and the settled run stays in contact with the worm sliding forward
  (the mesh's law is then linear, so the vibration decays at the linear rate: no steady chatter);
- 'long simulation' otherwise: the settled run's vibration, with the best shooting residual (none where the run
  still stays in contact on the linearly unstable side: an orbit in contact is one of the linearized drive, whose
  amplitude the mesh does not fix), its stability undecided.

Each point's run starts from the state its neighbour settled to (the first from the continuation's last orbit), so
the chatter is followed where it outlives the linear boundary.
"""
from __future__ import annotations

import math
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np

from .chatter import MONODROMY_PERTURBATION, FindSteadyChatter, OrbitAmplitude
from .continuation import BranchPoint
from .exudynflow import STEPS_PER_PERIOD
from .lowering import BuildRigidBodyLoweringModel, StateScale, _LoweringFlow
from .periodic import FlowVelocity, Monodromy, PeriodicOrbit, ShootingError
from .settling import SettleOnSection
from ...drive.wholedrive import Drive

__all__ = ['SETTLED_ORBIT_TOLERANCE', 'SETTLED_STEP_RATIO', 'SettledBranchPoints', 'SettledValues']

#: an orbit of the 3D model found by shooting from a settled run is accepted where Newton stops with a residual
#: (relative to the state scale) below this: a tenth of the smallest jump of the one-period map measured beside a
#: stalled iterate (0.0096-0.049 of the state scale within 1e-3 state scales, wheelRadialStiffness = 1.112e9 N/m of
#: reel-3d.toml, 400-1600 steps per period; docs/chatter-amplitude.md). Each point reports its own residual.
SETTLED_ORBIT_TOLERANCE = 1e-3
#: neighbouring natural-parameter points differ by at most this factor (ten points per decade)
SETTLED_STEP_RATIO = 10. ** 0.1


def SettledValues(start: float, end: float, ratio: float = SETTLED_STEP_RATIO) -> List[float]:
    """Parameter values from ``start`` (excluded) to ``end`` (included), neighbours differing by at most the factor
    ``ratio`` (evenly spaced in the logarithm; for values that are not all positive evenly spaced in steps of at most
    1/25 of the distance).

    Parameters
    ----------
    start : float
        Where the points start (the end of what is already covered); not among the values.
    end : float
        The last value.
    ratio : float
        Largest ratio of neighbouring values, > 1.

    Returns
    -------
    list of float
        Ordered from ``start`` towards ``end``; empty if they are equal.
    """
    if start == end:
        return []
    if start > 0 and end > 0:
        count = max(1, math.ceil(abs(math.log(end / start)) / math.log(ratio) - 1e-9))
        values = [start * (end / start) ** (k / count) for k in range(1, count + 1)]
    else:
        values = list(np.linspace(start, end, 26)[1:])
    values[-1] = end
    return [float(v) for v in values]


def SettledBranchPoints(drive: Drive, name: str, values: Sequence[float], growth: Callable[[float], float],
                        restForceFactor: float, start: Optional[Sequence[float]] = None,
                        onPoint: Optional[Callable] = None) -> Tuple[List[BranchPoint], List[Dict[str, Any]]]:
    """The chatter of the 3D model's lowering phase at each of ``values`` of ``name``, each point from its own time
    simulation settled on the Poincare section (see the module's text).

    Parameters
    ----------
    drive : Drive
        A drive with shaft bearings and the reel changer's duty.
    name : str
        The parameter varied.
    values : sequence of float
        Its values, in SI units.
    growth : callable
        ``growth(value)``: the linearized drive's largest real part in 1/s (> 0: linearly unstable).
    restForceFactor : float
        A settled run whose largest normal force stays below this multiple of the static one stays in contact.
    start : array_like, optional
        Flow state the first point's time simulation starts from (e.g. the last orbit of the continuation); each
        further point's starts from the state its neighbour settled to, so that the chatter is followed (default:
        the first from the kicked steady state).
    onPoint : callable, optional
        Called with each orbit's :class:`~exudyn_worm.analysis.orbits.continuation.BranchPoint`.

    Returns
    -------
    (list of BranchPoint, list of dict)
        The orbits (``info``: the amplitudes of
        :func:`~exudyn_worm.analysis.orbits.chatter.OrbitAmplitude`, ``method`` 'shooting', ``residual``,
        ``settledS``), and the points without an orbit: ``value``, ``method`` ('rest' or 'long simulation'),
        ``frequencyHz`` (of the settled run, nan without oscillation), ``amplitude`` (its last 0.5 s),
        ``residual`` (the best shooting iterate's, None where no shooting was tried), ``linearGrowth`` (1/s),
        ``settled``, ``settledS``, ``sectionChange``, ``stabilityDecided`` (True for 'rest': the linear analysis
        decides it; False for 'long simulation') and ``reason``.
    """
    orbits, simulated = [], []
    for value in values:
        model = BuildRigidBodyLoweringModel(drive.Replace(**{name: value}))
        settled = SettleOnSection(model, initialState=start)
        start = settled['state']
        rate = float(growth(value))
        vibration = settled['vibration']
        common = {'settled': bool(settled['settled']), 'settledS': float(settled['duration']),
                  'sectionChange': float(settled['change']), 'linearGrowth': rate}
        inContact = not np.isfinite(settled['period']) or vibration['forceFactor'] < restForceFactor
        # in contact and sliding forward the mesh's law is linear: a linearly stable drive's vibration decays
        if rate < 0 and inContact and vibration['minWormSpeed'] > 0:
            simulated.append(_Simulated(value, 'rest', settled, None, True, common,
                                        'linearly stable and the settled run stays in contact with the worm '
                                        'sliding forward: it decays at the linear rate'))
            continue
        if inContact:
            # an orbit in contact is one of the linearized drive, whose amplitude the mesh does not fix: not shot
            simulated.append(_Simulated(value, 'long simulation', settled, None, False, common,
                                        f"linearly unstable (growth {rate:.2g} 1/s), but the run still stays in "
                                        f"contact after {settled['duration']:g} s: the chatter has not developed"))
            continue
        try:
            orbit = FindSteadyChatter(model.whole, model=model, start=(settled['state'], settled['period']))
        except ShootingError as err:
            last = err.lastOrbit
            residual = float(last.residual) if last is not None else math.nan
            if not residual <= SETTLED_ORBIT_TOLERANCE:
                simulated.append(_Simulated(value, 'long simulation', settled, residual, False, common,
                                            f"shooting from the settled run stopped at a residual of {residual:.2g} "
                                            f"of the state scale (accepted: {SETTLED_ORBIT_TOLERANCE:g})"))
                continue
            orbit = _AcceptedOrbit(model, last)
        info = {k: v for k, v in orbit.info.items() if k not in ('model', 'flow')}
        orbit.info.clear()
        info.update(method='shooting', residual=float(orbit.residual), settledS=common['settledS'])
        point = BranchPoint(float(value), orbit, info)
        orbits.append(point)
        if onPoint is not None:
            onPoint(point)
    return orbits, simulated


def _AcceptedOrbit(model, last: PeriodicOrbit) -> PeriodicOrbit:
    """The last Newton iterate as an orbit (``converged`` False), with the monodromy matrix and the amplitudes a
    converged orbit has (central differences, :data:`~exudyn_worm.analysis.orbits.chatter.MONODROMY_PERTURBATION`)."""
    flow = _LoweringFlow(model, STEPS_PER_PERIOD)
    x, T = np.asarray(last.state, dtype=float), float(last.period)
    orbit = PeriodicOrbit(state=x, period=T,
                          monodromy=Monodromy(flow, x, T, StateScale(model), MONODROMY_PERTURBATION, central=True),
                          velocity=FlowVelocity(flow, x, T), residual=float(last.residual),
                          iterations=last.iterations, converged=False)
    orbit.info.update(OrbitAmplitude(model, flow, x, T))
    return orbit


def _Simulated(value: float, method: str, settled: Dict[str, Any], residual: Optional[float], decided: bool,
               common: Dict[str, Any], reason: str) -> Dict[str, Any]:
    """A point without an orbit: the settled run's vibration."""
    period = float(settled['period'])
    return {'value': float(value), 'method': method,
            'frequencyHz': 1. / period if np.isfinite(period) else math.nan,
            'amplitude': {k: float(v) for k, v in settled['vibration'].items()},
            'residual': residual, 'stabilityDecided': decided, 'reason': reason, **common}
