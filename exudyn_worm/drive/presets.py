"""Parameter sets of the paper and the resolution of a flat parameter dictionary into an ElasticDrive.

A parameter set is a flat dictionary keyed by the names used everywhere (Python API, ``--set``,
TOML config): ``alphaN gamma mu rho r1 r2 kV dV DV backlash J1 J2 kT dT DT DTV`` and, for the
reel changer, ``loadMass leverArm motorSpeed``. All values are SI, angles in rad, speeds in rad/s.

Damping is held as the measures D_T, D_V of eqs. (22)-(23) (or D_TV = D_T/D_V), so a changed J1 or
kT keeps the measure, as the paper's chart points assume; an explicit ``dT`` or ``dV`` overrides.

Optional components beyond the two-mass drive (absent = the drive of Figure 2):

- **Drive-side chain (Figure 19)**: ``J4`` (kg*m^2, *inertia4*), ``k4`` (N*m/rad) and ``d4`` (N*m*s/rad,
  *spring-Damper4*), continued as ``J5, k5, d5``, ``J6, k6, d6``, ... Topology (worm first)::

      worm J1 --(kT, dT)-- J4 --(k4, d4)-- J5 --(k5, d5)-- ... --(kn, dn)-- motor phi0(t)

  i.e. spring-damper *i* sits on the motor side of inertia *i*, as *spring-Damper1* (the drive shaft
  kT, dT) sits on the motor side of *inertia1* (the worm) in Figures 7 and 19. This is the reading of
  section 3.2.5: inertia4 "increases the equivalent drive mass" and stabilizes "if the additional
  inertia and the stiffness of spring-Damper1 are large enough and the stiffness of spring-Damper4 is
  small enough", i.e. inertia4 is tied to the worm through spring-Damper1 and to the motor through
  spring-Damper4. ``Ji`` needs ``ki`` > 0; ``di`` is optional (default 0); the chain has no gaps
  (``J5`` needs ``J4``). See :func:`DriveSideChain`.
- **Load-side chain** (wheel to driven machine): ``JL1`` (kg*m^2), ``kL1`` (N*m/rad) and ``dL1``
  (N*m*s/rad), continued as ``JL2, kL2, dL2``, ... Topology (wheel first)::

      wheel J2 --(kL1, dL1)-- JL1 --(kL2, dL2)-- JL2 -- ... -- JLn <- load torque

  i.e. load shaft *i* sits on the wheel side of inertia *i*; the load torque (the reel changer's lever) acts
  on the last inertia. J2 is then the wheel's own inertia. ``JLi`` needs ``kLi`` > 0; ``dLi`` is optional
  (default 0); no gaps. See :func:`LoadSideChain`; when lumping the chain into J2 is safe:
  docs/drive-files.md, "Load-side chain".
- **Worm axial bearing**: ``kA`` (N/m), ``dA`` (N*s/m, default 0), ``mA`` (kg, the worm's axially moving
  mass, required when ``kA`` > 0). Absent or ``kA = 0``: axially rigid worm. See
  :func:`AxialBearingFromParameters` and :func:`exudyn_worm.model.contact.MeshContact` for the kinematics.
"""
from __future__ import annotations

import math
import os
from typing import Dict, List, Mapping, Optional, Tuple

import numpy as np

from .._checks import CheckMapping, CheckNonNegative
from ..model.drive import AxialBearing, ElasticDrive, MeshDampingFromMeasure, TorsionalDampingFromMeasure
from ..model.gear import WormGear
from ..model.geometry import GEOMETRY_FORMS, GEOMETRY_KEYS, GeometryForm, GeometryFromParameters, MissingGeometryKeys
from ..params.parameters import PARAMETERS, MissingParameterError, ParameterError
from ..items.bearings import WHEEL_MASS, WORM_MASS, ShaftBearings, ShaftSupports
from ..model.bodies import BodyInertia, CheckBodyInertia, CylinderInertia
from ..model.friction import FrictionLaw, ReadFrictionTable
from ..model.stability import CharacteristicCoefficients

__all__ = ['DRIVE_KEYS', 'REEL_KEYS', 'DUTY_KEYS', 'CHAIN_KEYS', 'AXIAL_KEYS', 'PARAMETER_UNITS', 'PRESETS', 'GetPreset',
           'ExtraComponents',
           'ApplyOverrides', 'CheckParameterKeys', 'CheckParameters', 'UnknownParameterMessage', 'GearFromParameters',
           'FrictionLawFromParameters',
           'DriveFromParameters', 'ElasticDriveFromParameters', 'ElasticDriveWithGear',
           'DriveSideChain', 'LoadSideChain', 'LOAD_CHAIN_KEYS',
           'AxialBearingFromParameters', 'ShaftSupportsFromParameters', 'SHAFT_KEYS', 'BODY_KEYS', 'MAX_RATE', 'MIN_RATE_SPREAD']

#: keys of the elastic drive (Figure 2): the drive-file tables [gear], [worm], [wheel], [driveShaft]
DRIVE_KEYS = PARAMETERS.KeysOf('gear', 'worm', 'wheel', 'driveShaft')
#: keys of the paper-reel-changer load case (section 3.2): the lever's mass and arm, the motor speed
REEL_KEYS = ('loadMass', 'leverArm', 'motorSpeed')
#: keys of the duty cycle: load and motor (the reel changer's and the others, see exudyn_worm.drive.duty)
DUTY_KEYS = PARAMETERS.KeysOf('load', 'motor')

#: keys of the first element of the drive-side chain (Figure 19); J5/k5/d5, ... continue it
CHAIN_KEYS = PARAMETERS.KeysOf('driveSide')
#: keys of the first stage of the load-side chain (wheel to driven machine); JL2/kL2/dL2, ... continue it
LOAD_CHAIN_KEYS = PARAMETERS.KeysOf('loadSide')
#: keys of the worm's axial bearing
AXIAL_KEYS = PARAMETERS.KeysOf('axialBearing')
#: the bodies' keys of the 3D model: mass, own inertias or the shape they come from
BODY_KEYS = tuple(f'{body}{key}' for body in ('worm', 'wheel')
                  for key in ('Mass', 'TiltInertia', 'PolarInertia', 'Radius', 'InnerRadius', 'Length'))
