"""Writing files safely: the one way every file of tribodyn is written.

* A file is written to a temporary name that is fresh and random (``.NAME.XXXXXXXX.tmp``
  in the target's folder), created exclusively (``O_CREAT | O_EXCL | O_NOFOLLOW``): a
  file or a symbolic link planted under a predictable name is never opened, followed or
  overwritten. The data are flushed to the disk (``fsync``), then the temporary file is
  renamed onto the target in one step (:func:`os.replace`, which replaces a link at the
  target by the file and never writes through it); with ``replace=False`` an existing
  target is never replaced (:class:`FileExistsError`).
* Files get the permissions the user's umask gives (``0o666`` masked) and folders
  ``0o777`` masked, unlike :func:`tempfile.mkstemp`/``mkdtemp`` (0600/0700), which would
  leave results readable by their owner alone once renamed into place.
* :func:`remove_tree` and :func:`make_dirs` work without recursion (any depth of nesting)
  and never follow a link to a folder.

:func:`atomic_open` gives a file object; :func:`atomic_write` writes text or bytes;
:func:`atomic_write_with` hands the exclusively created temporary path to a writer that
needs a file name (netCDF, PNG); :func:`copy_file` copies a file.
"""

from __future__ import annotations

import contextlib
import os
import secrets
import shutil
import stat
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import IO, Any

__all__ = [
    "new_dir",
    "new_file",
    "atomic_open",
    "atomic_write",
    "atomic_write_with",
    "copy_file",
    "make_dirs",
    "remove_tree",
    "TOKEN_CHARS",
]

#: Random characters in a temporary name (hexadecimal).
TOKEN_CHARS = 8

_NOFOLLOW = getattr(os, "O_NOFOLLOW", 0)
_CLOEXEC = getattr(os, "O_CLOEXEC", 0)


