"""Each case value with a range is checked once, where it enters: by the physics
constructor it is given to, or (no constructor checks it) by the schema. Every key with a
range is checked, and the message names the key and the range with its unit."""

from __future__ import annotations

import copy
import tomllib
from collections import Counter

import pytest

from tribodyn import InputError, _validation
from tribodyn.config import schema, schema_surfaces, schema_valvetrain
from tribodyn.config.build import THERMAL_KEYS as THERMAL_ARGUMENT_KEYS
from tribodyn.config.build import build
from tribodyn.config.case import DEFAULT_CASE, Case
from tribodyn.config.paths import set_path
from tribodyn.config.schema_fields import Section
from tribodyn.contact.ehl import thermal_field
from tribodyn.physics import heat_conduction, thermal_oil
from tribodyn.physics import limits as L

#: where each section with ranged keys sits in the bundled paper case
PLACES = {
    schema.Engine: "engine",
    schema.AuxiliaryFrictionConfig: "engine.auxiliary",
    schema.AccelerationCamConfig: "cam",
    schema.Valvetrain: "valvetrain",
    schema.LubricantConfig: "lubricant",
    schema.MaterialConfig: "materials.steel",
    schema.SurfaceSetConfig: "surface_sets[1]",
    schema.RoughnessConfig: "surface_sets[1].roughness",
    schema.Numerics: "numerics",
}
#: sections whose ranged keys are those of a placed section (the other cam types)
SAME_AS = {
    schema.CircularArcCamConfig: schema.AccelerationCamConfig,
    schema.TableCamConfig: schema.AccelerationCamConfig,
    schema_valvetrain._CamBase: schema.AccelerationCamConfig,
}


def _ranged(model) -> dict[str, dict]:
    """The keys of ``model`` that record a shared limit's range, with that range."""
    out = {}
    for name, fi in model.model_fields.items():
        extra = fi.json_schema_extra if isinstance(fi.json_schema_extra, dict) else {}
        if "range" in extra:
            out[fi.alias or name] = extra
    return out


def _sections() -> set[type]:
    mods = (schema, schema_surfaces, schema_valvetrain)
    return {
        v
        for m in mods
        for v in vars(m).values()
        if isinstance(v, type) and issubclass(v, Section) and v is not Section
    }


KEYS = [
    (f"{place}.{key}", extra, model.model_fields[key].annotation)
    for model, place in PLACES.items()
    for key, extra in _ranged(model).items()
]


def _paper_data() -> dict:
    return tomllib.loads(DEFAULT_CASE.read_text(encoding="utf-8"))


#: the datasheet keys of [lubricant] (valid with a datasheet only), with values to give
DATASHEET = {
    "kinematic_viscosity_40_cst": 48.0,
    "kinematic_viscosity_100_cst": 8.6,
    "density_15": 850.0,
}
#: [lubricant] keys in another unit than their ThermalLubricant argument: key →
#: (argument, shared limit, argument = key × scale + offset)
CONVERTED = {
    "kinematic_viscosity_40_cst": ("kinematic_viscosity_40", L.KINEMATIC_VISCOSITY_40, 1e-6, 0),
    "kinematic_viscosity_100_cst": ("kinematic_viscosity_100", L.KINEMATIC_VISCOSITY_100, 1e-6, 0),
    "density_15": ("density", L.DENSITY, 1.0, 0.0),
    "inlet_temperature_c": ("inlet_temperature", L.OIL_TEMPERATURE, 1.0, 273.15),
}


def _datasheet_data(thermal: bool = False) -> dict:
    """The paper case with its oil given as datasheet keys at 90 °C."""
    data = _paper_data()
    for k in ("viscosity", "density", "pressure_viscosity"):
        data["lubricant"].pop(k, None)
    data["lubricant"].update(DATASHEET, inlet_temperature_c=90.0)
    data["numerics"]["thermal"] = thermal
    return data


def _data_for(key: str) -> dict:
    """The paper case, with a datasheet oil where ``key`` is one of its keys."""
    return _datasheet_data() if key.split(".")[-1] in DATASHEET else _paper_data()


def _outside(bounds: dict, integer: bool):
    """A value above the upper bound of ``bounds``."""
    top = bounds.get("le", bounds.get("lt"))
    assert top is not None
    v = top + max(1.0, abs(top))
    return int(v) if integer else float(v)


