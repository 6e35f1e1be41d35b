"""``tribodyn contact``: a quick single-point line-contact calculator (EHL or dry).

The cam is steel and the tappet carries the coating. Everything not given on the command
line comes from ``--case FILE`` (``--surface-set NAME`` of it), else from the bundled
default case (:data:`tribodyn.config.DEFAULT_CASE`, the one ``tribodyn run`` runs): its
lubricant, materials, ς, τ₀ and numerics, from one source. ``--help`` quotes the values of
that case (:func:`stated_defaults`). The table shows engineering units (µm, MPa);
``--json`` prints SI values with the unit in each key name (``central_film_m``,
``friction_N``, …). The computation is :func:`tribodyn.workflow.point.solve_point`; this
module parses options.

Exit codes: 0 solved and converged, 1 solved but not converged (results still printed),
2 bad input (message on stderr, no traceback).
"""

from __future__ import annotations

import dataclasses
import math
import re
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import typer
from rich.console import Console

from .. import _json
from .._validation import InputError
from .contact_options import prefixed, roughness_numbers, three_numbers
from .contact_table import _table
from .failure import fail
from .help_defaults import stating

__all__ = ["ContactRequest", "contact_command", "compute_contact", "stated_defaults"]

_LUB = "Lubricant (default: the \\[lubricant] of --case, else of the bundled case {case})"
_SURF = "Surfaces (cam: steel; tappet: coated or not)"
_NUM = "Numerics (default: the \\[numerics] of --case, else of {case})"


def _flag(name: str) -> str:  # a ContactRequest field's option: n_x → --n-x
    return "--" + name.replace("_", "-")


#: API argument names in error messages → the options that give them
_OPTION_OF = {
    **{n: _flag(n) for n in ("coating", "coating_material", "coating_thickness", "roughness")},
    **{n: _flag(n) for n in ("surface_set", "shear_coefficient", "load_per_length", "width")},
    "load": "load per length (--load / --width, or --load-per-length)",
    "radius": "--radius",
    "entrainment_speed": "--ue",
    "sliding_speed": "--us",
}


def _as_option(exc: InputError) -> InputError:
    """The message with the API argument names replaced by the CLI option names."""
    msg = str(exc)
    for arg, opt in sorted(_OPTION_OF.items(), key=lambda kv: -len(kv[0])):
        msg = re.sub(rf"(?<![\w-]){arg}(?![\w(])", opt, msg)
    return InputError(msg)


@dataclass(frozen=True)
class ContactRequest:
    """The options of ``tribodyn contact`` (values as typed; None: not given), built once
    from the command line or by a Python caller; :func:`compute_contact` solves it.

    ``coating`` and ``roughness`` are the option strings ``"E,NU,THICKNESS"`` and
    ``"ETA,SIGMA,BETA"`` (or ``"SIGMA"`` alone for the surface law). The lubricant
    options (``viscosity`` … ``viscosity_model``) and the numerics options (``n``,
    ``viscous_model``, ``limiting_shear``) of an EHL contact change the case's keys
    (:data:`CASE_KEYS`) through
    :meth:`~tribodyn.config.Case.updated`, so they are validated as in a case file;
    ``eyring_stress`` and ``limiting_shear_coefficient`` also set τ_E and Λ of the
    ``thermal``/``oil`` oil. A ``dry`` contact takes none of them (``n`` is its grid).
    """

    load: float | None = None
    load_per_length: float | None = None
    width: float | None = None
    radius: float | None = None
    ue: float | None = None
    us: float | None = None
    dry: bool = False
    coating: str | None = None
    coating_material: str | None = None
    coating_thickness: float | None = None
    roughness: str | None = None
    asperity_model: str | None = None
    surface_set: str | None = None
    case_file: Path | str | None = None
    shear_coefficient: float | None = None
    viscosity: float | None = None
    pressure_viscosity: float | None = None
    density: float | None = None
    eyring_stress: float | None = None
    limiting_shear_coefficient: float | None = None
    viscosity_model: str | None = None
    viscous_model: str | None = None
    limiting_shear: bool | None = None
    n: int | None = None
    thermal: bool = False
    oil: str | None = None
    inlet_temperature: float | None = None
    stress: bool = False

    def case_changes(self) -> dict[str, Any]:
        """The given lubricant and numerics options as case updates (dotted key → value)."""
        return {
            key: getattr(self, name)
            for name, key in CASE_KEYS.items()
            if getattr(self, name) is not None
        }


