"""The parameter registry: every parameter of a flat parameter set declared once.

Each :class:`Parameter` carries its name, SI unit (pint syntax), range, kind of value, the quantity whose
alternative forms it belongs to (``mu`` | ``rho``, ``dV`` | ``DV``, ``dT`` | ``DT`` | ``DTV``), its table and
key in a whole-drive file, a short label for axes and table heads, and a one-line description. Everything
else derives from :data:`PARAMETERS`: the range checks of :func:`~exudyn_worm.drive.presets.CheckParameters`, the
unit parsing of :func:`~exudyn_worm.drive.config.ParseQuantity` and ``--set``, the drive-file mapping of
:mod:`exudyn_worm.params.drivefile`, the messages for unknown keys, the axis labels of studies and the parameter
table of docs/parameters.md (:meth:`ParameterRegistry.MarkdownTable`).

To add a key, declare it in :data:`PARAMETERS` below (or, at run time, ``PARAMETERS.Declare(Parameter(...))``)::

    Parameter('muStatic', '', 'nonNegative', 'static flank friction coefficient', table='gear',
              fileKey='staticFrictionCoefficient')
    Parameter('frictionLaw', kind='choice', choices=('constant', 'stribeck', 'agma', 'table'),
              description='friction law of the flank contact', table='gear', fileKey='frictionLaw')
    Parameter('frictionTable', kind='table', columns=(('speed', 'm/s', 'nonNegative'), ('mu', '', 'nonNegative')),
              description='sliding speed and friction coefficient', table='gear', fileKey='frictionTable')

Kinds of value (parsed by :meth:`ParameterRegistry.Parse`, checked by :meth:`ParameterRegistry.Check`):

- ``'number'``: a real number in ``unit`` (SI; angles in rad); a string carries its own unit (``"0.5 mm"``,
  ``"8 deg"``, ``"472.5 rpm"``) and is converted by pint. Ranges: :data:`RANGES`. In text and drive files a plain
  number of an angle, an angular speed or a length is refused (zero excepted): :data:`UNIT_REQUIRED`.
- ``'choice'``: a string, one of ``choices``.
- ``'table'``: a file path (a string) or rows of numbers, one per row with one value per entry of
  ``columns`` (``(name, unit, range)``); each value parsed like a number in its column's unit, the first
  column strictly increasing. From ``--set`` or a string, an inline TOML array ``"[[0, 0.1], [1, 0.05]]"``.

A *series* parameter (``series=4``) stands for the numbered keys ``J4, J5, J6, ...`` (the drive-side chain of
Figure 19): its ``name`` is the prefix (``'J'``), it is listed under its first key (``J4``) and in a drive file
it is a key of the array of tables ``table`` (``[[driveSide]]``), entry i giving number ``series + i``. The
load-side chain is the series ``JL1, kL1, dL1, JL2, ...`` (prefix ``'JL'``, ``series=1``, ``[[loadSide]]``).
"""
from __future__ import annotations

import functools
import math
import pathlib
import re
import sys
import tokenize
from collections.abc import Mapping as _MappingABC
from dataclasses import dataclass
from numbers import Real
from typing import Any, Dict, Iterable, Iterator, List, Mapping, Optional, Tuple

from .._checks import CheckAngle, CheckNonNegative, CheckPositive, CheckRange, CheckReal, Suggest

__all__ = ['KINDS', 'RANGES', 'UNIT_REQUIRED', 'ParameterError', 'Parameter', 'ParameterRegistry', 'PARAMETERS',
           'ParametersMarkdown', 'WithGeneratedTables', 'MAX_STAGES']

#: the most stages of one chain (``J4, J5, ...``; ``JL1, JL2, ...``): the linear analysis of 100 stages takes a few
#: seconds, its cost grows with the cube of the number of stages (300 stages: half a minute)
MAX_STAGES = 100


class MissingParameterError(ValueError):
    """A parameter set lacks parameters a model needs; ``keys`` names them (the CLI adds where to put them).

    Parameters
    ----------
    message : str
        The error message.
    keys : iterable of str
        The missing parameter keys (kept as the tuple ``keys``).
    """

    def __init__(self, message: str, keys: Iterable[str]):
        super().__init__(message)
        self.keys = tuple(keys)


class ParameterError(ValueError):
    """A value of a parameter set is refused; ``keys`` names the keys it is about (the first one the value at fault),
    so that a drive can name where they came from (a drive file's line, :meth:`At`).

    Parameters
    ----------
    where : str
        Who refuses it (the function, or the location of the value).
    detail : str
        What is wrong: the key, the expected range and unit, the value received.
    keys : iterable of str
        The parameter keys the message is about.
    """

    def __init__(self, where: str, detail: str, keys: Iterable[str]):
        super().__init__(f"{where}: {detail}")
        self.where, self.detail, self.keys = where, detail, tuple(keys)

    def At(self, where: str) -> 'ParameterError':
        """The same error said at ``where`` (a drive file's ``"LoadConfig: 'f.toml', line 7: [gear] key"``).

        Parameters
        ----------
        where : str
            The new prefix.

        Returns
        -------
        ParameterError
        """
        return ParameterError(where, self.detail, self.keys)


#: kinds of value a parameter may take
KINDS = ('number', 'choice', 'table')

#: ranges of a number -> the text shown in the docs
RANGES = {'positive': '> 0', 'nonNegative': '>= 0', 'angle': '(0, pi/2)', 'angleFromZero': '[0, pi/2)',
          'count': 'whole number >= 1', 'finite': 'finite'}

#: SI units of the quantities that drive engineers read in another unit, so that a number copied from a data sheet,
#: a nameplate or a drawing is easily meant in it: a plain number of such a quantity in a drive file, ``--set`` or
#: ``--vary`` is refused (zero excepted). SI unit -> (the quantity, the other unit, its factor to SI, the units a
#: value may take). Every other quantity (inertia, stiffness, damping, mass, torque, time, sliding speed) is printed
#: in its SI unit or a decimal multiple of it, and a plain number there is SI; see docs/drive-files.md, "Values".
UNIT_REQUIRED: Dict[str, Tuple[str, str, float, str]] = {
    'rad': ('an angle', 'deg', math.pi / 180., '"20 deg" or "0.349 rad"'),
    'rad/s': ('an angular speed', 'rpm', math.pi / 30., '"472.5 rpm" (= 1/min), "49.48 rad/s" or "2830 deg/s"'),
    'm': ('a length', 'mm', 1e-3, '"18.05 mm" or "0.01805 m" (also um, cm)'),
}


