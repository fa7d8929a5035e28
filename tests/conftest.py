"""Shared test helpers."""
import importlib.util
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def LoadScript(relativePath: str, name: str):
    """Import a script of the repository that is not part of the package (an example, a benchmark, a
    validation script) as module ``name``."""
    spec = importlib.util.spec_from_file_location(name, ROOT / relativePath)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module          # dataclasses and pickling look the module up here
    spec.loader.exec_module(module)
    return module


@pytest.fixture
def emptyWorkingDirectory(tmp_path, monkeypatch):
    """Run the test in an empty directory and check that nothing was written to it (use with
    ``pytestmark = pytest.mark.usefixtures('emptyWorkingDirectory')``)."""
    cwd = tmp_path / 'cwd'
    cwd.mkdir()
    monkeypatch.chdir(cwd)
    yield cwd
    assert sorted(p.name for p in cwd.iterdir()) == []
