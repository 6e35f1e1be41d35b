"""Report figures of a cam-cycle study, drawn from the results Dataset.

:func:`make_figures` reads only the Dataset built by
:func:`tribodyn.results_io.study_to_dataset` (dimensions and variables are documented
there) and writes one PNG per paper figure (Figs. 5, 6, 8–18 of Andreou et al. 2023)
plus two summary figures (19: friction power and energy, 20: minimum film and λ).

Conventions of every figure:

* quantities in engineering units: µm, MPa, N, m/s, W, J; time axes in crank degrees;
* EHL quantities are plotted only where the contact is loaded (``loaded``), and the
  crank-angle axis of the EHL figures is restricted to the cam event (samples where the
  contact force exceeds :data:`EVENT_FRACTION` of its maximum, plus a small margin):
  the base circle carries only a few newtons of ringing;
* EHL steps that did not converge (``converged == 0``) are marked with red crosses;
* files are written atomically (temporary file, then rename) by
  :func:`tribodyn.plots.save_figure`.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np

from .plots import plt, save_figure

__all__ = ["FIGURES", "EVENT_FRACTION", "make_figures"]

#: File names and titles of the figures :func:`make_figures` writes, in order.
FIGURES = {
    "fig05_dry_pressure.png":
        "Dry contact pressure for coating/steel modulus ratios (paper Fig. 5)",
    "fig06_ehl_pressure_film.png":
        "EHL pressure and film for coating moduli and real pairs (paper Fig. 6)",
    "fig08_tappet_velocity.png": "Tappet velocity, explicit vs implicit EHL (paper Fig. 8)",
    "fig09_contact_force.png":
        "Cam–tappet contact force, explicit vs implicit EHL (paper Fig. 9)",
    "fig10_tappet_acceleration.png":
        "Tappet acceleration, explicit vs implicit EHL (paper Fig. 10)",
    "fig11_entrainment_speed.png":
        "Entraining speed, sliding speed and radius of curvature (paper Fig. 11)",
    "fig12_greenwood_chart.png": "Greenwood chart of the operating points (paper Fig. 12)",
    "fig13_pressure_film_points.png":
        "Pressure and film at the six representative points (paper Fig. 13)",
    "fig14_coatings_pressure_film.png": "Pressure and film of the coated surfaces (paper Fig. 14)",
    "fig15_central_film.png": "Central film thickness over the cycle (paper Fig. 15)",
    "fig16_boundary_load.png": "Asperity (boundary) load over the cycle (paper Fig. 16)",
    "fig17_boundary_friction.png": "Boundary friction over the cycle (paper Fig. 17)",
    "fig18_viscous_friction.png": "Viscous friction over the cycle (paper Fig. 18)",
    "fig19_friction_power.png": "Friction power and friction energy per cycle",
    "fig20_min_film_lambda.png": "Minimum film thickness and λ = h_min/σ over the cycle",
}

#: A sample belongs to the cam event where the contact force exceeds this share of its max.
EVENT_FRACTION = 0.05
_EVENT_MARGIN_DEG = 5.0
_UM, _MPA, _MM = 1e6, 1e-6, 1e3
_FAMILY_COLOURS = ("tab:blue", "tab:red", "tab:green", "tab:purple", "tab:brown", "tab:olive")
_TITLE_SIZE = 11


# ----------------------------------------------------------------------------- helpers

def _has(ds, *names) -> bool:
    return all(n in ds.variables for n in names)


def _arr(ds, name) -> np.ndarray:
    return np.asarray(ds[name].values, dtype=float)


def _set_labels(ds) -> list[str]:
    if "surface_label" in ds:
        return [str(v) for v in ds["surface_label"].values]
    return [str(v) for v in ds["surface_set"].values]


def _set_styles(ds) -> list[dict]:
    """Line style per surface set: uncoated black; one colour per coating family,
    the thinnest coating dashed, the thickest solid."""
    labels = _set_labels(ds)
    parsed = []
    for lab in labels:
        m = re.match(r"^(.*?)\s*([0-9]+(?:\.[0-9]+)?)\s*µm", lab)
        parsed.append((m.group(1).strip(), float(m.group(2))) if m else (lab, None))
    families = []
    for i, (fam, _) in enumerate(parsed):
        bare = i == 0 or fam.lower() in ("uncoated", "steel", "steel (uncoated)")
        if not bare and fam not in families:
            families.append(fam)
    styles = []
    for i, ((fam, thick), lab) in enumerate(zip(parsed, labels)):
        if i == 0 or fam not in families:
            styles.append(dict(color="k", ls="-", lw=1.8, label=lab))
            continue
        col = _FAMILY_COLOURS[families.index(fam) % len(_FAMILY_COLOURS)]
        thicknesses = sorted({t for f, t in parsed if f == fam and t is not None})
        dashed = thick is not None and len(thicknesses) > 1 and thick == thicknesses[0]
        styles.append(dict(color=col, ls="--" if dashed else "-", lw=1.4, label=lab))
    return styles


def _loaded(ds) -> np.ndarray:
    """Boolean (surface_set, ehl_crank) mask of loaded EHL samples."""
    return np.asarray(ds["loaded"].values).astype(bool)


def _masked(ds, name) -> np.ndarray:
    """EHL cycle variable (surface_set, ehl_crank) with NaN where unloaded."""
    return np.where(_loaded(ds), _arr(ds, name), np.nan)


def _event_window(ds) -> tuple[float, float]:
    """Crank window [deg] of the cam event in the EHL samples (loaded and the contact
    force above EVENT_FRACTION of its maximum), with a small margin."""
    e = _arr(ds, "ehl_crank")
    force = _arr(ds, "ehl_contact_force") if "ehl_contact_force" in ds else None
    sel = _loaded(ds).any(axis=0)
    if force is not None and np.isfinite(force).any() and np.nanmax(force) > 0:
        sel &= force >= EVENT_FRACTION * np.nanmax(force)
    if not sel.any():
        return float(e[0]), float(e[-1])
    return (max(float(e[sel][0]) - _EVENT_MARGIN_DEG, float(e[0])),
            min(float(e[sel][-1]) + _EVENT_MARGIN_DEG, float(e[-1])))


def _in_window(x, window) -> np.ndarray:
    return (x >= window[0]) & (x <= window[1])


def _dynamics_event(ds) -> tuple[float, float]:
    """Engagement and disengagement crank angles [deg] of the dynamics output."""
    ca = _arr(ds, "crank_angle")
    f = _arr(ds, "contact_force")
    on = np.flatnonzero(f >= EVENT_FRACTION * np.nanmax(f)) if np.nanmax(f) > 0 else []
    if len(on) == 0:
        return float(ca[0]), float(ca[-1])
    return float(ca[on[0]]), float(ca[on[-1]])


def _crank_axis(ax, window=None):
    ax.set_xlabel("crank angle [deg]")
    if window is not None:
        ax.set_xlim(*window)
    ax.grid(alpha=0.3)


def _mark_failures(ax, ds, values, window=None, label=True) -> int:
    """Red crosses at loaded, non-converged EHL steps; returns how many were drawn."""
    if "converged" not in ds:
        return 0
    e = _arr(ds, "ehl_crank")
    bad = (np.asarray(ds["converged"].values) == 0) & _loaded(ds)
    if window is not None:
        bad &= _in_window(e, window)[None, :]
    idx = np.nonzero(bad & np.isfinite(values))
    if idx[0].size == 0:
        return 0
    ax.plot(e[idx[1]], values[idx], "x", color="red", ms=7, mew=1.8, ls="none",
            label="EHL step not converged" if label else None, zorder=5)
    return int(idx[0].size)


def _failure_note(ds) -> str:
    if "converged" not in ds:
        return ""
    n = int(((np.asarray(ds["converged"].values) == 0) & _loaded(ds)).sum())
    return f"{n} non-converged EHL step(s) marked ×" if n else "all EHL steps converged"


def _place_labels(ax, xs, ys, texts, *, avoid=None, radius_pt=20.0, fontsize=9,
                  marker=True, color="k"):
    """Annotate points with short labels, choosing for each label the offset direction
    farthest from the other points, the labels already placed and ``avoid`` (x, y).
    Points closer than a marker size share one label ("3,4")."""
    xs = np.asarray(xs, dtype=float)
    ys = np.asarray(ys, dtype=float)
    scale = 72.0 / ax.figure.dpi
    tr = ax.transData
    pts = tr.transform(np.column_stack([xs, ys])) * scale
    # merge (nearly) coincident points
    merged = []
    for k in range(len(xs)):
        for grp in merged:
            if np.hypot(*(pts[k] - pts[grp[0]])) < 6.0:
                grp.append(k)
                break
        else:
            merged.append([k])
    obstacles = [pts]
    if avoid is not None:
        ax_, ay_ = (np.asarray(a, dtype=float) for a in avoid)
        ok = np.isfinite(ax_) & np.isfinite(ay_)
        if ok.any():
            obstacles.append(tr.transform(np.column_stack([ax_[ok], ay_[ok]])) * scale)
    obst = np.vstack(obstacles)
    bbox = ax.get_window_extent()
    x0, y0, x1, y1 = np.array([bbox.x0, bbox.y0, bbox.x1, bbox.y1]) * scale
    angles = np.deg2rad(np.arange(0, 360, 30) + 15)
    placed = []
    for grp in merged:
        px, py = pts[grp[0]]
        text = ",".join(texts[k] for k in grp)
        best, best_score = None, -np.inf
        for r in (radius_pt, 1.6 * radius_pt, 2.3 * radius_pt):
            for a in angles:
                cx, cy = px + r * np.cos(a), py + r * np.sin(a)
                if not (x0 + 10 < cx < x1 - 10 and y0 + 10 < cy < y1 - 10):
                    continue
                d = np.min(np.hypot(obst[:, 0] - cx, obst[:, 1] - cy))
                if placed:
                    pl = np.array(placed)
                    d = min(d, 0.7 * np.min(np.hypot(pl[:, 0] - cx, pl[:, 1] - cy)))
                score = min(d, 2.5 * radius_pt) - 0.2 * r
                if score > best_score:
                    best, best_score = (cx - px, cy - py), score
        if best is None:
            best = (radius_pt * 0.7, radius_pt * 0.7)
        placed.append((px + best[0], py + best[1]))
        if marker:
            ax.plot(xs[grp], ys[grp], "o", ms=6, mfc="white", mec=color, mew=1.5, zorder=6)
        box = "circle,pad=0.15" if len(grp) == 1 else "round,pad=0.2"
        ax.annotate(text, (xs[grp[0]], ys[grp[0]]), xytext=best, textcoords="offset points",
                    ha="center", va="center", fontsize=fontsize, fontweight="bold",
                    color=color, zorder=7,
                    bbox=dict(boxstyle=box, fc="white", ec=color, lw=0.8),
                    arrowprops=dict(arrowstyle="-", color=color, lw=0.8, shrinkA=0,
                                    shrinkB=3))

def _point_indices(ds) -> list[int]:
    """Indices into ehl_crank of the six representative points."""
    if "point_crank" not in ds:
        return []
    e = _arr(ds, "ehl_crank")
    return [int(np.argmin(np.abs(e - c))) for c in _arr(ds, "point_crank")]


def _signed(v, digits) -> str:
    """'+1.23' / '−1.23' with a typographic minus and no '−0.00'."""
    v = round(float(v), digits) + 0.0
    return f"{v:+.{digits}f}".replace("-", "−")


def _log_ticks(ax, axis="y"):
    """Plain-number labels (0.1, 0.2, 0.5, 1, …) on a logarithmic axis."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter
    a = ax.yaxis if axis == "y" else ax.xaxis
    a.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    a.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    a.set_minor_formatter(NullFormatter())


