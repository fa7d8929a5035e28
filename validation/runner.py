"""The validation runner: the package against the numbers printed in the paper (``python -m validation``).

Published values live in ``validation/<source>/reference.csv`` beside the scripts that analyse them, one
row per number or statement with its equation/section/figure, the phrase of the paper it checks (the
``rule`` column: one reading rule per phrase, see :data:`RULES` and ``validation/README.md``) and the
hypotheses its published number was used to identify (``identifies``). :func:`RunValidation` computes our
value for every row with the package's own functions and compares it with the interval the rule gives,
widened by the propagated rounding of the printed inputs (:func:`InputRounding`, the one function that
does this for every row). It writes the Markdown report only when asked (``reportPath``).

Checks come from *check groups*: a check group is a function ``Group(context) -> list[Check]`` that
computes the rows of its group (the ``group`` column) and returns one :class:`Check` per row (two for a
time-domain row: one per mesh reading), made with :meth:`ValidationContext.Compare`; it may add prose
sections to the report with :meth:`ValidationContext.AddSection`. Register a new group with
:func:`RegisterCheckGroup`. A group has a level: 0 runs always, 1 (slow: the simulations) is skipped by
``quick``, 2 (the slow forensic searches) runs only with ``full``. Every row of a group that ran must
receive a check, and every row must belong to a registered group, otherwise the row fails.

Verdicts
--------
PASS
    The comparison holds (for an ``exclusion`` row: the rejected reading is indeed outside the interval).
FAIL
    The comparison does not hold, the value is not finite, or the group crashed or computed no value.
    :attr:`ValidationSummary.passed` is then False.
DIFFERS
    The comparison does not hold, and the check is a known, explained model difference listed with its
    reason in ``validation/<source>/differences.csv`` (the one list). A listed check that passes is
    reported as stale (:attr:`ValidationSummary.stale`); a non-finite value is FAIL even when listed.
"""
from __future__ import annotations

import csv
import math
import re
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple, Union

from exudyn_worm._files import WriteTextAtomically
from exudyn_worm.drive.presets import PRESETS
from exudyn_worm.items.solve import IsInterrupt

from .model import (KINDS, READINGS, RULES, VERDICTS, Check, CheckGroup, Fmt, GroupFunction, HeadLine, ReferenceRow,
                    ValidationSummary)
from .report import Report

__all__ = ['VALIDATION_DIR', 'COMMITTED_REPORT', 'PAPER_MU', 'KINDS', 'RULES', 'READINGS', 'VERDICTS',
           'ReferenceRow', 'Check', 'ValidationContext', 'CheckGroup', 'ValidationSummary', 'CHECK_GROUPS',
           'RegisterCheckGroup', 'LoadReference', 'LoadKnownDifferences', 'HalfUnit', 'ReadingInterval',
           'InputRounding', 'RunValidation', 'WriteText', 'HeadLine', 'Fmt']

#: the validation data beside this module (``validation/<source>/reference.csv``)
VALIDATION_DIR = Path(__file__).resolve().parent
#: the committed report (written only by the explicit command of ``validation/README.md``)
COMMITTED_REPORT = VALIDATION_DIR / 'REPORT.md'

#: friction coefficient of the gear of set (28) as the paper computed b1..b4 and (19): the value printed
#: with (25), mu = 0.132 (rho = 7.996 deg, printed as "8 deg"); the 0.134 printed in (28) is rejected
PAPER_MU = PRESETS['reel-P1']['mu']

_COLUMNS = ('id', 'group', 'quantity', 'S', 'published', 'unit', 'source', 'rule', 'kind', 'inputs', 'identifies',
            'note')
_HYPOTHESES = ('mu', 'circ')
_CHART_FACTOR = 10**0.05


# --- reading rules -------------------------------------------------------------------------------------

