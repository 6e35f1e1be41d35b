"""Reading and writing areal topography files through SurfaceTopography.

SurfaceTopography reads some 40 instrument formats (Wyko/Bruker ``.opd``, Zygo ``.datx``
and MetroPro, Digital Surf ``.sur``, ISO 5436-2 ``.x3p``, Sensofar ``.plu``/``.plux``,
Keyence, Alicona, Gwyddion, netCDF, …) and detects the format from the file contents.
Everything returned here is converted to SI metres (lateral and height), so the
analysis never sees instrument units.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from .._safe_write import atomic_write_with, make_dirs
from .._typing import PathLike
from .._user_files import check_regular_file
from .._validation import InputError
from .errors import TopographyError, TopographyReadError

__all__ = ["read_topography", "write_topography", "supported_formats", "WRITERS"]

_NO_MAGIC = ("hgt",)

#: File suffix -> SurfaceTopography writer method (all write lateral size and unit).
WRITERS = {
    ".x3p": "to_x3p",
    ".nc": "to_netcdf",
    ".gwy": "to_gwy",
    ".txt": "to_matrix",
    ".asc": "to_matrix",
}


def supported_formats() -> list[tuple[str, str]]:
    """(identifier, name) of every format SurfaceTopography can read."""
    from SurfaceTopography.IO import readers

    return [(r.format(), r.name()) for r in readers]


def _unknown_format(path: Path) -> TopographyReadError:
    names = ", ".join(f for f, _ in supported_formats())
    return TopographyReadError(
        f"cannot read topography file '{path}': not a surface-topography format that "
        f"SurfaceTopography recognises (readable formats: {names})"
    )


def read_topography(
    path: PathLike,
    *,
    channel: int | None = None,
    physical_sizes: tuple[float, ...] | None = None,
    unit: str | None = None,
) -> Any:
    """Read an areal topography map and return it in metres.

    Parameters
    ----------
    path : file name of any format SurfaceTopography reads (format detected from content).
    channel : channel index for multi-channel files (default: the file's default channel,
        the height channel for optical profilers).
    physical_sizes : (Lx, Ly) in ``unit``; only for files without lateral calibration
        (e.g. ``.npy``, bare text matrices).
    unit : length unit of the file's numbers (``"m"``, ``"µm"``, ``"nm"``, …); only for
        files that do not store one.

    Returns
    -------
    SurfaceTopography ``Topography`` (areal map) or ``UniformLineScan`` (profile) in
    ``"m"``, possibly with undefined (masked) points; ``info["source"]`` holds the file
    name, format and channel.

    Raises
    ------
    TopographyReadError
        File missing, not a recognised format, damaged, or lacking lateral size / unit
        information that was not supplied.
    """
    from SurfaceTopography import open_topography
    from SurfaceTopography.Exceptions import CannotDetectFileFormat, MetadataAlreadyFixedByFile

    path = Path(path)
    try:  # no pipes or devices (the format readers would wait or read without end)
        check_regular_file(path, "topography file")
    except InputError as exc:
        raise TopographyReadError(str(exc)) from None
    try:
        reader = open_topography(str(path))
    except CannotDetectFileFormat:
        raise _unknown_format(path) from None
    except Exception as exc:  # damaged files make readers fail in many ways
        raise TopographyReadError(
            f"cannot read topography file '{path}': {type(exc).__name__}: {exc}"
        ) from None

    fmt = reader.name()
    if reader.format() == "sdf":
        _check_sdf_complete(path)
    # Readers without file magic (e.g. NASA SRTM .hgt) accept almost any file.
    if reader.format() in _NO_MAGIC and path.suffix.lower().lstrip(".") != reader.format():
        raise _unknown_format(path)
    channels = reader.channels
    if channel is None:
        ch = reader.default_channel
    else:
        if not 0 <= channel < len(channels):
            raise TopographyReadError(
                f"'{path}' has {len(channels)} channel(s) (0…{len(channels) - 1}); "
                f"channel {channel} does not exist"
            )
        ch = channels[channel]
    if ch.dim not in (1, 2):
        raise TopographyReadError(
            f"'{path}' ({fmt}) channel '{ch.name}' has {ch.dim} "
            "dimensions: a profile or an areal map is needed"
        )
    # a "map" of one line (SDF, SUR, … store profiles so) is a profile
    single_line = (
        ch.dim == 2
        and ch.nb_grid_pts is not None
        and min(ch.nb_grid_pts) == 1
        and max(ch.nb_grid_pts) >= 3
    )
    if ch.dim == 2 and not single_line and ch.nb_grid_pts is not None and min(ch.nb_grid_pts) < 3:
        raise TopographyReadError(
            f"'{path}' read as {fmt} has only {ch.nb_grid_pts[0]} × {ch.nb_grid_pts[1]} "
            "points: not a usable topography map"
        )

    if ch.nb_grid_pts is not None:  # before the heights are read
        from .filtering import check_map_size

        try:
            check_map_size(ch.nb_grid_pts, f"'{path}' ({fmt})")
        except TopographyError as exc:
            raise TopographyReadError(str(exc)) from None
    kwargs: dict[str, Any] = {}
    if physical_sizes is not None:
        if ch.physical_sizes is not None:
            raise TopographyReadError(
                f"'{path}' already stores its lateral size {tuple(ch.physical_sizes)} "
                f"{ch.unit}; do not pass physical_sizes"
            )
        try:
            sizes = tuple(float(s) for s in np.atleast_1d(physical_sizes))
        except (TypeError, ValueError):
            sizes = ()
        if len(sizes) not in (1, 2) or not all(np.isfinite(sizes)) or min(sizes) <= 0:
            raise TopographyReadError(
                f"physical_sizes must be one or two positive lengths (got {physical_sizes!r})"
            )
        kwargs["physical_sizes"] = (
            sizes[0] if ch.dim == 1 else (sizes if len(sizes) == 2 else sizes * 2)
        )
    elif ch.physical_sizes is None:
        raise TopographyReadError(
            f"'{path}' ({fmt}) has no lateral calibration: give its size and unit "
            "(physical_sizes and unit; CLI: --size LX LY --unit UNIT)"
        )
    if unit is not None:
        from SurfaceTopography.Support.UnitConversion import length_units

        if unit not in length_units:
            raise TopographyReadError(
                f"unit must be a length unit ({', '.join(length_units)}) (got {unit!r})"
            )
        if ch.unit is not None:
            raise TopographyReadError(
                f"'{path}' already stores its unit ({ch.unit}); do not pass unit"
            )
        kwargs["unit"] = unit
    elif ch.unit is None:
        raise TopographyReadError(
            f"'{path}' ({fmt}) does not store a length unit: give unit (e.g. 'µm'; CLI: --unit)"
        )
    try:
        topo = ch.topography(**kwargs)
        topo = topo.to_unit("m")
    except MetadataAlreadyFixedByFile as exc:
        raise TopographyReadError(f"'{path}': {exc}") from None
    except Exception as exc:  # readers raise many kinds of errors on damaged files
        raise TopographyReadError(
            f"cannot read topography data of '{path}': {type(exc).__name__}: {exc}"
        ) from None
    # Materialise once (later steps read the heights several times); non-finite values
    # are masked as undefined.
    from SurfaceTopography import Topography, UniformLineScan

    heights = np.ma.masked_invalid(topo.heights())
    info = {"source": {"file": str(path), "format": reader.format(), "channel": ch.name}}
    sizes = tuple(float(s) for s in np.atleast_1d(topo.physical_sizes))
    if not all(np.isfinite(sizes)) or min(sizes) <= 0:
        raise TopographyReadError(f"'{path}': invalid lateral size {sizes} in the file")
    if heights.count() == 0:
        raise TopographyReadError(f"'{path}': no measured (defined) height in the file")
    if single_line:
        axis = 0 if heights.shape[0] > 1 else 1
        heights, sizes = heights.reshape(-1), (sizes[axis],)
    if topo.dim == 1 or single_line:
        if heights.size < 3:
            raise TopographyReadError(
                f"'{path}' ({fmt}) holds a profile of only {heights.size} points"
            )
        return UniformLineScan(
            heights, sizes[0], periodic=bool(topo.is_periodic), unit="m", info=info
        )
    return Topography(heights, sizes, periodic=bool(topo.is_periodic), unit="m", info=info)


def _check_sdf_complete(path: Path) -> None:
    """An ASCII ISO 25178-71 file ends its data with a line "*": a file cut short (a copy
    interrupted, a disk full) would otherwise lose its last heights silently."""
    with open(path, "rb") as f:
        head = f.read(8)
        if not head.startswith((b"aISO", b"aBCR")):
            return  # binary variant: sizes are checked
        f.seek(0)
        markers = sum(1 for line in f if line.strip() == b"*")
    if markers < 2:
        raise TopographyReadError(
            f"'{path}' (ISO 25178-71 SDF, text) is truncated: the data "
            "section has no closing '*' line"
        )


def write_topography(topography: Any, path: PathLike) -> Path:
    """Write a topography map with SurfaceTopography's writers, chosen by suffix.

    ``.x3p`` (ISO 5436-2), ``.nc`` (netCDF), ``.gwy`` (Gwyddion) or ``.txt``/``.asc``
    (text matrix with size and unit header). Lateral size and unit are stored, so the
    file reads back with :func:`read_topography` unchanged.
    """
    path = Path(path)
    method = WRITERS.get(path.suffix.lower())
    if method is None:
        raise TopographyReadError(
            f"cannot write '{path}': supported suffixes are {', '.join(sorted(WRITERS))}"
        )
    make_dirs(path.parent)
    return atomic_write_with(
        path, lambda tmp: getattr(topography, method)(str(tmp)), keep_suffix=True
    )
