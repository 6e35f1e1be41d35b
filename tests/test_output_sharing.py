"""Result folders keep the user's files, follow the umask, refer to the files the case reads
by relative path (a moved folder runs again), and the command line refuses bad output
names before computing and prints tables that read well at 80 columns."""

import io
import json
import os
import shutil
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr
from rich.console import Console
from typer.testing import CliRunner

from tribodyn import InputError
from tribodyn.cli import app
from tribodyn.config import load_case
from tribodyn.config.build import build
from tribodyn.config.case import CASES_DIR
from tribodyn.config.sweep import SWEEPS_DIR
from tribodyn.output import check_output_dir, foreign_files, write_atomic, write_results
from tribodyn.output import writer as W

runner = CliRunner()

LABELS = ["uncoated", "DLC 1 µm", "DLC 4 µm", "WC-C 1 µm", "WC-C 4 µm"]


def _summary():
    """A summary with the widest values a run prints (five sets, forces > 1000 N)."""
    sets = {}
    for i, label in enumerate(LABELS):
        sets[f"s{i}"] = {
            "label": label,
            "min_film_m": 1.234e-7,
            "max_central_film_m": 5.55e-7,
            "max_film_gain_vs_uncoated_pct": -12.345 if i else 0.0,
            "max_boundary_friction_N": 1234.5,
            "max_viscous_friction_N": 12.3456,
            "boundary_friction_cycle_integral_change_pct": -97.25 if i else 0.0,
            "friction_energy_per_cycle_J": 0.12345,
            "failed_steps": 120,
        }
    return {
        "surface_sets": sets,
        "reference_set": "s0",
        "implicit_vs_explicit": {},
        "warnings": [],
        "runtime_s": 1.0,
    }


@pytest.fixture
def fake_run(monkeypatch):
    """``tribodyn run`` without the computation: a stand-in study (its Dataset, summary
    and case) is written by the real writer."""
    import tribodyn.output.report as report
    import tribodyn.workflow.cycle as cycle

    ds = xr.Dataset({"central_film": ("crank", [1e-7, 2e-7])}, coords={"crank": [0.0, 1.0]})
    monkeypatch.setattr(W, "study_to_dataset", lambda study: ds)
    monkeypatch.setattr(
        report, "write_report", lambda study, ds, figs, path: Path(path).write_text("report")
    )
    calls = []

    def study(case, **kw):
        calls.append(case)
        return SimpleNamespace(case=case, analyse=lambda: SimpleNamespace(summary=_summary()))

    monkeypatch.setattr(cycle, "run_cycle_study", study)
    return calls


def _run(*args):
    return runner.invoke(app, ["run", *map(str, args), "-q"])


# ----------------------------------------------------------------------------- user's files
def test_run_into_an_earlier_result_folder_keeps_the_users_files(tmp_path, fake_run):
    out = tmp_path / "res"
    assert _run("-o", out).exit_code == 0
    (out / "notes.txt").write_text("my notes")
    (out / "cams").mkdir()
    (out / "cams" / "lift.csv").write_text("0,0\n")
    (out / "empty").mkdir()
    ino = (out / "notes.txt").stat().st_ino
    (out / "summary.json").write_text(json.dumps({"old": 1}))  # changed: the user's now
    r = _run("-o", out)  # summary.json would be replaced: refused before computing
    assert r.exit_code == 2 and "summary.json" in r.output and len(fake_run) == 1
    (out / "summary.json").unlink()
    r = _run("-o", out)
    assert r.exit_code == 0, r.output
    assert (out / "notes.txt").read_text() == "my notes"
    assert (out / "notes.txt").stat().st_ino == ino  # the same file, not a copy
    assert (out / "cams" / "lift.csv").read_text() == "0,0\n" and (out / "empty").is_dir()
    assert "surface_sets" in json.loads((out / "summary.json").read_text())  # replaced
    assert sorted(foreign_files(out)) == ["cams/lift.csv", "empty/", "notes.txt"]
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".res")]


def test_a_file_added_while_writing_is_kept(tmp_path):
    out = write_atomic(tmp_path / "res", lambda d: (d / "results.nc").write_text("1"))

    def writer(d):
        (out / "late.txt").write_text("added meanwhile")  # after the files were linked
        (d / "results.nc").write_text("2")

    write_atomic(out, writer)
    assert (out / "late.txt").read_text() == "added meanwhile"
    assert (out / "results.nc").read_text() == "2"


