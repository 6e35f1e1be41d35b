"""``tribodyn contact``: table and JSON output, Pan–Hamrock and Hertz checks, bad input."""

import json
import math

import pytest
from typer.testing import CliRunner

from tribodyn.cli import app
from tribodyn.config.build import build
from tribodyn.physics.regimes import hamrock_groups, pan_hamrock

runner = CliRunner()
E_STEEL_PAIR = 210e9 / (1.0 - 0.3**2)  # E' of steel on steel, 1/E' = ½Σ(1−ν²)/E


def run(*args):
    return runner.invoke(app, ["contact", *args])


#: The paper's oil (Table 5), stated: without a case the oil is the typical one.
PAPER_OIL = ("--viscosity", "0.055", "--pressure-viscosity", "1.05e-8")


def test_ehl_table():
    r = run(
        "--load",
        "633",
        "--radius",
        "0.01",
        "--ue",
        "5",
        "--us",
        "2",
        "--roughness",
        "8.3e9,0.408e-6,0.669e-6",
        "--n",
        "256",
        *PAPER_OIL,
    )
    assert r.exit_code == 0, r.output
    for label in (
        "central film h_c",
        "minimum film h_min",
        "λ = h_min/σ",
        "half-width b",
        "friction coefficient",
        "regime",
        "converged",
    ):
        assert label in r.stdout
    from tribodyn.physics.regimes import greenwood_chart_groups, lubrication_regime

    W, U, G = hamrock_groups(633 / 0.012, 0.01, 5.0, 0.055, 1.05e-8, E_STEEL_PAIR)
    assert lubrication_regime(*greenwood_chart_groups(W, U, G)) in r.stdout


def test_roughness_follows_the_default_surface_law_unless_greenwood_tripp_is_asked():
    """--roughness gives the default surface law (the typical spectrum with its σ), as a
    case file does; --asperity-model greenwood_tripp gives Greenwood–Tripp with its η, β.
    At λ < 1 the surface law carries far more of the load (validation-friction page)."""
    base = ["--load", "600", "--radius", "0.005", "--ue", "0.5", "--us", "1", "--json"]
    base += ["--roughness", "1e9,0.2e-6,200e-6", "--n", "128"]
    surf = json.loads(run(*base).stdout)
    gt = json.loads(run(*base, "--asperity-model", "greenwood_tripp").stdout)
    assert surf["asperity_model"] == "measured" and "H 0.85" in surf["asperity_law"]
    assert gt["asperity_model"] == "greenwood_tripp"
    assert surf["asperity_load_N"] > 5 * gt["asperity_load_N"]
    r = run(*base, "--asperity-model", "persson")
    assert r.exit_code == 2 and "--asperity-model" in r.output


def test_roughness_sigma_alone_takes_the_typical_summits_as_a_case_file_does():
    """--roughness SIGMA: the surface law needs σ alone; η and β follow from the typical
    σ/β = 1e-3 and ηβσ = 0.04 (physics.typical), so it equals the three numbers."""
    base = ["--load", "600", "--radius", "0.005", "--ue", "0.5", "--us", "1", "--json"]
    base += ["--n", "128"]
    alone = json.loads(run(*base, "--roughness", "0.2e-6").stdout)
    beta = 0.2e-6 / 1e-3
    three = json.loads(
        run(*base, "--roughness", f"{0.04 / (beta * 0.2e-6)!r},0.2e-6,{beta!r}").stdout
    )
    assert alone["summit_radius_m"] == pytest.approx(200e-6, rel=1e-12)
    assert alone["asperity_density_per_m2"] == pytest.approx(1e9, rel=1e-12)
    assert alone["central_film_m"] == pytest.approx(three["central_film_m"], rel=1e-12)
    assert alone["asperity_load_N"] == pytest.approx(three["asperity_load_N"], rel=1e-12)
    r = run(*base, "--roughness", "0.2e-6", "--asperity-model", "greenwood_tripp")
    assert r.exit_code == 2 and "--roughness" in r.output and "needs all three" in r.output
    r = run(*base, "--roughness", "-1e-7")
    assert r.exit_code == 2 and "--roughness: sigma must be > 0" in r.output


