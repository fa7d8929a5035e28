"""The static equilibrium under load of a worm-gear drive: the starting state of a simulation or a linearization.

Topology (worm side of the mesh, as Figure 19; wheel side, a load-side chain of any length)::

    motor phi0 --(kn)-- ... --(k5)-- J5 --(k4)-- J4 --(kT)-- worm J1 ==mesh== wheel J2 --(kL1)-- JL1 --(kL2)-- ... JLm
                                                                                                               <- load M

At a constant speed (every rotor of the worm side turning at the motor speed, every rotor of the wheel side at
motor speed / u) the damping torques vanish and every spring carries the torque that passes through it:

- the mesh carries the load, wheelTorque + M = 0, solved for the normal deflection Delta s with the contact law
  itself (:func:`~exudyn_worm.model.contact.MeshContact`, friction included);
- each load-side shaft i is pre-twisted by M / kLi (its far end turned ahead by M / kLi when M > 0);
- each drive-side spring (kT, k4, ...) carries the worm's mesh torque: twist -wormTorque / k;
- an axial bearing carries the mesh's axial force: kA xA = axial force.

:func:`~exudyn_worm.analysis.stability.linearization.AnalyzeLinearStability` linearizes a system about its initial state, in
which every mesh must be in contact: start your own Exudyn model from this state (docs/equilibrium.md).
"""
from __future__ import annotations

import math
from numbers import Real
from typing import Any, Dict, Optional, Sequence, Tuple

from .._checks import CheckNonNegative, CheckPositive, CheckReal
from .._roots import FindRoot
from ..model.drive import AxialBearing
from ..model.contact import ContactOptions, MeshContact
from ..model.friction import MATH_OPS
from ..model.drive import ElasticDrive

__all__ = ['SteadyInitialState', 'LoadSideStages']

#: fixed-point steps at most for a load that depends on its angle, and the relative change of the load torque
#: at which they stop (with a load-side chain)
_MAX_STEPS = 100
_TORQUE_RTOL = 1e-14


def LoadSideStages(loadSide: Sequence[Sequence[float]], where: str = 'SteadyInitialState') -> Tuple[Tuple[float, float, float], ...]:
    """Check a load-side chain and return it as ``((J, k, d), ...)``, wheel side first.

    Parameters
    ----------
    loadSide : sequence of (J, k) or (J, k, d)
        Inertia in kg*m^2 (> 0), stiffness in N*m/rad (> 0) of the shaft on its wheel side and its damping in
        N*m*s/rad (>= 0, default 0), from the wheel to the driven machine.
    where : str
        Prefix of error messages.

    Returns
    -------
    tuple of (float, float, float)

    Raises
    ------
    TypeError, ValueError
        For a stage that is not 2 or 3 numbers or a value out of range.
    """
    if isinstance(loadSide, (str, bytes)) or not hasattr(loadSide, '__iter__'):
        raise TypeError(f"{where}: 'loadSide' must be a sequence of (inertia, stiffness[, damping]) stages, "
                        f"got {type(loadSide).__name__} {loadSide!r}")
    stages = []
    for i, stage in enumerate(loadSide, start=1):
        if isinstance(stage, (str, bytes)) or not hasattr(stage, '__len__') or len(stage) not in (2, 3):
            raise TypeError(f"{where}: 'loadSide' stage {i} must be (inertia kg*m^2, stiffness N*m/rad[, damping "
                            f"N*m*s/rad]), got {stage!r}")
        J = CheckPositive(where, f'loadSide[{i - 1}] inertia', stage[0], 'kg*m^2')
        k = CheckPositive(where, f'loadSide[{i - 1}] stiffness', stage[1], 'N*m/rad')
        d = CheckNonNegative(where, f'loadSide[{i - 1}] damping', stage[2] if len(stage) == 3 else 0., 'N*m*s/rad')
        stages.append((J, k, d))
    return tuple(stages)


def _LoadTorque(load, angle: float, speed: float, where: str) -> float:
    if load is None:
        return 0.
    if isinstance(load, Real) and not isinstance(load, bool):
        return CheckReal(where, 'load', load, 'N*m')
    return float(load.Torque(angle, speed, 0., MATH_OPS))


