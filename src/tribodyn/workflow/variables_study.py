"""The variables of a cycle study's Dataset (``results.nc``): the table of
:mod:`~tribodyn.workflow.variables`, extracted from a :class:`StudySource`.

Groups, in the order written: dynamics over ``crank_angle`` (and the implicit coupling's
curves), the transient-EHL samples over ``ehl_crank`` and ``(surface_set, ehl_crank)``
with the regime map of the Greenwood chart over ``(chart_gV, chart_gE)``, the pressure
and film profiles, the representative points, the single-contact coating studies
(Figs. 5, 6), the subsurface stresses and safety factors with the stress map of
each set, the engineering outputs (camshaft torque, cam kinematics, lift table, spring
surge), the oil as used and the thermal variables. EHL quantities are NaN where the
contact carries no load.
"""

from __future__ import annotations

from functools import cached_property

import numpy as np

from ..config.build import build
from ..physics.regimes import REGIMES
from .conventions import CRANK_ANGLE
from .stress_study import MODE_PEAK, PEAKS
from .variables import Group, Variable, var

__all__ = ["StudySource", "STUDY", "THERMAL_GROUP", "ALL", "DYNAMICS", "EHL", "SET_DESCRIPTION"]


class StudySource:
    """What the study's variables are extracted from: the study and what is derived from
    it once (analysis, engineering outputs, oil as used, common profile grids). A source
    with only ``dynamics`` serves the dynamics traces of a dynamics-only sweep point."""

    def __init__(self, study=None, *, dynamics=None):
        self.study = study
        self.dynamics = study.dynamics if study is not None else dynamics

    def __getattr__(self, name: str):
        """The study's own fields (case, inputs, sets, stresses, isothermal_sets, …)."""
        if name.startswith("__") or "study" not in self.__dict__:
            raise AttributeError(name)
        return getattr(self.study, name)

    @cached_property
    def built(self):
        """The study's :class:`~tribodyn.config.build.BuiltCase`."""
        return build(self.study.case)

    @cached_property
    def analysis(self):
        return self.study.analyse()

    @cached_property
    def engineering(self):
        return self.study.engineering_outputs()

    @cached_property
    def oil(self) -> dict:
        from .engineering import oil_as_used

        return oil_as_used(self.built)

    @cached_property
    def dry_x(self) -> np.ndarray:
        from .coating_study import dry_grid

        return dry_grid(self.study.dry)

    @cached_property
    def ehl_x(self) -> np.ndarray:
        r = self.study.ehl_coating.results
        return np.linspace(max(q.x[0] for q in r), min(q.x[-1] for q in r), 601)


S = StudySource
TWO = ("surface_set", "ehl_crank")
THREE = ("surface_set", "ehl_crank", "k")


def _dyn(k):
    return lambda s: getattr(s.dynamics, k)


def _per_set(k, sets=lambda s: s.sets):
    return lambda s: np.array([getattr(r, k) for r in sets(s)])


def _names(s: S) -> list[str]:
    return [r.name for r in s.sets]


#: dynamics over crank_angle (name, units, description)
_DYN = (
    ("contact_force", "N", "cam–tappet contact force (total over the width)"),
    ("tappet_displacement", "m", "tappet displacement"),
    ("tappet_velocity", "m/s", "tappet velocity"),
    ("tappet_acceleration", "m/s²", "tappet acceleration"),
    ("valve_lift", "m", "valve lift"),
    ("seat_force", "N", "valve seat force"),
    ("cam_lift", "m", "cam lift s"),
    ("cam_torque", "N·m", "camshaft drive torque"),
    ("friction_power", "W", "contact friction power (analytic tribology of the dynamics)"),
    ("entrainment_speed", "m/s", "entraining speed u_e"),
    ("sliding_speed", "m/s", "sliding speed u_s"),
    ("radius_of_curvature", "m", "radius of curvature R of the cam at the contact"),
    ("contact_offset", "m", "contact offset e on the tappet face"),
)
DYNAMICS: dict[str, Variable] = {
    ("analytic_friction_power" if k == "friction_power" else k): var(
        "analytic_friction_power" if k == "friction_power" else k, "crank_angle", u, d, _dyn(k)
    )
    for k, u, d in _DYN
}
CRANK = var("crank_angle", "crank_angle", "deg", CRANK_ANGLE, _dyn("crank_angle"), coord=True)


