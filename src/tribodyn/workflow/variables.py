"""The registry of output variables: every variable that tribodyn writes to ``results.nc``,
to a sweep point's file or to ``sweep.nc`` is named, given its dimensions, units and
description, and told how it is extracted from its source, in one table.

A :class:`Variable` is one row: ``name``, ``dims``, ``units`` (UDUNITS strings, ``"1"``
for dimensionless numbers, counts and 0/1 flags; ``None`` only for text), ``description``
(written as the netCDF ``long_name``) and ``extract`` (a function of the source object:
the study, a sweep point's values, …). A :class:`Group` is a list of rows written together,
with the condition under which they exist (e.g. only in a thermal study).
:func:`build` iterates groups and writes their variables into a Dataset; it is the only
place where an output variable's attributes are made.

The tables are in :mod:`~tribodyn.workflow.variables_study` (the study Dataset, including
the thermal, stress and engineering variables),
:mod:`~tribodyn.workflow.variables_sweep` (sweep points and the combined sweep) and
:mod:`~tribodyn.workflow.variables_engine` (an engine study's Dataset). The
registry lives in ``workflow`` so that the sweep points (workflow) and the results
Dataset (output) share it without an upward import. A name used in several tables has
the same units everywhere (``tests/test_variables.py``).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import xarray as xr

__all__ = ["Variable", "Group", "build", "registry", "number"]


@dataclass(frozen=True)
class Variable:
    """One output variable.

    ``dims`` is ``None`` for a variable whose dimensions are given when it is built (the
    axes of a sweep). ``coord`` makes it a coordinate; ``dtype`` converts the extracted
    values (e.g. ``np.int8`` for flags); ``attrs`` are further netCDF attributes (CF
    ``flag_values``/``flag_meanings``)."""

    name: str
    dims: tuple[str, ...] | None
    units: str | None
    description: str
    extract: Callable[[Any], Any] = field(repr=False, compare=False)
    dtype: Any = None
    coord: bool = False
    attrs: Mapping[str, str] = field(default_factory=dict)

    def attributes(self) -> dict[str, str]:
        """The netCDF attributes: ``units`` (if any), ``long_name``, then ``attrs``."""
        a = {} if self.units is None else {"units": self.units}
        return {**a, "long_name": self.description, **self.attrs}

    def make(self, source, dims: tuple[str, ...] | None = None) -> xr.Variable:
        """The variable's values extracted from ``source``, with its attributes."""
        d = self.dims if dims is None else dims
        if d is None:
            raise ValueError(f"variable {self.name!r} needs its dimensions")
        data = self.extract(source)
        data = np.asarray(data) if self.dtype is None else np.asarray(data, self.dtype)
        return xr.Variable(d, data, self.attributes())


def var(
    name: str,
    dims: str | tuple[str, ...] | None,
    units: str | None,
    description: str,
    extract: Callable[[Any], Any],
    **kw,
) -> Variable:
    """A :class:`Variable` (``dims`` may be one dimension name)."""
    return Variable(
        name, (dims,) if isinstance(dims, str) else dims, units, description, extract, **kw
    )


@dataclass(frozen=True)
class Group:
    """Variables written together: only where ``when(source)`` holds (always if None);
    all as coordinates if ``coords``."""

    variables: tuple[Variable, ...]
    when: Callable[[Any], bool] | None = None
    coords: bool = False

    def __iter__(self):
        return iter(self.variables)


def build(ds: xr.Dataset, groups: Iterable[Group], source) -> xr.Dataset:
    """Write every variable of ``groups`` that exists for ``source`` into ``ds``."""
    for g in groups:
        if g.when is not None and not g.when(source):
            continue
        for v in g.variables:
            target = ds.coords if (g.coords or v.coord) else ds
            target[v.name] = v.make(source)
    return ds


def number(v) -> float:
    """A scalar for a netCDF variable: None and non-finite → NaN, booleans → 0/1."""
    if v is None:
        return math.nan
    if isinstance(v, bool):
        return float(v)
    v = float(v)
    return v if math.isfinite(v) else math.nan


def registry() -> tuple[Variable, ...]:
    """Every registered variable (a name may occur in several tables, with one unit)."""
    from . import variables_engine, variables_study, variables_sweep

    # the sweep reuses study rows
    rows = (*variables_study.ALL, *variables_sweep.ALL, *variables_engine.ALL)
    return tuple({id(v): v for v in rows}.values())
