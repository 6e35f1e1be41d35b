"""Shared helpers of the report figures: matplotlib set-up (Agg), atomic saving, the
figure index, styles per surface set, event windows, failure markers, label placement.

Conventions of every figure: engineering units (µm, MPa, N, m/s, W, J), crank-angle time
axes; EHL quantities only where the contact is loaded (``loaded``), on the cam event
(samples where the contact force exceeds :data:`EVENT_FRACTION` of its maximum, plus a
margin); EHL steps that did not converge are marked with red crosses.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from PIL import Image
from PIL.PngImagePlugin import PngInfo

from ..._safe_write import atomic_open, make_dirs
from ...workflow.conventions import EVENT_FRACTION
from ..figure_names import FIGURES

__all__ = ["plt", "save_figure", "FIGURES", "EVENT_FRACTION"]


EVENT_MARGIN_DEG = 5.0
UM, MPA, MM = 1e6, 1e-6, 1e3
FAMILY_COLOURS = ("tab:blue", "tab:red", "tab:green", "tab:purple", "tab:brown", "tab:olive")
TITLE_SIZE = 11


_DPI = 150


def save_figure(fig, path) -> Path:
    """Save atomically (:func:`~tribodyn._safe_write.atomic_open`) and close the figure."""
    path = Path(path)
    make_dirs(path.parent)
    # one draw (layout included) at the saved resolution, written by PIL: savefig would
    # draw a laid-out figure twice (a layout pass with rendering off, then the real one)
    fig.set_dpi(_DPI)
    fig.canvas.draw()
    rgba = np.asarray(fig.canvas.buffer_rgba())
    info = PngInfo()
    info.add_text(
        "Software", f"Matplotlib version{matplotlib.__version__}, https://matplotlib.org/"
    )
    # fast zlib level: 40 % less encoding time for 14 % larger files
    with atomic_open(path, "wb") as f:
        Image.fromarray(rgba).save(
            f, format="png", dpi=(_DPI, _DPI), pnginfo=info, compress_level=1
        )
    plt.close(fig)
    return path


# ----------------------------------------------------------------------------- helpers


def has(ds, *names) -> bool:
    return all(n in ds.variables for n in names)


def point_legend_entry(ax, ds) -> None:
    """The legend entry of the numbered representative-point markers (no data drawn)."""
    ax.plot(
        [],
        [],
        "o",
        ms=6,
        mfc="white",
        mec="k",
        mew=1.5,
        label="representative points 1–6" + (" (Fig. 13)" if compares_paper(ds) else ""),
    )


def compares_paper(ds) -> bool:
    """Whether the figures carry the paper's comparison (the Dataset's ``compare_paper``
    attribute; absent: yes)."""
    return bool(ds.attrs.get("compare_paper", 1))


def arr(ds, name) -> np.ndarray:
    return np.asarray(ds[name].values, dtype=float)


def set_labels(ds) -> list[str]:
    """Display names of the surface sets: ``surface_label``, else from the case the
    Dataset carries (a sweep's ``base_case_toml``), else the names made readable
    (``dlc_4um`` → ``DLC 4 µm``)."""
    if "surface_label" in ds:
        return [str(v) for v in ds["surface_label"].values]
    from ..explorer_data import set_display_names

    names = [str(v) for v in ds["surface_set"].values]
    text = ds.attrs.get("base_case_toml") or ds.attrs.get("case_toml")
    labels = set_display_names(str(text) if text else None, names)
    return [labels[n] for n in names]


def set_styles(ds) -> list[dict]:
    """Line style per surface set: uncoated black; one colour per coating material
    (``coating_material``), the thinnest of several thicknesses dashed, the rest solid."""
    labels = set_labels(ds)
    n = len(labels)
    mats = (
        [str(v) for v in ds["coating_material"].values]
        if "coating_material" in ds
        else [""] + ["coating"] * (n - 1)
    )
    thick = (
        np.asarray(ds["coating_thickness"].values, float)
        if "coating_thickness" in ds
        else np.zeros(n)
    )
    families = list(dict.fromkeys(m for m in mats if m))
    styles = []
    for i, (mat, lab) in enumerate(zip(mats, labels)):
        if not mat:
            styles.append(dict(color="k", ls="-", lw=1.8, label=lab))
            continue
        col = FAMILY_COLOURS[families.index(mat) % len(FAMILY_COLOURS)]
        sizes = sorted({t for m, t in zip(mats, thick) if m == mat})
        dashed = len(sizes) > 1 and thick[i] == sizes[0]
        styles.append(dict(color=col, ls="--" if dashed else "-", lw=1.4, label=lab))
    return styles


def loaded_mask(ds) -> np.ndarray:
    """Boolean (surface_set, ehl_crank) mask of loaded EHL samples."""
    return np.asarray(ds["loaded"].values).astype(bool)


def masked(ds, name) -> np.ndarray:
    """EHL cycle variable (surface_set, ehl_crank) with NaN where unloaded."""
    return np.where(loaded_mask(ds), arr(ds, name), np.nan)


def event_window(ds) -> tuple[float, float]:
    """Crank window [deg] of the cam event in the EHL samples (loaded and the contact
    force above EVENT_FRACTION of its maximum), with a small margin."""
    e = arr(ds, "ehl_crank")
    force = arr(ds, "ehl_contact_force") if "ehl_contact_force" in ds else None
    sel = loaded_mask(ds).any(axis=0)
    if force is not None and np.isfinite(force).any() and np.nanmax(force) > 0:
        sel &= force >= EVENT_FRACTION * np.nanmax(force)
    if not sel.any():
        return float(e[0]), float(e[-1])
    return (
        max(float(e[sel][0]) - EVENT_MARGIN_DEG, float(e[0])),
        min(float(e[sel][-1]) + EVENT_MARGIN_DEG, float(e[-1])),
    )


def in_window(x, window) -> np.ndarray:
    return (x >= window[0]) & (x <= window[1])


def event_samples(ds):
    """(the cam event's crank window :func:`event_window`, the sets' styles
    :func:`set_styles`, the EHL crank angles, which of them lie in the window)."""
    win = event_window(ds)
    e = arr(ds, "ehl_crank")
    return win, set_styles(ds), e, in_window(e, win)


def set_lines(ax, e, values, sel, styles, label_fmt=None, **kw):
    """Each set's row of ``values`` (surface_set, ehl_crank) over the samples ``sel`` of
    the crank angles ``e``, in its style (``kw`` overrides it; ``label_fmt(j, label)``
    gives the legend label of set ``j``)."""
    for j, st in enumerate(styles):
        lab = st["label"] if label_fmt is None else label_fmt(j, st["label"])
        ax.plot(e[sel], values[j][sel], **{**st, "label": lab, **kw})


def dynamics_event(ds) -> tuple[float, float]:
    """Engagement and disengagement crank angles [deg] of the dynamics output."""
    ca = arr(ds, "crank_angle")
    f = arr(ds, "contact_force")
    on = (
        np.flatnonzero(f >= EVENT_FRACTION * np.nanmax(f))
        if np.nanmax(f) > 0
        else np.zeros(0, dtype=int)
    )
    if len(on) == 0:
        return float(ca[0]), float(ca[-1])
    return float(ca[on[0]]), float(ca[on[-1]])


def crank_axis(ax, window=None):
    ax.set_xlabel("crank angle [deg]")
    if window is not None:
        ax.set_xlim(*window)
    ax.grid(alpha=0.3)


def mark_failures(ax, ds, values, window) -> int:
    """Red crosses at loaded, non-converged EHL steps; returns how many were drawn."""
    if "converged" not in ds:
        return 0
    e = arr(ds, "ehl_crank")
    bad = (np.asarray(ds["converged"].values) == 0) & loaded_mask(ds)
    bad &= in_window(e, window)[None, :]
    idx = np.nonzero(bad & np.isfinite(values))
    if idx[0].size == 0:
        return 0
    ax.plot(
        e[idx[1]],
        values[idx],
        "x",
        color="red",
        ms=7,
        mew=1.8,
        ls="none",
        label="EHL step not converged",
        zorder=5,
    )
    return int(idx[0].size)


def failure_note(ds) -> str:
    if "converged" not in ds:
        return ""
    n = int(((np.asarray(ds["converged"].values) == 0) & loaded_mask(ds)).sum())
    return f"{n} non-converged EHL step(s) marked ×" if n else "all EHL steps converged"


def place_labels(ax, xs, ys, texts, *, avoid=None, radius_pt=20.0, fontsize=9):
    """Annotate points with short labels, choosing for each label the offset direction
    farthest from the other points, the labels already placed and ``avoid`` (x, y).
    Points closer than a marker size share one label ("3,4")."""
    xs = np.asarray(xs, dtype=float)
    ys = np.asarray(ys, dtype=float)
    scale = 72.0 / ax.figure.dpi
    tr = ax.transData
    pts = tr.transform(np.column_stack([xs, ys])) * scale
    # merge (nearly) coincident points
    merged: list[list[int]] = []
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
    placed: list[tuple[float, float]] = []
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
        ax.plot(xs[grp], ys[grp], "o", ms=6, mfc="white", mec="k", mew=1.5, zorder=6)
        box = "circle,pad=0.15" if len(grp) == 1 else "round,pad=0.2"
        ax.annotate(
            text,
            (xs[grp[0]], ys[grp[0]]),
            xytext=best,
            textcoords="offset points",
            ha="center",
            va="center",
            fontsize=fontsize,
            fontweight="bold",
            color="k",
            zorder=7,
            bbox=dict(boxstyle=box, fc="white", ec="k", lw=0.8),
            arrowprops=dict(arrowstyle="-", color="k", lw=0.8, shrinkA=0, shrinkB=3),
        )


def point_indices(ds) -> list[int]:
    """Indices into ehl_crank of the six representative points."""
    if "point_crank" not in ds:
        return []
    e = arr(ds, "ehl_crank")
    return [int(np.argmin(np.abs(e - c))) for c in arr(ds, "point_crank")]


def signed(v, digits) -> str:
    """'+1.23' / '−1.23' with a typographic minus and no '−0.00'."""
    v = round(float(v), digits) + 0.0
    return f"{v:+.{digits}f}".replace("-", "−")


def log_ticks(ax):
    """Plain-number labels (0.1, 0.2, 0.5, 1, …) on a logarithmic y axis."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    a = ax.yaxis
    a.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    a.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    a.set_minor_formatter(NullFormatter())


def cycle_seconds_per_deg(ds) -> float:
    """Seconds per crank degree: one engine cycle is 720° crank = 120/rpm seconds."""
    rpm = float(ds.attrs.get("engine_speed_rpm", 3000.0))
    return 120.0 / rpm / 720.0


def fitted_suptitle(fig, text: str, fontsize=12):
    """``fig.suptitle(text)`` with each line too wide for the figure wrapped at word
    boundaries, so that no title runs off the canvas."""
    import textwrap

    width = fig.get_figwidth() * 72.0 * 0.96  # points, a margin either side
    # a conservative estimate of the text's width: 0.6 em per character
    chars = max(20, int(width / (0.6 * fontsize)))
    out = [textwrap.fill(ln, chars) if len(ln) > chars else ln for ln in text.split("\n")]
    return fig.suptitle("\n".join(out), fontsize=fontsize)


def fitted_legend(fig, handles, labels, fontsize=8, **kw):
    """A figure legend below the axes (``outside lower center``) in as many columns (at
    most 5) as fit the figure's width."""
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    leg = None
    for ncol in range(min(len(labels), 5), 0, -1):
        leg = fig.legend(
            handles, labels, loc="outside lower center", ncol=ncol, fontsize=fontsize, **kw
        )
        if ncol == 1 or leg.get_window_extent(r).width <= 0.98 * fig.bbox.width:
            break
        leg.remove()
    return leg


def finish(fig, path, title, subtitle=None) -> Path:
    fitted_suptitle(fig, title if subtitle is None else f"{title}\n{subtitle}", fontsize=12)
    return save_figure(fig, path)


def finish_numbered(fig, path, subtitle=None) -> Path:
    """:func:`finish` under the figure's title in :data:`FIGURES` (by file name)."""
    return finish(fig, path, FIGURES[path.name], subtitle)


def legend_below(fig, handles, labels, ncol=None, fontsize=9):
    ncol = ncol or min(len(labels), 5)
    fig.legend(
        handles, labels, loc="outside lower center", ncol=ncol, fontsize=fontsize, frameon=False
    )


def support(x, p, frac=1e-3, pad=0.35):
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
