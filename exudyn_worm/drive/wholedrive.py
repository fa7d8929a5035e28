"""The user's whole drive as one immutable, self-checking object: :class:`Drive`.

A drive is resolved once, at the boundary (a preset, a drive file, ``--set`` options or a Python dictionary), into
a :class:`Drive`: the gear with its friction law and the two-mass core of Figure 2 (:class:`ElasticDrive`), the
drive-side chain of Figure 19, the load-side chain, the worm's axial bearing, the load and the motor (the duty),
and where each value came from. Every analysis and every command takes the drive; what it contains is a typed
property (:attr:`Drive.components`, :attr:`Drive.isTwoMass`, ...), so no code compares phrases to find out which
model fits it.

Checks made when the drive is built (so that no command meets them later):

- every key and value (the parameter registry), the two-mass core (:func:`~exudyn_worm.drive.presets.ElasticDriveFromParameters`),
  both chains complete, the axial bearing with its mass;
- the duty: a load or motor type that is named needs its keys (``motorType = characteristic`` without
  ``motorInertia`` is refused here, with the keys it needs); the reel changer's default lever and constant speed
  are optional (a drive without them has no duty: it is analysed at rest);
- a value the duty would ignore is refused when the user gave it with ``--set`` or in the drive file:
  ``motorSpeed`` for a speed-table motor or a motor on its characteristic (the ``motorSpeed`` of a preset or of a
  dictionary built on one is dropped when the motor type changes).
"""
from __future__ import annotations

import enum
import os
import types
from dataclasses import dataclass, field, replace
from typing import Any, Dict, Iterable, Mapping, Optional, Tuple, Union

from ..items.bearings import ShaftSupports
from ..model.drive import AxialBearing
from ..params.drives import ConfigPath
from ..model.drive import ElasticDrive
from ..model.gear import WormGear
from ..model.geometry import GeometryForm, GeometryFormKind
from .config import (DropReplacedChoiceKeys, ResolveParametersWithSources, SourceKind, ValueSource, _CheckChain,
                     _Overrides)
from .duty import LOAD_TYPES, MOTOR_TYPES, LoadType, MotorType, _LoadLaw, _MotorLaw
from .presets import (ApplyOverrides, AxialBearingFromParameters, CheckParameterKeys, DriveSideChain,
                      ElasticDriveWithGear, GearFromParameters, _CheckCore, _GearFreeKeys, _WithOverrides,
                      LoadSideChain, ShaftSupportsFromParameters)
from ..params.parameters import PARAMETERS, MissingParameterError, ParameterError

__all__ = ['Component', 'Drive', 'ResolveDrive', 'CheckDrive']


class Component(str, enum.Enum):
    """A part of a drive beyond the two-mass drive of Figure 2 (which eqs. (15)-(21) describe).

    Attributes
    ----------
    DRIVE_SIDE_CHAIN, LOAD_SIDE_CHAIN, AXIAL_BEARING, MOTOR_CHARACTERISTIC : Component
        The components; the value is the component's short name.
    """
    DRIVE_SIDE_CHAIN = 'drive-side chain'
    LOAD_SIDE_CHAIN = 'load-side chain'
    AXIAL_BEARING = 'worm axial bearing'
    MOTOR_CHARACTERISTIC = 'motor on its characteristic'
    SHAFT_BEARINGS = 'shaft bearings'

    @property
    def text(self) -> str:
        """How the component is named in messages, with the keys that give it."""
        return _COMPONENT_TEXT[self]


_COMPONENT_TEXT = {Component.DRIVE_SIDE_CHAIN: 'a drive-side chain (J4, ...)',
                   Component.LOAD_SIDE_CHAIN: 'a load-side chain (JL1, ...)',
                   Component.AXIAL_BEARING: 'a worm axial bearing (kA > 0)',
                   Component.MOTOR_CHARACTERISTIC: 'a motor on its characteristic (motorType characteristic)',
                   Component.SHAFT_BEARINGS: 'shaft bearings of worm and wheel as rigid bodies ([wormBearing], '
                                             '[wheelBearing])'}