def _range_text(bounds: dict, unit: str, auto=None) -> str:
    """'> 0 m and <= 0.01 m' (degrees as °), the form of the case-file messages; a key
    whose ``auto`` value means automatic: '0 (automatic) or >= 32 and <= 4096'."""
    u = f" {unit}" if unit and not unit.startswith("deg") else ("°" if unit else "")
    sym = {"gt": ">", "ge": ">=", "lt": "<", "le": "<="}
    num = [(k, str(v) if isinstance(v, int) else f"{v:.6g}") for k, v in bounds.items()]
    text = " and ".join(
        f"{sym[k]} {v}{u}" for k, v in sorted(num, key=lambda kv: list(sym).index(kv[0]))
    )
    return text if auto is None else f"{auto} (automatic) or {text}"


def test_every_section_with_ranged_keys_is_placed():
    for model in _sections():
        ranged = _ranged(model)
        if not ranged or model in PLACES:
            continue
        assert model in SAME_AS, f"{model.__name__}: ranged keys {list(ranged)} not placed"
        assert set(ranged) <= set(_ranged(SAME_AS[model]))


def test_the_ranged_keys_are_the_shared_limits():
    assert len(KEYS) >= 50
    limits = {
        (lim.unit, tuple(lim.constraints().items()))
        for lim in vars(L).values()
        if isinstance(lim, L.Limit)
    }
    for key, extra, _ in KEYS:
        if key.split(".")[-1] in CONVERTED:  # below
            continue
        assert (extra["unit"], tuple(extra["range"].items())) in limits, key


@pytest.mark.parametrize("key", CONVERTED)
def test_a_key_in_another_unit_records_its_arguments_limit_in_its_unit(key):
    """lubricant.kinematic_viscosity_*_cst (mm²/s), density_15, inlet_temperature_c (°C):
    the range recorded is the ThermalLubricant argument's limit in the key's unit."""
    _, limit, scale, offset = CONVERTED[key]
    recorded = _ranged(schema.LubricantConfig)[key]["range"]
    expected = {k: (v - offset) / scale for k, v in limit.constraints().items()}
    assert recorded.keys() == expected.keys()
    assert recorded == pytest.approx(expected, rel=1e-12, abs=1e-9)


@pytest.mark.parametrize("key, extra, annotation", KEYS, ids=[k for k, _, _ in KEYS])
def test_every_ranged_key_is_checked_and_named(key, extra, annotation):
    value = _outside(extra["range"], "int" in str(annotation))
    data = copy.deepcopy(_data_for(key))
    set_path(data, key, value)
    with pytest.raises(InputError) as e:
        Case.from_dict(data, base_dir=DEFAULT_CASE.parent)
    msg = str(e.value)
    assert msg.startswith("invalid case: 1 problem\n"), msg
    expected = (
        f"{key}: must be {_range_text(extra['range'], extra['unit'], extra.get('auto'))} (got "
    )
    assert expected in msg, msg


def test_all_out_of_range_keys_of_a_file_are_reported_in_file_order():
    data = _paper_data()
    for key, value in (
        ("numerics.tol", 2.0),
        ("surface_sets[0].roughness.rms", 1.0),
        ("materials.wcc.E", 1.0),
        ("lubricant.viscosity", 300.0),
        ("valvetrain.spring_rate", -1.0),
        ("cam.width", 2.0),
    ):
        set_path(data, key, value)
    with pytest.raises(InputError) as e:
        Case.from_dict(data, base_dir=DEFAULT_CASE.parent)
    assert str(e.value).splitlines() == [
        "invalid case: 6 problems",
        "  cam.width: must be > 0 m and < 1 m (got 2.0)",
        "  valvetrain.spring_rate: must be > 0 N/m and <= 1e+07 N/m (got -1.0)",
        "  lubricant.viscosity: must be > 6.31499e-05 Pa·s and <= 100 Pa·s (got 300.0)",
        "  materials.wcc.E: must be >= 1e+06 Pa and <= 2e+12 Pa (got 1.0)",
        "  surface_sets[0].roughness.rms: must be > 0 m and < 0.0001 m (got 1.0)",
        "  numerics.tol: must be > 0 and < 1 (got 2.0)",
    ]


