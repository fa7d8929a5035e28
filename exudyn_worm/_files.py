"""Files that are complete or absent, and outputs that one process writes at a time.

:func:`WriteAtomically` is the package's one rule for writing a file: into a hidden temporary file beside it,
then renamed over it, so that an interrupt, a signal or an error leaves the old file (or none) and no partial
one. :class:`OutputLock` keeps a second process off an output that a long job (a study) is writing: the second
one is refused at once with one line naming the holder (process id, host, start time).
"""
from __future__ import annotations

import contextlib
import os
import re
import socket
import stat
import time
from pathlib import Path
from typing import Callable, Optional, Sequence, Union

__all__ = ['WriteAtomically', 'WriteTextAtomically', 'PartialPath', 'OutputLock', 'LockPath', 'OutputBusyError',
           'CheckOutputPath', 'OutputPathError', 'ReadRegularFile', 'MAX_TABLE_FILE_BYTES']

#: the largest table file read (a friction table, a load or speed table over time): 10 MB, some 300,000 rows
MAX_TABLE_FILE_BYTES = 10_000_000


def ReadRegularFile(path: Union[str, os.PathLike], maxBytes: int, where: str, what: str) -> bytes:
    """Read an input file within bounds: a regular file (a FIFO, a device such as ``/dev/zero``, a folder or a
    socket is refused without reading it, so it cannot block or never end) of at most ``maxBytes`` bytes.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    maxBytes : int
        The largest size accepted.
    where : str
        Prefix of the messages, e.g. ``"LoadConfig: 'drive.toml'"``.
    what : str
        What the file should be, for the messages, e.g. ``'a TOML file'``.

    Returns
    -------
    bytes
        Its content.

    Raises
    ------
    ValueError
        One line: ``<where>: is a FIFO (named pipe), expected <what>``, ``<where>: larger than the limit of ...
        bytes for <what>``, ``<where>: cannot read it: <reason>``.
    """
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)     # a FIFO with no writer does not block the open
        try:
            mode = os.fstat(fd).st_mode
            if not stat.S_ISREG(mode):
                kind = ('a folder' if stat.S_ISDIR(mode) else 'a FIFO (named pipe)' if stat.S_ISFIFO(mode) else
                        'a device' if stat.S_ISCHR(mode) or stat.S_ISBLK(mode) else 'a socket' if stat.S_ISSOCK(mode)
                        else 'not a regular file')
                raise ValueError(f"{where}: is {kind}, expected {what}")
            with os.fdopen(fd, 'rb', closefd=False) as file:
                raw = file.read(maxBytes + 1)
        finally:
            os.close(fd)
    except OSError as err:
        raise ValueError(f"{where}: cannot read it: {err.strerror or err}") from None
    if len(raw) > maxBytes:
        raise ValueError(f"{where}: larger than the limit of {maxBytes:,} bytes for {what}")
    return raw


def PartialPath(path: Union[str, os.PathLike]) -> Path:
    """The hidden temporary file that :func:`WriteAtomically` writes before renaming it to ``path``.

    Parameters
    ----------
    path : str or os.PathLike
        The file to write.

    Returns
    -------
    pathlib.Path
        ``.<stem>.<pid>.partial<suffix>`` in the same folder (same suffix, so that a writer choosing its format by
        the suffix chooses the same one; the process id keeps two writers apart).
    """
    path = Path(path)
    return path.with_name(f'.{path.stem}.{os.getpid()}.partial{path.suffix}')


def WriteAtomically(path: Union[str, os.PathLike], write: Callable[[Path], object]) -> Path:
    """Write a file so that it is either complete or absent: into a temporary file beside it, then renamed.

    An interrupt (Ctrl-C, SIGTERM handled as one) or an error during ``write`` removes the temporary file and
    leaves ``path`` as it was. An ``OSError`` of the temporary file (a full disk) is raised naming ``path``. A
    symbolic link is followed: the file it points to is replaced, the link stays.

    Parameters
    ----------
    path : str or os.PathLike
        The file to write.
    write : callable
        ``write(temporaryPath)`` writes the whole file to the path it is given (:func:`PartialPath`: same folder
        and suffix as ``path``).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    path = Path(path)
    target = Path(os.path.realpath(path)) if os.path.islink(path) else path   # a link's file is written, not replaced
    tmp = PartialPath(target)
    try:
        write(tmp)
        os.replace(tmp, target)
    except BaseException as err:
        with contextlib.suppress(OSError):
            tmp.unlink()
        if isinstance(err, OSError) and err.errno is not None and err.filename in (None, os.fspath(tmp)):
            raise OSError(err.errno, err.strerror, os.fspath(path)) from None   # the user's name, not the temporary one
        raise
    return path


def WriteTextAtomically(path: Union[str, os.PathLike], text: str) -> Path:
    """:func:`WriteAtomically` of a text (UTF-8).

    Parameters
    ----------
    path : str or os.PathLike
        The file to write.
    text : str
        Its whole content.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    return WriteAtomically(path, lambda tmp: Path(tmp).write_text(text, encoding='utf-8'))


