"""The temporary folder a result folder is written in, and what is left of killed runs.

* :func:`make_work_folder` creates ``.NAME.tmp-PID-TOKEN`` next to the target, private
  (0o700) while it is written, with a proof of origin (:data:`~.result_folder.ORIGIN`:
  the tool, the PID and the token of its name); the folder it replaces is renamed to
  ``.NAME.old-PID-TOKEN`` (:func:`old_name`) and gets the same proof.
* :func:`_keep_foreign` brings the user's files of the target into it (hard links, else
  copies); the target's folders keep their group and mode (:func:`adopt_attributes`).
* A folder owned by someone else (this process not being root's) cannot be replaced
  without changing its owner: :func:`update_in_place` moves the new files into it.
* :func:`clean_stale` removes such folders of runs that were killed, and only those that
  carry their proof of origin: a folder of someone else's named alike is never touched.
"""

from __future__ import annotations

import json
import os
import re
import secrets
import shutil
import stat
from contextlib import suppress
from pathlib import Path

from .. import _json
from .._safe_write import TOKEN_CHARS, atomic_write, make_dirs, new_dir, remove_tree
from .._system import pid_alive
from .._typing import PathLike
from .._validation import InputError
from .result_folder import (
    MARKER,
    ORIGIN,
    _dirs,
    _iter_dir,
    _marker_info,
    _same_file_content,
    foreign_files,
    is_result_folder,
    mark_folder,
    own_files,
    regular_file_bytes,
)

__all__ = [
    "make_work_folder",
    "old_name",
    "prove_origin",
    "clean_stale",
    "folder_attributes",
    "adopt_attributes",
    "must_update_in_place",
    "update_in_place",
]


def make_work_folder(target: Path) -> tuple[Path, os.stat_result]:
    """Create the temporary folder ``.NAME.tmp-PID-TOKEN`` next to ``target`` with its
    proof of origin (:data:`ORIGIN`); it is private (0o700, the set-group-ID bit kept)
    while it is written. Returns it and its status as created (the mode the umask
    gives a new folder there)."""
    p = new_dir(target.parent, f".{target.name}.tmp-{os.getpid()}-")
    st = os.stat(p)
    os.chmod(p, 0o700 | (stat.S_IMODE(st.st_mode) & stat.S_ISGID))
    prove_origin(p)
    return p, st


def old_name(target: Path) -> Path:
    """A fresh name ``.NAME.old-PID-TOKEN`` for the folder ``target`` replaces."""
    return target.with_name(
        f".{target.name}.old-{os.getpid()}-{secrets.token_hex(TOKEN_CHARS // 2)}"
    )


def prove_origin(folder: Path, name: str | None = None) -> None:
    """Write :data:`ORIGIN` into ``folder``, named ``.NAME.KIND-PID-TOKEN`` (or to be
    renamed to ``name`` of that form)."""
    info = _origin(*(name or folder.name).rsplit(".", 1)[1].split("-"))
    atomic_write(folder / ORIGIN, _json.dumps(info) + "\n", fsync=False)


def _origin(kind: str, pid: str, token: str) -> dict:
    """The proof of origin of a folder ``.NAME.KIND-PID-TOKEN``."""
    return {"tool": "tribodyn", "kind": kind, "pid": int(pid), "token": token}


def _has_origin(folder: Path, kind: str, pid: str, token: str) -> bool:
    """True if ``folder`` holds tribodyn's proof of origin with this PID and token."""
    try:
        info = json.loads((regular_file_bytes(folder, ORIGIN, 4096) or b"").decode("utf-8"))
    except (OSError, ValueError):
        return False
    return info == _origin(kind, pid, token)


def clean_stale(target: PathLike) -> list[Path]:
    """Remove the ``.NAME.tmp-PID-TOKEN`` and ``.NAME.old-PID-TOKEN`` folders next to
    ``target`` left by runs that were killed (process gone), and only those that hold
    tribodyn's proof of origin (:data:`ORIGIN`, with that PID and token): a folder of
    someone else's with a name of that form is never touched. An ``.old`` folder with
    its proof (or one of an earlier version, ``.NAME.old-PID``, if it is a result folder)
    is moved back to ``target`` if the target is missing (the kill came between the two
    renames). Returns what was removed or restored."""
    target = Path(target).absolute()
    parent = target.parent
    if not parent.is_dir():
        return []
    done = []
    head = f".{target.name}."
    for p in _iter_dir(parent):
        if not p.name.startswith(head) or p.is_symlink() or not p.is_dir():
            continue
        m = re.fullmatch(rf"(tmp|old)-(\d+)(?:-([0-9a-f]{{{TOKEN_CHARS}}}))?", p.name[len(head) :])
        if not m:
            continue
        kind, pid, token = m.groups()
        if int(pid) == os.getpid() or pid_alive(int(pid)):
            continue
        proven = token is not None and _has_origin(p, kind, pid, token)
        legacy = token is None and is_result_folder(p)
        if kind == "old" and not os.path.lexists(target) and (proven or legacy):
            p.rename(target)
            (target / ORIGIN).unlink(missing_ok=True)
        elif proven:
            if kind == "old":
                _salvage(p, target)
            remove_tree(p, ignore_errors=True)
        else:
            continue
        done.append(p)
    return done


