"""Line-contact solvers: dry (coated) contact and mixed elastohydrodynamic lubrication."""

from .dry import DryContactResult, solve_dry_contact
from .ehl import EHLOptions, EHLResult, TransientEHL, solve_ehl

__all__ = [
    "DryContactResult",
    "EHLOptions",
    "EHLResult",
    "TransientEHL",
    "solve_dry_contact",
    "solve_ehl",
]
