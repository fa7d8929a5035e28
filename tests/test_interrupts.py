"""Ctrl-C everywhere: every subcommand and ``python -m validation`` end an interrupt with one
line on stderr and exit status 130, without a traceback and without a half-written file; the validation stops
instead of recording FAILs; ``sweep`` cancels its queued runs, terminates its running ones and keeps the finished
ones; a study draws one progress bar, not one per worker."""
import json
import multiprocessing
import os
import signal
import subprocess
import sys
import threading
import time
from concurrent.futures import InvalidStateError, ProcessPoolExecutor
from pathlib import Path

import pytest

from exudyn_worm.cli.main import Main
from exudyn_worm._files import WriteAtomically
from exudyn_worm._workers import _QUIET_THREADS, _QuietAboutCancelledJobs, CancelPool, INTERRUPTED_STATUS
from exudyn_worm.items.solve import Interruptible, IsInterrupt
import exudyn_worm.plotting.plot as plot
import exudyn_worm.analysis.simulation.reelchanger as reelchanger
import exudyn_worm.items.results as results
import exudyn_worm.analysis.charts.stabilitychart as charts
import exudyn_worm.analysis.design.designcheck as design
from validation.runner import CheckGroup, RunValidation, WriteText
import validation.runner as runner
from validation.cli import Main as ValidationMain
from exudyn_worm._workers import CancelPool
from exudyn_worm.drive.config import ResolveParameters
from exudyn_worm.analysis.studies.studyfiles import ReadResults
from exudyn_worm.analysis.studies.study import Study, StudySidecarPath
from exudyn_worm.analysis.studies.studypoint import RunPoint
from exudyn_worm.analysis.studies.studygrid import Variation

ROOT = Path(__file__).resolve().parents[1]

pytestmark = pytest.mark.usefixtures('emptyWorkingDirectory')   # nothing written to the cwd


@pytest.fixture
def folder(tmp_path):
    """An empty folder for the outputs of one test (tmp_path also holds the working directory)."""
    path = tmp_path / 'out'
    path.mkdir()
    return path


def _ExudynStyleInterrupt(*args, **kwargs):
    """What Exudyn's C++ solver does on Ctrl-C: it returns with the KeyboardInterrupt pending, and Python raises
    ``SystemError: ... returned a result with an exception set`` with the interrupt as its context."""
    try:
        raise KeyboardInterrupt
    except KeyboardInterrupt:
        raise SystemError('<built-in method SolveSystem> returned a result with an exception set')


def _HalfWrittenThenInterrupted(path, *args, **kwargs):
    """A writer interrupted half-way: part of the file is on disk when Ctrl-C arrives."""
    Path(path).write_text('half a file')
    raise KeyboardInterrupt


def _SaveHalfAFigure(fig, path, *args, **kwargs):
    _HalfWrittenThenInterrupted(path)


def _Leftovers(folder: Path):
    return sorted(p.name for p in folder.iterdir())


def _AssertInterrupted(status, out, err):
    assert status == INTERRUPTED_STATUS
    lines = err.strip().splitlines()
    assert len(lines) == 1 and 'interrupted' in lines[0] and 'Traceback' not in err, err


