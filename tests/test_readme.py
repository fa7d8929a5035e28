"""The Python examples of the README and of the docs pages run as written (docs that are true), without writing
to the cwd; the README's links into the docs site lead to pages that exist."""
import os
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / 'README.md'
#: the README and every page of the docs site (docs/*.md: the reference text moved there from the README)
PAGES = [README] + sorted((ROOT / 'docs').glob('*.md'))
BLOCKS = [(page, index, block) for page in PAGES
          for index, block in enumerate(re.findall(r'```python\n(.*?)```', page.read_text(), flags=re.S))]


@pytest.mark.parametrize('page, index, block', BLOCKS,
                         ids=[f'{page.relative_to(ROOT)}-{index}' for page, index, _ in BLOCKS])
def test_python_block_runs(page, index, block, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    exec(compile(block, f'{page.name} python block {index}', 'exec'), {'__name__': 'readme'})
    assert os.listdir(tmp_path) == []


def test_the_moved_examples_are_still_run():
    """The README's former examples (connector, linear stability, charts) live in docs pages and run here."""
    names = {page.name for page, _, _ in BLOCKS}
    assert {'README.md', 'python.md', 'charts.md'} <= names
    assert any('CreateWormGear' in block for _, _, block in BLOCKS)


def test_readme_starts_with_the_two_commands():
    text = README.read_text()
    commands = re.findall(r'```bash\n(.*?)\n```', text, flags=re.S)[:2]
    assert 'examples/paper_reel_changer.py' in commands[0]
    assert commands[1].endswith('pytest')
    ci = (README.parent / '.ci' / 'run').read_text()
    assert "pip install -e '.[test]'" in ci and 'pytest' in ci


def test_readme_links_into_the_docs_lead_to_pages():
    links = re.findall(r'\]\((docs/[^)#]+)', README.read_text())
    assert len(links) >= 10
    missing = [link for link in links if not (ROOT / link).is_file()]
    assert missing == []


def test_readme_and_ci_build_the_docs_with_warnings_as_errors():
    """One README command builds the site; .ci/run builds it with -W outside the checkout (-d for the doctrees)."""
    readme = [c for c in re.findall(r'```bash\n(.*?)\n```', README.read_text(), flags=re.S) if 'sphinx' in c]
    assert len(readme) == 1 and "'.[docs]'" in readme[0] and ' -W ' in readme[0] and ' docs ' in readme[0]
    ci = (ROOT / '.ci' / 'run').read_text()
    build = [line for line in ci.splitlines() if 'python -m sphinx' in line]
    assert len(build) == 1 and ' -W ' in build[0] and '-d "$tmp/' in build[0] and ' docs "$tmp/docs"' in build[0]
