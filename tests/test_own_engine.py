"""An engine no paper describes, through ``tribodyn run``: its own cam table (7 mm lift,
160° event, ``;``-separated), a datasheet 0W-20 at 100 °C, engineering roughness
(ηβσ = 0.04), steel against DLC 2 µm, reduced numerics. The report is about that case;
camshaft torque, CSV and a self-contained HTML report are written; the torque's cycle
integral is the friction energy; plausibility checks name suspicious roughness."""

from __future__ import annotations

import base64
import csv
import json
import math
import re
import shutil
from html.parser import HTMLParser
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr
from typer.testing import CliRunner

from tribodyn.cli import app
from tribodyn.config import load_case
from tribodyn.config.build import build
from tribodyn.workflow.engineering import (
    camshaft_torque,
    compares_paper,
    cycle_integral,
    plausibility_warnings,
)

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"

#: ηβσ = 0.04 (Greenwood & Williamson 1966) with σ = 0.15 µm, β = 15 µm: a ground,
#: superfinished tappet and cam (combined σ of 0.1–0.2 µm).
ROUGHNESS = "{ asperity_density = 1.78e10, rms = 0.15e-6, summit_radius = 15e-6 }"

CASE = f"""
[case]
name = "bucket_0w20"
description = "Direct-acting bucket, own cam table, 0W-20 at 100 °C, steel vs DLC 2 µm"

[engine]
speed_rpm = 3000.0

[cam]
type = "table"
path = "bucket_lift.csv"
angle_unit = "deg"
lift_unit = "mm"
base_radius = 0.018
width = 0.010

[lubricant]
oil = "0W-20"
inlet_temperature_c = 100.0

[[surface_sets]]
name = "steel"
roughness = {ROUGHNESS}

[[surface_sets]]
name = "dlc_2um"
coating = "dlc"
coating_thickness = 2e-6
roughness = {ROUGHNESS}

[numerics]
crank_step_deg = 5.0
n = 128
coupling_iterations = 1
output_step_deg = 2.5
workers = 1
"""


def _write_case(folder: Path) -> Path:
    """The case file and its cam table: s = 7 mm (1 − u²)³, u = (θ − 180°)/80°, a C²
    lift over a 160° cam event, written as ``angle;lift`` rows."""
    ang = np.arange(-80.0, 80.001, 1.0)
    lift = 7.0 * (1.0 - (ang / 80.0) ** 2) ** 3
    rows = "\n".join(f"{a + 180:.1f};{s:.5f}" for a, s in zip(ang, lift))
    (folder / "bucket_lift.csv").write_text("cam angle (deg);lift (mm)\n" + rows + "\n")
    path = folder / "bucket.toml"
    path.write_text(CASE)
    return path


@pytest.fixture(scope="module")
def own_run(tmp_path_factory):
    """``tribodyn run`` of the own case (once for the module)."""
    folder = tmp_path_factory.mktemp("engine")
    case = _write_case(folder)
    out = folder / "results"
    r = CliRunner().invoke(app, ["run", str(case), "-o", str(out), "-q", "--figures"])
    assert r.exit_code == 0, r.output
    return out


def test_the_report_is_about_the_case(own_run):
    text = (own_run / "report.md").read_text()
    assert text.startswith("# tribodyn report — bucket_0w20")
    prose = text.split("## Case as run")[0]  # the case file lists the default materials
    for paper_word in ("paper's claims", "Table 4", "paper Fig", "Winer", "+41", "WC-C"):
        assert paper_word not in prose, paper_word
    # the oil as used, the cam table, the surfaces
    assert "Oil as used (0W-20) at 100 °C inlet" in text
    oil = json.loads((own_run / "summary.json").read_text())["lubricant"]
    assert oil["inlet_temperature_C"] == 100.0
    assert f"μ₀ = {oil['viscosity_Pa_s']:.4g} Pa s" in text
    assert f"α = {oil['pressure_viscosity_1_Pa']:.4g} 1/Pa" in text
    assert f"ρ₀ = {oil['density_kg_m3']:.4g} kg/m³" in text
    assert "bucket_lift.csv" in text and "DLC 2 µm" in text
    assert "## Camshaft torque and contact pressure" in text
    assert "## Single contact at the cam nose" in text
    # figures named by content; the paper's Figs. 5/6 (its conditions, its DLC 4 µm) absent
    names = {p.name for p in own_run.glob("*.png")}
    assert not [n for n in names if re.match(r"fig\d\d_", n)]
    assert {"camshaft_torque.png", "contact_pressure.png", "cam_kinematics.png"} <= names
    assert "spring_surge.png" in names
    assert not {"dry_pressure.png", "ehl_pressure_film.png"} & names
    for n in names:
        assert f"]({n})" in text


