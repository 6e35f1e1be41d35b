"""Design sweeps on Dask: one task per point, on a local cluster or an existing scheduler.

:func:`run_sweep` takes a validated :class:`~tribodyn.config.sweep.SweepSpec`, plans its
points, and submits one task per point (:func:`tribodyn.workflow.sweep_point.run_point`:
the full cam-cycle study of the point's case, or the dynamics alone) to a
``dask.distributed`` client. Without a client it starts a ``LocalCluster`` of process
workers sized to the machine (one single-threaded worker per available CPU core, at most
one per point); :func:`connect` attaches to an existing scheduler (``tcp://host:8786`` or
a scheduler file), so the same sweep runs on a laptop, a ``dask scheduler`` +
``dask worker`` cluster or an HPC queue (dask-jobqueue).

With an output folder every finished point is written at once (:class:`PointStore`, one
file per point, atomically); ``resume=True`` skips the points already finished. A point
that fails — an invalid combination of values, a solver failure, a worker that died — is
recorded with its error and the others go on. The result is one xarray Dataset indexed by
the sweep's dimensions (:func:`combine_points`).
"""

from __future__ import annotations

import json
import logging
import math
import os
import statistics
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import xarray as xr

from .._typing import PathLike
from .._user_files import read_user_bytes
from .._validation import InputError
from .sweep_point import failed_point, run_point
from .sweep_store import PointStore, combine_points

if TYPE_CHECKING:
    from distributed import Client, LocalCluster

    from ..config.case import Case
    from ..config.sweep import SweepSpec

__all__ = [
    "SweepResult",
    "run_sweep",
    "connect",
    "local_cluster",
    "machine_workers",
    "estimate_point_seconds",
    "estimate_sweep",
]


@dataclass
class SweepResult:
    """A finished (or partly failed) sweep."""

    spec: SweepSpec
    points: list  #: the plan (SweepPoint, in dimension order)
    dataset: xr.Dataset  #: all points, indexed by the sweep dimensions
    ran: int = 0  #: points run now
    skipped: int = 0  #: points already finished (resume)
    failed: list = field(default_factory=list)  #: [(SweepPoint, error)]
    runtime_s: float = 0.0
    workers: int = 0
    scheduler: str = ""

    @property
    def n_ok(self) -> int:
        return len(self.points) - len(self.failed)


