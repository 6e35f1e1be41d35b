"""The build step and the study's task graph: a case's objects are built once (at
validation) and the study reads them; the tasks are declared once and give the same
study in this process (InlineExecutor) and in a process pool."""

import os
import subprocess
import sys
from concurrent.futures import Future

import numpy as np
import pytest

import tribodyn.config.case as case_module
import tribodyn.config.case_valvetrain as vt_module
from tribodyn.config import Case, load_case
from tribodyn.config.build import build
from tribodyn.cycle.tasks import InlineExecutor, Task, run_tasks
from tribodyn.workflow.cycle import run_cycle_study


def _tiny_data() -> dict:
    """The paper's case, two surface sets, one engine cycle, coarse steps and grid, no
    implicit coupling or stresses: the plumbing is under test, not the physics."""
    data = (
        load_case()
        .updated(
            {
                "numerics.crank_step_deg": 4.0,
                "numerics.n": 128,
                "numerics.implicit_coupling": False,
                "numerics.cycles": 1,
                "numerics.output_step_deg": 1.0,
                "stress.enabled": False,
            }
        )
        .to_dict()
    )
    data["surface_sets"] = data["surface_sets"][:2]  # uncoated (reference), dlc_1um
    return data


def _counting(monkeypatch, module, name, calls):
    original = getattr(module, name)

    def make(*args, **kwargs):
        calls[name] = calls.get(name, 0) + 1
        return original(*args, **kwargs)

    monkeypatch.setattr(module, name, make)


def test_the_study_builds_each_object_once(monkeypatch):
    """Loading the case and running its study (in this process) constructs the cam, the
    lubricant, the valvetrain, the EHL options once and each set's roughness once: the
    study reads the objects built at validation. (The code before the build step built
    the lubricant and options again for every set and task.)"""
    data = _tiny_data()
    calls: dict[str, int] = {}
    for module, name in [
        (case_module, "Lubricant"),
        (case_module, "EHLOptions"),
        (case_module, "Roughness"),
        (vt_module, "AccelerationCam"),
        (vt_module, "ValvetrainParameters"),
    ]:
        _counting(monkeypatch, module, name, calls)
    once = {
        "Lubricant": 1,
        "EHLOptions": 1,
        "Roughness": 2,
        "AccelerationCam": 1,
        "ValvetrainParameters": 1,
    }
    case = Case.from_dict(data)
    assert calls == once
    study = run_cycle_study(case, workers=1, compare_paper=False)
    assert [s.name for s in study.sets] == ["uncoated", "dlc_1um"]
    assert calls == once
    built = build(case)
    assert build(case) is built  # kept by the case, not built again
    assert built.set("dlc_1um").options.boundary_shear_coefficient == pytest.approx(
        built.set("dlc_1um").surface.boundary_shear_coefficient
    )


def test_the_built_case_holds_materials_strengths_and_wear():
    """The BuiltCase holds what the studies read: each material's E and ν, its strength
    (``[strength.<m>]`` over the typical values), each set's Archard coefficient and its
    source; the thermal oil of a case that is not thermal is built on demand, or its
    error names the missing key."""
    from tribodyn import InputError
    from tribodyn.config.build import build
    from tribodyn.physics.strength import TYPICAL_WEAR_COEFFICIENT

    data = _tiny_data()
    data["strength"] = {"dlc": {"wear_coefficient": 2.5e-17, "hardness": 2.0e10}}
    built = build(Case.from_dict(data))
    for key, m in data["materials"].items():
        assert (built.materials[key].E, built.materials[key].nu) == (m["E"], m["nu"])
    assert built.material_strengths["dlc"].hardness == 2.0e10
    dlc, steel = built.set("dlc_1um"), built.set("uncoated")
    assert (dlc.wear_coefficient, dlc.wear_source) == (2.5e-17, "case [strength.dlc]")
    assert steel.wear_coefficient == TYPICAL_WEAR_COEFFICIENT["steel"]
    assert steel.wear_source.startswith("assumed")
    assert built.thermal_lubricant is None  # not thermal; its [numerics] thermal options:
    assert built.thermal_options.x_nodes == data["numerics"]["thermal_x_nodes"]
    with pytest.raises(InputError, match="lubricant.inlet_temperature_c"):
        built.thermal_oil()
    data["lubricant"] |= {"inlet_temperature_c": 90.0, "viscosity_temperature_coefficient": 0.03}
    warm = build(Case.from_dict(data))
    assert warm.thermal_oil().inlet_temperature == pytest.approx(363.15)
    assert warm.thermal_solver_options().x_nodes == data["numerics"]["thermal_x_nodes"]


