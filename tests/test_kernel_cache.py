"""The compiled kernels' cache is dropped when any kernel package's source changes
(numba alone would keep a kernel that calls a changed function of another file)."""

import os

from tribodyn import _kernel_cache as kc


def _tree(root):
    for pkg in kc.KERNEL_PACKAGES:
        (root / pkg / "__pycache__").mkdir(parents=True)
        (root / pkg / "law.py").write_text("x = 1\n")
    (root / "output").mkdir()
    (root / "output" / "page.py").write_text("y = 1\n")
    return root / "valvetrain" / "__pycache__" / "compiled._rhs-1.py311"


def _cache(entry):
    for suffix in (".nbi", ".1.nbc"):
        entry.with_name(entry.name + suffix).write_bytes(b"k")
    return sorted(p.name for p in entry.parent.iterdir())


def test_cache_is_dropped_when_another_kernel_file_changes(tmp_path):
    entry = _tree(tmp_path)
    _cache(entry)
    assert kc.refresh(tmp_path)  # no stamp yet: the cache's sources are unknown
    assert list(entry.parent.iterdir()) == []
    kept = _cache(entry)
    assert not kc.refresh(tmp_path)  # nothing changed
    assert sorted(p.name for p in entry.parent.iterdir()) == kept
    (tmp_path / "output" / "page.py").write_text("y = 2\n")  # not a kernel package
    assert not kc.refresh(tmp_path)
    law = tmp_path / "physics" / "law.py"  # a file the cached kernel does not live in
    law.write_text("x = 2\n")
    st = law.stat()
    os.utime(law, ns=(st.st_atime_ns, st.st_mtime_ns + 1_000_000))
    assert kc.refresh(tmp_path)
    assert list(entry.parent.iterdir()) == []


def test_file_system_errors_do_not_raise(tmp_path):
    """A stamp that cannot be written (here the folder's place is taken by a file) makes
    refresh return False instead of raising; the file is not replaced."""
    _tree(tmp_path)
    (tmp_path / "__pycache__").write_text("not a folder")
    assert not kc.refresh(tmp_path)
    assert (tmp_path / "__pycache__").read_text() == "not a folder"
