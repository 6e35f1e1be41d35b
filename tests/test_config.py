"""Case files: the bundled paper case, validation messages, builders, TOML round trip."""

import math
import re
import tomllib
from pathlib import Path

import numpy as np
import pytest

from tribodyn import EHLOptions, InputError, Lubricant, Roughness
from tribodyn.config import (
    CASES_DIR,
    DEFAULT_CASE,
    Case,
    SurfaceSet,
    bundled_cases,
    load_case,
    to_toml,
)
from tribodyn.config.build import build
from tribodyn.valvetrain import (
    AccelerationCam,
    CircularArcCam,
    TabulatedCam,
    ValvetrainParameters,
)

ROUGH = "roughness = { asperity_density = 1e9, rms = 1e-7, summit_radius = 1e-6 }\n"


@pytest.fixture(scope="module")
def paper():
    return load_case()


def reject(text, *fragments, base_dir=None):
    """Assert the TOML text is rejected and every fragment appears in the message."""
    with pytest.raises(InputError) as ei:
        Case.from_toml_string(text, base_dir=base_dir)
    msg = str(ei.value)
    for f in fragments:
        assert f in msg, f"{f!r} not in:\n{msg}"
    return msg


# ----------------------------------------------------------------------------- bundled
def test_bundled_case_loads_and_builds_everything(paper):
    assert paper.name == "andreou2023"
    assert paper.source == DEFAULT_CASE
    cam = build(paper).cam
    assert isinstance(cam, AccelerationCam)
    assert cam.min_radius_of_curvature > 0.0
    assert isinstance(build(paper).lubricant, Lubricant)
    vp = build(paper).valvetrain
    assert isinstance(vp, ValvetrainParameters)
    assert vp.cam_width == 0.012
    assert isinstance(build(paper).options, EHLOptions)
    assert paper.cam_speed == pytest.approx(1500.0 * 2.0 * math.pi / 60.0)  # cam = engine/2
    sets = build(paper).surface_sets
    assert [s.name for s in sets] == ["uncoated", "dlc_1um", "dlc_4um", "wcc_1um", "wcc_4um"]
    assert all(isinstance(s, SurfaceSet) and isinstance(s.roughness, Roughness) for s in sets)
    dyn = build(paper).dynamics_options
    assert dyn["engine_speed"] == 3000.0 and dyn["cycles"] == 2
    trib = build(paper).analytic_tribology("wcc_4um")
    assert trib.width == 0.012 and trib.kwargs["boundary_shear_coefficient"] == 0.54


def test_a_copy_with_changes_builds_its_own_objects(paper):
    """``model_copy(update=…)`` keeps the original's built objects; they are rebuilt for
    the copy (its lubricant has the new viscosity), while deepcopy and pickle keep a
    consistent case and its objects."""
    import copy
    import pickle

    assert build(paper).lubricant.viscosity == 0.055
    lub = paper.lubricant_config.model_copy(update={"viscosity": 0.02})
    changed = paper.model_copy(update={"lubricant_config": lub})
    assert build(changed).lubricant.viscosity == 0.02
    assert build(changed).case is changed
    assert build(paper).lubricant.viscosity == 0.055 and build(paper).case is paper
    for twin in (copy.deepcopy(paper), pickle.loads(pickle.dumps(paper))):
        assert build(twin).case is twin and build(twin).lubricant.viscosity == 0.055


