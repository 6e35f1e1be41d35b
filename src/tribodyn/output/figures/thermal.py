"""Figs. 21–22 of a thermal study: temperatures along the cycle, and film and viscous
friction of the thermal model beside the isothermal one."""

from __future__ import annotations

import numpy as np

from .common import (
    TITLE_SIZE,
    UM,
    crank_axis,
    event_samples,
    failure_note,
    finish_numbered,
    masked,
    plt,
    set_lines,
)


def fig21(ds, path):
    """(a) maximum tappet surface temperature, (b) maximum cam surface temperature,
    (c) mid-film temperature at the centre and maximum temperature, per set [°C]."""
    win, styles, e, sel = event_samples(ds)
    c = 273.15
    t_in = float(ds.attrs.get("inlet_temperature_K", np.nan)) - c
    fig, axes = plt.subplots(3, 1, figsize=(11, 11), sharex=True, layout="constrained")
    panels = (
        ("surface_temperature_tappet", "(a) tappet surface (max over the contact)"),
        ("surface_temperature_cam", "(b) cam surface (max over the contact)"),
        (
            "mid_film_temperature",
            "(c) mid-film at the centre (solid) and maximum of film and surfaces (thin)",
        ),
    )
    for ax, (key, title) in zip(axes, panels):
        set_lines(ax, e, masked(ds, key) - c, sel, styles)
        if key == "mid_film_temperature":
            set_lines(
                ax, e, masked(ds, "max_temperature") - c, sel, styles, lw=0.7, alpha=0.7, label=None
            )
        ax.axhline(t_in, color="0.5", ls=":", lw=1)
        ax.set_ylabel("temperature [°C]")
        ax.set_title(title, fontsize=TITLE_SIZE)
        crank_axis(ax, win)
    axes[0].legend(fontsize=9, ncol=3, loc="best")
    for ax in axes[:-1]:
        ax.set_xlabel("")
    return finish_numbered(
        fig,
        path,
        f"inlet (sump) temperature {t_in:.0f} °C (dotted); cam event only; {failure_note(ds)}",
    )


def fig22(ds, path):
    """(a) central film thermal (solid) and isothermal (dotted) [µm]; (b) viscous friction
    thermal and isothermal [N]; (c) their ratios thermal/isothermal."""
    win, styles, e, sel = event_samples(ds)
    hc, hci = masked(ds, "central_film"), masked(ds, "central_film_isothermal")
    fv, fvi = masked(ds, "viscous_friction"), masked(ds, "viscous_friction_isothermal")
    fig, (a, b, c) = plt.subplots(3, 1, figsize=(11, 11), sharex=True, layout="constrained")
    set_lines(a, e, hc * UM, sel, styles)
    set_lines(a, e, hci * UM, sel, styles, ls=":", label=None)
    a.set_yscale("log")
    a.set_ylabel("central film h_c [µm]")
    a.set_title(
        "(a) central film: thermal (solid), isothermal at the inlet temperature (dotted)",
        fontsize=TITLE_SIZE,
    )
    set_lines(b, e, fv, sel, styles)
    set_lines(b, e, fvi, sel, styles, ls=":", label=None)
    b.set_ylim(bottom=0)
    b.set_ylabel("viscous friction F_v [N]")
    b.set_title("(b) viscous friction: thermal (solid), isothermal (dotted)", fontsize=TITLE_SIZE)
    with np.errstate(divide="ignore", invalid="ignore"):
        set_lines(c, e, hc / hci, sel, styles)
        set_lines(c, e, fv / fvi, sel, styles, ls="--", label=None)
    c.axhline(1.0, color="0.5", lw=0.8)
    c.set_ylabel("thermal / isothermal")
    c.set_title("(c) ratios: central film (solid), viscous friction (dashed)", fontsize=TITLE_SIZE)
    for ax in (a, b, c):
        crank_axis(ax, win)
    for ax in (a, b):
        ax.set_xlabel("")
    a.legend(fontsize=9, ncol=3, loc="best")
    return finish_numbered(fig, path, f"cam event only; {failure_note(ds)}")
