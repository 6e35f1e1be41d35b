"""One convention per quantity in every output (docs/conventions.md, *Output
conventions*): a change against the reference set is 100·(x/x_ref − 1) % (negative =
less) with the same value in the console, summary.json and the report, labelled as a
maximum or a cycle integral; one crank-angle clock per kind of result, stated; unique
coordinate labels. The expected numbers are recomputed from results.nc, not read from
the key under test."""

import io
import json
import re
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr
from rich.console import Console
from typer.testing import CliRunner

from tribodyn.cli import app


def _summary(folder: Path) -> dict:
    return json.loads((folder / "summary.json").read_text(encoding="utf-8"))


def _table(md: str, head: str) -> tuple[list[str], list[list[str]]]:
    """(header cells, rows of cells) of the first Markdown table whose header starts
    with ``head``."""
    lines = md.splitlines()
    i = next(k for k, line in enumerate(lines) if line.startswith(f"| {head}"))
    cells = [[c.strip() for c in line.strip().strip("|").split("|")] for line in lines[i:]]
    rows = []
    for row in cells[2:]:
        if len(row) != len(cells[0]):
            break
        rows.append(row)
    return cells[0], rows


def _pct(text: str) -> float:
    return float(text.replace("−", "-").replace("%", "").strip())


def _event_integral(ds, name: str, var: str) -> float:
    """∫ var dt over the loaded samples of the cam event (results.nc)."""
    i = [str(s) for s in ds["surface_set"].values].index(name)
    t = np.asarray(ds["ehl_time"].values if "ehl_time" in ds else ds["ehl_crank"].values)
    dt = np.gradient(t)
    on = ds["loaded"].values[i].astype(bool) & ds["in_event"].values.astype(bool)
    return float(np.nansum(np.where(on, ds[var].values[i], 0.0) * dt))


def test_boundary_friction_change_has_one_sign_and_value_everywhere(reduced_results):
    """The console table, report.md and summary.json give the same change of the
    boundary friction against the reference set, negative for the coatings that lower
    it, labelled as the cycle integral ∫F_b dt or the maximum."""
    from tribodyn.cli.run import summary_table

    s = _summary(reduced_results)
    ref = s["reference_set"]
    sets = s["surface_sets"]
    with xr.open_dataset(reduced_results / "results.nc", engine="h5netcdf") as ds:
        # the cycle integral from the traces (∝ ∫F_b dt: the ratio does not need dt's unit)
        integral = {n: _event_integral(ds, n, "boundary_friction") for n in sets}
    expect = {n: 100.0 * (integral[n] / integral[ref] - 1.0) for n in sets}
    wcc = s["roles"]["wcc"]
    assert expect[wcc] < -80  # WC-C lowers it: negative

    # console: the column is the cycle integral (not "of max F_b"), negative = less
    buf = Console(width=80, file=io.StringIO(), record=True)
    buf.print(summary_table(s, s["case"]))
    text = buf.export_text()
    assert "of max F_b" not in text
    assert "∫F_b dt" in text and "negative = less" in text
    for name, v in sets.items():
        row = next(x for x in text.splitlines() if x.strip().startswith(v["label"] + " "))
        assert f"{expect[name] + 0.0:+.1f}" in row.split(), (row, expect[name])

    # report: both changes in their labelled columns
    md = (reduced_results / "report.md").read_text(encoding="utf-8")
    head, rows = _table(md, "surface | min film")
    label = sets[ref]["label"]
    assert f"∫F_b dt vs {label}" in head and f"max F_b vs {label}" in head, head
    c_int, c_max = head.index(f"∫F_b dt vs {label}"), head.index(f"max F_b vs {label}")
    for row in rows:
        name = next(n for n, v in sets.items() if v["label"] == row[0])
        if name == ref:
            assert row[c_int] == row[c_max] == "reference"
            continue
        mx = 100.0 * (
            sets[name]["max_boundary_friction_N"] / sets[ref]["max_boundary_friction_N"] - 1
        )
        assert _pct(row[c_int]) == pytest.approx(expect[name], abs=0.051)
        assert _pct(row[c_max]) == pytest.approx(mx, abs=0.051)

    # summary.json: the same numbers with the same sign
    assert s["conventions"]["change_pct"].startswith("change against the reference set")
    for name, v in sets.items():
        assert v["boundary_friction_cycle_integral_change_pct"] == pytest.approx(
            expect[name], abs=0.05
        )
        mx = 100.0 * (v["max_boundary_friction_N"] / sets[ref]["max_boundary_friction_N"] - 1.0)
        assert v["max_boundary_friction_change_pct"] == pytest.approx(mx, rel=1e-9, abs=1e-9)
        e = 100.0 * (
            v["friction_energy_per_cycle_J"] / sets[ref]["friction_energy_per_cycle_J"] - 1.0
        )
        assert v["friction_energy_change_pct"] == pytest.approx(e, rel=1e-9, abs=1e-9)
        if v.get("coating_verdict"):  # the verdict's change is the same number
            assert v["coating_verdict"]["friction_energy_change_pct"] == pytest.approx(
                v["friction_energy_change_pct"], rel=1e-9
            )
    # the maximum and the cycle integral are different quantities, with different changes
    assert sets[wcc]["max_boundary_friction_change_pct"] != pytest.approx(
        sets[wcc]["boundary_friction_cycle_integral_change_pct"], abs=0.05
    )


