"""A results file is never lost: a resume that is refused leaves the file as it was, the lock follows the file
itself (a hard or symbolic link to an output being written is refused), a resume keeps only the rows that are
runs of the study with the study's own parameters (the others are dropped, named, and run again), and a full
disk leaves no empty results file, sidecar or lock file behind.

The runs are not simulated: ``studypoint.RunPoint`` is replaced by a function that returns a row of the run's
parameters at once, since what is checked here is the file, not a run."""
import errno
import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from exudyn_worm._files import OutputBusyError, OutputLock, LockPath
from exudyn_worm.analysis.studies import study as study_module
from exudyn_worm.analysis.studies import studypoint
from exudyn_worm.analysis.studies.study import RunStudy, Study, StudySidecarPath
from exudyn_worm.analysis.studies.studyfiles import ReadResults, StudyFileWarning
from exudyn_worm.analysis.studies.studygrid import Variation
from exudyn_worm.cli.main import Main
from exudyn_worm.drive.config import ResolveParameters


def _InstantPoint(task):
    """A row of the run's own parameters, as RunPoint writes it, without simulating."""
    return {'run': task.run, 'status': 'ok', 'error': '', 'seconds': 0.001, **task.varied}


@pytest.fixture(autouse=True)
def _instant(monkeypatch):
    monkeypatch.setattr(studypoint, 'RunPoint', _InstantPoint)


def _Study(n=40):
    return Study(ResolveParameters('reel-P1'), [Variation('J1', tuple(0.1 + 0.01 * i for i in range(n)))],
                 endTime=0.2, windows=[(0., 0.1), (0.1, 0.2)])


def _Finished(tmp_path, n=40):
    out = tmp_path / 'runs.csv'
    RunStudy(_Study(n), out, workers=1, quiet=True)
    assert len(out.read_text().splitlines()) == n + 1
    return out


@pytest.mark.parametrize('damage', ['renamed', 'deleted'])
def test_a_resume_refused_for_its_header_leaves_every_row(tmp_path, damage):
    out = _Finished(tmp_path)
    lines = out.read_bytes().splitlines(keepends=True)
    lines[0] = lines[0].replace(b'J1', b'J_1') if damage == 'renamed' else b''
    out.write_bytes(b''.join(lines))
    before = out.read_bytes()
    with pytest.raises(ValueError, match=r"^RunStudy: '.*runs.csv' has other columns than this study \(column .*: its "
                                         r"header line was changed or lost\), so it cannot be resumed; the file is "
                                         r"left as it is"):
        RunStudy(_Study(), out, workers=1, quiet=True)
    assert out.read_bytes() == before                          # not one of its 40 rows lost
    assert sorted(p.name for p in tmp_path.iterdir()) == ['runs.csv', 'runs.study.json']


def test_read_results_refuses_a_file_whose_header_was_lost(tmp_path):
    out = _Finished(tmp_path, 3)
    out.write_text(''.join(out.read_text().splitlines(keepends=True)[1:]))
    with pytest.raises(ValueError, match=r"ReadResults: '.*runs.csv' has other columns than its study"):
        ReadResults(out)


@pytest.mark.parametrize('alias', ['symlink', 'hardlink'])
def test_a_study_on_another_name_of_a_locked_output_is_refused(tmp_path, alias):
    out = _Finished(tmp_path, 3)
    other = tmp_path / 'other.csv'
    (other.symlink_to if alias == 'symlink' else other.hardlink_to)(out)
    before = out.read_bytes()
    with OutputLock(out, 'first'):
        with pytest.raises(OutputBusyError, match=r"^RunStudy: '.*other.csv' is being written by "):
            RunStudy(_Study(3), other, workers=1, quiet=True)
    assert out.read_bytes() == before


