"""How strong the chatter gets along one parameter: the branch of steady chatter orbits of the lowering phase.

:func:`AnalyzeChatterBranch` finds the steady chatter (:func:`~exudyn_worm.analysis.orbits.chatter.FindSteadyChatter`) where the
drive is linearly unstable, follows it by pseudo-arclength continuation
(:func:`~exudyn_worm.analysis.orbits.continuation.ContinueOrbits`) in both directions until the orbit shrinks into the linear
range of the mesh (its largest normal force below twice the static force: the orbit no longer loses contact,
it is one of the neutral orbits of the linearized drive, i.e. the branch has reached its Hopf point) or leaves
the range, and reports per point the amplitude (normal-force factor, largest ``|phi2''|``), the frequency and the
Floquet stability; for the branch the Hopf points beside the linear boundaries (roots of the largest real part
of the S = -1 eigenvalues, :func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive`), their type, the folds and the
ranges in which rest and stable chatter coexist. The smooth branch from a linear boundary (speed-dependent friction)
is :mod:`exudyn_worm.analysis.orbits.smoothbranch`, the smallest disturbance that starts chatter
:mod:`exudyn_worm.analysis.orbits.disturbance`.
"""
from __future__ import annotations

import math
import multiprocessing
import os
import sys
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass, field
from typing import Callable, Dict, List, Optional, Tuple

import numpy as np

from .chatter import MONODROMY_PERTURBATION, FindSteadyChatter, OrbitAmplitude, _ElasticBearings, _SettledStart
from .lowering import (BuildLoweringModel, BuildRigidBodyLoweringModel, LoweringModel, StateScale,
                       UpdateLoweringModel, _LoweringFlow)
from .settling import SettleOnSection
from .settledbranch import SettledBranchPoints, SettledValues
from .continuation import Branch, BranchPoint, ContinueOrbits, StopKind
from .periodic import PeriodicOrbit, ShootingError
from ..._checks import CheckPositive
from ...items.bearings import BEARING_LOADS
from ...drive.wholedrive import CheckDrive, Drive
from ..stability.drivestability import AnalyzeDrive
from ..._workers import CancelPool, SignalsHeld, WorkerInit
from ...params.parameters import PARAMETERS
from ...drive.presets import BODY_KEYS
from .disturbance import COEXISTENCE_KICK, SmallestDisturbance
from .smoothbranch import ChatterBranchError, SmoothHopfBranch

# prefixes of the chain keys (``J4, k4, d4``, ``JL1, kL1, dL1``, ...)
_SERIES_PREFIXES = tuple(p for table in PARAMETERS.arrayTables.values() for p in table.values())

__all__ = ['CONTINUABLE', 'ChatterBranch', 'LinearBoundaries', 'AnalyzeChatterBranch', 'REST_FORCE_FACTOR',
           'BEARING_LOAD_KEYS', 'NEAR_ONE']

#: parameters that can be continued (flat parameter keys, SI units); ``muStatic`` and ``stribeckVelocity`` exist
#: with the Stribeck friction law
CONTINUABLE = ('J1', 'J2', 'kT', 'dT', 'DT', 'DTV', 'kV', 'dV', 'DV', 'mu', 'muStatic', 'stribeckVelocity',
               'backlash', 'motorSpeed', 'loadMass', 'leverArm')
#: the largest bearing loads in N that :func:`~exudyn_worm.analysis.orbits.chatter.OrbitAmplitude` measures on an orbit of
#: the 3D model, as each branch point's ``info`` and ``ToDict()['points'][i]['amplitude']`` hold them
BEARING_LOAD_KEYS = tuple(key for key, _ in BEARING_LOADS)
#: on the 3D model with elastic bearings, a largest nontrivial Floquet multiplier this close to 1 is within the
#: uncertainty of the finite-difference monodromy (0.987-0.994 from two starts of the same orbit, reel-3d-chatter.toml,
#: docs/chatter-amplitude.md): a message says so
NEAR_ONE = 0.01
#: an orbit whose largest normal force is below this multiple of the static force stays in contact all the time:
#: it is an orbit of the linearized drive, so the branch has reached its Hopf point (the linear boundary)
REST_FORCE_FACTOR = 1.9


