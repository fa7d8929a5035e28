"""Sphinx configuration of the exudyn-worm documentation.

Build (writes nothing into the checkout): ``sphinx-build -W --keep-going -b html -d /tmp/doctrees docs /tmp/html``
after ``pip install -e '.[docs]'``. The pages are listed by the toctrees of ``index.md``.

Generated at build time, so they follow the code without edits:

- the API reference, ``api/index.md`` (the package and the names it re-exports) and one page per subpackage,
  ``api/<subpackage>.md`` (one autodoc section per public module; a nested subpackage
  has its own page, ``api/analysis.stability.md``, listed on its parent's page);
  a subpackage without its page, or a page
  without its subpackage, is a build warning;
- the gallery, ``gallery.md``: every script of ``examples/`` is run as the reader would run it,
  ``python examples/NAME.py --out DIR``, with DIR and its working folder in the doctree folder (``-d``), while
  the other pages are read; the page shows each example's docstring, the figures it wrote with their captions
  from ``gallery.toml``, what it printed, and its source. A caption's placeholders ``{name}`` are filled with
  what the example printed at this build (``[NAME.printed]`` of ``gallery.toml``: a regular expression per
  name); a number typed into a caption must be an input of the example (in its source). A failed example, a
  figure without a caption, a caption without its figure, an unfilled placeholder or a typed-in result is a
  build warning.

Equations are rendered by MathJax shipped with the site (``sphinx-mathjax-offline``): nothing is fetched from
the network. At the end of the build ``sitecheck.py`` checks every local link and anchor of the built site and
that no page loads a remote asset; each problem is a build warning, so ``-W`` fails on it.
"""
from __future__ import annotations

import ast
import importlib
import importlib.util
import os
import pkgutil
import re
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(ROOT))      # exudyn_worm from this checkout even without an install
sys.path.insert(0, str(DOCS))      # sitecheck.py

import exudyn_worm  # noqa: E402
import sitecheck  # noqa: E402
from sphinx.util import logging  # noqa: E402

if sys.version_info >= (3, 11):
    import tomllib
else:                               # a dependency of the package below Python 3.11
    import tomli as tomllib

logger = logging.getLogger('exudyn_worm.docs')

project = 'exudyn-worm'
author = 'exudyn-worm developers'
copyright = 'exudyn-worm developers'
release = version = exudyn_worm.__version__

extensions = ['myst_parser', 'sphinx.ext.autodoc', 'sphinx.ext.mathjax', 'sphinx-mathjax-offline',
              'sphinx.ext.viewcode', 'numpydoc']
source_suffix = {'.md': 'markdown', '.rst': 'restructuredtext'}
root_doc = 'index'
exclude_patterns = ['_build']
html_theme = 'furo'
html_title = f'exudyn-worm {release}'
html_static_path = ['_static']
html_css_files = ['math.css']

# MathJax 3 from the sphinx-mathjax-offline package, copied into _static/mathjax/ of the site
mathjax_path = 'mathjax/tex-chtml.js'

myst_enable_extensions = ['dollarmath', 'amsmath']
myst_heading_anchors = 3

autodoc_member_order = 'bysource'
autodoc_typehints = 'none'           # numpydoc's Parameters sections carry the types
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False

#: title of each subpackage's API page (the layers of docs/development.md, lowest first)
SUBPACKAGE_TITLES = {
    'params': 'Parameter registry and drive files',
    'model': 'The gear model and the analytical theory',
    'items': 'Exudyn items: the connector, the drivetrain, the solver',
    'drive': 'The drive boundary: the Drive, the resolver, preset data, duty',
    'builders': 'Exudyn model builders',
    'analysis': 'Analyses of a drive',
    'analysis.stability': 'Linear stability of a drive',
    'analysis.charts': 'Stability charts',
    'analysis.simulation': 'Time simulation of the machine',
    'analysis.orbits': 'Periodic orbits and chatter amplitude',
    'analysis.design': 'The design check',
    'analysis.studies': 'Parameter studies',
    'plotting': 'Plots',
    'cli': 'The command line',
}
GALLERY_DOC = 'gallery'
GALLERY_CAPTIONS = DOCS / 'gallery.toml'
#: seconds one example may run at build time
EXAMPLE_TIMEOUT = 900


# ---- API reference ---------------------------------------------------------------------------------------------