def _cycle_seconds_per_deg(ds) -> float:
    """Seconds per crank degree: one engine cycle is 720° crank = 120/rpm seconds."""
    rpm = float(ds.attrs.get("engine_speed_rpm", 3000.0))
    return 120.0 / rpm / 720.0


def _finish(fig, path, title, subtitle=None) -> Path:
    fig.suptitle(title if subtitle is None else f"{title}\n{subtitle}", fontsize=12)
    return save_figure(fig, path)


def _legend_below(fig, handles, labels, ncol=None, fontsize=9):
    ncol = ncol or min(len(labels), 5)
    fig.legend(handles, labels, loc="outside lower center", ncol=ncol, fontsize=fontsize,
               frameon=False)


# ----------------------------------------------------------------------------- Fig. 5

def _fig05(ds, path):
    from .physics.hertz import hertz_line_contact
    from .physics.materials import STEEL
    from .workflow.coating_study import PAPER_FIG5

    cond = (json.loads(ds.attrs["dry_coating_conditions"])
            if "dry_coating_conditions" in ds.attrs else PAPER_FIG5)
    ratios = _arr(ds, "dry_ratio")
    x = _arr(ds, "dry_x") * _UM
    p = _arr(ds, "dry_pressure") * _MPA
    b = _arr(ds, "dry_half_width") * _UM if "dry_half_width" in ds else np.full(ratios.size, np.nan)
    pm = (_arr(ds, "dry_max_pressure") * _MPA if "dry_max_pressure" in ds
          else np.nanmax(p, axis=1))
    fig, (ax, az) = plt.subplots(1, 2, figsize=(12, 5), layout="constrained",
                                 gridspec_kw=dict(width_ratios=(1.3, 1)))
    cmap = plt.get_cmap("viridis")
    for i, r in enumerate(ratios):
        col = cmap(i / max(ratios.size - 1, 1))
        lab = f"E_c/E_s = {r:g}: b = {b[i]:.1f} µm, p_max = {pm[i]:.0f} MPa"
        for a in (ax, az):
            a.plot(x, p[i], color=col, lw=1.6, label=lab)
    w = cond["load_total"] / cond["width"]
    e_prime = STEEL.E / (1.0 - STEEL.nu**2)
    h = hertz_line_contact(w, cond["radius"], e_prime)
    xs = np.linspace(x[0], x[-1], 801)
    for a in (ax, az):
        a.plot(xs, h.pressure(xs / _UM) * _MPA, "k:", lw=1.2,
               label=f"Hertz, uncoated steel: b = {h.half_width * _UM:.1f} µm, "
                     f"p_h = {h.max_pressure * _MPA:.0f} MPa")
        a.set_xlabel("x [µm]")
        a.set_ylabel("contact pressure p [MPa]")
        a.grid(alpha=0.3)
    ax.set_xlim(x[0], x[-1])
    ax.set_ylim(0, 1.08 * np.nanmax(p))
    ax.set_title("(a) complete distribution", fontsize=_TITLE_SIZE)
    top = np.nanmax(pm)
    bmax = np.nanmax(b) if np.isfinite(b).any() else 0.5 * (x[-1] - x[0]) / 1.3
    az.set_xlim(-0.45 * bmax, 0.45 * bmax)
    az.set_ylim(0.85 * np.nanmin(pm), 1.01 * top)
    az.set_title("(b) zoom on the pressure peak", fontsize=_TITLE_SIZE)
    handles, labels = ax.get_legend_handles_labels()
    _legend_below(fig, handles, labels, ncol=2)
    return _finish(fig, path, FIGURES[path.name],
                   f"steel cam on coated steel tappet: coating {cond['thickness'] * _UM:g} µm, "
                   f"{cond['load_total']:g} N over {cond['width'] * _MM:g} mm, "
                   f"R = {cond['radius'] * _MM:g} mm assumed (not given in the paper)")


