"""Whole-drive TOML files: one table per component of the drive, mapped onto the flat parameter keys.

A drive file describes a whole drive in the words of a drive engineer; :data:`DRIVE_FILE_TABLES` says which
file key becomes which parameter key of :mod:`exudyn_worm.drive.presets` (the keys that ``--set`` takes and the solver
receives). It is derived from the registry :data:`~exudyn_worm.params.parameters.PARAMETERS`, where each parameter
names its table and file key. The format requires no table or key: what a file leaves out comes from the
``preset`` it names; a file with component tables that names no preset inherits nothing, and a value the drive
needs but the file leaves out is reported missing (a flat ``[parameters]`` table without a preset is applied on
top of ``reel-P1``, see :mod:`exudyn_worm.drive.config`). Values are strings with units (``"18.05 mm"``,
``"8 deg"``, ``"472.5 rpm"``) or plain numbers in the key's SI unit, read by
:func:`exudyn_worm.drive.config.ParseQuantity`; an angle, an angular speed or a length needs its unit (zero excepted,
docs/drive-files.md, "Values").

Example (the reel changer at P1, parameter set (28))::

    description = "paper-reel changer, point P1"
    preset = "reel-P1"                    # optional base; what is given below replaces it

    [gear]                                # the worm-gear mesh, eqs. (3)-(13)
    pressureAngle = "20 deg"              # alphaN
    pitchAngle = "5.3228 deg"             # gamma
    frictionCoefficient = 0.132           # mu   (or frictionAngle = "8 deg")
    wormRadius = "18.05 mm"               # r1
    wheelRadius = "105.95 mm"             # r2
    meshStiffness = "2e8 N/m"             # kV
    meshDampingMeasure = 0.014            # DV, eq. (23) (or meshDamping = "21.47 kN*s/m")
    backlash = "0 mm"

    [worm]
    inertia = "0.1 kg*m^2"                # J1

    [wheel]
    inertia = "33 kg*m^2"                 # J2

    [driveShaft]                          # motor to worm
    stiffness = "7000 N*m/rad"            # kT
    dampingMeasure = 0.014                # DT, eq. (22) (or damping = "... N*m*s/rad", or dampingMeasureRatio)

    [load]                                # the reel's weight on a lever
    mass = "175 kg"
    leverArm = "1.2 m"

    [motor]
    speed = "472.5 rpm"

    [[driveSide]]                         # Figure 19: extra inertias and shafts on the drive side, in order
    inertia = "0.05 kg*m^2"               # J4
    stiffness = "2000 N*m/rad"            # k4
    damping = "0.1 N*m*s/rad"             # d4

    [[loadSide]]                          # wheel to driven machine, in order: wheel --kL1-- JL1 --kL2-- JL2 ...
    inertia = "0.5 kg*m^2"                # JL1 (the last stage carries the load torque)
    stiffness = "2e4 N*m/rad"             # kL1, the load shaft between wheel and JL1
    damping = "1 N*m*s/rad"               # dL1

    [axialBearing]                        # the worm's axial bearing, in series with the mesh
    stiffness = "1e8 N/m"                 # kA
    damping = "1e3 N*s/m"                 # dA
    mass = "3 kg"                         # mA

The flat form of earlier versions, a ``[parameters]`` table keyed by the parameter names, is still read; a
quantity given twice (in two tables, or as two forms such as ``frictionCoefficient`` and ``frictionAngle``)
is an error. docs/drive-files.md documents the format for users.
"""
from __future__ import annotations

import os
import re
import sys
from typing import Any, Dict, List, Mapping, Optional, Tuple, Union

from .._checks import Suggest as _Suggest
from .._files import ReadRegularFile
from .parameters import MAX_STAGES, PARAMETERS

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

