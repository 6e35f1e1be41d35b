"""A lubricant whose properties depend on temperature and pressure (thermal EHL).

Two ways to give the oil:

* **datasheet** — kinematic viscosities ν₄₀, ν₁₀₀ at 40 and 100 °C, density at 15 °C and
  its thermal expansion; the viscosity at ambient pressure follows the ASTM D341 (Walther)
  line through the two points.
* **inlet** — the dynamic viscosity μᵢ at the inlet temperature Tᵢ and the
  temperature–viscosity coefficient β = −d ln μ/dT there; the viscosity at ambient
  pressure follows Roelands' temperature term (below) with S₀ = β(Tᵢ − 138)/(ln μᵢ + 9.67).

Equations (T in K, p in Pa, SI unless stated):

* ASTM D341 (2009 form), ν in mm²/s (cSt)::

      log₁₀ log₁₀ Z = A − B log₁₀ T,   Z = ν + 0.7 + exp(−1.47 − 1.84ν − 0.51ν²)
      ν = (Z − 0.7) − exp(−0.7487 − 3.295(Z−0.7) + 0.6119(Z−0.7)² − 0.3193(Z−0.7)³)

* Roelands (1966) with temperature and pressure terms (the paper's Eq. 3 at T = Tᵢ)::

      ln μ(p, T) + 9.67 = (ln μ₀(T) + 9.67) (1 + 5.1e-9 p)^Z
      roelands:  ln μ₀(T) + 9.67 = (ln μᵢ + 9.67) ((T − 138)/(Tᵢ − 138))^(−S₀)
      walther:   μ₀(T) = ν_D341(T) ρ(0, T)

  Z is constant (Roelands found it nearly temperature independent), from α at the inlet:
  Z = α/(5.1e-9 (ln μᵢ + 9.67)); so α(T) = 5.1e-9 Z (ln μ₀(T) + 9.67) falls with T.
  ``viscosity_model="barus"``: ln μ = ln μ₀(T) + α p. The pressure laws are the
  isothermal oil's (:mod:`tribodyn.physics.lubricant`) with μ₀(T) at each node.
* Pressure–viscosity coefficient when not given: So & Klaus (1980, ASLE Trans. 23:409)
  correlation from ν, ρ and the ASTM slope b = B at the inlet temperature, α in 1e-8 m²/N::

      α = 1.216 + 4.143 (log ν)^3.0627 + 2.848e-4 b^5.1903 (log ν)^1.5976
          − 3.999 (log ν)^3.0975 ρ^0.1162                    (ν in cSt, ρ in g/cm³)

  Along an oil's viscosity–temperature line the fitted polynomial has a maximum (near
  ν ≈ 1000–3000 cSt, −20…0 °C, for engine oils) and falls on the colder side, to negative α
  below about −45 °C, whereas the α of a cooled oil rises. Colder than the temperature T*
  of that maximum the estimate is therefore carried by
  Roelands' constant Z (above): Z from So–Klaus at T*, α(Tᵢ) = 5.1e-9 Z (ln μ₀(Tᵢ) + 9.67)
  (continuous at T*, rising as the oil cools). Above ν = 1 cSt only (hot end: give α).

* Density: Dowson–Higginson in pressure (:mod:`tribodyn.physics.lubricant`) times a
  linear thermal expansion (Yang & Wen 1990, J. Tribol. 112:631)::

      ρ(p, T) = ρ_r [1 + 0.6p/(1 + 1.7p)] [1 − ε (T − T_r)]    (p in GPa)

* Thermal conductivity with the pressure law of Larsson & Andersson (2000, Proc. IMechE J
  214:337) and Cragoe's (1929, US Bureau of Standards Misc. Publ. 97) temperature slope::

      k(p, T) = k_r (1 − 5.4e-4 t)/(1 − 5.4e-4 t_r) (1 + 1.72p/(1 + 0.54p))   (t in °C, p GPa)

  Volumetric heat capacity ρc_p with Cragoe's specific heat slope; its pressure dependence
  is carried by the density (c_p taken pressure independent)::

      c_p(T) = c_r (1.685 + 0.00339 t)/(1.685 + 0.00339 t_r)

  Without given values k and c_p are Cragoe's estimates from the specific gravity s:
  k = 0.1172 (1 − 5.4e-4 t)/s W/(m K), c_p = (1685 + 3.39 t)/√s J/(kg K).
* Shear: Eyring stress τ_E ∝ T (Eyring's τ₀ = k_B T/V); limiting shear stress
  τ_L = (τ_L0 + Λp) max(0.1, 1 − c_L (T − Tᵢ)) (c_L = 0: temperature independent).
"""