def HalfUnit(text: str) -> float:
    """Half a unit of the last printed digit of a number given as text.

    Trailing zeros of a number printed without a decimal point are placeholders, not digits: "110" and
    "21470" are read to their last non-zero digit (the convention of ``validation/README.md``).

    Parameters
    ----------
    text : str
        The number as printed, e.g. ``'13.615'``, ``'1.279e5'``, ``'110'``.

    Returns
    -------
    float
        Half a unit of its last significant digit.

    Raises
    ------
    ValueError
        If ``text`` is not a decimal number.

    Examples
    --------
    >>> HalfUnit('13.615'), HalfUnit('1.279e5'), HalfUnit('63'), HalfUnit('-2.607e10'), HalfUnit('110')
    (0.0005, 50.0, 0.5, 5000000.0, 5.0)
    """
    m = re.fullmatch(r'\s*[-+]?(\d*)(?:(\.)(\d*))?(?:[eE]([-+]?\d+))?\s*', text)
    if m is None or not (m.group(1) or m.group(3)):
        raise ValueError(f"HalfUnit: 'text' must be a decimal number, got {text!r}")
    exponent = int(m.group(4) or 0)
    if m.group(2):
        return 0.5 * 10.0**(exponent - len(m.group(3)))
    digits = m.group(1)
    zeros = len(digits) - len(digits.rstrip('0')) if digits.strip('0') else 0
    return 0.5 * 10.0**(exponent + zeros)


def ReadingInterval(rule: str, publishedText: str, propagated: float = 0.) -> Tuple[float, float]:
    """The interval of values that agree with a published number or statement under its reading rule.

    Parameters
    ----------
    rule : str
        A key of :data:`RULES`.
    publishedText : str
        The published value as in ``reference.csv``: a number, ``'N-M'`` for ``range``, ``'many'`` for
        ``many-times``.
    propagated : float, optional
        Propagated rounding of the printed inputs (:func:`InputRounding`), added on both sides.

    Returns
    -------
    (float, float)
        Closed interval (lo, hi); ``inf`` for an open end.

    Raises
    ------
    ValueError
        For an unknown rule or a published text the rule cannot read.
    """
    if rule not in RULES:
        raise ValueError(f"ReadingInterval: 'rule' must be one of {', '.join(RULES)}, got {rule!r}")
    if rule == 'range':
        m = re.fullmatch(r'\s*([0-9.]+)\s*-\s*([0-9.]+)\s*', publishedText)
        if m is None:
            raise ValueError(f"ReadingInterval: rule 'range' needs 'N-M', got {publishedText!r}")
        lo, hi = float(m.group(1)), float(m.group(2))
    elif rule == 'many-times':
        if publishedText.strip() != 'many':
            raise ValueError(f"ReadingInterval: rule 'many-times' needs 'many', got {publishedText!r}")
        lo, hi = 3., math.inf
    elif rule == 'robustness':
        lo, hi = 0., 3.
    else:
        x, h = float(publishedText), HalfUnit(publishedText)
        if rule == 'printed':
            w = h
        elif rule == 'about':
            w = max(0.1 * abs(x), h)
        elif rule == 'virtually':
            if x == 0:                      # "ceased to exist": at most 10 % of the reference size
                return 0., 0.1 + propagated
            w = 0.1 * abs(x)
        elif rule == 'ratio':
            w = 0.05 * abs(x)
        elif rule == 'chart-bound-linear':  # a linear axis is read to the same absolute precision everywhere
            w = h
        elif rule == 'chart-bound':
            if h >= x * (_CHART_FACTOR - 1):
                w = h
            else:
                return x / _CHART_FACTOR - propagated, x * _CHART_FACTOR + propagated
        else:                               # comparison, none, yes-no: exact
            w = 0.
        lo, hi = x - w, x + w
    return lo - propagated, hi + propagated


