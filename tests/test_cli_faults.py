"""No traceback, no hang, no partial file: a full disk (ENOSPC, simulated by a write that raises it, or /dev/full),
a file name too long, an output under /proc or on a device, special and oversized drive files, a stdout that
cannot be written and a signal while the command line loads each end in one line on stderr with a non-zero exit
status, and leave no file half-written or lost."""
import errno
import os
import re
import signal
import subprocess
import sys
import threading
from pathlib import Path

import pytest

import exudyn_worm.plotting.plot as plot
from exudyn_worm._files import WriteTextAtomically
from exudyn_worm.analysis.studies import study as study_module
from exudyn_worm.analysis.studies import studypoint
from exudyn_worm._workers import SignalsHeld, SigtermAsInterrupt
from exudyn_worm.cli import main as cli_main
from exudyn_worm.cli.main import BadInput, Main, Subcommand
from exudyn_worm.params.drivefile import MAX_FILE_BYTES, MAX_KEYS, MAX_NESTING
from exudyn_worm.params.parameters import MAX_STAGES
from exudyn_worm.model.friction import ReadFrictionTable
from exudyn_worm.drive.config import LoadConfig, ParseSetOption
from exudyn_worm.drive.duty import LoadFromParameters
from exudyn_worm.drive.presets import GetPreset
import validation.cli as validation_cli
import validation.runner as runner

ROOT = Path(__file__).resolve().parents[1]
FIGURE19 = ROOT / 'examples' / 'drives' / 'figure19.toml'

pytestmark = pytest.mark.usefixtures('emptyWorkingDirectory')   # nothing written to the cwd


def _Full(*args, **kwargs):
    raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


def _OneLine(capsys, start: str) -> str:
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and 'Traceback' not in err, err
    assert lines[0].startswith(start), lines[0]
    return lines[0]


@pytest.fixture
def folder(tmp_path):
    path = tmp_path / 'out'
    path.mkdir()
    return path


# --- a full disk --------------------------------------------------------------------------------------------
def test_a_full_disk_for_chart_output_is_one_line_and_no_file(capsys, folder, monkeypatch):
    from matplotlib.figure import Figure      # lazy: matplotlib only for the test that patches its savefig
    monkeypatch.setattr(Figure, 'savefig', lambda self, path, **kw: (Path(path).write_bytes(b'half'), _Full()))
    out = folder / 'c.png'
    assert Main(['chart', '--preset', 'chart', '--DV', '0.014', '--DTV', '5', '--resolution', '20', '--quiet',
                 '--output', str(out)]) == 1
    assert _OneLine(capsys, 'exudyn-worm: error: ') == f"exudyn-worm: error: {out}: No space left on device"
    assert list(folder.iterdir()) == []                   # no 0-byte or half PNG, no temporary file


def _InstantPoint(task):
    """A row of the run's own parameters at once (the runs are not what these tests check)."""
    return {'run': task.run, 'status': 'ok', 'error': '', 'seconds': 0.001, **task.varied}


def test_a_full_disk_for_sweep_output_is_one_line_and_no_file(capsys, folder, monkeypatch):
    monkeypatch.setattr(studypoint, 'RunPoint', _InstantPoint)

    class FullWriter:
        def __init__(self, file):
            pass

        writerow = staticmethod(_Full)
    monkeypatch.setattr(study_module.csv, 'writer', FullWriter)
    out = folder / 'runs.csv'
    assert Main(['sweep', '--vary', 'J1=0.1,0.2', '--output', str(out), '--quiet']) == 1
    assert _OneLine(capsys, 'exudyn-worm: error: ') == f"exudyn-worm: error: {out}: No space left on device"
    assert list(folder.iterdir()) == []                   # no empty results file, sidecar or lock file


