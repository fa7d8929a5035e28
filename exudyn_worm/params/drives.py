"""The example drive files and the user documentation that ship with the package.

A wheel carries the drive files of ``examples/drives/`` in ``exudyn_worm/drives/`` and the Markdown files of
``docs/`` in ``exudyn_worm/docs/`` (copied by ``setup.py`` at build time; the checkout keeps one copy of each).
In a source checkout or an editable install, the checkout's folders are used. Every subcommand's
``--config`` takes a shipped drive by name (``--config figure19``) as well as a file path.
"""
from __future__ import annotations

import argparse
import os
from pathlib import Path
from typing import Dict, Optional, Union

__all__ = ['DrivesFolder', 'DocsFolder', 'ShippedDrives', 'ShippedDrive', 'DocPath', 'ConfigPath', 'ConfigArgument']

_PACKAGE = Path(__file__).resolve().parents[1]   # exudyn_worm/ (this module is in exudyn_worm/params/)
_CHECKOUT = _PACKAGE.parent


def _Folder(installed: str, checkout: str, pattern: str) -> Optional[Path]:
    for folder in (_PACKAGE / installed, _CHECKOUT / checkout):
        if folder.is_dir() and any(folder.glob(pattern)):
            return folder
    return None


def DrivesFolder() -> Optional[Path]:
    """The folder of the shipped drive files: ``exudyn_worm/drives`` of an installed wheel, else the source
    checkout's ``examples/drives``; None if neither exists."""
    return _Folder('drives', 'examples/drives', '*.toml')


def DocsFolder() -> Optional[Path]:
    """The folder of the user documentation: ``exudyn_worm/docs`` of an installed wheel, else the source
    checkout's ``docs``; None if neither exists."""
    return _Folder('docs', 'docs', '*.md')


def ShippedDrives() -> Dict[str, Path]:
    """``{name: path}`` of the shipped drive files, the name being the file name without ``.toml``
    (``'figure19'``, ``'reel-P1'``, ...), sorted by name."""
    folder = DrivesFolder()
    return {} if folder is None else {p.stem: p for p in sorted(folder.glob('*.toml'), key=lambda p: p.stem)}


def ShippedDrive(name: str) -> Path:
    """The path of a shipped drive file, e.g. ``ShippedDrive('figure19')`` for
    :func:`~exudyn_worm.drive.config.LoadConfig`.

    Parameters
    ----------
    name : str
        File name without ``.toml`` (or with it).

    Returns
    -------
    Path

    Raises
    ------
    ValueError
        For a name that is not a shipped drive (the message lists them).
    """
    drives = ShippedDrives()
    key = name[:-5] if isinstance(name, str) and name.endswith('.toml') else name
    if key not in drives:
        raise ValueError(f"ShippedDrive: 'name' must be a shipped drive ({', '.join(drives) or 'none found'}), "
                         f"got {name!r}")
    return drives[key]


def DocPath(name: str) -> str:
    """Where a user document can be read: its path in the installed package (or checkout), e.g. for
    ``--help``; the bare name if the documentation is not there.

    Parameters
    ----------
    name : str
        File name in ``docs/``, e.g. ``'drive-files.md'``.
    """
    folder = DocsFolder()
    return os.fspath(folder / name) if folder is not None and (folder / name).is_file() else name


def ConfigPath(text: Union[str, os.PathLike]) -> Union[str, os.PathLike]:
    """A ``--config`` argument as a path: an existing file, or anything that looks like a path (a folder
    separator or a ``.toml`` suffix), as it is; else the shipped drive of that name if there is one; else as
    it is (reading it then says that it cannot be read).

    Parameters
    ----------
    text : str or path-like
        The argument.
    """
    path = Path(text)
    # os.path.exists: False (not PermissionError) in a folder one may not search; reading it then says why
    if os.path.exists(path) or path.suffix or len(path.parts) > 1:
        return text
    drive = ShippedDrives().get(os.fspath(text))
    return os.fspath(drive) if drive is not None else text


def ConfigArgument(text: str) -> str:
    """argparse ``type`` of ``--config``: :func:`ConfigPath`, and for a bare name that is neither a file nor a
    shipped drive an error that lists the shipped drives.

    Parameters
    ----------
    text : str
        The argument.
    """
    path = ConfigPath(text)
    if path is text and not os.path.exists(text) and not Path(text).suffix and len(Path(text).parts) == 1:
        raise argparse.ArgumentTypeError(
            f"'{text}' is neither a file nor a shipped drive ({', '.join(ShippedDrives()) or 'none found'}); "
            f"give a path such as ./{text}.toml")
    return os.fspath(path)