@dataclass(frozen=True)
class Parameter:
    """One parameter: everything the package knows about a key of a flat parameter set.

    Parameters
    ----------
    name : str
        The key (``'kT'``); for a series the prefix (``'J'`` for ``J4, J5, ...``).
    unit : str
        SI unit in pint syntax (``'N*m/rad'``, ``'kg*m^2'``); ``''`` for a dimensionless number or a value that
        is not a number.
    range : str
        One of :data:`RANGES` (numbers only).
    description : str
        One line for the docs and messages.
    kind : str
        One of :data:`KINDS`.
    quantity : str
        Label of the quantity this key is one form of (``'flank friction'``): keys with the same quantity are
        alternative forms; a set may hold one of them, and setting one drops the others. ``''``: none.
    forms : tuple of str
        For a quantity given by groups of keys (the gear geometry: ``r1 r2 gamma`` or ``a u gamma`` or
        ``mx z1 z2 q``): the groups this key belongs to. Two keys of the quantity are then alternatives only if
        no group holds both (``a`` and ``gamma`` go together, ``a`` and ``r1`` do not).
    table : str
        Drive-file table (``'gear'``; the array of tables for a series); ``''``: only in ``[parameters]``.
    fileKey : str
        Key in that table (``'frictionCoefficient'``).
    label : str
        Short label for axes and table heads; default the name (the first key for a series).
    choices : tuple of str
        The allowed strings of a ``'choice'``.
    columns : tuple of (str, str, str)
        ``(name, unit, range)`` of each column of a ``'table'``.
    series : int
        0 for a single key; else the first number of a numbered series (4: ``J4, J5, ...``).
    displayUnit : str
        Unit shown on plot axes if not the SI unit (``'mm'`` for the backlash), with ``displayFactor``.
    displayFactor : float
        Factor from the SI value to ``displayUnit``.
    """

    name: str
    unit: str = ''
    range: str = 'finite'
    description: str = ''
    kind: str = 'number'
    quantity: str = ''
    forms: Tuple[str, ...] = ()
    table: str = ''
    fileKey: str = ''
    label: str = ''
    choices: Tuple[str, ...] = ()
    columns: Tuple[Tuple[str, str, str], ...] = ()
    series: int = 0
    displayUnit: str = ''
    displayFactor: float = 1.

    def __post_init__(self):
        w = 'Parameter'
        if not isinstance(self.name, str) or not re.match(r'^[A-Za-z][A-Za-z0-9]*$', self.name):
            raise ValueError(f"{w}: 'name' must be an identifier of letters and digits, got {self.name!r}")
        if self.kind not in KINDS:
            raise ValueError(f"{w}: 'kind' of {self.name!r} must be one of {', '.join(KINDS)}, got {self.kind!r}")
        if self.range not in RANGES:
            raise ValueError(f"{w}: 'range' of {self.name!r} must be one of {', '.join(RANGES)}, got {self.range!r}")
        if self.kind == 'choice' and not (self.choices and all(isinstance(c, str) for c in self.choices)):
            raise ValueError(f"{w}: the choice {self.name!r} needs 'choices', a tuple of strings, got {self.choices!r}")
        if self.kind == 'table' and not (self.columns and all(len(c) == 3 and c[2] in RANGES for c in self.columns)):
            raise ValueError(f"{w}: the table {self.name!r} needs 'columns', tuples (name, unit, range), "
                             f"got {self.columns!r}")
        if self.series and self.kind != 'number':
            raise ValueError(f"{w}: a series ({self.name!r}) must be of kind 'number'")
        if self.forms and not self.quantity:
            raise ValueError(f"{w}: {self.name!r} has 'forms' but no 'quantity' they are forms of")
        if bool(self.table) != bool(self.fileKey):
            raise ValueError(f"{w}: {self.name!r} needs both 'table' and 'fileKey' or neither")

    @property
    def key(self) -> str:
        """The key under which the parameter is listed: the name, or the first key of a series (``J4``)."""
        return f'{self.name}{self.series}' if self.series else self.name

    @property
    def shortLabel(self) -> str:
        """The label for axes and table heads (``label``, else :attr:`key`)."""
        return self.label or self.key

    @property
    def rangeText(self) -> str:
        """The range for the docs: ``> 0``, ``(0, pi/2)``, ``one of: a, b``, ..."""
        if self.kind == 'choice':
            return 'one of: ' + ', '.join(self.choices)
        if self.kind == 'table':
            return 'file path, or rows (' + ', '.join(f"{n} {u or '–'} {RANGES[r]}" for n, u, r in self.columns) + ')'
        return RANGES[self.range]


class _Units(dict):
    """The unit of every listed key; besides them it knows every key of a series (``J12`` -> ``kg*m^2``)."""

    def __init__(self, registry: 'ParameterRegistry'):
        super().__init__()
        self._registry = registry

    def __contains__(self, key):
        return dict.__contains__(self, key) or self._registry.Get(key) is not None

    def __missing__(self, key):
        parameter = self._registry.Get(key)
        if parameter is None:
            raise KeyError(key)
        return parameter.unit

    def get(self, key, default=None):
        return self[key] if key in self else default


def _MarkdownUnit(unit: str) -> str:
    """A unit in a Markdown table cell: '–' for none, its asterisks escaped (``N*m*s/rad`` is no emphasis)."""
    return unit.replace('*', '\\*') if unit else '–'