from __future__ import annotations

import math
from dataclasses import InitVar, dataclass, field, fields, replace

import numpy as np

from .._validation import InputError, check_bool, check_choice
from . import limits as L
from . import typical
from .lubricant import LIMITS as LUBRICANT_LIMITS
from .lubricant import (
    ROELANDS_LN_MU_INF,
    ROELANDS_MU_INF,
    Lubricant,
    rheology_at,
    roelands_alpha,
    roelands_index,
    roelands_log_factor,
)

__all__ = [
    "ThermalLubricant",
    "walther_constants",
    "walther_viscosity",
    "so_klaus_alpha",
    "celsius",
    "kelvin",
    "T40",
    "T100",
    "T15",
]

T15, T40, T100 = 288.15, 313.15, 373.15
#: Roelands' temperature of infinite viscosity in his temperature term [K].
ROELANDS_T_INF = 138.0
#: Larsson & Andersson (2000) pressure law of the conductivity, k ∝ 1 + a p/(1 + b p) [1/Pa].
CONDUCTIVITY_PRESSURE = (1.72e-9, 0.54e-9)
_ZERO_C = 273.15
#: the ranges of the thermal oil's own arguments (the isothermal oil's: LUBRICANT_LIMITS)
LIMITS = {
    "inlet_temperature": L.OIL_TEMPERATURE,
    "kinematic_viscosity_40": L.KINEMATIC_VISCOSITY_40,
    "kinematic_viscosity_100": L.KINEMATIC_VISCOSITY_100,
    "viscosity_temperature_coefficient": L.VISCOSITY_TEMPERATURE,
    "thermal_expansion": L.THERMAL_EXPANSION,
    "thermal_conductivity": L.OIL_CONDUCTIVITY,
    "specific_heat": L.OIL_SPECIFIC_HEAT,
    "limiting_shear_temperature_coefficient": L.LIMITING_SHEAR_TEMPERATURE,
}


def celsius(T):
    """K → °C."""
    return np.asarray(T, dtype=float) - _ZERO_C


def kelvin(t):
    """°C → K."""
    return np.asarray(t, dtype=float) + _ZERO_C


def _d341_z(nu_cst):
    nu = np.asarray(nu_cst, dtype=float)
    return nu + 0.7 + np.exp(-1.47 - 1.84 * nu - 0.51 * nu * nu)


def walther_constants(nu40, nu100) -> tuple[float, float]:
    """ASTM D341 constants (A, B) of the line through ν(40 °C), ν(100 °C) [m²/s]."""
    y1 = math.log10(math.log10(float(_d341_z(nu40 * 1e6))))
    y2 = math.log10(math.log10(float(_d341_z(nu100 * 1e6))))
    x1, x2 = math.log10(T40), math.log10(T100)
    B = (y1 - y2) / (x2 - x1)
    return y1 + B * x1, B


def walther_viscosity(T, A, B):
    """Kinematic viscosity [m²/s] of the ASTM D341 line (A, B) at T [K]."""
    z = 10.0 ** (10.0 ** (A - B * np.log10(np.asarray(T, dtype=float))))
    zz = z - 0.7
    nu = zz - np.exp(-0.7487 - 3.295 * zz + 0.6119 * zz**2 - 0.3193 * zz**3)
    return nu * 1e-6


def so_klaus_alpha(nu, rho, slope) -> float:
    """So & Klaus (1980) pressure–viscosity coefficient [1/Pa] from the kinematic
    viscosity ν [m²/s] and density ρ [kg/m³] at the temperature of interest and the ASTM
    D341 slope b (= B)."""
    lv = math.log10(nu * 1e6)
    if lv <= 0.0:
        raise InputError(f"the So–Klaus correlation needs ν > 1 mm²/s (got {nu * 1e6:.3g})")
    a = (
        1.216
        + 4.143 * lv**3.0627
        + 2.848e-4 * slope**5.1903 * lv**1.5976
        - 3.999 * lv**3.0975 * (rho * 1e-3) ** 0.1162
    )
    return a * 1e-8