#: Option of :class:`ContactRequest` → the case key it changes.
CASE_KEYS = {
    "viscosity": "lubricant.viscosity",
    "pressure_viscosity": "lubricant.pressure_viscosity",
    "density": "lubricant.density",
    "eyring_stress": "lubricant.eyring_stress",
    "limiting_shear_coefficient": "lubricant.limiting_shear_coefficient",
    "viscosity_model": "lubricant.viscosity_model",
    "viscous_model": "numerics.viscous_model",
    "limiting_shear": "numerics.limiting_shear",
    "n": "numerics.n",
}


def _updated(case, changes: dict[str, Any]):
    """``case`` with the option changes applied (validated as a case file); an error
    names the option, then the case file's message for its key."""
    if not changes:
        return case
    try:
        return case.updated(changes)
    except InputError as exc:
        option = {key: _flag(name) for name, key in CASE_KEYS.items()}
        out = []
        for line in str(exc).splitlines():
            if line.startswith("invalid case"):
                continue
            key = line.strip().split(":", 1)[0]
            out.append(f"{option[key]} ({line.strip()})" if key in option else line.strip())
        raise InputError("; ".join(out)) from None


def compute_contact(request: ContactRequest | None = None, /, **options: Any) -> dict:
    """Solve one :class:`ContactRequest` (or its fields as keyword arguments, as typed on
    the command line).

    Raises :class:`~tribodyn.InputError` naming the offending option on bad input.
    """
    from ..config import load_case
    from ..config.build import build, options_for
    from ..physics.asperity import Roughness
    from ..physics.materials import Coating
    from ..workflow.point import point_surfaces, solve_point

    if request is None:
        request = ContactRequest(**options)
    elif options:
        raise TypeError("give a ContactRequest or its fields as keywords, not both")
    q = request
    built = build(load_case(q.case_file))  # None: the bundled default case, as tribodyn run
    case = built.case
    coat = rough = None
    if q.coating is not None:
        E, nu, t = three_numbers(q.coating, "--coating", "E [Pa], nu [-], thickness [m]")
        coat = prefixed("--coating", lambda: Coating(E=E, nu=nu, thickness=t))
    model = q.asperity_model or "surface"
    if model not in ("surface", "greenwood_tripp"):
        raise InputError(
            f"--asperity-model must be surface or greenwood_tripp (got {q.asperity_model!r})"
        )
    if q.roughness is not None:
        eta, sig, beta = roughness_numbers(q.roughness, model)
        rough = prefixed(
            "--roughness",
            lambda: Roughness(
                asperity_density=eta,
                rms=sig,
                summit_radius=beta,
                method=case.numerics.greenwood_tripp,
            ),
        )
    try:
        surfaces = point_surfaces(
            built,
            surface_set=q.surface_set,
            coating=coat,
            coating_material=q.coating_material,
            coating_thickness=q.coating_thickness,
            roughness=rough,
            shear_coefficient=q.shear_coefficient,
        )
    except InputError as exc:
        raise _as_option(exc) from None
    if q.asperity_model is not None and rough is None:
        raise InputError("--asperity-model needs --roughness (a case's set carries its own law)")
    if rough is not None and model == "surface":  # the default law, as in a case file
        from dataclasses import replace

        from ..config.measured_surface import typical_surface_law

        law = typical_surface_law(rough.rms, surfaces.bodies)
        surfaces = replace(surfaces, roughness=replace(rough, law=law))

    width = q.width if q.width is not None else case.cam_config.width
    _check_positive("--width", width, "m")
    if (q.load is None) == (q.load_per_length is None):
        raise InputError(
            "give exactly one of --load [N, total over --width] and --load-per-length [N/m]"
        )
    _check_positive("--load", q.load, "N")
    _check_positive("--load-per-length", q.load_per_length, "N/m")
    if q.load_per_length is not None:
        w = q.load_per_length
    else:
        assert q.load is not None  # exactly one of the two (checked above)
        w = q.load / width
    if q.radius is None:
        raise InputError("--radius [m] is required (reduced radius of curvature)")
    _check_positive("--radius", q.radius, "m")
    if q.n is not None and q.n < 32:
        raise InputError(f"--n must be >= 32 grid nodes (got {q.n})")
    if q.dry:
        _check_dry(q)
    lub = opts = None
    thermal_oil = None
    if not q.dry and (q.thermal or q.oil is not None or q.inlet_temperature is not None):
        thermal_oil = _thermal_oil(
            built,
            q.oil,
            q.inlet_temperature,
            {_flag(k): getattr(q, k) for k in _THERMAL_OIL_OPTIONS},
        )
    if not q.dry:  # the lubricant and numerics options: case updates, built once
        built = build(_updated(case, q.case_changes()))
        lub = built.lubricant
        opts = options_for(built, surfaces)
    if thermal_oil is not None:  # its shear law: the options given (validated just above)
        shear = {k: getattr(q, k) for k in _OIL_SHEAR if getattr(q, k) is not None}
        thermal_oil = dataclasses.replace(thermal_oil, **shear)
    try:
        r = solve_point(
            built,
            surfaces,
            load_per_length=w,
            radius=q.radius,
            width=width,
            entrainment_speed=q.ue,
            sliding_speed=q.us,
            dry=q.dry,
            # --oil/--inlet-temperature without --thermal: the oil at its inlet temperature
            lubricant=None if q.thermal else (thermal_oil or lub),
            options=opts,
            n=q.n,
            thermal_oil=thermal_oil if q.thermal else None,
            stress=q.stress,
        )
    except InputError as exc:
        raise _as_option(exc) from None
    return r