def test_results_hold_the_engineering_outputs_with_units(own_run):
    with xr.open_dataset(own_run / "results.nc", engine="h5netcdf") as ds:
        for name in ("camshaft_friction_torque", "camshaft_drive_torque"):
            assert ds[name].attrs["units"] == "N m"
            assert ds[name].dims == ("surface_set", "ehl_crank")
            assert ds[name].attrs["long_name"]
        assert ds["hertz_pressure"].attrs["units"] == "Pa"
        assert float(ds["oil_inlet_temperature"]) == 100.0
        assert ds["oil_viscosity"].attrs["units"] == "Pa s"
        assert {"kinematic_lift", "table_lift", "table_fit_residual", "surge_frequency"} <= set(
            ds.data_vars
        )
        # the table's points are reproduced by the fit to far better than a µm
        assert float(np.abs(ds["table_fit_residual"]).max()) < 1e-6
        assert float(ds["table_lift"].max()) == pytest.approx(7e-3, rel=1e-6)
    summ = json.loads((own_run / "summary.json").read_text())
    for v in summ["surface_sets"].values():
        assert v["mean_friction_torque_Nm"] > 0
        assert v["max_hertz_pressure_Pa"] > 1e8
    assert summ["compare_paper"] is False


def test_friction_torque_integral_is_the_friction_energy(own_run):
    """∮T_f dθ over the cam revolution (torque trace) equals the friction energy per cycle
    integrated over time from the friction power (viscous + boundary)·|u_s| (1 %)."""
    summ = json.loads((own_run / "summary.json").read_text())
    with xr.open_dataset(own_run / "results.nc", engine="h5netcdf") as ds:
        crank = ds["ehl_crank"].values
        for k, name in enumerate(ds["surface_set"].values):
            tf = ds["camshaft_friction_torque"].values[k]
            e_torque = cycle_integral(tf, crank)
            e_power = summ["surface_sets"][str(name)]["friction_energy_per_cycle_J"]
            assert e_power > 0.05
            assert e_torque == pytest.approx(e_power, rel=0.01)
            # and the mean friction torque is that energy per radian
            mean = summ["surface_sets"][str(name)]["mean_friction_torque_Nm"]
            assert mean == pytest.approx(e_power / (2 * math.pi), rel=0.01)


def test_csv_traces_and_self_contained_html(own_run):
    with open(own_run / "traces.csv", newline="") as f:
        rows = list(csv.reader(f))
    head = rows[0]
    assert head[0] == "crank_angle [deg]"
    assert "steel:camshaft_friction_torque [N m]" in head
    assert "dlc_2um:camshaft_drive_torque [N m]" in head
    with xr.open_dataset(own_run / "results.nc", engine="h5netcdf") as ds:
        assert len(rows) - 1 == ds.sizes["ehl_crank"]
        k = head.index("dlc_2um:camshaft_drive_torque [N m]")
        col = np.array([float(r[k]) if r[k] else np.nan for r in rows[1:]])
        assert np.allclose(col, ds["camshaft_drive_torque"].values[1], rtol=1e-8)
    assert (own_run / "dynamics.csv").read_text().startswith("crank_angle [deg],")
    _check_html(own_run / "report.html", {p.name for p in own_run.glob("*.png")})


