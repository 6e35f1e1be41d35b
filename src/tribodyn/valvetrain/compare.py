"""Comparison of two valvetrain runs (e.g. explicit vs implicit tribology, paper Figs. 8–10).

:func:`compare_results` interpolates both presented cycles onto a common crank-angle grid
and reports, for tappet velocity, contact force and tappet acceleration, the largest
absolute difference, where it occurs (crank angle, with the contact force, u_e and cam
lift there), the RMS difference, and both relative to the quantity's range in the
reference run.
"""

from __future__ import annotations

import numpy as np

from .._validation import InputError
from .dynamics import ValvetrainResult

__all__ = ["compare_results", "COMPARED"]

COMPARED = ("tappet_velocity", "contact_force", "tappet_acceleration")


def compare_results(
    reference: ValvetrainResult, other: ValvetrainResult, quantities: tuple[str, ...] = COMPARED
) -> dict:
    """Differences other − reference over the presented cycle (dict per quantity)."""
    for name, r in (("reference", reference), ("other", other)):
        if not isinstance(r, ValvetrainResult) or not r.converged:
            raise InputError(f"{name} must be a converged ValvetrainResult")
    c = reference.crank_angle
    out = {}
    for q in quantities:
        a = getattr(reference, q)
        b = np.interp(c, other.crank_angle, getattr(other, q))
        d = b - a
        k = int(np.argmax(np.abs(d)))
        rng = float(np.ptp(a)) or 1.0
        out[q] = {
            "max_abs_difference": float(abs(d[k])),
            "max_difference_crank_deg": float(c[k]),
            "relative_to_range": float(abs(d[k]) / rng),
            "rms_difference": float(np.sqrt(np.mean(d * d))),
            "contact_force_there_N": float(reference.contact_force[k]),
            "entrainment_speed_there_m_s": float(reference.entrainment_speed[k]),
            "cam_lift_there_m": float(reference.cam_lift[k]),
        }
    return out
