"""Sweep files and dotted case paths: parsing, selectors, validation before anything runs,
ranges, combination of axes, the plan and its point keys. No solver runs here."""

import math
import re
from pathlib import Path

import pytest

from tribodyn import InputError
from tribodyn.config import Case, load_case
from tribodyn.config.build import build
from tribodyn.config.paths import (
    All,
    Index,
    Key,
    Match,
    PathError,
    find_paths,
    format_path,
    parse_path,
    schema_field,
    set_path,
)
from tribodyn.config.schema import CAM_MODELS
from tribodyn.config.sweep import (
    AxisConfig,
    SweepFile,
    SweepInfo,
    SweepSpec,
    bundled_sweeps,
    load_sweep,
)

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def paper():
    return load_case()


def spec(text, **kw) -> SweepSpec:
    return SweepSpec.from_toml_string(text, **kw)


def problems(text) -> str:
    with pytest.raises(InputError) as exc:
        spec(text)
    return str(exc.value)


# ----------------------------------------------------------------------------- paths
def test_parse_and_format_round_trip():
    for p in (
        "engine.speed_rpm",
        "surface_sets[2].coating_thickness",
        "surface_sets[name=wcc_4um].coating_thickness",
        "surface_sets[*].roughness.rms",
        'materials."my mat".E',
        "materials[*].nu",
    ):
        assert format_path(parse_path(p)) == p
    assert parse_path('surface_sets[name="dlc_1um"].coating') == (
        Key("surface_sets"),
        Match("name", "dlc_1um"),
        Key("coating"),
    )
    assert parse_path("a[0][*].b") == (Key("a"), Index(0), All(), Key("b"))


@pytest.mark.parametrize(
    "bad", ["", "engine..speed", "engine.", "surface_sets[x].a", "[0].a", "engine speed", "a[1"]
)
def test_unparsable_paths(bad):
    with pytest.raises(PathError):
        parse_path(bad)


def get_path(data, path):
    """The values at every place ``path`` addresses."""
    return [value for _, value in find_paths(data, path)]


def test_set_path_selectors(paper):
    d = paper.to_dict()
    assert set_path(d, "surface_sets[name=wcc_4um].coating_thickness", 2e-6) == 1
    assert set_path(d, "surface_sets[*].roughness.rms", 0.3e-6) == 5
    assert set_path(d, "materials[*].nu", 0.29) == 3
    assert set_path(d, "surface_sets[1].boundary_shear_strength", 3e6) == 1
    assert get_path(d, "surface_sets[name=wcc_4um].coating_thickness") == [2e-6]
    assert get_path(d, "surface_sets[*].roughness.rms") == [0.3e-6] * 5
    assert get_path(d, "materials[*].nu") == [0.29] * 3
    assert d["surface_sets"][1]["boundary_shear_strength"] == 3e6
    assert d["surface_sets"][0]["boundary_shear_strength"] != 3e6


def test_set_path_errors_name_the_place(paper):
    d = paper.to_dict()
    with pytest.raises(
        PathError,
        match=r"surface_sets\[name=wcc_5um\]: no entry has name "
        r"= 'wcc_5um'.*did you mean 'wcc_4um'",
    ):
        set_path(d, "surface_sets[name=wcc_5um].coating_thickness", 1e-6)
    with pytest.raises(
        PathError,
        match=r"surface_sets\[9\]: index out of range \(the array "
        r"has 5 entries",
    ):
        set_path(d, "surface_sets[9].coating_thickness", 1e-6)
    with pytest.raises(PathError, match="needs an array"):
        set_path(d, "engine[0].speed_rpm", 1.0)
    with pytest.raises(PathError, match="must end on a key"):
        set_path(d, "surface_sets[0]", 1.0)


def test_case_updated_with_selectors(paper):
    c = paper.updated(
        {
            "surface_sets[name=wcc_4um].coating_thickness": 2e-6,
            "surface_sets[*].roughness.rms": 0.3e-6,
        }
    )
    assert build(c).set("wcc_4um").surface.coating.thickness == 2e-6
    assert build(c).set("wcc_1um").surface.coating.thickness == 1e-6
    assert all(s.roughness.rms == 0.3e-6 for s in build(c).surface_sets)


