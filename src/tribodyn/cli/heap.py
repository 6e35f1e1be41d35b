"""The command's garbage collection: the objects a command keeps until its process ends
are left out of CPython's full collections (a policy of the command-line process, not of
the library).

A full collection (generation 2) walks every object the collector tracks. After its
imports (numpy, SciPy, numba, xarray, Bokeh) and the case, ``tribodyn run`` holds
≈ 280 000 of them; the paper case's run made five full collections, most of them
while the writing's modules were imported beside the study's workers (0.7–1.3 s of the
main process's time in three runs), and the interpreter's collections at exit took
0.35 s more. :func:`long_lived_heap` moves the objects that exist to the permanent
generation (:func:`gc.freeze`), which no collection walks and which forked workers
inherit; :func:`skip_collections_at_exit` does so at the process's exit, whose memory
the operating system frees. Objects made later are collected as before.
"""

from __future__ import annotations

import atexit
import gc
from collections.abc import Callable, Iterator
from contextlib import contextmanager

__all__ = ["long_lived_heap", "skip_collections_at_exit"]


@contextmanager
def long_lived_heap() -> Iterator[Callable[[], None]]:
    """Freeze the objects that exist now for the block; yields ``keep()``, which freezes
    those made since (e.g. modules imported in the block). On exit they are unfrozen, so
    that a caller in the same process (a test invoking the command) collects them again."""
    gc.freeze()
    try:
        yield gc.freeze
    finally:
        gc.unfreeze()


def skip_collections_at_exit() -> None:
    """Freeze the heap at the process's exit (before the interpreter's last collections);
    for the command's own process only: finalisers of objects in reference cycles then do
    not run, so every file is closed before (the writers close theirs)."""
    atexit.register(gc.freeze)
