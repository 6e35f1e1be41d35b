"""tribodyn — tribo-dynamics of coated cam–flat-tappet contacts.

Valvetrain multi-body dynamics drive a transient mixed-EHL line-contact solver that
predicts pressure, film, asperity load, friction and power loss over the cam cycle for
uncoated and coated (DLC, WC-C) tappets. Method after Andreou et al., Appl. Sci. 13 (2023)
7815. All quantities are SI.
"""

# The names below load on first use (PEP 562), so that importing tribodyn does not import
# numpy: the command line sets its BLAS thread environment first (tribodyn._threads).
import importlib as _importlib
from typing import TYPE_CHECKING

from ._kernel_cache import refresh as _refresh_kernel_cache
from ._version import __version__

_refresh_kernel_cache()  # before any compiled kernel loads from numba's cache

#: public name → module that defines it
_EXPORTS = {
    "InputError": "._validation",
    "DryContactResult": ".contact.dry",
    "solve_dry_contact": ".contact.dry",
    "EHLOptions": ".contact.ehl",
    "EHLResult": ".contact.ehl",
    "ThermalEHLResult": ".contact.ehl",
    "ThermalOptions": ".contact.ehl",
    "ThermalTransientEHL": ".contact.ehl",
    "TransientEHL": ".contact.ehl",
    "solve_ehl": ".contact.ehl",
    "solve_thermal_ehl": ".contact.ehl",
    "Roughness": ".physics.asperity",
    "greenwood_tripp": ".physics.asperity",
    "DeformationOperator": ".physics.elasticity",
    "ThermalBody": ".physics.heat_conduction",
    "ThermalProperties": ".physics.heat_conduction",
    "hertz_line_contact": ".physics.hertz",
    "Lubricant": ".physics.lubricant",
    "Body": ".physics.materials",
    "Coating": ".physics.materials",
    "Material": ".physics.materials",
    "reduced_modulus": ".physics.materials",
    "SubsurfaceStress": ".physics.stress",
    "subsurface_stress": ".physics.stress",
    "ThermalLubricant": ".physics.thermal_oil",
}

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


#: subpackages imported on first attribute use (``tribodyn.physics``); not ``cli``, whose
#: import sets the BLAS thread environment
_SUBPACKAGES = frozenset(
    {"config", "contact", "cycle", "output", "physics", "topography", "valvetrain", "workflow"}
)


def __getattr__(name: str):
    if name in _SUBPACKAGES:
        return _importlib.import_module(f".{name}", __name__)  # binds it in globals()
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'tribodyn' has no attribute {name!r}")
    value = getattr(_importlib.import_module(module, __name__), name)
    globals()[name] = value  # later look-ups skip this function
    return value


def __dir__():
    return sorted(set(globals()) | set(_EXPORTS) | _SUBPACKAGES)


if TYPE_CHECKING:
    from ._validation import InputError
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
