"""The README's Python examples run as written (docs that are true), without writing to the cwd."""
import os
import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[1] / 'README.md'
BLOCKS = re.findall(r'```python\n(.*?)```', README.read_text(), flags=re.S)


@pytest.mark.parametrize('index', range(len(BLOCKS)))
def test_readme_python_block_runs(index, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    exec(compile(BLOCKS[index], f'README.md python block {index}', 'exec'), {'__name__': 'readme'})
    assert os.listdir(tmp_path) == []


def test_readme_starts_with_the_two_commands():
    text = README.read_text()
    commands = re.findall(r'```bash\n(.*?)\n```', text, flags=re.S)[:2]
    assert 'examples/paper_reel_changer.py' in commands[0]
    assert commands[1].endswith('pytest')
    ci = (README.parent / '.ci' / 'run').read_text()
    assert "pip install -e '.[test]'" in ci and 'pytest' in ci
