"""Figures (matplotlib, Agg backend, PNG). Each function takes results and a path."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

__all__ = ["plot_dry_coating_study", "save_figure"]

_CMAP = plt.get_cmap("viridis")


def save_figure(fig, path) -> Path:
    """Save atomically (temporary file, then rename) and close the figure."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.stem + ".tmp" + path.suffix)
    fig.savefig(tmp, dpi=150, bbox_inches="tight")
    plt.close(fig)
    tmp.replace(path)
    return path


def plot_dry_coating_study(cases, path, *, radius: float, thickness: float, load_total: float,
                           width: float):
    """Paper Fig. 5: dry pressure for several coating/steel modulus ratios."""
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    ref = next((c for c in cases if c.ratio == 1.0), cases[0]).result
    n = len(cases)
    for i, c in enumerate(cases):
        r = c.result
        col = _CMAP(i / max(n - 1, 1))
        lab = f"{c.label}: b = {r.half_width * 1e6:.1f} µm, p_max = {r.max_pressure / 1e6:.0f} MPa"
        for a in (ax, ax2):
            a.plot(r.x * 1e6, r.pressure / 1e6, color=col, label=lab)
    h = ref.hertz
    xs = np.linspace(-1.3 * h.half_width, 1.3 * h.half_width, 400)
    for a in (ax, ax2):
        a.plot(xs * 1e6, h.pressure(xs) / 1e6, "k:", lw=1, label="Hertz, uncoated steel")
    ax.set_xlabel("x [µm]")
    ax.set_ylabel("pressure p [MPa]")
    ax.set_title("Dry contact pressure (paper Fig. 5)")
    handles, labels = ax.get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=8, frameon=False,
               bbox_to_anchor=(0.5, -0.15))
    ax.grid(alpha=0.3)
    pmax = max(c.result.max_pressure for c in cases) / 1e6
    ax2.set_xlim(-0.6 * h.half_width * 1e6, 0.6 * h.half_width * 1e6)
    ax2.set_ylim(0.85 * pmax, 1.01 * pmax)
    ax2.set_xlabel("x [µm]")
    ax2.set_ylabel("pressure p [MPa]")
    ax2.set_title("Zoom on the pressure peak")
    ax2.grid(alpha=0.3)
    fig.suptitle(f"Steel cam on coated steel tappet: coating {thickness * 1e6:g} µm, "
                 f"w = {load_total:g} N over {width * 1e3:g} mm, "
                 f"R = {radius * 1e3:g} mm (assumed: not given in the paper)", fontsize=9)
    return save_figure(fig, path)
