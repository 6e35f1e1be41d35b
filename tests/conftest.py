import atexit
import os
import shutil
import tempfile

# One BLAS thread, as the command line runs the solvers (their matrices are small; set
# before numpy loads, since a runtime limit does not remove the threads' overhead).
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

# The surface laws' cache (tribodyn._cache) in a folder of this test session: the tests
# neither read the user's cache nor write into it, and their outcome does not depend on it.
_CACHE = tempfile.mkdtemp(prefix="tribodyn-test-cache-")
os.environ["TRIBODYN_CACHE_DIR"] = _CACHE
atexit.register(shutil.rmtree, _CACHE, ignore_errors=True)

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from tribodyn import Body, Coating, Material  # noqa: E402
from tribodyn.config.build import build  # noqa: E402


@pytest.fixture
def steel():
    return Material(E=210e9, nu=0.3)


@pytest.fixture
def steel_pair(steel):
    return (Body(steel), Body(steel))


@pytest.fixture
def rng():
    return np.random.default_rng(12345)


def coated_pair(steel, E, nu, thickness):
    return (Body(steel), Body(steel, Coating(E=E, nu=nu, thickness=thickness)))


# The paper case at reduced resolution: 4° crank steps, fixed 256-node EHL grid, one
# coupling iteration, coarser dynamics output. Physics and inputs are unchanged.
REDUCED = {
    "numerics.crank_step_deg": 4.0,
    "numerics.n": 256,
    "numerics.coupling_iterations": 1,
    "numerics.output_step_deg": 1.0,
    "numerics.workers": 1,
}


# A four-cylinder in-line engine (firing order 1-3-4-2, 1.6 l) around the paper's valvetrain.
ENGINE = {
    "engine.cylinders": 4,
    "engine.firing_order": [1, 3, 4, 2],
    "engine.displacement": 0.0016,
    "engine.intake": {"centre_angle_deg": 470.0},
    "engine.exhaust": {"centre_angle_deg": 250.0},
}


@pytest.fixture(scope="session")
def reduced_results(tmp_path_factory):
    """A result folder of ``tribodyn run`` on the reduced paper case (run once per session;
    tests that change files must copy it)."""
    from typer.testing import CliRunner

    from tribodyn.cli import app
    from tribodyn.config import load_case

    path = tmp_path_factory.mktemp("case") / "reduced.toml"
    load_case().updated(REDUCED).write_toml(path)
    out = tmp_path_factory.mktemp("run") / "results"
    r = CliRunner().invoke(app, ["run", str(path), "-o", str(out), "--quiet", "--figures"])
    assert r.exit_code == 0, r.output
    return out


@pytest.fixture(scope="session")
def plain_run(tmp_path_factory):
    """``tribodyn run`` of the reduced paper case without ``--figures`` (as
    ``reduced_results``, which has them; run once per session, tests that change files
    must copy it)."""
    from typer.testing import CliRunner

    from tribodyn.cli import app
    from tribodyn.config import load_case

    path = tmp_path_factory.mktemp("case") / "reduced.toml"
    load_case().updated(REDUCED).write_toml(path)
    out = tmp_path_factory.mktemp("plain") / "results"
    r = CliRunner().invoke(app, ["run", str(path), "-o", str(out), "--quiet"])
    assert r.exit_code == 0, r.output
    assert "tribodyn figures" in " ".join(r.output.split())
    return out


@pytest.fixture(scope="session")
def drawn_by_a_user(plain_run, tmp_path_factory):
    """``tribodyn figures -j 1`` (drawing in this process) into a copy of ``plain_run``
    whose report.md the user wrote, under the umask 027: (folder, its report.html before,
    the command's result, {figure file name: texts outside its canvas}, each figure
    checked as it is saved). The tests read it and change nothing."""
    from typer.testing import CliRunner

    from test_figure_canvas import check_saved_figures
    from tribodyn.cli import app

    res = tmp_path_factory.mktemp("drawn") / "results"
    shutil.copytree(plain_run, res, symlinks=True)
    (res / "report.md").write_text("# my notes\n\n## Figures\n\nmine\n", encoding="utf-8")
    html = (res / "report.html").read_bytes()
    old = os.umask(0o027)
    try:
        with pytest.MonkeyPatch.context() as mp:
            found = check_saved_figures(mp)
            r = CliRunner().invoke(app, ["figures", str(res), "-j", "1"])
    finally:
        os.umask(old)
    return res, html, r, found


def case_builders() -> frozenset[str]:
    """The private constructors of :class:`~tribodyn.config.Case` (``_new_*``,
    ``_build_*``: its own and its builder mixins'), called by ``config.build.collect``
    and the ``BuiltCase``; everywhere else the code reads the built objects."""
    import inspect

    from tribodyn.config import Case

    return frozenset(
        n
        for c in Case.__mro__
        for n, v in vars(c).items()
        if inspect.isfunction(v) and n.startswith(("_new_", "_build_"))
    )


def explicit_run(case, set_name="uncoated"):
    """(surface set, explicit dynamics, cycle inputs) of ``case``: the valvetrain driven
    with the set's analytic tribology, sampled on the case's crank step."""
    from tribodyn.cycle.driver import CycleInputs
    from tribodyn.valvetrain import simulate_valvetrain

    built = build(case)
    s = built.set(set_name).surface
    dyn = simulate_valvetrain(
        built.cam,
        built.valvetrain,
        tribology=built.analytic_tribology(set_name),
        **built.dynamics_options,
    )
    return s, dyn, CycleInputs.from_dynamics(dyn, case.numerics.crank_step_deg, case.width)