class ParameterRegistry:
    """The parameters of a flat parameter set, each declared once; see the module docstring.

    Parameters
    ----------
    parameters : iterable of Parameter
        Declared in order (the order of listings, messages and the docs).
    seriesText : str or mapping
        What a series stands for, in messages: ``'drive-side chain'``; a mapping gives one text per array of
        tables (``{'driveSide': 'drive-side chain', 'loadSide': 'load-side chain'}``).
    """

    def __init__(self, parameters=(), seriesText: Any = 'series'):
        self._byName: Dict[str, Parameter] = {}
        self._series: Dict[str, Parameter] = {}
        self.seriesText = seriesText
        #: key -> SI unit (a live view: a declared key appears at once); the public ``PARAMETER_UNITS``
        self.units = _Units(self)
        #: drive-file table -> {file key: parameter key}, for single keys (the public ``DRIVE_FILE_TABLES``)
        self.fileTables: Dict[str, Dict[str, str]] = {}
        #: array of tables -> {file key: series prefix} (``{'driveSide': {'inertia': 'J', ...}}``)
        self.arrayTables: Dict[str, Dict[str, str]] = {}
        for parameter in parameters:
            self.Declare(parameter)

    # -- declaring and finding --------------------------------------------------------------------------------
    def Declare(self, parameter: Parameter) -> Parameter:
        """Add ``parameter``; its name, listed key and drive-file key must be new.

        Parameters
        ----------
        parameter : Parameter
            The new parameter.

        Returns
        -------
        Parameter
            ``parameter``.

        Raises
        ------
        TypeError, ValueError
            For a non-Parameter or a name, key or drive-file key already declared.
        """
        w = 'ParameterRegistry.Declare'
        if not isinstance(parameter, Parameter):
            raise TypeError(f"{w}: 'parameter' must be a Parameter, got {type(parameter).__name__}")
        if parameter.name in self._series or parameter.key in self or (parameter.series and any(
                self._SeriesMatch(k, parameter) for k in self._byName)):
            raise ValueError(f"{w}: {parameter.key!r} is declared already")
        tables = self.arrayTables if parameter.series else self.fileTables
        if parameter.table and parameter.fileKey in tables.get(parameter.table, {}):
            raise ValueError(f"{w}: [{parameter.table}] {parameter.fileKey} is declared already")
        if parameter.series:
            self._series[parameter.name] = parameter
        self._byName[parameter.key] = parameter
        dict.__setitem__(self.units, parameter.key, parameter.unit)
        if parameter.table:
            tables.setdefault(parameter.table, {})[parameter.fileKey] = parameter.name
        return parameter

    @staticmethod
    def _SeriesMatch(key, parameter: Parameter) -> bool:
        match = re.match(r'^([A-Za-z]+?)([1-9][0-9]*)$', key) if isinstance(key, str) else None
        return bool(match and match.group(1) == parameter.name and int(match.group(2)) >= parameter.series)

    def SeriesText(self, table: str) -> str:
        """What the series of the array of tables ``table`` stands for, in messages (``'load-side chain'``).

        Parameters
        ----------
        table : str
            An array of tables (``'driveSide'``).

        Returns
        -------
        str
        """
        if isinstance(self.seriesText, str):
            return self.seriesText
        return self.seriesText.get(table, 'series')

    def SeriesIndex(self, key) -> Optional[Tuple[str, int]]:
        """``(prefix, number)`` of a series key (``'k5'`` -> ``('k', 5)``), else None.

        Parameters
        ----------
        key : object
            A parameter key.

        Returns
        -------
        (str, int) or None
        """
        if not isinstance(key, str):
            return None
        match = re.match(r'^([A-Za-z]+?)([1-9][0-9]*)$', key)
        if match and match.group(1) in self._series and int(match.group(2)) >= self._series[match.group(1)].series:
            return match.group(1), int(match.group(2))
        return None

    def Series(self, prefix: str) -> Parameter:
        """The series parameter of ``prefix`` (``'J'`` -> the one of ``J4, J5, ...``).

        Parameters
        ----------
        prefix : str
            The series' name.

        Returns
        -------
        Parameter

        Raises
        ------
        KeyError
            If ``prefix`` names no series.
        """
        return self._series[prefix]

    def Get(self, key) -> Optional[Parameter]:
        """The :class:`Parameter` of ``key`` (a series key gives its series), or None for an unknown key.

        Parameters
        ----------
        key : object
            A parameter key.

        Returns
        -------
        Parameter or None
        """
        if isinstance(key, str) and key in self._byName:
            return self._byName[key]
        series = self.SeriesIndex(key)
        return self._series[series[0]] if series else None

    def __getitem__(self, key) -> Parameter:
        parameter = self.Get(key)
        if parameter is None:
            raise KeyError(key)
        return parameter

    def __contains__(self, key) -> bool:
        return self.Get(key) is not None

    def __iter__(self) -> Iterator[Parameter]:
        return iter(self._byName.values())

    def Keys(self) -> Tuple[str, ...]:
        """The listed keys in declaration order (a series under its first key, ``J4``).

        Returns
        -------
        tuple of str
        """
        return tuple(self._byName)

    def KeysOf(self, *tables: str) -> Tuple[str, ...]:
        """The listed keys whose drive-file table is one of ``tables``, in declaration order.

        Parameters
        ----------
        *tables : str
            Drive-file tables (``'load'``, ``'motor'``; ``'driveSide'`` gives ``J4 k4 d4``).

        Returns
        -------
        tuple of str
        """
        return tuple(p.key for p in self if p.table in tables)

    # -- alternative forms ------------------------------------------------------------------------------------
    def Alternatives(self, key) -> Tuple[str, ...]:
        """The other forms of the quantity of ``key`` (``'dT'`` -> ``('DT', 'DTV')``); empty if none.

        Parameters
        ----------
        key : str
            A parameter key.

        Returns
        -------
        tuple of str
        """
        parameter = self.Get(key)
        if parameter is None or not parameter.quantity:
            return ()
        return tuple(p.key for p in self if p.quantity == parameter.quantity and p.key != key
                     and not set(p.forms) & set(parameter.forms))

    def Forms(self, quantity: str) -> Dict[str, Tuple[str, ...]]:
        """The forms of a quantity given by groups of keys: form -> its keys, in declaration order.

        Parameters
        ----------
        quantity : str
            The label of the quantity (``'gear geometry'``).

        Returns
        -------
        dict
            E.g. ``{'radii': ('gamma', 'r1', 'r2'), 'centre distance': ('gamma', 'a', 'u'), ...}``; empty for a
            quantity without forms.
        """
        groups: Dict[str, List[str]] = {}
        for p in self:
            if p.quantity == quantity:
                for form in p.forms:
                    groups.setdefault(form, []).append(p.key)
        return {form: tuple(keys) for form, keys in groups.items()}

    def FormsText(self, key) -> str:
        """The forms of the quantity of ``key`` as text (``'gamma, r1, r2 (radii); or gamma, a, u (centre
        distance); ...'``); ``''`` for a key without forms.

        Parameters
        ----------
        key : str
            A parameter key.

        Returns
        -------
        str
        """
        parameter = self.Get(key)
        if parameter is None or not parameter.forms:
            return ''
        return '; or '.join(f"{', '.join(keys)} ({form})" for form, keys in self.Forms(parameter.quantity).items())

    def Quantity(self, key) -> str:
        """The label of the quantity ``key`` is one form of (``'flank friction'``), ``''`` if none.

        Parameters
        ----------
        key : str
            A parameter key.

        Returns
        -------
        str
        """
        parameter = self.Get(key)
        return parameter.quantity if parameter else ''

    def Conflicts(self, parameters: Mapping[str, Any]) -> List[Tuple[str, Tuple[str, ...]]]:
        """Keys of ``parameters`` given together with one of their alternative forms.

        Parameters
        ----------
        parameters : mapping
            A flat parameter dictionary.

        Returns
        -------
        list of (str, tuple of str)
            ``[(key, (others, ...))]``, each group once, in the order of the keys (``key`` is the first of its
            group in ``parameters``).
        """
        found, seen = [], set()
        for key in parameters:
            if key in seen:
                continue
            alternatives = self.Alternatives(key)
            others = tuple(k for k in parameters if k in alternatives)
            if others:
                found.append((key, others))
                seen.update((key,) + others)
        return found

    # -- messages, labels, drive files ------------------------------------------------------------------------
    def UnknownKeyMessage(self, where: str, key) -> str:
        """The message for an unknown key: ``where``, the key, a near miss and the known keys.

        Parameters
        ----------
        where : str
            Prefix of the message.
        key : object
            The key received.

        Returns
        -------
        str
        """
        keys = self.Keys()
        text = f"{where}: unknown parameter {key!r}{Suggest(key, keys)}; expected one of: {' '.join(keys)}"
        series = list(self._series.values())
        if series:
            groups = {}                                    # one group per array of tables (one chain each)
            for p in series:
                groups.setdefault(p.table, []).append(p)
            text += ' (and ' + '; '.join(
                f"{' '.join(f'{p.name}{p.series + 1}' for p in group)}, {group[0].name}{group[0].series + 2} ... "
                f"for a longer {self.SeriesText(group[0].table)}" for group in groups.values()) + ')'
        return text

    def ExpectedText(self, key) -> str:
        """What a value of ``key`` must be, for messages: ``'a length with its unit, e.g. "18.05 mm" or ...'``.

        Parameters
        ----------
        key : str
            A parameter key.

        Returns
        -------
        str
        """
        parameter = self[key]
        if parameter.kind == 'number':
            return _ExpectedText(parameter.unit)
        return parameter.rangeText

    def UnitRequired(self, key) -> bool:
        """True if a plain number of ``key`` (other than 0) is refused in text and drive files: an angle, an angular
        speed or a length (:data:`UNIT_REQUIRED`).

        Parameters
        ----------
        key : str
            A parameter key.

        Returns
        -------
        bool
        """
        parameter = self.Get(key)
        return parameter is not None and parameter.kind == 'number' and parameter.unit in UNIT_REQUIRED

    def AxisLabel(self, key: str, display: bool = True, dash: str = '–') -> Tuple[str, float]:
        """Axis label of ``key`` and the factor from SI to the unit shown.

        Parameters
        ----------
        key : str
            A parameter key.
        display : bool
            Show the parameter's ``displayUnit`` (``'backlash [mm]'``) instead of its SI unit.
        dash : str
            Shown in the brackets for a dimensionless key.

        Returns
        -------
        (str, float)
            E.g. ``('kT [N*m/rad]', 1.0)``, ``('backlash [mm]', 1000.0)``.
        """
        parameter = self[key]
        label = parameter.label or key
        if display and parameter.displayUnit:
            return f'{label} [{parameter.displayUnit}]', parameter.displayFactor
        return f'{label} [{parameter.unit or dash}]', 1.

    def FileKeyOf(self, key: str) -> str:
        """Where ``key`` goes in a drive file: ``'[wheel] inertia'``, ``'[[driveSide]] stiffness'`` for ``k5``,
        ``'[parameters] KEY'`` for a key without a table.

        Parameters
        ----------
        key : str
            A parameter key.

        Returns
        -------
        str
        """
        parameter = self.Get(key)
        if parameter is None or not parameter.table:
            return f'[parameters] {key}'
        table = f'[{parameter.table}]' if parameter.series else parameter.table
        return f'[{table}] {parameter.fileKey}'

    # -- values -----------------------------------------------------------------------------------------------
    def Parse(self, key: str, value: Any, where: str, fromFile: bool = False) -> Any:
        """Parse a value of ``key`` as a user wrote it (``--set``, a drive file, a ``(key, value)`` pair).

        Text and a drive file's numbers must carry the unit of a quantity in :data:`UNIT_REQUIRED` (an angle, an
        angular speed, a length): a plain number other than zero is refused there. A Python number (the API,
        ``fromFile`` False) is SI.

        Parameters
        ----------
        key : str
            A known parameter key.
        value : object
            A number or a string with a unit (number); a string (choice); a path or rows of numbers, or a
            string with an inline TOML array (table).
        where : str
            Prefix of error messages.
        fromFile : bool, optional
            True for a value read from a drive file: its plain numbers (TOML numbers, also in the rows of a
            table) follow the rule for text.

        Returns
        -------
        float, str or tuple of tuple of float
            The value in SI (number), the choice, the path or the rows as floats (table).

        Raises
        ------
        ValueError, TypeError
            For an unknown key, a malformed value, a wrong unit or a value out of range (a choice and a table
            are checked here; the range of a number is checked by :meth:`Check`, so that its message names the
            key's location in a drive file).
        """
        parameter = self.Get(key)
        if parameter is None:
            raise ValueError(self.UnknownKeyMessage(where, key))
        self._CheckStage(key, parameter, where)
        if parameter.kind == 'number':
            return _ParseNumber(key, value, parameter.unit, where, fromFile)
        if parameter.kind == 'choice':
            text = value.strip() if isinstance(value, str) else value
            self.Check(key, text, where)
            return text
        if isinstance(value, str) and value.strip().startswith('['):
            value, fromFile = _InlineArray(key, value, where), True     # text: its numbers follow the rule for text
        if isinstance(value, str):
            self.Check(key, value.strip(), where)
            return value.strip()
        rows = self._Rows(parameter, key, value, where)
        parsed = tuple(tuple(_ParseNumber(f'{key}[{i}] {name}', cell, unit, where, fromFile)
                             for cell, (name, unit, _) in zip(row, parameter.columns)) for i, row in enumerate(rows))
        return self.Check(key, parsed, where)

    def Check(self, key: str, value: Any, where: str) -> Any:
        """Check a parsed value of ``key`` against its kind and range; return it.

        Parameters
        ----------
        key : str
            A known parameter key.
        value : object
            The value (SI).
        where : str
            Prefix of error messages, e.g. ``parameter set: 'kT' must be > 0 N*m/rad, got -5 N*m/rad``.

        Returns
        -------
        object
            ``value``.

        Raises
        ------
        ValueError, TypeError
            For an unknown key or a value out of range or of the wrong type.
        """
        parameter = self.Get(key)
        if parameter is None:
            raise ValueError(self.UnknownKeyMessage(where, key))
        self._CheckStage(key, parameter, where)
        if parameter.kind == 'number':
            _CheckNumber(where, key, value, parameter.range, parameter.unit)
        elif parameter.kind == 'choice':
            if not isinstance(value, str) or value not in parameter.choices:
                got = f'{type(value).__name__} {value!r}' if not isinstance(value, str) else repr(value)
                raise ValueError(f"{where}: '{key}' must be one of: {', '.join(parameter.choices)}, got {got}"
                                 f"{Suggest(value, parameter.choices) if isinstance(value, str) else ''}")
        elif isinstance(value, str):
            if not value.strip():
                raise ValueError(f"{where}: '{key}' must be a file path or rows of "
                                 f"({', '.join(n for n, _, _ in parameter.columns)}), got an empty string")
        else:
            rows = self._Rows(parameter, key, value, where)
            for i, row in enumerate(rows):
                for cell, (name, unit, rangeName) in zip(row, parameter.columns):
                    _CheckNumber(where, f'{key}[{i}] {name}', cell, rangeName, unit)
            first = [float(row[0]) for row in rows]
            for i in range(1, len(first)):
                if not first[i] > first[i - 1]:
                    raise ValueError(f"{where}: '{key}': the {parameter.columns[0][0]} must increase from row to "
                                     f"row, got {first[i - 1]:g} then {first[i]:g} (rows {i - 1} and {i})")
        return value

    def _CheckStage(self, key: str, parameter: Parameter, where: str) -> None:
        """Refuse a numbered key (``J104``, ``kL101``) of a stage beyond :data:`MAX_STAGES` of its chain."""
        series = self.SeriesIndex(key)
        if series and series[1] - parameter.series + 1 > MAX_STAGES:
            raise ValueError(f"{where}: '{key}' is stage {series[1] - parameter.series + 1:,} of the "
                             f"{self.SeriesText(parameter.table)}, above the limit of {MAX_STAGES} stages")

    @staticmethod
    def _Rows(parameter: Parameter, key: str, value, where: str):
        n = len(parameter.columns)
        shape = f"rows of {n} values ({', '.join(c[0] for c in parameter.columns)})"
        if isinstance(value, (str, bytes, _MappingABC)) or not hasattr(value, '__len__'):
            raise TypeError(f"{where}: '{key}' must be a file path or {shape}, got {type(value).__name__} {value!r}")
        rows = list(value)
        if not rows:
            raise ValueError(f"{where}: '{key}' must have at least one row ({shape}), got none")
        for i, row in enumerate(rows):
            if isinstance(row, (str, bytes)) or not hasattr(row, '__len__') or len(row) != n:
                raise ValueError(f"{where}: '{key}': row {i} must hold {n} values "
                                 f"({', '.join(c[0] for c in parameter.columns)}), got {row!r}")
        return rows

    # -- docs -------------------------------------------------------------------------------------------------
    def MarkdownTable(self) -> str:
        """The parameter table in Markdown: key, unit, range, drive-file table and key, description.

        Returns
        -------
        str
            The table (its lines end with newlines).
        """
        lines = ['| key | SI unit | range | drive file | description |', '|---|---|---|---|---|']
        for p in self:
            key = f'`{p.key}`, `{p.name}{p.series + 1}`, ...' if p.series else f'`{p.key}`'
            where = f'`{self.FileKeyOf(p.key)}`' if p.table else '–'
            text = p.description
            others = self.Alternatives(p.key)
            if p.forms:
                forms = ' and '.join(p.forms) + (' forms' if len(p.forms) > 1 else ' form')
                text += f" (key of the {forms} of the {p.quantity}; give one form: {self.FormsText(p.key)})"
            elif others:
                text += f" (or give {' or '.join(f'`{k}`' for k in others)}: one form of the {p.quantity})"
            lines.append(f"| {key} | {_MarkdownUnit(p.unit)} | {p.rangeText} | {where} | {text} |")
        return '\n'.join(lines) + '\n'

    def DriveFileMarkdownTable(self) -> str:
        """The table of drive-file tables and keys in Markdown: table, key, parameter, description, SI unit.

        Returns
        -------
        str
            The table (its lines end with newlines); the keys without a drive-file table are left out.
        """
        lines = ['| table | key | parameter | meaning | SI unit |', '|---|---|---|---|---|']
        last = None
        for p in sorted((p for p in self if p.table), key=lambda p: list(self._Tables()).index(p.table)):
            table = (f'`[[{p.table}]]`' if p.series else f'`[{p.table}]`') if p.table != last else ''
            last = p.table
            key = f'`{p.key}`, `{p.name}{p.series + 1}`, ...' if p.series else f'`{p.key}`'
            others = [f'`{o.fileKey}`' for o in map(self.Get, self.Alternatives(p.key)) if o.table]
            text = p.description + (f" (one form of the {p.quantity}, see below)" if p.forms else
                                    f" (or {' or '.join(others)})" if others else '')
            lines.append(f"| {table} | `{p.fileKey}` | {key} | {text} | {_MarkdownUnit(p.unit)} |".replace('|  |', '| |'))
        return '\n'.join(lines) + '\n'

    def _Tables(self) -> Dict[str, None]:
        """The drive-file tables in the order of their first parameter."""
        return dict.fromkeys(p.table for p in self if p.table)