#: keys of the 3D model (worm and wheel as rigid bodies, docs/mesh-3d.md): the shafts' bearings and the bodies
SHAFT_KEYS = PARAMETERS.KeysOf('wormBearing', 'wheelBearing') + BODY_KEYS

#: SI unit of every key (pint syntax), used to parse quantities such as ``8 deg`` or ``0.5 mm``; the
#: chain keys J5, k5, d5, J6, ... are accepted too (``'J5' in PARAMETER_UNITS``), though only J4/k4/d4 are listed.
#: Derived from the registry :data:`~exudyn_worm.params.parameters.PARAMETERS`, where every key is declared.
PARAMETER_UNITS = PARAMETERS.units

_deg = math.radians
_RPM = 2 * math.pi / 60

#: gear of parameter set (28) with mu = 0.132 (rho = 7.996 deg, printed "8 deg"): only this friction
#: reproduces all printed b-coefficients and the value of (19); the mu = 0.134 printed with (28) does not
#: (see validation/REPORT.md, "Which friction the paper used")
_REEL_P1 = {'alphaN': _deg(20), 'gamma': _deg(5.3228), 'mu': 0.132, 'r1': 18.05e-3, 'r2': 105.95e-3,
            'J2': 33., 'kV': 2e8, 'DV': 0.014, 'J1': 0.1, 'kT': 7000., 'DT': 0.014, 'backlash': 0.,
            'loadMass': 175., 'leverArm': 1.2, 'motorSpeed': 472.5 * _RPM}

#: every preset, with its source in the paper
PRESETS: Dict[str, Dict[str, float]] = {
    # set (25), section 2.3 (mu = 0.132 (rho = 8 deg); dV = 1250 N*s/m printed, D_V = 0.028): the chart sweeps J1 and kT
    'chart': {'alphaN': _deg(20), 'gamma': _deg(5.3228), 'mu': 0.132, 'r1': 3.235e-3, 'r2': 18.98e-3,
              'J2': 0.1, 'kV': 1.7728e6, 'dV': 1250., 'backlash': 0.},
    'reel-P1': dict(_REEL_P1),                                   # set (28), section 3.1
    'reel-P2': {**_REEL_P1, 'J1': 0.3},                          # section 3.2.4
    'reel-P3': {**_REEL_P1, 'J1': 0.033},                        # section 3.2.4
    'reel-P4': {**_REEL_P1, 'kT': 2 * 7000.},                    # section 3.2.4
    'reel-P5': {**_REEL_P1, 'kT': 7000. / 5},                    # section 3.2.4
    'reel-P6': {**{k: v for k, v in _REEL_P1.items() if k != 'DT'},
                'J1': 0.2, 'kT': 12000., 'DTV': 2.},              # section 3.2.4, at D_V = 0.014
    'reel-P7': {**_REEL_P1, 'J1': 0.01, 'kT': 700.},             # section 3.2.3
}

#: the paper's verdict for each reel preset (Figure 4, sections 3.2.2-3.2.4)
PAPER_CHATTERS = {'reel-P1': True, 'reel-P2': False, 'reel-P3': False, 'reel-P4': False,
                  'reel-P5': False, 'reel-P6': True, 'reel-P7': True}


def GetPreset(name: str) -> Dict[str, float]:
    """Return a copy of preset ``name`` (one of :data:`PRESETS`).

    Parameters
    ----------
    name : str
        Preset name, e.g. ``'reel-P1'``.

    Returns
    -------
    dict
        Flat parameter set (SI units, angles in rad).

    Raises
    ------
    ValueError
        For an unknown name.
    """
    if name not in PRESETS:
        raise ValueError(f"GetPreset: 'name': unknown preset {name!r}; expected one of: {', '.join(PRESETS)}")
    return dict(PRESETS[name])


def UnknownParameterMessage(where: str, key) -> str:
    """The message for an unknown parameter key: names ``where`` and ``key``, a near miss and the known keys.

    Parameters
    ----------
    where : str
        Prefix of the message (the function or the file location).
    key : object
        The key received.

    Returns
    -------
    str
        E.g. ``"DriveFromParameters: unknown parameter 'Kt' (did you mean 'kT'?); expected one of: alphaN ..."``.
    """
    return PARAMETERS.UnknownKeyMessage(where, key)


def CheckParameterKeys(parameters: Mapping[str, float], where: str = 'parameter set', name: str = 'parameters') -> None:
    """Check the keys of a flat parameter dictionary: a mapping, only known keys, one form per quantity.

    Parameters
    ----------
    parameters : mapping
        Flat parameter dictionary (SI).
    where : str
        Prefix of the error messages (the function that received the set).
    name : str
        The argument's name in the messages.

    Raises
    ------
    TypeError
        If ``parameters`` is not a mapping (a string is taken for a preset name: the message suggests
        ``GetPreset(name)``).
    ValueError
        For a key that is not a parameter (with a near-miss suggestion, e.g. ``'Kt'`` -> ``'kT'``), or two
        forms of one quantity given together (``mu`` with ``rho``, ``dV`` with ``DV``, two of ``dT``, ``DT``,
        ``DTV``): which one is meant is not clear. To change one form of a set that holds another, use
        :func:`ApplyOverrides`, which drops the other forms.
    """
    CheckMapping(where, name, parameters, preset=name == 'parameters')
    if name != 'parameters':
        where = f"{where}: '{name}'"
    for key in parameters:
        if key not in PARAMETER_UNITS:
            raise ValueError(UnknownParameterMessage(where, key))
    for key, others in PARAMETERS.Conflicts(parameters):
        group = (key,) + others
        last, earlier = group[-1], ' and '.join(repr(k) for k in group[:-1])
        forms = PARAMETERS.FormsText(key)
        if forms:       # the gear geometry: groups of keys
            raise ValueError(f"{where}: {' and '.join(repr(k) for k in group)} are given together, which belong to "
                             f"different forms of the {PARAMETERS.Quantity(key)}; give one form: {forms} (to change "
                             f"the form of a set, use ApplyOverrides, which drops the keys of the other forms)")
        raise ValueError(f"{where}: {' and '.join(repr(k) for k in group)} are given together, which describe the "
                         f"same quantity ({PARAMETERS.Quantity(key)}); give only one of them (to replace one form by another, "
                         f"use ApplyOverrides(parameters, {{{last!r}: {parameters[last]!r}}}), which sets {last!r} "
                         f"and drops {earlier})")