def test_json_film_matches_pan_hamrock():
    load, width, radius, ue = 2400.0, 0.012, 0.01, 1.0  # w = 2e5 N/m
    r = run(
        "--load", str(load), "--radius", str(radius), "--ue", str(ue), "--us", "0.5", "--json",
        *PAPER_OIL,
    )  # fmt: skip
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    assert out["converged"] is True
    assert out["load_per_length_N_per_m"] == pytest.approx(load / width)
    assert out["reduced_modulus_Pa"] == pytest.approx(E_STEEL_PAIR)
    W, U, G = hamrock_groups(load / width, radius, ue, 0.055, 1.05e-8, E_STEEL_PAIR)
    hc, hmin = pan_hamrock(W, U, G, radius)
    assert out["central_film_m"] == pytest.approx(hc, rel=0.10)
    assert out["min_film_m"] == pytest.approx(hmin, rel=0.10)
    assert out["regime"] in ("PE", "PR", "IE", "IR")
    assert out["film_parameter_lambda"] is None  # smooth by default
    assert out["friction_N"] == pytest.approx(
        out["viscous_friction_N"] + out["boundary_friction_N"]
    )
    assert out["friction_coefficient"] == pytest.approx(out["friction_N"] / load)


def test_json_surface_set_from_the_paper_case():
    r = run(
        "--surface-set",
        "wcc_4um",
        "--load-per-length",
        "5e4",
        "--radius",
        "0.01",
        "--ue",
        "5",
        "--us",
        "1",
        "--n",
        "256",
        "--json",
    )
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    assert out["coating_thickness_m"] == 4e-6 and out["coating_E_Pa"] == 175e9
    assert out["boundary_shear_coefficient"] == 0.54
    assert out["roughness_rms_m"] == 0.347e-6
    assert out["film_parameter_lambda"] == pytest.approx(out["min_film_m"] / 0.347e-6)
    assert out["load_N"] == pytest.approx(5e4 * 0.012)


def test_dry_matches_hertz():
    load, width, radius = 633.0, 0.012, 0.01
    r = run("--dry", "--load", str(load), "--radius", str(radius), "--json")
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    b = math.sqrt(8.0 * (load / width) * radius / (math.pi * E_STEEL_PAIR))
    assert out["half_width_m"] == pytest.approx(b, rel=0.01)
    assert out["hertz_half_width_m"] == pytest.approx(b, rel=1e-12)
    # coating = substrate on the tappet: still Hertz
    r = run("--dry", "--load", str(load), "--radius", str(radius), "--coating", "210e9,0.3,4e-6")
    assert r.exit_code == 0, r.output
    assert "b / b_Hertz" in r.stdout


@pytest.mark.parametrize(
    "args, name",
    [
        (("--load", "-5", "--radius", "0.01", "--ue", "1"), "--load"),
        (("--load", "600", "--radius", "0", "--ue", "1"), "--radius"),
        (("--load", "600", "--radius", "0.01"), "--ue"),
        (("--load", "600", "--radius", "0.01", "--ue", "1", "--coating", "1,2"), "--coating"),
        (
            ("--load", "600", "--radius", "0.01", "--ue", "1", "--coating", "175e9,0.5,4e-6"),
            "--coating",
        ),
        (
            ("--load", "600", "--radius", "0.01", "--ue", "1", "--roughness", "1e9,-1e-7,1e-6"),
            "--roughness",
        ),
        (
            ("--load", "600", "--radius", "0.01", "--ue", "1", "--surface-set", "nope"),
            "--surface-set",
        ),
        (("--load", "600", "--radius", "0.01", "--ue", "1", "--viscosity", "1e-6"), "--viscosity"),
        (
            ("--load", "600", "--radius", "0.01", "--ue", "1", "--coating-material", "dlc"),
            "--coating-thickness",
        ),
        (("--load", "abc", "--radius", "0.01", "--ue", "1"), "--load"),
    ],
)
def test_bad_input_exits_2_naming_the_parameter(args, name):
    r = run(*args)
    assert r.exit_code == 2
    assert name in r.output
    assert "Traceback" not in r.output


def test_inlet_temperature_out_of_range_names_the_option_and_the_case_keys_range():
    """--inlet-temperature has the range of lubricant.inlet_temperature_c (the thermal
    oil's 200–600 K, in °C)."""
    base = ["--load", "633", "--radius", "0.01", "--ue", "5", "--us", "2"]
    r = run(*base, "--oil", "5W-30", "--inlet-temperature", "400")
    assert r.exit_code != 0
    assert "--inlet-temperature must be >= -73.15 and <= 326.85 [°C] (got 400)" in r.output
    # the case's datasheet oil moved to another inlet temperature: the same message
    r = run(*base, "--thermal", "--case", "andreou2023_thermal", "--inlet-temperature", "-100")
    assert r.exit_code != 0
    assert "--inlet-temperature must be >= -73.15 and <= 326.85 [°C] (got -100)" in r.output
    r = run(*base, "--oil", "5W-30", "--inlet-temperature", "nan")
    assert "--inlet-temperature must be >= -73.15 and <= 326.85 [°C] (got nan)" in r.output