__all__ = ['COMPONENT_TABLES', 'DRIVE_FILE_TABLES', 'DRIVE_SIDE_TABLE', 'DRIVE_SIDE_KEYS', 'LOAD_SIDE_TABLE',
           'LOAD_SIDE_KEYS', 'ARRAY_TABLES', 'TOP_LEVEL_KEYS', 'DriveSideKey', 'StageKey', 'FileKeyOf', 'FlattenDriveFile',
           'ReadDriveFile', 'MAX_FILE_BYTES', 'MAX_NESTING', 'MAX_KEYS']

#: file table -> {file key: parameter key}; the mapping from a drive file to the flat parameters, derived from the
#: ``table`` and ``fileKey`` of each parameter in the registry :data:`~exudyn_worm.params.parameters.PARAMETERS`
DRIVE_FILE_TABLES: Dict[str, Dict[str, str]] = PARAMETERS.fileTables

#: the arrays of tables (one stage of a chain each): table -> {file key: prefix of the numbered parameter key}
ARRAY_TABLES: Dict[str, Dict[str, str]] = PARAMETERS.arrayTables

#: every component table of a whole-drive file
COMPONENT_TABLES = tuple(DRIVE_FILE_TABLES) + tuple(ARRAY_TABLES)

#: the array of tables ``[[driveSide]]``: entry i (from 0) gives the keys with number 4 + i
DRIVE_SIDE_TABLE = 'driveSide'
#: file key -> letter of the numbered parameter key of a drive-side stage (J4, k4, d4, J5, ...)
DRIVE_SIDE_KEYS: Dict[str, str] = ARRAY_TABLES[DRIVE_SIDE_TABLE]
#: the array of tables ``[[loadSide]]`` (wheel to driven machine): entry i (from 0) gives JL<i+1>, kL<i+1>, dL<i+1>
LOAD_SIDE_TABLE = 'loadSide'
#: file key -> prefix of the numbered parameter key of a load-side stage (JL1, kL1, dL1, JL2, ...)
LOAD_SIDE_KEYS: Dict[str, str] = ARRAY_TABLES[LOAD_SIDE_TABLE]

#: keys allowed at the top of a file besides the tables
TOP_LEVEL_KEYS = ('preset', 'description', 'parameters')

#: the largest drive file read, in bytes (the shipped drives have a few kB; a friction table is a file of its own)
MAX_FILE_BYTES = 1_000_000
#: the deepest nesting of tables, arrays and inline tables in a drive file (a friction table inside a table is 4)
MAX_NESTING = 16
#: the most keys (and tables) in a drive file, counted over all its tables (the shipped drives have fewer than 100;
#: each key is located by its line for messages, a cost that grows with the square of their number)
MAX_KEYS = 1_000


def DriveSideKey(fileKey: str, index: int) -> str:
    """Parameter key of ``fileKey`` in the drive-side stage ``index`` (0 for the first ``[[driveSide]]``).

    Parameters
    ----------
    fileKey : str
        One of :data:`DRIVE_SIDE_KEYS` (``inertia``, ``stiffness``, ``damping``).
    index : int
        Position of the stage in the file, >= 0.

    Returns
    -------
    str
        ``J4``, ``k4``, ``d4`` for the first stage (Figure 19's inertia4 and spring-Damper4), then 5, 6, ...

    Examples
    --------
    >>> DriveSideKey('inertia', 0), DriveSideKey('stiffness', 1)
    ('J4', 'k5')
    """
    return StageKey(DRIVE_SIDE_TABLE, fileKey, index, 'DriveSideKey')


