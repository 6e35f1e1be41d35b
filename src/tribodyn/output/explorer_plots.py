"""The interactive figures of :mod:`.explorer` (Bokeh): overlays over crank angle of
runs' and engines' traces, and a sweep's lines and heat maps. Each function returns
figures: a :class:`LineFigure` (its samples and styles, drawn by BokehJS in the browser)
or Bokeh models (the heat maps); :mod:`.explorer` embeds them with the Bokeh library
inline (no network).

Styles: a colour per surface set (by display name, the same in every figure), a line
style per result folder (or camshaft), so that overlapping curves stay visible; the
legend sits beside the plot and hides a trace on click; hovering shows the trace's name
and values; the crank-angle plots of a page share their zoom.
"""

from __future__ import annotations

from itertools import product

import numpy as np

from ..workflow.conventions import EVENT_FRACTION
from .explorer_data import Result, decimate
from .report_engine import ENGINE_PARTS

__all__ = ["run_figures", "engine_figures", "sweep_figures", "Styles", "LineFigure", "LINE_STYLE"]

PALETTE = (
    "#1f77b4",
    "#d62728",
    "#2ca02c",
    "#9467bd",
    "#8c564b",
    "#ff7f0e",
    "#17becf",
    "#7f7f7f",
    "#bcbd22",
    "#e377c2",
)
DASHES = ("solid", "dashed", "dotted", "dotdash", "dashdot")
WIDTH, HEIGHT = 900, 330


class Styles:
    """Colours by display name and dashes by result, handed out in order of use."""

    def __init__(self):
        self.colours: dict[str, str] = {}

    def colour(self, key: str) -> str:
        if key not in self.colours:
            self.colours[key] = PALETTE[len(self.colours) % len(PALETTE)]
        return self.colours[key]


#: How the drawing script of :mod:`.explorer` draws a :class:`LineFigure` in BokehJS:
#: the figure's options, the hover tool (the trace's name, the sample's x and y: column
#: ``x`` and the column named as the trace), the title's size, the legend beside the plot
#: (a click hides a trace) and the width it adds, the markers' size.
LINE_STYLE = {
    "figure": {
        "width": WIDTH,
        "height": HEIGHT,
        "tools": "pan,box_zoom,wheel_zoom,reset,save",
        "active_scroll": None,
    },
    "hover": {
        "tooltips": [["", "$name"], ["x", "@x{%0.5g}"], ["y", "@$name{%0.5g}"]],
        "formatters": {"@x": "printf", "@$name": "printf"},
        "line_policy": "nearest",
    },
    "title_size": "13px",
    "legend": {"click_policy": "hide", "label_text_font_size": "11px", "spacing": 0},
    "legend_width": 260,
    "marker_size": 6,
}


def _width(i: int) -> float:
    """Line width of the i-th set: the first widest, so that the sets' curves lying on
    one another stay visible."""
    return max(1.2, 2.8 - 0.6 * i)


def _packed(a: np.ndarray) -> str:
    """A float32 array as base64 of its gzip-compressed little-endian bytes (no time
    stamp: the same samples give the same text)."""
    import base64
    import gzip

    raw = np.ascontiguousarray(a, dtype="<f4").tobytes()
    return base64.b64encode(gzip.compress(raw, compresslevel=6, mtime=0)).decode("ascii")


class LineFigure:
    """A figure of named traces over one x axis, drawn in the browser (BokehJS builds
    its models from :meth:`spec` with :data:`LINE_STYLE`: Python builds none). The
    traces sharing an x array share one data source (column ``x`` and one column per
    trace, named by it); a trace is a renderer with its one glyph (the not-selected and
    muted looks are BokehJS's defaults: no selection tool, and the legend hides, never
    mutes); one legend item per name, its renderers those of the name. ``x_range``:
    (key, start, end) of a zoom range shared by the page's figures of that key, or None
    (fitted to the data)."""

    def __init__(self, title: str, x_label: str, y_label: str, x_range=None):
        self.title, self.x_label, self.y_label, self.x_range = title, x_label, y_label, x_range
        self.columns: list[dict[str, np.ndarray]] = []
        self.drawn: list[tuple[int, str, str, str, float, bool]] = []

    def add(self, x, y, name, colour, dash, width, markers=False) -> None:
        """Trace ``name`` of float32 ``x``, ``y``: a line (``width`` px, ``dash``), with
        markers at the samples if ``markers``."""
        g = next(
            (
                k
                for k, c in enumerate(self.columns)
                if name not in c and np.array_equal(c["x"], x, equal_nan=True)
            ),
            None,
        )
        if g is None:
            g = len(self.columns)
            self.columns.append({"x": x})
        self.columns[g][name] = y
        self.drawn.append((g, name, colour, dash, width, markers))

    def spec(self) -> dict:
        """What BokehJS draws: titles, range key, columns (:func:`_packed`), traces (a
        dash by name as Bokeh's Python side resolves it: BokehJS's own names differ)."""
        from bokeh.core.property.visual import DashPattern

        dashes = DashPattern()
        return {
            "title": self.title,
            "x_label": self.x_label,
            "y_label": self.y_label,
            "x_range": self.x_range[0] if self.x_range else None,
            "columns": [{k: _packed(v) for k, v in c.items()} for c in self.columns],
            "traces": [
                [g, name, colour, dashes.transform(dash), width, markers]
                for g, name, colour, dash, width, markers in self.drawn
            ],
        }


