"""Case files: TOML input validated with pydantic, and builders of tribodyn objects.

Modules: :mod:`.schema` (one model per TOML section, with units and ranges) ·
:mod:`.case` (:class:`Case`, :class:`SurfaceSet`, :func:`load_case`, bundled cases) ·
:mod:`.errors` (one readable line per problem) · :mod:`.paths` (dotted key paths with
selectors) · :mod:`.sweep` (sweep files). Usage::

    from tribodyn.config import load_case
    from tribodyn.config.build import build
    case = load_case()                      # the bundled paper case
    built = build(load_case("my_case.toml"))
    cam, params = built.cam, built.valvetrain
    for s in built.surface_sets:            # SurfaceSet(name, bodies, roughness, ς, …)
        r = solve_ehl(w, R, ue, us, s.bodies, built.lubricant, s.roughness,
                      options=built.set(s.name).options)
"""

from . import case as _case
from . import schema as _schema
from .case import *  # noqa: F403 (the names in its __all__)
from .errors import format_validation_error
from .paths import PathError, parse_path, set_path
from .schema import *  # noqa: F403 (the names in its __all__)
from .sweep import SweepPoint, SweepSpec, bundled_sweeps, load_sweep

#: the public names of :mod:`.case` and :mod:`.schema`, and a few of the others
__all__ = [
    *_case.__all__,
    *_schema.__all__,
    "format_validation_error",
    "PathError",
    "parse_path",
    "set_path",
    "SweepSpec",
    "SweepPoint",
    "load_sweep",
    "bundled_sweeps",
]
