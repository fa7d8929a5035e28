"""The layers of the package: the graph of its internal imports.

Every module of ``exudyn_worm`` is parsed with :mod:`ast`. An import at module level (outside every function;
``if TYPE_CHECKING:`` blocks are left out, they never run) is an edge of the import graph; an import inside a
function is *lazy*. The rules, also written down in docs/development.md:

- the module-level graph has no cycle;
- a module's ``__all__`` lists only names it defines, and an internal import takes a name from the module that
  defines it (no re-exports; the package's ``__init__`` alone hands on the public names);
- a lazy import is of exudyn, scipy, matplotlib or pint (or a submodule), or it is the ``plot`` method of a
  result object importing its ``plot*`` module, or it says why on the same line or the line above with a
  comment ``# lazy: <reason>``. A cycle is not a reason (break it instead); a reason that names the start-up
  (tests/test_startup.py) must be true: the imported module pulls in a heavy package at module level.

The lazy imports that break these rules today are listed in ``ALLOWED`` with their reason. The list may only
shrink: an entry that is no longer needed fails the test too.
"""
import ast
import re
import sys
from pathlib import Path
from typing import Dict, List, NamedTuple, Set, Tuple

import pytest

from test_startup import HELP_HEAVY

PACKAGE = 'exudyn_worm'
ROOT = Path(__file__).resolve().parents[1] / PACKAGE
#: lazy imports of these packages need no comment (the heavy packages of docs/development.md)
LAZY_PACKAGES = ('exudyn', 'scipy', 'matplotlib', 'pint')
_LAZY_COMMENT = re.compile(r'#\s*lazy\b\W*(.*)', re.IGNORECASE)

#: (importing module, imported module) -> why the lazy import is still there. May only shrink.
ALLOWED: Dict[Tuple[str, str], str] = {
}


#: the layers of docs/development.md, lowest first: the subpackages and the helpers below them.
#: A module imports (at module level) only modules of its own or a lower layer; inside a subpackage any module may
#: import any other, as long as there is no cycle. A new module goes into the subpackage it belongs to.
LAYERS = (
    ('helpers', '_checks _files _roots _spacing _workers progress'),
    ('parameters and files', 'params'),
    ('gear model', 'model'),
    ('Exudyn items', 'items'),
    ('the drive', 'drive'),
    ('model builders', 'builders'),
    ('analyses: stability', 'analysis.stability'),
    ('analyses: charts', 'analysis.charts'),
    ('analyses: simulation', 'analysis.simulation'),
    ('analyses: orbits', 'analysis.orbits'),
    ('analyses: design', 'analysis.design'),
    ('analyses: studies', 'analysis.studies'),
    ('analyses', 'analysis'),       # the package analysis itself, above its sub-layers
    ('plotting', 'plotting'),
    ('command line', 'cli __main__'),
)


def LayerOf(module: str) -> int:
    """Index in :data:`LAYERS` of a module (``exudyn_worm.x.y``): the layer of its subpackage or its own name."""
    parts = module.split('.')[1:]
    for index, (_, names) in enumerate(LAYERS):
        for name in names.split():
            if parts[:len(name.split('.'))] == name.split('.'):
                return index
    raise KeyError(module)


class Import(NamedTuple):
    module: str          # importing module, e.g. 'exudyn_worm.analysis.studies.study'
    target: str          # imported module, e.g. 'exudyn_worm.drive.presets' or 'numpy'
    function: str        # enclosing function ('' at module level)
    line: int
    comment: str         # the reason of a '# lazy: ...' comment on the line or the line above, else ''


def _ModuleName(path: Path) -> str:
    parts = list(path.relative_to(ROOT.parent).with_suffix('').parts)
    return '.'.join(parts[:-1] if parts[-1] == '__init__' else parts)


MODULES = {_ModuleName(path): path for path in sorted(ROOT.rglob('*.py'))}


def _Targets(module: str, node) -> List[str]:
    if isinstance(node, ast.Import):
        return [alias.name for alias in node.names]
    if node.level == 0:
        base = node.module
    else:
        base = module if MODULES[module].name == '__init__.py' else module.rsplit('.', 1)[0]
        for _ in range(node.level - 1):
            base = base.rsplit('.', 1)[0]
        if node.module:
            base = f'{base}.{node.module}'
    # 'from . import plot' imports the module exudyn_worm.plotting.plot; 'from .presets import X' the module presets
    return [f'{base}.{alias.name}' if f'{base}.{alias.name}' in MODULES else base for alias in node.names]


def _Comment(lines: List[str], line: int) -> str:
    """The reason on the import's line or the line above; for a block of imports, the comment above the block."""
    index = line - 1
    while True:
        match = _LAZY_COMMENT.search(lines[index])
        if match:
            return match.group(1).strip()
        index -= 1
        if index < 0 or not (index == line - 2 or lines[index + 1].strip().startswith(('from ', 'import '))):
            return ''
        if not lines[index].strip().startswith(('from ', 'import ', '#')):
            return ''