def StageKey(table: str, fileKey: str, index: int, where: str = 'StageKey') -> str:
    """Parameter key of ``fileKey`` in stage ``index`` (from 0) of the array of tables ``table``.

    Parameters
    ----------
    table : str
        One of :data:`ARRAY_TABLES` (``'driveSide'``, ``'loadSide'``).
    fileKey : str
        ``inertia``, ``stiffness`` or ``damping``.
    index : int
        Position of the stage in the file, >= 0.
    where : str, optional
        Function named in error messages.

    Returns
    -------
    str
        E.g. ``J4`` for the first ``[[driveSide]]`` inertia, ``kL2`` for the second ``[[loadSide]]`` stiffness.

    Examples
    --------
    >>> StageKey('loadSide', 'inertia', 0), StageKey('loadSide', 'stiffness', 1)
    ('JL1', 'kL2')
    """
    if table not in ARRAY_TABLES:
        raise ValueError(f"{where}: 'table' must be one of {', '.join(ARRAY_TABLES)}, got {table!r}")
    keys = ARRAY_TABLES[table]
    if fileKey not in keys:
        raise ValueError(f"{where}: 'fileKey' must be one of {', '.join(keys)}, got {fileKey!r}")
    if isinstance(index, bool) or not isinstance(index, int) or index < 0:
        raise ValueError(f"{where}: 'index' must be an integer >= 0, got {index!r}")
    return f'{keys[fileKey]}{PARAMETERS.Series(keys[fileKey]).series + index}'


def FileKeyOf(key: str) -> str:
    """Where parameter ``key`` goes in a drive file: its table and file key (the inverse of the mapping).

    Parameters
    ----------
    key : str
        A parameter key, e.g. ``'J2'``.

    Returns
    -------
    str
        E.g. ``'[wheel] inertia'``, ``'[[driveSide]] stiffness'`` for ``k4``; ``'[parameters] KEY'`` for a
        key that has no component table.

    Examples
    --------
    >>> FileKeyOf('J2'), FileKeyOf('r1'), FileKeyOf('k5')
    ('[wheel] inertia', '[gear] wormRadius', '[[driveSide]] stiffness')
    """
    return PARAMETERS.FileKeyOf(key)


class _Lines:
    """Finds the line of a key in the file's text, for messages (best effort: None where not found)."""

    def __init__(self, text: Optional[str]):
        self.lines = text.splitlines() if text else []

    def _HeaderLines(self, header: str) -> List[int]:
        pattern = re.compile(r'^\s*' + re.escape(header) + r'\s*(#.*)?$')
        return [i for i, line in enumerate(self.lines) if pattern.match(line)]

    def Header(self, table: str) -> Optional[int]:
        """1-based line of the first ``[table]`` or ``[[table]]`` header, or None."""
        found = self._HeaderLines(f'[{table}]') + self._HeaderLines(f'[[{table}]]')
        return min(found) + 1 if found else None

    def ArrayHeader(self, table: str, index: int) -> Optional[int]:
        """1-based line of the ``index``-th (from 0) ``[[table]]`` header, or None."""
        found = self._HeaderLines(f'[[{table}]]')
        return found[index] + 1 if index < len(found) else None

    def Find(self, table: Optional[str], key: str, index: int = 0, array: bool = False) -> Optional[int]:
        """1-based line of ``key`` in ``[table]`` (or in the ``index``-th ``[[table]]``), or None."""
        if table is None:
            start, headers = 0, [0]
        else:
            headers = self._HeaderLines(f'[[{table}]]' if array else f'[{table}]')
            if len(headers) <= index:
                return None
            start = headers[index] + 1
        keyPattern = re.compile(r'^\s*["\']?' + re.escape(key) + r'["\']?\s*=')
        for i in range(start, len(self.lines)):
            line = self.lines[i]
            if re.match(r'^\s*\[', line):       # the next table begins
                break
            if keyPattern.match(line):
                return i + 1
        return None


def _Where(where: str, line: Optional[int], path: str) -> str:
    return f"{where}, line {line}: {path}" if line else f"{where}: {path}"


