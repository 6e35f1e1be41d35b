"""``tribodyn warmup``: compile the numba kernels once, into numba's on-disk cache.

The EHL and valvetrain kernels are compiled on first use (``cache=True``): the first
``tribodyn run`` after an installation spends most of its time compiling. ``warmup``
runs the bundled paper case at a coarse resolution (the same code paths and argument
types as a full run, fewer samples) without writing anything, so that the compiled
kernels are cached and later runs load them. It also computes the default surface laws
that the paper case's plausibility checks compare its Greenwood–Tripp sets with, into
the user's cache folder (:mod:`tribodyn._cache`). ``make run`` calls it after installing.
"""

from __future__ import annotations

import time

import typer

__all__ = ["warmup_command", "warm_up"]

#: Coarse numerics of the warm-up study (every kernel is reached; sizes do not matter
#: to numba's compiled signatures).
WARMUP_NUMERICS = {
    "numerics.crank_step_deg": 5.0,
    "numerics.n": 128,
    "numerics.coupling_iterations": 1,
    "numerics.output_step_deg": 2.0,
    "numerics.workers": 1,
}


def warm_up() -> float:
    """Run the warm-up study in this process; returns its wall time [s]."""
    from ..config import load_case
    from ..contact.ehl.gmres_kernels import compile_fallbacks
    from ..physics.asperity import greenwood_tripp
    from ..workflow.cycle import run_cycle_study
    from ..workflow.engineering import typical_surface_laws

    t0 = time.perf_counter()
    typical_surface_laws(load_case())
    case = load_case().updated(WARMUP_NUMERICS)
    run_cycle_study(case, workers=1, compare_paper=False)
    compile_fallbacks()  # the EHL solver's variants the study reaches only on fallbacks
    greenwood_tripp(2.5, -13.0)  # F_n's asymptotic series far into contact (compiled)
    return time.perf_counter() - t0


def warmup_command():
    """Compile and cache the numerical kernels (a coarse run of the paper case, nothing
    written) and the paper case's reference surface laws, so that the first real run
    does not spend its time compiling."""
    typer.echo(f"tribodyn: compiled kernels cached in {warm_up():.1f} s")
