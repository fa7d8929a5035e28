"""Parameter values with units, TOML config files and the resolution of a parameter set.

A parameter set is the flat dictionary of :mod:`exudyn_worm.drive.presets` (SI, angles in rad). It is
resolved in three layers, each applied with :func:`~exudyn_worm.drive.presets.ApplyOverrides` (so a value
replaces its alternative forms: ``mu`` drops ``rho``, ``dT`` drops ``DT``/``DTV``, ``DV`` drops ``dV``):

1. a preset (default ``'reel-P1'``; a config file's ``preset`` replaces the default, an explicit
   ``preset`` argument replaces the config file's; a whole-drive file that names no preset starts from
   nothing, so that what it leaves out is reported missing instead of taken from the reel changer);
2. the values of a TOML config file: the component tables of a whole-drive file
   (:mod:`exudyn_worm.params.drivefile`: ``[gear]``, ``[worm]``, ``[wheel]``, ``[driveShaft]``, ``[load]``,
   ``[motor]``, ``[[driveSide]]``, ``[[loadSide]]``, ``[axialBearing]``) and/or the flat ``[parameters]`` table;
3. ``KEY=VALUE`` overrides (the CLI's ``--set``).

A value is a string with units parsed by pint, e.g. ``'0.5 mm'``, ``'8 deg'``, ``'7 kN*m'``, ``'472.5 rpm'``, or
a plain number in the key's SI unit; in text and drive files an angle, an angular speed or a length needs its unit
(a plain number other than 0 is refused: :data:`~exudyn_worm.params.parameters.UNIT_REQUIRED`). Python numbers are
SI. The target unit of every key is
:data:`~exudyn_worm.drive.presets.PARAMETER_UNITS`; unit, range and kind of every key are declared once in
:data:`~exudyn_worm.params.parameters.PARAMETERS`, which parses the values.

Example config file (flat form; whole-drive files are described in :mod:`exudyn_worm.params.drivefile`)::

    preset = "reel-P1"          # optional

    [parameters]
    J1 = "0.2 kg*m^2"
    kT = 12000                  # SI: N*m/rad
    DTV = 2
    backlash = "0.25 mm"

This module holds no command-line code; :mod:`exudyn_worm.cli.main` uses it.
"""
from __future__ import annotations

import enum
import os
import re
from dataclasses import dataclass
from numbers import Real
from typing import Dict, Iterable, Mapping, Optional, Tuple, Union

from ..params.drivefile import (ARRAY_TABLES, COMPONENT_TABLES, DRIVE_FILE_TABLES, DRIVE_SIDE_TABLE, LOAD_SIDE_TABLE,
                        TOP_LEVEL_KEYS, FlattenDriveFile, ReadDriveFile)
from .._checks import Suggest
from ..params.parameters import PARAMETERS
from .duty import LOAD_TYPES, MOTOR_TYPES
from .presets import _LAW_KEYS, PRESETS, ApplyOverrides, CheckParameters, DriveSideChain, GetPreset, LoadSideChain

__all__ = ['DEFAULT_PRESET', 'CONFIG_KEYS', 'SourceKind', 'ValueSource', 'ParseQuantity', 'ParseSetOption', 'LoadConfig',
           'LoadedConfig', 'ResolveParametersWithSources', 'ResolveParameters', 'DropReplacedChoiceKeys']

#: preset used when neither an explicit preset nor a config file names one
DEFAULT_PRESET = 'reel-P1'

#: top-level keys of a config file besides the component tables of :mod:`exudyn_worm.params.drivefile`
CONFIG_KEYS = TOP_LEVEL_KEYS


class SourceKind(enum.IntEnum):
    """Where a value of a parameter set came from; a larger kind was given later, closer to the run.

    Attributes
    ----------
    API, PRESET, FILE, SET, CHANGED : SourceKind
        A Python dictionary or number, a preset (the base set), a drive file, a ``--set`` option (or a ``KEY=VALUE``
        string of ``sets``), :meth:`~exudyn_worm.drive.wholedrive.Drive.Replace`.
    """
    API = 0
    PRESET = 1
    FILE = 2
    SET = 3
    CHANGED = 4

    @property
    def isBase(self) -> bool:
        """True for the values of a base set (a preset, or a dictionary built on one), which a later choice may drop."""
        return self in (SourceKind.API, SourceKind.PRESET)