def PublicModules() -> list:
    """Names of the public modules of exudyn_worm (no part of the path starts with an underscore), sorted."""
    names = ['exudyn_worm']
    for info in pkgutil.walk_packages(exudyn_worm.__path__, 'exudyn_worm.'):
        if not any(part.startswith('_') for part in info.name.split('.')):
            names.append(info.name)
    return sorted(names)


def Subpackages() -> list:
    """Public subpackages below exudyn_worm ('analysis', 'analysis.stability', 'cli', ...), sorted."""
    return sorted(info.name.split('.', 1)[1] for info in pkgutil.walk_packages(exudyn_worm.__path__, 'exudyn_worm.')
                  if info.ispkg and not any(part.startswith('_') for part in info.name.split('.')))


def _Children(subpackage: str) -> list:
    """The subpackages directly below ``subpackage`` ('' for the package), in layer order."""
    depth = subpackage.count('.') + 1 if subpackage else 0
    return sorted((name for name in Subpackages() if name.count('.') == depth
                   and (not subpackage or name.startswith(subpackage + '.'))), key=_LayerOrder)


def _ApiDocs() -> list:
    return ['api/index'] + [f'api/{name}' for name in Subpackages()]


def _DefiningModule(name: str) -> str:
    """The public module below exudyn_worm whose ``__all__`` lists ``name`` and that defines the same object."""
    obj = getattr(exudyn_worm, name)
    home = getattr(obj, '__module__', None)
    candidates = []
    for modname in PublicModules()[1:]:
        module = importlib.import_module(modname)
        if name in getattr(module, '__all__', ()) and getattr(module, name, None) is obj:
            candidates.append(modname)
    return home if home in candidates else (candidates[0] if candidates else 'exudyn_worm')


def ApiIndexPage() -> str:
    """MyST text of the API reference's front page: the package, its re-exported names, the subpackage pages."""
    own = [n for n in exudyn_worm.__all__ if not n.startswith('_')
           and getattr(getattr(exudyn_worm, n), '__module__', None) == 'exudyn_worm']
    reexported = [n for n in exudyn_worm.__all__ if not n.startswith('_') and n not in own]
    others = [m for m in PublicModules() if m.count('.') == 1 and m.split('.')[1] not in Subpackages()]
    out = ['# API reference', '',
           'Generated from the docstrings (numpydoc) of every public module of `exudyn_worm` when the site is built:',
           'one page per subpackage (the layers of the package, lowest first, see [development](../development.md)),',
           'one section per module. A name that `exudyn_worm` re-exports (`import exudyn_worm as ew;',
           'ew.CreateWormGear`) is documented once, in the module that defines it; the table below links to it.',
           '', '```{toctree}', ':maxdepth: 1', '']
    out += _Children('')
    out += ['```', '', '## The package `exudyn_worm`', '', '```{eval-rst}', '.. automodule:: exudyn_worm']
    if own:
        out += [f'   :members: {", ".join(own)}']
    out += ['```', '', '### Names re-exported by `exudyn_worm`', '', '| name | defined in |', '| --- | --- |']
    for name in reexported:
        home = _DefiningModule(name)
        out.append(f'| {{py:obj}}`{name} <{home}.{name}>` | {{py:mod}}`{home}` |')
    for modname in others:
        out += ['', f'## `{modname}`', ''] + ModuleSection(modname)
    return '\n'.join(out) + '\n'


def _LayerOrder(name: str):
    order = list(SUBPACKAGE_TITLES)
    return (order.index(name) if name in order else len(order), name)


def SubpackagePage(subpackage: str) -> str:
    """MyST text of one subpackage's API page: its docstring, then one section per public module."""
    package = f'exudyn_worm.{subpackage}'
    title = SUBPACKAGE_TITLES.get(subpackage, package)
    out = [f'# {title} (`{package}`)', '', '```{eval-rst}', f'.. automodule:: {package}', '```', '']
    children = _Children(subpackage)
    if children:                      # nested subpackages: one page each, listed here
        out += ['```{toctree}', ':maxdepth: 1', ''] + children + ['```', '']
    for modname in PublicModules():
        if modname.rsplit('.', 1)[0] == package and modname.split('.', 1)[1] not in Subpackages():
            out += [f'## `{modname}`', ''] + ModuleSection(modname)
    return '\n'.join(out)


