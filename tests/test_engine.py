"""A whole engine's valvetrain: lobe phasing, the energy identity, lobes solved once,
auxiliary friction beside the contact, the case's [engine] layout."""

import math

import numpy as np
import pytest

from conftest import ENGINE, REDUCED
from test_variables import assert_registered
from tribodyn import InputError
from tribodyn.config import load_case
from tribodyn.config.build import build
from tribodyn.workflow.engine import place_trace, run_engine_study
from tribodyn.workflow.engineering import cycle_integral


def _case(**more):
    base = load_case()
    sets = base.to_dict()["surface_sets"][:2]  # uncoated and DLC 1 µm
    return base.updated({**REDUCED, "surface_sets": sets, **ENGINE, **more})


@pytest.fixture(scope="module")
def engine():
    return run_engine_study(_case(), workers=1)


def test_identical_lobes_repeat_every_180_deg_of_crank(engine):
    crank = engine.crank_angle
    i180 = int(np.flatnonzero(np.isclose(crank, 180.0))[0])
    i90 = int(np.flatnonzero(np.isclose(crank, 90.0))[0])
    for j, shaft in enumerate(engine.camshafts):
        for t in (engine.friction_torque[0, j], engine.drive_torque[0, j]):
            scale = np.max(np.abs(t))
            assert scale > 0
            assert np.max(np.abs(t[i180:] - t[: t.size - i180])) < 1e-9 * scale, shaft
            # not a trivial constant: a quarter of that period is another torque
            assert np.max(np.abs(t[i90:] - t[: t.size - i90])) > 0.05 * scale, shaft


def test_lobe_of_cylinder_3_is_cylinder_1_shifted_by_its_firing_interval(engine):
    names = [f"{v['kind']}{v['cylinder']}" for v in engine.valves]
    t1 = engine.lobe_friction_torque[0, names.index("intake1")]
    t3 = engine.lobe_friction_torque[0, names.index("intake3")]  # fires 180° after 1
    k = int(np.flatnonzero(np.isclose(engine.crank_angle, 180.0))[0])
    assert np.allclose(t3[k:], t1[: t1.size - k], rtol=0, atol=1e-12 * np.abs(t1).max())
    assert not np.allclose(t3, t1)


def test_cycle_integral_of_torque_equals_summed_valve_energy(engine):
    for i, name in enumerate(engine.set_names):
        total = cycle_integral(engine.friction_torque[i].sum(axis=0), engine.crank_angle)
        valves = sum(engine.lobes[v["kind"]].energy[name] for v in engine.valves)
        assert len(engine.valves) == 16
        assert total == pytest.approx(valves, rel=0.01)
        # and the single-valve study's own energy (its engineering outputs)
        study = engine.lobes["intake"].study
        e1 = study.engineering_outputs().scalars[name]["friction_energy_per_cycle_from_torque_J"]
        assert total == pytest.approx(16 * e1, rel=0.01)


def test_identical_lobes_are_solved_once(engine):
    assert engine.lobes["intake"].study is engine.lobes["exhaust"].study
    assert list(engine.timings) == ["intake_study_s"]


def test_summary_fmep_and_parts(engine):
    s = engine.summary()
    for kind in ("intake", "exhaust"):  # the paper's spring holds the train at 3000 rpm
        jump = s["valve_jump"][kind]
        assert jump["jump"] is False and jump["contact_loss_crank_deg"] == []
        assert jump["max_separation_m"] < 1e-5  # the contact's compliance only
    for d in s["surface_sets"].values():
        e = d["engine_friction_energy_per_cycle_J"]
        assert e == pytest.approx(sum(d["friction_energy_per_cycle_J"].values()))
        assert d["valvetrain_friction_mep_Pa"] == pytest.approx(e / 0.0016)
        assert d["mean_friction_power_W"] == pytest.approx(e * engine.cam_speed / (2 * math.pi))
        assert all(v > 0 for v in d["friction_energy_per_cycle_J"].values())
    ds = engine.to_dataset()
    for k in ("camshaft_friction_torque", "camshaft_drive_torque", "camshaft_friction_power"):
        assert ds[k].attrs["units"] in ("N m", "W") and ds[k].attrs["long_name"]
        assert ds[k].dims == ("engine_set", "camshaft", "engine_crank")
    assert_registered(ds)  # every variable's units and description from the registry


