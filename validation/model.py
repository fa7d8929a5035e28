"""The data model of the validation: reading rules, reference rows, checks, check groups and the summary.

The lowest layer of ``validation/``: :mod:`validation.runner` (which computes the checks) and
:mod:`validation.report` (which writes the Markdown report) both import it, and it imports neither.
"""
from __future__ import annotations

import importlib
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Dict, FrozenSet, List, Optional, Sequence, Tuple, Union

__all__ = ['KINDS', 'RULES', 'READINGS', 'VERDICTS', 'ReferenceRow', 'Check', 'Fmt', 'GroupFunction', 'CheckGroup',
           'ValidationSummary', 'HeadLine']

#: how a row is compared: kind -> 'match' (passes inside the interval) or 'exclude' (a rejected reading:
#: passes outside). Kinds only describe what is compared; every kind is gated the same way.
KINDS = {'value': 'match', 'consistency': 'match', 'forensic': 'match', 'eigenvalue': 'match',
         'exclusion': 'exclude'}

#: the reading rules of validation/README.md: rule -> the phrase of the paper it reads
RULES = {
    'printed': 'a printed number without qualifier: +- half a unit of the last printed digit',
    'about': '"about X": +- 10 % of X, or half a unit of the last printed digit if wider',
    'virtually': '"virtually <exact statement>": the exact value +- 10 % ("ceased to exist": at most 10 % of the '
                 'reference size)',
    'ratio': 'an unqualified ratio statement ("is also doubled", "do not depend on"): the exact ratio +- 5 %',
    'range': '"N-M times": the closed interval [N, M]',
    'many-times': '"many times": at least 3 times',
    'chart-bound': 'a bound read off a chart: within a factor 10^0.05 of X, or half a unit of its last digit if wider',
    'chart-bound-linear': 'a bound read off a chart with a linear axis: +- half a unit of the last printed digit of X',
    'comparison': 'a comparison of regions ("smallest", "smaller", "broadens", "shorter"): the strict inequality '
                  'holds (1) or not (0)',
    'none': '"no unstable regions": zero unstable grid points',
    'yes-no': 'a yes/no verdict or a count: exact',
    'robustness': 'our own requirement: a numerical knob changes the result by at most 3 %',
}
#: the two mesh readings of every time-domain row: tooth normal (eq. (5)) and wheel circumference
READINGS = ('normal', 'paperMesh')
#: possible verdicts
VERDICTS = ('PASS', 'FAIL', 'DIFFERS')


@dataclass(frozen=True)
class ReferenceRow:
    """One published number or statement (a row of a ``reference.csv``).

    ``publishedText`` keeps the value as printed; ``published`` is its nominal number (the midpoint of a
    range, 3 for "many"); ``identifies`` the hypotheses ('mu', 'circ') this number was used to identify.
    """
    id: str
    group: str
    quantity: str
    S: Optional[int]
    published: float
    publishedText: str
    unit: str
    source: str
    rule: str
    kind: str
    inputs: str
    identifies: FrozenSet[str]
    note: str
    file: Path


