"""The documentation site: pages a reader can follow, the checker of the built site, and (slow, with the docs
extra installed) the built site itself: every local link and anchor resolves and the equations need no network."""
import ast
import importlib
import importlib.util
import inspect
import pkgutil
import re
import subprocess
import sys
from pathlib import Path

import pytest

import exudyn_worm

if sys.version_info >= (3, 11):
    import tomllib
else:
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / 'docs'
_spec = importlib.util.spec_from_file_location('sitecheck', DOCS / 'sitecheck.py')
sitecheck = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(sitecheck)

#: what the site shows or the repository's front pages say: the docs pages and their captions, the reports the
#: site includes, the examples (the gallery shows their docstrings, output and source) and their drive files
PAGES = sorted([*DOCS.rglob('*.md'), DOCS / 'gallery.toml', *(ROOT / 'validation').glob('*.md'), ROOT / 'README.md',
                ROOT / 'benchmarks' / 'README.md', *(ROOT / 'examples').glob('*.py'),
                *(ROOT / 'examples' / 'drives').glob('*.toml')])
#: a tracker entry (the word issue and its number) means nothing to a reader, who has no access to the tracker
TRACKER = re.compile(r'\bissues? #?\d+', re.IGNORECASE)
#: paths outside the repository (the project's shared notes, the machine's work folders)
OUTSIDE = re.compile(r'\.\./shared\b|/work' + '/')     # split: this file passes the same grep


#: folders of build output, caches and environments (what .gitignore leaves out), when git cannot list the files
_NOT_SOURCE = {'.git', '__pycache__', '.venv', '.pytest_cache', '.hypothesis', 'build', 'dist', 'out', 'solution',
               'reel_changer_output'}


def _RepositoryFiles():
    """Every file of the checkout that git does not ignore (tracked or new), or, without git, every file outside
    the folders of build output."""
    try:
        listed = subprocess.run(['git', '-C', str(ROOT), 'ls-files', '-z', '--cached', '--others', '--exclude-standard'],
                                capture_output=True, check=True).stdout.decode('utf-8').split('\0')
        files = [ROOT / name for name in listed if name]
    except (OSError, subprocess.CalledProcessError):
        files = [path for path in ROOT.rglob('*') if not _NOT_SOURCE.intersection(path.relative_to(ROOT).parts)
                 and not any(part.endswith('.egg-info') for part in path.relative_to(ROOT).parts)]
    return sorted(path for path in files if path.is_file())


def _TextFiles():
    """The repository's text files (UTF-8 without NUL bytes; figures and other binary files are left out)."""
    texts = {}
    for path in _RepositoryFiles():
        data = path.read_bytes()
        try:
            texts[path] = data.decode('utf-8') if b'\0' not in data else None
        except UnicodeDecodeError:
            texts[path] = None
    return {path: text for path, text in texts.items() if text is not None}


TEXT_FILES = _TextFiles()


def _Hits(pattern, files):
    return [f'{path.relative_to(ROOT)}:{number}: {line.strip()}' for path, text in files.items()
            for number, line in enumerate(text.splitlines(), 1) if pattern.search(line)]


def test_the_greps_cover_the_repository():
    names = {path.relative_to(ROOT).as_posix() for path in TEXT_FILES}
    assert {page.relative_to(ROOT).as_posix() for page in PAGES} <= names
    assert {'tests/test_docs_site.py', 'exudyn_worm/__init__.py', 'validation/__main__.py', '.ci/run',
            'pyproject.toml'} <= names
    assert not any(name.startswith('.git/') or '__pycache__' in name or name.endswith('.png') for name in names)


def test_no_file_names_a_tracker_entry():
    """Code, docs, tests and reports name the requirement, never an entry of the project's tracker."""
    assert len(PAGES) > 40
    assert _Hits(TRACKER, TEXT_FILES) == []


def test_no_file_names_a_path_outside_the_repository():
    assert _Hits(OUTSIDE, TEXT_FILES) == []


def test_the_greps_find_what_they_look_for():
    word, number = 'issue', 15          # built here, so that this file passes a repository-wide grep too
    assert TRACKER.search(f'as asked in {word} {number}, item 2') and TRACKER.search(f'{word.title()} #{number}')
    assert TRACKER.search(f'{word}s {number}')
    assert not TRACKER.search(f'an {word} of the mesh') and not TRACKER.search(f't{word} {number}')
    shared, work = '../' + 'shared', '/' + 'work/'
    assert OUTSIDE.search(f'see {shared}/notes/exudyn-1.13.md') and OUTSIDE.search(f'{work}shared/paper')