def test_paper_numbers(paper):
    # Table 7
    assert paper.engine.speed_rpm == 3000.0
    c = paper.cam_config
    assert (c.base_radius, c.max_lift, c.width) == (0.015, 0.0093, 0.012)
    v = paper.valvetrain
    assert (v.valve_mass, v.spring_mass, v.spring_rate) == (0.07, 0.036, 33750.0)
    # assumed (docs/conventions.md)
    assert (v.tappet_mass, v.spring_preload, v.lash) == (0.040, 250.0, 0.0)
    assert (c.ramp_height, c.ramp_angle_deg, c.event_angle_deg, c.nose_radius) == (
        0.2e-3,
        20.0,
        171.0,
        3e-3,
    )
    # Table 5 (+ assumed density)
    lub = build(paper).lubricant
    assert (
        lub.viscosity,
        lub.pressure_viscosity,
        lub.eyring_stress,
        lub.limiting_shear_coefficient,
        lub.density,
    ) == (0.055, 1.05e-8, 2e6, 0.08, 850.0)
    assert lub.viscosity_model == "roelands" and lub.compressible
    assert lub.limiting_shear_stress == 0.0  # paper: τ_L = Λp only
    assert (
        build(
            paper.updated({"lubricant.limiting_shear_stress": 3e6})
        ).lubricant.limiting_shear_stress
        == 3e6
    )
    # Table 6 (moduli in GPa)
    m = paper.materials
    assert (m["steel"].E, m["dlc"].E, m["wcc"].E) == (210e9, 185e9, 175e9)
    assert all(x.nu == 0.3 for x in m.values())
    assert (
        m["steel"].boundary_shear_coefficient,
        m["dlc"].boundary_shear_coefficient,
        m["wcc"].boundary_shear_coefficient,
    ) == (0.185, 0.44, 0.54)
    # Table 4 roughness, coatings on the tappet, steel cam
    table4 = {
        "uncoated": (8.3e9, 0.408e-6, 0.669e-6),
        "dlc": (3.8e9, 0.358e-6, 0.332e-6),
        "wcc": (2.7e9, 0.347e-6, 0.217e-6),
    }
    expect = {
        "uncoated": (None, None, 0.185, "uncoated"),
        "dlc_1um": (185e9, 1e-6, 0.44, "dlc"),
        "dlc_4um": (185e9, 4e-6, 0.44, "dlc"),
        "wcc_1um": (175e9, 1e-6, 0.54, "wcc"),
        "wcc_4um": (175e9, 4e-6, 0.54, "wcc"),
    }
    for s in build(paper).surface_sets:
        E, t, sig, rough_key = expect[s.name]
        cam, tappet = s.bodies
        assert cam.coating is None and cam.material.E == 210e9 and cam.material.nu == 0.3
        assert tappet.material.E == 210e9
        if E is None:
            assert tappet.coating is None and s.coating_label == "uncoated"
        else:
            assert (tappet.coating.E, tappet.coating.nu, tappet.coating.thickness) == (E, 0.3, t)
        assert s.boundary_shear_coefficient == sig
        assert s.boundary_shear_strength == 2e6
        r = s.roughness
        assert (r.asperity_density, r.rms, r.summit_radius) == table4[rough_key]
        assert r.method == "exact"
    assert build(paper).set("dlc_4um").surface.coating_label == "DLC 4 µm"
    assert build(paper).set("wcc_1um").options.boundary_shear_coefficient == 0.54
    assert 0.0 < paper.numerics.crank_step_deg <= 1.0
    assert paper.numerics.implicit_coupling is True  # the comparison of Figs. 8–10
    assert paper.numerics.n == 0  # automatic EHL grid


def test_bundled_file_itself_holds_the_numbers_and_comments():
    text = DEFAULT_CASE.read_text(encoding="utf-8")
    raw = tomllib.loads(text)
    assert raw["lubricant"]["viscosity"] == 0.055
    assert raw["materials"]["wcc"]["E"] == 175e9
    assert raw["surface_sets"][0]["roughness"]["asperity_density"] == 8.3e9
    assert raw["valvetrain"]["tappet_mass"] == 0.040
    for tag in ("Table 4", "Table 5", "Table 6", "Table 7", "ASSUMED", "ERRATUM"):
        assert tag in text
    for line in text.splitlines():  # every assumption is marked on its line
        if re.match(
            r"\s*(tappet_mass|spring_preload|density|event_angle_deg|nose_radius)\s*=", line
        ):
            assert "ASSUMED" in line, line