# ----------------------------------------------------------------------------- Fig. 6

def _support(x, p, frac=1e-3, pad=0.35):
    """x-window around where p exceeds ``frac`` of its max, padded by ``pad`` × width and
    kept inside the range where p is finite (profiles are NaN outside the solver domain)."""
    p2 = np.atleast_2d(p)
    fin = np.flatnonzero(np.isfinite(p2).any(axis=0))
    if fin.size == 0:
        return float(x[0]), float(x[-1])
    xa, xb = float(x[fin[0]]), float(x[fin[-1]])
    pm = np.nanmax(np.where(np.isfinite(p2), p2, -np.inf), axis=0)
    on = np.flatnonzero(pm > frac * np.max(pm)) if np.max(pm) > 0 else np.array([], int)
    if on.size == 0:
        return xa, xb
    lo, hi = x[on[0]], x[on[-1]]
    d = pad * (hi - lo)
    return max(xa, lo - d), min(xb, hi + d)

def _fig06(ds, path):
    cond = json.loads(ds.attrs.get("ehl_coating_conditions", "{}") or "{}")
    x = _arr(ds, "ehl_x") * _UM
    groups = []
    if _has(ds, "ehl_ratio_pressure", "ehl_ratio_film"):
        ratios = _arr(ds, "ehl_ratio")
        ref = int(np.argmin(np.abs(ratios - 1.0)))
        cmap = plt.get_cmap("viridis")
        styles = [dict(color=cmap(i / max(ratios.size - 1, 1)), ls="-", lw=1.5,
                       label=f"E_c/E_s = {r:g}") for i, r in enumerate(ratios)]
        th = cond.get("thickness")
        what = "coating/steel modulus ratios" + (f", coating {th * _UM:g} µm" if th else "")
        groups.append(("ehl_ratio", styles, ref, what, f"E_c/E_s = {ratios[ref]:g}"))
    if _has(ds, "ehl_pair_pressure", "ehl_pair_film"):
        pairs = [str(v) for v in ds["ehl_pair"].values]
        cols = ["k", "tab:blue", "tab:red", "tab:green", "tab:purple"]
        styles = [dict(color=cols[i % len(cols)], ls=("-", "--", "-.", ":")[i % 4], lw=1.5,
                       label=lab) for i, lab in enumerate(pairs)]
        groups.append(("ehl_pair", styles, 0, "the paper's pairs", pairs[0]))
    if not groups:
        return None
    fig, axes = plt.subplots(3, len(groups), figsize=(6.2 * len(groups), 10.5), squeeze=False,
                             layout="constrained", sharex="col",
                             gridspec_kw=dict(height_ratios=(1.2, 1.2, 1)))
    for col, (dim, styles, ref, what, ref_name) in enumerate(groups):
        p = _arr(ds, f"{dim}_pressure") * _MPA
        h = _arr(ds, f"{dim}_film") * _UM
        hc = (_arr(ds, f"{dim}_central_film") * _UM if f"{dim}_central_film" in ds
              else h[:, np.argmin(np.abs(x))])
        hm = (_arr(ds, f"{dim}_min_film") * _UM if f"{dim}_min_film" in ds
              else np.nanmin(h, axis=1))
        conv = (np.asarray(ds[f"{dim}_converged"].values).astype(bool)
                if f"{dim}_converged" in ds else np.ones(len(styles), bool))
        lo, hi = _support(x, p, pad=0.3)
        win = (x >= lo) & (x <= hi)
        ap, ah, ad = axes[:, col]
        for i, st in enumerate(styles):
            flag = "" if conv[i] else " (NOT converged)"
            ap.plot(x, p[i], **{**st, "label": f"{st['label']}: "
                                                f"p_max = {np.nanmax(p[i]):.0f} MPa{flag}"})
            ah.plot(x, h[i], **{**st, "label": f"{st['label']}: h_c = {hc[i]:.4f} µm, "
                                                f"h_min = {hm[i]:.4f} µm"})
            ad.plot(x, (h[i] - h[ref]) * 1e3, **st)
        ap.set_ylabel("pressure p [MPa]")
        ap.set_title(f"({'ab'[col]}) {what}", fontsize=_TITLE_SIZE)
        ap.set_ylim(0, 1.08 * np.nanmax(p[:, win]))
        ah.set_ylabel("film h [µm]")
        hwin = h[:, win]
        ah.set_ylim(0, min(np.nanmax(hwin), 2.5 * np.nanmax(hc)) * 1.05)
        ad.set_ylabel(f"h − h({ref_name}) [nm]")
        ad.axhline(0, color="0.5", lw=0.8)
        dwin = (h[:, win] - h[ref, win]) * 1e3
        lim = np.nanmax(np.abs(dwin)) * 1.15 or 1.0
        ad.set_ylim(-lim, lim)
        ad.set_title("film difference in the contact (zoom: the differences are nm)",
                     fontsize=9)
        ad.set_xlabel("x [µm]  (entraining direction →)")
        for a in (ap, ah, ad):
            a.set_xlim(lo, hi)
            a.grid(alpha=0.3)
        ap.legend(fontsize=8, loc="upper left")
        ah.legend(fontsize=8, loc="lower left")
    sub = ""
    if cond:
        sub = (f"{cond.get('load_total', float('nan')):g} N over "
               f"{cond.get('width', float('nan')) * _MM:g} mm, "
               f"u_e = {cond.get('entrainment_speed', float('nan')):g} m/s, pure rolling, "
               f"R = {cond.get('radius', float('nan')) * _MM:g} mm assumed "
               "(not given in the paper)")
        if cond.get("pair_thickness"):
            sub += f"; pairs: coating {cond['pair_thickness'] * _UM:g} µm"
    return _finish(fig, path, FIGURES[path.name], sub or None)


# ----------------------------------------------------------------------------- Figs. 8–10

def _zoom_windows(ds) -> list[tuple[float, float]]:
    """Engagement and disengagement windows [deg], widened to hold the largest
    explicit/implicit force difference on each side of the nose."""
    t_on, t_off = _dynamics_event(ds)
    wins = [[t_on - 12.0, t_on + 38.0], [t_off - 32.0, t_off + 18.0]]
    if "contact_force_implicit" in ds:
        ca = _arr(ds, "crank_angle")
        d = np.abs(_arr(ds, "contact_force_implicit") - _arr(ds, "contact_force"))
        mid = 0.5 * (t_on + t_off)
        for k, side in enumerate((ca < mid, ca >= mid)):
            near = side & (np.abs(ca - (t_on, t_off)[k]) < 60.0)
            if near.any() and np.nanmax(d[near]) > 0:
                c = ca[near][np.nanargmax(d[near])]
                wins[k][0] = min(wins[k][0], c - 10.0)
                wins[k][1] = max(wins[k][1], c + 10.0)
    return [tuple(w) for w in wins]