def ModuleSection(modname: str) -> list:
    """MyST lines documenting one module: its docstring and the members of ``__all__`` it defines itself.

    A name the module re-exports from another public module is listed with a link to where it is documented:
    documenting it twice would give two entries, and the source page's "[docs]" link would point at the
    module that happened to be documented first.
    """
    module = importlib.import_module(modname)
    names = getattr(module, '__all__', None)
    lines = ['```{eval-rst}', f'.. automodule:: {modname}']
    if names is None:
        lines.append('   :members:')
    own, elsewhere = [], []
    for name in names or ():
        home = getattr(getattr(module, name, None), '__module__', None)
        public = home in PublicModules() if home else False
        (elsewhere if home and home != modname and public else own).append((name, home))
    if own:
        lines.append(f'   :members: {", ".join(name for name, _ in own)}')
    lines += ['```', '']
    if elsewhere:
        lines += ['Also importable from here: ' + ', '.join(
            f'{{py:obj}}`{name} <{home}.{name}>` (from {{py:mod}}`{home}`)' for name, home in elsewhere) + '.', '']
    return lines


# ---- gallery ---------------------------------------------------------------------------------------------------

def ExampleScripts() -> list:
    """The example scripts (``examples/*.py``), sorted by name."""
    return sorted((ROOT / 'examples').glob('*.py'))


class _Gallery:
    """Runs the examples in the background (started when the gallery page is to be read) and waits for them."""

    def __init__(self) -> None:
        self.futures = {}
        self.folder = None
        self.workers = 1

    def Start(self, folder: Path) -> None:
        self.folder = folder
        workers = self.workers = max(1, min(len(ExampleScripts()), os.cpu_count() or 1))
        pool = ThreadPoolExecutor(max_workers=workers)
        self.futures = {path.stem: pool.submit(_RunExample, path, folder / path.stem) for path in ExampleScripts()}
        pool.shutdown(wait=False)

    def Result(self, name: str) -> dict:
        return self.futures[name].result()


def _RunExample(script: Path, outDir: Path) -> dict:
    """Run ``python examples/NAME.py --out DIR`` from a scratch folder; its figures, output and run time."""
    import shutil
    shutil.rmtree(outDir, ignore_errors=True)
    work = outDir.with_name(outDir.name + '.cwd')     # the example's working folder: nothing lands in the checkout
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    env = {**os.environ, 'MPLBACKEND': 'Agg', 'PYTHONPATH': os.pathsep.join(
        [str(ROOT)] + ([os.environ['PYTHONPATH']] if os.environ.get('PYTHONPATH') else []))}
    start = time.perf_counter()
    status, stdout, stderr, cpu = _RunTimed([sys.executable, str(script), '--out', str(outDir)], work, env,
                                            EXAMPLE_TIMEOUT)
    seconds = time.perf_counter() - start
    figures = sorted(outDir.glob('*.png')) if outDir.is_dir() else []
    return {'status': status, 'stdout': stdout.replace(str(outDir), 'DIR'), 'stderr': stderr,
            'seconds': seconds, 'cpuSeconds': cpu, 'figures': figures}


def _RunTimed(command: list, cwd: Path, env: dict, timeout: float):
    """Run ``command``; (exit status or None on timeout, stdout, stderr, processor seconds or None).

    The processor time (user + system, of the process and the processes it waited for) is what the example costs
    whatever else the machine runs: the wall time of a build that runs examples side by side on a shared machine
    is several times that.
    """
    import tempfile
    import threading
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        process = subprocess.Popen(command, cwd=cwd, env=env, stdout=out, stderr=err, stdin=subprocess.DEVNULL)
        killed = threading.Event()

        def Kill():
            killed.set()
            process.kill()
        timer = threading.Timer(timeout, Kill)
        timer.start()
        try:
            if hasattr(os, 'wait4'):
                _, waitStatus, usage = os.wait4(process.pid, 0)
                process.returncode = os.waitstatus_to_exitcode(waitStatus)
                cpu = usage.ru_utime + usage.ru_stime
            else:                                       # no wait4 (Windows): no processor time
                process.wait()
                cpu = None
        finally:
            timer.cancel()
        timedOut = killed.is_set()
        out.seek(0)
        err.seek(0)
        stdout, stderr = (f.read().decode('utf-8', errors='replace') for f in (out, err))
    if timedOut:
        return None, stdout, f'did not finish within {timeout:g} s', cpu
    return process.returncode, stdout, stderr, cpu


