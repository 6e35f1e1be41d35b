"""Figures of a design sweep, drawn from the combined sweep Dataset.

* ``sweep_friction.png`` — friction energy per cycle and mean friction power against the
  sweep's x axis (engine speed when it is swept), one line per surface set;
* ``sweep_film.png`` — minimum film thickness and minimum λ = h_min/σ;
* ``sweep_dynamics.png`` — peak contact force and minimum contact force in the cam event
  (jumps marked, jump onset speed drawn), seating velocity (valve bounce marked);
* ``sweep_heatmap.png`` — any sweep with two or more numeric dimensions: friction energy
  (or, for dynamics sweeps, peak contact force) and minimum film (minimum contact force)
  over the first two, one panel per surface set.

The x axis is the dimension of ``engine.speed_rpm`` if it is swept, else the first numeric
dimension. Further dimensions: up to four combinations share a panel as line styles;
with more, the line figures show the first combination (named in the subtitle) and the
heat map shows the rest. Failed points are gaps (NaN) in the lines and crossed-out cells
in the heat maps.
"""

from __future__ import annotations

import itertools
import json
from pathlib import Path

import numpy as np

from ..._safe_write import make_dirs
from .common import UM, fitted_legend, fitted_suptitle, has, plt, save_figure, set_styles

__all__ = ["sweep_figures", "x_dim", "other_combinations", "onset_speeds", "SWEEP_FIGURES"]

SWEEP_FIGURES = {
    "sweep_friction.png": "Friction energy per cycle and mean friction power",
    "sweep_film.png": "Minimum film thickness and minimum λ",
    "sweep_dynamics.png": "Peak and minimum contact force, jump and bounce",
    "sweep_heatmap.png": "Two-axis maps",
}
_LINESTYLES = ("-", "--", ":", "-.")
_MAX_COMBOS = 4


def _sweep_dims(ds) -> list[str]:
    axes = json.loads(ds.attrs.get("axes", "[]"))
    return list(dict.fromkeys(a["dim"] for a in axes))


def _numeric(ds, dim) -> bool:
    return np.asarray(ds[dim].values).dtype.kind in "iuf"


def x_dim(ds) -> str | None:
    """The dimension for the x axis: that of engine.speed_rpm, else the first numeric."""
    axes = json.loads(ds.attrs.get("axes", "[]"))
    speed = next((a["dim"] for a in axes if a["path"] == "engine.speed_rpm"), None)
    dims = _sweep_dims(ds)
    return speed or next((d for d in dims if _numeric(ds, d)), dims[0] if dims else None)


def _x_values(ds, xd):
    """Values along the x dimension: engine speed if it is there, else the dim's own."""
    axes = json.loads(ds.attrs.get("axes", "[]"))
    for a in axes:
        if a["dim"] == xd and a["path"] == "engine.speed_rpm":
            return np.asarray(ds[a["name"]].values, float), "engine speed [rpm]"
    a = next((a for a in axes if a["dim"] == xd), None)
    label = xd if a is None else f"{a['name']} [{a['unit']}]" if a["unit"] else a["name"]
    v = np.asarray(ds[xd].values)
    return (v.astype(float) if v.dtype.kind in "iufb" else np.arange(v.size)), label


def other_combinations(ds, xd) -> list[tuple[dict, str]]:
    """Index selections and labels of every combination of the dimensions other than
    ``xd``."""
    dims = [d for d in _sweep_dims(ds) if d != xd]
    out = [
        (
            dict(zip(dims, pos)),
            ", ".join(f"{d} = {_fmt(ds[d].values[i])}" for d, i in zip(dims, pos)),
        )
        for pos in itertools.product(*(range(ds.sizes[d]) for d in dims))
    ]
    return out or [({}, "")]


def _fmt(v) -> str:
    return f"{v:.4g}" if isinstance(v, (float, np.floating)) else str(v)


def onset_speeds(ds, var="jump") -> list[tuple[str, float, float]]:
    """Per combination of the other dimensions: (label, highest x without ``var`` below
    the onset, lowest x with it) — the onset lies between; NaN where it does not occur
    (or where every point has it: then the first is NaN)."""
    xd = x_dim(ds)
    if xd is None or var not in ds:
        return []
    x, _ = _x_values(ds, xd)
    order = np.argsort(x)
    xs = x[order]
    out = []
    for sel, label in other_combinations(ds, xd):
        vs = np.asarray(ds[var].isel(sel).transpose(xd, ...).values, float)[order]
        hit = np.flatnonzero(vs == 1)
        if hit.size == 0:
            out.append((label, np.nan, np.nan))
            continue
        k = hit[0]
        below = np.flatnonzero(vs[:k] == 0)
        out.append((label, float(xs[below[-1]]) if below.size else np.nan, float(xs[k])))
    return out


