"""Decisions on types, never on text; below the drive boundary, typed drives, never flat parameter mappings.

Two walks over the package's source with :mod:`ast`:

- **no decision on a phrase**: code that compares a message or a label with a phrase (a string literal with a
  space in it: ``reason.startswith('the corrector did not converge')``, ``form == 'centre distance'``,
  ``source.startswith('preset ')``) breaks when the words change. Such a decision reads a typed field instead (an
  enum of stop kinds, directions, value sources, geometry forms). Parsing text a user gave (a drive file, an
  option) compares with single tokens and is not caught.
- **no flat mapping below the boundary**: the drive is resolved once (``ResolveDrive``: presets, drive files,
  ``--set`` and API keywords) and everything below takes the :class:`~exudyn_worm.drive.wholedrive.Drive` or its
  typed parts. A public function of the analyses or the model builder whose argument is a mapping
  (``Mapping``/``Dict`` in its annotation) or is named like a flat parameter set (``parameters``, ``base``,
  ``params``) is listed in ``FLAT_ALLOWED`` with the reason it is still there. The list may only shrink: an entry
  that is no longer needed fails the test too.
"""
import ast
import re
from pathlib import Path
from typing import Dict, List, Tuple

import pytest

ROOT = Path(__file__).resolve().parents[1] / 'exudyn_worm'
_PHRASE = re.compile(r'\w ')           # a word and a space: a phrase ('preset ...'), not a token ('#', '.toml')


def _Modules():
    return sorted(ROOT.rglob('*.py'))


def _IsPhrase(node) -> bool:
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return bool(_PHRASE.search(node.value))
    if isinstance(node, ast.Tuple):
        return any(_IsPhrase(e) for e in node.elts)
    return False


def PhraseDecisions(source: str) -> List[Tuple[int, str]]:
    """(line, code) of every comparison with a phrase: ``x == 'a b'``, ``x != 'a b'``, ``'a b' in x``,
    ``x.startswith('a b')``, ``x.endswith('a b')``.

    Parameters
    ----------
    source : str
        Python source.

    Returns
    -------
    list of (int, str)
    """
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Compare):
            ops = [type(op) for op in node.ops]
            sides = [node.left, *node.comparators]
            if any(op in (ast.Eq, ast.NotEq, ast.In, ast.NotIn) for op in ops) and any(_IsPhrase(s) for s in sides):
                found.append((node.lineno, ast.unparse(node)))
        elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
              and node.func.attr in ('startswith', 'endswith') and node.args and _IsPhrase(node.args[0])):
            found.append((node.lineno, ast.unparse(node)))
    return found


def test_no_decision_compares_a_phrase():
    found = [f"{path.relative_to(ROOT.parent)}:{line}: {code}" for path in _Modules()
             for line, code in PhraseDecisions(path.read_text())]
    assert not found, 'decisions on message text (use a typed field):\n' + '\n'.join(found)


def test_the_phrase_rule_catches_what_it_should():
    """Not vacuous: the comparisons the package made before its enums are caught, a token is not."""
    caught = PhraseDecisions("if branch.stopReason[-1].startswith('the corrector did not converge'):\n    pass\n"
                             "if form == 'centre distance':\n    pass\n"
                             "if e['direction'].startswith('away from'):\n    pass\n"
                             "ok = src.startswith(('API', 'preset '))\n")
    assert [line for line, _ in caught] == [1, 3, 5, 7]
    assert PhraseDecisions("if line.startswith('#') or key == 'kT' or name.endswith('.toml'):\n    pass\n") == []


# --- no flat mapping below the boundary ---------------------------------------------------------------------------
#: the modules below the drive boundary (they receive the resolved drive)
BELOW = ('analysis', 'builders', 'drive/operatingpoints.py')
_FLAT_NAMES = ('parameters', 'base', 'params')
_MAPPING = re.compile(r'\b(Mapping|Dict|dict|MutableMapping)\b')

_LOG_FACTORS = 'a mapping of design-parameter keys to log factors (decades), not a parameter set'
_ROW = 'a row of the results table (CSV), not a parameter set'
_SOLVER = 'solver settings by their path in exudyn.SimulationSettings, not a parameter set'
_METRICS = 'window metrics (dicts of numbers), not a parameter set'
#: the reasons of the entries that are no parameter set at all
_NOT_A_SET = (_LOG_FACTORS, _ROW, _SOLVER, _METRICS)

#: (module, function) -> why it still takes a mapping. May only shrink.
FLAT_ALLOWED: Dict[Tuple[str, str], str] = {
    ('analysis/studies/study.py', 'RunStudy'): _ROW,
    ('analysis/studies/studyfiles.py', 'Run'): _ROW,
    ('analysis/simulation/reelchanger.py', 'SolverSettings'): _SOLVER,
    ('analysis/simulation/reelchanger.py', 'SimulateReelChanger'): _SOLVER,
    ('analysis/simulation/stepsize.py', 'CompareHalfStep'): _METRICS,
    **{('analysis/design/designscan.py', f): _LOG_FACTORS for f in ('Stable', 'Changed', 'Analysis', 'StableAt', 'After')},
    ('analysis/charts/stabilitychart.py', 'ChartPoints'): 'chart points by label (the user\'s marks), not a parameter set',
}


def FlatMappingArguments() -> Dict[Tuple[str, str], List[str]]:
    """Public functions and methods below the boundary with an argument that is a mapping or named like a flat
    parameter set: ``{(module, function): [argument, ...]}``.

    Returns
    -------
    dict
    """
    out: Dict[Tuple[str, str], List[str]] = {}
    for path in _Modules():
        rel = str(path.relative_to(ROOT))
        if not any(rel == b or rel.startswith(b + '/') for b in BELOW):
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) or node.name.startswith('_'):
                continue
            args = node.args.posonlyargs + node.args.args + node.args.kwonlyargs
            flat = [a.arg for a in args
                    if a.arg in _FLAT_NAMES or (a.annotation is not None and _MAPPING.search(ast.unparse(a.annotation)))]
            if flat:
                out[(rel, node.name)] = flat
    return out


def test_no_flat_mapping_below_the_boundary():
    found = FlatMappingArguments()
    new = {k: v for k, v in found.items() if k not in FLAT_ALLOWED}
    assert not new, ('functions below the drive boundary that take a flat mapping (take the Drive or its typed '
                     'parts):\n' + '\n'.join(f"{m}: {f}({', '.join(a)})" for (m, f), a in sorted(new.items())))
    stale = sorted(k for k in FLAT_ALLOWED if k not in found)
    assert not stale, f'FLAT_ALLOWED entries no longer needed (remove them): {stale}'


@pytest.mark.parametrize('module', ['analysis/simulation/reelchanger.py', 'analysis/simulation/stepsize.py', 'analysis/design/designcheck.py',
                                    'analysis/stability/drivestability.py', 'builders/oneangle.py'])
def test_the_simulation_and_stability_paths_take_the_drive(module):
    """The simulation (step size, phases, the builder, the run) and the stability and design analyses take the
    Drive: none of their public functions reads a flat set (the solver settings excepted)."""
    found = {f: a for (m, f), a in FlatMappingArguments().items() if m == module}
    assert all(FLAT_ALLOWED.get((module, f)) in _NOT_A_SET for f in found), found
    assert all('parameters' not in a and 'base' not in a for a in found.values()), found