#: lubricant options refused with a --thermal/--oil oil (it brings its μ₀, α, ρ₀ and law)
_THERMAL_OIL_OPTIONS = ("viscosity", "pressure_viscosity", "density", "viscosity_model")
#: options that set the shear law of the --thermal/--oil oil (τ_E, Λ)
_OIL_SHEAR = ("eyring_stress", "limiting_shear_coefficient")

#: options of a lubricated contact, not for --dry (option → ContactRequest field)
_NOT_DRY = {
    "--thermal": "thermal",
    "--oil": "oil",
    "--inlet-temperature": "inlet_temperature",
    **{_flag(name): name for name in CASE_KEYS if name != "n"},
}


def _check_dry(q: ContactRequest) -> None:
    """A dry contact has no oil or film: the lubricant and EHL options are errors (``--n``
    is the dry grid)."""
    given = [
        opt
        for opt, name in _NOT_DRY.items()
        if (q.thermal if name == "thermal" else getattr(q, name) is not None)
    ]
    if given:
        raise InputError(
            f"{', '.join(given)}: not with --dry (a dry contact has no lubricant or film; "
            "drop them, or drop --dry for an EHL solution)"
        )


def _thermal_oil(built, oil, inlet_temperature, lub_options):
    """The oil of --oil/--inlet-temperature [°C], else the datasheet oil of the case
    (its BuiltCase ``built``)."""
    from ..config.schema_surfaces import OIL_KEYS
    from ..physics.limits import RangeError

    clash = [k for k, v in lub_options.items() if v is not None]
    if clash:
        raise InputError(
            f"{', '.join(clash)}: not with --thermal/--oil/--inlet-temperature "
            "(the oil comes from --oil or the case's [lubricant])"
        )
    to_kelvin = OIL_KEYS["inlet_temperature_c"]  # the case key's range and unit (°C)
    try:  # the oil checks the temperature; its error named as the option, in °C
        return _oil_at(built, oil, inlet_temperature, to_kelvin)
    except RangeError as exc:
        if inlet_temperature is None:
            raise
        raise to_kelvin.renamed(exc, "--inlet-temperature", inlet_temperature) from None