def test_schema_field_units_and_unknown_keys(paper):
    d = paper.to_dict()

    def unit(p):
        fi = schema_field(Case, p, d, variants={"cam": CAM_MODELS})
        return fi.json_schema_extra["unit"]

    assert unit("engine.speed_rpm") == "rpm"
    assert unit("materials.wcc.E") == "Pa"
    assert unit("surface_sets[name=wcc_4um].coating_thickness") == "m"
    assert unit("surface_sets[*].roughness.summit_radius") == "m"
    assert unit("cam.nose_radius") == "m"
    with pytest.raises(PathError, match="unknown key; did you mean 'speed_rpm'"):
        unit("engine.speed")
    # the key of another cam type is unknown for the case's acceleration cam
    with pytest.raises(PathError, match="cam.flank_radius: unknown key"):
        unit("cam.flank_radius")
    with pytest.raises(PathError, match="is a table"):
        unit("surface_sets[0].roughness")


# ----------------------------------------------------------------------------- validation
def test_minimal_sweep_and_defaults():
    s = spec('[[axes]]\npath = "engine.speed_rpm"\nvalues = [1000.0, 2000.0]')
    assert s.mode == "study" and not s.traces and s.base.name == "andreou2023"
    assert s.shape == (2,) and s.n_points == 2
    a = s.axes[0]
    assert (a.name, a.unit, a.dim, a.values) == ("speed_rpm", "rpm", "speed_rpm", (1000.0, 2000.0))


def test_errors_are_collected_and_name_the_key():
    msg = problems('[sweep]\nmod = "study"\n[[axes]]\npath = "engine.speed_rpm"\nvalues = [1000.0]')
    assert "sweep.mod: unknown key; did you mean 'mode'?" in msg
    msg = problems(
        '[[axes]]\npath = "engine.speed"\nvalues = [1.0]\n'
        '[[axes]]\npath = "surface_sets[name=wcc_5um].coating_thickness"\n'
        "values = [1e-6]\n"
        '[[axes]]\npath = "lubricant.viscosity"\nvalues = [0.05, 1e-6, 200.0]'
    )
    assert msg.startswith("invalid sweep: 4 problems")
    assert "axes[0].path: engine.speed: unknown key; did you mean 'speed_rpm'?" in msg
    assert "axes[1].path: surface_sets[name=wcc_5um]: no entry has name" in msg
    assert re.search(
        r"axes\[2\]\.values\[1\]: 1e-06: lubricant\.viscosity: must be > "
        r"6\.31499e-05 Pa·s and <= 100 Pa·s",
        msg,
    )
    assert "axes[2].values[2]: 200: lubricant.viscosity" in msg
    assert "axes[2].values[0]" not in msg


def test_range_values_out_of_range_are_rejected():
    msg = problems(
        '[[axes]]\npath = "lubricant.viscosity"\nstart = 1e-6\nstop = 0.1\nnum = 4\nspacing = "log"'
    )
    assert "axes[0] (range value 1 of 4): 1e-06: lubricant.viscosity: must be >" in msg
    assert "(range value 3 of 4)" not in msg