def ApplyOverrides(parameters: Mapping[str, float], overrides: Mapping[str, float]) -> Dict[str, float]:
    """Return ``parameters`` updated by ``overrides``; an override removes its alternative forms.

    Setting ``mu`` drops ``rho``, ``dT`` drops ``DT``/``DTV``, ``DV`` drops ``dV``, ...: this is how one form of
    a quantity replaces another (a set with two forms is refused by :func:`CheckParameterKeys`).

    Parameters
    ----------
    parameters : mapping
        Flat parameter dictionary (SI), e.g. a preset.
    overrides : mapping
        The new values, keyed by parameter keys, applied in order (of two forms of one quantity here, the later
        one is kept: ``{'mu': 0.13, 'rho': 0.14}`` sets rho).

    Returns
    -------
    dict
        A new dictionary; ``parameters`` is not changed.

    Raises
    ------
    TypeError, ValueError
        For an argument that is not a mapping, an unknown key (with a near-miss suggestion), or two forms of
        one quantity within ``parameters`` (:func:`CheckParameterKeys`).
    """
    w = 'ApplyOverrides'
    CheckParameterKeys(parameters, w)
    CheckMapping(w, 'overrides', overrides, "{'J1': 0.3}", preset=False)
    for key in overrides:        # applied in order: two forms here are fine, the later one replaces the earlier
        if key not in PARAMETER_UNITS:
            raise ValueError(UnknownParameterMessage(f"{w}: 'overrides'", key))
    return _WithOverrides(parameters, overrides)


def _WithOverrides(parameters: Mapping[str, float], overrides: Mapping[str, float]) -> Dict[str, float]:
    """``parameters`` with ``overrides`` applied in order, each removing its alternative forms (keys checked by the
    caller: :func:`ApplyOverrides`, :meth:`~exudyn_worm.drive.wholedrive.Drive.Replace`); a value None removes the
    key itself."""
    out = dict(parameters)
    for key, value in overrides.items():
        if value is None:
            out.pop(key, None)
            continue
        for alt in PARAMETERS.Alternatives(key):
            out.pop(alt, None)
        out[key] = value
    return out


def _Require(parameters, keys, what):
    missing = [k for k in keys if k not in parameters]
    if missing:
        geometry = [k for k in missing if k in GEOMETRY_KEYS]
        form = GeometryForm(parameters)
        hint = (f" ({', '.join(geometry)} of the gear geometry in the {form} form, "
                f"{', '.join(GEOMETRY_FORMS[form])}; the forms are: {PARAMETERS.FormsText(geometry[0])})"
                if geometry else '')
        raise MissingParameterError(f"{what}: missing parameter(s) {', '.join(missing)}{hint}; give them with --set "
                                    f"KEY=VALUE or in the config file", missing)


def _FiniteDamping(value: float, name: str, formula: str, inputs: Mapping[str, float], where: str = 'parameter set'
                   ) -> float:
    """``value``, a damping derived from its measure, if finite; else a ValueError naming the largest input, its
    unit and range (``J1 = 1e308`` overflows ``dT``: the message blames J1, not the derived dT)."""
    if math.isfinite(value):
        return value
    key = max(inputs, key=lambda k: abs(inputs[k]))
    unit = PARAMETER_UNITS[key]
    others = ', '.join(f"{k} = {v:g}{' ' + PARAMETER_UNITS[k] if PARAMETER_UNITS[k] else ''}"
                       for k, v in inputs.items() if k != key)
    raise ParameterError(where, f"'{key}' = {inputs[key]:g} {unit} is out of range (it must be "
                         f"{PARAMETERS[key].rangeText} {unit} and of a size a drive can have): the {name} {formula} "
                         f"overflows with {others}; check the value and its unit", (key, *inputs))


def CheckParameters(parameters: Mapping[str, float], where: str = 'parameter set') -> None:
    """Check a flat parameter dictionary: its keys (:func:`CheckParameterKeys`: known keys, one form per
    quantity) and the range of every value, naming the key as the user wrote it.

    The range (``> 0``, ``>= 0``, an angle in (0, pi/2) rad, ...) and kind (number, choice, table) of every key
    are declared once in the registry :data:`~exudyn_worm.params.parameters.PARAMETERS` and listed in
    docs/parameters.md; drive files, :func:`DriveSideChain` and the model builders all check with it. The
    plausibility of values against each other (backlash against the worm radius, overflow of the model's coefficients)
    is checked by :class:`~exudyn_worm.model.gear.WormGear` and :func:`DriveFromParameters`.

    Parameters
    ----------
    parameters : mapping
        Flat parameter dictionary (SI).
    where : str
        Prefix of the error messages.

    Raises
    ------
    ValueError, TypeError
        E.g. ``parameter set: 'kT' must be > 0 N*m/rad, got -5 N*m/rad``; for the keys see
        :func:`CheckParameterKeys`.
    """
    CheckParameterKeys(parameters, where)
    for key, value in parameters.items():
        PARAMETERS.Check(key, value, where)


#: largest rate ``|b_i|^(1/i)`` of eq. (16), 1/s, that a parameter set may reach: no mechanical drive comes near it,
#: so a drive above it has a value or unit off by orders of magnitude (and kT = 1e300 would overflow the analysis)
MAX_RATE = 1e12
#: smallest b4^(1/4) / b2^(1/2) of eq. (16) accepted (natural frequencies at most 1e12 apart)
MIN_RATE_SPREAD = 1e-6