@dataclass(frozen=True)
class ValueSource:
    """Where one value came from: a kind to decide on and a text for messages and JSON.

    Parameters
    ----------
    kind : SourceKind
        What gave the value.
    text : str
        How messages and JSON name it: ``'--set'``, ``"LoadConfig: 'f.toml', line 7: [gear] wormRadius"``,
        ``'preset reel-P1'``, ``'API'``, ``'changed'``.

    Examples
    --------
    >>> ValueSource.Preset('reel-P1')
    ValueSource(kind=<SourceKind.PRESET: 1>, text='preset reel-P1')
    >>> str(ValueSource.Set())
    '--set'
    """
    kind: SourceKind
    text: str

    def __post_init__(self):
        if not isinstance(self.kind, SourceKind):
            raise TypeError(f"ValueSource: 'kind' must be a SourceKind, got {type(self.kind).__name__} {self.kind!r}")
        if not isinstance(self.text, str):
            raise TypeError(f"ValueSource: 'text' must be a string, got {type(self.text).__name__} {self.text!r}")

    def __str__(self) -> str:
        return self.text

    @classmethod
    def Api(cls) -> 'ValueSource':
        """A value given from Python."""
        return cls(SourceKind.API, 'API')

    @classmethod
    def Preset(cls, name: str) -> 'ValueSource':
        """A value of the preset ``name``.

        Parameters
        ----------
        name : str
            The preset's name.
        """
        return cls(SourceKind.PRESET, f'preset {name}')

    @classmethod
    def File(cls, location: str) -> 'ValueSource':
        """A value of a drive file at ``location`` (file, line, table and key).

        Parameters
        ----------
        location : str
            E.g. ``"LoadConfig: 'f.toml', line 7: [gear] wormRadius"``.
        """
        return cls(SourceKind.FILE, location)

    @classmethod
    def Set(cls) -> 'ValueSource':
        """A value of a ``--set`` option."""
        return cls(SourceKind.SET, '--set')

    @classmethod
    def Changed(cls) -> 'ValueSource':
        """A value changed by :meth:`~exudyn_worm.drive.wholedrive.Drive.Replace`."""
        return cls(SourceKind.CHANGED, 'changed')

def _CheckKey(where: str, key) -> str:
    if not isinstance(key, str) or key not in PARAMETERS:
        raise ValueError(PARAMETERS.UnknownKeyMessage(where, key))
    return key


def ParseQuantity(key: str, text: Union[str, float]) -> float:
    """Parse the value of parameter ``key`` into a float in its SI unit.

    Parameters
    ----------
    key : str
        A parameter name of :data:`~exudyn_worm.drive.presets.PARAMETER_UNITS`, e.g. ``'kT'``.
    text : str or float
        A number followed by a unit that pint understands, e.g. ``'0.5 mm'``, ``'8 deg'``, ``'7 kN*m'``,
        ``'472.5 rpm'``, ``'1.4 %'``, or a plain number in the key's SI unit; a plain number in text is refused
        (zero excepted) for an angle, an angular speed or a length (docs/drive-files.md, "Values"). Numbers (int
        or float, not bool) are SI and accepted as they are.

    Returns
    -------
    float
        The value in the unit of ``PARAMETER_UNITS[key]``. (A key whose value is not a number, see
        :mod:`exudyn_worm.params.parameters`, gives its parsed value: the choice, or the path or rows of a table.)

    Raises
    ------
    ValueError
        For an unknown key, malformed text, an unknown unit, a wrong dimension (the message names the
        key, the expected unit and what was received), a plain number in text for an angle, an angular speed
        or a length, or a non-finite value.
    TypeError
        If ``text`` is neither a string nor a real number.

    Notes
    -----
    pint treats rad as dimensionless, so an angle unit could silently convert into a plain ratio
    (``mu = "8 deg"``) and ``Hz`` into ``rad/s`` without the factor 2 pi. To prevent that, the power of
    rad must match the target unit; the one exception is a torque per angle (``kT``, ``dT``), where
    ``N*m`` stands for ``N*m/rad`` as is customary.

    Examples
    --------
    >>> ParseQuantity('backlash', '0.5 mm')
    0.0005
    >>> ParseQuantity('kT', '7 kN*m')
    7000.0
    >>> round(ParseQuantity('motorSpeed', '472.5 rpm'), 4)
    49.4801
    """
    return _ParseQuantity(key, text, 'ParseQuantity')