def test_every_value_of_a_set_out_of_range_is_reported():
    """A coated set whose coating thickness and roughness are both out of range: two
    objects of one set, both problems named (the coating's error does not hide the
    roughness's)."""
    data = _paper_data()
    set_path(data, "surface_sets[1].coating_thickness", 0.5)
    set_path(data, "surface_sets[1].roughness.rms", 0.5)
    with pytest.raises(InputError) as e:
        Case.from_dict(data, base_dir=DEFAULT_CASE.parent)
    assert str(e.value).splitlines() == [
        "invalid case: 2 problems",
        "  surface_sets[1].coating_thickness: must be > 0 m and <= 0.01 m (got 0.5)",
        "  surface_sets[1].roughness.rms: must be > 0 m and < 0.0001 m (got 0.5)",
    ]


def test_the_schema_problems_and_the_constructors_are_reported_together():
    data = _paper_data()
    for key, value in (
        ("engine.speed_rpm", -5.0),  # the schema's range
        ("valvetrain.tappet_radius", "wide"),  # the schema's type (the cam needs it)
        ("lubricant.viscosty", 0.05),  # unknown key
        ("lubricant.viscosity", 300.0),  # the constructors' ranges
        ("surface_sets[0].roughness.rms", 1.0),
        ("surface_sets[0].boundary_shear_strength", -1.0),
    ):
        set_path(data, key, value)
    with pytest.raises(InputError) as e:
        Case.from_dict(data, base_dir=DEFAULT_CASE.parent)
    lines = str(e.value).splitlines()
    assert lines[0] == "invalid case: 6 problems"
    assert [line.split(":")[0].strip() for line in lines[1:]] == [
        "engine.speed_rpm",
        "valvetrain.tappet_radius",
        "lubricant.viscosity",
        "lubricant.viscosty",
        "surface_sets[0].roughness.rms",
        "surface_sets[0].boundary_shear_strength",
    ]
    assert (
        lines[3] == "  lubricant.viscosity: must be > 6.31499e-05 Pa·s and <= 100 Pa·s (got 300.0)"
    )


def test_the_second_look_builds_no_surface_law(monkeypatch):
    """With schema problems, the constructors' ranges are checked without computing the
    sets' surface laws (the typical sets use them): the error comes at once."""
    from tribodyn.config import case as case_module

    calls = []
    monkeypatch.setattr(case_module, "measured_roughness", lambda *a: calls.append(a))
    with pytest.raises(InputError) as e:
        Case.from_dict({"lubricant": {"viscosity": 1e-5, "viscosty": 0.05}})
    assert [line.split(":")[0].strip() for line in str(e.value).splitlines()[1:]] == [
        "lubricant.viscosity",
        "lubricant.viscosty",
    ]
    assert calls == []


def _count_checks(monkeypatch, key=lambda limit, name, value: limit) -> Counter:
    """Count every ``Limit.check`` while the test runs, by ``key(limit, name, value)``."""
    calls: Counter = Counter()
    check = L.Limit.check

    def counting(self, name, value):
        calls[key(self, name, value)] += 1
        return check(self, name, value)

    monkeypatch.setattr(L.Limit, "check", counting)
    return calls


def _counted(calls: Counter, checker):
    """``checker`` (a ``check_*`` function) counting its calls by (name, value)."""

    def counting(name, value, *args, **kw):
        calls[name, value] += 1
        return checker(name, value, *args, **kw)

    return counting


def _checked_by_schema(field) -> bool:
    """Whether a schema field checks a bound itself (pydantic constraints)."""
    return any(getattr(m, b, None) is not None for m in field.metadata for b in L_BOUNDS)


def test_loading_checks_each_value_once(monkeypatch):
    """Each material's E, the tolerance, the spring rate, each set's σ and coating
    thickness: one range check each while the paper case loads."""
    data = _paper_data()
    calls = _count_checks(monkeypatch)
    Case.from_dict(data, base_dir=DEFAULT_CASE.parent)
    sets = data["surface_sets"]
    assert calls[L.YOUNGS_MODULUS] == len(data["materials"])
    assert calls[L.NEWTON_TOL] == 1
    assert calls[L.SPRING_RATE] == 1
    assert calls[L.ROUGHNESS_RMS] == len(sets)
    assert calls[L.COATING_THICKNESS] == sum("coating" in s for s in sets)
    assert calls[L.BOUNDARY_SHEAR_STRENGTH] == len(sets) + 1  # each set's, the default's
    # ς: a material's by the schema, not again by each set that takes it; the default's
    own = sum("boundary_shear_coefficient" in s for s in sets)
    assert calls[L.BOUNDARY_SHEAR_COEFFICIENT] == own + 1


