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


# ----------------------------------------------------------------------------- repeated rows
def test_exact_repeats_are_counted_once():
    """A copied row is not a new measurement: the ± values stay those of the distinct
    points (before, 10 copied rows shrank them as if they were new data)."""
    d = _measured(0)
    first = calibrate_friction(d, SETUP)
    rep = np.r_[np.arange(len(d)), np.arange(10)]
    copied = FrictionData(
        d.entrainment_speed[rep], d.sliding_speed[rep], d.load[rep], d.friction_coefficient[rep]
    )
    cal = calibrate_friction(copied, SETUP)
    assert cal.n_points == len(d)
    for name in TRUTH:
        assert cal.std[name] == pytest.approx(first.std[name], rel=1e-6)
        assert cal.values[name] == pytest.approx(first.values[name], rel=1e-6)
    (warning,) = cal.warnings
    assert "10 measured point(s) repeat an earlier one exactly (points 29, 30" in warning
    # a repeated measurement (same conditions, another μ) is data: kept
    again = FrictionData(
        d.entrainment_speed[rep],
        d.sliding_speed[rep],
        d.load[rep],
        np.r_[d.friction_coefficient, d.friction_coefficient[:10] + 1e-4],
    )
    assert calibrate_friction(again, SETUP).n_points == len(d) + 10


def test_too_few_distinct_points():
    with pytest.raises(InputError, match="only 2 distinct measured points"):
        calibrate_friction(
            FrictionData([1.0, 1.0, 2.0], [0.1] * 3, [1e5] * 3, [0.05] * 3),
            SETUP,
            free=("boundary_shear_coefficient",),
        )


# ----------------------------------------------------------------------------- wrong units
def _stribeck(lo, hi):
    """A Stribeck curve (slide-to-roll 0.2) from u_e = lo to hi and a traction curve at hi,
    measured with the true viscosity of SETUP (0.02 Pa·s)."""
    ue = np.r_[np.geomspace(lo, hi, 14), np.full(14, hi)]
    us = np.r_[0.2 * ue[:14], np.geomspace(hi / 1000, 2 * hi, 14)]
    return _measured(0, ue, us, np.full(ue.size, 2e5))


def _with_viscosity(mu0):
    from dataclasses import replace

    return replace(SETUP, lubricant=Lubricant(mu0, 2e-8))


RHEOLOGY = {"eyring_stress": 3e6, "limiting_shear_coefficient": 0.025}


def test_viscosity_in_mpas_given_as_pas_is_named():
    """20 (mPa·s) given as Pa·s: the film is ~125× too thick and ς came out 5.6× too large
    with "converged". The measured friction keeps rising towards low speed where these
    inputs put the contact in full film, so the model cannot follow the Stribeck curve."""
    d = _stribeck(1e-3, 0.2)
    kw = {"free": ("boundary_shear_coefficient",), "fixed": RHEOLOGY}
    right = calibrate_friction(d, _with_viscosity(0.02), **kw)
    assert right.converged, right.message
    wrong = calibrate_friction(d, _with_viscosity(20.0), **kw)
    assert not wrong.converged
    msg = wrong.message
    assert "viscosity 20 Pa·s is probably 1000× too high" in msg, msg
    assert "with 0.02 Pa·s" in msg and "mPa·s" in msg
    assert "boundary_shear_coefficient = 0.6" in msg  # the implausible value is shown


def test_wrong_viscosity_flagged_when_fitting_rheology_too():
    """All three default parameters free, a Stribeck curve at low speed: before, ς came
    out 3× too large and the fit said converged."""
    d = _stribeck(1e-5, 0.01)
    assert calibrate_friction(d, _with_viscosity(0.02)).converged
    wrong = calibrate_friction(d, _with_viscosity(20.0))
    assert not wrong.converged
    assert "viscosity" in wrong.message and "Pa·s" in wrong.message


# ----------------------------------------------------------------------------- the data file
def _csv_text(d, sep=",", decimal="."):
    lines = [
        "# twin disc, 90 °C",
        sep.join(("entrainment_speed", "slide_roll_ratio", "friction_coefficient")),
    ]
    for a, b, c in zip(d.entrainment_speed, d.sliding_speed, d.friction_coefficient, strict=True):
        lines.append(sep.join(f"{v:.9g}".replace(".", decimal) for v in (a, b / a, c)))
    return "\n".join(lines) + "\n"


def _fit_json(path, *extra):
    import json

    r = CliRunner().invoke(app, ["calibrate", str(path), *ARGS, "--json", *extra])
    return r, (json.loads(r.stdout) if r.exit_code == 0 else None)