def _ParseQuantity(key, text, where: str, fromFile: bool = False):
    return PARAMETERS.Parse(_CheckKey(where, key), text, where, fromFile)


def ParseSetOption(text: str) -> Tuple[str, float]:
    """Parse one ``KEY=VALUE`` override (the CLI's ``--set``).

    Parameters
    ----------
    text : str
        ``KEY=VALUE`` with a key of :data:`~exudyn_worm.drive.presets.PARAMETER_UNITS` and a value as
        :func:`ParseQuantity` accepts, e.g. ``'backlash=0.5 mm'`` or ``'J1=0.3'``.

    Returns
    -------
    (str, float)
        The key and its value in SI units.

    Raises
    ------
    ValueError
        If there is no ``=``, the key is unknown (the message lists the allowed keys) or the value is
        invalid.
    """
    where = 'ParseSetOption'
    if not isinstance(text, str):
        raise TypeError(f"{where}: expected a string 'KEY=VALUE', got {type(text).__name__} {text!r}")
    key, sep, value = text.partition('=')
    key = key.strip()
    if not sep or not key:
        raise ValueError(f"{where}: expected KEY=VALUE (e.g. 'J1=0.3' or 'backlash=0.5 mm'), got {text!r}")
    _CheckKey(where, key)
    if not value.strip():
        raise ValueError(f"{where}: {text!r}: '{key}' must be a number or a value with units "
                         f"({PARAMETERS.ExpectedText(key)}), got no value (an empty value, --set {key}=, takes the key "
                         f"back, among the overrides of ResolveParameters and the CLI only)")
    parsed = _ParseQuantity(key, value.strip(), f"{where}: {text!r}")
    parameter = PARAMETERS.Get(key)
    if parameter is not None and parameter.kind == 'table' and isinstance(parsed, str) \
            and not os.path.isfile(os.path.expanduser(parsed)):
        columns = ', '.join(name for name, _, _ in parameter.columns)
        why = 'not a regular file' if os.path.exists(os.path.expanduser(parsed)) else 'no such file'
        raise ValueError(f"{where}: {text!r}: '{key}': cannot read the table file {parsed!r} ({why}); expected the "
                         f"path of a table file or rows of ({columns}) such as "
                         f"'[[{', '.join('0' for _ in parameter.columns)}]]'")
    return key, parsed


def _RejectAlternatives(values: Mapping[str, float], where: str, locations: Optional[Mapping[str, str]] = None
                        ) -> None:
    """Raise if ``values`` gives two forms of one quantity (e.g. ``mu`` and ``rho``), naming where each is."""
    for key, dropped in PARAMETERS.Conflicts(values):
        others = ' and '.join(f"'{k}'" for k in dropped)
        forms = PARAMETERS.FormsText(key)
        what = (f"which belong to different forms of the {PARAMETERS.Quantity(key)}; give one form: {forms}" if forms
                else 'which describe the same quantity; give only one of them')
        if locations:
            places = '; '.join(locations[k][len(where):].lstrip(',: ') for k in (key, *dropped))
            raise ValueError(f"{where}: both '{key}' and {others} are given ({places}), {what}")
        raise ValueError(f"{where}: both '{key}' and {others} are given, {what}")


class LoadedConfig(dict):
    """A drive file as :func:`LoadConfig` read it: what :func:`ResolveParametersWithSources` takes instead of the
    path, so that a command reads its file once.

    Parameters
    ----------
    content : mapping
        ``preset``, ``parameters``, ``wholeDrive`` and ``locations``, as :func:`LoadConfig` returns them.
    """

    def __init__(self, content: Mapping) -> None:
        super().__init__(content)


