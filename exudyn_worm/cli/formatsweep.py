"""Text of ``exudyn-worm sweep``: the study's table (the numbers come from :mod:`exudyn_worm.analysis.studies.study`; this
module only formats them).
"""
from __future__ import annotations

from typing import List

from ..analysis.stability.drivestability import VerdictWord
from ..params.parameters import PARAMETERS

__all__ = ['FormatStudy']

#: the chatter cell of a window in the table: chatter, none, unresolved (changes at half the step), undecided (a
#: vibration that decays slower than the window, or a steady one below saturation), not computed
_VERDICT_CELLS = {True: 'YES', False: 'no', 'unresolved': 'UNR', 'undecided': 'UND', None: '-'}


def FormatStudy(result, title: str = 'Study') -> List[str]:
    """Human-readable table of a study: one line per run (varied values, status, chatter per window, the
    drive's linear verdict at the operating points of its duty as ``exudyn-worm stability`` gives it (the
    analytical two-mass model or the linearized whole drive), the verdict of its lowering points; time) and a
    summary with the agreement.

    Parameters
    ----------
    result : StudyResult
        Result of :func:`~exudyn_worm.analysis.studies.study.RunStudy`.
    title : str, optional
        First line.

    Returns
    -------
    list of str
        The lines, without trailing newlines.
    """
    keys = result.study.keys
    n = result.study.numberOfWindows
    heads = [PARAMETERS.AxisLabel(k, display=False, dash='-')[0] for k in keys]
    widths = [max(12, len(h)) for h in heads]
    lines = [title, '', '  '.join(['run'.rjust(5)] + [h.rjust(w) for h, w in zip(heads, widths)]
                                  + ['status', 'chatter per window'.ljust(max(18, 4 * n)), 'linear drive ',
                                     'S=-1 linear  ', 'seconds'])]
    for r in result.rows:
        chatter = ' '.join(_VERDICT_CELLS.get(r.get(f'w{i}.chatter'), '?') for i in range(n))
        drive, verdict = ('-' if r[k] is None else VerdictWord(r[k], r.get(kind))
                          for k, kind in (('analyticStable', 'analyticInstability'),
                                          ('analyticStableLowering', 'analyticInstabilityLowering')))
        cells = [f"{r['run']:>5d}"] + [f"{r[k]:>{w}.5g}" for k, w in zip(keys, widths)]
        cells += [f"{r['status']:<6}", chatter.ljust(max(18, 4 * n)), f"{drive:<13}", f"{verdict:<13}",
                  f"{r['seconds']:7.2f}"]
        lines.append('  '.join(cells) + (f"  {r['error']}" if r['error'] else ''))
    agreement, judged = result.agreement, len(result.judged)
    unresolved = sum(any(r.get(f'w{i}.chatter') == 'unresolved' for i in range(n)) for r in result.rows)
    undecided = sum(r.get('loweringChatter') == 'undecided' for r in result.finished)
    checked = sum(bool(r.get('stepChecked')) for r in result.rows)
    lines += ['', f"step check (a second run at half the step): {checked} of {len(result.rows)} runs; "
                  f"{unresolved} with an unresolved verdict (UNR: it changes when the step is halved)"]
    lines += [f"{len(result.rows)} runs: {len(result.finished)} ok, {len(result.failed)} failed; "
                  f"agreement of chatter while lowering with the linear verdict of the duty's lowering "
                  f"operating points (S = -1; 'linear drive' is the verdict of 'exudyn-worm stability', the "
                  f"worst operating point): "
                  + ('n/a (no decided lowering window)' if agreement is None else
                     f"{100 * agreement:.0f} % of {judged} run{'s' if judged != 1 else ''} with a decided lowering "
                     f"window")
                  + (f"; {undecided} run{'s' if undecided != 1 else ''} left out, lowering undecided (UND: a "
                     f"vibration that decays slower than the window, a steady one below the saturated amplitude, or "
                     f"too few periods in the window; "
                     f"'simulate' on the run says which)" if undecided else '')
                  + (f"; {len(result.divergent)} left out whose lowering points diverge (DIVERGENT: a real "
                     f"eigenvalue, a runaway or creep, not chatter)" if result.divergent else '')]
    return lines