@dataclass
class ChatterBranch:
    """Result of :func:`AnalyzeChatterBranch`.

    Attributes
    ----------
    parameter : str
        The continued parameter.
    bounds : (float, float)
        The range.
    points : list of BranchPoint
        Orbits along the branch, ordered along the arclength; ``info`` holds ``forceFactor``,
        ``maxWheelAcceleration`` (rad/s^2), ``minWormSpeed`` (rad/s), and on the 3D model the largest bearing loads
        in N (:data:`BEARING_LOAD_KEYS`).
    linearBoundaries : list of float
        Parameter values in the range where the linearized drive (S = -1) changes stability.
    hopf : list of dict
        ``value``, ``type`` ('supercritical' or 'subcritical'), ``linearBoundary`` and ``relativeDifference``.
    folds : list of float
        Parameter values where the branch turns.
    coexistence : list of (float, float)
        Ranges where the drive is linearly stable and a stable chatter orbit exists.
    disturbances : list of dict
        In the middle of each coexistence range: ``value``, the smallest initial worm-speed disturbance that ends
        in chatter as a fraction of the motor speed (``wormSpeedFraction``) and in rad/s (``wormSpeed``).
    messages : list of str
        Why each end of the branch stopped, and anything the user should know.
    model : str
        ``'one-angle'`` or ``'3D'`` (worm and wheel as rigid bodies on their shafts' bearings).
    settling : dict or None
        On the 3D model with elastic bearings: how the first orbit's start was settled
        (:func:`~exudyn_worm.analysis.orbits.settling.SettleOnSection`: ``value``, ``duration`` and ``change``), else None.
    simulated : list of dict
        On the 3D model with elastic bearings, where the continuation failed: the natural-parameter points without
        an orbit (:func:`~exudyn_worm.analysis.orbits.settledbranch.SettledBranchPoints`: 'rest' or 'long
        simulation', with the settled run's vibration), by value.
    """
    parameter: str
    bounds: Tuple[float, float]
    points: List[BranchPoint] = field(default_factory=list)
    linearBoundaries: List[float] = field(default_factory=list)
    hopf: List[Dict] = field(default_factory=list)
    folds: List[float] = field(default_factory=list)
    coexistence: List[Tuple[float, float]] = field(default_factory=list)
    disturbances: List[Dict] = field(default_factory=list)
    messages: List[str] = field(default_factory=list)
    model: str = 'one-angle'
    settling: Optional[Dict] = None
    simulated: List[Dict] = field(default_factory=list)

    def ToDict(self) -> Dict:
        """JSON-ready dictionary: ``{"parameter", "hopf": {"value", "type"}, "folds", "points": [...], ...}``
        (``hopf`` is the first Hopf point or None; ``hopfPoints`` lists all). On the 3D model also ``model`` ('3D'),
        ``settling``, ``simulated`` and, per point, the largest bearing loads in N in ``amplitude``
        (:data:`BEARING_LOAD_KEYS`), ``residual`` and ``method``."""
        out = {'parameter': self.parameter, 'range': list(self.bounds),
                'hopf': ({'value': self.hopf[0]['value'], 'type': self.hopf[0]['type']} if self.hopf else None),
                'hopfPoints': [dict(h) for h in self.hopf], 'linearBoundaries': list(self.linearBoundaries),
                'folds': list(self.folds), 'coexistence': [list(c) for c in self.coexistence],
                'disturbances': [dict(d) for d in self.disturbances],
                'points': [{'value': float(p.value),
                            'amplitude': {'forceFactor': p.info.get('forceFactor'),
                                          'maxWheelAcceleration': p.info.get('maxWheelAcceleration'),
                                          **{k: float(p.info[k]) for k in BEARING_LOAD_KEYS if k in p.info}},
                            'frequencyHz': float(p.orbit.frequencyHz), 'stable': bool(p.stable),
                            'multipliers': [abs(complex(m)) for m in p.orbit.nontrivialMultipliers],
                            'trivialMultiplierError': p.orbit.trivialMultiplierError,
                            'stabilityDecided': bool(p.orbit.stabilityDecided)}
                           for p in self.points],
                'messages': list(self.messages)}
        if self.model != 'one-angle':
            out.update(model=self.model, settling=None if self.settling is None else dict(self.settling),
                       simulated=[dict(s, amplitude=dict(s['amplitude'])) for s in self.simulated])
            for p, d in zip(self.points, out['points']):
                d.update(residual=float(p.orbit.residual), method=p.info.get('method', 'shooting'))
        return out

    def plot(self, fileName: Optional[str] = None, **kwargs):
        """Draw the branch (:func:`exudyn_worm.plotting.plot_orbits.PlotChatterBranch`)."""
        from ...plotting.plot_orbits import PlotChatterBranch
        return PlotChatterBranch(self, fileName=fileName, **kwargs)