@dataclass(frozen=True, eq=False)
class Drive:
    """One drive: its resolved parameters, its parts as typed objects, and where each value came from.

    Build it with :func:`ResolveDrive` (preset, drive file, ``--set``) or :meth:`FromParameters` (a flat
    dictionary); change it with :meth:`Replace`, which gives a new, checked drive. Analyses take it:
    :func:`~exudyn_worm.analysis.stability.drivestability.AnalyzeDrive` (the verdict at the duty's operating points).

    Attributes
    ----------
    parameters : mapping
        The flat parameter set (SI, read-only), as :mod:`exudyn_worm.drive.presets` describes it.
    sources : mapping
        Per key, where its value came from, a :class:`~exudyn_worm.drive.config.ValueSource`: its ``kind``
        (``SourceKind.SET``, ``FILE``, ``PRESET``, ``API``, ``CHANGED``) and its ``text`` for messages and JSON
        (``'--set'``, a drive file's location, ``'preset NAME'``, ``'API'``, ``'changed'``).
    elastic : ElasticDrive
        The two-mass core of Figure 2 (gear with its friction law, J1, J2, kT, dT).
    driveSideChain : tuple of (float, float, float)
        Drive-side chain ``(J4, k4, d4), ...`` (Figure 19), worm side first; empty: none.
    loadSideChain : tuple of (float, float, float)
        Load-side chain ``(JL1, kL1, dL1), ...``, wheel side first; empty: none.
    axialBearing : AxialBearing or None
        The worm's axial bearing; None: axially rigid worm.
    shaftSupports : ShaftSupports or None
        The shafts' bearings and the bodies' masses of the 3D model (worm and wheel as rigid bodies,
        docs/mesh-3d.md); None: the one-angle model.
    load : object or None
        The load law (:mod:`exudyn_worm.drive.duty`); None: no load torque given.
    motor : object or None
        The motor (a prescribed motion or a characteristic); None: no motor given (no duty).
    name : str
        What the drive is called in messages (the preset or file it came from).
    """
    parameters: Mapping[str, Any]
    sources: Mapping[str, ValueSource]
    elastic: ElasticDrive
    driveSideChain: Tuple[Tuple[float, float, float], ...] = ()
    loadSideChain: Tuple[Tuple[float, float, float], ...] = ()
    axialBearing: Optional[AxialBearing] = None
    shaftSupports: Optional[ShaftSupports] = None
    load: Optional[Any] = None
    motor: Optional[Any] = None
    name: str = 'drive'
    _cache: Dict[str, Any] = field(default_factory=dict, repr=False, compare=False)

    @classmethod
    def FromParameters(cls, parameters: Mapping[str, Any], sources: Optional[Mapping[str, ValueSource]] = None,
                       name: str = 'drive', where: Optional[str] = None) -> 'Drive':
        """Build and check the drive of a flat parameter set.

        Parameters
        ----------
        parameters : mapping
            Flat parameter set (SI), e.g. :func:`~exudyn_worm.drive.config.ResolveParameters` or a preset.
        sources : mapping, optional
            Where each value came from, a :class:`~exudyn_worm.drive.config.ValueSource` per key (default
            ``ValueSource.Api()`` for every key not in it). A key of a choice (friction law, load or motor type)
            other than the chosen one is dropped if it came from a base set or an earlier layer than the choice
            (:func:`~exudyn_worm.drive.config.DropReplacedChoiceKeys`), else refused.
        name : str, optional
            What the drive is called in messages.
        where : str, optional
            The function the user called, named in messages (default ``Drive``).

        Returns
        -------
        Drive

        Raises
        ------
        ValueError, TypeError
            For a missing, unknown or invalid parameter, an incomplete chain or duty, or a value the duty ignores.
        """
        if isinstance(parameters, Drive):
            return parameters
        where = where or (f'Drive ({name})' if name != 'drive' else 'Drive')
        CheckParameterKeys(parameters, where)
        if sources is not None and not isinstance(sources, Mapping):
            raise TypeError(f"{where}: 'sources' must be a mapping of parameter keys to ValueSource, got "
                            f"{type(sources).__name__} {sources!r}")
        bad = next(((k, v) for k, v in (sources or {}).items() if not isinstance(v, ValueSource)), None)
        if bad is not None:
            raise TypeError(f"{where}: 'sources' must map each key to a ValueSource (exudyn_worm.drive.config), got "
                            f"{type(bad[1]).__name__} {bad[1]!r} for {bad[0]!r}")
        src = {k: (sources or {}).get(k, ValueSource.Api()) for k in parameters}
        p, src = DropReplacedChoiceKeys(parameters, src, where)
        try:
            _CheckCore(p, where)                   # the core's values; then its gear and the core in one step each
            elastic = ElasticDriveWithGear(GearFromParameters(p, where=where), p, where)
            load, motor = _Duty(p, where)
            supports = ShaftSupportsFromParameters(p, where)
            axialBearing = AxialBearingFromParameters(p, where)
            driveSideChain, loadSideChain = tuple(DriveSideChain(p)), tuple(LoadSideChain(p))
            if supports is not None and (driveSideChain or MotorType(p) == 'characteristic'):
                other, key = (('a drive-side chain ([[driveSide]])', 'J4') if driveSideChain else
                              ('a motor on its characteristic (motorType characteristic)', 'motorType'))
                raise ParameterError(where, f"the shafts' bearings ([wormBearing], [wheelBearing]) make the drive the "
                                            f"3D model of worm and wheel as rigid bodies, which has no {other[2:]}; "
                                            f"remove one of them", (key,))
        except ParameterError as err:      # said where the value came from: its drive file's line, else the drive
            located = next((src[k] for k in err.keys if k in src and src[k].kind == SourceKind.FILE), None)
            raise err.At(where if located is None else located.text) from None
        drive = cls(parameters=types.MappingProxyType(p), sources=types.MappingProxyType(src), elastic=elastic,
                    driveSideChain=driveSideChain, loadSideChain=loadSideChain,
                    axialBearing=axialBearing, shaftSupports=supports, load=load, motor=motor,
                    name=name)
        return drive

    @classmethod
    def OfTwoMass(cls, elastic: ElasticDrive, name: str = 'two-mass drive') -> 'Drive':
        """The drive of Figure 2 alone: its two-mass core and nothing else (no chains, bearings or duty; no flat
        parameters). The paper's two-mass analyses build their Exudyn model from it
        (:func:`~exudyn_worm.analysis.stability.linearization.ExudynStabilityAnalysis`).

        Parameters
        ----------
        elastic : ElasticDrive
            The two-mass drive.
        name : str, optional
            What the drive is called in messages.

        Returns
        -------
        Drive
        """
        if not isinstance(elastic, ElasticDrive):
            raise TypeError(f"Drive.OfTwoMass: 'elastic' must be an ElasticDrive, got {type(elastic).__name__}")
        return cls(parameters=types.MappingProxyType({}), sources=types.MappingProxyType({}), elastic=elastic,
                   name=name)

    def Replace(self, **changes: Any) -> 'Drive':
        """A new drive with some values changed, checked where it changed.

        Each new value is checked against the parameter registry (kind, range, unit); one form of a quantity
        replaces the others (``DT=...`` drops ``dT``, as :func:`~exudyn_worm.drive.presets.ApplyOverrides`).
        Inertias, the shaft stiffness and the dampings that leave the gear as it is
        (J1, kT, the shaft damping in any form, and J2 while the mesh damping is given as dV) keep the gear, the chains, the bearings, the duty and
        its operating points (they do not depend on them); any other change builds the drive anew, with all its
        checks. This is how variations make their drives (the design check's trials, scans, studies).

        Parameters
        ----------
        **changes : float, str or None
            New values by parameter key (SI), e.g. ``drive.Replace(J1=0.3, DV=0.056)``; None leaves the key out
            (``drive.Replace(kA=None)``: no axial bearing; the drive is then checked as a whole).

        Returns
        -------
        Drive

        Raises
        ------
        ValueError, TypeError
            For an unknown key or a value out of range; for a changed drive that fails its checks.

        Examples
        --------
        >>> drive = ResolveDrive('reel-P1')
        >>> drive.Replace(J1=0.3).elastic.J1, drive.Replace(J1=0.3).gear is drive.gear
        (0.3, True)
        """
        if not changes:
            return self
        where = f'{self.name}: Replace' if self.name != 'drive' else 'Drive.Replace'
        for key, value in changes.items():
            if value is not None:
                PARAMETERS.Check(key, value, where)
            elif PARAMETERS.Get(key) is None:
                raise ValueError(PARAMETERS.UnknownKeyMessage(where, key))
        p = _WithOverrides(self.parameters, changes)
        sources = {**{k: v for k, v in self.sources.items() if k in p},
                   **{k: ValueSource.Changed() for k, v in changes.items() if v is not None}}
        if None not in changes.values() and set(changes) <= set(_GearFreeKeys(self.parameters)):     # none of them adds or drops DV: the same keys
            # the gear, the chains, the bearings and the duty stay; the operating points do not depend on them
            elastic = ElasticDriveWithGear(self.gear, p, where)
            drive = replace(self, parameters=types.MappingProxyType(p), sources=types.MappingProxyType(sources),
                            elastic=elastic, _cache={})
            if 'dutyOperatingPoints' in self._cache:
                drive._cache['dutyOperatingPoints'] = self._cache['dutyOperatingPoints']
            return drive
        return Drive.FromParameters(p, sources, self.name)

    @property
    def gear(self) -> WormGear:
        """The worm gear with its friction law."""
        return self.elastic.gear

    @property
    def geometryForm(self) -> GeometryFormKind:
        """The form in which the parameters give the gear geometry (radii, centre distance or designation)."""
        return GeometryForm(self.parameters)

    @property
    def loadType(self) -> str:
        """``lever``, ``constant``, ``timeTable``, ``angleTable`` or ``none``."""
        return LoadType(self.parameters) if self.load is not None else 'none'

    @property
    def motorType(self) -> Optional[str]:
        """``constantSpeed``, ``startStop``, ``speedTable``, ``characteristic``, or None without a motor."""
        return MotorType(self.parameters) if self.motor is not None else None

    @property
    def hasDuty(self) -> bool:
        """True if the drive has a motor (and so phases in which it runs)."""
        return self.motor is not None

    @property
    def hasMotorCharacteristic(self) -> bool:
        """True for a free motor rotor on its torque-speed line."""
        return self.motorType == 'characteristic'

    @property
    def components(self) -> Tuple[Component, ...]:
        """The parts beyond the two-mass drive of Figure 2, in a fixed order; empty for the two-mass drive."""
        return tuple(c for c, present in ((Component.DRIVE_SIDE_CHAIN, bool(self.driveSideChain)),
                                          (Component.LOAD_SIDE_CHAIN, bool(self.loadSideChain)),
                                          (Component.MOTOR_CHARACTERISTIC, self.hasMotorCharacteristic),
                                          (Component.AXIAL_BEARING, self.axialBearing is not None),
                                          (Component.SHAFT_BEARINGS, self.shaftSupports is not None)) if present)

    @property
    def isRigidBody(self) -> bool:
        """True if the drive is the 3D model: worm and wheel as rigid bodies on their shafts' bearings."""
        return self.shaftSupports is not None

    @property
    def isTwoMass(self) -> bool:
        """True if eqs. (15)-(21) describe the whole drive (no component beyond Figure 2)."""
        return not self.components

    @property
    def freeMotor(self) -> Optional[Tuple[float, float]]:
        """For a motor on its characteristic: (rotor inertia in kg*m^2, slope stallTorque/noLoadSpeed in
        N*m*s/rad); else None (the motor is held on its path)."""
        if not self.hasMotorCharacteristic:
            return None
        p = self.parameters
        return p['motorInertia'], p['stallTorque'] / p['noLoadSpeed']

    def ComponentsText(self) -> str:
        """The components as a phrase for messages (``'a load-side chain (JL1, ...)'``), ``''`` for none."""
        return ' and '.join(c.text for c in self.components)

    def Cached(self, key: str, compute):
        """The value of ``compute()`` computed once per drive under ``key`` (analyses of this drive).

        Parameters
        ----------
        key : str
            Name of the cached result.
        compute : callable
            Computes it (no arguments).
        """
        if key not in self._cache:
            self._cache[key] = compute()
        return self._cache[key]

    def __reduce__(self):
        # a worker process (a study's point, a branch's direction) gets the drive by its values; it is built and
        # checked again there, as the same drive
        return _Rebuild, (dict(self.parameters), dict(self.sources), self.name)

    def ToDict(self) -> Dict:
        """JSON-ready ``{name, components, loadType, motorType, parameters, sources}``."""
        return {'name': self.name, 'components': [c.value for c in self.components], 'loadType': self.loadType,
                'motorType': self.motorType,
                'parameters': {k: (v if isinstance(v, (int, float, str)) else str(v)) for k, v in self.parameters.items()},
                'sources': {k: v.text for k, v in self.sources.items()}}


