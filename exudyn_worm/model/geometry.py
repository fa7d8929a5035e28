"""Worm-gear geometry from its designation: reference radii r1, r2 and lead angle gamma of the model.

The model (eqs. (3)-(13)) takes the reference radius of the worm ``r1``, of the wheel ``r2`` and the lead
(pitch) angle ``gamma``; its transmission ratio is eq. (3), u = r2 / (r1 tan(gamma)). Worm gears are
specified in other terms, and a parameter set may give the geometry in one of three *forms*
(:data:`GEOMETRY_FORMS`):

- ``radii``: ``r1, r2, gamma`` (the model's own);
- ``centre distance``: ``a`` (centre distance), ``u`` (ratio), ``gamma``;
- ``designation``: ``mx`` (axial module), ``z1`` (number of starts), ``z2`` (wheel teeth), ``q`` (diameter
  quotient), the names of DIN 3975 / ISO/TR 10828.

Relations of the cylindrical worm gear without profile shift (reference = working circles):

- d1 = q mx, d2 = z2 mx, tan(gamma) = z1 / q (the lead is z1 px = z1 pi mx = pi d1 tan(gamma)),
  a = (d1 + d2) / 2, u = z2 / z1. Sources: Autodesk Inventor help, "Basic Geometric Calculation for Worm
  Gears" (https://help.autodesk.com/view/INVNTOR/2026/ENU/?guid=GUID-F287879C-3787-40A8-A01B-F980F6E16F85:
  d1 = q m, d2 = z2 mx, gamma = arctan(z1/q) for ZA worms, working diameter dw1 = d1 + 2 x m); tandwiel.info,
  "Cylindrical worm and wormwheel" (http://www.tandwiel.info/en/gears/cylindrical-worm-wormwheel/: d2 = z2 mx,
  dm1 = 2 a - d2, lead pz = z1 px = dm1 pi tan(gamma)).
- With r1 = d1/2 and r2 = d2/2, eq. (3) gives u = r2 / (r1 tan(gamma)) = (z2 mx) / (q mx z1 / q) = z2 / z1:
  the model's ratio is the tooth ratio.
- From ``a, u, gamma``: a = r1 + r2 and r2 = u r1 tan(gamma) (eq. (3)) give r1 = a / (1 + u tan(gamma)),
  r2 = a - r1.

A wheel with profile shift x2 has a = (d1 + d2)/2 + x2 mx; its working circle of the worm is dw1 = d1 + 2 x2 mx
and the lead angle there is tan(gamma_w) = z1 mx / dw1. The model then takes r1 = dw1/2, r2 = d2/2 and
gamma_w (u = z2/z1 still holds): give these as ``r1, r2, gamma``, or ``a, u, gamma_w``.
"""
from __future__ import annotations

import enum
import math
from typing import Dict, Mapping, Tuple

from .._checks import CheckAngle, CheckPositive
from ..params.parameters import PARAMETERS, MissingParameterError

__all__ = ['GEOMETRY_FORMS', 'GEOMETRY_KEYS', 'GeometryFormKind', 'GeometryForm', 'RadiiFromCentreDistance', 'RadiiFromDesignation',
           'DesignationFromRadii', 'GeometryFromParameters', 'MissingGeometryKeys', 'DescribeGeometry',
           'MeshStiffnessFromWheelTorsion']



class GeometryFormKind(str, enum.Enum):
    """The form in which a parameter set gives the gear geometry; the value is its name in messages and JSON.

    Attributes
    ----------
    RADII, CENTRE_DISTANCE, DESIGNATION : GeometryFormKind
        ``r1 r2 gamma``; ``a u gamma``; ``mx z1 z2 q`` (the forms of the registry's ``gear geometry``).
    """
    RADII = 'radii'
    CENTRE_DISTANCE = 'centre distance'
    DESIGNATION = 'designation'

    def __str__(self) -> str:
        return self.value

    def __format__(self, spec: str) -> str:
        return format(self.value, spec)

    def __hash__(self) -> int:          # equal to its name, so also a key of a dictionary by name
        return hash(self.value)