def _BuildModel(drive: Drive) -> LoweringModel:
    """The lowering model of ``drive``: the 3D model (a drive with shaft bearings) or the one-angle model."""
    return BuildRigidBodyLoweringModel(drive) if drive.isRigidBody else BuildLoweringModel(drive)


def _MaxRealPart(drive: Drive) -> float:
    return float(AnalyzeDrive(drive).State(-1).maxRealPart)


def LinearBoundaries(drive: Drive, name: str, low: float, high: float, samples: int = 41
                     ) -> Tuple[List[float], Callable[[float], float]]:
    """Where the linearized drive (S = -1, the lowering phase) changes stability on ``[low, high]``.

    Parameters
    ----------
    drive : Drive
        The drive.
    name : str
        Parameter varied (its key, e.g. ``'J1'``).
    low, high : float
        Range.
    samples : int
        Scan points before the roots are refined (brentq).

    Returns
    -------
    (list of float, callable)
        The boundaries, and ``growth(value)``: the largest real part in 1/s at a value (> 0: unstable).
    """
    from scipy.optimize import brentq

    drive = CheckDrive('LinearBoundaries', drive)

    def Growth(v):
        return _MaxRealPart(drive.Replace(**{name: v}))
    grid = np.linspace(low, high, samples)
    values = [Growth(v) for v in grid]
    roots = [brentq(Growth, a, b, xtol=1e-12 * max(1., abs(b)), rtol=1e-12)
             for a, b, fa, fb in zip(grid[:-1], grid[1:], values[:-1], values[1:]) if fa * fb < 0]
    return roots, Growth


def _ComponentKeys(drive: Drive) -> List[str]:
    """The keys of the drive's drive-side and load-side chain stages and axial bearing (``J4, k4, d4, ...,
    JL1, kL1, dL1, ..., kA, dA, mA``) that can be continued too (each value rebuilds the lowering model); on the 3D
    model (a drive with shaft bearings) the shafts' bearing keys and the bodies' keys the drive gives
    (``wormRadialStiffness``, ..., ``wheelBearingSpan``, ``wormMass``, ``wheelTiltInertia``, ...)."""
    parameters = drive.parameters
    if drive.isRigidBody:
        return [k for k in PARAMETERS.KeysOf('wormBearing') + PARAMETERS.KeysOf('wheelBearing')
                + BODY_KEYS + ('kA', 'dA', 'mA') if k in parameters]
    keys = [k for k in parameters if (PARAMETERS.SeriesIndex(k) or ('',))[0] in _SERIES_PREFIXES]
    if float(parameters.get('kA', 0.)) > 0:
        keys += [k for k in ('kA', 'dA', 'mA') if k in parameters]
    return keys