def test_a_check_left_out_is_seen(monkeypatch):
    """The key test fails when a constructor no longer checks its argument."""
    from tribodyn.valvetrain import parameters

    monkeypatch.setattr(
        parameters, "_LIMITS", {k: v for k, v in parameters._LIMITS.items() if k != "lash"}
    )
    key = "valvetrain.lash"
    extra = _ranged(schema.Valvetrain)["lash"]
    with pytest.raises(pytest.fail.Exception):
        test_every_ranged_key_is_checked_and_named(key, extra, float)


@pytest.mark.parametrize("form", ["inlet", "datasheet"])
def test_a_thermal_oil_checks_the_lubricant_values_once(monkeypatch, form):
    """The thermal oil takes the values the isothermal oil checked (inlet form), and its
    isothermal oil at the inlet takes those the thermal oil checked (datasheet): each
    lubricant limit runs once; each material's thermal properties are checked once, by
    its ThermalProperties (not by the schema too), and each thermal oil key by the thermal
    oil."""
    data = _paper_data()
    data["numerics"]["thermal"] = True
    data["lubricant"]["inlet_temperature_c"] = 90.0
    if form == "inlet":
        data["lubricant"]["viscosity_temperature_coefficient"] = 0.03
    else:
        for k in ("viscosity", "pressure_viscosity", "density"):
            data["lubricant"].pop(k, None)
        data["lubricant"]["oil"] = "5W-20"
    calls = _count_checks(monkeypatch)
    data["lubricant"]["thermal_expansion"] = 7e-4  # given: not checked by the schema too
    data["lubricant"]["limiting_shear_temperature_coefficient"] = 0.01
    data["lubricant"]["thermal_conductivity"] = 0.13
    data["lubricant"]["specific_heat"] = 2000.0
    data["materials"]["steel"].update(
        thermal_conductivity=40.0, density=7800.0, specific_heat=450.0
    )
    Case.from_dict(data, base_dir=DEFAULT_CASE.parent)
    for lim in (L.SOLID_CONDUCTIVITY, L.SOLID_DENSITY, L.SOLID_SPECIFIC_HEAT):
        assert calls[lim] == len(data["materials"])  # once each, not per set
    for lim in (L.THERMAL_EXPANSION, L.LIMITING_SHEAR_TEMPERATURE):
        assert calls[lim] == 1
    assert calls[L.OIL_CONDUCTIVITY] == calls[L.OIL_SPECIFIC_HEAT] == 1
    assert calls[L.VISCOSITY_TEMPERATURE] == (1 if form == "inlet" else 0)
    for lim in (L.EYRING_STRESS, L.LIMITING_SHEAR_COEFFICIENT, L.LIMITING_SHEAR_STRESS):
        assert calls[lim] == 1
    assert calls[L.PRESSURE_VISCOSITY] == 1  # given (inlet), estimated (datasheet)
    assert calls[L.VISCOSITY] == (1 if form == "inlet" else 0)  # datasheet: μ(Tᵢ) bounds
    # the given density (inlet); the datasheet's at 15 °C and its oil's ρ(0, Tᵢ) (two values)
    assert calls[L.DENSITY] == (1 if form == "inlet" else 2)


L_BOUNDS = ("gt", "ge", "lt", "le")
#: thermal keys of the paper case made thermal (inlet-form oil), with values to give
THERMAL_KEYS = {
    "lubricant.thermal_expansion": 7e-4,
    "lubricant.limiting_shear_temperature_coefficient": 0.01,
    "lubricant.thermal_conductivity": 0.13,
    "lubricant.specific_heat": 2000.0,
    "lubricant.viscosity_temperature_coefficient": 0.03,
    "materials.steel.thermal_conductivity": 40.0,
    "materials.steel.density": 7800.0,
    "materials.steel.specific_heat": 450.0,
}


def _thermal_data() -> dict:
    data = _paper_data()
    data["numerics"]["thermal"] = True
    data["lubricant"]["inlet_temperature_c"] = 90.0
    for key, value in THERMAL_KEYS.items():
        set_path(data, key, value)
    return data


