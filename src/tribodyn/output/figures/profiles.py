"""Figs. 13 and 14: pressure and film profiles at the representative points."""

from __future__ import annotations

import json
from typing import Any

import numpy as np

from .common import (
    MM,
    MPA,
    TITLE_SIZE,
    UM,
    arr,
    compares_paper,
    finish_numbered,
    legend_below,
    loaded_mask,
    plt,
    point_indices,
    set_labels,
    set_styles,
    support,
)

# ----------------------------------------------------------------------------- Figs. 13–14


def _compared_set(ds) -> int:
    """Index of the set compared with the reference in Fig. 13: the WC-C set of the
    ``surface_roles`` attribute (the paper's comparison), else the last set."""
    roles = json.loads(ds.attrs.get("surface_roles", "{}") or "{}")
    names = [str(v) for v in ds["surface_set"].values]
    name = roles.get("wcc")
    return names.index(name) if name in names else len(names) - 1


def _profiles_at(ds, i, sets):
    """(x [µm], p [MPa] rows, h [µm] rows) of the given sets at EHL sample i, on the first
    set's stored profile positions (each sample stores its whole solver domain)."""
    X = ds["profile_x"].values
    P = ds["pressure"].values
    H = ds["film"].values
    ref = next((j for j in sets if np.isfinite(X[j, i]).all()), sets[0])
    x = X[ref, i]

    def on_x(v, j):  # NaN where set j has no profile at this sample
        if not np.isfinite(X[j, i]).all():
            return np.full(x.size, np.nan)
        return np.interp(x, X[j, i], v[j, i], left=np.nan, right=np.nan)

    p, h = (np.array([on_x(v, j) for j in sets]) for v in (P, H))
    return x * UM, p * MPA, h * UM


def _load_fraction(ds, p, x):
    """Share of the total contact force carried by the stored profile (∫p dx × width)."""
    width = float(ds.attrs.get("cam_width_m", np.nan))
    good = np.isfinite(p)
    return np.trapezoid(p[good], x[good]) * width if good.sum() > 1 else np.nan


def _point_title(ds, n, i):
    e = arr(ds, "ehl_crank")
    w = arr(ds, "ehl_contact_force")[i]
    u = arr(ds, "ehl_entrainment_speed")[i]
    R = arr(ds, "ehl_radius")[i] * MM
    return f"point {n}: {e[i]:.0f}°\nW = {w:.0f} N, u_e = {u:.2f} m/s, R = {R:.1f} mm"


def fig13(ds, path):
    from matplotlib.lines import Line2D

    idx = point_indices(ds)
    sets = [0, _compared_set(ds)]
    labels = set_labels(ds)
    hyd = arr(ds, "hydrodynamic_load") if "hydrodynamic_load" in ds else None
    hc_all = arr(ds, "central_film")
    conv = np.asarray(ds["converged"].values) if "converged" in ds else None
    fig, axes = plt.subplots(2, 3, figsize=(15, 9.4), layout="constrained")
    # uncoated: broad light line; coated: thin dark dashed line on top (they often coincide)
    pst: list[dict[str, Any]] = [
        dict(color="tab:blue", ls="-", lw=2.6, alpha=0.55),
        dict(color="navy", ls="--", lw=1.3),
    ]
    hst: list[dict[str, Any]] = [
        dict(color="tab:red", ls="-", lw=2.6, alpha=0.55),
        dict(color="darkred", ls="--", lw=1.3),
    ]
    for k, (a, i) in enumerate(zip(axes.flat, idx)):
        n = int(arr(ds, "point")[k])
        ah = a.twinx()
        x, p, h = _profiles_at(ds, i, sets)
        loaded = loaded_mask(ds)[sets, i]
        lo, hi = support(x, p, frac=1e-3, pad=0.25)
        win = (x >= lo) & (x <= hi)
        for j in range(2):
            if not loaded[j]:
                continue
            a.plot(x, p[j], **pst[j])
            ah.plot(x, h[j], **hst[j])
            if conv is not None and int(conv[sets[j], i]) == 0:
                a.plot(x[win][::6], p[j][win][::6], "x", color="red", ms=6)
        a.set_xlim(lo, hi)
        pw, hw = p[:, win], h[:, win]
        if np.isfinite(pw).any():
            a.set_ylim(0, 1.1 * np.nanmax(pw))
        if np.isfinite(hw).any():
            ah.set_ylim(0, 1.1 * np.nanmax(hw))
        if not loaded.any():
            a.text(0.5, 0.5, "contact unloaded", transform=a.transAxes, ha="center")
        a.set_title(_point_title(ds, n, i), fontsize=10)
        a.set_xlabel("x [µm]")
        a.tick_params(axis="y", colors="tab:blue")
        ah.tick_params(axis="y", colors="tab:red")
        if k % 3 == 0:
            a.set_ylabel("pressure p [MPa]", color="tab:blue")
        if k % 3 == 2:
            ah.set_ylabel("film h [µm]", color="tab:red")
        a.grid(alpha=0.3)
        if hyd is not None and loaded[0] and hyd[0, i] > 0:
            p0 = p[0] / MPA
            share = _load_fraction(ds, p0, x / UM) / hyd[0, i]
            fin = np.flatnonzero(np.isfinite(p0))
            edge = fin.size and max(p0[fin[0]], p0[fin[-1]]) > 0.05 * np.nanmax(p0)
            if np.isfinite(share) and (share < 0.9 or edge):
                a.text(
                    0.03,
                    0.04,
                    "pressure not negligible at the domain edge:\n"
                    f"∫p dx × width = {share:.0%} of the fluid load",
                    transform=a.transAxes,
                    fontsize=8,
                    va="bottom",
                    color="0.2",
                    bbox=dict(fc="lightyellow", ec="0.6", alpha=0.9),
                )
        a.text(
            0.98,
            0.97,
            f"h_c = {hc_all[sets[0], i] * UM:.3f} / {hc_all[sets[1], i] * UM:.3f} µm",
            transform=a.transAxes,
            ha="right",
            va="top",
            fontsize=8,
            bbox=dict(fc="white", ec="none", alpha=0.8),
        )
    handles = [Line2D([], [], **st) for st in (*pst, *hst)]
    names = [f"{q}, {labels[s]}" for q in ("pressure", "film") for s in sets]
    legend_below(fig, handles, names, ncol=4, fontsize=10)
    sub = (
        f"{labels[sets[0]]} solid, {labels[sets[1]]} dashed"
        f"{' (as in the paper)' if compares_paper(ds) else ''}; "
        f"h_c given as {labels[sets[0]]} / {labels[sets[1]]}; "
        "x positive in the direction of positive u_e"
    )
    return finish_numbered(fig, path, sub)


