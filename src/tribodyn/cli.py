"""Command-line interface: ``tribodyn run``, ``tribodyn contact``, ``tribodyn topography``."""

from __future__ import annotations

import time
from pathlib import Path

import typer
from rich.console import Console

from .cli_contact import contact_command
from .topography.cli import topography_command

app = typer.Typer(add_completion=False, no_args_is_help=True,
                  help="Tribo-dynamics of coated cam–flat-tappet contacts.")
console = Console()


@app.callback()
def _main():
    """tribodyn: cam–tappet tribo-dynamics with coated surfaces."""


@app.command()
def run(out: Path = typer.Option(Path("results"), "-o", "--out", help="output folder")):
    """Run the main job (currently: the dry coating study, paper Fig. 5)."""
    from .plots import plot_dry_coating_study
    from .workflow.coating_study import PAPER_FIG5, dry_coating_study

    t0 = time.perf_counter()
    cases = dry_coating_study()
    path = plot_dry_coating_study(cases, out / "fig05_dry_pressure.png",
                                  radius=PAPER_FIG5["radius"], thickness=PAPER_FIG5["thickness"],
                                  load_total=PAPER_FIG5["load_total"], width=PAPER_FIG5["width"])
    for c in cases:
        r = c.result
        console.print(f"{c.label:16s} b = {r.half_width * 1e6:7.2f} µm  "
                      f"p_max = {r.max_pressure / 1e6:7.1f} MPa  converged={r.converged}")
    console.print(f"wrote {path} in {time.perf_counter() - t0:.1f} s")


app.command("topography")(topography_command)
app.command("contact")(contact_command)


def main():  # pragma: no cover
    app()


if __name__ == "__main__":  # pragma: no cover
    main()
