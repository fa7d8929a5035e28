"""Worm-gear geometry, friction and the mesh coefficients (paper eqs. (3), (5), (9)-(13)).

This module is the single source of truth for the coefficients c1..c4: the analytical
stability model, the Exudyn connector and post-processing all call
:meth:`WormGear.Coefficients`. A gear may carry a speed-dependent friction law
(:mod:`exudyn_worm.model.friction`); the coefficients are then evaluated at ``mu(v)``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Optional, Union

from .._checks import CheckAngle, CheckNonNegative, CheckPositive
from .friction import AgmaFriction, ConstantFriction, StribeckFriction, TableFriction
from ..params.plausibility import CheckGearPlausibility

FrictionLawType = Union[ConstantFriction, StribeckFriction, AgmaFriction, TableFriction]

__all__ = ['WormGear']

#: relative tolerance for ``mu`` and ``rho`` given together (they must describe one friction)
FRICTION_CONSISTENCY_RTOL = 1e-6


@dataclass(frozen=True)
class WormGear:
    """A worm-gear mesh: geometry, mesh stiffness/damping in the normal direction, backlash, friction.

    Parameters
    ----------
    alphaN : float
        Normal pressure angle in rad, in (0, pi/2).
    gamma : float
        Pitch (lead) angle of the worm in rad, in (0, pi/2).
    r1 : float
        Reference radius of the worm in m, > 0.
    r2 : float
        Reference radius of the wheel in m, > 0.
    kV : float
        Mesh stiffness in the normal direction in N/m, > 0.
    dV : float
        Mesh damping in the normal direction in N*s/m, >= 0.
    backlash : float, optional
        Total normal backlash delta in m, in [0, r1] (no force while ``|Delta s| <= delta/2``); a value
        above the worm radius is rejected as a unit mistake (mm given as m). Values that no worm gear has are
        refused (ratio u < 1, gamma + rho >= 90 deg) or warned about (mu > 0.5, r1 > r2), naming the likely
        unit slip: :func:`~exudyn_worm.params.plausibility.CheckGearPlausibility`.
    mu : float, optional
        Flank friction coefficient, >= 0. Give ``mu`` or ``rho`` (or both, consistent via eq. (13)).
    rho : float, optional
        Friction angle in rad, in [0, pi/2).
    friction : ConstantFriction, StribeckFriction, AgmaFriction or TableFriction, optional
        Friction law mu(v) over the sliding speed v in m/s (:mod:`exudyn_worm.model.friction`). None (default): the
        constant ``mu``, exactly the paper's model. ``mu`` stays the nominal coefficient of the constant-mu
        formulas (:attr:`rho`, the efficiencies, the stability charts); for a constant or Stribeck law it is
        the law's (kinetic) ``mu`` and may be left out; for an AGMA or table law give it as well.

    Raises
    ------
    ValueError
        If a value is out of range or non-finite, if neither or inconsistent ``mu``/``rho`` are given, or for a
        ratio u below 1 or gamma + rho >= 90 deg (efficiency with the worm driving <= 0).
    TypeError
        If a value is not a real number.

    Examples
    --------
    >>> import math
    >>> g = WormGear(alphaN=math.radians(20), gamma=math.radians(5.3228), r1=0.01805, r2=0.10595,
    ...              kV=2e8, dV=21470., rho=math.radians(8))
    >>> round(g.ratio, 2), g.selfLocking
    (63.0, True)
    """
    alphaN: float
    gamma: float
    r1: float
    r2: float
    kV: float
    dV: float
    backlash: float = 0.
    mu: Optional[float] = None
    rho: Optional[float] = None
    friction: Optional[FrictionLawType] = None

    def __post_init__(self):
        w = 'WormGear'
        set_ = lambda k, v: object.__setattr__(self, k, v)  # frozen dataclass: normalise once here
        set_('alphaN', CheckAngle(w, 'alphaN', self.alphaN))
        set_('gamma', CheckAngle(w, 'gamma', self.gamma))
        set_('r1', CheckPositive(w, 'r1', self.r1, 'm'))
        set_('r2', CheckPositive(w, 'r2', self.r2, 'm'))
        set_('kV', CheckPositive(w, 'kV', self.kV, 'N/m'))
        set_('dV', CheckNonNegative(w, 'dV', self.dV, 'N*s/m'))
        set_('backlash', CheckNonNegative(w, 'backlash', self.backlash, 'm'))
        if self.backlash > self.r1:       # a gap wider than the worm radius cannot exist: a unit mistake
            b = self.backlash
            raise ValueError(f"{w}: 'backlash' must be <= the worm radius r1 = {self.r1:g} m, got {b:g} m; "
                             f"backlash is in m: for {b:g} mm give {b * 1e-3:g} (on the command line "
                             f"--set 'backlash={b:g} mm')")
        law = self.friction
        if law is not None and not isinstance(law, (ConstantFriction, StribeckFriction, AgmaFriction, TableFriction)):
            raise TypeError(f"{w}: 'friction' must be a friction law of exudyn_worm.model.friction (ConstantFriction, "
                            f"StribeckFriction, AgmaFriction, TableFriction) or None, got {type(law).__name__}")
        if self.mu is None and self.rho is None and isinstance(law, (ConstantFriction, StribeckFriction)):
            set_('mu', law.mu)                                  # the law's (kinetic) mu is the nominal one
        if self.mu is None and self.rho is None and law is not None:
            raise ValueError(f"{w}: with the '{law.kind}' friction law give the nominal friction 'mu' (>= 0) too "
                             f"(used by the constant-mu formulas, e.g. mu at the operating sliding speed), got none")
        if self.mu is None and self.rho is None:
            raise ValueError(f"{w}: give the friction as 'mu' (>= 0) or as 'rho' (in [0, pi/2) rad), got neither")
        cosA = math.cos(self.alphaN)
        if self.mu is not None:
            set_('mu', CheckNonNegative(w, 'mu', self.mu, ''))
        if self.rho is not None:
            rho = CheckNonNegative(w, 'rho', self.rho, 'rad')
            if rho >= 0.5 * math.pi:
                raise ValueError(f"{w}: 'rho' must be in [0, pi/2) rad, got {rho:g} rad ({math.degrees(rho):g} deg)")
            set_('rho', rho)
        if self.rho is None:
            set_('rho', math.atan(self.mu / cosA))              # eq. (13)
        elif self.mu is None:
            set_('mu', math.tan(self.rho) * cosA)               # eq. (13) inverted
        elif not math.isclose(self.mu, math.tan(self.rho) * cosA, rel_tol=FRICTION_CONSISTENCY_RTOL,
                              abs_tol=1e-12):
            raise ValueError(f"{w}: 'mu' and 'rho' are inconsistent through eq. (13) rho = atan(mu/cos(alphaN)): "
                             f"mu = {self.mu:g} needs rho = {math.degrees(math.atan(self.mu / cosA)):.6g} deg, "
                             f"got rho = {math.degrees(self.rho):.6g} deg; give only one of them")
        if isinstance(law, (ConstantFriction, StribeckFriction)) and not math.isclose(
                self.mu, law.mu, rel_tol=FRICTION_CONSISTENCY_RTOL, abs_tol=1e-12):
            raise ValueError(f"{w}: 'mu' = {self.mu:g} differs from the {law.kind} friction law's mu = {law.mu:g}; "
                             f"give one of them (the law's mu is the gear's nominal mu)")
        CheckGearPlausibility(self, w)     # values that no worm gear has: refused or warned, naming the unit slip

    # --- derived quantities -------------------------------------------------------------
    @property
    def ratio(self) -> float:
        """Transmission ratio u = r2 / (r1 tan(gamma)), eq. (3)."""
        return self.r2 / (self.r1 * math.tan(self.gamma))

    @property
    def frictionLaw(self) -> FrictionLawType:
        """The friction law mu(v): :attr:`friction`, or ``ConstantFriction(mu)`` if none is given."""
        return ConstantFriction(self.mu) if self.friction is None else self.friction

    @property
    def speedDependentFriction(self) -> bool:
        """True if the friction law is not the constant ``mu`` (the contact law then evaluates mu(v))."""
        return self.friction is not None and not isinstance(self.friction, ConstantFriction)

    @property
    def muStatic(self) -> float:
        """Friction coefficient at rest, mu(0) of the law (= ``mu`` for the constant law)."""
        return self.mu if self.friction is None else float(self.friction.muStatic)

    def SlidingSpeed(self, omega1, ops=math):
        """Sliding speed of the flanks ``v = r1 abs(omega1) / cos(gamma)`` in m/s for the worm speed ``omega1``
        (rad/s).

        Parameters
        ----------
        omega1 : float, ndarray or symbolic
            Worm speed in rad/s (either sign).
        ops : namespace
            Backend supplying ``abs`` (``math``/:data:`~exudyn_worm.model.friction.MATH_OPS`, numpy, symbolic).
        """
        absolute = abs if ops is math else ops.abs
        return absolute(omega1) * (self.r1 / math.cos(self.gamma))

    def FrictionCoefficient(self, slidingSpeed, ops=None):
        """Friction coefficient mu(v) of the gear's law at the sliding speed ``slidingSpeed`` (m/s).

        Parameters
        ----------
        slidingSpeed : float, ndarray or symbolic
            Sliding speed in m/s, >= 0 (:meth:`SlidingSpeed`).
        ops : namespace, optional
            Arithmetic backend of :mod:`exudyn_worm.model.contact`; None: Python floats.
        """
        return self.frictionLaw.Mu(slidingSpeed, ops)

    @property
    def frictionAngle(self) -> float:
        """Friction angle rho in rad, eq. (13)."""
        return self.rho

    @property
    def selfLocking(self) -> bool:
        """True if the gear is self-locking: gamma < rho."""
        return self.gamma < self.rho

    @property
    def normalLever(self) -> float:
        """Normal displacement per worm-side relative angle, r1 cos(alphaN) sin(gamma) in m/rad, eq. (5)."""
        return self.r1 * math.cos(self.alphaN) * math.sin(self.gamma)

    @property
    def axialLever(self) -> float:
        """Normal displacement per axial worm displacement, cos(alphaN) cos(gamma) (dimensionless).

        An axial shift x of the worm moves its thread like a worm rotation of x / (r1 tan(gamma)), so the
        normal displacement of eq. (5) grows by ``normalLever * x / (r1 tan(gamma)) = cos(alphaN) cos(gamma) x``
        (see :func:`exudyn_worm.model.contact.MeshContact`).
        """
        return math.cos(self.alphaN) * math.cos(self.gamma)

    def NormalDisplacement(self, deltaPhi):
        """Relative normal displacement Delta s = r1 cos(alphaN) sin(gamma) Delta phi in m, eq. (5)."""
        return self.normalLever * deltaPhi

    def RelativeAngle(self, phi1, phi2):
        """Relative angle Delta phi = phi1 - u phi2 in rad (worm side), eq. (4)."""
        return phi1 - self.ratio * phi2

    def LeverArms(self, S, ops=math, mu=None):
        """Torque per unit normal force on worm and wheel, (c2, c4) of eqs. (10), (12), in m.

        ``S`` may be +-1 or, for the connector's regularized friction model, any value in [-1, 1]
        (0 = frictionless); ``ops`` supplies ``sin``/``cos`` (and ``atan`` with ``mu``) (``math``, ``numpy`` or
        Exudyn symbolic). ``mu`` (float, array or symbolic): evaluate at this friction coefficient, with
        rho = atan(mu / cos(alphaN)) (eq. (13)); None (default): at the gear's ``mu`` (its :attr:`rho`).
        """
        cosA = math.cos(self.alphaN)
        if mu is None:
            k = cosA / math.cos(self.rho)
            arg = self.gamma + self.rho * S
        else:
            rho = ops.atan(mu * (1. / cosA))                    # eq. (13)
            k = cosA / ops.cos(rho)
            arg = self.gamma + rho * S
        return self.r1 * k * ops.sin(arg), self.r2 * k * ops.cos(arg)

    def Coefficients(self, S, ops=math, mu=None):
        """Mesh coefficients (c1, c2, c3, c4) of eqs. (9)-(12) for contact parameter ``S``.

        c1 = c2 * normalLever and c3 = c4 * normalLever: the normal force acts on the worm through
        the lever c2 and on the wheel through c4. ``mu``: evaluate at this friction coefficient instead of
        the gear's ``mu`` (see :meth:`LeverArms`).
        """
        c2, c4 = self.LeverArms(S, ops, mu)
        return c2 * self.normalLever, c2, c4 * self.normalLever, c4

    def Efficiencies(self, mu=None):
        """Efficiencies (worm driving, wheel driving) at the friction coefficient ``mu`` (default: the gear's).

        Worm driving: tan(gamma)/tan(gamma + rho); wheel driving: tan(gamma - rho)/tan(gamma) (<= 0: self-locking).

        Parameters
        ----------
        mu : float, optional
            Friction coefficient, >= 0.
        """
        c2p, c4p = self.LeverArms(+1, math, mu)
        c2m, c4m = self.LeverArms(-1, math, mu)
        return c4p / (self.ratio * c2p), self.ratio * c2m / c4m

    @property
    def efficiencyWormDriving(self) -> float:
        """Efficiency with the worm driving (S = +1): c4 / (u c2) = tan(gamma)/tan(gamma + rho)."""
        c2, c4 = self.LeverArms(+1)
        return c4 / (self.ratio * c2)

    @property
    def efficiencyWheelDriving(self) -> float:
        """Efficiency with the wheel driving (S = -1): u c2 / c4 = tan(gamma - rho)/tan(gamma); <= 0: self-locking."""
        c2, c4 = self.LeverArms(-1)
        return self.ratio * c2 / c4

    def Replace(self, **changes) -> 'WormGear':
        """Return a copy with some parameters changed (``mu`` or ``rho`` given alone replaces both; a new ``mu``
        with a constant or Stribeck law needs a new ``friction`` too)."""
        if 'mu' in changes and 'rho' not in changes:
            changes['rho'] = None
        if 'rho' in changes and 'mu' not in changes:
            changes['mu'] = None
        return replace(self, **changes)
