"""Figs. 8–11: explicit vs implicit dynamics; entraining and sliding speed, radius."""

from __future__ import annotations

import json
from typing import Any

import numpy as np

from .common import (
    MM,
    TITLE_SIZE,
    arr,
    crank_axis,
    dynamics_event,
    finish_numbered,
    in_window,
    log_ticks,
    place_labels,
    plt,
    point_legend_entry,
)

# ----------------------------------------------------------------------------- Figs. 8–10


def _zoom_windows(ds) -> list[tuple[float, float]]:
    """Engagement and disengagement windows [deg], widened to hold the largest
    explicit/implicit force difference on each side of the nose."""
    t_on, t_off = dynamics_event(ds)
    wins = [[t_on - 12.0, t_on + 38.0], [t_off - 32.0, t_off + 18.0]]
    if "contact_force_implicit" in ds:
        ca = arr(ds, "crank_angle")
        d = np.abs(arr(ds, "contact_force_implicit") - arr(ds, "contact_force"))
        mid = 0.5 * (t_on + t_off)
        for k, side in enumerate((ca < mid, ca >= mid)):
            near = side & (np.abs(ca - (t_on, t_off)[k]) < 60.0)
            if near.any() and np.nanmax(d[near]) > 0:
                c = ca[near][np.nanargmax(d[near])]
                wins[k][0] = min(wins[k][0], c - 10.0)
                wins[k][1] = max(wins[k][1], c + 10.0)
    return [(w[0], w[1]) for w in wins]


_EXPLICIT_STYLE: dict[str, Any] = dict(
    color="tab:blue", lw=1.5, label="explicit (analytic film in the dynamics)"
)
_IMPLICIT_STYLE: dict[str, Any] = dict(
    color="tab:orange", lw=1.3, ls="--", label="implicit (numerical EHL in the dynamics)"
)


def _shade_contact_loss(ax, ds) -> None:
    """Shade the intervals in which the tappet left the cam (``valve_jump`` of the
    results), say the maximum separation in the legend, and draw the separation tappet
    lift − cam lift [mm] on a right-hand axis."""
    jump = json.loads(ds.attrs.get("valve_jump", "{}") or "{}")
    intervals = jump.get("contact_loss_crank_deg") or []
    if not intervals:
        return
    sep = jump.get("max_separation_m") or 0.0
    label: str | None = f"contact lost (valve jump; max separation {sep * 1e3:.3g} mm)"
    for a, b in intervals:
        ax.axvspan(a, b, color="tab:red", alpha=0.18, lw=0, zorder=0, label=label)
        label = None  # one legend entry
    if "tappet_displacement" in ds and "cam_lift" in ds:
        gap = np.maximum(arr(ds, "tappet_displacement") - arr(ds, "cam_lift"), 0.0) * MM
        right = ax.twinx()
        right.plot(arr(ds, "crank_angle"), gap, color="tab:red", lw=1.0, ls=":")
        right.set_ylabel("separation, tappet − cam lift [mm]", color="tab:red")
        right.tick_params(axis="y", colors="tab:red")
        right.set_ylim(bottom=0.0, top=max(1.1 * float(np.max(gap)), 1e-3))


def _explicit_implicit(ds, path, var, ylabel, diff_unit, *, points=False, jumps=False):
    ca = arr(ds, "crank_angle")
    y = arr(ds, var)
    yi = arr(ds, f"{var}_implicit") if f"{var}_implicit" in ds else None
    fig = plt.figure(figsize=(12, 9.5), layout="constrained")
    gs = fig.add_gridspec(3, 2, height_ratios=(2.2, 1.0, 1.9))
    ax = fig.add_subplot(gs[0, :])
    ad = fig.add_subplot(gs[1, :], sharex=ax)
    zooms = [fig.add_subplot(gs[2, 0]), fig.add_subplot(gs[2, 1])]
    wins = _zoom_windows(ds)
    full = (float(ca[0]), float(ca[-1]))
    for a in [ax] + zooms:
        a.plot(ca, y, **_EXPLICIT_STYLE)
        if yi is not None:
            a.plot(ca, yi, **_IMPLICIT_STYLE)
        a.axhline(0, color="0.5", lw=0.6)
        a.set_ylabel(ylabel)
    crank_axis(ax, full)
    ax.set_xlabel("")
    ax.tick_params(labelbottom=False)
    ax.set_title("(a) presented engine cycle", fontsize=TITLE_SIZE)
    for k, (w, a) in enumerate(zip(wins, zooms)):
        ax.axvspan(*w, color="0.85", zorder=0)
        ax.text(
            0.5 * (w[0] + w[1]),
            1.0,
            "cd"[k],
            transform=ax.get_xaxis_transform(),
            ha="center",
            va="bottom",
            fontsize=9,
        )
        crank_axis(a, w)
        sel = in_window(ca, w)
        vals = y[sel] if yi is None else np.concatenate([y[sel], yi[sel]])
        lo, hi = np.nanmin(vals), np.nanmax(vals)
        pad = 0.08 * (hi - lo) or 1.0
        a.set_ylim(lo - pad, hi + pad)
        a.set_title(f"({'cd'[k]}) zoom: {('engagement', 'disengagement')[k]}", fontsize=TITLE_SIZE)
    if yi is not None:
        d = yi - y
        ad.plot(ca, d, color="tab:purple", lw=1.0)
        i = int(np.nanargmax(np.abs(d)))
        big = abs(d[i])
        txt = f"{big:.0f}" if big >= 100 else f"{big:.3g}"
        ad.annotate(
            f"max |Δ| = {txt} {diff_unit} at {ca[i]:.1f}°",
            (ca[i], d[i]),
            xytext=(12, 0),
            textcoords="offset points",
            fontsize=9,
            va="center",
            ha="left" if ca[i] < 0.8 * full[1] + 0.2 * full[0] else "right",
        )
        ad.axhline(0, color="0.5", lw=0.6)
    else:
        ad.text(
            0.5,
            0.5,
            "implicit run not in the results: explicit only",
            transform=ad.transAxes,
            ha="center",
            va="center",
            fontsize=11,
            color="tab:red",
        )
        ad.set_yticks([])
    ad.set_ylabel(f"implicit − explicit\n[{diff_unit}]")
    crank_axis(ad, full)
    ad.set_title("(b) difference", fontsize=TITLE_SIZE)
    if jumps:
        _shade_contact_loss(ax, ds)
    loaded = "loaded" not in ds or bool(ds["loaded"].any())
    if points and loaded and "point_crank" in ds:  # no EHL sample: no points
        pc = arr(ds, "point_crank")
        py = np.interp(pc, ca, y)
        ev = in_window(ca, (pc.min() - 40, pc.max() + 40))
        place_labels(
            ax,
            pc,
            py,
            [str(int(n)) for n in arr(ds, "point")],
            avoid=(ca[ev][::4], y[ev][::4]),
            radius_pt=16,
        )
        point_legend_entry(ax, ds)
    ax.legend(fontsize=9, loc="upper left")
    sub = None if yi is not None else "implicit run not in the results: explicit only"
    return finish_numbered(fig, path, sub)