def test_own_files_are_those_listed_with_their_hash(tmp_path):
    out = write_atomic(tmp_path / "res", lambda d: (d / "report.md").write_text("a"))
    info = json.loads((out / W.MARKER).read_text())
    assert list(info["files"]) == ["report.md"]
    assert foreign_files(out) == []
    (out / "report.md").write_text("edited")
    assert foreign_files(out) == ["report.md"]
    with pytest.raises(InputError, match="report.md"):
        check_output_dir(out)


def test_sweep_refuses_a_file_or_a_foreign_folder_before_computing(tmp_path, monkeypatch):
    import tribodyn.workflow.sweep as sweep

    monkeypatch.setattr(sweep, "run_sweep", lambda *a, **k: pytest.fail("must not run"))
    f = tmp_path / "sweep_out"
    f.write_text("a file")
    r = runner.invoke(app, ["sweep", "andreou2023_dynamics", "-o", str(f), "-q"])
    assert r.exit_code == 2 and "existing file" in r.output, r.output
    assert f.read_text() == "a file"
    mine = tmp_path / "mine"
    mine.mkdir()
    text = "# my comments\n" + (SWEEPS_DIR / "andreou2023_dynamics.toml").read_text()
    (mine / "sweep.toml").write_text(text)
    r = runner.invoke(app, ["sweep", str(mine / "sweep.toml"), "-o", str(mine), "-q"])
    assert r.exit_code == 2 and "did not write" in r.output and "sweep.toml" in r.output
    assert (mine / "sweep.toml").read_text() == text


def test_write_sweep_does_not_replace_a_changed_file(tmp_path):
    from tribodyn.output.sweep import write_sweep

    out = tmp_path / "sw"
    out.mkdir()
    (out / "sweep.toml").write_text("generated")
    W.mark_folder(out, {"sweep.toml": W._sha256(out / "sweep.toml")})
    (out / "sweep.toml").write_text("# my comments\ngenerated")
    with pytest.raises(InputError, match="sweep.toml"):
        write_sweep(SimpleNamespace(), out)  # refused before anything is written
    assert (out / "sweep.toml").read_text() == "# my comments\ngenerated"


# ----------------------------------------------------------------------------- umask
@pytest.mark.parametrize("mask", [0o022, 0o027])
def test_results_follow_the_umask(tmp_path, mask):
    from tribodyn._safe_write import atomic_write
    from tribodyn.workflow.sweep_store import PointStore

    old = os.umask(mask)
    try:
        out = write_atomic(tmp_path / "res", lambda d: (d / "x.txt").write_text("1"))
        atomic_write(tmp_path / "sweep.toml", "x")  # as write_sweep writes its text files
        point = SimpleNamespace(index=0, key="abc", values={}, changes={}, label="p", case=None)
        pfile = PointStore(tmp_path / "sw").write(point, xr.Dataset({"a": ("x", [1.0])}))
    finally:
        os.umask(old)
    assert out.stat().st_mode & 0o777 == 0o777 & ~mask
    for f in (out / "x.txt", out / W.MARKER, tmp_path / "sweep.toml", pfile):
        assert f.stat().st_mode & 0o777 == 0o666 & ~mask, f


# ----------------------------------------------------------------------------- long names
def test_a_name_too_long_is_an_input_error(tmp_path, monkeypatch):
    import tribodyn.workflow.sweep as sweep

    limit = os.pathconf(tmp_path, "PC_NAME_MAX")
    for name in ("r" * (limit + 1), "r" * (limit - 5)):  # too long; no room for .tmp-…
        with pytest.raises(InputError, match="shorter name"):
            check_output_dir(tmp_path / name)
        r = _run("-o", tmp_path / name)
        assert r.exit_code == 2 and "shorter name" in r.output, r.output
    assert check_output_dir(tmp_path / ("r" * (limit - W._NAME_OVERHEAD)))
    with pytest.raises(InputError, match="too long|bytes long"):
        check_output_dir(tmp_path / ("d" * (limit + 1)) / "res")
    monkeypatch.setattr(sweep, "run_sweep", lambda *a, **k: pytest.fail("must not run"))
    r = runner.invoke(app, ["sweep", "andreou2023_dynamics", "-o", str(tmp_path / name), "-q"])
    assert r.exit_code == 2 and "shorter name" in r.output
    assert list(tmp_path.iterdir()) == []