def test_a_full_disk_for_sweep_plot_is_one_line_and_keeps_the_results(capsys, folder, monkeypatch):
    monkeypatch.setattr(studypoint, 'RunPoint', _InstantPoint)
    from matplotlib.figure import Figure      # lazy: matplotlib only for the test that patches its savefig
    monkeypatch.setattr(Figure, 'savefig', lambda self, path, **kw: (Path(path).write_bytes(b'half'), _Full()))
    out, figure = folder / 'runs.csv', folder / 'j1.png'
    assert Main(['sweep', '--vary', 'J1=0.1,0.2', '--output', str(out), '--plot', str(figure), '--quiet',
                 '--metric', 'seconds']) == 1
    assert _OneLine(capsys, 'exudyn-worm: error: ') == f"exudyn-worm: error: {figure}: No space left on device"
    assert sorted(p.name for p in folder.iterdir()) == ['runs.csv', 'runs.study.json']
    assert len(out.read_text().splitlines()) == 3         # both runs kept


def test_a_full_disk_for_the_validation_report_is_one_line_and_no_file(capsys, folder, monkeypatch):
    report = folder / 'report.md'

    def Validation(reportPath=None, **kwargs):
        runner.WriteText(reportPath, '# report\n')
        raise AssertionError('not reached')
    monkeypatch.setattr(runner, 'RunValidation', Validation)
    monkeypatch.setattr(Path, 'write_text', lambda self, *a, **k: (Path.write_bytes(self, b'half'), _Full()))
    assert validation_cli.Main(['--report', str(report)]) == 1
    assert _OneLine(capsys, 'python -m validation: error: ') == \
        f"python -m validation: error: {report}: No space left on device"
    assert list(folder.iterdir()) == []


def test_a_full_disk_for_simulate_plot_leaves_no_half_made_folder(capsys, folder, monkeypatch):
    calls = []

    def SecondFails(fig, path, *args, **kwargs):
        calls.append(path)
        if len(calls) == 2:
            _Full()
        Path(path).write_bytes(b'png')
    monkeypatch.setattr(plot, 'SaveFigure', SecondFails)
    figures = folder / 'figs'
    assert Main(['simulate', '--end-time', '0.3', '--quiet', '--plot', str(figures)]) == 2
    line = _OneLine(capsys, 'exudyn-worm: error: ')
    assert line.startswith(f"exudyn-worm: error: --plot {figures}: cannot write: No space left on device"), line
    assert list(folder.iterdir()) == []                   # the folder it made is gone, with the figure in it


@pytest.mark.parametrize('argv', [['stability', '--json'], ['--version']])   # argparse swallows the error of --version
def test_stdout_that_cannot_be_written_is_one_line_exit_1(argv):
    if not os.path.exists('/dev/full'):
        pytest.skip('no /dev/full on this system')
    with open('/dev/full', 'w') as full:
        done = subprocess.run([sys.executable, '-m', 'exudyn_worm', *argv], stdout=full,
                              stderr=subprocess.PIPE, text=True, timeout=120)
    assert done.returncode == 1
    assert done.stderr == 'exudyn-worm: error: cannot write standard output: No space left on device\n'


def test_stdout_that_cannot_be_written_in_process(capsys, monkeypatch):
    class Full:
        def write(self, text):
            _Full()

        def flush(self):
            pass
    monkeypatch.setattr(sys, 'stdout', Full())
    assert Main(['stability', '--json']) == 1
    assert _OneLine(capsys, 'exudyn-worm: error: ') == \
        'exudyn-worm: error: cannot write standard output: No space left on device'


# --- outputs that cannot be written: refused before computing ------------------------------------------------
def test_an_output_under_proc_is_refused_before_computing(capsys):
    if not os.path.isdir('/proc/self'):
        pytest.skip('no /proc on this system')
    assert Main(['chart', '--output', '/proc/x.png']) == 2
    assert _OneLine(capsys, 'exudyn-worm: error: ') == \
        'exudyn-worm: error: --output /proc/x.png: cannot create a file in the folder /proc: No such file or directory'


@pytest.mark.parametrize('length', [300, 240])
def test_a_file_name_too_long_is_refused_before_computing(capsys, folder, length):
    out = folder / ('a' * length + '.png')
    assert Main(['chart', '--output', str(out)]) == 2
    line = _OneLine(capsys, f'exudyn-worm: error: --output {out}: ')
    assert line.endswith('File name too long') if length == 300 else \
        f'the file name is {length + 4} bytes long, above the limit of ' in line
    assert list(folder.iterdir()) == []