def LoadConfig(path: Union[str, os.PathLike, Mapping]) -> LoadedConfig:
    """Read a TOML config file (or take its content as a dictionary) and parse its values.

    Parameters
    ----------
    path : str, path-like or mapping
        A TOML file: a whole-drive file with component tables (``[gear]``, ``[worm]``, ``[driveShaft]``, ...,
        see :mod:`exudyn_worm.params.drivefile` and docs/drive-files.md) and/or a flat ``[parameters]`` table, and
        an optional ``preset = "NAME"``. Values are numbers (SI, angles in rad) or strings with units (see
        :func:`ParseQuantity`). A mapping is the content of such a file (what
        :func:`ResolveParameters` takes as ``config``).

    Returns
    -------
    LoadedConfig
        ``{'preset': str or None, 'parameters': {key: float in SI}, 'wholeDrive': bool, 'locations': {key:
        str}}``; ``wholeDrive`` is True when the file has component tables (then :func:`ResolveParameters`
        inherits no preset unless the file or the caller names one); ``locations`` names the file, line,
        table and key of each parameter, for messages.

    Raises
    ------
    ValueError
        If the file cannot be read, is no regular file or exceeds a limit of
        :func:`~exudyn_worm.params.drivefile.ReadDriveFile` (size, nesting, keys, stages), is not valid TOML, has
        unknown keys, an unknown preset, a value that is
        invalid or out of range (:func:`~exudyn_worm.drive.presets.CheckParameters`), gives one quantity twice or in
        two forms (e.g. both ``mu`` and ``rho``), or gives neither a parameter nor a preset. The message
        names the file, the line where it can be found, the table and key, and what was expected.
    """
    if isinstance(path, Mapping):                # the content of a file, given as a dictionary
        data, text, folder, where = path, None, None, 'ResolveParameters: config'
    else:
        where = f"LoadConfig: '{path}'"
        data, text = ReadDriveFile(path, where)     # bounded: size, nesting, keys, stages; never a FIFO or a device
        folder = os.path.dirname(os.path.abspath(path))
    # a relative file path of a table (frictionTable) is taken relative to the file's folder; the plain numbers of
    # an angle, an angular speed or a length are refused (the rule of docs/drive-files.md)
    preset, raw = FlattenDriveFile(data, where, text)
    if preset is not None and preset not in PRESETS:
        line = next((i for i, row in enumerate((text or '').splitlines(), 1)
                     if re.match(r'\s*["\']?preset["\']?\s*=', row)), None)
        raise ValueError(f"{where}{f', line {line}' if line else ''}: preset: unknown preset '{preset}'"
                         f"{Suggest(preset, PRESETS)}; expected one of: {', '.join(PRESETS)}")
    parameters, locations = {}, {}
    for key, value, location in raw:
        if key not in PARAMETERS:
            raise ValueError(PARAMETERS.UnknownKeyMessage(location, key))
        if PARAMETERS[key].kind == 'number' and (isinstance(value, bool) or not isinstance(value, (str, Real))):
            what = 'a string with units' if PARAMETERS.UnitRequired(key) else 'a number (SI) or a string with units'
            raise ValueError(f"{location}: must be {what}, got {type(value).__name__} {value!r}; '{key}' is "
                             f"{PARAMETERS.ExpectedText(key)}")
        parameters[key] = _ParseQuantity(key, value, location, fromFile=True)
        if PARAMETERS[key].kind == 'table' and isinstance(parameters[key], str) and folder is not None \
                and not os.path.isabs(os.path.expanduser(parameters[key])):
            parameters[key] = os.path.join(folder, parameters[key])   # a table file beside the drive file
        CheckParameters({key: parameters[key]}, location)        # the range, named by the file's line and key
        locations[key] = location
    _RejectAlternatives(parameters, where, locations)
    if not parameters and preset is None:
        raise ValueError(f"{where}: the file gives no parameters: a drive file must give the drive's values in "
                         f"component tables ({', '.join(f'[{t}]' for t in DRIVE_FILE_TABLES)}, "
                         f"[[{DRIVE_SIDE_TABLE}]], [[{LOAD_SIDE_TABLE}]]; see docs/drive-files.md) or in a [parameters] table, or name a "
                         f"preset (preset = \"{DEFAULT_PRESET}\")")
    # a file with component tables describes a whole drive: nothing is inherited unless it names a preset
    wholeDrive = any(table in data for table in COMPONENT_TABLES)
    return LoadedConfig({'preset': preset, 'parameters': parameters, 'wholeDrive': wholeDrive,
                         'locations': locations})