def _CheckScale(drive: ElasticDrive, where: str) -> None:
    """The rates of the characteristic polynomial (eq. (16)) must be finite and below :data:`MAX_RATE`."""
    with np.errstate(over='ignore', invalid='ignore'):
        rates = [abs(b) ** (1. / (i + 1)) for S in (1, -1)
                 for i, b in enumerate(CharacteristicCoefficients(drive, S))]
    rate = max(rates)
    # b4^(1/4) / b2^(1/2) is about the square root of the ratio of the two natural frequencies (0.5-0.8 for the
    # paper's drives); far below, the slow mode is lost in round-off and the verdicts contradict each other
    spread = min(rates[3] / rates[1], rates[7] / rates[5]) if all(r > 0 for r in rates[1::2]) else 0.
    if math.isfinite(rate) and rate <= MAX_RATE and spread >= MIN_RATE_SPREAD:
        return
    g = drive.gear
    values = ', '.join(f"{k} = {v:g} {PARAMETER_UNITS[k]}" for k, v in
                       (('J1', drive.J1), ('J2', drive.J2), ('kT', drive.kT), ('dT', drive.dT), ('kV', g.kV),
                        ('dV', g.dV), ('r1', g.r1), ('r2', g.r2)))
    what = (f"the drive's rates |b_i|^(1/i) of eq. (16) reach {rate:.3g} 1/s (a mechanical drive stays far below "
            f"{MAX_RATE:g} 1/s)" if not (math.isfinite(rate) and rate <= MAX_RATE) else
            f"its two natural frequencies lie more than 1e12 apart (b4^(1/4) / b2^(1/2) of eq. (16) = {spread:.3g}, "
            f"below {MIN_RATE_SPREAD:g})")
    raise ParameterError(where, f"out of range: {what} with {values}; check these values and their units", ())


def GearFromParameters(parameters: Mapping[str, float], meshDamping: bool = True,
                       where: str = 'GearFromParameters') -> WormGear:
    """Build the :class:`WormGear` of a flat parameter dictionary (no J1, kT or shaft damping needed).

    Parameters
    ----------
    parameters : mapping
        Flat parameter dictionary (SI) with ``alphaN``, the geometry as ``r1 r2 gamma`` or ``a u gamma`` or
        ``mx z1 z2 q`` (:mod:`exudyn_worm.model.geometry`), ``kV``, ``mu`` or ``rho`` and, if ``meshDamping``,
        ``dV`` or ``DV`` (with ``J2``); optionally the friction law ``frictionLaw`` (``muStatic``,
        ``stribeckVelocity``, ``frictionTable``; see :func:`FrictionLawFromParameters`), which the gear carries
        (:attr:`~exudyn_worm.model.gear.WormGear.friction`) into the connector and the analysis.
    meshDamping : bool, optional
        If False, the mesh damping is not required and the gear gets dV = 0 (for the stability charts,
        which set dV from the swept D_V).
    where : str, optional
        Function name used in error messages.

    Returns
    -------
    WormGear

    Raises
    ------
    ValueError, TypeError
        For a missing, unknown or invalid parameter or two forms of one quantity (:func:`CheckParameters`).
    """
    CheckParameterKeys(parameters, where)            # names the function: unknown keys, two forms of a quantity
    p = dict(parameters)
    CheckParameters(p)
    _Require(p, ('alphaN',) + MissingGeometryKeys(p) + ('kV',), where)
    r1, r2, gamma = GeometryFromParameters(p, where)     # r1 r2 gamma, or a u gamma, or mx z1 z2 q
    if 'mu' not in p and 'rho' not in p:
        raise MissingParameterError(f"{where}: missing the flank friction: give 'mu' ([gear] frictionCoefficient) or "
                                    f"the friction angle 'rho' ([gear] frictionAngle)", ('mu',))
    if not meshDamping:
        dV = 0.
    elif 'dV' in p:
        dV = p['dV']
    elif 'DV' in p:
        _Require(p, ('J2',), where)
        dV = _FiniteDamping(MeshDampingFromMeasure(p['DV'], p['kV'], r2, p['J2']), 'mesh damping',
                            'dV = 2 DV sqrt(kV r2^2 J2) / r2^2 of eq. (23)', {k: p[k] for k in ('J2', 'kV', 'DV')})
    else:
        raise MissingParameterError(f"{where}: missing the mesh damping: give 'dV' in N*s/m ([gear] meshDamping) or "
                                    f"the measure 'DV' ([gear] meshDampingMeasure)", ('DV',))
    gear = WormGear(alphaN=p['alphaN'], gamma=gamma, r1=r1, r2=r2, kV=p['kV'], dV=dV,
                    backlash=p.get('backlash', 0.), mu=p.get('mu'), rho=p.get('rho'))
    law = FrictionLawFromParameters(p, gear.mu, where)
    return gear if law is None else gear.Replace(friction=law)


#: the keys of the friction laws besides 'mu' (or 'rho'), and the laws that use each
_LAW_KEYS = {'muStatic': ('stribeck',), 'stribeckVelocity': ('stribeck',), 'frictionTable': ('table',)}


