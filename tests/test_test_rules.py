"""The rules for tests of docs/development.md ("Tests") that a parser can check: an import inside a function of
a test module is lazy on purpose and says why in a ``# lazy: <reason>`` comment, on its line or the line above
(one comment above a block of imports covers the block), as in the package."""
import ast
from pathlib import Path

TESTS = Path(__file__).resolve().parent
_LAZY = '# lazy:'


def LocalImportsWithoutReason(source: str) -> list:
    """Line numbers of the imports inside functions of ``source`` that no ``# lazy:`` comment explains."""
    lines = source.splitlines()
    found = set()
    for function in ast.walk(ast.parse(source)):
        if not isinstance(function, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        for node in ast.walk(function):
            if isinstance(node, (ast.Import, ast.ImportFrom)):
                first = node.lineno - 1
                while first > 0 and lines[first - 1].strip().startswith(('import ', 'from ')):
                    first -= 1          # the first import of the block: its comment covers the block
                explained = _LAZY in lines[node.lineno - 1] or (first > 0 and lines[first - 1].strip().startswith(_LAZY))
                if not explained:
                    found.add(node.lineno)
    return sorted(found)


def test_imports_inside_test_functions_say_why():
    bad = [f'{path.name}:{number}: {path.read_text(encoding="utf-8").splitlines()[number - 1].strip()}'
           for path in sorted(TESTS.glob('*.py')) for number in LocalImportsWithoutReason(path.read_text(encoding='utf-8'))]
    assert bad == [], 'move these imports to the top of the module, or say why they are lazy (# lazy: reason)'


def test_the_rule_finds_what_it_looks_for():
    source = ('import json\n\n'
              'def test_a():\n    import os\n    return os\n\n'
              'def test_b():\n    # lazy: the test checks that importing it is cheap\n    import sys\n    import re\n'
              '    return sys, re\n\n'
              'def test_c():\n    import math  # lazy: an optional dependency\n'
              '    # the value below\n    import cmath\n    return math, cmath\n')
    assert LocalImportsWithoutReason(source) == [4, 16]
