"""A study's task graph, declared once and run by any :class:`concurrent.futures.Executor`.

A :class:`Task` is a picklable top-level function with picklable arguments and a key;
:func:`run_tasks` submits a list of them in order to an executor (a process pool, a Dask
client's ``get_executor()``, or :class:`InlineExecutor`, which runs each task in this
process when it is submitted) and hands every result to ``done(key, result)`` in the
calling process as soon as it is in. The tasks of a study are independent once their
inputs are known, so the graph is a list; serial and parallel runs execute the same
functions on the same arguments and give the same results.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from concurrent.futures import Executor, Future, as_completed
from dataclasses import dataclass, field
from typing import Any

__all__ = ["InlineExecutor", "Task", "run_tasks"]


@dataclass(frozen=True)
class Task:
    """One task: ``fn(*args)`` under ``key`` (unique in its graph)."""

    key: str
    fn: Callable[..., Any]
    args: tuple = field(default=())


class InlineExecutor(Executor):
    """The minimal serial executor: ``submit`` runs the call at once in this process and
    returns a finished :class:`~concurrent.futures.Future` (its result or its exception)."""

    def submit(self, fn, /, *args, **kwargs):
        f: Future = Future()
        try:
            f.set_result(fn(*args, **kwargs))
        except Exception as exc:  # re-raised by f.result(), as from a pool
            f.set_exception(exc)
        return f


def run_tasks(
    executor: Executor,
    tasks: Sequence[Task],
    done: Callable[[str, Any], None],
    started: Callable[[str], None] | None = None,
) -> None:
    """Submit ``tasks`` in order to ``executor``; ``started(key)`` before each submission
    and ``done(key, result)`` for each result, in this process, as soon as it is in (at
    once for :class:`InlineExecutor`, in order of completion for a pool). A task's
    exception is raised here; the remaining futures are cancelled."""
    keys = [t.key for t in tasks]
    if len(set(keys)) != len(keys):
        raise ValueError(f"task keys are not unique: {keys}")
    pending: dict[Future, str] = {}
    try:
        for t in tasks:
            if started is not None:
                started(t.key)
            fut = executor.submit(t.fn, *t.args)
            pending[fut] = t.key
            for f in [f for f in pending if f.done()]:  # an inline executor: done at once
                done(pending.pop(f), f.result())
        for f in as_completed(list(pending)):
            done(pending.pop(f), f.result())
    finally:
        for f in pending:
            f.cancel()
