"""First-run time of ``tribodyn run`` with and without ``tribodyn warmup`` (prints JSON).

    python benchmarks/bench_first_run.py [CASE] [--keep]

A first run is simulated by removing numba's cache of tribodyn's kernels (the ``*.nbi``
and ``*.nbc`` files in the package's ``__pycache__`` folders). Each step runs in a fresh
interpreter (``python -m tribodyn``) and is timed by wall clock and by the children's
CPU time:

1. ``cold``: cache removed, ``tribodyn run CASE`` — what a first run costs without the
   warm-up (compilation inside the run);
2. ``warmup``: cache removed, ``tribodyn warmup`` — what ``make run`` adds to the
   installation;
3. ``after_warmup``: ``tribodyn run CASE`` with the cache the warm-up wrote — the first
   run a user sees after ``make run``'s installation;
4. ``warm``: the same run again (everything cached, files in the OS cache).

The cache files are left as the last run wrote them. On a shared machine compare CPU
seconds as well as walls.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import tribodyn

PKG = Path(tribodyn.__file__).parent


def clear_cache() -> int:
    """Remove numba's cache files of the package; returns how many were removed."""
    n = 0
    for p in PKG.rglob("__pycache__/*"):
        if p.suffix in (".nbi", ".nbc"):
            p.unlink()
            n += 1
    return n


def timed(*args: str) -> dict:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    r = subprocess.run(
        [sys.executable, "-m", "tribodyn", *args], capture_output=True, text=True, check=False
    )
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if r.returncode != 0:
        raise SystemExit(f"tribodyn {' '.join(args)} failed:\n{r.stdout}\n{r.stderr}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return {"wall_s": round(wall, 2), "cpu_s": round(cpu, 2)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case", nargs="?", default="andreou2023")
    a = ap.parse_args()
    out: dict = {"case": a.case, "cpu_count": os.cpu_count()}
    with tempfile.TemporaryDirectory() as tmp:
        run = ("run", a.case, "-q", "-o")
        out["removed_cache_files"] = clear_cache()
        out["cold"] = timed(*run, str(Path(tmp) / "cold"))
        clear_cache()
        out["warmup"] = timed("warmup")
        out["after_warmup"] = timed(*run, str(Path(tmp) / "after"))
        out["warm"] = timed(*run, str(Path(tmp) / "warm"))
    out["first_run_saving_pct"] = round(
        100.0 * (1.0 - out["after_warmup"]["wall_s"] / out["cold"]["wall_s"]), 1
    )
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