def test_each_thermal_key_is_checked_once(monkeypatch):
    """A thermal case: each thermal key given is range-checked once, by the constructor
    that takes it (ThermalLubricant, ThermalProperties), not by the schema too."""
    # (argument, value) of each constructor check
    seen = _count_checks(monkeypatch, key=lambda limit, name, value: (name, value))
    for module in (thermal_oil, heat_conduction):
        if hasattr(module, "check_range"):
            monkeypatch.setattr(module, "check_range", _counted(seen, _validation.check_range))
    case = Case.from_dict(_thermal_data(), base_dir=DEFAULT_CASE.parent)
    for key, value in THERMAL_KEYS.items():
        section, name = key.rsplit(".", 1)
        oil = section == "lubricant"
        model = case.lubricant_config if oil else case.materials["steel"]
        by_schema = _checked_by_schema(type(model).model_fields[name])
        arg = name if oil or name != "thermal_conductivity" else "conductivity"
        assert seen[arg, value] + by_schema == 1, key


@pytest.mark.parametrize("key", THERMAL_KEYS)
def test_each_thermal_key_out_of_range_is_one_problem(key):
    extra = _ranged(
        schema.LubricantConfig if key.startswith("lubricant") else schema.MaterialConfig
    )
    bounds = extra[key.rsplit(".", 1)[1]]
    data = _thermal_data()
    set_path(data, key, _outside(bounds["range"], False))
    with pytest.raises(InputError) as e:
        Case.from_dict(data, base_dir=DEFAULT_CASE.parent)
    msg = str(e.value)
    assert msg.startswith("invalid case: 1 problem\n"), msg
    assert f"{key}: must be {_range_text(bounds['range'], bounds['unit'])} (got " in msg, msg


def test_a_thermal_key_out_of_range_is_reported_beside_a_schema_problem():
    """The constructors' range problems of keys whose unit has parentheses (W/(m K)) are
    listed with the schema's problems."""
    data = _paper_data()
    set_path(data, "engine.speed_rpm", -5.0)
    set_path(data, "materials.dlc.thermal_conductivity", 1e9)
    set_path(data, "lubricant.specific_heat", 1.0)
    with pytest.raises(InputError) as e:
        Case.from_dict(data, base_dir=DEFAULT_CASE.parent)
    assert [line.split(":")[0].strip() for line in str(e.value).splitlines()] == [
        "invalid case",
        "engine.speed_rpm",
        "lubricant.specific_heat",
        "materials.dlc.thermal_conductivity",
    ]


#: the [numerics] keys of ThermalOptions, by argument (the build's mapping)
NUMERICS_THERMAL = {arg: key.split(".", 1)[1] for arg, key in THERMAL_ARGUMENT_KEYS.items()}


def test_the_thermal_numerics_keys_record_the_thermal_options_ranges():
    """numerics.thermal_* record the ranges ThermalOptions checks (one Limit each), not
    ranges of their own."""
    ranged = _ranged(schema.Numerics)
    assert set(NUMERICS_THERMAL.values()) <= set(ranged)
    for arg, key in NUMERICS_THERMAL.items():
        limit = thermal_field._LIMITS[arg]
        assert ranged[key] == {"unit": limit.unit, "range": limit.constraints()}, key


@pytest.mark.parametrize("arg", NUMERICS_THERMAL)
def test_a_thermal_numerics_bound_is_accepted_by_the_case_and_the_solver(arg):
    """The bound of each numerics.thermal_* key is inside the one range both use."""
    limit = thermal_field._LIMITS[arg]
    top = limit.le if limit.le is not None else limit.lt
    value = int(top) if limit.integer else top
    data = _paper_data()
    set_path(data, f"numerics.{NUMERICS_THERMAL[arg]}", value)
    built = build(Case.from_dict(data, base_dir=DEFAULT_CASE.parent))
    assert getattr(built.thermal_options, arg) == value


