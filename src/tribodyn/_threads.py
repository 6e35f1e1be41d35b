"""The BLAS/OpenMP thread policy: one thread for the solvers.

The solvers' dense matrices are small (a few hundred nodes); multi-threaded BLAS costs
several times the single-threaded time on them (docs/architecture.md, "BLAS threads":
a steady EHL solve takes 0.03 s with one thread, 0.16 s median with two on two cores).
A runtime limit (threadpoolctl) measured as fast as the environment variable, so:

* the command line sets the environment variables before numpy loads
  (:func:`set_blas_env`, called by :mod:`tribodyn.cli`; ``tribodyn`` itself imports
  nothing until a name is used), which child processes inherit;
* a local process pool starts its fresh interpreters with them
  (:func:`single_blas_thread_env`);
* the workflow's entry points and every task run under a runtime limit
  (:func:`single_blas_thread`), which also covers Dask workers;
* the public solvers (``solve_ehl``, ``solve_dry_contact``, ``solve_thermal_ehl``, the
  transient stepper's calls) carry the same limit themselves (:func:`one_blas_thread`),
  so a Python caller who set nothing gets the one-thread speed; the limit is lifted when
  the call returns, so the caller's own BLAS work keeps its threads. Entering and leaving
  it costs about 0.1 ms (``benchmarks/bench_blas_threads.py``).

A variable the user set is never changed.
"""

from __future__ import annotations

import functools
import os
import threading
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any, ParamSpec, TypeVar

__all__ = [
    "BLAS_ENV",
    "blas_single_threaded",
    "one_blas_thread",
    "set_blas_env",
    "single_blas_thread",
    "single_blas_thread_env",
]

#: The thread-count variables of OpenBLAS, OpenMP and MKL.
BLAS_ENV = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")

# The limit is process-wide, so it is one limiter shared by all threads: applied when the
# first single_blas_thread() is entered, restored when the last one (in any thread) leaves.
_lock = threading.Lock()
_depth = 0  # single_blas_thread() blocks open in this process (all threads)
_limiter: Any = None  # the shared threadpoolctl limiter while _depth > 0


def set_blas_env() -> None:
    """One BLAS thread for this process and its children, unless the environment says
    otherwise; effective only before numpy is imported."""
    for var in BLAS_ENV:
        os.environ.setdefault(var, "1")


@contextmanager
def single_blas_thread_env() -> Iterator[None]:
    """Set the variables to one thread for the processes started inside (restored
    after; a value the user set is kept)."""
    saved = {k: os.environ.get(k) for k in BLAS_ENV}
    set_blas_env()
    try:
        yield
    finally:
        for k, v in saved.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v


@contextmanager
def single_blas_thread() -> Iterator[None]:
    """Limit BLAS/OpenMP to one thread in this process while inside (threadpoolctl).

    Thread-safe and nestable: a lock-protected count of open blocks (in any thread); the
    first applies the limit, the last to leave restores the original thread counts.
    """
    global _depth, _limiter
    with _lock:
        if _depth == 0:
            from threadpoolctl import threadpool_limits

            _release_openblas_control()
            _limiter = threadpool_limits(limits=1)
            _release_openblas_control()
        _depth += 1
    try:
        yield
    finally:
        with _lock:
            _depth -= 1
            if _depth == 0:
                limiter, _limiter = _limiter, None
                _release_openblas_control()
                limiter.restore_original_limits()
                _release_openblas_control()


_P = ParamSpec("_P")
_R = TypeVar("_R")


def one_blas_thread(func: Callable[_P, _R]) -> Callable[_P, _R]:
    """Run ``func`` under :func:`single_blas_thread` (a decorator for the public solvers)."""

    @functools.wraps(func)
    def wrapper(*args: _P.args, **kwargs: _P.kwargs) -> _R:
        with single_blas_thread():
            return func(*args, **kwargs)

    return wrapper


def _release_openblas_control() -> None:
    """Let the calling thread set OpenBLAS's process-wide thread count.

    threadpoolctl >= 3.8 lets only the first thread that set it change it while that
    thread lives (later calls from other threads are ignored); the shared limiter is
    applied and restored by whichever thread opens the first and closes the last block,
    under the lock, so the hold is released around each change.
    """
    import threadpoolctl

    controller = getattr(threadpoolctl, "OpenBLASController", None)
    release = getattr(controller, "clear_controlling_thread", None)
    if release is not None:
        release(force=True)


def blas_single_threaded() -> bool:
    """Whether every BLAS/OpenMP library loaded in this process runs one thread."""
    from threadpoolctl import threadpool_info

    return all(i.get("num_threads", 1) <= 1 for i in threadpool_info())
