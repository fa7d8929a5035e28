"""Self-locking verdicts of a worm gear: static (friction at rest) and dynamic (friction at the sliding speed).

Theory: the wheel cannot drive the worm when the friction angle exceeds the lead angle, rho > gamma
(rho = atan(mu / cos(alphaN)), eq. (13)); the wheel-driving efficiency tan(gamma - rho)/tan(gamma) is then <= 0.
Static self-locking takes mu at rest (``muStatic``): the load holds when the worm stands. Dynamic self-locking
takes mu at the operating sliding speed: a moving worm comes to rest once the drive stops pushing. A gear that
is statically but not dynamically self-locking holds its load at rest but runs away once it moves.

Gear makers do not trust the sharp limit: their catalogues rate self-locking by the worm-driving efficiency
eta = tan(gamma)/tan(gamma + rho) (theory: eta < 0.5 roughly where rho > gamma) with a grey zone,
:data:`GREY_ZONE` = (0.45, 0.55). Source: SEVA-tec GmbH, FAQ "2.1.3 At what efficiency level does a helical worm
gear unit have self-locking?" (https://www.seva-tec.de/en/faq-for-electric-motors-gearmotors-and-frequency-inverters/
2.1.0-gear-motors-technology/10/2.1.3-ab-welchem-wirkungsgrad-hat-ein-schneckengetriebe-eine-selbsthemmung/102):
self-locking below 0.45, uncertain between 0.45 and 0.55, none above 0.55; it distinguishes static and dynamic
self-locking as we do. The page does not say which efficiency it means; we read it as the worm-driving
efficiency of the mesh (the one a catalogue lists).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Dict, Optional
from .._checks import CheckNonNegative

__all__ = ['GREY_ZONE', 'SelfLockingState', 'SelfLockingVerdict', 'SelfLocking', 'Rating']

#: worm-driving efficiencies between which self-locking is uncertain (SEVA-tec FAQ 2.1.3, module text)
GREY_ZONE = (0.45, 0.55)


def Rating(efficiencyWormDriving: float) -> str:
    """Gear makers' rating of a worm-driving efficiency: ``self-locking`` (< 0.45), ``uncertain``
    (0.45 to 0.55) or ``not self-locking`` (> 0.55).

    Parameters
    ----------
    efficiencyWormDriving : float
        tan(gamma)/tan(gamma + rho).
    """
    low, high = GREY_ZONE
    return ('self-locking' if efficiencyWormDriving < low else 'not self-locking' if efficiencyWormDriving > high
            else 'uncertain')


@dataclass(frozen=True)
class SelfLockingState:
    """Self-locking at one friction coefficient.

    Attributes
    ----------
    mu : float
        Friction coefficient.
    slidingSpeed : float or None
        Sliding speed in m/s at which mu holds (0 at rest; None: any speed, constant friction).
    frictionAngle : float
        rho = atan(mu / cos(alphaN)) in rad.
    efficiencyWormDriving, efficiencyWheelDriving : float
        Efficiencies at mu (wheel driving <= 0: self-locking).
    selfLocking : bool
        rho > gamma.
    rating : str
        :func:`Rating` of the worm-driving efficiency.
    """
    mu: float
    slidingSpeed: Optional[float]
    frictionAngle: float
    efficiencyWormDriving: float
    efficiencyWheelDriving: float
    selfLocking: bool
    rating: str

    def ToDict(self) -> Dict:
        """JSON-ready dictionary."""
        return {'mu': self.mu, 'slidingSpeed': self.slidingSpeed, 'frictionAngle': self.frictionAngle,
                'efficiencyWormDriving': self.efficiencyWormDriving,
                'efficiencyWheelDriving': self.efficiencyWheelDriving, 'selfLocking': self.selfLocking,
                'rating': self.rating}


@dataclass(frozen=True)
class SelfLockingVerdict:
    """Static (at rest) and dynamic (at the operating sliding speed) self-locking of a gear.

    Attributes
    ----------
    static : SelfLockingState
        At mu(0) = muStatic.
    dynamic : SelfLockingState or None
        At mu(v0); None if the friction depends on speed and no speed was given.
    """
    static: SelfLockingState
    dynamic: Optional[SelfLockingState]

    @property
    def dangerous(self) -> bool:
        """Statically but not dynamically self-locking: the load holds at rest but runs away once moving."""
        return self.static.selfLocking and self.dynamic is not None and not self.dynamic.selfLocking

    def ToDict(self) -> Dict:
        """JSON-ready ``{static, dynamic, dangerous, greyZone}``."""
        return {'static': self.static.ToDict(), 'dynamic': None if self.dynamic is None else self.dynamic.ToDict(),
                'dangerous': self.dangerous, 'greyZone': list(GREY_ZONE)}


def _State(gear, mu: float, slidingSpeed) -> SelfLockingState:
    rho = math.atan(mu / math.cos(gear.alphaN))
    etaWorm, etaWheel = gear.Efficiencies(mu)
    return SelfLockingState(mu=float(mu), slidingSpeed=slidingSpeed, frictionAngle=rho, efficiencyWormDriving=etaWorm,
                            efficiencyWheelDriving=etaWheel, selfLocking=gear.gamma < rho, rating=Rating(etaWorm))


def SelfLocking(gear: 'WormGear', slidingSpeed: Optional[float] = None) -> SelfLockingVerdict:
    """Static and dynamic self-locking of ``gear``.

    Parameters
    ----------
    gear : WormGear
        The mesh and its friction law.
    slidingSpeed : float, optional
        Operating sliding speed in m/s, >= 0 (:meth:`~exudyn_worm.model.gear.WormGear.SlidingSpeed` of the motor speed).
        None: the dynamic verdict is that of the constant mu for a constant law, and None for a speed-dependent one.

    Returns
    -------
    SelfLockingVerdict
    """
    static = _State(gear, gear.muStatic, 0.)
    if slidingSpeed is None:
        dynamic = None if gear.speedDependentFriction else _State(gear, gear.mu, None)
    else:
        v = CheckNonNegative('SelfLocking', 'slidingSpeed', slidingSpeed, 'm/s')
        dynamic = _State(gear, float(gear.FrictionCoefficient(v)), v)
    return SelfLockingVerdict(static, dynamic)