@pytest.mark.parametrize('alias', ['symlink', 'hardlink'])
def test_a_sweep_on_another_name_of_an_output_another_process_writes_is_refused(capsys, tmp_path, alias):
    out = _Finished(tmp_path, 3)
    other = tmp_path / 'other.csv'
    (other.symlink_to if alias == 'symlink' else other.hardlink_to)(out)
    before = out.read_bytes()
    holder = subprocess.Popen([sys.executable, '-c', 'import sys, time\nfrom exudyn_worm._files import OutputLock\n'
                               'lock = OutputLock(sys.argv[1]).__enter__()\nprint("ready", flush=True)\n'
                               'time.sleep(120)\n', str(out)], stdout=subprocess.PIPE, text=True)
    try:
        assert holder.stdout.readline() == 'ready\n'
        assert Main(['sweep', '--vary', 'J1=0.1,0.11,0.12', '--output', str(other), '--quiet']) == 2
    finally:
        holder.send_signal(signal.SIGKILL)
        holder.wait()
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"exudyn-worm: error: RunStudy: '{other}' is being written by "), err
    assert out.read_bytes() == before


def test_the_lock_of_a_new_output_covers_the_file_once_it_exists(tmp_path):
    """A study that starts on a new file locks it as soon as it is created: a hard link made afterwards is refused."""
    out = tmp_path / 'runs.csv'
    link = tmp_path / 'link.csv'
    seen = []

    def Second(row):
        if not seen:
            link.hardlink_to(out)
            with pytest.raises(OutputBusyError, match='under another name'):
                with OutputLock(link, 'second'):
                    pass
        seen.append(row['run'])
    RunStudy(_Study(2), out, workers=1, quiet=True, onRow=Second)
    assert seen == [0, 1] and link.read_bytes() == out.read_bytes()


def test_a_resume_keeps_only_the_runs_of_the_study_and_names_the_rest(tmp_path):
    out = _Finished(tmp_path, 6)
    lines = out.read_bytes().splitlines(keepends=True)
    header = lines[0].decode().rstrip('\r\n').split(',')
    runCol, statusCol, j1Col = header.index('run'), header.index('status'), header.index('J1')

    def Changed(line: bytes, column: int, value: bytes) -> bytes:
        cells = line.rstrip(b'\r\n').split(b',')
        cells[column] = value
        return b','.join(cells) + b'\r\n'
    lines[2] = Changed(lines[2], j1Col, b'0.5')                  # run 1 with a parameter the study does not have
    lines[3] = Changed(lines[3], statusCol, b'o\xffk')           # run 2: its status is not UTF-8 text
    lines.append(Changed(lines[1], runCol, b'999'))              # no run of the study
    lines.append(lines[4])                                       # run 3 written twice
    out.write_bytes(b''.join(lines))
    seen = []
    with pytest.warns(StudyFileWarning) as caught:
        result = RunStudy(_Study(6), out, workers=1, quiet=True, onRow=seen.append)
    message = str(caught[0].message)
    assert message.startswith(f"'{out}': dropped 5 lines that cannot be read or are no run of the study, their runs "
                              f"are run again (line 3: run 1: J1 = 0.5, but the study's run 1 has J1 = 0.11; "
                              f"line 4: not UTF-8 text"), message
    assert 'line 5: run 3 is written again on line 9 (both dropped)' in message
    assert 'line 8: run 999 is no run of the study (runs 0 to 5)' in message
    assert sorted(r['run'] for r in seen) == [1, 2, 3]           # run again; 999 is no run of the study
    assert [r['run'] for r in result.rows] == [0, 1, 2, 3, 4, 5]
    again = ReadResults(out)
    assert [r['run'] for r in again.rows] == [0, 1, 2, 3, 4, 5]
    assert [r['J1'] for r in again.rows] == [0.1 + 0.01 * i for i in range(6)]
    assert all(r['status'] == 'ok' for r in again.rows)
    assert len(out.read_text().splitlines()) == 7


