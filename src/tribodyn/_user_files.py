"""Reading the user's files: case and sweep TOML, cam lift tables, calibration data and
the marker of a result folder all come through :func:`read_user_bytes` and
:func:`decode_user_text`.

**Which files.** Only regular files (or links to them) are read. A named pipe (FIFO), a
device (``/dev/zero``, a terminal), a socket or a folder is refused by its ``stat``
before it is opened, and the file is opened without blocking (``O_NONBLOCK``) and checked
again on the open descriptor (``fstat``), so that a file replaced by a pipe in between
cannot make the read wait forever. A name containing a NUL character is refused (no file
system allows one).

**How much.** At most ``limit`` bytes are read (:data:`MAX_TABLE_BYTES` for tables,
:data:`MAX_MARKER_BYTES` for the marker of a result folder; the case files have their
own limit): a larger file, or one that grows while it is read, is refused without reading
the rest.

**Which encoding** (``legacy=True``, tables):

1. a byte-order mark decides: UTF-8 (the mark is removed; Excel's "CSV UTF-8"), UTF-16 or
   UTF-32 (little- or big-endian; Excel's "Unicode text");
2. without a mark, a NUL byte marks a binary file (or UTF-16 saved without a mark): refused,
   naming the byte offset;
3. else UTF-8 if the bytes are valid UTF-8;
4. else Windows-1252 (the Western-European code page of Windows, a superset of
   ISO 8859-1's printable characters), or ISO 8859-1 (latin-1) where a byte is not defined
   in Windows-1252. This fallback is reported in :attr:`UserText.note`, with the offset of
   the first byte that is not UTF-8. Numbers are ASCII in all of these, so only header
   text (°, µ) depends on the guess.

With ``legacy=False`` (TOML, which is UTF-8 by its specification) only step 1's UTF-8 mark
and step 3 apply; anything else is refused naming the first byte that is not UTF-8.

Every refusal is an :class:`~tribodyn.InputError` that starts with ``what`` (the user's
name for the file: ``"lift table"``, ``"DATA"``, ``"case file"``) and the file's name.
"""

from __future__ import annotations

import os
import stat
from dataclasses import dataclass

from ._typing import PathLike
from ._validation import InputError

__all__ = [
    "MAX_TABLE_BYTES",
    "MAX_MARKER_BYTES",
    "UserText",
    "check_regular_file",
    "read_user_bytes",
    "decode_user_text",
    "read_user_text",
]

#: Largest table file (cam lift table, calibration data) [bytes]: a million rows
#: (``LIFT_TABLE_ROWS``) of a few columns.
MAX_TABLE_BYTES = 64_000_000
#: Largest marker of a result folder [bytes] (JSON: a few lines per file of the folder).
MAX_MARKER_BYTES = 4_000_000

_BOMS = (  # longest first: the UTF-32-LE mark begins with the UTF-16-LE one
    (b"\xff\xfe\x00\x00", "utf-32-le", "UTF-32"),
    (b"\x00\x00\xfe\xff", "utf-32-be", "UTF-32"),
    (b"\xef\xbb\xbf", "utf-8", "UTF-8"),
    (b"\xff\xfe", "utf-16-le", "UTF-16"),
    (b"\xfe\xff", "utf-16-be", "UTF-16"),
)

_KINDS = (
    (stat.S_ISDIR, "a folder"),
    (stat.S_ISFIFO, "a named pipe (FIFO)"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISSOCK, "a socket"),
)


@dataclass(frozen=True)
class UserText:
    """Text of a user's file: the text (byte-order mark removed), the encoding it was
    read with and a note when that encoding was a guess (else None)."""

    text: str
    encoding: str
    note: str | None = None


def _shown(path: PathLike) -> str:
    return repr(os.fspath(path))


def _kind(mode: int) -> str:
    return next((name for test, name in _KINDS if test(mode)), "not a regular file")


def _size(n: int) -> str:
    return f"{n / 1e6:g} MB" if n >= 1_000_000 else f"{n} bytes"


def _cannot(what: str, shown: str, exc: OSError) -> InputError:
    why = "no such file" if isinstance(exc, FileNotFoundError) else (exc.strerror or str(exc))
    return InputError(f"cannot read {what} {shown}: {why}")


