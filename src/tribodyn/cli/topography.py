"""``tribodyn topography FILE [FILE2]``: measured topography → case-file roughness block.

Heavy imports (SurfaceTopography, matplotlib) happen inside the command, so the main CLI
starts quickly.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import typer
from rich.console import Console
from rich.markup import escape
from rich.table import Table

from .. import _json
from .failure import fail, writing
from .help_defaults import stating

__all__ = ["topography_command", "TopographyCommand"]

_SYN = "Synthetic surfaces (--synthetic)"
_LIMITATION = (
    "η and β depend strongly on the band and the sampling. The 8-neighbour summit "
    "values converge to the continuous-surface (McCool) values only when the "
    "shortest filtered wavelength spans many pixels (≳ 16); the spectral values "
    "assume an isotropic Gaussian surface."
)


def _um(x: float) -> str:
    return f"{x * 1e6:.4g}"


def _dev(a: float, b: float) -> str:
    return f"{a / b - 1:+.1%}"


def _new_table(title: str, caption: str, right: tuple[str, ...]) -> Table:
    """A table headed by ``title`` and ``caption``, columns quantity, unit, ``*right``."""
    t = Table(title=title, title_justify="left", caption=caption, caption_justify="left")
    t.add_column("quantity")
    t.add_column("unit")
    for name in right:
        t.add_column(name, justify="right")
    return t


def _parameter_table(title: str, summits, spectral, count=None, alpha=None) -> Table:
    t = _new_table(
        title,
        "summits: 8-neighbour summits, 3-point curvature; spectral: McCool (1986) from "
        "spectral moments; Δ = summits/spectral − 1",
        ("summits", "spectral", "Δ"),
    )
    rows = [
        ("σ  RMS height", "µm", "rms", _um),
        ("η  summit density", "1/m²", "asperity_density", lambda v: f"{v:.4g}"),
        ("β  summit radius", "µm", "summit_radius", _um),
        ("ηβσ", "-", "roughness_parameter", lambda v: f"{v:.4g}"),
        ("summit height, mean", "µm", "summit_height_mean", _um),
        ("summit height, std", "µm", "summit_height_std", _um),
    ]
    for label, unit, attr, fmt in rows:
        b = getattr(spectral, attr)
        if summits is None:
            t.add_row(label, unit, "–", fmt(b), "")
        else:
            a = getattr(summits, attr)
            t.add_row(label, unit, fmt(a), fmt(b), _dev(a, b))
    t.add_row(
        "summits / bandwidth α", "-", "–" if count is None else str(count), f"α = {alpha:.3g}", ""
    )
    return t


def _print_surface(console: Console, r) -> None:
    src = r.source or {}
    where = f" ({src.get('format')}, channel '{src.get('channel')}')" if src else ""
    console.print(f"[bold]{escape(r.name)}[/bold]{escape(where)}")
    console.print(f"  band:     {r.band.describe()}", markup=False, soft_wrap=True)
    console.print(f"  sampling: {r.sampling.describe()}", markup=False, soft_wrap=True)
    console.print(
        f"  filled:   {r.sampling.undefined_fraction:.1%} of the points (not "
        "measured; excluded from the statistics)",
        markup=False,
    )
    for w in r.warnings:
        console.print(f"  warning: {w}", markup=False, style="yellow", soft_wrap=True)
    h = r.heights
    from ..topography.profile import ProfileAnalysis

    if isinstance(r, ProfileAnalysis):
        _print_profile(console, r)
    else:
        console.print(
            _parameter_table(
                f"Greenwood–Tripp parameters of {escape(r.name)}",
                r.summits,
                r.spectral,
                r.summit_stats.count,
                r.moments.alpha,
            )
        )
        console.print(
            f"  height distribution: Ssk = {h.skewness:.3f}, Sku = "
            f"{h.kurtosis:.3f} (Gaussian 0, 3); slope anisotropy "
            f"{r.slope_anisotropy:.2f} (isotropic 1)",
            markup=False,
        )
    for note in r.notes:
        console.print(f"  note: {note}", markup=False, soft_wrap=True)
    console.print()


def _print_profile(console: Console, r) -> None:
    from ..topography.profile import ISOTROPIC_LABEL

    t = _new_table(f"Profile {escape(r.name)}", f"η, β: {ISOTROPIC_LABEL}", ("value",))
    m, h, p = r.moments, r.heights, r.spectral
    for label, unit, value in (
        ("σ = Rq  RMS height", "µm", _um(h.rms)),
        ("Rsk  skewness", "-", f"{h.skewness:.3f}"),
        ("Rku  kurtosis", "-", f"{h.kurtosis:.3f}"),
        ("m0, m2, m4  profile moments", "m², -, 1/m²", f"{m.m0:.4g}, {m.m2:.4g}, {m.m4:.4g}"),
        ("α  bandwidth m0 m4/m2²", "-", f"{m.alpha:.3g}"),
        ("peaks per mm, counted", "1/mm", f"{r.peak_density * 1e-3:.4g}"),
        ("peaks per mm, Gaussian (1/2π)√(m4/m2)", "1/mm", f"{r.peak_density_gaussian * 1e-3:.4g}"),
        ("η  summit density (isotropic estimate)", "1/m²", f"{p.asperity_density:.4g}"),
        ("β  summit radius (isotropic estimate)", "µm", _um(p.summit_radius)),
        ("ηβσ (isotropic estimate)", "-", f"{p.roughness_parameter:.4g}"),
    ):
        t.add_row(label, unit, value)
    console.print(t)


def _print_pair(console: Console, p) -> None:
    console.print(
        f"[bold]composite pair[/bold] {escape(p.first.name)} + "
        f"{escape(p.second.name)}: σ = √(σ₁² + σ₂²); spectral: summed moments; "
        "summits: sum surface h₁ + h₂"
    )
    console.print(
        _parameter_table(
            "Composite Greenwood–Tripp parameters",
            p.summits,
            p.spectral,
            None if p.summit_stats is None else p.summit_stats.count,
            p.moments.alpha,
        )
    )
    for note in p.notes:
        console.print(f"  note: {note}", markup=False, soft_wrap=True)
    console.print()


def _synthetic_options(grid, pixel, rms, hurst, cutoffs) -> dict[str, Any]:
    """Keyword arguments of ``synthetic_surface``: the options given, else its defaults."""
    from ..topography.synthetic import DEFAULT_SYNTHETIC

    given = {
        "nb_grid_pts": None if grid is None else (grid, grid),
        "pixel_size": pixel,
        "rms": rms,
        "hurst": hurst,
        "short_cutoff": None if cutoffs is None else cutoffs[0],
        "long_cutoff": None if cutoffs is None else cutoffs[1],
    }
    return {k: v if (v := given[k]) is not None else d for k, d in DEFAULT_SYNTHETIC.items()}


def stated_defaults() -> dict[str, Any]:
    """The values ``tribodyn topography --help`` quotes: the default band of the filter
    [µm], the fewest summits an analysis accepts, its default share of measured points
    and the synthetic surface's defaults."""
    import inspect

    from ..topography.analysis import MIN_SUMMITS, analyse_surface
    from ..topography.filtering import TYPICAL_BAND
    from ..topography.synthetic import DEFAULT_SYNTHETIC as S

    analysis = inspect.signature(analyse_surface).parameters
    return {
        "band_short": TYPICAL_BAND[0] * 1e6,
        "band_long": TYPICAL_BAND[1] * 1e6,
        "min_summits": MIN_SUMMITS,
        "min_defined": analysis["min_defined_fraction"].default,
        "grid": S["nb_grid_pts"][0],
        "pixel": S["pixel_size"],
        **{k: S[k] for k in ("rms", "hurst", "short_cutoff", "long_cutoff")},
    }