def test_rows_of_another_shard_are_dropped_on_resume(tmp_path):
    study = _Study(4)
    out = tmp_path / 'part.csv'
    RunStudy(study, out, workers=1, quiet=True, shard='0/2')             # runs 0, 2
    whole = tmp_path / 'whole.csv'
    RunStudy(study, whole, workers=1, quiet=True)
    extra = whole.read_text().splitlines(keepends=True)[2]              # run 1: of the other shard
    out.write_text(out.read_text() + extra)
    with pytest.warns(StudyFileWarning, match=r"line 4: run 1 is no run of this shard"):
        result = RunStudy(study, out, workers=1, quiet=True, shard='0/2')
    assert [r['run'] for r in result.rows] == [0, 2]


@pytest.mark.parametrize('which', ['sidecar', 'lock'])
def test_a_folder_in_place_of_the_sidecar_or_lock_file_is_refused(tmp_path, which):
    out = tmp_path / 'runs.csv'
    folder = StudySidecarPath(out) if which == 'sidecar' else LockPath(out)
    folder.mkdir()
    what = 'its sidecar' if which == 'sidecar' else 'its lock file'
    with pytest.raises(ValueError, match=rf"^RunStudy: the path of {what} '.*' is a folder; move it away or choose "
                                         rf"another output file"):
        RunStudy(_Study(2), out, workers=1, quiet=True)
    assert sorted(p.name for p in tmp_path.iterdir()) == [folder.name]


def test_a_full_disk_when_the_results_file_is_created_leaves_nothing(tmp_path, monkeypatch):
    out = tmp_path / 'runs.csv'

    class Full:
        def __init__(self, file):
            pass

        def writerow(self, row):
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
    monkeypatch.setattr(study_module.csv, 'writer', Full)
    with pytest.raises(OSError, match='No space left on device'):
        RunStudy(_Study(2), out, workers=1, quiet=True)
    assert list(tmp_path.iterdir()) == []                         # no empty results file, sidecar or lock file


def test_a_full_disk_while_taking_the_lock_keeps_the_lock_and_leaves_no_lock_file(tmp_path, monkeypatch):
    out = tmp_path / 'runs.csv'
    real = os.write

    def Full(fd, data):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
    monkeypatch.setattr(os, 'write', Full)
    with OutputLock(out, 'here') as lock:
        assert lock.lockPath.exists()
        monkeypatch.setattr(os, 'write', real)
        with pytest.raises(OutputBusyError):
            OutputLock(out, 'again').__enter__()
    assert list(tmp_path.iterdir()) == []


def test_a_disk_full_after_some_rows_keeps_them_and_a_resume_completes_the_study(capsys, tmp_path, monkeypatch):
    out = tmp_path / 'runs.csv'
    real = study_module.csv.writer

    class FillsUp:
        """Writes the header and two rows, then half a row before the disk is full."""

        def __init__(self, file):
            self.file, self.writer, self.rows = file, real(file), 0

        def writerow(self, row):
            self.rows += 1
            if self.rows == 4:
                self.file.write('half,a,row')
                self.file.flush()
                raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
            self.writer.writerow(row)
    monkeypatch.setattr(study_module.csv, 'writer', FillsUp)
    argv = ['sweep', '--vary', 'J1=0.1,0.11,0.12,0.13,0.14', '--output', str(out), '--quiet', '--workers', '1']
    assert Main(argv) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f'exudyn-worm: error: {out}: No space left on device']
    assert len(out.read_text().splitlines()) == 4                     # header, two rows, the half row
    monkeypatch.setattr(study_module.csv, 'writer', real)
    assert Main(argv + ['--json']) == 0
    err = capsys.readouterr().err
    assert "dropped 1 line that cannot be read or is no run of the study, their runs are run again (line 4: cut " \
           "off" in err and 'Traceback' not in err
    assert [r['run'] for r in ReadResults(out).rows] == [0, 1, 2, 3, 4]


def test_read_results_refuses_a_sidecar_that_cannot_be_read(tmp_path):
    out = _Finished(tmp_path, 2)
    StudySidecarPath(out).write_text('{"study": {"base": 3}}')
    with pytest.raises(ValueError, match=r"^ReadResults: its sidecar '.*runs.study.json' cannot be read \("):
        ReadResults(out)