def _combos(ds, xd):
    combos = other_combinations(ds, xd)
    note = None
    if len(combos) > _MAX_COMBOS:
        note = f"at {combos[0][1]} (first of {len(combos)} combinations; see the heat map)"
        combos = combos[:1]
    return combos, note


def _set_lines(ds, combos):
    """(style dict, surface-set index or None, combination) for every line to draw."""
    if "surface_set" not in ds.dims:
        return [
            (dict(color="k", ls=_LINESTYLES[j % 4], lw=1.5, label=lab or None), None, sel)
            for j, (sel, lab) in enumerate(combos)
        ]
    styles = set_styles(ds)
    lines = []
    for j, (sel, lab) in enumerate(combos):
        for i, st in enumerate(styles):
            st = dict(st)
            st["lw"] = max(1.0, 2.6 - 0.6 * i)  # sets lying on one another stay visible
            if len(combos) > 1:
                st["color"] = plt.get_cmap("tab10")(i % 10)
                st["ls"] = _LINESTYLES[j % 4]
                st["label"] = f"{st['label']} ({lab})"
            lines.append((st, i, sel))
    return lines


def _series(ds, name, xd, i, sel):
    v = ds[name].isel(sel)
    if i is not None:
        v = v.isel(surface_set=i)
    return np.asarray(v.transpose(xd, ...).values, float)


def _mark_events(ax, x, y, hit, label):
    """Red crosses at the points where an event (jump, bounce) occurred (``hit``)."""
    if hit.any():
        ax.plot(x[hit], y[hit], "x", color="red", ms=9, mew=2, label=label, zorder=5)


def _line_panel(ax, ds, name, xd, combos, scale=1.0, ylabel=""):
    x, xlabel = _x_values(ds, xd)
    order = np.argsort(x)
    for st, i, sel in _set_lines(ds, combos):
        y = _series(ds, name, xd, i, sel) * scale
        if not np.isfinite(y).any():  # every point of this line failed
            continue
        ax.plot(x[order], y[order], marker="o", ms=3.5, **st)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3)


def _finish(fig, axes, path, title, note):
    h, lab = axes[0].get_legend_handles_labels()
    if h:
        fitted_legend(fig, h, lab, fontsize=8, frameon=False)
    fitted_suptitle(fig, title if note is None else f"{title}\n{note}", fontsize=11)
    return save_figure(fig, path)