def _token() -> str:
    return secrets.token_hex(TOKEN_CHARS // 2)


def new_dir(parent: Path, prefix: str) -> Path:
    """Create ``parent/PREFIX<random>`` (mode 0o777 minus the umask) and return it."""
    for _ in range(100):
        p = Path(parent) / f"{prefix}{_token()}"
        try:
            os.mkdir(p, 0o777)
        except FileExistsError:
            continue
        return p
    raise FileExistsError(f"no free name {prefix}… in {parent}")


def new_file(parent: Path, prefix: str, suffix: str = "") -> tuple[int, Path]:
    """Create ``parent/PREFIX<random>SUFFIX`` exclusively, never through a link (mode
    0o666 minus the umask); return its open descriptor (write-only) and path."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | _NOFOLLOW | _CLOEXEC
    for _ in range(100):
        p = Path(parent) / f"{prefix}{_token()}{suffix}"
        try:
            return os.open(p, flags, 0o666), p
        except FileExistsError:
            continue
    raise FileExistsError(f"no free name {prefix}…{suffix} in {parent}")


def _temporary(path: Path, keep_suffix: bool = False) -> tuple[int, Path]:
    """A fresh temporary file next to ``path``: ``.NAME.XXXXXXXX.tmp`` (with
    ``keep_suffix``, ``path``'s suffix follows, for writers that go by it)."""
    return new_file(path.parent, f".{path.name}.", ".tmp" + (path.suffix if keep_suffix else ""))


def _commit(tmp: Path, path: Path, replace: bool) -> None:
    """Rename ``tmp`` onto ``path``; without ``replace`` an existing ``path`` (a file,
    folder or link, even a dangling one) raises :class:`FileExistsError`."""
    if replace:
        os.replace(tmp, path)
        return
    try:
        os.link(tmp, path, follow_symlinks=False)  # fails on any existing name
    except FileExistsError:
        raise
    except OSError:  # no hard links on this file system
        if os.path.lexists(path):
            raise FileExistsError(f"{path} exists") from None
        os.rename(tmp, path)
    else:
        os.unlink(tmp)


@contextlib.contextmanager
def atomic_open(
    path: os.PathLike | str,
    mode: str = "w",
    *,
    newline: str | None = None,
    replace: bool = True,
    fsync: bool = True,
) -> Iterator[IO[Any]]:
    """A file object open for writing (``mode`` ``"w"``, UTF-8 text, or ``"wb"``) on a fresh
    temporary file next to ``path``, renamed onto ``path`` when the block ends without
    an exception (module docstring); on an exception the temporary file is removed and
    ``path`` is left as it was."""
    if mode not in ("w", "wb"):
        raise ValueError(f"mode must be 'w' or 'wb' (got {mode!r})")
    path = Path(path)
    fd, tmp = _temporary(path)
    try:
        f: IO[Any]
        if mode == "wb":
            f = os.fdopen(fd, "wb")
        else:
            f = os.fdopen(fd, "w", encoding="utf-8", newline=newline)
        with f:
            yield f
            f.flush()
            if fsync:
                os.fsync(f.fileno())
        _commit(tmp, path, replace)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def atomic_write(
    path: os.PathLike | str,
    data: str | bytes,
    *,
    replace: bool = True,
    fsync: bool = True,
) -> Path:
    """Write ``data`` (text as UTF-8, or bytes) to ``path`` (:func:`atomic_open`)."""
    mode = "wb" if isinstance(data, bytes) else "w"
    with atomic_open(path, mode, replace=replace, fsync=fsync) as f:
        f.write(data)
    return Path(path)


def atomic_write_with(
    path: os.PathLike | str,
    write: Callable[[Path], object],
    *,
    keep_suffix: bool = False,
) -> Path:
    """Call ``write(tmp)`` on the path of a fresh, exclusively created (empty) temporary
    file next to ``path`` (for writers that want a file name: netCDF, PNG), then rename it
    onto ``path`` (module docstring). With ``keep_suffix`` the temporary name ends with
    ``path``'s suffix (for writers that choose the format by it). ``write`` must not
    remove or replace ``tmp``."""
    path = Path(path)
    fd, tmp = _temporary(path, keep_suffix)
    os.close(fd)
    try:
        write(tmp)
        fd = os.open(tmp, os.O_RDONLY | _NOFOLLOW | _CLOEXEC)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)
        _commit(tmp, path, replace=True)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    return path


def copy_file(src: os.PathLike | str, dst: os.PathLike | str) -> Path:
    """Copy the content of ``src`` to ``dst`` (:func:`atomic_open`; the mode follows the
    umask)."""
    with open(src, "rb") as s, atomic_open(dst, "wb") as d:
        shutil.copyfileobj(s, d, 1 << 20)
    return Path(dst)


def make_dirs(path: os.PathLike | str, mode: int = 0o777) -> Path:
    """Create ``path`` and its missing parents (``mode`` minus the umask), without
    recursion; an existing folder is fine, a file or link in the way raises."""
    path = Path(path)
    missing = []
    p = path
    while not os.path.lexists(p):
        missing.append(p)
        if p.parent == p:
            break
        p = p.parent
    for q in reversed(missing):
        try:
            os.mkdir(q, mode)
        except FileExistsError:
            if not q.is_dir() or q.is_symlink():
                raise
    if not path.is_dir() or path.is_symlink():
        raise NotADirectoryError(f"{path} is not a folder")
    return path


def remove_tree(path: os.PathLike | str, *, ignore_errors: bool = False) -> None:
    """Remove the folder ``path`` and everything below it, without recursion (any depth)
    and without following links (a link is removed, not what it points to)."""
    root = Path(path)
    try:
        if not stat.S_ISDIR(os.lstat(root).st_mode):
            raise NotADirectoryError(f"{root} is not a folder")
        stack = [root]
        done: list[Path] = []
        while stack:
            d = stack.pop()
            done.append(d)
            with os.scandir(d) as it:
                for e in it:
                    if e.is_dir(follow_symlinks=False):
                        stack.append(Path(e.path))
                    else:
                        os.unlink(e.path)
        for d in reversed(done):  # children before their parents
            os.rmdir(d)
    except OSError:
        if not ignore_errors:
            raise