def test_run_crank_angles_are_the_presented_cycle_everywhere(reduced_results):
    """The coating-integrity table quotes summary.json's crank angle, on the clock of
    results.nc (the presented cycle, 720–1440°), and says so."""
    s = _summary(reduced_results)
    md = (reduced_results / "report.md").read_text(encoding="utf-8")
    head, rows = _table(md, "surface | closest failure")
    col = next(k for k, h in enumerate(head) if h.startswith("crank"))
    with xr.open_dataset(reduced_results / "results.nc", engine="h5netcdf") as ds:
        ehl = ds["ehl_crank"].values
        first, last = float(ds["crank_angle"].values[0]), float(ds["crank_angle"].values[-1])
        long_names = [ds[k].attrs["long_name"] for k in ("crank_angle", "ehl_crank")]
    assert (first, last) == (720.0, 1440.0)
    for row in rows:
        name = next(n for n, v in s["surface_sets"].items() if v["label"] == row[0])
        w = s["surface_sets"][name]["stress_closest_failure"]
        assert first <= w["crank_deg"] <= last and np.isclose(ehl, w["crank_deg"]).any()
        assert float(row[col]) == pytest.approx(w["crank_deg"], abs=0.5), (row, w)
        assert "crank_in_cycle_deg" not in w  # one clock
    assert len(rows) == len(s["surface_sets"])
    # the clock is stated: table header, sentence, summary.json, netCDF attributes
    assert head[col] == "crank [°, 720–1440°]"
    worst = re.search(r"Closest to failure: .* at (\d+)° crank \(presented cycle 720–1440°\)", md)
    assert worst and first <= float(worst.group(1)) <= last
    assert s["presented_cycle_crank_deg"] == [first, last]
    assert "720–1440°" in s["conventions"]["crank_angle"]
    assert all("720–1440°" in n for n in long_names), long_names


def test_engine_valve_coordinate_is_unique(engine_results):
    from tribodyn.output.figures.engine import valve_labels

    with xr.open_dataset(engine_results / "results.nc", engine="h5netcdf") as ds:
        valves = [str(v) for v in ds["valve"].values]
        assert len(valves) == 16 and len(set(valves)) == len(valves), valves
        kinds = [str(v) for v in ds["valve_kind"].values]
        cyl = [int(v) for v in ds["valve_cylinder"].values]
        assert "cylinder 1" in ds["engine_crank"].attrs["long_name"]
        assert "0–720°" in ds["engine_crank"].attrs["long_name"]
    assert valves[:4] == ["intake1a", "intake1b", "exhaust1a", "exhaust1b"]
    assert kinds[:4] == ["intake", "intake", "exhaust", "exhaust"] and cyl[:4] == [1] * 4
    labels = valve_labels(valves)
    assert len(set(labels)) == len(labels)
    assert labels[:3] == ["cyl. 1 intake a", "cyl. 1 intake b", "cyl. 1 exhaust a"]


def test_engine_console_and_summary_give_the_change_with_the_run_sign(
    engine_results, tmp_path, monkeypatch
):
    """The engine command prints the change of friction energy against the reference
    set as the run does (negative = less), the value of summary.json."""
    import tribodyn.output.engine as out_engine
    import tribodyn.workflow.engine as wf_engine

    summ = _summary(engine_results)
    e = summ["engine"]
    ref = e["reference_set"]
    stub = SimpleNamespace(warnings=[], runtime_s=1.0)
    monkeypatch.setattr(wf_engine, "run_engine_study", lambda case, **kw: stub)
    monkeypatch.setattr(
        out_engine, "write_engine_results", lambda study, out, **kw: {"summary": summ}
    )
    r = CliRunner().invoke(
        app, ["engine", str(engine_results / "case.toml"), "-o", str(tmp_path / "e")]
    )
    assert r.exit_code == 0, r.output
    e0 = e["surface_sets"][ref]["engine_friction_energy_per_cycle_J"]
    for name, d in e["surface_sets"].items():
        expect = 100.0 * (d["engine_friction_energy_per_cycle_J"] / e0 - 1.0)
        if name == ref:
            continue
        line = next(x for x in r.output.splitlines() if x.strip().startswith(f"{name}:"))
        assert f"{expect:+.2f} % vs {ref}" in line, line
        assert d["friction_energy_change_pct"] == pytest.approx(expect, rel=1e-9)
    assert "negative = less" in " ".join(r.output.split())
    assert "friction_reduction_vs_uncoated_pct" not in json.dumps(summ)


def test_engine_jump_crank_angles_are_on_the_engine_clock(engine_results):
    e = _summary(engine_results)["engine"]
    for kind, j in e["valve_jump"].items():
        assert 0.0 <= j["max_separation_crank_deg"] < 720.0, kind
        for a, _ in j["contact_loss_crank_deg"]:
            assert 0.0 <= a < 720.0
        assert "cylinder 1" in j["crank_angle"], kind
    assert "cylinder 1" in e["conventions"]["crank_angle"]


def test_explorer_reads_old_and_new_sweep_changes():
    """The explorer's coating change is negative = less for a sweep.nc of either name."""
    from tribodyn.output.explorer_plots import coating_delta

    mep = np.array([[100.0, 98.0]])
    coords = {"speed_rpm": [3000.0], "surface_set": ["uncoated", "dlc"]}
    dims = ("speed_rpm", "surface_set")
    new = xr.Dataset(
        {
            "valvetrain_friction_mep_Pa": (dims, mep),
            "engine_friction_energy_change_pct": (dims, [[0.0, -2.0]]),
        },
        coords=coords,
    )
    old = xr.Dataset(
        {
            "valvetrain_friction_mep_Pa": (dims, mep),
            "engine_friction_reduction_vs_uncoated_pct": (dims, [[0.0, 2.0]]),
        },
        coords=coords,
    )
    for ds in (new, old):
        d = coating_delta(ds, "valvetrain_friction_mep_Pa", "uncoated")
        assert float(d.sel(surface_set="dlc")[0]) == pytest.approx(-2.0)