def AnalyzeChatterBranch(drive: Drive, name: str, low: float, high: float,
                         maxPoints: int = 60, settleTime: float = 1.0, onPoint: Optional[Callable] = None,
                         restarts: int = 3, stepLength: float = 0.5, processes: int = 2) -> ChatterBranch:
    """Branch of steady chatter of the lowering phase in parameter ``name`` over ``[low, high]``.

    On the 3D model (a drive with shaft bearings: worm and wheel as rigid bodies on their shafts' bearings,
    :func:`~exudyn_worm.analysis.orbits.lowering.BuildRigidBodyLoweringModel`) with elastic bearings the first orbit is
    found as without continuation (:func:`~exudyn_worm.analysis.orbits.chatter.SteadyChatterSummary`): shooting from a time
    simulation settled on its Poincare section (:func:`~exudyn_worm.analysis.orbits.settling.SettleOnSection`, about 14 s
    simulated for ``examples/drives/reel-3d-chatter.toml``), at the parameter set's own value of ``name`` where that lies in
    the range and the drive is linearly unstable there (else in the middle of the widest unstable interval, as on
    the one-angle model); the continuation then follows it from that orbit, and each point carries the largest
    bearing loads. Where a direction's corrector fails, the rest of the range towards that end comes by
    natural-parameter points, each from its own settled time simulation
    (:func:`~exudyn_worm.analysis.orbits.settledbranch.SettledBranchPoints`): orbits join ``points``, the points at rest
    or without an orbit go to ``simulated``.

    Parameters
    ----------
    drive : Drive
        A drive with the reel changer's duty (e.g. ``ResolveDrive('reel-P1')``; any other duty through
        :func:`~exudyn_worm.analysis.orbits.lowering.LoweringPhaseDrive`).
    name : str
        The parameter, one of :data:`CONTINUABLE`, or a key of the drive's drive-side or load-side chain
        (``J4, k4, d4, ...``, ``JL1, kL1, dL1, ...``) or axial bearing (``kA, dA, mA``); on the 3D model a key of
        the shafts' bearings or the bodies (mass, inertias, shape) that the set gives (``wormRadialStiffness``, ...,
        ``wheelBearingSpan``, ``wormMass``, ``wheelTiltInertia``, ...).
    low, high : float
        Range of the parameter in its SI unit, ``low < high``.
    maxPoints : int
        Largest number of orbits per direction.
    settleTime : float
        Time simulation in s before the first shooting (the 3D model with elastic bearings settles on its Poincare
        section instead, as long as it needs).
    onPoint : callable, optional
        Called with each new :class:`~exudyn_worm.analysis.orbits.continuation.BranchPoint`.
    restarts : int
        How often a direction may start again from a time simulation a little further on when the corrector is
        stuck (at a kink of the non-smooth map); each restart is noted in ``messages``.
    stepLength : float
        First continuation step in scaled units (the parameter in units of 1/25 of the range, the state in units
        of :func:`~exudyn_worm.analysis.orbits.lowering.StateScale`), > 0; the step grows to at most 4 times this after easy steps
        (a smaller value gives more orbits along the branch).
    processes : int
        Worker processes: with 2 (default) the two directions of the branch from the first orbit are computed at
        the same time in two processes (Linux, fork; each builds its own model), with 1 one after the other. The
        results are the same; ``onPoint`` is then called once a direction is done.

    Returns
    -------
    ChatterBranch

    Raises
    ------
    ValueError
        For a parameter that cannot be continued or a bad range.
    ChatterBranchError
        If the drive is linearly stable on the whole range (no chatter to follow), or the first orbit cannot be
        found; ``.branch`` keeps what was computed.
    """
    w = 'AnalyzeChatterBranch'
    drive = CheckDrive(w, drive)
    rigidBody = drive.isRigidBody
    components = _ComponentKeys(drive)
    if name not in CONTINUABLE and name not in components:
        extra = ', '.join(components)
        what = "shaft bearings and bodies' masses" if rigidBody else "chains and axial bearing"
        raise ValueError(f"{w}: parameter {name!r} cannot be continued; choose one of {', '.join(CONTINUABLE)}"
                         + (f" or a key of this drive's {what} ({extra})" if extra else ''))
    low, high = float(low), float(high)
    if not (math.isfinite(low) and math.isfinite(high) and low < high):
        raise ValueError(f"{w}: the range of {name} must be two finite numbers low < high, got {low:g}:{high:g}")
    stepLength = CheckPositive(w, 'stepLength', stepLength)
    if isinstance(processes, bool) or not isinstance(processes, int) or processes < 1:
        raise ValueError(f"{w}: 'processes' must be an integer >= 1, got {processes!r}")
    _BuildModel(drive.Replace(**{name: low}))         # checks the drive and the low end early
    roots, Growth = LinearBoundaries(drive, name, low, high)
    result = ChatterBranch(name, (low, high), linearBoundaries=roots, model='3D' if rigidBody else 'one-angle')
    # a friction law that falls with the sliding speed can limit the chatter while the mesh stays in contact: the
    # branch then leaves a linear boundary with zero amplitude (a smooth Hopf point), which the continuation below
    # (from an orbit that loses contact, stopped where the orbit stays in contact) cannot follow
    if roots and _SpeedDependentFriction(drive) and _SmoothBranches(drive, name, low, high, roots, Growth, maxPoints,
                                                                    onPoint, result):
        return result
    # start in the middle of the widest linearly unstable interval
    edges = [low] + roots + [high]
    unstable = [(a, b) for a, b in zip(edges[:-1], edges[1:]) if Growth(0.5 * (a + b)) > 0]
    own = drive.parameters.get(name)
    if unstable and rigidBody and own is not None and low <= own <= high and Growth(own) > 0:
        # the 3D model: at the drive's own value, where the first orbit is the one without continuation (shooting
        # from the settled start converges there; in the middle of reel-3d-chatter.toml's unstable interval of
        # wheelRadialStiffness in [5e8, 2e9], 1.112e9 N/m, it stalled at a residual of 0.016)
        start, kick = float(own), 0.01
    elif unstable:
        a, b = max(unstable, key=lambda ab: ab[1] - ab[0])
        start, kick = 0.5 * (a + b), 0.01
    else:
        # linearly stable everywhere: chatter can still coexist with rest; look for it after a large kick
        start, kick = 0.5 * (low + high), COEXISTENCE_KICK
    model = _BuildModel(drive.Replace(**{name: start}))
    try:
        orbit = _FirstOrbit(model, settleTime, kick, result)
    except ShootingError as err:
        if not unstable:
            raise ChatterBranchError(f"{w}: the drive is linearly stable for every {name} in [{low:g}, {high:g}] "
                                     f"(largest real part {max(Growth(low), Growth(high)):.3g} 1/s at the ends), and "
                                     f"a worm-speed kick of {COEXISTENCE_KICK:.0%} of the motor speed at {name} = "
                                     f"{start:g} dies out: no chatter found on this range; widen the range or pick a "
                                     f"parameter set that chatters (e.g. reel-P1)", result) from err
        hint = ''
        if not roots and _SpeedDependentFriction(drive):
            hint = (f"; with a speed-dependent friction law the chatter near a linear boundary is small and settles "
                    f"slowly: include the linear boundary in the range, the branch is then followed from its Hopf "
                    f"point")
        raise ChatterBranchError(f"{w}: no steady chatter found at {name} = {start:g}: {err}{hint}", result) from err
    if not unstable:
        result.messages.append(f"linearly stable on the whole range; chatter found at {name} = {start:g} after a kick "
                               f"of {kick:.0%} of the motor speed")
    scale = StateScale(model)
    scaleP = (high - low) / 25.
    # the start orbit without its model and flow (those cannot be pickled): each direction builds its own
    seed = PeriodicOrbit(state=orbit.state, period=orbit.period, monodromy=orbit.monodromy, velocity=orbit.velocity,
                         residual=orbit.residual, iterations=orbit.iterations, converged=orbit.converged)
    jobs = [(drive, name, low, high, seed, start, scale, scaleP, direction, maxPoints, settleTime, restarts,
             stepLength, orbit.info['flow'].steps) for direction in (-1, 1)]
    halves = []
    for branch, messages in _RunDirections(jobs, processes, onPoint, result.messages):
        halves.append(branch)
        result.messages += messages
    result.points = [p for p in list(reversed(halves[0].points)) + halves[1].points[1:] if low <= p.value <= high]
    if _ElasticBearings(model):
        _SettledEnds(drive, name, low, high, halves, Growth, onPoint, result)
        near = [p.value for p in result.points
                if abs(max((abs(complex(m)) for m in p.orbit.nontrivialMultipliers), default=0.) - 1.) < NEAR_ONE]
        if near:
            result.messages.append(
                f"3D model: {len(near)} of {len(result.points)} orbits have their largest nontrivial Floquet multiplier "
                f"within {NEAR_ONE:g} of 1 (the wheel's barely damped tilt mode; the map is non-smooth at the level of "
                f"the bearings' kHz modes, so such multipliers are uncertain by about 0.01): their stability is not "
                f"decided by the multipliers")
    if not roots and unstable:
        result.messages.append(f"the drive is linearly unstable for every {name} in [{low:g}, {high:g}]: the range "
                               f"crosses no linear boundary, so the branch has no Hopf point in it")
    # Hopf points: ends at which the orbit shrank into the linear range
    for branch in halves:
        end = branch.points[-1]
        if end.info.get('forceFactor', math.inf) >= REST_FORCE_FACTOR:
            continue
        if not roots:       # no linear boundary to shrink into: an orbit held in contact by friction, no Hopf point
            result.messages.append(f"the branch ends at {name} = {end.value:.6g} with an orbit that stays in contact "
                                   f"(normal force up to {end.info['forceFactor']:.3g} times the static one); with no "
                                   f"linear boundary in the range this is not a Hopf point")
            continue
        nearest = min(roots, key=lambda r: abs(r - end.value))
        # kind of Hopf point: the last orbit before the vertical part that still loses contact lies on the linearly
        # unstable side (the branch comes out of the unstable range: supercritical) or on the stable side (subcritical)
        outer = [p for p in branch.points if p.info.get('forceFactor', 0.) >= 2.]
        side = Growth(outer[-1].value) if outer else math.nan
        result.hopf.append({'value': float(end.value), 'type': 'supercritical' if side > 0 else 'subcritical',
                            'linearBoundary': float(nearest),
                            'relativeDifference': float(abs(end.value - nearest) / abs(nearest))})
    for r in roots:
        if not any(abs(h['linearBoundary'] - r) <= 1e-9 * abs(r) for h in result.hopf):
            result.messages.append(f"the branch has no Hopf point at the linear boundary {name} = {r:.6g} (it passes "
                                   f"it or ends before); the small unstable orbits born there are not followed")
    # folds: a fold of periodic orbits has a Floquet multiplier through +1, so an orbit beside it is unstable;
    # turning points among stable orbits only (the finite-difference Jacobian through the mesh's switches lets the
    # corrector step back and forth where the branch is flat) and the vertical part at a Hopf point are left out
    real, ignored = [], 0
    for half in halves:
        for a, b, c in zip(half.points, half.points[1:], half.points[2:]):
            if (b.value - a.value) * (c.value - b.value) < 0 and b.info.get('forceFactor', 0.) >= 2.:
                if not (a.stable and b.stable and c.stable):
                    real.append(float(b.value))
                else:
                    ignored += 1
    result.folds = sorted(real)
    if ignored:
        result.messages.append(f"{ignored} turning point(s) without a change of stability ignored (numerical)")
    # coexistence: stable orbits where the drive is linearly stable
    inside = [p.value for p in result.points if p.stable and p.info.get('forceFactor', 0.) >= 2.
              and Growth(p.value) < 0]
    if inside:
        result.coexistence.append((float(min(inside)), float(max(inside))))
    if rigidBody and result.coexistence:
        result.messages.append("the smallest disturbance that starts chatter is computed on the one-angle model "
                               "only: not given for the 3D model")
    for lo, hi in ([] if rigidBody else result.coexistence):
        middle = 0.5 * (lo + hi)
        there = drive.Replace(**{name: middle})
        kick = SmallestDisturbance(there)
        result.disturbances.append({'value': middle, 'wormSpeedFraction': kick,
                                    'wormSpeed': kick * float(there.motor.speed)})
    return result