def _line(fig: LineFigure, x, y, name, colour, dash, width=1.6) -> None:
    fig.add(*decimate(x, y), name, colour, dash, width)


# ----------------------------------------------------------------------------- runs
#: Overlays of a run's per-set traces: (title, y label, variables summed, scale).
RUN_TRACES = (
    (
        "Camshaft friction torque T_f = F_f (r_b + s)",
        "T_f [N·m]",
        ("camshaft_friction_torque",),
        1.0,
    ),
    ("Central film h_c", "h_c [µm]", ("central_film",), 1e6),
    ("Minimum film h_min", "h_min [µm]", ("min_film",), 1e6),
    (
        "λ = h_min/σ (below 1: mixed lubrication, asperities carry load)",
        "λ [–]",
        ("lambda_ratio",),
        1.0,
    ),
    ("Peak EHL pressure", "p_max [MPa]", ("max_pressure",), 1e-6),
    ("Hertz pressure p_h", "p_h [MPa]", ("hertz_pressure",), 1e-6),
    (
        "Friction force F_f = viscous + boundary",
        "F_f [N]",
        ("viscous_friction", "boundary_friction"),
        1.0,
    ),
    ("Camshaft drive torque T = W s' + T_f", "T [N·m]", ("camshaft_drive_torque",), 1.0),
    ("Friction power", "P_f [W]", ("friction_power",), 1.0),
)
CRANK = "crank angle [°]"


def event_window(results: list[Result]) -> tuple[float, float] | None:
    """Crank-angle window of the runs' loaded samples (padded by 5°), or None."""
    lo, hi = np.inf, -np.inf
    for r in results:
        ds = r.ds
        if "loaded" not in ds:
            continue
        x = np.asarray(ds["ehl_crank"].values, float)
        on = np.asarray(ds["loaded"].values, bool).any(axis=0)
        if "ehl_contact_force" in ds:
            w = np.nan_to_num(np.asarray(ds["ehl_contact_force"].values, float))
            on &= w > EVENT_FRACTION * w.max()
        if on.any():
            lo, hi = min(lo, x[on].min()), max(hi, x[on].max())
    return (float(lo) - 5.0, float(hi) + 5.0) if np.isfinite(lo) else None


def run_figures(results: list[Result], styles: Styles) -> list:
    """Overlays over crank angle of every set of every run (module docstring)."""
    runs = [r for r in results if r.kind == "run"]
    if not runs:
        return []
    win = event_window(runs)
    xr = ("runs", *win) if win else None
    figs: list = []
    for title, ylab, names, scale in RUN_TRACES:
        p = LineFigure(title, CRANK, ylab, xr)
        for k, r in enumerate(runs):
            ds = r.ds
            if not all(n in ds for n in names):
                continue
            x = ds["ehl_crank"].values
            shape = np.shape(ds[names[0]].values)
            loaded = (
                np.asarray(ds["loaded"].values, bool) if "loaded" in ds else np.ones(shape, bool)
            )
            for i, s in enumerate(r.sets):
                y = sum(np.asarray(ds[n].values[i], float) for n in names) * scale
                y = np.where(loaded[i], y, np.nan)
                disp = r.labels.get(s, s)
                name = f"{r.label} · {disp}"
                _line(p, x, y, name, styles.colour(disp), DASHES[k % 5], _width(i))
        if p.drawn:
            figs.append(p)
    p = LineFigure("Cam–tappet contact force W (explicit dynamics)", CRANK, "W [N]", xr)
    for k, r in enumerate(runs):
        if "contact_force" in r.ds:
            ds = r.ds
            _line(
                p,
                ds["crank_angle"].values,
                ds["contact_force"].values,
                f"{r.label} · contact force",
                "#333333",
                DASHES[k % 5],
            )
    figs.insert(4, p)
    return figs


