"""``tribodyn view``: the comparison page of run, engine and sweep result folders (its
content, its size, how the inputs differ) and its file safety (no overwriting)."""

import re
import shutil

import pytest
from typer.testing import CliRunner

from conftest import fake_sweep_folder
from tribodyn.cli import app
from tribodyn.output.explorer import bokeh_js, build_page, write_page
from tribodyn.output.explorer_data import display_name, load_result, set_display_names

runner = CliRunner()


@pytest.fixture(scope="module")
def folders(reduced_results, engine_results, tmp_path_factory):
    """Two runs (the second a copy whose case file says 5000 rpm), an engine, a sweep."""
    root = tmp_path_factory.mktemp("view")
    fast = root / "fast"
    shutil.copytree(reduced_results, fast)
    case = fast / "case.toml"
    case.write_text(
        case.read_text(encoding="utf-8").replace("speed_rpm = 3000.0", "speed_rpm = 5000.0"),
        encoding="utf-8",
    )
    return [reduced_results, fast, engine_results, fake_sweep_folder(root / "map")]


def test_display_names_of_sets():
    assert display_name("dlc_4um") == "DLC 4 µm"
    assert display_name("wcc_1um") == "WC-C 1 µm"
    assert display_name("my_set") == "my_set"
    text = (
        '[materials.dlc]\nlabel = "a-C:H"\n[[surface_sets]]\nname = "x"\ncoating = "dlc"\n'
        'coating_thickness = 2e-6\n[[surface_sets]]\nname = "y"\n'
    )
    assert set_display_names(text, ["x", "y"]) == {"x": "a-C:H 2 µm", "y": "uncoated"}


def test_page_compares_runs_engine_and_sweep(folders):
    page, n = build_page(folders)
    # the Bokeh library once, inline: no network resource at all
    assert not re.search(r"<script[^>]*\bsrc=|<link\b|<img\b", page)
    assert page.count(bokeh_js()) == 1 and page.count("Bokeh.embed.embed_items(") == 1
    # runs: overlays over crank angle with the sets' display names per run
    assert "Central film h_c" in page and "λ = h_min/σ" in page
    assert "results · DLC 4 µm" in page and "fast · DLC 4 µm" in page
    # engine: per camshaft, sums said to be sums; sweep: loss and heat map
    assert "intake camshaft" in page and "camshafts summed" in page
    assert "valvetrain friction MEP against speed_rpm" in page
    assert "coatings' change" in page
    # coating verdict: the sweep's made-up DLC is not there; the engine's and runs' are
    assert page.count("DLC 4 µm lowers") + page.count("DLC 4 µm does not lower") == 3
    # the inputs differ by the speed: a unified diff says so
    assert "-speed_rpm = 3000.0" in page and "+speed_rpm = 5000.0" in page
    assert n >= 10 + 4 + 4 + 1
    assert len(page.encode()) < 5e6


def test_summary_table_differences_against_first_column(folders):
    from tribodyn.output.explorer import summary_rows

    results = [load_result(p) for p in folders[:2]]
    heads, rows = summary_rows(results, "run")
    assert heads[0] == "results · uncoated" and len(heads) == 10  # 5 sets × 2 runs
    energy = next(r for r in rows if r[0] == "friction energy per cycle")
    assert energy[1] == "J" and 0 < energy[2] < 10
    assert energy[2] == energy[7]  # the copy holds the same numbers


def test_not_a_result_is_refused(tmp_path):
    r = runner.invoke(app, ["view", str(tmp_path), "-o", str(tmp_path / "p.html")])
    assert r.exit_code == 2 and "no results.nc or sweep.nc" in r.output
    assert not (tmp_path / "p.html").exists()


def test_page_never_overwrites_without_force(folders, tmp_path):
    mine = tmp_path / "page.html"
    mine.write_text("my notes", encoding="utf-8")
    r = runner.invoke(app, ["view", str(folders[3]), "-o", str(mine)])
    assert r.exit_code == 2 and "--force" in r.output
    assert mine.read_text(encoding="utf-8") == "my notes"
    r = runner.invoke(app, ["view", str(folders[3]), "-o", str(mine), "--force"])
    assert r.exit_code == 0, r.output
    assert mine.read_text(encoding="utf-8").startswith("<!DOCTYPE html>")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["page.html"]  # no temporary left
    with pytest.raises(Exception, match="exists"):
        write_page("x", mine)


def test_default_name_is_new_and_serve_is_local(tmp_path, monkeypatch):
    import urllib.error
    import urllib.request
    from threading import Thread

    from tribodyn.cli.view_serve import page_server
    from tribodyn.output.explorer import default_page_path

    (tmp_path / "tribodyn_view.html").write_text("mine", encoding="utf-8")
    assert default_page_path(tmp_path).name == "tribodyn_view-2.html"
    server = page_server(b"<html>page</html>", 0)
    host, port = server.server_address[:2]
    assert host == "127.0.0.1"
    Thread(target=server.serve_forever, daemon=True).start()
    try:
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=10) as r:
            assert r.read() == b"<html>page</html>"
        with pytest.raises(urllib.error.HTTPError):
            urllib.request.urlopen(f"http://127.0.0.1:{port}/etc/passwd", timeout=10)
    finally:
        server.shutdown()
        server.server_close()


def test_line_figures_carry_the_samples_and_the_dashes_of_the_python_pages():
    """A figure drawn in the browser: the traces of one x array share its column, each
    trace's column holds its float32 samples (NaN kept), a name given twice gets a source
    of its own; dashes as Bokeh's Python side drew them ("dashed" 6 px on and off;
    BokehJS's own "dashed" is 3–2)."""
    import base64
    import gzip

    import numpy as np

    from tribodyn.output.explorer_plots import LineFigure

    x = np.linspace(0.0, 1.0, 7, dtype=np.float32)
    y1 = x**2
    y2 = np.where(x > 0.5, np.nan, x).astype(np.float32)
    f = LineFigure("t", "x [m]", "y [m]", ("runs", 0.0, 1.0))
    f.add(x, y1, "a · b", "#1f77b4", "dashed", 2.0)
    f.add(x.copy(), y2, "c", "#d62728", "solid", 1.2, markers=True)
    f.add(x[:3], y1[:3], "a · b", "#1f77b4", "dotted", 1.0)
    spec = f.spec()

    def unpack(text):
        return np.frombuffer(gzip.decompress(base64.b64decode(text)), "<f4")

    cols = spec["columns"]
    assert len(cols) == 2 and sorted(cols[0]) == ["a · b", "c", "x"]
    np.testing.assert_array_equal(unpack(cols[0]["x"]), x)
    np.testing.assert_array_equal(unpack(cols[0]["c"]), y2)
    np.testing.assert_array_equal(unpack(cols[1]["a · b"]), y1[:3])
    assert [t[0] for t in spec["traces"]] == [0, 0, 1]
    assert [t[3] for t in spec["traces"]] == [[6], [], [2, 4]]
    assert [t[5] for t in spec["traces"]] == [False, True, False]
    assert spec["x_range"] == "runs" and spec["title"] == "t"