class _Refs(HTMLParser):
    def __init__(self):
        super().__init__()
        self.images: list[str] = []
        self.refs: list[tuple[str, str, str]] = []

    def handle_starttag(self, tag, attrs):
        for k, v in attrs:
            if k in ("src", "href", "srcset", "data", "action", "poster") and v:
                self.refs.append((tag, k, v))
        if tag == "img":
            self.images.append(dict(attrs).get("src") or "")
        if tag in ("link", "iframe", "object", "embed"):
            self.refs.append((tag, "tag", ""))
        # inline scripts (the interactive traces) are part of the page; one with a
        # src would load from elsewhere and is caught by the attributes above


def _check_html(path: Path, figures: set[str]) -> None:
    """Every figure embedded as a PNG data URI; nothing loaded from anywhere else."""
    text = path.read_text(encoding="utf-8")
    p = _Refs()
    p.feed(text)
    assert len(p.images) == len(figures) > 0
    for src in p.images:
        assert src.startswith("data:image/png;base64,")
        assert base64.b64decode(src.split(",", 1)[1])[:8] == PNG_MAGIC
    external = [r for r in p.refs if not (r[0] == "img" and r[2].startswith("data:"))]
    assert external == [], external
    styles = " ".join(re.findall(r"<style[^>]*>(.*?)</style>", text, flags=re.S))
    assert not re.search(r"url\(|@import|https?://", styles)  # the CSS loads nothing


def test_export_writes_the_same_files_again(own_run, tmp_path):
    """``tribodyn export`` of a result folder rebuilds the CSV and HTML byte for byte."""
    moved = tmp_path / "shared"
    shutil.copytree(own_run, moved)
    for n in ("traces.csv", "dynamics.csv", "report.html"):
        (moved / n).unlink()
    r = CliRunner().invoke(app, ["export", str(moved)])
    assert r.exit_code == 0, r.output
    for n in ("traces.csv", "dynamics.csv", "report.html"):
        assert (moved / n).read_bytes() == (own_run / n).read_bytes(), n
    (moved / "traces.csv").write_text("the user's own")  # never replaced
    r = CliRunner().invoke(app, ["export", str(moved)])
    assert r.exit_code == 2 and "traces.csv" in r.output
    assert (moved / "traces.csv").read_text() == "the user's own"


def test_a_moved_result_folder_refers_to_its_own_cam_table(own_run, tmp_path):
    moved = tmp_path / "elsewhere"
    shutil.copytree(own_run, moved)
    case = load_case(moved / "case.toml")
    assert case.cam_table_path == moved / "inputs" / "bucket_lift.csv"
    assert build(case).cam.max_lift == pytest.approx(7e-3, rel=1e-6)


# ----------------------------------------------------------------------------- torque
def test_conservative_train_does_no_net_work_per_cycle():
    """Frictionless, quasi-static with inertia: W = k(s + s₀) + m s''ω² is a function of
    the cam angle only through s and its derivatives, so ∮W s' dθ = ∮W ds = 0; the drive
    torque's cycle integral vanishes while its absolute integral does not."""
    cam = build(load_case()).cam
    theta = np.linspace(0.0, 2 * np.pi, 7201)
    s, s1, s2 = cam.derivatives(theta)
    omega = 2 * np.pi * 1500 / 60
    w = 33750.0 * (s + 250.0 / 33750.0) + 0.12 * s2 * omega**2
    t_f, t_d = camshaft_torque(w, np.zeros_like(s), s, s1, cam.base_radius, omega * (0.015 + s))
    crank = np.degrees(theta) * 2
    assert np.all(t_f == 0.0)
    gross = cycle_integral(np.abs(t_d), crank)
    assert gross > 1.0  # J: the train is driven and drives back
    assert abs(cycle_integral(t_d, crank)) < 1e-6 * gross


def test_friction_torque_is_signed_by_the_sliding_direction():
    t_f, t_d = camshaft_torque(
        np.array([100.0, 100.0]),
        np.array([2.0, 2.0]),
        np.array([0.0, 0.001]),
        np.array([0.0, 0.004]),
        0.015,
        np.array([5.0, -5.0]),
    )
    assert t_f == pytest.approx([2.0 * 0.015, -2.0 * 0.016])
    assert t_d == pytest.approx([0.03, 100.0 * 0.004 - 0.032])


