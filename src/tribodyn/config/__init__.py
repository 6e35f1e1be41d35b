"""Case files: TOML input validated with pydantic, and builders of tribodyn objects.

Modules: :mod:`.schema` (one model per TOML section, with units and ranges) ·
:mod:`.case` (:class:`Case`, :class:`SurfaceSet`, :func:`load_case`, bundled cases) ·
:mod:`.errors` (one readable line per problem) · :mod:`.paths` (dotted key paths with
selectors) · :mod:`.sweep` (sweep files). Usage::

    from tribodyn.config import load_case
    case = load_case()                      # the bundled paper case
    case = load_case("my_case.toml")
    cam, params = case.cam(), case.valvetrain_parameters()
    for s in case.surface_sets():           # SurfaceSet(name, bodies, roughness, ς, …)
        r = solve_ehl(w, R, ue, us, s.bodies, case.lubricant(), s.roughness,
                      options=case.ehl_options(s))
"""

from .case import (
    CASES_DIR,
    DEFAULT_CASE,
    Case,
    SurfaceSet,
    bundled_cases,
    load_case,
    set_dotted,
    to_toml,
)
from .errors import format_validation_error
from .paths import PathError, get_path, parse_path, set_path
from .schema import (
    CAM_MODELS,
    AccelerationCamConfig,
    AuxiliaryFrictionConfig,
    CamshaftConfig,
    CaseInfo,
    CircularArcCamConfig,
    Engine,
    LobeConfig,
    LubricantConfig,
    MaterialConfig,
    MeasuredSurfaceConfig,
    Numerics,
    RoughnessConfig,
    SpringConfig,
    StrengthConfig,
    StressConfig,
    SurfaceSetConfig,
    TableCamConfig,
    TappetConfig,
    ValveConfig,
    Valvetrain,
)
from .sweep import SweepPoint, SweepSpec, bundled_sweeps, load_sweep

__all__ = [
    "Case",
    "SurfaceSet",
    "load_case",
    "bundled_cases",
    "DEFAULT_CASE",
    "CASES_DIR",
    "to_toml",
    "set_dotted",
    "format_validation_error",
    "CAM_MODELS",
    "CaseInfo",
    "Engine",
    "LobeConfig",
    "AuxiliaryFrictionConfig",
    "AccelerationCamConfig",
    "CircularArcCamConfig",
    "TableCamConfig",
    "Valvetrain",
    "LubricantConfig",
    "MaterialConfig",
    "MeasuredSurfaceConfig",
    "RoughnessConfig",
    "StrengthConfig",
    "StressConfig",
    "SurfaceSetConfig",
    "Numerics",
    "ValveConfig",
    "TappetConfig",
    "SpringConfig",
    "CamshaftConfig",
    "PathError",
    "parse_path",
    "set_path",
    "get_path",
    "SweepSpec",
    "SweepPoint",
    "load_sweep",
    "bundled_sweeps",
]
