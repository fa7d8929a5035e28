"""Regression baseline of the validation: record every check of a run, compare a later run with it.

The plain validation fails as long as the package disagrees with the paper somewhere (it honestly does,
see ``REPORT.md``), so its exit status cannot tell a regression from the known state. A baseline is the
record of one run: for every check its verdict, our computed value and the row's tolerance.
:func:`CompareWithBaseline` reports a check as changed when its verdict differs, when its value moved by
more than the row's tolerance (:func:`Tolerance`), or when it is new or missing. ``python -m validation
--record-baseline FILE`` writes one, ``python -m validation --baseline FILE`` compares with it
(``validation/README.md``).
"""
from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Dict, List, Mapping, Optional, Union

from .model import Check, ValidationSummary
from .runner import HalfUnit

__all__ = ['BASELINE_FORMAT', 'Tolerance', 'BaselineRecord', 'LoadBaseline', 'CompareWithBaseline']

#: version of the baseline file format
BASELINE_FORMAT = 1


def Tolerance(check: Check) -> float:
    """How far a check's computed value may move before it counts as changed: the row's tolerance.

    Half the width of the row's accepted interval (its reading rule, widened by the propagated rounding of the
    printed inputs). For a row read exactly (yes/no, counts, comparisons: an interval of width 0) or without an
    upper end ("many times"), half a unit of the last digit of the published value (0.5 for "1", "0" and
    the lower bound 3 of "many"), so that a count or a yes/no changing by one is reported.

    Parameters
    ----------
    check : Check
        A check of a run.

    Returns
    -------
    float
        The tolerance (>= 0), in the unit of the row.
    """
    lo, hi = check.interval
    if math.isfinite(lo) and math.isfinite(hi) and hi > lo:
        return 0.5 * (hi - lo)
    text = check.row.publishedText
    if check.row.rule == 'many-times':
        text = '3'
    elif check.row.rule == 'range':
        text = text.split('-')[0]
    try:
        return HalfUnit(text)
    except ValueError:
        return 0.


def _Number(value: float) -> Optional[float]:
    return float(value) if math.isfinite(value) else None


def BaselineRecord(summary: ValidationSummary) -> Dict:
    """The baseline of a run: ``{format, mode, checks: {id: {verdict, computed, tolerance}}}`` (JSON-ready).

    Parameters
    ----------
    summary : ValidationSummary
        A run of :func:`validation.RunValidation`.

    Returns
    -------
    dict
        A non-finite computed value is stored as null.
    """
    from exudyn_worm import __version__
    return {'format': BASELINE_FORMAT, 'mode': summary.mode, 'exudynWormVersion': __version__,
            'checks': {c.id: {'verdict': c.verdict, 'computed': _Number(c.computed), 'tolerance': Tolerance(c)}
                       for c in summary.checks}}


def LoadBaseline(path: Union[str, os.PathLike], mode: Optional[str] = None) -> Dict:
    """Read a baseline file and check it before anything is computed.

    Parameters
    ----------
    path : str or path-like
        A file written by ``--record-baseline``.
    mode : str, optional
        The mode of the run it will be compared with (``'quick'``, ``'default'``, ``'full'``); it must be
        the mode the baseline was recorded in.

    Returns
    -------
    dict
        The baseline (:func:`BaselineRecord`).

    Raises
    ------
    ValueError
        If the file is missing or unreadable, is no baseline of this format, or was recorded in another mode.
    """
    path = Path(path)
    try:
        data = json.loads(path.read_text())
    except OSError as err:
        raise ValueError(f"--baseline {path}: cannot read it: {err.strerror or err}") from None
    except ValueError as err:
        raise ValueError(f"--baseline {path}: not a JSON file ({err})") from None
    if not isinstance(data, dict) or data.get('format') != BASELINE_FORMAT or not isinstance(data.get('checks'), dict):
        raise ValueError(f"--baseline {path}: not a validation baseline of format {BASELINE_FORMAT} "
                         f"(write one with --record-baseline FILE)")
    if mode is not None and data.get('mode') != mode:
        flag = {'quick': ' --quick', 'full': ' --full'}.get(data.get('mode'), '')
        raise ValueError(f"--baseline {path}: recorded in {data.get('mode')} mode, this run is in {mode} mode; "
                         f"run 'python -m validation{flag} --baseline {path}'")
    return data


def _Text(value: Optional[float]) -> str:
    return 'nan' if value is None else f'{value:.6g}'


def CompareWithBaseline(summary: ValidationSummary, baseline: Mapping) -> List[str]:
    """The checks of a run that changed against a baseline, one line each (empty: nothing changed).

    A check has changed when its verdict differs, when its computed value differs from the recorded one by
    more than the row's tolerance (:func:`Tolerance` of the check as it is now; a value turning non-finite,
    or finite again, is a change), or when it is new in this run or missing from it.

    Parameters
    ----------
    summary : ValidationSummary
        The run.
    baseline : mapping
        From :func:`LoadBaseline`.

    Returns
    -------
    list of str
        E.g. ``'CHANGED P1_force_factor: verdict FAIL -> PASS; computed 2.548 -> 3.1 (tolerance 0.5)'``.
    """
    recorded = baseline['checks']
    out = []
    now = {c.id: c for c in summary.checks}
    for checkId, c in now.items():
        old = recorded.get(checkId)
        if old is None:
            out.append(f"NEW     {checkId}: {c.verdict}, computed {_Text(_Number(c.computed))} (not in the baseline)")
            continue
        value, before = _Number(c.computed), old.get('computed')
        tolerance = Tolerance(c)
        moved = (value is None) != (before is None) or (value is not None and abs(value - before) > tolerance)
        parts = []
        if c.verdict != old.get('verdict'):
            parts.append(f"verdict {old.get('verdict')} -> {c.verdict}")
        if moved:
            parts.append(f"computed {_Text(before)} -> {_Text(value)} (tolerance {tolerance:.3g})")
        elif parts:
            parts.append(f"computed {_Text(before)} -> {_Text(value)}")
        if parts:
            out.append(f"CHANGED {checkId}: {'; '.join(parts)}")
    for checkId, old in recorded.items():
        if checkId not in now:
            out.append(f"MISSING {checkId}: {old.get('verdict')}, computed {_Text(old.get('computed'))} in the baseline, "
                       f"not in this run")
    return out