@pytest.mark.parametrize("thermal", [False, True], ids=["isothermal", "thermal"])
def test_each_thermal_numerics_key_is_checked_once(monkeypatch, thermal):
    """Each numerics.thermal_* value given is range-checked once, by ThermalOptions (not
    by the schema too), also in a case that is not thermal."""
    values = {"x_nodes": 80, "film_nodes": 9, "solid_nodes": 14, "step_iter": 3, "tol": 0.04}
    data = _thermal_data() if thermal else _paper_data()
    for arg, value in values.items():
        data["numerics"][NUMERICS_THERMAL[arg]] = value
    seen = _count_checks(monkeypatch, key=lambda limit, name, value: (name, value))
    for name in ("check_int", "check_positive", "check_range"):  # the checks of the solver
        if hasattr(thermal_field, name):
            monkeypatch.setattr(thermal_field, name, _counted(seen, getattr(thermal_field, name)))
    case = Case.from_dict(data, base_dir=DEFAULT_CASE.parent)
    for arg, value in values.items():
        by_schema = _checked_by_schema(schema.Numerics.model_fields[NUMERICS_THERMAL[arg]])
        assert seen[arg, value] + by_schema == 1, arg
        assert getattr(build(case).thermal_options, arg) == value


#: the grid keys: 0 (automatic) or a node count, one range (the cycle's transient grid)
GRID_KEYS = ("numerics.n", "numerics.coupling_n")


@pytest.mark.parametrize("key", GRID_KEYS)
@pytest.mark.parametrize("value", [16, 8192, -1])
def test_a_grid_key_out_of_range_is_one_problem_with_the_full_range(key, value):
    """Below 32, above 4096 or negative: one line naming the key and the whole range."""
    data = _paper_data()
    set_path(data, key, value)
    with pytest.raises(InputError) as e:
        Case.from_dict(data, base_dir=DEFAULT_CASE.parent)
    assert str(e.value).splitlines() == [
        "invalid case: 1 problem",
        f"  {key}: must be 0 (automatic) or >= 32 and <= 4096 (got {value})",
    ]


@pytest.mark.parametrize("nodes", [0, 32, 4096])
def test_each_grid_key_is_checked_once(monkeypatch, nodes):
    """numerics.n and numerics.coupling_n given: each range-checked once while the case
    loads and builds (not by the schema, not by EHLOptions again); 0 is the automatic
    grid (EHLOptions n=None)."""
    data = _paper_data()
    data["numerics"].update(n=nodes, coupling_n=nodes)
    seen = _count_checks(monkeypatch, key=lambda limit, name, value: name)
    case = Case.from_dict(data, base_dir=DEFAULT_CASE.parent)
    options = build(case).options
    for name in ("n", "coupling_n"):
        by_schema = _checked_by_schema(schema.Numerics.model_fields[name])
        assert seen[name] + by_schema == 1, name
    assert options.n == (nodes or None)


def test_the_transient_solver_checks_a_direct_n():
    """Options made directly (steady range, up to 65536 nodes): the transient solver
    names n and its range."""
    from ehl_cases import OIL, PAIR
    from tribodyn import EHLOptions, TransientEHL

    with pytest.raises(InputError, match=r"n must be an integer >= 32 and <= 4096 \(got 8192\)"):
        TransientEHL(PAIR, OIL, options=EHLOptions(n=8192))


@pytest.mark.parametrize("form", ["datasheet", "datasheet-thermal", "inlet-thermal", "isothermal"])
def test_each_key_in_another_unit_is_checked_once(monkeypatch, form):
    """The datasheet keys and inlet_temperature_c: each value given is range-checked once,
    under its ThermalLubricant argument's name and unit (the inlet form's density
    reference temperature, Tᵢ, not again), also where no thermal oil is built; not by the
    schema too."""
    if form.startswith("datasheet"):
        data = _datasheet_data(thermal=form == "datasheet-thermal")
    else:
        data = _paper_data()
        data["lubricant"]["inlet_temperature_c"] = 90.0
        if form == "inlet-thermal":
            data["lubricant"]["viscosity_temperature_coefficient"] = 0.03
            data["numerics"]["thermal"] = True
    seen = _count_checks(monkeypatch, key=lambda limit, name, value: (name, value))
    for name in ("check_positive", "check_range"):  # the oil's checks of other forms
        if hasattr(thermal_oil, name):
            monkeypatch.setattr(thermal_oil, name, _counted(seen, getattr(thermal_oil, name)))
    Case.from_dict(data, base_dir=DEFAULT_CASE.parent)
    lub = data["lubricant"]
    given = [k for k in CONVERTED if k in lub]
    assert given == (list(CONVERTED) if form.startswith("datasheet") else ["inlet_temperature_c"])
    for key in given:
        arg, _, scale, offset = CONVERTED[key]
        value = lub[key] * scale + offset
        again = seen["density_temperature", value] if arg == "inlet_temperature" else 0
        by_schema = _checked_by_schema(schema.LubricantConfig.model_fields[key])
        assert seen[arg, value] + again + by_schema == 1, key