# --- in-process: KeyboardInterrupt raised at a monkeypatched point -----------------------------------------
def _InterruptCases(tmp_path, monkeypatch):
    """name -> (argv, patch): patch() installs the interrupt; the files the run must not leave behind are
    checked by the test (the folder tmp_path must stay empty)."""
    short = ['--end-time', '0.3', '--quiet']
    return {
        'simulate: in the solver (Exudyn SystemError)': (
            ['simulate', *short, '--csv', str(tmp_path / 'a.csv')],
            lambda: monkeypatch.setattr(reelchanger, 'SolveDynamicInChunks', _ExudynStyleInterrupt)),
        'simulate: while writing --csv': (
            ['simulate', *short, '--csv', str(tmp_path / 'a.csv')],
            lambda: monkeypatch.setattr(results.SimulationResult, 'ToCsv',
                                        lambda self, path: _HalfWrittenThenInterrupted(path))),
        'simulate: while writing a --plot figure': (
            ['simulate', *short, '--plot', str(tmp_path / 'figs')],
            lambda: monkeypatch.setattr(plot, 'SaveFigure', _SaveHalfAFigure)),
        'chart: while computing': (
            ['chart', '--preset', 'chart', '--DV', '0.014', '--resolution', '20', '--output', str(tmp_path / 'c.png')],
            lambda: monkeypatch.setattr(charts, 'ComputeStabilityChart', lambda *a, **k: (_ for _ in ()).throw(
                KeyboardInterrupt()))),
        'chart: while writing --output': (
            ['chart', '--preset', 'chart', '--DV', '0.014', '--DTV', '5', '--resolution', '20', '--quiet',
             '--output', str(tmp_path / 'c.png')],
            lambda: monkeypatch.setattr(plot, 'SaveFigure', _SaveHalfAFigure)),
        'check: while computing': (
            ['check', '--preset', 'reel-P1', '--plot', str(tmp_path / 'c.png')],
            lambda: monkeypatch.setattr(design, 'DesignCheck', lambda *a, **k: (_ for _ in ()).throw(
                KeyboardInterrupt()))),
        'stability: while computing': (
            ['stability', '--preset', 'reel-P1', '--json'],
            lambda: monkeypatch.setattr('exudyn_worm.analysis.stability.drivestability.AnalyzeDrive', lambda *a, **k: (_ for _ in ()).throw(
                KeyboardInterrupt()))),
        'sweep: while writing --plot': (
            ['sweep', '--vary', 'J1=0.1,0.2', '--windows', '0:0.1,0.1:0.2', '--end-time', '0.2', '--quiet', '--workers', '1',
             '--plot', str(tmp_path / 's.png')],
            lambda: monkeypatch.setattr(plot, 'SaveFigure', _SaveHalfAFigure)),
    }


CASES = ['simulate: in the solver (Exudyn SystemError)', 'simulate: while writing --csv',
         'simulate: while writing a --plot figure', 'chart: while computing', 'chart: while writing --output',
         'check: while computing', 'stability: while computing', 'sweep: while writing --plot']


@pytest.mark.parametrize('case', CASES)
def test_interrupt_is_one_line_exit_130_nothing_half_written(capsys, tmp_path, monkeypatch, case):
    out_dir = tmp_path / 'out'
    out_dir.mkdir()
    cases = _InterruptCases(out_dir, monkeypatch)
    assert set(cases) == set(CASES)
    argv, patch = cases[case]
    patch()
    status = Main(argv)
    out, err = capsys.readouterr()
    _AssertInterrupted(status, out, err)
    leftovers = [p for p in out_dir.rglob('*') if p.is_file()]
    assert leftovers == [], f'half-written: {leftovers}'


def test_write_atomically_keeps_the_old_file_on_interrupt(folder):
    path = folder / 'r.csv'
    path.write_text('old complete file')
    with pytest.raises(KeyboardInterrupt):
        WriteAtomically(path, _HalfWrittenThenInterrupted)
    assert path.read_text() == 'old complete file' and _Leftovers(folder) == ['r.csv']
    WriteAtomically(path, lambda tmp: Path(tmp).write_text('new'))
    assert path.read_text() == 'new' and _Leftovers(folder) == ['r.csv']


def test_exudyn_error_around_an_interrupt_is_an_interrupt():
    with pytest.raises(SystemError) as info:
        _ExudynStyleInterrupt()
    assert IsInterrupt(info.value) and not IsInterrupt(SystemError('a real bug'))
    with pytest.raises(KeyboardInterrupt):
        with Interruptible():
            _ExudynStyleInterrupt()
    with pytest.raises(ValueError):               # other errors pass unchanged
        with Interruptible():
            raise ValueError('bad input')