@pytest.mark.parametrize(
    "text, expected",
    [
        (
            '[[axes]]\npath = "engine.speed_rpm"\nvalues = [1000.0, "fast"]',
            "axes[0].values: must all be numbers, all strings or all booleans",
        ),
        (
            '[[axes]]\npath = "engine.speed_rpm"\nvalues = [1000.0]\nstart = 1',
            "axes[0].start: give either values or a range",
        ),
        ('[[axes]]\npath = "engine.speed_rpm"\nstart = 1000', "axes[0].stop: required key"),
        (
            '[[axes]]\npath = "engine.speed_rpm"\nstart = 1000\nstop = 2000',
            "axes[0].num: give exactly one of num and step",
        ),
        (
            '[[axes]]\npath = "engine.speed_rpm"\nstart = 1000\nstop = 2000\nstep = -5',
            "axes[0].step: must be > 0",
        ),
        (
            '[[axes]]\npath = "engine.speed_rpm"\nstart = 0\nstop = 2000\nnum = 3\nspacing = "log"',
            "axes[0].start: a log range needs start > 0",
        ),
        (
            '[[axes]]\npath = "numerics.n"\nstart = 64\nstop = 200\nnum = 4',
            "axes[0].values: numerics.n takes integers (got 109.333)",
        ),
        (
            '[[axes]]\npath = "engine.speed_rpm"\nvalues = ["fast"]',
            "axes[0].values[0]: fast: engine.speed_rpm: must be a number",
        ),
        ('[sweep]\nname = "x"', "axes: required key is missing"),
        (
            '[sweep]\ncombine = "zip"\n[[axes]]\npath = "engine.speed_rpm"\n'
            'values = [1000.0, 2000.0]\n[[axes]]\npath = "lubricant.viscosity"\nvalues = [0.01]',
            "sweep.combine: zipped axes need the same number of values (speed_rpm: 2, "
            "viscosity: 1)",
        ),
        (
            '[[axes]]\npath = "engine.speed_rpm"\nvalues = [1000.0]\n[[axes]]\n'
            'path = "engine.speed_rpm"\nvalues = [2000.0]\nname = "n2"',
            "axes[1].path: 'engine.speed_rpm' is swept twice",
        ),
        (
            '[[axes]]\npath = "surface_sets[*].roughness.rms"\nvalues = [1e-7]\n[[axes]]\n'
            'path = "materials.steel.rms"\nvalues = [1.0]',
            "axes[1].path: materials.steel.rms: unknown key",
        ),
        (
            '[[axes]]\npath = "surface_sets[0].roughness.rms"\nvalues = [1e-7]\n[[axes]]\n'
            'path = "surface_sets[1].roughness.rms"\nvalues = [1e-7]',
            "axes[1].name: duplicate dimension name 'rms'",
        ),
        (
            '[[axes]]\npath = "engine.speed_rpm"\nvalues = [1e3]\nname = "status"',
            "axes[0].name: 'status' is reserved",
        ),
        (
            '[fixed]\n"numerics.crank_stp_deg" = 2.0\n[[axes]]\npath = "engine.speed_rpm"\n'
            "values = [1000.0]",
            'fixed."numerics.crank_stp_deg": numerics.crank_stp_deg: '
            "unknown key; did you mean 'crank_step_deg'?",
        ),
        (
            '[fixed]\n"numerics.crank_step_deg" = 20.0\n[[axes]]\npath = "engine.speed_rpm"\n'
            "values = [1000.0]",
            "fixed: numerics.crank_step_deg: must be > 0° and <= 5°",
        ),
        (
            '[sweep]\ncase = "nope.toml"\n[[axes]]\npath = "engine.speed_rpm"\nvalues = [1e3]',
            "sweep.case: no case file",
        ),
        (
            '[[axes]]\npath = "engine.speed_rpm"\nvalues = [1000.0]\n[[axes]]\npath = "cam.type"'
            '\nvalues = ["circular_arc"]\n',
            "axes[1].values[0]: circular_arc: cam.event_angle_deg: "
            "unknown key for cam type 'circular_arc'",
        ),
    ],
)
def test_sweep_file_problems(text, expected):
    if expected is None:  # valid file; the combination is judged per point
        spec(text)
        return
    assert expected in problems(text)


def test_ranges():
    s = spec(
        '[[axes]]\npath = "engine.speed_rpm"\nstart = 1000\nstop = 7000\nstep = 1000\n'
        '[[axes]]\npath = "lubricant.viscosity"\nstart = 0.01\nstop = 0.1\nnum = 3\n'
        'spacing = "log"\n'
        '[[axes]]\npath = "numerics.n"\nstart = 64\nstop = 256\nnum = 4'
    )
    speed, visc, n = s.axes
    assert speed.values == (1000, 2000, 3000, 4000, 5000, 6000, 7000)
    assert all(isinstance(v, int) for v in speed.values)
    assert visc.values[0] == 0.01 and visc.values[-1] == 0.1
    assert math.isclose(visc.values[1], math.sqrt(0.01 * 0.1), rel_tol=1e-12)
    assert n.values == (64, 128, 192, 256)
    assert s.shape == (7, 3, 4) and s.n_points == 84
    # a step that does not divide the span stops at or before stop
    s = spec('[[axes]]\npath = "engine.speed_rpm"\nstart = 1000.0\nstop = 2000.0\nstep = 300.0')
    assert s.axes[0].values == (1000.0, 1300.0, 1600.0, 1900.0)


