"""The validation runner: the package against the numbers printed in the paper (``python -m validation``).

Published values live in ``validation/<source>/reference.csv`` beside the scripts that analyse them,
one row per number with its equation/section/figure and a tolerance set by the printed digits.
:func:`RunValidation` computes our value for every row with the package's own functions, compares,
and writes the Markdown report only when asked (``reportPath``).

Checks come from *check groups*: a check group is a function ``Group(context) -> list[Check]`` that
computes the rows of its group (the ``group`` column of the reference tables) and returns one
:class:`Check` per row, made with :meth:`ValidationContext.Compare`; it may add prose sections to the
report with :meth:`ValidationContext.AddSection`. Register a new group (e.g. the time-domain checks)
with :func:`RegisterCheckGroup`, as a callable or lazily as ``'module:function'``; a group marked
``slow`` is skipped by ``RunValidation(quick=True)``. Every row of a group that ran must receive a
check, and every row must belong to a registered group, otherwise the row fails.

Verdicts
--------
PASS
    The comparison holds (for an ``exclusion`` row: the rejected hypothesis is indeed outside tolerance).
FAIL
    A gated comparison does not hold; :attr:`ValidationSummary.passed` is then False.
DIFFERS
    Only for ``eigenvalue`` rows (published eigenvalues and the numbers derived from them, which the
    paper computed inconsistently with its own eq. (16)) and ``difference`` rows (a statement of the
    paper our model does not reproduce, discussed in the report): reported with an explanation, not gated.
"""
from __future__ import annotations

import csv
import importlib
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Dict, List, Optional, Sequence, Tuple, Union

from exudyn_worm.presets import PRESETS

__all__ = ['VALIDATION_DIR', 'COMMITTED_REPORT', 'PAPER_MU', 'KINDS', 'GATED_KINDS', 'VERDICTS',
           'ReferenceRow', 'Check', 'ValidationContext', 'CheckGroup', 'ValidationSummary', 'CHECK_GROUPS',
           'RegisterCheckGroup', 'LoadReference', 'HalfUnit', 'RunValidation']

#: the validation data beside this module (``validation/<source>/reference.csv``)
VALIDATION_DIR = Path(__file__).resolve().parent
#: the committed report (written only by the explicit command of ``validation/README.md``)
COMMITTED_REPORT = VALIDATION_DIR / 'REPORT.md'

#: friction coefficient of the gear of set (28) as the paper computed b1..b4 and (19): the value printed
#: with (25), mu = 0.132 (rho = 7.996 deg, printed as "8 deg"); the 0.134 printed in (28) is rejected
PAPER_MU = PRESETS['reel-P1']['mu']

#: how a row is compared: kind -> (gated, rule); rule 'match' passes within tolerance, 'exclude'
#: passes outside tolerance (a rejected hypothesis), 'report' gives PASS or DIFFERS and is not gated
KINDS = {'value': (True, 'match'), 'consistency': (True, 'match'), 'forensic': (True, 'match'),
         'exclusion': (True, 'exclude'), 'eigenvalue': (False, 'report'), 'difference': (False, 'report')}
#: kinds whose failure makes the validation fail
GATED_KINDS = tuple(k for k, (gated, _) in KINDS.items() if gated)
#: possible verdicts
VERDICTS = ('PASS', 'FAIL', 'DIFFERS')

_COLUMNS = ('id', 'group', 'quantity', 'S', 'published', 'unit', 'source', 'tolerance', 'kind', 'inputs', 'note')
_PROPAGATED = 'propagated'


# --- reference data ------------------------------------------------------------------------------------

@dataclass(frozen=True)
class ReferenceRow:
    """One published number (a row of a ``reference.csv``).

    ``tolerance`` is None when the table says ``propagated``: the check group then computes it.
    ``publishedText`` keeps the digits as printed.
    """
    id: str
    group: str
    quantity: str
    S: Optional[int]
    published: float
    publishedText: str
    unit: str
    source: str
    tolerance: Optional[float]
    kind: str
    inputs: str
    note: str
    file: Path