def _FirstOrbit(model: LoweringModel, settleTime: float, kick: float, result: ChatterBranch) -> PeriodicOrbit:
    """The branch's first orbit: :func:`~exudyn_worm.analysis.orbits.chatter.FindSteadyChatter` after ``settleTime``; on the
    3D model with elastic bearings from a run settled on the Poincare section
    (:func:`~exudyn_worm.analysis.orbits.settling.SettleOnSection`, noted in ``result.settling`` and ``messages``)."""
    if not _ElasticBearings(model):
        return FindSteadyChatter(model.whole, settleTime=settleTime, model=model, kick=kick)
    w = 'AnalyzeChatterBranch'
    settled = SettleOnSection(model, kick=kick)
    start = _SettledStart(model, w, 'the lowering phase', settled)
    value = model.whole.parameters[result.parameter]
    result.settling = {'value': float(value), 'duration': float(settled['duration']),
                       'change': float(settled['change']), 'settled': bool(settled['settled'])}
    orbit = FindSteadyChatter(model.whole, model=model, start=start)
    result.messages.append(f"3D model: the first orbit ({result.parameter} = {value:.6g}) by shooting from a "
                           f"{settled['duration']:g} s time simulation settled on the Poincare section (its section "
                           f"point moved by {settled['change']:.2g} of the state scale over the last 2 s)")
    return orbit