def fig14(ds, path):
    idx = point_indices(ds)
    force = arr(ds, "ehl_contact_force")
    if idx:
        k = int(np.argmax(force[idx]))
        i, n = idx[k], int(arr(ds, "point")[k])
    else:
        i, n = int(np.nanargmax(force)), None
    styles = set_styles(ds)
    x, P, H = _profiles_at(ds, i, list(range(ds.sizes["surface_set"])))
    L = loaded_mask(ds)[:, i]
    fig, axes = plt.subplots(2, 3, figsize=(16, 8.8), layout="constrained")
    lo, hi = support(x, P[L], frac=1e-3, pad=0.25)
    win = (x >= lo) & (x <= hi)
    ip = int(np.nanargmax(np.where(win, P[0], -np.inf)))
    ih = int(np.nanargmin(np.where(win, H[0], np.inf)))
    span = 0.12 * (hi - lo)
    for j, st in enumerate(styles):
        if not L[j]:
            continue
        ref = j == 0
        kw = dict(
            st,
            lw=2.4 if ref else st["lw"],
            color="0.6" if ref else st["color"],
            zorder=2 if ref else 3,
            label=st["label"] + (" (reference)" if ref else ""),
        )
        axes[0, 0].plot(x, P[j], **kw)
        axes[1, 0].plot(x, H[j], **kw)
        axes[0, 1].plot(x, P[j], marker=".", ms=4, **kw)
        axes[1, 1].plot(x, H[j], marker=".", ms=4, **kw)
        axes[0, 2].plot(x, P[j] - P[0], **kw)
        axes[1, 2].plot(x, (H[j] - H[0]) * 1e3, **kw)
    axes[0, 0].set_ylim(0, 1.08 * np.nanmax(P[L][:, win]))
    axes[1, 0].set_ylim(0, 1.05 * np.nanmax(H[L][:, win]))
    for a in (axes[0, 0], axes[1, 0], axes[0, 2], axes[1, 2]):
        a.set_xlim(lo, hi)
    zp = (x >= x[ip] - span) & (x <= x[ip] + span)
    zh = (x >= x[ih] - span) & (x <= x[ih] + span)
    axes[0, 1].set_xlim(x[ip] - span, x[ip] + span)
    pz = P[L][:, zp]
    axes[0, 1].set_ylim(0.9 * np.nanmin(pz[pz > 0.5 * np.nanmax(pz)]), 1.02 * np.nanmax(pz))
    axes[1, 1].set_xlim(x[ih] - span, x[ih] + span)
    hz = H[L][:, zh]
    hmin = np.nanmin(hz)
    axes[1, 1].set_ylim(0.97 * hmin, hmin + 0.25 * (np.nanmax(hz) - hmin) + 0.03 * hmin)
    for a in axes[:, 2]:
        a.axhline(0, color="0.4", lw=0.8)
    titles = [
        [
            "(a) complete distribution",
            f"(b) zoom: {z} (dots: grid points)",
            "(c) difference to uncoated",
        ]
        for z in ("pressure peak", "film minimum")
    ]
    ylabels = [
        ["pressure p [MPa]", "pressure p [MPa]", "p − p(uncoated) [MPa]"],
        ["film h [µm]", "film h [µm]", "h − h(uncoated) [nm]"],
    ]
    for r in range(2):
        for c in range(3):
            a = axes[r, c]
            a.set_title(titles[r][c], fontsize=TITLE_SIZE)
            a.set_ylabel(ylabels[r][c])
            a.set_xlabel("x [µm]")
            a.grid(alpha=0.3)
    handles, labels = axes[0, 0].get_legend_handles_labels()
    legend_below(fig, handles, labels, ncol=len(labels))
    e = arr(ds, "ehl_crank")[i]
    what = f"point {n}, " if n else ""
    sub = (
        f"heaviest-loaded representative point: {what}{e:.0f}° crank, "
        f"W = {force[i]:.0f} N, u_e = {arr(ds, 'ehl_entrainment_speed')[i]:.2f} m/s, "
        f"R = {arr(ds, 'ehl_radius')[i] * MM:.2f} mm"
    )
    return finish_numbered(fig, path, sub)