def HalfUnit(text: str) -> float:
    """Half a unit of the last printed digit of a number given as text.

    Examples
    --------
    >>> HalfUnit('13.615'), HalfUnit('1.279e5'), HalfUnit('63'), HalfUnit('-2.607e10')
    (0.0005, 50.0, 0.5, 5000000.0)
    """
    m = re.fullmatch(r'\s*[-+]?(\d*)(?:\.(\d*))?(?:[eE]([-+]?\d+))?\s*', text)
    if m is None or not (m.group(1) or m.group(2)):
        raise ValueError(f"HalfUnit: 'text' must be a decimal number, got {text!r}")
    decimals = len(m.group(2) or '')
    exponent = int(m.group(3) or 0)
    return 0.5 * 10.0**(exponent - decimals)


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
        If there is no reference table (e.g. the package is installed without its source tree).
    ValueError
        For a malformed table: missing column, duplicate id, unknown kind, bad number.
    """
    validationDir = Path(VALIDATION_DIR if validationDir is None else validationDir)
    files = sorted(validationDir.glob('*/reference.csv'))
    if not files:
        raise FileNotFoundError(f"LoadReference: no '*/reference.csv' under {validationDir}; the validation data "
                                f"ship with the source tree (git checkout), not with the installed package")
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
                tol = r['tolerance'].strip()
                try:
                    tolerance = None if tol == _PROPAGATED else float(tol)
                    published = float(r['published'])
                    S = int(r['S']) if r['S'].strip() else None
                except ValueError as e:
                    raise ValueError(f"LoadReference: bad number in {where}: {e}") from None
                if tolerance is not None and not tolerance >= 0:
                    raise ValueError(f"LoadReference: 'tolerance' must be >= 0 or '{_PROPAGATED}', got {tol} in {where}")
                rows[r['id']] = ReferenceRow(r['id'], r['group'], r['quantity'], S, published, r['published'].strip(),
                                             r['unit'], r['source'], tolerance, r['kind'], r['inputs'], r['note'], path)
    return rows


# --- checks --------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Check:
    """The comparison of one reference row with our computed value."""
    row: ReferenceRow
    computed: float
    tolerance: float
    verdict: str
    detail: str = ''

    @property
    def id(self) -> str:
        """Row id."""
        return self.row.id

    @property
    def gated(self) -> bool:
        """True if a FAIL of this check fails the validation."""
        return KINDS[self.row.kind][0]

    @property
    def difference(self) -> float:
        """computed - published."""
        return self.computed - self.row.published

    @property
    def failed(self) -> bool:
        """True for a gated check that did not pass."""
        return self.gated and self.verdict != 'PASS'

    def Line(self) -> str:
        """One human-readable line."""
        r = self.row
        S = '' if r.S is None else f' (S = {r.S:+d})'
        cmp = '>' if KINDS[r.kind][1] == 'exclude' else '<='
        return (f'{self.verdict:<7s} {r.id}: {r.quantity}{S}: published {r.publishedText}, computed '
                f'{_Fmt(self.computed, r.publishedText)}, diff {self.difference:+.3g}, |diff| {cmp} {self.tolerance:.3g} '
                f'{_Unit(r.unit).strip()} [{r.source}]' + (f' -- {self.detail}' if self.detail else ''))


def _Unit(unit: str) -> str:
    return '' if unit.strip() in ('', '-') else ' ' + unit.strip()


def _Fmt(value: float, like: str) -> str:
    """Format ``value`` with two more significant digits than the printed ``like``."""
    if not math.isfinite(value):
        return str(value)
    digits = len(re.sub(r'[^0-9]', '', re.split(r'[eE]', like)[0]).lstrip('0')) or 1
    return f'{value:.{max(digits + 2, 5)}g}'


def _Verdict(kind: str, difference: float, tolerance: float, published: float) -> str:
    rule = KINDS[kind][1]
    if not math.isfinite(difference):
        return 'FAIL' if KINDS[kind][0] else 'DIFFERS'
    within = abs(difference) <= tolerance + 1e-12 * abs(published)
    if rule == 'match':
        return 'PASS' if within else 'FAIL'
    if rule == 'exclude':
        return 'PASS' if not within else 'FAIL'
    return 'PASS' if within else 'DIFFERS'


@dataclass
class ValidationContext:
    """What a check group receives: the reference rows, the run options and the report under construction."""
    reference: Dict[str, ReferenceRow]
    quick: bool = False
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

    def Compare(self, rowId: str, computed: float, tolerance: Optional[float] = None, detail: str = '') -> Check:
        """Build the :class:`Check` of row ``rowId`` for our ``computed`` value.

        ``tolerance`` is required for a row whose table tolerance is ``propagated`` and must not be
        given otherwise (the printed digits set it).
        """
        row = self.Row(rowId)
        if row.tolerance is None:
            if tolerance is None:
                raise ValueError(f"Compare: row '{rowId}' has a propagated tolerance; pass 'tolerance'")
        elif tolerance is not None:
            raise ValueError(f"Compare: row '{rowId}' has the tabulated tolerance {row.tolerance:g}; "
                             f"do not override it (got {tolerance:g})")
        else:
            tolerance = row.tolerance
        computed = float(computed)
        return Check(row, computed, float(tolerance),
                     _Verdict(row.kind, computed - row.published, float(tolerance), row.published), detail)

    def AddSection(self, title: str, markdown: str) -> None:
        """Add a prose section to the report."""
        self.sections.append((title, markdown.strip() + '\n'))


GroupFunction = Callable[[ValidationContext], Sequence[Check]]


@dataclass(frozen=True)
class CheckGroup:
    """A named group of checks.

    ``function`` is a callable ``(context) -> list[Check]`` or a string ``'package.module:Function'``
    imported when the group runs (so a group can live in a module that imports heavy dependencies).
    """
    name: str
    function: Union[GroupFunction, str]
    slow: bool = False
    title: str = ''

    def Resolve(self) -> GroupFunction:
        """The callable of this group."""
        if callable(self.function):
            return self.function
        module, _, attr = str(self.function).partition(':')
        if not module or not attr:
            raise ValueError(f"CheckGroup '{self.name}': 'function' must be a callable or 'module:function', "
                             f"got {self.function!r}")
        return getattr(importlib.import_module(module), attr)


@dataclass
class ValidationSummary:
    """Result of :func:`RunValidation`."""
    checks: List[Check]
    lines: List[str]
    skipped: List[str] = field(default_factory=list)
    sections: List[Tuple[str, str]] = field(default_factory=list)
    reportPath: Optional[Path] = None

    @property
    def passed(self) -> bool:
        """True if no gated check failed."""
        return not any(c.failed for c in self.checks)

    def Count(self, verdict: str) -> int:
        """Number of checks with ``verdict``."""
        return sum(c.verdict == verdict for c in self.checks)


#: the check groups run by :func:`RunValidation`, in report order
CHECK_GROUPS: List[CheckGroup] = [
    CheckGroup('analytical', 'validation.analytical:AnalyticalChecks', title='Analytical model: eqs. (3), (13), (16)-(24), Figures 4-5'),
    CheckGroup('eigenvalues', 'validation.analytical:EigenvalueChecks', title='Published eigenvalues and frequencies (section 3.1)'),
    CheckGroup('forensics', 'validation.analytical:ForensicsChecks', title='Eigenvalue forensics'),
    CheckGroup('forensics-slow', 'validation.analytical:ForensicsSlowChecks', slow=True, title='Eigenvalue forensics (slow)'),
    CheckGroup('simulation', 'validation.timedomain:SimulationChecks', slow=True,
               title='Time domain: statements of section 3.2 (reel changer simulations)'),
]


def RegisterCheckGroup(name: str, function: Union[GroupFunction, str], slow: bool = False, title: str = '',
                       replace: bool = False) -> CheckGroup:
    """Add a check group to :data:`CHECK_GROUPS`.

    Parameters
    ----------
    name : str
        Group name; the rows with this value in the ``group`` column belong to it.
    function : callable or str
        ``function(context) -> list[Check]`` or ``'module:function'`` (imported when run).
    slow : bool, optional
        Skipped by ``RunValidation(quick=True)``.
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
    group = CheckGroup(name, function, slow, title)
    for i, g in enumerate(CHECK_GROUPS):
        if g.name == name:
            if not replace:
                raise ValueError(f"RegisterCheckGroup: a group '{name}' exists; pass replace=True")
            CHECK_GROUPS[i] = group
            return group
    CHECK_GROUPS.append(group)
    return group


