"""No clipped titles or legends: every figure a run, an engine study and a sweep write is
drawn, and every visible text (titles, suptitles, labels, tick labels, legend entries)
and every legend must lie inside the figure canvas (matplotlib window extents with the
renderer)."""

import matplotlib
import pytest
import xarray as xr

from conftest import fake_sweep_folder
from tribodyn.output.figures import common

TOL = 1.0  # pixels


def outside(fig) -> list[str]:
    """The texts and legends of ``fig`` that leave its canvas: the figure's own texts
    (suptitle, notes) and legends, and per axes the box of what it draws (title, axis
    labels, the tick labels drawn, its legend, a colour bar's)."""
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    box = fig.bbox
    items = []
    for t in dict.fromkeys([fig._suptitle, fig._supxlabel, fig._supylabel, *fig.texts]):
        if t is not None and t.get_visible() and t.get_text().strip():
            items.append((t.get_text(), t.get_window_extent(r)))
    items += [("figure legend", leg.get_window_extent(r)) for leg in fig.legends]
    for ax in fig.axes:
        if not ax.get_visible():
            continue
        leg = ax.get_legend()
        if leg is not None and leg.get_visible():
            items.append((f"legend of {ax.get_title()!r}", leg.get_window_extent(r)))
        items.append((f"axes {ax.get_title()!r} with its labels", ax.get_tightbbox(r)))
    bad = []
    for what, e in items:
        if e is None:
            continue
        if e.x0 < box.x0 - TOL or e.y0 < box.y0 - TOL or e.x1 > box.x1 + TOL or e.y1 > box.y1 + TOL:
            bad.append(f"{what[:70]!r} at x {e.x0:.0f}–{e.x1:.0f}, y {e.y0:.0f}–{e.y1:.0f}")
    return bad


def check_saved_figures(mp) -> dict[str, list[str]]:
    """Through ``mp`` (a pytest MonkeyPatch), every figure saved through save_figure is
    checked first; returns the record {file name: problems}, filled as figures are
    saved."""
    found: dict[str, list[str]] = {}
    original = common.save_figure

    def check_then_save(fig, path):
        fig.set_dpi(100)
        found[str(getattr(path, "name", path))] = outside(fig)
        return original(fig, path)

    import tribodyn.output.figures.sweep as sweep_figs

    mp.setattr(common, "save_figure", check_then_save)
    mp.setattr(sweep_figs, "save_figure", check_then_save)
    return found


@pytest.fixture
def checked(monkeypatch):
    """Every figure saved through save_figure is checked first: {file name: problems}."""
    return check_saved_figures(monkeypatch)


def _assert_inside(found):
    assert found, "no figure drawn"
    bad = {k: v for k, v in found.items() if v}
    assert not bad, "texts outside the canvas:\n" + "\n".join(f"{k}: {v}" for k, v in bad.items())


def test_run_figures_stay_on_canvas(drawn_by_a_user):
    """The run's figures, as ``tribodyn figures`` draws them in this process (checked
    while ``drawn_by_a_user`` draws them)."""
    res, _, r, found = drawn_by_a_user
    assert r.exit_code == 0, r.output
    assert "fig23_camshaft_torque.png" in found
    assert set(found) == {p.name for p in res.glob("*.png")}  # every figure drawn
    _assert_inside(found)


def test_engine_figures_stay_on_canvas(engine_results, checked, tmp_path):
    from tribodyn.output.figures.engine import engine_figures

    with xr.open_dataset(engine_results / "results.nc") as ds:
        engine_figures(ds.load(), tmp_path, {"dlc_4um": "DLC 4 µm"})
    assert len(checked) == 2
    _assert_inside(checked)


def test_sweep_figures_stay_on_canvas(checked, tmp_path):
    from tribodyn.output.figures.sweep import sweep_figures

    folder = fake_sweep_folder(tmp_path / "sweep")
    with xr.open_dataset(folder / "sweep.nc") as ds:
        sweep_figures(ds.load(), tmp_path)
    assert "sweep_engine_map.png" in checked
    _assert_inside(checked)


def test_the_check_sees_a_clipped_legend():
    """The check can fail: a legend pushed off the canvas is found."""
    fig, ax = matplotlib.pyplot.subplots(figsize=(4, 3))
    ax.plot([0, 1], label="a long legend entry")
    ax.legend(loc="center left", bbox_to_anchor=(1.2, 0.5))
    assert any("legend of" in b for b in outside(fig))
    fig.suptitle("a suptitle far too long for a figure of four inches, it runs off both sides")
    assert any("a suptitle" in b for b in outside(fig))
    matplotlib.pyplot.close(fig)
