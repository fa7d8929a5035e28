"""Parameter values with units, TOML config files and the resolution of a parameter set.

A parameter set is the flat dictionary of :mod:`exudyn_worm.setups.presets` (SI, angles in rad). It is
resolved in three layers, each applied with :func:`~exudyn_worm.setups.presets.ApplyOverrides` (so a value
replaces its alternative forms: ``mu`` drops ``rho``, ``dT`` drops ``DT``/``DTV``, ``DV`` drops ``dV``):

1. a preset (default ``'reel-P1'``; a config file's ``preset`` replaces the default, an explicit
   ``preset`` argument replaces the config file's; a whole-drive file that names no preset starts from
   nothing, so that what it leaves out is reported missing instead of taken from the reel changer);
2. the values of a TOML config file: the component tables of a whole-drive file
   (:mod:`exudyn_worm.params.drivefile`: ``[gear]``, ``[worm]``, ``[wheel]``, ``[driveShaft]``, ``[load]``,
   ``[motor]``, ``[[driveSide]]``, ``[[loadSide]]``, ``[axialBearing]``) and/or the flat ``[parameters]`` table;
3. ``KEY=VALUE`` overrides (the CLI's ``--set``).

A value is a plain SI number (angles in rad, ``motorSpeed`` in rad/s) or a string with units parsed by
pint, e.g. ``'0.5 mm'``, ``'8 deg'``, ``'7 kN*m'``, ``'472.5 rpm'``. The target unit of every key is
:data:`~exudyn_worm.setups.presets.PARAMETER_UNITS`; unit, range and kind of every key are declared once in
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

import os
from numbers import Real
from typing import Dict, Iterable, Mapping, Optional, Tuple, Union

from ..params.drivefile import (ARRAY_TABLES, COMPONENT_TABLES, DRIVE_FILE_TABLES, DRIVE_SIDE_TABLE, LOAD_SIDE_TABLE,
                        TOP_LEVEL_KEYS, FlattenDriveFile, ReadDriveFile)
from ..params.parameters import PARAMETERS
from .presets import PRESETS, ApplyOverrides, CheckParameters, DriveSideChain, GetPreset, LoadSideChain

__all__ = ['DEFAULT_PRESET', 'CONFIG_KEYS', 'ParseQuantity', 'ParseSetOption', 'LoadConfig', 'ResolveParametersWithSources',
           'ResolveParameters']

#: preset used when neither an explicit preset nor a config file names one
DEFAULT_PRESET = 'reel-P1'

#: top-level keys of a config file besides the component tables of :mod:`exudyn_worm.params.drivefile`
CONFIG_KEYS = TOP_LEVEL_KEYS

def _CheckKey(where: str, key) -> str:
    if not isinstance(key, str) or key not in PARAMETERS:
        raise ValueError(PARAMETERS.UnknownKeyMessage(where, key))
    return key


def ParseQuantity(key: str, text: Union[str, float]) -> float:
    """Parse the value of parameter ``key`` into a float in its SI unit.

    Parameters
    ----------
    key : str
        A parameter name of :data:`~exudyn_worm.setups.presets.PARAMETER_UNITS`, e.g. ``'kT'``.
    text : str or float
        A plain number, taken as SI (angles in rad, speeds in rad/s), or a number followed by a unit
        that pint understands, e.g. ``'0.5 mm'``, ``'8 deg'``, ``'7 kN*m'``, ``'472.5 rpm'``,
        ``'1.4 %'``. Numbers (int or float, not bool) are accepted as they are.

    Returns
    -------
    float
        The value in the unit of ``PARAMETER_UNITS[key]``. (A key whose value is not a number, see
        :mod:`exudyn_worm.params.parameters`, gives its parsed value: the choice, or the path or rows of a table.)

    Raises
    ------
    ValueError
        For an unknown key, malformed text, an unknown unit, a wrong dimension (the message names the
        key, the expected unit and what was received) or a non-finite value.
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


def _ParseQuantity(key, text, where: str):
    return PARAMETERS.Parse(_CheckKey(where, key), text, where)


def ParseSetOption(text: str) -> Tuple[str, float]:
    """Parse one ``KEY=VALUE`` override (the CLI's ``--set``).

    Parameters
    ----------
    text : str
        ``KEY=VALUE`` with a key of :data:`~exudyn_worm.setups.presets.PARAMETER_UNITS` and a value as
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


def _ConfigFromData(data: Mapping, where: str, text: Optional[str] = None, folder: Optional[str] = None) -> Dict:
    """Check the content of a config (drive) file and parse its values (see :mod:`exudyn_worm.params.drivefile`); a
    relative file path of a table (``frictionTable``) is taken relative to ``folder``, the file's folder."""
    preset, raw = FlattenDriveFile(data, where, text)
    if preset is not None and preset not in PRESETS:
        raise ValueError(f"{where}: unknown preset '{preset}'; expected one of: {', '.join(PRESETS)}")
    parameters, locations = {}, {}
    for key, value, location in raw:
        if key not in PARAMETERS:
            raise ValueError(PARAMETERS.UnknownKeyMessage(location, key))
        if PARAMETERS[key].kind == 'number' and (isinstance(value, bool) or not isinstance(value, (str, Real))):
            raise ValueError(f"{location}: must be a number (SI) or a string with units, "
                             f"got {type(value).__name__} {value!r}")
        parameters[key] = _ParseQuantity(key, value, location)
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
    return {'preset': preset, 'parameters': parameters, 'wholeDrive': wholeDrive, 'locations': locations}