# -- numbers with units (pint, loaded on first use only) ----------------------------------------------------

# a number (no inf/nan) followed by an optional unit expression
_NUMBER_UNIT = re.compile(r'^\s*([+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)\s*(.*?)\s*$')

# human form of each target unit for messages
_UNIT_TEXT = {'': 'a dimensionless number (plain, or e.g. "1.4 %")',
              'N*m/rad': 'in N*m/rad (N*m is accepted; e.g. "7 kN*m")',
              'N*m*s/rad': 'in N*m*s/rad (N*m*s is accepted)'}


def _ExpectedText(unit: str) -> str:
    if unit in UNIT_REQUIRED:
        what, _, _, units = UNIT_REQUIRED[unit]
        return f'{what} in {unit} (written with its unit, e.g. {units})'
    return _UNIT_TEXT.get(unit, f'in {unit} (plain numbers are SI)')


def _RefusePlain(key: str, value: float, text, target: str, where: str) -> None:
    """Refuse a plain number (not zero) of a quantity in :data:`UNIT_REQUIRED`, with both readings of it."""
    if target not in UNIT_REQUIRED or value == 0.:
        return
    what, other, factor, units = UNIT_REQUIRED[target]
    raise ValueError(f"{where}: '{key}' is {what} and needs its unit, e.g. {units}; got the plain number {text!r} "
                     f"(meant in {other}: {value:g} {other} = {value * factor:.4g} {target}; in {target}: {value:g} {target} = "
                     f"{value / factor:.4g} {other}); only 0 may be written without a unit")