#: the forms in which a parameter set may give the gear geometry: form -> its keys (all required), as declared in
#: the registry (``radii``: gamma r1 r2, ``centre distance``: gamma a u, ``designation``: mx z1 z2 q)
GEOMETRY_FORMS: Dict[GeometryFormKind, Tuple[str, ...]] = {GeometryFormKind(form): keys for form, keys
                                                           in PARAMETERS.Forms('gear geometry').items()}
#: every key of the gear geometry, in the order of the registry
GEOMETRY_KEYS: Tuple[str, ...] = tuple(dict.fromkeys(k for keys in GEOMETRY_FORMS.values() for k in keys))


def RadiiFromDesignation(mx: float, z1: float, z2: float, q: float) -> Tuple[float, float, float]:
    """Reference radii and lead angle from the designation (axial module, starts, wheel teeth, diameter quotient).

    r1 = d1/2 = q mx / 2, r2 = d2/2 = z2 mx / 2, gamma = atan(z1 / q) (module docstring for the sources).

    Parameters
    ----------
    mx : float
        Axial module in m, > 0.
    z1 : float
        Number of starts (threads) of the worm, > 0.
    z2 : float
        Number of teeth of the wheel, > 0.
    q : float
        Diameter quotient d1 / mx, > 0.

    Returns
    -------
    (float, float, float)
        ``(r1, r2, gamma)`` in m, m, rad.

    Examples
    --------
    >>> r1, r2, gamma = RadiiFromDesignation(3e-3, 2, 30, 44 / 3)   # d1 = 44 mm, d2 = 90 mm
    >>> round(r1 * 1e3, 9), round(r2 * 1e3, 9), round(math.degrees(gamma), 10)
    (22.0, 45.0, 7.7651660184)
    """
    w = 'RadiiFromDesignation'
    mx = CheckPositive(w, 'mx', mx, 'm')
    z1, z2, q = (CheckPositive(w, name, value) for name, value in (('z1', z1), ('z2', z2), ('q', q)))
    return 0.5 * q * mx, 0.5 * z2 * mx, math.atan(z1 / q)


def RadiiFromCentreDistance(a: float, u: float, gamma: float) -> Tuple[float, float]:
    """Reference radii from centre distance, ratio and lead angle, consistent with eq. (3).

    a = r1 + r2 and u = r2 / (r1 tan(gamma)) give r1 = a / (1 + u tan(gamma)), r2 = a - r1.

    Parameters
    ----------
    a : float
        Centre distance in m, > 0.
    u : float
        Transmission ratio (z2 / z1), > 0.
    gamma : float
        Lead angle in rad, in (0, pi/2).

    Returns
    -------
    (float, float)
        ``(r1, r2)`` in m.

    Examples
    --------
    >>> r1, r2 = RadiiFromCentreDistance(0.067, 15., math.atan(2 / (44 / 3)))
    >>> round(r1 * 1e3, 9), round(r2 * 1e3, 9)
    (22.0, 45.0)
    """
    w = 'RadiiFromCentreDistance'
    a = CheckPositive(w, 'a', a, 'm')
    u = CheckPositive(w, 'u', u)
    gamma = CheckAngle(w, 'gamma', gamma)
    r1 = a / (1. + u * math.tan(gamma))
    return r1, a - r1