@dataclass(frozen=True)
class Check:
    """The comparison of one reference row with our computed value (under one mesh reading).

    ``holds`` is the bare comparison; ``verdict`` adds the known-differences list; ``uses`` names the
    hypotheses the computation relies on ('mu': the friction 0.132 of set (28); 'circ': the mesh referred
    to the wheel circumference), so that a check is in-sample when its row identified one of them.
    """
    row: ReferenceRow
    computed: float
    interval: Tuple[float, float]
    verdict: str
    holds: bool
    detail: str = ''
    reading: str = ''
    uses: FrozenSet[str] = frozenset()
    knownDifference: str = ''

    @property
    def id(self) -> str:
        """Check id: the row id, with ``@paperMesh`` for the wheel-circumference reading."""
        return self.row.id + ('@paperMesh' if self.reading == 'paperMesh' else '')

    @property
    def failed(self) -> bool:
        """True for a FAIL (including non-finite values and crashed groups)."""
        return self.verdict == 'FAIL'

    @property
    def stale(self) -> bool:
        """True for a check listed as a known difference that passes."""
        return bool(self.knownDifference) and self.holds

    @property
    def inSample(self) -> bool:
        """True if the row's published number was used to identify a hypothesis this check uses."""
        return bool(self.row.identifies & self.uses)

    @property
    def difference(self) -> float:
        """computed - published (nominal)."""
        return self.computed - self.row.published

    def IntervalText(self) -> str:
        """The accepted interval as text (``outside [lo, hi]`` for an exclusion)."""
        lo, hi = self.interval
        like = self.row.publishedText if self.row.rule not in ('range', 'many-times') else '0.00'
        text = (f'>= {Fmt(lo, like)}' if math.isinf(hi) else
                f'{Fmt(lo, like)}' if lo == hi else f'[{Fmt(lo, like)}, {Fmt(hi, like)}]')
        return ('outside ' if KINDS[self.row.kind] == 'exclude' else '') + text

    def Line(self) -> str:
        """One human-readable line."""
        r = self.row
        S = '' if r.S is None else f' (S = {r.S:+d})'
        reading = f' [{self.reading}]' if self.reading else ''
        return (f'{self.verdict:<7s} {self.id}: {r.quantity}{S}{reading}: published {r.publishedText}{_Unit(r.unit)} '
                f'({r.rule}), computed {Fmt(self.computed, r.publishedText)}, accepted {self.IntervalText()}'
                f' [{r.source}]' + (' (in-sample)' if self.inSample else '')
                + (f' -- {self.detail}' if self.detail else '')
                + (f' -- known difference: {self.knownDifference}' if self.verdict == 'DIFFERS' else '')
                + (' -- STALE: listed as a known difference but passes' if self.stale else ''))


def _Unit(unit: str) -> str:
    return '' if unit.strip() in ('', '-') else ' ' + unit.strip()


def Fmt(value: float, like: str) -> str:
    """Format ``value`` with two more significant digits than the printed ``like``.

    Parameters
    ----------
    value : float
        The number.
    like : str
        A printed number whose significant digits set the precision.

    Returns
    -------
    str
    """
    if not math.isfinite(value):
        return str(value)
    digits = len(re.sub(r'[^0-9]', '', re.split(r'[eE]', like)[0]).lstrip('0')) or 1
    return f'{value:.{max(digits + 2, 5)}g}'


#: a check group: ``function(context) -> list[Check]`` (context: :class:`validation.runner.ValidationContext`)
GroupFunction = Callable[[Any], Sequence[Check]]


@dataclass(frozen=True)
class CheckGroup:
    """A named group of checks.

    ``function`` is a callable ``(context) -> list[Check]`` or a string ``'package.module:Function'``
    imported when the group runs. ``level``: 0 always runs, 1 is skipped by quick runs, 2 runs only in
    full runs.
    """
    name: str
    function: Union[GroupFunction, str]
    level: int = 0
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
    crashed: Dict[str, str] = field(default_factory=dict)
    mode: str = 'default'
    seconds: float = 0.
    reportPath: Optional[Path] = None

    @property
    def passed(self) -> bool:
        """True if no check failed."""
        return not any(c.failed for c in self.checks)

    @property
    def stale(self) -> List[Check]:
        """Checks listed as known differences that pass (the list should drop them)."""
        return [c for c in self.checks if c.stale]

    def Count(self, verdict: str) -> int:
        """Number of checks with ``verdict``."""
        return sum(c.verdict == verdict for c in self.checks)

    def Checks(self, verdict: Optional[str] = None, group: Optional[str] = None) -> List[Check]:
        """The checks with ``verdict`` (any if None) of ``group`` (any if None)."""
        return [c for c in self.checks if (verdict is None or c.verdict == verdict)
                and (group is None or c.row.group == group)]


def HeadLine(summary: ValidationSummary) -> str:
    """The one-line summary of a run (first line of :attr:`ValidationSummary.lines`)."""
    n = len(summary.checks)
    return (f"validation {'PASSED' if summary.passed else 'FAILED'} ({summary.mode} mode): {n} checks, "
            f"{summary.Count('PASS')} PASS, {summary.Count('FAIL')} FAIL, {summary.Count('DIFFERS')} DIFFERS "
            f"(known differences)" + (f"; {len(summary.stale)} stale known difference(s)" if summary.stale else '')
            + (f"; skipped group(s): {', '.join(summary.skipped)}" if summary.skipped else ''))