def _SettledEnds(drive: Drive, name: str, low: float, high: float, halves: List[Branch], Growth: Callable,
                 onPoint: Optional[Callable], result: ChatterBranch) -> None:
    """On the 3D model with elastic bearings: where a direction's corrector failed, the rest of the range by
    natural-parameter points, each from its own settled time simulation
    (:func:`~exudyn_worm.analysis.orbits.settledbranch.SettledBranchPoints`), put into ``result``."""
    ends = ([min(p.value for p in halves[0].points), low], [max(p.value for p in halves[1].points), high])
    for index, (half, (covered, end)) in enumerate(zip(halves, ends)):
        values = SettledValues(covered, end)
        if half.stopKinds[-1] is not StopKind.CORRECTOR_FAILED or not values:
            continue
        orbits, simulated = SettledBranchPoints(drive, name, values, Growth, REST_FORCE_FACTOR,
                                                half.points[-1].orbit.state, onPoint)
        result.points = (orbits[::-1] + result.points) if index == 0 else (result.points + orbits)
        result.simulated = sorted(result.simulated + simulated, key=lambda s: s['value'])
        kinds = [s['method'] for s in simulated]
        result.messages.append(
            f"3D model: {name} from {covered:.6g} to {end:.6g} by {len(values)} natural-parameter points (the "
            f"continuation's corrector failed), each shot from its own time simulation settled on the Poincare "
            f"section: {len(orbits)} orbits, {kinds.count('long simulation')} long simulations (no orbit), "
            f"{kinds.count('rest')} at rest (linearly stable, the mesh stays in contact)")