def ResolveParameters(preset: Optional[str] = None,
                      config: Union[None, str, os.PathLike, Mapping] = None,
                      sets: Iterable[Union[str, Tuple[str, float]]] = ()) -> Dict[str, float]:
    """Resolve a parameter set from a preset, a config file and ``KEY=VALUE`` overrides.

    Parameters
    ----------
    preset : str, optional
        Preset name (see :data:`~exudyn_worm.drive.presets.PRESETS`); overrides the config's preset.
        Default: the config's preset, else none for a whole-drive file (one with component tables: it
        describes the whole drive), else :data:`DEFAULT_PRESET`.
    config : str, path-like or dict, optional
        A TOML file (read with :func:`LoadConfig`) or a dict of the form :func:`LoadConfig` returns.
    sets : iterable of str or (str, float), or None
        Overrides ``'KEY=VALUE'`` (parsed with :func:`ParseSetOption`) or ``(key, value)`` pairs (a number is SI),
        applied last, in order (the last value of a repeated key wins); ``'KEY='`` takes the key back. A choice
        set here drops the keys of the file or preset that only the replaced choice used
        (:func:`DropReplacedChoiceKeys`). None: no overrides.

    Returns
    -------
    dict
        The flat parameter dictionary (SI) for :func:`~exudyn_worm.drive.presets.DriveFromParameters`.

    Raises
    ------
    ValueError
        For an unknown or empty preset name, an unknown key, an invalid value (a plain number of an angle, an
        angular speed or a length in text or a file among them), an unreadable config file, overrides giving two
        forms of one quantity (e.g. ``dT`` and ``DT``), or a key of a load or motor type that the chosen one does
        not use, given as late as the choice.

    Examples
    --------
    >>> p = ResolveParameters('reel-P6', sets=['DV=0.056'])
    >>> p['DV'], p['J1'], p['DTV']
    (0.056, 0.2, 2.0)
    """
    return ResolveParametersWithSources(preset, config, sets)[0]


def ResolveParametersWithSources(preset: Optional[str] = None,
                                 config: Union[None, str, os.PathLike, Mapping] = None,
                                 sets: Iterable[Union[str, Tuple[str, float]]] = ()
                                 ) -> Tuple[Dict[str, float], Dict[str, str]]:
    """:func:`ResolveParameters`, and where each value came from.

    Parameters
    ----------
    preset : str, optional
        As for :func:`ResolveParameters`.
    config : str, path-like, dict or LoadedConfig, optional
        As for :func:`ResolveParameters`, or a file :func:`LoadConfig` has read already.
    sets : iterable of str or (str, float)
        As for :func:`ResolveParameters`.

    Returns
    -------
    (dict, dict)
        The flat parameter dictionary (SI) and, per key, its :class:`ValueSource`: ``--set``, the drive file's
        location (text ``"LoadConfig: 'FILE', line N: [table] key"``) or the preset (text ``'preset NAME'``).
    """
    if config is None:
        cfg = {'preset': None, 'parameters': {}, 'wholeDrive': False, 'locations': {}}
    elif isinstance(config, LoadedConfig):                 # read already (by the command that resolves it)
        cfg = config
    elif isinstance(config, (Mapping, str, os.PathLike)):
        cfg = LoadConfig(config)
    else:
        raise TypeError(f"ResolveParameters: 'config' must be a path or a dict, got {type(config).__name__}")
    if preset is not None and not isinstance(preset, str):
        raise TypeError(f"ResolveParameters: 'preset' must be a string, got {type(preset).__name__}")
    if preset is not None and not preset.strip():      # '' is no name: never taken silently for the default
        raise ValueError(f"ResolveParameters: 'preset' must name a preset, got an empty name {preset!r}; expected "
                         f"one of: {', '.join(PRESETS)} (or no preset: the default {DEFAULT_PRESET})")
    if preset is not None and preset not in PRESETS:
        raise ValueError(f"ResolveParameters: 'preset': unknown preset {preset!r}{Suggest(preset, PRESETS)}; expected "
                         f"one of: {', '.join(PRESETS)}")
    name = preset or cfg['preset'] or (None if cfg['wholeDrive'] else DEFAULT_PRESET)
    parameters = ApplyOverrides(GetPreset(name) if name else {}, cfg['parameters'])
    overrides, removed = _Overrides(sets)
    parameters = ApplyOverrides(parameters, overrides)
    for key in removed:                      # --set KEY= : the key is taken back
        parameters.pop(key, None)
    locations = cfg.get('locations', {})
    sources = {k: ValueSource.Set() if k in overrides else ValueSource.File(locations[k]) if k in locations
               else ValueSource.Preset(name) if name else ValueSource.Api() for k in parameters}
    parameters, sources = DropReplacedChoiceKeys(parameters, sources, 'ResolveParameters')
    _CheckChain(parameters, {k: v for k, v in locations.items() if k not in overrides and k in parameters})
    return parameters, sources