# ----------------------------------------------------------------------------- re-runnable
def test_a_moved_result_folder_runs_again(tmp_path):
    """A small case with its own cam table: run, move the results, remove the table, run
    the moved case.toml: the same case and the same results."""
    from tribodyn.workflow.cycle import run_cycle_study

    cams = tmp_path / "cams"
    cams.mkdir()
    shutil.copy(CASES_DIR / "example_cam_lift.csv", cams / "my_lift.csv")
    case = load_case("example_table_cam").updated(
        {
            "cam.path": str(cams / "my_lift.csv"),
            "numerics.crank_step_deg": 5.0,
            "numerics.n": 128,
            "numerics.coupling_iterations": 1,
            "numerics.output_step_deg": 2.5,
            "numerics.workers": 1,
        }
    )
    study = run_cycle_study(case, workers=1)
    write_results(study, tmp_path / "res", figures=False, report=False)
    text = (tmp_path / "res" / "case.toml").read_text()
    assert 'path = "inputs/my_lift.csv"' in text and str(tmp_path) not in text
    moved = tmp_path / "elsewhere" / "shared"
    moved.parent.mkdir()
    (tmp_path / "res").rename(moved)
    shutil.rmtree(cams)
    again = load_case(moved / "case.toml")
    assert again.cam_table_path == moved / "inputs" / "my_lift.csv"
    theta = np.linspace(0.0, 2 * np.pi, 721)
    assert np.array_equal(build(again).cam.lift(theta), build(case).cam.lift(theta))
    first = study.analyse().summary["surface_sets"]
    second = run_cycle_study(again, workers=1).analyse().summary["surface_sets"]
    for name in first:
        for key in ("min_film_m", "friction_energy_per_cycle_J", "max_boundary_friction_N"):
            assert second[name][key] == pytest.approx(first[name][key], rel=1e-12)


def test_result_folder_copies_every_sets_measured_map(tmp_path):
    """Each surface set's measured map is copied to inputs/ and its own key names its
    copy: one file read by two sets is copied once, two files of the same name get
    distinct names; the moved folder reads back with the originals gone."""
    from tribodyn.topography import write_topography
    from tribodyn.topography.synthetic import synthetic_surface

    for folder, seed in (("a", 4), ("b", 5)):
        (tmp_path / folder).mkdir()
        t = synthetic_surface(
            (48, 48), 0.4e-6, rms=0.2e-6, hurst=0.8, short_cutoff=3.2e-6,
            long_cutoff=9.6e-6, seed=seed,
        )  # fmt: skip
        write_topography(t, tmp_path / folder / "pair.nc")
    rough = "roughness = { asperity_density = 1e9, rms = 0.2e-6, summit_radius = 200e-6 }"
    sets = [("gt", ""), ("m1", "a/pair.nc"), ("m2", "b/pair.nc"), ("m3", "a/pair.nc")]
    text = "".join(
        f'[[surface_sets]]\nname = "{name}"\n{rough}\n'
        + (
            f'asperity_model = "measured"\nmeasured_surface = {{ topography = "{m}" }}\n'
            if m
            else ""
        )
        for name, m in sets
    )
    (tmp_path / "case.toml").write_text(text, encoding="utf-8")
    case = load_case(tmp_path / "case.toml")
    data, copies = W.case_inputs(case)
    assert copies == {
        "inputs/pair.nc": tmp_path / "a" / "pair.nc",
        "inputs/pair-2.nc": tmp_path / "b" / "pair.nc",
    }
    maps = [s.get("measured_surface", {}).get("topography") for s in data["surface_sets"]]
    assert maps == [None, "inputs/pair.nc", "inputs/pair-2.nc", "inputs/pair.nc"]
    folder = write_atomic(tmp_path / "res", lambda d: W._write_case(case, d))
    moved = tmp_path / "elsewhere" / "shared"
    moved.parent.mkdir()
    folder.rename(moved)
    shutil.rmtree(tmp_path / "a")
    shutil.rmtree(tmp_path / "b")
    again = load_case(moved / "case.toml")
    for name in ("m1", "m2", "m3"):
        law, law0 = (
            build(again).set(name).surface.roughness.law,
            build(case).set(name).surface.roughness.law,
        )
        np.testing.assert_array_equal(law.pressure, law0.pressure)
    assert not np.array_equal(
        build(again).set("m1").surface.roughness.law.pressure,
        build(again).set("m2").surface.roughness.law.pressure,
    )
    assert check_output_dir(moved, writes=W.case_inputs(again)[1]) == moved  # its own copies
    # a user's own file of that name in the folder is never replaced
    (moved / "inputs" / "pair-2.nc").write_bytes(b"my notes")
    with pytest.raises(InputError, match=r"inputs/pair-2\.nc in this result folder changed"):
        check_output_dir(moved, writes=W.case_inputs(case)[1])


