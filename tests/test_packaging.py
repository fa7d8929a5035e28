"""The example drives and the docs ship with the package; `--config NAME` loads a shipped
drive; `--help` points to documentation that exists; a built wheel, installed into a fresh venv, runs
`exudyn-worm stability` on a shipped drive."""
import json
import os
import shutil
import subprocess
import sys
import sysconfig
import zipfile
from pathlib import Path

import pytest

from exudyn_worm.cli.main import Main
from exudyn_worm.params.drives import ConfigPath, DocPath, ShippedDrive, ShippedDrives

ROOT = Path(__file__).resolve().parents[1]


def test_every_example_drive_is_shipped_by_name():
    names = sorted(p.stem for p in (ROOT / 'examples' / 'drives').glob('*.toml'))
    assert list(ShippedDrives()) == names and 'figure19' in names
    assert ShippedDrive('figure19').read_bytes() == (ROOT / 'examples/drives/figure19.toml').read_bytes()
    assert ShippedDrive('figure19.toml') == ShippedDrive('figure19')
    with pytest.raises(ValueError, match=r"ShippedDrive: 'name' must be a shipped drive \(chart, figure19, .*got 'x'"):
        ShippedDrive('x')


def test_config_path_prefers_files(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert ConfigPath('figure19') == os.fspath(ShippedDrive('figure19'))
    (tmp_path / 'figure19').write_text('[parameters]\nJ1 = 0.2\n')
    assert ConfigPath('figure19') == 'figure19'                          # a file of that name wins
    for text in ('missing.toml', 'sub/figure19', 'nothing'):
        assert ConfigPath(text) == text


def _Json(capsys, *argv):
    rc = Main(list(argv) + ['--json'])
    out, err = capsys.readouterr()
    assert rc == 0, err
    return json.loads(out)


def test_stability_by_name_equals_stability_by_path(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)                                          # no examples/ folder here
    byName = _Json(capsys, 'stability', '--config', 'figure19')
    byPath = _Json(capsys, 'stability', '--config', str(ROOT / 'examples/drives/figure19.toml'))
    byName.pop('source', None), byPath.pop('source', None)
    assert byName == byPath


def test_unknown_name_lists_the_shipped_drives(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert Main(['stability', '--config', 'figure20']) == 2
    err = capsys.readouterr().err
    assert err.count('\n') == 1 and "'figure20' is neither a file nor a shipped drive (chart, figure19" in err


def test_help_points_to_docs_that_exist(capsys):
    try:
        Main(['stability', '--help'])
    except SystemExit:
        pass
    out = ''.join(capsys.readouterr().out.split())          # the help wraps lines (also at hyphens)
    path = DocPath('drive-files.md')
    assert Path(path).is_file() and ''.join(path.split()) in out
    assert 'examples/drives/' not in out and 'figure19' in out


@pytest.mark.slow
def test_wheel_ships_drives_and_docs_and_runs_stability(tmp_path):
    """Build the wheel, install it (no dependencies: they come from this environment through a .pth file)
    into a fresh venv without the source checkout, and run `exudyn-worm stability --config figure19`."""
    source = tmp_path / 'src'                  # a copy: building writes build/ and *.egg-info next to the sources
    ignore = shutil.ignore_patterns('__pycache__', '*.egg-info', 'build')
    source.mkdir()
    for name in ('pyproject.toml', 'setup.py', 'MANIFEST.in', 'README.md'):
        shutil.copy2(ROOT / name, source / name)
    for folder in ('exudyn_worm', 'examples/drives', 'docs'):
        shutil.copytree(ROOT / folder, source / folder, ignore=ignore)
    build = subprocess.run([sys.executable, '-m', 'pip', 'wheel', str(source), '--no-deps', '-q', '-w',
                            str(tmp_path / 'dist')], capture_output=True, text=True)
    assert build.returncode == 0, build.stderr[-2000:]
    wheel, = (tmp_path / 'dist').glob('exudyn_worm-*.whl')
    names = zipfile.ZipFile(wheel).namelist()
    for drive in ShippedDrives():
        assert f'exudyn_worm/drives/{drive}.toml' in names
    assert 'exudyn_worm/docs/drive-files.md' in names
    venv = tmp_path / 'venv'
    subprocess.run([sys.executable, '-m', 'venv', '--without-pip', str(venv)], check=True)
    python = venv / ('Scripts/python.exe' if os.name == 'nt' else 'bin/python')
    purelib = subprocess.run([str(python), '-c', 'import sysconfig; print(sysconfig.get_paths()["purelib"])'],
                             capture_output=True, text=True, check=True).stdout.strip()
    # the dependencies (exudyn, numpy, ...) from this environment; its editable exudyn_worm is not activated
    # (.pth files of a directory added by a .pth file are not run)
    Path(purelib, 'deps.pth').write_text(sysconfig.get_paths()['purelib'] + '\n')
    install = subprocess.run([sys.executable, '-m', 'pip', '--python', str(python), 'install', '--no-deps',
                              '--no-index', '-q', str(wheel)], capture_output=True, text=True)
    assert install.returncode == 0, install.stderr[-2000:]
    script = venv / ('Scripts/exudyn-worm.exe' if os.name == 'nt' else 'bin/exudyn-worm')
    env = {k: v for k, v in os.environ.items() if k not in ('PYTHONPATH', 'VIRTUAL_ENV')}
    run = subprocess.run([str(script), 'stability', '--config', 'figure19'], capture_output=True, text=True,
                         cwd=tmp_path, env=env)
    assert run.returncode == 0, run.stderr
    installed = Path(purelib, 'exudyn_worm')
    assert f"config {installed / 'drives' / 'figure19.toml'}" in run.stdout
    assert 'S = -1' in run.stdout
    helpText = subprocess.run([str(script), 'check', '--help'], capture_output=True, text=True, cwd=tmp_path,
                              env=env, check=True).stdout
    docs = os.fspath(installed / 'docs' / 'drive-files.md')
    assert docs.replace(os.sep, '') in ''.join(helpText.split()).replace(os.sep, '') and Path(docs).is_file()
    assert str(ROOT) not in helpText