# ----------------------------------------------------------------------------- trust
def test_paper_comparison_only_for_the_papers_case():
    assert compares_paper(load_case("andreou2023"))
    assert not compares_paper(load_case("example_table_cam"))
    assert compares_paper(load_case("example_table_cam"), True)


def _fake_study(case, lam, share):
    n = 3
    force = np.full(n, 500.0)
    res = SimpleNamespace(
        name=build(case).surface_sets[0].name,
        loaded=np.ones(n, bool),
        converged=np.ones(n, bool),
        lambda_ratio=np.full(n, lam),
        asperity_load=force * share,
    )
    inputs = SimpleNamespace(
        contact_force=force,
        width=case.width,
        radius=np.full(n, 0.005),
        crank_angle=np.arange(n) * 5.0,
    )
    return SimpleNamespace(case=case, inputs=inputs, sets=[res])


def test_roughness_outside_measured_surfaces_is_named():
    """The paper's Table 4 roughness (ηβσ 2e-4…2.3e-3) is flagged with what it affects
    and what to change; ηβσ = 0.04 is not."""
    paper = load_case("andreou2023")
    msgs = plausibility_warnings(_fake_study(paper, 2.0, 0.5))
    assert len(msgs) == 1 and "ηβσ" in msgs[0] and "outside 0.01–0.1" in msgs[0]
    assert "boundary friction" in msgs[0] and "check asperity_density" in msgs[0]
    ok = load_case("example_table_cam").updated(
        {"surface_sets": [{"name": "steel", "roughness": _rough()}]}
    )
    assert plausibility_warnings(_fake_study(ok, 2.0, 0.5)) == []


def _rough():
    return {"asperity_density": 1.78e10, "rms": 0.15e-6, "summit_radius": 15e-6}


def test_asperity_share_inconsistent_with_lambda_is_named():
    """λ = 0.02 with 0.8 % of the load on the asperities (the issue's example) is flagged;
    the same λ with most of the load on the asperities is not."""
    case = load_case("example_table_cam").updated(
        {"surface_sets": [{"name": "steel", "roughness": _rough()}]}
    )
    msgs = plausibility_warnings(_fake_study(case, 0.02, 0.008))
    assert len(msgs) == 1 and "λ = 0.02" in msgs[0] and "0.8 %" in msgs[0]
    assert plausibility_warnings(_fake_study(case, 0.02, 0.9)) == []


def test_asperity_share_reference_is_the_default_surface_law():
    """For a Greenwood–Tripp set the share to compare with is the default surface law's (a
    self-affine surface with the set's σ and the typical spectrum), not Greenwood–Tripp
    with any parameters: by hand p_a = E'_s Φ(0.22) of that law, p_mean = w/(2b)."""
    import math
    import re

    from tribodyn.config.measured_surface import default_spectrum
    from tribodyn.physics.materials import reduced_modulus
    from tribodyn.topography.load_separation import synthetic_load_separation

    paper = load_case("andreou2023")
    s = build(paper).surface_sets[0]
    msgs = [m for m in plausibility_warnings(_fake_study(paper, 0.22, 2.4e-4)) if "λ =" in m]
    assert len(msgs) == 1
    got = float(re.search(r"same σ carries ([0-9.e+-]+) %", msgs[0]).group(1))
    d = default_spectrum()
    e_s = reduced_modulus(s.bodies, surface=True)
    law = synthetic_load_separation(
        s.roughness.rms, d["hurst"], d["short_cutoff"], d["long_cutoff"], e_s, d["hardness"]
    )
    e = reduced_modulus(s.bodies)
    w = 500.0 / paper.width
    b = math.sqrt(8 * w * 0.005 / (math.pi * e))
    expect = min(100.0, 100 * e_s * float(law.pressure_ratio(0.22)[0]) * 2 * b / w)
    assert got == pytest.approx(expect, rel=0.05)
    assert "remove asperity_model" in msgs[0]
    # the paper's summits (σ/β = 0.6) are steep: no "smoother than ground steel" remark
    assert "smoother" not in msgs[0]


