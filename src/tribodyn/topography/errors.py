"""Errors of the topography analysis; all are :class:`tribodyn.InputError` (``ValueError``)."""

from __future__ import annotations

from .._validation import InputError

__all__ = ["TopographyError", "TopographyReadError", "BandLimitError", "InsufficientDataError"]


class TopographyError(InputError):
    """A measured or synthetic topography cannot be analysed as requested."""


class TopographyReadError(TopographyError):
    """The file cannot be read as an areal topography (missing, unknown format, damaged,
    line scan, no lateral calibration)."""


class BandLimitError(TopographyError):
    """The band-pass limits lie outside what the measurement resolves."""


class InsufficientDataError(TopographyError):
    """Too few defined points (or grid points) for a meaningful analysis."""