def machine_workers() -> int:
    """CPU cores this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


def local_cluster(workers: int | None = None) -> LocalCluster:
    """A ``LocalCluster`` of single-threaded process workers (default: one per core)."""
    from distributed import LocalCluster

    n = machine_workers() if not workers else int(workers)
    if n < 1:
        raise InputError(f"workers: must be >= 1 (got {workers})")
    return LocalCluster(
        n_workers=n,
        threads_per_worker=1,
        processes=True,
        dashboard_address=":0",
        silence_logs=logging.ERROR,
    )


def _scheduler_file_address(path: Path) -> str:
    """The address in a Dask scheduler file (JSON with ``"address"``, as written by
    ``dask scheduler --scheduler-file FILE``), or :class:`InputError` naming
    ``--scheduler``."""
    what = (
        f"--scheduler: {str(path)!r} is not a Dask scheduler file (a JSON file with the "
        'scheduler\'s "address", written by `dask scheduler --scheduler-file FILE`)'
    )
    raw = read_user_bytes(path, "--scheduler", limit=1_000_000, hint=what)  # no pipes
    try:
        info = json.loads(raw.decode("utf-8"))
    except (UnicodeDecodeError, ValueError, RecursionError):
        raise InputError(what) from None
    address = info.get("address") if isinstance(info, dict) else None
    if not isinstance(address, str) or "://" not in address:
        raise InputError(what)
    return address


#: Address schemes of a remote Dask scheduler (inproc is in-process; ucx needs ucx-py).
SCHEDULER_SCHEMES = ("tcp", "tls", "ws", "wss")


def _check_address(address: str, shown: str) -> None:
    """:class:`InputError` naming ``--scheduler`` unless ``address`` has the form
    scheme://host:port with a network scheme (malformed addresses are not handed to
    dask, whose client can stall on them)."""
    from distributed.comm.addressing import parse_address, parse_host_port

    how = "give a running scheduler's address, e.g. tcp://host:8786, or a scheduler file"
    if "://" not in address:
        raise InputError(f"--scheduler: {shown!r} is neither an address nor a file; {how}")
    scheme, location = parse_address(address)
    if scheme not in SCHEDULER_SCHEMES:
        raise InputError(
            f"--scheduler: {shown!r}: unsupported scheme {scheme!r} (use "
            f"{', '.join(s + '://' for s in SCHEDULER_SCHEMES)}); {how}"
        )
    try:
        _, port = parse_host_port(location)
    except (ValueError, TypeError) as exc:
        raise InputError(f"--scheduler: {shown!r} is not host:port ({exc}); {how}") from None
    if not 0 < int(port) < 65536:
        raise InputError(f"--scheduler: port {port} of {shown!r} is not in 1…65535; {how}")


def connect(address: str, *, workers: int | None = None, timeout: float = 30.0) -> Client:
    """A client of an existing Dask scheduler: ``tcp://host:port`` (or another Dask
    address) or the path of a scheduler file. ``workers``: wait until that many workers
    are connected. Raises :class:`InputError` naming ``--scheduler`` if it cannot: a
    missing scheduler, a malformed address or a file that is not a scheduler file."""
    from distributed import Client

    if not isinstance(address, str) or not address.strip():
        raise InputError(
            "--scheduler: give the scheduler's address, e.g. tcp://host:8786, or a scheduler file"
        )
    shown = address if len(address) <= 80 else address[:77] + "..."
    target = address
    if "://" not in address and Path(address).exists():
        if Path(address).is_dir():
            raise InputError(
                f"--scheduler: {shown!r} is a folder; give the scheduler's address, e.g. "
                "tcp://host:8786, or a scheduler file"
            )
        target = _scheduler_file_address(Path(address))
    _check_address(target, shown)
    try:
        client = Client(target, timeout=timeout)
    except Exception as exc:  # dask raises OSError, ValueError, TypeError, AssertionError…
        detail = str(exc) if len(str(exc)) <= 200 else str(exc)[:197] + "..."
        raise InputError(
            f"--scheduler: cannot connect to {shown!r} within {timeout:g} s "
            f"({type(exc).__name__}: {detail}); start one with `dask scheduler` "
            "or give a running scheduler's address, e.g. tcp://host:8786"
        ) from None
    if workers:
        try:
            client.wait_for_workers(int(workers), timeout=timeout)
        except Exception:  # TimeoutError, or a scheduler gone meanwhile
            have = _n_workers(client)
            client.close()
            raise InputError(
                f"--workers: {workers} workers requested, {have} connected to "
                f"{shown} after {timeout:g} s"
            ) from None
    return client


def _n_workers(client) -> int:
    try:
        return len(client.scheduler_info().get("workers", {}))
    except Exception:  # a scheduler that does not answer: report 0
        return 0


def run_sweep(
    spec: SweepSpec | PathLike,
    client: Client | None = None,
    *,
    out_dir: PathLike | None = None,
    resume: bool = False,
    workers: int | None = None,
    progress: Callable[..., None] | None = None,
) -> SweepResult:
    """Run a sweep; return its :class:`SweepResult`.

    spec : a :class:`~tribodyn.config.sweep.SweepSpec` (or a sweep file path).
    client : a ``distributed.Client``; None starts a ``LocalCluster`` with ``workers``
        process workers (default: one per CPU core, at most one per point) and closes it
        at the end.
    out_dir : folder for the point files (``out_dir/points``); None keeps everything in
        memory (no resume).
    resume : skip the points whose file in ``out_dir`` is finished. Without it an
        ``out_dir`` that already holds points is refused, so no finished point is lost.
    progress : ``progress(event, **info)`` with ``"start"`` (total, skipped, todo,
        workers) and ``"point"`` (done, failed, total, label, status, error) events.
    """
    from ..config.sweep import SweepSpec, load_sweep

    if not isinstance(spec, SweepSpec):
        spec = load_sweep(spec)
    t_start = time.perf_counter()
    report = progress or (lambda *a, **k: None)
    plan = spec.points()
    store = PointStore(out_dir) if out_dir is not None else None
    results: dict[int, xr.Dataset] = {}
    skipped = 0
    if store is not None:
        store.clean()
        if store.keys() and not resume:
            raise InputError(
                f"{store.folder} already holds points of a sweep: pass resume "
                "(--resume) to go on with it, or choose another output folder"
            )
        if resume:
            for p in plan:
                if p.case is not None and store.status(p.key) == "ok":
                    finished = store.load(p.key)
                    if finished is not None:
                        results[p.index] = finished
                        skipped += 1
    failed: list = []
    for p in plan:  # invalid combinations: recorded, never run
        if p.case is None:
            results[p.index] = failed_point(p.error or "invalid combination")
            if store is not None:
                store.write(p, results[p.index])
            failed.append((p, p.error))
    todo = [p for p in plan if p.index not in results]

    own = None
    if client is None and todo:
        n = min(workers or machine_workers(), len(todo))
        own = local_cluster(n)
        from distributed import Client

        client = Client(own)
    n_workers = _n_workers(client) if client is not None else 0
    scheduler = getattr(getattr(client, "scheduler", None), "address", "") or ""
    if own is not None:
        scheduler = ""  # a cluster of this run: not an address to report
    report(
        "start",
        total=len(plan),
        skipped=skipped,
        todo=len(todo),
        workers=n_workers,
        scheduler=scheduler,
        invalid=len(failed),
    )
    done = skipped + len(failed)
    futures = []
    try:
        if todo:
            futures = _submit(client, spec, todo)
            by_key = {f.key: p for f, p in zip(futures, todo)}
            from distributed import as_completed

            for fut in as_completed(futures):
                p = by_key[fut.key]
                try:
                    ds = fut.result()
                except Exception as exc:  # worker died, cancelled, …
                    ds = failed_point(f"{type(exc).__name__}: {exc}")
                fut.release()
                results[p.index] = ds
                if store is not None:
                    store.write(p, ds)
                status = ds.attrs.get("status", "failed")
                if status != "ok":
                    failed.append((p, ds.attrs.get("error", "")))
                done += 1
                report(
                    "point",
                    done=done,
                    failed=len(failed),
                    total=len(plan),
                    label=p.label,
                    status=status,
                    error=ds.attrs.get("error", ""),
                )
    except BaseException:  # interrupted: finished points are on disk
        if futures and own is None and client is not None:
            client.cancel([f for f in futures if not f.done()])
        raise
    finally:
        if own is not None:
            if client is not None:
                client.close()
            own.close()
    failed.sort(key=lambda f: f[0].index)
    dataset = combine_points(spec, plan, results)
    runtime = time.perf_counter() - t_start
    dataset.attrs["runtime_s"] = runtime
    dataset.attrs["points_run"] = len(todo)
    dataset.attrs["points_resumed"] = skipped
    return SweepResult(
        spec=spec,
        points=plan,
        dataset=dataset,
        ran=len(todo),
        skipped=skipped,
        failed=failed,
        runtime_s=runtime,
        workers=n_workers,
        scheduler=scheduler,
    )


def _cost_rank(todo) -> dict[int, int]:
    """Scheduling priority of each point (index → rank, higher first): by engine speed,
    fastest first, ties in plan order. Faster points cost more (measured on
    ``engine_dohc16_map``: ≈ 6–8 s of CPU per point at 1000 rpm, ≈ 8–10 s at 4000 rpm and
    more above), and starting the longest first keeps the last point to finish short
    (longest-processing-time order), so the workers end together."""
    order = sorted(todo, key=lambda p: (p.case.engine_speed, -p.index))
    return {p.index: rank for rank, p in enumerate(order)}


def _submit(client, spec, todo):
    """One task per point (unique keys: a rerun never picks up an old task's result),
    submitted and prioritised costliest first (:func:`_cost_rank`: idle workers take the
    first tasks as they arrive); the futures in the order of ``todo``."""
    import uuid

    tag = uuid.uuid4().hex[:8]
    rank = _cost_rank(todo)
    futures = {
        p.index: client.submit(
            run_point,
            p.case,
            spec.mode,
            spec.traces,
            pure=False,
            key=f"tribodyn-point-{p.index}-{p.key}-{tag}",
            priority=rank[p.index],
        )
        for p in sorted(todo, key=lambda p: -rank[p.index])
    }
    return [futures[p.index] for p in todo]


# ----------------------------------------------------------------------------- estimate
def estimate_point_seconds(case: Case, mode: str = "study", steps: int = 8) -> float:
    """Estimated CPU time [s] of one point on one core, from a calibration run.

    Dynamics mode: the dynamics is run (its time is the estimate). Study mode: the
    dynamics is run, ``steps`` transient-EHL steps of the reference set are timed from the
    peak contact force, and the study's time is extrapolated: dynamics + EHL over the
    loaded samples for every surface set + (implicit coupling) ``coupling_iterations`` ×
    (dynamics + reference-set EHL) + the single-contact studies (timed). The coupling
    term is an upper bound (iterations stop once converged)."""
    from .._threads import single_blas_thread
    from ..config.build import build
    from ..contact.ehl import TransientEHL
    from ..cycle.driver import CycleInputs
    from .cycle import StudyError, coating_studies_task, study_dynamics
    from .postprocess import surface_roles
    from .sensitivity import nose_condition

    clock = time.process_time  # CPU time: one core, whatever the machine's load
    built = build(case)
    with single_blas_thread():
        t0 = clock()
        dyn = study_dynamics(built)
        t_dyn = clock() - t0
        if mode == "dynamics" or not dyn.converged:
            return t_dyn
        n = case.numerics
        inp = CycleInputs.from_dynamics(dyn, n.crank_step_deg, case.width)
        loaded = inp.contact_force >= n.min_load
        n_loaded = int(loaded.sum())
        if n_loaded == 0:
            raise StudyError("no EHL sample is loaded")
        ref_name = surface_roles(built)["reference"]
        ref = built.set(ref_name)
        i0 = int(inp.contact_force.argmax())
        i0 = max(1, min(i0, inp.crank_angle.size - steps))
        tr = TransientEHL(
            ref.surface.bodies, built.lubricant, ref.surface.roughness, options=ref.options
        )
        t0 = clock()
        timed = range(i0, min(i0 + steps, inp.crank_angle.size))
        for i in timed:
            w = inp.contact_force[i] / case.width
            args = (max(w, 1.0), inp.radius[i], inp.entrainment_speed[i], inp.sliding_speed[i])
            if i == i0:
                tr.start_steady(*args, time=inp.time[i])
            else:
                tr.step(inp.time[i] - inp.time[i - 1], *args)
        t_step = (clock() - t0) / max(len(timed), 1)
        t0 = clock()
        coating_studies_task(built, ref_name, nose_condition(inp))  # as the study's task
        t_single = clock() - t0
    t_ehl = n_loaded * t_step
    t = t_dyn + len(case.surface_set_names) * t_ehl + t_single
    if n.implicit_coupling:
        t += n.coupling_iterations * (t_dyn + t_ehl)
    return t


#: A dry run validates every combination of sweeps up to this many points; larger ones
#: are counted from their shape and calibrated on their first and last point only.
PLAN_CHECK_LIMIT = 1000


def estimate_sweep(spec: SweepSpec, *, workers: int, out_dir: PathLike | None = None) -> dict:
    """Estimated wall time of a sweep on ``workers`` single-threaded workers.

    The time per point is the median CPU time of points already finished in ``out_dir``
    (resume) if any, else :func:`estimate_point_seconds` calibrated on the first and the
    last valid point of the plan. Returns points, invalid, done, todo, seconds_per_point,
    seconds, method, checked. Up to :data:`PLAN_CHECK_LIMIT` points every combination is
    validated (``checked`` True); a larger plan is not built (seconds, not hours): its
    ``invalid`` is None, ``done`` counts the point files in ``out_dir``, and it is
    calibrated on its first and last point."""
    n = spec.n_points
    store = PointStore(out_dir) if out_dir is not None else None
    done_times = []
    checked = n <= PLAN_CHECK_LIMIT
    if checked:
        plan = spec.points()
        valid = [p for p in plan if p.case is not None]
        invalid: int | None = n - len(valid)
        if store is not None:
            for p in valid:
                ds = store.load(p.key) if store.status(p.key) == "ok" else None
                if ds is not None:
                    done_times.append(
                        float(ds.attrs.get("cpu_s", ds.attrs.get("runtime_s", math.nan)))
                    )
        done = len(done_times)  # the finished points (their times, finite or not)
        todo = len(valid) - done
    else:
        ends = [spec.point(0), spec.point(n - 1)]
        valid = [p for p in ends if p.case is not None]
        invalid = None
        done = len(store.keys()) if store is not None else 0
        todo = max(n - done, 0)
    done_times = [t for t in done_times if math.isfinite(t)]
    if done_times:
        per = statistics.median(done_times)
        method = f"median CPU time of the {len(done_times)} finished points"
    elif valid:
        cal = [valid[0]] if len(valid) == 1 else [valid[0], valid[-1]]
        times = [estimate_point_seconds(p.case, spec.mode) for p in cal if p.case is not None]
        per = sum(times) / len(times)
        method = "calibration run of " + " and ".join(f"point {p.index} ({p.label})" for p in cal)
    else:
        per, method = 0.0, "no valid point"
    w = max(1, min(workers, max(todo, 1)))
    return {
        "points": n,
        "invalid": invalid,
        "done": done,
        "todo": todo,
        "seconds_per_point": per,
        "seconds": math.ceil(todo / w) * per,
        "workers": w,
        "method": method,
        "checked": checked,
    }
