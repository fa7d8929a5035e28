"""No orphans, every signal: the worker processes of ``sweep``, ``chatter``, ``check --simulate`` and
``python -m validation`` end with their parent, also when it is killed with SIGKILL; SIGTERM ends a command as
Ctrl-C does (one line on stderr, exit status 143, no file left, hidden temporary files included)."""
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from exudyn_worm._workers import TERMINATED_STATUS

ROOT = Path(__file__).resolve().parents[1]

pytestmark = [pytest.mark.usefixtures('emptyWorkingDirectory'),
              pytest.mark.skipif(not sys.platform.startswith('linux'), reason='Linux: /proc and the parent-death signal')]


def _Session(sid: int):
    """Process ids of the live processes of session ``sid`` (a command started with ``start_new_session``: the
    command and every process it forked, also those whose parent has died)."""
    out = []
    for entry in Path('/proc').iterdir():
        if not entry.name.isdigit():
            continue
        try:
            fields = (entry / 'stat').read_text().rsplit(')', 1)[1].split()
        except OSError:
            continue
        if int(fields[3]) == sid and fields[0] != 'Z':          # fields: state ppid pgrp session ...
            out.append(int(entry.name))
    return out


def _Start(argv, cwd, env=None):
    return subprocess.Popen([sys.executable, *argv], cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, start_new_session=True, env=env)


def _WaitFor(condition, timeout: float) -> bool:
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if condition():
            return True
        time.sleep(0.05)
    return condition()


def _CatchesSigterm(pid: int) -> bool:
    """Whether the process has installed its SIGTERM handler (bit 15 of SigCgt in /proc): a SIGTERM sent before
    that, while Python still imports the package, ends it by the signal's default action."""
    try:
        with open(f'/proc/{pid}/status') as status:
            caught = next(line for line in status if line.startswith('SigCgt:'))
    except (OSError, StopIteration):
        return False
    return bool(int(caught.split()[1], 16) & (1 << (signal.SIGTERM - 1)))


def _Cli(*args):
    return ['-m', 'exudyn_worm', *args]


#: name -> (argv, whether it starts worker processes, working directory)
COMMANDS = {
    'sweep': (_Cli('sweep', '--vary', 'J1=0.01:0.4:40', '--workers', '2', '--quiet'), True, None),
    'chatter': (_Cli('chatter', '--preset', 'reel-P1', '--vary', 'kT=6000:9500'), True, None),
    'check --simulate': (_Cli('check', '--preset', 'reel-P1', '--simulate', '--step-size', '2e-5'), False, None),
    # python -m validation runs no workers (its studies and chatter branches use the pools of sweep and chatter)
    'python -m validation': (['-m', 'validation', '--quiet'], False, ROOT),
}


@pytest.mark.slow
@pytest.mark.parametrize('name', list(COMMANDS))
def test_sigkill_of_the_parent_leaves_no_worker(name, tmp_path):
    argv, workers, cwd = COMMANDS[name]
    folder = tmp_path / 'out'
    folder.mkdir()
    process = _Start([a.format(out=folder) for a in argv], cwd or tmp_path / 'cwd')
    try:
        if workers:      # killed once it runs workers
            assert _WaitFor(lambda: len(_Session(process.pid)) >= 2, 120.), f'{name} started no worker'
        else:
            time.sleep(3.)
            assert process.poll() is None
        assert process.pid in _Session(process.pid)
        process.kill()
        process.wait(timeout=10)
        assert _WaitFor(lambda: not _Session(process.pid), 5.), f'{name}: orphans {_Session(process.pid)}'
    finally:
        for pid in _Session(process.pid):          # never leave a process behind, even when the test fails
            os.kill(pid, signal.SIGKILL)
        process.communicate()


def _AssertTerminated(process, folder: Path):
    out, err = process.communicate(timeout=120)
    assert process.returncode == TERMINATED_STATUS, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and 'interrupted (SIGTERM)' in lines[0] and 'Traceback' not in err, err
    assert sorted(p.name for p in folder.iterdir()) == []          # no file, no hidden .partial file
    assert _WaitFor(lambda: not _Session(process.pid), 5.)


@pytest.mark.slow
@pytest.mark.parametrize('name,argv', [
    ('simulate', ['simulate', '--end-time', '600', '--quiet', '--csv', '{out}/a.csv']),
    ('chart', ['chart', '--preset', 'chart', '--DV', '0.014', '--resolution', '2000', '--quiet',
               '--output', '{out}/c.png']),
])
def test_sigterm_is_one_line_exit_143_and_no_file(name, argv, tmp_path):
    folder = tmp_path / 'out'
    folder.mkdir()
    process = _Start(_Cli(*[a.format(out=folder) for a in argv]), tmp_path / 'cwd')
    assert _WaitFor(lambda: _CatchesSigterm(process.pid), 60.), process.communicate()
    time.sleep(1.)                                              # into the work
    assert process.poll() is None, process.communicate()
    process.terminate()
    _AssertTerminated(process, folder)


@pytest.mark.parametrize('name', ['chatter', 'sweep'])
def test_sigterm_stops_the_workers_with_one_line(name, tmp_path):
    folder = tmp_path / 'out'
    folder.mkdir()
    argv, _, _ = COMMANDS[name]
    process = _Start(argv, tmp_path / 'cwd')
    assert _WaitFor(lambda: len(_Session(process.pid)) >= 2, 120.)
    time.sleep(0.5)
    process.terminate()
    _AssertTerminated(process, folder)


@pytest.mark.slow
def test_sigterm_of_python_m_validation(tmp_path):
    folder = tmp_path / 'out'
    folder.mkdir()
    process = _Start(['-m', 'validation', '--quiet', '--report', str(folder / 'r.md')], ROOT)
    time.sleep(4.)
    assert process.poll() is None
    process.terminate()
    _AssertTerminated(process, folder)