def _implicit(k):
    return lambda s: np.interp(
        s.dynamics.crank_angle, s.study.implicit.crank_angle, getattr(s.study.implicit, k)
    )


IMPLICIT = tuple(
    var(
        k + "_implicit",
        "crank_angle",
        DYNAMICS[k].units,
        DYNAMICS[k].description + " (implicit: numerical EHL in the dynamics)",
        _implicit(k),
    )
    for k in ("contact_force", "tappet_velocity", "tappet_acceleration", "valve_lift")
)

#: the surface sets and their description (data variables here, coordinates in a sweep)
SET_DESCRIPTION = (
    var(
        "surface_label",
        "surface_set",
        None,
        "tappet surface",
        lambda s: [s.study.labels[n] for n in _names(s)],
    ),
    var(
        "coating_material",
        "surface_set",
        None,
        "coating material key ('' = uncoated)",
        lambda s: [s.built.set(n).surface.coating_material or "" for n in _names(s)],
    ),
    var(
        "coating_thickness",
        "surface_set",
        "m",
        "coating thickness (0 = uncoated)",
        lambda s: [
            c.thickness if (c := s.built.set(n).surface.coating) is not None else 0.0
            for n in _names(s)
        ],
    ),
)
SURFACE_SET = var(
    "surface_set", "surface_set", None, "surface set (name in the case file)", _names, coord=True
)
EHL_CRANK = var(
    "ehl_crank",
    "ehl_crank",
    "deg",
    f"crank angle of the transient-EHL samples: {CRANK_ANGLE}",
    lambda s: s.inputs.crank_angle,
    coord=True,
)
CONDITIONS = (
    var("ehl_contact_force", "ehl_crank", "N", "contact force at the EHL samples",
        lambda s: s.inputs.contact_force),
    var("ehl_entrainment_speed", "ehl_crank", "m/s", "u_e at the EHL samples",
        lambda s: s.inputs.entrainment_speed),
    var("ehl_sliding_speed", "ehl_crank", "m/s", "u_s at the EHL samples",
        lambda s: s.inputs.sliding_speed),
    var("ehl_radius", "ehl_crank", "m", "R at the EHL samples", lambda s: s.inputs.radius),
)  # fmt: skip
_CODES = " ".join(str(k) for k in range(len(REGIMES)))  # the regimes' flag values
REGIME = (
    var("gV", "ehl_crank", "1", "Greenwood-chart viscosity group g_V", lambda s: s.analysis.gV),
    var("gE", "ehl_crank", "1", "Greenwood-chart elasticity group g_E", lambda s: s.analysis.gE),
    var(
        "regime",
        "ehl_crank",
        "1",
        "lubrication regime",
        lambda s: s.analysis.regime,
        attrs={"flag_values": f"-1 {_CODES}", "flag_meanings": "unloaded " + " ".join(REGIMES)},
    ),
    var(
        "in_event",
        "ehl_crank",
        "1",
        "inside the cam lift event (lift > 10 µm)",
        lambda s: s.analysis.in_event,
        dtype=np.int8,
    ),
    var("chart_gE", "chart_gE", "1", "g_E axis of the Greenwood chart",
        lambda s: s.analysis.regime_map.gE, coord=True),
    var("chart_gV", "chart_gV", "1", "g_V axis of the Greenwood chart",
        lambda s: s.analysis.regime_map.gV, coord=True),
    var(
        "regime_map",
        ("chart_gV", "chart_gE"),
        "1",
        "lubrication regime on the Greenwood chart",
        lambda s: s.analysis.regime_map.regime,
        dtype=np.int8,
        attrs={"flag_values": _CODES, "flag_meanings": " ".join(REGIMES)},
    ),
)  # fmt: skip
LOADED = var("loaded", TWO, "1", "contact loaded (EHL solved)", _per_set("loaded"), dtype=np.int8)
CONVERGED = var("converged", TWO, "1", "EHL step converged", _per_set("converged"), dtype=np.int8)
_EHL = (
    ("central_film", "m", "central film thickness h_c (x = 0)"),
    ("min_film", "m", "minimum film thickness h_min"),
    ("max_pressure", "Pa", "maximum hydrodynamic pressure"),
    ("hydrodynamic_load", "N", "load carried by the fluid (total over the width)"),
    ("asperity_load", "N", "load carried by the asperities (total over the width)"),
    ("viscous_friction", "N", "viscous (Couette) friction force"),
    (
        "viscous_friction_newtonian",
        "N",
        "viscous friction with the Newtonian law (Eq. 16), same film and pressure",
    ),
    (
        "viscous_friction_eyring",
        "N",
        "viscous friction with the Eyring law, same film and pressure",
    ),
    ("boundary_friction", "N", "boundary friction force"),
    (
        "rolling_friction",
        "N",
        "hydrodynamic rolling force (Poiseuille part of Eq. 16) on each surface, cam and "
        "tappet alike, > 0 against the entrainment; not in the friction total",
    ),
    ("friction_power", "W", "friction power (viscous + boundary) × u_s"),
    ("lambda_ratio", "1", "λ = h_min/σ"),
)
#: transient-EHL results over (surface_set, ehl_crank)
EHL: dict[str, Variable] = {k: var(k, TWO, u, d, _per_set(k)) for k, u, d in _EHL}
PROFILES = (
    var(
        "k",
        "k",
        "1",
        "profile sample index (each step's whole solver domain, uniform)",
        lambda s: np.arange(s.sets[0].x.shape[1]),
        coord=True,
    ),
    var("profile_x", THREE, "m",
        "position along the contact (positive in the direction of positive u_e)", _per_set("x")),
    var("pressure", THREE, "Pa", "hydrodynamic pressure p(x)", _per_set("pressure")),
    var("film", THREE, "m", "film thickness h(x)", _per_set("film")),
    var("point", "point", "1", "representative point (Fig. 13), numbered from 1",
        lambda s: np.arange(1, s.analysis.point_crank.size + 1), coord=True),
    var("point_crank", "point", "deg", "crank angle of the representative points (Fig. 13)",
        lambda s: s.analysis.point_crank),
)  # fmt: skip