def InputRounding(compute: Callable[[Dict[str, float]], float], parameters: Mapping[str, float],
                  printed: Mapping[str, Tuple[str, float]]) -> Dict[str, float]:
    """Propagate the half-unit rounding of printed inputs into a computed quantity (linear worst case).

    The one place where the printed digits of the inputs enter a tolerance: every analytical row, value
    or exclusion alike, gets its contributions from here.

    Parameters
    ----------
    compute : callable
        ``compute(parameters) -> float``, the quantity of the row.
    parameters : mapping
        The parameter set the row is computed with.
    printed : mapping
        ``{name: (text, factor)}``: the printed text of each rounded input and the factor from its printed
        unit to SI (e.g. ``('18.05', 1e-3)`` for r1 in mm); the parameter must equal ``float(text) * factor``.

    Returns
    -------
    dict
        ``{name: 0.5 |compute(p + h) - compute(p - h)|}`` with h half a unit of the printed digit.

    Raises
    ------
    ValueError
        If a parameter differs from its printed value (the rounding would be propagated around the
        wrong point).
    """
    parts = {}
    for name, (text, factor) in printed.items():
        value = float(text) * factor
        if not math.isclose(parameters[name], value, rel_tol=1e-12, abs_tol=1e-15):
            raise ValueError(f"InputRounding: parameter '{name}' = {parameters[name]!r} is not its printed value "
                             f"{text} (x {factor:g})")
        h = HalfUnit(text) * factor
        up, down = compute({**parameters, name: value + h}), compute({**parameters, name: value - h})
        parts[name] = 0.5 * abs(up - down)
    return parts


# --- reference data ------------------------------------------------------------------------------------

def _Nominal(rule: str, text: str) -> float:
    lo, hi = ReadingInterval(rule, text)
    return lo if math.isinf(hi) else 0.5 * (lo + hi) if rule == 'range' else float(text)


def LoadReference(validationDir: Optional[Path] = None) -> Dict[str, ReferenceRow]:
    """Read every ``<validationDir>/*/reference.csv``.

    Parameters
    ----------
    validationDir : Path, optional
        Directory holding one sub-directory per source; default :data:`VALIDATION_DIR`.

    Returns
    -------
    dict
        ``{id: ReferenceRow}`` in file order.

    Raises
    ------
    FileNotFoundError
        If there is no reference table.
    ValueError
        For a malformed table: missing column, duplicate id, unknown kind, rule or hypothesis, bad number.
    """
    validationDir = Path(VALIDATION_DIR if validationDir is None else validationDir)
    files = sorted(validationDir.glob('*/reference.csv'))
    if not files:
        raise FileNotFoundError(f"LoadReference: no '*/reference.csv' under {validationDir}")
    rows: Dict[str, ReferenceRow] = {}
    for path in files:
        with open(path, newline='') as f:
            reader = csv.DictReader(f)
            missing = [c for c in _COLUMNS if c not in (reader.fieldnames or [])]
            if missing:
                raise ValueError(f"LoadReference: {path} lacks column(s) {', '.join(missing)}")
            for n, r in enumerate(reader, start=2):
                where = f'{path}:{n}'
                if r['id'] in rows:
                    raise ValueError(f"LoadReference: duplicate id '{r['id']}' in {where}")
                if r['kind'] not in KINDS:
                    raise ValueError(f"LoadReference: 'kind' must be one of {', '.join(KINDS)}, got "
                                     f"'{r['kind']}' in {where}")
                identifies = frozenset(r['identifies'].split())
                if not identifies <= set(_HYPOTHESES):
                    raise ValueError(f"LoadReference: 'identifies' must name hypotheses among "
                                     f"{', '.join(_HYPOTHESES)}, got '{r['identifies']}' in {where}")
                try:
                    published = _Nominal(r['rule'], r['published'])
                    S = int(r['S']) if r['S'].strip() else None
                except ValueError as e:
                    raise ValueError(f"LoadReference: bad value in {where}: {e}") from None
                rows[r['id']] = ReferenceRow(r['id'], r['group'], r['quantity'], S, published, r['published'].strip(),
                                             r['unit'], r['source'], r['rule'], r['kind'], r['inputs'], identifies,
                                             r['note'], path)
    return rows