def _Rebuild(parameters: Dict[str, Any], sources: Dict[str, ValueSource], name: str) -> Drive:
    """The drive of :meth:`Drive.__reduce__` (unpickled)."""
    return Drive.FromParameters(parameters, sources, name)


def _Duty(p: Mapping[str, Any], where: str):
    """(load, motor) of a parameter set; a named type needs its keys, the default lever / constant speed are optional."""
    loadNamed, motorNamed = 'loadType' in p, 'motorType' in p
    loadKeys, motorKeys = LOAD_TYPES[LoadType(p)], MOTOR_TYPES[MotorType(p)]
    load = motor = None
    for named, keys, kind in ((loadNamed, loadKeys, 'load'), (motorNamed, motorKeys, 'motor')):
        given = [k for k in keys if k in p]
        if (named or given) and len(given) < len(keys):
            missing = [k for k in keys if k not in p]
            typ = LoadType(p) if kind == 'load' else MotorType(p)
            raise MissingParameterError(f"{where}: the {kind} ({kind}Type {typ}) needs {', '.join(keys)}; missing "
                                        f"{', '.join(missing)} (give them with --set KEY=VALUE or in [{kind}] of the "
                                        f"drive file)", missing)
    if loadNamed or all(k in p for k in loadKeys):
        load = _LoadLaw(p, where)
    if motorNamed or all(k in p for k in motorKeys):
        motor = _MotorLaw(p, where)
    return load, motor