def _oil_at(built, oil, inlet_temperature, to_kelvin):
    """The thermal oil of :func:`_thermal_oil` (``to_kelvin``: the °C key's conversion)."""
    from ..physics.oils import OILS
    from ..physics.thermal_oil import ThermalLubricant

    if oil is not None:
        if oil not in OILS:
            raise InputError(f"--oil must be one of {', '.join(OILS)} (got {oil!r})")
        if inlet_temperature is None:
            raise InputError("--oil needs --inlet-temperature [°C] (the sump temperature)")
        sheet: dict[str, Any] = {k: v for k, v in OILS[oil].items() if k != "description"}
        return ThermalLubricant(to_kelvin.value(inlet_temperature), **sheet, name=oil)
    try:
        base = built.thermal_oil()
    except InputError:
        raise InputError(
            "--thermal needs an oil with a temperature: --oil 5W-30 "
            "--inlet-temperature 90, or a --case whose [lubricant] has "
            "inlet_temperature_c"
        ) from None
    if inlet_temperature is not None:
        return base.with_inlet_temperature(to_kelvin.value(inlet_temperature))
    return base


def _check_positive(option: str, value: float | None, unit: str) -> None:
    if value is not None and not (math.isfinite(value) and value > 0.0):
        raise InputError(f"{option} must be a finite number > 0 [{unit}] (got {value:g})")


def _option(flag: str, *, help: str, panel: str | None = None, **more: Any) -> Any:
    """The command's option ``flag``: None when not given (the case's value applies),
    listed under ``panel`` in ``--help``."""
    return typer.Option(None, flag, rich_help_panel=panel, help=help, **more)


def stated_defaults() -> dict[str, Any]:
    """The defaults ``tribodyn contact --help`` states, from the objects
    :func:`compute_contact` uses: the bundled default case (its lubricant, materials,
    first set's τ₀, EHL options), the ``--oil`` lubricant's field defaults and the dry
    solver's grid."""
    import inspect

    from ..config import load_case
    from ..config.build import build, options_for
    from ..contact.dry import solve_dry_contact
    from ..contact.ehl.grid import N_AUTO, N_MAX_AUTO
    from ..physics.oils import OILS
    from ..physics.thermal_oil import ThermalLubricant
    from ..workflow.point import point_surfaces

    built = build(load_case())
    case = built.case
    lub = built.lubricant
    surfaces = point_surfaces(built)
    opts = options_for(built, surfaces)
    oil = {f.name: f.default for f in dataclasses.fields(ThermalLubricant)}
    shear = ", ".join(
        f"{k} {m.boundary_shear_coefficient:g}"
        for k, m in case.materials.items()
        if m.boundary_shear_coefficient is not None
    )
    n_ehl = (
        f"{case.name}: {opts.n}"
        if opts.n is not None
        else f"automatic ({case.name}: numerics.n = {case.numerics.n}): {N_AUTO} nodes over "
        f"the contact, steady solves refined up to {N_MAX_AUTO}"
    )
    return {
        "case": case.name,
        "width": case.cam_config.width,
        "materials": ", ".join(case.materials),
        "shear": shear,
        "tau0": surfaces.boundary_shear_strength,
        # the lubricant options: the values of the case's lubricant keys they change
        **{k: getattr(lub, k) for k, key in CASE_KEYS.items() if key.startswith("lubricant.")},
        "oil_eyring_stress": oil["eyring_stress"],
        "oil_limiting_shear_coefficient": oil["limiting_shear_coefficient"],
        "viscous_model": opts.viscous_model,
        "limiting_shear": "on" if opts.limiting_shear else "off",
        "n_ehl": n_ehl,
        "n_dry": inspect.signature(solve_dry_contact).parameters["n"].default,
        "oils": ", ".join(OILS),
    }