_GALLERY = _Gallery()


def _Captions() -> dict:
    with open(GALLERY_CAPTIONS, 'rb') as f:
        return tomllib.load(f)


def GalleryPage(srcdir: Path) -> str:
    """MyST text of the gallery: per example its docstring, figures with captions, printed output and source."""
    captions = _Captions()
    unknown = sorted(set(captions) - {p.stem for p in ExampleScripts()})
    for name in unknown:
        logger.warning(f'{GALLERY_CAPTIONS.name}: [{name}] names no script of examples/')
    out = ['# Gallery of examples', '',
           'Every script of `examples/` in the source checkout, run when this site was built exactly as you would run it,',
           '`python examples/NAME.py --out DIR`, with the figures it wrote into `DIR` and what it printed. Each',
           'example is also checked by its test in `tests/` (`tests/test_example_NAME.py`); `--help` lists its',
           'options. The drive files of `examples/drives/` are described in [Whole-drive files](drive-files.md).',
           "A caption's numbers are filled in at this build from what its example printed (shown below its figures);",
           'the other numbers of a caption are inputs of the example (in its source). The time beside each example',
           'is measured at this build.', '']
    index = []
    sections = []
    for path in ExampleScripts():
        name = path.stem
        run = _GALLERY.Result(name)
        docstring = ast.get_docstring(ast.parse(path.read_text(encoding='utf-8'))) or ''
        title, _, body = docstring.partition('\n')
        title = title.strip().rstrip('.')
        index.append(f'- [`{path.name}`](#example-{name}): {title}')
        if run['status'] != 0:
            logger.warning(f'gallery: examples/{path.name} failed (exit status {run["status"]}): '
                           f'{run["stderr"].strip().splitlines()[-1:] or ""}')
        own = dict(captions.get(name, {}))
        printed = own.pop(sitecheck.PRINTED_KEY, {})
        drawn = {p.name: p for p in run['figures']}
        for missing in sorted(set(drawn) - set(own)):
            logger.warning(f'gallery: examples/{path.name} drew {missing}, which has no caption in '
                           f'{GALLERY_CAPTIONS.name} [{name}]')
        for stale in sorted(set(own) - set(drawn)):
            logger.warning(f'gallery: {GALLERY_CAPTIONS.name} [{name}] has a caption for {stale}, which '
                           f'examples/{path.name} did not draw')
        part = [f'(example-{name})=', f'## {title}', '', f'`examples/{path.name}`: '
                f'`python examples/{path.name} --out DIR`, {_RunTime(run)}.', '',
                '```{eval-rst}', body.strip(), '```', '']
        source = path.read_text(encoding='utf-8')
        for figureName, figurePath in drawn.items():
            if figureName in own:
                caption, problems = sitecheck.FillCaption(own[figureName].strip(), printed, run['stdout'], source)
                for problem in problems:
                    logger.warning(f'gallery: {GALLERY_CAPTIONS.name} [{name}] {figureName}: {problem}')
                part += [f'```{{figure}} {os.path.relpath(figurePath, srcdir)}', f':alt: {figureName}', ':width: 100%',
                         '', f'`{figureName}`: {caption}', '```', '']
        part += ['What it prints:', '', '```text', run['stdout'].rstrip() or '(nothing)', '```', '',
                 'Its source:', '', f'```{{literalinclude}} ../examples/{path.name}', ':language: python',
                 f':lines: {_FirstLineAfterDocstring(path)}-', '```', '']
        sections += part
    return '\n'.join(out + index + [''] + sections)


def _RunTime(run: dict) -> str:
    """What the example cost when this site was built: its processor time, and the wall time beside the build."""
    if run.get('cpuSeconds') is None:
        return f'{run["seconds"]:.0f} s when this site was built'
    return (f'{run["cpuSeconds"]:.1f} s of processor time when this site was built ({run["seconds"]:.0f} s on the '
            f'clock, with {_GALLERY.workers} examples running at once beside the build)')


def _FirstLineAfterDocstring(path: Path) -> int:
    module = ast.parse(path.read_text(encoding='utf-8'))
    first = module.body[0]
    isDocstring = isinstance(first, ast.Expr) and isinstance(getattr(first, 'value', None), ast.Constant)
    return first.end_lineno + 1 if isDocstring else 1