def asperity_pressure_derivative(roughness, gap, reduced_modulus):
    """dp_a/dh [Pa/m] of a Roughness as the solvers take it: K/σ · dF/dλ from its
    ``load_function`` (K its ``pressure_scale``)."""
    lam = np.asarray(gap, dtype=float) / roughness.rms
    scale = roughness.pressure_scale(reduced_modulus) / roughness.rms
    return scale * roughness.load_function(lam)[1]


def cycle_inputs(crank, force, ue, us, radius, width):
    """Cycle inputs at the crank angles ``crank`` [deg] of a crankshaft at 3000 rpm
    (t = crank/(360° · 50 Hz)): contact force ``force`` [N] (array or constant), constant
    u_e = ``ue``, u_s = ``us`` [m/s] and cam radius ``radius`` [m]; cam width [m]."""
    from tribodyn.cycle.driver import CycleInputs

    t = np.radians(crank) / (2 * np.pi * 50.0)

    def full(value):
        return np.full(crank.size, value, dtype=float)

    return CycleInputs(crank, t, full(force), full(ue), full(us), full(radius), width)


def ramp_inputs(step_deg, end_deg, width):
    """An engagement: the force rises from 0 by 10 N per crank degree from 2.3° (at most
    400 N) at u_e = 3 m/s, u_s = 6 m/s, R = 20 mm (:func:`cycle_inputs`), sampled every
    ``step_deg`` up to ``end_deg``; the first sample above 5 N is at 3° for 1° and 0.25°
    steps."""
    crank = np.arange(0.0, end_deg + 1e-9, step_deg)
    return cycle_inputs(crank, np.clip((crank - 2.3) * 10.0, 0.0, 400.0), 3.0, 6.0, 0.02, width)


def isothermal_cycle(case, surface_set, inputs):
    """The isothermal EHL march (``march_cycle`` with ``IsothermalCycle``) of ``inputs``
    on ``surface_set`` of ``case``: its bodies, roughness and EHL options, the case's
    lubricant."""
    from tribodyn.cycle.driver import IsothermalCycle, march_cycle

    s = surface_set
    method = IsothermalCycle(
        s.bodies, build(case).lubricant, s.roughness, build(case).set(s.name).options
    )
    return march_cycle(inputs, "u", "u", method)


@pytest.fixture(scope="session")
def engine_results(tmp_path_factory):
    """A result folder of ``tribodyn engine`` on the reduced paper case as a four-cylinder
    engine with two surface sets (run once per session; tests that change files must
    copy it)."""
    from typer.testing import CliRunner

    from tribodyn.cli import app
    from tribodyn.config import load_case

    base = load_case()
    sets = base.to_dict()["surface_sets"]
    sets = [s for s in sets if s["name"] in ("uncoated", "dlc_4um")]
    path = tmp_path_factory.mktemp("engine_case") / "engine.toml"
    base.updated({**REDUCED, "surface_sets": sets, **ENGINE}).write_toml(path)
    out = tmp_path_factory.mktemp("engine") / "engine"
    r = CliRunner().invoke(app, ["engine", str(path), "-o", str(out), "-j", "1"])
    assert r.exit_code == 0, r.output
    return out


def fake_sweep_folder(folder):
    """A sweep result folder of made-up numbers (engine mode: 3 speeds × 3 oil
    temperatures × 3 surface sets, the bundled map's legend) for tests of the output that
    reads sweep.nc: the friction MEP rises with speed and falls with temperature, DLC 2 %
    and WC-C 3 % below steel."""
    import json

    import xarray as xr

    speed = np.array([1000.0, 3000.0, 6000.0])
    temp = np.array([40.0, 90.0, 120.0])
    base = 10e3 + 1.0 * speed[:, None] - 40.0 * temp[None, :]
    mep = np.stack([base, 0.98 * base, 0.97 * base], axis=-1)
    energy = mep * 0.0016
    point = ("speed_rpm", "inlet_temperature_c")
    dims = (*point, "surface_set")
    force = 400.0 + 1e-5 * speed[:, None] ** 2 + 0.0 * temp[None, :]
    data = {
        "valvetrain_friction_mep_Pa": (dims, mep, {"units": "Pa"}),
        "engine_friction_energy_per_cycle_J": (dims, energy, {"units": "J"}),
        "engine_friction_power_W": (dims, energy * speed[:, None, None] / 120.0, {"units": "W"}),
        "engine_friction_torque_Nm": (dims, energy / (2 * np.pi), {"units": "N m"}),
        "engine_friction_energy_change_pct": (
            dims,
            100.0 * (mep / mep[..., :1] - 1.0),
            {"units": "%"},
        ),
        "peak_contact_force_N": (point, force, {"units": "N"}),
        "min_contact_force_in_event_N": (point, 0.5 * force, {"units": "N"}),
        "seating_velocity_m_s": (point, 0.2 + 0.0 * force, {"units": "m/s"}),
        "jump": (point, np.zeros(force.shape, int)),
        "valve_bounce": (point, np.zeros(force.shape, int)),
        "status": (point, np.ones(force.shape, int)),
    }
    axes = [
        {"path": "engine.speed_rpm", "name": "speed_rpm", "dim": "speed_rpm", "unit": "rpm"},
        {
            "path": "lubricant.inlet_temperature_c",
            "name": "inlet_temperature_c",
            "dim": "inlet_temperature_c",
            "unit": "°C",
        },
    ]
    ds = xr.Dataset(
        data,
        coords={
            "speed_rpm": speed,
            "inlet_temperature_c": temp,
            "surface_set": ["uncoated", "dlc_4um", "wcc_4um"],
        },
        attrs={"mode": "engine", "reference_set": "uncoated", "axes": json.dumps(axes)},
    )
    folder.mkdir(parents=True, exist_ok=True)
    ds.to_netcdf(folder / "sweep.nc", engine="h5netcdf")
    return folder
