"""Worker processes start with the thread variables of BLAS and OpenMP at 1 (a pool has a worker per core already),
and SingleThreadedBlas limits a BLAS already loaded, as a forked worker inherits it."""
import ctypes
import os

import numpy as np
import pytest

from exudyn_worm._workers import THREAD_VARIABLES, SingleThreadedBlas, _LoadedLibraries
from exudyn_worm.analysis.studies.study import _Executor

#: the thread getters of OpenBLAS builds (numpy's wheels bundle the scipy_openblas one)
GETTERS = ('openblas_get_num_threads', 'openblas_get_num_threads64_', 'scipy_openblas_get_num_threads64_',
           'scipy_openblas_get_num_threads')


def _OpenBlas(prefix: str):
    """The thread getter or setter (``prefix`` 'get' or 'set') of the OpenBLAS numpy loaded, or None."""
    for path in _LoadedLibraries('openblas'):
        library = ctypes.CDLL(path)
        for name in GETTERS:
            function = getattr(library, name.replace('_get_', f'_{prefix}_'), None)
            if function is not None:
                return function
    return None


def _WorkerThreads(limit: bool):
    """In a worker: the number of threads of its OpenBLAS (after ``SingleThreadedBlas()`` if ``limit``) and the
    thread variables of its environment."""
    if limit:
        SingleThreadedBlas()
    np.ones((2, 2)) @ np.ones((2, 2))          # numpy's BLAS in use
    return _OpenBlas('get')(), {name: os.environ.get(name) for name in THREAD_VARIABLES}


def test_a_study_worker_starts_with_one_thread_variables_and_can_limit_its_blas():
    """The study's pool forks its workers from a process with numpy loaded: the variables alone come too late for
    that BLAS (the worker keeps the parent's threads), SingleThreadedBlas() limits it."""
    if _OpenBlas('get') is None:
        pytest.skip('numpy without OpenBLAS: no thread count to read')
    setter = _OpenBlas('set')
    before = _OpenBlas('get')()
    setter(2)                                  # two threads in the parent, which a forked worker inherits
    try:
        pool = _Executor('process', 1)
        try:
            inherited, variables = pool.submit(_WorkerThreads, False).result(timeout=120)
            limited, _ = pool.submit(_WorkerThreads, True).result(timeout=120)
        finally:
            pool.shutdown()
        assert _OpenBlas('get')() == 2            # the parent keeps its threads
    finally:
        setter(before)
    assert variables == dict.fromkeys(THREAD_VARIABLES, '1')
    assert inherited == 2 and limited == 1