def check_regular_file(path: PathLike, what: str) -> os.stat_result:
    """The ``stat`` of ``path`` if it names a regular file (or a link to one), else
    :class:`~tribodyn.InputError` starting with ``what`` and the file's name: a NUL in
    the name, a missing file, a pipe, device, socket or folder. Opens nothing."""
    shown = _shown(path)
    if "\x00" in os.fspath(path):
        raise InputError(
            f"{what} {shown}: the file name contains a NUL character, which no file name can"
        )
    try:
        st = os.stat(path)
    except OSError as exc:
        raise _cannot(what, shown, exc) from None
    if not stat.S_ISREG(st.st_mode):
        raise InputError(f"{what} {shown} is {_kind(st.st_mode)}, not a regular file")
    return st


def read_user_bytes(path: PathLike, what: str, *, limit: int, hint: str = "") -> bytes:
    """The bytes of the regular file ``path`` (at most ``limit``), or
    :class:`~tribodyn.InputError` starting with ``what`` and the file's name (module
    docstring); ``hint`` is added to the message of a file that is too large."""
    shown = _shown(path)
    st = check_regular_file(path, what)
    too_big = f"{what} {shown} is larger than {_size(limit)}" + (f"; {hint}" if hint else "")
    if st.st_size > limit:
        raise InputError(too_big)
    flags = (
        os.O_RDONLY
        | getattr(os, "O_NONBLOCK", 0)
        | getattr(os, "O_NOCTTY", 0)
        | getattr(os, "O_CLOEXEC", 0)
        | getattr(os, "O_BINARY", 0)
    )
    try:
        fd = os.open(path, flags)
    except OSError as exc:
        raise _cannot(what, shown, exc) from None
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):  # replaced since the stat above
            raise InputError(f"{what} {shown} is {_kind(mode)}, not a regular file")
        chunks: list[bytes] = []
        size = 0
        while size <= limit:  # files of /proc report size 0: the count bounds the read
            block = os.read(fd, min(1 << 20, limit + 1 - size))
            if not block:
                break
            chunks.append(block)
            size += len(block)
    except OSError as exc:
        raise _cannot(what, shown, exc) from None
    finally:
        os.close(fd)
    if size > limit:
        raise InputError(too_big)
    return b"".join(chunks)


def decode_user_text(raw: bytes, what: str, path: PathLike, *, legacy: bool = True) -> UserText:
    """Decode the bytes of a user's file by the policy of the module docstring
    (``legacy=False``: UTF-8 only); ``what`` and ``path`` name the file in messages."""
    shown = _shown(path)
    for bom, codec, name in _BOMS:
        if raw.startswith(bom) and (legacy or codec == "utf-8"):
            try:
                return UserText(raw[len(bom) :].decode(codec), name)
            except UnicodeDecodeError as exc:
                raise InputError(
                    f"{what} {shown} starts with a {name} byte-order mark but is not "
                    f"{name} text (byte {exc.start + len(bom)}: {exc.reason}); save it "
                    "again as UTF-8"
                ) from None
    nul = raw.find(b"\x00")
    if legacy and nul >= 0:
        raise InputError(
            f"{what} {shown} has a NUL byte at byte {nul} and no UTF-16 byte-order mark: "
            "a binary file, not text; export it as CSV text (UTF-8)"
        )
    try:
        return UserText(raw.decode("utf-8"), "UTF-8")
    except UnicodeDecodeError as exc:
        bad = exc
    if not legacy:
        raise InputError(
            f"{what} {shown} is not UTF-8 text (byte {bad.start}: {bad.reason}); save it as UTF-8"
        )
    found = f"byte {bad.start} (0x{raw[bad.start]:02x}) is not UTF-8"
    try:
        text, name = raw.decode("cp1252"), "Windows-1252"
    except UnicodeDecodeError:
        text, name = raw.decode("latin-1"), "ISO 8859-1 (latin-1)"
    return UserText(text, name, f"{what} {shown}: {found}; read as {name}")


def read_user_text(
    path: PathLike, what: str, *, limit: int, legacy: bool = True, hint: str = ""
) -> UserText:
    """:func:`read_user_bytes` then :func:`decode_user_text`."""
    raw = read_user_bytes(path, what, limit=limit, hint=hint)
    return decode_user_text(raw, what, path, legacy=legacy)