def LoadConfig(path: Union[str, os.PathLike]) -> Dict:
    """Read a TOML config file.

    Parameters
    ----------
    path : str or path-like
        A TOML file: a whole-drive file with component tables (``[gear]``, ``[worm]``, ``[driveShaft]``, ...,
        see :mod:`exudyn_worm.params.drivefile` and docs/drive-files.md) and/or a flat ``[parameters]`` table, and
        an optional ``preset = "NAME"``. Values are numbers (SI, angles in rad) or strings with units (see
        :func:`ParseQuantity`).

    Returns
    -------
    dict
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
        invalid or out of range (:func:`~exudyn_worm.setups.presets.CheckParameters`), gives one quantity twice or in
        two forms (e.g. both ``mu`` and ``rho``), or gives neither a parameter nor a preset. The message
        names the file, the line where it can be found, the table and key, and what was expected.
    """
    where = f"LoadConfig: '{path}'"
    data, text = ReadDriveFile(path, where)     # bounded: size, nesting, keys, stages; never a FIFO or a device
    return _ConfigFromData(data, where, text, os.path.dirname(os.path.abspath(path)))


def ResolveParameters(preset: Optional[str] = None,
                      config: Union[None, str, os.PathLike, Mapping] = None,
                      sets: Iterable[Union[str, Tuple[str, float]]] = ()) -> Dict[str, float]:
    """Resolve a parameter set from a preset, a config file and ``KEY=VALUE`` overrides.

    Parameters
    ----------
    preset : str, optional
        Preset name (see :data:`~exudyn_worm.setups.presets.PRESETS`); overrides the config's preset.
        Default: the config's preset, else none for a whole-drive file (one with component tables: it
        describes the whole drive), else :data:`DEFAULT_PRESET`.
    config : str, path-like or dict, optional
        A TOML file (read with :func:`LoadConfig`) or a dict of the form :func:`LoadConfig` returns.
    sets : iterable of str or (str, float)
        Overrides ``'KEY=VALUE'`` (parsed with :func:`ParseSetOption`) or ``(key, value)`` pairs,
        applied last, in order (the last value of a repeated key wins).

    Returns
    -------
    dict
        The flat parameter dictionary (SI) for :func:`~exudyn_worm.setups.presets.DriveFromParameters`.

    Raises
    ------
    ValueError
        For an unknown or empty preset name, an unknown key, an invalid value, an unreadable config file, or
        overrides giving two forms of one quantity (e.g. ``dT`` and ``DT``).

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
    config : str, path-like or dict, optional
        As for :func:`ResolveParameters`.
    sets : iterable of str or (str, float)
        As for :func:`ResolveParameters`.

    Returns
    -------
    (dict, dict)
        The flat parameter dictionary (SI) and, per key, its source: ``'--set'``, the drive file's location
        (``'FILE: [table] key'``) or ``'preset NAME'``.
    """
    if config is None:
        cfg = {'preset': None, 'parameters': {}, 'wholeDrive': False, 'locations': {}}
    elif isinstance(config, Mapping):
        cfg = _ConfigFromData(config, 'ResolveParameters: config')
    elif isinstance(config, (str, os.PathLike)):
        cfg = LoadConfig(config)
    else:
        raise TypeError(f"ResolveParameters: 'config' must be a path or a dict, got {type(config).__name__}")
    if preset is not None and not isinstance(preset, str):
        raise TypeError(f"ResolveParameters: 'preset' must be a string, got {type(preset).__name__}")
    if preset is not None and not preset.strip():      # '' is no name: never taken silently for the default
        raise ValueError(f"ResolveParameters: 'preset' must name a preset, got an empty name {preset!r}; expected "
                         f"one of: {', '.join(PRESETS)} (or no preset: the default {DEFAULT_PRESET})")
    name = preset or cfg['preset'] or (None if cfg['wholeDrive'] else DEFAULT_PRESET)
    parameters = ApplyOverrides(GetPreset(name) if name else {}, cfg['parameters'])
    if isinstance(sets, (str, bytes)):
        raise TypeError("ResolveParameters: 'sets' must be a list of 'KEY=VALUE' strings, got a single string")
    overrides: Dict[str, float] = {}
    for item in sets:
        if isinstance(item, str):
            key, value = ParseSetOption(item)
        elif isinstance(item, tuple) and len(item) == 2:
            key, value = _CheckKey('ResolveParameters', item[0]), _ParseQuantity(item[0], item[1], 'ResolveParameters')
        else:
            raise TypeError(f"ResolveParameters: each of 'sets' must be 'KEY=VALUE' or (key, value), got {item!r}")
        overrides.pop(key, None)      # a repeated key: the last one wins, in its new position
        overrides[key] = value
    _RejectAlternatives(overrides, 'ResolveParameters: the overrides (--set)')
    parameters = ApplyOverrides(parameters, overrides)
    locations = cfg.get('locations', {})
    _CheckChain(parameters, {k: v for k, v in locations.items() if k not in overrides})
    sources = {k: '--set' if k in overrides else locations.get(k, f'preset {name}') for k in parameters}
    return parameters, sources


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
