"""The README's commands and the Python examples of the README and of the docs pages run as written (docs that are
true), without writing to the cwd; the README's links into the docs site lead to pages that exist."""
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

from exudyn_worm.cli.main import Main

if sys.version_info >= (3, 11):
    import tomllib
else:
    import tomli as tomllib

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


def _BashBlocks(path):
    return re.findall(r'```bash\n(.*?)\n```', path.read_text(encoding='utf-8'), flags=re.S)


_VENV = 'python -m venv .venv && . .venv/bin/activate'
#: the README's two commands, as written: the main job (the paper's reel changer) and the test suite
MAIN_JOB = f'{_VENV} && pip install -e . && python examples/paper_reel_changer.py --out reel_changer_output'
TEST_SUITE = f"{_VENV} && pip install -e '.[test]' && pytest"
PNG = b'\x89PNG\r\n\x1a\n'


def test_readme_starts_with_the_two_commands():
    """The README and the getting-started page open with the same two commands; .ci/run runs the second one's
    steps, and pytest without options runs every test (no marker filter in the configuration: ``slow`` tests too)."""
    assert _BashBlocks(README)[:2] == [MAIN_JOB, TEST_SUITE]
    assert _BashBlocks(ROOT / 'docs' / 'getting-started.md')[:2] == [MAIN_JOB, TEST_SUITE]
    ci = [line.strip() for line in (ROOT / '.ci' / 'run').read_text().splitlines()]
    assert "python -m pip install -e '.[test]'" in ci and 'pytest || status=$?' in ci
    options = tomllib.loads((ROOT / 'pyproject.toml').read_text())['tool']['pytest']['ini_options']
    assert '-m' not in shlex.split(options.get('addopts', '')) and options['testpaths'] == ['tests']


@pytest.mark.slow
def test_main_job_writes_the_figures_it_promises(tmp_path):
    """The first command's run, as written, from the checkout (the output folder in tmp_path): exit status 0, the
    summary table of every case (P1, its variants P2 and P7, the backlash studies), and the paper's Figures 8-18 as
    PNG files, the ones the gallery shows; nothing else written into the checkout."""
    command = shlex.split(MAIN_JOB.split(' && ')[-1])
    assert command[0] == 'python' and command[-2:] == ['--out', 'reel_changer_output']
    before = sorted(p.name for p in ROOT.iterdir())
    out = tmp_path / 'reel_changer_output'
    run = subprocess.run([sys.executable, *command[1:-1], str(out)], cwd=ROOT, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr[-3000:]
    assert sorted(p.name for p in ROOT.iterdir()) == before
    figures = sorted(p.name for p in out.iterdir())
    assert [name[:5] for name in figures] == [f'fig{n:02d}' for n in range(8, 19)]        # Figures 8-18
    assert all(name.endswith('.png') and (out / name).read_bytes()[:8] == PNG for name in figures)
    captions = tomllib.loads((ROOT / 'docs' / 'gallery.toml').read_text(encoding='utf-8'))['paper_reel_changer']
    assert figures == sorted(k for k in captions if k != 'printed')     # [NAME.printed]: what the captions quote
    rows = [line.split() for line in run.stdout.splitlines() if re.match(r'P\d .* (yes|no)$', line)]
    assert {row[0] for row in rows} == {'P1', 'P2', 'P7'} and any(row[1].startswith('δ=') for row in rows)
    # section 3.2.2: P1 chatters while lowering (2-6 s), not while lifting
    assert [(row[1], row[-1]) for row in rows if row[0] == 'P1' and row[1] in ('lift', 'lower')] == [
        ('lift', 'no'), ('lower', 'yes'), ('lift', 'no')]


def _Unstable(out, cwd):
    return (re.search(r'^Contact states: UNSTABLE for S = -1(;|$)', out, re.M) and 'stable for J1 <=' in out
            and 'or for kT <=' in out and 'nearest stable values' in out)


def _HoistUnstable(out, cwd):
    return all(re.search(rf'^\s+{phase}\s+{rpm}\s.*UNSTABLE', out, re.M)
               for phase, rpm in (('lifting', '100'), ('lowering', '-100')))


def _Recommends(out, cwd):
    return ('Smallest single changes that make the drive stable with margin' in out and re.search(r'^Margin: ', out, re.M)
            and all(re.search(rf'^\s+{key}\s+[x/]\d', out, re.M) for key in ('J1', 'kT')))


def _OneRotationWithFigures(out, cwd):
    simulated = re.search(r'^simulated (\S+) s in ', out, re.M)
    figures = sorted(p.name for p in (cwd / 'p7').iterdir())
    # one rotation of the reel: u / n0 = 63.002 / (472.5 rpm) = 8.0003 s (eq. (3))
    return (simulated and abs(float(simulated[1]) - 8.0003) < 0.01 and os.listdir(cwd) == ['p7'] and figures
            and all(name.endswith('.png') and (cwd / 'p7' / name).read_bytes()[:8] == PNG for name in figures))


#: the "Shortest use" commands of the README, each with the check of what its comment says
SHORTEST_USE = {
    'exudyn-worm stability --preset reel-P1': _Unstable,
    'exudyn-worm stability --config hoist': _HoistUnstable,
    'exudyn-worm check --preset reel-P1': _Recommends,
    'exudyn-worm simulate --preset reel-P7 --plot p7': _OneRotationWithFigures,
}


def _ShortestUse():
    block = next(b for b in _BashBlocks(README) if b.startswith('exudyn-worm '))
    return [line.split('#')[0].strip() for line in block.splitlines()]


def test_shortest_use_lists_the_commands_checked_here():
    assert _ShortestUse() == list(SHORTEST_USE)
    scripts = tomllib.loads((ROOT / 'pyproject.toml').read_text())['project']['scripts']
    assert scripts == {'exudyn-worm': 'exudyn_worm.__main__:Run'}     # signals handled while the rest loads


@pytest.mark.parametrize('command', [pytest.param(c, marks=pytest.mark.slow) if ' simulate ' in c else c   # 2 s
                                     for c in SHORTEST_USE])
def test_shortest_use_command_does_what_its_comment_says(command, tmp_path, monkeypatch, capsys):
    """Run in an empty folder through the function the console script runs (``exudyn-worm`` is ``Run``, around ``Main``)."""
    monkeypatch.chdir(tmp_path)
    status = Main(shlex.split(command)[1:])
    out, err = capsys.readouterr()
    assert status == 0, err
    assert SHORTEST_USE[command](out, tmp_path), out[-3000:]
    if ' --plot ' not in command:
        assert os.listdir(tmp_path) == []


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
