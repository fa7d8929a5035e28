"""Studies that cannot be lost: an output is locked while a study writes it (a second study on it is refused with
one line naming the holder), every write is atomic, a resume drops only the lines it cannot read and says which,
and the shards of a job array merge into the study run in one piece."""
import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from exudyn_worm._files import OutputBusyError, OutputLock, WriteTextAtomically
from exudyn_worm.analysis.studies.studyfiles import ReadResults
from exudyn_worm.analysis.studies.study import RunStudy, Study, StudySidecarPath
from exudyn_worm.analysis.studies.studygrid import StudyGrid, StudyPoints, Variation
from exudyn_worm.analysis.studies.studyfiles import StudyFileWarning
from exudyn_worm.cli.main import Main
from exudyn_worm.drive.config import ResolveParameters

SHORT = ['--windows', '0:0.1,0.1:0.2', '--end-time', '0.2', '--quiet']


def _Holder(path: Path):
    """Another process holding the lock of ``path`` (it prints 'ready' once it holds it)."""
    process = subprocess.Popen([sys.executable, '-c',
                                'import sys, time\nfrom exudyn_worm._files import OutputLock\n'
                                'lock = OutputLock(sys.argv[1]).__enter__()\nprint("ready", flush=True)\n'
                                'time.sleep(120)\n', str(path)], stdout=subprocess.PIPE, text=True)
    assert process.stdout.readline() == 'ready\n'
    return process


def test_a_second_study_on_a_locked_output_is_refused_naming_the_holder(capsys, tmp_path):
    out = tmp_path / 'runs.csv'
    holder = _Holder(out)
    try:
        assert Main(['sweep', '--vary', 'J1=0.1,0.2', '--output', str(out)] + SHORT) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and err[0].startswith('exudyn-worm: error: RunStudy:'), err
        assert f"'{out}' is being written by process {holder.pid} on host" in err[0]
        assert 'wait for it to end or choose another output' in err[0]
        assert not out.exists() and not StudySidecarPath(out).exists()     # nothing touched, nothing computed
    finally:
        holder.send_signal(signal.SIGKILL)
        holder.wait()
    # the holder was killed (-9): the kernel released its lock; its lock file is taken over, and removed at the end
    assert Main(['sweep', '--vary', 'J1=0.1,0.2', '--output', str(out)] + SHORT) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ['runs.csv', 'runs.study.json']
    assert len(ReadResults(out).rows) == 2


def test_the_lock_keeps_every_other_writer_off_and_is_released(tmp_path):
    out = tmp_path / 'a.csv'
    with OutputLock(out, 'here') as lock:
        assert lock.lockPath.read_text().startswith(f'process {os.getpid()} on host ')   # reading it keeps it
        child = subprocess.run([sys.executable, '-c', 'import sys\nfrom exudyn_worm._files import OutputLock\n'
                                'OutputLock(sys.argv[1], "there").__enter__()', str(out)],
                               capture_output=True, text=True)
        assert child.returncode == 1 and 'OutputBusyError: there:' in child.stderr
        assert f'process {os.getpid()}' in child.stderr
        with pytest.raises(OutputBusyError, match=r"^again: .* is being written by process"):
            OutputLock(out, 'again').__enter__()          # a second study in the same process, too
    assert list(tmp_path.iterdir()) == []
    with OutputLock(out):                                      # free again
        pass


def test_a_killed_holders_dying_worker_delays_the_lock_instead_of_refusing_it(tmp_path):
    """A study killed with -9 ends before its forked workers, which share its lock for a moment: a study started
    at once on the same output waits for them (the holder named in the lock file is gone) and is not refused."""
    out = tmp_path / 'runs.csv'
    script = ('import os, sys, time\nfrom exudyn_worm._files import OutputLock\n'
              'lock = OutputLock(sys.argv[1]).__enter__()\n'
              'if os.fork() == 0:\n'                   # the 'worker' inherits the locked file
              '    time.sleep(0.8)\n    os._exit(0)\n'
              'print("ready", flush=True)\nos._exit(0)\n')  # the 'study' ends first, its lock file left behind
    study = subprocess.Popen([sys.executable, '-c', script, str(out)], stdout=subprocess.PIPE, text=True)
    assert study.stdout.readline() == 'ready\n'
    study.wait()
    with OutputLock(out, 'resume') as lock:                    # waits for the worker, then takes the lock over
        assert lock.lockPath.read_text().startswith(f'process {os.getpid()} on host ')


