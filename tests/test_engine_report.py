"""The engine study's report: what an engineer asks first (friction, FMEP, coating
verdict) before the method; per-camshaft torques with the sums over the camshafts
named as sums; display names of the sets; interactive traces in report.html; unique
lobe labels in the figures."""

import json
import re

import numpy as np
import xarray as xr

from tribodyn.output.figures.engine import valve_labels


def test_engine_report_order_and_numbers(engine_results):
    md = (engine_results / "report.md").read_text(encoding="utf-8")
    heads = re.findall(r"^## (.+)$", md, flags=re.M)
    assert heads[0] == "Friction and coating verdict"
    assert heads.index("Camshaft torque per camshaft") < heads.index("Figures")
    assert heads.index("Figures") < heads.index("Method")
    summ = json.loads((engine_results / "summary.json").read_text())["engine"]
    d, ref = summ["surface_sets"]["dlc_4um"], summ["surface_sets"]["uncoated"]
    pct = 100 * (
        d["engine_friction_energy_per_cycle_J"] / ref["engine_friction_energy_per_cycle_J"] - 1
    )
    word = "lowers" if pct < 0 else "does not lower"
    assert f"**DLC 4 µm** {word} the valvetrain friction" in md
    assert f"{pct:+.2f} %".replace("-", "−") in md
    # each camshaft's peak drive torque is its own trace's, and the summed key is named
    with xr.open_dataset(engine_results / "results.nc") as ds:
        t = ds["camshaft_drive_torque"].values
        shafts = [str(c) for c in ds["camshaft"].values]
    for j, c in enumerate(shafts):
        peak = np.nanmax(np.abs(t[0, j]))
        assert re.search(rf"\| uncoated \| {c} \|[^\n]*\| {peak:.4g} N·m \|", md), c
    assert "`peak_camshaft_drive_torque_Nm` is the peak |drive torque| of the summed" in md
    assert f"uncoated {ref['peak_camshaft_drive_torque_Nm']:.4g} N·m" in md
    assert ref["peak_camshaft_drive_torque_Nm"] > max(np.nanmax(np.abs(t[0, j])) for j in (0, 1))
    assert "dlc_4um |" not in md.split("## Warnings")[0]  # display names, not set keys


def test_engine_report_html_is_self_contained_and_interactive(engine_results):
    page = (engine_results / "report.html").read_text(encoding="utf-8")
    assert "<h2>Interactive traces</h2>" in page
    assert page.index("Interactive traces") < page.index("<h2>Figures</h2>")
    assert "friction torque per camshaft" in page  # a figure title in the JSON
    assert not re.search(r"<script[^>]*\bsrc=|<link\b", page)
    assert page.count('src="data:image/png;base64,') == 2


def test_valve_labels_are_unique():
    valves = ["intake1", "intake1", "exhaust1", "exhaust1", "intake2", "intake2"]
    labels = valve_labels(valves)
    assert len(set(labels)) == len(labels)
    assert labels[:3] == ["cyl. 1 intake a", "cyl. 1 intake b", "cyl. 1 exhaust a"]
    assert valve_labels(["intake3"]) == ["cyl. 3 intake"]
