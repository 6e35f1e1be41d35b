"""Stress maps: x–z contours of the von Mises stress of the body closest to failure, at
the instant of its greatest risk (the crank angle of the smallest safety factor), with
the coating–substrate interface drawn. Plotted from the fields the study stored in
``results.nc`` (``stress_map_*``, :mod:`tribodyn.workflow.stress_map`) and the stress
traces and safety factors beside them; nothing is computed here."""

from __future__ import annotations

import math

import numpy as np

from ...workflow.stress_study import MODE_PEAK
from .common import MPA, TITLE_SIZE, UM, finish, plt

__all__ = ["stress_maps", "greatest_risk", "stored_map", "fig27", "NO_MAP"]

#: why a results.nc has no stress maps to draw
NO_MAP = (
    "results.nc has no stored stress maps (stress_map_*): [stress] enabled = false, no "
    "finite safety factor, or a results.nc written by an older tribodyn (run the case "
    "again to draw them)"
)


def greatest_risk(ds, name: str) -> dict | None:
    """The stored instant of greatest risk of surface set ``name`` in ``results.nc``
    (the stress map's body, failure mode and EHL sample): {body, mode, safety_factor,
    index (EHL sample), crank_deg (the run's crank angle, as everywhere: the presented
    cycle 720–1440° by default), x_m, z_m (the governing peak)}; None without a map."""
    if "stress_map_sample" not in ds:
        return None
    i = int(ds["stress_map_sample"].sel(surface_set=name))
    if i < 0:
        return None
    body = str(ds["stress_map_body"].sel(surface_set=name).values)
    mode = str(ds["stress_map_mode"].sel(surface_set=name).values)
    base = f"stress_{body}_{MODE_PEAK[mode]}"
    return {
        "body": body,
        "mode": mode,
        "safety_factor": float(ds[f"safety_factor_{body}_{mode}"].sel(surface_set=name)),
        "index": i,
        "crank_deg": float(ds["ehl_crank"][i]),
        "x_m": float(ds[base + "_x"].sel(surface_set=name)[i]),
        "z_m": float(ds[base + "_z"].sel(surface_set=name)[i]),
    }


def stored_map(ds, name: str):
    """The stored stress map of set ``name``: (x [m], depths [m], von Mises [Pa] on
    (depths, x), coating thickness [m] of the mapped body or None), without padding."""
    x = ds["stress_map_x"].sel(surface_set=name).values
    z = ds["stress_map_depth"].sel(surface_set=name).values
    vm = ds["stress_map_von_mises"].sel(surface_set=name).values
    kx, kz = np.isfinite(x), np.isfinite(z)
    hc = float(ds["stress_map_coating_thickness"].sel(surface_set=name))
    return x[kx], z[kz], vm[np.ix_(kz, kx)], (hc if hc > 0 else None)


def stress_maps(ds, path):
    """One panel per surface set with stress results: von Mises [MPa]
    over x and depth z [µm] of the body closest to failure at its riskiest crank angle,
    the interface (dashed) and the peak of the governing mode (cross)."""
    names = [str(n) for n in ds["surface_set"].values]
    risks = [(n, r) for n in names if (r := greatest_risk(ds, n)) is not None]
    if not risks:
        raise ValueError(NO_MAP)
    ncol = min(len(risks), 3)
    nrow = math.ceil(len(risks) / ncol)
    fig, axes = plt.subplots(
        nrow, ncol, figsize=(5.2 * ncol, 3.9 * nrow), layout="constrained", squeeze=False
    )
    for ax in axes.flat[len(risks) :]:
        ax.set_visible(False)
    for ax, (name, r) in zip(axes.flat, risks, strict=False):
        x, depths, vm, hc = stored_map(ds, name)
        X, Z = np.meshgrid(x * UM, depths * UM)
        vm = vm * MPA
        cs = ax.contourf(X, Z, vm, levels=24, cmap="magma_r")
        fig.colorbar(cs, ax=ax, label="von Mises [MPa]", shrink=0.9)
        if hc is not None:
            ax.axhline(hc * UM, color="tab:cyan", ls="--", lw=1.2, label="interface")
            ax.legend(loc="lower right", fontsize=8)
        ax.plot(r["x_m"] * UM, r["z_m"] * UM, "x", color="tab:green", ms=9, mew=2)
        if hc is not None:  # √z axis: the coating stays visible above the deep maximum
            ax.set_yscale("function", functions=(np.sqrt, np.square))
            zmax = float(depths[-1]) * UM
            ticks = [0.0, hc * UM] + [v for v in (10, 25, 50, 100, 200, 400) if v < zmax]
            ax.set_yticks(ticks, [f"{t:g}" for t in ticks])
        ax.invert_yaxis()
        ax.set_xlabel("x [µm]")
        ax.set_ylabel("depth z [µm]" + (" (√ scale)" if hc is not None else ""))
        label = str(ds["surface_label"].sel(surface_set=name).values)
        ax.set_title(
            f"{label}: {r['body']}, {r['mode'].replace('_', ' ')}, "
            f"SF {r['safety_factor']:.2f} at {r['crank_deg']:.0f}° crank",
            fontsize=TITLE_SIZE - 1,
        )
    return finish(
        fig,
        path,
        "Subsurface von Mises stress at the instant of greatest risk",
        "cross: peak of the governing mode; SF: strength / cycle maximum",
    )


def fig27(ds, path):
    """The report's stress map (:func:`stress_maps` of every set with stress results);
    None when no set has a finite safety factor (its stress step failed or was off)."""
    names = [str(n) for n in ds["surface_set"].values]
    if not any(greatest_risk(ds, n) is not None for n in names):
        return None
    return stress_maps(ds, path)
