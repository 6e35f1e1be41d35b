"""Report figures of a cam-cycle study, drawn from the results Dataset.

:func:`make_figures` reads only the Dataset built by
:func:`tribodyn.output.dataset.study_to_dataset` and writes one PNG per paper figure
(Figs. 5, 6, 8–18 of Andreou et al. 2023) plus two summary figures (19: friction power and
energy, 20: minimum film and λ). One module per family: :mod:`.coating` (5, 6),
:mod:`.dynamics` (8–11), :mod:`.regimes` (12), :mod:`.profiles` (13, 14), :mod:`.cycle`
(15–20), :mod:`.thermal` (21, 22: temperatures, thermal vs isothermal, in thermal
studies), :mod:`.engineering` (23–26: camshaft torque, contact pressure, cam kinematics,
spring surge), :mod:`.stress` (27: stress map at the instant of greatest risk);
:mod:`.topography` draws the measured-surface figure (paper Fig. 7).

File names: the paper's case (``compare_paper`` attribute of the Dataset true or absent)
keeps the numbered names ``figNN_content.png``; any other case gets the content names
(``content.png``, :func:`~.common.content_name`) and titles without paper figure numbers.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path

from ..._safe_write import make_dirs
from ..._system import exit_with_parent
from ..._validation import InputError
from ..figure_names import FIGURES, content_name
from .coating import fig05, fig06
from .common import EVENT_FRACTION, TITLE_SIZE, compares_paper, has, plt
from .cycle import fig15, fig16, fig17, fig18, fig19, fig20
from .dynamics import fig08, fig09, fig10, fig11
from .engineering import fig23, fig24, fig25, fig26
from .profiles import fig13, fig14
from .regimes import fig12
from .stress import fig27
from .thermal import fig21, fig22

__all__ = ["FIGURES", "EVENT_FRACTION", "content_name", "figure_files", "make_figures"]

_MAKERS = {
    "fig05_dry_pressure.png": (fig05, ("dry_ratio", "dry_x", "dry_pressure")),
    "fig06_ehl_pressure_film.png": (fig06, ("ehl_x",)),
    "fig08_tappet_velocity.png": (fig08, ("crank_angle", "tappet_velocity", "contact_force")),
    "fig09_contact_force.png": (fig09, ("crank_angle", "contact_force")),
    "fig10_tappet_acceleration.png": (
        fig10,
        ("crank_angle", "tappet_acceleration", "contact_force"),
    ),
    "fig11_entrainment_speed.png": (
        fig11,
        ("entrainment_speed", "sliding_speed", "radius_of_curvature", "contact_force"),
    ),
    "fig12_greenwood_chart.png": (
        fig12,
        ("gV", "gE", "loaded", "ehl_contact_force", "regime_map", "chart_gE", "chart_gV"),
    ),
    "fig13_pressure_film_points.png": (
        fig13,
        ("pressure", "film", "profile_x", "point_crank", "loaded"),
    ),
    "fig14_coatings_pressure_film.png": (
        fig14,
        ("pressure", "film", "profile_x", "loaded", "ehl_contact_force"),
    ),
    "fig15_central_film.png": (fig15, ("central_film", "loaded")),
    "fig16_boundary_load.png": (fig16, ("asperity_load", "loaded")),
    "fig17_boundary_friction.png": (fig17, ("boundary_friction", "loaded")),
    "fig18_viscous_friction.png": (fig18, ("viscous_friction", "loaded")),
    "fig19_friction_power.png": (fig19, ("friction_power", "loaded")),
    "fig20_min_film_lambda.png": (fig20, ("min_film", "lambda_ratio", "loaded")),
    "fig21_temperatures.png": (fig21, ("max_temperature", "surface_temperature_tappet", "loaded")),
    "fig22_thermal_vs_isothermal.png": (
        fig22,
        ("central_film_isothermal", "viscous_friction_isothermal", "loaded"),
    ),
    "fig23_camshaft_torque.png": (
        fig23,
        ("camshaft_drive_torque", "camshaft_friction_torque", "loaded"),
    ),
    "fig24_contact_pressure.png": (fig24, ("hertz_pressure", "max_pressure", "loaded")),
    "fig25_cam_kinematics.png": (fig25, ("kinematic_lift", "kinematic_radius")),
    "fig26_spring_surge.png": (fig26, ("harmonic_amplitude", "surge_frequency")),
    "fig27_stress_map.png": (fig27, ("stress_map_von_mises",)),
}


#: Relative drawing cost of the figures (CPU time of the paper case's figures, the
#: average one = 1), to start the costliest first when several processes draw them.
_COST = {
    "fig13_pressure_film_points.png": 2.2,
    "fig14_coatings_pressure_film.png": 1.8,
    "fig12_greenwood_chart.png": 1.8,
    "fig20_min_film_lambda.png": 1.5,
    "fig06_ehl_pressure_film.png": 1.4,
    "fig05_dry_pressure.png": 0.6,
    "fig08_tappet_velocity.png": 0.7,
    "fig18_viscous_friction.png": 0.6,
    "fig19_friction_power.png": 0.55,
}


def _wanted(ds, only=None) -> list[str]:
    """The numbered names of the figures the Dataset has the variables for (of ``only``,
    numbered or content names, if given), in :data:`_MAKERS` order."""
    if only is not None:
        by_content = {content_name(n): n for n in _MAKERS}
        only = [by_content.get(n, n) for n in only]
        unknown = sorted(set(only) - set(_MAKERS))
        if unknown:
            raise InputError(
                f"unknown figure name(s) {', '.join(unknown)}; known: {', '.join(_MAKERS)}"
            )
    wanted = [n for n in _MAKERS if (only is None or n in set(only)) and has(ds, *_MAKERS[n][1])]
    if "loaded" in ds and not bool(ds["loaded"].any()):  # no EHL sample: nothing to draw
        wanted = [n for n in wanted if "loaded" not in _MAKERS[n][1]]
    return wanted


def figure_files(ds, only=None) -> list[str]:
    """The file names :func:`make_figures` may write for ``ds`` (a figure with nothing to
    draw is left out when drawn, so it writes these or fewer): numbered (module text)
    where the Dataset's ``compare_paper`` attribute says so (absent: numbered)."""
    numbered = compares_paper(ds)
    return [n if numbered else content_name(n) for n in _wanted(ds, only)]