def _SpeedDependentFriction(drive: Drive) -> bool:
    """Whether the mesh's friction coefficient depends on the sliding speed. With a constant one the contact law is
    piecewise linear, so an orbit that stays in contact is one of the linearized drive: no smooth Hopf branch."""
    return drive.gear.frictionLaw.kind != 'constant'


def _SmoothBranches(drive: Drive, name: str, low: float, high: float, roots: List[float], Growth: Callable,
                    maxPoints: int, onPoint: Optional[Callable], result: ChatterBranch) -> bool:
    """The smooth branches (:func:`~exudyn_worm.analysis.orbits.smoothbranch.SmoothHopfBranch`) from the linear boundaries ``roots`` into their linearly
    unstable sides, put into ``result``; False (only why in ``result.messages``) if no boundary has one (each
    start orbit loses contact or none is found): the branch is then limited by the mesh."""
    edges = [low] + list(roots) + [high]
    found, notes = [], []
    for i, r in enumerate(roots, start=1):
        above = Growth(0.5 * (r + edges[i + 1])) > 0
        side, limit = (1, edges[i + 1]) if above else (-1, edges[i - 1])
        try:
            found.append(SmoothHopfBranch(drive, name, r, side, limit=limit, maxPoints=maxPoints,
                                          maxSeedForceFactor=REST_FORCE_FACTOR, onPoint=onPoint))
        except (ShootingError, ChatterBranchError) as err:
            notes.append(f"no smooth branch from the linear boundary {name} = {r:.6g}: {str(err).split(';')[0]}")
    if not found:
        result.messages += notes
        return False
    result.points = sorted((p for b in found for p in b.points), key=lambda p: p.value)
    result.hopf = [b.hopf for b in found if b.hopf is not None]
    for b in found:
        result.messages.append(f"smooth branch from the linear boundary {name} = {b.boundary:.6g} (the orbits stay in "
                               f"contact: the speed-dependent friction limits the chatter): "
                               f"{len(b.points)} orbits by natural-parameter continuation from a settled time "
                               f"simulation, the Hopf point where the squared largest |phi2''| extrapolates to zero")
        result.messages += b.messages
        result.messages += [f"no orbit at {name} = {v:.6g}: {why}" for v, why in b.failed]
    result.messages += notes
    return True