def test_product_zip_and_groups():
    text = (
        '[[axes]]\npath = "engine.speed_rpm"\nvalues = [1000.0, 2000.0, 3000.0]\n'
        '[[axes]]\npath = "lubricant.viscosity"\nvalues = [0.02, 0.05]\ngroup = "oil"\n'
        '[[axes]]\npath = "lubricant.pressure_viscosity"\nvalues = [1.5e-8, 2e-8]\n'
        'group = "oil"\n'
    )
    s = spec(text)
    assert [(d, [a.name for a in ax]) for d, ax in s.dims] == [
        ("speed_rpm", ["speed_rpm"]),
        ("oil", ["viscosity", "pressure_viscosity"]),
    ]
    assert s.shape == (3, 2)
    pts = s.points()
    assert len(pts) == 6 and [p.index for p in pts] == list(range(6))
    # C order: the last dimension varies fastest; zipped axes move together
    assert pts[1].values == {"speed_rpm": 1000.0, "viscosity": 0.05, "pressure_viscosity": 2e-8}
    assert pts[1].case.lubricant_config.pressure_viscosity == 2e-8
    assert pts[4].position == (2, 0) and pts[4].case.engine_speed == 3000.0
    with pytest.raises(InputError, match="zipped axes need the same number"):
        spec('[sweep]\ncombine = "zip"\n' + text)


def test_zip_combines_everything():
    s = spec(
        '[sweep]\ncombine = "zip"\n[[axes]]\npath = "engine.speed_rpm"\n'
        'values = [1000.0, 2000.0]\n[[axes]]\npath = "lubricant.viscosity"\n'
        "values = [0.02, 0.05]\n"
    )
    assert s.shape == (2,) and s.dims[0][0] == "speed_rpm"
    assert [p.values for p in s.points()] == [
        {"speed_rpm": 1000.0, "viscosity": 0.02},
        {"speed_rpm": 2000.0, "viscosity": 0.05},
    ]


def test_invalid_combination_is_a_failed_point_not_a_rejected_file():
    """Each value is valid alone (validated up front); one combination is not: a lift of
    9.9 mm needs a contact offset beyond a 14.5 mm tappet radius."""
    s = spec(
        '[[axes]]\npath = "cam.max_lift"\nvalues = [0.0093, 0.0099]\n'
        '[[axes]]\npath = "valvetrain.tappet_radius"\nvalues = [0.0165, 0.0145]\n'
    )
    pts = s.points()
    bad = [p for p in pts if p.case is None]
    assert [p.values for p in bad] == [{"max_lift": 0.0099, "tappet_radius": 0.0145}]
    assert bad[0].error.startswith("invalid combination: cam: ")
    assert "tappet radius" in bad[0].error


def test_point_keys_identify_the_case():
    s = spec('[[axes]]\npath = "engine.speed_rpm"\nvalues = [1000.0, 2000.0, 1000.0]\nname = "n"')
    k = [p.key for p in s.points()]
    assert k[0] == k[2] != k[1] and all(re.fullmatch(r"[0-9a-f]{16}", x) for x in k)
    # the same case in another sweep has the same key; another mode does not
    t = spec('[[axes]]\npath = "engine.speed_rpm"\nvalues = [2000.0]')
    assert t.points()[0].key == k[1]
    d = spec('[sweep]\nmode = "dynamics"\n[[axes]]\npath = "engine.speed_rpm"\nvalues = [2000.0]')
    assert d.points()[0].key != k[1]


def test_fixed_changes_and_base_case_file(tmp_path):
    case = tmp_path / "c.toml"
    load_case().updated({"engine.speed_rpm": 2500.0}).write_toml(case)
    f = tmp_path / "s.toml"
    f.write_text(
        '[sweep]\ncase = "c.toml"\n[fixed]\n"numerics.implicit_coupling" = false\n'
        '"surface_sets[*].boundary_shear_strength" = 1e6\n'
        '[[axes]]\npath = "lubricant.viscosity"\nvalues = [0.02]\n'
    )
    s = load_sweep(f)
    assert s.base.engine_speed == 2500.0 and not s.base.numerics.implicit_coupling
    assert all(c.boundary_shear_strength == 1e6 for c in s.base.surface_set_configs)
    assert s.base_source == str(case.resolve())
    again = SweepSpec.from_toml_string(s.to_toml())
    assert [p.key for p in again.points()] == [p.key for p in s.points()]


def test_bundled_sweeps():
    assert {"andreou2023_speed", "andreou2023_dynamics"} <= set(bundled_sweeps())
    s = load_sweep("andreou2023_speed")
    assert s.mode == "study" and s.axes[0].values == tuple(range(1000, 7001, 1000))
    assert s.base.surface_set_names == ["uncoated", "dlc_1um", "dlc_4um", "wcc_1um", "wcc_4um"]
    d = load_sweep("andreou2023_dynamics")
    assert d.mode == "dynamics" and d.shape == (37, 3)


