"""A small on-disk cache of computed arrays, in the user's cache folder.

Some results are deterministic functions of a few numbers and of tribodyn's code, yet
take seconds to compute (the load–separation law of a synthetic surface: its heights
come from SurfaceTopography's Fourier synthesis, whose import alone takes a second). They
are kept as ``.npz`` files named by a SHA-256 of:

* their inputs, as given by the caller (exact ``repr`` of the floats), and
* the code that computes them: the caller names its modules, whose source text is
  hashed, plus the versions of tribodyn and of the distributions it names (e.g. numpy,
  whose random generator draws the heights). Any change of either gives a new name.

Where: ``TRIBODYN_CACHE_DIR`` if set (empty: no cache), else ``$XDG_CACHE_HOME/tribodyn``
(``~/.cache/tribodyn`` without it; ``%LOCALAPPDATA%\\tribodyn\\cache`` on Windows,
``~/Library/Caches/tribodyn`` on macOS). Nothing is ever written into a result folder.

Safety: files and folders are created with the user's umask
(:mod:`tribodyn._safe_write`: a fresh temporary file renamed into place, so readers
never see half a file); arrays are read without pickles. A file that cannot be read or
does not hold the arrays the caller expects (corrupt, truncated, foreign) counts as
missing: the value is computed again and the file replaced. A cache that cannot be
written (read-only home, full disk) is skipped silently; the value is still returned.
"""

from __future__ import annotations

import hashlib
import importlib.util
import io
import os
import sys
from collections.abc import Callable, Sequence
from functools import lru_cache
from importlib import metadata
from pathlib import Path
from typing import Any

import numpy as np

from ._version import __version__

__all__ = ["CACHE_ENV", "cache_dir", "cached_arrays"]

#: Environment variable naming the cache folder (empty: no on-disk cache).
CACHE_ENV = "TRIBODYN_CACHE_DIR"


def cache_dir() -> Path | None:
    """The cache folder (module docstring), or None when the cache is switched off."""
    given = os.environ.get(CACHE_ENV)
    if given is not None:
        return Path(given).expanduser() if given else None
    if sys.platform == "win32":
        base = os.environ.get("LOCALAPPDATA")
        return Path(base) / "tribodyn" / "cache" if base else None
    if sys.platform == "darwin":
        return Path.home() / "Library" / "Caches" / "tribodyn"
    xdg = os.environ.get("XDG_CACHE_HOME")
    return (Path(xdg) if xdg and os.path.isabs(xdg) else Path.home() / ".cache") / "tribodyn"


@lru_cache(maxsize=16)
def _code_fingerprint(modules: tuple[str, ...], distributions: tuple[str, ...]) -> str:
    """SHA-256 of the source of ``modules`` and the versions of tribodyn and of
    ``distributions`` (read without importing anything)."""
    h = hashlib.sha256(f"tribodyn {__version__}".encode())
    for name in modules:
        spec = importlib.util.find_spec(name)
        origin = spec.origin if spec is not None else None
        h.update(f"\0{name}\0".encode())
        h.update(Path(origin).read_bytes() if origin else b"?")
    for dist in distributions:
        try:
            version = metadata.version(dist)
        except metadata.PackageNotFoundError:
            version = "?"
        h.update(f"\0{dist} {version}".encode())
    return h.hexdigest()


def _key(kind: str, inputs: Sequence, modules, distributions) -> str:
    text = "\0".join(repr(x) for x in (kind, *inputs))
    code = _code_fingerprint(tuple(modules), tuple(distributions))
    return hashlib.sha256(f"{text}\0{code}".encode()).hexdigest()


def _read(path: Path, names: Sequence[str], check) -> dict[str, np.ndarray] | None:
    """The arrays ``names`` of the ``.npz`` file ``path`` if ``check`` accepts them;
    None if it is missing, not such a file, or refused."""
    try:
        with np.load(path, allow_pickle=False) as f:
            if sorted(f.files) != sorted(names):
                return None
            arrays = {n: np.array(f[n]) for n in names}
        return arrays if check(arrays) else None
    except Exception:  # missing, unreadable, truncated, not an npz file, refused
        return None


def _write(path: Path, arrays: dict[str, np.ndarray]) -> None:
    """Store ``arrays`` at ``path`` (atomically; errors ignored: the cache is optional)."""
    from ._safe_write import atomic_write, make_dirs

    buf = io.BytesIO()
    named: dict[str, Any] = dict(arrays)
    np.savez(buf, **named)
    try:
        make_dirs(path.parent)
        atomic_write(path, buf.getvalue(), fsync=False)
    except OSError:
        pass


def cached_arrays(
    kind: str,
    inputs: Sequence,
    names: Sequence[str],
    compute: Callable[[], dict[str, np.ndarray]],
    *,
    modules: Sequence[str],
    distributions: Sequence[str] = (),
    check: Callable[[dict[str, np.ndarray]], bool] = lambda arrays: True,
) -> dict[str, np.ndarray]:
    """``compute()``, a dict of the arrays ``names``, or the arrays it returned before
    for the same ``kind``, ``inputs`` (numbers and strings, part of the file name by
    their ``repr``) and code (the source of ``modules`` and the versions of
    ``distributions``): module docstring. Stored arrays that ``check`` refuses (or that
    make it raise) count as missing. The result is the same either way (``.npz`` keeps
    every bit of the arrays)."""
    folder = cache_dir()
    if folder is None:
        return compute()
    path = folder / kind / f"{_key(kind, inputs, modules, distributions)}.npz"
    arrays = _read(path, names, check)
    if arrays is None:
        arrays = compute()
        _write(path, arrays)
    return arrays
