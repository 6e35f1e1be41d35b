"""Engine figures (:mod:`tribodyn.workflow.engine`): camshaft torque traces per camshaft
and surface set, and the lobe contributions to a camshaft's friction torque; both read
the engine variables of a results Dataset (:meth:`EngineStudy.to_dataset`).

Surface sets are named by their display names (``labels``, e.g. ``DLC 4 µm``) and drawn
with a colour and a line style each, so that curves lying on one another stay visible;
each valve has its own legend entry (cylinder, valve of its kind)."""

from __future__ import annotations

import re
from collections import Counter

import numpy as np

from ..report_engine import ENGINE_PARTS
from .common import finish as _finish
from .common import plt

__all__ = ["engine_torque_figure", "engine_lobe_figure", "engine_figures", "valve_labels"]

_STYLES = ("-", "--", ":", "-.")
_COLOURS = ("tab:blue", "tab:red", "tab:green", "tab:purple", "tab:brown", "tab:olive")
_X_LABEL = "crank angle of cylinder 1 from its firing TDC, 0–720° [°]"


def _set_style(i: int) -> dict:
    return {
        "color": _COLOURS[i % len(_COLOURS)],
        "ls": _STYLES[i % len(_STYLES)],
        "lw": 1.8 if i == 0 else 1.3,
    }


def valve_labels(valves) -> list[str]:
    """Unique legend labels of the valves (the ``valve`` coordinate): ``intake1a``,
    ``intake1b``, ``exhaust1`` → ``cyl. 1 intake a``, ``cyl. 1 intake b``,
    ``cyl. 1 exhaust``. Repeated names of an older results file (``intake1``,
    ``intake1``) get their letters here."""
    names = [str(v) for v in valves]
    total = Counter(names)
    seen: Counter = Counter()
    out = []
    for n in names:
        m = re.fullmatch(r"(\D+?)(\d+)([a-z]*)", n)
        if m is None:
            kind, cyl, tail = n, "", ""
        else:
            kind, cyl, tail = m.group(1), m.group(2), m.group(3)
        if not tail and total[n] > 1:
            tail = "abcdefghijklmnopqrstuvwxyz"[seen[n] % 26]
        seen[n] += 1
        tail = f" {tail}" if tail else ""
        out.append(f"cyl. {cyl} {kind}{tail}" if cyl else f"{kind}{tail}")
    return out


def engine_torque_figure(ds, path, labels=None):
    """Camshaft drive torque and friction torque (cam–tappet, auxiliary) over crank angle,
    per camshaft and surface set."""
    labels = labels or {}
    x = np.asarray(ds["engine_crank"])
    shafts = list(ds["camshaft"].values)
    sets = [str(s) for s in ds["engine_set"].values]
    fig, axes = plt.subplots(
        2, len(shafts), figsize=(6 * len(shafts), 7.5), layout="constrained", squeeze=False
    )
    for j, shaft in enumerate(shafts):
        a, b = axes[0, j], axes[1, j]
        for i, name in enumerate(sets):
            st = _set_style(i)
            lab = labels.get(name, name)
            a.plot(x, ds["camshaft_drive_torque"].values[i, j], label=lab, **st)
            b.plot(x, ds["camshaft_friction_torque"].values[i, j], label=f"{lab}: cam–tappet", **st)
        aux = sum(ds[f"{k}_torque"].values[0, j] for k, _ in ENGINE_PARTS[1:])  # auxiliary
        ref = labels.get(sets[0], sets[0])
        b.plot(
            x,
            aux,
            color="k",
            ls=(0, (5, 1, 1, 1)),
            lw=1.0,
            label=f"{ref}: bores + guides + journals",
        )
        a.axhline(0.0, color="k", lw=0.6)
        a.set_title(f"{shaft} camshaft")
        a.set_ylabel("drive torque [N m]")
        b.set_ylabel("friction torque [N m]")
        b.set_xlabel(_X_LABEL)
        for ax in (a, b):
            ax.set_xlim(0, 720)
            ax.set_xticks(np.arange(0, 721, 90))
            ax.grid(alpha=0.3)
    h, lab = axes[1, -1].get_legend_handles_labels()
    fig.legend(h, lab, loc="outside lower center", ncol=min(len(lab), 4), fontsize=9)
    return _finish(
        fig,
        path,
        "Camshaft torque of the engine, per camshaft",
        "top: drive torque of the cam–tappet contacts; bottom: friction torque",
    )


def engine_lobe_figure(ds, path, labels=None):
    """Each valve's cam–tappet friction torque (first surface set), stacked per camshaft,
    with the camshaft's sum."""
    labels = labels or {}
    x = np.asarray(ds["engine_crank"])
    valves = [str(v) for v in ds["valve"].values]
    names = valve_labels(valves)
    t = ds["lobe_friction_torque"].values[0]
    shafts = list(ds["camshaft"].values)
    first = str(ds["engine_set"].values[0])
    fig, axes = plt.subplots(
        1, len(shafts), figsize=(6 * len(shafts), 5.5), layout="constrained", squeeze=False
    )
    for j, shaft in enumerate(shafts):
        ax = axes[0, j]
        if "valve_camshaft" in ds.coords:
            on = [str(c) for c in ds["valve_camshaft"].values]
            keep = [k for k, c in enumerate(on) if c == shaft]
        else:  # an older results file
            keep = [k for k, v in enumerate(valves) if shaft == "camshaft" or v.startswith(shaft)]
        ax.stackplot(x, t[keep], labels=[names[k] for k in keep], alpha=0.8)
        ax.plot(x, ds["camshaft_friction_torque"].values[0, j], "k", lw=1.0, label="sum")
        ax.set_title(f"{shaft} camshaft, {labels.get(first, first)}")
        ax.set_xlabel(_X_LABEL)
        ax.set_ylabel("cam–tappet friction torque [N m]")
        ax.set_xlim(0, 720)
        ax.set_xticks(np.arange(0, 721, 90))
        ax.legend(fontsize=8, ncol=3, loc="upper center", bbox_to_anchor=(0.5, -0.14))
    return _finish(fig, path, "Lobe contributions to the camshaft friction torque")


def engine_figures(ds, folder, labels=None) -> list:
    """Write both engine figures into ``folder``; returns their paths. ``labels``:
    display names of the surface sets."""
    from pathlib import Path

    folder = Path(folder)
    return [
        engine_torque_figure(ds, folder / "engine_camshaft_torque.png", labels),
        engine_lobe_figure(ds, folder / "engine_lobe_contributions.png", labels),
    ]