def test_docs_cover_every_sweep_key():
    doc = (ROOT / "docs" / "sweep-files.md").read_text(encoding="utf-8")
    missing = [
        f"{m.__name__}.{k}"
        for m in (SweepInfo, AxisConfig)
        for k in m.model_fields
        if f"`{k}`" not in doc
    ]
    missing += [
        k
        for k in SweepFile.model_fields
        if f"### `[{k}]`" not in doc and f"### `[[{k}]]`" not in doc
    ]
    assert not missing, missing


# ----------------------------------------------------------------------------- file reading
def test_sweep_file_with_a_byte_order_mark_is_read(tmp_path):
    f = tmp_path / "bom.toml"
    f.write_bytes(
        "\ufeff[sweep]\nmode = 'dynamics'\n[[axes]]\npath = 'engine.speed_rpm'\n"
        "values = [2000, 3000]\n".encode()
    )
    assert load_sweep(f).n_points == 2


def test_deeply_nested_sweep_file_is_an_input_error(tmp_path):
    f = tmp_path / "deep.toml"
    f.write_text("[fixed]\n'engine.speed_rpm' = " + "[" * 5000 + "]" * 5000 + "\n")
    with pytest.raises(InputError, match="nested more than 32 levels"):
        load_sweep(f)


# ----------------------------------------------------------------------------- --scheduler
@pytest.mark.parametrize(
    "content",
    [b"garbage\n", b'{"address": 5}', b"[1, 2]", b"\xff\xfe", b'{"address": "nowhere"}'],
    ids=["text", "address-not-a-string", "not-an-object", "binary", "no-scheme"],
)
def test_junk_scheduler_file_names_the_option(tmp_path, content):
    """A junk scheduler file used to end in an AssertionError from dask."""
    from tribodyn.workflow.sweep import connect

    f = tmp_path / "scheduler.json"
    f.write_bytes(content)
    with pytest.raises(InputError, match="^--scheduler: .* is not a Dask scheduler file"):
        connect(str(f), timeout=2)


@pytest.mark.parametrize(
    "address",
    ["ucx://a:1", "garbage", "tcp://", "xyz://a:1", "tcp://h:notaport", "tcp://h:0", "tcp://[::1"],
)
def test_malformed_scheduler_address_names_the_option(tmp_path, address):
    from tribodyn.workflow.sweep import connect

    with pytest.raises(InputError, match="^--scheduler: .*tcp://host:8786"):
        connect(address, timeout=2)
    with pytest.raises(InputError, match="^--scheduler: .* is a folder"):
        connect(str(tmp_path), timeout=2)


@pytest.mark.parametrize("command", ["sweep", "run"])
def test_cli_junk_scheduler_is_a_clear_error(tmp_path, command):
    from typer.testing import CliRunner

    from tribodyn.cli import app

    junk = tmp_path / "junk"
    junk.write_text("garbage")
    first = ["sweep", "andreou2023_dynamics"] if command == "sweep" else ["run"]
    r = CliRunner().invoke(app, [*first, "-o", str(tmp_path / "out"), "--scheduler", str(junk)])
    assert r.exit_code == 2, r.output
    assert r.exception is None or isinstance(r.exception, SystemExit)
    assert "--scheduler" in r.output and "not a Dask scheduler file" in " ".join(r.output.split())


@pytest.mark.parametrize("command", ["sweep", "run"])
def test_cli_error_shows_brackets_in_the_message_as_text(tmp_path, command):
    """The message names the user's path as typed: rich markup in it (here ``[/x]``) is
    shown, not read as a closing tag (which ended ``tribodyn sweep`` in a MarkupError)."""
    from typer.testing import CliRunner

    from tribodyn.cli import app

    (tmp_path / "[").mkdir()
    junk = tmp_path / "[" / "x] junk"
    junk.write_text("garbage")
    first = ["sweep", "andreou2023_dynamics"] if command == "sweep" else ["run"]
    r = CliRunner().invoke(app, [*first, "-o", str(tmp_path / "out"), "--scheduler", str(junk)])
    assert r.exit_code == 2, r.output
    assert r.exception is None or isinstance(r.exception, SystemExit)
    assert "[/x] junk" in r.output and "not a Dask scheduler file" in r.output


# ----------------------------------------------------------------------------- large sweeps
def _range_sweep(tmp_path, *axes):
    text = "[sweep]\nmode = 'dynamics'\n" + "".join(
        f"[[axes]]\npath = '{p}'\nstart = {a}\nstop = {b}\nnum = {n}\n" for p, a, b, n in axes
    )
    f = tmp_path / "big.toml"
    f.write_text(text)
    return f