def LockPath(path: Union[str, os.PathLike]) -> Path:
    """The lock file of :class:`OutputLock` for an output: ``.<name>.lock`` beside the file that ``path`` names
    (a symbolic link is followed, so that the file and its link share one lock).

    Parameters
    ----------
    path : str or os.PathLike
        The output file.

    Returns
    -------
    pathlib.Path
    """
    real = Path(os.path.realpath(path))
    return real.with_name(f'.{real.name}.lock')


class OutputBusyError(ValueError):
    """Another process holds the lock of an output (:class:`OutputLock`); the message names it."""


class OutputLock:
    """An exclusive lock on an output file for as long as a process writes it (a context manager).

    The lock is an advisory ``flock`` on a hidden file ``.<name>.lock`` beside the output, which holds one line
    naming the holder. The kernel releases it when the holder ends in any way (``kill -9`` included; forked
    workers share it until they end, which they do with their parent), so a stale lock file of a killed process
    is taken over (if the holder named in it has ended on this host, its dying workers are waited for, up to
    5 s). Unlike a POSIX record lock it is not lost when the holder opens and closes the file again, and
    it also keeps a second study of the same process off. On NFS, Linux maps it to a POSIX lock on the server.
    The file is removed on release. The output itself is locked too, by its device and inode (:meth:`HoldFile`,
    once it exists), and the lock file sits beside the file a symbolic link points to (:func:`LockPath`): a second
    process on another name of the same file (a hard or symbolic link) is refused as well. Where ``fcntl`` is
    missing (Windows) it only records the holder.

    Parameters
    ----------
    path : str or os.PathLike
        The output file.
    where : str, optional
        Prefix of the refusal message (the function or command).

    Raises
    ------
    OutputBusyError
        On entering, if another process holds the lock: ``where: 'runs.csv' is being written by another process
        (pid 4242 on host node7, since 2026-12-02T07:00:00+0000); wait for it to end or choose another output``.
    """

    def __init__(self, path: Union[str, os.PathLike], where: str = 'OutputLock'):
        self.path = Path(path)
        self.lockPath = LockPath(self.path)
        self.where = where
        self._fd: Optional[int] = None
        self._fileFds: list = []

    def __enter__(self) -> 'OutputLock':
        try:
            import fcntl                                  # lazy: POSIX only
        except ImportError:                               # pragma: no cover - Windows
            fcntl = None
        for _ in range(10):                               # retried only if the lock file was replaced meanwhile
            try:
                fd = os.open(self.lockPath, os.O_RDWR | os.O_CREAT | os.O_NONBLOCK, 0o644)
            except OSError as err:
                raise OutputPathError(f"{self.where}: '{self.path}': cannot create its lock file "
                                      f"{self.lockPath.name}: {err.strerror or err}") from None
            try:
                if fcntl is not None:
                    _Flock(fcntl, fd)
            except OSError:
                holder = os.read(fd, 400).decode('utf-8', 'replace').strip() or 'another process'
                os.close(fd)
                raise OutputBusyError(f"{self.where}: '{self.path}' is being written by {holder}; wait for it to "
                                      f"end or choose another output") from None
            try:
                same = os.path.samestat(os.fstat(fd), os.stat(self.lockPath))
            except OSError:
                same = False
            if not same:                                  # the holder removed it as we opened it: take the new one
                os.close(fd)
                continue
            with contextlib.suppress(OSError):           # the holder's name is for messages: a full disk keeps the lock
                os.ftruncate(fd, 0)
                os.write(fd, f"process {os.getpid()} on host {socket.gethostname()} (since "
                             f"{time.strftime('%Y-%m-%dT%H:%M:%S%z')})\n".encode())
            self._fd = fd
            try:
                self.HoldFile()
            except BaseException:
                self.__exit__(None, None, None)
                raise
            return self
        raise OutputBusyError(f"{self.where}: '{self.path}': its lock file {self.lockPath.name} keeps changing")

    def HoldFile(self) -> None:
        """Lock the output file itself (its device and inode), if it exists: another name of it (a hard link, a
        symbolic link) is then refused too. Called on entering, and again after the output is created or replaced.

        Raises
        ------
        OutputBusyError
            If another process (or another lock of this one) holds the file under any name.
        """
        try:
            import fcntl                                  # lazy: POSIX only
        except ImportError:                               # pragma: no cover - Windows
            return
        try:                                              # for writing: NFS maps flock to a POSIX write lock
            fd = os.open(self.path, os.O_RDWR | os.O_NONBLOCK)
        except OSError:                                   # none yet (or not writable: then the writing fails later)
            return
        try:
            info = os.fstat(fd)
            if not stat.S_ISREG(info.st_mode) or any(os.path.samestat(info, os.fstat(held)) for held in self._fileFds):
                os.close(fd)                              # not a file, or held already
                return
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as err:
            os.close(fd)
            if not isinstance(err, BlockingIOError):      # a file system without locks: the name's lock remains
                return
            raise OutputBusyError(f"{self.where}: '{self.path}' is being written by another process under another "
                                  f"name (a hard or symbolic link to the same file); wait for it to end or choose "
                                  f"another output") from None
        self._fileFds.append(fd)

    def __exit__(self, *exc) -> None:
        for fd in self._fileFds:
            with contextlib.suppress(OSError):
                os.close(fd)
        self._fileFds = []
        if self._fd is not None:
            with contextlib.suppress(OSError):
                self.lockPath.unlink()                    # while still held, so that no one locks a removed file
            os.close(self._fd)
            self._fd = None