def test_engine_coating_verdict_matches_the_fmep(engine):
    """The engine verdict's nominal change is the change of engine friction energy (and
    FMEP) between the sets; at ς' = ς and k = 1 the FMEP range contains the FMEP; the
    DLC 1 µm pair's ς range (paper ς 0.44 scaled by the a-C:H spread) moves it."""
    s = engine.summary()
    ref, dlc = s["surface_sets"]["uncoated"], s["surface_sets"]["dlc_1um"]
    assert ref["coating_verdict"] is None
    v = dlc["coating_verdict"]
    e0, e1 = ref["engine_friction_energy_per_cycle_J"], dlc["engine_friction_energy_per_cycle_J"]
    assert v["friction_energy_change_pct"] == pytest.approx(100 * (e1 / e0 - 1), rel=1e-9)
    lo, hi = v["range_pct"]
    assert lo <= v["friction_energy_change_pct"] <= hi and hi > lo
    mep = dlc["valvetrain_friction_mep_range_Pa"]
    assert mep[0] < dlc["valvetrain_friction_mep_Pa"] < mep[1]
    assert "FMEP" in v["method"] and v["sentence"].startswith("DLC 1 µm")
    assert "Greenwood–Tripp" in dlc["asperity_law"]  # the paper's sets


def test_one_camshaft_carries_all_lobes(engine):
    one = run_engine_study(_case(**{"engine.camshafts": 1}), workers=1)
    assert one.camshafts == ["camshaft"]
    assert np.allclose(one.friction_torque[:, 0], engine.friction_torque.sum(axis=1))


def test_place_trace_periodic_shift():
    x = np.arange(-360.0, 361.0, 4.0)
    v = np.cos(np.radians(x) / 4.0) ** 2  # period 720°, 1 at the nose, 0 opposite
    crank = np.arange(0.0, 720.5, 0.5)
    a = place_trace(x, v, 100.0, crank)
    assert a[np.isclose(crank, 100.0)][0] == pytest.approx(1.0)
    assert a[np.isclose(crank, 100.0 + 360.0)][0] == pytest.approx(0.0, abs=1e-12)


def test_engine_case_errors_name_the_key():
    with pytest.raises(InputError, match=r"engine\.displacement: required"):
        load_case().updated({"engine.cylinders": 4})
    with pytest.raises(InputError, match=r"engine\.firing_order"):
        load_case().updated({**ENGINE, "engine.firing_order": [1, 2, 2, 4]})
    with pytest.raises(InputError, match=r"engine\.exhaust\.changes: cam\.max_lift"):
        load_case().updated(
            {
                **ENGINE,
                "engine.exhaust": {"centre_angle_deg": 250.0, "changes": {"cam.max_lift": -1.0}},
            }
        )
    with pytest.raises(InputError, match="engine.cylinders"):
        run_engine_study(load_case())


def test_engine_sweep_point_and_bundled_map():
    from tribodyn.config import load_sweep
    from tribodyn.workflow.sweep_point import run_point

    ds = run_point(_case(), mode="engine")
    assert ds.attrs["status"] == "ok", ds.attrs.get("error")
    assert list(ds["surface_set"].values) == ["uncoated", "dlc_1um"]
    e = ds["engine_friction_energy_per_cycle_J"].values
    parts = sum(
        ds[k].values
        for k in (
            "cam_tappet_energy_J",
            "tappet_bore_energy_J",
            "valve_guide_energy_J",
            "camshaft_journal_energy_J",
        )
    )
    assert np.allclose(e, parts)
    assert ds["valvetrain_friction_mep_Pa"].attrs["units"] == "Pa"
    spec = load_sweep("engine_dohc16_map")
    assert spec.mode == "engine" and len(spec.points()) == 21
    assert spec.base.engine.cylinders == 4 and len(spec.base.surface_set_names) == 3


def test_engine_cli_writes_results(engine_results, tmp_path):
    import json

    from typer.testing import CliRunner

    from tribodyn.cli import app

    out = engine_results  # ``tribodyn engine`` of this engine (conftest), run once
    s = json.loads((out / "summary.json").read_text())["engine"]
    d = s["surface_sets"]["uncoated"]
    assert d["valvetrain_friction_mep_Pa"] == pytest.approx(
        d["engine_friction_energy_per_cycle_J"] / 0.0016
    )
    assert (out / "engine_camshaft_torque.png").stat().st_size > 0
    assert (out / "engine_lobe_contributions.png").stat().st_size > 0
    import xarray as xr

    with xr.open_dataset(out / "results.nc") as ds:
        assert ds["camshaft_friction_torque"].attrs["units"] == "N m"
    # a single-valve case is refused with the key named, not a traceback
    single = tmp_path / "single.toml"
    load_case().write_toml(single)
    r = CliRunner().invoke(app, ["engine", str(single), "-o", str(tmp_path / "o2")])
    assert r.exit_code == 2 and "engine.cylinders" in r.output


def test_engine_sweep_needs_an_engine_case():
    from tribodyn.config import SweepSpec

    text = '[sweep]\nname = "e"\nmode = "engine"\n[[axes]]\npath = "engine.speed_rpm"\nvalues = [1000.0]\n'
    with pytest.raises(InputError, match=r"sweep\.mode.*cylinders"):
        SweepSpec.from_toml_string(text)


