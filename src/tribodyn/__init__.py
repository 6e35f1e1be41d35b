"""tribodyn — tribo-dynamics of coated cam–flat-tappet contacts.

Valvetrain multi-body dynamics drive a transient mixed-EHL line-contact solver that
predicts pressure, film, asperity load, friction and power loss over the cam cycle for
uncoated and coated (DLC, WC-C) tappets. Method after Andreou et al., Appl. Sci. 13 (2023)
7815. All quantities are SI.
"""

import os as _os
import sys as _sys

if "numpy" not in _sys.modules:
    # The solvers' dense matrices are small (a few hundred nodes): multi-threaded BLAS
    # costs several times the single-threaded time on them, and a runtime limit does not
    # remove that overhead. Imported before numpy, tribodyn therefore asks for one BLAS
    # thread unless the environment says otherwise.
    for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        _os.environ.setdefault(_var, "1")

from ._validation import InputError
from ._version import __version__
from .contact.dry import DryContactResult, solve_dry_contact
from .contact.ehl import (
    EHLOptions,
    EHLResult,
    ThermalEHLResult,
    ThermalOptions,
    ThermalTransientEHL,
    TransientEHL,
    solve_ehl,
    solve_thermal_ehl,
)
from .physics.asperity import Roughness, greenwood_tripp
from .physics.elasticity import DeformationOperator
from .physics.heat_conduction import ThermalBody, ThermalProperties
from .physics.hertz import hertz_line_contact
from .physics.lubricant import Lubricant
from .physics.materials import Body, Coating, Material, reduced_modulus
from .physics.stress import SubsurfaceStress, subsurface_stress
from .physics.thermal_oil import ThermalLubricant

__all__ = [
    "Body",
    "Coating",
    "DeformationOperator",
    "DryContactResult",
    "EHLOptions",
    "EHLResult",
    "InputError",
    "Lubricant",
    "Material",
    "Roughness",
    "TransientEHL",
    "greenwood_tripp",
    "hertz_line_contact",
    "reduced_modulus",
    "solve_dry_contact",
    "solve_ehl",
    "SubsurfaceStress",
    "subsurface_stress",
    "__version__",
    "ThermalBody",
    "ThermalEHLResult",
    "ThermalLubricant",
    "ThermalOptions",
    "ThermalProperties",
    "ThermalTransientEHL",
    "solve_thermal_ehl",
]
