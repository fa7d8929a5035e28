"""Flat memory: a process that runs many simulations (a sweep worker) does not grow with the number of runs.

Exudyn 1.13.6 never frees a system whose symbolic user function's recording names the MainSystem
(docs/exudyn-notes.md, benchmarks/exudyn_symbolic_leak.py); the recorder leaves it out."""
import gc

import pytest

from exudyn_worm.analysis.reelchanger import BuildReelChanger
from exudyn_worm.analysis.studypoint import RunPoint
from exudyn_worm.items._userfunctions import _KEEP_ALIVE
from exudyn_worm.setups.presets import GetPreset

from conftest import LoadScript

#: the plain-Exudyn reproduction; its Rss() reads VmRSS of /proc/self/status
LEAK = LoadScript('benchmarks/exudyn_symbolic_leak.py', 'exudyn_symbolic_leak')


def test_recordings_do_not_hold_the_system():
    # the cycle system -> user function -> recording -> MainSystem -> container -> system is what keeps a system
    model = BuildReelChanger(GetPreset('reel-P1'))
    recordings = model.mbs.variables[_KEEP_ALIVE]
    assert recordings                    # the symbolic laws of the mesh and the motor
    for _, fnDict in recordings:
        assert not any(type(arg).__name__ == 'MainSystem' for arg in fnDict['argList'])


@pytest.mark.slow
def test_200_study_runs_keep_memory_flat():
    # the sweep worker's path: linear verdict, simulation and the half-step check of one study point; before the fix
    # each run kept its systems (about 0.5 MB per run of this length, 100 MB for 200 runs)
    task = dict(run=0, parameters=GetPreset('reel-P1'), varied={}, windows=None, endTime=0.5, stepSize=None,
                checkStep=True)
    for _ in range(5):                   # warm-up: imports, caches, the allocator's pools
        assert RunPoint(task)['status'] == 'ok'
    gc.collect()
    before = LEAK.Rss()
    for _ in range(200):
        RunPoint(task)
    gc.collect()
    growth = LEAK.Rss() - before
    assert growth < 20., f"resident memory grew by {growth:.1f} MB over 200 runs"


def test_plain_exudyn_keeps_a_system_whose_recording_names_the_main_system():
    # the reproduction of docs/exudyn-notes.md: 10 runs of 10,000 steps, each with 320 kB of sensor data; when a
    # later Exudyn frees such systems, this fails and the notes (and the workaround) can go
    assert LEAK.Growth('exudyn', runs=10) > 200.
    assert LEAK.Growth('noMainSystem', runs=10) < 50.
    assert LEAK.Growth('reset', runs=10) < 50.
