"""The Markdown report of a validation run (``python -m validation --report PATH``).

Every sentence that states a conclusion is generated from the verdicts it summarizes; the check groups add
their own sections under the same rule. The sweep studies (``validation/STUDIES.md``, written by the sweep
branch's command, see ``validation/README.md``) are included as the last section when present.
"""
from __future__ import annotations

from pathlib import Path
from typing import Dict, List, Sequence

from .model import RULES, VERDICTS, Check, CheckGroup, Fmt, HeadLine, ValidationSummary

__all__ = ['Report', 'STUDIES_FILE']

#: the studies file of the sweep branch, included as the last section when present
STUDIES_FILE = 'STUDIES.md'


def _Md(text: str) -> str:
    return text.replace('|', '\\|')


def _Unit(unit: str) -> str:
    return '' if unit.strip() in ('', '-') else ' ' + unit.strip()


def _Reason(c: Check) -> str:
    return '; '.join(filter(None, [c.detail, c.row.note])) or c.row.quantity


def _Summary(summary: ValidationSummary, groups: Sequence[CheckGroup]) -> List[str]:
    out = [HeadLine(summary), '']
    fails, differs = summary.Checks('FAIL'), summary.Checks('DIFFERS')
    if summary.passed:
        out.append(f'No check fails. {len(differs)} check(s) are known, explained model differences (DIFFERS, listed '
                   f'below with their reasons).')
    else:
        out.append(f'**{len(fails)} check(s) fail**, each with its row, our value, the accepted interval and what the '
                   f'row reads:')
        out.append('')
        out += [f'- `{c.id}`: {_Md(c.row.quantity)}; published {c.row.publishedText}{_Unit(c.row.unit)} '
                f'({c.row.rule}, accepted {c.IntervalText()}), computed {Fmt(c.computed, c.row.publishedText)}. '
                f'{_Md(_Reason(c))}' for c in fails]
    out.append('')
    if summary.crashed:
        out += ['Crashed check groups (their rows are FAIL): '
                + '; '.join(f'`{g}`: {_Md(e)}' for g, e in summary.crashed.items()) + '.', '']
    if differs:
        out += [f'Known differences ({len(differs)}; the one list `paper/differences.csv`, pinned by the tests):', '']
        out += [f'- `{c.id}`: computed {Fmt(c.computed, c.row.publishedText)} vs published {c.row.publishedText} '
                f'(accepted {c.IntervalText()}): {_Md(c.knownDifference)}' for c in differs]
        out.append('')
    if summary.stale:
        out += ['**Stale known differences** (listed but passing; remove them from the list): '
                + ', '.join(f'`{c.id}`' for c in summary.stale) + '.', '']
    if summary.skipped:
        out += [f"Not run in this mode: group(s) {', '.join(f'`{g}`' for g in summary.skipped)}; nothing is claimed "
                f"from them.", '']
    out += ['| group | checks | ' + ' | '.join(VERDICTS) + ' | in-sample |', '|---|---|---|---|---|---|']
    for g in groups:
        cs = summary.Checks(group=g.name)
        if cs:
            out.append(f'| {g.name} | {len(cs)} | ' + ' | '.join(str(sum(c.verdict == v for c in cs)) for v in VERDICTS)
                       + f' | {sum(c.inSample for c in cs)} |')
    inSample = [c for c in summary.checks if c.inSample]
    out += ['', f'{len(inSample)} check(s) are in-sample (their published number was used to identify the friction '
            f'mu = 0.132 or the wheel-circumference mesh reading the check uses); they are not counted as confirmation.',
            '']
    return out


def _RulesTable(summary: ValidationSummary) -> List[str]:
    counts: Dict[str, int] = {}
    for c in summary.checks:
        counts[c.row.rule] = counts.get(c.row.rule, 0) + 1
    out = ['| rule | reading (validation/README.md) | checks |', '|---|---|---|']
    out += [f'| `{r}` | {_Md(text)} | {counts.get(r, 0)} |' for r, text in RULES.items()]
    return out + ['']


def _GroupTable(checks: List[Check]) -> List[str]:
    out = ['| id | quantity | S | reading | published | rule | accepted | computed | verdict | kind | sample | source |',
           '|---|---|---|---|---|---|---|---|---|---|---|---|']
    for c in checks:
        r = c.row
        verdict = f'**{c.verdict}**' if c.verdict != 'PASS' else c.verdict
        out.append(f'| `{c.id}` | {_Md(r.quantity)} | {"" if r.S is None else f"{r.S:+d}"} | {c.reading or "-"} | '
                   f'{r.publishedText}{_Unit(r.unit)} | {r.rule} | {c.IntervalText()} | {Fmt(c.computed, r.publishedText)} | '
                   f'{verdict} | {r.kind} | {"in" if c.inSample else "out"} | {_Md(r.source)} |')
    notes = [c for c in checks if c.reading != 'paperMesh' and (c.row.note or c.detail or c.row.inputs)]
    if notes:
        out += ['', 'Inputs and notes:', '']
        out += [f'- `{c.row.id}`: inputs: {_Md(c.row.inputs or "-")}' + (f'. {_Md(c.row.note)}' if c.row.note else '')
                + (f' ({_Md(c.detail)})' if c.detail else '') for c in notes]
    return out + ['']