def _line_figure(ds, panels, rows=1, height=4.4):
    """(fig, axes, note): a line panel per ``(name, scale, ylabel)`` of ``panels`` over
    the sweep's x axis (one line per surface set and combination of the other axes), in
    ``rows`` rows; ``height`` of the figure [in]."""
    xd = x_dim(ds)
    combos, note = _combos(ds, xd)
    fig, axes = plt.subplots(rows, len(panels) // rows, figsize=(11, height), layout="constrained")
    axes = list(np.ravel(axes))
    for ax, (name, scale, ylabel) in zip(axes, panels, strict=True):
        _line_panel(ax, ds, name, xd, combos, scale, ylabel)
    return fig, axes, note


def fig_friction(ds, path):
    fig, axes, note = _line_figure(
        ds,
        (
            ("friction_energy_per_cycle_J", 1.0, "friction energy per cycle [J]"),
            ("mean_friction_power_W", 1.0, "mean friction power [W]"),
        ),
    )
    return _finish(fig, axes, path, "Cam–tappet friction loss (transient mixed EHL)", note)


def fig_engine_map(ds, path):
    """Engine sweep (``mode = "engine"``): valvetrain FMEP, mean camshaft friction torque
    and power, and each surface's change against the reference (negative = less), over
    the x axis, one
    line per surface set and combination of the other axes (e.g. oil temperature)."""
    fig, axes, note = _line_figure(
        ds,
        (
            ("valvetrain_friction_mep_Pa", 1e-3, "valvetrain FMEP [kPa]"),
            ("engine_friction_torque_Nm", 1.0, "mean camshaft friction torque [N m]"),
            ("engine_friction_power_W", 1.0, "friction power [W]"),
            (
                "engine_friction_energy_change_pct",
                1.0,
                "friction energy vs reference [%, − = less]",
            ),
        ),
        rows=2,
        height=8,
    )
    return _finish(fig, axes, path, "Valvetrain friction map of the engine", note)


def fig_film(ds, path):
    fig, axes, note = _line_figure(
        ds,
        (("min_film_m", UM, "minimum film h_min [µm]"), ("min_lambda", 1.0, "minimum λ = h_min/σ")),
    )
    axes[1].axhline(1.0, color="0.5", lw=0.8, ls="--")
    axes[1].axhline(3.0, color="0.5", lw=0.8, ls=":")
    axes[1].text(
        0.99,
        1.0,
        "λ = 1 (boundary)",
        transform=axes[1].get_yaxis_transform(),
        ha="right",
        va="bottom",
        fontsize=7,
        color="0.4",
    )
    return _finish(fig, axes, path, "Minimum film in the cam event", note)


def fig_dynamics(ds, path):
    xd = x_dim(ds)
    combos, note = _combos(ds, xd)
    x, xlabel = _x_values(ds, xd)
    order = np.argsort(x)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.4), layout="constrained")
    for j, (sel, lab) in enumerate(combos):
        ls = _LINESTYLES[j % 4]
        sfx = f" ({lab})" if lab else ""
        pk = _series(ds, "peak_contact_force_N", xd, None, sel)[order]
        mn = _series(ds, "min_contact_force_in_event_N", xd, None, sel)[order]
        axes[0].plot(x[order], pk, ls=ls, marker="o", ms=3.5, color="tab:blue", label=f"peak{sfx}")
        axes[0].plot(
            x[order],
            mn,
            ls=ls,
            marker="s",
            ms=3.5,
            color="tab:orange",
            label=f"minimum in the cam event{sfx}",
        )
        jump = _series(ds, "jump", xd, None, sel)[order] == 1
        _mark_events(axes[0], x[order], mn, jump, "jump (contact lost)" if j == 0 else None)
        sv = _series(ds, "seating_velocity_m_s", xd, None, sel)[order]
        axes[1].plot(
            x[order], sv, ls=ls, marker="o", ms=3.5, color="k", label=f"seating velocity{sfx}"
        )
        bounce = _series(ds, "valve_bounce", xd, None, sel)[order] == 1
        _mark_events(axes[1], x[order], sv, bounce, "valve bounce" if j == 0 else None)
    speed = xlabel.startswith("engine speed")
    for ax, var, name in ((axes[0], "jump", "jump"), (axes[1], "valve_bounce", "bounce")):
        for k, (_lab, lo, hi) in enumerate(onset_speeds(ds, var)[: len(combos)]):
            if np.isfinite(hi):
                ax.axvline(hi, color="red", lw=0.8, ls=_LINESTYLES[k % 4], alpha=0.6)
                where = f"{lo:g}–{hi:g}" if np.isfinite(lo) else f"≤ {hi:g}"
                ax.text(
                    hi,
                    0.98,
                    f"{name} onset {where}" + (" rpm" if speed else "") + " ",
                    transform=ax.get_xaxis_transform(),
                    rotation=90,
                    va="top",
                    ha="right",
                    fontsize=7,
                    color="red",
                )
    clipped = _clip_impacts(axes[0], ds, xd, combos, x, order)
    axes[0].axhline(0.0, color="0.5", lw=0.8)
    axes[0].set_ylabel("cam–tappet contact force [N]")
    axes[1].set_ylabel("valve seating velocity [m/s]")
    for ax in axes:
        ax.set_xlabel(xlabel)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="best")
    sub = "; ".join(t for t in (note, clipped) if t)
    fitted_suptitle(fig, "Valvetrain dynamics" + (f"\n{sub}" if sub else ""), fontsize=11)
    return save_figure(fig, path)


def _clip_impacts(ax, ds, xd, combos, x, order):
    """After a jump the tappet lands on the cam: impact peaks can be tens of times the
    cam-driven peak. Keep the axis on the cam-driven range (2.5× the largest peak without
    a jump) and mark the points above it at the top edge."""
    pk = np.concatenate([_series(ds, "peak_contact_force_N", xd, None, s) for s, _ in combos])
    jump = np.concatenate([_series(ds, "jump", xd, None, s) for s, _ in combos]) == 1
    calm = pk[np.isfinite(pk) & ~jump]
    if calm.size == 0 or not np.isfinite(pk).any():
        return None
    top = 2.5 * float(calm.max())
    if np.nanmax(pk) <= top:
        return None
    lows = np.concatenate(
        [_series(ds, "min_contact_force_in_event_N", xd, None, s) for s, _ in combos]
    )
    low = min(0.0, float(np.nanmin(lows))) if np.isfinite(lows).any() else 0.0
    ax.set_ylim(low - 0.04 * top, top)
    for sel, _ in combos:
        y = _series(ds, "peak_contact_force_N", xd, None, sel)[order]
        off = np.isfinite(y) & (y > top)
        ax.plot(
            x[order][off],
            np.full(off.sum(), top),
            "^",
            color="tab:blue",
            ms=6,
            clip_on=False,
            zorder=6,
        )
    return f"▲ peak off scale: impact after a jump, up to {np.nanmax(pk):.3g} N"