def _Imports(module: str) -> List[Import]:
    source = MODULES[module].read_text(encoding='utf-8')
    lines = source.splitlines()
    found = []

    def Walk(node, function):
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.If) and 'TYPE_CHECKING' in ast.unparse(child.test):
                continue
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
                Walk(child, getattr(child, 'name', '<lambda>'))
            elif isinstance(child, (ast.Import, ast.ImportFrom)):
                comment = _Comment(lines, child.lineno) if function else ''
                found.extend(Import(module, target, function, child.lineno, comment)
                             for target in _Targets(module, child) if target != module)
            else:
                Walk(child, function)
    Walk(ast.parse(source), '')
    return found


IMPORTS = [item for module in MODULES for item in _Imports(module)]


def _Internal(target: str) -> bool:
    return target == PACKAGE or target.startswith(PACKAGE + '.')


def ModuleGraph() -> Dict[str, Set[str]]:
    """Internal imports at module level: module -> the internal modules it imports."""
    graph = {module: set() for module in MODULES}
    for item in IMPORTS:
        if not item.function and _Internal(item.target):
            graph[item.module].add(item.target)
    return graph


def _Cycle(graph: Dict[str, Set[str]]) -> List[str]:
    state: Dict[str, int] = {}    # 1 on the path, 2 done
    path: List[str] = []

    def Visit(node):
        state[node] = 1
        path.append(node)
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == 1:
                return path[path.index(nxt):] + [nxt]
            if nxt not in state:
                cycle = Visit(nxt)
                if cycle:
                    return cycle
        state[node] = 2
        path.pop()
        return []
    for node in sorted(graph):
        if node not in state:
            cycle = Visit(node)
            if cycle:
                return cycle
    return []


def _HeavyAtModuleLevel(target: str, graph: Dict[str, Set[str]]) -> bool:
    """Whether importing ``target`` imports a heavy package or numpy (``HELP_HEAVY`` of tests/test_startup.py) at
    module level."""
    if not _Internal(target):
        return target.split('.')[0] in HELP_HEAVY
    seen, todo = set(), [target]
    while todo:
        module = todo.pop()
        if module in seen or module not in MODULES:
            continue
        seen.add(module)
        todo.extend(graph[module])
    return any(item.module in seen and not item.function and item.target.split('.')[0] in HELP_HEAVY
               for item in IMPORTS)


def _Problem(item: Import, graph: Dict[str, Set[str]]) -> str:
    """Why a lazy import breaks the rule ('' when it does not)."""
    if item.target.split('.')[0] in LAZY_PACKAGES:
        return ''
    if (item.function == 'plot' and _Internal(item.target)
            and item.target.rsplit('.', 1)[-1].startswith('plot')):
        return ''
    if not item.comment:
        return 'no "# lazy: <reason>" comment'
    if 'cycle' in item.comment.lower():
        return 'an import cycle is no reason: break the cycle'
    if re.search(r'start-?up', item.comment, re.IGNORECASE) and not _HeavyAtModuleLevel(item.target, graph):
        # `exudyn-worm --help` imports every command module: its run function may defer the analyses it calls
        if not item.module.startswith(f'{PACKAGE}.cli.') or item.module == f'{PACKAGE}.cli.main':
            return (f'the reason names the start-up, but {item.target} imports no heavy package {HELP_HEAVY} at '
                    f'module level')
        if item.target in graph[item.module]:
            return f'the reason names the start-up, but {item.module} imports {item.target} at module level anyway'
    return ''


def test_every_module_is_parsed():
    assert f'{PACKAGE}.cli.main' in MODULES and f'{PACKAGE}.cli.simulate' in MODULES
    assert any(item.function for item in IMPORTS) or not ALLOWED


def test_no_cycle_among_module_level_imports():
    assert _Cycle(ModuleGraph()) == []


def test_every_module_has_a_layer():
    missing = []
    for module in sorted(set(MODULES) - {PACKAGE}):
        try:
            LayerOf(module)
        except KeyError:
            missing.append(module)
    assert missing == []


def test_the_package_has_no_flat_modules_beyond_the_helpers():
    # the layers show as subpackages
    flat = sorted(m for m in MODULES if m.count('.') == 1 and not (ROOT / m.split('.')[1]).is_dir())
    assert flat == [f'{PACKAGE}.{name}' for name in sorted('__main__ _checks _files _roots _spacing _workers progress'.split())]


