"""Figs. 15–20: films, loads, friction, power and λ over the cycle."""

from __future__ import annotations

import numpy as np

from .common import (
    TITLE_SIZE,
    UM,
    arr,
    compares_paper,
    crank_axis,
    cycle_seconds_per_deg,
    event_samples,
    failure_note,
    finish_numbered,
    in_window,
    loaded_mask,
    log_ticks,
    mark_failures,
    masked,
    plt,
    set_labels,
    set_lines,
    signed,
)

# ----------------------------------------------------------------------------- Figs. 15–20


def _cycle_lines(ax, ds, values, window, styles, *, label_fmt=None):
    """Plot (surface_set, ehl_crank) values over the event for every set."""
    e = arr(ds, "ehl_crank")
    set_lines(ax, e, values, in_window(e, window), styles, label_fmt)
    mark_failures(ax, ds, values, window)
    crank_axis(ax, window)


def _groups(values, tol):
    """Group sorted positions closer than ``tol``: list of index arrays."""
    order = np.argsort(values)  # a NaN sorts last and stands alone
    cuts = np.flatnonzero(~(np.diff(values[order]) < tol)) + 1
    return np.split(order, cuts) if order.size else []


def _point_ticks(ax, ds):
    """Thin vertical lines at the representative points, numbered above the axes
    (points closer than ~1 % of the axis share one label, e.g. "3,4")."""
    if "point_crank" not in ds:
        return
    pc = arr(ds, "point_crank")
    nums = arr(ds, "point").astype(int)
    xl = ax.get_xlim()
    for g in _groups(pc, 0.012 * (xl[1] - xl[0])):
        c = float(np.mean(pc[g]))
        if not xl[0] <= c <= xl[1]:
            continue
        for k in g:
            ax.axvline(pc[k], color="0.6", lw=0.6, ls="--", zorder=0)
        ax.annotate(
            ",".join(str(nums[k]) for k in g),
            (c, 1.0),
            xycoords=("data", "axes fraction"),
            xytext=(0, 2),
            textcoords="offset points",
            ha="center",
            va="bottom",
            fontsize=8,
            color="0.35",
        )
    ax.set_title(ax.get_title(), pad=14)


def _cycle_figure(ds, height_ratios=None):
    """Two panels over the crank angle of the cam event (shared axis): (fig, (a, b),
    event window, set styles, EHL samples inside the window)."""
    win, styles, _, sel = event_samples(ds)
    fig, (a, b) = plt.subplots(
        2,
        1,
        figsize=(11, 9),
        sharex=True,
        layout="constrained",
        gridspec_kw=None if height_ratios is None else dict(height_ratios=height_ratios),
    )
    return fig, (a, b), win, styles, sel


def _top_panel(ax, ds, title, *, ncol):
    """Legend, title and point ticks of the upper of two panels (its x label dropped)."""
    ax.set_xlabel("")
    ax.legend(fontsize=9, ncol=ncol, loc="best")
    ax.set_title(title, fontsize=TITLE_SIZE)
    _point_ticks(ax, ds)


def fig15(ds, path):
    fig, (a, b), win, styles, sel = _cycle_figure(ds, (1.6, 1))
    hc = masked(ds, "central_film")
    ref = hc[0]
    gain = (hc / ref - 1.0) * 100.0
    _cycle_lines(a, ds, hc * UM, win, styles)
    a.set_yscale("log")
    log_ticks(a)
    a.set_ylabel("central film h_c [µm]")
    a.grid(alpha=0.3, which="both")
    _top_panel(a, ds, "(a) central film thickness", ncol=3)

    _difference_panel(
        b,
        ds,
        gain,
        sel,
        win,
        styles,
        "%",
        2,
        "h_c change vs uncoated [%]",
        "(b) film change relative to uncoated"
        + (" (paper claims up to +41 %)" if compares_paper(ds) else ""),
    )
    return finish_numbered(fig, path, f"cam event only; {failure_note(ds)}")


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
        return (
            f"{lab}: max {signed(np.nanmax(g), digits)} {unit}, "
            f"min {signed(np.nanmin(g), digits)} {unit}"
        )

    _cycle_lines(ax, ds, diff, win, styles, label_fmt=fmt)
    ax.axhline(0, color="0.4", lw=0.8)
    ax.set_ylabel(ylabel)
    ax.legend(fontsize=8, ncol=2, loc="best")
    ax.set_title(title, fontsize=TITLE_SIZE)