def make_figures(
    ds,
    out_dir,
    *,
    only=None,
    workers: int = 1,
    meanwhile: Callable[[], object] | None = None,
) -> dict[str, Path]:
    """Write the report figures of a cycle-study Dataset into ``out_dir``.

    Returns ``{file name: path}`` for the figures written (keys as in :data:`FIGURES`).
    Comparisons are made against the ``reference_set`` attribute (the first uncoated
    set), which is plotted first. A figure whose variables are not in the Dataset (e.g. a study without the
    single-contact coating studies) is skipped, and so are the EHL figures when no sample
    was loaded (a train thrown off the cam); the explicit/implicit figures plot the
    explicit run alone, and say so, when the ``*_implicit`` variables are absent.
    ``only``: optional iterable of file names to restrict the output. ``workers`` > 1
    draws the figures in that many processes, the costliest first (each figure is
    written atomically by its own process; the result is the same as drawing them in
    turn). ``meanwhile``: called in this process while the other processes draw (e.g.
    to write the data files), or before drawing when there are none.
    The file names are those of :func:`figure_files`; ``only`` takes either name.
    """
    out = Path(out_dir)
    make_dirs(out)
    ref = ds.attrs.get("reference_set")
    if ref is not None and "surface_set" in ds.dims:
        names = [str(v) for v in ds["surface_set"].values]
        if ref in names and names[0] != ref:  # the figures compare against index 0
            k = names.index(ref)
            ds = ds.isel(surface_set=[k] + [i for i in range(len(names)) if i != k])
    wanted = _wanted(ds, only)
    k = min(max(1, int(workers)), len(wanted) // 2)  # at least two figures per process
    if k <= 1:
        if meanwhile is not None:
            meanwhile()
        return _draw(ds, out, wanted)
    import multiprocessing as mp
    import sys
    from concurrent.futures import ProcessPoolExecutor

    # fork shares the loaded modules and the Dataset (Linux); elsewhere a fresh
    # interpreter per process, which receives the Dataset once; the processes end with
    # this one, even if it is killed
    ctx = mp.get_context("fork" if sys.platform.startswith("linux") else "spawn")
    written: dict[str, Path] = {}
    with ProcessPoolExecutor(
        max_workers=k, mp_context=ctx, initializer=_hold, initargs=(ds, os.getpid())
    ) as pool:
        order = sorted(wanted, key=lambda n: -_COST.get(n, 1.0))
        parts = [pool.submit(_draw_held, out, n) for n in order]
        try:
            if meanwhile is not None:
                meanwhile()
            for part in parts:
                written.update(part.result())
        except BaseException:
            pool.shutdown(wait=True, cancel_futures=True)  # no figures after a failure
            raise
    return {f: written[f] for f in figure_files(ds, only) if f in written}


_HELD: list = []  # the Dataset of a drawing process


def _hold(ds, starter: int) -> None:
    exit_with_parent(starter)
    _HELD[:] = [ds]


def _draw_held(out: Path, name: str) -> dict[str, Path]:
    return _draw(_HELD[0], out, [name])


def _draw(ds, out: Path, names) -> dict[str, Path]:
    """Draw ``names`` in this process (file names: :func:`figure_files`)."""
    paper_numbers = compares_paper(ds)
    written = {}
    with plt.rc_context(
        {"font.size": 10, "axes.titlesize": TITLE_SIZE, "figure.dpi": 100, "savefig.dpi": 150}
    ):
        for name in names:
            file = name if paper_numbers else content_name(name)
            path = _MAKERS[name][0](ds, out / file)
            if path is not None:
                written[file] = path
    return written