def FrictionLawFromParameters(parameters: Mapping[str, object], mu: float, where: str = 'FrictionLawFromParameters'
                              ) -> Optional[object]:
    """The friction law of a flat parameter set (keys ``frictionLaw muStatic stribeckVelocity frictionTable``).

    Parameters
    ----------
    parameters : mapping
        Flat parameter dictionary; ``frictionLaw`` absent or ``'constant'``: the constant ``mu`` (None is returned,
        the gear keeps the paper's model); ``'stribeck'`` needs ``muStatic`` (>= ``mu``) and ``stribeckVelocity``
        (m/s, > 0); ``'agma'`` needs nothing more; ``'table'`` needs ``frictionTable`` (a file path, read with
        :func:`~exudyn_worm.model.friction.ReadFrictionTable`, or rows of (sliding speed in m/s, mu)).
    mu : float
        The gear's friction coefficient (from ``mu`` or ``rho``): the constant, or the kinetic value of Stribeck.
    where : str, optional
        Prefix of error messages.

    Returns
    -------
    StribeckFriction, AgmaFriction, TableFriction or None
        None for the constant law.

    Raises
    ------
    ValueError
        For a key that the chosen law does not use, a missing key, ``muStatic < mu``, or a table that cannot be
        read or is not a valid table (fewer than 2 points, speeds not increasing).
    """
    kind = parameters.get('frictionLaw', 'constant')
    PARAMETERS.Check('frictionLaw', kind, where)
    for key, laws in _LAW_KEYS.items():
        if key in parameters and kind not in laws:
            raise ParameterError(where, f"'{key}' is used only with frictionLaw = {' or '.join(laws)}, got frictionLaw "
                                 f"= {kind!r}{'' if 'frictionLaw' in parameters else ' (the default)'}; set "
                                 f"frictionLaw={laws[0]} or remove '{key}' (on the command line --set {key}=)", (key,))
    missing = [k for k, laws in _LAW_KEYS.items() if kind in laws and k not in parameters]
    if missing:
        raise MissingParameterError(f"{where}: frictionLaw = {kind!r} needs {', '.join(repr(k) for k in missing)}; "
                                    f"give {'them' if len(missing) > 1 else 'it'} with --set KEY=VALUE or in the "
                                    f"[gear] table of the drive file", missing)
    if kind == 'constant':
        return None
    if kind == 'stribeck':
        muStatic = parameters['muStatic']
        if muStatic < mu:
            raise ParameterError(where, f"'muStatic' (friction at rest, frictionLaw = stribeck) must be >= the "
                                 f"kinetic 'mu' = {mu:g}, got {muStatic:g}", ('muStatic', 'mu'))
        return FrictionLaw('stribeck', mu=mu, muStatic=muStatic, stribeckVelocity=parameters['stribeckVelocity'])
    if kind == 'agma':
        return FrictionLaw('agma')
    return FrictionLaw('table', table=_FrictionTable(parameters['frictionTable'], where).points)


_TABLES: Dict[Tuple[str, int, int], object] = {}


def _FrictionTable(value, where: str):
    """The :class:`~exudyn_worm.model.friction.TableFriction` of a ``frictionTable`` value (a path: read once per
    version of the file; design scans build a drive hundreds of times)."""
    try:
        if isinstance(value, (str, os.PathLike)):
            try:
                stat = os.stat(value)
            except OSError:
                return ReadFrictionTable(value)                 # raises, naming the file
            key = (os.path.abspath(value), stat.st_mtime_ns, stat.st_size)
            if key not in _TABLES:
                _TABLES[key] = ReadFrictionTable(value)
            return _TABLES[key]
        return ReadFrictionTable(tuple(tuple(row) for row in value))
    except (ValueError, TypeError) as err:
        raise ParameterError(where, f"'frictionTable': {err}", ('frictionTable',)) from None


def DriveFromParameters(parameters: Mapping[str, float]) -> ElasticDrive:
    """The :class:`ElasticDrive` of a flat parameter set of the two-mass drive of Figure 2.

    A set with parts beyond it (a drive-side or load-side chain, the worm's axial bearing, a motor on its
    characteristic) is refused, because the two-mass drive would leave them out without a word: resolve such a
    drive with :func:`~exudyn_worm.drive.wholedrive.ResolveDrive` and analyse it with
    :func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive`, or take its two-mass core on purpose with
    :func:`ElasticDriveFromParameters`.

    Parameters
    ----------
    parameters : mapping
        Flat parameter dictionary with the keys of :data:`PARAMETER_UNITS` (SI).

    Returns
    -------
    ElasticDrive

    Raises
    ------
    ValueError
        For a set with components beyond the two-mass drive, and as :func:`ElasticDriveFromParameters`.
    TypeError
        If ``parameters`` is not a mapping.
    """
    CheckParameterKeys(parameters, 'DriveFromParameters')
    extra = ExtraComponents(parameters)
    if extra:
        raise ValueError(f"DriveFromParameters: the parameter set has {' and '.join(extra)}, which the two-mass "
                         f"ElasticDrive of Figure 2 leaves out; use exudyn_worm.ResolveDrive(parameters=...) with "
                         f"AnalyzeDrive for the whole drive, or ElasticDriveFromParameters for its two-mass core")
    return ElasticDriveFromParameters(parameters, 'DriveFromParameters')


def ElasticDriveFromParameters(parameters: Mapping[str, float], where: str = 'ElasticDriveFromParameters'
                               ) -> ElasticDrive:
    """Build the two-mass core (:class:`ElasticDrive`, Figure 2) of a flat parameter dictionary; the keys of
    parts beyond it (chains, axial bearing, motor) are not part of it and are left to the caller.

    Damping: ``dT``, ``DT`` or ``DTV * DV`` (eq. (24)); ``dV`` or ``DV``. Friction: ``mu`` or ``rho`` (eq. (13)),
    and optionally a speed-dependent law (``frictionLaw`` ..., :func:`FrictionLawFromParameters`) that the gear
    (``.gear``) carries into :func:`~exudyn_worm.items.connector.CreateWormGear`.
    Each quantity in one form only: a set with two forms (``dV`` and ``DV``) is refused; to change the form,
    use :func:`ApplyOverrides`, which drops the other one.

    Parameters
    ----------
    parameters : mapping
        Flat parameter dictionary with the keys of :data:`PARAMETER_UNITS` (SI).
    where : str, optional
        Prefix of error messages.

    Returns
    -------
    ElasticDrive

    Raises
    ------
    ValueError
        For a missing, unknown or invalid parameter, two forms of one quantity (see :func:`CheckParameters`)
        or parameters whose model coefficients overflow.
    TypeError
        If ``parameters`` is not a mapping.
    """
    CheckParameterKeys(parameters, where)
    p = dict(parameters)
    _CheckCore(p, where)
    return ElasticDriveWithGear(GearFromParameters(p, where=where), p, where)