def test_empty_file_is_a_typical_engine_not_the_papers(paper):
    """Defaults: a typical engine, cam, valvetrain, oil, friction, rheology and roughness
    (tribodyn.physics.typical*), none of them the paper's; the paper's values live in its
    case file."""
    from tribodyn.physics import typical, typical_engine

    d_default = Case.from_toml_string("").to_dict()
    d_paper = paper.to_dict()
    for key in ("engine", "numerics"):
        assert d_default[key] == d_paper[key], key
    cam, vt = d_default["cam"], d_default["valvetrain"]
    assert cam["width"] == typical_engine.CAM_WIDTH.value != d_paper["cam"]["width"]
    assert cam["max_lift"] == typical_engine.CAM_MAX_LIFT.value != d_paper["cam"]["max_lift"]
    for k, t in typical_engine.VALVETRAIN.items():
        assert vt[k] == t.value, k
    for k in ("valve_mass", "spring_mass", "spring_rate"):  # Table 7
        assert vt[k] != d_paper["valvetrain"][k], k
    assert d_default["lubricant"]["viscosity"] == typical.VISCOSITY.value
    assert d_default["lubricant"]["viscosity"] != d_paper["lubricant"]["viscosity"]
    for k in ("dlc", "wcc"):  # Table 6 moduli are the paper's, not the defaults
        assert d_default["materials"][k]["E"] != d_paper["materials"][k]["E"], k
    lub = d_default["lubricant"]
    assert (
        lub["eyring_stress"] == typical.EYRING_STRESS.value != d_paper["lubricant"]["eyring_stress"]
    )
    assert lub["limiting_shear_coefficient"] == typical.LIMITING_SHEAR_COEFFICIENT.value
    mats = d_default["materials"]
    assert mats["steel"]["boundary_shear_coefficient"] == typical.boundary_friction("steel").value
    assert mats["dlc"]["boundary_shear_coefficient"] == typical.boundary_friction("a-C:H").value
    assert mats["wcc"]["boundary_shear_coefficient"] == typical.boundary_friction("WC-C").value
    for s in d_default["surface_sets"]:
        assert s["boundary_shear_strength"] == 0.0
        r = s["roughness"]
        eta_beta_sigma = r["asperity_density"] * r["summit_radius"] * r["rms"]
        assert eta_beta_sigma == pytest.approx(typical.ROUGHNESS_PARAMETER.value)
        assert r["rms"] / r["summit_radius"] == pytest.approx(typical.RMS_TO_SUMMIT_RADIUS.value)
    # the paper's case states the paper's friction values itself
    assert d_paper["lubricant"]["eyring_stress"] == 2e6
    assert {s["boundary_shear_strength"] for s in d_paper["surface_sets"]} == {2e6}
    assert d_paper["materials"]["dlc"]["boundary_shear_coefficient"] == 0.44


def test_numerics_defaults_are_the_ehl_solvers():
    """Every default [numerics] shares with EHLOptions is the same value, and an empty
    case's EHL options are EHLOptions() in those fields (one source: EHLOptions)."""
    import dataclasses

    from tribodyn.config.schema import Numerics

    ehl = {f.name: f.default for f in dataclasses.fields(EHLOptions)}
    # n differs by design: 0 (automatic) in the case file, None in EHLOptions
    shared = (set(Numerics.model_fields) & set(ehl)) - {"n"}
    assert shared >= {
        "inlet",
        "outlet",
        "inlet_truncation",
        "inlet_rigid",
        "outlet_rigid",
        "tol",
        "max_iter",
        "time_order",
        "viscous_model",
        "limiting_shear",
    }
    differ = {k: (Numerics.model_fields[k].default, ehl[k]) for k in sorted(shared)}
    differ = {k: v for k, v in differ.items() if v[0] != v[1] or type(v[0]) is not type(v[1])}
    assert not differ, f"[numerics] default != EHLOptions default: {differ}"
    built = build(Case.from_toml_string("")).options
    for k in shared:
        assert getattr(built, k) == getattr(EHLOptions(), k), k