# ---- command output ----------------------------------------------------------------------------------------------

#: seconds one command of a ``command-output`` block may run
COMMAND_TIMEOUT = 300


def CommandLine(text: str) -> list:
    """The argument list that runs ``text`` as a reader would: ``exudyn-worm ...`` is ``python -m exudyn_worm ...``
    and ``python`` this interpreter, both with the package of this checkout."""
    import shlex
    words = shlex.split(text)
    if words and words[0] == 'exudyn-worm':
        return [sys.executable, '-m', 'exudyn_worm'] + words[1:]
    if words and words[0] == 'python':
        return [sys.executable] + words[1:]
    return words


def SelectLines(text: str, pattern: 'str | None') -> str:
    """The lines of ``text`` that match ``pattern`` (a regular expression; all lines if None), each run of lines
    left out shown as one ``  ...``."""
    if not pattern:
        return text.rstrip()
    keep, skipped = [], False
    for line in text.rstrip().splitlines():
        if re.search(pattern, line):
            keep.append(line)
            skipped = False
        elif not skipped and keep:
            keep.append('  ...')
            skipped = True
        elif not keep:
            skipped = True
    if keep and keep[-1] == '  ...':
        keep.pop()
    return '\n'.join(keep)


def _CommandOutputDirective():
    """The ``command-output`` directive: runs its command when the page is read and shows what it printed.

    ````
    ```{command-output} exudyn-worm simulate --preset reel-P1
    :lines: window|lift|lower
    ```
    ````

    ``:lines:`` keeps the lines that match a regular expression (each run of the others becomes ``  ...``);
    ``:needs: MODULE`` shows a note instead of running the command when MODULE cannot be imported. The command runs
    in a scratch folder (nothing lands in the checkout), with ``:in-checkout:`` in the checkout (a command that
    writes nothing there, such as ``pytest --collect-only -p no:cacheprovider``); a failed command, or no line
    matching, is a build warning.
    A number on a page shown this way comes from the command beside it, run when the site was built.
    """
    import tempfile
    from docutils import nodes
    from docutils.parsers.rst import Directive, directives

    class CommandOutput(Directive):
        required_arguments = 1
        final_argument_whitespace = True
        option_spec = {'lines': directives.unchanged, 'needs': directives.unchanged, 'in-checkout': directives.flag}
        has_content = False

        def run(self):
            command = self.arguments[0].strip()
            where = f'{self.state.document.current_source}:{self.lineno}'
            needs = self.options.get('needs')
            if needs and importlib.util.find_spec(needs) is None:
                text = f'({needs} is not installed where this site was built: run `{command}` yourself)'
                return [nodes.literal_block(text, text, language='text')]
            env = {**os.environ, 'MPLBACKEND': 'Agg', 'PYTHONPATH': os.pathsep.join(
                [str(ROOT)] + ([os.environ['PYTHONPATH']] if os.environ.get('PYTHONPATH') else []))}
            with tempfile.TemporaryDirectory() as scratch:
                if 'in-checkout' in self.options:          # e.g. pytest, which finds the tests from there
                    env['PYTHONDONTWRITEBYTECODE'] = '1'
                cwd = ROOT if 'in-checkout' in self.options else Path(scratch)
                status, stdout, stderr, _ = _RunTimed(CommandLine(command), cwd, env, COMMAND_TIMEOUT)
            if status != 0:
                logger.warning(f'{where}: `{command}` failed (exit status {status}): '
                               f'{stderr.strip().splitlines()[-1:] or ""}')
            text = SelectLines(stdout.replace('\r\n', '\n'), self.options.get('lines'))
            if not text.strip():
                logger.warning(f'{where}: `{command}` printed no line that matches {self.options.get("lines")!r}')
            return [nodes.literal_block(text, text, language='text')]

    return CommandOutput


# ---- Sphinx hooks ----------------------------------------------------------------------------------------------

def _CheckApiPages(app) -> None:
    have = {p.stem for p in (DOCS / 'api').glob('*.md')} - {'index'}
    for name in sorted(set(Subpackages()) - have):
        logger.warning(f'docs/api/{name}.md is missing: every subpackage of exudyn_worm has its API page '
                       f'(a one-line placeholder, generated by docs/conf.py)')
    for name in sorted(have - set(Subpackages())):
        logger.warning(f'docs/api/{name}.md names no subpackage of exudyn_worm')
    for name in sorted(set(Subpackages()) - set(SUBPACKAGE_TITLES)):
        logger.warning(f'docs/conf.py: SUBPACKAGE_TITLES has no title for exudyn_worm.{name}')


