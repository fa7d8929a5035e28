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
- flank friction, two models (:class:`ContactOptions` ``frictionModel``):

  * ``'sticking'`` (default): Coulomb friction with a true stick state (docs/friction-sticking.md). While the
    worm slides in direction ``m = +-1`` the friction force on the flank is ``Phi = mu m Fn`` (``sf = m``, held
    fixed during Newton's iteration as Exudyn's own dry-friction connector does). When the worm turns back it sticks:
    ``Phi = kStick (s - sAnchor) + dStick ds/dt``, a tangential spring on the sliding coordinate
    ``s = r1 cos(gamma) phi1 + r2 sin(gamma) phi2`` (:func:`SlidingCoordinate`), which holds without creep;
    it breaks away when ``|Phi| > muStatic Fn`` (:func:`StickSlipUpdate`). The state
    (:class:`FrictionState`) is switched between time steps by the connector (Exudyn's discontinuous
    iteration); without a state the law is the exact Coulomb law ``sf = sign(phi1')``;
  * ``'regularized'``: ``sf = sat(phi1' / frictionSpeed)`` in [-1, 1] (regularized ``sign(phi1')``, the
    law of earlier versions; it has no friction at zero worm speed, so a self-locking gear creeps;
    ``frictionSpeed = 0`` gives the exact sign, meant for evaluating the law: a simulation in which the worm
    speed crosses zero, e.g. a start from rest, can stop there, as Newton's iteration cannot cross the jump);

  contact parameter ``S = sigma * sf`` (eq. (8));
- torques: worm ``-c2(S) sigma Fn``, wheel ``+c4(S) sigma Fn`` with c2, c4 of eqs. (10), (12). With
  ``mu = tan(rho) cos(alphaN)`` (eq. (13)) and S = +-1 these are ``c2 = r1 (cos(alphaN) sin(gamma) + mu S
  cos(gamma))``, ``c4 = r2 (cos(alphaN) cos(gamma) - mu S sin(gamma))``: the normal force acts through the
  levers ``r1 cos(alphaN) sin(gamma)``, ``r2 cos(alphaN) cos(gamma)`` and the friction force
  ``Phi = mu S sigma Fn`` through ``r1 cos(gamma)``, ``r2 sin(gamma)`` (the gradient of ``s``). The sticking
  model uses this form for any ``Phi``; the regularized model keeps eqs. (10), (12) with ``|S| < 1``.
- friction coefficient: the gear's constant ``mu`` (rho of eq. (13)), or, for a speed-dependent law
  (:attr:`WormGear.friction <exudyn_worm.model.gear.WormGear>`, :mod:`exudyn_worm.model.friction`), ``mu(v)`` at the sliding
  speed ``v = r1 |phi1'| / cos(gamma)`` (:func:`FrictionCoefficientAt`), in both friction models. The constant
  law records exactly the expression it always did.

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
from typing import Any, Optional, Tuple

import numpy as np

from .friction import MATH_OPS, NUMPY_OPS  # the arithmetic backends live in friction.py, below gear and contact
from .gear import WormGear
from .._checks import CheckBool, CheckNonNegative, CheckPositive, Suggest

__all__ = ['SymbolicOps', 'MeshState', 'MeshContact', 'ContactOptions',
           'NormalForceFlanks', 'FRICTION_MODELS', 'FrictionState', 'SlidingCoordinate', 'StickSlipUpdate',
           'FrictionCoefficientAt']

#: friction models of :class:`ContactOptions` (``frictionModel``)
FRICTION_MODELS = ('sticking', 'regularized')


def SymbolicOps():
    """Exudyn symbolic backend (``exudyn.symbolic``): records an expression evaluated in C++."""
    import exudyn
    esym = exudyn.symbolic

    def Where(condition, a, b):  # IfThenElse takes symbolic operands only
        return esym.IfThenElse(condition, *(x if isinstance(x, esym.Real) else esym.Real(float(x)) for x in (a, b)))

    # Vector: a constant vector times a scalar expression evaluates the scalar once (MeshContact's generalized forces)
    return SimpleNamespace(sin=esym.sin, cos=esym.cos, abs=esym.abs, sign=esym.sign, max=esym.max, min=esym.min,
                           where=Where, exp=esym.exp, atan=esym.atan, Vector=esym.Vector)


@dataclass(frozen=True)
class ContactOptions:
    """Numerical and modelling options of the contact law.

    Parameters
    ----------
    frictionSpeed : float
        Worm speed in rad/s below which the flank friction of the ``'regularized'`` model is regularized
        linearly (``sf = phi1'/frictionSpeed``); 0 gives the discontinuous sign law. Default 0.05 rad/s
        (0.1 % of the reel changer's worm speed). Not used by the ``'sticking'`` model.
    dampingCanPull : bool
        If True, use the paper's linear law in which the damping force may make the normal force
        negative (the mesh pulls). Default False: the normal force is clipped at zero.
    fixedS : int or None
        Hold the contact parameter S at +1 or -1 (full flank contact, for linearization); None: S
        follows eq. (8). A fixed S overrides the friction model (no stick state).
    frictionModel : str
        ``'sticking'`` (default): Coulomb friction with a stick state, switched between time steps by the
        connector; a self-locking gear holds its load without creep (docs/friction-sticking.md).
        ``'regularized'``: ``sf = sat(phi1'/frictionSpeed)`` without a state (earlier versions' law; no
        friction at zero worm speed, so a self-locking gear creeps).
    stickingStiffness : float or None
        Tangential stiffness of the stuck flanks in N/m along the sliding coordinate (> 0); None
        (default): the mesh stiffness ``kV`` of the gear (the same flank compliance).
    stickingDamping : float or None
        Tangential damping of the stuck flanks in N*s/m (>= 0); None (default): the mesh damping ``dV``.

    Raises
    ------
    ValueError, TypeError
        For a negative or non-finite ``frictionSpeed``, a ``dampingCanPull`` that is not a bool, a
        ``fixedS`` other than None, +1, -1, an unknown ``frictionModel`` or a bad sticking stiffness/damping.
    """
    frictionSpeed: float = 0.05
    dampingCanPull: bool = False
    fixedS: Optional[int] = None
    frictionModel: str = 'sticking'
    stickingStiffness: Optional[float] = None
    stickingDamping: Optional[float] = None

    def __post_init__(self):
        w = 'ContactOptions'
        object.__setattr__(self, 'frictionSpeed', CheckNonNegative(w, 'frictionSpeed', self.frictionSpeed, 'rad/s'))
        object.__setattr__(self, 'dampingCanPull', CheckBool(w, 'dampingCanPull', self.dampingCanPull))
        if isinstance(self.fixedS, bool) or self.fixedS not in (None, 1, -1):
            raise ValueError(f"ContactOptions: 'fixedS' must be None, +1 or -1, got {self.fixedS!r}")
        if not isinstance(self.frictionModel, str) or self.frictionModel not in FRICTION_MODELS:
            raise ValueError(f"{w}: 'frictionModel' must be one of {', '.join(repr(m) for m in FRICTION_MODELS)}, "
                             f"got {self.frictionModel!r}{Suggest(self.frictionModel, FRICTION_MODELS)}")
        if self.stickingStiffness is not None:
            object.__setattr__(self, 'stickingStiffness', CheckPositive(w, 'stickingStiffness',
                                                                        self.stickingStiffness, 'N/m'))
        if self.stickingDamping is not None:
            object.__setattr__(self, 'stickingDamping', CheckNonNegative(w, 'stickingDamping',
                                                                         self.stickingDamping, 'N*s/m'))

    @property
    def hasStickState(self) -> bool:
        """True if the law carries a stick/slip state (``frictionModel='sticking'`` and no fixed S)."""
        return self.frictionModel == 'sticking' and self.fixedS is None

    def StickingStiffness(self, gear: WormGear) -> float:
        """Tangential stiffness of the stuck flanks in N/m (``stickingStiffness`` or the gear's ``kV``)."""
        return gear.kV if self.stickingStiffness is None else self.stickingStiffness

    def StickingDamping(self, gear: WormGear) -> float:
        """Tangential damping of the stuck flanks in N*s/m (``stickingDamping`` or the gear's ``dV``)."""
        return gear.dV if self.stickingDamping is None else self.stickingDamping


@dataclass
class FrictionState:
    """Stick/slip state of the sticking friction model (floats, arrays or Exudyn symbolic variables).

    Attributes
    ----------
    stuck : float
        1 while the flanks stick, 0 while they slide.
    direction : float
        Sliding direction ``m`` (+1 or -1) of the worm while sliding (also kept while stuck).
    anchor : float
        Sliding coordinate in m at which the stuck flanks carry no friction force (:func:`SlidingCoordinate`).
    """
    stuck: Any = 0.
    direction: Any = 1.
    anchor: Any = 0.


def SlidingCoordinate(gear: WormGear, phi1: Any, phi2: Any) -> Any:
    """Sliding coordinate of the flanks ``s = r1 cos(gamma) phi1 + r2 sin(gamma) phi2`` in m.

    Its rate is the sliding speed along the thread, ``r1 phi1'/cos(gamma)`` when the mesh rolls without normal
    deflection (``r2 phi2' = r1 tan(gamma) phi1'``); the friction force acts on worm and wheel through its
    gradient ``(r1 cos(gamma), r2 sin(gamma))``. The same function converts speeds (pass ``phi1', phi2'``).

    Parameters
    ----------
    gear : WormGear
        The mesh (``r1``, ``r2``, ``gamma``).
    phi1, phi2 : float, ndarray or symbolic
        Worm and wheel angles in rad (or speeds in rad/s).

    Returns
    -------
    float, ndarray or symbolic
        ``s`` in m (or its rate in m/s).
    """
    return (gear.r1 * math.cos(gear.gamma)) * phi1 + (gear.r2 * math.sin(gear.gamma)) * phi2


@dataclass
class MeshState:
    """Mesh quantities of one evaluation of the contact law (scalars, arrays or symbolic), SI units.

    Sign conventions: angles and speeds are positive in the direction in which a positive worm rotation
    turns the wheel (:func:`~exudyn_worm.items.connector.CreateWormGear`); ``Delta s > 0`` means the worm leads
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
        Contact parameter of eq. (8), dimensionless: sigma * sf. The paper's S is +1 or -1; S takes values
        between -1 and +1 while the flanks stick (or, with the regularized model, while the worm speed is
        within ``ContactOptions.frictionSpeed`` of zero), and 0 inside the backlash (sigma = 0 at Delta s = 0).
    sf : float or ndarray
        Friction state: the friction force in units of ``mu Fn`` (+-1 sliding; while sticking the force the
        stuck flanks carry, up to ``muStatic/mu`` in magnitude).
    wormTorque : float or ndarray
        Mesh torque on the worm in N*m (positive in the worm's positive direction).
    wheelTorque : float or ndarray
        Mesh torque on the wheel in N*m (positive in the wheel's positive direction).
    axialForce : float or ndarray
        Mesh force on the worm along its axis in N (+ in the direction of xA): ``-wheelTorque / r2``, the worm's
        axial thrust, with or without an axial bearing (without one the rigid bearing carries it).
    time : ndarray or None
        Times in s of the states, when the state comes from a simulation
        (:meth:`~exudyn_worm.items.connector.WormGearConnector.StoredMeshState`); None otherwise.
    frictionForce : float or ndarray
        Friction force on the flank in N along the sliding coordinate (:func:`SlidingCoordinate`), positive
        when it resists a positive worm rotation: ``mu sf Fn`` while sliding, the stuck flanks' force while
        sticking.
    stuck : float or ndarray
        1 where the flanks stick (sticking model with a state), else 0.
    radialForce : float or ndarray
        Mesh force on the worm along the centre line towards the wheel in N: ``-sin(alphaN) Fn``, the separating
        force (<= 0 unless ``dampingCanPull``); the wheel takes the opposite force.
    generalizedForces : list or symbolic vector
        ``[wormTorque, wheelTorque]`` in N*m (with an axial displacement also ``axialForce`` in N): the forces on the law's
        coordinates. With the symbolic backend one vector expression in which each shared term (the normal force,
        the friction state) is evaluated once (a recorded expression is a tree, evaluated node by node).
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
    frictionForce: Any = 0.
    stuck: Any = 0.
    radialForce: Any = 0.
    generalizedForces: Any = None

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
                ops=MATH_OPS, axialDisplacement=None, axialSpeed=None,
                frictionState: Optional[FrictionState] = None, radialApproach=None, radialSpeed=None,
                forceMap: Optional[Any] = None) -> MeshState:
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
    frictionState : FrictionState, optional
        Stick/slip state of the sticking model (floats, arrays of the same shape as the angles, or symbolic
        variables). None: the exact Coulomb law ``sf = sign(phi1')`` (no stick state). Ignored by the
        regularized model and with a fixed S.
    radialApproach, radialSpeed : float, ndarray or symbolic, optional
        Approach ``C`` (m) of worm and wheel along the centre line (worm towards wheel positive) and its rate
        (m/s), e.g. from radial bearing compliance (:mod:`exudyn_worm.items.rigidmesh`). Both flanks are inclined
        by ``alphaN`` towards the centre line, so an approach deepens the contact on either flank by
        ``sin(alphaN) C``: the penetration becomes ``|Delta s| + sin(alphaN) C - delta/2``. None (default): the
        law is evaluated exactly as without this option.
    forceMap : array_like, optional
        A constant matrix (n x 4) that maps ``[wormTorque, wheelTorque, axialForce, radialForce]`` onto the
        generalized forces of a model whose coordinates are not the law's inputs (the 3D model's, e.g.
        :mod:`exudyn_worm.items.rigidmesh`): ``generalizedForces`` is then ``forceMap @ [...]``, with the symbolic
        backend one vector expression (each shared term once). None (default): ``generalizedForces`` as below.

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
    sinAlpha = math.sin(gear.alphaN)
    if radialApproach is not None:               # both flanks lean towards the centre line by alphaN
        fn = fn + (gear.kV * sinAlpha) * radialApproach
        if radialSpeed is not None:
            fn = fn + (gear.dV * sinAlpha) * radialSpeed
    if gear.backlash > 0:
        fn = fn - 0.5 * gear.kV * gear.backlash
    if not options.dampingCanPull:
        fn = ops.max(fn, 0.)
    if gear.backlash > 0:                        # inside the backlash there is no force at all
        if radialApproach is None:
            fn = ops.where(ops.abs(d) > 0.5 * gear.backlash / lever, fn, 0.)
        else:
            fn = ops.where(lever * ops.abs(d) + sinAlpha * radialApproach > 0.5 * gear.backlash, fn, 0.)
    normalForce = sigma * fn
    vector = getattr(ops, 'Vector', None)        # the symbolic backend's constant vectors (see generalizedForces)
    if options.frictionModel == 'regularized' or options.fixedS is not None:   # eqs. (10), (12) as printed
        if options.frictionSpeed > 0:
            sf = ops.max(-1., ops.min(1., omega1 * (1. / options.frictionSpeed)))
        else:
            sf = ops.sign(omega1)
        S = sigma * sf if options.fixedS is None else float(options.fixedS)
        if gear.speedDependentFriction:          # mu(v) at the sliding speed r1 |phi1'| / cos(gamma)
            c2, c4 = gear.LeverArms(S, ops, FrictionCoefficientAt(gear, omega1, ops))
        else:                                    # constant mu: exactly the paper's expression
            c2, c4 = gear.LeverArms(S, ops)
        wormTorque, wheelTorque = -(c2 * normalForce), c4 * normalForce
        frictionForce = (wormTorque * (-1. / gear.r1) - math.cos(gear.alphaN) * math.sin(gear.gamma) * normalForce) \
            * (1. / math.cos(gear.gamma))
        stuck = 0.
        levers = [-c2, c4] + ([c4 * (-1. / gear.r2)] if axialDisplacement is not None else [])
        if forceMap is not None:                 # the map's rows over the levers of [worm, wheel, axial, radial]
            levers = [_Combine(row, [-c2, c4, c4 * (-1. / gear.r2), (-sinAlpha) * sigma]) for row in _Rows(forceMap)]
        generalized = (vector(levers) * normalForce if vector is not None
                       else [lv * normalForce for lv in levers] if forceMap is not None
                       else [wormTorque, wheelTorque] + ([wheelTorque * (-1. / gear.r2)] if len(levers) > 2 else []))
    else:
        frictionForce, sf, stuck, slipFactor, stickForce = _FrictionForce(gear, options, ops, sigma, fn, phi1, phi2,
                                                                           omega1, omega2, frictionState)
        S = sigma * sf
        # eqs. (10), (12) with the friction force written out (module text): levers of normal and friction force
        normalLevers = [-(gear.r1 * math.cos(gear.alphaN) * math.sin(gear.gamma)),
                        gear.r2 * math.cos(gear.alphaN) * math.cos(gear.gamma)]
        frictionLevers = [-(gear.r1 * math.cos(gear.gamma)), -(gear.r2 * math.sin(gear.gamma))]
        wormTorque, wheelTorque = (a * normalForce + b * frictionForce
                                   for a, b in zip(normalLevers, frictionLevers))
        radialLevers = None
        if forceMap is not None:                 # [worm, wheel, axial, radial] mapped: constant levers
            rows = _Rows(forceMap)
            radialLevers = [row[3] * -sinAlpha for row in rows]
            normalLevers, frictionLevers = ([_Combine(row, [a[0], a[1], a[1] * (-1. / gear.r2), 0.]) for row in rows]
                                            for a in (normalLevers, frictionLevers))
        elif axialDisplacement is not None:      # axialForce = -wheelTorque / r2
            normalLevers.append(normalLevers[1] * (-1. / gear.r2))
            frictionLevers.append(frictionLevers[1] * (-1. / gear.r2))
        # frictionForce = slipFactor * normalForce + stickForce (slipFactor = mu m sigma sliding, 0 stuck; stickForce
        # the stuck flanks' force, 0 sliding): each generalized force is (a + b slipFactor) normalForce + b stickForce
        # (+ c sigma normalForce = c fn with a force map's radial levers c)
        if vector is not None:                   # one vector expression: each shared term once
            factor = vector(normalLevers) + vector(frictionLevers) * slipFactor
            if radialLevers is not None:
                factor = factor + vector(radialLevers) * sigma
            generalized = factor * normalForce
            if stickForce is not None:
                generalized = generalized + vector(frictionLevers) * stickForce
        elif radialLevers is not None:
            generalized = [a * normalForce + b * frictionForce + c * (sigma * normalForce)
                           for a, b, c in zip(normalLevers, frictionLevers, radialLevers)]
        else:
            generalized = [wormTorque, wheelTorque] + ([wheelTorque * (-1. / gear.r2)] if len(normalLevers) > 2 else [])
    return MeshState(deltaPhi=deltaPhi, deltaS=lever * d, normalForce=normalForce, S=S, sf=sf,
                     wormTorque=wormTorque, wheelTorque=wheelTorque, axialForce=wheelTorque * (-1. / gear.r2),
                     frictionForce=frictionForce, stuck=stuck, radialForce=fn * (-sinAlpha),
                     generalizedForces=generalized)


def _Rows(forceMap) -> list:
    """The rows of a force map (n x 4) as lists of floats."""
    rows = [[float(x) for x in row] for row in np.asarray(forceMap, dtype=float).reshape(-1, 4)]
    return rows


def _Combine(row, values):
    """row . values, leaving out the zero entries of the constant row (no '0 *' node in a recorded expression)."""
    total = None
    for c, v in zip(row, values):
        if c != 0.:
            term = v if c == 1. else c * v
            total = term if total is None else total + term
    return 0. if total is None else total


def FrictionCoefficientAt(gear: WormGear, omega1: Any, ops: Any = MATH_OPS) -> Any:
    """Flank friction coefficient at worm speed ``omega1``: the gear's constant ``mu``, or its law's mu(v) at the
    sliding speed ``v = r1 |omega1| / cos(gamma)`` (:meth:`WormGear.SlidingSpeed`).

    Parameters
    ----------
    gear : WormGear
        The mesh and its friction law (:attr:`WormGear.friction`).
    omega1 : float, ndarray or symbolic
        Worm speed in rad/s.
    ops : namespace
        Arithmetic backend (:data:`MATH_OPS`, :data:`NUMPY_OPS` or :func:`SymbolicOps`).

    Returns
    -------
    float, ndarray or symbolic
        The friction coefficient (dimensionless).
    """
    if not gear.speedDependentFriction:
        return gear.mu
    return gear.friction.Mu(gear.SlidingSpeed(omega1, ops), ops)


def _FrictionForce(gear, options, ops, sigma, fn, phi1, phi2, omega1, omega2, state):
    """Friction force (N), sf, the stuck flag of the sticking model (see the module text), and the friction force
    split as ``slipFactor * normalForce + stickForce`` (``stickForce`` None without a stick state)."""
    mu = FrictionCoefficientAt(gear, omega1, ops)
    if state is None:                                      # exact Coulomb law, no stick state
        sf = ops.sign(omega1)
        return mu * sf * fn, sf, 0., mu * sf * sigma, None
    sfSlip = state.direction           # held during Newton's iteration; a reversal is a switch to sticking
    slip = mu * sfSlip * fn
    stick = options.StickingStiffness(gear) * (SlidingCoordinate(gear, phi1, phi2) - state.anchor) \
        + options.StickingDamping(gear) * SlidingCoordinate(gear, omega1, omega2)
    isStuck = state.stuck > 0.5
    frictionForce = ops.where(isStuck, stick, slip)
    if ops is NUMPY_OPS or ops is MATH_OPS:               # sf of the stuck flanks, for post-processing only
        scale = mu * ops.abs(fn)
        sfStick = ops.where(scale > 0, stick / ops.where(scale > 0, scale, 1.), 0.)
        sf = ops.where(isStuck, sfStick, sfSlip)
    else:
        sf = sfSlip
    # sliding: mu m fn = (mu m sigma) (sigma fn), exactly (sigma = +-1, or 0 where fn = 0)
    slipFactor = ops.where(isStuck, 0., mu * sfSlip * sigma)
    return frictionForce, sf, ops.where(isStuck, 1., 0.), slipFactor, ops.where(isStuck, stick, 0.)


def StickSlipUpdate(gear: WormGear, options: ContactOptions, state: FrictionState, phi1: float, phi2: float,
                    omega1: float, omega2: float, axialDisplacement: Optional[float] = None,
                    axialSpeed: Optional[float] = None, forces: Optional[Tuple[float, float]] = None,
                    reversalCoordinate: Optional[float] = None) -> Tuple[Optional['FrictionState'], float]:
    """One stick/slip decision of the sticking model after a converged time step (plain floats).

    Rules (as Exudyn's ``ObjectConnectorCoordinateSpringDamperExt`` does for its dry friction):

    - sliding in direction ``m`` and the worm has turned back (``phi1' m < 0``): the flanks stick from the
      next step on; the anchor is placed so that the stuck flanks carry the sliding friction ``mu Fn m`` of the
      moment, so the friction force does not jump (repeating the step with the stuck flanks was tried: it
      makes the reel changer's P7 peaks depend erratically on the step size, docs/friction-sticking.md);
    - stuck and the friction force needed exceeds the static limit ``|Phi| > muStatic Fn``: the flanks break
      away and slide in the direction of ``Phi`` (the direction the load pushes the worm).

    Parameters
    ----------
    gear : WormGear
        The mesh (``mu``, ``muStatic`` and the geometry).
    options : ContactOptions
        Options of the law (``frictionModel='sticking'``).
    state : FrictionState
        The state the step was computed with (floats).
    phi1, phi2, omega1, omega2 : float
        Worm and wheel angles (rad, including the node reference values) and speeds (rad/s) at the end of the step.
    axialDisplacement, axialSpeed : float, optional
        The worm's axial state, as for :func:`MeshContact`.
    forces : (float, float), optional
        ``(frictionForce, normalForce)`` of :func:`MeshContact` at this state, if already evaluated (e.g.
        by the law recorded in C++); None: evaluated here.
    reversalCoordinate : float, optional
        Sliding coordinate in m (:func:`SlidingCoordinate`) at which the worm turned back within the step,
        if known: the stuck flanks then carry ``mu Fn m`` there (and less where the worm has come back
        since); None: at the present state.

    Returns
    -------
    (FrictionState or None, float)
        The new state (None: unchanged) and the jump of the friction force in N that the switch causes at
        this state (the discontinuous error: the step is repeated when it exceeds Exudyn's
        ``timeIntegration.discontinuous.iterationTolerance``).
    """
    if state.stuck < 0.5 and omega1 * state.direction >= 0.:
        return None, 0.
    if forces is None:
        mesh = MeshContact(gear, phi1, phi2, omega1, omega2, options, MATH_OPS, axialDisplacement, axialSpeed, state)
        forces = (mesh.frictionForce, mesh.normalForce)
    frictionForce, fn = forces[0], abs(forces[1])
    if state.stuck > 0.5:
        if abs(frictionForce) <= gear.muStatic * fn:
            return None, 0.
        m = 1. if frictionForce > 0 else -1.
        return FrictionState(0., m, state.anchor), abs(frictionForce - FrictionCoefficientAt(gear, omega1) * fn * m)
    target = FrictionCoefficientAt(gear, omega1) * fn * state.direction    # the sliding friction before the reversal
    if reversalCoordinate is None:
        rate = options.StickingDamping(gear) * SlidingCoordinate(gear, omega1, omega2)
        anchor = SlidingCoordinate(gear, phi1, phi2) - (target - rate) / options.StickingStiffness(gear)
    else:
        anchor = reversalCoordinate - target / options.StickingStiffness(gear)
    return FrictionState(1., state.direction, anchor), abs(target - frictionForce)