def test_a_device_as_output_is_refused_even_with_overwrite(capsys):
    assert Main(['simulate', '--csv', os.devnull, '--overwrite']) == 2
    assert _OneLine(capsys, 'exudyn-worm: error: ') == \
        f'exudyn-worm: error: --csv {os.devnull}: is not a regular file (a device, FIFO or socket); give a file name'
    assert os.path.exists(os.devnull) and not os.path.isfile(os.devnull)


# --- drive files: special, large, deep, many keys, many stages ---------------------------------------------
@pytest.mark.messages
def test_a_fifo_as_drive_file_is_refused_at_once(capsys, folder):
    fifo = folder / 'drive.toml'
    os.mkfifo(fifo)                                       # no writer: reading it would block for ever
    assert Main(['stability', '--config', str(fifo)]) == 2
    assert _OneLine(capsys, 'exudyn-worm: error: ') == \
        f"exudyn-worm: error: LoadConfig: '{fifo}': is a FIFO (named pipe), expected a TOML drive file"


@pytest.mark.messages
def test_a_device_as_drive_file_is_refused_without_reading_it():
    with pytest.raises(ValueError, match=r"^LoadConfig: '/dev/zero': is a device, expected a TOML drive file$"):
        LoadConfig('/dev/zero')


#: drive file -> (its text, the message after "LoadConfig: '<file>': ")
_OVER_A_LIMIT = {
    'size': ('# ' + 'x' * MAX_FILE_BYTES + '\n', 'larger than the limit of 1,000,000 bytes for a TOML drive file'),
    'nesting': ('x = ' + '[' * (MAX_NESTING + 1) + ']' * (MAX_NESTING + 1) + '\n',
                f'nested deeper than the limit of {MAX_NESTING} levels (tables, arrays or inline tables)'),
    'deep nesting': ('x = ' + '[' * 5000 + ']' * 5000 + '\n',       # a RecursionError of the TOML parser
                     f'nested deeper than the limit of {MAX_NESTING} levels (arrays or inline tables)'),
    'digits': ('[gear]\nwormRadius = ' + '9' * 5000 + '\n',
               'not valid TOML: Exceeds the limit (4300 digits) for integer string conversion: value has 5000 digits; '
               'use sys.set_int_max_str_digits() to increase the limit'),
    'keys': ('[parameters]\n' + ''.join(f'unknown{i} = 1\n' for i in range(MAX_KEYS + 1)),
             'more than the limit of 1,000 keys in a drive file'),
    'stages': (FIGURE19.read_text() + ''.join('\n[[driveSide]]\ninertia = 0.01\nstiffness = 1e4\n'
                                              for _ in range(MAX_STAGES + 1)),
               None),
}


@pytest.mark.messages
@pytest.mark.parametrize('limit', list(_OVER_A_LIMIT))
def test_a_drive_file_over_a_limit_is_refused_naming_it(folder, limit):
    text, message = _OVER_A_LIMIT[limit]
    path = folder / 'drive.toml'
    path.write_text(text)
    if message is None:                                   # the file's own stages plus the limit's + 1
        stages = text.count('[[driveSide]]')
        message = f'[[driveSide]]: {stages} stages, above the limit of {MAX_STAGES} stages of a chain'
    with pytest.raises(ValueError) as caught:
        LoadConfig(path)
    assert str(caught.value) == f"LoadConfig: '{path}': {message}"


@pytest.mark.messages
def test_a_numbered_key_beyond_the_stage_limit_is_refused(capsys):
    assert Main(['stability', '--set', 'J200=1', '--set', 'k200=1']) == 2
    assert _OneLine(capsys, 'exudyn-worm: error: ') == (
        "exudyn-worm: error: ParseSetOption: 'J200=1': 'J200' is stage 197 of the drive-side chain, above the "
        f"limit of {MAX_STAGES} stages")