def _CheckCore(p: Mapping[str, Any], where: str) -> None:
    """The checks of the two-mass core's values before its gear is built (keys checked already): every value in
    range, then the core's keys present."""
    CheckParameters(p)                   # a value out of range (z1 = 1.5) is named before the keys it leaves missing
    _Require(p, ('alphaN',) + MissingGeometryKeys(p) + ('kV', 'J1', 'J2', 'kT'), where)


#: the keys of the two-mass core that never change its gear: a drive changed only in these keeps its gear
#: (:meth:`~exudyn_worm.drive.wholedrive.Drive.Replace`); J2 only while the mesh damping is given as dV (with DV,
#: dV = 2 DV sqrt(kV r2^2 J2) / r2^2 of eq. (23) depends on it)
_GEAR_FREE_KEYS = ('J1', 'kT', 'dT', 'DT', 'DTV')


def _GearFreeKeys(parameters: Mapping[str, float]) -> Tuple[str, ...]:
    """The keys of ``parameters`` whose change leaves the gear as it is (``_GEAR_FREE_KEYS``, and J2 unless the
    mesh damping is the measure DV).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set (SI).

    Returns
    -------
    tuple of str
    """
    return _GEAR_FREE_KEYS + (() if 'DV' in parameters else ('J2',))


def ElasticDriveWithGear(gear: WormGear, parameters: Mapping[str, float], where: str = 'ElasticDriveWithGear'
                         ) -> ElasticDrive:
    """The two-mass core of a parameter set whose gear is built already: J1, J2, kT and the shaft damping in its
    form (``dT``, ``DT`` or ``DTV`` with eqs. (22)-(24)), checked for scale.

    Parameters
    ----------
    gear : WormGear
        The drive's gear (:func:`GearFromParameters`).
    parameters : mapping
        Flat parameter set (SI) with J1, J2, kT and one form of the shaft damping.
    where : str, optional
        Prefix of error messages.

    Returns
    -------
    ElasticDrive
    """
    p = parameters
    if 'dT' in p:
        dT = p['dT']
    else:
        if 'DT' in p:
            DT = p['DT']
        elif 'DTV' in p:
            DV = p['DV'] if 'DV' in p else gear.dV * gear.r2 / (2 * math.sqrt(gear.kV * p['J2']))
            DT = p['DTV'] * DV
        else:
            raise MissingParameterError(f"{where}: missing the drive shaft's damping: give 'dT' in N*m*s/rad "
                                        f"([driveShaft] damping), the measure 'DT' ([driveShaft] dampingMeasure) or the "
                                        f"ratio 'DTV' ([driveShaft] dampingMeasureRatio)", ('DT',))
        dT = _FiniteDamping(TorsionalDampingFromMeasure(DT, p['kT'], p['J1']), 'shaft damping',
                            'dT = 2 DT sqrt(kT J1) of eq. (22)', {'J1': p['J1'], 'kT': p['kT'], 'DT': DT})
    drive = ElasticDrive(gear=gear, J1=p['J1'], J2=p['J2'], kT=p['kT'], dT=dT)
    _CheckScale(drive, 'parameter set')
    return drive


def ExtraComponents(parameters: Mapping[str, float]) -> List[str]:
    """Components of a parameter set beyond the two-mass drive of Figure 2 (which eqs. (15)-(21) describe).

    Parameters
    ----------
    parameters : mapping
        Flat parameter dictionary (SI).

    Returns
    -------
    list of str
        ``'a drive-side chain (J4, ...)'``, ``'a load-side chain (JL1, ...)'`` and/or
        ``'a worm axial bearing (kA > 0)'``; empty for the two-mass
        drive. The analytical model and the design check do not include these; the linearized Exudyn model
        (:func:`exudyn_worm.analysis.stability.linearization.LinearStabilityFromParameters`) and the simulation do.

    Examples
    --------
    >>> ExtraComponents(GetPreset('reel-P1'))
    []
    >>> ExtraComponents({**GetPreset('reel-P1'), 'J4': 0.05, 'k4': 2e4})
    ['a drive-side chain (J4, ...)']
    """
    return ((['a drive-side chain (J4, ...)'] if DriveSideChain(parameters) else []) +
            (['a load-side chain (JL1, ...)'] if LoadSideChain(parameters) else []) +
            (['a motor on its characteristic (motorType characteristic)']
             if parameters.get('motorType') == 'characteristic' else []) +
            (['a worm axial bearing (kA > 0)'] if parameters.get('kA', 0.) > 0 else []))


def _SeriesChain(parameters: Mapping[str, float], table: str, where: str) -> List[Tuple[float, float, float]]:
    """The stages ``(J, k, d)`` of the chain of the array of tables ``table`` (``'driveSide'``, ``'loadSide'``),
    in order of their numbers; see :func:`DriveSideChain` and :func:`LoadSideChain`."""
    J, k, d = (PARAMETERS.arrayTables[table][f] for f in ('inertia', 'stiffness', 'damping'))
    first = PARAMETERS.Series(J).series
    text = PARAMETERS.SeriesText(table)
    prefixes = (J, k, d)
    mine = [key for key in parameters if (PARAMETERS.SeriesIndex(key) or ('',))[0] in prefixes]
    indices = sorted({PARAMETERS.SeriesIndex(key)[1] for key in mine})
    side = 'motor' if table == 'driveSide' else 'wheel'
    chain = []
    for expected, i in enumerate(indices, start=first):
        if i != expected or f'{J}{i}' not in parameters:
            missing = f'{J}{expected}' if i != expected else f'{J}{i}'
            raise ValueError(f"{where}: the {text} must be {J}{first}, {J}{first + 1}, ... without gaps, each with "
                             f"its spring {k}<i>; got keys {', '.join(mine)} (missing '{missing}')")
        if f'{k}{i}' not in parameters:
            raise ValueError(f"{where}: '{J}{i}' needs the stiffness '{k}{i}' (N*m/rad) of the spring-damper on its "
                             f"{side} side")
        stage = {f'{J}{i}': parameters[f'{J}{i}'], f'{k}{i}': parameters[f'{k}{i}'],
                 f'{d}{i}': parameters.get(f'{d}{i}', 0.)}
        CheckParameters(stage, where)
        chain.append(tuple(float(v) for v in stage.values()))
    return chain