def _AlwaysOutdated(app, env, added, changed, removed):
    """The generated pages follow the code and the examples, which Sphinx does not watch: read them every build."""
    return [d for d in _ApiDocs() + [GALLERY_DOC] if d in env.found_docs]


def _StartGallery(app, env, docnames):
    if GALLERY_DOC in docnames and not _GALLERY.futures:
        _GALLERY.Start(Path(app.doctreedir).resolve() / 'gallery')


def _Generate(app, docname, source):
    if docname == 'api/index':
        source[0] = ApiIndexPage()
    elif docname.startswith('api/'):
        source[0] = SubpackagePage(docname.split('/', 1)[1])
    elif docname == GALLERY_DOC:
        source[0] = GalleryPage(Path(app.srcdir))


def _ReexportedReference(app, env, node, contnode):
    """Resolve a reference to a name re-exported by exudyn_worm (``:func:`exudyn_worm.CreateWormGear```, or
    ``:func:`CreateWormGear``` in the package's own docstring) to the module that defines and documents it."""
    if node.get('refdomain') != 'py':
        return None
    target = node['reftarget'].lstrip('~.')
    if target.startswith('exudyn_worm.') and target.count('.') == 1:
        name = target.split('.', 1)[1]
    elif node.get('py:module') == 'exudyn_worm' and '.' not in target:
        name = target
    else:
        return None
    if name not in exudyn_worm.__all__ or name.startswith('_'):
        return None
    home = _DefiningModule(name)
    if home == 'exudyn_worm':
        return None
    return env.get_domain('py').resolve_xref(env, node['refdoc'], app.builder, node['reftype'], f'{home}.{name}',
                                             node, contnode)


#: an asterisk between a unit's letters or digits and a letter (``N*m*s/rad``, ``kg*m^2``): Markdown reads a pair of
#: them as emphasis (``N<em>m</em>s/rad``)
_UNIT_ASTERISK = re.compile(r'(?<=[A-Za-z0-9^)\]])\*(?=[A-Za-z])')
_FENCE = re.compile(r'\s*(`{3,}|~{3,})')


def EscapeUnitAsterisks(text: str) -> str:
    """Markdown ``text`` with the asterisks inside units escaped (``N\\*m\\*s/rad``), outside code blocks and spans.

    The reports the site includes from the repository (``validation/REPORT.md``, ...) are written by their own
    commands and not edited by hand; their units are written as the code writes them (``N*m*s``).
    """
    out, fence = [], None
    for line in text.split('\n'):
        opening = _FENCE.match(line)
        if fence is None and opening:
            fence = opening.group(1)
        elif fence is not None:
            if line.strip() == fence or (line.strip().startswith(fence[0] * len(fence)) and not line.strip().strip(fence[0])):
                fence = None
        else:
            parts = re.split(r'(`+[^`]*`+)', line)
            line = ''.join(part if i % 2 else _UNIT_ASTERISK.sub(r'\\*', part) for i, part in enumerate(parts))
        out.append(line)
    return '\n'.join(out)


def _EscapeIncluded(app, relativePath, parentDocname, content):
    """``include-read``: the units of an included report (Markdown) are no emphasis."""
    if str(relativePath).endswith('.md'):
        content[0] = EscapeUnitAsterisks(content[0])


def _CheckBuiltSite(app, exception):
    if exception is None and app.builder.format == 'html' and app.builder.name in ('html', 'dirhtml'):
        for problem in sitecheck.CheckSite(app.outdir):
            logger.warning(f'site check: {problem}')


def setup(app):
    app.connect('builder-inited', _CheckApiPages)
    app.connect('env-get-outdated', _AlwaysOutdated)
    app.connect('env-before-read-docs', _StartGallery)
    app.connect('source-read', _Generate)
    app.connect('include-read', _EscapeIncluded)
    app.add_directive('command-output', _CommandOutputDirective())
    app.connect('missing-reference', _ReexportedReference)
    app.connect('build-finished', _CheckBuiltSite, priority=900)    # after MathJax is copied (priority 500)
    return {'parallel_read_safe': False}
