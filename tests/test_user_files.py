"""Reading the user's files (tribodyn._user_files): only regular files, bounded, one
decoding policy; and the files read through it (case, lift table, result-folder marker).

Encodings are written here with Python's own codecs (the reference), never by the reader.
"""

from __future__ import annotations

import json
import os
import stat
import sys
from pathlib import Path

import pytest

from tribodyn import InputError
from tribodyn._user_files import (
    MAX_MARKER_BYTES,
    decode_user_text,
    read_user_bytes,
    read_user_text,
)

posix_only = pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs named pipes")


def _fifo(tmp_path: Path, name: str) -> Path:
    p = tmp_path / name
    os.mkfifo(p)
    return p


# ----------------------------------------------------------------------------- which files
@posix_only
@pytest.mark.timeout(20)
def test_a_named_pipe_is_refused_without_waiting_for_a_writer(tmp_path):
    p = _fifo(tmp_path, "data.csv")
    with pytest.raises(InputError, match=r"DATA '.*data\.csv' is a named pipe \(FIFO\)"):
        read_user_bytes(p, "DATA", limit=1000)


@pytest.mark.skipif(not Path("/dev/zero").exists(), reason="needs /dev/zero")
def test_a_device_is_refused_before_reading():
    with pytest.raises(InputError, match="'/dev/zero' is a character device"):
        read_user_bytes("/dev/zero", "lift table", limit=1000)


def test_a_folder_and_a_missing_file_are_refused(tmp_path):
    with pytest.raises(InputError, match="is a folder, not a regular file"):
        read_user_bytes(tmp_path, "DATA", limit=1000)
    with pytest.raises(InputError, match="cannot read DATA .*missing.csv"):
        read_user_bytes(tmp_path / "missing.csv", "DATA", limit=1000)


def test_a_nul_in_the_name_is_refused_naming_the_file():
    with pytest.raises(
        InputError, match="lift table 'a\\\\x00b.csv': the file name contains a NUL"
    ):
        read_user_bytes("a\x00b.csv", "lift table", limit=1000)


def test_size_limit(tmp_path):
    p = tmp_path / "big.csv"
    p.write_bytes(b"1,2\n" * 100)  # 400 bytes
    assert len(read_user_bytes(p, "DATA", limit=400)) == 400
    with pytest.raises(InputError, match="is larger than 399 bytes; split it"):
        read_user_bytes(p, "DATA", limit=399, hint="split it")


@pytest.mark.skipif(not Path("/proc/self/status").is_file(), reason="needs /proc")
def test_a_file_that_reports_size_zero_is_still_bounded():
    """Files of /proc report st_size 0 but have content: the read itself is bounded."""
    assert os.stat("/proc/self/status").st_size == 0
    with pytest.raises(InputError, match="larger than"):
        read_user_bytes("/proc/self/status", "DATA", limit=10)


@posix_only
@pytest.mark.timeout(20)
def test_a_file_replaced_by_a_pipe_after_the_stat_is_refused(tmp_path, monkeypatch):
    """The race: stat saw a regular file, the name is a pipe when opened. The open does
    not block (O_NONBLOCK) and fstat on the descriptor refuses it."""
    import tribodyn._user_files as uf

    regular = tmp_path / "regular.csv"
    regular.write_text("1,2\n")
    fifo = _fifo(tmp_path, "swapped.csv")
    real_stat = os.stat
    monkeypatch.setattr(
        uf.os, "stat", lambda p, *a, **k: real_stat(regular if p == fifo else p, *a, **k)
    )
    with pytest.raises(InputError, match="is a named pipe"):
        read_user_bytes(fifo, "DATA", limit=1000)
    assert stat.S_ISFIFO(real_stat(fifo).st_mode)


# ----------------------------------------------------------------------------- encodings
TEXT = "angle [°];lift [µm]\n0,5;12,5\n"


@pytest.mark.parametrize(
    "raw, encoding",
    [
        (TEXT.encode("utf-8"), "UTF-8"),
        (b"\xef\xbb\xbf" + TEXT.encode("utf-8"), "UTF-8"),  # Excel "CSV UTF-8"
        (TEXT.encode("utf-16"), "UTF-16"),  # with BOM, native order
        (b"\xfe\xff" + TEXT.encode("utf-16-be"), "UTF-16"),
        (b"\xff\xfe" + TEXT.encode("utf-16-le"), "UTF-16"),
        (TEXT.encode("utf-32"), "UTF-32"),
    ],
    ids=["utf8", "utf8-bom", "utf16", "utf16-be", "utf16-le", "utf32"],
)
def test_unicode_files_by_their_byte_order_mark(raw, encoding):
    got = decode_user_text(raw, "DATA", "x.csv")
    assert got.text == TEXT  # the mark removed
    assert got.encoding == encoding and got.note is None


def test_legacy_code_page_is_read_with_a_note_naming_the_byte():
    raw = TEXT.encode("cp1252")
    offset = raw.index("°".encode("cp1252"))
    got = decode_user_text(raw, "DATA", "x.csv")
    assert got.text == TEXT and got.encoding == "Windows-1252"
    assert f"byte {offset} (0xb0) is not UTF-8" in got.note and "Windows-1252" in got.note
    # 0x81 is not defined in Windows-1252: ISO 8859-1
    got = decode_user_text(b"a\x81b\n", "DATA", "x.csv")
    assert got.text == "a\x81b\n" and "latin-1" in got.encoding