def _Findings(summary: ValidationSummary) -> List[str]:
    """How each finding of the review of the validation is addressed: method text, results generated from the verdicts."""
    by = {c.id: c for c in summary.checks}

    def v(checkId: str) -> str:
        c = by.get(checkId)
        return f'`{checkId}` {c.verdict} (computed {Fmt(c.computed, c.row.publishedText)}, accepted {c.IntervalText()})' \
            if c else f'`{checkId}` not run in this mode'
    sim = [c for c in summary.checks if c.row.group == 'simulation']
    return [
        '1. *Gating followed the outcome.* Every row now names the phrase it reads (`rule` column); the interval follows '
        'from the rule of `validation/README.md` and the printed value, and every kind is gated the same way. The backlash '
        f'rows all read "2-4 times": {v("P1_backlash_0.25")}, {v("P1_backlash_0.5")}, {v("P1_backlash_0.75")}. '
        f'"Virtually" is +-10 % everywhere: {v("P7_backlash_independence")}, {v("P7_speed_doubling")}.',
        '2. *Exclusions propagated rounding selectively.* `runner.InputRounding` adds the propagated half-unit rounding of '
        'the printed inputs to every analytical row, values and exclusions alike: '
        f'{v("b4_28_u63")}; {v("mu_28_from_rho")}; {v("b1_28_dT0741")}; {v("hurwitz19_28_rho8")}.',
        '3. *In-sample checks were called out of sample.* Each row names the hypotheses its number identified '
        '(`identifies`); a check using such a hypothesis is in-sample and not counted as confirmation. Every '
        f'time-domain row is reported under both mesh readings ({len(sim)} time-domain checks in this run; the section '
        "'Time domain: both mesh readings side by side' counts confirmations only out of sample).",
        '4. *DIFFERS could hide a failure.* A non-finite value and a crashed group are FAIL, and `Check.failed` counts '
        'every FAIL; DIFFERS is only for a check listed in `paper/differences.csv` with its reason, and the tests pin '
        f'that list (stale entries in this run: {len(summary.stale)}).',
        '5. *Conclusions were fixed text.* The sentences of this report that state a conclusion are generated from the '
        'verdicts and numbers they summarize; the slow forensic searches run only in the full mode and are claimed only '
        f"in their section ({'run' if 'forensics-slow' not in summary.skipped else 'not run'} in this run).",
        '6. *`validate --quick` overwrote the committed report.* The suite lives in `validation/` and writes a file only '
        'with `--report PATH`; it runs from the source checkout as `python -m validation`, its one way in.',
        '7. *A test tolerance far wider than the source.* `tests/test_example_reel_changer.py` now compares P1\'s max '
        '|phi2\'\'| with the printed 110 under the reading rule (110 +- 5) under the wheel-circumference reading and '
        'pins the tooth-normal result as the known difference of `P1_max_acceleration`.',
        "8. *The section 2.3 chart statements were not rows.* They are the group `charts` (section 'Stability charts').",
        '',
    ]


def _Demoted(markdown: str) -> str:
    """``markdown`` with every heading one level lower (outside code fences), to sit under the report's title."""
    out, fence = [], False
    for line in markdown.splitlines():
        if line.lstrip().startswith('```'):
            fence = not fence
        out.append('#' + line if not fence and line.startswith('#') else line)
    return '\n'.join(out)


def Report(summary: ValidationSummary, groups: Sequence[CheckGroup], validationDir: Path) -> str:
    """The Markdown report of ``summary``.

    Parameters
    ----------
    summary : ValidationSummary
        The run.
    groups : sequence of CheckGroup
        The groups of the run (titles and order).
    validationDir : Path
        Where ``STUDIES.md`` is looked for.

    Returns
    -------
    str
        Markdown text.
    """
    from exudyn_worm import __version__
    out = ['# Validation report', '',
           f'Generated by `python -m validation` (exudyn-worm {__version__}, {summary.mode} mode, '
           f'{summary.seconds:.0f} s); regenerate with `python -m validation --full --overwrite --report validation/REPORT.md` '
           '(validation/README.md). Do not edit by hand.', '', '## Summary', '']
    out += _Summary(summary, groups)
    out += ['## Reading rules applied', ''] + _RulesTable(summary)
    out += ['## How the findings of the review of this validation are addressed', ''] + _Findings(summary)
    titles = {g.name: g.title or g.name for g in groups}
    for name in dict.fromkeys(c.row.group for c in summary.checks):
        out += [f'## {titles.get(name, name)}', ''] + _GroupTable(summary.Checks(group=name))
    for title, text in summary.sections:
        out += [f'## {title}', '', text]
    studies = Path(validationDir) / STUDIES_FILE
    if studies.is_file():
        out += [_Demoted(studies.read_text().strip()), '']
    return '\n'.join(out).rstrip() + '\n'