# ----------------------------------------------------------------------------- engines
ENGINE_TRACES = (
    (
        "Camshaft drive torque per camshaft (cam–tappet contacts)",
        "T [N·m]",
        ("camshaft_drive_torque",),
    ),
    ("Cam–tappet friction torque per camshaft", "T_f [N·m]", ("camshaft_friction_torque",)),
    (
        "Auxiliary friction torque per camshaft: tappet bores + valve guides + journals",
        "T_aux [N·m]",
        tuple(f"{k}_torque" for k, _ in ENGINE_PARTS[1:]),
    ),
    (
        "Valvetrain friction power per camshaft (contacts + auxiliary)",
        "P_f [W]",
        ("camshaft_friction_power",),
    ),
)
ENGINE_CRANK = "crank angle of cylinder 1 from its firing TDC, 0–720° [°]"


def engine_figures(results: list[Result], styles: Styles) -> list:
    """Per-camshaft traces of every set of every engine result."""
    engines = [r for r in results if r.kind == "engine"]
    if not engines:
        return []
    xr = ("engines", 0.0, 720.0)
    figs: list = []
    for title, ylab, names in ENGINE_TRACES:
        p = LineFigure(title, ENGINE_CRANK, ylab, xr)
        for k, r in enumerate(engines):
            ds = r.ds
            if not all(n in ds for n in names):
                continue
            x = ds["engine_crank"].values
            shafts = [str(c) for c in ds["camshaft"].values]
            for (i, s), (j, c) in product(enumerate(r.sets), enumerate(shafts)):
                y = sum(np.asarray(ds[n].values[i, j], float) for n in names)
                disp = r.labels.get(s, s)
                prefix = f"{r.label} · " if len(engines) > 1 else ""
                dash = DASHES[(k * len(shafts) + j) % 5]
                name = f"{prefix}{disp} · {c} camshaft"
                _line(p, x, y, name, styles.colour(disp), dash, _width(i))
        if p.drawn:
            figs.append(p)
    return figs


# ----------------------------------------------------------------------------- sweeps
#: A sweep's friction-loss variable by preference: (variable, label, unit, scale).
SWEEP_LOSS = (
    ("valvetrain_friction_mep_Pa", "valvetrain friction MEP", "kPa", 1e-3),
    ("friction_energy_per_cycle_J", "friction energy per cycle", "J", 1.0),
    ("dynamics_friction_energy_per_cycle_J", "friction energy per cycle (dynamics)", "J", 1.0),
)


def axes_of(ds) -> list[str]:
    """The sweep's numeric axes (dimensions other than ``surface_set``)."""
    return (
        [
            d
            for d in ds[next(iter(ds.data_vars))].dims
            if d != "surface_set" and d in ds.coords and ds[d].dtype.kind in "fiu"
        ]
        if ds.data_vars
        else []
    )


def coating_delta(ds, loss: str, ref: str | None):
    """Change of ``loss`` against the reference set in % (negative: less friction):
    the sweep's stored ``engine_friction_energy_change_pct`` (a sweep.nc written before
    that name stores ``engine_friction_reduction_vs_uncoated_pct``, positive = less:
    negated), else the ratio of the stored values."""
    if "engine_friction_energy_change_pct" in ds:
        return ds["engine_friction_energy_change_pct"]
    if "engine_friction_reduction_vs_uncoated_pct" in ds:
        return -ds["engine_friction_reduction_vs_uncoated_pct"]
    v = ds[loss]
    if ref is None:
        raise ValueError("coating_delta: no reference set")
    return 100.0 * (v / v.sel(surface_set=ref) - 1.0)


def _unit(ds, dim):
    import json

    axes = json.loads(ds.attrs.get("axes", "[]") or "[]")
    return next((a.get("unit") or "" for a in axes if a.get("dim") == dim), "")


