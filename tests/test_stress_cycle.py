"""Strength keys of the case, and the stresses of the cycle study in summary.json,
results.nc and the sweep outputs (checked against the traces and independent sums)."""

import math

import numpy as np
import pytest

from tribodyn import InputError
from tribodyn.config import load_case
from tribodyn.config.build import build
from tribodyn.config.case import Case
from tribodyn.physics.strength import TYPICAL_STRENGTH, TYPICAL_WEAR_COEFFICIENT
from tribodyn.workflow.stress_study import MODE_PEAK
from tribodyn.workflow.sweep_point import SET_SCALARS


def _with(section: dict) -> dict:
    d = load_case().to_dict()
    d.update(section)
    return d


@pytest.mark.parametrize(
    ("section", "words"),
    [
        ({"strength": {"dlcx": {"hardness": 1e10}}}, ["strength.dlcx", "unknown material"]),
        ({"strength": {"dlc": {"hardness": -1.0}}}, ["strength.dlc.hardness", "Pa"]),
        ({"strength": {"dlc": {"hardnes": 1e10}}}, ["strength.dlc.hardnes", "hardness"]),
        ({"strength": {"dlc": {"wear_coefficient": 1.0}}}, ["wear_coefficient", "m³/(N m)"]),
        ({"stress": {"running_hours": 0.0}}, ["stress.running_hours", "h"]),
    ],
)
def test_bad_strength_keys_name_the_field(section, words):
    with pytest.raises(InputError) as e:
        Case.from_dict(_with(section))
    for w in words:
        assert w in str(e.value)


def test_strength_keys_override_the_typical_values_and_read_back():
    case = Case.from_dict(
        _with({"strength": {"dlc": {"tensile_strength": 1.2e9, "wear_coefficient": 2e-17}}})
    )
    built = build(case)
    sub, coat = built.set("dlc_1um").strengths["tappet"]
    assert coat.tensile_strength == 1.2e9
    assert coat.hardness == TYPICAL_STRENGTH["dlc"].hardness  # not given: typical
    assert "case [strength.dlc]" in coat.source
    assert sub == TYPICAL_STRENGTH["steel"]
    dlc, wcc = built.set("dlc_4um"), built.set("wcc_4um")
    assert (dlc.wear_coefficient, dlc.wear_source) == (2e-17, "case [strength.dlc]")
    # not given: the labelled assumption
    assert wcc.wear_coefficient == TYPICAL_WEAR_COEFFICIENT["wcc"]
    assert "assumed" in wcc.wear_source
    again = Case.from_toml_string(case.to_toml())
    assert again.strength_configs == case.strength_configs


@pytest.fixture(scope="module")
def light_study():
    from tribodyn.workflow.cycle import run_cycle_study

    d = load_case().to_dict()
    d["surface_sets"] = [d["surface_sets"][0], d["surface_sets"][2]]  # uncoated, dlc_4um
    d["stress"] = {"running_hours": 1000.0}
    case = Case.from_dict(d).updated(
        {
            "numerics.crank_step_deg": 4.0,
            "numerics.n": 128,
            "numerics.implicit_coupling": False,
            "numerics.cycles": 1,
            "numerics.output_step_deg": 1.0,
        }
    )
    return run_cycle_study(case, workers=1)