def RunValidation(reportPath: Optional[Union[str, Path]] = None, quick: bool = False,
                  groups: Optional[Sequence[CheckGroup]] = None,
                  validationDir: Optional[Union[str, Path]] = None) -> ValidationSummary:
    """Check the package against every published number of the reference tables.

    Parameters
    ----------
    reportPath : str or Path, optional
        Write the Markdown report there. Nothing is written if None.
    quick : bool, optional
        Skip the groups marked ``slow`` (their rows are listed as skipped, not failed).
    groups : sequence of CheckGroup, optional
        Groups to run instead of :data:`CHECK_GROUPS`.
    validationDir : str or Path, optional
        Directory of the reference tables instead of :data:`VALIDATION_DIR`.

    Returns
    -------
    ValidationSummary
        ``passed`` (no gated check failed), ``checks`` and human-readable ``lines``.

    Raises
    ------
    FileNotFoundError
        If the reference tables are missing.
    """
    reference = LoadReference(None if validationDir is None else Path(validationDir))
    groups = list(CHECK_GROUPS if groups is None else groups)
    ctx = ValidationContext(reference, quick)
    checks: List[Check] = []
    skipped: List[str] = []
    groupLines: List[str] = []
    names = {g.name for g in groups}
    for group in groups:
        rows = ctx.Rows(group.name)
        if group.slow and quick:
            skipped.append(group.name)
            groupLines.append(f"SKIPPED group '{group.name}' (slow; {len(rows)} row(s)): run without quick")
            continue
        try:
            got = list(group.Resolve()(ctx))
        except Exception as e:  # a broken group fails its rows instead of hiding the other groups
            groupLines.append(f"FAIL    group '{group.name}' raised {type(e).__name__}: {e}")
            got = [Check(r, math.nan, r.tolerance or 0., 'FAIL', f'group raised {type(e).__name__}: {e}')
                   for r in rows]
        done = {c.id for c in got}
        for c in got:
            if c.row.group != group.name:
                groupLines.append(f"note    group '{group.name}' checked row '{c.id}' of group '{c.row.group}'")
        checks += got
        checks += [Check(r, math.nan, r.tolerance or 0., 'FAIL', f"group '{group.name}' computed no value")
                   for r in rows if r.id not in done]
    for r in reference.values():
        if r.group not in names:
            checks.append(Check(r, math.nan, r.tolerance or 0., 'FAIL', f"no check group '{r.group}' is registered"))
    order = {rowId: i for i, rowId in enumerate(reference)}
    checks.sort(key=lambda c: order.get(c.id, len(order)))
    summary = ValidationSummary(checks, [], skipped, ctx.sections)
    summary.lines = _Lines(summary, groupLines)
    if reportPath is not None:
        summary.reportPath = Path(reportPath)
        summary.reportPath.write_text(_Report(summary, groups, quick))
    return summary