def _linear_and_log(ds, path, name, ylabel, sub, *, decades=4):
    fig, (a, b), win, styles, sel = _cycle_figure(ds)
    v = masked(ds, name)

    def fmt(j, lab):
        m = np.nanmax(v[j][sel]) if np.isfinite(v[j][sel]).any() else np.nan
        return f"{lab}: max {m:.3g} N"

    _cycle_lines(a, ds, v, win, styles, label_fmt=fmt)
    a.set_ylabel(ylabel)
    a.set_ylim(bottom=0)
    _top_panel(a, ds, "(a) linear scale", ncol=2)
    floor = _log_floor(v[:, sel], decades)
    _cycle_lines(b, ds, np.where(v > floor, v, np.nan), win, styles)
    b.set_yscale("log")
    b.set_ylim(floor, 2 * np.nanmax(v[:, sel]) if np.isfinite(v[:, sel]).any() else 1)
    b.set_ylabel(ylabel)
    b.grid(alpha=0.3, which="both")
    b.set_title(
        f"(b) logarithmic scale (values below {floor:.1e} N not drawn)", fontsize=TITLE_SIZE
    )
    return finish_numbered(fig, path, sub)


def _energy(ds, values) -> np.ndarray:
    """∫ values dt over the presented cycle, per set (NaN where unloaded counts as 0)."""
    e = arr(ds, "ehl_crank")
    v = np.where(loaded_mask(ds) & np.isfinite(values), values, 0.0)
    return np.trapezoid(v, e, axis=1) * cycle_seconds_per_deg(ds)


def _reduction_note(ds, name, what):
    """'∫x dt vs uncoated' percentages per coated set (the summary's definition)."""
    tot = _energy(ds, arr(ds, name))
    labels = set_labels(ds)
    if not tot[0] > 0:
        return None
    return f"{what} vs uncoated: " + ", ".join(
        f"{labels[j]} {signed((tot[j] / tot[0] - 1) * 100, 0)} %" for j in range(1, len(labels))
    )


def fig16(ds, path):
    return _linear_and_log(
        ds,
        path,
        "asperity_load",
        "asperity load W_a [N]",
        _reduction_note(ds, "asperity_load", "∫W_a dt over the cycle"),
        decades=5,
    )


def fig17(ds, path):
    sub = _reduction_note(ds, "boundary_friction", "∫F_b dt over the cycle")
    if sub and compares_paper(ds):
        sub += " (paper: > 95 % lower for WC-C)"
    return _linear_and_log(ds, path, "boundary_friction", "boundary friction F_b [N]", sub)


def fig18(ds, path):
    fig, (a, b), win, styles, sel = _cycle_figure(ds, (1.5, 1))
    v = masked(ds, "viscous_friction")
    d = v - v[0]
    _cycle_lines(a, ds, v, win, styles)
    a.set_ylabel("viscous friction F_v [N]")
    a.set_ylim(bottom=0)
    _top_panel(a, ds, "(a) viscous (Couette) friction", ncol=3)

    _difference_panel(
        b,
        ds,
        d,
        sel,
        win,
        styles,
        "N",
        3,
        "F_v − F_v(uncoated) [N]",
        "(b) difference to uncoated"
        + (" (paper: WC-C up to +0.43 N)" if compares_paper(ds) else ""),
    )
    return finish_numbered(fig, path, f"cam event only; {failure_note(ds)}")