def test_bundled_names(paper):
    assert set(bundled_cases()) == {
        "andreou2023",
        "andreou2023_flexible",
        "andreou2023_thermal",
        "engine_dohc16",
        "example_table_cam",
        "flat_tappet_rig",
        "flat_tappet_rig_measured",
    }
    assert load_case("andreou2023") == paper


def test_example_table_cam():
    case = load_case(CASES_DIR / "example_table_cam.toml")
    cam = build(case).cam
    assert isinstance(cam, TabulatedCam)
    assert case.cam_table_path == CASES_DIR / "example_cam_lift.csv"
    assert cam.max_lift == pytest.approx(9.3e-3, rel=1e-6)
    # same kinematics as the default cam it was sampled from
    th = np.linspace(0.0, 2.0 * np.pi, 721)
    ref = AccelerationCam(0.015, 9.3e-3)  # the paper's sizes (Table 7)
    assert np.max(np.abs(cam.lift(th) - ref.lift(th))) < 1e-8
    assert [s.coating_label for s in build(case).surface_sets] == ["uncoated", "WC-C 4 µm"]
    header = case.cam_table_path.read_text(encoding="utf-8").splitlines()[0]
    assert header.startswith("#") and "AccelerationCam" in case.cam_table_path.read_text(
        encoding="utf-8"
    )


def test_other_cam_types():
    case = Case.from_toml_string('[cam]\ntype = "circular_arc"\nflank_radius = 0.04\n')
    assert isinstance(build(case).cam, CircularArcCam)
    assert build(case).cam.flank_radius == 0.04


# ----------------------------------------------------------------------------- rejection
def test_unknown_keys_are_rejected_with_dotted_path():
    reject("[foo]\nx = 1\n", "foo: unknown key", "allowed: case, engine")
    reject(
        "[lubricant]\nviscosty = 0.05\n",
        "lubricant.viscosty: unknown key",
        "did you mean 'viscosity'",
    )
    reject("[materials.dlc]\nE = 185e9\nnu = 0.3\nYoung = 1\n", "materials.dlc.Young")
    reject(
        "[[surface_sets]]\nname = 'a'\n"
        "roughness = { asperity_density = 1e9, rms = 1e-7, summit_radius = 1e-6, x = 2 }\n",
        "surface_sets[0].roughness.x: unknown key",
    )
    reject(
        "[cam]\ntype = 'circular_arc'\nevent_angle_deg = 100\n",
        "cam.event_angle_deg: unknown key for cam type 'circular_arc'",
    )


def test_out_of_range_values_name_the_key():
    reject(
        "[materials.steel]\nE = -2.1e11\nnu = 0.3\nboundary_shear_coefficient = 0.185\n",
        "materials.steel.E: must be >= 1e+06 Pa",
        "(got -2.1e+11)",
    )
    reject(
        "[materials.steel]\nE = 210e9\nnu = 0.5\nboundary_shear_coefficient = 0.185\n",
        "materials.steel.nu: must be > -1 and < 0.5",
        "(got 0.5)",
    )
    reject("[numerics]\ncrank_step_deg = 0\n", "numerics.crank_step_deg: must be > 0", "<= 5")
    reject(
        "[lubricant]\nviscosity = 1e-5\n",
        "lubricant.viscosity: must be > 6.31",
        "Pa·s",
        "(got 1e-05)",
    )
    reject("[cam]\nbase_radius = 0.0\n", "cam.base_radius: must be > 0 m")
    reject("[cam]\nnose_radius = -0.003\n", "cam.nose_radius: must be > 0 m")
    reject(
        "[cam]\ntype = 'circular_arc'\nnose_radius = 0.02\n",
        "cam: nose_radius must be < base_radius",
    )
    reject("[valvetrain]\ntappet_radius = 0.01\n", "cam:", "tappet radius")
    reject("[cam]\ntype = 'spline'\n", "cam.type: must be one of 'acceleration'", "(got 'spline')")
    reject(
        "[numerics]\nn = 512.0\nviscous_model = 'foo'\n",
        "numerics.n: must be an integer (got 512.0)",
        "numerics.viscous_model: must be 'eyring' or 'newtonian' (got 'foo')",
        "2 problems",
    )
    grid = "must be 0 (automatic) or >= 32 and <= 4096"  # one range, the upper bound too
    reject("[numerics]\ncoupling_n = 10\n", f"numerics.coupling_n: {grid} (got 10)")
    # the key once, not under its section as well ("numerics: numerics.n: …")
    msg = reject("[numerics]\nn = 16\n", f"\n  numerics.n: {grid} (got 16)")
    assert "numerics: " not in msg
    reject("[engine]\nspeed_rpm = '3000'\n", "engine.speed_rpm: must be a number")
    reject("[lubricant]\nviscosity = nan\n", "lubricant.viscosity: must be a finite number")


