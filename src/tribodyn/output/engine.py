"""Writing an engine valvetrain study (:mod:`tribodyn.workflow.engine`): results.nc
(camshaft torque traces with units and descriptions), summary.json (``engine``: per
surface set the engine friction energy per cycle, the valvetrain FMEP, mean power and
torque, the parts, per camshaft), case.toml, the engine figures and the report
(report.md, and report.html with interactive traces; :mod:`.report_engine`),
atomically."""

from __future__ import annotations

from pathlib import Path

from .. import _json
from .._safe_write import atomic_write, atomic_write_with
from .._typing import PathLike
from .writer import _write_case, write_atomic

__all__ = ["write_engine_results"]


def write_engine_results(
    study, out_dir: PathLike, *, figures: bool = True, report: bool = True
) -> dict:
    """Write results.nc, summary.json, case.toml, the figures and the report into
    ``out_dir`` (the rules of :func:`~tribodyn.output.writer.write_atomic`). Returns
    ``{"summary": …, "figures": [names], "path": out_dir}``."""
    ds = study.to_dataset()
    summ = {  # summary.json
        "case": study.case.name,
        "engine": study.summary(),
        "warnings": list(study.warnings),
        "runtime_s": study.runtime_s,
        "timings": study.timings,
    }
    names: list[str] = []
    labels = dict(study.labels)  # display names of the sets (``DLC 4 µm``, ``uncoated``)

    def writer(tmp: Path) -> None:
        atomic_write_with(tmp / "results.nc", ds.to_netcdf)
        atomic_write(tmp / "summary.json", _json.dumps(summ, indent=1) + "\n")
        _write_case(study.case, tmp)
        if figures:
            from .figures.engine import engine_figures

            names.extend(p.name for p in engine_figures(ds, tmp, labels=labels))
        if report:
            from .explorer import write_report_html
            from .report_engine import engine_report_text

            text = engine_report_text(study, ds, summ, names, labels)
            atomic_write(tmp / "report.md", text)
            write_report_html(text, tmp)

    path = write_atomic(Path(out_dir), writer, meta={"kind": "engine", "case": study.case.name})
    return {"summary": summ, "figures": names, "path": path}