@pytest.mark.parametrize("thermal", [False, True], ids=["isothermal", "thermal"])
def test_the_keys_in_another_unit_out_of_range_are_reported_together_in_their_units(thermal):
    """A datasheet whose keys are all out of range, beside a schema problem: one line per
    key, naming the key and its range in the key's unit (mm²/s, °C), all in one message."""
    data = _datasheet_data(thermal)
    set_path(data, "engine.speed_rpm", -5.0)
    data["lubricant"].update(
        kinematic_viscosity_40_cst=1.0,
        kinematic_viscosity_100_cst=2e4,
        density_15=6000.0,
        inlet_temperature_c=400.0,
    )
    with pytest.raises(InputError) as e:
        Case.from_dict(data, base_dir=DEFAULT_CASE.parent)
    lines = str(e.value).splitlines()
    assert lines[:2] == [
        "invalid case: 5 problems",
        "  engine.speed_rpm: must be > 0 rpm and <= 50000 rpm (got -5.0)",
    ]
    assert sorted(lines[2:]) == sorted(  # in [lubricant]: in the order the oil checks them
        [
            "  lubricant.kinematic_viscosity_40_cst: must be > 1.5 mm²/s and <= 100000 mm²/s (got 1.0)",
            "  lubricant.kinematic_viscosity_100_cst: must be >= 1.5 mm²/s and <= 10000 mm²/s "
            "(got 20000.0)",
            "  lubricant.density_15: must be > 0 kg/m³ and <= 5000 kg/m³ (got 6000.0)",
            "  lubricant.inlet_temperature_c: must be >= -73.15 °C and <= 326.85 °C (got 400.0)",
        ]
    )


def test_the_supply_film_is_checked_at_load_and_by_a_direct_caller_only(monkeypatch):
    """numerics.coupling_supply_film: checked once, by the schema at load; the coupling's
    film state takes it unchecked (``checked``); a film state made directly checks its
    supply film against the same limit."""
    from tribodyn.valvetrain.tribology import FilmStateTribology, Frictionless

    field = schema.Numerics.model_fields["coupling_supply_film"]
    assert _checked_by_schema(field)
    assert _ranged(schema.Numerics)["coupling_supply_film"]["range"] == {"gt": 0.0, "le": 1.0}
    oil = build(Case.from_dict(_paper_data(), base_dir=DEFAULT_CASE.parent)).lubricant
    seen = _count_checks(monkeypatch, key=lambda limit, name, value: name)
    kw = {"width": 0.012, "lubricant": oil, "e_prime": 2.3e11, "supply_film": 2e-5}
    assert FilmStateTribology(Frictionless(), **kw, checked=("supply_film",)).supply_film == 2e-5
    assert seen["supply_film"] == 0
    FilmStateTribology(Frictionless(), **kw)
    assert seen["supply_film"] == 1
    with pytest.raises(InputError, match=r"supply_film must be > 0 and <= 1 \[m\] \(got 2"):
        FilmStateTribology(Frictionless(), **(kw | {"supply_film": 2.0}))


def test_the_coupling_takes_the_supply_film_checked_at_load(monkeypatch):
    """The coupling passes numerics.coupling_supply_film on as checked (at load): its film
    states do not check it again."""
    from types import SimpleNamespace

    import numpy as np

    from tribodyn.cycle import coupling

    data = _paper_data()
    data["numerics"].update(implicit_coupling=True, coupling_supply_film=3e-5)
    built = build(Case.from_dict(data, base_dir=DEFAULT_CASE.parent))
    given: list[dict] = []

    class Stop(Exception):
        pass

    def film_state_tribology(*args, **kw):
        given.append(kw)
        raise Stop

    monkeypatch.setattr(coupling, "film_state_tribology", film_state_tribology)
    dynamics = SimpleNamespace(event_mask=lambda: np.ones(3, bool), contact_force=np.ones(3))
    with pytest.raises(Stop):
        coupling.run_coupling(built, built.surface_sets[0], dynamics, None, None)
    assert given == [{"supply_film": 3e-5, "checked": ("supply_film",)}]
