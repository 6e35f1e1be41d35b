"""Engine figures (:mod:`tribodyn.workflow.engine`): camshaft torque traces per camshaft
and surface set, and the lobe contributions to a camshaft's friction torque; both read
the engine variables of a results Dataset (:meth:`EngineStudy.to_dataset`)."""

from __future__ import annotations

import numpy as np

from .common import finish as _finish
from .common import plt

__all__ = ["engine_torque_figure", "engine_lobe_figure", "engine_figures"]


def engine_torque_figure(ds, path):
    """Camshaft drive torque and friction torque (cam–tappet, auxiliary) over crank angle,
    per camshaft and surface set."""
    x = np.asarray(ds["engine_crank"])
    shafts = list(ds["camshaft"].values)
    sets = list(ds["engine_set"].values)
    fig, axes = plt.subplots(
        2, len(shafts), figsize=(6 * len(shafts), 7), layout="constrained", squeeze=False
    )
    w = None
    for j, shaft in enumerate(shafts):
        a, b = axes[0, j], axes[1, j]
        for i, name in enumerate(sets):
            a.plot(x, ds["camshaft_drive_torque"].values[i, j], lw=1.2, label=str(name))
            b.plot(
                x, ds["camshaft_friction_torque"].values[i, j], lw=1.2, label=f"{name}: cam–tappet"
            )
        aux = (
            ds["tappet_bore_torque"].values[0, j]
            + ds["valve_guide_torque"].values[0, j]
            + ds["camshaft_journal_torque"].values[0, j]
        )
        b.plot(x, aux, "k--", lw=1.0, label=f"{sets[0]}: bore + guides + journals")
        a.axhline(0.0, color="k", lw=0.6)
        a.set_title(f"{shaft} camshaft")
        a.set_ylabel("drive torque [N m]")
        b.set_ylabel("friction torque [N m]")
        b.set_xlabel("crank angle from cylinder 1 firing TDC [°]")
        for ax in (a, b):
            ax.set_xlim(0, 720)
            ax.set_xticks(np.arange(0, 721, 90))
            ax.grid(alpha=0.3)
        b.legend(fontsize=8)
        w = a
    if w is not None:
        w.legend(fontsize=8)
    return _finish(fig, path, "Camshaft torque of the engine")


def engine_lobe_figure(ds, path):
    """Each valve's cam–tappet friction torque (first surface set), stacked per camshaft,
    with the camshaft's sum."""
    x = np.asarray(ds["engine_crank"])
    valves = [str(v) for v in ds["valve"].values]
    t = ds["lobe_friction_torque"].values[0]
    shafts = list(ds["camshaft"].values)
    fig, axes = plt.subplots(
        1, len(shafts), figsize=(6 * len(shafts), 4.5), layout="constrained", squeeze=False
    )
    for j, shaft in enumerate(shafts):
        ax = axes[0, j]
        keep = [k for k, v in enumerate(valves) if shaft == "camshaft" or v.startswith(shaft)]
        ax.stackplot(x, t[keep], labels=[valves[k] for k in keep], alpha=0.8)
        ax.plot(x, ds["camshaft_friction_torque"].values[0, j], "k", lw=1.0, label="sum")
        ax.set_title(f"{shaft} camshaft, {ds['engine_set'].values[0]}")
        ax.set_xlabel("crank angle from cylinder 1 firing TDC [°]")
        ax.set_ylabel("cam–tappet friction torque [N m]")
        ax.set_xlim(0, 720)
        ax.set_xticks(np.arange(0, 721, 90))
        ax.legend(fontsize=7, ncol=2)
    return _finish(fig, path, "Lobe contributions to the camshaft friction torque")


def engine_figures(ds, folder) -> list:
    """Write both engine figures into ``folder``; returns their paths."""
    from pathlib import Path

    folder = Path(folder)
    return [
        engine_torque_figure(ds, folder / "engine_camshaft_torque.png"),
        engine_lobe_figure(ds, folder / "engine_lobe_contributions.png"),
    ]
