"""The public solvers run their small dense kernels with one BLAS thread, whatever the
caller's setting, and give the caller's setting back when they return
(``tribodyn._threads.one_blas_thread``; measured: a 768-node steady solve takes 2.3× the
one-thread time with two threads on two cores, ``benchmarks/bench_blas_threads.py``)."""

import pytest
from threadpoolctl import threadpool_info, threadpool_limits

from tribodyn import Body, Lubricant, Material, TransientEHL, solve_dry_contact, solve_ehl
from tribodyn._threads import blas_single_threaded
from tribodyn.contact import dry
from tribodyn.contact.ehl import steady, transient

STEEL = Body(Material(210e9, 0.3))
PAIR = (STEEL, STEEL)
OIL = Lubricant(0.01, 1.5e-8)


def _max_threads() -> int:
    return max((i.get("num_threads", 1) for i in threadpool_info()), default=1)


@pytest.fixture
def two_threads():
    with threadpool_limits(limits=2):
        if _max_threads() < 2:
            pytest.skip("this BLAS runs one thread only; nothing to limit")
        yield


def _spy(monkeypatch, module, name, seen):
    real = getattr(module, name)

    def spy(*args, **kwargs):
        seen.append(blas_single_threaded())
        return real(*args, **kwargs)

    monkeypatch.setattr(module, name, spy)


def test_solve_ehl_runs_one_thread_and_restores_the_callers(two_threads, monkeypatch):
    seen: list[bool] = []
    _spy(monkeypatch, steady, "newton", seen)
    r = solve_ehl(4e4, 0.01, 2.0, 0.5, PAIR, OIL, n=96)
    assert r.converged
    assert seen and all(seen)
    assert _max_threads() == 2


def test_dry_contact_runs_one_thread(two_threads, monkeypatch):
    seen: list[bool] = []
    _spy(monkeypatch, dry, "_cgm", seen)
    solve_dry_contact(load=1e5, radius=0.01, bodies=PAIR, n=128)
    assert seen and all(seen)
    assert _max_threads() == 2


def test_transient_steps_run_one_thread(two_threads, monkeypatch):
    seen: list[bool] = []
    _spy(monkeypatch, transient, "newton", seen)
    t = TransientEHL(PAIR, OIL, None, n=96)
    t.start_steady(4e4, 0.01, 2.0, 0.5)
    t.step(1e-5, 4.1e4, 0.01, 2.0, 0.5)
    assert seen and all(seen)
    assert _max_threads() == 2
