"""Output of a cycle study: the results Dataset, atomic writing, the report and figures.

:mod:`.dataset` (study → xarray Dataset) · :mod:`.writer` (results folder, atomically) ·
:mod:`.report` (report.md) · :mod:`.figures` (one module per figure family).
"""

from .dataset import study_to_dataset
from .writer import (
    OutputWriteError,
    check_output_dir,
    clean_stale,
    is_result_folder,
    write_atomic,
    write_results,
)

__all__ = ["OutputWriteError", "check_output_dir", "clean_stale", "is_result_folder",
           "study_to_dataset", "write_atomic", "write_results"]