def DriveSideChain(parameters: Mapping[str, float]) -> List[Tuple[float, float, float]]:
    """The drive-side chain of Figure 19 as ``[(J4, k4, d4), (J5, k5, d5), ...]``, worm side first.

    ``(Ji, ki, di)`` is inertia *i* in kg*m^2 and the spring-damper on its motor side in N*m/rad and
    N*m*s/rad (topology in the module docstring); the last spring-damper ends at the motor. Empty if
    no ``J4`` is given (the two-mass drive).

    Parameters
    ----------
    parameters : mapping
        Flat parameter dictionary (SI) with the chain keys ``J4, k4, d4, J5, ...`` (others are ignored).

    Returns
    -------
    list of (float, float, float)

    Raises
    ------
    ValueError
        For a gap in the chain, a spring-damper without its inertia, or a value out of range.
    """
    return _SeriesChain(parameters, 'driveSide', 'DriveSideChain')


def LoadSideChain(parameters: Mapping[str, float]) -> List[Tuple[float, float, float]]:
    """The load-side chain as ``[(JL1, kL1, dL1), (JL2, kL2, dL2), ...]``, wheel side first.

    ``(JLi, kLi, dLi)`` is inertia *i* of the driven machine in kg*m^2 and the load shaft on its wheel side in
    N*m/rad and N*m*s/rad (topology in the module docstring: ``wheel J2 --(kL1, dL1)-- JL1 --(kL2, dL2)-- JL2``);
    the load torque acts on the last inertia. Empty if no ``JL1`` is given (the load acts on the wheel).

    Parameters
    ----------
    parameters : mapping
        Flat parameter dictionary (SI) with the chain keys ``JL1, kL1, dL1, JL2, ...`` (others are ignored).

    Returns
    -------
    list of (float, float, float)

    Raises
    ------
    ValueError
        For a gap in the chain, a spring-damper without its inertia, or a value out of range.

    Examples
    --------
    >>> LoadSideChain({'JL1': 0.5, 'kL1': 2e4})
    [(0.5, 20000.0, 0.0)]
    """
    return _SeriesChain(parameters, 'loadSide', 'LoadSideChain')


def AxialBearingFromParameters(parameters: Mapping[str, float], where: str = 'AxialBearingFromParameters'
                               ) -> Optional['AxialBearing']:
    """The worm's :class:`~exudyn_worm.model.drive.AxialBearing` from ``kA, dA, mA``, or None (absent or kA = 0).

    Parameters
    ----------
    parameters : mapping
        Flat parameter dictionary (SI); reads ``kA`` (N/m), ``dA`` (N*s/m, default 0) and ``mA`` (kg).
    where : str, optional
        Prefix of error messages.

    Returns
    -------
    AxialBearing or None

    Raises
    ------
    ValueError
        If ``kA`` > 0 without ``mA`` or a value is out of range.
    """
    w = where
    kA = CheckNonNegative(w, 'kA', parameters.get('kA', 0.), 'N/m')
    if kA == 0.:
        return None
    if 'mA' not in parameters:
        raise MissingParameterError(f"{w}: 'kA' = {kA:g} N/m > 0 needs the worm's axially moving mass 'mA' (kg), "
                                    f"[axialBearing] mass in a drive file; missing mA", ('mA',))
    return AxialBearing(stiffness=kA, damping=parameters.get('dA', 0.), mass=parameters['mA'])


