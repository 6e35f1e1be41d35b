"""Gaussian conformity figure (paper Fig. 7): height histogram against the Gaussian with the
same σ, per surface, on linear and logarithmic density axes (the tails above ~2σ carry
the asperity contacts in Greenwood–Tripp's model)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ...topography.profile import ProfileAnalysis
from ...topography.results import PairAnalysis, SurfaceAnalysis
from .common import plt, save_figure

__all__ = ["plot_height_distribution"]


def _panels(results):
    """(title, heights [m], their statistics, their Gaussian) per surface; a pair adds its
    sum surface."""
    if isinstance(results, (SurfaceAnalysis, PairAnalysis, ProfileAnalysis)):
        results = [results]
    panels = []
    for r in results:
        if isinstance(r, PairAnalysis):
            panels += _panels([r.first, r.second])
            if r.sum_surface is not None:  # None: a profile, or different pixel sizes
                title = f"sum surface {r.first.name} + {r.second.name}"
                panels.append((title, r.sum_surface, r.sum_heights, r.sum_gaussian))
        elif isinstance(r, SurfaceAnalysis):
            if r.topography is None:
                raise TypeError(f"analysis '{r.name}' carries no height map to plot")
            h = np.asarray(r.topography.heights(), dtype=float)
            h = h if r.filled is None else h[~np.asarray(r.filled)]
            panels.append((r.name, h, r.heights, r.gaussian))
        elif isinstance(r, ProfileAnalysis):
            h = np.asarray(r.profile, dtype=float)
            h = h if r.filled is None else h[~r.filled]
            panels.append((f"profile {r.name}", h, r.heights, r.gaussian))
        else:
            raise TypeError(f"expected SurfaceAnalysis or PairAnalysis (got {type(r).__name__})")
    return panels


def _conditions(results) -> str:
    items = results if isinstance(results, (list, tuple)) else [results]
    surfaces = [
        s for r in items for s in ((r.first, r.second) if isinstance(r, PairAnalysis) else (r,))
    ]
    lines = []
    for attr in ("band", "sampling"):
        values = [getattr(r, attr) for r in surfaces]
        prefix = "band " if attr == "band" else ""
        if all(v == values[0] for v in values):
            lines.append(prefix + values[0].describe())
        else:
            lines += [f"{r.name}: {prefix}{v.describe()}" for r, v in zip(surfaces, values)]
    return "\n".join(lines)


def plot_height_distribution(results, path, *, bins: int = 80) -> Path:
    """Write the height-distribution figure to ``path`` (PNG) and return the path.

    ``results``: a SurfaceAnalysis, a PairAnalysis (both surfaces and their sum surface)
    or a list of them.
    """
    panels = _panels(results)
    n = len(panels)
    fig, axes = plt.subplots(
        2,
        n,
        figsize=(max(4.3 * n, 6.5), 6.8),
        squeeze=False,
        gridspec_kw={"height_ratios": [1.3, 1.0]},
    )
    for j, (title, h, s, g) in enumerate(panels):
        z = (h.ravel() - s.mean) * 1e6  # µm
        sig = s.rms * 1e6
        lim = g.span * 1e6  # the Gaussian's grid covers the heights
        edges = np.linspace(-lim, lim, bins + 1)
        dens, _ = np.histogram(z, bins=edges, density=True)
        zz, gauss = g.z * 1e6, g.pdf * 1e-6  # µm, 1/µm
        for i, ax in enumerate(axes[:, j]):
            ax.stairs(
                dens,
                edges,
                fill=True,
                color="tab:blue",
                alpha=0.45,
                label="heights of the filtered map",
            )
            ax.plot(zz, gauss, "k-", lw=1.4, label="Gaussian with the same σ")
            for k in (-3, 3):
                ax.axvline(k * sig, color="grey", ls=":", lw=0.8)
            ax.set_xlabel("height above mean plane z [µm]")
            ax.set_ylabel("probability density [1/µm]")
            ax.grid(alpha=0.3)
            if i == 1:
                ax.set_yscale("log")
                pos = dens[dens > 0]
                ax.set_ylim(
                    0.5 * pos.min() if pos.size else 1e-6, 2.0 * max(dens.max(), gauss.max())
                )
                ax.set_title("log scale (tails; dotted: ±3σ)", fontsize=9)
            else:
                ax.set_title(
                    f"{title}\nσ = {sig:.3g} µm, Ssk = {s.skewness:.2f}, Sku = {s.kurtosis:.2f}",
                    fontsize=10,
                )
    fig.suptitle(
        "Height distribution vs Gaussian (cf. paper Fig. 7)\n" + _conditions(results), fontsize=9
    )
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    fig.legend(handles, labels, loc="lower center", ncol=2, fontsize=9, frameon=False)
    return save_figure(fig, path)