def LoadKnownDifferences(validationDir: Optional[Path] = None,
                         reference: Optional[Mapping[str, ReferenceRow]] = None) -> Dict[str, str]:
    """Read the list of known, explained model differences (``<validationDir>/*/differences.csv``).

    Parameters
    ----------
    validationDir : Path, optional
        Default :data:`VALIDATION_DIR`.
    reference : mapping, optional
        The reference rows; every listed check must name one (``id`` or ``id@paperMesh``).

    Returns
    -------
    dict
        ``{check id: reason}``.

    Raises
    ------
    ValueError
        For a check naming no reference row, a duplicate, or an empty reason.
    """
    validationDir = Path(VALIDATION_DIR if validationDir is None else validationDir)
    out: Dict[str, str] = {}
    for path in sorted(validationDir.glob('*/differences.csv')):
        with open(path, newline='') as f:
            for n, r in enumerate(csv.DictReader(f), start=2):
                checkId, reason = r['check'].strip(), r['reason'].strip()
                rowId, _, reading = checkId.partition('@')
                if reference is not None and rowId not in reference or reading not in ('', 'paperMesh'):
                    raise ValueError(f"LoadKnownDifferences: '{checkId}' in {path}:{n} names no reference row")
                if checkId in out or not reason:
                    raise ValueError(f"LoadKnownDifferences: duplicate '{checkId}' or empty reason in {path}:{n}")
                out[checkId] = reason
    return out


# --- checks --------------------------------------------------------------------------------------------

def _Holds(kind: str, computed: float, interval: Tuple[float, float]) -> bool:
    lo, hi = interval
    eps = 1e-12 * max(abs(lo) if math.isfinite(lo) else 0., abs(hi) if math.isfinite(hi) else 0.)
    within = lo - eps <= computed <= hi + eps
    return within if KINDS[kind] == 'match' else not within


@dataclass
class ValidationContext:
    """What a check group receives: the reference rows, the known differences, the run level and the report."""
    reference: Dict[str, ReferenceRow]
    known: Dict[str, str] = field(default_factory=dict)
    level: int = 1
    quiet: Optional[bool] = None
    sections: List[Tuple[str, str]] = field(default_factory=list)

    def Rows(self, group: str) -> List[ReferenceRow]:
        """The reference rows of ``group``."""
        return [r for r in self.reference.values() if r.group == group]

    def Row(self, rowId: str) -> ReferenceRow:
        """The reference row ``rowId`` (KeyError naming the id if absent)."""
        try:
            return self.reference[rowId]
        except KeyError:
            raise KeyError(f"no reference row with id '{rowId}'") from None

    def Compare(self, rowId: str, computed: float, propagated: Union[float, Mapping[str, float]] = 0.,
                detail: str = '', reading: str = '', uses: Iterable[str] = ('mu',)) -> Check:
        """Build the :class:`Check` of row ``rowId`` for our ``computed`` value.

        Parameters
        ----------
        rowId : str
            Reference row.
        computed : float
            Our value (1/0 for a yes/no statement).
        propagated : float or dict, optional
            Propagated rounding of the printed inputs, or its parts from :func:`InputRounding` (summed and
            listed in the detail).
        detail : str, optional
            Extra text for the report.
        reading : str, optional
            '' or one of :data:`READINGS` (time-domain rows).
        uses : iterable of str, optional
            Hypotheses the computation relies on (default: the friction mu = 0.132).

        Returns
        -------
        Check
        """
        row = self.Row(rowId)
        if isinstance(propagated, Mapping):
            if propagated:
                detail = '; '.join(filter(None, [detail, 'input rounding: ' + ', '.join(
                    f'{k} {v:.2g}' for k, v in propagated.items())]))
            propagated = sum(propagated.values())
        if reading not in ('',) + READINGS:
            raise ValueError(f"Compare: 'reading' must be '' or one of {', '.join(READINGS)}, got {reading!r}")
        computed = float(computed)
        interval = ReadingInterval(row.rule, row.publishedText, float(propagated))
        checkId = rowId + ('@paperMesh' if reading == 'paperMesh' else '')
        known = self.known.get(checkId, '')
        if not math.isfinite(computed):
            holds, verdict = False, 'FAIL'
            detail = '; '.join(filter(None, [detail, 'non-finite result']))
        else:
            holds = _Holds(row.kind, computed, interval)
            verdict = 'PASS' if holds else 'DIFFERS' if known else 'FAIL'
        return Check(row, computed, interval, verdict, holds, detail, reading, frozenset(uses), known)

    def AddSection(self, title: str, markdown: str) -> None:
        """Add a prose section to the report."""
        self.sections.append((title, markdown.strip() + '\n'))