def _Overrides(sets) -> Tuple[Dict[str, object], Tuple[str, ...]]:
    """The values of ``sets`` (``'KEY=VALUE'`` or ``(key, value)``; the last value of a repeated key wins) and the keys
    taken back with an empty value (``'KEY='``)."""
    where = 'ResolveParameters'
    if sets is None:
        return {}, ()
    if isinstance(sets, (str, bytes)):
        raise TypeError(f"{where}: 'sets' must be a list of 'KEY=VALUE' strings, got a single string {sets!r}; "
                        f"write sets=[{sets!r}]")
    if not isinstance(sets, Iterable):
        raise TypeError(f"{where}: 'sets' must be a list of 'KEY=VALUE' strings or (key, value) pairs, got "
                        f"{type(sets).__name__} {sets!r}")
    overrides: Dict[str, object] = {}
    removed: Dict[str, None] = {}
    for item in sets:
        if isinstance(item, str) and item.partition('=')[1] and not item.partition('=')[2].strip():
            key = _CheckKey(f"{where}: {item!r}", item.partition('=')[0].strip())
            overrides.pop(key, None)
            removed[key] = None
            continue
        if isinstance(item, str):
            key, value = ParseSetOption(item)
            itemWhere = f"ParseSetOption: {item!r}"
        elif isinstance(item, tuple) and len(item) == 2:
            itemWhere = f"{where}: sets item {item!r}"
            key, value = _CheckKey(itemWhere, item[0]), _ParseQuantity(item[0], item[1], itemWhere)
        else:
            raise TypeError(f"{where}: each of 'sets' must be 'KEY=VALUE' or (key, value), got "
                            f"{type(item).__name__} {item!r}")
        CheckParameters({key: value}, itemWhere)      # the range, named by the option as the user wrote it
        removed.pop(key, None)
        overrides.pop(key, None)      # a repeated key: the last one wins, in its new position
        overrides[key] = value
    _RejectAlternatives(overrides, f'{where}: the overrides (--set)')
    return overrides, tuple(removed)


def _ChoiceKeys() -> Dict[str, Dict[str, Tuple[str, ...]]]:
    """choice key -> {value: the keys that value uses}: the friction law, the load type and the motor type."""
    laws = {law: tuple(k for k, used in _LAW_KEYS.items() if law in used) for law in PARAMETERS['frictionLaw'].choices}
    motors = {**MOTOR_TYPES, 'startStop': MOTOR_TYPES['startStop'] + ('brakeTime',)}    # brakeTime: optional
    return {'frictionLaw': laws, 'loadType': dict(LOAD_TYPES), 'motorType': motors}


#: the default value of each choice of :func:`_ChoiceKeys`
_CHOICE_DEFAULTS = {'frictionLaw': 'constant', 'loadType': 'lever', 'motorType': 'constantSpeed'}