def fig08(ds, path):
    return _explicit_implicit(ds, path, "tappet_velocity", "tappet velocity [m/s]", "m/s")


def fig09(ds, path):
    return _explicit_implicit(
        ds, path, "contact_force", "contact force W [N]", "N", points=True, jumps=True
    )


def fig10(ds, path):
    return _explicit_implicit(ds, path, "tappet_acceleration", "tappet acceleration [m/s²]", "m/s²")


# ----------------------------------------------------------------------------- Fig. 11


def _zero_crossings(x, y):
    s = np.sign(y)
    i = np.flatnonzero((s[:-1] * s[1:]) < 0)
    return x[i] - y[i] * (x[i + 1] - x[i]) / (y[i + 1] - y[i])


def fig11(ds, path):
    ca = arr(ds, "crank_angle")
    t_on, t_off = dynamics_event(ds)
    win = (max(ca[0], t_on - 40.0), min(ca[-1], t_off + 40.0))
    sel = in_window(ca, win)
    fig, axes = plt.subplots(
        3,
        1,
        figsize=(11, 9.5),
        sharex=True,
        layout="constrained",
        gridspec_kw=dict(height_ratios=(1.6, 1, 1)),
    )
    ue = arr(ds, "entrainment_speed")
    a = axes[0]
    a.plot(ca[sel], ue[sel], color="tab:blue", lw=1.6, label="u_e = ω(r_b + s + 2s'')/2")
    a.fill_between(
        ca[sel],
        ue[sel],
        0,
        where=ue[sel] < 0,
        color="tab:red",
        alpha=0.2,
        label="u_e < 0 (entrainment reversed)",
    )
    a.axhline(0, color="k", lw=0.9)
    zc = _zero_crossings(ca[sel], ue[sel])
    for k, z in enumerate(zc):
        a.axvline(z, color="tab:red", lw=0.8, ls=":")
        left = k % 2 == 0
        a.annotate(
            f"u_e = 0 at {z:.1f}°",
            (z, 0),
            xytext=(-8 if left else 8, -16),
            textcoords="offset points",
            ha="right" if left else "left",
            va="center",
            fontsize=8,
            color="tab:red",
            arrowprops=dict(arrowstyle="-", color="tab:red", lw=0.6),
        )
    a.set_ylabel("entraining speed u_e [m/s]")
    if "point_crank" in ds:
        pc = arr(ds, "point_crank")
        place_labels(
            a,
            pc,
            np.interp(pc, ca, ue),
            [str(int(n)) for n in arr(ds, "point")],
            avoid=(ca[sel][::4], ue[sel][::4]),
            radius_pt=15,
            fontsize=8,
        )
        a.plot([], [], "o", ms=6, mfc="white", mec="k", mew=1.5, label="representative points 1–6")
    a.legend(fontsize=9, loc="center")
    a.set_title("(a) entraining (mean rolling) speed", fontsize=TITLE_SIZE)
    a.grid(alpha=0.3)
    us = arr(ds, "sliding_speed")
    axes[1].plot(ca[sel], us[sel], color="tab:green", lw=1.5)
    axes[1].set_ylabel("sliding speed u_s [m/s]")
    axes[1].set_title("(b) sliding speed u_s = ω(r_b + s)", fontsize=TITLE_SIZE)
    axes[1].grid(alpha=0.3)
    R = arr(ds, "radius_of_curvature") * MM
    axes[2].plot(ca[sel], R[sel], color="tab:purple", lw=1.5)
    axes[2].set_yscale("log")
    log_ticks(axes[2])
    axes[2].set_ylabel("radius of curvature R [mm]")
    axes[2].set_title("(c) cam radius of curvature R = r_b + s + s''", fontsize=TITLE_SIZE)
    i = np.flatnonzero(sel)[np.argmin(R[sel])]
    axes[2].annotate(
        f"R_min = {R[i]:.2f} mm",
        (ca[i], R[i]),
        xytext=(0, 14),
        textcoords="offset points",
        ha="center",
        fontsize=8,
    )
    crank_axis(axes[2], win)
    axes[2].grid(alpha=0.3, which="both")
    return finish_numbered(
        fig,
        path,
        f"cam event {t_on:.0f}–{t_off:.0f}° crank (±40° of base circle shown); "
        f"{ds.attrs.get('engine_speed_rpm', float('nan')):g} rpm",
    )