def _Subpackages():
    # nested subpackages too ('analysis.stability'): each has its page, docs/api/<dotted name>.md
    return sorted(i.name.split('.', 1)[1] for i in pkgutil.walk_packages(exudyn_worm.__path__, 'exudyn_worm.')
                  if i.ispkg and not any(p.startswith('_') for p in i.name.split('.')))


def test_every_subpackage_has_its_api_page():
    """docs/conf.py fills docs/api/<subpackage>.md; a placeholder must exist for each subpackage, and no other."""
    pages = {p.stem for p in (DOCS / 'api').glob('*.md')} - {'index'}
    assert pages == set(_Subpackages())


def test_every_module_parses_for_its_source_page():
    """The source pages (sphinx.ext.viewcode) parse each module with type comments on: a comment beginning with
    '# type:' that is no type comment makes the parse fail and the module's source page go missing."""
    bad = []
    for path in sorted((ROOT / 'exudyn_worm').rglob('*.py')):
        try:
            ast.parse(path.read_text(encoding='utf-8'), type_comments=True)
        except SyntaxError as error:
            bad.append(f'{path.relative_to(ROOT)}:{error.lineno}: {error.msg}')
    assert bad == []


def test_gallery_captions_belong_to_examples():
    """Each table of docs/gallery.toml is an example, each caption names a PNG file and says something; each
    placeholder of a caption has its regular expression (one group) in the example's [printed] table, and each
    expression there is used."""
    captions = tomllib.loads((DOCS / 'gallery.toml').read_text(encoding='utf-8'))
    assert set(captions) == {p.stem for p in (ROOT / 'examples').glob('*.py')}
    for name, figures in captions.items():
        figures = dict(figures)
        printed = figures.pop(sitecheck.PRINTED_KEY, {})
        assert figures, name
        used = set()
        for figure, caption in figures.items():
            assert figure.endswith('.png') and len(caption.split()) >= 10, (name, figure)
            used.update(re.findall(r'\{(\w+)\}', caption))
        assert used <= set(printed), (name, sorted(used - set(printed)))
        assert set(printed) <= used, (name, sorted(set(printed) - used))
        for key, expression in printed.items():
            assert re.compile(expression).groups == 1, (name, key)


def test_gallery_captions_type_no_results():
    """A number typed into a gallery caption is an input of its example (it occurs in the example's source); a
    result is a placeholder filled from what the example printed when the site is built. The captions had typed
    results that no build checked: the 3D example's bearing loads read "about 59 kN" while it printed 48471 N."""
    captions = tomllib.loads((DOCS / 'gallery.toml').read_text(encoding='utf-8'))
    typed = {}
    for name, figures in captions.items():
        source = (ROOT / 'examples' / f'{name}.py').read_text(encoding='utf-8')
        for figure, caption in figures.items():
            if figure != sitecheck.PRINTED_KEY and sitecheck.TypedNumbers(caption, source):
                typed[name, figure] = sitecheck.TypedNumbers(caption, source)
    assert typed == {}


def test_fill_caption_takes_the_printed_digits():
    """FillCaption puts in the text the example printed, reports a placeholder without its expression or without
    a match, and a typed-in number that is no input of the example."""
    source = 'BACKLASH = 0.25  # mm\n'
    stdout = 'case   peak\nP1     102.4\nP7     795.0\n'
    printed = {'p1': r'^P1 +(\S+)', 'p9': r'^P9 +(\S+)'}
    text, problems = sitecheck.FillCaption('peak {p1} rad/s² with backlash 0.25 mm', printed, stdout, source)
    assert (text, problems) == ('peak 102.4 rad/s² with backlash 0.25 mm', [])
    text, problems = sitecheck.FillCaption('about 100 rad/s², {p9}, {p2}', printed, stdout, source)
    assert text == 'about 100 rad/s², {p9}, {p2}'
    assert len(problems) == 3
    assert 'the number 100 is neither an input' in problems[0]
    assert "{p9}" in problems[1] and 'matches nothing' in problems[1]
    assert '{p2}' in problems[2] and 'no entry' in problems[2]