def test_serial_and_pool_give_the_same_study():
    """The one task graph run by InlineExecutor (workers=1) and by the local process pool
    (workers=2) gives bit-identical per-set results and the same summary."""
    case = Case.from_dict(_tiny_data())
    serial = run_cycle_study(case, workers=1, compare_paper=False)
    pool = run_cycle_study(case, workers=2, compare_paper=False)
    assert [s.name for s in serial.sets] == [s.name for s in pool.sets]
    compared = 0
    for x, y in zip(serial.sets, pool.sets, strict=True):
        for key, value in vars(x).items():
            if isinstance(value, np.ndarray):
                assert np.array_equal(value, getattr(y, key), equal_nan=True), (x.name, key)
                compared += 1
        assert x.failures == y.failures and x.validity == y.validity
    assert compared >= 2 * 15
    assert serial.analyse().summary["surface_sets"] == pool.analyse().summary["surface_sets"]
    assert serial.nose_sets is not None and pool.nose_sets is not None
    assert serial.nose_sets.to_dict() == pool.nose_sets.to_dict()


def _square(x):
    return x * x


def _fail(x):
    raise ValueError(f"bad {x}")


def test_run_tasks_reports_each_result_once_and_raises_task_errors():
    seen, started = [], []
    tasks = [Task(f"t{i}", _square, (i,)) for i in range(4)]
    run_tasks(InlineExecutor(), tasks, lambda k, r: seen.append((k, r)), started.append)
    # inline: each result is handed over before the next task starts
    assert started == ["t0", "t1", "t2", "t3"]
    assert seen == [("t0", 0), ("t1", 1), ("t2", 4), ("t3", 9)]
    f = InlineExecutor().submit(_fail, 3)
    assert isinstance(f, Future) and isinstance(f.exception(), ValueError)
    with pytest.raises(ValueError, match="bad 2"):
        run_tasks(InlineExecutor(), [Task("a", _fail, (2,))], lambda k, r: None)
    with pytest.raises(ValueError, match="not unique"):
        run_tasks(InlineExecutor(), [Task("a", _square, (1,))] * 2, lambda k, r: None)


def _add(x, y):
    return x + y


@pytest.mark.parametrize("pool", [False, True], ids=["inline", "one thread"])
def test_a_task_after_another_gets_its_result_and_its_priority(pool):
    from concurrent.futures import ThreadPoolExecutor

    seen, started = {}, []
    tasks = [
        Task("a", _square, (3,)),
        Task("c", _square, (5,)),
        Task("b", _add, (1,), after="a"),
        Task("d", _add, (2,), after="b"),
    ]
    ex = ThreadPoolExecutor(1) if pool else InlineExecutor()
    with ex:
        run_tasks(ex, tasks, seen.__setitem__, started.append, limit=1)
    assert seen == {"a": 9, "c": 25, "b": 10, "d": 12}
    # one at a time, in list order among the ready ones
    assert started == ["a", "c", "b", "d"]
    with pytest.raises(ValueError, match="not before it"):
        run_tasks(InlineExecutor(), [Task("b", _add, (1,), after="a")], lambda k, r: None)


def test_the_limit_orders_a_pool_by_the_list():
    # a task made ready by a result starts before the later ones of the list
    from concurrent.futures import ThreadPoolExecutor

    started = []
    tasks = [Task("a", _square, (1,)), Task("b", _add, (1,), after="a")]
    tasks += [Task(f"x{i}", _square, (i,)) for i in range(3)]
    with ThreadPoolExecutor(1) as ex:
        run_tasks(ex, tasks, lambda k, r: None, started.append, limit=1)
    assert started == ["a", "b", "x0", "x1", "x2"]


def _python(code: str, extra_path: str = "") -> str:
    """Run ``code`` in a fresh interpreter without the BLAS thread variables."""
    env = {k: v for k, v in os.environ.items() if not k.endswith("_NUM_THREADS")}
    src = os.path.join(os.path.dirname(__file__), "..", "src")
    env["PYTHONPATH"] = os.pathsep.join(p for p in [src, extra_path, env.get("PYTHONPATH")] if p)
    r = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120
    )
    assert r.returncode == 0, r.stderr
    return r.stdout.strip()