def test_oil_without_thermal_sets_the_isothermal_lubricant():
    """``--oil 5W-30 --inlet-temperature 90`` without ``--thermal``: the isothermal solve
    uses the oil at 90 °C (μ₀, α, ρ₀ as the thermal solver derives them), not the given
    0.055 Pa·s, and says so; h_c follows Pan & Hamrock with that oil's μ₀ and α."""
    from tribodyn import Body, Material, solve_ehl
    from tribodyn.physics.oils import OILS
    from tribodyn.physics.thermal_oil import ThermalLubricant

    base = ["--load", "633", "--radius", "0.01", "--ue", "5", "--us", "2", "--json"]
    r = run(*base, "--oil", "5W-30", "--inlet-temperature", "90")
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    default = json.loads(run(*base, *PAPER_OIL).stdout)
    sheet = {k: v for k, v in OILS["5W-30"].items() if k != "description"}
    oil = ThermalLubricant(90.0 + 273.15, **sheet, name="5W-30").isothermal()
    assert out["oil"] == "5W-30" and out["thermal"] is False
    assert out["inlet_temperature_K"] == pytest.approx(363.15)
    assert out["viscosity_Pa_s"] == pytest.approx(oil.viscosity, rel=1e-12)
    assert out["pressure_viscosity_per_Pa"] == pytest.approx(oil.pressure_viscosity, rel=1e-12)
    assert out["density_kg_per_m3"] == pytest.approx(oil.density, rel=1e-12)
    w = 633 / 0.012
    W, U, G = hamrock_groups(w, 0.01, 5.0, oil.viscosity, oil.pressure_viscosity, E_STEEL_PAIR)
    assert out["central_film_m"] == pytest.approx(pan_hamrock(W, U, G, 0.01)[0], rel=0.05)
    steel = Body(Material(210e9, 0.3))
    api = solve_ehl(w, 0.01, 5.0, 2.0, (steel, steel), oil)
    assert out["central_film_m"] == pytest.approx(api.central_film, rel=1e-9)
    assert out["central_film_m"] < 0.6 * default["central_film_m"]  # 0.011 vs 0.055 Pa·s
    assert default["oil"] is None


def test_stress_peaks_and_margins_in_json_and_table():
    """--stress: the cam's (steel, homogeneous) von Mises peak of a heavily loaded, slowly
    entrained contact is Johnson's 0.557 p0 at 0.70 b of the Hertz pressure (the EHL
    pressure is nearly Hertzian there); its margin is Tabor's H/3 of steel over it."""
    args = ["--surface-set", "dlc_4um", "--load-per-length", "4e5", "--radius", "0.01"]
    args += ["--ue", "0.5", "--us", "0.0", "--n", "512", "--stress"]
    r = run(*args, "--json")
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    st = out["stress"]
    p0, b = out["hertz_max_pressure_Pa"], out["hertz_half_width_m"]
    assert st["cam_max_von_mises_substrate_Pa"] == pytest.approx(0.557 * p0, rel=0.03)
    assert st["cam_max_von_mises_substrate_z_m"] == pytest.approx(0.70 * b, abs=0.06 * b)
    assert st["cam_max_von_mises_coating_Pa"] is None  # the cam is uncoated
    assert st["safety_factor_cam_substrate_yield"] == pytest.approx(
        7e9 / 3.0 / st["cam_max_von_mises_substrate_Pa"], rel=1e-12
    )
    w = st["closest_failure"]
    factors = {k: v for k, v in st.items() if k.startswith("safety_factor_") and v is not None}
    assert w["safety_factor"] == min(factors.values())
    t = run(*args)
    assert t.exit_code == 0, t.output
    assert "closest to failure" in t.stdout and "interface shear" in t.stdout
    d = run("--dry", "--load", "633", "--radius", "0.01", "--stress")
    assert d.exit_code == 2 and "--dry" in d.output


@pytest.mark.parametrize(
    "option, value, section, key, toml_value",
    [
        ("--viscosity", "1e-6", "lubricant", "viscosity", "1e-6"),
        ("--viscous-model", "foo", "numerics", "viscous_model", '"foo"'),
        ("--eyring-stress", "-3", "lubricant", "eyring_stress", "-3.0"),
    ],
)
def test_bad_override_gives_the_case_file_error(tmp_path, option, value, section, key, toml_value):
    """A lubricant or numerics option is a case update: its error is the case file's
    message for the same key, with the option named in front."""
    from tribodyn import InputError
    from tribodyn.config import load_case

    path = tmp_path / "bad.toml"
    path.write_text(f"[{section}]\n{key} = {toml_value}\n", encoding="utf-8")
    with pytest.raises(InputError) as info:
        load_case(path)
    lines = [ln.strip() for ln in str(info.value).splitlines()]
    line = [ln for ln in lines if ln.startswith(f"{section}.{key}:")]
    assert len(line) == 1, lines
    r = run("--load", "600", "--radius", "0.01", "--ue", "1", option, value)
    assert r.exit_code == 2 and "Traceback" not in r.output
    assert option in r.output and line[0] in r.output


