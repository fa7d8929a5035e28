r"""Checks of the built documentation site: every local link and anchor resolves, nothing is fetched from the network.

Run on a built site (``docs/conf.py`` runs it at the end of every HTML build, so ``sphinx-build -W`` fails on a
problem)::

    python docs/sitecheck.py build/docs

It reads every ``*.html`` file below the folder and reports

- a broken local link: an ``href`` or ``src`` to a file that is not in the site, or to an ``#anchor`` (an ``id`` or
  ``name``) that the target page does not have; the source pages' "[docs]" back-links are such links;
- a remote asset: a script, style sheet, image or font loaded from another host (``http:``, ``https:`` or ``//``),
  by a page or by one of its style sheets (``url(...)``, ``@import``), which a reader behind a firewall or offline
  does not get;
- a page with equations (an element of class ``math``) that loads no math renderer shipped with the site;
- a code block (``<pre>``) with a line that starts with a Markdown code fence (three backticks or tildes): a
  closing fence followed by text on its line does not close the block, so the text and the next example are
  shown as one code block with a literal fence line;
- emphasis inside a word (``N<em>m</em>s/rad``): the asterisks of a unit (``N*m*s/rad``) read as Markdown
  emphasis, so the reader sees "Nms/rad";
- an equation with ``\tag`` inside the ``split`` environment that Sphinx wraps around a display equation with a
  line break (``\\``): MathJax shows an error instead of the equation (write such an equation as an amsmath
  block, ``\begin{equation*} \begin{aligned} ... \end{aligned} \tag{1} \end{equation*}``, which Sphinx does not
  number again).

Links to other sites (``<a href="https://...">``) are not followed: the check is about the site's own pages.

The gallery's captions (``docs/gallery.toml``) are checked while the gallery is built: :func:`FillCaption` fills
their placeholders with what each example printed at that build and reports a number typed into a caption that is
no input of its example (:func:`TypedNumbers`); ``docs/conf.py`` turns each report into a build warning.
Exit status 0 when there is no problem, 1 otherwise (one line per problem on stdout), 2 for a folder that is no
built site.
"""
from __future__ import annotations

import re
import sys
from html.parser import HTMLParser
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Set, Tuple
from urllib.parse import unquote, urlsplit

__all__ = ['MATH_RENDERERS', 'PRINTED_KEY', 'PageLinks', 'ReadPage', 'CheckSite', 'TypedNumbers', 'FillCaption',
           'main']

#: file names of the math renderers the site may ship (MathJax 3 components, KaTeX)
MATH_RENDERERS = ('tex-chtml.js', 'tex-svg.js', 'tex-mml-chtml.js', 'tex-mml-svg.js', 'katex.min.js', 'katex.js')

# tag -> attributes that load an asset the page needs (as opposed to <a href>, a link the reader may follow)
_ASSET_ATTRIBUTES = {'script': ('src',), 'img': ('src',), 'source': ('src', 'srcset'), 'iframe': ('src',),
                     'embed': ('src',), 'video': ('src', 'poster'), 'audio': ('src',), 'object': ('data',)}


class PageLinks:
    """What one HTML page defines and refers to.

    Attributes
    ----------
    anchors : set of str
        Every ``id`` and ``name`` (of ``<a>``) on the page.
    links : list of (str, str)
        ``(tag, url)`` of every ``<a href>`` and ``<link href>`` (not followed when remote).
    assets : list of (str, str)
        ``(tag, url)`` of every script, image, frame and media source the page loads, and of the style sheets,
        preloads and icons among the ``<link>`` elements.
    hasMath : bool
        The page has an element of class ``math`` (an equation for MathJax or KaTeX).
    fenceLines : list of str
        Lines of its code blocks (``<pre>``) that start with a Markdown code fence (a fence that swallowed text).
    wordEmphasis : list of str
        Emphasis (``<em>`` without a class) that begins or ends inside a word, shown as ``N<em>m</em>s/rad``
        with a few characters around it (the asterisks of a unit read as Markdown emphasis).
    taggedSplits : list of str
        The tags (``\tag{1}``) of display equations that have them inside a ``split`` environment.
    """

    def __init__(self) -> None:
        self.anchors: Set[str] = set()
        self.links: List[Tuple[str, str]] = []
        self.assets: List[Tuple[str, str]] = []
        self.hasMath = False
        self.fenceLines: List[str] = []
        self.wordEmphasis: List[str] = []
        self.taggedSplits: List[str] = []