def _dry_pressure(s: S):
    return np.array(
        [np.interp(s.dry_x, c.result.x, c.result.pressure, left=0, right=0) for c in s.study.dry]
    )


DRY = (
    var("dry_x", "dry_x", "m", "position along the dry contact (Fig. 5)", lambda s: s.dry_x,
        coord=True),
    var("dry_ratio", "dry_ratio", "1", "coating/steel modulus ratio",
        lambda s: [c.ratio for c in s.study.dry], coord=True),
    var("dry_pressure", ("dry_ratio", "dry_x"), "Pa", "dry contact pressure (Fig. 5)",
        _dry_pressure),
    var("dry_half_width", "dry_ratio", "m", "dry contact half-width (Fig. 5)",
        lambda s: [c.result.half_width for c in s.study.dry]),
    var("dry_max_pressure", "dry_ratio", "Pa", "dry contact maximum pressure (Fig. 5)",
        lambda s: [c.result.max_pressure for c in s.study.dry]),
)  # fmt: skip
#: the Hertz contact of uncoated steel at the dry study's conditions (Fig. 5's reference)
DRY_HERTZ = (
    var("dry_hertz_x", "dry_hertz_x", "m", "position along the Hertz reference contact "
        "(Fig. 5)", lambda s: s.study.dry_hertz.x, coord=True),
    var("dry_hertz_pressure", "dry_hertz_x", "Pa", "Hertz pressure of uncoated steel at "
        "the dry study's conditions (Fig. 5)", lambda s: s.study.dry_hertz.pressure),
    var("dry_hertz_half_width", (), "m", "Hertz half-width of uncoated steel (Fig. 5)",
        lambda s: s.study.dry_hertz.half_width),
    var("dry_hertz_max_pressure", (), "Pa", "Hertz maximum pressure of uncoated steel "
        "(Fig. 5)", lambda s: s.study.dry_hertz.max_pressure),
)  # fmt: skip