_EXPLICIT_STYLE = dict(color="tab:blue", lw=1.5, label="explicit (analytic film in the dynamics)")
_IMPLICIT_STYLE = dict(color="tab:orange", lw=1.3, ls="--",
                       label="implicit (numerical EHL in the dynamics)")


def _explicit_implicit(ds, path, var, scale, ylabel, diff_unit, *, points=False):
    ca = _arr(ds, "crank_angle")
    y = _arr(ds, var) * scale
    imp = f"{var}_implicit"
    has_imp = imp in ds
    yi = _arr(ds, imp) * scale if has_imp else None
    fig = plt.figure(figsize=(12, 9.5), layout="constrained")
    gs = fig.add_gridspec(3, 2, height_ratios=(2.2, 1.0, 1.9))
    ax = fig.add_subplot(gs[0, :])
    ad = fig.add_subplot(gs[1, :], sharex=ax)
    zooms = [fig.add_subplot(gs[2, 0]), fig.add_subplot(gs[2, 1])]
    wins = _zoom_windows(ds)
    full = (float(ca[0]), float(ca[-1]))
    for a in [ax] + zooms:
        a.plot(ca, y, **_EXPLICIT_STYLE)
        if has_imp:
            a.plot(ca, yi, **_IMPLICIT_STYLE)
        a.axhline(0, color="0.5", lw=0.6)
        a.set_ylabel(ylabel)
    _crank_axis(ax, full)
    ax.set_xlabel("")
    ax.tick_params(labelbottom=False)
    ax.set_title("(a) presented engine cycle", fontsize=_TITLE_SIZE)
    for k, (w, a) in enumerate(zip(wins, zooms)):
        ax.axvspan(*w, color="0.85", zorder=0)
        ax.text(0.5 * (w[0] + w[1]), 1.0, "cd"[k], transform=ax.get_xaxis_transform(),
                ha="center", va="bottom", fontsize=9)
        _crank_axis(a, w)
        sel = _in_window(ca, w)
        vals = y[sel] if yi is None else np.concatenate([y[sel], yi[sel]])
        lo, hi = np.nanmin(vals), np.nanmax(vals)
        pad = 0.08 * (hi - lo) or 1.0
        a.set_ylim(lo - pad, hi + pad)
        a.set_title(f"({'cd'[k]}) zoom: {('engagement', 'disengagement')[k]}",
                    fontsize=_TITLE_SIZE)
    if has_imp:
        d = yi - y
        ad.plot(ca, d, color="tab:purple", lw=1.0)
        i = int(np.nanargmax(np.abs(d)))
        big = abs(d[i])
        txt = f"{big:.0f}" if big >= 100 else f"{big:.3g}"
        ad.annotate(f"max |Δ| = {txt} {diff_unit} at {ca[i]:.1f}°", (ca[i], d[i]),
                    xytext=(12, 0), textcoords="offset points", fontsize=9, va="center",
                    ha="left" if ca[i] < 0.8 * full[1] + 0.2 * full[0] else "right")
        ad.axhline(0, color="0.5", lw=0.6)
    else:
        ad.text(0.5, 0.5, "implicit run not in the results: explicit only",
                transform=ad.transAxes, ha="center", va="center", fontsize=11, color="tab:red")
        ad.set_yticks([])
    ad.set_ylabel(f"implicit − explicit\n[{diff_unit}]")
    _crank_axis(ad, full)
    ad.set_title("(b) difference", fontsize=_TITLE_SIZE)
    if points and "point_crank" in ds:
        pc = _arr(ds, "point_crank")
        py = np.interp(pc, ca, y)
        ev = _in_window(ca, (pc.min() - 40, pc.max() + 40))
        _place_labels(ax, pc, py, [str(int(n)) for n in _arr(ds, "point")],
                      avoid=(ca[ev][::4], y[ev][::4]), radius_pt=16)
        ax.plot([], [], "o", ms=6, mfc="white", mec="k", mew=1.5,
                label="representative points 1–6 (Fig. 13)")
    ax.legend(fontsize=9, loc="upper left")
    sub = None if has_imp else "implicit run not in the results: explicit only"
    return _finish(fig, path, FIGURES[path.name], sub)


def _fig08(ds, path):
    return _explicit_implicit(ds, path, "tappet_velocity", 1.0, "tappet velocity [m/s]", "m/s")


def _fig09(ds, path):
    return _explicit_implicit(ds, path, "contact_force", 1.0, "contact force W [N]", "N",
                              points=True)


def _fig10(ds, path):
    return _explicit_implicit(ds, path, "tappet_acceleration", 1.0,
                              "tappet acceleration [m/s²]", "m/s²")


# ----------------------------------------------------------------------------- Fig. 11

def _zero_crossings(x, y):
    s = np.sign(y)
    i = np.flatnonzero((s[:-1] * s[1:]) < 0)
    return x[i] - y[i] * (x[i + 1] - x[i]) / (y[i + 1] - y[i])


def _fig11(ds, path):
    ca = _arr(ds, "crank_angle")
    t_on, t_off = _dynamics_event(ds)
    win = (max(ca[0], t_on - 40.0), min(ca[-1], t_off + 40.0))
    sel = _in_window(ca, win)
    fig, axes = plt.subplots(3, 1, figsize=(11, 9.5), sharex=True, layout="constrained",
                             gridspec_kw=dict(height_ratios=(1.6, 1, 1)))
    ue = _arr(ds, "entrainment_speed")
    a = axes[0]
    a.plot(ca[sel], ue[sel], color="tab:blue", lw=1.6, label="u_e = ω(r_b + s + 2s'')/2")
    a.fill_between(ca[sel], ue[sel], 0, where=ue[sel] < 0, color="tab:red", alpha=0.2,
                   label="u_e < 0 (entrainment reversed)")
    a.axhline(0, color="k", lw=0.9)
    zc = _zero_crossings(ca[sel], ue[sel])
    for k, z in enumerate(zc):
        a.axvline(z, color="tab:red", lw=0.8, ls=":")
        left = k % 2 == 0
        a.annotate(f"u_e = 0 at {z:.1f}°", (z, 0), xytext=(-8 if left else 8, -16),
                   textcoords="offset points", ha="right" if left else "left", va="center",
                   fontsize=8, color="tab:red",
                   arrowprops=dict(arrowstyle="-", color="tab:red", lw=0.6))
    a.set_ylabel("entraining speed u_e [m/s]")
    if "point_crank" in ds:
        pc = _arr(ds, "point_crank")
        _place_labels(a, pc, np.interp(pc, ca, ue), [str(int(n)) for n in _arr(ds, "point")],
                      avoid=(ca[sel][::4], ue[sel][::4]), radius_pt=15, fontsize=8)
        a.plot([], [], "o", ms=6, mfc="white", mec="k", mew=1.5,
               label="representative points 1–6")
    a.legend(fontsize=9, loc="center")
    a.set_title("(a) entraining (mean rolling) speed", fontsize=_TITLE_SIZE)
    a.grid(alpha=0.3)
    us = _arr(ds, "sliding_speed")
    axes[1].plot(ca[sel], us[sel], color="tab:green", lw=1.5)
    axes[1].set_ylabel("sliding speed u_s [m/s]")
    axes[1].set_title("(b) sliding speed u_s = ω(r_b + s)", fontsize=_TITLE_SIZE)
    axes[1].grid(alpha=0.3)
    R = _arr(ds, "radius_of_curvature") * _MM
    axes[2].plot(ca[sel], R[sel], color="tab:purple", lw=1.5)
    axes[2].set_yscale("log")
    _log_ticks(axes[2])
    axes[2].set_ylabel("radius of curvature R [mm]")
    axes[2].set_title("(c) cam radius of curvature R = r_b + s + s''", fontsize=_TITLE_SIZE)
    i = np.flatnonzero(sel)[np.argmin(R[sel])]
    axes[2].annotate(f"R_min = {R[i]:.2f} mm", (ca[i], R[i]), xytext=(0, 14),
                     textcoords="offset points", ha="center", fontsize=8)
    _crank_axis(axes[2], win)
    axes[2].grid(alpha=0.3, which="both")
    return _finish(fig, path, FIGURES[path.name],
                   f"cam event {t_on:.0f}–{t_off:.0f}° crank (±40° of base circle shown); "
                   f"{ds.attrs.get('engine_speed_rpm', float('nan')):g} rpm")


