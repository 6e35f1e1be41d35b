"""Every registered output variable: the union of the study, sweep and engine tables
(:mod:`~tribodyn.workflow.variables`; each table imports the base, none imports this)."""

from __future__ import annotations

from . import variables_engine, variables_study, variables_sweep
from .variables import Variable

__all__ = ["registry"]


def registry() -> tuple[Variable, ...]:
    """Every registered variable (a name may occur in several tables, with one unit)."""
    rows = (*variables_study.ALL, *variables_sweep.ALL, *variables_engine.ALL)
    return tuple({id(v): v for v in rows}.values())  # the sweep reuses study rows