_FENCE_LINE = re.compile(r'^\s*(```|~~~)')
#: characters a unit's asterisk stands between: ``N*m``, ``kg*m^2``, ``1/(m*s)``
_WORD_BEFORE, _WORD_AFTER = re.compile(r'[A-Za-z0-9^)\]]\Z'), re.compile(r'^[A-Za-z0-9/^]')

_BLOCKS = {'p', 'div', 'td', 'th', 'tr', 'li', 'dt', 'dd', 'br', 'pre', 'table', 'section', 'blockquote',
           'h1', 'h2', 'h3', 'h4', 'h5', 'h6', 'figcaption'}


class _Parser(HTMLParser):
    def __init__(self, page: PageLinks) -> None:
        super().__init__(convert_charrefs=True)
        self.page = page
        self.preDepth = 0
        self.mathDepth = 0              # inside <div class="math">: the equation's TeX as MathJax gets it
        self.preText: List[str] = []
        self.before = ''               # the last characters of text outside code blocks
        self.emphasis: Optional[List[str]] = None     # text of the plain <em> being read
        self.emBefore = ''
        self.afterEm: Optional[Tuple[str, str]] = None   # (text before, emphasized text) waiting for what follows

    def handle_data(self, data):
        if self.mathDepth and '\\begin{split}' in data:
            self.page.taggedSplits += re.findall(r'\\tag\{[^}]*\}', data.split('\\begin{split}', 1)[1])
        if self.preDepth:
            self.preText.append(data)
            return
        if self.afterEm is not None and data:
            self._CheckEmphasis(*self.afterEm, data)
            self.afterEm = None
        if self.emphasis is not None:
            self.emphasis.append(data)
        self.before = (self.before + data)[-24:]

    def _CheckEmphasis(self, before: str, text: str, after: str) -> None:
        opensInWord = bool(_WORD_BEFORE.search(before)) and bool(_WORD_AFTER.search(text))
        closesInWord = bool(re.search(r'[A-Za-z0-9^]\Z', text)) and bool(_WORD_AFTER.search(after))
        if text and (opensInWord or closesInWord):
            shown = f'{before[-12:]}<em>{text}</em>{after[:8]}'.split('\n')
            self.page.wordEmphasis.append(' '.join(part.strip() for part in shown))

    def handle_endtag(self, tag):
        if tag == 'div' and self.mathDepth:
            self.mathDepth -= 1
        if tag == 'pre' and self.preDepth:
            self.preDepth -= 1
            if not self.preDepth:
                self.page.fenceLines += [line.strip() for line in ''.join(self.preText).splitlines()
                                         if _FENCE_LINE.match(line)]
                self.preText = []
        elif tag == 'em' and self.emphasis is not None and not self.preDepth:
            self.afterEm = (self.emBefore, ''.join(self.emphasis))
            self.emphasis = None

    def handle_starttag(self, tag, attrs):
        a = {k: (v or '') for k, v in attrs}
        if tag in _BLOCKS:                           # a new block: no word goes on from the text before
            self.before = ''
        if tag == 'pre':
            self.preDepth += 1
        elif self.afterEm is not None:             # a tag after </em>: no word goes on
            self.afterEm = None
        if tag == 'em' and not self.preDepth and not a.get('class'):
            self.emphasis, self.emBefore = [], self.before
        if a.get('id'):
            self.page.anchors.add(a['id'])
        if tag == 'a' and a.get('name'):
            self.page.anchors.add(a['name'])
        if 'math' in a.get('class', '').split():
            self.page.hasMath = True
            if tag == 'div':
                self.mathDepth += 1
        elif tag == 'div' and self.mathDepth:
            self.mathDepth += 1
        if tag == 'a' and 'href' in a:
            self.page.links.append((tag, a['href']))
        elif tag == 'link' and 'href' in a:
            rel = set(a.get('rel', '').lower().split())
            target = self.page.assets if rel & {'stylesheet', 'preload', 'icon', 'modulepreload'} else self.page.links
            target.append((tag, a['href']))
        for name in _ASSET_ATTRIBUTES.get(tag, ()):
            if a.get(name):
                urls = [part.split()[0] for part in a[name].split(',') if part.strip()] if name == 'srcset' \
                    else [a[name]]
                self.page.assets += [(tag, url) for url in urls]

    def handle_startendtag(self, tag, attrs):
        self.handle_starttag(tag, attrs)
        if tag == 'pre':                            # <pre/> holds nothing
            self.handle_endtag(tag)