def test_contact_request_is_the_keyword_call():
    """compute_contact takes one ContactRequest, or its fields as keywords (as before)."""
    from tribodyn.cli.contact import ContactRequest, compute_contact

    kw = dict(load=633.0, radius=0.01, ue=5.0, us=2.0, viscosity=0.03, n=256)
    a = compute_contact(ContactRequest(**kw))
    b = compute_contact(**kw)
    assert a == b and a["viscosity_Pa_s"] == 0.03


def test_shear_options_set_the_oil_of_oil_and_thermal():
    """--eyring-stress and --limiting-shear-coefficient with --oil (isothermal) or
    --thermal: the oil's τ_E and Λ are the given ones; the output shows them and its
    friction is the solver's with that oil (Python API), not the oil's default."""
    import dataclasses

    from tribodyn import Body, Material, solve_ehl
    from tribodyn.config import load_case
    from tribodyn.physics.oils import OILS
    from tribodyn.physics.thermal_oil import ThermalLubricant
    from tribodyn.workflow.point import point_surfaces, solve_point

    base = ["--load", "2400", "--radius", "0.01", "--ue", "2", "--us", "2", "--json"]
    shear = ["--eyring-stress", "5e7", "--limiting-shear-coefficient", "0.05"]
    r = run(*base, "--oil", "5W-30", "--inlet-temperature", "90", *shear)
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    assert out["eyring_stress_Pa"] == 5e7 and out["limiting_shear_coefficient"] == 0.05
    sheet = {k: v for k, v in OILS["5W-30"].items() if k != "description"}
    oil = ThermalLubricant(
        363.15, **sheet, eyring_stress=5e7, limiting_shear_coefficient=0.05, name="5W-30"
    )
    steel = Body(Material(210e9, 0.3))
    api = solve_ehl(2400 / 0.012, 0.01, 2.0, 2.0, (steel, steel), oil.isothermal())
    assert out["friction_coefficient"] == pytest.approx(api.friction_coefficient, rel=1e-9)
    plain = json.loads(run(*base, "--oil", "5W-30", "--inlet-temperature", "90").stdout)
    assert plain["eyring_stress_Pa"] == 5e6  # the oil's default, typical τ_E
    assert out["friction_coefficient"] > 1.2 * plain["friction_coefficient"]  # 0.048, 0.036

    r = run(*base, "--thermal", "--case", "andreou2023_thermal", "--n", "128", *shear[:2])
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    assert out["eyring_stress_Pa"] == 5e7 and out["thermal"] is True
    case = load_case("andreou2023_thermal").updated({"numerics.n": 128})
    thermal_oil = dataclasses.replace(build(case).thermal_oil(), eyring_stress=5e7)
    ref = solve_point(
        case,
        point_surfaces(case),
        load_per_length=2400 / case.cam_config.width,
        radius=0.01,
        width=case.cam_config.width,
        entrainment_speed=2.0,
        sliding_speed=2.0,
        thermal_oil=thermal_oil,
    )
    assert out["friction_N"] == pytest.approx(ref["friction_N"], rel=1e-9)


@pytest.mark.parametrize(
    "extra",
    [
        ["--viscous-model", "foo"],
        ["--viscosity", "0.02"],
        ["--eyring-stress", "5e7"],
        ["--no-limiting-shear"],
        ["--inlet-temperature", "90"],
        ["--oil", "5W-30", "--inlet-temperature", "90"],
        ["--thermal"],
    ],
)
def test_dry_rejects_the_lubricant_and_numerics_options(extra):
    """--dry has no oil or film: a lubricant or EHL numerics option is an error naming it
    (not silently dropped); --n (the dry grid) is allowed."""
    r = run("--dry", "--load", "633", "--radius", "0.01", *extra)
    assert r.exit_code == 2 and "Traceback" not in r.output
    named = extra[0].replace("--no-", "--")
    assert named in r.output and "not with --dry" in r.output


def test_dry_takes_its_grid():
    r = run("--dry", "--load", "633", "--radius", "0.01", "--n", "256", "--json")
    assert r.exit_code == 0, r.output