# --- bad input refused in one line --------------------------------------------------------------------------
@pytest.mark.messages
@pytest.mark.parametrize('argv, message', [
    (['stability', '--set', 'loadTorqueOverTime=notalist'],
     "ParseSetOption: 'loadTorqueOverTime=notalist': 'loadTorqueOverTime': cannot read the table file 'notalist' "
     "(no such file); expected the path of a table file or rows of (time, torque) such as '[[0, 0]]'"),
    (['chatter', '--vary', 'J1=0.1:0.2', '--vary', 'J1=0.1:0.3'],
     "argument --vary: expected once (one parameter is continued), got 'J1=0.1:0.2' and 'J1=0.1:0.3' "
     "(see 'exudyn-worm chatter --help')"),
    (['chatter', '--max-points', '0'],
     "argument --max-points: must be >= 1 orbits, got 0 orbits (see 'exudyn-worm chatter --help')"),
    (['chatter', '--max-points', '-3'],
     "argument --max-points: must be >= 1 orbits, got -3 orbits (see 'exudyn-worm chatter --help')"),
    (['chatter', '--max-points', '5'],
     "chatter: --max-points bounds the branch of --vary; without --vary there is one orbit to report, got "
     "--max-points 5"),
    (['chatter', '--vary', 'J1=0.1:0.2', '--plot', 'x.txt'],
     "--plot: expected a file ending in .png, .pdf, .svg, got 'x.txt'"),
])
def test_bad_input_is_one_line_naming_the_option(capsys, argv, message):
    assert Main(argv) == 2
    assert _OneLine(capsys, 'exudyn-worm: error: ') == f'exudyn-worm: error: {message}'


# --- signals while the command line loads -------------------------------------------------------------------
#: the entry point, with the signal sent to itself when the command line imports numpy (while it loads)
_SIGNAL_WHILE_LOADING = '''
import builtins, os, signal, sys
from exudyn_worm import __main__ as entry
number = getattr(signal, sys.argv.pop(1))
real = builtins.__import__
def Import(name, *args, **kwargs):
    if name == 'numpy' and 'numpy' not in sys.modules:
        os.kill(os.getpid(), number)
    return real(name, *args, **kwargs)
builtins.__import__ = Import
sys.exit(entry.Run())
'''


@pytest.mark.parametrize('name, status, what', [('SIGINT', 130, 'Ctrl-C'), ('SIGTERM', 143, 'SIGTERM')])
@pytest.mark.parametrize('command', ['simulate', 'sweep', 'chatter'])
def test_a_signal_while_the_command_line_loads_is_one_line(command, name, status, what):
    # sweep needs its --vary, or argparse refuses it before anything loads (no numpy for --help and argument errors)
    argv = [command] + (['--vary', 'J1=0.1'] if command == 'sweep' else [])
    done = subprocess.run([sys.executable, '-c', _SIGNAL_WHILE_LOADING, name, *argv], capture_output=True,
                          text=True, timeout=120, env=dict(os.environ, PYTHONPATH=str(ROOT)))
    assert done.returncode == status, done.stderr
    assert done.stderr == f'exudyn-worm: interrupted ({what}); no output file was left half-written\n'


def test_the_console_script_is_the_entry_point_that_handles_signals():
    text = (ROOT / 'pyproject.toml').read_text()
    assert 'exudyn-worm = "exudyn_worm.__main__:Run"' in text


#: a command whose Ctrl-C is raised inside code a C extension runs (pybind11's exec, as while Exudyn loads): CPython
#: remembers it although the command handled it
_INTERRUPT_IN_C_EXTENSION_CODE = '''
import ctypes, sys
from exudyn_worm import __main__ as entry
from exudyn_worm.cli import main
run = ctypes.pythonapi.PyRun_String
run.restype, run.argtypes = ctypes.py_object, [ctypes.c_char_p, ctypes.c_int, ctypes.py_object, ctypes.py_object]
def Main(argv=None):
    try:
        run(b'raise KeyboardInterrupt', 257, {}, {})
    except KeyboardInterrupt as err:
        return main.InterruptedLine(err)
main.Main = Main
sys.exit(entry.Run())
'''