def fig19(ds, path):
    win, styles, _, _ = event_samples(ds)
    pw = masked(ds, "friction_power")
    energy = _energy(ds, arr(ds, "friction_power"))
    fig = plt.figure(figsize=(14, 6.5), layout="constrained")
    gs = fig.add_gridspec(1, 2, width_ratios=(2.2, 1))
    a = fig.add_subplot(gs[0])
    b = fig.add_subplot(gs[1])
    _cycle_lines(a, ds, pw, win, styles)
    a.set_ylabel("friction power [W]")
    a.set_ylim(bottom=0)
    a.legend(fontsize=9, loc="center")
    a.set_title("(a) friction power (viscous + boundary) × u_s", fontsize=TITLE_SIZE)
    _point_ticks(a, ds)
    labels = [st["label"] for st in styles]
    ypos = np.arange(len(labels))
    b.barh(ypos, energy, color=[st["color"] for st in styles], alpha=0.8, edgecolor="k")
    for y, en in zip(ypos, energy):
        txt = f"{en:.4f} J"
        if y > 0 and energy[0] > 0:
            txt += f" ({signed((en / energy[0] - 1) * 100, 2)} %)"
        b.text(
            en * 0.02,
            float(y),
            txt,
            va="center",
            ha="left",
            fontsize=9,
            color="white",
            fontweight="bold",
        )
    b.set_yticks(ypos, labels)
    b.invert_yaxis()
    b.set_xlabel("friction energy per engine cycle [J]")
    b.set_title("(b) ∫ friction power dt over one engine cycle", fontsize=TITLE_SIZE)
    b.grid(alpha=0.3, axis="x")
    rpm = ds.attrs.get("engine_speed_rpm", float("nan"))
    period = 120.0 / float(rpm)
    return finish_numbered(
        fig,
        path,
        f"one engine cycle = 720° crank = {period * 1e3:.0f} ms at {rpm:g} rpm; "
        f"mean power uncoated {energy[0] / period:.2f} W",
    )


def fig20(ds, path):
    fig, (a, b), win, styles, sel = _cycle_figure(ds)
    hm = masked(ds, "min_film") * UM
    lam = masked(ds, "lambda_ratio")

    def fmt_h(j, lab):
        return f"{lab}: min {np.nanmin(hm[j][sel]):.3f} µm"

    _cycle_lines(a, ds, hm, win, styles, label_fmt=fmt_h)
    a.set_yscale("log")
    log_ticks(a)
    a.set_ylabel("minimum film h_min [µm]")
    a.grid(alpha=0.3, which="both")
    _top_panel(a, ds, "(a) minimum film thickness", ncol=2)

    def fmt_l(j, lab):
        return f"{lab}: min λ = {np.nanmin(lam[j][sel]):.2f}"

    _cycle_lines(b, ds, lam, win, styles, label_fmt=fmt_l)
    b.set_yscale("log")
    pos = lam[:, sel][lam[:, sel] > 0]  # failed steps may hold λ ≤ 0
    lo = min(0.5, 0.8 * float(pos.min())) if pos.size else 0.5
    b.set_ylim(lo, max(1.5 * float(np.nanmax(lam[:, sel])), 10.0 * lo))
    log_ticks(b)
    b.axhspan(lo, 1.0, color="tab:red", alpha=0.08, zorder=0)
    b.axhspan(1.0, 3.0, color="tab:orange", alpha=0.08, zorder=0)
    for lv, txt in ((1.0, "λ = 1 (boundary below)"), (3.0, "λ = 3 (full film above)")):
        b.axhline(lv, color="k", lw=1.0, ls="--")
        b.text(0.5 * (win[0] + win[1]), lv, txt, va="bottom", ha="center", fontsize=8)
    b.set_ylabel("λ = h_min/σ")
    b.grid(alpha=0.3, which="both")
    b.legend(fontsize=8, ncol=2, loc="best")
    b.set_title("(b) film parameter (σ: composite RMS roughness of each set)", fontsize=TITLE_SIZE)
    return finish_numbered(fig, path, f"cam event only; {failure_note(ds)}")
