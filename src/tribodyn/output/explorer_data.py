"""Reading result folders for the interactive page (:mod:`.explorer`): a cycle study's
(``tribodyn run``: results.nc with ``crank_angle``), an engine study's (``tribodyn
engine``: results.nc with ``engine_crank``) and a design sweep's (``tribodyn sweep``:
sweep.nc) folder, with their summary.json and case file; display names of the surface sets.

Reads files only: no solver is called and no case is built.
"""

from __future__ import annotations

import json
import re
import tomllib
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from .._typing import PathLike
from .._validation import InputError

__all__ = ["Result", "load_result", "set_display_names", "display_name"]

_MATERIAL_NAMES = {"dlc": "DLC", "wcc": "WC-C", "steel": "steel"}


def display_name(name: str) -> str:
    """A surface set's name made readable when its case gives no label: ``dlc_4um`` →
    ``DLC 4 µm``, ``wcc_1um`` → ``WC-C 1 µm``; other names are returned as they are."""
    m = re.fullmatch(r"([A-Za-z-]+)_(\d+(?:[.p]\d+)?)(um|nm)", name)
    if m is None:
        return name
    mat = _MATERIAL_NAMES.get(m.group(1).lower(), m.group(1))
    unit = "µm" if m.group(3) == "um" else "nm"
    return f"{mat} {m.group(2).replace('p', '.')} {unit}"


def set_display_names(case_text: str | None, names: Iterable[str]) -> dict[str, str]:
    """Display names of the surface sets ``names`` from a case file's text: the coating
    material's ``label`` (or key) and thickness in µm, ``uncoated`` without a coating, as
    the cycle study labels them; :func:`display_name` where the case does not say."""
    out = {str(n): display_name(str(n)) for n in names}
    if not case_text:
        return out
    try:
        doc = tomllib.loads(case_text)
    except tomllib.TOMLDecodeError:
        return out
    materials = doc.get("materials", {}) if isinstance(doc.get("materials"), dict) else {}
    for s in doc.get("surface_sets", []) or []:
        if not isinstance(s, dict) or str(s.get("name")) not in out:
            continue
        coat, t = s.get("coating"), s.get("coating_thickness")
        if not coat:
            out[str(s["name"])] = "uncoated"
        elif isinstance(t, int | float):
            m = materials.get(coat, {}) if isinstance(materials.get(coat), dict) else {}
            out[str(s["name"])] = f"{m.get('label') or coat} {t * 1e6:.3g} µm"
    return out


@dataclass
class Result:
    """One result folder: ``kind`` is ``"run"``, ``"engine"`` or ``"sweep"``; ``ds`` its
    Dataset (loaded into memory, the file closed); ``case_text`` the case as run (a
    sweep's base case); ``labels`` the display names of its surface sets."""

    path: Path
    kind: str
    label: str
    ds: Any
    summary: dict = field(default_factory=dict)
    case_text: str = ""
    labels: dict[str, str] = field(default_factory=dict)

    @property
    def sets(self) -> list[str]:
        dim = "engine_set" if self.kind == "engine" else "surface_set"
        if dim not in self.ds.coords:
            return []
        return [str(v) for v in self.ds[dim].values]

    @property
    def reference(self) -> str | None:
        """The reference (first uncoated) set the coatings are compared with."""
        ref = self.summary.get("reference_set") or (
            self.summary.get("engine", {}).get("reference_set")
        )
        ref = ref or self.ds.attrs.get("reference_set")
        sets = self.sets
        return str(ref) if ref in sets else (sets[0] if sets else None)

    def set_summary(self, name: str) -> dict:
        """summary.json's block of the surface set ``name`` (empty if none)."""
        block = self.summary.get("engine", self.summary).get("surface_sets", {})
        return block.get(name, {}) if isinstance(block, dict) else {}


def _read_text(path: Path) -> str:
    try:
        return path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return ""


#: Variables of a run's or engine's results.nc that the explorer does not show (the
#: profiles and the stress maps): not loaded.
_NOT_SHOWN = ("pressure", "film", "profile_x", "stress_map_von_mises")


def load_result(path: PathLike, label: str | None = None, ds: Any = None) -> Result:
    """The result folder ``path`` (module docstring). Raises :class:`InputError` naming
    the folder if it holds no tribodyn result. ``ds``: the Dataset of its results.nc
    when it is already in memory (the one just written there), not read again."""
    import xarray as xr

    p = Path(path)
    if not p.is_dir():
        raise InputError(f"RESULT {str(p)!r}: not a folder (give a result folder of tribodyn)")
    label = label or p.resolve().name
    if ds is None and (p / "sweep.nc").is_file():
        with xr.open_dataset(p / "sweep.nc", engine="h5netcdf") as ds:
            ds = ds.load()
        text = _read_text(p / "base_case.toml") or str(ds.attrs.get("base_case_toml", ""))
        return _labelled(Result(p, "sweep", label, ds, {}, text))
    if ds is not None:
        ds = ds[[v for v in ds.data_vars if v not in _NOT_SHOWN]]
    elif not (p / "results.nc").is_file():
        raise InputError(
            f"RESULT {str(p)!r}: no results.nc or sweep.nc (give a folder written by "
            "tribodyn run, engine or sweep)"
        )
    else:
        with xr.open_dataset(p / "results.nc", engine="h5netcdf") as ds:
            ds = ds[[v for v in ds.data_vars if v not in _NOT_SHOWN]].load()
    try:
        summary = json.loads(_read_text(p / "summary.json") or "{}")
    except json.JSONDecodeError:
        summary = {}
    text = _read_text(p / "case.toml") or str(ds.attrs.get("case_toml", ""))
    if "engine_crank" in ds.coords:
        return _labelled(Result(p, "engine", label, ds, summary, text))
    if "crank_angle" not in ds.coords:
        raise InputError(f"RESULT {str(p)!r}: results.nc holds neither a run nor an engine")
    r = _labelled(Result(p, "run", label, ds, summary, text))
    if "surface_label" in ds:
        r.labels.update(zip(r.sets, (str(v) for v in ds["surface_label"].values)))
    return r


def _labelled(r: Result) -> Result:
    """``r`` with the display names of its sets from its case (:func:`set_display_names`)."""
    r.labels = set_display_names(r.case_text, r.sets)
    return r


def unique_labels(paths: Iterable[PathLike]) -> list[str]:
    """Labels of the result folders ``paths``: their names, with as many parent folders
    as make them unique."""
    parts = [Path(p).resolve().parts for p in paths]
    for k in range(1, max((len(q) for q in parts), default=1) + 1):
        labels = ["/".join(q[-k:]) for q in parts]
        if len(set(labels)) == len(labels):
            return labels
    return [str(Path(p)) for p in paths]


def decimate(x: ArrayLike, y: ArrayLike, max_points: int = 1500) -> tuple[np.ndarray, np.ndarray]:
    """``x``, ``y`` as float32 with at most about ``max_points`` samples (every k-th; the
    last sample kept): a page of a few MB for several runs at full resolution."""
    xa = np.asarray(x, float)
    ya = np.asarray(y, float)
    if xa.size > max_points:
        k = int(np.ceil(xa.size / max_points))
        idx = np.unique(np.r_[np.arange(0, xa.size, k), xa.size - 1])
        xa, ya = xa[idx], ya[idx]
    return xa.astype(np.float32), ya.astype(np.float32)