def ReadDriveFile(path: Union[str, os.PathLike], where: str) -> Tuple[Dict[str, Any], str]:
    """Read and parse a drive file (TOML) within bounds: a regular file (never a FIFO, device or folder, which
    could block or never end), at most :data:`MAX_FILE_BYTES` bytes, nested at most :data:`MAX_NESTING` levels, with
    at most :data:`MAX_KEYS` keys and :data:`~exudyn_worm.params.parameters.MAX_STAGES` stages in each chain.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    where : str
        Prefix of error messages, e.g. ``"LoadConfig: 'drive.toml'"``.

    Returns
    -------
    (dict, str)
        The parsed document and its text.

    Raises
    ------
    ValueError
        One line naming the file and what is wrong (the limit it exceeds, the kind of file it is, the TOML error).
    """
    raw = ReadRegularFile(path, MAX_FILE_BYTES, where, 'a TOML drive file')     # never blocks, never without end
    try:
        text = raw.decode('utf-8-sig')          # a byte-order mark (some Windows editors write one) is no content
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise ValueError(f"{where}: not valid TOML: {err}") from None
    except UnicodeDecodeError as err:
        raise ValueError(f"{where}: not valid TOML (not UTF-8 text: {err.reason})") from None
    except ValueError as err:                   # e.g. an integer of more than 4300 digits
        raise ValueError(f"{where}: not valid TOML: {' '.join(str(err).split())}") from None
    except RecursionError:
        raise ValueError(f"{where}: nested deeper than the limit of {MAX_NESTING} levels (arrays or inline "
                         f"tables)") from None
    _CheckBounds(data, where)
    return data, text


def _CheckBounds(data: Mapping[str, Any], where: str) -> None:
    """The limits of :func:`ReadDriveFile` on a parsed document: nesting, keys, stages."""
    keys, todo = 0, [(data, 1)]
    while todo:
        value, depth = todo.pop()
        if depth > MAX_NESTING:
            raise ValueError(f"{where}: nested deeper than the limit of {MAX_NESTING} levels (tables, arrays or "
                             f"inline tables)")
        children = value.values() if isinstance(value, Mapping) else value
        keys += len(value) if isinstance(value, Mapping) else 0
        if keys > MAX_KEYS:
            raise ValueError(f"{where}: more than the limit of {MAX_KEYS:,} keys in a drive file")
        todo.extend((child, depth + 1) for child in children if isinstance(child, (Mapping, list)))
    for table in ARRAY_TABLES:
        stages = data.get(table)
        if isinstance(stages, list) and len(stages) > MAX_STAGES:
            raise ValueError(f"{where}: [[{table}]]: {len(stages):,} stages, above the limit of {MAX_STAGES} stages "
                             f"of a chain")


