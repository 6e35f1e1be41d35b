"""A study's task graph, declared once and run by any :class:`concurrent.futures.Executor`.

A :class:`Task` is a picklable top-level function with picklable arguments and a key;
it may wait for one earlier task (``after``), whose result is then its last argument.
:func:`run_tasks` submits them to an executor (a process pool, a Dask client's
``get_executor()``, or :class:`InlineExecutor`, which runs each task in this process
when it is submitted) in list order as their inputs are ready, and hands every result to
``done(key, result)`` in the calling process as soon as it is in. With ``limit`` (a
process pool's number of workers) no more tasks are submitted than can run at once, so
that a task made ready by a result starts before the later tasks of the list: the list
order is the priority. Serial and parallel runs execute the same functions on the same
arguments and give the same results.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from concurrent.futures import FIRST_COMPLETED, Executor, Future, wait
from dataclasses import dataclass, field
from typing import Any

__all__ = ["InlineExecutor", "Task", "run_tasks"]


@dataclass(frozen=True)
class Task:
    """One task: ``fn(*args)`` under ``key`` (unique in its graph), or
    ``fn(*args, result)`` with the result of the earlier task ``after``."""

    key: str
    fn: Callable[..., Any]
    args: tuple = field(default=())
    after: str | None = None


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


def _check(tasks: Sequence[Task]) -> None:
    keys = [t.key for t in tasks]
    if len(set(keys)) != len(keys):
        raise ValueError(f"task keys are not unique: {keys}")
    for i, t in enumerate(tasks):
        if t.after is not None and t.after not in keys[:i]:
            raise ValueError(f"task {t.key!r} waits for {t.after!r}, which is not before it")


def run_tasks(
    executor: Executor,
    tasks: Sequence[Task],
    done: Callable[[str, Any], None],
    started: Callable[[str], None] | None = None,
    limit: int | None = None,
) -> None:
    """Run ``tasks`` on ``executor`` (module docstring): each is submitted, in list order
    among those whose ``after`` result is in, while fewer than ``limit`` (None: any
    number) are running; ``started(key)`` before each submission and ``done(key,
    result)`` for each result, in this process, as soon as it is in (at once for
    :class:`InlineExecutor`, in order of completion for a pool). A task's exception is
    raised here; the remaining futures are cancelled."""
    _check(tasks)
    needed = {t.after for t in tasks if t.after is not None}
    results: dict[str, Any] = {}  # the results later tasks wait for
    waiting = list(tasks)
    pending: dict[Future, str] = {}

    def finish(f: Future) -> None:
        key = pending.pop(f)
        r = f.result()
        if key in needed:
            results[key] = r
        done(key, r)

    try:
        while waiting or pending:
            ready = next((t for t in waiting if t.after is None or t.after in results), None)
            if ready is not None and (limit is None or len(pending) < limit):
                waiting.remove(ready)
                if started is not None:
                    started(ready.key)
                args = ready.args if ready.after is None else (*ready.args, results[ready.after])
                pending[executor.submit(ready.fn, *args)] = ready.key
                for f in [f for f in pending if f.done()]:  # an inline executor: done at once
                    finish(f)
                continue
            if not pending:  # cannot happen after _check: every ``after`` comes first
                raise RuntimeError(f"tasks wait for results never computed: {waiting}")
            finished, _ = wait(list(pending), return_when=FIRST_COMPLETED)
            for f in finished:
                finish(f)
    finally:
        for f in pending:
            f.cancel()