def test_validation_stops_on_interrupt_instead_of_recording_fails():
    """A check group interrupted inside Exudyn used to turn into FAIL rows and the run went on."""
    ran = []

    def Interrupted(ctx):
        _ExudynStyleInterrupt()

    def Later(ctx):
        ran.append('later')
        return []
    with pytest.raises(KeyboardInterrupt):
        RunValidation(groups=[CheckGroup('simulation', Interrupted), CheckGroup('charts', Later)], quiet=True)
    assert ran == []                               # stopped: the next group did not run


def test_validation_cli_interrupt(capsys, folder, monkeypatch):
    monkeypatch.setattr(runner, 'RunValidation', lambda **kw: _ExudynStyleInterrupt())
    report = folder / 'r.md'
    status = ValidationMain(['--quick', '--report', str(report)])
    out, err = capsys.readouterr()
    _AssertInterrupted(status, out, err)
    assert out == '' and _Leftovers(folder) == []


def test_validation_report_write_is_atomic(folder, monkeypatch):
    path = folder / 'r.md'

    def Interrupted(self, text, *args, **kwargs):
        Path.write_bytes(self, b'half')
        raise KeyboardInterrupt
    monkeypatch.setattr(Path, 'write_text', Interrupted)
    with pytest.raises(KeyboardInterrupt):
        WriteText(path, '# report')
    assert _Leftovers(folder) == []


# --- sweep: cancel at once, keep the finished runs, one bar ------------------------------------------------
def _Sleep(seconds):
    time.sleep(seconds)
    return seconds


def test_cancel_terminates_running_workers_and_drops_queued_runs():
    executor = ProcessPoolExecutor(max_workers=2, mp_context=multiprocessing.get_context('fork'))
    futures = [executor.submit(_Sleep, 60.) for _ in range(5)]
    while not all(f.running() for f in futures[:2]):
        time.sleep(0.05)
    processes = list(executor._processes.values())
    CancelPool(executor, futures)
    # the running runs are stopped, not awaited (60 s). The pool's manager thread reaps the workers too, and a
    # poll that loses that race reports a dead worker as alive for a moment: look again for up to 5 s
    for _ in range(100):
        if all(not p.is_alive() for p in processes):
            break
        time.sleep(0.05)
    assert all(not p.is_alive() for p in processes)
    for _ in range(600):                                         # (concurrent.futures.wait ignores cancelled ones)
        if all(f.done() for f in futures):
            break
        time.sleep(0.05)
    assert all(f.cancelled() or f.exception() is not None for f in futures)   # no run completed


def test_a_study_run_draws_no_bar_of_its_own(monkeypatch):
    seen = {}

    def Capture(p, **kwargs):
        seen.update(kwargs)
        raise RuntimeError('stop here')
    monkeypatch.setattr(reelchanger, 'SimulateReelChanger', Capture)
    study = Study(ResolveParameters('reel-P1'), [Variation('J1', (0.1,))], endTime=0.2, windows=[(0., 0.2)],
                  maxSteps=5000)
    row = RunPoint(study.Task(0))
    assert row['status'] == 'failed' and seen['progress'] is False and seen['maxSteps'] == 5000