@functools.lru_cache(maxsize=None)
def _UnitRegistry():
    """The pint registry, built on first use only (it takes about half a second)."""
    import pint  # lazy: pint costs about half a second at start-up
    return pint.UnitRegistry()


def _PintErrors() -> tuple:
    """Exceptions pint's unit parser raises for malformed text."""
    import pint  # lazy, see _UnitRegistry
    return (pint.errors.PintError, ValueError, TypeError, AttributeError, AssertionError, SyntaxError,
            ZeroDivisionError, OverflowError, tokenize.TokenError)


def _RadianExponent(units) -> float:
    """Power of radian in ``units`` expressed in base units (pint treats rad as dimensionless)."""
    ureg = _UnitRegistry()
    return dict(ureg.Quantity(1., units).to_base_units().unit_items()).get('radian', 0)


def _DimensionText(ureg, units, radians) -> str:
    """Dimension of ``units`` for messages, with the angle that pint drops shown as [angle]."""
    dim = ureg.Quantity(1., units).dimensionality
    parts = [] if not dim else [str(dim)]
    if radians:
        parts.insert(0, '[angle]' if radians == 1 else f'[angle] ** {radians:g}')
    return ' * '.join(parts) or 'dimensionless'


def _ParseNumber(key: str, text, target: str, where: str, fromFile: bool = False) -> float:
    """A number (SI) or a string with a unit, converted to ``target``; see :func:`~exudyn_worm.drive.config.ParseQuantity`.
    A plain number in text (or, with ``fromFile``, a file's number) of a quantity in :data:`UNIT_REQUIRED` is refused."""
    if isinstance(text, bool) or not isinstance(text, (str, Real)):
        raise TypeError(f"{where}: value of '{key}' must be a number or a string such as '0.5 mm', "
                        f"got {type(text).__name__} {text!r}")
    if isinstance(text, Real):
        value = float(text)
        if not math.isfinite(value):
            raise ValueError(f"{where}: '{key}' must be finite, got {value}")
        if fromFile:
            _RefusePlain(key, value, text, target, where)
        return value
    try:  # plain number: no unit registry needed
        value = float(text)
    except ValueError:
        pass
    else:
        if not math.isfinite(value):
            raise ValueError(f"{where}: '{key}' must be finite, got {text!r}")
        _RefusePlain(key, value, text.strip(), target, where)
        return value
    match = _NUMBER_UNIT.match(text)
    if match is None:
        first = text.split()[0] if text.split() else ''
        try:
            nonFinite = not math.isfinite(float(first))
        except ValueError:
            nonFinite = False
        if nonFinite:
            raise ValueError(f"{where}: '{key}' must be finite, got {text!r}")
        raise ValueError(f"{where}: '{key}' must be a number optionally followed by a unit, "
                         f"{_ExpectedText(target)}, got {text!r}")
    number, unitText = float(match.group(1)), match.group(2)
    if not math.isfinite(number):
        raise ValueError(f"{where}: '{key}' must be finite, got {text!r}")
    ureg = _UnitRegistry()
    try:
        units = ureg.parse_units(unitText)
    except _PintErrors() as err:
        detail = str(err).strip() or 'not a unit expression'
        raise ValueError(f"{where}: '{key}': cannot read the unit {unitText!r} in {text!r} ({detail}); "
                         f"expected {_ExpectedText(target)}") from None
    targetUnits = ureg.parse_units(target) if target else ureg.dimensionless
    radTarget, radReceived = _RadianExponent(targetUnits), _RadianExponent(units)
    wrong = (f"{where}: '{key}' must be {_ExpectedText(target)}, got {text!r} "
             f"(unit {units:~}, dimension {_DimensionText(ureg, units, radReceived)})")
    if radReceived != radTarget and not (radTarget < 0 and radReceived == 0):
        raise ValueError(wrong)
    try:
        value = float(ureg.Quantity(number, units).to(targetUnits).magnitude)
    except _PintErrors():
        raise ValueError(wrong) from None
    if not math.isfinite(value):
        raise ValueError(f"{where}: '{key}' must be finite, got {text!r}")
    return value