def test_long_axis_validates_a_bounded_sample(tmp_path, monkeypatch):
    """Every value of an axis used to be validated with the whole case (~10 ms each: an
    axis of 10⁶ values took hours); beyond MAX_VALIDATED_VALUES a spread sample is."""
    from tribodyn.config.sweep import MAX_VALIDATED_VALUES

    calls = []
    original = Case.updated
    monkeypatch.setattr(Case, "updated", lambda self, ch: calls.append(ch) or original(self, ch))
    spec = load_sweep(_range_sweep(tmp_path, ("engine.speed_rpm", 1000, 7000, 3000)))
    assert spec.n_points == 3000
    assert len(calls) <= MAX_VALIDATED_VALUES + 2  # (+ the fixed changes)
    values = [c["engine.speed_rpm"] for c in calls if "engine.speed_rpm" in c]
    assert min(values) == 1000 and max(values) == 7000


def test_long_axis_still_reports_values_out_of_range(tmp_path):
    f = _range_sweep(tmp_path, ("engine.speed_rpm", 1000, 70000, 5000))
    with pytest.raises(InputError) as err:
        load_sweep(f)
    msg = str(err.value)
    assert "engine.speed_rpm: must be > 0 rpm and <= 50000 rpm" in msg
    assert msg.count("range value") == 10 and "more invalid values" in msg


def test_dry_run_of_a_million_points_answers_fast(tmp_path, monkeypatch):
    """--dry-run built and validated every point (10⁶ case validations, hours)."""
    from typer.testing import CliRunner

    import tribodyn.workflow.sweep as ws
    from tribodyn.cli import app
    from tribodyn.config.sweep import SweepSpec

    def no_plan(self):
        raise AssertionError("the whole plan was built")

    monkeypatch.setattr(SweepSpec, "points", no_plan)
    monkeypatch.setattr(ws, "estimate_point_seconds", lambda case, mode="study": 2.0)
    f = _range_sweep(
        tmp_path,
        ("engine.speed_rpm", 1000, 7000, 1000),
        ("valvetrain.spring_preload", 200, 300, 1000),
    )
    r = CliRunner().invoke(
        app, ["sweep", str(f), "-o", str(tmp_path / "out"), "--dry-run", "-j", "4"]
    )
    assert r.exit_code == 0, r.output
    text = " ".join(r.output.split())
    assert "1000000 points" in text and "1000000 to run" in text
    assert "validated up to 1000 points only" in text
    assert "about 138.9 h on 4 worker(s)" in text  # 10⁶ × 2 s / 4


def test_find_paths_gives_each_place_its_own_address():
    from tribodyn.config.paths import find_paths

    d = {"s": [{"n": "a", "m": {"t": "x"}}, {"n": "b"}, {"n": "c", "m": {"t": "y"}}]}
    assert find_paths(d, "s[*].m.t") == [("s[0].m.t", "x"), ("s[2].m.t", "y")]
    assert find_paths(d, "s[n=c].m.t") == [("s[2].m.t", "y")]
    assert find_paths(d, "s[1].m.t") == [] and find_paths(d, "cam.path") == []
    assert find_paths({"t": {"a": {"v": 1}, "b": {"v": 2}}}, "t[*].v") == [
        ("t.a.v", 1),
        ("t.b.v", 2),
    ]
    for where, _ in find_paths(d, "s[*].m.t"):
        set_path(d, where, where)
    assert [e.get("m", {}).get("t") for e in d["s"]] == ["s[0].m.t", None, "s[2].m.t"]
    with pytest.raises(PathError, match="ends with a key"):
        find_paths(d, "s[*]")


@pytest.mark.parametrize(
    "form, where, what",
    [
        ("values = [[1000.0, 2000.0], [3000.0]]", "axes[0].values[0]", "an array"),
        ("values = [1000.0, {a = 1}]", "axes[0].values[1]", "a table"),
        ("start = [1000.0]\nstop = 2000.0\nnum = 3", "axes[0].start", "an array"),
    ],
)
def test_array_axis_values_get_one_clear_line(form, where, what):
    """An array where one value belongs used to list every type the value is not (bool,
    int, float, str); one line names the place, the axis key and what is wrong."""
    text = f'[[axes]]\npath = "engine.speed_rpm"\n{form}\n'
    msg = problems(text)
    assert (
        f"{where}: axis engine.speed_rpm: each value is one number, string or boolean (got {what})"
    ) in msg
    assert ".bool:" not in msg and ".float:" not in msg