def test_stress_figure_of_a_relative_map_drawn_from_another_folder(tmp_path, monkeypatch):
    """A measured map given relative to the case file is found when tribodyn runs in
    another folder, and the stress figure is drawn (from the fields the study stored in
    results.nc; before, the figure rebuilt the sets and the writing failed)."""
    import tomli_w

    from tribodyn.topography import write_topography
    from tribodyn.topography.synthetic import synthetic_surface
    from tribodyn.workflow.cycle import run_cycle_study

    (tmp_path / "case" / "maps").mkdir(parents=True)
    t = synthetic_surface(
        (48, 48), 0.4e-6, rms=0.2e-6, hurst=0.8, short_cutoff=3.2e-6, long_cutoff=9.6e-6, seed=4
    )
    write_topography(t, tmp_path / "case" / "maps" / "pair.nc")
    data = load_case("flat_tappet_rig_measured").to_dict()
    data["surface_sets"] = data["surface_sets"][:1]
    data["surface_sets"][0]["measured_surface"] = {"topography": "maps/pair.nc"}
    data["numerics"].update(crank_step_deg=5.0, n=128, coupling_iterations=1, workers=1)
    (tmp_path / "case" / "case.toml").write_text(tomli_w.dumps(data), encoding="utf-8")
    (tmp_path / "elsewhere").mkdir()
    monkeypatch.chdir(tmp_path / "elsewhere")
    study = run_cycle_study(load_case(tmp_path / "case" / "case.toml"), workers=1)
    out = write_results(
        study, tmp_path / "res", figures=["stress_map.png"], report=False, workers=1
    )
    assert (out["path"] / "stress_map.png").is_file()
    assert (out["path"] / "inputs" / "pair.nc").is_file()


# ----------------------------------------------------------------------------- console
def test_run_table_reads_well_at_80_columns(tmp_path, fake_run, monkeypatch):
    import tribodyn.cli.run as run_mod

    buf = io.StringIO()
    monkeypatch.setattr(run_mod, "console", Console(file=buf, width=80))
    r = _run("-o", tmp_path / "res")
    assert r.exit_code == 0, r.output
    text = buf.getvalue()
    assert "…" not in text, text
    assert all(len(line) <= 80 for line in text.splitlines())
    rows = [
        line
        for line in text.splitlines()
        if line.strip().startswith(tuple(LABELS)) and "120" in line
    ]
    assert len(rows) == len(LABELS), text
    for label, row in zip(LABELS, rows):  # every cell whole, on the label's line
        assert row.split() == [
            *label.split(),
            *("0.123", "0.55"),
            *(("+0.00",) if label == "uncoated" else ("-12.35",)),
            *("1234", "12.35"),
            *(("+0.0",) if label == "uncoated" else ("-97.2",)),
            *("0.123", "120"),
        ], text
    for head in ("surface", "film", "h_c", "gain", "F_b", "F_v", "J/cycle", "steps"):
        assert head in text


def test_unknown_case_name_lists_the_bundled_cases_and_sweeps(tmp_path):
    r = _run("andreou2032", "-o", tmp_path / "res")
    assert r.exit_code == 2
    text = " ".join(r.output.split())
    for name in ("andreou2023", "example_table_cam", "andreou2023_dynamics"):
        assert name in text, r.output


def test_a_users_folder_or_file_in_the_way_is_a_clash(tmp_path):
    out = write_atomic(tmp_path / "res", lambda d: (d / "results.nc").write_text("1"))
    (out / "report.md").mkdir()  # a folder where tribodyn writes a file
    with pytest.raises(InputError, match="report.md"):
        check_output_dir(out)
    (out / "report.md").rmdir()
    (out / "inputs").write_text("x")  # a file where tribodyn needs a folder
    with pytest.raises(InputError, match="inputs"):
        check_output_dir(out, writes={"inputs/lift.csv": None})
    (out / "inputs").unlink()
    (out / "inputs").mkdir()
    (out / "inputs" / "lift.csv").write_text("0,0\n")  # the same table: no clash
    src = tmp_path / "lift.csv"
    src.write_text("0,0\n")
    assert check_output_dir(out, writes={"inputs/lift.csv": src}) == out
    src.write_text("0,1\n")  # another table of the same name
    with pytest.raises(InputError, match="inputs/lift.csv"):
        check_output_dir(out, writes={"inputs/lift.csv": src})