def DesignationFromRadii(r1: float, r2: float, gamma: float, z1: float = 1.) -> Dict[str, float]:
    """The designation and centre distance of a gear given by the model's radii and lead angle.

    For a chosen number of starts z1: q = z1 / tan(gamma), mx = 2 r1 / q, z2 = u z1 with u of eq. (3),
    a = r1 + r2. z2 is a whole number only if the radii fit a real gear.

    Parameters
    ----------
    r1, r2 : float
        Reference radii of worm and wheel in m, > 0.
    gamma : float
        Lead angle in rad, in (0, pi/2).
    z1 : float, optional
        Number of starts of the worm, > 0 (default 1).

    Returns
    -------
    dict
        ``{'a': m, 'u': -, 'mx': m, 'z1': -, 'z2': -, 'q': -}``.

    Examples
    --------
    >>> d = DesignationFromRadii(0.022, 0.045, math.atan(2 / (44 / 3)), z1=2)
    >>> round(d['z2'], 9), round(d['mx'] * 1e3, 9), round(d['q'], 9), round(d['a'] * 1e3, 9)
    (30.0, 3.0, 14.666666667, 67.0)
    """
    w = 'DesignationFromRadii'
    r1, r2 = CheckPositive(w, 'r1', r1, 'm'), CheckPositive(w, 'r2', r2, 'm')
    gamma = CheckAngle(w, 'gamma', gamma)
    z1 = CheckPositive(w, 'z1', z1)
    q = z1 / math.tan(gamma)
    u = r2 / (r1 * math.tan(gamma))                     # eq. (3)
    return {'a': r1 + r2, 'u': u, 'mx': 2. * r1 / q, 'z1': z1, 'z2': u * z1, 'q': q}


def GeometryForm(parameters: Mapping[str, float]) -> GeometryFormKind:
    """The form in which ``parameters`` give the gear geometry (a key of :data:`GEOMETRY_FORMS`).

    ``designation`` if any of ``mx, z1, z2, q`` is given, else ``centre distance`` if ``a`` or ``u`` is,
    else ``radii``. Whether the form is complete is checked by :func:`GeometryFromParameters`.

    Parameters
    ----------
    parameters : mapping
        Flat parameter dictionary.

    Returns
    -------
    GeometryFormKind
        A str enum: its value is the form's name (``'centre distance'``).
    """
    for form in (GeometryFormKind.DESIGNATION, GeometryFormKind.CENTRE_DISTANCE):
        if any(k in parameters for k in GEOMETRY_FORMS[form] if k != 'gamma'):
            return form
    return GeometryFormKind.RADII


def MissingGeometryKeys(parameters: Mapping[str, float]) -> Tuple[str, ...]:
    """The keys missing from the geometry form that ``parameters`` use (empty if complete).

    Parameters
    ----------
    parameters : mapping
        Flat parameter dictionary.

    Returns
    -------
    tuple of str
    """
    return tuple(k for k in GEOMETRY_FORMS[GeometryForm(parameters)] if k not in parameters)


def GeometryFromParameters(parameters: Mapping[str, float], where: str = 'GeometryFromParameters'
                           ) -> Tuple[float, float, float]:
    """``(r1, r2, gamma)`` of a flat parameter dictionary that gives the geometry in one of :data:`GEOMETRY_FORMS`.

    Parameters
    ----------
    parameters : mapping
        Flat parameter dictionary (SI); mixed forms (``r1`` with ``a``) are refused by
        :func:`~exudyn_worm.drive.presets.CheckParameterKeys` before this is called.
    where : str
        Prefix of error messages.

    Returns
    -------
    (float, float, float)
        ``(r1, r2, gamma)`` in m, m, rad.

    Raises
    ------
    MissingParameterError
        (a ValueError) if the form is incomplete; it names the missing keys and the three forms.
    """
    form = GeometryForm(parameters)
    missing = MissingGeometryKeys(parameters)
    if missing:
        given = [k for k in GEOMETRY_FORMS[form] if k in parameters]
        raise MissingParameterError(
            f"{where}: missing parameter(s) {', '.join(missing)} of the gear geometry"
            + (f" (given {', '.join(given)}: the {form} form needs {', '.join(GEOMETRY_FORMS[form])})" if given else '')
            + f"; give one of: {PARAMETERS.FormsText('gamma')}; with --set KEY=VALUE or in the config file", missing)
    p = parameters
    if form is GeometryFormKind.DESIGNATION:
        return RadiiFromDesignation(p['mx'], p['z1'], p['z2'], p['q'])
    if form is GeometryFormKind.CENTRE_DISTANCE:
        return RadiiFromCentreDistance(p['a'], p['u'], p['gamma']) + (float(p['gamma']),)
    return float(p['r1']), float(p['r2']), float(p['gamma'])