def ReadPage(path: Path) -> PageLinks:
    """Parse one HTML file.

    Parameters
    ----------
    path : Path
        The HTML file.

    Returns
    -------
    PageLinks
        Its anchors, links, assets and whether it has equations.
    """
    page = PageLinks()
    _Parser(page).feed(path.read_text(encoding='utf-8', errors='replace'))
    return page


def _HasScheme(url: str) -> bool:
    """A URL with a scheme (``https:``, ``mailto:``, ``data:``) or a host (``//host/...``): not a file of the site."""
    return bool(urlsplit(url).scheme) or url.startswith('//')


def _IsRemote(url: str) -> bool:
    """A URL that is fetched from another host (``data:`` and the like are inline, not fetched)."""
    return url.startswith('//') or urlsplit(url).scheme.lower() in ('http', 'https', 'ftp')


def CheckSite(siteDir) -> List[str]:
    """Every problem of the built site in ``siteDir``, one sentence each (empty: none).

    Parameters
    ----------
    siteDir : str or Path
        Output folder of ``sphinx-build -b html`` (it holds ``index.html``).

    Returns
    -------
    list of str
        ``'<page>: ...'`` per broken local link or anchor, remote asset, page with equations but no math
        renderer from the site, code fence line inside a code block, emphasis inside a word and tagged equation
        inside a ``split`` environment; sorted.

    Raises
    ------
    ValueError
        If ``siteDir`` holds no ``index.html``.
    """
    root = Path(siteDir).resolve()
    if not (root / 'index.html').is_file():
        raise ValueError(f"CheckSite: 'siteDir' must be a built HTML site (a folder with index.html), got {str(siteDir)!r}")
    pages: Dict[Path, PageLinks] = {p.resolve(): ReadPage(p) for p in root.rglob('*.html')}
    problems = set()
    allStylesheets = set()
    for path, page in pages.items():
        where = path.relative_to(root).as_posix()
        renderers, stylesheets = [], []
        for kind, items in (('link', page.links), ('asset', page.assets)):
            for tag, url in items:
                if _HasScheme(url):
                    if kind == 'asset' and _IsRemote(url):
                        problems.add(f'{where}: <{tag}> loads a remote asset {url}')
                    continue
                problem, target = _CheckLocal(root, path, url, pages)
                if problem:
                    problems.add(f'{where}: <{tag}> {problem}')
                elif kind == 'asset' and target is not None and target.name in MATH_RENDERERS:
                    renderers.append(target)
                elif kind == 'asset' and target is not None and target.suffix == '.css':
                    stylesheets.append(target)
        allStylesheets.update(stylesheets)
        problems.update(f'{where}: a code block holds a Markdown code fence line {line!r}: text after a closing '
                        f'fence keeps the block open' for line in page.fenceLines)
        problems.update(f'{where}: equation {tag} is inside the split environment Sphinx wraps around a display '
                        f'equation with a line break: MathJax shows an error; write it as an amsmath block '
                        f'(\\begin{{equation*}} \\begin{{aligned}} ... \\end{{aligned}} \\tag{{..}} '
                        f'\\end{{equation*}})' for tag in page.taggedSplits)
        problems.update(f'{where}: emphasis inside a word, {shown!r}: asterisks of a unit (N*m*s) read as Markdown '
                        f'emphasis; escape them (N\\*m\\*s) or write N·m·s' for shown in page.wordEmphasis)
        if page.hasMath and not renderers:
            problems.add(f'{where}: has equations but loads no math renderer shipped with the site '
                         f'(one of {", ".join(MATH_RENDERERS)})')
    for stylesheet in sorted(allStylesheets):
        problems.update(f'{stylesheet.relative_to(root).as_posix()}: loads a remote asset {url}'
                        for url in _RemoteUrlsInCss(stylesheet))
    return sorted(problems)


_CSS_URL = re.compile(r"""url\(\s*['"]?([^'")\s]+)|@import\s+['"]([^'"]+)""")


def _RemoteUrlsInCss(path: Path) -> List[str]:
    """URLs of other hosts that a style sheet loads (``url(...)``, ``@import``): fonts, images, more styles."""
    text = path.read_text(encoding='utf-8', errors='replace')
    return sorted({url for match in _CSS_URL.finditer(text) for url in match.groups() if url and _IsRemote(url)})