def _FollowDirection(drive: Drive, name: str, low: float, high: float, start: PeriodicOrbit, value: float,
                     scale: np.ndarray, scaleP: float, direction: int, maxPoints: int, settleTime: float,
                     restarts: int, stepLength: float, steps: int, onPoint: Optional[Callable] = None) -> Tuple[Branch, List[str]]:
    """One direction of the branch from ``start`` at ``value``: continuation, and restarts from a time simulation
    where the corrector is stuck (on the 3D model: shooting from the last orbit, whose slow tilt modes a short
    simulation would not settle). Builds its own model, so that it can run in a worker process."""
    rigidBody = drive.isRigidBody
    model = _BuildModel(drive.Replace(**{name: value}))
    current = {'model': model, 'flow': _LoweringFlow(model, steps)}
    messages = []

    def ModelAt(v):
        m = current['model']
        new = UpdateLoweringModel(m, drive.Replace(**{name: v}))
        if new is not m:
            current['flow'] = _LoweringFlow(new, current['flow'].steps)
            current['model'] = new
        return current['model'], current['flow']

    def FlowAt(v):
        return ModelAt(v)[1]

    def Measure(v, orb):
        m, flow = ModelAt(v)
        return OrbitAmplitude(m, flow, orb.state, orb.period)

    def Stop(point):
        if point.info['forceFactor'] < REST_FORCE_FACTOR:
            return (f"stopped at {name} = {point.value:.6g}: the orbit stays in contact (at a linear boundary, or held "
                    f"by friction)")
        return None

    side = 'lower' if direction < 0 else 'higher'
    settings = dict(stepLength=stepLength, maxStepLength=4. * stepLength, minStepLength=0.02, measure=Measure,
                    stop=Stop, onPoint=onPoint, monodromyPerturbation=MONODROMY_PERTURBATION)
    branch = ContinueOrbits(FlowAt, start, value, (low, high), scale, scaleP, name, direction=direction,
                            maxPoints=maxPoints, **settings)
    messages += [f"towards {side} {name}: {r}" for r in branch.stopReason]
    for _ in range(restarts):
        last = branch.points[-1]
        if branch.stopKinds[-1] is not StopKind.CORRECTOR_FAILED or len(branch.points) > maxPoints:
            break
        # the corrector is stuck at a kink of the map (e.g. the orbit starts to touch the other flank): start
        # again from a time simulation a little further on (from the last orbit), and continue from there
        again = last.value + direction * scaleP
        if not low <= again <= high:
            break
        m, _ = ModelAt(again)
        try:
            if rigidBody:
                orbit = FindSteadyChatter(m.whole, model=m,
                                          start=(last.orbit.state, last.orbit.period))
            else:
                orbit = FindSteadyChatter(m.whole, settleTime=settleTime, model=m,
                                          initialState=last.orbit.state)
        except ShootingError:
            messages.append(f"towards {side} {name}: no steady chatter found again at {name} = {again:.6g}")
            break
        current['flow'] = orbit.info['flow']
        messages.append(f"towards {side} {name}: restarted from "
                        + ("the last orbit" if rigidBody else "a time simulation") + f" at {name} = {again:.6g}")
        orbit.info.clear()
        more = ContinueOrbits(FlowAt, orbit, again, (low, high), scale, scaleP, name, direction=direction,
                              maxPoints=maxPoints - len(branch.points), **settings)
        branch.points += more.points
        branch.folds += more.folds
        branch.stopReason, branch.stopKinds = more.stopReason, more.stopKinds
        messages += [f"towards {side} {name}: {r}" for r in more.stopReason]
    return branch, messages


def _FollowDirectionJob(job: Tuple) -> Tuple[Branch, List[str]]:
    return _FollowDirection(*job)


def _RunDirections(jobs: List[Tuple], processes: int, onPoint: Optional[Callable], messages: List[str]
                   ) -> List[Tuple[Branch, List[str]]]:
    """Both directions of the branch: in two worker processes (fork, Linux) if ``processes`` >= 2, else one after
    the other (also when the workers cannot start; noted in ``messages``). ``onPoint`` is called as the points
    come (serial) or for each point once a direction is done (parallel)."""
    if processes >= 2 and sys.platform.startswith('linux'):
        try:
            context = multiprocessing.get_context('fork')
            # workers end with this process (Ctrl-C, SIGTERM, kill -9) and print no traceback of their own
            pool = ProcessPoolExecutor(max_workers=2, mp_context=context, initializer=WorkerInit,
                                       initargs=(os.getpid(),))
            futures = []
            try:
                with SignalsHeld():                    # the first submit forks the workers
                    futures.append(pool.submit(_FollowDirectionJob, jobs[0]))
                futures += [pool.submit(_FollowDirectionJob, job) for job in jobs[1:]]
                results = [future.result() for future in futures]
            except BaseException:
                CancelPool(pool, futures)              # at once: no waiting for the running directions
                raise
            pool.shutdown(wait=True)
        except (OSError, BrokenProcessPool) as err:
            messages.append(f"worker processes could not run ({type(err).__name__}: {err}); computed serially")
        else:
            if onPoint is not None:
                for branch, _ in results:
                    for point in branch.points[1:]:
                        onPoint(point)
            return results
    return [_FollowDirection(*job, onPoint=onPoint) for job in jobs]


