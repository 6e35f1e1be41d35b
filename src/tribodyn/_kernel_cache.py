"""numba's on-disk cache of the compiled kernels, kept consistent across source files.

numba compiles a cached kernel afresh when the kernel's own file changes, but not when
a compiled function it calls from another file changes (a documented limitation of
``cache=True``). The kernels of ``physics``, ``contact`` and ``valvetrain`` call each
other across files, so :func:`refresh` keeps one stamp of those packages' sources
(path, size and modification time of every ``.py`` file) beside the cache, and removes
the package's cached kernels (``__pycache__/*.nbi``, ``*.nbc``) when the stamp differs:
after an edit every kernel compiles once more. A folder that cannot be written (an
installation owned by another user, where numba keeps its cache elsewhere) is left as
it is.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

__all__ = ["KERNEL_PACKAGES", "refresh", "source_stamp"]

#: sub-packages whose modules define compiled kernels or the functions they compile
KERNEL_PACKAGES = ("physics", "contact", "valvetrain")
_STAMP = Path("__pycache__") / "kernel-sources.stamp"


def source_stamp(root: Path) -> str:
    """SHA-256 over (relative path, size, mtime in ns) of the kernel packages' sources."""
    h = hashlib.sha256()
    for pkg in KERNEL_PACKAGES:
        for f in sorted((root / pkg).rglob("*.py")):
            st = f.stat()
            h.update(f"{f.relative_to(root)}\0{st.st_size}\0{st.st_mtime_ns}\n".encode())
    return h.hexdigest()


def refresh(root: Path = Path(__file__).parent) -> bool:
    """Remove the cached kernels under ``root`` if its kernel sources changed since the
    stamp was written (or no stamp exists), and write the new stamp; True if removed.
    Any file-system error leaves the cache as it is (numba then works as without)."""
    try:
        stamp = source_stamp(root)
        path = root / _STAMP
        if path.is_file() and path.read_text() == stamp:
            return False
        for f in root.rglob("__pycache__/*.nb[ic]"):
            f.unlink(missing_ok=True)
        path.parent.mkdir(exist_ok=True)
        tmp = path.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_text(stamp)
        tmp.replace(path)
        return True
    except OSError:
        return False