def test_coating_rules():
    head = "[[surface_sets]]\nname = 'a'\ncoating = 'dlc'\n"
    reject(
        head + "coating_thickness = 0\n" + ROUGH, "surface_sets[0].coating_thickness: must be > 0 m"
    )
    reject(head + ROUGH, "surface_sets[0].coating_thickness: required when a coating is named")
    reject(
        "[[surface_sets]]\nname = 'a'\ncoating_thickness = 1e-6\n" + ROUGH,
        "surface_sets[0].coating_thickness: given but no coating",
    )
    reject(
        "[[surface_sets]]\nname = 'a'\n" + ROUGH + "[[surface_sets]]\nname = 'b'\n"
        "coating = 'dcl'\ncoating_thickness = 1e-6\n" + ROUGH,
        "surface_sets[1].coating: unknown material 'dcl'",
        "did you mean 'dlc'",
    )
    reject(
        "[[surface_sets]]\nname = 'a'\n" + ROUGH + "[[surface_sets]]\nname = 'a'\n" + ROUGH,
        "surface_sets[1].name: duplicate surface-set name 'a'",
    )
    reject("[cam]\nmaterial = 'iron'\n", "cam.material: unknown material 'iron'")
    reject(
        "[materials.x]\nE = 1e11\nnu = 0.3\n[[surface_sets]]\nname = 'a'\nsubstrate = 'x'\n"
        + ROUGH
        + "[cam]\nmaterial = 'x'\n",
        "surface_sets[0].boundary_shear_coefficient: required",
    )
    # "none" means uncoated
    case = Case.from_toml_string("[[surface_sets]]\nname = 'a'\ncoating = 'none'\n" + ROUGH)
    assert build(case).surface_sets[0].tappet.coating is None


def test_lift_table_problems(tmp_path):
    rows = [(a, 0.0) for a in range(0, 360, 10)]
    rows[20], rows[21] = rows[21], rows[20]  # not monotonic
    (tmp_path / "bad.csv").write_text("\n".join(f"{a},{s}" for a, s in rows))
    msg = reject(
        "[cam]\ntype = 'table'\npath = 'bad.csv'\n",
        "cam.path:",
        "non-monotonic lift table",
        base_dir=tmp_path,
    )
    assert "bad.csv" in msg
    reject(
        "[cam]\ntype = 'table'\npath = 'missing.csv'\n",
        "cam.path:",
        "cannot read lift table",
        base_dir=tmp_path,
    )
    reject("[cam]\ntype = 'table'\n", "cam.path: required key is missing")


def test_toml_syntax_error_and_missing_file(tmp_path):
    with pytest.raises(InputError, match="TOML syntax error"):
        Case.from_toml_string("[cam\n")
    with pytest.raises(InputError, match="cannot read case file"):
        load_case(tmp_path / "nope.toml")