def test_smooth_greenwood_tripp_roughness_is_named_with_its_slope():
    """Typical Greenwood–Tripp parameters (ηβσ 0.04, σ/β 1e-3) at λ = 0.3 carrying what
    they carry: the warning names the RMS slope they imply (≈ 0.018, Nayak/McCool) and
    what to change; the same set with the surface law and most of the load on the
    asperities gives no warning."""
    gt = load_case("example_table_cam").updated(
        {
            "surface_sets": [
                {
                    "name": "steel",
                    "roughness": {
                        "asperity_density": 1e9,
                        "rms": 0.2e-6,
                        "summit_radius": 200e-6,
                    },
                    "asperity_model": "greenwood_tripp",
                }
            ]
        }
    )
    msgs = plausibility_warnings(_fake_study(gt, 0.3, 0.02))
    assert len(msgs) == 1 and "RMS slope of 0.018" in msgs[0]
    assert "remove asperity_model" in msgs[0]
    law = gt.updated({"surface_sets[0].asperity_model": "surface"})
    assert plausibility_warnings(_fake_study(law, 0.3, 0.9)) == []


def test_surface_law_sets_are_not_judged_by_greenwood_tripp_parameters():
    """ηβσ only matters to Greenwood–Tripp: the paper's Table 4 roughness under the
    surface law is not flagged for it."""
    paper = load_case("andreou2023").updated({"surface_sets[0].asperity_model": "surface"})
    msgs = plausibility_warnings(_fake_study(paper, 2.0, 0.5))
    assert msgs == []


def test_warmup_numerics_are_a_valid_case():
    """``tribodyn warmup`` (run by ``make run`` at installation) uses a valid case."""
    from tribodyn.cli.warmup import WARMUP_NUMERICS

    case = load_case().updated(WARMUP_NUMERICS)
    assert case.numerics.crank_step_deg == WARMUP_NUMERICS["numerics.crank_step_deg"]


@pytest.mark.parametrize(
    "text, advice",
    [
        (
            "film h_c = 1e-05 m is 0.002 R and 0.2 of the length over which it varies "
            "(ℓ = 5e-05 m): Reynolds' thin-film approximation needs h/ℓ ≪ 1",
            "light load",
        ),
        ("the Hertz half-width b = 0.2 R: half-space elasticity needs", "minimum radius"),
        (
            "the load-carrying zone reaches 0.3 R (Hertz b = 0.001 R), where the parabolic "
            "gap x²/(2R) falls short of the circle by 2.2 %",
            "long inlet",
        ),
        ("modified Reynolds number ρu_e h_c²/(μ₀ℓ) = 0.3: fluid inertia", "uncertain by Re*"),
        ("peak contact pressure 5 GPa exceeds 4 GPa: beyond the elastic limit", "beyond 4 GPa"),
        # before, the word "pressure" sent this to the 4 GPa advice
        ("pressure not negligible at the outlet (increase outlet)", "numerics.outlet"),
        ("truncated inlet carries an estimated 3% of the load", "numerics.inlet"),
    ],
)
def test_every_validity_warning_says_what_to_change(text, advice):
    """Each kind of the EHL validity checks (contact.ehl.validity) gets its own advice."""
    from tribodyn.workflow.cycle import _validity_advice

    assert advice in _validity_advice(text)


def test_the_papers_case_keeps_its_comparison(reduced_results):
    """The paper's case (reduced numerics, shared with other tests): the claims table,
    the numbered paper figures with the engineering ones, and every figure in the HTML."""
    text = (reduced_results / "report.md").read_text()
    assert "## The paper's claims beside tribodyn" in text and "(paper Fig. 9)" in text
    names = {p.name for p in reduced_results.glob("*.png")}
    assert {"fig05_dry_pressure.png", "fig06_ehl_pressure_film.png"} <= names
    assert {"fig23_camshaft_torque.png", "fig25_cam_kinematics.png"} <= names
    _check_html(reduced_results / "report.html", names)