def _ehl_coating(dim) -> tuple[Variable, ...]:
    cases = "ratios" if dim == "ehl_ratio" else "pairs"  # of the EHLCoatingStudy
    what = "modulus ratio" if dim == "ehl_ratio" else "surface pair"

    def r(s: S):
        return [c.result for c in getattr(s.study.ehl_coating, cases)]

    return (
        var(f"{dim}_pressure", (dim, "ehl_x"), "Pa", "EHL pressure (Fig. 6)",
            lambda s: np.array([np.interp(s.ehl_x, q.x, q.pressure) for q in r(s)])),
        var(f"{dim}_film", (dim, "ehl_x"), "m", "EHL film (Fig. 6)",
            lambda s: np.array([np.interp(s.ehl_x, q.x, q.film) for q in r(s)])),
        var(f"{dim}_central_film", dim, "m", f"EHL central film per {what} (Fig. 6)",
            lambda s: [q.central_film for q in r(s)]),
        var(f"{dim}_min_film", dim, "m", f"EHL minimum film per {what} (Fig. 6)",
            lambda s: [q.min_film for q in r(s)]),
        var(f"{dim}_converged", dim, "1", f"EHL solution converged, per {what} (Fig. 6)",
            lambda s: [q.converged for q in r(s)], dtype=np.int8),
    )  # fmt: skip


EHL_COATING = (
    var("ehl_x", "ehl_x", "m", "position along the EHL contact (Fig. 6)", lambda s: s.ehl_x,
        coord=True),
    var("ehl_ratio", "ehl_ratio", "1", "coating/steel modulus ratio (Fig. 6)",
        lambda s: [c.ratio for c in s.study.ehl_coating.ratios], coord=True),
    var("ehl_pair", "ehl_pair", None, "surface pair (Fig. 6)",
        lambda s: [c.label for c in s.study.ehl_coating.pairs], coord=True),
    *_ehl_coating("ehl_ratio"),
    *_ehl_coating("ehl_pair"),
)  # fmt: skip

#: long names of the stress peaks (workflow.stress_study.PEAKS)
PEAK_NAMES = {
    "max_von_mises_coating": "largest von Mises stress in the coating",
    "max_von_mises_substrate": "largest von Mises stress in the substrate (whole body if uncoated)",
    "max_tension_surface": "largest tensile principal stress on the surface",
    "max_tension_coating": "largest tensile principal stress in the coating",
    "max_interface_shear": "largest |shear stress| at the coating–substrate interface",
    "max_interface_tension": "largest tensile normal stress at the coating–substrate interface",
}


def _stress_trace(body, peak, q):
    """(surface_set, ehl_crank) trace of one stress peak (``q``: value, x or z); NaN for
    the sets whose stresses were not computed."""

    def extract(s: S):
        out = np.full((len(s.sets), s.inputs.crank_angle.size), np.nan)
        for i, r in enumerate(s.sets):
            cs = s.stresses.get(r.name)
            if cs is not None:
                out[i] = getattr(getattr(cs, body), q)[peak]
        return out

    return extract


def _safety(body, mode):
    def extract(s: S):
        st = s.stresses
        return [
            float(st[r.name].safety_factors[body].get(mode, np.nan)) if r.name in st else np.nan
            for r in s.sets
        ]

    return extract


def _stress_variables() -> tuple[Variable, ...]:
    out = []
    for body in ("cam", "tappet"):
        for peak in PEAKS:
            name, long = f"stress_{body}_{peak}", f"{PEAK_NAMES[peak]}, {body}"
            out += [
                var(name, TWO, "Pa", long, _stress_trace(body, peak, "value")),
                var(name + "_x", TWO, "m", f"position along the contact of: {long}",
                    _stress_trace(body, peak, "x")),
                var(name + "_z", TWO, "m", f"depth below the surface of: {long}",
                    _stress_trace(body, peak, "z")),
            ]  # fmt: skip
        out += [
            var(
                f"safety_factor_{body}_{mode}",
                "surface_set",
                "1",
                f"safety factor (strength / cycle maximum) of the {body} against "
                f"{mode.replace('_', ' ')}; inf: not loaded in this mode, NaN: no strength",
                _safety(body, mode),
            )
            for mode in MODE_PEAK
        ]
    return tuple(out)


STRESSES = _stress_variables()


def _maps(s: S) -> list:
    """The stress map of each set (workflow.stress_map), None where there is none."""
    return [getattr(s.stresses.get(n), "map", None) for n in _names(s)]


def _padded(field: str, axis: str | None = None):
    """(surface_set, …) array of a map field, NaN-padded to the longest set; ``axis``
    "z"/"x" pads a field over depths or x, None the 2-D von Mises field."""

    def extract(s: S):
        maps = _maps(s)
        nz = max((m.depths.size for m in maps if m is not None), default=0)
        nx = max((m.x.size for m in maps if m is not None), default=0)
        shape = {"z": (nz,), "x": (nx,), None: (nz, nx)}[axis]
        out = np.full((len(maps), *shape), np.nan)
        for i, m in enumerate(maps):
            if m is not None:
                v = getattr(m, field)
                out[i][tuple(slice(0, n) for n in v.shape)] = v
        return out

    return extract