def test_write_text_atomically_replaces_whole_files_only(tmp_path):
    path = tmp_path / 's.study.json'
    WriteTextAtomically(path, 'one')
    WriteTextAtomically(path, 'two')
    assert path.read_text() == 'two' and [p.name for p in tmp_path.iterdir()] == ['s.study.json']
    with pytest.raises(OSError):
        WriteTextAtomically(tmp_path / 'missing' / 'x.json', 'three')
    assert OutputBusyError.__mro__[1] is ValueError             # a refusal is bad input (one line, exit 2)


def _Study(n=4):
    return Study(ResolveParameters('reel-P1'), [Variation('J1', tuple(0.1 + 0.05 * i for i in range(n)))],
                 endTime=0.2, windows=[(0., 0.1), (0.1, 0.2)])


def test_a_resume_drops_only_the_unreadable_lines_and_names_them(tmp_path):
    out = tmp_path / 'runs.csv'
    study = _Study()
    first = RunStudy(study, out, workers=1, quiet=True)
    lines = out.read_text().splitlines(keepends=True)
    assert len(lines) == 5 and all(r['status'] == 'ok' for r in first.rows)
    cells = lines[2].split(',')
    cells[3] = 'garbage'                                   # one damaged value in the second run's line
    lines[2] = ','.join(cells)
    out.write_text(''.join(lines))
    seen = []
    with pytest.warns(StudyFileWarning, match=r"dropped 1 line that cannot be read or is no run of the study, their runs are run again "
                                              r"\(line 3: could not convert"):
        again = RunStudy(study, out, workers=1, quiet=True, onRow=seen.append)
    assert [r['run'] for r in seen] == [1]                 # only the damaged run is run again, not those behind it
    assert [r['run'] for r in again.rows] == [0, 1, 2, 3]
    for a, b in zip(first.rows, again.rows):
        assert a['run'] == b['run'] and a['J1'] == b['J1'] and a['status'] == b['status']
    assert 'garbage' not in out.read_text()
    assert sorted(p.name for p in tmp_path.iterdir()) == ['runs.csv', 'runs.study.json']


def test_the_results_file_lists_its_runs_in_run_order(tmp_path):
    """Rows are appended as the runs finish (a stopped study keeps every finished run); on finishing, the file is
    rewritten in run order: here run 1, lost and run again on resuming, was appended behind runs 2 and 3."""
    out = tmp_path / 'runs.csv'
    study = _Study()
    RunStudy(study, out, workers=1, quiet=True)
    lines = out.read_text().splitlines(keepends=True)
    out.write_text(''.join(lines[:2] + lines[3:]))          # run 1 lost
    seen = []
    again = RunStudy(study, out, workers=1, quiet=True, onRow=seen.append)
    assert [r['run'] for r in seen] == [1]
    kept = out.read_text().splitlines(keepends=True)
    assert [line.split(',')[0] for line in kept] == ['run', '0', '1', '2', '3']
    assert kept[:2] + kept[3:] == lines[:2] + lines[3:]       # the other lines as they were written
    assert [r['run'] for r in again.rows] == [r['run'] for r in ReadResults(out).rows] == [0, 1, 2, 3]


def test_a_cut_off_last_line_is_named_too(tmp_path):
    out = tmp_path / 'runs.csv'
    study = _Study(2)
    RunStudy(study, out, workers=1, quiet=True)
    text = out.read_text()
    out.write_text(text[:-7])                              # a job killed while writing its last row
    with pytest.warns(StudyFileWarning, match=r"line 3: cut off"):
        assert [r['run'] for r in ReadResults(out).rows] == [0]


