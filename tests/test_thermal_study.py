"""Thermal EHL in the command line and the main job: ``tribodyn contact --thermal`` and
``tribodyn run`` on a reduced thermal variant of the paper case."""

import json

import pytest
import xarray as xr
from typer.testing import CliRunner

from test_variables import assert_registered
from tribodyn.cli import app
from tribodyn.config import Case, load_case

runner = CliRunner()
POINT = ("contact", "--load", "2400", "--radius", "0.01", "--ue", "2", "--us", "2")


def test_contact_thermal_json():
    r = runner.invoke(
        app,
        [
            *POINT,
            "--thermal",
            "--oil",
            "5W-30",
            "--inlet-temperature",
            "90",
            "--coating-material",
            "dlc",
            "--coating-thickness",
            "4e-6",
            "--json",
        ],
    )
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    assert out["thermal"] and out["converged"] and out["oil"] == "5W-30"
    assert out["inlet_temperature_K"] == pytest.approx(363.15)
    assert out["max_temperature_K"] > out["inlet_temperature_K"] + 5.0
    assert out["max_surface_temperature_tappet_K"] > out["max_surface_temperature_cam_K"]
    assert out["viscous_friction_N"] < out["isothermal_viscous_friction_N"]
    assert out["central_film_m"] <= out["isothermal_central_film_m"] * 1.001


@pytest.mark.parametrize(
    "args, name",
    [
        (("--thermal",), "--thermal needs an oil"),
        (("--thermal", "--oil", "5W-30"), "--inlet-temperature"),
        (("--thermal", "--oil", "SAE90", "--inlet-temperature", "90"), "--oil must be one of"),
        (("--thermal", "--oil", "5W-30", "--inlet-temperature", "900"), "--inlet-temperature"),
        (
            ("--thermal", "--oil", "5W-30", "--inlet-temperature", "90", "--viscosity", "0.01"),
            "--viscosity: not with --thermal",
        ),
        (
            (
                "--thermal",
                "--oil",
                "5W-30",
                "--inlet-temperature",
                "90",
                "--coating",
                "185e9,0.3,4e-6",
            ),
            "coating needs a material",
        ),
    ],
)
def test_contact_thermal_bad_input_exits_2(args, name):
    r = runner.invoke(app, [*POINT, *args])
    assert r.exit_code == 2, r.output
    assert name in r.output and "Traceback" not in r.output


@pytest.fixture(scope="module")
def thermal_run(tmp_path_factory):
    """The thermal variant with the uncoated and DLC 4 µm tappets at reduced resolution:
    5° crank steps, a fixed 256-node EHL grid, a coarse thermal grid, staggered
    coupling, one worker."""
    d = load_case("andreou2023_thermal").to_dict()
    d["surface_sets"] = [d["surface_sets"][0], d["surface_sets"][2]]
    case = Case.from_dict(d).updated(
        {
            "numerics.crank_step_deg": 5.0,
            "numerics.n": 256,
            "numerics.output_step_deg": 1.0,
            "numerics.workers": 1,
            "numerics.thermal_x_nodes": 48,
            "numerics.thermal_solid_nodes": 8,
            "numerics.thermal_film_nodes": 5,
            "numerics.thermal_iterations": 1,
        }
    )
    path = tmp_path_factory.mktemp("case") / "thermal.toml"
    case.write_toml(path)
    out = tmp_path_factory.mktemp("run") / "results"
    # the single-contact coating studies (Figs. 5, 6, nose sensitivity) are the paper
    # case's and tested there; skipped here to keep the test short
    from tribodyn.workflow import cycle

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(cycle, "coating_studies_task", lambda *a: ([], None, None, None))
        r = runner.invoke(app, ["run", str(path), "-o", str(out), "--quiet", "--figures"])
    assert r.exit_code == 0, r.output
    return out


def test_thermal_run_outputs(thermal_run):
    s = json.loads((thermal_run / "summary.json").read_text())
    th = s["thermal"]
    assert th["inlet_temperature_K"] == pytest.approx(363.15)
    unc, dlc = th["surface_sets"]["uncoated"], th["surface_sets"]["dlc_4um"]
    for v in (unc, dlc):
        assert v["samples"] > 10
        assert v["max_temperature_K"] > 363.15 + 5.0
        assert v["viscous_friction_energy_thermal_J"] < v["viscous_friction_energy_isothermal_J"]
    # the insulating DLC layer: hotter tappet surface, less viscous friction than steel
    assert dlc["max_surface_temperature_tappet_K"] > unc["max_surface_temperature_tappet_K"] + 5
    eff = th["coating_thermal_effect"]["dlc_4um"]
    assert eff["viscous_energy_thermal_effect_pct"] < -1.0
    # (that the thermal march counts its steps outside the model's validity as the
    # isothermal one does, which the study reports alike, is
    # test_cycle_driver.test_thermal_march_reports_validity_warnings: this reduced case
    # has none since the contact-size check flags the parabolic gap's error, not 0.1 R)
    assert abs(eff["viscous_energy_vs_reference_isothermal_pct"]) < 2.0
    ds = xr.open_dataset(thermal_run / "results.nc", engine="h5netcdf")
    for v in (
        "max_temperature",
        "surface_temperature_tappet",
        "mid_film_temperature",
        "central_film_isothermal",
        "viscous_friction_isothermal",
    ):
        assert v in ds and ds[v].attrs["units"]
    assert ds.attrs["thermal"] == 1
    assert_registered(ds)  # every variable's units and description from the registry
    ds.close()
    report = (thermal_run / "report.md").read_text()
    assert "## Thermal EHL" in report and "Coatings' thermal effect" in report
    for f in ("fig21_temperatures.png", "fig22_thermal_vs_isothermal.png"):
        assert (thermal_run / f).stat().st_size > 10_000
        assert f"]({f})" in report
