"""Line-contact solvers: dry (coated) contact and mixed elastohydrodynamic lubrication."""

from .dry import DryContactResult, solve_dry_contact

__all__ = ["DryContactResult", "solve_dry_contact"]