def _CheckLocal(root: Path, page: Path, url: str, pages: Dict[Path, PageLinks]) -> Tuple[Optional[str], Optional[Path]]:
    """(problem or None, the target file) of one local URL on ``page``."""
    parts = urlsplit(url)
    fragment = unquote(parts.fragment)
    target = page if not parts.path else (page.parent / unquote(parts.path)).resolve()
    if target.is_dir():
        target = target / 'index.html'
    if root not in target.parents and target != root:
        return f'links outside the site: {url}', None
    if not target.is_file():
        return f'links to a missing file: {url}', None
    if fragment and target.suffix == '.html':
        anchors = pages[target].anchors if target in pages else ReadPage(target).anchors
        if fragment not in anchors:
            return f'links to a missing anchor: {url}', target
    return None, target


# ---- the gallery's captions (docs/gallery.toml; docs/conf.py fills them when it builds the gallery) ---------------

#: the key of an example's table in ``gallery.toml`` that says where its captions' numbers are printed
PRINTED_KEY = 'printed'
#: a number in a caption's text: not part of a name (``P1``, ``fig08``, ``D_V``)
_CAPTION_NUMBER = re.compile(r'(?<![\w.])[-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?(?![\w])')
#: a placeholder in a caption: ``{name}``, filled with what the example printed
_CAPTION_PLACEHOLDER = re.compile(r'\{(\w+)\}')


def TypedNumbers(caption: str, source: str) -> List[str]:
    """The numbers typed into a gallery caption (outside its placeholders) that are no input of its example.

    A number in a caption's text must occur as a number in the example's source (a backlash of 0.25 mm, a speed
    of 160 rpm); a result typed in by hand (a peak, a frequency) is a placeholder instead, filled at each build
    from what the example printed (:func:`FillCaption`).

    Parameters
    ----------
    caption : str
        A caption of ``gallery.toml``.
    source : str
        The source of its example.

    Returns
    -------
    list of str
        The offending numbers, in the order of the caption (empty: none).
    """
    inputs = {m.group().lstrip('+-') for m in _CAPTION_NUMBER.finditer(source)}
    return [m.group() for m in _CAPTION_NUMBER.finditer(_CAPTION_PLACEHOLDER.sub(' ', caption))
            if m.group().lstrip('+-') not in inputs]


def FillCaption(caption: str, printed: Dict[str, str], stdout: str, source: str) -> Tuple[str, List[str]]:
    """A gallery caption with its numbers from this build's run of its example, and what is wrong with it.

    Each placeholder ``{name}`` of ``caption`` becomes the text that the regular expression ``printed[name]``
    captures (its first group) in the example's printed output ``stdout``, searched line by line: the digits the
    example printed at this build. A number typed into the caption must be an input of the example
    (:func:`TypedNumbers`).

    Parameters
    ----------
    caption : str
        A caption of ``gallery.toml``.
    printed : dict of str
        Placeholder name -> regular expression with one group, searched in ``stdout``.
    stdout : str
        What the example printed at this build.
    source : str
        The example's source.

    Returns
    -------
    (str, list of str)
        The caption with its placeholders filled (one that cannot be filled is left as it is), and one sentence
        per problem (empty: none).
    """
    problems = [f'the number {number} is neither an input of the example (a number in its source) nor a '
                f'placeholder filled from what it printed' for number in TypedNumbers(caption, source)]

    def Fill(match):
        name = match.group(1)
        if name not in printed:
            problems.append(f'the placeholder {{{name}}} has no entry in [{PRINTED_KEY}]')
            return match.group()
        found = re.search(printed[name], stdout, re.MULTILINE)
        if found is None or not found.groups() or found.group(1) is None:
            problems.append(f'the placeholder {{{name}}}: {printed[name]!r} matches nothing the example printed')
            return match.group()
        return found.group(1)
    return _CAPTION_PLACEHOLDER.sub(Fill, caption), problems


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Command line: check the site in the folder given; print one line per problem. Returns the exit status.

    Parameters
    ----------
    argv : sequence of str, optional
        ``[SITE_DIR]`` (default: ``sys.argv[1:]``).
    """
    args = list(sys.argv[1:] if argv is None else argv)
    if len(args) != 1 or args[0].startswith('-'):
        print('usage: python docs/sitecheck.py SITE_DIR   (the output folder of sphinx-build -b html)', file=sys.stderr)
        return 2
    try:
        problems = CheckSite(args[0])
    except ValueError as error:
        print(f'sitecheck.py: error: {error}', file=sys.stderr)
        return 2
    for line in problems:
        print(line)
    print(f'sitecheck.py: {len(problems)} problem(s) in {args[0]}', file=sys.stderr)
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
