"""Figs. 5 and 6: dry pressure and EHL pressure/film for coating moduli and pairs."""

from __future__ import annotations

import json
from typing import Any

import numpy as np

from .common import MM, MPA, TITLE_SIZE, UM, arr, finish_numbered, has, legend_below, plt, support

# ----------------------------------------------------------------------------- Fig. 5


def fig05(ds, path):
    from ... import paper

    cond: dict[str, Any] = (
        json.loads(ds.attrs["dry_coating_conditions"])
        if "dry_coating_conditions" in ds.attrs
        else paper.FIG5
    )
    ratios = arr(ds, "dry_ratio")
    x = arr(ds, "dry_x") * UM
    p = arr(ds, "dry_pressure") * MPA
    b = arr(ds, "dry_half_width") * UM if "dry_half_width" in ds else np.full(ratios.size, np.nan)
    pm = arr(ds, "dry_max_pressure") * MPA if "dry_max_pressure" in ds else np.nanmax(p, axis=1)
    fig, (ax, az) = plt.subplots(
        1, 2, figsize=(12, 5), layout="constrained", gridspec_kw=dict(width_ratios=(1.3, 1))
    )
    cmap = plt.get_cmap("viridis")
    for i, r in enumerate(ratios):
        col = cmap(i / max(ratios.size - 1, 1))
        lab = f"E_c/E_s = {r:g}: b = {b[i]:.1f} µm, p_max = {pm[i]:.0f} MPa"
        for a in (ax, az):
            a.plot(x, p[i], color=col, lw=1.6, label=lab)
    hertz = "dry_hertz_pressure" in ds  # the study's reference (absent in older results)
    for a in (ax, az):
        if hertz:
            a.plot(
                arr(ds, "dry_hertz_x") * UM,
                arr(ds, "dry_hertz_pressure") * MPA,
                "k:",
                lw=1.2,
                label=f"Hertz, uncoated steel: b = {float(ds['dry_hertz_half_width']) * UM:.1f}"
                f" µm, p_h = {float(ds['dry_hertz_max_pressure']) * MPA:.0f} MPa",
            )
        a.set_xlabel("x [µm]")
        a.set_ylabel("contact pressure p [MPa]")
        a.grid(alpha=0.3)
    ax.set_xlim(x[0], x[-1])
    ax.set_ylim(0, 1.08 * np.nanmax(p))
    ax.set_title("(a) complete distribution", fontsize=TITLE_SIZE)
    top = np.nanmax(pm)
    bmax = np.nanmax(b) if np.isfinite(b).any() else 0.5 * (x[-1] - x[0]) / 1.3
    az.set_xlim(-0.45 * bmax, 0.45 * bmax)
    az.set_ylim(0.85 * np.nanmin(pm), 1.01 * top)
    az.set_title("(b) zoom on the pressure peak", fontsize=TITLE_SIZE)
    handles, labels = ax.get_legend_handles_labels()
    legend_below(fig, handles, labels, ncol=2)
    return finish_numbered(
        fig,
        path,
        f"steel cam on coated steel tappet: coating {cond['thickness'] * UM:g} µm, "
        f"{cond['load_total']:g} N over {cond['width'] * MM:g} mm, "
        f"R = {cond['radius'] * MM:g} mm assumed (not given in the paper)",
    )


# ----------------------------------------------------------------------------- Fig. 6