def _HolderGone(fd: int) -> bool:
    """Whether the process named in a lock file ran on this host and has ended (its pid no longer exists)."""
    text = os.pread(fd, 400, 0).decode('utf-8', 'replace')
    match = re.match(r'process (\d+) on host (\S+) ', text)
    if match is None or match.group(2) != socket.gethostname():
        return False
    try:
        os.kill(int(match.group(1)), 0)
    except ProcessLookupError:
        return True
    except OSError:                                       # alive under another user
        return False
    return False


def _Flock(fcntl, fd: int, grace: float = 5.0) -> None:
    """Take the lock; if its holder was killed, wait up to ``grace`` s for its dying workers to let it go.

    A study killed with ``kill -9`` ends before its forked workers do (they share the lock and die with it), so
    a study started at once on the same output would otherwise be refused for a fraction of a second.
    """
    deadline = time.monotonic() + grace
    while True:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            return
        except OSError:
            if time.monotonic() > deadline or not _HolderGone(fd):
                raise
            time.sleep(0.02)


class OutputPathError(ValueError):
    """An output path that cannot be written (:func:`CheckOutputPath`)."""


def CheckOutputPath(path, option: str, kind: str = 'file', overwrite: bool = False,
                    contents: Sequence[str] = ()) -> Path:
    """Check, before any computation, that an output named on the command line can be written.

    One rule for every subcommand: the output you name (a file, or a folder for ``kind='folder'``) is
    created; an existing file is refused unless ``--overwrite`` is given (``overwrite=True``); the folder
    that holds it must already exist. Nothing is created here.

    Parameters
    ----------
    path : str or os.PathLike
        The path given by the user.
    option : str
        The option that named it, for the message (e.g. ``'--csv'``).
    kind : {'file', 'folder'}
        What the path is to be.
    overwrite : bool, optional
        Allow replacing an existing file (for a folder: the files of ``contents`` in it).
    contents : sequence of str, optional
        For ``kind='folder'``: the names of the files that will be written into it (an existing folder is
        fine; these files in it are refused unless ``overwrite``).

    Returns
    -------
    pathlib.Path
        The path (unchanged).

    Raises
    ------
    OutputPathError
        A ValueError: if the path is empty, is a folder where a file is wanted or the other way round, is a device,
        FIFO or socket, exists without ``overwrite``, its parent is missing or not a folder, it is not writable, no
        file can be created in its folder (``/proc``, a read-only file system) or its name leaves no room for the
        temporary file beside it (ENAMETOOLONG).
    """
    if kind not in ('file', 'folder'):
        raise ValueError(f"CheckOutputPath: 'kind' must be 'file' or 'folder', got {kind!r}")
    text = os.fspath(path)
    p = Path(text)
    if not text.strip():
        raise OutputPathError(f"{option}: expected a {kind} name, got ''")
    state = _PathState(p, option, text)
    if state != 'missing':
        if state == 'special':                            # replaced by a rename, /dev/null would be lost
            raise OutputPathError(f"{option} {text}: is not a regular file (a device, FIFO or socket); give a "
                                  f"{kind} name")
        if kind == 'file' and state == 'folder':
            raise OutputPathError(f"{option} {text}: is a folder; give a file name (e.g. {Path(text) / 'out.csv'})"
                             if option == '--csv' else f"{option} {text}: is a folder; give a file name")
        if kind == 'folder' and state != 'folder':
            raise OutputPathError(f"{option} {text}: is a file, expected a folder (the figures are written into it)")
        if not os.access(p, os.W_OK) or (kind == 'folder' and not os.access(p, os.X_OK)):
            raise OutputPathError(f"{option} {text}: not writable (permission denied)")
        existing = [p] if kind == 'file' else [p / name for name in contents if (p / name).exists()]
        if existing and not overwrite:
            what = 'exists' if kind == 'file' else \
                f"holds {', '.join(e.name for e in existing[:3])}{' ...' if len(existing) > 3 else ''}"
            raise OutputPathError(f"{option} {text}: {what}; give --overwrite to replace "
                             f"{'it' if len(existing) == 1 else 'them'}, or choose another name")
        _CheckCreate(p if kind == 'folder' else p.parent, option, text)
        return p
    parent = p.parent
    state = _PathState(parent, option, text)
    if state == 'missing':
        raise OutputPathError(f"{option} {text}: the folder {parent} does not exist (create it first; "
                         f"exudyn-worm creates only the {kind} you name)")
    if state != 'folder':
        raise OutputPathError(f"{option} {text}: {parent} is not a folder")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise OutputPathError(f"{option} {text}: cannot write into the folder {parent} (permission denied)")
    _CheckName(p, option, text)
    _CheckCreate(parent, option, text)
    return p