#: the check groups run by :func:`RunValidation`, in report order
CHECK_GROUPS: List[CheckGroup] = [
    CheckGroup('analytical', 'validation.analytical:AnalyticalChecks', title='Analytical model: eqs. (3), (13), (16)-(24), Figures 4-5'),
    CheckGroup('eigenvalues', 'validation.analytical:EigenvalueChecks', title='Published eigenvalues and frequencies (section 3.1)'),
    CheckGroup('forensics', 'validation.analytical:ForensicsChecks', title='Eigenvalue forensics'),
    CheckGroup('charts', 'validation.charts:ChartChecks', title='Stability charts: the statements of section 2.3 (Figures 4 and 5)'),
    CheckGroup('charts-paper', 'validation.charts_paper:PaperChartChecks',
               title="Stability charts on the paper's domain (section 2.3: J1 1e-6..1e-3 kg*m^2, kT 5e-3..5 N*m), log and linear axes"),
    CheckGroup('friction', 'validation.friction:FrictionChecks',
               title='Friction over sliding speed: the AGMA 6034 values at the speeds its source gives'),
    CheckGroup('simulation', 'validation.timedomain:SimulationChecks', level=1,
               title='Time domain: statements of section 3.2 (reel changer simulations), both mesh readings'),
    CheckGroup('forensics-slow', 'validation.analytical:ForensicsSlowChecks', level=2,
               title='Eigenvalue forensics: slow searches (full mode)'),
]


def RegisterCheckGroup(name: str, function: Union[GroupFunction, str], level: int = 0, title: str = '',
                       replace: bool = False) -> CheckGroup:
    """Add a check group to :data:`CHECK_GROUPS`.

    Parameters
    ----------
    name : str
        Group name; the rows with this value in the ``group`` column belong to it.
    function : callable or str
        ``function(context) -> list[Check]`` or ``'module:function'`` (imported when run).
    level : int, optional
        0 always runs, 1 skipped by quick runs, 2 only in full runs.
    title : str, optional
        Heading in the report.
    replace : bool, optional
        Replace an existing group of the same name instead of raising.

    Returns
    -------
    CheckGroup

    Raises
    ------
    ValueError
        If a group ``name`` exists and ``replace`` is False.
    """
    group = CheckGroup(name, function, level, title)
    for i, g in enumerate(CHECK_GROUPS):
        if g.name == name:
            if not replace:
                raise ValueError(f"RegisterCheckGroup: a group '{name}' exists; pass replace=True")
            CHECK_GROUPS[i] = group
            return group
    CHECK_GROUPS.append(group)
    return group


def _FailAll(rows: Iterable[ReferenceRow], detail: str) -> List[Check]:
    return [Check(r, math.nan, (math.nan, math.nan), 'FAIL', False, detail) for r in rows]


