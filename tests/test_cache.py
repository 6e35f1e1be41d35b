"""The on-disk cache of computed arrays (tribodyn._cache) and its use for synthetic
load–separation laws: the same bits as computed, the user's umask, corrupt files
harmless, switched off by an empty TRIBODYN_CACHE_DIR."""

from __future__ import annotations

import os
import stat

import numpy as np
import pytest

from tribodyn import _cache
from tribodyn.topography import load_separation as ls
from tribodyn.topography import synthetic

#: a small law (32² points): E' 2.2e11 Pa, H 7 GPa
ARGS = (0.3e-6, 0.85, 3.2e-6, 25.6e-6, 2.2e11, 7e9, 32, 1)


def _law():
    ls._synthetic_law.cache_clear()  # the per-process cache: only the disk remains
    return ls.synthetic_load_separation(*ARGS)


def _same(a, b) -> bool:
    return all(
        np.array_equal(getattr(a, k), getattr(b, k)) for k in ("lam", "pressure", "area")
    ) and (a.reduced_modulus, a.hardness, a.source) == (b.reduced_modulus, b.hardness, b.source)


def _files(folder):
    return sorted(p for p in folder.rglob("*") if p.is_file())


@pytest.fixture
def cache(tmp_path, monkeypatch):
    folder = tmp_path / "cache"
    monkeypatch.setenv(_cache.CACHE_ENV, str(folder))
    yield folder
    ls._synthetic_law.cache_clear()


def test_cached_law_is_the_computed_one_and_skips_the_surface(cache, monkeypatch):
    monkeypatch.setenv(_cache.CACHE_ENV, "")
    computed = _law()
    monkeypatch.setenv(_cache.CACHE_ENV, str(cache))
    first = _law()
    assert _same(first, computed)
    (f,) = _files(cache)
    assert f.suffix == ".npz"

    def no_surface(*a, **k):
        raise AssertionError("computed again")

    monkeypatch.setattr(synthetic, "synthetic_surface", no_surface)
    assert _same(_law(), computed)


def test_other_inputs_get_another_file(cache):
    _law()
    ls._synthetic_law.cache_clear()
    ls.synthetic_load_separation(*ARGS[:4], 2.1e11, *ARGS[5:])
    assert len(_files(cache)) == 2


def test_files_follow_the_umask(cache):
    old = os.umask(0o027)
    try:
        _law()
    finally:
        os.umask(old)
    (f,) = _files(cache)
    assert stat.S_IMODE(f.stat().st_mode) == 0o640
    assert stat.S_IMODE(f.parent.stat().st_mode) == 0o750


@pytest.mark.parametrize(
    "content",
    [b"", b"not a zip file", b"PK\x03\x04" + b"\0" * 40],
    ids=["empty", "text", "broken zip"],
)
def test_a_corrupt_file_is_computed_again(cache, content):
    good = _law()
    (f,) = _files(cache)
    f.write_bytes(content)
    assert _same(_law(), good)
    assert _files(cache) == [f] and f.stat().st_size > 100  # replaced


def test_foreign_arrays_are_computed_again(cache):
    good = _law()
    (f,) = _files(cache)
    np.savez(f, lam=np.array([1.0, 0.0, 2.0]), pressure=np.ones(3), area=np.ones(3))
    assert _same(_law(), good)
    np.savez(f, other=np.ones(3))
    assert _same(_law(), good)


def test_an_unwritable_cache_is_skipped(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("")
    monkeypatch.setenv(_cache.CACHE_ENV, str(blocker / "cache"))  # under a file
    law = _law()
    monkeypatch.setenv(_cache.CACHE_ENV, "")
    assert _same(law, _law())


def test_the_folder(monkeypatch, tmp_path):
    monkeypatch.setenv(_cache.CACHE_ENV, str(tmp_path))
    assert _cache.cache_dir() == tmp_path
    monkeypatch.setenv(_cache.CACHE_ENV, "")
    assert _cache.cache_dir() is None
    monkeypatch.delenv(_cache.CACHE_ENV)
    if os.name == "posix" and os.uname().sysname == "Linux":
        monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
        assert _cache.cache_dir() == tmp_path / "tribodyn"
        monkeypatch.setenv("XDG_CACHE_HOME", "relative")  # not absolute: ignored (XDG)
        assert _cache.cache_dir() == _cache.Path.home() / ".cache" / "tribodyn"


def test_warmup_laws_are_those_of_the_paper_case(cache):
    from tribodyn.config import load_case
    from tribodyn.workflow.engineering import typical_surface_laws

    laws = typical_surface_laws(load_case())
    assert len(laws) == 5  # every set of the paper case is Greenwood–Tripp
    assert len(_files(cache)) == len({(law.source, law.reduced_modulus) for law in laws})