def ShaftSupportsFromParameters(parameters: Mapping[str, float], where: str = 'ShaftSupportsFromParameters'
                                ) -> Optional[ShaftSupports]:
    """The 3D model's :class:`~exudyn_worm.items.bearings.ShaftSupports` from the bearing keys, or None without them.

    A drive is simulated and analysed as the 3D model (worm and wheel as rigid bodies, docs/mesh-3d.md) when it
    gives a shaft's bearings (drive file ``[wormBearing]``, ``[wheelBearing]``; keys ``wormRadialStiffness``,
    ``wormAxialStiffness``, ``wormRadialDamping``, ``wormAxialDamping``, ``wormBearingSpan`` and the same for the
    wheel). A shaft with bearings needs both stiffnesses and its body's mass (``wormMass``, ``wheelMass``); a shaft
    without turns on an ideal revolute joint (its mass defaults to 5 kg for the worm, 30 kg for the wheel: only the
    joint feels it). With the worm's axial bearing ``kA, dA, mA`` the worm slides on its joint, its mass is ``mA``.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set (SI).
    where : str, optional
        Caller named in messages.

    Returns
    -------
    ShaftSupports or None
        None if no shaft has bearings (the one-angle model).

    Raises
    ------
    MissingParameterError
        For a shaft's bearings without a stiffness or without the body's mass.
    ValueError
        For a mass without any bearings (the one-angle model does not use it), the worm's axial bearing given twice
        (``[axialBearing]`` and ``[wormBearing]``) or its mass given twice (``mA`` and ``wormMass``).
    """
    bearings = {}
    for body in ('worm', 'wheel'):
        keys = PARAMETERS.KeysOf(f'{body}Bearing')
        given = [k for k in keys if k in parameters]
        if not given:
            bearings[body] = None
            continue
        needed = [f'{body}RadialStiffness', f'{body}AxialStiffness'] + ([] if f'{body}Mass' in parameters
                                                                         else [f'{body}Mass'])
        missing = [k for k in needed if k not in parameters]
        if missing:
            raise MissingParameterError(
                f"{where}: the {body}'s bearings ([{body}Bearing]) need its radialStiffness, axialStiffness (N/m) "
                f"and the {body}'s mass ([{body}] mass, kg); missing {', '.join(missing)} (give them in the drive "
                f"file or with --set KEY=VALUE)", missing)
        bearings[body] = ShaftBearings(
            radialStiffness=parameters[f'{body}RadialStiffness'], axialStiffness=parameters[f'{body}AxialStiffness'],
            radialDamping=parameters.get(f'{body}RadialDamping', 0.), axialDamping=parameters.get(f'{body}AxialDamping', 0.),
            span=parameters.get(f'{body}BearingSpan', 0.1))
    bodyKeys = [k for k in BODY_KEYS if k in parameters]
    if bearings['worm'] is None and bearings['wheel'] is None:
        if bodyKeys:
            k = bodyKeys[0]
            body = 'worm' if k.startswith('worm') else 'wheel'
            what = {'Mass': 'mass', 'TiltInertia': 'tilt inertia', 'PolarInertia': 'polar inertia', 'Radius': 'radius',
                    'InnerRadius': 'inner radius', 'Length': 'length'}[k[len(body):]]
            raise ParameterError(where, f"'{k}' (the {body}'s {what}, {PARAMETERS.units[k]}) is used only by the 3D "
                                 f"model, which the shafts' bearings select ([wormBearing], [wheelBearing]), got {parameters[k]:g} "
                                 f"{PARAMETERS.units[k]} without them; add them or remove '{k}'", (k,))
        return None
    axial = AxialBearingFromParameters(parameters, where)
    if axial is not None and bearings['worm'] is not None:
        raise ParameterError(where, f"the worm's axial bearing is given twice, as kA = {parameters['kA']:g} N/m "
                             f"([axialBearing] stiffness) and as wormAxialStiffness = "
                             f"{parameters['wormAxialStiffness']:g} N/m ([wormBearing]); give it once",
                             ('wormAxialStiffness', 'kA'))
    if axial is not None and 'wormMass' in parameters:
        raise ParameterError(where, f"the worm's mass is given twice, as mA = {parameters['mA']:g} kg ([axialBearing] "
                             f"mass) and as wormMass = {parameters['wormMass']:g} kg ([worm] mass); give it once",
                             ('wormMass', 'mA'))
    masses = {'worm': axial.mass if axial is not None else parameters.get('wormMass', WORM_MASS),
              'wheel': parameters.get('wheelMass', WHEEL_MASS)}
    inertias = {body: _BodyInertiaFromParameters(parameters, body, masses[body], bearings[body] is not None, where)
                for body in ('worm', 'wheel')}
    return ShaftSupports(wormBearings=bearings['worm'], wheelBearings=bearings['wheel'],
                         wormMass=masses['worm'], wheelMass=masses['wheel'],
                         wormInertia=inertias['worm'], wheelInertia=inertias['wheel'])


def _BodyInertiaFromParameters(p: Mapping[str, float], body: str, mass: float, onBearings: bool,
                               where: str) -> Optional[BodyInertia]:
    """The 3D model's body ``body`` ('worm' or 'wheel'): its own mass, polar and tilt inertia from
    ``{body}TiltInertia`` (with ``{body}PolarInertia``, default the shaft's J1 or J2) or from its shape
    (``{body}Radius``, ``{body}Length``, ``{body}InnerRadius``), checked against the shaft's inertia and the
    perpendicular-axis bound; None for a body on an ideal joint without them. A body on elastic bearings without them
    is refused: its tilt inertia is never taken from the polar one."""
    J = 'J1' if body == 'worm' else 'J2'
    shape = [k for k in (f'{body}Radius', f'{body}Length', f'{body}InnerRadius') if k in p]
    direct = [k for k in (f'{body}TiltInertia', f'{body}PolarInertia') if k in p]
    if shape and direct:
        raise ParameterError(where, f"the {body}'s inertia is given twice, as its shape ({', '.join(shape)}) and "
                             f"as {', '.join(direct)}; give one of them", (direct[0], shape[0]))
    if shape:
        missing = [k for k in (f'{body}Radius', f'{body}Length') if k not in p]
        if missing:
            raise MissingParameterError(f"{where}: the {body}'s shape (a cylinder) needs its radius and length "
                                        f"([{body}] radius, length in m); missing {', '.join(missing)}", missing)
        try:
            own = CylinderInertia(mass, p[f'{body}Radius'], p[f'{body}Length'], p.get(f'{body}InnerRadius', 0.),
                                  where=where, body=body)
        except ValueError as error:
            raise ParameterError(where, str(error).split(': ', 1)[1], (f'{body}InnerRadius',)) from None
        polarText = f"the {body}'s polar inertia from its shape"
    elif f'{body}TiltInertia' in p:
        polar = p.get(f'{body}PolarInertia', p[J])
        polarText = (f'{body}PolarInertia' if f'{body}PolarInertia' in p else
                     f"{J}, all of the shaft's inertia in the {body} body without {body}PolarInertia")
        try:
            CheckBodyInertia(where, body, mass, polar, p[f'{body}TiltInertia'], what=polarText)
        except ValueError as error:
            raise ParameterError(where, str(error).split(': ', 1)[1], (f'{body}TiltInertia',)) from None
        own = BodyInertia(mass=mass, polar=polar, tilt=p[f'{body}TiltInertia'])
    elif direct:
        raise MissingParameterError(f"{where}: '{body}PolarInertia' needs the {body}'s tilt inertia: missing "
                                    f"{body}TiltInertia ([{body}] tiltInertia, kg*m^2)", (f'{body}TiltInertia',))
    elif onBearings:
        raise MissingParameterError(
            f"{where}: the {body} on elastic bearings ([{body}Bearing]) needs its tilt inertia: missing "
            f"{body}TiltInertia ([{body}] tiltInertia, kg*m^2, about a line across the axis through its centre; or "
            f"its shape: [{body}] radius, length)", (f'{body}TiltInertia',))
    else:
        return None
    if own.polar > p[J] * (1. + 1e-12):
        raise ParameterError(where, f"the {body}'s own polar inertia ({polarText}, {own.polar:g} kg*m^2) must be "
                             f"<= {J} = {p[J]:g} kg*m^2, the inertia of everything on the {body} shaft",
                             ((shape or direct)[0], J))
    return own