@pytest.mark.parametrize(
    "encode, note",
    [
        (lambda t: t.encode("cp1252"), "read as Windows-1252"),
        (lambda t: t.encode("latin-1"), "read as Windows-1252"),
        (lambda t: t.encode("utf-16"), None),
        (lambda t: b"\xef\xbb\xbf" + t.encode("utf-8"), None),  # Excel "CSV UTF-8"
        (lambda t: t.replace("\n", "\r\n").encode("utf-8"), None),
    ],
    ids=["cp1252", "latin-1", "utf-16", "utf-8-bom", "crlf"],
)
def test_cli_reads_data_as_spreadsheets_save_it(tmp_path, encode, note):
    """The same points in other encodings give the same fit (the UTF-8 file is the
    reference); a guessed code page is noted. Before, the BOM was a missing column and
    the others were not UTF-8."""
    d = _measured(0)
    ref = tmp_path / "utf8.csv"
    ref.write_text(_csv_text(d), encoding="utf-8")
    other = tmp_path / "other.csv"
    other.write_bytes(encode(_csv_text(d)))
    _, want = _fit_json(ref)
    r, got = _fit_json(other)
    assert r.exit_code == 0, r.output
    assert got["values"] == want["values"]
    guessed = [w for w in got["warnings"] if "read as" in w]
    if note is None:
        assert guessed == []
    else:
        assert len(guessed) == 1 and note in guessed[0]


def test_cli_semicolons_with_decimal_commas(tmp_path):
    d = _measured(0)
    ref = tmp_path / "ref.csv"
    ref.write_text(_csv_text(d))
    semi = tmp_path / "semi.csv"
    semi.write_text(_csv_text(d, sep=";", decimal=","))
    assert _fit_json(semi)[1]["values"] == _fit_json(ref)[1]["values"]


def test_cli_decimal_commas_in_a_comma_separated_file_are_refused(tmp_path):
    """Before, '0,002,0,2,0,0302' was cut to its first three fields without a word."""
    bad = tmp_path / "comma.csv"
    bad.write_text(_csv_text(_measured(0), decimal=","))
    r = CliRunner().invoke(app, ["calibrate", str(bad), *ARGS])
    text = " ".join(r.output.split())
    assert r.exit_code == 2 and "Traceback" not in r.output
    assert "line 3: 6 fields, but the header has 3 columns" in text
    assert "decimal commas" in text and "';'" in text


@pytest.mark.timeout(60)
def test_cli_data_that_is_a_pipe_or_a_device_is_refused(tmp_path):
    import os
    from pathlib import Path

    cases = []
    if hasattr(os, "mkfifo"):
        os.mkfifo(tmp_path / "pipe.csv")
        cases.append((tmp_path / "pipe.csv", "named pipe"))
    if Path("/dev/zero").exists():
        cases.append((Path("/dev/zero"), "character device"))
    for path, what in cases:
        r = CliRunner().invoke(app, ["calibrate", str(path), *ARGS])
        assert r.exit_code == 2 and what in r.output and "DATA" in r.output, r.output


def test_cli_repeated_rows_are_noted(tmp_path):
    d = _measured(0)
    text = _csv_text(d)
    rows = text.splitlines()
    path = tmp_path / "dup.csv"
    path.write_text(text + "\n".join(rows[2:5]) + "\n")
    r, out = _fit_json(path)
    assert r.exit_code == 0, r.output
    assert out["n_points"] == len(d)
    assert any("3 measured point(s) repeat" in w for w in out["warnings"])


# ----------------------------------------------------------------------------- the TOML made
def test_cli_label_with_control_characters_is_refused(tmp_path):
    data = tmp_path / "m.csv"
    _write_csv(data, _measured(0))
    label = 'pair\n[numerics]\nn = 1\n"'
    r = CliRunner().invoke(app, ["calibrate", str(data), *ARGS, "--label", label])
    assert r.exit_code == 2 and "--label" in r.output and "Traceback" not in r.output


def test_toml_of_a_calibration_cannot_be_injected():
    """Text from the user (label, file name, message) stays inside comments and strings:
    the TOML parses to exactly the sections the calibration writes."""
    from tribodyn.cli.calibrate import calibration_toml

    cal = calibrate_friction(_measured(0), SETUP)
    evil = 'x\n[numerics]\nn = 1\n# "\r\n[[surface_sets]]\nname = "y'
    rough = {"asperity_density": 5e8, "rms": 3e-7, "summit_radius": 3e-4}
    text = calibration_toml(cal, evil, evil, rough, notes=[evil])
    doc = tomllib.loads(text)
    assert set(doc) == {"lubricant", "surface_sets"}
    (surface,) = doc["surface_sets"]
    assert set(surface) == {
        "name",
        "roughness",
        "boundary_shear_coefficient",
        "boundary_shear_strength",
    }
    SurfaceSetConfig(**surface)
    assert "from the Jacobian covariance s²(JᵀJ)⁻¹" in text  # how the ± is computed


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
