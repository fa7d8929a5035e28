"""Shared test helpers."""
import copy
import hashlib
import importlib.util
import os
import pickle
import sys
from pathlib import Path

import pytest

try:
    import fcntl
except ImportError:             # not POSIX: each worker computes its own
    fcntl = None

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


#: results of deterministic analyses that several tests compute with the same arguments (the 3D model's steady
#: chatter and branch of examples/drives/reel-3d-chatter.toml: minutes each, mostly its settling run): computed once per
#: test run by :func:`Shared` and handed to each caller as a copy
_SHARED = {}
#: [the folder where :func:`Shared` leaves its results for the other pytest-xdist workers of the run]
_SHARED_FOLDER = [None]


@pytest.fixture(scope='session', autouse=True)
def _sharedFolder(tmp_path_factory):
    """The run's base temporary folder, which pytest-xdist's workers share (their own folders are inside it)."""
    base = tmp_path_factory.getbasetemp()
    _SHARED_FOLDER[0] = base.parent if os.environ.get('PYTEST_XDIST_WORKER') else base
    yield


def Shared(function, *args, **kwargs):
    """``function(*args, **kwargs)``, computed once per test run for equal arguments (a mapping argument by its
    items, a drive by its values); a deep copy is returned, so that a test that changes it changes nothing for the
    next. Only for functions whose result depends on their arguments alone. Under pytest-xdist the first worker to ask computes it (under a
    file lock) and leaves it pickled in the run's temporary folder; another worker asking meanwhile waits for it."""
    def Key(value):
        if hasattr(value, 'parameters') and hasattr(value, 'elastic'):      # a Drive: by its values
            return Key(dict(value.parameters))
        if isinstance(value, dict) or hasattr(value, 'items'):
            return tuple(sorted((k, Key(v)) for k, v in value.items()))
        return repr(value)
    key = (function.__module__, function.__qualname__, tuple(Key(a) for a in args), Key(kwargs))
    if key not in _SHARED:
        folder = _SHARED_FOLDER[0]
        if folder is None or fcntl is None:
            _SHARED[key] = function(*args, **kwargs)
        else:
            path = Path(folder) / f"shared-{hashlib.sha256(repr(key).encode()).hexdigest()[:24]}.pickle"
            with open(path.with_suffix('.lock'), 'w') as lock:
                fcntl.flock(lock, fcntl.LOCK_EX)          # released when the file is closed
                if path.exists():
                    _SHARED[key] = pickle.loads(path.read_bytes())
                else:
                    _SHARED[key] = function(*args, **kwargs)
                    partial = path.with_suffix('.partial')
                    partial.write_bytes(pickle.dumps(_SHARED[key]))
                    partial.replace(path)
    return copy.deepcopy(_SHARED[key])


@pytest.fixture
def sharedChatterAnalyses(monkeypatch):
    """``SteadyChatterSummary`` and ``AnalyzeChatterBranch`` through :func:`Shared` for the test's calls (the command
    line's included: ``chatter`` imports them from their modules when it runs)."""
    import exudyn_worm.analysis.orbits.chatter as chatter                  # lazy: only the tests that use this fixture
    import exudyn_worm.analysis.orbits.chatterbranch as chatterbranch      # lazy: only the tests that use this fixture
    for module, name in ((chatter, 'SteadyChatterSummary'), (chatterbranch, 'AnalyzeChatterBranch')):
        original = getattr(module, name)
        monkeypatch.setattr(module, name, lambda *a, _f=original, **k: Shared(_f, *a, **k))