def fig_heatmap(ds, path):
    """Maps over the first two numeric dimensions (others at their first value)."""
    xd = x_dim(ds)
    num = [d for d in _sweep_dims(ds) if d != xd and _numeric(ds, d)]
    if xd is None or not num:
        return None
    yd = num[0]
    rest = {d: 0 for d in _sweep_dims(ds) if d not in (xd, yd)}
    study = "surface_set" in ds.dims and has(ds, "friction_energy_per_cycle_J")
    if study:
        quantities = [
            ("friction_energy_per_cycle_J", 1.0, "friction energy per cycle [J]"),
            ("min_film_m", UM, "minimum film [µm]"),
        ]
        cols: list[int | None] = list(range(ds.sizes["surface_set"]))
        labels = [
            str(v)
            for v in (
                ds["surface_label"].values
                if "surface_label" in ds.coords
                else ds["surface_set"].values
            )
        ]
    else:
        quantities = [
            ("peak_contact_force_N", 1.0, "peak contact force [N]"),
            ("min_contact_force_in_event_N", 1.0, "min. contact force in event [N]"),
        ]
        cols, labels = [None], [""]
    x, xlabel = _x_values(ds, xd)
    y, ylabel = _x_values(ds, yd)
    fig, axes = plt.subplots(
        len(quantities),
        len(cols),
        squeeze=False,
        figsize=(2.9 * len(cols) + 1.5, 2.6 * len(quantities) + 0.8),
        layout="constrained",
    )
    ok = np.asarray(ds["status"].isel(rest).transpose(yd, xd).values) == 1
    for r, (name, scale, qlabel) in enumerate(quantities):
        da = ds[name].isel(rest)
        vals = [
            np.asarray(
                (da.isel(surface_set=c) if c is not None else da).transpose(yd, xd).values, float
            )
            * scale
            for c in cols
        ]
        fin = np.concatenate([v[np.isfinite(v)] for v in vals]) if vals else np.array([])
        vmin, vmax = (float(fin.min()), float(fin.max())) if fin.size else (0.0, 1.0)
        for c, (v, lab) in enumerate(zip(vals, labels)):
            ax = axes[r, c]
            # one cell per point, labelled with the axis values (any spacing)
            m = ax.pcolormesh(
                np.arange(x.size + 1) - 0.5,
                np.arange(y.size + 1) - 0.5,
                v,
                cmap="viridis",
                vmin=vmin,
                vmax=vmax,
            )
            if v.size <= 64:
                for iy, ix in np.argwhere(np.isfinite(v)):
                    ax.text(
                        ix,
                        iy,
                        f"{v[iy, ix]:.3g}",
                        ha="center",
                        va="center",
                        fontsize=6.5,
                        color="w" if v[iy, ix] < 0.5 * (vmin + vmax) else "k",
                    )
            for iy, ix in np.argwhere(~ok):
                ax.plot(ix, iy, "x", color="red", ms=8, mew=1.5)
            for axis, vals in ((ax.xaxis, x), (ax.yaxis, y)):
                k = max(1, int(np.ceil(vals.size / 8)))
                axis.set_ticks(np.arange(0, vals.size, k))
                axis.set_ticklabels([f"{t:.4g}" for t in vals[::k]], fontsize=7)
            if r == 0 and lab:
                ax.set_title(lab, fontsize=9)
            ax.set_xlabel(xlabel, fontsize=8)
            if c == 0:
                ax.set_ylabel(ylabel, fontsize=8)
        fig.colorbar(m, ax=axes[r, :], label=qlabel, shrink=0.9)
    sub = ", ".join(f"{d} = {_fmt(ds[d].values[0])}" for d in rest)
    title = (
        "Sweep maps" + (f" (at {sub})" if sub else "") + ("; × failed point" if (~ok).any() else "")
    )
    fitted_suptitle(fig, title, fontsize=11)
    return save_figure(fig, path)


def sweep_figures(ds, out_dir) -> dict[str, Path]:
    """Write the sweep figures that the Dataset supports; returns {file name: path}."""
    out = Path(out_dir)
    make_dirs(out)
    if x_dim(ds) is None or int(ds["status"].sum()) == 0:
        return {}
    made = {}
    makers = [
        ("sweep_friction.png", fig_friction, ("friction_energy_per_cycle_J",)),
        ("sweep_engine_map.png", fig_engine_map, ("valvetrain_friction_mep_Pa",)),
        ("sweep_film.png", fig_film, ("min_film_m", "min_lambda")),
        ("sweep_dynamics.png", fig_dynamics, ("peak_contact_force_N",)),
        ("sweep_heatmap.png", fig_heatmap, ("status",)),
    ]
    for name, fn, need in makers:
        if has(ds, *need):
            p = fn(ds, out / name)
            if p is not None:
                made[name] = p
    return made
