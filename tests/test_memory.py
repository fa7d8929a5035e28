"""Flat memory: a process that runs many simulations (a sweep worker) does not grow with the number of runs.

Exudyn 1.13.6 never frees a system whose symbolic user function's recording names the MainSystem
(docs/exudyn-notes.md, benchmarks/exudyn_symbolic_leak.py); the recorder leaves it out. The measurements run in a
fresh process each: memory this test process freed before would be reused and hide a growth."""
import json
import os
import subprocess
import sys

import exudyn as exu
import pytest

from exudyn_worm.analysis.simulation.reelchanger import BuildReelChanger
from exudyn_worm.items._userfunctions import _KEEP_ALIVE
from exudyn_worm.drive.presets import GetPreset
from exudyn_worm.drive.wholedrive import ResolveDrive

from conftest import ROOT


def _InFreshProcess(call: str):
    """Evaluate ``call`` (an expression using the benchmark scripts' functions) in a new Python; its JSON value."""
    code = f"import json, sys; sys.path.insert(0, 'benchmarks'); import bench_memory as B, exudyn_symbolic_leak as L; " \
           f"print(json.dumps({call}))"
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get('PYTHONPATH', '')]),
               PYTHONWARNINGS='ignore')
    result = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True, cwd=ROOT, env=env,
                            timeout=600)
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout.splitlines()[-1])


def test_recordings_do_not_hold_the_system():
    # the cycle system -> user function -> recording -> MainSystem -> container -> system is what keeps a system
    model = BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=GetPreset('reel-P1')))
    recordings = model.mbs.variables[_KEEP_ALIVE]
    assert recordings                    # the symbolic laws of the mesh and the motor
    for _, fnDict in recordings:
        assert not any(type(arg).__name__ == 'MainSystem' for arg in fnDict['argList'])


@pytest.mark.slow
def test_200_study_runs_keep_memory_flat():
    # the sweep worker's path: linear verdict, simulation and the half-step check of one study point, after 5 runs of
    # warm-up; before the fix each run kept its systems (0.5 MB per run of this length, 98 MB for 200 runs)
    growth = _InFreshProcess("B.WorkerGrowth('reel-P1', runs=200, endTime=0.5, warmUp=5)")
    assert growth['status'] == 'ok' and growth['stepChecked']
    assert growth['after'] - growth['before'] < 20., growth


def test_plain_exudyn_keeps_a_system_whose_recording_names_the_main_system():
    # the reproduction of docs/exudyn-notes.md: 10 runs of 10,000 steps, each with 320 kB of sensor data; when a
    # later Exudyn frees such systems, this fails and the notes (and the workaround) can go
    kB = _InFreshProcess("{v: L.Growth(v, runs=10) for v in ('exudyn', 'noMainSystem', 'reset')}")
    assert kB['exudyn'] > 200.
    assert kB['noMainSystem'] < 50. and kB['reset'] < 50.
