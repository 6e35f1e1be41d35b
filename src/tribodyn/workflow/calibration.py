"""Calibration of boundary friction and rheology from measured friction of a line contact.

Measured friction coefficients μ_i of a lubricated line contact (twin-disc,
cylinder-on-flat, a cam rig reduced to its contact conditions) at entrainment speeds
u_e,i, sliding speeds u_s,i and loads w_i (per unit length) are fitted by the analytic
mixed-lubrication model that tribodyn uses inside the valvetrain dynamics
(:func:`tribodyn.physics.analytic_contact.analytic_contact`):

    μ(θ) = [F_v(τ_E, Λ, τ_L0) + 2b (τ₀ A_a/A + ς p_a)] / w

F_v: Eyring viscous shear ∫ τ_E asinh(η(p) u_s/(τ_E h_c)) dx over the Hertz width, capped
at τ_L0 + Λ p; h_c: Moes central film; p_a, A_a/A: Greenwood–Tripp at h_c (this is the
Stribeck-curve model of Gelinck & Schipper, Tribol. Int. 33 (2000) 175–181, with
tribodyn's film and shear laws). The parameters θ ⊂ {ς, τ₀, τ_E, Λ, τ_L0, ηβσ} are found
by non-linear least squares (scipy ``least_squares``, trust-region reflective, bounds of
:data:`PARAMETERS`; τ_E and ηβσ are fitted as logarithms).

Asperity load share: Greenwood–Tripp with typical ηβσ = 0.04 and σ/β = 1e-3 carries at
most p_a(λ = 0) = (8√2/15)π F_{5/2}(0) (ηβσ)² √(σ/β) E' = 1.461 (ηβσ)² √(σ/β) E' ≈ 17 MPa
on steel (E' = 231 GPa), a few per cent of a Hertz pressure, so a model with those values cannot reach a measured boundary
friction coefficient. ηβσ (through the summit density η, σ and β kept) can therefore be
fitted as an *effective* value from a Stribeck curve that spans the mixed regime: ς sets
the boundary plateau, ηβσ the λ at which friction rises towards it. Uncertainty: the covariance

    C = s² (JᵀJ)⁻¹,   s² = Σ r_i² / (n − k)

of the k fitted parameters at the optimum (J: Jacobian of the residuals, r_i = μ(θ; x_i) −
μ_i; Gauss–Newton linearisation, errors assumed independent with equal variance). A
parameter the data do not determine (a singular or ill-conditioned JᵀJ: no points at low
λ for ς, no high-slide points for Λ) is reported with an infinite uncertainty and a
message; fix it instead (``fixed=``).

The model is isothermal: the fitted τ_E and Λ are the *effective* values that make the
isothermal friction law reproduce the measurement (shear heating included), which is
what tribodyn's isothermal solvers need. Fit at the oil temperature of use.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.optimize import least_squares

from .._validation import InputError
from ..physics import typical
from ..physics.analytic_contact import analytic_contact
from ..physics.asperity import Roughness
from ..physics.lubricant import Lubricant
from ..physics.materials import STEEL, Body, Material
from .calibration_checks import distinct_points, fit_problems, repeated_message, units_hint

__all__ = [
    "PARAMETERS",
    "FrictionData",
    "CalibrationSetup",
    "Calibration",
    "model_friction",
    "calibrate_friction",
]

#: Fittable parameters: name → (unit, lower bound, upper bound, typical start value).
PARAMETERS: dict[str, tuple[str, float, float, float]] = {
    "boundary_shear_coefficient": ("-", 0.0, 1.0, typical.boundary_friction("steel").value),
    "boundary_shear_strength": ("Pa", 0.0, 1e8, typical.BOUNDARY_SHEAR_STRENGTH.value),
    "eyring_stress": ("Pa", 1e4, 1e8, typical.EYRING_STRESS.value),
    "limiting_shear_coefficient": ("-", 1e-4, 0.5, typical.LIMITING_SHEAR_COEFFICIENT.value),
    "limiting_shear_stress": ("Pa", 0.0, 1e8, typical.LIMITING_SHEAR_STRESS.value),
    "roughness_parameter": ("-", 1e-4, 1.0, typical.ROUGHNESS_PARAMETER.value),
}
_DEFAULT_FREE = ("boundary_shear_coefficient", "eyring_stress", "limiting_shear_coefficient")
_LOG = ("eyring_stress", "roughness_parameter")  # fitted as ln(value)


@dataclass(frozen=True)
class FrictionData:
    """Measured points: entrainment speed u_e [m/s], sliding speed u_s [m/s], load per
    unit length w [N/m] and friction coefficient μ [-] (arrays of equal length), and
    optionally the reduced radius R [m] per point (a cam trace reduced to its contact
    conditions angle by angle; absent: the setup's radius)."""

    entrainment_speed: np.ndarray
    sliding_speed: np.ndarray
    load: np.ndarray
    friction_coefficient: np.ndarray
    radius: np.ndarray | None = None

    def __post_init__(self):
        names = ("entrainment_speed", "sliding_speed", "load", "friction_coefficient")
        arrays = []
        for name in names:
            a = np.atleast_1d(np.asarray(getattr(self, name), dtype=float))
            if a.ndim != 1 or not np.all(np.isfinite(a)):
                raise InputError(f"{name} must be a 1-D array of finite numbers")
            arrays.append(a)
        n = arrays[0].size
        if any(a.size != n for a in arrays):
            raise InputError(
                "entrainment_speed, sliding_speed, load and friction_coefficient "
                "must have the same length"
            )
        if n < 3:
            raise InputError(f"at least 3 measured points are needed (got {n})")
        if np.any(arrays[0] <= 0.0):
            raise InputError("entrainment_speed must be > 0 m/s")
        if np.any(arrays[2] <= 0.0):
            raise InputError("load must be > 0 N/m")
        if np.any(arrays[3] < 0.0) or np.any(arrays[3] > 1.0):
            raise InputError("friction_coefficient must lie in [0, 1]")
        for name, a in zip(names, arrays, strict=True):
            object.__setattr__(self, name, a)
        if self.radius is not None:
            r = np.atleast_1d(np.asarray(self.radius, dtype=float))
            if r.shape != (n,) or not np.all((r > 0.0) & (r < 1.0)):
                raise InputError(f"radius must give {n} values in (0, 1) m, one per point")
            object.__setattr__(self, "radius", r)

    def __len__(self) -> int:
        return int(self.friction_coefficient.size)


@dataclass(frozen=True)
class CalibrationSetup:
    """The known part of the contact: geometry, elasticity, base oil and roughness.

    radius : reduced radius R of the line contact [m].
    lubricant : base oil at the test temperature (μ₀, α; its τ_E, Λ, τ_L0 are start
        values or, when fixed, the values used).
    roughness : composite Greenwood–Tripp roughness (None: smooth, no boundary friction).
    materials : the two surface materials (E, ν), bulk = surface (thin coatings).
    """

    radius: float
    lubricant: Lubricant
    roughness: Roughness | None
    materials: tuple[Material, Material] = field(default_factory=lambda: (STEEL, STEEL))

    def __post_init__(self):
        if not (isinstance(self.radius, (int, float)) and 0.0 < self.radius < 1.0):
            raise InputError(f"radius must be a number in (0, 1) m (got {self.radius!r})")


def _start(setup: CalibrationSetup, name: str) -> float:
    if name == "roughness_parameter" and setup.roughness is not None:
        return setup.roughness.roughness_parameter
    if name in ("eyring_stress", "limiting_shear_coefficient", "limiting_shear_stress"):
        return float(getattr(setup.lubricant, name))
    return PARAMETERS[name][3]


def model_friction(setup: CalibrationSetup, data: FrictionData, **params: float) -> np.ndarray:
    """Model friction coefficient μ at the measured conditions for parameter values
    ``params`` (names of :data:`PARAMETERS`; missing ones from ``setup`` / typical)."""
    return np.asarray(_contact(setup, data, params).friction) / data.load


def _contact(setup: CalibrationSetup, data: FrictionData, params: dict[str, float]):
    """The analytic contact of :func:`model_friction` at the measured conditions."""
    unknown = set(params) - set(PARAMETERS)
    if unknown:
        raise InputError(f"unknown parameter(s) {sorted(unknown)}; allowed: {list(PARAMETERS)}")
    p = {name: params.get(name, _start(setup, name)) for name in PARAMETERS}
    lub = replace(
        setup.lubricant,
        eyring_stress=p["eyring_stress"],
        limiting_shear_coefficient=p["limiting_shear_coefficient"],
        limiting_shear_stress=p["limiting_shear_stress"],
    )
    bodies = (Body(setup.materials[0]), Body(setup.materials[1]))
    rough = setup.roughness
    if rough is not None and "roughness_parameter" in params:
        # ηβσ scaled through η, keeping σ and β (σ/β sets the asperity pressure scale)
        scale = params["roughness_parameter"] / rough.roughness_parameter
        rough = replace(rough, asperity_density=rough.asperity_density * scale)
    return analytic_contact(
        data.load,
        setup.radius if data.radius is None else data.radius,
        data.entrainment_speed,
        data.sliding_speed,
        bodies,
        lub,
        rough,
        boundary_shear_coefficient=p["boundary_shear_coefficient"],
        boundary_shear_strength=p["boundary_shear_strength"],
    )


@dataclass(frozen=True)
class Calibration:
    """Result of :func:`calibrate_friction`.

    values / std : fitted values and 1σ standard uncertainties (inf: not determined).
    covariance : covariance of the fitted parameters (order of ``free``), physical units.
    fixed : parameters held fixed and their values.
    rms_residual : RMS of μ_model − μ_measured at the optimum.
    converged : the optimiser met its tolerance and every parameter is determined.
    message : what happened, and what to change if it did not work.
    bootstrap_std : 1σ from a residual bootstrap (``bootstrap`` > 0), else empty.
    warnings : remarks on the data that do not stop the fit (repeated rows).
    n_points : the number of distinct points fitted (exact repeats counted once).
    """

    free: tuple[str, ...]
    values: dict[str, float]
    std: dict[str, float]
    covariance: np.ndarray
    fixed: dict[str, float]
    rms_residual: float
    n_points: int
    converged: bool
    message: str
    bootstrap_std: dict[str, float] = field(default_factory=dict)
    warnings: tuple[str, ...] = ()

    def within(self, truth: dict[str, float], k: float = 3.0) -> dict[str, bool]:
        """Whether each true value lies within k standard uncertainties of the fit."""
        return {n: abs(self.values[n] - truth[n]) <= k * self.std[n] for n in truth}


def calibrate_friction(
    data: FrictionData,
    setup: CalibrationSetup,
    free: tuple[str, ...] | list[str] = _DEFAULT_FREE,
    fixed: dict[str, float] | None = None,
    bootstrap: int = 0,
    seed: int = 0,
) -> Calibration:
    """Fit the parameters ``free`` to the measured friction ``data`` (module docstring).

    ``fixed`` overrides the values of parameters that are not fitted. ``bootstrap`` > 0
    also refits that many synthetic data sets, the fitted model plus residuals drawn with
    replacement (residual bootstrap, seeded by ``seed``), and reports the standard
    deviation of the refitted values as ``bootstrap_std``: a check of the linearised
    uncertainty that does not assume the model is linear in its parameters. Raises
    :class:`~tribodyn.InputError` for unknown names or a free parameter that is also fixed.
    """
    free = tuple(free)
    fixed = dict(fixed or {})
    data, repeated = distinct_points(data)
    warnings = (repeated_message(repeated),) if repeated else ()
    for name in (*free, *fixed):
        if name not in PARAMETERS:
            raise InputError(f"unknown parameter {name!r}; allowed: {list(PARAMETERS)}")
    if not free:
        raise InputError("nothing to fit: give at least one free parameter")
    if set(free) & set(fixed):
        raise InputError(f"parameter(s) {sorted(set(free) & set(fixed))} both free and fixed")
    if not (isinstance(bootstrap, int) and 0 <= bootstrap <= 10000):
        raise InputError(f"bootstrap must be an integer in [0, 10000] (got {bootstrap!r})")
    if len(data) <= len(free):
        raise InputError(
            f"{len(data)} points cannot determine {len(free)} parameters with an uncertainty; "
            f"measure more points or fix some parameters"
        )
    for name, value in fixed.items():
        _, low, high, _ = PARAMETERS[name]
        if not low <= value <= high:
            raise InputError(f"fixed {name} must lie in [{low:g}, {high:g}] (got {value!r})")
    boundary = {"boundary_shear_coefficient", "boundary_shear_strength", "roughness_parameter"}
    if setup.roughness is None and boundary & (set(free) | set(fixed)):
        raise InputError("boundary parameters cannot be fitted without a roughness")
    rough = setup.roughness
    if (
        rough is not None
        and rough.law is not None
        and "roughness_parameter" in set(free) | set(fixed)
    ):
        raise InputError(
            "roughness_parameter (ηβσ) is a Greenwood–Tripp parameter; this roughness uses "
            "a measured load–separation law, which has none: fit ς, τ₀, τ_E or Λ instead"
        )

    def to_x(name, v):
        return math.log(v) if name in _LOG else v

    def from_x(name, x):
        return math.exp(x) if name in _LOG else x

    lo = np.array([to_x(n, PARAMETERS[n][1]) for n in free])
    hi = np.array([to_x(n, PARAMETERS[n][2]) for n in free])
    x0 = np.array([to_x(n, fixed.get(n, _start(setup, n))) for n in free])
    x0 = np.clip(x0, lo + 1e-9 * (hi - lo), hi - 1e-9 * (hi - lo))
    x_scale = np.array(
        [
            1.0 if n in _LOG else max(abs(x), PARAMETERS[n][3], 1e-3)
            for n, x in zip(free, x0, strict=True)
        ]
    )

    def params_of(x):
        return {**fixed, **{n: from_x(n, xi) for n, xi in zip(free, x, strict=True)}}

    def residuals(x, setup_=setup, target=data.friction_coefficient):
        return model_friction(setup_, data, **params_of(x)) - target

    r0 = residuals(x0)
    if not np.all(np.isfinite(r0)):
        bad = int(np.flatnonzero(~np.isfinite(r0))[0])
        raise InputError(
            f"the model friction is not finite at measured point {bad + 1} (u_e = "
            f"{data.entrainment_speed[bad]:g} m/s, u_s = {data.sliding_speed[bad]:g} m/s, "
            f"w = {data.load[bad]:g} N/m): check the units of the data and the setup"
        )
    # The cap τ_L0 + Λp is flat (zero gradient) where it is not reached, so Λ is also
    # started at levels of the measured friction coefficient; the best fit is kept.
    starts = [x0]
    if "limiting_shear_coefficient" in free:
        i = free.index("limiting_shear_coefficient")
        mu_max = float(np.max(data.friction_coefficient))
        for level in (mu_max, 0.5 * mu_max):
            x = x0.copy()
            x[i] = float(np.clip(level, lo[i] + 1e-9, hi[i] - 1e-9))
            starts.append(x)

    def fit(setup_: CalibrationSetup):
        """The best of the fits from ``starts`` (and all of them) with ``setup_``."""
        trials = [
            least_squares(
                residuals,
                x_start,
                kwargs={"setup_": setup_},
                bounds=(lo, hi),
                x_scale=x_scale,
                method="trf",
                xtol=1e-8,
                ftol=1e-8,
                gtol=1e-8,
                max_nfev=1000,
            )
            for x_start in starts
        ]
        # the best fit; among fits as good (0.1 %), one whose optimiser met its tolerance
        best = min(t.cost for t in trials)
        good = [t for t in trials if t.cost <= best * 1.001 + 1e-30]
        return min(good, key=lambda t: (not t.success, t.cost)), trials

    def at_bounds(x) -> list[str]:
        return [
            nm
            for nm, xi, a, b in zip(free, x, lo, hi, strict=True)
            if min(xi - a, b - xi) <= 1e-6 * (b - a)
        ]

    sol, trials = fit(setup)
    n, k = len(data), len(free)
    r = sol.fun
    s2 = float(r @ r) / (n - k)
    # Jacobian in physical units: d r/d v = d r/d x · d x/d v
    dxdv = np.array(
        [1.0 / from_x(nm, xi) if nm in _LOG else 1.0 for nm, xi in zip(free, sol.x, strict=True)]
    )
    J = sol.jac * dxdv[None, :]
    # scale columns to unit norm before inverting (parameters differ by 1e8)
    norms = np.linalg.norm(J, axis=0)
    problems = [nm for nm, c in zip(free, norms, strict=True) if c == 0.0]
    norms_safe = np.where(norms > 0.0, norms, 1.0)
    Js = J / norms_safe
    jtj = Js.T @ Js
    cond = np.linalg.cond(jtj) if not problems else math.inf
    if problems or not np.isfinite(cond) or cond > 1e12:
        cov = np.full((k, k), math.inf)
        undetermined = problems or [
            nm for nm, v in zip(free, np.abs(np.linalg.eigh(jtj)[1][:, 0]), strict=True) if v > 0.3
        ]
        message = (
            f"the data do not determine {', '.join(undetermined)} (condition number of JᵀJ "
            f"{cond:.3g}); fix it (fixed=…) or add measured points where it matters "
            f"(ς: low λ, mixed/boundary; Λ: high slide-to-roll ratio; τ_E: moderate slide)"
        )
    else:
        cov = s2 * np.linalg.inv(jtj) / np.outer(norms_safe, norms_safe)
        message = (
            f"fitted {k} parameters to {n} points; RMS residual {math.sqrt(float(r @ r) / n):.3g}"
        )
    values = params_of(sol.x)
    std = {
        nm: float(math.sqrt(cov[i, i])) if np.isfinite(cov[i, i]) else math.inf
        for i, nm in enumerate(free)
    }
    converged = bool(sol.success) and all(np.isfinite(list(std.values())))
    if not sol.success:
        message = f"least squares did not converge ({sol.message}); " + message
    vague = [nm for nm in free if math.isfinite(std[nm]) and std[nm] > abs(values[nm])]
    if vague:
        converged = False
        message += (
            f"; {', '.join(vague)} not determined (1σ uncertainty larger than the value); "
            "fix it or add measured points where it matters"
        )
    # other starts that fit as well (within 2σ in χ²) but elsewhere: not unique
    if np.all(np.isfinite(cov)):
        sd_x = np.sqrt(np.diag(cov))
        v_best = np.array([from_x(nm, xi) for nm, xi in zip(free, sol.x, strict=True)])
        for t in trials:
            if t is sol or 2.0 * (t.cost - sol.cost) / s2 > 4.0:
                continue
            v_t = np.array([from_x(nm, xi) for nm, xi in zip(free, t.x, strict=True)])
            far = [
                nm
                for nm, a, b, sd in zip(free, v_best, v_t, sd_x, strict=True)
                if abs(a - b) > 3.0 * sd
            ]
            if far:
                converged = False
                alt = ", ".join(f"{nm} = {b:.4g}" for nm, b in zip(free, v_t, strict=True))
                message += (
                    f"; the data fit as well with {alt}: {', '.join(far)} not determined "
                    "(the uncertainty above is local); fix it or add measured points where "
                    "it matters"
                )
                break
    at_bound = at_bounds(sol.x)
    if at_bound:
        converged = False
        message += (
            f"; {', '.join(at_bound)} at the bound of its allowed range: the model cannot fit "
            "these data with a value inside it (check units and the fixed inputs)"
        )
    # a fit that does not follow the data, or implausible values: inputs in wrong units?
    symptoms = fit_problems(data.friction_coefficient, r, {nm: values[nm] for nm in free})
    if symptoms or at_bound:

        def refit(other: CalibrationSetup) -> tuple[float, dict[str, float], bool]:
            alt, _ = fit(other)
            v = params_of(alt.x)
            return float(alt.cost), {nm: float(v[nm]) for nm in free}, bool(at_bounds(alt.x))

        lam = None
        if setup.roughness is not None:
            film = _contact(setup, data, params_of(sol.x)).central_film
            lam = np.asarray(film) / setup.roughness.rms
        converged = False
        message += "; " + "; ".join([*symptoms, units_hint(setup, float(sol.cost), refit, lam)])
    boot: dict[str, float] = {}
    if bootstrap:
        rng = np.random.default_rng(seed)
        fitted = data.friction_coefficient + r  # the model at the optimum
        samples = []
        for _ in range(bootstrap):
            target = fitted + rng.choice(r, size=n, replace=True)
            b = least_squares(  # trust-region reflective, as the fit
                residuals, sol.x, bounds=(lo, hi), x_scale=x_scale, kwargs={"target": target}
            )
            samples.append([from_x(nm, xi) for nm, xi in zip(free, b.x, strict=True)])
        spread = np.std(np.array(samples), axis=0, ddof=1)
        boot = {nm: float(v) for nm, v in zip(free, spread, strict=True)}
        ratio = [
            nm
            for nm in free
            if math.isfinite(std[nm]) and std[nm] > 0 and not 0.5 <= boot[nm] / std[nm] <= 2.0
        ]
        if ratio:
            message += (
                f"; the bootstrap spread of {', '.join(ratio)} differs from the linearised "
                "uncertainty by more than 2×: the model is not linear in it over its "
                "uncertainty, trust the bootstrap value"
            )
    return Calibration(
        bootstrap_std=boot,
        free=free,
        values={nm: float(values[nm]) for nm in free},
        std=std,
        covariance=cov,
        fixed={nm: float(v) for nm, v in fixed.items()},
        rms_residual=math.sqrt(float(r @ r) / n),
        n_points=n,
        converged=converged,
        message=message,
        warnings=warnings,
    )