def ResolveDrive(preset: Optional[str] = None, config: Union[None, str, Mapping] = None,
                 sets: Iterable[Union[str, Tuple[str, float]]] = (),
                 parameters: Optional[Mapping[str, Any]] = None) -> Drive:
    """Resolve a drive once: a preset, a drive file and ``KEY=VALUE`` overrides, or a flat parameter set.

    Parameters
    ----------
    preset : str, optional
        Preset name (see :data:`~exudyn_worm.drive.presets.PRESETS`).
    config : str, path-like or dict, optional
        A drive file (TOML), the name of a shipped drive (``'hoist'``, ``'figure19'``, ...) or the file's content
        (:func:`~exudyn_worm.drive.config.LoadConfig`).
    sets : iterable of str or (str, float)
        Overrides ``'KEY=VALUE'`` (units allowed) applied last.
    parameters : mapping, optional
        A flat parameter set instead of preset and file (``sets`` are applied on top).

    Returns
    -------
    Drive

    Raises
    ------
    ValueError, TypeError
        For any bad input (unknown preset or key, bad value or unit, unreadable file, incomplete drive).

    Examples
    --------
    >>> drive = ResolveDrive('reel-P6', sets=['DV=0.056'])
    >>> drive.isTwoMass, drive.parameters['DV'], drive.sources['DV'].text
    (True, 0.056, '--set')
    """
    if parameters is not None:
        if preset is not None or config is not None:
            raise ValueError("ResolveDrive: give either 'parameters' or 'preset'/'config', not both")
        if not isinstance(parameters, Mapping):
            raise TypeError(f"ResolveDrive: 'parameters' must be a mapping (a flat parameter set), got "
                            f"{type(parameters).__name__} {parameters!r}")
        overrides, removed = _Overrides(sets)
        if not overrides and not removed:     # its messages name the function the user called
            return Drive.FromParameters(parameters, name='drive', where='ResolveDrive')
        CheckParameterKeys(parameters, 'ResolveDrive')
        p = {k: v for k, v in ApplyOverrides(parameters, overrides).items() if k not in removed}
        _CheckChain(p, {})
        return Drive.FromParameters(p, {k: ValueSource.Set() if k in overrides else ValueSource.Api() for k in p})
    if isinstance(config, (str, os.PathLike)):
        config = ConfigPath(config)                       # a shipped drive by its name, as --config takes it
    p, sources = ResolveParametersWithSources(preset, config, sets)
    name = preset or (str(config) if isinstance(config, (str, bytes)) or hasattr(config, '__fspath__') else None) \
        or next((v.text[len('preset '):] for v in sources.values() if v.kind == SourceKind.PRESET), 'drive')
    return Drive.FromParameters(p, sources, name=name)


def CheckDrive(where: str, drive: Any, name: str = 'drive') -> Drive:
    """``drive`` if it is a :class:`Drive`; else a TypeError that says how to make one.

    Below the boundary every function takes the resolved drive, never a flat parameter set: a set becomes a drive
    once, with :func:`ResolveDrive` (``ResolveDrive(parameters=...)``).

    Parameters
    ----------
    where : str
        The caller, named in the message.
    drive : object
        What the caller received.
    name : str, optional
        The argument's name in the message.

    Returns
    -------
    Drive

    Raises
    ------
    TypeError
        If ``drive`` is not a :class:`Drive`.
    """
    if isinstance(drive, Drive):
        return drive
    hint = ("; a flat parameter set becomes one with exudyn_worm.ResolveDrive(parameters=...)"
            if isinstance(drive, Mapping) else
            "; the two-mass core alone is analysed with AnalyzeStability" if isinstance(drive, ElasticDrive) else
            "; a preset or a drive file becomes one with exudyn_worm.ResolveDrive(preset=..., config=...)")
    raise TypeError(f"{where}: '{name}' must be a Drive (exudyn_worm.ResolveDrive), got {type(drive).__name__}{hint}")
