"""Fig. 12: the Greenwood chart of the operating points."""

from __future__ import annotations

import numpy as np

from .common import (
    EVENT_FRACTION,
    arr,
    finish_numbered,
    loaded_mask,
    place_labels,
    plt,
    point_indices,
    point_legend_entry,
)

# ----------------------------------------------------------------------------- Fig. 12

_REGIME_NAMES = {
    "IR": "IR\nisoviscous–rigid\n(hydrodynamic)",
    "PR": "PR\npiezoviscous–rigid",
    "IE": "IE\nisoviscous–elastic\n(soft EHL)",
    "PE": "PE\npiezoviscous–elastic\n(classical EHL)",
}
_REGIME_COLOURS = {"IR": "#dbe9f6", "PR": "#e2f0d9", "IE": "#fff2cc", "PE": "#f8dcdc"}


def fig12(ds, path):
    """The stored regime map (``regime_map`` over ``chart_gV``, ``chart_gE``) with the
    operating points (``gV``, ``gE``) on it."""
    from matplotlib.colors import BoundaryNorm, ListedColormap
    from scipy.ndimage import distance_transform_edt, gaussian_filter
    from scipy.spatial import cKDTree

    e = arr(ds, "ehl_crank")
    gV, gE = arr(ds, "gV"), arr(ds, "gE")
    loaded = loaded_mask(ds).any(axis=0) & np.isfinite(gV) & np.isfinite(gE) & (gV > 0) & (gE > 0)
    force = arr(ds, "ehl_contact_force")
    event = loaded & (force >= EVENT_FRACTION * np.nanmax(force))
    light = loaded & ~event
    any_ = loaded.any()
    ge_axis, gv_axis = arr(ds, "chart_gE"), arr(ds, "chart_gV")
    regimes = ds["regime_map"].attrs["flag_meanings"].split()  # in code order
    code = arr(ds, "regime_map")
    ni, nj = code.shape
    n = min(ni, nj)
    lge, lgv = np.log10(ge_axis), np.log10(gv_axis)
    GE, GV = np.meshgrid(ge_axis, gv_axis)
    fig, ax = plt.subplots(figsize=(10.5, 8), layout="constrained")
    cmap = ListedColormap([_REGIME_COLOURS.get(r, "0.9") for r in regimes])
    ax.pcolormesh(
        GE,
        GV,
        code,
        cmap=cmap,
        shading="auto",
        zorder=0,
        rasterized=True,
        norm=BoundaryNorm(np.arange(len(regimes) + 1) - 0.5, cmap.N),
    )
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(ge_axis[0], ge_axis[-1])
    ax.set_ylim(gv_axis[0], gv_axis[-1])
    # region names: at the coarse-grid cell farthest from both the region's edge and the data
    step = max(1, n // 150)
    ci, cj = np.meshgrid(np.arange(0, ni, step), np.arange(0, nj, step), indexing="ij")
    if any_:
        di = (np.log10(gV[loaded]) - lgv[0]) / (lgv[1] - lgv[0])
        dj = (np.log10(gE[loaded]) - lge[0]) / (lge[1] - lge[0])
        tree = cKDTree(np.c_[di, dj])
        d_data = tree.query(np.c_[ci.ravel(), cj.ravel()])[0].reshape(ci.shape)
    else:
        d_data = np.full(ci.shape, np.inf)
    for k, r in enumerate(regimes):
        ind = code == k
        if not ind.any():
            continue
        if not ind.all():
            # contour of the (slightly smoothed) indicator: the boundary of the region
            ax.contour(
                GE,
                GV,
                gaussian_filter(ind.astype(float), 1.0),
                levels=[0.5],
                colors="k",
                linewidths=1.4,
                zorder=1,
            )
        coarse = ind[::step, ::step]
        inner = distance_transform_edt(np.pad(coarse, 1, constant_values=False))[1:-1, 1:-1]
        score = np.where(coarse, np.minimum(np.minimum(inner * step, 0.18 * n), d_data), -1.0)
        a, b = np.unravel_index(np.argmax(score), score.shape)
        i, j = ci[a, b], cj[a, b]
        ax.text(
            ge_axis[j],
            gv_axis[i],
            _REGIME_NAMES.get(r, r),
            ha="center",
            va="center",
            fontsize=10,
            fontweight="bold",
            color="0.25",
            zorder=2,
            bbox=dict(fc="white", ec="none", alpha=0.6, pad=1.5),
        )
    order = np.argsort(e)
    path_sel = order[event[order]]
    ax.plot(gE[path_sel], gV[path_sel], color="0.4", lw=0.6, zorder=3)
    if light.any():
        ax.plot(
            gE[light],
            gV[light],
            ".",
            color="0.45",
            ms=4,
            zorder=3,
            label=f"loaded base circle / ramps (W < {EVENT_FRACTION:.0%} of max)",
        )
    sc = ax.scatter(
        gE[event],
        gV[event],
        c=e[event],
        cmap="plasma",
        s=16,
        zorder=4,
        edgecolors="none",
        label="cam event (coloured by crank angle)",
    )
    cb = fig.colorbar(sc, ax=ax, pad=0.01)
    cb.set_label("crank angle [deg]")
    idx = point_indices(ds)
    if idx:
        place_labels(
            ax,
            gE[idx],
            gV[idx],
            [str(int(v)) for v in arr(ds, "point")],
            avoid=(gE[event], gV[event]),
            radius_pt=18,
        )
        point_legend_entry(ax, ds)
    ax.set_xlabel("elasticity parameter g_E = W' U^(−1/2)")
    ax.set_ylabel("viscosity parameter g_V = G W'^(3/2) U^(−1/2)")
    ax.legend(loc="lower right", fontsize=9, framealpha=0.9)
    ax.grid(alpha=0.25, which="major")
    return finish_numbered(
        fig,
        path,
        "boundaries where the Johnson (1970) asymptotes IR, PR, IE, PE meet; "
        "g_V, g_E with the bulk E' of the first surface set",
    )