def test_the_docs_extra_ships_the_math_renderer():
    """The docs extra installs MathJax; conf.py loads it from the site (a local path, no host)."""
    extras = tomllib.loads((ROOT / 'pyproject.toml').read_text())['project']['optional-dependencies']['docs']
    assert any(req.startswith('sphinx-mathjax-offline') for req in extras)
    assignments = {t.id: node.value for node in ast.parse((DOCS / 'conf.py').read_text()).body
                   if isinstance(node, ast.Assign) for t in node.targets if isinstance(t, ast.Name)}
    assert 'sphinx-mathjax-offline' in ast.literal_eval(assignments['extensions'])
    path = ast.literal_eval(assignments['mathjax_path'])
    assert '//' not in path and Path(path).name in sitecheck.MATH_RENDERERS


# ---- the checker of the built site, on small hand-made sites ---------------------------------------------------

def _Site(tmp_path, pages, files=()):
    """A folder of HTML pages (``{name: body}``) and other files (names, or ``{name: text}``)."""
    for name, html in pages.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(f'<html><head></head><body>{html}</body></html>')
    for name, text in (files.items() if isinstance(files, dict) else ((f, 'x') for f in files)):
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    return tmp_path


_MATHJAX = '<script defer src="_static/mathjax/tex-chtml.js?v=1"></script>'


def test_sitecheck_passes_a_sound_site(tmp_path):
    site = _Site(tmp_path, {
        'index.html': '<a href="model.html#eq-1">eq</a> <a href="#top" id="top">top</a> <a href="api/">api</a>'
                      '<a href="https://example.org/x.html#nowhere">away</a> <link rel="stylesheet" href="s.css">',
        'model.html': f'{_MATHJAX}<div class="math notranslate" id="eq-1">\\[x\\]</div><img src="_images/a.png">',
        'api/index.html': '<a href="../_modules/m.html#F" name="F">src</a>',
        '_modules/m.html': '<div id="F"><a class="viewcode-back" href="../api/index.html#F">[docs]</a></div>'},
        files={'s.css': 'a { background: url("data:image/svg+xml;charset=utf-8,<svg/>") } @font-face { src: url(f.woff) }',
               '_static/mathjax/tex-chtml.js': 'x', '_images/a.png': 'x'})
    assert sitecheck.CheckSite(site) == []
    assert sitecheck.main([str(site)]) == 0


def test_sitecheck_finds_each_kind_of_problem(tmp_path):
    site = _Site(tmp_path, {
        'index.html': '<a href="model.html#missing">a</a> <a href="gone.html">b</a> <img src="_images/none.png">',
        'model.html': '<div class="math">\\(x\\)</div>'
                      '<script src="https://cdn.jsdelivr.net/npm/mathjax@4/tex-mml-chtml.js"></script>',
        '_modules/m.html': '<a class="viewcode-back" href="../index.html#exudyn_worm.F">[docs]</a>'
                           '<link rel="stylesheet" href="//fonts.example.org/f.css"><link rel="stylesheet" href="../s.css">'},
        files={'s.css': '@import "https://fonts.example.org/x.css"; b { src: url(https://cdn.example.org/f.woff2) }'})
    problems = sitecheck.CheckSite(site)
    assert problems == sorted([
        '_modules/m.html: <a> links to a missing anchor: ../index.html#exudyn_worm.F',
        '_modules/m.html: <link> loads a remote asset //fonts.example.org/f.css',
        'index.html: <a> links to a missing anchor: model.html#missing',
        'index.html: <a> links to a missing file: gone.html',
        'index.html: <img> links to a missing file: _images/none.png',
        'model.html: <script> loads a remote asset https://cdn.jsdelivr.net/npm/mathjax@4/tex-mml-chtml.js',
        'model.html: has equations but loads no math renderer shipped with the site '
        f'(one of {", ".join(sitecheck.MATH_RENDERERS)})',
        's.css: loads a remote asset https://cdn.example.org/f.woff2',
        's.css: loads a remote asset https://fonts.example.org/x.css'])
    assert sitecheck.main([str(site)]) == 1