def FlattenDriveFile(data: Mapping[str, Any], where: str, text: Optional[str] = None
                     ) -> Tuple[Optional[str], List[Tuple[str, Any, str]]]:
    """Map the tables of a drive file onto parameter keys, without parsing the values.

    Parameters
    ----------
    data : mapping
        The parsed TOML document (``tomllib.load``).
    where : str
        Prefix of error messages, e.g. ``"LoadConfig: 'drive.toml'"``.
    text : str, optional
        The file's text, used to name the line of a bad key in messages.

    Returns
    -------
    (str or None, list of (str, value, str))
        The ``preset`` named by the file, and for every value its parameter key, its raw value (number or
        string) and the location to name in messages (``"LoadConfig: 'f.toml', line 7: [gear] wormRadius"``).

    Raises
    ------
    ValueError
        For an unknown table or key (with a suggestion for a near miss and the line where possible), a table
        that is not a table, an empty ``[[driveSide]]`` or ``[[loadSide]]`` table, a ``preset`` or ``description`` that is not a
        string, or one parameter given twice.
    """
    if not isinstance(data, Mapping):
        raise TypeError(f"{where}: a config must be a mapping, got {type(data).__name__}")
    lines = _Lines(text)
    known = list(TOP_LEVEL_KEYS) + list(DRIVE_FILE_TABLES) + list(ARRAY_TABLES)
    for key in data:
        if key not in known:
            line = lines.Find(None, key) or lines.Header(key)
            raise ValueError(f"{_Where(where, line, f'unknown top-level key or table {key!r}')}"
                             f"{_Suggest(key, known)}; expected one of: {', '.join(known)}")
    for key in ('preset', 'description'):
        if key in data and not isinstance(data[key], str):
            raise ValueError(f"{_Where(where, lines.Find(None, key), repr(key))} must be a string, "
                             f"got {type(data[key]).__name__} {data[key]!r}")

    values: List[Tuple[str, Any, str]] = []
    # the flat [parameters] table of earlier versions: keys are parameter keys (checked by the parser)
    flat = data.get('parameters', {})
    if not isinstance(flat, Mapping):
        raise ValueError(f"{_Where(where, lines.Find(None, 'parameters'), repr('parameters'))} must be a table "
                         f"([parameters]), got {type(flat).__name__} {flat!r}")
    for key, value in flat.items():
        values.append((key, value, _Where(where, lines.Find('parameters', key), f'[parameters] {key}')))

    for table, keys in DRIVE_FILE_TABLES.items():
        if table not in data:
            continue
        content = data[table]
        if not isinstance(content, Mapping):
            raise ValueError(f"{_Where(where, lines.Find(None, table), repr(table))} must be a table "
                             f"([{table}]), got {type(content).__name__} {content!r}")
        for fileKey, value in content.items():
            line = lines.Find(table, fileKey)
            if fileKey not in keys:
                raise ValueError(f"{_Where(where, line, f'[{table}]')}: unknown key {fileKey!r}"
                                 f"{_Suggest(fileKey, keys)}; expected one of: {', '.join(keys)}")
            values.append((keys[fileKey], value, _Where(where, line, f'[{table}] {fileKey}')))

    for table, keys in ARRAY_TABLES.items():
        values += _StageValues(data, table, keys, where, lines)

    seen: Dict[str, str] = {}
    for key, _, location in values:
        if key in seen:
            raise ValueError(f"{location}: '{key}' is given a second time (first at "
                             f"{seen[key][len(where):].lstrip(',: ')}); give it once")
        seen[key] = location
    return data.get('preset'), values


def _StageValues(data: Mapping[str, Any], table: str, keys: Mapping[str, str], where: str, lines: _Lines
                 ) -> List[Tuple[str, Any, str]]:
    """The values of the array of tables ``table`` (one stage of a chain each) as (parameter key, value, location)."""
    stages = data.get(table, [])
    if not isinstance(stages, list) or not all(isinstance(s, Mapping) for s in stages):
        line = lines.Find(None, table) or lines.Header(table)
        raise ValueError(f"{_Where(where, line, repr(table))} must be an array of tables ([[{table}]]), got "
                         f"{type(stages).__name__} {stages!r}")
    values = []
    for index, stage in enumerate(stages):
        label = f'[[{table}]] number {index + 1}'
        if not stage:        # every table is a stage: an empty one would silently shorten or shift the chain
            raise ValueError(f"{_Where(where, lines.ArrayHeader(table, index), label)}: the table is "
                             f"empty; each [[{table}]] table is one stage of the {PARAMETERS.SeriesText(table)} "
                             f"({StageKey(table, 'inertia', index)}, {StageKey(table, 'stiffness', index)}) and needs "
                             f"'inertia' and 'stiffness' ('damping' is optional); give them or remove the table")
        for fileKey, value in stage.items():
            line = lines.Find(table, fileKey, index, array=True)
            if fileKey not in keys:
                raise ValueError(f"{_Where(where, line, label)}: unknown key {fileKey!r}"
                                 f"{_Suggest(fileKey, keys)}; expected one of: {', '.join(keys)}")
            values.append((StageKey(table, fileKey, index), value, _Where(where, line, f'{label} {fileKey}')))
    return values