def _CheckNumber(where: str, key: str, value, rangeName: str, unit: str) -> float:
    """Check a number against one of :data:`RANGES`, naming ``key`` and ``unit``."""
    if rangeName == 'positive':
        return CheckPositive(where, key, value, unit)
    if rangeName == 'nonNegative':
        return CheckNonNegative(where, key, value, unit)
    if rangeName == 'angle':
        return CheckAngle(where, key, value)
    if rangeName == 'angleFromZero':
        return CheckRange(where, key, value, 0., 0.5 * math.pi, 'rad', highOpen=True)
    if rangeName == 'count':
        value = CheckRange(where, key, value, 1., None, unit)
        if not value.is_integer():
            raise ValueError(f"{where}: '{key}' must be a whole number >= 1 (a count of teeth or starts), got {value:g}")
        return value
    return CheckReal(where, key, value, unit)


def _InlineArray(key: str, text: str, where: str):
    """An inline TOML array such as ``[[0, 0.1], [1, 0.05]]`` (a table value given on the command line)."""
    if sys.version_info >= (3, 11):
        import tomllib  # lazy: tomllib from Python 3.11, tomli before
    else:  # pragma: no cover - Python 3.10
        import tomli as tomllib  # lazy: tomllib from Python 3.11, tomli before
    try:
        return tomllib.loads(f'value = {text.strip()}')['value']
    except tomllib.TOMLDecodeError as err:
        raise ValueError(f"{where}: '{key}': cannot read the array {text!r} ({err}); write it as in TOML, "
                         f"e.g. [[0, 0.1], [1, 0.05]]") from None


# -- the parameters of the package ---------------------------------------------------------------------------