def test_import_is_lazy_and_the_command_line_sets_one_blas_thread():
    """``import tribodyn`` loads no numpy (its names load on first use), so the command
    line's BLAS environment (set by ``tribodyn.cli`` before numpy loads) takes effect;
    the Python API leaves the user's environment alone."""
    out = _python(
        "import sys, os, tribodyn; print('numpy' in sys.modules, "
        "os.environ.get('OPENBLAS_NUM_THREADS')); tribodyn.solve_ehl; "
        "print('numpy' in sys.modules)"
    )
    assert out.splitlines() == ["False None", "True"]
    out = _python("import os, tribodyn.cli; print(os.environ['OPENBLAS_NUM_THREADS'])")
    assert out == "1"


PROBE = """
import os


def blas_threads():
    import numpy  # noqa: F401  (loads BLAS)
    from threadpoolctl import threadpool_info

    return max((i.get("num_threads", 1) for i in threadpool_info()), default=1)
"""


def test_pool_workers_start_with_one_blas_thread(tmp_path):
    """A parent with multi-threaded BLAS starts the study's pool in fresh interpreters;
    they start (on the first submission) with the one-thread environment, and the
    parent's environment is restored afterwards."""
    (tmp_path / "blas_probe.py").write_text(PROBE, encoding="utf-8")
    out = _python(
        "import os, sys\n"
        f"sys.path.insert(0, {str(tmp_path)!r})\n"
        "from blas_probe import blas_threads\n"
        "from tribodyn.workflow.cycle import _study_executor\n"
        "print(blas_threads())\n"
        "with _study_executor(None, 2) as pool:\n"
        "    print(pool.submit(blas_threads).result())\n"
        "print(os.environ.get('OPENBLAS_NUM_THREADS'))\n",
        extra_path=str(tmp_path),
    )
    lines = out.splitlines()
    if int(lines[0]) <= 1:  # nothing to limit: the parent already runs one thread
        pytest.skip("BLAS runs one thread by default here")
    assert lines[1:] == ["1", "None"]


def test_the_runtime_limit_holds_until_the_outer_block_closes():
    """single_blas_thread: an inner block does not lift the limit of the outer one; the
    outer one restores the default."""
    out = _python(
        "import numpy\n"
        "from tribodyn._threads import single_blas_thread as one, blas_single_threaded as q\n"
        "r = [q()]\n"
        "with one():\n"
        "    with one(): r.append(q())\n"
        "    r.append(q())\n"
        "r.append(q())\n"
        "print(r)\n"
    )
    r = out.strip("[]").split(", ")
    assert r[1:3] == ["True", "True"] and r[3] == r[0]  # the default comes back


def _process_wide_blas() -> bool:
    """Whether every BLAS/OpenMP library numpy loads keeps one process-wide thread count
    (OpenBLAS built with pthreads); OpenMP and MKL limits are per thread."""
    out = _python(
        "import numpy\n"
        "from threadpoolctl import threadpool_info\n"
        "i = threadpool_info()\n"
        "print(bool(i) and all(x.get('internal_api') == 'openblas' and "
        "x.get('threading_layer') == 'pthreads' for x in i))\n"
    )
    return out == "True"


def test_the_runtime_limit_is_shared_by_overlapping_threads():
    """Two threads (ThreadPoolExecutor) inside single_blas_thread with overlapping
    blocks: the limit holds while either runs (also after the first one left), the
    default is restored after both, the count returns to 0 and a later block limits
    again. Where the limit is per thread (OpenMP, MKL) there is nothing shared to test."""
    if not _process_wide_blas():
        pytest.skip("BLAS thread limits are per thread here (not pthreads OpenBLAS)")
    out = _python(
        "import threading\n"
        "from concurrent.futures import ThreadPoolExecutor\n"
        "import numpy\n"
        "from tribodyn import _threads\n"
        "from tribodyn._threads import single_blas_thread as one, blas_single_threaded as q\n"
        "a_in, b_in, a_out = threading.Event(), threading.Event(), threading.Event()\n"
        "def a():\n"
        "    with one():\n"
        "        a_in.set(); b_in.wait(10); r = q()\n"
        "    a_out.set(); return r\n"
        "def b():\n"
        "    a_in.wait(10)\n"
        "    with one():\n"
        "        b_in.set(); a_out.wait(10); return q()\n"
        "default = q()\n"
        "with ThreadPoolExecutor(2) as pool:\n"
        "    fa, fb = pool.submit(a), pool.submit(b)\n"
        "    r = [fa.result(), fb.result()]\n"
        "r += [q() == default, _threads._depth]\n"
        "with one(): r.append(q())\n"
        "r += [q() == default, _threads._depth]\n"
        "print(r)\n"
    )
    assert out == "[True, True, True, 0, True, True, 0]"