def RunValidation(reportPath: Optional[Union[str, Path]] = None, quick: bool = False, full: bool = False,
                  groups: Optional[Sequence[CheckGroup]] = None,
                  validationDir: Optional[Union[str, Path]] = None, quiet: Optional[bool] = None) -> ValidationSummary:
    """Check the package against every published number and statement of the reference tables.

    Parameters
    ----------
    reportPath : str or Path, optional
        Write the Markdown report there (its directory must exist; checked before computing). Nothing is
        written if None.
    quick : bool, optional
        Skip the slow groups (level 1: the simulations) and the full-mode groups.
    full : bool, optional
        Also run the full-mode groups (level 2: the slow forensic searches).
    groups : sequence of CheckGroup, optional
        Groups to run instead of :data:`CHECK_GROUPS`.
    validationDir : str or Path, optional
        Directory of the reference tables instead of :data:`VALIDATION_DIR`.
    quiet : bool or None, optional
        Progress on stderr: see :func:`exudyn_worm.progress.ProgressBar`.

    Returns
    -------
    ValidationSummary
        ``passed`` (no check failed), ``checks`` and human-readable ``lines``.

    Raises
    ------
    ValueError
        If ``quick`` and ``full`` are both given, or ``reportPath`` is not a file in an existing directory.
    FileNotFoundError
        If the reference tables are missing.
    """
    from exudyn_worm.progress import ProgressBar
    if quick and full:
        raise ValueError("RunValidation: give 'quick' or 'full', not both")
    if reportPath is not None:
        reportPath = Path(reportPath)
        if reportPath.is_dir() or not reportPath.parent.is_dir():
            raise ValueError(f"RunValidation: 'reportPath' must be a file in an existing directory, got '{reportPath}'")
    start = time.perf_counter()
    validationDir = None if validationDir is None else Path(validationDir)
    reference = LoadReference(validationDir)
    known = LoadKnownDifferences(validationDir, reference)
    groups = list(CHECK_GROUPS if groups is None else groups)
    level = 0 if quick else 2 if full else 1
    ctx = ValidationContext(reference, known, level, quiet)
    checks: List[Check] = []
    skipped: List[str] = []
    crashed: Dict[str, str] = {}
    groupLines: List[str] = []
    names = {g.name for g in groups}
    with ProgressBar(total=len(groups), desc='validation', unit='group', quiet=quiet) as bar:
        for group in groups:
            bar.set_postfix_str(group.name)
            rows = ctx.Rows(group.name)
            if group.level > level:
                skipped.append(group.name)
                groupLines.append(f"SKIPPED group '{group.name}' ({len(rows)} row(s)): "
                                  + ('run without --quick' if group.level == 1 else 'run with --full'))
                bar.update(1)
                continue
            try:
                got = list(group.Resolve()(ctx))
            except Exception as e:  # a broken group fails its rows instead of hiding the other groups
                if IsInterrupt(e):  # Ctrl-C stops the validation; it is no failure of the group
                    raise KeyboardInterrupt() from None
                crashed[group.name] = f'{type(e).__name__}: {e}'
                groupLines.append(f"FAIL    group '{group.name}' raised {type(e).__name__}: {e}")
                got = _FailAll(rows, f'group raised {type(e).__name__}: {e}')
            done = {c.row.id for c in got}
            for c in got:
                if c.row.group != group.name:
                    groupLines.append(f"note    group '{group.name}' checked row '{c.id}' of group '{c.row.group}'")
            checks += got
            checks += _FailAll([r for r in rows if r.id not in done], f"group '{group.name}' computed no value")
            bar.update(1)
    checks += _FailAll([r for r in reference.values() if r.group not in names],
                       'no check group of this name is registered')
    order = {rowId: i for i, rowId in enumerate(reference)}
    checks.sort(key=lambda c: (order.get(c.row.id, len(order)), c.reading == 'paperMesh'))
    summary = ValidationSummary(checks, [], skipped, ctx.sections, crashed,
                                'quick' if quick else 'full' if full else 'default')
    summary.seconds = time.perf_counter() - start
    summary.lines = _Lines(summary, groupLines)
    if reportPath is not None:
        summary.reportPath = reportPath
        WriteText(reportPath, Report(summary, groups, validationDir or VALIDATION_DIR))
    return summary


def WriteText(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` so that the file is complete or absent (temporary file, then renamed; an
    interrupt removes the temporary file): :func:`exudyn_worm._files.WriteTextAtomically`, the package's one rule.

    Parameters
    ----------
    path : Path
        The file.
    text : str
        Its content.
    """
    WriteTextAtomically(path, text)


def _Lines(summary: ValidationSummary, groupLines: List[str]) -> List[str]:
    return [HeadLine(summary), *groupLines, *(c.Line() for c in summary.checks)]