def test_closest_failure_is_the_smallest_factor_at_its_peak(light_study):
    from tribodyn.output.dataset import study_to_dataset

    study = light_study
    assert set(study.stresses) == {"uncoated", "dlc_4um"}
    summ = study.analyse().summary["surface_sets"]
    ds = study_to_dataset(study)
    crank = ds["ehl_crank"].values
    for name in ("uncoated", "dlc_4um"):
        e = summ[name]
        w = e["stress_closest_failure"]
        # the smallest finite factor over both bodies and all modes, from results.nc
        factors = {
            (b, m): float(ds[f"safety_factor_{b}_{m}"].sel(surface_set=name))
            for b in ("cam", "tappet")
            for m in MODE_PEAK
        }
        finite = {k: v for k, v in factors.items() if math.isfinite(v)}
        body, mode = min(finite, key=finite.get)
        assert (w["body"], w["mode"]) == (body, mode)
        assert w["safety_factor"] == pytest.approx(finite[(body, mode)], rel=1e-12)
        assert e["min_safety_factor"] == w["safety_factor"]
        # where and when: the peak of that mode's trace
        tr = ds[f"stress_{body}_{MODE_PEAK[mode]}"].sel(surface_set=name).values
        i = int(np.nanargmax(tr))
        assert w["stress_Pa"] == pytest.approx(tr[i], rel=1e-12)
        assert w["crank_deg"] == crank[i]
        base = f"stress_{body}_{MODE_PEAK[mode]}"
        assert w["x_m"] == float(ds[base + "_x"].sel(surface_set=name)[i])
        assert w["z_m"] == float(ds[base + "_z"].sel(surface_set=name)[i])
        for k in SET_SCALARS:  # every sweep output is in summary.json
            assert k in e
    # the tappet's substrate yield factor: Tabor's H/3 of steel over the trace maximum
    vm = ds["stress_tappet_max_von_mises_substrate"].sel(surface_set="dlc_4um").values
    y = TYPICAL_STRENGTH["steel"].hardness / 3.0
    assert summ["dlc_4um"]["safety_factor_substrate_yield"] == pytest.approx(
        y / np.nanmax(vm), rel=1e-12
    )
    assert ds["stress_tappet_max_interface_shear"].attrs["units"] == "Pa"
    # the uncoated tappet has no coating peaks
    assert np.all(np.isnan(ds["stress_tappet_max_interface_shear"].sel(surface_set="uncoated")))


def test_wear_per_cycle_and_hours_against_an_independent_sum(light_study):
    study = light_study
    e = study.analyse().summary["surface_sets"]["dlc_4um"]
    res, inp = study.set("dlc_4um"), study.inputs
    w = np.where(res.loaded, res.asperity_load, 0.0) / study.case.width  # N/m
    rate = np.nan_to_num(w) * np.abs(inp.sliding_speed)
    sliding_work = float(np.sum(0.5 * (rate[1:] + rate[:-1]) * np.diff(inp.time)))
    swept = float(study.dynamics.contact_offset.max() - study.dynamics.contact_offset.min())
    k = TYPICAL_WEAR_COEFFICIENT["dlc"]
    depth = k * sliding_work / swept
    assert e["wear_coefficient_m3_per_Nm"] == k and "assumed" in e["wear_coefficient_source"]
    assert e["wear_depth_per_cycle_m"] == pytest.approx(depth, rel=1e-12)
    cycles_per_hour = study.case.engine_speed / 2.0 * 60.0  # cam turns at half the crank
    assert e["hours_to_wear_through"] == pytest.approx(4e-6 / (depth * cycles_per_hour), rel=1e-9)
    assert e["wear_depth_after_running_hours_m"] == pytest.approx(
        depth * cycles_per_hour * 1000.0, rel=1e-9
    )
    assert e["worn_through_in_running_hours"] is False
    assert study.analyse().summary["surface_sets"]["uncoated"]["hours_to_wear_through"] is None