def _map_scalar(field: str, empty):
    return lambda s: [empty if m is None else getattr(m, field) for m in _maps(s)]


MAP = ("surface_set", "map_z", "map_x")
#: the von Mises field at the instant of greatest risk per set (the report's stress map)
STRESS_MAP = (
    var("stress_map_x", MAP[::2], "m", "position along the contact of the stress map "
        "(NaN: padding)", _padded("x", "x")),
    var("stress_map_depth", MAP[:2], "m", "depth below the surface of the stress map "
        "(NaN: padding)", _padded("depths", "z")),
    var("stress_map_von_mises", MAP, "Pa", "von Mises stress of the body closest to "
        "failure at its instant of greatest risk (NaN: padding)", _padded("von_mises")),
    var("stress_map_body", "surface_set", None, "body of the stress map: cam or tappet "
        "('' = no map)", _map_scalar("body", "")),
    var("stress_map_mode", "surface_set", None, "failure mode of the smallest safety "
        "factor, governing the stress map ('' = no map)", _map_scalar("mode", "")),
    var("stress_map_sample", "surface_set", "1", "EHL sample (index along ehl_crank) of "
        "the stress map (-1 = no map)", _map_scalar("index", -1), dtype=np.int32),
    var("stress_map_coating_thickness", "surface_set", "m", "coating thickness of the "
        "body of the stress map (0 = uncoated or no map)",
        lambda s: [0.0 if m is None or m.coating_thickness is None else m.coating_thickness
                   for m in _maps(s)]),
)  # fmt: skip


def _eng(k):
    return lambda s: getattr(s.engineering, k)


def _kinematics(key):
    return lambda s: s.engineering.kinematics[key]


ENGINEERING = (
    var("camshaft_friction_torque", TWO, "N m",
        "camshaft friction torque T_f = F_f (r_b + s), F_f = viscous + boundary "
        "friction of the EHL signed by the sliding direction (0 where unloaded)",
        _eng("friction_torque")),
    var("camshaft_drive_torque", TWO, "N m",
        "camshaft drive torque T = W s' + F_f (r_b + s) (W contact force, s' = ds/dθ "
        "the contact offset on the tappet)", _eng("drive_torque")),
    var("hertz_pressure", TWO, "Pa", "Hertz maximum pressure p_h = √(w E'/(2πR))",
        _eng("hertz_pressure")),
    var("ehl_lift", "ehl_crank", "m", "cam lift s at the EHL samples", _eng("lift")),
    var("ehl_contact_offset", "ehl_crank", "m", "contact offset e = s' at the EHL samples",
        _eng("lift_velocity")),
    var("cam_angle_deg", "cam_angle_deg", "deg", "cam angle (kinematics grid)",
        _eng("cam_angle_deg"), coord=True),
    *(
        var(name, "cam_angle_deg", u, d, _kinematics(key))
        for name, key, u, d in (
            ("kinematic_lift", "lift", "m", "cam lift s(θ) of the fitted profile"),
            ("kinematic_velocity", "velocity", "m/s", "tappet velocity s'ω (rigid)"),
            ("kinematic_acceleration", "acceleration", "m/s²", "tappet acceleration s''ω²"),
            ("kinematic_radius", "radius", "m", "radius of curvature r_b + s + s''"),
        )
    ),
)  # fmt: skip
TABLE = (
    var("table_angle_deg", "table_angle_deg", "deg", "cam angle of the table points",
        lambda s: s.engineering.table["angle_deg"], coord=True),
    var("table_lift", "table_angle_deg", "m", "lift table",
        lambda s: s.engineering.table["lift"]),
    var("table_fit_residual", "table_angle_deg", "m",
        "table lift minus the fitted profile at the table points",
        lambda s: s.engineering.table["residual"]),
)  # fmt: skip
SURGE = (
    var("harmonic", "harmonic", "1", "cam excitation harmonic number n",
        lambda s: np.arange(1, s.engineering.surge["harmonic_amplitude_m"].size + 1), coord=True),
    var("harmonic_frequency", "harmonic", "Hz", "cam excitation harmonic n f_cam",
        lambda s: s.engineering.surge["harmonic_frequency_Hz"]),
    var("harmonic_amplitude", "harmonic", "m", "amplitude of the lift's harmonic n",
        lambda s: s.engineering.surge["harmonic_amplitude_m"]),
    var("surge_mode", "surge_mode", "1", "valve-spring surge mode number k",
        lambda s: np.arange(1, s.engineering.surge["surge_frequency_Hz"].size + 1), coord=True),
    var("surge_frequency", "surge_mode", "Hz",
        "valve-spring surge frequency (k/2)√(k_s/m_s), both ends fixed",
        lambda s: s.engineering.surge["surge_frequency_Hz"]),
)  # fmt: skip
OIL = (
    var("oil_viscosity", (), "Pa s", "oil dynamic viscosity μ₀ at the inlet",
        lambda s: s.oil["viscosity_Pa_s"]),
    var("oil_pressure_viscosity", (), "1/Pa", "oil α (inlet)",
        lambda s: s.oil["pressure_viscosity_1_Pa"]),
    var("oil_density", (), "kg/m³", "oil density ρ₀ at the inlet",
        lambda s: s.oil["density_kg_m3"]),
    var("oil_inlet_temperature", (), "degC",
        "oil inlet temperature (NaN: not given; the viscosity was given directly)",
        lambda s: np.nan if (t := s.oil["inlet_temperature_C"]) is None else t),
)  # fmt: skip