#: the command's class: its --help quotes :func:`stated_defaults`
TopographyCommand = stating(stated_defaults)


def topography_command(
    files: list[Path] | None = typer.Argument(
        None,
        show_default=False,
        metavar="FILE [FILE2]",
        help="Areal topography file(s) in any format SurfaceTopography reads (.opd, .x3p, "
        ".sur, .datx, .plu, .nc, …). Two files (cam and tappet) also give the "
        "composite pair.",
    ),
    band: tuple[float, float] | None = typer.Option(
        None,
        "--band",
        metavar="SHORT LONG",
        show_default=False,
        help="Band-pass wavelength limits in m; must lie within the measurement's range "
        "(see --clip-band). Default: the typical roughness band of a ground surface, "
        "{band_short:g}–{band_long:g} µm (physics.typical), clipped to what the measurement "
        "resolves (a warning says which band was used).",
    ),
    no_filter: bool = typer.Option(False, "--no-filter", help="Level only, no band-pass."),
    filter_kind: str = typer.Option(
        "gaussian", "--filter", help="'gaussian' (50 % at the cutoffs) or 'step'."
    ),
    detrend: str = typer.Option(
        "height", "--detrend", help="'height' (plane), 'curvature' (2nd order) or 'center'."
    ),
    clip_band: bool = typer.Option(
        False,
        "--clip-band",
        help="Narrow a --band outside the measurement's range instead of failing.",
    ),
    min_defined: float | None = typer.Option(
        None,
        "--min-defined",
        show_default=False,
        help="Smallest accepted share of measured points "
        "(default {min_defined:g}: dropouts are filled and excluded "
        "from the statistics; refused only if fewer "
        "than {min_summits} summits remain).",
    ),
    method: str = typer.Option(
        "summits",
        "--method",
        help="Estimator for the roughness TOML block: 'summits' or 'spectral'.",
    ),
    as_json: bool = typer.Option(False, "--json", help="Print JSON instead of tables."),
    figure: Path | None = typer.Option(
        None, "--figure", metavar="PATH", help="Write the height-distribution figure (PNG)."
    ),
    channel: int | None = typer.Option(None, "--channel", help="Channel index."),
    unit: str | None = typer.Option(None, "--unit", help="Length unit, for files that store none."),
    size: tuple[float, float] | None = typer.Option(
        None,
        "--size",
        metavar="LX LY",
        help="Lateral size (in --unit), for files without lateral calibration.",
    ),
    synthetic: bool = typer.Option(
        False,
        "--synthetic",
        rich_help_panel=_SYN,
        help="First write synthetic isotropic Gaussian surfaces "
        "to FILE [FILE2] (.x3p, .nc, .gwy, .txt), then "
        "analyse them.",
    ),
    grid: int | None = typer.Option(
        None, "--grid", rich_help_panel=_SYN, help="Points per side (default {grid})."
    ),
    pixel: float | None = typer.Option(
        None, "--pixel", rich_help_panel=_SYN, help="Pixel size in m (default {pixel:g})."
    ),
    rms: float | None = typer.Option(
        None, "--rms", rich_help_panel=_SYN, help="RMS height σ in m (default {rms:g})."
    ),
    hurst: float | None = typer.Option(
        None, "--hurst", rich_help_panel=_SYN, help="Hurst exponent (default {hurst:g})."
    ),
    cutoffs: tuple[float, float] | None = typer.Option(
        None,
        "--cutoffs",
        metavar="SHORT LONG",
        show_default=False,
        rich_help_panel=_SYN,
        help="Spectrum cutoff wavelengths in m (default {short_cutoff:g} and {long_cutoff:g}).",
    ),
    seed: int = typer.Option(1, "--seed", rich_help_panel=_SYN, help="Random seed."),
):
    """Greenwood–Tripp roughness (η, σ, β) from measured surface topography.

    Fills undefined points (dropouts), levels, band-pass filters and reports σ, summit
    density η and mean summit radius β from 8-neighbour summits and from McCool's spectral
    moments, plus skewness and kurtosis, with the band, sampling and share of filled points.
    A profile (line scan) gives σ, Rsk, Rku, its spectral moments and the isotropic-surface
    estimates of η and β. Prints the roughness TOML block (asperity_density, rms,
    summit_radius) to paste into a case file.
    """
    from .._validation import InputError
    from ..topography.analysis import analyse_surface, composite_roughness
    from ..topography.reading import write_topography
    from ..topography.synthetic import synthetic_surface

    console = Console()
    err = Console(stderr=True)
    files = list(files or [])
    try:
        if not 1 <= len(files) <= 2:
            raise InputError(f"give one or two topography files (got {len(files)})")
        if synthetic:
            s = _synthetic_options(grid, pixel, rms, hurst, cutoffs)
            for i, path in enumerate(files):
                topo = synthetic_surface(**s, seed=seed + i)
                write_topography(topo, path)
                if not as_json:
                    nx, ny = s["nb_grid_pts"]
                    console.print(
                        f"wrote synthetic surface {path} ({nx} × {ny} points, "
                        f"pixel {_um(s['pixel_size'])} µm, σ = {_um(s['rms'])} µm, "
                        f"H = {s['hurst']:g}, wavelengths {_um(s['short_cutoff'])}–"
                        f"{_um(s['long_cutoff'])} µm)",
                        markup=False,
                    )
        kwargs: dict[str, Any] = dict(
            kind=filter_kind,
            detrend=detrend,
            clip_band=clip_band,
            channel=channel,
            unit=unit,
            physical_sizes=size,
        )
        if min_defined is not None:
            kwargs["min_defined_fraction"] = min_defined
        use_band = None if no_filter else ("auto" if band is None else band)
        analyses = [analyse_surface(f, use_band, **kwargs) for f in files]
        result = composite_roughness(*analyses) if len(analyses) == 2 else analyses[0]
        if method == "summits" and result.summits is None:
            method = "spectral"  # profiles (and mixed pairs) have no summits
        block = result.toml_block(method)
        fig_path = None
        if figure is not None:
            from ..output.figures.topography import plot_height_distribution

            if figure.is_dir() or figure.suffix.lower() not in (".png", ".pdf", ".svg"):
                raise InputError(
                    f"--figure must be a file name ending in .png, .pdf or .svg "
                    f"(got {str(figure)!r})"
                )
            with writing("--figure", figure):
                fig_path = plot_height_distribution(result, figure)
    except InputError as exc:
        fail(err, exc)

    if as_json:
        for r in analyses:
            for w in r.warnings:
                err.print(f"warning: {r.name}: {w}", markup=False, style="yellow", soft_wrap=True)
        out = result.to_dict()
        out.update(
            method=method, roughness_toml=block, figure=None if fig_path is None else str(fig_path)
        )
        sys.stdout.write(_json.dumps(out, indent=2, ensure_ascii=False) + "\n")
        return
    for r in analyses:
        _print_surface(console, r)
    if len(analyses) == 2:
        _print_pair(console, result)
    console.print(_LIMITATION, markup=False, style="dim")
    console.print()
    console.print(
        f"[bold]case-file block[/bold] (method: {escape(method)}; paste into the case TOML)"
    )
    console.print(block, markup=False, highlight=False, soft_wrap=True)
    if fig_path is not None:
        console.print(f"wrote {fig_path}", markup=False)
