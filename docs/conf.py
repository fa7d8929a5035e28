"""Sphinx configuration of the exudyn-worm documentation.

Build (writes nothing into the checkout): ``sphinx-build -W --keep-going -b html -d /tmp/doctrees docs /tmp/html``
after ``pip install -e '.[docs]'``. Every ``docs/*.md`` page is found by the glob toctree in ``index.md``.
Two pages are generated at read time from the code, so they follow the package without edits:
``api.md`` (one autodoc section per public module of exudyn_worm) and ``examples.md`` (each script in
``examples/`` with its docstring and source). Nothing is executed besides importing the package.
"""
from __future__ import annotations

import ast
import importlib
import pkgutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))      # exudyn_worm from this checkout even without an install

import exudyn_worm  # noqa: E402

project = 'exudyn-worm'
author = 'exudyn-worm developers'
copyright = 'exudyn-worm developers'
release = version = exudyn_worm.__version__

extensions = ['myst_parser', 'sphinx.ext.autodoc', 'sphinx.ext.mathjax', 'sphinx.ext.viewcode', 'numpydoc']
source_suffix = {'.md': 'markdown', '.rst': 'restructuredtext'}
root_doc = 'index'
exclude_patterns = ['_build']
html_theme = 'furo'
html_title = f'exudyn-worm {release}'

myst_enable_extensions = ['dollarmath', 'amsmath']
myst_heading_anchors = 3

autodoc_member_order = 'bysource'
autodoc_typehints = 'none'           # numpydoc's Parameters sections carry the types
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False


def PublicModules() -> list:
    """Names of the public modules of exudyn_worm (no part of the path starts with an underscore), sorted."""
    names = ['exudyn_worm']
    for info in pkgutil.walk_packages(exudyn_worm.__path__, 'exudyn_worm.'):
        if not any(part.startswith('_') for part in info.name.split('.')):
            names.append(info.name)
    return sorted(names)


def ApiPage() -> str:
    """MyST text of the API reference: the module docstring and the public members (``__all__``) of each module."""
    out = ['# API reference', '',
           'Generated from the docstrings (numpydoc) of every public module of `exudyn_worm`; a name re-exported by',
           '`exudyn_worm` (`import exudyn_worm as ew; ew.CreateWormGear`) is documented in the module that defines it.',
           '']
    for name in PublicModules():
        importlib.import_module(name)
        out += [f'## `{name}`', '', '```{eval-rst}', f'.. automodule:: {name}', '   :members:', '```', '']
    return '\n'.join(out)


def ExamplesPage() -> str:
    """MyST text of the examples page: per script of examples/, its docstring (reST) and its source."""
    out = ['# Examples', '',
           'The scripts in `examples/` of the source checkout; each runs as `python examples/NAME.py --out DIR`',
           '(`--help` lists its options) and is checked by its test in `tests/`. The drive files of',
           '`examples/drives/` are described in [Whole-drive files](drive-files.md).', '']
    for path in sorted((ROOT / 'examples').glob('*.py')):
        docstring = ast.get_docstring(ast.parse(path.read_text())) or ''
        title, _, body = docstring.partition('\n')
        out += [f'## `{path.name}`', '', f'*{title.strip()}*', '',
                '```{eval-rst}', body.strip(), '```', '',
                f'```{{literalinclude}} ../examples/{path.name}', ':language: python', ':lines: '
                f'{_FirstLineAfterDocstring(path)}-', '```', '']
    return '\n'.join(out)


def _FirstLineAfterDocstring(path: Path) -> int:
    module = ast.parse(path.read_text())
    first = module.body[0]
    isDocstring = isinstance(first, ast.Expr) and isinstance(getattr(first, 'value', None), ast.Constant)
    return first.end_lineno + 1 if isDocstring else 1


GENERATED = {'api': ApiPage, 'examples': ExamplesPage}


def _Generate(app, docname, source):
    if docname in GENERATED:
        source[0] = GENERATED[docname]()


def setup(app):
    app.connect('source-read', _Generate)
    return {'parallel_read_safe': True}
