"""Stress maps: x–z contours of the von Mises stress of the body closest to failure, at
the instant of its greatest risk (the crank angle of the smallest safety factor), with
the coating–substrate interface drawn. Rebuilt from ``results.nc`` alone: the recorded
pressure and film profile of that sample, the surface loads of
:func:`tribodyn.contact.stress.profile_surface_loads` and
:func:`tribodyn.subsurface_stress`."""

from __future__ import annotations

import math
import tomllib
from typing import Any

import numpy as np

from ...workflow.stress_study import MODE_PEAK
from .common import MPA, TITLE_SIZE, UM, finish, plt

__all__ = ["stress_maps", "greatest_risk", "stress_field_at", "fig27"]


def greatest_risk(ds, name: str) -> dict | None:
    """Smallest safety factor of surface set ``name`` over both bodies and all modes in
    ``results.nc``: {body, mode, safety_factor, index (EHL sample), crank_deg (the run's
    crank angle, as everywhere: the presented cycle 720–1440° by default), x_m, z_m};
    None without stress results."""
    best: dict[str, Any] | None = None
    for body in ("cam", "tappet"):
        for mode, peak in MODE_PEAK.items():
            key = f"safety_factor_{body}_{mode}"
            if key not in ds:
                return None
            sf = float(ds[key].sel(surface_set=name))
            if not math.isfinite(sf) or (best is not None and sf >= best["safety_factor"]):
                continue
            base = f"stress_{body}_{peak}"
            tr = ds[base].sel(surface_set=name).values
            i = int(np.nanargmax(tr))
            best = {
                "body": body,
                "mode": mode,
                "safety_factor": sf,
                "index": i,
                "crank_deg": float(ds["ehl_crank"][i]),
                "x_m": float(ds[base + "_x"].sel(surface_set=name)[i]),
                "z_m": float(ds[base + "_z"].sel(surface_set=name)[i]),
            }
    return best


def stress_field_at(ds, name: str, index: int, body: str, nz: int = 121):
    """Stress field of ``body`` ("cam"/"tappet") of set ``name`` at EHL sample ``index``
    of ``results.nc``: (SubsurfaceStress, coating thickness [m] or None, half-width b)."""
    from ...config.case import Case
    from ...contact.stress import loaded_half_width, profile_surface_loads, shear_options
    from ...physics.stress import subsurface_stress

    # only the surfaces, the oil and the EHL options are needed: the cam section is left
    # out, so a lift table that is not where results.nc is read does not matter
    data = tomllib.loads(ds.attrs["case_toml"])
    data.pop("cam", None)
    case = Case.from_dict(data)
    s = case.surface_set(name)
    opts = case.ehl_options(s)
    x = ds["profile_x"].sel(surface_set=name).values[index]
    p = ds["pressure"].sel(surface_set=name).values[index]
    h = ds["film"].sel(surface_set=name).values[index]
    ld = profile_surface_loads(
        x,
        p,
        h,
        float(ds["ehl_sliding_speed"][index]),
        s.bodies,
        case.lubricant(),
        s.roughness,
        **shear_options(opts),
    )
    b = loaded_half_width(x, ld.pressure)
    bod = s.cam if body == "cam" else s.tappet
    hc = bod.coating.thickness if bod.coating is not None else None
    z = np.linspace(0.0, 2.5 * b, nz)
    if hc is not None:  # resolve the coating: 12 levels in it, the interface on the grid
        z = np.unique(np.concatenate([z, np.linspace(0.0, hc, 13), [hc * (1 + 1e-9)]]))
    q = ld.traction_cam if body == "cam" else ld.traction_tappet
    return subsurface_stress(x, ld.pressure, q, bod, z), hc, b


def stress_maps(ds, path, sets=None):
    """One panel per surface set (default: all with stress results): von Mises [MPa]
    over x and depth z [µm] of the body closest to failure at its riskiest crank angle,
    the interface (dashed) and the peak of the governing mode (cross)."""
    names = [str(n) for n in ds["surface_set"].values] if sets is None else list(sets)
    risks = [(n, r) for n in names if (r := greatest_risk(ds, n)) is not None]
    if not risks:
        raise ValueError("results.nc has no stress results ([stress] enabled = false?)")
    ncol = min(len(risks), 3)
    nrow = math.ceil(len(risks) / ncol)
    fig, axes = plt.subplots(
        nrow, ncol, figsize=(5.2 * ncol, 3.9 * nrow), layout="constrained", squeeze=False
    )
    for ax in axes.flat[len(risks) :]:
        ax.set_visible(False)
    for ax, (name, r) in zip(axes.flat, risks, strict=False):
        st, hc, b = stress_field_at(ds, name, r["index"], r["body"])
        xs = (st.x - r["x_m"]) / b  # centred on the peak, in half-widths
        keep = np.abs(xs) <= 2.5
        X, Z = np.meshgrid(st.x[keep] * UM, st.depths * UM)
        vm = st.von_mises[:, keep] * MPA
        cs = ax.contourf(X, Z, vm, levels=24, cmap="magma_r")
        fig.colorbar(cs, ax=ax, label="von Mises [MPa]", shrink=0.9)
        if hc is not None:
            ax.axhline(hc * UM, color="tab:cyan", ls="--", lw=1.2, label="interface")
            ax.legend(loc="lower right", fontsize=8)
        ax.plot(r["x_m"] * UM, r["z_m"] * UM, "x", color="tab:green", ms=9, mew=2)
        if hc is not None:  # √z axis: the coating stays visible above the deep maximum
            ax.set_yscale("function", functions=(np.sqrt, np.square))
            zmax = float(st.depths[-1]) * UM
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