#: every parameter of a flat parameter set, in the order of listings, messages and docs/parameters.md
PARAMETERS = ParameterRegistry([
    # the worm-gear mesh, eqs. (3)-(13)
    Parameter('alphaN', 'rad', 'angle', 'normal pressure angle', table='gear', fileKey='pressureAngle'),
    Parameter('gamma', 'rad', 'angle', 'pitch (lead) angle of the worm', quantity='gear geometry',
              forms=('radii', 'centre distance'), table='gear', fileKey='pitchAngle'),
    Parameter('mu', '', 'nonNegative', 'flank friction coefficient', quantity='flank friction', table='gear',
              fileKey='frictionCoefficient'),
    Parameter('rho', 'rad', 'angleFromZero', 'friction angle, eq. (13)', quantity='flank friction', table='gear',
              fileKey='frictionAngle'),
    Parameter('r1', 'm', 'positive', 'reference radius of the worm', quantity='gear geometry', forms=('radii',),
              table='gear', fileKey='wormRadius'),
    Parameter('r2', 'm', 'positive', 'reference radius of the wheel', quantity='gear geometry', forms=('radii',),
              table='gear', fileKey='wheelRadius'),
    # the gear geometry from its designation (DIN 3975 / ISO/TR 10828 names), exudyn_worm/model/geometry.py
    Parameter('a', 'm', 'positive', 'centre distance, a = r1 + r2', quantity='gear geometry',
              forms=('centre distance',), table='gear', fileKey='centreDistance', displayUnit='mm',
              displayFactor=1e3),
    Parameter('u', '', 'positive', 'transmission ratio z2/z1 = r2/(r1 tan(gamma)), eq. (3)', quantity='gear geometry',
              forms=('centre distance',), table='gear', fileKey='ratio'),
    Parameter('mx', 'm', 'positive', 'axial module of the worm (d1 = q mx, d2 = z2 mx)', quantity='gear geometry',
              forms=('designation',), table='gear', fileKey='axialModule', displayUnit='mm', displayFactor=1e3),
    Parameter('z1', '', 'count', 'number of starts (threads) of the worm', quantity='gear geometry',
              forms=('designation',), table='gear', fileKey='starts'),
    Parameter('z2', '', 'count', 'number of teeth of the wheel', quantity='gear geometry', forms=('designation',),
              table='gear', fileKey='wheelTeeth'),
    Parameter('q', '', 'positive', 'diameter quotient d1/mx of the worm (tan(gamma) = z1/q)', quantity='gear geometry',
              forms=('designation',), table='gear', fileKey='diameterQuotient'),
    Parameter('kV', 'N/m', 'positive', 'mesh stiffness, normal direction', table='gear', fileKey='meshStiffness'),
    Parameter('dV', 'N*s/m', 'nonNegative', 'mesh damping, normal direction', quantity='mesh damping',
              table='gear', fileKey='meshDamping'),
    Parameter('DV', '', 'nonNegative', 'mesh damping measure D_V, eq. (23)', quantity='mesh damping',
              table='gear', fileKey='meshDampingMeasure'),
    Parameter('backlash', 'm', 'nonNegative', 'total normal backlash delta', table='gear', fileKey='backlash',
              displayUnit='mm', displayFactor=1e3),
    # the friction law mu(v) over the sliding speed v = r1 |phi1'| / cos(gamma) (exudyn_worm.model.friction, docs/friction.md)
    Parameter('frictionLaw', kind='choice', choices=('constant', 'stribeck', 'agma', 'table'),
              description="friction law mu(v) of the flanks over the sliding speed (default constant: 'mu'; "
              "stribeck: 'mu' kinetic, 'muStatic', 'stribeckVelocity'; agma: ANSI/AGMA 6034-B92; table: "
              "'frictionTable')", table='gear', fileKey='frictionLaw'),
    Parameter('muStatic', '', 'nonNegative', "friction coefficient at rest of the Stribeck law (>= the kinetic 'mu')",
              table='gear', fileKey='staticFrictionCoefficient'),
    Parameter('stribeckVelocity', 'm/s', 'positive', 'sliding speed of the Stribeck law over which mu falls from '
              "'muStatic' to 'mu'", table='gear', fileKey='stribeckVelocity'),
    Parameter('frictionTable', kind='table', columns=(('speed', 'm/s', 'nonNegative'), ('mu', '', 'nonNegative')),
              description='measured (sliding speed, mu) points of the table law: a text file (relative to the drive '
              'file) or rows', table='gear', fileKey='frictionTable'),
    # the two-mass drive, Figure 2
    Parameter('J1', 'kg*m^2', 'positive', 'inertia on the worm shaft (worm, coupling, motor rotor)', table='worm',
              fileKey='inertia'),
    Parameter('J2', 'kg*m^2', 'positive', 'inertia on the wheel shaft (wheel and driven machine; with a load-side '
              'chain the wheel side only)', table='wheel',
              fileKey='inertia'),
    Parameter('kT', 'N*m/rad', 'positive', 'torsional stiffness of the drive shaft (motor to worm)',
              table='driveShaft', fileKey='stiffness'),
    Parameter('dT', 'N*m*s/rad', 'nonNegative', 'torsional damping of the drive shaft',
              quantity='drive-shaft damping', table='driveShaft', fileKey='damping'),
    Parameter('DT', '', 'nonNegative', 'torsional damping measure D_T, eq. (22)', quantity='drive-shaft damping',
              table='driveShaft', fileKey='dampingMeasure'),
    Parameter('DTV', '', 'nonNegative', "damping ratio D_TV = D_T / D_V, eq. (24), the charts' parameter",
              quantity='drive-shaft damping', table='driveShaft', fileKey='dampingMeasureRatio'),
    # the paper-reel changer, section 3.2
    Parameter('loadMass', 'kg', 'nonNegative', 'reel mass m2 on its lever (reel changer, eq. (27))', table='load',
              fileKey='mass'),
    Parameter('leverArm', 'm', 'nonNegative', 'lever arm l2 of that mass (reel changer, eq. (27))', table='load',
              fileKey='leverArm'),
    Parameter('motorSpeed', 'rad/s', 'positive', 'motor speed n0 (reel changer)', table='motor', fileKey='speed'),
    # duty cycles: what loads the wheel side and how the motor moves (default: the reel changer's lever, constant speed)
    Parameter('loadType', kind='choice', choices=('lever', 'constant', 'timeTable', 'angleTable', 'none'),
              description='the load: lever (mass on a lever, eq. (27); default), constant (loadTorque), timeTable '
              '(loadTorqueOverTime), angleTable (loadTorqueOverAngle) or none', table='load', fileKey='type'),
    Parameter('loadTorque', 'N*m', 'finite', 'constant load torque (loadType constant; < 0 opposes positive wheel '
              'rotation: lifting)', table='load', fileKey='torque'),
    Parameter('loadTorqueOverTime', kind='table', columns=(('time', 's', 'nonNegative'), ('torque', 'N*m', 'finite')),
              description='load torque over time, linear between rows, constant beyond (loadType timeTable)',
              table='load', fileKey='torqueOverTime'),
    Parameter('loadTorqueOverAngle', kind='table', columns=(('angle', 'rad', 'finite'), ('torque', 'N*m', 'finite')),
              description='load torque over the angle of the rotor it acts on (wheel or last load-side inertia), '
              'linear between rows, constant beyond (loadType angleTable)', table='load', fileKey='torqueOverAngle'),
    Parameter('motorType', kind='choice', choices=('constantSpeed', 'startStop', 'speedTable', 'characteristic'),
              description='the motor: constantSpeed (motorSpeed; default), startStop (motorSpeed, rampTime, '
              'brakeTime), speedTable (motorSpeedOverTime) or characteristic (stallTorque, noLoadSpeed, '
              'motorInertia)', table='motor', fileKey='type'),
    Parameter('rampTime', 's', 'positive', 'duration of the start and stop ramps (motorType startStop)',
              table='motor', fileKey='rampTime'),
    Parameter('brakeTime', 's', 'nonNegative', 'start of braking, >= rampTime (motorType startStop; absent: no stop)',
              table='motor', fileKey='brakeTime'),
    Parameter('motorSpeedOverTime', kind='table', columns=(('time', 's', 'nonNegative'), ('speed', 'rad/s', 'finite')),
              description='motor speed over time from t = 0, linear between rows, constant beyond (motorType '
              'speedTable)', table='motor', fileKey='speedOverTime'),
    Parameter('stallTorque', 'N*m', 'positive', 'motor torque at standstill of the line M = stallTorque (1 - omega / '
              'noLoadSpeed) (motorType characteristic)', table='motor', fileKey='stallTorque'),
    Parameter('noLoadSpeed', 'rad/s', 'positive', 'motor speed at zero torque of that line (motorType characteristic)',
              table='motor', fileKey='noLoadSpeed'),
    Parameter('motorInertia', 'kg*m^2', 'positive', 'inertia of the motor rotor on the motor side of the drive shaft '
              '(motorType characteristic)', table='motor', fileKey='inertia'),
    # the drive-side chain, Figure 19: worm J1 --(kT, dT)-- J4 --(k4, d4)-- J5 -- ... -- motor
    Parameter('J', 'kg*m^2', 'positive', 'drive-side chain of Figure 19: inertia4, inertia5, ... (optional)',
              table='driveSide', fileKey='inertia', series=4),
    Parameter('k', 'N*m/rad', 'positive', 'stiffness of spring-Damper4, ... on the motor side of inertia4, ...',
              table='driveSide', fileKey='stiffness', series=4),
    Parameter('d', 'N*m*s/rad', 'nonNegative', 'damping of spring-Damper4, ... (default 0)', table='driveSide',
              fileKey='damping', series=4),
    # the load-side chain, from the wheel to the driven machine: wheel J2 --(kL1, dL1)-- JL1 --(kL2, dL2)-- JL2 ...
    # (the load torque acts on the last inertia)
    Parameter('JL', 'kg*m^2', 'positive', 'load-side chain: inertia of stage i (JL1 next to the wheel, the last one '
              'carries the load torque; optional)', table='loadSide', fileKey='inertia', series=1),
    Parameter('kL', 'N*m/rad', 'positive', 'stiffness of the load shaft on the wheel side of JLi (kL1: wheel to JL1)',
              table='loadSide', fileKey='stiffness', series=1),
    Parameter('dL', 'N*m*s/rad', 'nonNegative', 'damping of that load shaft (default 0)', table='loadSide',
              fileKey='damping', series=1),
    # the worm's axial bearing, in series with the mesh
    Parameter('kA', 'N/m', 'nonNegative', "axial stiffness of the worm's bearing (optional; absent or 0: axially "
              "rigid worm)", table='axialBearing', fileKey='stiffness'),
    Parameter('dA', 'N*s/m', 'nonNegative', "axial damping of the worm's bearing (default 0)", table='axialBearing',
              fileKey='damping'),
    Parameter('mA', 'kg', 'positive', "the worm's axially moving mass (required with kA > 0)", table='axialBearing',
              fileKey='mass'),
    # the 3D model: worm and wheel as rigid bodies on elastic shaft bearings (docs/mesh-3d.md)
    Parameter('wormMass', 'kg', 'positive', 'mass of the worm body (3D model: required with [wormBearing])',
              table='worm', fileKey='mass'),
    Parameter('wheelMass', 'kg', 'positive', 'mass of the wheel body (3D model: required with [wheelBearing])',
              table='wheel', fileKey='mass'),
    *[Parameter(f'{body}{key[0].upper()}{key[1:]}', unit, rng, text.format(body=body, J=J), table=body, fileKey=key,
                quantity=f'{body} inertia', forms=(('given',) if key.endswith('Inertia') else ('shape',)))
      for body, J in (('worm', 'J1'), ('wheel', 'J2'))
      for key, unit, rng, text in (
          ('tiltInertia', 'kg*m^2', 'positive', "the {body} body's own moment of inertia about a line across its "
           "axis through its centre, >= polarInertia / 2 (3D model: required with [{body}Bearing], or the shape)"),
          ('polarInertia', 'kg*m^2', 'positive', "the {body} body's own moment of inertia about its axis, <= {J}; "
           "the rest of {J} turns with it without tilting (3D model; default {J}: all of it tilts with the body)"),
          ('radius', 'm', 'positive', "outer radius of the {body} body as a cylinder: with its mass and length it "
           "gives polarInertia and tiltInertia (3D model)"),
          ('innerRadius', 'm', 'nonNegative', "inner radius of the {body} body as a hollow cylinder (default 0: "
           "solid)"),
          ('length', 'm', 'positive', "length of the {body} body as a cylinder, along its axis (3D model; with "
           "radius)"))],
    *[Parameter(f'{body}{key[0].upper()}{key[1:]}', unit, rng, text.format(body=body), table=f'{body}Bearing',
                fileKey='span' if key == 'bearingSpan' else key)
      for body in ('worm', 'wheel')
      for key, unit, rng, text in (
          ('radialStiffness', 'N/m', 'positive', "stiffness of each of the {body}'s two radial bearings, across the "
           "axis (3D model; with axialStiffness)"),
          ('axialStiffness', 'N/m', 'positive', "stiffness of the {body}'s axial bearing (3D model; with "
           "radialStiffness)"),
          ('radialDamping', 'N*s/m', 'nonNegative', "damping of each of the {body}'s radial bearings (default 0)"),
          ('axialDamping', 'N*s/m', 'nonNegative', "damping of the {body}'s axial bearing (default 0)"),
          ('bearingSpan', 'm', 'positive', "distance of the {body}'s two radial bearings along the axis, centred on "
           "the mesh (default 0.1 m)"))],
], seriesText={'driveSide': 'drive-side chain', 'loadSide': 'load-side chain'})