def sweep_figures(results: list[Result], styles: Styles) -> list:
    """Friction loss against each numeric axis (a line per set and value of the other
    axes), the coatings' change against the reference set, heat maps over two axes."""
    from bokeh.layouts import row

    figs: list = []
    for r in (r for r in results if r.kind == "sweep"):
        ds = r.ds
        spec = next((s for s in SWEEP_LOSS if s[0] in ds), None)  # the loss it holds
        axes = axes_of(ds)
        if spec is None or not axes:
            continue
        var, name, unit, scale = spec
        sets: list[str | None] = list(r.sets) or [None]
        has_sets = "surface_set" in ds[var].dims
        ref = r.reference
        # (values, y label, title's what, reference drawn): the loss, the coatings' change
        shown = [(ds[var] * scale, f"{name} [{unit}]", name, True)]
        if has_sets and ref is not None and len(sets) >= 2:
            shown.append(
                (
                    coating_delta(ds, var, ref),
                    f"change vs {r.labels.get(str(ref), str(ref))} [%]",
                    f"coatings' change of the {name}",
                    False,
                )
            )
        for xd in axes:
            others = [d for d in axes if d != xd]
            for da, ylab, what, with_ref in shown:
                title = f"{r.label}: {what} against {xd}" + (
                    "" if with_ref else " (negative = less friction)"
                )
                p = LineFigure(title, f"{xd} [{_unit(ds, xd)}]", ylab)
                combos = list(product(*[[(d, v) for v in ds[d].values] for d in others]))
                for ci, combo in enumerate(combos):
                    for s in sets:
                        if not with_ref and s == ref:
                            continue
                        sel = dict(combo)
                        if s is not None and has_sets:
                            sel["surface_set"] = s
                        y = da.sel(sel).transpose(xd).values
                        disp = r.labels.get(s, s) if s is not None else name
                        tail = ", ".join(f"{d} = {v:g} {_unit(ds, d)}".rstrip() for d, v in combo)
                        label = disp + (f" · {tail}" if tail else "")
                        xs, ys = np.asarray(ds[xd].values, np.float32), np.asarray(y, np.float32)
                        p.add(xs, ys, label, styles.colour(disp), DASHES[ci % 5], 1.8, True)
                figs.append(p)
        if len(axes) >= 2:
            maps = [_heatmap(r, var, name, unit, scale, axes[0], axes[1], s) for s in sets]
            figs.append(row(*maps))
    return figs


def _heatmap(r: Result, var, name, unit, scale, xd, yd, s):
    """Heat map of ``var`` over the axes ``xd`` × ``yd`` (other axes: their first
    value) of set ``s``; the colour scale is shared by the sets."""
    from bokeh.models import ColumnDataSource, HoverTool, LinearColorMapper
    from bokeh.models.annotations.labels import Title
    from bokeh.models.annotations.legends import ColorBar
    from bokeh.palettes import Viridis256
    from bokeh.plotting import figure

    ds = r.ds
    da = ds[var] * scale
    rest = {d: ds[d].values[0] for d in da.dims if d not in (xd, yd, "surface_set")}
    if s is not None and "surface_set" in da.dims:
        rest["surface_set"] = s
    grid = da.sel(rest).transpose(yd, xd).values
    xs, ys = ds[xd].values.astype(float), ds[yd].values.astype(float)
    xi, yi = np.meshgrid(np.arange(xs.size), np.arange(ys.size))
    src = ColumnDataSource(
        {
            "x": xi.ravel().astype(np.float32),
            "y": yi.ravel().astype(np.float32),
            "xv": np.repeat(xs[None, :], ys.size, 0).ravel().astype(np.float32),
            "yv": np.repeat(ys[:, None], xs.size, 1).ravel().astype(np.float32),
            "v": grid.ravel().astype(np.float32),
        }
    )
    lo, hi = float(np.nanmin(da.values)), float(np.nanmax(da.values))
    cmap = LinearColorMapper(palette=Viridis256, low=lo, high=hi if hi > lo else lo + 1.0)
    disp = r.labels.get(s, s) if s is not None else name
    p = figure(
        title=f"{disp}: {name} [{unit}]",
        width=360,
        height=330,
        x_axis_label=f"{xd} [{_unit(ds, xd)}]",
        y_axis_label=f"{yd} [{_unit(ds, yd)}]",
        tools="pan,box_zoom,reset,save",
    )
    p.rect(
        "x",
        "y",
        1.0,
        1.0,
        source=src,
        fill_color={"field": "v", "transform": cmap},
        line_color=None,
    )
    p.xaxis.ticker = list(range(xs.size))
    p.yaxis.ticker = list(range(ys.size))
    p.xaxis.major_label_overrides = {i: f"{v:g}" for i, v in enumerate(xs)}
    p.yaxis.major_label_overrides = {i: f"{v:g}" for i, v in enumerate(ys)}
    p.add_tools(
        HoverTool(
            tooltips=[(xd, "@xv{%0.5g}"), (yd, "@yv{%0.5g}"), (f"{name} [{unit}]", "@v{%0.4g}")],
            formatters={"@xv": "printf", "@yv": "printf", "@v": "printf"},
        )
    )
    p.add_layout(ColorBar(color_mapper=cmap, width=10), "right")
    if isinstance(p.title, Title):
        p.title.text_font_size = "12px"
    return p