def test_sitecheck_finds_a_code_fence_that_swallowed_text(tmp_path):
    """A closing fence with text after it (```` ``` In --json the ````) leaves the block open: the paragraph and the
    next example become one code block with a literal fence line in it."""
    swallowed = ('<div class="highlight-bash"><div class="highlight"><pre><span></span>exudyn-worm chart\n'
                 '<span class="err">```</span> In --json the\nranges are\n\n'
                 '<span class="err">```</span>python\nfrom exudyn_worm import x\n</pre></div></div>')
    sound = ('<div class="highlight"><pre>exudyn-worm chart\n</pre></div><p>In <code>--json</code> the ranges, '
             'and a fence quoted inside a line: <code>```python</code></p><pre>s = "```" if x else y\n</pre>')
    site = _Site(tmp_path, {'index.html': sound, 'charts.html': swallowed})
    assert sitecheck.CheckSite(site) == [
        "charts.html: a code block holds a Markdown code fence line '``` In --json the': text after a closing "
        "fence keeps the block open",
        "charts.html: a code block holds a Markdown code fence line '```python': text after a closing fence keeps "
        "the block open"]


def test_sitecheck_finds_unit_asterisks_read_as_emphasis(tmp_path):
    """``N*m*s/rad`` in Markdown shows as "Nms/rad" with an italic m; ``kg*m^2 ... N*m`` italicizes the text
    between the two units."""
    site = _Site(tmp_path, {
        'index.html': '<p>A setting\n<em>passes</em> if both; <em>stable with margin</em>, (<em>S</em> = -1); '
                      'N·m·s/rad, N*m*s/rad, <code>N*m</code></p><pre>a <em>b</em>c</pre>'
                      '<dt><em class="sig-param">mbs</em></dt>',
        'parameters.html': '<td><p>N<em>m</em>s/rad</p></td>',
        'presets.html': '<p>J2 = 33 kg<em>m^2, kT = 7000 N</em>m/rad</p><p>dV = 1250 N<em>s/m), D_V = 0.028 '
                        '(set (25), dV = 625 N</em>s/m</p>'})
    assert sitecheck.CheckSite(site) == [
        "parameters.html: emphasis inside a word, 'N<em>m</em>s/rad': asterisks of a unit (N*m*s) read as Markdown "
        "emphasis; escape them (N\\*m\\*s) or write N·m·s",
        "presets.html: emphasis inside a word, 'J2 = 33 kg<em>m^2, kT = 7000 N</em>m/rad': asterisks of a unit "
        "(N*m*s) read as Markdown emphasis; escape them (N\\*m\\*s) or write N·m·s",
        "presets.html: emphasis inside a word, 'dV = 1250 N<em>s/m), D_V = 0.028 (set (25), dV = 625 N</em>s/m': "
        "asterisks of a unit (N*m*s) read as Markdown emphasis; escape them (N\\*m\\*s) or write N·m·s"]


def test_sitecheck_finds_a_tag_inside_the_split_sphinx_adds(tmp_path):
    """Sphinx wraps a display equation with a line break in ``split``, where MathJax refuses ``\\tag`` ("\\tag not
    allowed in split environment", as MathJax 3 printed for eq. (16)); an amsmath block keeps its tag."""
    site = _Site(tmp_path, {
        'index.html': f'{_MATHJAX}<div class="math notranslate nohighlight">\\[\\begin{{equation*}}\\begin{{aligned}}'
                      'a \\\\ b\\end{aligned}\\tag{1}\\end{equation*}\\]</div>'
                      '<div class="math">\\[x \\tag{3}\\]</div>',
        'model.html': f'{_MATHJAX}<div class="math notranslate nohighlight">\\[\\begin{{split}}\\begin{{aligned}}'
                      'b_1 &= x\\\\ b_2 &= y\\end{aligned} \\tag{16}\\end{split}\\]</div>'},
        files={'_static/mathjax/tex-chtml.js': 'x'})
    assert sitecheck.CheckSite(site) == [
        'model.html: equation \\tag{16} is inside the split environment Sphinx wraps around a display equation with '
        'a line break: MathJax shows an error; write it as an amsmath block (\\begin{equation*} \\begin{aligned} ... '
        '\\end{aligned} \\tag{..} \\end{equation*})']


def test_sitecheck_refuses_a_folder_that_is_no_site(tmp_path, capsys):
    with pytest.raises(ValueError, match="'siteDir' must be a built HTML site"):
        sitecheck.CheckSite(tmp_path)
    assert sitecheck.main([str(tmp_path)]) == 2
    assert 'sitecheck.py: error:' in capsys.readouterr().err


# ---- what docs/conf.py does to the pages (needs the docs extra) -------------------------------------------------

def _Conf():
    spec = importlib.util.spec_from_file_location('docs_conf', DOCS / 'conf.py')
    conf = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(conf)
    return conf