def test_an_interrupt_handled_in_c_extension_code_ends_with_its_status_not_by_sigint(tmp_path):
    # run with -m, as `python -m exudyn_worm`: CPython checks the flag at the exit of a module run so (not of -c)
    (tmp_path / 'interrupted_in_c.py').write_text(_INTERRUPT_IN_C_EXTENSION_CODE)
    done = subprocess.run([sys.executable, '-m', 'interrupted_in_c'], capture_output=True, text=True, timeout=120,
                          env=dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), str(tmp_path)])))
    assert done.returncode == 130, (done.returncode, done.stderr)    # not -2: killed by SIGINT at exit
    assert done.stderr == 'exudyn-worm: interrupted (Ctrl-C); no output file was left half-written\n'


@pytest.mark.messages
@pytest.mark.parametrize('special', ['fifo', 'device'])
def test_a_special_table_file_is_refused_without_reading_it(folder, special):
    path = folder / 'table.csv'
    if special == 'fifo':
        os.mkfifo(path)
    else:
        path = Path('/dev/zero')
    kind = 'a FIFO (named pipe)' if special == 'fifo' else 'a device'
    with pytest.raises(ValueError) as caught:
        ReadFrictionTable(str(path))
    assert str(caught.value) == f"ReadFrictionTable: the friction table '{path}': is {kind}, expected a table file"
    parameters = dict(GetPreset('reel-P1'), loadType='timeTable', loadTorqueOverTime=str(path))
    with pytest.raises(ValueError) as caught:
        LoadFromParameters(parameters, 'here')
    assert str(caught.value) == f"here: 'loadTorqueOverTime': the table file '{path}': is {kind}, expected a table file"
    with pytest.raises(ValueError, match=re.escape(f"cannot read the table file '{path}' (not a regular file)")):
        ParseSetOption(f'loadTorqueOverTime={path}')


def test_an_atomic_write_through_a_symbolic_link_replaces_the_file_not_the_link(folder):
    target = folder / 'target.csv'
    target.write_text('old')
    link = folder / 'link.csv'
    link.symlink_to(target)
    WriteTextAtomically(link, 'new')
    assert link.is_symlink() and target.read_text() == 'new'
    assert sorted(p.name for p in folder.iterdir()) == ['link.csv', 'target.csv']


def _Swallowing(number, then):
    """A subcommand whose library swallows the interrupt of signal ``number``, then does ``then``."""
    def Run(args):
        try:
            os.kill(os.getpid(), number)
            sum(range(1000))                                  # the handler runs here
        except BaseException:                                 # a bare `except:` of a library
            pass
        return then()
    return Subcommand('swallow', 'a library that swallows an interrupt', lambda parser: None, Run,
                      parameterOptions=False)


def _BadInputAfterIt():
    with BadInput():
        raise ValueError('zero-size array to reduction operation minimum which has no identity')


@pytest.mark.parametrize('name, status, what', [('SIGINT', 130, 'Ctrl-C'), ('SIGTERM', 143, 'SIGTERM')])
@pytest.mark.parametrize('then', [lambda: 0, _BadInputAfterIt, lambda: 1 / 0], ids=['success', 'bad input', 'error'])
def test_an_interrupt_a_library_swallows_still_ends_the_command_as_one(capsys, monkeypatch, name, status, what,
                                                                        then):
    monkeypatch.setattr(cli_main, 'SUBCOMMANDS', [_Swallowing(getattr(signal, name), then)])
    assert Main(['swallow']) == status
    assert _OneLine(capsys, 'exudyn-worm: interrupted') == \
        f'exudyn-worm: interrupted ({what}); no output file was left half-written'


def test_signals_held_arrive_when_the_block_ends():
    arrived = []
    with SigtermAsInterrupt():
        with pytest.raises(KeyboardInterrupt):
            with SignalsHeld():                               # to this thread: held by its mask
                signal.pthread_kill(threading.main_thread().ident, signal.SIGINT)
                sum(range(1000))
                arrived.append('not yet')                     # the signal waits for the end of the block
    assert arrived == ['not yet']
