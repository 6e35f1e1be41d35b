"""Writing a cycle study: results.nc, summary.json, case.toml, figures and report.md, into
one folder, atomically.

Everything goes to a temporary folder next to the target, which then replaces the target
folder in one rename (the previous results are kept until then).
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
from pathlib import Path

from .dataset import study_to_dataset

__all__ = ["write_atomic", "write_results"]


def write_atomic(target: Path, writer) -> Path:
    """Call ``writer(tmpdir)`` to fill a fresh folder, then replace ``target`` with it.

    If ``writer`` raises, ``target`` is left exactly as it was.
    """
    target = Path(target).resolve()
    target.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{target.name}.tmp-", dir=target.parent))
    try:
        writer(tmp)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    old = None
    if target.exists():
        old = target.with_name(f".{target.name}.old-{os.getpid()}")
        if old.exists():
            shutil.rmtree(old)
        target.rename(old)
    try:
        tmp.rename(target)
    except BaseException:
        if old is not None:
            old.rename(target)
        raise
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)
    return target


def write_results(study, out_dir, *, figures=True, report=True) -> dict:
    """Write results.nc, summary.json, case.toml, figures and report.md atomically into
    ``out_dir``. Returns ``{"summary": …, "figures": {name: path}}``."""
    ds = study_to_dataset(study)
    summ = study.analyse().summary
    written = {}

    def writer(tmp: Path):
        enc = {v: {"compression": "gzip", "compression_opts": 4}
               for v in ("profile_x", "pressure", "film")}
        ds.to_netcdf(tmp / "results.nc", engine="h5netcdf", encoding=enc)
        (tmp / "summary.json").write_text(json.dumps(summ, indent=2))
        study.case.write_toml(tmp / "case.toml")
        figs = {}
        if figures:
            from .figures import make_figures
            figs = make_figures(ds, tmp)
        if report:
            from .report import write_report
            write_report(study, ds, figs, tmp / "report.md")
        written.update(figures=figs)

    write_atomic(Path(out_dir), writer)
    return {"summary": summ, **written}