@dataclass(frozen=True)
class ThermalLubricant:
    """Temperature- and pressure-dependent oil (module docstring for the laws).

    Parameters
    ----------
    inlet_temperature : Tᵢ, oil supply (sump) temperature [K], also the temperature of
        the solids far from the contact.
    kinematic_viscosity_40, kinematic_viscosity_100 : ν at 40 and 100 °C [m²/s]
        (datasheet form; both or neither).
    viscosity, viscosity_temperature_coefficient : μᵢ at Tᵢ [Pa·s] and β [1/K] (inlet
        form, instead of the datasheet viscosities).
    density, density_temperature : ρ_r [kg/m³] at ambient pressure and T_r [K] (datasheet:
        15 °C).
    thermal_expansion : ε [1/K] of the density.
    pressure_viscosity : α at Tᵢ [1/Pa]; None: So & Klaus estimate (datasheet form only;
        below the temperature of the correlation's maximum carried by Roelands' Z).
    thermal_conductivity, specific_heat : k [W/(m K)], c_p [J/(kg K)] at Tᵢ and ambient
        pressure; None: Cragoe's estimates from the density.
    eyring_stress : τ_E at Tᵢ [Pa]; limiting_shear_coefficient Λ, limiting_shear_stress
        τ_L0 [Pa], limiting_shear_temperature_coefficient c_L [1/K].
    compressible, viscosity_model : as :class:`~tribodyn.Lubricant`.
    name : label (e.g. the oil's grade).
    _checked : the :class:`~tribodyn.Lubricant` whose checked values (μᵢ, α, τ_E, Λ, τ_L0)
        this oil takes: those equal to its are not checked again.
    """

    inlet_temperature: float
    kinematic_viscosity_40: float | None = None
    kinematic_viscosity_100: float | None = None
    viscosity: float | None = None
    viscosity_temperature_coefficient: float | None = None
    density: float = typical.DENSITY.value
    density_temperature: float = T15
    thermal_expansion: float = 6.5e-4
    pressure_viscosity: float | None = None
    thermal_conductivity: float | None = None
    specific_heat: float | None = None
    eyring_stress: float = typical.EYRING_STRESS.value
    limiting_shear_coefficient: float = typical.LIMITING_SHEAR_COEFFICIENT.value
    limiting_shear_stress: float = typical.LIMITING_SHEAR_STRESS.value
    limiting_shear_temperature_coefficient: float = 0.0
    compressible: bool = True
    viscosity_model: str = "roelands"
    name: str = ""
    _c: dict = field(default_factory=dict, init=False, repr=False, compare=False)
    _checked: InitVar[Lubricant | None] = None

    def __post_init__(self, _checked: Lubricant | None):
        L.check_fields(  # the isothermal Lubricant's ranges (unless it checked them) and its own
            self,
            {
                k: lim
                for k, lim in LUBRICANT_LIMITS.items()
                if _checked is None or getattr(self, k) != getattr(_checked, k)
            }
            | LIMITS,
            optional=tuple(f.name for f in fields(self) if f.default is None),  # may be absent
        )
        object.__setattr__(self, "compressible", check_bool("compressible", self.compressible))
        Ti = self.inlet_temperature  # in range (checked above, as ν₄₀, ν₁₀₀)
        n40, n100 = sheet = (self.kinematic_viscosity_40, self.kinematic_viscosity_100)
        inlet = (self.viscosity, self.viscosity_temperature_coefficient)
        c: dict = {"Ti": Ti}
        if n40 is not None and n100 is not None and all(v is None for v in inlet):
            if not n100 < n40:
                raise InputError(
                    "kinematic_viscosity_100 must be below kinematic_viscosity_40 "
                    f"(got {n100 * 1e6:.4g} and {n40 * 1e6:.4g} mm²/s)"
                )
            c["form"] = "datasheet"
            c["A"], c["B"] = walther_constants(n40, n100)
        elif all(v is not None for v in inlet) and all(v is None for v in sheet):
            mu, beta = inlet  # in range (checked above)
            assert mu is not None and beta is not None
            c["form"] = "inlet"
            c["S0"] = beta * (Ti - ROELANDS_T_INF) / roelands_log_factor(mu)
            c["mu_i"] = mu
        else:
            raise InputError(
                "give either kinematic_viscosity_40 and kinematic_viscosity_100 "
                "(datasheet) or viscosity and viscosity_temperature_coefficient "
                "(inlet form), not a mix"
            )
        if self.density_temperature != Ti:  # the inlet form's is Tᵢ, checked
            L.OIL_TEMPERATURE.check("density_temperature", self.density_temperature)
        check_choice("viscosity_model", self.viscosity_model, ("roelands", "barus"))
        object.__setattr__(self, "_c", c)
        mu_i = float(self.ambient_viscosity(Ti))
        if not mu_i > ROELANDS_MU_INF:
            raise InputError(
                f"viscosity at the inlet temperature {mu_i:.3g} Pa·s is below "
                "Roelands' limit 6.3e-5 Pa·s (oil too thin or too hot)"
            )
        mu_max = L.VISCOSITY.le
        assert mu_max is not None  # the lubricant model's upper viscosity bound
        if not mu_i <= mu_max and c["form"] == "datasheet":  # the inlet form's: μ, checked
            coldest = self._temperature_where(lambda T: self.ambient_viscosity(T) - mu_max)
            raise InputError(
                f"inlet_temperature must be >= {coldest:.5g} K ({coldest - _ZERO_C:.4g} °C) "
                f"for this oil (got {Ti:.6g} K = {Ti - _ZERO_C:.4g} °C): its viscosity there "
                f"is {mu_i:.3g} Pa·s, above the {L.VISCOSITY.le:g} Pa·s the lubricant model "
                "allows (near the pour point)"
            )
        c["mu_i"] = mu_i
        if self.pressure_viscosity is None:
            if c["form"] != "datasheet":
                raise InputError(
                    "pressure_viscosity is required with the inlet form (the So–"
                    "Klaus estimate needs the ASTM D341 slope of a datasheet)"
                )
            alpha = self._so_klaus_inlet_alpha(Ti, mu_i)
        else:
            alpha = self.pressure_viscosity
        c["alpha_i"] = alpha
        c["Z"] = roelands_index(alpha, mu_i)
        barus = self.viscosity_model == "barus"
        a_i = float(roelands_log_factor(mu_i))
        c["law"] = (bool(self.compressible), barus, float(alpha), a_i, c["Z"])
        s = (
            self.density
            / 1000.0
            * (1.0 + self.thermal_expansion * (self.density_temperature - T15))
        )
        ti, k_i, c_i = Ti - _ZERO_C, self.thermal_conductivity, self.specific_heat
        if k_i is None:  # Cragoe's estimates from the specific gravity s at 15 °C
            k_i = L.OIL_CONDUCTIVITY.check("thermal_conductivity", 0.1172 * (1 - 5.4e-4 * ti) / s)
        if c_i is None:
            c_i = L.OIL_SPECIFIC_HEAT.check("specific_heat", (1685.0 + 3.39 * ti) / math.sqrt(s))
        c["k_i"], c["cp_i"] = k_i, c_i
        self._check_isothermal(c, Ti, _checked)

    def _check_isothermal(self, c: dict, Ti: float, checked: Lubricant | None) -> None:
        """Check the values of the isothermal oil at Tᵢ that no key gave (μᵢ is checked
        above), unless ``checked`` has them: an estimated α and the density ρ(0, Tᵢ); keep
        that oil (:meth:`isothermal`)."""
        iso = self._isothermal_values(Ti)
        derived = {"density": L.DENSITY}
        if self.pressure_viscosity is None:
            derived["pressure_viscosity"] = L.PRESSURE_VISCOSITY
        for k, lim in derived.items():
            if checked is None or iso[k] != getattr(checked, k):
                lim.check(k, iso[k])
        c["isothermal"] = L.unchecked(Lubricant, **iso)

    def _temperature_where(self, f) -> float:
        """The temperature in the range of :data:`~.limits.OIL_TEMPERATURE` where ``f``
        (falling with T) crosses 0."""
        lo, hi = L.OIL_TEMPERATURE.ge, L.OIL_TEMPERATURE.le
        assert lo is not None and hi is not None
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if float(f(mid)) > 0.0 else (lo, mid)
        return hi

    def _so_klaus_inlet_alpha(self, Ti: float, mu_i: float) -> float:
        """α at Tᵢ from So–Klaus; colder than the correlation's maximum (T*), carried
        from T* by Roelands' constant Z (module docstring)."""
        B = self._c["B"]

        def estimate(T):  # So–Klaus α at T (−1 where ν ≤ 1 cSt: outside the correlation)
            nu = float(self.kinematic_viscosity(T))
            return so_klaus_alpha(nu, float(self.density_at(0.0, T)), B) if nu > 1e-6 else -1.0

        def past_peak(T):  # > 0 colder than the maximum of the estimate over T
            return estimate(T + 0.01) - estimate(T - 0.01)

        nu_i = float(self.kinematic_viscosity(Ti))
        if nu_i * 1e6 <= 1.0:
            hottest = self._temperature_where(lambda T: self.kinematic_viscosity(T) * 1e6 - 1.0)
            raise InputError(
                f"inlet_temperature must be < {hottest:.5g} K ({hottest - _ZERO_C:.4g} °C) "
                f"for the So–Klaus estimate of pressure_viscosity (got {Ti:.6g} K): the oil's "
                f"kinematic viscosity there is {nu_i * 1e6:.3g} mm²/s, below the "
                "correlation's 1 mm²/s; give pressure_viscosity"
            )
        if past_peak(Ti) <= 0.0:
            return estimate(Ti)
        Ts = self._temperature_where(past_peak)
        self._c["so_klaus_temperature"] = Ts
        alpha_s = estimate(Ts)
        mu_s = float(self.ambient_viscosity(Ts))
        return roelands_alpha(roelands_index(alpha_s, mu_s), mu_i)

    # -- viscosity ---------------------------------------------------------------------
    @property
    def form(self) -> str:
        """ "datasheet" or "inlet"."""
        return self._c["form"]

    @property
    def roelands_z(self) -> float:
        return self._c["Z"]

    @property
    def inlet_viscosity(self) -> float:
        """μ at the inlet temperature and ambient pressure [Pa·s]."""
        return self._c["mu_i"]

    @property
    def inlet_pressure_viscosity(self) -> float:
        """α at the inlet temperature [1/Pa] (given or So–Klaus)."""
        return self._c["alpha_i"]

    def kinematic_viscosity(self, T):
        """ν at ambient pressure [m²/s]."""
        return self.ambient_viscosity(T) / self.density_at(0.0, T)

    def ambient_viscosity(self, T):
        """μ₀(T) at ambient pressure [Pa·s]."""
        T = np.asarray(T, dtype=float)
        c = self._c
        if c["form"] == "datasheet":
            return walther_viscosity(T, c["A"], c["B"]) * self.density_at(0.0, T)
        t = (T - ROELANDS_T_INF) / (c["Ti"] - ROELANDS_T_INF)
        return np.exp(roelands_log_factor(c["mu_i"]) * t ** (-c["S0"]) + ROELANDS_LN_MU_INF)

    def temperature_viscosity_coefficient(self, T=None) -> float:
        """β = −d ln μ₀/dT at T (default the inlet) [1/K]."""
        T = self._c["Ti"] if T is None else float(T)
        d = 0.01
        return float(
            -(np.log(self.ambient_viscosity(T + d)) - np.log(self.ambient_viscosity(T - d)))
            / (2 * d)
        )

    @property
    def rheology_law(self) -> tuple[bool, bool, float, float, float]:
        """:attr:`Lubricant.rheology_law` at the inlet (while α and Z are being found,
        only the density's constant, compressible)."""
        return self._c.get("law", (bool(self.compressible), False, 0.0, 0.0, 0.0))

    def log_viscosity(self, p, T):
        """ln μ(p, T) = ln μ₀(T) + ln(μ/μ₀) of the pressure law [ln Pa·s] (p < 0 taken
        as 0)."""
        l0 = np.log(self.ambient_viscosity(T))
        return l0 + rheology_at(self.rheology_law, 2, p, l0 - ROELANDS_LN_MU_INF)

    def viscosity_at(self, p, T):
        return np.exp(self.log_viscosity(p, T))

    def dlog_viscosity_dp(self, p, T):
        """∂ ln μ/∂p [1/Pa] of the pressure law with μ₀(T) (0 for p < 0)."""
        a = roelands_log_factor(self.ambient_viscosity(T))
        return rheology_at(self.rheology_law, 3, p, a)

    # -- density, heat ------------------------------------------------------------------
    def _thermal_factor(self, T):
        return 1.0 - self.thermal_expansion * (
            np.asarray(T, dtype=float) - self.density_temperature
        )

    def density_at(self, p, T):
        """ρ(p, T) = ρ_r (ρ/ρ₀)(p) [1 − ε (T − T_r)] [kg/m³] (Dowson–Higginson ratio)."""
        return self.density * rheology_at(self.rheology_law, 0, p) * self._thermal_factor(T)

    def ddensity_dp(self, p, T):
        """∂ρ/∂p [kg/(m³ Pa)]."""
        return self.density * rheology_at(self.rheology_law, 1, p) * self._thermal_factor(T)

    def expansivity(self, T):
        """ε_T = −(1/ρ) ∂ρ/∂T [1/K] (compression heating)."""
        return self.thermal_expansion / self._thermal_factor(T)

    def conductivity(self, p, T):
        """k(p, T) [W/(m K)]."""
        pp = np.maximum(np.asarray(p, dtype=float), 0.0)
        t, ti = celsius(T), self._c["Ti"] - _ZERO_C
        a, b = CONDUCTIVITY_PRESSURE
        return (
            self._c["k_i"]
            * (1.0 - 5.4e-4 * t)
            / (1.0 - 5.4e-4 * ti)
            * (1.0 + a * pp / (1.0 + b * pp))
        )

    def specific_heat_at(self, T):
        """c_p(T) [J/(kg K)]."""
        t, ti = celsius(T), self._c["Ti"] - _ZERO_C
        return self._c["cp_i"] * (1.685 + 0.00339 * t) / (1.685 + 0.00339 * ti)

    def volumetric_heat_capacity(self, p, T):
        """ρ c_p [J/(m³ K)]."""
        return self.density_at(p, T) * self.specific_heat_at(T)

    # -- shear ---------------------------------------------------------------------------
    def eyring_stress_at(self, T):
        """τ_E(T) = τ_E(Tᵢ) T/Tᵢ [Pa]."""
        return self.eyring_stress * np.asarray(T, dtype=float) / self._c["Ti"]

    def _limiting_shear_factor(self, T):
        """max(0.1, 1 − c_L (T − Tᵢ)) [-], the temperature factor of τ_L."""
        dT = np.asarray(T, dtype=float) - self._c["Ti"]
        return np.maximum(0.1, 1.0 - self.limiting_shear_temperature_coefficient * dT)

    def limiting_shear_stress_at(self, p, T):
        """τ_L(p, T) [Pa]."""
        f = self._limiting_shear_factor(T)
        return (
            self.limiting_shear_stress
            + self.limiting_shear_coefficient * np.maximum(np.asarray(p, dtype=float), 0.0)
        ) * f

    # -- isothermal views ----------------------------------------------------------------
    def at(self, T) -> Lubricant:
        """The isothermal :class:`~tribodyn.Lubricant` of this oil at temperature T [K]."""
        return Lubricant(**self._isothermal_values(T))

    def _isothermal_values(self, T) -> dict:
        """The arguments of :meth:`at`."""
        T = float(T)
        mu = float(self.ambient_viscosity(T))
        if self.viscosity_model == "barus":
            alpha = self._c["alpha_i"]
        else:
            alpha = roelands_alpha(self._c["Z"], mu)
        f = float(self._limiting_shear_factor(T))
        return dict(
            viscosity=mu,
            pressure_viscosity=alpha,
            density=float(self.density_at(0.0, T)),
            eyring_stress=float(self.eyring_stress_at(T)),
            limiting_shear_coefficient=self.limiting_shear_coefficient * f,
            limiting_shear_stress=self.limiting_shear_stress * f,
            compressible=self.compressible,
            viscosity_model=self.viscosity_model,
        )

    def isothermal(self) -> Lubricant:
        """The oil at its inlet temperature (what the isothermal solvers use; :meth:`at`
        Tᵢ, its values checked by this oil's constructor)."""
        return self._c["isothermal"]

    def with_inlet_temperature(self, T) -> ThermalLubricant:
        """The same oil supplied at another temperature (α re-estimated if not given)."""
        if self.form == "inlet":
            raise InputError(
                "an inlet-form oil is defined at its inlet temperature; give a datasheet to move it"
            )
        return replace(self, inlet_temperature=float(T))
