"""Allowed ranges of the physical and numerical inputs, defined once.

The constructors of the physics objects (:class:`~tribodyn.Material`,
:class:`~tribodyn.Lubricant`, :class:`~tribodyn.Roughness`, …), the solver options and the
valvetrain parameters check their arguments against these limits. Each value is checked
once, where it enters: a case-file key passed to such a constructor is checked there (its
:class:`RangeError` names the argument; the case names the key), a key no constructor
checks is checked by the case-file schema (``config/schema_fields.py``); both describe the
range from the same :class:`Limit`.

The ranges are wide: they exclude what is physically meaningless or outside what the
models describe, not unusual designs. Each limit says why (``why``); docs/case-files.md
lists them per key.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from numbers import Real

from .._validation import InputError, _fmt, check_int, check_real

#: the checking functions and Roelands' constants; every Limit below is appended at the end
__all__ = [
    "Limit",
    "RangeError",
    "check_fields",
    "unchecked",
    "ROELANDS_LN_MU_INF",
    "ROELANDS_MU_INF",
]

#: ln μ∞ of Roelands' law, μ∞ = exp(−9.67) = 6.31e-5 Pa·s; μ₀ must exceed μ∞ (paper Eq. 3).
ROELANDS_LN_MU_INF = -9.67
ROELANDS_MU_INF = math.exp(ROELANDS_LN_MU_INF)


def _num(v: float) -> str:
    return f"{v:.6g}"


@dataclass(frozen=True)
class Limit:
    """An allowed range: bounds ``gt`` (>), ``ge`` (≥), ``lt`` (<), ``le`` (≤), a unit,
    whether the value must be an integer, the reason for the bounds, and ``auto``: a value
    outside the bounds that stands for an automatic choice (a case file's 0 nodes)."""

    unit: str = ""
    gt: float | None = None
    ge: float | None = None
    lt: float | None = None
    le: float | None = None
    integer: bool = False
    why: str = ""
    auto: float | None = None

    def constraints(self) -> dict:
        """The bounds as pydantic ``Field`` keywords (``gt=…``, ``le=…``)."""
        return {
            k: getattr(self, k) for k in ("gt", "ge", "lt", "le") if getattr(self, k) is not None
        }

    def describe(self, unit: bool = True) -> str:
        """'> 0 and <= 0.0001 m', '0 (automatic) or >= 32 and <= 4096' (the form the
        case-file messages use)."""
        u = f" {self.unit}" if unit and self.unit else ""
        text = " and ".join(
            f"{sym} {_num(v)}{u}"
            for sym, v in ((">", self.gt), (">=", self.ge), ("<", self.lt), ("<=", self.le))
            if v is not None
        )
        return text if self.auto is None else f"{_num(self.auto)} (automatic) or {text}"

    def contains(self, v: float) -> bool:
        return v == self.auto or not (
            (self.gt is not None and not v > self.gt)
            or (self.ge is not None and not v >= self.ge)
            or (self.lt is not None and not v < self.lt)
            or (self.le is not None and not v <= self.le)
        )

    def check(self, name: str, value):
        """``value`` as float (int if ``integer``) if it is a finite number inside the
        range, else :class:`~tribodyn.InputError` naming ``name``, the range and the value,
        e.g. ``rms must be > 0 and < 0.0001 [m] (got 1)`` (a :class:`RangeError` if it is a
        number)."""
        try:
            v = check_int(name, value) if self.integer else check_real(name, value, self.unit)
        except InputError:
            if isinstance(value, bool) or not isinstance(value, Real):
                raise
            v = None  # a number outside the float range, NaN or inf: say the range too
        if v is None or not self.contains(v):
            raise RangeError([(name, self, value)])
        return v


class RangeError(InputError):
    """Values outside their :class:`Limit`: ``items`` are (argument name, limit, value
    given), the message one ``name must be … (got …)`` per item, joined by ``; ``."""

    def __init__(self, items: list[tuple[str, Limit, object]]):
        super().__init__("; ".join(_out_of_range(*item) for item in items))
        self.items = items


def _out_of_range(name: str, limit: Limit, value) -> str:
    """'rms must be > 0 and < 0.0001 [m] (got 1)'."""
    u = f" [{limit.unit}]" if limit.unit else ""
    what = "an integer " if limit.integer else ""
    return f"{name} must be {what}{limit.describe(unit=False)}{u} (got {_fmt(value)})"


def check_fields(obj, limits: dict[str, Limit], optional: tuple[str, ...] = ()) -> None:
    """Check the fields ``limits`` names of the frozen dataclass ``obj`` (those in
    ``optional`` may be None: absent) and store them converted (:meth:`Limit.check`); one
    :class:`RangeError` lists every field out of range."""
    bad: list[tuple[str, Limit, object]] = []
    for name, limit in limits.items():
        value = getattr(obj, name)
        if value is None and name in optional:
            continue
        try:
            object.__setattr__(obj, name, limit.check(name, value))
        except RangeError as exc:
            bad += exc.items
    if bad:
        raise RangeError(bad)


def unchecked(cls, **values):
    """An instance of the frozen dataclass ``cls`` with ``values`` (every field) that were
    checked where they entered: its ``__post_init__`` does not check them again."""
    obj = object.__new__(cls)
    obj.__dict__.update(values)
    return obj


# -- materials -------------------------------------------------------------------------
YOUNGS_MODULUS = Limit(
    "Pa", ge=1e6, le=2e12, why="soft elastomers (~1 MPa) to diamond (1.05–1.2 TPa)"
)
POISSON_RATIO = Limit(
    "", gt=-1.0, lt=0.5, why="positive-definite strain energy of an isotropic solid"
)
COATING_THICKNESS = Limit(
    "m", gt=0.0, le=1e-2, why="thin films to overlays and sprayed layers of several mm"
)

# -- roughness (Greenwood–Tripp) -------------------------------------------------------
ASPERITY_DENSITY = Limit(
    "1/m²", gt=0.0, le=1e18, why="at most one summit per nm² (atomic spacing ≈ 0.3 nm)"
)
ROUGHNESS_RMS = Limit(
    "m",
    gt=0.0,
    lt=1e-4,
    why="composite RMS roughness below 100 µm: rougher surfaces are not lubricated contacts",
)
SUMMIT_RADIUS = Limit("m", gt=0.0, lt=1e-2, why="summit radii below 10 mm")

# -- lubricant -------------------------------------------------------------------------
VISCOSITY = Limit(
    "Pa·s",
    gt=ROELANDS_MU_INF,
    le=100.0,
    why="Roelands' law needs μ₀ > exp(−9.67) Pa·s; 100 Pa·s is a heavy gear oil "
    "far below its pour point",
)
PRESSURE_VISCOSITY = Limit(
    "1/Pa", ge=0.0, le=1e-6, why="α of mineral and synthetic oils is 1e-8…4e-8 1/Pa"
)
DENSITY = Limit("kg/m³", gt=0.0, le=5000.0, why="liquids lighter than 5000 kg/m³")
EYRING_STRESS = Limit("Pa", gt=0.0, le=1e9, why="τ_E of lubricants is 1–20 MPa")
LIMITING_SHEAR_COEFFICIENT = Limit("", ge=0.0, le=1.0, why="Λ of oils is 0.03–0.1")
LIMITING_SHEAR_STRESS = Limit("Pa", ge=0.0, le=1e9, why="τ_L0 of oils is a few MPa")
BOUNDARY_SHEAR_COEFFICIENT = Limit(
    "", ge=0.0, le=2.0, why="ς (a friction coefficient of the asperity tips) below 2"
)
BOUNDARY_SHEAR_STRENGTH = Limit("Pa", ge=0.0, le=1e9, why="τ₀ of boundary films is ~2 MPa")

# -- thermal oil and solids (thermal EHL) ----------------------------------------------
THERMAL_EXPANSION = Limit("1/K", ge=0.0, le=3e-3, why="ε of oils is 6–9e-4 1/K (Yang & Wen 1990)")
VISCOSITY_TEMPERATURE = Limit("1/K", gt=0.0, le=0.5, why="β = −d ln μ/dT of oils: 0.01–0.1 1/K")
OIL_CONDUCTIVITY = Limit(
    "W/(m K)", ge=0.01, le=1e8, why="oils 0.1–0.2 (Larsson & Andersson 2000); 1e8: isothermal film"
)
OIL_SPECIFIC_HEAT = Limit("J/(kg K)", ge=100.0, le=1e4, why="oils: 1.7–2.5 kJ/(kg K) (Cragoe 1929)")
LIMITING_SHEAR_TEMPERATURE = Limit("1/K", ge=0.0, le=0.05, why="τ_L halves over ≥ 10 K")
KINEMATIC_VISCOSITY_40 = Limit(
    "m²/s", gt=1.5e-6, le=0.1, why="above ν₁₀₀ (≥ 1.5 mm²/s); 1e5 mm²/s: heavy gear oils"
)
KINEMATIC_VISCOSITY_100 = Limit(
    "m²/s", ge=1.5e-6, le=0.01, why="ASTM D341 (Walther) holds down to 1.5 mm²/s"
)
OIL_TEMPERATURE = Limit(
    "K", ge=200.0, le=600.0, why="oil temperatures of −73 °C to 327 °C (pour point to cracking)"
)
SOLID_CONDUCTIVITY = Limit(
    "W/(m K)", ge=1e-3, le=1e8, why="aerogels 1e-3 to diamond ~2000; 1e8: an isothermal solid"
)
SOLID_DENSITY = Limit("kg/m³", ge=10.0, le=1e5, why="foams to osmium (22 600 kg/m³)")
SOLID_SPECIFIC_HEAT = Limit("J/(kg K)", ge=10.0, le=1e5, why="solids: 0.1–2 kJ/(kg K)")

# -- valvetrain ------------------------------------------------------------------------
MASS = Limit(
    "kg",
    ge=1e-3,
    le=10.0,
    why="valvetrain parts from a gram (collets) to the few kg of the largest "
    "poppet valves; outside, the spring cannot control the valve",
)
SPRING_RATE = Limit("N/m", gt=0.0, le=1e7, why="valve springs are 10–500 kN/m")
SPRING_PRELOAD = Limit("N", gt=0.0, le=1e5, why="installed loads are 0.1–10 kN")
STIFFNESS = Limit(
    "N/m",
    gt=0.0,
    le=1e11,
    why="joint stiffnesses of valvetrains are 1e7–1e9 N/m; above 1e11 N/m the "
    "joint is rigid for the dynamics and only makes the integration stiff",
)
DAMPING = Limit("N·s/m", ge=0.0, le=1e6, why="above the critical damping of any joint")
CONTACT_MODULUS = Limit("Pa", ge=1e6, le=1e13, why="E' of pairs of materials within YOUNGS_MODULUS")
SPRING_MASSES = Limit(
    "",
    ge=0,
    le=200,
    integer=True,
    why="lumped coil masses; 200 resolve surge modes far above any excitation",
)
SPRING_DAMPING_RATIO = Limit("", ge=0.0, lt=1.0, why="under-damped surge modes")
LASH = Limit("m", ge=0.0, lt=0.01, why="valve clearance below 10 mm")
DAMPING_FORCE_RAMP = Limit("N", gt=0.0, le=1e4, why="force over which contact damping phases in")
BORE_FRICTION_COEFFICIENT = Limit("", ge=0.0, le=2.0, why="friction coefficients below 2")
BORE_FRICTION_VELOCITY = Limit(
    "m/s", gt=0.0, le=10.0, why="regularisation below the tappet speeds (~1–10 m/s)"
)
SUPPLY_FILM_THICKNESS = Limit(
    "m", gt=0.0, le=1.0, why="oil supply layer of the film state; 1 m: flooded for any contact"
)
LENGTH_BELOW_1M = Limit("m", gt=0.0, lt=1.0, why="valvetrain dimensions below 1 m")
ENGINE_SPEED = Limit("rpm", gt=0.0, le=50000.0, why="engine speeds below 50 000 rpm")
ENGINE_DISPLACEMENT = Limit(
    "m³", ge=1e-5, le=0.1, why="swept volumes of engines from 10 cm³ (models) to 100 l"
)
TAPPET_BORE_DIAMETER = Limit("m", ge=2e-3, lt=0.2, why="tappet bores of 2 mm to 200 mm")
CAM_SPEED = Limit(
    "rad/s",
    gt=0.0,
    le=50000.0 * math.pi / 60.0,
    why="the cam speed of ENGINE_SPEED (four-stroke: ω = 2π n/120)",
)
LIFT_TABLE_ROWS = Limit(
    "",
    ge=12,
    le=1_000_000,
    integer=True,
    why="cam lift table rows: a 0.00036° table at most (fitted in about 5 s; jump "
    "detection on bin means, at most 7200 spline knots)",
)

# -- line-contact operating point (solve_ehl, TransientEHL, solve_dry_contact) ----------
LINE_LOAD = Limit(
    "N/m",
    ge=1e-3,
    le=1e9,
    why="load per unit length from a milligram-force per metre to 1 MN per mm; gear "
    "teeth and rolling bearings carry up to ~1e7 N/m, cam-tappet contacts ~1e5 N/m",
)
CONTACT_RADIUS = Limit(
    "m",
    ge=1e-6,
    le=1e6,
    why="reduced radius from a micrometre (below, continuum EHL does not apply) to "
    "nearly flat surfaces (a 1000 km radius is a flat to any contact width)",
)
SURFACE_SPEED = Limit(
    "m/s",
    ge=-1e3,
    le=1e3,
    why="entrainment and sliding speeds below 1 km/s: the Reynolds equation assumes "
    "flow far below the speed of sound in oil (~1.4 km/s)",
)

# -- numerics --------------------------------------------------------------------------
DYNAMICS_CYCLES = Limit(
    "", ge=1, le=50, integer=True, why="engine cycles of the dynamics (the last is presented)"
)
OUTPUT_STEP = Limit(
    "deg (crank)",
    gt=0.0,
    le=5.0,
    why="crank-angle output step of the dynamics: coarser grids miss the force peak",
)
MAX_STEP = Limit(
    "deg (crank)", gt=0.0, le=10.0, why="largest integrator step of the dynamics (crank angle)"
)
DYNAMICS_RTOL = Limit("", gt=0.0, lt=0.1, why="relative tolerance of the dynamics")
DYNAMICS_ATOL = Limit("", gt=0.0, le=1e-2, why="absolute tolerances of the dynamics (SI)")
JUMP_LIFT_THRESHOLD = Limit(
    "m",
    gt=0.0,
    le=1e-3,
    why="cam lift above which a contact loss counts as a jump (ramps are 0.1–0.5 mm)",
)
EHL_NODES = Limit(
    "",
    ge=32,
    le=65536,
    integer=True,
    why="steady solves (two-grid preconditioning above 1024 nodes)",
)
EHL_NODES_TRANSIENT = Limit(
    "", ge=32, le=4096, integer=True, why="the transient steps factor dense matrices"
)
#: numerics.n and numerics.coupling_n: the cycle's transient grid; 0 chooses it
EHL_NODES_CYCLE = replace(EHL_NODES_TRANSIENT, auto=0)
STRESS_NODES = Limit(
    "", ge=3, le=65536, integer=True, why="surface loads on at most the finest EHL grid"
)
STRESS_DEPTHS = Limit(
    "", ge=1, le=2000, integer=True, why="depths evaluated at once (memory: depths × FFT length)"
)
STRESS_DEPTH = Limit("m", ge=0.0, lt=1.0, why="depths below a contact, below 1 m")
STRESS_FFT_LENGTH = Limit(
    "",
    ge=3,
    le=2**18,
    integer=True,
    why="periodic length of the stress transforms (2n, and 32 coating thicknesses / dx)",
)
SURFACE_LOAD = Limit(
    "Pa", ge=-1e11, le=1e11, why="surface pressures and tractions below 100 GPa (any strength)"
)
DOMAIN_HALF_WIDTHS = Limit("", ge=1.0, le=100.0, why="EHL domain in Hertz half-widths")
DOMAIN_RIGID_LENGTHS = Limit("", ge=1.0, le=200.0, why="EHL domain in rigid inlet lengths")
INLET_TRUNCATION = Limit("", gt=0.0, le=0.1, why="share of the load lost to the cut inlet")
NEWTON_TOL = Limit("", gt=0.0, lt=1.0, why="scaled Newton tolerance")
NEWTON_MAX_ITER = Limit("", ge=1, le=10000, integer=True, why="Newton iterations per solve")
MAX_SUBSTEPS = Limit(
    "",
    ge=0,
    le=10,
    integer=True,
    why="a failing transient step is halved at most this often (sub-steps "
    "down to dt/2^max_substeps), which bounds the effort of one step",
)
GREENWOOD_TRIPP_ORDER = Limit(
    "",
    ge=0.0,
    le=10.0,
    why="the theory uses n = 0…5/2; orders up to 10 are verified against quadrature",
)

# -- thermal EHL (ThermalOptions) -------------------------------------------------------
#: Worker processes of a study (``numerics.workers``, ``-j/--workers``): 0 means one per
#: CPU core.
WORKERS = Limit("", ge=0, le=4096, integer=True, why="0: one per CPU core")
THERMAL_X_NODES = Limit("", ge=16, le=4096, integer=True, why="along x, as EHL_NODES_TRANSIENT")
THERMAL_FILM_NODES = Limit("", ge=3, le=41, integer=True, why="across the film (made odd)")
THERMAL_SOLID_NODES = Limit("", ge=6, le=200, integer=True, why="depth nodes per solid")
THERMAL_DEPTH = Limit("", ge=0.05, le=20.0, why="solid depth in EHL domain lengths")
THERMAL_TOL = Limit("K", gt=0.0, le=10.0, why="coarser misses the film's 10–100 K rise in a cam")
THERMAL_MAX_ITER = Limit("", ge=1, le=10000, integer=True, why="steady fixed-point iterations")
THERMAL_STEP_ITER = Limit("", ge=1, le=100, integer=True, why="iterations per transient step")
THERMAL_RELAXATION = Limit("", gt=0.0, le=1.0, why="under-relaxation of the temperature")

__all__ += [k for k, v in list(globals().items()) if isinstance(v, Limit)]