# ----------------------------------------------------------------------------- Fig. 12

_REGIME_NAMES = {"IR": "IR\nisoviscous–rigid\n(hydrodynamic)",
                 "PR": "PR\npiezoviscous–rigid",
                 "IE": "IE\nisoviscous–elastic\n(soft EHL)",
                 "PE": "PE\npiezoviscous–elastic\n(classical EHL)"}
_REGIME_COLOURS = {"IR": "#dbe9f6", "PR": "#e2f0d9", "IE": "#fff2cc", "PE": "#f8dcdc"}


def _fig12(ds, path):
    from matplotlib.colors import BoundaryNorm, ListedColormap
    from scipy.ndimage import distance_transform_edt, gaussian_filter

    from .physics.regimes import REGIMES, lubrication_regime

    e = _arr(ds, "ehl_crank")
    gV, gE = _arr(ds, "gV"), _arr(ds, "gE")
    loaded = _loaded(ds).any(axis=0) & np.isfinite(gV) & np.isfinite(gE) & (gV > 0) & (gE > 0)
    force = _arr(ds, "ehl_contact_force")
    event = loaded & (force >= EVENT_FRACTION * np.nanmax(force))
    light = loaded & ~event
    any_ = loaded.any()
    ge_lo = min(1e-2, np.nanmin(gE[loaded]) / 3) if any_ else 1e-2
    ge_hi = max(1e2, np.nanmax(gE[loaded]) * 3) if any_ else 1e2
    gv_lo = min(1e-2, np.nanmin(gV[loaded]) / 3) if any_ else 1e-2
    gv_hi = max(1e4, np.nanmax(gV[loaded]) * 3) if any_ else 1e4
    n = 1200
    lge = np.linspace(np.log10(ge_lo), np.log10(ge_hi), n)
    lgv = np.linspace(np.log10(gv_lo), np.log10(gv_hi), n)
    GE, GV = np.meshgrid(10**lge, 10**lgv)
    lab = lubrication_regime(GV, GE)
    code = np.full(lab.shape, -1.0)
    for k, r in enumerate(REGIMES):
        code[lab == r] = k
    fig, ax = plt.subplots(figsize=(10.5, 8), layout="constrained")
    cmap = ListedColormap([_REGIME_COLOURS.get(r, "0.9") for r in REGIMES])
    ax.pcolormesh(GE[::2, ::2], GV[::2, ::2], code[::2, ::2], cmap=cmap, shading="auto",
                  zorder=0, rasterized=True,
                  norm=BoundaryNorm(np.arange(len(REGIMES) + 1) - 0.5, cmap.N))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(ge_lo, ge_hi)
    ax.set_ylim(gv_lo, gv_hi)
    # region names: at the coarse-grid cell farthest from both the region's edge and the data
    step = max(1, n // 150)
    ci, cj = np.meshgrid(np.arange(0, n, step), np.arange(0, n, step), indexing="ij")
    if any_:
        di = (np.log10(gV[loaded]) - lgv[0]) / (lgv[1] - lgv[0])
        dj = (np.log10(gE[loaded]) - lge[0]) / (lge[1] - lge[0])
        d_data = np.min(np.hypot(ci[..., None] - di, cj[..., None] - dj), axis=-1)
    else:
        d_data = np.full(ci.shape, np.inf)
    for k, r in enumerate(REGIMES):
        ind = code == k
        if not ind.any():
            continue
        if not ind.all():
            # contour of the (slightly smoothed) indicator: the boundary of the region
            ax.contour(GE, GV, gaussian_filter(ind.astype(float), 2.0), levels=[0.5],
                       colors="k", linewidths=1.4, zorder=1)
        coarse = ind[::step, ::step]
        inner = distance_transform_edt(np.pad(coarse, 1, constant_values=False))[1:-1, 1:-1]
        score = np.where(coarse, np.minimum(np.minimum(inner * step, 0.18 * n), d_data), -1.0)
        a, b = np.unravel_index(np.argmax(score), score.shape)
        i, j = ci[a, b], cj[a, b]
        ax.text(10 ** lge[j], 10 ** lgv[i], _REGIME_NAMES.get(r, r), ha="center",
                va="center", fontsize=10, fontweight="bold", color="0.25", zorder=2,
                bbox=dict(fc="white", ec="none", alpha=0.6, pad=1.5))
    order = np.argsort(e)
    path_sel = order[event[order]]
    ax.plot(gE[path_sel], gV[path_sel], color="0.4", lw=0.6, zorder=3)
    if light.any():
        ax.plot(gE[light], gV[light], ".", color="0.45", ms=4, zorder=3,
                label=f"loaded base circle / ramps (W < {EVENT_FRACTION:.0%} of max)")
    sc = ax.scatter(gE[event], gV[event], c=e[event], cmap="plasma", s=16, zorder=4,
                    edgecolors="none", label="cam event (coloured by crank angle)")
    cb = fig.colorbar(sc, ax=ax, pad=0.01)
    cb.set_label("crank angle [deg]")
    idx = _point_indices(ds)
    if idx:
        _place_labels(ax, gE[idx], gV[idx], [str(int(v)) for v in _arr(ds, "point")],
                      avoid=(gE[event], gV[event]), radius_pt=18)
        ax.plot([], [], "o", ms=6, mfc="white", mec="k", mew=1.5,
                label="representative points 1–6 (Fig. 13)")
    ax.set_xlabel("elasticity parameter g_E = W' U^(−1/2)")
    ax.set_ylabel("viscosity parameter g_V = G W'^(3/2) U^(−1/2)")
    ax.legend(loc="lower right", fontsize=9, framealpha=0.9)
    ax.grid(alpha=0.25, which="major")
    return _finish(fig, path, FIGURES[path.name],
                   "boundaries where the Johnson (1970) asymptotes IR, PR, IE, PE meet; "
                   "g_V, g_E with the bulk E' of the first surface set")

# ----------------------------------------------------------------------------- Figs. 13–14

def _pick_set(ds, pattern="WC-C 4") -> int:
    labels = _set_labels(ds)
    for i, lab in enumerate(labels):
        if pattern.lower() in lab.lower():
            return i
    return len(labels) - 1


def _profiles_at(ds, i, sets):
    """(x [µm], p [MPa] rows, h [µm] rows) of the given sets at EHL sample i, on the first
    set's stored profile positions (each sample stores its whole solver domain)."""
    X = ds["profile_x"].values
    P = ds["pressure"].values
    H = ds["film"].values
    ref = next((j for j in sets if np.isfinite(X[j, i]).all()), sets[0])
    x = X[ref, i]
    rows_p, rows_h = [], []
    for j in sets:
        if not np.isfinite(X[j, i]).all():
            rows_p.append(np.full(x.size, np.nan))
            rows_h.append(np.full(x.size, np.nan))
            continue
        rows_p.append(np.interp(x, X[j, i], P[j, i], left=np.nan, right=np.nan))
        rows_h.append(np.interp(x, X[j, i], H[j, i], left=np.nan, right=np.nan))
    return x * _UM, np.array(rows_p) * _MPA, np.array(rows_h) * _UM


def _load_fraction(ds, p, x):
    """Share of the total contact force carried by the stored profile (∫p dx × width)."""
    width = float(ds.attrs.get("cam_width_m", np.nan))
    good = np.isfinite(p)
    return np.trapezoid(p[good], x[good]) * width if good.sum() > 1 else np.nan


def _point_title(ds, n, i):
    e = _arr(ds, "ehl_crank")
    w = _arr(ds, "ehl_contact_force")[i]
    u = _arr(ds, "ehl_entrainment_speed")[i]
    R = _arr(ds, "ehl_radius")[i] * _MM
    return f"point {n}: {e[i]:.0f}°\nW = {w:.0f} N, u_e = {u:.2f} m/s, R = {R:.1f} mm"


def _fig13(ds, path):
    from matplotlib.lines import Line2D

    idx = _point_indices(ds)
    sets = [0, _pick_set(ds)]
    labels = _set_labels(ds)
    hyd = _arr(ds, "hydrodynamic_load") if "hydrodynamic_load" in ds else None
    hc_all = _arr(ds, "central_film")
    conv = np.asarray(ds["converged"].values) if "converged" in ds else None
    fig, axes = plt.subplots(2, 3, figsize=(15, 9.4), layout="constrained")
    # uncoated: broad light line; coated: thin dark dashed line on top (they often coincide)
    pst = [dict(color="tab:blue", ls="-", lw=2.6, alpha=0.55),
           dict(color="navy", ls="--", lw=1.3)]
    hst = [dict(color="tab:red", ls="-", lw=2.6, alpha=0.55),
           dict(color="darkred", ls="--", lw=1.3)]
    for k, (a, i) in enumerate(zip(axes.flat, idx)):
        n = int(_arr(ds, "point")[k])
        ah = a.twinx()
        x, p, h = _profiles_at(ds, i, sets)
        loaded = _loaded(ds)[sets, i]
        lo, hi = _support(x, p, frac=1e-3, pad=0.25)
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
            p0 = p[0] / _MPA
            share = _load_fraction(ds, p0, x / _UM) / hyd[0, i]
            fin = np.flatnonzero(np.isfinite(p0))
            edge = fin.size and max(p0[fin[0]], p0[fin[-1]]) > 0.05 * np.nanmax(p0)
            if np.isfinite(share) and (share < 0.9 or edge):
                a.text(0.03, 0.04, "pressure not negligible at the domain edge:\n"
                                   f"∫p dx × width = {share:.0%} of the fluid load",
                       transform=a.transAxes, fontsize=8, va="bottom", color="0.2",
                       bbox=dict(fc="lightyellow", ec="0.6", alpha=0.9))
        a.text(0.98, 0.97, f"h_c = {hc_all[sets[0], i] * _UM:.3f} / "
                           f"{hc_all[sets[1], i] * _UM:.3f} µm",
               transform=a.transAxes, ha="right", va="top", fontsize=8,
               bbox=dict(fc="white", ec="none", alpha=0.8))
    handles = [Line2D([], [], **pst[0]), Line2D([], [], **pst[1]),
               Line2D([], [], **hst[0]), Line2D([], [], **hst[1])]
    names = [f"pressure, {labels[sets[0]]}", f"pressure, {labels[sets[1]]}",
             f"film, {labels[sets[0]]}", f"film, {labels[sets[1]]}"]
    _legend_below(fig, handles, names, ncol=4, fontsize=10)
    sub = (f"{labels[sets[0]]} solid, {labels[sets[1]]} dashed (as in the paper); "
           f"h_c given as {labels[sets[0]]} / {labels[sets[1]]}; "
           "x positive in the direction of positive u_e")
    return _finish(fig, path, FIGURES[path.name], sub)

def _fig14(ds, path):
    idx = _point_indices(ds)
    force = _arr(ds, "ehl_contact_force")
    if idx:
        k = int(np.argmax(force[idx]))
        i, n = idx[k], int(_arr(ds, "point")[k])
    else:
        i, n = int(np.nanargmax(force)), None
    styles = _set_styles(ds)
    x, P, H = _profiles_at(ds, i, list(range(ds.sizes["surface_set"])))
    L = _loaded(ds)[:, i]
    fig, axes = plt.subplots(2, 3, figsize=(16, 8.8), layout="constrained")
    lo, hi = _support(x, P[L], frac=1e-3, pad=0.25)
    win = (x >= lo) & (x <= hi)
    ip = int(np.nanargmax(np.where(win, P[0], -np.inf)))
    ih = int(np.nanargmin(np.where(win, H[0], np.inf)))
    span = 0.12 * (hi - lo)
    for j, st in enumerate(styles):
        if not L[j]:
            continue
        ref = j == 0
        kw = dict(st, lw=2.4 if ref else st["lw"], color="0.6" if ref else st["color"],
                  zorder=2 if ref else 3, label=st["label"] + (" (reference)" if ref else ""))
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
    titles = [["(a) complete distribution", "(b) zoom: pressure peak (dots: grid points)",
               "(c) difference to uncoated"],
              ["(a) complete distribution", "(b) zoom: film minimum (dots: grid points)",
               "(c) difference to uncoated"]]
    ylabels = [["pressure p [MPa]", "pressure p [MPa]", "p − p(uncoated) [MPa]"],
               ["film h [µm]", "film h [µm]", "h − h(uncoated) [nm]"]]
    for r in range(2):
        for c in range(3):
            a = axes[r, c]
            a.set_title(titles[r][c], fontsize=_TITLE_SIZE)
            a.set_ylabel(ylabels[r][c])
            a.set_xlabel("x [µm]")
            a.grid(alpha=0.3)
    handles, labels = axes[0, 0].get_legend_handles_labels()
    _legend_below(fig, handles, labels, ncol=len(labels))
    e = _arr(ds, "ehl_crank")[i]
    what = f"point {n}, " if n else ""
    sub = (f"heaviest-loaded representative point: {what}{e:.0f}° crank, "
           f"W = {force[i]:.0f} N, u_e = {_arr(ds, 'ehl_entrainment_speed')[i]:.2f} m/s, "
           f"R = {_arr(ds, 'ehl_radius')[i] * _MM:.2f} mm")
    return _finish(fig, path, FIGURES[path.name], sub)

# ----------------------------------------------------------------------------- Figs. 15–20

def _cycle_lines(ax, ds, values, window, styles, *, label_fmt=None, floor=None):
    """Plot (surface_set, ehl_crank) values over the event for every set."""
    e = _arr(ds, "ehl_crank")
    sel = _in_window(e, window)
    for j, st in enumerate(styles):
        y = values[j].copy()
        if floor is not None:
            y = np.where(y < floor, floor, y)
        lab = st["label"] if label_fmt is None else label_fmt(j, st["label"])
        ax.plot(e[sel], y[sel], **{**st, "label": lab})
    _mark_failures(ax, ds, values, window)
    _crank_axis(ax, window)


def _groups(values, tol):
    """Group sorted positions closer than ``tol``: list of index lists."""
    order = np.argsort(values)
    groups = []
    for k in order:
        if groups and values[k] - values[groups[-1][-1]] < tol:
            groups[-1].append(int(k))
        else:
            groups.append([int(k)])
    return groups


def _point_ticks(ax, ds):
    """Thin vertical lines at the representative points, numbered above the axes
    (points closer than ~1 % of the axis share one label, e.g. "3,4")."""
    if "point_crank" not in ds:
        return
    pc = _arr(ds, "point_crank")
    nums = _arr(ds, "point").astype(int)
    xl = ax.get_xlim()
    for g in _groups(pc, 0.012 * (xl[1] - xl[0])):
        c = float(np.mean(pc[g]))
        if not xl[0] <= c <= xl[1]:
            continue
        for k in g:
            ax.axvline(pc[k], color="0.6", lw=0.6, ls="--", zorder=0)
        ax.annotate(",".join(str(nums[k]) for k in g), (c, 1.0),
                    xycoords=("data", "axes fraction"), xytext=(0, 2),
                    textcoords="offset points", ha="center", va="bottom", fontsize=8,
                    color="0.35")
    ax.set_title(ax.get_title(), pad=14)

def _fig15(ds, path):
    win = _event_window(ds)
    styles = _set_styles(ds)
    hc = _masked(ds, "central_film")
    ref = hc[0]
    gain = (hc / ref - 1.0) * 100.0
    e = _arr(ds, "ehl_crank")
    sel = _in_window(e, win)
    fig, (a, b) = plt.subplots(2, 1, figsize=(11, 9), sharex=True, layout="constrained",
                               gridspec_kw=dict(height_ratios=(1.6, 1)))
    _cycle_lines(a, ds, hc * _UM, win, styles)
    a.set_yscale("log")
    _log_ticks(a)
    a.set_ylabel("central film h_c [µm]")
    a.grid(alpha=0.3, which="both")
    a.set_xlabel("")
    a.legend(fontsize=9, ncol=3, loc="best")
    a.set_title("(a) central film thickness", fontsize=_TITLE_SIZE)
    _point_ticks(a, ds)

    _difference_panel(b, ds, gain, sel, win, styles, "%", 2, "h_c change vs uncoated [%]",
                      "(b) film change relative to uncoated (paper claims up to +41 %)")
    return _finish(fig, path, FIGURES[path.name], f"cam event only; {_failure_note(ds)}")


def _log_floor(values, decades=4):
    v = values[np.isfinite(values) & (values > 0)]
    if v.size == 0:
        return 1e-12
    return float(np.nanmax(v)) * 10.0 ** (-decades)


def _difference_panel(ax, ds, diff, sel, win, styles, unit, digits, ylabel, title):
    """Lower panel of Figs. 15 and 18: each set's difference to the reference set (index
    0), labelled with its extremes over the event window ``sel``."""
    def fmt(j, lab):
        g = diff[j][sel]
        if j == 0 or not np.isfinite(g).any():
            return lab + " (reference)"
        return (f"{lab}: max {_signed(np.nanmax(g), digits)} {unit}, "
                f"min {_signed(np.nanmin(g), digits)} {unit}")
    _cycle_lines(ax, ds, diff, win, styles, label_fmt=fmt)
    ax.axhline(0, color="0.4", lw=0.8)
    ax.set_ylabel(ylabel)
    ax.legend(fontsize=8, ncol=2, loc="best")
    ax.set_title(title, fontsize=_TITLE_SIZE)


def _linear_and_log(ds, path, name, ylabel, sub, *, decades=4):
    win = _event_window(ds)
    styles = _set_styles(ds)
    v = _masked(ds, name)
    e = _arr(ds, "ehl_crank")
    sel = _in_window(e, win)
    fig, (a, b) = plt.subplots(2, 1, figsize=(11, 9), sharex=True, layout="constrained")

    def fmt(j, lab):
        m = np.nanmax(v[j][sel]) if np.isfinite(v[j][sel]).any() else np.nan
        return f"{lab}: max {m:.3g} N"
    _cycle_lines(a, ds, v, win, styles, label_fmt=fmt)
    a.set_ylabel(ylabel)
    a.set_ylim(bottom=0)
    a.set_xlabel("")
    a.legend(fontsize=9, ncol=2, loc="best")
    a.set_title("(a) linear scale", fontsize=_TITLE_SIZE)
    _point_ticks(a, ds)
    floor = _log_floor(v[:, sel], decades)
    _cycle_lines(b, ds, np.where(v > floor, v, np.nan), win, styles)
    b.set_yscale("log")
    b.set_ylim(floor, 2 * np.nanmax(v[:, sel]) if np.isfinite(v[:, sel]).any() else 1)
    b.set_ylabel(ylabel)
    b.grid(alpha=0.3, which="both")
    b.set_title(f"(b) logarithmic scale (values below {floor:.1e} N not drawn)",
                fontsize=_TITLE_SIZE)
    return _finish(fig, path, FIGURES[path.name], sub)


def _energy(ds, values) -> np.ndarray:
    """∫ values dt over the presented cycle, per set (NaN where unloaded counts as 0)."""
    e = _arr(ds, "ehl_crank")
    v = np.where(_loaded(ds) & np.isfinite(values), values, 0.0)
    return np.trapezoid(v, e, axis=1) * _cycle_seconds_per_deg(ds)


def _reduction_note(ds, name, what):
    """'∫x dt vs uncoated' percentages per coated set (the summary's definition)."""
    tot = _energy(ds, _arr(ds, name))
    labels = _set_labels(ds)
    if not tot[0] > 0:
        return None
    return f"{what} vs uncoated: " + ", ".join(
        f"{labels[j]} {_signed((tot[j] / tot[0] - 1) * 100, 0)} %" for j in range(1, len(labels)))


def _fig16(ds, path):
    return _linear_and_log(ds, path, "asperity_load", "asperity load W_a [N]",
                           _reduction_note(ds, "asperity_load", "∫W_a dt over the cycle"),
                           decades=5)


def _fig17(ds, path):
    sub = _reduction_note(ds, "boundary_friction", "∫F_b dt over the cycle")
    if sub:
        sub += " (paper: > 95 % lower for WC-C)"
    return _linear_and_log(ds, path, "boundary_friction", "boundary friction F_b [N]", sub)


def _fig18(ds, path):
    win = _event_window(ds)
    styles = _set_styles(ds)
    v = _masked(ds, "viscous_friction")
    d = v - v[0]
    e = _arr(ds, "ehl_crank")
    sel = _in_window(e, win)
    fig, (a, b) = plt.subplots(2, 1, figsize=(11, 9), sharex=True, layout="constrained",
                               gridspec_kw=dict(height_ratios=(1.5, 1)))
    _cycle_lines(a, ds, v, win, styles)
    a.set_ylabel("viscous friction F_v [N]")
    a.set_ylim(bottom=0)
    a.set_xlabel("")
    a.legend(fontsize=9, ncol=3, loc="best")
    a.set_title("(a) viscous (Couette) friction", fontsize=_TITLE_SIZE)
    _point_ticks(a, ds)

    _difference_panel(b, ds, d, sel, win, styles, "N", 3, "F_v − F_v(uncoated) [N]",
                      "(b) difference to uncoated (paper: WC-C up to +0.43 N)")
    return _finish(fig, path, FIGURES[path.name], f"cam event only; {_failure_note(ds)}")


def _fig19(ds, path):
    win = _event_window(ds)
    styles = _set_styles(ds)
    pw = _masked(ds, "friction_power")
    energy = _energy(ds, _arr(ds, "friction_power"))
    fig = plt.figure(figsize=(14, 6.5), layout="constrained")
    gs = fig.add_gridspec(1, 2, width_ratios=(2.2, 1))
    a = fig.add_subplot(gs[0])
    b = fig.add_subplot(gs[1])
    _cycle_lines(a, ds, pw, win, styles)
    a.set_ylabel("friction power [W]")
    a.set_ylim(bottom=0)
    a.legend(fontsize=9, loc="center")
    a.set_title("(a) friction power (viscous + boundary) × u_s", fontsize=_TITLE_SIZE)
    _point_ticks(a, ds)
    labels = [st["label"] for st in styles]
    ypos = np.arange(len(labels))
    b.barh(ypos, energy, color=[st["color"] for st in styles], alpha=0.8,
           edgecolor="k")
    for y, en in zip(ypos, energy):
        txt = f"{en:.4f} J"
        if y > 0 and energy[0] > 0:
            txt += f" ({_signed((en / energy[0] - 1) * 100, 2)} %)"
        b.text(en * 0.02, y, txt, va="center", ha="left", fontsize=9, color="white",
               fontweight="bold")
    b.set_yticks(ypos, labels)
    b.invert_yaxis()
    b.set_xlabel("friction energy per engine cycle [J]")
    b.set_title("(b) ∫ friction power dt over one engine cycle", fontsize=_TITLE_SIZE)
    b.grid(alpha=0.3, axis="x")
    rpm = ds.attrs.get("engine_speed_rpm", float("nan"))
    period = 120.0 / float(rpm)
    return _finish(fig, path, FIGURES[path.name],
                   f"one engine cycle = 720° crank = {period * 1e3:.0f} ms at {rpm:g} rpm; "
                   f"mean power uncoated {energy[0] / period:.2f} W")


def _fig20(ds, path):
    win = _event_window(ds)
    styles = _set_styles(ds)
    hm = _masked(ds, "min_film") * _UM
    lam = _masked(ds, "lambda_ratio")
    fig, (a, b) = plt.subplots(2, 1, figsize=(11, 9), sharex=True, layout="constrained")
    e = _arr(ds, "ehl_crank")
    sel = _in_window(e, win)

    def fmt_h(j, lab):
        return f"{lab}: min {np.nanmin(hm[j][sel]):.3f} µm"
    _cycle_lines(a, ds, hm, win, styles, label_fmt=fmt_h)
    a.set_yscale("log")
    _log_ticks(a)
    a.set_ylabel("minimum film h_min [µm]")
    a.grid(alpha=0.3, which="both")
    a.set_xlabel("")
    a.legend(fontsize=9, ncol=2, loc="best")
    a.set_title("(a) minimum film thickness", fontsize=_TITLE_SIZE)
    _point_ticks(a, ds)

    def fmt_l(j, lab):
        return f"{lab}: min λ = {np.nanmin(lam[j][sel]):.2f}"
    _cycle_lines(b, ds, lam, win, styles, label_fmt=fmt_l)
    b.set_yscale("log")
    lo = min(0.5, 0.8 * np.nanmin(lam[:, sel]))
    b.set_ylim(lo, 1.5 * np.nanmax(lam[:, sel]))
    _log_ticks(b)
    b.axhspan(lo, 1.0, color="tab:red", alpha=0.08, zorder=0)
    b.axhspan(1.0, 3.0, color="tab:orange", alpha=0.08, zorder=0)
    for lv, txt in ((1.0, "λ = 1 (boundary below)"), (3.0, "λ = 3 (full film above)")):
        b.axhline(lv, color="k", lw=1.0, ls="--")
        b.text(0.5 * (win[0] + win[1]), lv, txt, va="bottom", ha="center", fontsize=8)
    b.set_ylabel("λ = h_min/σ")
    b.grid(alpha=0.3, which="both")
    b.legend(fontsize=8, ncol=2, loc="best")
    b.set_title("(b) film parameter (σ: composite RMS roughness of each set)",
                fontsize=_TITLE_SIZE)
    return _finish(fig, path, FIGURES[path.name], f"cam event only; {_failure_note(ds)}")


# ----------------------------------------------------------------------------- driver

_MAKERS = {
    "fig05_dry_pressure.png": (_fig05, ("dry_ratio", "dry_x", "dry_pressure")),
    "fig06_ehl_pressure_film.png": (_fig06, ("ehl_x",)),
    "fig08_tappet_velocity.png": (_fig08, ("crank_angle", "tappet_velocity", "contact_force")),
    "fig09_contact_force.png": (_fig09, ("crank_angle", "contact_force")),
    "fig10_tappet_acceleration.png": (_fig10, ("crank_angle", "tappet_acceleration",
                                               "contact_force")),
    "fig11_entrainment_speed.png": (_fig11, ("entrainment_speed", "sliding_speed",
                                             "radius_of_curvature", "contact_force")),
    "fig12_greenwood_chart.png": (_fig12, ("gV", "gE", "loaded", "ehl_contact_force")),
    "fig13_pressure_film_points.png": (_fig13, ("pressure", "film", "profile_x",
                                                "point_crank", "loaded")),
    "fig14_coatings_pressure_film.png": (_fig14, ("pressure", "film", "profile_x", "loaded",
                                                  "ehl_contact_force")),
    "fig15_central_film.png": (_fig15, ("central_film", "loaded")),
    "fig16_boundary_load.png": (_fig16, ("asperity_load", "loaded")),
    "fig17_boundary_friction.png": (_fig17, ("boundary_friction", "loaded")),
    "fig18_viscous_friction.png": (_fig18, ("viscous_friction", "loaded")),
    "fig19_friction_power.png": (_fig19, ("friction_power", "loaded")),
    "fig20_min_film_lambda.png": (_fig20, ("min_film", "lambda_ratio", "loaded")),
}


def make_figures(ds, out_dir, *, only=None) -> dict[str, Path]:
    """Write the report figures of a cycle-study Dataset into ``out_dir``.

    Returns ``{file name: path}`` for the figures written (keys as in :data:`FIGURES`).
    Comparisons are made against the ``reference_set`` attribute (the first uncoated
    set), which is plotted first. A figure whose variables are not in the Dataset (e.g. a study without the
    single-contact coating studies) is skipped; the explicit/implicit figures plot the
    explicit run alone, and say so, when the ``*_implicit`` variables are absent.
    ``only``: optional iterable of file names to restrict the output.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    ref = ds.attrs.get("reference_set")
    if ref is not None and "surface_set" in ds.dims:
        names = [str(v) for v in ds["surface_set"].values]
        if ref in names and names[0] != ref:      # the figures compare against index 0
            k = names.index(ref)
            ds = ds.isel(surface_set=[k] + [i for i in range(len(names)) if i != k])
    wanted = list(_MAKERS) if only is None else [n for n in _MAKERS if n in set(only)]
    written = {}
    with plt.rc_context({"font.size": 10, "axes.titlesize": _TITLE_SIZE,
                         "figure.dpi": 100, "savefig.dpi": 150}):
        for name in wanted:
            maker, needs = _MAKERS[name]
            if not _has(ds, *needs):
                continue
            path = maker(ds, out / name)
            if path is not None:
                written[name] = path
    return written