def fig06(ds, path):
    cond = json.loads(ds.attrs.get("ehl_coating_conditions", "{}") or "{}")
    x = arr(ds, "ehl_x") * UM
    groups = []
    if has(ds, "ehl_ratio_pressure", "ehl_ratio_film"):
        ratios = arr(ds, "ehl_ratio")
        ref = int(np.argmin(np.abs(ratios - 1.0)))
        cmap = plt.get_cmap("viridis")
        styles = [
            dict(color=cmap(i / max(ratios.size - 1, 1)), ls="-", lw=1.5, label=f"E_c/E_s = {r:g}")
            for i, r in enumerate(ratios)
        ]
        th = cond.get("thickness")
        what = "coating/steel modulus ratios" + (f", coating {th * UM:g} µm" if th else "")
        groups.append(("ehl_ratio", styles, ref, what, f"E_c/E_s = {ratios[ref]:g}"))
    if has(ds, "ehl_pair_pressure", "ehl_pair_film"):
        pairs = [str(v) for v in ds["ehl_pair"].values]
        cols = ["k", "tab:blue", "tab:red", "tab:green", "tab:purple"]
        styles = [
            dict(color=cols[i % len(cols)], ls=("-", "--", "-.", ":")[i % 4], lw=1.5, label=lab)
            for i, lab in enumerate(pairs)
        ]
        groups.append(("ehl_pair", styles, 0, "the paper's pairs", pairs[0]))
    if not groups:
        return None
    fig, axes = plt.subplots(
        3,
        len(groups),
        figsize=(6.2 * len(groups), 10.5),
        squeeze=False,
        layout="constrained",
        sharex="col",
        gridspec_kw=dict(height_ratios=(1.2, 1.2, 1)),
    )
    for col, (dim, styles, ref, what, ref_name) in enumerate(groups):
        p = arr(ds, f"{dim}_pressure") * MPA
        h = arr(ds, f"{dim}_film") * UM
        hc = (
            arr(ds, f"{dim}_central_film") * UM
            if f"{dim}_central_film" in ds
            else h[:, np.argmin(np.abs(x))]
        )
        hm = arr(ds, f"{dim}_min_film") * UM if f"{dim}_min_film" in ds else np.nanmin(h, axis=1)
        conv = (
            np.asarray(ds[f"{dim}_converged"].values).astype(bool)
            if f"{dim}_converged" in ds
            else np.ones(len(styles), bool)
        )
        lo, hi = support(x, p, pad=0.3)
        win = (x >= lo) & (x <= hi)
        ap, ah, ad = axes[:, col]
        for i, st in enumerate(styles):
            flag = "" if conv[i] else " (NOT converged)"
            ap.plot(
                x,
                p[i],
                **{**st, "label": f"{st['label']}: p_max = {np.nanmax(p[i]):.0f} MPa{flag}"},
            )
            ah.plot(
                x,
                h[i],
                **{**st, "label": f"{st['label']}: h_c = {hc[i]:.4f} µm, h_min = {hm[i]:.4f} µm"},
            )
            ad.plot(x, (h[i] - h[ref]) * 1e3, **st)
        ap.set_ylabel("pressure p [MPa]")
        ap.set_title(f"({'ab'[col]}) {what}", fontsize=TITLE_SIZE)
        ap.set_ylim(0, 1.08 * np.nanmax(p[:, win]))
        ah.set_ylabel("film h [µm]")
        hwin = h[:, win]
        ah.set_ylim(0, min(np.nanmax(hwin), 2.5 * np.nanmax(hc)) * 1.05)
        ad.set_ylabel(f"h − h({ref_name}) [nm]")
        ad.axhline(0, color="0.5", lw=0.8)
        dwin = (h[:, win] - h[ref, win]) * 1e3
        lim = np.nanmax(np.abs(dwin)) * 1.15 or 1.0
        ad.set_ylim(-lim, lim)
        ad.set_title("film difference in the contact (zoom: the differences are nm)", fontsize=9)
        ad.set_xlabel("x [µm]  (entraining direction →)")
        for a in (ap, ah, ad):
            a.set_xlim(lo, hi)
            a.grid(alpha=0.3)
        ap.legend(fontsize=8, loc="upper left")
        ah.legend(fontsize=8, loc="lower left")
    sub = ""
    if cond:
        sub = (
            f"{cond.get('load_total', float('nan')):g} N over "
            f"{cond.get('width', float('nan')) * MM:g} mm, "
            f"u_e = {cond.get('entrainment_speed', float('nan')):g} m/s, pure rolling, "
            f"R = {cond.get('radius', float('nan')) * MM:g} mm assumed "
            "(not given in the paper)"
        )
        if cond.get("pair_thickness"):
            sub += f"; pairs: coating {cond['pair_thickness'] * UM:g} µm"
    return finish_numbered(fig, path, sub or None)