def test_binary_and_broken_unicode_name_the_byte():
    with pytest.raises(InputError, match="NUL byte at byte 3 .*binary"):
        decode_user_text(b"abc\x00def", "DATA", "x.csv")
    with pytest.raises(InputError, match="UTF-16 byte-order mark but is not UTF-16 text"):
        decode_user_text(b"\xff\xfe" + "ab".encode("utf-16-le") + b"\x00\xd8", "DATA", "x.csv")


def test_utf8_only_for_toml():
    raw = "# Motoröl\n".encode("latin-1")
    with pytest.raises(InputError, match=r"case file 'c.toml' is not UTF-8 text \(byte 7"):
        decode_user_text(raw, "case file", "c.toml", legacy=False)
    assert decode_user_text(b"\xef\xbb\xbfa = 1\n", "case file", "c", legacy=False).text == (
        "a = 1\n"
    )


def test_read_user_text_reads_a_file(tmp_path):
    p = tmp_path / "t.csv"
    p.write_bytes(TEXT.encode("utf-16"))
    assert read_user_text(p, "DATA", limit=1000).text == TEXT


# ----------------------------------------------------------------------------- its users
CAM = "[cam]\ntype = 'table'\npath = '{}'\n"


def _cam_error(tmp_path, name) -> str:
    from tribodyn.config import Case

    with pytest.raises(InputError) as ei:
        Case.from_toml_string(CAM.format(name), base_dir=tmp_path)
    return str(ei.value)


@posix_only
@pytest.mark.timeout(20)
def test_cam_table_that_is_a_pipe_is_a_cam_path_error(tmp_path):
    _fifo(tmp_path, "lift.csv")
    msg = _cam_error(tmp_path, "lift.csv")
    assert "cam.path" in msg and "named pipe" in msg


@pytest.mark.skipif(not Path("/dev/zero").exists(), reason="needs /dev/zero")
@pytest.mark.timeout(20)
def test_cam_table_that_is_a_device_is_a_cam_path_error(tmp_path):
    msg = _cam_error(tmp_path, "/dev/zero")
    assert "cam.path" in msg and "character device" in msg


def test_nul_in_the_cam_path_is_filed_under_cam_path(tmp_path):
    from tribodyn.config import Case

    with pytest.raises(InputError) as ei:
        Case.from_dict({"cam": {"type": "table", "path": "lift\x00.csv"}}, base_dir=tmp_path)
    msg = str(ei.value)
    assert "cam.path" in msg and "NUL" in msg and "(top level)" not in msg


@posix_only
@pytest.mark.timeout(20)
def test_case_file_that_is_a_pipe_is_refused(tmp_path):
    from tribodyn.config import load_case

    with pytest.raises(InputError, match="case file .* is a named pipe"):
        load_case(_fifo(tmp_path, "case.toml"))


@posix_only
@pytest.mark.timeout(20)
def test_result_folder_marker_that_is_a_pipe_or_too_large_is_not_read(tmp_path):
    from tribodyn.output.result_folder import MARKER, _marker_info

    _fifo(tmp_path, MARKER)
    assert _marker_info(tmp_path) == {}
    big = tmp_path / "big"
    big.mkdir()
    pad = "x" * MAX_MARKER_BYTES
    (big / MARKER).write_text(json.dumps({"tool": "tribodyn", "pad": pad}))
    assert _marker_info(big) == {}
    ok = tmp_path / "ok"
    ok.mkdir()
    (ok / MARKER).write_text(json.dumps({"tool": "tribodyn", "files": {}}))
    assert _marker_info(ok) == {"tool": "tribodyn", "files": {}}


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX link")
@pytest.mark.timeout(20)
def test_marker_linked_to_a_device_is_not_read(tmp_path):
    from tribodyn.output.result_folder import MARKER, _marker_info

    if not Path("/dev/zero").exists():
        pytest.skip("needs /dev/zero")
    (tmp_path / MARKER).symlink_to("/dev/zero")
    assert _marker_info(tmp_path) == {}


@pytest.mark.timeout(20)
@pytest.mark.parametrize("kind", ["nul", "pipe", "device"])
def test_measured_map_that_is_not_a_file_is_filed_under_its_key(tmp_path, kind):
    """Before, a NUL in measured_surface.topography gave '(top level): embedded null byte'
    and a pipe or device 'no such file'."""
    import tomllib

    from tribodyn.config import Case
    from tribodyn.config.case import bundled_cases

    if kind == "pipe":
        if not hasattr(os, "mkfifo"):
            pytest.skip("needs named pipes")
        name, says = str(_fifo(tmp_path, "map.x3p")), "named pipe"
    elif kind == "device":
        if not Path("/dev/zero").exists():
            pytest.skip("needs /dev/zero")
        name, says = "/dev/zero", "character device"
    else:
        name, says = "map\x00.x3p", "NUL character"
    d = tomllib.loads(bundled_cases()["flat_tappet_rig_measured"].read_text(encoding="utf-8"))
    d["surface_sets"] = d["surface_sets"][:1]
    d["surface_sets"][0]["measured_surface"] = {"topography": name, "hardness": 7e9}
    with pytest.raises(InputError) as ei:
        Case.from_dict(d, base_dir=tmp_path)
    msg = str(ei.value)
    assert "surface_sets[0].measured_surface.topography: topography file" in msg, msg
    assert says in msg and "(top level)" not in msg