@pytest.mark.skipif(importlib.util.find_spec('sphinx') is None, reason="needs the docs extra: pip install -e '.[docs]'")
def test_included_reports_keep_the_asterisks_of_their_units():
    """The reports the site includes write units as the code does (N*m*s); escaped, they are no emphasis."""
    escape = _Conf().EscapeUnitAsterisks
    text = ('dT = 0.741 N*m*s, J1 = 0.1 kg*m^2 and kT = 7000 N*m/rad; *stable* and **bold**, `N*m` in code\n'
            '```text\nN*m*s\n```\nafter the block N*s/m')
    assert escape(text) == ('dT = 0.741 N\\*m\\*s, J1 = 0.1 kg\\*m^2 and kT = 7000 N\\*m/rad; *stable* and **bold**, '
                            '`N*m` in code\n```text\nN*m*s\n```\nafter the block N\\*s/m')


@pytest.mark.skipif(importlib.util.find_spec('sphinx') is None, reason="needs the docs extra: pip install -e '.[docs]'")
def test_command_output_shows_the_selected_lines_and_marks_the_rest():
    conf = _Conf()
    text = 'head\n  a 1\n  b 2\n  c 3\nVerdict: x\nHint: y\n'
    assert conf.SelectLines(text, r'^head|b 2|^Verdict') == 'head\n  ...\n  b 2\n  ...\nVerdict: x'
    assert conf.SelectLines(text, None) == text.rstrip()
    assert conf.CommandLine('exudyn-worm simulate --preset reel-P1')[1:] == ['-m', 'exudyn_worm', 'simulate',
                                                                           '--preset', 'reel-P1']
    assert conf.CommandLine('python -m pytest -m "not slow"')[1:] == ['-m', 'pytest', '-m', 'not slow']


# ---- the built site (needs the docs extra) ---------------------------------------------------------------------

def _DocsExtraInstalled():
    return all(importlib.util.find_spec(name) is not None
               for name in ('sphinx', 'myst_parser', 'numpydoc', 'furo', 'sphinx-mathjax-offline'))


def _ModulesWithCode():
    """Public modules that define a function or class of their ``__all__``: each has a highlighted source page."""
    names = []
    for info in pkgutil.walk_packages(exudyn_worm.__path__, 'exudyn_worm.'):
        if any(part.startswith('_') for part in info.name.split('.')):
            continue
        module = importlib.import_module(info.name)
        objects = [getattr(module, n) for n in getattr(module, '__all__', ())]
        if any((inspect.isfunction(obj) or inspect.isclass(obj)) and obj.__module__ == info.name for obj in objects):
            names.append(info.name)
    return names


@pytest.mark.slow
@pytest.mark.skipif(not _DocsExtraInstalled(), reason="needs the docs extra: pip install -e '.[docs]'")
def test_built_site_has_working_links_and_offline_math(tmp_path):
    """The site as .ci/run builds it (-W): no warning, every link and anchor resolves, MathJax comes with it."""
    out = tmp_path / 'html'
    run = subprocess.run([sys.executable, '-m', 'sphinx', '-W', '--keep-going', '-q', '-b', 'html',
                          '-d', str(tmp_path / 'doctrees'), str(DOCS), str(out)], capture_output=True, text=True,
                         cwd=tmp_path)
    assert run.returncode == 0, run.stderr[-3000:]
    assert sitecheck.CheckSite(out) == []
    model = sitecheck.ReadPage(out / 'model.html')
    assert model.hasMath and ('script', '_static/mathjax/tex-chtml.js') in model.assets
    assert (out / '_static' / 'mathjax' / 'output' / 'chtml' / 'fonts' / 'woff-v2').is_dir()
    assert _ModulesWithCode() and [m for m in _ModulesWithCode()
                                   if not (out / '_modules' / (m.replace('.', '/') + '.html')).is_file()] == []
    gallery = (out / 'gallery.html').read_text(encoding='utf-8')
    captions = tomllib.loads((DOCS / 'gallery.toml').read_text(encoding='utf-8'))
    for figures in captions.values():
        printed = figures.get(sitecheck.PRINTED_KEY, {})
        for figure in figures:
            if figure != sitecheck.PRINTED_KEY:
                assert f'_images/{figure}' in gallery, figure
        for name in printed:                          # filled from what the example printed at this build
            assert '{' + name + '}' not in gallery, name
