"""Engineering figures: camshaft torque, contact pressure, cam kinematics as used, the
spring's surge modes against the cam's harmonics (:mod:`tribodyn.workflow.engineering`)."""

from __future__ import annotations

import numpy as np

from ...workflow.engineering import cycle_integral
from .common import (
    MM,
    TITLE_SIZE,
    arr,
    crank_axis,
    event_samples,
    finish_numbered,
    in_window,
    plt,
    set_lines,
)

__all__ = ["fig23", "fig24", "fig25", "fig26"]


def _lines(ax, ds, name, win, styles):
    x = arr(ds, "ehl_crank")
    set_lines(ax, x, arr(ds, name), in_window(x, win), styles, lw=1.4)
    crank_axis(ax, win)


def fig23(ds, path):
    """Camshaft drive and friction torque over crank angle, per surface set."""
    win, styles, _, _ = event_samples(ds)
    fig, (a, b) = plt.subplots(2, 1, figsize=(11, 8), layout="constrained", sharex=True)
    _lines(a, ds, "camshaft_drive_torque", win, styles)
    a.axhline(0.0, color="k", lw=0.6)
    a.set_ylabel("drive torque T [N m]")
    a.set_title("(a) T = W s' + F_f (r_b + s)", fontsize=TITLE_SIZE)
    a.legend(fontsize=9)
    _lines(b, ds, "camshaft_friction_torque", win, styles)
    b.set_ylabel("friction torque T_f [N m]")
    b.set_title("(b) T_f = F_f (r_b + s), F_f = viscous + boundary", fontsize=TITLE_SIZE)
    crank, tf = arr(ds, "ehl_crank"), arr(ds, "camshaft_friction_torque")
    means = [  # ∮T_f dθ / 2π, as the summary's mean friction torque
        f"{st['label']} {cycle_integral(t, crank) / (2 * np.pi):.3g} N m"
        for st, t in zip(styles, tf)
    ]
    return finish_numbered(fig, path, "mean friction torque: " + "; ".join(means))


def fig24(ds, path):
    """Hertz maximum pressure and the EHL peak pressure along the cycle."""
    win, styles, x, m = event_samples(ds)
    fig, ax = plt.subplots(figsize=(11, 5.5), layout="constrained")
    for k, st in enumerate(styles):
        ax.plot(x[m], arr(ds, "hertz_pressure")[k][m] / 1e9, color=st["color"], ls="--", lw=1.0)
        ax.plot(x[m], arr(ds, "max_pressure")[k][m] / 1e9, color=st["color"], label=st["label"])
    crank_axis(ax, win)
    ax.set_ylabel("pressure [GPa]")
    ax.legend(fontsize=9)
    return finish_numbered(fig, path, "solid: EHL peak; dashed: Hertz p_h")


def fig25(ds, path):
    """Lift, velocity, acceleration and radius of curvature of the fitted cam profile,
    with the table's points and the fit residual when the cam is a table."""
    th = arr(ds, "cam_angle_deg")
    table = "table_lift" in ds
    fig, axes = plt.subplots(
        5 if table else 4, 1, figsize=(10, 13 if table else 10.5), sharex=True, layout="constrained"
    )
    a, b, c, d = axes[:4]
    a.plot(th, arr(ds, "kinematic_lift") * MM, label="fitted profile")
    if table:
        ta = arr(ds, "table_angle_deg") % 360.0
        a.plot(ta, arr(ds, "table_lift") * MM, ".", ms=3, color="k", label="table points")
    a.set_ylabel("lift s [mm]")
    a.legend(fontsize=9)
    b.plot(th, arr(ds, "kinematic_velocity"))
    b.set_ylabel("velocity s'ω [m/s]")
    c.plot(th, arr(ds, "kinematic_acceleration"))
    c.set_ylabel("acceleration s''ω² [m/s²]")
    r = arr(ds, "kinematic_radius") * MM
    d.plot(th, r)
    d.set_ylabel("radius of curvature [mm]")
    d.set_yscale("log")
    sub = f"minimum radius of curvature {np.min(r):.3g} mm"
    if table:
        res = arr(ds, "table_fit_residual") * 1e6
        axes[4].plot(arr(ds, "table_angle_deg") % 360.0, res, ".", ms=3, color="k")
        axes[4].set_ylabel("table − fit [µm]")
        sub += f"; fit residual RMS {np.sqrt(np.mean(res**2)):.3g} µm"
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("cam angle [deg]")
    return finish_numbered(fig, path, sub)


def fig26(ds, path):
    """Harmonic amplitudes of the lift at n·f_cam against the spring's surge frequencies."""
    f = arr(ds, "harmonic_frequency")
    amp = arr(ds, "harmonic_amplitude") * MM
    fig, ax = plt.subplots(figsize=(11, 5), layout="constrained")
    ax.bar(f, amp, width=0.6 * (f[1] - f[0]) if f.size > 1 else 1.0, color="tab:blue")
    ax.set_yscale("log")
    for k, fs in enumerate(arr(ds, "surge_frequency"), 1):
        ax.axvline(fs, color="tab:red", ls="--", lw=1.2)
        ax.text(fs, ax.get_ylim()[1], f" surge {k}: {fs:.0f} Hz", color="tab:red", va="top")
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("lift harmonic amplitude [mm]")
    ax.grid(alpha=0.3)
    f_cam = f[0] if f.size else float("nan")
    return finish_numbered(fig, path, f"cam frequency {f_cam:.3g} Hz; surge: (k/2)√(k_s/m_s)")
