"""Engine inputs are checked before any computing: lobe changes by their parsed key path,
the lobes' surface sets, the auxiliary parts and the displacement; a table named in a
lobe's changes travels with the results."""

import shutil

import pytest

from conftest import ENGINE
from tribodyn import InputError
from tribodyn.config import Case, load_case
from tribodyn.config.case import CASES_DIR


def _engine(**more):
    return load_case().updated({**ENGINE, **more})


@pytest.mark.parametrize(
    "key", ['"engine".speed_rpm', " engine.speed_rpm", '"numerics".n', "case.name"]
)
def test_lobe_changes_of_shared_keys_are_refused_in_any_spelling(key):
    """A quoted or space-led spelling of an engine, case or numerics key is the same key
    (TOML key paths): the exhaust lobes would otherwise run at another speed than the
    engine's summary says."""
    value = "other" if key.endswith("name") else 6000.0
    if key.endswith(".n"):
        value = 256
    lobe = {"centre_angle_deg": 250.0, "changes": {key: value}}
    with pytest.raises(InputError, match=r"engine\.exhaust\.changes:.*share the engine"):
        _engine(**{"engine.exhaust": lobe})


def test_lobe_changes_may_not_rename_a_surface_set():
    """Renaming a set in one lobe kind used to pass validation and fail after both lobes
    were computed; it is refused when the case loads."""
    lobe = {"centre_angle_deg": 250.0, "changes": {"surface_sets[0].name": "other"}}
    with pytest.raises(InputError, match=r"engine\.exhaust\.changes:.*surface sets"):
        _engine(**{"engine.exhaust": lobe})


@pytest.mark.parametrize("value", [5e-324, 1e-9, 0.5])
def test_displacement_outside_engines_is_refused(value):
    """5e-324 m³ used to give FMEP = inf in summary.json."""
    with pytest.raises(InputError, match=r"engine\.displacement.*>= 1e-05 m³ and <= 0\.1 m³"):
        _engine(**{"engine.displacement": value})


def test_tappet_bore_is_checked_when_the_case_loads():
    """A 1 µm bore used to fail in the auxiliary friction after both lobe studies."""
    with pytest.raises(InputError, match=r"engine\.auxiliary\.bore_diameter.*>= 0\.002 m"):
        _engine(**{"engine.auxiliary": {"bore_diameter": 1e-6}})
    # narrower than the tappet face (2 × 16.5 mm): it cannot slide in it
    with pytest.raises(InputError, match=r"engine\.auxiliary\.bore_diameter.*tappet_radius"):
        _engine(**{"engine.auxiliary": {"bore_diameter": 0.02}})
    # a clearance of 5 % of the diameter or more is no thin film
    with pytest.raises(InputError, match=r"engine\.auxiliary\.journal_clearance.*5 %"):
        _engine(**{"engine.auxiliary": {"journal_radius": 0.0125, "journal_clearance": 8e-4}})
    _engine(**{"engine.auxiliary": {"bore_diameter": 0.0331}})  # a real bore loads


def test_a_lobe_cam_table_is_copied_into_the_results_inputs(tmp_path):
    """``changes."cam.path"`` names a table: the result folder's case reads a copy in
    inputs/, not the file beside the original case (which may change or vanish)."""
    from tribodyn.output.writer import _write_case

    src = tmp_path / "case"
    (src / "tables").mkdir(parents=True)
    shutil.copy(CASES_DIR / "example_cam_lift.csv", src / "tables" / "cam1.csv")
    shutil.copy(CASES_DIR / "example_cam_lift.csv", src / "tables" / "cam2.csv")
    text = (CASES_DIR / "example_table_cam.toml").read_text(encoding="utf-8")
    text = text.replace('path = "example_cam_lift.csv"', 'path = "tables/cam1.csv"')
    text = text.replace(
        "[engine]\nspeed_rpm = 3000.0\n",
        "[engine]\nspeed_rpm = 3000.0\ncylinders = 4\ndisplacement = 0.0016\n"
        "intake = {centre_angle_deg = 470.0}\n"
        'exhaust = {centre_angle_deg = 250.0, changes = {"cam.path" = "tables/cam2.csv"}}\n',
    )
    (src / "engine.toml").write_text(text, encoding="utf-8")
    case = Case.from_toml(src / "engine.toml")
    out = tmp_path / "results"
    out.mkdir()
    _write_case(case, out)
    assert (out / "inputs" / "cam1.csv").is_file() and (out / "inputs" / "cam2.csv").is_file()
    moved = tmp_path / "moved"
    shutil.move(out, moved)
    shutil.rmtree(src)  # the original tables are gone
    again = Case.from_toml(moved / "case.toml")
    assert again.cam_table_path == moved / "inputs" / "cam1.csv"
    lobe = again.engine_lobe_case("exhaust")
    assert lobe.cam_table_path == moved / "inputs" / "cam2.csv"
