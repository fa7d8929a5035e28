"""The inertia of the 3D model's bodies (worm and wheel as rigid bodies of revolution): mass, polar and tilt inertia.

A body of revolution turning about its axis has the inertia tensor ``diag(tilt, tilt, polar)`` about its centre of
mass, in body coordinates with the local z along its axis: ``polar`` about the axis, ``tilt`` (the diametral
inertia) about any line across the axis through the centre. Since the tensor's entries obey the triangle
inequality (here the perpendicular-axis bound ``2 tilt >= polar``, equality for a flat disc), a tilt inertia below
half the polar one belongs to no body: :func:`CheckBodyInertia` refuses it.

:func:`CylinderInertia` gives the two of a solid or hollow cylinder of mass m, outer radius ro, inner radius ri and
length L: ``polar = m (ro^2 + ri^2) / 2``, ``tilt = m (3 (ro^2 + ri^2) + L^2) / 12`` (about the centre).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

from .._checks import CheckNonNegative, CheckPositive

__all__ = ['BodyInertia', 'CylinderInertia', 'CheckBodyInertia']


@dataclass(frozen=True)
class BodyInertia:
    """A body of revolution's own mass and moments of inertia about its centre (SI).

    Parameters
    ----------
    mass : float
        Mass in kg (> 0).
    polar : float
        Moment of inertia about the axis in kg*m^2 (> 0).
    tilt : float
        Moment of inertia about a line across the axis through the centre of mass in kg*m^2 (>= polar / 2).
    """
    mass: float
    polar: float
    tilt: float

    def __post_init__(self):
        CheckBodyInertia('BodyInertia', 'body', self.mass, self.polar, self.tilt)


def CheckBodyInertia(where: str, body: str, mass: float, polar: float, tilt: float,
                     what: str = '') -> None:
    """Refuse a mass or inertia that is not positive and a tilt inertia below half the polar one.

    Parameters
    ----------
    where : str
        Who checks (function or file), first in the message.
    body : str
        The body (``'worm'``, ``'wheel'``), in the message and in the keys named (``wheelTiltInertia``).
    mass, polar, tilt : float
        Mass in kg, polar and tilt inertia in kg*m^2.
    what : str
        What the polar inertia is, in the message (default ``'{body}PolarInertia'``).

    Raises
    ------
    ValueError
        Naming the key, the bound and the values received.
    """
    CheckPositive(where, f'{body}Mass', mass, 'kg')
    CheckPositive(where, f'{body}PolarInertia', polar, 'kg*m^2')
    CheckPositive(where, f'{body}TiltInertia', tilt, 'kg*m^2')
    if 2. * tilt < polar * (1. - 1e-12):
        raise ValueError(f"{where}: '{body}TiltInertia' must be >= half the {body}'s polar inertia "
                         f"({what or f'{body}PolarInertia'}: {polar:g} kg*m^2), as for every body of revolution "
                         f"(perpendicular-axis bound 2 tilt >= polar, equality for a flat disc), got {tilt:g} "
                         f"kg*m^2")


def CylinderInertia(mass: float, radius: float, length: float, innerRadius: float = 0.,
                    where: str = 'CylinderInertia', body: str = 'body') -> BodyInertia:
    """Mass, polar and tilt inertia of a solid or hollow cylinder about its centre (module docstring).

    Parameters
    ----------
    mass : float
        Mass in kg (> 0).
    radius : float
        Outer radius in m (> 0).
    length : float
        Length along the axis in m (> 0).
    innerRadius : float
        Inner radius in m (>= 0, < radius; 0: solid).
    where : str
        Who asks, first in messages.
    body : str
        The body in messages (the keys ``{body}Radius``, ...).

    Returns
    -------
    BodyInertia

    Raises
    ------
    ValueError
        For a value out of range.
    """
    mass = CheckPositive(where, f'{body}Mass', mass, 'kg')
    ro = CheckPositive(where, f'{body}Radius', radius, 'm')
    L = CheckPositive(where, f'{body}Length', length, 'm')
    ri = CheckNonNegative(where, f'{body}InnerRadius', innerRadius, 'm')
    if ri >= ro:
        raise ValueError(f"{where}: '{body}InnerRadius' must be < {body}Radius = {ro:g} m, got {ri:g} m")
    squares = ro * ro + ri * ri
    return BodyInertia(mass=mass, polar=mass * squares / 2., tilt=mass * (3. * squares + L * L) / 12.)

