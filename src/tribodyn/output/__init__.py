"""Output of a cycle study: the results Dataset, atomic writing, the report and figures.

:mod:`.dataset` (study → xarray Dataset) · :mod:`.writer` (results folder, atomically) ·
:mod:`.report` (report.md) · :mod:`.figures` (one module per figure family) ·
:mod:`.sweep` (a design sweep's sweep.nc, sweep_report.md and figures).
"""

from .dataset import study_to_dataset
from .sweep import write_sweep
from .writer import (
    OutputWriteError,
    check_output_dir,
    clean_stale,
    foreign_files,
    is_result_folder,
    write_atomic,
    write_results,
)

__all__ = [
    "OutputWriteError",
    "check_output_dir",
    "clean_stale",
    "foreign_files",
    "is_result_folder",
    "study_to_dataset",
    "write_atomic",
    "write_results",
    "write_sweep",
]