def DescribeGeometry(parameters: Mapping[str, float]) -> str:
    """One line saying how the radii were derived, e.g. for ``exudyn-worm stability``; ``''`` for the radii form.

    Parameters
    ----------
    parameters : mapping
        Flat parameter dictionary (SI) with a complete geometry form.

    Returns
    -------
    str
        E.g. ``'gear geometry from a = 40 mm, u = 40, gamma = 3.5 deg: r1 = 11.61 mm, r2 = 28.39 mm,
        gamma = 3.5 deg, u = r2/(r1 tan(gamma)) = 40 (eq. (3))'``.
    """
    form = GeometryForm(parameters)
    if form is GeometryFormKind.RADII:
        return ''
    r1, r2, gamma = GeometryFromParameters(parameters, 'DescribeGeometry')
    text = {'mx': lambda v: f'{v * 1e3:.6g} mm', 'a': lambda v: f'{v * 1e3:.6g} mm',
            'gamma': lambda v: f'{math.degrees(v):.6g} deg'}
    given = ', '.join(f"{k} = {text.get(k, lambda v: f'{v:.6g}')(parameters[k])}" for k in GEOMETRY_FORMS[form])
    u = r2 / (r1 * math.tan(gamma))
    return (f"gear geometry from the {form} {given}: r1 = {r1 * 1e3:.6g} mm, r2 = {r2 * 1e3:.6g} mm, "
            f"gamma = {math.degrees(gamma):.6g} deg, u = r2/(r1 tan(gamma)) = {u:.6g} (eq. (3))")


def MeshStiffnessFromWheelTorsion(torsionalStiffness: float, r2: float, alphaN: float, gamma: float) -> float:
    """Mesh stiffness kV in the normal direction from a torsional stiffness of the mesh measured at the wheel.

    With the worm held (phi1 = 0) and no friction, a wheel rotation phi2 deflects the mesh by
    Delta s = -r1 cos(alphaN) sin(gamma) u phi2 = -r2 cos(alphaN) cos(gamma) phi2 (eqs. (3)-(5)), and the normal
    force acts on the wheel through the lever c4 = r2 cos(alphaN) cos(gamma) (eq. (12) with rho = 0). The wheel
    therefore feels k_phi2 = kV (r2 cos(alphaN) cos(gamma))^2, and kV = k_phi2 / (r2 cos(alphaN) cos(gamma))^2.
    This is the model's own relation, not an estimate from materials: ``torsionalStiffness`` must be the mesh's
    share of a measured (or catalogue) torsional stiffness, without shafts, bearings and housing. With friction
    the lever is r2 cos(alphaN) cos(gamma + rho S) / cos(rho), a few percent different (docs/gear-data.md).

    Parameters
    ----------
    torsionalStiffness : float
        Torsional stiffness of the mesh at the wheel, worm held, in N*m/rad, > 0.
    r2 : float
        Reference radius of the wheel in m, > 0.
    alphaN : float
        Normal pressure angle in rad, in (0, pi/2).
    gamma : float
        Lead angle in rad, in (0, pi/2).

    Returns
    -------
    float
        kV in N/m.

    Examples
    --------
    >>> kV = MeshStiffnessFromWheelTorsion(2e8 * (0.10595 * math.cos(math.radians(20))
    ...                                    * math.cos(math.radians(5.3228)))**2, 0.10595, math.radians(20),
    ...                                    math.radians(5.3228))
    >>> round(kV / 1e8, 9)
    2.0
    """
    w = 'MeshStiffnessFromWheelTorsion'
    torsionalStiffness = CheckPositive(w, 'torsionalStiffness', torsionalStiffness, 'N*m/rad')
    r2 = CheckPositive(w, 'r2', r2, 'm')
    lever = r2 * math.cos(CheckAngle(w, 'alphaN', alphaN)) * math.cos(CheckAngle(w, 'gamma', gamma))
    return torsionalStiffness / lever**2
