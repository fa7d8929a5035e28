"""Paths the user may not use: every command refuses them before any work, in one line, exit status 2.

Root is not subject to file permissions (its capabilities CAP_DAC_OVERRIDE and CAP_DAC_READ_SEARCH override
them), so as root the commands run under ``setpriv`` with these two capabilities dropped from the bounding set:
the process keeps its user id but the kernel checks the permission bits for it as for anyone else.
"""
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DROP = ['setpriv', '--bounding-set=-dac_override,-dac_read_search']


def _Run(args, cwd):
    prefix = []
    if os.geteuid() == 0:
        if shutil.which('setpriv') is None:
            pytest.skip('running as root without setpriv: file permissions cannot be tested here')
        prefix = DROP
    return subprocess.run(prefix + [sys.executable] + args, cwd=cwd, capture_output=True, text=True, timeout=120,
                          env={**os.environ, 'PYTHONPATH': str(ROOT)})


@pytest.fixture
def folders(tmp_path):
    """A folder that may not be searched (mode 000), one that may be searched but not written (mode 500) and a
    drive file that may not be read (mode 000); the modes are restored at the end so that pytest can clean up."""
    locked, readOnly = tmp_path / 'locked', tmp_path / 'readonly'
    locked.mkdir()
    readOnly.mkdir()
    drive = tmp_path / 'drive.toml'
    drive.write_text('preset = "reel-P1"\n')
    locked.chmod(0)
    readOnly.chmod(0o500)
    drive.chmod(0)
    yield {'locked': locked, 'readonly': readOnly, 'drive': drive, 'tmp': tmp_path}
    locked.chmod(0o700)
    readOnly.chmod(0o700)
    drive.chmod(0o600)


def _Listing(folders):
    return sorted(p.name for p in folders['tmp'].rglob('*') if p.stat().st_mode & 0o700)


CLI = ['-m', 'exudyn_worm']
CASES = {
    'simulate --csv, unsearchable': (CLI + ['simulate', '--preset', 'reel-P1', '--csv', '{locked}/run.csv'], '--csv'),
    'simulate --plot, unwritable': (CLI + ['simulate', '--preset', 'reel-P1', '--plot', '{readonly}/figures'], '--plot'),
    'sweep --output, unsearchable': (CLI + ['sweep', '--vary', 'J1=0.1,0.2', '--output', '{locked}/runs.csv'], '--output'),
    'sweep --output, unwritable': (CLI + ['sweep', '--vary', 'J1=0.1,0.2', '--output', '{readonly}/runs.csv'], '--output'),
    'chart --output, unwritable': (CLI + ['chart', '--output', '{readonly}/chart.png'], '--output'),
    'check --plot, unsearchable': (CLI + ['check', '--preset', 'reel-P1', '--plot', '{locked}/check.png'], '--plot'),
    'stability --config, unreadable': (CLI + ['stability', '--config', '{drive}'], 'drive.toml'),
    'simulate --config, unreadable': (CLI + ['simulate', '--config', '{drive}'], 'drive.toml'),
    'validation --report, unwritable': (['-m', 'validation', '--quick', '--report', '{readonly}/report.md'], '--report'),
    'validation --record-baseline, unsearchable': (['-m', 'validation', '--quick', '--record-baseline',
                                                    '{locked}/baseline.json'], '--record-baseline'),
}


@pytest.mark.parametrize('case', list(CASES), ids=list(CASES))
def test_a_path_the_user_may_not_use_is_one_line_before_any_work(folders, case):
    args, option = CASES[case]                 # option: what the line must name (the option, or the file)
    before = _Listing(folders)
    run = _Run([a.format(**folders) for a in args], cwd=folders['tmp'])
    err = run.stderr.strip().splitlines()
    assert run.returncode == 2, (run.returncode, run.stderr[-2000:])
    assert len(err) == 1 and 'Traceback' not in run.stderr, run.stderr[-2000:]
    text = err[0].lower()
    assert option in err[0] and ('permission denied' in text or 'not writable' in text or 'may not' in text), err[0]
    assert run.stdout == ''                                       # refused before any work: nothing printed
    assert _Listing(folders) == before                            # and nothing written