def SteadyInitialState(drive: ElasticDrive, load: Optional[Any] = None, motorSpeed: float = 0.,
                       options: ContactOptions = ContactOptions(), axialBearing: Optional[AxialBearing] = None,
                       chain: Sequence[Tuple[float, float, float]] = (),
                       loadSide: Sequence[Sequence[float]] = ()) -> Dict[str, float]:
    """Static equilibrium at t = 0 under the load, every rotor moving at its nominal speed.

    Solves the wheel balance (mesh torque = -load torque) for Delta s with the contact law itself, the
    worm balance (shaft torque = mesh torque) for the twist of the drive shaft, and pre-twists every spring of
    the drive-side and load-side chains by the torque it carries over its stiffness, so that a run or a
    linearization starts without a spurious transient (module docstring for the topology).

    Parameters
    ----------
    drive : ElasticDrive
        The drive (gear, J1, J2, kT, dT).
    load : object with ``Torque(phi, omega, t, ops)``, float or None, optional
        The load torque in N*m on the last rotor of the wheel side (the wheel without a load-side chain), positive
        in the direction of positive wheel rotation: e.g. :class:`~exudyn_worm.model.profiles.GravityLeverTorque`
        (evaluated at that rotor's angle and speed, t = 0), a constant torque, or None (no load).
    motorSpeed : float, optional
        Motor (and worm) speed in rad/s, phi0(0) = 0. At 0 the contact law's regularized friction vanishes: the
        state is the frictionless one.
    options : ContactOptions, optional
        Options of the contact law.
    axialBearing : AxialBearing, optional
        The worm's axial bearing (None: axially rigid worm).
    chain : sequence of (J, k, d), optional
        Drive-side chain, worm side first (:func:`~exudyn_worm.drive.presets.DriveSideChain`): inertia i and the
        spring-damper on its motor side.
    loadSide : sequence of (J, k) or (J, k, d), optional
        Load-side chain, wheel side first: inertia i in kg*m^2 and the shaft on its wheel side in N*m/rad (and
        N*m*s/rad); the load acts on the last inertia.

    Returns
    -------
    dict
        ``phi1, phi2`` in rad and ``omega1, omega2`` in rad/s; with a drive-side chain ``phi4, omega4, ...``;
        with a load-side chain ``phiL1, omegaL1, ...`` (wheel side first); with an axial bearing ``xA``
        in m and ``vA`` in m/s.

    Raises
    ------
    TypeError, ValueError
        For a ``drive`` that is not an :class:`ElasticDrive`, ``options`` that are not
        :class:`~exudyn_worm.model.contact.ContactOptions`, a ``load`` without ``Torque``, a non-finite
        ``motorSpeed`` or a bad chain stage.

    Examples
    --------
    >>> from exudyn_worm.drive.presets import DriveFromParameters, GetPreset
    >>> drive = DriveFromParameters(GetPreset('reel-P1'))
    >>> state = SteadyInitialState(drive, load=-2000., motorSpeed=49.48, loadSide=[(0.5, 2e4)])
    >>> round((state['phiL1'] - state['phi2']) * 2e4, 6)          # the load shaft carries the load: M / k
    -2000.0
    """
    w = 'SteadyInitialState'
    if not isinstance(drive, ElasticDrive):
        raise TypeError(f"{w}: 'drive' must be an ElasticDrive (e.g. DriveFromParameters(...)), "
                        f"got {type(drive).__name__}")
    if not isinstance(options, ContactOptions):
        raise TypeError(f"{w}: 'options' must be a ContactOptions, got {type(options).__name__} {options!r}")
    if load is not None and not isinstance(load, Real) and not callable(getattr(load, 'Torque', None)):
        raise TypeError(f"{w}: 'load' must be None, a torque in N*m or have Torque(phi, omega, t, ops) (e.g. "
                        f"GravityLeverTorque), got {type(load).__name__} {load!r}")
    motorSpeed = CheckReal(w, 'motorSpeed', motorSpeed, 'rad/s')
    stages = LoadSideStages(loadSide, w)
    g = drive.gear
    u = g.ratio
    omega1, omega2 = motorSpeed, motorSpeed / u
    phi2 = phiEnd = 0.
    # the load may depend on the angle it acts at: fixed-point steps. Three for a load on the wheel (the steps
    # of the reel changer's start, whose results stay as they were); behind a load-side chain the load's angle
    # moves more with the load, so the steps go on until the load torque is settled
    for step in range(_MAX_STEPS):
        loadTorque = _LoadTorque(load, phiEnd, omega2, w)
        if step >= 3 and (not stages or abs(loadTorque - lastTorque) <= _TORQUE_RTOL * abs(loadTorque)):
            break
        lastTorque = loadTorque

        def WheelBalance(deltaS):
            deltaPhi = deltaS / g.normalLever
            return MeshContact(g, deltaPhi, 0., omega1, omega2, options, MATH_OPS).wheelTorque + loadTorque

        span = 0.5 * g.backlash + 10 * (abs(loadTorque) / g.r2 + 1.) / g.kV
        deltaS = FindRoot(WheelBalance, -span, span, xtol=1e-15) if loadTorque != 0 else 0.
        mesh = MeshContact(g, deltaS / g.normalLever, 0., omega1, omega2, options, MATH_OPS)
        wormTorque = mesh.wormTorque
        xA = 0. if axialBearing is None else mesh.axialForce / axialBearing.stiffness   # kA xA = axial mesh force
        deltaPhi = (deltaS - g.axialLever * xA) / g.normalLever
        # every spring-damper between motor and worm carries -wormTorque: k (phi_motorSide - phi) + wormTorque = 0
        angles, phi = [], 0.                               # phi0(0) = 0
        for _, k, _ in reversed(chain):
            phi += wormTorque / k
            angles.append(phi)
        phi1 = phi + wormTorque / drive.kT
        phi2 = (phi1 - deltaPhi) / u
        # every load-side shaft carries the load: kL (phi_wheelSide - phi) + loadTorque = 0
        loadAngles, phiEnd = [], phi2
        for _, k, _ in stages:
            phiEnd += loadTorque / k
            loadAngles.append(phiEnd)
    else:
        raise ValueError(f"{w}: the load torque at the end of the load-side chain did not settle in {_MAX_STEPS} "
                         f"steps (last change {abs(loadTorque - lastTorque):.3g} N*m): the load changes too fast "
                         f"with its angle for the chain's stiffness")
    state = {'phi1': phi1, 'phi2': phi2, 'omega1': omega1, 'omega2': omega2}
    for i, angle in enumerate(reversed(angles), start=4):
        state[f'phi{i}'], state[f'omega{i}'] = angle, omega1
    for i, angle in enumerate(loadAngles, start=1):
        state[f'phiL{i}'], state[f'omegaL{i}'] = angle, omega2
    if axialBearing is not None:
        state.update(xA=xA, vA=0.)
    return state