def test_module_level_imports_go_down_the_layers():
    layer = {module: LayerOf(module) for module in MODULES if module != PACKAGE}
    layer[PACKAGE] = 0        # the package's __init__: lazy attributes; no internal import at module level
    upward = sorted(f'{module} ({LAYERS[layer[module]][0]}) imports {target} ({LAYERS[layer[target]][0]})'
                    for module, targets in ModuleGraph().items() for target in targets
                    if layer[target] > layer[module])
    assert upward == []


def test_cycle_finder_finds_a_cycle():
    assert _Cycle({'a': {'b'}, 'b': {'c'}, 'c': {'a'}}) == ['a', 'b', 'c', 'a']
    assert _Cycle({'a': {'b'}, 'b': set(), 'c': {'a', 'b'}}) == []


def test_lazy_imports_are_heavy_plot_or_say_why():
    graph = ModuleGraph()
    problems = sorted(f'{item.module}:{item.line} imports {item.target} in {item.function}(): {why}'
                      for item in IMPORTS if item.function and (item.module, item.target) not in ALLOWED
                      for why in [_Problem(item, graph)] if why)
    assert problems == []


def test_allowed_list_only_shrinks():
    graph = ModuleGraph()
    needed = {(item.module, item.target) for item in IMPORTS if item.function and _Problem(item, graph)}
    assert sorted(set(ALLOWED) - needed) == [], 'no longer needed: remove these entries from ALLOWED'


@pytest.mark.parametrize('comment, target, ok', [
    ('', 'exudyn_worm.drive.presets', False),
    ('cycle with presets', 'exudyn_worm.drive.presets', False),
    ('start-up (tests/test_startup.py)', 'tqdm', True),
    ('start-up (tests/test_startup.py)', 'exudyn_worm._files', False),      # loads neither numpy nor a heavy package
    ('start-up (numpy: the help)', 'exudyn_worm._checks', True),               # loads numpy
    ('optional dependency (the mpi extra)', 'mpi4py.futures', True),
])
def test_rule_on_examples(comment, target, ok):
    item = Import('exudyn_worm.analysis.studies.study', target, 'RunStudy', 1, comment)
    assert (_Problem(item, ModuleGraph()) == '') is ok


_DEFINED: Dict[Path, Set[str]] = {}


def _Defined(module: str) -> Set[str]:
    """Names a module defines at its top level (functions, classes, assignments), not the ones it imports."""
    path = MODULES[module]
    if path in _DEFINED:
        return _DEFINED[path]
    names = _DEFINED[path] = set()
    for node in ast.parse(path.read_text(encoding='utf-8')).body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            for target in (node.targets if isinstance(node, ast.Assign) else [node.target]):
                names.update(n.id for n in ast.walk(target) if isinstance(n, ast.Name))
    return names


def _ListedNames(module: str) -> List[str]:
    for node in ast.parse(MODULES[module].read_text(encoding='utf-8')).body:
        if isinstance(node, ast.Assign) and any(getattr(t, 'id', '') == '__all__' for t in node.targets):
            return [e.value for e in node.value.elts]
    return []


def test_a_module_lists_only_the_names_it_defines():
    # one home per name: a module's __all__ names what it defines (the package itself hands on the public names)
    foreign = sorted(f'{module}.{name}' for module in MODULES if module != PACKAGE
                     for name in _ListedNames(module) if name not in _Defined(module))
    assert foreign == []


def test_an_internal_import_takes_a_name_from_the_module_that_defines_it():
    # no name is imported through a module that only imports it itself (the old re-exports)
    through = []
    for module, path in MODULES.items():
        for node in ast.walk(ast.parse(path.read_text(encoding='utf-8'))):
            if not isinstance(node, ast.ImportFrom):
                continue
            source = _Targets(module, node)
            for alias, target in zip(node.names, source):
                if target.rsplit('.', 1)[-1] == alias.name:       # 'from . import study': the module itself
                    continue
                if target in MODULES and target != PACKAGE and alias.name not in _Defined(target):
                    through.append(f'{module}:{node.lineno} imports {alias.name} from {target}')
    assert through == []


def test_the_guards_see_a_re_export(tmp_path, monkeypatch):
    """The two checks above are not vacuous: a module that hands on a name it imports fails both."""
    (tmp_path / 'a.py').write_text('X = 1\n')
    (tmp_path / 'b.py').write_text("from .a import X\n__all__ = ['X']\n")
    (tmp_path / 'c.py').write_text('from .b import X\n')
    fake = {f'{PACKAGE}.fake.{n}': tmp_path / f'{n}.py' for n in 'abc'}
    monkeypatch.setattr(sys.modules[__name__], 'MODULES', fake)
    with pytest.raises(AssertionError, match='fake.b.X'):
        test_a_module_lists_only_the_names_it_defines()
    with pytest.raises(AssertionError, match='imports X from exudyn_worm.fake.b'):
        test_an_internal_import_takes_a_name_from_the_module_that_defines_it()