def test_case_file_with_a_byte_order_mark_is_read(tmp_path):
    f = tmp_path / "bom.toml"
    f.write_bytes("\ufeff[engine]\nspeed_rpm = 2000\n".encode())
    assert load_case(f).engine.speed_rpm == 2000
    assert Case.from_toml_string("\ufeff[engine]\nspeed_rpm = 2500\n").engine.speed_rpm == 2500


@pytest.mark.parametrize(
    "text",
    [
        "a = " + "[" * 5000 + "]" * 5000,  # RecursionError in the parser before
        "a = " + "{b = " * 3000 + "1" + "}" * 3000,
        "a = " + "[" * 40 + "]" * 40,  # parses, but deeper than any key
        "a" + ".b" * 5000 + " = 1",
        "[" + ".".join(["t"] * 5000) + "]\nx = 1\n",
    ],
    ids=["arrays", "inline-tables", "arrays-40", "dotted-key", "table-header"],
)
def test_deeply_nested_case_files_are_input_errors(tmp_path, text):
    f = tmp_path / "deep.toml"
    f.write_text(text)
    with pytest.raises(InputError, match="nested more than 32 levels"):
        load_case(f)
    deep: dict = {}
    for _ in range(3000):
        deep = {"x": deep}
    with pytest.raises(InputError, match="nested more than 32 levels"):
        Case.from_dict({"engine": deep})


def test_oversized_case_file_is_refused_without_reading_it_all(tmp_path):
    from tribodyn.config.tomlfile import MAX_BYTES

    f = tmp_path / "big.toml"
    f.write_bytes(b"# " + b"x" * MAX_BYTES + b"\n")
    with pytest.raises(InputError, match="larger than 10 MB"):
        load_case(f)


# ----------------------------------------------------------------------------- round trip
def test_round_trip_is_lossless(paper):
    text = paper.to_toml()
    again = Case.from_toml_string(text)
    assert again == paper
    assert again.to_dict() == paper.to_dict()
    assert again.to_toml() == text


def test_round_trip_of_awkward_values(paper, tmp_path):
    case = paper.updated(
        {
            "lubricant.viscosity": 1.0 / 30.0,
            "case.description": 'quote " backslash \\ tab\t new\nline µ',
            "valvetrain.contact_stiffness": 3.3e8,
            "surface_sets[1].coating_thickness": 1.2345678901234567e-6,
        }
    )
    assert case.lubricant_config.viscosity == 1.0 / 30.0
    again = Case.from_toml_string(case.to_toml())
    assert again == case and again.valvetrain.contact_stiffness == 3.3e8
    path = case.write_toml(tmp_path / "c.toml")
    assert load_case(path) == case


def test_round_trip_of_table_cam(tmp_path):
    case = load_case("example_table_cam")
    again = Case.from_toml_string(case.to_toml(), base_dir=CASES_DIR)
    assert again == case
    moved = load_case(case.write_toml(tmp_path / "moved.toml"))  # absolute table path
    assert moved.cam_table_path == case.cam_table_path


def test_updated_validates(paper):
    faster = paper.updated({"engine.speed_rpm": 2000})
    assert faster.cam_speed == pytest.approx(2000 / 2 * 2 * math.pi / 60)
    assert paper.engine.speed_rpm == 3000.0
    with pytest.raises(InputError, match=r"surface_sets\[2\].coating_thickness"):
        paper.updated({"surface_sets[2].coating_thickness": -1e-6})


