"""`exudyn-worm stability` on drives beyond two masses: the whole drive is linearized, never silently reduced."""
import json
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

from exudyn_worm.cli import main as cli
from exudyn_worm.cli.main import Main
from exudyn_worm.drive.config import ResolveParameters
from exudyn_worm.analysis.stability.linearization import LinearStabilityOfDrive
from exudyn_worm.drive.wholedrive import ResolveDrive

ROOT = Path(__file__).resolve().parents[1]
FIGURE19 = ROOT / 'examples' / 'drives' / 'figure19.toml'


def _Run(tmp_path, *args):
    return subprocess.run([sys.executable, '-m', 'exudyn_worm', 'stability', *args], capture_output=True, text=True,
                          cwd=tmp_path)


def test_chain_uses_the_linearized_whole_drive(tmp_path):
    run = _Run(tmp_path, '--config', str(FIGURE19), '--json')
    assert run.returncode == 0, run.stderr
    data = json.loads(run.stdout)
    assert data['method'] == 'exudyn' and data['components'] == ['a drive-side chain (J4, ...)']
    assert 'inertia4' in data['coordinates']
    expected = LinearStabilityOfDrive(ResolveDrive(parameters=ResolveParameters(config=FIGURE19)))       # at rest, constant mu
    assert data['stable'] is expected.stable is False
    byS = {tuple(s['S']): s for s in data['states']}
    # at the lowering operating point (moving at the motor speed): with constant mu the same eigenvalues as at rest,
    # up to Exudyn's numerical differentiation of the mesh law at another state
    assert byS[(-1,)]['maxRealPart'] == pytest.approx(expected.State(-1).maxRealPart, rel=1e-8)
    assert len(byS[(1,)]['frequenciesHz']) == 3           # the third mode of inertia4 is there
    table = _Run(tmp_path, '--config', str(FIGURE19))
    assert table.returncode == 0 and 'method exudyn' in table.stdout and 'inertia4' in table.stdout
    assert 'preset' not in table.stdout.splitlines()[0]    # a whole-drive file inherits no preset
    assert list(tmp_path.iterdir()) == []


@pytest.mark.messages
@pytest.mark.parametrize('sets', [['--set', 'J4=0.05', '--set', 'k4=2e4'], ['--set', 'kA=7e8', '--set', 'mA=5']])
def test_analytical_method_refuses_components_it_does_not_model(tmp_path, sets):
    run = _Run(tmp_path, '--preset', 'reel-P1', *sets, '--method', 'analytical')
    assert run.returncode == 2 and run.stdout == ''
    assert run.stderr.startswith('exudyn-worm: error: --method analytical: eqs. (15)-(19) describe the two-mass')
    assert 'use --method exudyn' in run.stderr and 'Traceback' not in run.stderr
    assert len(run.stderr.strip().splitlines()) == 1


@pytest.mark.messages
def test_warnings_of_any_subcommand_read_as_one_line(capsys):
    """A Python warning raised inside a subcommand is printed as `exudyn-worm: warning: ...`, without a path."""
    command = cli.Subcommand(name='warn-test', help='emits a warning', addArguments=lambda parser: None,
                             run=lambda args: warnings.warn('something\n to note', UserWarning) or 0,
                             parameterOptions=False)
    cli.SUBCOMMANDS.append(command)
    try:
        assert cli.Main(['warn-test']) == 0
    finally:
        cli.SUBCOMMANDS.remove(command)
    err = capsys.readouterr().err
    assert err == 'exudyn-worm: warning: something to note\n'


CHAIN_WITHOUT_STIFFNESS = 'preset = "reel-P1"\n[[driveSide]]\ninertia = "0.05 kg*m^2"\ndamping = 1\n'
# an incomplete drive-side chain, in every subcommand: (arguments, fragment of the one-line message)
INCOMPLETE_CHAIN = [(['--set', 'J4=0.05'], "DriveSideChain: 'J4' needs the stiffness 'k4'"),
                    (['--set', 'k4=1e4'], "DriveSideChain: the drive-side chain must be J4, J5, ... without gaps"),
                    (['--set', 'J4=0.05', '--set', 'k4=1e4', '--set', 'J6=0.1'], "missing 'J5'"),
                    (['--config', '{tmp}/chain.toml'], "line 3: [[driveSide]] number 1 inertia: DriveSideChain: "
                                                       "'J4' needs the stiffness 'k4'")]
SUBCOMMAND_ARGS = {'stability': [], 'check': [], 'chart': ['--resolution', '10'], 'simulate': ['--quiet'],
                   'sweep': ['--vary', 'J1=0.1,0.2', '--quiet', '--output', 'out.csv']}


@pytest.mark.messages
@pytest.mark.parametrize('command', sorted(SUBCOMMAND_ARGS))
@pytest.mark.parametrize('argv, fragment', INCOMPLETE_CHAIN, ids=[' '.join(a) for a, _ in INCOMPLETE_CHAIN])
def test_incomplete_chain_is_one_line_exit_2_in_every_subcommand(capsys, tmp_path, monkeypatch, command, argv,
                                                                 fragment):
    """Checked where the parameter set is resolved: exit 2, one line, no traceback, nothing written."""
    (tmp_path / 'chain.toml').write_text(CHAIN_WITHOUT_STIFFNESS)
    work = tmp_path / 'cwd'
    work.mkdir()
    monkeypatch.chdir(work)
    status = Main([command, *SUBCOMMAND_ARGS[command], *[a.replace('{tmp}', str(tmp_path)) for a in argv]])
    out, err = capsys.readouterr()
    assert status == 2 and out == ''
    assert err.count('\n') == 1 and err.startswith('exudyn-worm: error: ') and fragment in err, err
    assert 'Traceback' not in err and list(work.iterdir()) == []