def _study_with_a_failed_sample(case):
    """Four samples: unloaded, solved, loaded with a failed EHL step (no friction known),
    solved; lift 1 mm and s' = 2 mm/rad throughout."""
    from types import SimpleNamespace

    nan = math.nan
    res = SimpleNamespace(
        name=case.surface_set_names[0],
        loaded=np.array([False, True, True, True]),
        converged=np.array([True, True, False, True]),
        viscous_friction=np.array([nan, 1.0, nan, 2.0]),
        boundary_friction=np.array([nan, 0.5, nan, 0.0]),
        max_pressure=np.array([nan, 1e9, nan, 1e9]),
    )
    inputs = SimpleNamespace(
        crank_angle=np.array([0.0, 10.0, 20.0, 30.0]),
        contact_force=np.array([0.0, 500.0, 500.0, 500.0]),
        sliding_speed=np.ones(4),
        width=case.width,
        radius=np.full(4, 0.01),
    )
    dyn = SimpleNamespace(
        crank_angle=np.array([0.0, 720.0]),
        cam_lift=np.full(2, 1e-3),
        lift_velocity=np.full(2, 2e-3),
    )
    return SimpleNamespace(case=case, dynamics=dyn, inputs=inputs, sets=[res])


def test_failed_sample_has_unknown_torques_not_zero():
    """A loaded sample whose EHL step failed has no friction: its cam–tappet torques are
    NaN in the study's and the engine's traces (they used to be 0, an invented number),
    and they are left out of the cycle integral and the maxima. By hand, T_f = F_f (r_b + s),
    T_drive = W s' + T_f."""
    from tribodyn.workflow.engine import lobe_traces
    from tribodyn.workflow.engineering import engineering_outputs

    case = _case()
    study = _study_with_a_failed_sample(case)
    rb = build(case).cam.base_radius
    t_f = np.array([0.0, 1.5 * (rb + 1e-3), math.nan, 2.0 * (rb + 1e-3)])
    eng = engineering_outputs(study)
    lobe = lobe_traces("intake", study, case)
    for got_f, got_d in (
        (eng.friction_torque, eng.drive_torque),
        (lobe.friction_torque, lobe.drive_torque),
    ):
        np.testing.assert_allclose(got_f[0], t_f, rtol=1e-12)
        np.testing.assert_allclose(got_d[0], 500.0 * 2e-3 * (np.arange(4) > 0) + t_f)
    assert np.isnan(lobe.bore_torque[0, 2]) and np.isfinite(lobe.bore_torque[0, [0, 1, 3]]).all()
    s = eng.scalars[case.surface_set_names[0]]
    assert s["max_friction_torque_Nm"] == pytest.approx(t_f[3])
    assert s["peak_drive_torque_Nm"] == pytest.approx(1.0 + t_f[3])
    known = np.nan_to_num(t_f)  # trapezoids over the known samples, the failed one as 0
    energy = np.sum(0.5 * (known[1:] + known[:-1])) * math.radians(10.0) / 2.0
    assert s["friction_energy_per_cycle_from_torque_J"] == pytest.approx(energy)
    assert lobe.energy[case.surface_set_names[0]] == pytest.approx(energy)


def test_a_failed_sample_of_one_valve_does_not_erase_the_others(monkeypatch):
    """One unconverged EHL sample per lobe (its friction unknown): the camshaft sums keep
    every other valve's known friction (the engine's cam–tappet energy equals the sum of
    the valves' own energies, which leave the unknown sample out), the bore and journal
    torques stay known, and the summary counts the failed steps."""
    import tribodyn.workflow.engine as engine_module

    real = engine_module.run_cycle_study

    def one_failure(case, **kw):
        study = real(case, **kw)
        for r in study.sets:
            i = int(np.argmax(np.where(r.loaded, study.inputs.contact_force, 0.0)))
            r.viscous_friction = r.viscous_friction.copy()
            r.viscous_friction[i] = np.nan
            r.converged = r.converged.copy()
            r.converged[i] = False
            r.failures = [*r.failures, (float(study.inputs.crank_angle[i]), "injected")]
        return study

    monkeypatch.setattr(engine_module, "run_cycle_study", one_failure)
    es = run_engine_study(_case(), workers=1)
    name = es.set_names[0]
    assert np.isnan(es.lobes["intake"].friction_torque[0]).any()  # the lobe's trace says so
    total = cycle_integral(es.friction_torque[0].sum(axis=0), es.crank_angle)
    valves = sum(es.lobes[v["kind"]].energy[name] for v in es.valves)
    assert total == pytest.approx(valves, rel=0.01)
    for t in (es.friction_torque, es.bore_torque, es.journal_torque, es.drive_torque):
        assert np.isfinite(t).all()
    assert es.summary()["surface_sets"][name]["failed_steps"] == {"intake": 1, "exhaust": 1}