def DropReplacedChoiceKeys(parameters: Mapping[str, object], sources: Mapping[str, 'ValueSource'], where: str
                           ) -> Tuple[Dict[str, object], Dict[str, 'ValueSource']]:
    """Drop the keys that belong only to a choice replaced later (``frictionLaw``, ``loadType``, ``motorType``).

    A key used only by another value of a choice than the chosen one (``muStatic`` with ``frictionLaw = constant``,
    ``loadMass`` with ``loadType = constant``, ``motorSpeed`` with ``motorType = speedTable``) is dropped if it came
    from a base set (a preset or a Python dictionary) and the choice is given (not the default), or from an earlier
    layer than the choice (a drive file's key when ``--set`` replaced the file's choice). A key given as late as the
    choice (both in the file, both with ``--set``) or later, or with the default choice, is refused: the drive would
    not use it.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set.
    sources : mapping
        Per key, its :class:`ValueSource`.
    where : str
        Prefix of error messages.

    Returns
    -------
    (dict, dict)
        The parameters and sources without the dropped keys.

    Raises
    ------
    ValueError
        For a key of a load or motor type other than the chosen one that the user gave as late as the choice
        (the friction law's own keys are refused by :func:`~exudyn_worm.drive.presets.FrictionLawFromParameters`).
    """
    p, src = dict(parameters), dict(sources)
    for choice, keysOf in _ChoiceKeys().items():
        value = p.get(choice, _CHOICE_DEFAULTS[choice])
        if value not in keysOf:
            continue                    # an invalid choice: refused with its own message by the registry's check
        used = keysOf[value]
        chosen = src.get(choice)
        for key in [k for k in p if k not in used and any(k in keys for keys in keysOf.values())]:
            given = src.get(key, ValueSource.Api())
            # a base set's key gives way to a choice that was made (not to the default: there the key more likely
            # means that the choice was forgotten); any key gives way to a choice made in a later layer
            if (given.kind.isBase and choice in p) or (chosen is not None and given.kind < chosen.kind):
                del p[key]
                src.pop(key, None)
            elif choice != 'frictionLaw':
                owners = [v for v, keys in keysOf.items() if key in keys]
                chosenText = chosen.text if chosen is not None else 'the default'
                if chosen is not None and chosen.kind == given.kind == SourceKind.FILE:     # the same file: its line
                    file, _, line = chosen.text.partition(', line ')
                    chosenText = f'line {line}' if line and given.text.startswith(file + ', line ') else chosen.text
                state = f"{choice} = {value!r} ({chosenText})"
                inFile = given.kind == SourceKind.FILE          # the location names the file, line and key
                raise ValueError(f"{given if inFile else where}: '{key}'{'' if inFile else f' ({given})'} is not used "
                                 f"by {state}, which takes {', '.join(used) or 'no keys'}; '{key}' belongs to "
                                 f"{choice} {' or '.join(owners)}: remove it (on the command line --set {key}=) "
                                 f"or choose {choice} = {owners[0]}")
    return p, src


def _CheckChain(parameters: Mapping[str, float], locations: Mapping[str, str]) -> None:
    """The drive-side and load-side chains must be complete (``J4`` with ``k4``, ``JL1`` with ``kL1``, no gaps) in
    every resolved parameter set, so that no command meets an incomplete chain later; a chain from a drive file is
    reported at the stage that is incomplete (its ``[[driveSide]]`` / ``[[loadSide]]`` number and line), or at the
    file's first stage of that chain if that stage was not in the file."""
    for table, Chain in ((DRIVE_SIDE_TABLE, DriveSideChain), (LOAD_SIDE_TABLE, LoadSideChain)):
        prefixes = tuple(ARRAY_TABLES[table].values())
        J, k = ARRAY_TABLES[table]['inertia'], ARRAY_TABLES[table]['stiffness']
        first = PARAMETERS.Series(J).series

        def Index(key):
            series = PARAMETERS.SeriesIndex(key)
            return series[1] if series and series[0] in prefixes else None
        try:
            Chain(parameters)
        except ValueError as err:
            stages = {}              # stage number (4, 5, ... / 1, 2, ...) -> location of its first key in the file
            for key, location in locations.items():
                if Index(key) is not None:
                    stages.setdefault(Index(key), location)
            if not stages:
                raise ValueError(f"ResolveParameters: {err}") from None
            given = sorted({Index(key) for key in parameters if Index(key) is not None})
            # the first stage that breaks the chain: a gap before it, or without its inertia or stiffness
            bad = next((i for expected, i in enumerate(given, start=first)
                        if i != expected or f'{J}{i}' not in parameters or f'{k}{i}' not in parameters), given[0])
            location = stages.get(bad, stages[min(stages)])
            raise ValueError(f"{location}: {err}; each [[{table}]] table needs 'inertia' and "
                             f"'stiffness' ('damping' is optional)") from None