def _PathState(p: Path, option: str, text: str) -> str:
    """'missing', 'folder', 'file' or 'special' (a device, FIFO, socket); a path behind a folder one may not search is refused, naming the folder."""
    try:
        return 'folder' if p.is_dir() else 'file' if p.is_file() else 'special' if p.exists() else 'missing'
    except PermissionError:
        blocked = next((q for q in reversed(p.absolute().parents) if not os.access(q, os.X_OK)), p.parent)
        raise OutputPathError(f"{option} {text}: cannot reach it: the folder {blocked} may not be searched "
                         f"(permission denied)") from None
    except OSError as err:                                # a name too long, a loop of symbolic links
        raise OutputPathError(f"{option} {text}: {err.strerror or err}") from None


#: bytes of a file name kept free for the temporary and lock files beside an output (``.<name>.<pid>.partial``)
_NAME_ROOM = 32


def _CheckName(p: Path, option: str, text: str) -> None:
    """Refuse a file name too long to leave room for the temporary file beside it."""
    try:
        limit = os.pathconf(p.parent if os.fspath(p.parent) else '.', 'PC_NAME_MAX')
    except (OSError, ValueError, AttributeError):
        limit = 255
    length = len(os.fsencode(p.name))
    if length > limit - _NAME_ROOM:
        raise OutputPathError(f"{option} {text}: the file name is {length} bytes long, above the limit of "
                              f"{limit - _NAME_ROOM} bytes (the file system allows {limit}; the temporary file "
                              f"written beside it needs the rest)")


def _CheckCreate(folder: Path, option: str, text: str) -> None:
    """Create and remove an empty hidden file in ``folder``: a folder that cannot hold a new file (``/proc``, a
    read-only file system) is refused before any computation."""
    probe = folder / f'.exudyn-worm-probe.{os.getpid()}'
    try:
        fd = os.open(probe, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
    except FileExistsError:
        return
    except OSError as err:
        raise OutputPathError(f"{option} {text}: cannot create a file in the folder {folder}: "
                              f"{err.strerror or err}") from None
    os.close(fd)
    with contextlib.suppress(OSError):
        os.unlink(probe)