def test_stress_map_and_report_section(light_study, tmp_path):
    from tribodyn.output.dataset import study_to_dataset
    from tribodyn.output.figures.stress import NO_MAP, greatest_risk, stored_map, stress_maps
    from tribodyn.output.report_stress import stress_section

    study = light_study
    summ = study.analyse().summary
    ds = study_to_dataset(study)
    r = greatest_risk(ds, "dlc_4um")
    w = summ["surface_sets"]["dlc_4um"]["stress_closest_failure"]
    assert (r["body"], r["mode"], r["crank_deg"]) == (w["body"], w["mode"], w["crank_deg"])
    assert (r["safety_factor"], r["x_m"], r["z_m"]) == (w["safety_factor"], w["x_m"], w["z_m"])
    # the map's field, stored by the study in results.nc, has the recorded peak in the
    # substrate (below the 4 µm coating) and reaches 2.5 loaded half-widths around it
    x, z, vm, hc = stored_map(ds, "dlc_4um")
    assert r["body"] == "tappet" and hc == 4e-6
    assert vm.shape == (z.size, x.size) and np.all(np.isfinite(vm))
    assert x[0] < r["x_m"] < x[-1]
    assert np.nanmax(vm[z > hc]) == pytest.approx(
        float(ds["stress_tappet_max_von_mises_substrate"].sel(surface_set="dlc_4um")[r["index"]]),
        rel=0.03,
    )
    png = stress_maps(ds, tmp_path / "stress.png")
    assert png.stat().st_size > 10_000
    # a results.nc without the stored maps (written before they were stored): no figure,
    # and a clear reason when one is asked for
    old = ds.drop_vars([v for v in ds.data_vars if str(v).startswith("stress_map_")])
    assert greatest_risk(old, "dlc_4um") is None
    with pytest.raises(ValueError, match="no stored stress maps"):
        stress_maps(old, tmp_path / "old.png")
    assert NO_MAP.startswith("results.nc has no stored stress maps")
    lines = stress_section(summ)
    assert lines[0] == "## Coating integrity"
    est = lines.index("### Estimates outside their validity (not headline numbers)")
    rows = [ln for ln in lines[:est] if ln.startswith(("| uncoated", "| DLC 4 µm"))]
    assert len(rows) == 2 and rows[1].endswith(f"| {w['safety_factor']:.2f} |")
    assert any("Closest to failure" in ln for ln in lines)
    # wear rests on an assumed coefficient: only below the estimates heading, as a
    # range k/10 … 10 k around the value at k
    assert not any("hours to wear" in ln for ln in lines[:est])
    hrs = summ["surface_sets"]["dlc_4um"]["hours_to_wear_through"]
    wear = [ln for ln in lines[est:] if ln.startswith("| DLC 4 µm")]
    assert len(wear) == 1 and f"{hrs / 10:.3g} … {hrs * 10:.3g}" in wear[0]
    assert stress_section({"surface_sets": {"a": {"label": "a"}}}) == []


def test_disabled_stresses_are_not_computed(light_study):
    from tribodyn.config.build import build
    from tribodyn.workflow.cycle import _stress_task

    study = light_study
    off = study.case.updated({"stress.enabled": False})
    first = study.set("dlc_4um")
    assert _stress_task(build(off), "dlc_4um", study.inputs, first) is None
    on = _stress_task(build(study.case), "dlc_4um", study.inputs, first)
    assert on.safety_factors == study.stresses["dlc_4um"].safety_factors


def test_asperity_scale_estimate_in_summary_and_report(light_study):
    from tribodyn.output.report_stress import stress_section
    from tribodyn.physics.asperity_stress import micro_contact_estimate
    from tribodyn.physics.materials import reduced_modulus

    study = light_study
    summ = study.analyse().summary
    for name in ("uncoated", "dlc_4um"):
        a = summ["surface_sets"][name]["asperity_scale_estimate"]
        res = study.set(name)
        ok = res.loaded & res.converged
        i = int(np.nanargmin(np.where(ok, res.min_film, np.nan)))
        assert a["crank_deg"] == float(res.crank_angle[i])
        s = build(study.case).set(name).surface
        e_s = reduced_modulus(s.bodies, surface=True)
        ref = micro_contact_estimate(s.roughness, float(res.min_film[i]), e_s, 0.3)
        assert a["cam"]["max_von_mises_Pa"] == pytest.approx(ref.max_von_mises)
    assert (
        "radius_over_thickness"
        in summ["surface_sets"]["dlc_4um"]["asperity_scale_estimate"]["tappet"]
    )
    lines = stress_section(summ)
    assert sum(ln.startswith(("| cam | ", "| tappet | ")) for ln in lines) == 4
    # the paper's Table 4 summits (β ≈ σ) are far too sharp for Hertz: said so
    assert (
        summ["surface_sets"]["uncoated"]["asperity_scale_estimate"]["cam"]["radius_over_summit"]
        > 0.3
    )
    assert any("a/β > 0.3" in ln for ln in lines)
    # rows outside Hertz theory give no stress numbers
    beyond = [ln for ln in lines if ln.startswith("| cam | uncoated")]
    assert len(beyond) == 1 and "beyond Hertz" in beyond[0]
    vm = summ["surface_sets"]["uncoated"]["asperity_scale_estimate"]["cam"]["max_von_mises_Pa"]
    assert f"{vm * 1e-6:.0f}" not in beyond[0].split("|")[7]