_TEMPERATURES = (
    ("max_temperature", "maximum temperature of film and surfaces"),
    ("mid_film_temperature", "mid-film temperature at the contact centre"),
    ("surface_temperature_cam", "maximum surface temperature of the cam"),
    ("surface_temperature_tappet", "maximum surface temperature of the tappet (coating)"),
    ("mean_film_temperature", "film-mean temperature at the contact centre"),
)
_ISO = (
    ("central_film", "central film, isothermal model at the inlet temperature"),
    ("min_film", "minimum film, isothermal model"),
    ("viscous_friction", "viscous friction, isothermal model"),
    ("boundary_friction", "boundary friction, isothermal model"),
    ("friction_power", "friction power, isothermal model"),
    ("asperity_load", "asperity load, isothermal model"),
)


def _iso(s: S):
    return s.isothermal_sets


#: a thermal study's temperatures [K] and its isothermal run (suffix ``_isothermal``)
THERMAL = (
    *(var(k, TWO, "K", d, _per_set(k)) for k, d in _TEMPERATURES),
    *(var(k + "_isothermal", TWO, EHL[k].units, d, _per_set(k, _iso)) for k, d in _ISO),
    var("converged_isothermal", TWO, "1", "isothermal EHL step converged",
        _per_set("converged", _iso), dtype=np.int8),
)  # fmt: skip


def _has_engineering(s: S) -> bool:
    return s.engineering is not None


ITERATIONS = var(
    "iterations", TWO, "1", "Newton iterations", _per_set("iterations"), dtype=np.int32
)
#: the study Dataset, group by group in the order written (the thermal group is written by
#: tribodyn.output.dataset)
STUDY = (
    Group((CRANK, *DYNAMICS.values())),
    Group(IMPLICIT, when=lambda s: s.study.implicit is not None),
    Group(
        (EHL_CRANK, SURFACE_SET, *SET_DESCRIPTION, *CONDITIONS, *REGIME, LOADED, CONVERGED,
         ITERATIONS, *EHL.values(), *PROFILES)
    ),
    Group(DRY, when=lambda s: bool(s.study.dry)),
    Group(DRY_HERTZ, when=lambda s: getattr(s.study, "dry_hertz", None) is not None),
    Group(EHL_COATING,
          when=lambda s: (e := s.study.ehl_coating) is not None and bool(e.results)),
    Group(STRESSES, when=lambda s: bool(s.stresses)),
    Group(STRESS_MAP, when=lambda s: any(m is not None for m in _maps(s))),
    Group(ENGINEERING, when=_has_engineering),
    Group(TABLE, when=lambda s: _has_engineering(s) and s.engineering.table is not None),
    Group(SURGE, when=_has_engineering),
    Group(OIL),
)  # fmt: skip
THERMAL_GROUP = Group(THERMAL, when=lambda s: s.isothermal_sets is not None)

ALL: tuple[Variable, ...] = (*(v for g in STUDY for v in g), *THERMAL)
