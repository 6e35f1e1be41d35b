"""CPU time of writing report.html alone for a finished run (prints JSON).

    python benchmarks/bench_report_html.py RESULT_FOLDER [--repeat 7] [--profile]

RESULT_FOLDER is a folder written by ``tribodyn run`` (e.g. of the paper case). Its
results.nc is read once (:func:`~tribodyn.output.dataset.load_run_results`) and the
folder copied to a temporary one, where
:func:`~tribodyn.output.explorer.write_report_html` writes report.html from report.md
and the Dataset in memory, as ``tribodyn run`` does. The first call (Bokeh's imports
and first uses) is reported apart; then the median and all of ``--repeat`` calls' CPU
seconds (``time.process_time``: on a shared machine less noisy than the wall) and the
page's size. ``--profile``: one more call under cProfile, its heaviest functions.
"""

from __future__ import annotations

import argparse
import cProfile
import json
import pstats
import shutil
import statistics
import tempfile
import time
from pathlib import Path

from tribodyn.output.dataset import load_run_results
from tribodyn.output.explorer import write_report_html
from tribodyn.output.export import report_markdown


def cpu_seconds(fn) -> float:
    """CPU seconds of one call of ``fn``."""
    t0 = time.process_time()
    fn()
    return time.process_time() - t0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folder", type=Path)
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--profile", action="store_true")
    args = ap.parse_args()
    ds = load_run_results(args.folder / "results.nc")
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "run"
        shutil.copytree(args.folder, out)
        md = report_markdown(out)
        write = lambda: write_report_html(md, out, ds=ds)  # noqa: E731
        first = cpu_seconds(write)
        times = [cpu_seconds(write) for _ in range(args.repeat)]
        size = (out / "report.html").stat().st_size
        if args.profile:
            prof = cProfile.Profile()
            prof.runcall(write)
            pstats.Stats(prof).sort_stats("tottime").print_stats(15)
    print(
        json.dumps(
            {
                "first_cpu_s": round(first, 3),
                "median_cpu_s": round(statistics.median(times), 3),
                "cpu_s": [round(t, 3) for t in times],
                "page_bytes": size,
            }
        )
    )


if __name__ == "__main__":
    main()