def ParametersMarkdown(registry: Optional[ParameterRegistry] = None) -> str:
    """The text of docs/parameters.md, generated from the registry (a test compares it with the file).

    Parameters
    ----------
    registry : ParameterRegistry, optional
        Default :data:`PARAMETERS`.

    Returns
    -------
    str
    """
    registry = PARAMETERS if registry is None else registry
    return ('# Parameters\n\n'
            '<!-- generated by exudyn_worm.params.parameters.ParametersMarkdown(); do not edit: declare a parameter in\n'
            '     exudyn_worm/params/parameters.py and run `python -m exudyn_worm.params.parameters docs` -->\n\n'
            'Every key of a parameter set: the name that `--set KEY=VALUE`, the `[parameters]` table of a config '
            'file and the\nPython API take, its SI unit (a string value carries its own unit, e.g. `"8 deg"`, '
            '`"0.5 mm"`, `"472.5 rpm"`;\na plain number is SI, but in text and drive files an angle, an angular '
            'speed or a length needs its\nunit, zero excepted: [drive files, "Values"](drive-files.md#values)), '
            'the allowed range, and where it goes in a\nwhole-drive file (docs/drive-files.md). Keys marked as one form of a quantity are alternatives: '
            'a set gives one of them,\nand `ApplyOverrides` (and `--set`) replaces one form by another.\n\n'
            + registry.MarkdownTable())


_BEGIN, _END = '<!-- begin generated: {} -->\n', '<!-- end generated: {} -->\n'


def WithGeneratedTables(text: str, registry: Optional[ParameterRegistry] = None) -> str:
    """``text`` (a docs page) with its generated tables replaced by the registry's current ones.

    A table is generated between the lines ``<!-- begin generated: NAME -->`` and ``<!-- end generated: NAME -->``;
    NAME ``drive-file-table`` is :meth:`ParameterRegistry.DriveFileMarkdownTable`, ``parameter-table`` is
    :meth:`ParameterRegistry.MarkdownTable`.

    Parameters
    ----------
    text : str
        The page.
    registry : ParameterRegistry, optional
        Default :data:`PARAMETERS`.

    Returns
    -------
    str
    """
    registry = PARAMETERS if registry is None else registry
    for name, table in (('drive-file-table', registry.DriveFileMarkdownTable),
                        ('parameter-table', registry.MarkdownTable)):
        begin, end = _BEGIN.format(name), _END.format(name)
        if begin in text and end in text:
            head, rest = text.split(begin, 1)
            text = head + begin + table() + end + rest.split(end, 1)[1]
    return text


def _WriteDocs(folder: str) -> None:
    """Write docs/parameters.md and the generated tables of the other pages of ``folder``."""
    docs = pathlib.Path(folder)
    (docs / 'parameters.md').write_text(ParametersMarkdown())
    for page in sorted(docs.glob('*.md')):
        text = page.read_text()
        new = WithGeneratedTables(text)
        if new != text:
            page.write_text(new)


if __name__ == '__main__':
    if sys.argv[1:2] == ['docs']:   # python -m exudyn_worm.params.parameters docs [FOLDER]: regenerate the docs pages
        _WriteDocs(sys.argv[2] if len(sys.argv) > 2 else 'docs')
    else:
        sys.stdout.write(ParametersMarkdown())
