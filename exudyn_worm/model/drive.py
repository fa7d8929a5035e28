"""The elastic-drive model of the paper's Figure 2 and its damping measures, eqs. (22)-(24)."""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from .._checks import CheckArray, CheckNonNegative, CheckPositive
from .gear import WormGear

__all__ = ['ElasticDrive', 'AxialBearing', 'TorsionalDampingFromMeasure', 'TorsionalDampingMeasure',
           'MeshDampingFromMeasure', 'MeshDampingMeasure']


def TorsionalDampingFromMeasure(DT: float, kT: float, J1: float) -> float:
    """Shaft damping dT = 2 D_T sqrt(kT J1) in N*m*s/rad, eq. (22).

    Parameters
    ----------
    DT : float
        Torsional damping measure D_T, >= 0.
    kT : float
        Shaft stiffness in N*m/rad, > 0.
    J1 : float
        Worm-side inertia in kg*m^2, > 0.

    The arguments may be numpy arrays (broadcast together; the stability charts use that).
    """
    w = 'TorsionalDampingFromMeasure'
    return 2. * CheckArray(w, 'DT', DT, lowOpen=False) * np.sqrt(CheckArray(w, 'kT', kT, unit='N*m/rad')
                                                                 * CheckArray(w, 'J1', J1, unit='kg*m^2'))


def TorsionalDampingMeasure(dT: float, kT: float, J1: float) -> float:
    """Damping measure D_T = dT / (2 sqrt(kT J1)), eq. (22) inverted.

    Parameters
    ----------
    dT : float
        Torsional damping of the drive shaft in N*m*s/rad, >= 0.
    kT : float
        Torsional stiffness of the drive shaft in N*m/rad, > 0.
    J1 : float
        Worm-side inertia in kg*m^2, > 0.

    Returns
    -------
    float
        D_T, dimensionless.
    """
    w = 'TorsionalDampingMeasure'
    return CheckNonNegative(w, 'dT', dT, 'N*m*s/rad') / (2. * math.sqrt(
        CheckPositive(w, 'kT', kT, 'N*m/rad') * CheckPositive(w, 'J1', J1, 'kg*m^2')))


def MeshDampingFromMeasure(DV: float, kV: float, r2: float, J2: float) -> float:
    """Mesh damping dV from dV r2^2 = 2 D_V sqrt(kV r2^2 J2), eq. (23), in N*s/m.

    Parameters
    ----------
    DV : float
        Mesh damping measure D_V, >= 0.
    kV : float
        Mesh stiffness in N/m, > 0.
    r2 : float
        Wheel radius in m, > 0.
    J2 : float
        Wheel-side inertia in kg*m^2, > 0.

    ``DV`` and ``J2`` may be numpy arrays (broadcast together).
    """
    w = 'MeshDampingFromMeasure'
    kV = CheckPositive(w, 'kV', kV, 'N/m')
    r2 = CheckPositive(w, 'r2', r2, 'm')
    return 2. * CheckArray(w, 'DV', DV, lowOpen=False) * np.sqrt(kV * r2**2 * CheckArray(w, 'J2', J2, unit='kg*m^2')
                                                                 ) / r2**2


def MeshDampingMeasure(dV: float, kV: float, r2: float, J2: float) -> float:
    """Damping measure D_V = dV r2^2 / (2 sqrt(kV r2^2 J2)), eq. (23) inverted.

    Parameters
    ----------
    dV : float
        Mesh damping in N*s/m, >= 0.
    kV : float
        Mesh stiffness in N/m, > 0.
    r2 : float
        Wheel radius in m, > 0.
    J2 : float
        Wheel-side inertia in kg*m^2, > 0.

    Returns
    -------
    float
        D_V, dimensionless.
    """
    w = 'MeshDampingMeasure'
    kV = CheckPositive(w, 'kV', kV, 'N/m')
    r2 = CheckPositive(w, 'r2', r2, 'm')
    return CheckNonNegative(w, 'dV', dV, 'N*s/m') * r2**2 / (
        2. * math.sqrt(kV * r2**2 * CheckPositive(w, 'J2', J2, 'kg*m^2')))


@dataclass(frozen=True)
class ElasticDrive:
    """Worm gear with elastic drive shaft (paper Figure 2): the 2-DOF model of eqs. (1)-(2).

    Parameters
    ----------
    gear : WormGear
        The mesh.
    J1 : float
        Inertia on the worm shaft in kg*m^2, > 0.
    J2 : float
        Inertia on the wheel shaft in kg*m^2, > 0.
    kT : float
        Torsional stiffness of the drive shaft in N*m/rad, > 0.
    dT : float
        Torsional damping of the drive shaft in N*m*s/rad, >= 0.

    Raises
    ------
    ValueError, TypeError
        For out-of-range or non-numeric values.
    """
    gear: WormGear
    J1: float
    J2: float
    kT: float
    dT: float

    def __post_init__(self):
        w = 'ElasticDrive'
        if not isinstance(self.gear, WormGear):
            raise TypeError(f"{w}: 'gear' must be a WormGear, got {type(self.gear).__name__}")
        object.__setattr__(self, 'J1', CheckPositive(w, 'J1', self.J1, 'kg*m^2'))
        object.__setattr__(self, 'J2', CheckPositive(w, 'J2', self.J2, 'kg*m^2'))
        object.__setattr__(self, 'kT', CheckPositive(w, 'kT', self.kT, 'N*m/rad'))
        object.__setattr__(self, 'dT', CheckNonNegative(w, 'dT', self.dT, 'N*m*s/rad'))

    @property
    def DT(self) -> float:
        """Torsional damping measure D_T, eq. (22)."""
        return TorsionalDampingMeasure(self.dT, self.kT, self.J1)

    @property
    def DV(self) -> float:
        """Mesh damping measure D_V, eq. (23)."""
        return MeshDampingMeasure(self.gear.dV, self.gear.kV, self.gear.r2, self.J2)

    @property
    def DTV(self) -> float:
        """Damping ratio D_TV = D_T / D_V, eq. (24) (inf if D_V = 0)."""
        DV = self.DV
        return self.DT / DV if DV > 0 else math.inf

    @property
    def stiffnessRatio(self) -> float:
        """Chart abscissa kT / (kV r1^2) of Figures 4 and 5."""
        return self.kT / (self.gear.kV * self.gear.r1**2)

    @property
    def inertiaRatio(self) -> float:
        """Chart ordinate J1 / J2 of Figures 3-5."""
        return self.J1 / self.J2

    def Replace(self, **changes) -> 'ElasticDrive':
        """Return a copy with some drive parameters changed."""
        return replace(self, **changes)


@dataclass(frozen=True)
class AxialBearing:
    """Axial bearing of the worm: the worm's axially moving mass on an axial spring-damper to the housing.

    Parameters
    ----------
    stiffness : float
        Axial stiffness kA in N/m, > 0.
    damping : float
        Axial damping dA in N*s/m, >= 0.
    mass : float
        Axially moving mass of the worm mA in kg, > 0 (worm, shaft and the bearing parts moving with it).
    """
    stiffness: float
    damping: float
    mass: float

    def __post_init__(self):
        w = 'AxialBearing'
        object.__setattr__(self, 'stiffness', CheckPositive(w, 'stiffness', self.stiffness, 'N/m'))
        object.__setattr__(self, 'damping', CheckNonNegative(w, 'damping', self.damping, 'N*s/m'))
        object.__setattr__(self, 'mass', CheckPositive(w, 'mass', self.mass, 'kg'))
