"""``tribodyn run`` draws no static figures unless asked (``--figures``); ``tribodyn
figures RESULTS`` draws them into a result folder afterwards: the same figures as
``--figures``, listed the same way in report.md and report.html, recorded as tribodyn's
files, never over a file of the user's, with the user's umask."""

import json
import shutil
import stat

import pytest
from typer.testing import CliRunner

from tribodyn.cli import app
from tribodyn.output.result_folder import MARKER, own_files

runner = CliRunner()


def _copy(folder, tmp_path):
    dst = tmp_path / "results"
    shutil.copytree(folder, dst, symlinks=True)
    return dst


def _figure_section(text: str) -> str:
    return text.split("\n## Figures\n", 1)[1].split("\n## ", 1)[0]


def test_a_run_without_figures_says_how_to_draw_them(plain_run):
    assert not list(plain_run.glob("*.png"))
    text = (plain_run / "report.md").read_text(encoding="utf-8")
    assert "`tribodyn figures FOLDER`" in _figure_section(text)
    assert ".png)" not in text  # no link to a missing image
    page = (plain_run / "report.html").read_text(encoding="utf-8")
    assert "missing figure" not in page and "Interactive traces" in page


def test_figures_command_draws_the_figures_of_a_run(plain_run, reduced_results, tmp_path):
    res = _copy(plain_run, tmp_path)
    r = runner.invoke(app, ["figures", str(res), "-j", "2"])
    assert r.exit_code == 0, r.output
    drawn = sorted(p.name for p in res.glob("*.png"))
    assert drawn == sorted(p.name for p in reduced_results.glob("*.png"))
    assert len(drawn) >= 15 and all((res / n).stat().st_size > 10_000 for n in drawn)
    # listed as `tribodyn run --figures` lists them
    text = (res / "report.md").read_text(encoding="utf-8")
    ref = (reduced_results / "report.md").read_text(encoding="utf-8")
    assert _figure_section(text) == _figure_section(ref)
    # the rest of the report is the run's
    before = (plain_run / "report.md").read_text(encoding="utf-8")
    assert text.split("\n## Figures\n")[0] == before.split("\n## Figures\n")[0]
    page = (res / "report.html").read_text(encoding="utf-8")
    plain = (plain_run / "report.html").read_text(encoding="utf-8")
    png = "data:image/png;base64,"  # the figures, and an image of the Bokeh library
    assert page.count(png) - plain.count(png) == len(drawn)
    assert "Interactive traces" in page and "missing figure" not in page
    # tribodyn's files now: a new run replaces them; drawing again replaces them
    own = own_files(res)
    assert set(drawn) | {"report.md", "report.html", "results.nc", "case.toml"} <= own
    assert json.loads((res / MARKER).read_text())["kind"] == "run"
    r = runner.invoke(app, ["figures", str(res), "-j", "1"])
    assert r.exit_code == 0, r.output
    assert (res / "report.md").read_text(encoding="utf-8") == text


def test_figures_command_never_overwrites_a_users_file(plain_run, tmp_path):
    res = _copy(plain_run, tmp_path)
    mine = res / "fig15_central_film.png"
    mine.write_bytes(b"my own picture")
    report = (res / "report.md").read_bytes()
    r = runner.invoke(app, ["figures", str(res)])
    assert r.exit_code == 2
    out = " ".join(r.output.split())
    assert "fig15_central_film.png" in out and "not written by tribodyn" in out
    assert mine.read_bytes() == b"my own picture"
    assert [p.name for p in res.glob("*.png")] == [mine.name]  # nothing drawn
    assert (res / "report.md").read_bytes() == report


def test_figures_command_leaves_a_users_report_alone(drawn_by_a_user):
    res, html, r, _ = drawn_by_a_user
    assert r.exit_code == 0, r.output
    assert list(res.glob("*.png"))
    assert (res / "report.md").read_text(encoding="utf-8").endswith("mine\n")
    assert (res / "report.html").read_bytes() == html
    assert "report.md is not tribodyn's" in " ".join(r.output.split())


@pytest.mark.parametrize("content", [None, b"not netCDF", "other netCDF"])
def test_figures_command_refuses_a_folder_that_is_not_a_runs(tmp_path, content):
    folder = tmp_path / "folder"
    folder.mkdir()
    (folder / "notes.txt").write_text("mine")
    if content == "other netCDF":
        import xarray as xr

        xr.Dataset({"x": ("i", [1.0, 2.0])}).to_netcdf(folder / "results.nc", engine="h5netcdf")
    elif content is not None:
        (folder / "results.nc").write_bytes(content)
    r = runner.invoke(app, ["figures", str(folder)])
    assert r.exit_code == 2
    out = " ".join(r.output.split())
    assert "Traceback" not in out
    assert (
        "not a result folder" in out or "cannot read" in out or "not a tribodyn results file" in out
    ), out
    assert sorted(p.name for p in folder.iterdir()) == sorted(
        ["notes.txt"] + (["results.nc"] if content else [])
    )


def test_figures_follow_the_umask(drawn_by_a_user):
    res, _, r, _ = drawn_by_a_user
    assert r.exit_code == 0, r.output
    assert list(res.glob("*.png"))
    for p in res.glob("*.png"):
        assert stat.S_IMODE(p.stat().st_mode) == 0o640, p.name


def test_writing_a_run_loads_no_plotting_library():
    """Without figures, writing a run (report.md, report.html) never imports matplotlib."""
    import subprocess
    import sys

    code = (
        "import sys; import tribodyn.output.writer, tribodyn.output.report, "
        "tribodyn.output.explorer, tribodyn.output.figures_folder; "
        "print('matplotlib' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_results_without_a_stored_regime_map_say_why_fig12_is_missing(plain_run, tmp_path):
    """Results written before the regime map was stored: the other figures are drawn and
    the message says why the Greenwood chart is not."""
    import xarray as xr

    res = _copy(plain_run, tmp_path)
    with xr.open_dataset(res / "results.nc", engine="h5netcdf") as ds:
        keep = ["crank_angle", "gV", "gE", "loaded", "ehl_contact_force", "central_film"]
        old = ds[keep].load()
    (res / "results.nc").unlink()
    old.to_netcdf(res / "results.nc", engine="h5netcdf")
    r = runner.invoke(app, ["figures", str(res), "-j", "1"])
    assert r.exit_code == 0, r.output
    assert not (res / "fig12_greenwood_chart.png").exists()
    assert (res / "fig15_central_film.png").exists()
    assert "Fig. 12 (Greenwood chart) is not drawn" in " ".join(r.output.split())
