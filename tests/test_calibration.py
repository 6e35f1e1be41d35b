"""Calibration of boundary friction and rheology from measured friction (round trip)."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from tribodyn import InputError
from tribodyn.cli.app import app
from tribodyn.config.schema import LubricantConfig, SurfaceSetConfig
from tribodyn.physics.asperity import Roughness
from tribodyn.physics.lubricant import Lubricant
from tribodyn.workflow.calibration import (
    CalibrationSetup,
    FrictionData,
    calibrate_friction,
    model_friction,
)

SIGMA = 0.3e-6
BETA = SIGMA / 1e-3
SETUP = CalibrationSetup(
    radius=0.01,
    lubricant=Lubricant(0.02, 2e-8),
    roughness=Roughness(0.15 / (BETA * SIGMA), SIGMA, BETA),
)
# a Stribeck curve (slide-to-roll 0.2) and a traction curve at u_e = 1 m/s, w = 200 kN/m
UE = np.r_[np.geomspace(0.002, 2.0, 14), np.full(14, 1.0)]
US = np.r_[0.2 * UE[:14], np.geomspace(0.002, 2.0, 14)]
W = np.full(UE.size, 2e5)
TRUTH = {
    "boundary_shear_coefficient": 0.11,
    "eyring_stress": 3e6,
    "limiting_shear_coefficient": 0.025,
}
NOISE = 0.001


def _measured(seed, ue=UE, us=US, w=W):
    exact = model_friction(SETUP, FrictionData(ue, us, w, np.zeros(ue.size)), **TRUTH)
    rng = np.random.default_rng(seed)
    return FrictionData(ue, us, w, exact + rng.normal(0.0, NOISE, exact.size))


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_round_trip_within_stated_uncertainty(seed):
    cal = calibrate_friction(_measured(seed), SETUP)
    assert cal.converged, cal.message
    for name, true in TRUTH.items():
        sd = cal.std[name]
        assert 0.0 < sd < 0.2 * true  # a meaningful, finite uncertainty
        assert abs(cal.values[name] - true) <= 3.0 * sd, (name, cal.values[name], sd)
    # the residual matches the noise that was added
    assert cal.rms_residual == pytest.approx(NOISE, rel=0.35)


def test_uncertainty_scales_with_noise():
    d = _measured(5)
    exact = model_friction(SETUP, d, **TRUTH)
    noisy = FrictionData(
        d.entrainment_speed, d.sliding_speed, d.load, exact + 4 * (d.friction_coefficient - exact)
    )
    s1 = calibrate_friction(d, SETUP).std["eyring_stress"]
    s4 = calibrate_friction(noisy, SETUP).std["eyring_stress"]
    assert s4 / s1 == pytest.approx(4.0, rel=0.25)


def test_undetermined_parameter_is_reported():
    # full-film points only (λ ≫ 1): no asperity contact, ς has no effect on the data
    ue = np.geomspace(10.0, 20.0, 8)
    d = _measured(0, ue, 0.2 * ue, np.full(8, 2e5))
    cal = calibrate_friction(d, SETUP, free=("boundary_shear_coefficient", "eyring_stress"))
    assert not cal.converged
    assert not cal.std["boundary_shear_coefficient"] < cal.values["boundary_shear_coefficient"]
    assert "boundary_shear_coefficient" in cal.message and "fix it" in cal.message


def test_fixed_parameters_are_used():
    cal = calibrate_friction(
        _measured(0),
        SETUP,
        free=("boundary_shear_coefficient", "eyring_stress"),
        fixed={"limiting_shear_coefficient": 0.025},
    )
    assert cal.converged, cal.message
    assert cal.fixed == {"limiting_shear_coefficient": 0.025}
    assert abs(cal.values["eyring_stress"] - 3e6) <= 3 * cal.std["eyring_stress"]


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"free": ("mu",)}, "unknown parameter 'mu'"),
        ({"free": ("eyring_stress",), "fixed": {"eyring_stress": 1e6}}, "both free and fixed"),
        ({"free": ()}, "nothing to fit"),
        ({"fixed": {"limiting_shear_stress": -1.0}}, "limiting_shear_stress must lie in"),
    ],
)
def test_bad_calibration_input(kwargs, match):
    with pytest.raises(InputError, match=match):
        calibrate_friction(_measured(0), SETUP, **kwargs)


def test_bad_data():
    with pytest.raises(InputError, match="at least 3"):
        FrictionData([1.0], [0.1], [1e5], [0.05])
    with pytest.raises(InputError, match="friction_coefficient must lie in"):
        FrictionData([1.0] * 3, [0.1] * 3, [1e5] * 3, [0.05, 2.0, 0.05])


def _write_csv(path, d):
    lines = ["# synthetic", "entrainment_speed,slide_roll_ratio,friction_coefficient"]
    for a, b, c in zip(d.entrainment_speed, d.sliding_speed, d.friction_coefficient, strict=True):
        lines.append(f"{a:.9g},{b / a:.9g},{c:.9g}")
    path.write_text("\n".join(lines) + "\n")


ARGS = ["--radius", "0.01", "--load", "2e5", "--viscosity", "0.02", "--pressure-viscosity", "2e-8"]
# the synthetic data are Greenwood–Tripp's (SETUP): the fit asks for it
ARGS += ["--rms", "0.3e-6", "--asperity-model", "greenwood_tripp", "--roughness-parameter", "0.15"]


def test_cli_writes_case_sections(tmp_path):
    data = tmp_path / "m.csv"
    _write_csv(data, _measured(0))
    out = tmp_path / "fit.toml"
    r = CliRunner().invoke(app, ["calibrate", str(data), *ARGS, "-o", str(out)])
    assert r.exit_code == 0, r.output
    doc = tomllib.loads(out.read_text())
    lub = LubricantConfig(**doc["lubricant"])  # valid case-file keys
    assert lub.eyring_stress == pytest.approx(3e6, rel=0.1)
    (surface,) = doc["surface_sets"]
    SurfaceSetConfig(**surface)  # valid case-file keys
    assert surface["boundary_shear_strength"] == 0.0
    assert surface["boundary_shear_coefficient"] == pytest.approx(0.11, abs=0.03)
    assert "± " in out.read_text()
    # an existing file is never replaced
    before = out.read_text()
    r = CliRunner().invoke(app, ["calibrate", str(data), *ARGS, "-o", str(out)])
    assert r.exit_code == 2 and "exists" in r.output
    assert out.read_text() == before


def test_cli_bad_csv_is_a_clear_error(tmp_path):
    data = tmp_path / "bad.csv"
    data.write_text("speed,mu\n1,0.1\n")
    r = CliRunner().invoke(app, ["calibrate", str(data), *ARGS])
    assert r.exit_code == 2
    assert "entrainment_speed" in r.output and "Traceback" not in r.output


def test_cli_json_and_fix(tmp_path):
    import json

    data = tmp_path / "m.csv"
    _write_csv(data, _measured(1))
    r = CliRunner().invoke(
        app,
        [
            "calibrate",
            str(data),
            *ARGS,
            "--fit",
            "boundary_shear_coefficient,eyring_stress",
            "--fix",
            "limiting_shear_coefficient=0.025",
            "--json",
        ],
    )
    assert r.exit_code == 0, r.output
    out = json.loads(r.output)
    assert out["fixed"] == {"limiting_shear_coefficient": 0.025}
    assert set(out["values"]) == {"boundary_shear_coefficient", "eyring_stress"}
    r = CliRunner().invoke(app, ["calibrate", str(data), *ARGS, "--fix", "eyring_stress"])
    assert r.exit_code == 2 and "NAME=VALUE" in r.output


def test_bootstrap_agrees_with_the_linearised_uncertainty():
    d = _measured(0)
    a = calibrate_friction(d, SETUP, bootstrap=12, seed=1)
    b = calibrate_friction(d, SETUP, bootstrap=12, seed=1)
    assert a.bootstrap_std == b.bootstrap_std  # seeded
    for name in TRUTH:
        assert 0.5 <= a.bootstrap_std[name] / a.std[name] <= 2.0
    with pytest.raises(InputError, match="bootstrap"):
        calibrate_friction(d, SETUP, bootstrap=-1)


def test_per_point_radius_of_a_cam_trace(tmp_path):
    """A cam trace reduced to its contact conditions: R varies from point to point."""
    radius = np.linspace(0.004, 0.03, UE.size)
    base = FrictionData(UE, US, W, np.zeros(UE.size), radius)
    exact = model_friction(SETUP, base, **TRUTH)
    assert not np.allclose(exact, model_friction(SETUP, _measured(0), **TRUTH))
    rng = np.random.default_rng(3)
    d = FrictionData(UE, US, W, exact + rng.normal(0.0, NOISE, UE.size), radius)
    cal = calibrate_friction(d, SETUP)
    assert cal.converged, cal.message
    assert all(cal.within(TRUTH).values())
    with pytest.raises(InputError, match="radius must give"):
        FrictionData(UE, US, W, exact, radius[:-1])
    # the CLI reads the radius column instead of --radius
    path = tmp_path / "trace.csv"
    rows = ["entrainment_speed,sliding_speed,load,radius,friction_coefficient"]
    rows += [
        ",".join(f"{v:.9g}" for v in row) for row in zip(UE, US, W, radius, d.friction_coefficient)
    ]
    path.write_text("\n".join(rows) + "\n")
    args = ["--viscosity", "0.02", "--pressure-viscosity", "2e-8", "--rms", "0.3e-6"]
    args += ["--asperity-model", "greenwood_tripp", "--roughness-parameter", "0.15", "--json"]
    r = CliRunner().invoke(app, ["calibrate", str(path), *args])
    assert r.exit_code == 0, r.output


def _guide_command() -> list[str]:
    """The `tribodyn calibrate` command of the calibration guide, as arguments."""
    import re
    import shlex
    from pathlib import Path

    text = (Path(__file__).parents[1] / "docs" / "guides" / "calibration.md").read_text()
    block = re.search(r"```bash\n(tribodyn calibrate .*?)```", text, re.S)
    assert block, "the guide has a tribodyn calibrate command"
    args = shlex.split(block.group(1).replace("\\\n", " "))
    assert args[:2] == ["tribodyn", "calibrate"]
    if "-o" in args:  # the test writes nothing
        i = args.index("-o")
        del args[i : i + 2]
    return args[1:]


def test_guide_command_fits_the_bundled_example_with_the_cli_defaults():
    """The guide's command, on the bundled example data (synthetic: the forward model at
    ς 0.11, τ_E 3 MPa, Λ 0.03 with the default asperity law, noise 0.001, as its header
    says), converges with the CLI's defaults and finds those values within 3σ."""
    import json

    args = _guide_command()
    assert args[1] == "example_friction.csv"
    r = CliRunner().invoke(app, [*args, "--json"])
    assert r.exit_code == 0, r.output
    out = json.loads(r.output)
    assert out["converged"], out["message"]
    stated = {
        "boundary_shear_coefficient": 0.11,
        "eyring_stress": 3e6,
        "limiting_shear_coefficient": 0.03,
    }
    for name, value in stated.items():
        assert abs(out["values"][name] - value) <= 3 * out["std"][name], name
    # the same data under Greenwood–Tripp's typical parameters cannot reach the plateau
    r = CliRunner().invoke(app, [*args, "--asperity-model", "greenwood_tripp", "--json"])
    assert r.exit_code == 1 and not json.loads(r.output.split("\nwarning")[0])["converged"]


def test_bundled_example_is_the_stated_model_plus_small_noise():
    """Each row of the bundled example lies within 5 noise σ (0.005) of the forward
    model at the values its header states (so the file and its header agree)."""
    from tribodyn.cli.calibrate import _surface_law, bundled_data, read_friction_csv
    from tribodyn.physics.materials import Material

    d = read_friction_csv(bundled_data(Path("example_friction.csv")), 2e5)
    steel = Material(210e9, 0.3)
    sigma = 0.1e-6
    rough = _surface_law(Roughness(0.04 / (sigma * 1e-4), sigma, 1e-4), (steel, steel))
    setup = CalibrationSetup(0.01, Lubricant(0.02, 2e-8), rough, materials=(steel, steel))
    mu = model_friction(
        setup,
        d,
        boundary_shear_coefficient=0.11,
        eyring_stress=3e6,
        limiting_shear_coefficient=0.03,
    )
    assert d.friction_coefficient.size == 28
    assert np.max(np.abs(d.friction_coefficient - mu)) < 0.005