def test_greenwood_tripp_needs_the_summits_the_surface_law_does_not():
    gt = '[[surface_sets]]\nname = "a"\nasperity_model = "greenwood_tripp"\n'
    msg = reject(
        gt + "roughness = { rms = 0.3e-6 }\n",
        "surface_sets[0].roughness.asperity_density: required with asperity_model = "
        '"greenwood_tripp"',
        "surface_sets[0].roughness.summit_radius: required with",
        "surface law, which needs only rms",
    )
    assert "2 problems" in msg
    reject(
        gt + "roughness = { rms = 0.3e-6, summit_radius = 1e-4 }\n",
        "surface_sets[0].roughness.asperity_density: required",
    )
    # the surface law takes σ alone; a σ whose typical β leaves β's range needs β given
    Case.from_toml_string('[[surface_sets]]\nname = "a"\nroughness = { rms = 0.3e-6 }\n')
    reject(
        '[[surface_sets]]\nname = "a"\nroughness = { rms = 5e-5 }\n',
        "surface_sets[0].roughness.summit_radius: required for rms = 5e-05 m",
        "< 0.01 m",
    )
    # σ out of its own range is reported as σ, not as the summits derived from it
    msg = reject('[[surface_sets]]\nname = "a"\nroughness = { rms = 0.0 }\n', "roughness.rms")
    assert "summit_radius" not in msg and "asperity_density" not in msg


def test_to_toml_writer_handles_keys_and_floats():
    text = to_toml({"a b": {"x": 1e-300, "y": float("inf"), "z": [1, 2.5], "s": "é"}})
    assert tomllib.loads(text) == {"a b": {"x": 1e-300, "y": float("inf"), "z": [1, 2.5], "s": "é"}}


# ----------------------------------------------------------------------------- docs
def test_docs_cover_every_key():
    doc = (Path(__file__).resolve().parents[1] / "docs" / "case-files.md").read_text(
        encoding="utf-8"
    )
    from tribodyn import config as cfg

    models = [
        cfg.CaseInfo,
        cfg.Engine,
        cfg.LobeConfig,
        cfg.AuxiliaryFrictionConfig,
        cfg.AccelerationCamConfig,
        cfg.CircularArcCamConfig,
        cfg.TableCamConfig,
        cfg.Valvetrain,
        cfg.ValveConfig,
        cfg.TappetConfig,
        cfg.SpringConfig,
        cfg.CamshaftConfig,
        cfg.LubricantConfig,
        cfg.MaterialConfig,
        cfg.RoughnessConfig,
        cfg.SurfaceSetConfig,
        cfg.MeasuredSurfaceConfig,
        cfg.Numerics,
        cfg.StrengthConfig,
        cfg.StressConfig,
    ]
    missing = [f"{m.__name__}.{k}" for m in models for k in m.model_fields if f"`{k}`" not in doc]
    assert not missing, missing


def test_surface_sets_boundary_shear_strength_reaches_the_dynamics_tribology():
    # τ₀ of a surface set is the analytic tribology's; the friction follows analytic_contact
    # with that τ₀ (the paper's Eq. 17 boundary shear τ₀ + ςp)
    from tribodyn.physics.analytic_contact import analytic_contact

    base = load_case()
    sets = base.to_dict()["surface_sets"][:1]
    sets[0]["boundary_shear_strength"] = 5e6
    case = base.updated({"surface_sets": sets})
    built = build(case)
    trib = built.analytic_tribology("uncoated")
    assert trib.boundary_shear_strength == 5e6 and trib.kwargs["boundary_shear_strength"] == 5e6
    with pytest.raises(TypeError):
        trib.kwargs["boundary_shear_strength"] = 0.0  # a read-only view
    force, ue, us, R = 400.0, 0.3, 0.3, 0.01  # thin film: mixed lubrication
    s = built.set("uncoated").surface
    c = analytic_contact(
        force / trib.width,
        R,
        ue,
        us,
        s.bodies,
        built.lubricant,
        s.roughness,
        boundary_shear_coefficient=s.boundary_shear_coefficient,
        boundary_shear_strength=5e6,
    )
    assert float(c.boundary_friction) > 0.0
    f = trib.friction(0.0, force, ue, us, R)
    assert float(f) == pytest.approx(float(c.friction) * trib.width, rel=1e-12)
    f0 = base.updated({"surface_sets": base.to_dict()["surface_sets"][:1]})
    assert float(build(f0).analytic_tribology("uncoated").friction(0.0, force, ue, us, R)) < float(
        f
    )