def test_the_shards_of_a_job_array_merge_into_the_whole_study(tmp_path):
    study = _Study(5)
    whole = RunStudy(study, tmp_path / 'whole.csv', workers=1, quiet=True)
    shards = [tmp_path / f'part-{i}.csv' for i in range(3)]
    for i, path in enumerate(shards):
        RunStudy(study, path, workers=1, quiet=True, shard=f'{i}/3')
    assert [[r['run'] for r in ReadResults(p).rows] for p in shards] == [[0, 3], [1, 4], [2]]
    merged = ReadResults(*shards)
    assert [r['run'] for r in merged.rows] == [0, 1, 2, 3, 4]
    for a, b in zip(merged.rows, whole.rows):              # the same runs, the same deterministic results
        assert {k: v for k, v in a.items() if 'econds' not in k} == {k: v for k, v in b.items() if 'econds' not in k}
    with pytest.raises(ValueError, match='belongs to a different study'):
        other = tmp_path / 'other.csv'
        RunStudy(_Study(2), other, workers=1, quiet=True)
        ReadResults(shards[0], other)


def test_a_shard_cut_short_resumes_alone_and_merges_with_the_others(tmp_path):
    """One task of a job array killed after its first run: the same call again runs only the rest of its shard,
    and the shard files merge into every run of the study once."""
    study = _Study(5)
    shards = [tmp_path / f'part-{i}.csv' for i in range(2)]
    RunStudy(study, shards[0], workers=1, quiet=True, shard='0/2')              # runs 0, 2, 4

    def Killed(row):
        raise KeyboardInterrupt                                               # after its row is saved
    with pytest.raises(KeyboardInterrupt):
        RunStudy(study, shards[1], workers=1, quiet=True, shard='1/2', onRow=Killed)   # runs 1, 3: only 1 saved
    assert [r['run'] for r in ReadResults(shards[1]).rows] == [1]
    seen = []
    resumed = RunStudy(study, shards[1], workers=1, quiet=True, shard='1/2', onRow=seen.append)
    assert [r['run'] for r in seen] == [3] and [r['run'] for r in resumed.rows] == [1, 3]
    merged = ReadResults(*shards)
    assert [r['run'] for r in merged.rows] == [0, 1, 2, 3, 4]
    assert [r['J1'] for r in merged.rows] == [p['J1'] for p in study.points]
    assert all(r['status'] == 'ok' for r in merged.rows)
    with pytest.raises(ValueError, match='shard'):                            # a shard file resumed as another shard
        RunStudy(study, shards[1], workers=1, quiet=True, shard='0/2')


def test_a_huge_grid_is_counted_not_built_and_refused_with_the_shards_to_split_into(tmp_path):
    """A grid of 1e8 points grew to 11.5 GB before a MemoryError: its points are built only when asked for."""
    base = ResolveParameters('reel-P1')
    study = Study(base, [Variation('J1', tuple(0.01 + 1e-5 * i for i in range(10_000))),
                         Variation('kT', tuple(700. + i for i in range(10_000)))])
    assert len(study.points) == 100_000_000
    assert study.points[10_001] == {'J1': 0.01 + 1e-5, 'kT': 701.} and study.points[-1] == study.points[99_999_999]
    with pytest.raises(ValueError, match=r"^RunStudy: the study has 100,000,000 runs \(J1: 10,000 x kT: 10,000\), above "
                                         r"the limit of 100,000 runs per call .* split it into at least 1,000 shards"):
        RunStudy(study, tmp_path / 'big.csv')
    with pytest.raises(ValueError, match=r"shard 1/2 has 2 of the study's 5 runs \(J1: 5\), above the limit of 1 runs "
                                         r".*at least 5 shards"):
        RunStudy(_Study(5), tmp_path / 'big.csv', shard='1/2', maxRuns=1)
    assert list(tmp_path.iterdir()) == []
    small = [Variation('J1', (1., 2., 3.)), Variation('kT', (10., 20.))]    # the order of StudyPoints: first slowest
    assert list(StudyGrid(small)) == StudyPoints(small) == [{'J1': a, 'kT': b} for a in (1., 2., 3.) for b in (10., 20.)]
    assert list(StudyGrid(small[:1] + [Variation('kT', (10., 20., 30.))], zipped=True)) == [
        {'J1': 1., 'kT': 10.}, {'J1': 2., 'kT': 20.}, {'J1': 3., 'kT': 30.}]
    assert list(StudyGrid([])) == [{}]
    with pytest.raises(IndexError):
        StudyGrid(small)[6]
