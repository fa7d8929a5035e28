"""The worm-gear contact law: the one place where mesh forces are computed.

The same function :func:`MeshContact` is evaluated
- recorded as an Exudyn symbolic expression (C++) inside the connector,
- with plain Python floats in the debugging variant of the connector and the scipy reference,
- with numpy arrays to post-process a simulated time series.
The arithmetic backend is passed as ``ops`` (:data:`MATH_OPS`, :data:`NUMPY_OPS`, :func:`SymbolicOps`).

Law (paper eqs. (1)-(2), (4)-(5), (8)-(12)), with ``lever = r1 cos(alphaN) sin(gamma)``:

- relative normal displacement ``Delta s = lever * (phi1 - u phi2)`` and its rate;
- flank in contact ``sigma = sign(Delta s)``; penetration ``p = |Delta s| - delta/2``;
- normal force on that flank ``Fn = kV p + dV sigma d(Delta s)/dt`` if ``p > 0``, else 0; the mesh cannot
  pull, so ``Fn`` is clipped at 0 unless ``dampingCanPull`` (the paper's linear law) is set;
- sliding state ``sf = sat(phi1' / frictionSpeed)`` in [-1, 1] (regularized ``sign(phi1')``;
  ``frictionSpeed = 0`` gives the exact sign, meant for evaluating the law: a simulation in which the worm
  speed crosses zero, e.g. a start from rest, can stop there, as Newton's iteration cannot cross the jump),
  contact parameter ``S = sigma * sf`` (eq. (8));
- torques: worm ``-c2(S) sigma Fn``, wheel ``+c4(S) sigma Fn`` with c2, c4 of eqs. (10), (12);
- friction: the gear's constant ``mu`` (rho of eq. (13)), or, for a speed-dependent law
  (:attr:`WormGear.friction <exudyn_worm.gear.WormGear>`, :mod:`exudyn_worm.friction`), ``mu(v)`` at the sliding
  speed ``v = r1 |phi1'| / cos(gamma)`` and rho = atan(mu(v)/cos(alphaN)) in c2, c4. The constant law records
  exactly the expression it always did.

Optional axial degree of freedom of the worm (its axial bearing, see :func:`MeshContact`): the worm's
axial displacement ``xA`` adds ``cos(alphaN) cos(gamma) xA`` to ``Delta s`` and the mesh pushes the worm
axially with ``-wheelTorque / r2``.

With S fixed to +-1 (``fixedS``), zero backlash and ``dampingCanPull`` the law is exactly linear and
reproduces eqs. (1)-(2); this is what the linearization test checks.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from types import SimpleNamespace
from typing import Any, Optional

import numpy as np

from .gear import WormGear

__all__ = ['MATH_OPS', 'NUMPY_OPS', 'SymbolicOps', 'MeshState', 'MeshContact', 'ContactOptions',
           'NormalForceFlanks']


def _Sign(x):
    return float(x > 0) - float(x < 0)      # also for numpy scalars (their bools do not subtract)


#: plain-Python backend (floats)
MATH_OPS = SimpleNamespace(sin=math.sin, cos=math.cos, abs=abs, sign=_Sign, max=max, min=min,
                           where=lambda c, a, b: a if c else b, exp=math.exp, atan=math.atan)
#: numpy backend (arrays, element-wise)
NUMPY_OPS = SimpleNamespace(sin=np.sin, cos=np.cos, abs=np.abs, sign=np.sign, max=np.maximum, min=np.minimum,
                            where=np.where, exp=np.exp, atan=np.arctan)


def SymbolicOps():
    """Exudyn symbolic backend (``exudyn.symbolic``): records an expression evaluated in C++."""
    import exudyn
    esym = exudyn.symbolic

    def Where(condition, a, b):  # IfThenElse takes symbolic operands only
        return esym.IfThenElse(condition, *(x if isinstance(x, esym.Real) else esym.Real(float(x)) for x in (a, b)))

    return SimpleNamespace(sin=esym.sin, cos=esym.cos, abs=esym.abs, sign=esym.sign, max=esym.max, min=esym.min,
                           where=Where, exp=esym.exp, atan=esym.atan)


@dataclass(frozen=True)
class ContactOptions:
    """Numerical and modelling options of the contact law.

    Parameters
    ----------
    frictionSpeed : float
        Worm speed in rad/s below which the flank friction is regularized linearly
        (``sf = phi1'/frictionSpeed``); 0 gives the discontinuous sign law. Default 0.05 rad/s
        (0.1 % of the reel changer's worm speed).
    dampingCanPull : bool
        If True, use the paper's linear law in which the damping force may make the normal force
        negative (the mesh pulls). Default False: the normal force is clipped at zero.
    fixedS : int or None
        Hold the contact parameter S at +1 or -1 (full flank contact, for linearization); None: S
        follows eq. (8).

    Raises
    ------
    ValueError, TypeError
        For a negative or non-finite ``frictionSpeed``, a ``dampingCanPull`` that is not a bool or a
        ``fixedS`` other than None, +1, -1.
    """
    frictionSpeed: float = 0.05
    dampingCanPull: bool = False
    fixedS: Optional[int] = None

    def __post_init__(self):
        from ._checks import CheckBool, CheckNonNegative
        object.__setattr__(self, 'frictionSpeed', CheckNonNegative('ContactOptions', 'frictionSpeed',
                                                                   self.frictionSpeed, 'rad/s'))
        object.__setattr__(self, 'dampingCanPull', CheckBool('ContactOptions', 'dampingCanPull', self.dampingCanPull))
        if isinstance(self.fixedS, bool) or self.fixedS not in (None, 1, -1):
            raise ValueError(f"ContactOptions: 'fixedS' must be None, +1 or -1, got {self.fixedS!r}")


@dataclass
class MeshState:
    """Mesh quantities of one evaluation of the contact law (scalars, arrays or symbolic), SI units.

    Sign conventions: angles and speeds are positive in the direction in which a positive worm rotation
    turns the wheel (:func:`~exudyn_worm.connector.CreateWormGear`); ``Delta s > 0`` means the worm leads
    and presses the first flank, ``Delta s < 0`` the second flank.

    Attributes
    ----------
    deltaPhi : float or ndarray
        Relative angle phi1 - u phi2, eq. (4), in rad (rotations only; ``deltaS`` adds the axial part).
    deltaS : float or ndarray
        Relative normal displacement of the flanks, eq. (5), in m.
    normalForce : float or ndarray
        **Signed** normal force sigma*Fn in N: >= 0 on the first flank (Delta s > 0, the worm drives),
        <= 0 on the second flank. Its minimum is the largest force on the second flank, not the smallest
        force: use :attr:`normalForceFlanks` (or ``abs``) for magnitudes.
    S : float or ndarray
        Contact parameter of eq. (8), dimensionless: sigma * sf. The paper's S is +1 or -1; here sf is
        regularized, so S takes values between -1 and +1 while the worm speed is within
        ``ContactOptions.frictionSpeed`` of zero (sticking), and 0 inside the backlash (sigma = 0 at Delta s = 0).
    sf : float or ndarray
        Friction state, the regularized sign of phi1' in [-1, 1] (+-1 sliding, ``|sf| < 1`` sticking).
    wormTorque : float or ndarray
        Mesh torque on the worm in N*m (positive in the worm's positive direction).
    wheelTorque : float or ndarray
        Mesh torque on the wheel in N*m (positive in the wheel's positive direction).
    axialForce : float or ndarray
        Mesh force on the worm along its axis in N (+ in the direction of xA); 0 without an axial bearing.
    time : ndarray or None
        Times in s of the states, when the state comes from a simulation
        (:meth:`~exudyn_worm.connector.WormGearConnector.StoredMeshState`); None otherwise.
    """
    deltaPhi: Any
    deltaS: Any
    normalForce: Any
    S: Any
    sf: Any
    wormTorque: Any
    wheelTorque: Any
    axialForce: Any = 0.
    time: Any = None

    @property
    def normalForceFlanks(self):
        """Normal force magnitudes (N, both >= 0) on the first flank (Delta s > 0) and on the second flank."""
        return NormalForceFlanks(self.normalForce)


def NormalForceFlanks(normalForce):
    """Split a signed normal force (N) into the magnitudes on the first and on the second flank.

    Parameters
    ----------
    normalForce : float or array_like
        Signed normal force sigma*Fn (:attr:`MeshState.normalForce`).

    Returns
    -------
    (ndarray, ndarray)
        ``max(F, 0)`` (first flank, Delta s > 0) and ``max(-F, 0)`` (second flank), both >= 0.
    """
    F = np.asarray(normalForce, dtype=float)
    return np.maximum(F, 0.), np.maximum(-F, 0.)


def MeshContact(gear: WormGear, phi1, phi2, omega1, omega2, options: ContactOptions = ContactOptions(),
                ops=MATH_OPS, axialDisplacement=None, axialSpeed=None) -> MeshState:
    """Evaluate the contact law for worm/wheel angles ``phi1, phi2`` and speeds ``omega1, omega2``.

    Parameters
    ----------
    gear : WormGear
        Geometry, stiffness, damping, backlash and friction of the mesh.
    phi1, phi2, omega1, omega2 : float, ndarray or symbolic
        Worm and wheel rotation angles (rad) and speeds (rad/s).
    options : ContactOptions
        Regularization and model options.
    ops : namespace
        Arithmetic backend: :data:`MATH_OPS`, :data:`NUMPY_OPS` or :func:`SymbolicOps`.
    axialDisplacement, axialSpeed : float, ndarray or symbolic, optional
        Axial displacement ``xA`` (m) and speed (m/s) of the worm in its axial bearing, positive in the
        direction in which the worm's thread advances when the worm turns positively. None (default):
        rigid axial bearing, and the law is evaluated exactly as without this option.

    Returns
    -------
    MeshState

    Raises
    ------
    TypeError
        If arrays are given with the plain-Python backend ``MATH_OPS`` (the default): pass ``ops=NUMPY_OPS``.

    Notes
    -----
    Kinematics of the axial degree of freedom. The worm's thread is a helix of lead angle ``gamma`` on
    the reference radius ``r1``: a worm rotation ``phi1`` advances it axially by ``r1 tan(gamma) phi1``,
    and the wheel's reference circle moves along the worm axis by ``r2 phi2`` (so ``u = r2/(r1 tan gamma)``,
    eq. (3)). An axial shift ``xA`` of the whole worm therefore moves the thread exactly like an extra
    worm rotation ``xA / (r1 tan(gamma))``; eq. (4) becomes ``Delta phi = phi1 - u phi2 + xA/(r1 tan gamma)``
    and eq. (5)

        Delta s = r1 cos(alphaN) sin(gamma) (phi1 - u phi2) + cos(alphaN) cos(gamma) xA.

    The same factor follows from projection: the flank normal has the component ``cos(alphaN)`` in the
    pitch plane (pressure angle) and, within that plane, the component ``cos(gamma)`` along the worm
    axis (pitch angle), so an axial displacement ``xA`` is seen by the normal spring as
    ``cos(alphaN) cos(gamma) xA`` (:attr:`WormGear.axialLever`).

    Force on the axial coordinate. The worm axis is the wheel's tangential direction at the mesh, so
    the worm takes the reaction to the wheel's tangential force ``c4 sigma Fn / r2`` (eqs. (7), (12), with
    friction): ``axialForce = -wheelTorque / r2``. Without friction (rho = 0) this is
    ``-cos(alphaN) cos(gamma) sigma Fn`` = ``-dV/dxA`` of the mesh spring energy, consistent with the
    kinematics above; with friction the coupling is non-conservative, as for the rotations (c2 vs. the
    normal lever). The friction state keeps the paper's rule ``sf = sign(phi1')`` (eq. (8)): the axial
    speed is not included in the sliding direction.
    """
    if ops is MATH_OPS and any(isinstance(x, (np.ndarray, list, tuple)) and np.ndim(x) > 0
                               for x in (phi1, phi2, omega1, omega2, axialDisplacement, axialSpeed)):
        raise TypeError("MeshContact: 'phi1', 'phi2', 'omega1', 'omega2' (and the axial state) include arrays, but "
                        "'ops' is MATH_OPS (plain Python floats, the default): pass ops=NUMPY_OPS for arrays")
    # Written for a small recorded expression (the symbolic user function is a tree evaluated node by node,
    # a subexpression used twice is evaluated twice): the relative displacement is kept in worm-angle units
    # d = Delta s / lever, the constants are folded, and |d| = sigma d lets penetration and damping share sigma.
    u, lever = gear.ratio, gear.normalLever
    deltaPhi = phi1 - u * phi2
    d, dRate = deltaPhi, omega1 - u * omega2
    if axialDisplacement is not None:
        axialFactor = gear.axialLever / lever
        d = d + axialFactor * axialDisplacement
        if axialSpeed is not None:
            dRate = dRate + axialFactor * axialSpeed
    sigma = ops.sign(d)
    fn = sigma * ((gear.kV * lever) * d + (gear.dV * lever) * dRate)     # kV penetration + dV sigma d(Delta s)/dt
    if gear.backlash > 0:
        fn = fn - 0.5 * gear.kV * gear.backlash
    if not options.dampingCanPull:
        fn = ops.max(fn, 0.)
    if gear.backlash > 0:                        # inside the backlash there is no force at all
        fn = ops.where(ops.abs(d) > 0.5 * gear.backlash / lever, fn, 0.)
    if options.frictionSpeed > 0:
        sf = ops.max(-1., ops.min(1., omega1 * (1. / options.frictionSpeed)))
    else:
        sf = ops.sign(omega1)
    S = sigma * sf if options.fixedS is None else float(options.fixedS)
    if gear.speedDependentFriction:              # mu(v) at the sliding speed r1 |phi1'| / cos(gamma)
        c2, c4 = gear.LeverArms(S, ops, gear.friction.Mu(gear.SlidingSpeed(omega1, ops), ops))
    else:                                        # constant mu: exactly the paper's (and today's) expression
        c2, c4 = gear.LeverArms(S, ops)
    normalForce = sigma * fn
    wheelTorque = c4 * normalForce
    return MeshState(deltaPhi=deltaPhi, deltaS=lever * d, normalForce=normalForce, S=S, sf=sf,
                     wormTorque=-(c2 * normalForce), wheelTorque=wheelTorque, axialForce=wheelTorque * (-1. / gear.r2))