def _salvage(old: Path, target: Path) -> None:
    """Move the user's files found in the replaced folder ``old`` but not in ``target``
    into ``target`` (files added while the new results were being written)."""
    for rel in foreign_files(old):
        dst = target / rel.rstrip("/")
        if os.path.lexists(dst):
            continue
        make_dirs(dst.parent)
        if rel.endswith("/"):
            make_dirs(dst)
        else:
            os.rename(old / rel, dst)


def folder_attributes(folder: Path) -> os.stat_result | None:
    """The status of the folder ``folder`` (not through a link), or None."""
    try:
        st = os.lstat(folder)
    except OSError:
        return None
    return st if stat.S_ISDIR(st.st_mode) else None


def adopt_attributes(folder: Path, like: os.stat_result, mode: int | None = None) -> None:
    """Give ``folder`` the group (the owner too, where allowed: as root) and then the
    mode (set-group-ID bit included) of the folder whose status is ``like``, or ``mode``.
    A group or owner that cannot be set leaves the folder's own; the mode is set in any
    case, so it is never wider than the one asked for."""
    uid = like.st_uid if os.geteuid() == 0 else -1
    with suppress(OSError):
        os.chown(folder, uid, like.st_gid, follow_symlinks=False)
    os.chmod(folder, stat.S_IMODE(like.st_mode) if mode is None else mode)


def _clash(target: Path, rel: str) -> InputError:
    return InputError(
        f"{str(target)!r}: {rel} was not written by tribodyn (or changed since) and the "
        "new results have a file of that name; it was left as it is"
    )


def must_update_in_place(target: Path) -> bool:
    """True if the folder ``target`` cannot be replaced by a new folder without changing
    its owner: it belongs to someone else and this process is not root's."""
    like = folder_attributes(target)
    return like is not None and os.geteuid() not in (0, like.st_uid)


def update_in_place(target: Path, tmp: Path, files: dict[str, str], meta: dict) -> None:
    """Move tribodyn's new files ``files`` (relative path → SHA-256) from ``tmp`` into the
    folder ``target`` itself, replacing its own earlier files and removing those it no
    longer writes; the folder and the user's files and folders stay as they are (owner,
    group, mode). Not one rename: while the files move, the marker lists the earlier
    hashes too, so an interrupted update leaves every file recognisable. A user's file
    with the name of a new one raises first (one with the same content is kept)."""
    before = own_files(target) - {MARKER, ORIGIN}
    for rel in foreign_files(target):
        name = rel.rstrip("/")
        if rel.endswith("/"):  # an empty folder of the user's: in the way of a file only
            if name in files:
                raise _clash(target, rel)
        elif any(w.startswith(name + "/") for w in files):
            raise _clash(target, rel)
        elif name in files:
            if not _same_file_content(target / name, tmp / name):
                raise _clash(target, rel)
            files.pop(name)
    listed = _marker_info(target).get("files")
    previous = listed if isinstance(listed, dict) else {}
    mark_folder(target, files, {**meta, "previous": previous})
    for rel in sorted(files):
        make_dirs((target / rel).parent)
        os.replace(tmp / rel, target / rel)
    for rel in sorted(before - set(files), reverse=True):
        (target / rel).unlink(missing_ok=True)
        parent = (target / rel).parent
        while parent != target:
            try:
                parent.rmdir()  # a folder of tribodyn's files only, now empty
            except OSError:
                break
            parent = parent.parent
    mark_folder(target, files, meta)


def _keep_foreign(target: Path, tmp: Path, files: dict[str, str]) -> None:
    """Hard-link (else copy) the user's files of ``target`` into the new folder ``tmp``;
    a file tribodyn wrote with the same content as the user's gives way to the user's
    (and leaves ``files``, the list of tribodyn's own). Any other clash raises. Every
    folder of ``target`` that ``tmp`` has then gets its group and mode."""
    for rel in foreign_files(target):
        src, dst = target / rel.rstrip("/"), tmp / rel.rstrip("/")
        if rel.endswith("/"):
            make_dirs(dst, 0o700)
            continue
        if os.path.lexists(dst):
            if dst.is_dir() or not _same_file_content(src, dst):
                raise _clash(target, rel)
            dst.unlink()
            files.pop(rel, None)
        make_dirs(dst.parent, 0o700)
        try:
            os.link(src, dst, follow_symlinks=False)
        except OSError:  # no hard links here: a copy (the original stays until the swap)
            shutil.copy2(src, dst, follow_symlinks=False)
    for rel in reversed(_dirs(tmp)):
        like = folder_attributes(target / rel)
        if like is not None and (tmp / rel).is_dir() and not (tmp / rel).is_symlink():
            adopt_attributes(tmp / rel, like)
