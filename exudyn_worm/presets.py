"""Parameter sets of the paper and the resolution of a flat parameter dictionary into an ElasticDrive.

A parameter set is a flat dictionary keyed by the names used everywhere (Python API, ``--set``,
TOML config): ``alphaN gamma mu rho r1 r2 kV dV DV backlash J1 J2 kT dT DT DTV`` and, for the
reel changer, ``loadMass leverArm motorSpeed``. All values are SI, angles in rad, speeds in rad/s.

Damping is held as the measures D_T, D_V of eqs. (22)-(23) (or D_TV = D_T/D_V), so a changed J1 or
kT keeps the measure, as the paper's chart points assume; an explicit ``dT`` or ``dV`` overrides.
"""
from __future__ import annotations

import math
from typing import Dict, Mapping

from .drive import ElasticDrive, MeshDampingFromMeasure, TorsionalDampingFromMeasure
from .gear import WormGear

__all__ = ['DRIVE_KEYS', 'REEL_KEYS', 'PARAMETER_UNITS', 'PRESETS', 'GetPreset', 'ApplyOverrides',
           'GearFromParameters', 'DriveFromParameters']

#: keys of the elastic drive (Figure 2)
DRIVE_KEYS = ('alphaN', 'gamma', 'mu', 'rho', 'r1', 'r2', 'kV', 'dV', 'DV', 'backlash',
              'J1', 'J2', 'kT', 'dT', 'DT', 'DTV')
#: keys of the paper-reel-changer load case (section 3.2)
REEL_KEYS = ('loadMass', 'leverArm', 'motorSpeed')

#: SI unit of every key (pint syntax), used to parse quantities such as ``8 deg`` or ``0.5 mm``
PARAMETER_UNITS = {'alphaN': 'rad', 'gamma': 'rad', 'mu': '', 'rho': 'rad', 'r1': 'm', 'r2': 'm',
                   'kV': 'N/m', 'dV': 'N*s/m', 'DV': '', 'backlash': 'm', 'J1': 'kg*m^2', 'J2': 'kg*m^2',
                   'kT': 'N*m/rad', 'dT': 'N*m*s/rad', 'DT': '', 'DTV': '',
                   'loadMass': 'kg', 'leverArm': 'm', 'motorSpeed': 'rad/s'}

# keys that describe the same physical quantity: setting one removes the others
_ALTERNATIVES = {'mu': ('rho',), 'rho': ('mu',), 'dT': ('DT', 'DTV'), 'DT': ('dT', 'DTV'), 'DTV': ('dT', 'DT'),
                 'dV': ('DV',), 'DV': ('dV',)}

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
    """Return a copy of preset ``name`` (one of :data:`PRESETS`)."""
    if name not in PRESETS:
        raise ValueError(f"unknown preset '{name}'; expected one of: {', '.join(PRESETS)}")
    return dict(PRESETS[name])


def ApplyOverrides(parameters: Mapping[str, float], overrides: Mapping[str, float]) -> Dict[str, float]:
    """Return ``parameters`` updated by ``overrides``; an override removes its alternative forms
    (setting ``mu`` drops ``rho``, ``dT`` drops ``DT``/``DTV``, ``DV`` drops ``dV``, ...)."""
    known = set(PARAMETER_UNITS)
    out = dict(parameters)
    for key, value in overrides.items():
        if key not in known:
            raise ValueError(f"unknown parameter '{key}'; expected one of: {' '.join(PARAMETER_UNITS)}")
        for alt in _ALTERNATIVES.get(key, ()):
            out.pop(alt, None)
        out[key] = value
    return out


def _Require(parameters, keys, what):
    missing = [k for k in keys if k not in parameters]
    if missing:
        raise ValueError(f"{what}: missing parameter(s) {', '.join(missing)}; give them with --set KEY=VALUE "
                         f"or in the config file")


def GearFromParameters(parameters: Mapping[str, float], meshDamping: bool = True,
                       where: str = 'GearFromParameters') -> WormGear:
    """Build the :class:`WormGear` of a flat parameter dictionary (no J1, kT or shaft damping needed).

    Parameters
    ----------
    parameters : mapping
        Flat parameter dictionary (SI) with ``alphaN gamma r1 r2 kV``, ``mu`` or ``rho`` and, if
        ``meshDamping``, ``dV`` or ``DV`` (with ``J2``).
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
    ValueError
        For a missing or invalid parameter.
    """
    p = dict(parameters)
    _Require(p, ('alphaN', 'gamma', 'r1', 'r2', 'kV'), where)
    if 'mu' not in p and 'rho' not in p:
        raise ValueError(f"{where}: give the friction as 'mu' or as the friction angle 'rho'")
    if not meshDamping:
        dV = 0.
    elif 'dV' in p:
        dV = p['dV']
    elif 'DV' in p:
        _Require(p, ('J2',), where)
        dV = MeshDampingFromMeasure(p['DV'], p['kV'], p['r2'], p['J2'])
    else:
        raise ValueError(f"{where}: give the mesh damping as 'dV' (N*s/m) or as the measure 'DV'")
    return WormGear(alphaN=p['alphaN'], gamma=p['gamma'], r1=p['r1'], r2=p['r2'], kV=p['kV'], dV=dV,
                    backlash=p.get('backlash', 0.), mu=p.get('mu'), rho=p.get('rho'))


def DriveFromParameters(parameters: Mapping[str, float]) -> ElasticDrive:
    """Build the :class:`ElasticDrive` described by a flat parameter dictionary.

    Damping: ``dT`` if given, else ``DT``, else ``DTV * DV`` (eq. (24)); ``dV`` if given, else ``DV``.
    Friction: ``mu`` or ``rho`` (eq. (13)).

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
        For a missing or invalid parameter.
    """
    p = dict(parameters)
    where = 'DriveFromParameters'
    _Require(p, ('alphaN', 'gamma', 'r1', 'r2', 'kV', 'J1', 'J2', 'kT'), where)
    gear = GearFromParameters(p, where=where)
    if 'dT' in p:
        dT = p['dT']
    else:
        if 'DT' in p:
            DT = p['DT']
        elif 'DTV' in p:
            DV = p['DV'] if 'DV' in p else gear.dV * gear.r2 / (2 * math.sqrt(gear.kV * p['J2']))
            DT = p['DTV'] * DV
        else:
            raise ValueError(f"{where}: give the shaft damping as 'dT' (N*m*s/rad), the measure 'DT' "
                             f"or the ratio 'DTV'")
        dT = TorsionalDampingFromMeasure(DT, p['kT'], p['J1'])
    return ElasticDrive(gear=gear, J1=p['J1'], J2=p['J2'], kT=p['kT'], dT=dT)