# --- real processes, real SIGINT ---------------------------------------------------------------------------
def _Started(code: str, cwd: Path):
    """Start ``python -c code`` with Ctrl-C at its default (a background job may inherit it ignored); wait until
    it prints 'ready' on stderr (imports done), so that the signal lands in the computation."""
    process = subprocess.Popen([sys.executable, '-c', code], cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True, preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    assert process.stderr.readline() == 'ready\n'
    return process


def _Interrupt(process, after: float):
    time.sleep(after)
    process.send_signal(signal.SIGINT)
    out, err = process.communicate(timeout=120)
    return process.returncode, out, err


def _InterruptWhen(process, ready, timeout: float = 120.):
    """SIGINT as soon as ``ready()`` holds (polled), not after a fixed time: a loaded machine may need longer."""
    end = time.monotonic() + timeout
    while not ready() and time.monotonic() < end and process.poll() is None:
        time.sleep(0.05)
    return _Interrupt(process, 0.)


@pytest.mark.skipif(not hasattr(signal, 'SIGINT') or os.name != 'posix', reason='POSIX signals')
def test_sigint_during_simulate(folder):
    csv = folder / 'long.csv'
    process = _Started(
        "import sys, signal, exudyn_worm.cli.main, exudyn_worm.analysis.simulation.reelchanger\n"
        "signal.signal(signal.SIGINT, signal.default_int_handler)\n"
        "print('ready', file=sys.stderr, flush=True)\n"
        f"raise SystemExit(exudyn_worm.cli.main.Main(['simulate', '--end-time', '600', '--csv', {str(csv)!r}]))",
        folder)
    status, out, err = _Interrupt(process, 1.5)
    _AssertInterrupted(status, out, err)
    assert _Leftovers(folder) == []


@pytest.mark.skipif(os.name != 'posix', reason='POSIX signals')
def test_sigint_during_sweep_keeps_the_finished_runs(folder):
    output = folder / 'runs.csv'
    process = _Started(
        "import sys, signal, exudyn_worm.cli.main, exudyn_worm.analysis.simulation.reelchanger\n"
        "signal.signal(signal.SIGINT, signal.default_int_handler)\n"
        "print('ready', file=sys.stderr, flush=True)\n"
        "raise SystemExit(exudyn_worm.cli.main.Main(['sweep', '--vary', 'J1=0.01:0.4:400', '--workers', '2', "
        f"'--output', {str(output)!r}]))",
        folder)
    # interrupted once a run is in the table (header + one row), whatever the machine's load
    status, out, err = _InterruptWhen(process, lambda: output.is_file() and output.read_text().count('\n') >= 2)
    assert status == INTERRUPTED_STATUS and 'Traceback' not in err
    assert err.strip().splitlines() == [f"exudyn-worm: interrupted (Ctrl-C); finished runs are saved in '{output}'; run the "
                                        f"same command again to resume"]
    meta = json.loads(StudySidecarPath(output).read_text())
    rows = ReadResults(output).rows
    assert 0 < len(rows) < 400 and meta['counts']['done'] == len(rows)       # valid files, finished runs kept
    assert all(r['status'] == 'ok' for r in rows)                          # no run recorded as failed by the stop
    assert output.read_text().endswith('\n')                               # no cut-off last line


@pytest.mark.slow
@pytest.mark.skipif(os.name != 'posix', reason='POSIX signals')
def test_sigint_during_python_m_validation(folder):
    report = folder / 'r.md'
    process = _Started(
        "import sys, signal, validation.cli, validation.timedomain, validation.analytical, validation.charts\n"
        "signal.signal(signal.SIGINT, signal.default_int_handler)\n"
        "print('ready', file=sys.stderr, flush=True)\n"
        f"raise SystemExit(validation.cli.Main(['--report', {str(report)!r}]))", ROOT)
    status, out, err = _Interrupt(process, 2.)
    _AssertInterrupted(status, out, err)
    assert out == '' and not report.exists() and _Leftovers(folder) == []


def test_a_cancelled_pool_prints_no_complaint_of_its_manager_thread(monkeypatch):
    """The pool's manager thread may fail on a job just cancelled when the terminated workers break the pool
    (Python 3.11 raises InvalidStateError there, and its traceback followed the one line of a SIGTERM): CancelPool
    keeps that thread quiet about it; other errors of it, and other threads, are reported as before."""
    reported = []
    monkeypatch.setattr(threading, 'excepthook', lambda args: reported.append(args.exc_type))   # what prints them

    def Run(error, quiet):
        def Raise():
            raise error
        thread = threading.Thread(target=Raise)
        if quiet:
            _QuietAboutCancelledJobs(thread)
        thread.start()
        thread.join()

    executor = ProcessPoolExecutor(max_workers=1)
    futures = [executor.submit(time.sleep, 0.01)]
    manager = executor._executor_manager_thread
    CancelPool(executor, futures)
    assert manager in _QUIET_THREADS
    Run(InvalidStateError('CANCELLED: <Future>'), quiet=True)
    assert reported == []
    Run(ValueError('another error'), quiet=True)
    Run(InvalidStateError('CANCELLED: <Future>'), quiet=False)
    assert reported == [ValueError, InvalidStateError]