#: the command's class: its --help quotes :func:`stated_defaults`
ContactCommand = stating(stated_defaults)


# ----------------------------------------------------------------------------- command
def contact_command(
    load: float | None = _option("--load", help="Normal load [N], total over --width."),
    load_per_length: float | None = _option(
        "--load-per-length", help="Normal load per unit length [N/m] (instead of --load)."
    ),
    width: float | None = _option(
        "--width", help="Contact width \\[m] (default: the case's cam.width; {case}: {width:g})."
    ),
    radius: float | None = _option("--radius", help="Reduced radius of curvature R \\[m]."),
    ue: float | None = _option("--ue", help="Entrainment speed u_e \\[m/s] (EHL; either sign)."),
    us: float | None = _option(
        "--us", help="Sliding speed u_s \\[m/s] (viscous friction; default 0)."
    ),
    dry: bool = typer.Option(False, "--dry", help="Dry (frictionless) contact instead of EHL."),
    coating: str | None = _option(
        "--coating",
        panel=_SURF,
        metavar="E,NU,THICKNESS",
        help="Tappet coating: E [Pa], ν, thickness \\[m].",
    ),
    coating_material: str | None = _option(
        "--coating-material",
        panel=_SURF,
        help="Tappet coating material: a key of the case's \\[materials] ({case}: {materials}).",
    ),
    coating_thickness: float | None = _option(
        "--coating-thickness", panel=_SURF, help="Coating thickness \\[m]."
    ),
    roughness: str | None = _option(
        "--roughness",
        panel=_SURF,
        metavar="[ETA,]SIGMA[,BETA]",
        help="Composite roughness: RMS \\[m] alone (summit density and radius from the "
        "typical ratios, as a case file's set with only rms), or summit density "
        "[1/m²], RMS \\[m], summit radius \\[m] (needed with greenwood_tripp) "
        "(default: smooth). The asperities follow --asperity-model.",
    ),
    asperity_model: str | None = _option(
        "--asperity-model",
        panel=_SURF,
        help="With --roughness: surface (default: the boundary-element law of a "
        "self-affine surface with its RMS and the typical spectrum, as in a case file) or "
        "greenwood_tripp (with its summit density and radius).",
    ),
    surface_set: str | None = _option(
        "--surface-set",
        panel=_SURF,
        help="Take bodies, roughness, ς and τ₀ from this surface set of the case (default "
        "case: --case, else {case}).",
    ),
    case_file: Path | None = _option(
        "--case",
        panel=_SURF,
        help="Case file (or bundled case name) for materials, lubricant, numerics and "
        "--surface-set (default: the bundled case {case}, as tribodyn run).",
    ),
    shear_coefficient: float | None = _option(
        "--shear-coefficient",
        panel=_SURF,
        help="Boundary shear coefficient ς of τ_b = τ₀ + ς p_a (default: the coating "
        "material's, else the tappet substrate's; {case}: {shear}, with τ₀ = {tau0:g} Pa "
        "of the case's first surface set).",
    ),
    viscosity: float | None = _option(
        "--viscosity", panel=_LUB, help="μ₀ [Pa·s] (default: {case}: {viscosity:g})."
    ),
    pressure_viscosity: float | None = _option(
        "--pressure-viscosity",
        panel=_LUB,
        help="α [1/Pa] (default: {case}: {pressure_viscosity:g}).",
    ),
    density: float | None = _option(
        "--density", panel=_LUB, help="ρ₀ \\[kg/m³] (default: {case}: {density:g})."
    ),
    eyring_stress: float | None = _option(
        "--eyring-stress",
        panel=_LUB,
        help="τ_E [Pa] (default: {case}: {eyring_stress:g}; with --oil: "
        "{oil_eyring_stress:g}, the typical value).",
    ),
    limiting_shear_coefficient: float | None = _option(
        "--limiting-shear-coefficient",
        panel=_LUB,
        help="Λ (default: {case}: {limiting_shear_coefficient:g}; with --oil: "
        "{oil_limiting_shear_coefficient:g}, the typical value).",
    ),
    viscosity_model: str | None = _option(
        "--viscosity-model",
        panel=_LUB,
        help="roelands or barus (default: {case}: {viscosity_model}).",
    ),
    viscous_model: str | None = _option(
        "--viscous-model",
        panel=_NUM,
        help="eyring or newtonian (default: {case}: {viscous_model}).",
    ),
    limiting_shear: bool | None = _option(
        "--limiting-shear/--no-limiting-shear",
        panel=_NUM,
        show_default=False,
        help="Cap viscous shear at Λp (default: {case}: {limiting_shear}).",
    ),
    n: int | None = _option(
        "--n", panel=_NUM, help="Grid nodes (default: EHL {n_ehl}; dry {n_dry})."
    ),
    thermal: bool = typer.Option(
        False,
        "--thermal",
        rich_help_panel=_LUB,
        help="Thermal EHL (film energy equation, conduction in "
        "cam and coated tappet); needs --oil and "
        "--inlet-temperature or a --case with a sump "
        "temperature.",
    ),
    oil: str | None = _option(
        "--oil",
        panel=_LUB,
        help="Bundled datasheet oil: {oils} (without "
        "--thermal: the isothermal EHL with this oil at --inlet-temperature).",
    ),
    inlet_temperature: float | None = _option(
        "--inlet-temperature", panel=_LUB, help="Oil supply (sump) temperature [°C]."
    ),
    stress: bool = typer.Option(
        False,
        "--stress",
        help="Also the subsurface stresses of cam and tappet (EHL only): peaks per body, "
        "safety factors against the case's strengths.",
    ),
    as_json: bool = typer.Option(False, "--json", help="Print a JSON object (SI units)."),
):
    """Single-point line contact: Hertz, EHL film, loads, friction and regime.

    The cam is steel, the tappet carries the coating. What no option gives comes from
    --case, else from the bundled case {case} (as tribodyn run): its lubricant,
    materials, ς, τ₀ and numerics. Examples:

      tribodyn contact --load 633 --radius 0.01 --ue 5 --us 2

      tribodyn contact --surface-set wcc_4um --load 633 --radius 0.01 --ue 5
      --us 2 --json

      tribodyn contact --dry --load 633 --radius 0.01 --coating-material dlc
      --coating-thickness 4e-6

      tribodyn contact --thermal --oil 5W-30 --inlet-temperature 90 --load 2400
      --radius 0.01 --ue 2 --us 2 --coating-material dlc --coating-thickness 4e-6

    Exit code 1 if the solver did not converge, 2 on bad input.
    """
    err = Console(stderr=True)
    options = locals()
    request = ContactRequest(
        **{f.name: options[f.name] for f in dataclasses.fields(ContactRequest)}
    )
    try:
        r = compute_contact(request)
    except InputError as exc:
        fail(err, exc)
    if as_json:
        sys.stdout.write(_json.dumps(r, indent=2, ensure_ascii=False) + "\n")
    else:
        console = Console()
        console.print(_table(r))
        style = "" if r["converged"] else "red"
        status = r["message"].split("; warning: ")[0]
        console.print(f"solver: {status}", markup=False, style=style, soft_wrap=True)
        for w in r.get("warnings", []):
            console.print(f"warning: {w}", markup=False, style="yellow", soft_wrap=True)
    if not r["converged"]:
        raise typer.Exit(code=1)