def _Lines(summary: ValidationSummary, groupLines: List[str]) -> List[str]:
    n = len(summary.checks)
    gated = sum(c.gated for c in summary.checks)
    failed = sum(c.failed for c in summary.checks)
    head = (f"validation {'PASSED' if summary.passed else 'FAILED'}: {n} checks, {summary.Count('PASS')} PASS, "
            f"{summary.Count('FAIL')} FAIL, {summary.Count('DIFFERS')} DIFFERS (not gated); "
            f"{failed} of {gated} gated checks failed"
            + (f"; skipped group(s): {', '.join(summary.skipped)}" if summary.skipped else ''))
    return [head, *groupLines, *(c.Line() for c in summary.checks)]


def _MdEscape(text: str) -> str:
    return text.replace('|', '\\|')


def _Report(summary: ValidationSummary, groups: Sequence[CheckGroup], quick: bool) -> str:
    from exudyn_worm import __version__
    out = ['# Validation report', '',
           f'Generated by `validation.RunValidation` (exudyn-worm {__version__}'
           f"{', quick: slow groups skipped' if quick else ''}); regenerate with the command in `validation/README.md`.",
           'Do not edit by hand.', '', '## Summary', '', summary.lines[0], '']
    if summary.skipped:
        out += [f"Skipped (slow) group(s): {', '.join(summary.skipped)}.", '']
    out += ['Verdicts: **PASS** the comparison holds (for an *exclusion* row: the rejected hypothesis is outside '
            'tolerance); **FAIL** a gated comparison does not hold; **DIFFERS** a published eigenvalue (or a number '
            'derived from it) that the paper computed inconsistently with its own eq. (16), or a time-domain '
            'statement our model does not reproduce (kind *difference*): shown with the explanation below, not gated. Kinds: *value* our model vs. the paper, *consistency* the paper\'s own '
            'arithmetic, *exclusion* a reading of the paper that must be rejected, *forensic* the identified '
            'explanation of the printed eigenvalues, *eigenvalue* and *difference* reported only.', '']
    titles = {g.name: g.title or g.name for g in groups}
    for name in dict.fromkeys(c.row.group for c in summary.checks):
        out += [f'## {titles.get(name, name)}', '',
                '| id | quantity | S | published | computed | difference | tolerance | verdict | kind | source |',
                '|---|---|---|---|---|---|---|---|---|---|']
        for c in (c for c in summary.checks if c.row.group == name):
            r = c.row
            tol = ('> ' if KINDS[r.kind][1] == 'exclude' else '') + f'{c.tolerance:.3g}'
            verdict = f'**{c.verdict}**' if c.verdict != 'PASS' else c.verdict
            out.append(f'| `{r.id}` | {_MdEscape(r.quantity)} | {"" if r.S is None else f"{r.S:+d}"} | '
                       f'{r.publishedText}{_Unit(r.unit)} | {_Fmt(c.computed, r.publishedText)} | {c.difference:+.3g} | '
                       f'{tol} | {verdict} | {r.kind} | {_MdEscape(r.source)} |')
        notes = [c for c in summary.checks if c.row.group == name and (c.row.note or c.detail or c.row.inputs)]
        if notes:
            out += ['', 'Inputs and notes:', '']
            out += [f'- `{c.id}`: inputs: {c.row.inputs or "-"}' + (f'. {c.row.note}' if c.row.note else '')
                    + (f' ({c.detail})' if c.detail else '') for c in notes]
        out.append('')
    for title, text in summary.sections:
        out += [f'## {title}', '', text]
    return '\n'.join(out).rstrip() + '\n'
