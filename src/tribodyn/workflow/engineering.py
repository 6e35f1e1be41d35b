"""Engineering outputs of a cam-cycle study: camshaft torque, contact pressure, the cam
kinematics as used, the spring's surge modes against the cam's harmonics, the oil as used,
and plausibility checks of the inputs.

Camshaft torque of a flat-faced follower (DESIGN.md "Engineering outputs"; cam angle θ,
lift s, s' = ds/dθ, base radius r_b): the normal force W acts at the contact offset
e = s' from the follower axis and the tappet face lies at r_b + s from the cam centre, so

    T_f = F_f (r_b + s),        T_drive = W s' + T_f        [N m]

with F_f = (F_v + F_b) sign(u_s) the viscous plus boundary friction of the transient EHL
in the face plane, signed by the sliding direction. ∮T_f dθ over one cam revolution is the
friction energy per cycle (T_f ω = F_f u_s is the friction power, since u_s = ω(r_b + s)),
and for a conservative (frictionless, undamped) train ∮W s' dθ = ∮W ds = 0.

Contact pressure: Hertz p_h = √(w E'/(2πR)) with w = W/l (Johnson, *Contact Mechanics*,
1985, §4.2; E' as in DESIGN.md), beside the EHL peak pressure of each surface set.

Spring surge: a helical spring fixed at both ends with active mass m_s and rate k has the
surge frequencies f_k = (k_mode/2)√(k/m_s), k_mode = 1, 2, … (Wahl, *Mechanical Springs*,
1963, ch. 25): those of a lumped valvetrain. A flexible valvetrain's spring is a coil
continuum of its own (:class:`~tribodyn.valvetrain.spring.HelicalSpring`): its surge
frequencies are the natural frequencies of that continuum held at both ends at the
installed length (valve closed; the same as Wahl's for a uniform pitch, higher for a
progressive spring whose coils touch at installation). The cam excites at the harmonics n·f_cam of the cam frequency with the
amplitudes of the lift's Fourier series (Norton, *Cam Design and Manufacturing Handbook*,
2009, ch. 11). A surge frequency close to a strong harmonic means spring resonance.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..config.build import as_built, build
from ..physics.materials import reduced_modulus
from ..valvetrain.cam_tabulated import TabulatedCam
from ..valvetrain.flexible import FlexibleValvetrain
from ..valvetrain.parameters import ValvetrainParameters

__all__ = [
    "PAPER_CASES",
    "MEASURED_ETA_BETA_SIGMA",
    "Engineering",
    "camshaft_torque",
    "set_torques",
    "compares_paper",
    "engineering_outputs",
    "oil_as_used",
    "plausibility_warnings",
    "surge_spectrum",
]

#: Case names of the paper's bundled case and its variants: their report carries the
#: paper's comparison (claims table, paper figure numbers, Figs. 5/6 at its conditions).
PAPER_CASES = ("andreou2023", "andreou2023_flexible", "andreou2023_thermal")

#: Range of ηβσ of measured engineering surfaces (Greenwood & Williamson 1966: 0.03–0.05;
#: McCool 1986: 0.02–0.08 for ground and honed steel); outside it a warning is given.
MEASURED_ETA_BETA_SIGMA = (0.01, 0.1)


def compares_paper(case, compare_paper: bool | None = None) -> bool:
    """Whether the study carries the paper's comparison: ``compare_paper`` if given,
    else whether ``case`` is the paper's bundled case (:data:`PAPER_CASES`)."""
    if compare_paper is not None:
        return bool(compare_paper)
    return case.name in PAPER_CASES


def camshaft_torque(
    contact_force, friction, lift, lift_velocity, base_radius: float, sliding_speed
) -> tuple[np.ndarray, np.ndarray]:
    """(T_f, T_drive) [N m] from the contact force W [N], the friction magnitude
    F_v + F_b [N], the lift s [m], s' = ds/dθ [m/rad], r_b [m] and the sliding speed
    u_s [m/s] (its sign is the friction's): T_f = F_f (r_b + s), T_drive = W s' + T_f
    (module docstring). A NaN friction (unknown) gives NaN torques."""
    f = np.asarray(friction, float) * np.sign(sliding_speed)
    t_f = f * (base_radius + np.asarray(lift, float))
    return t_f, np.asarray(contact_force, float) * np.asarray(lift_velocity, float) + t_f


def set_torques(study, base_radius: float):
    """The lift s [m] and s' = ds/dθ [m/rad] of the dynamics at the EHL samples of
    ``study``, and per surface set (rows in study order, one column per EHL sample) the
    signed friction F_f = (F_v + F_b) sign(u_s) [N], T_f and T_drive [N m]
    (:func:`camshaft_torque`, cam base radius r_b [m]): ``(s, s', F_f, T_f, T_drive)``.
    An unloaded sample has no friction (0); a loaded one whose EHL step failed has an
    unknown friction, so NaN torques: they are left out of the cycle integrals (as of the
    summary's friction energy, with the failed steps counted) and of the maxima."""
    dyn, inp = study.dynamics, study.inputs
    lift = np.interp(inp.crank_angle, dyn.crank_angle, dyn.cam_lift)
    lift_velocity = np.interp(inp.crank_angle, dyn.crank_angle, dyn.lift_velocity)
    fr = np.array(
        [np.where(r.loaded, r.viscous_friction + r.boundary_friction, 0.0) for r in study.sets]
    )
    t_f, t_d = camshaft_torque(
        inp.contact_force, fr, lift, lift_velocity, base_radius, inp.sliding_speed
    )
    return lift, lift_velocity, fr * np.sign(inp.sliding_speed), t_f, t_d


def cycle_integral(values, crank_deg):
    """∮ values dθ over the cam angle θ = crank/2 [rad] (trapezoids on the samples, along
    the last axis; a float for one trace) — with a torque in N m: the work per cam
    revolution [J]."""
    theta = np.radians(np.asarray(crank_deg, float)) / 2.0
    v = np.nan_to_num(np.ascontiguousarray(values, float))  # rows summed as one trace
    e = np.sum(0.5 * (v[..., 1:] + v[..., :-1]) * np.diff(theta), axis=-1)
    return float(e) if e.ndim == 0 else e


def surge_spectrum(
    cam,
    params: ValvetrainParameters | FlexibleValvetrain,
    cam_speed: float,
    harmonics: int = 40,
    modes: int = 3,
) -> dict:
    """The lift's harmonic amplitudes at n·f_cam [Hz] (at least ``harmonics``, and up to
    the highest surge mode) and the spring's first ``modes`` surge frequencies
    (``params.surge_frequencies``) of a lumped or flexible valvetrain. Returns
    ``{"harmonic_frequency_Hz", "harmonic_amplitude_m", "surge_frequency_Hz", "closest":
    [(mode, harmonic n, f_n, f_surge)]}``."""
    f_cam = cam_speed / (2.0 * math.pi)
    f_s = params.surge_frequencies(modes)
    harmonics = max(harmonics, int(math.ceil(f_s[-1] / f_cam)) + 2)  # up to the last mode
    n = max(2048, 4 * harmonics)
    theta = np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)
    c = np.fft.rfft(np.asarray(cam.lift(theta), float)) / n
    amp = 2.0 * np.abs(c[1 : harmonics + 1])
    f_h = f_cam * np.arange(1, harmonics + 1)
    nearest = [int(round(f / f_cam)) for f in f_s]
    closest = [(k, h, h * f_cam, float(f)) for k, (h, f) in enumerate(zip(nearest, f_s), 1)]
    return {
        "cam_frequency_Hz": f_cam,
        "harmonic_frequency_Hz": f_h,
        "harmonic_amplitude_m": amp,
        "surge_frequency_Hz": f_s,
        "closest": closest,
    }


@dataclass
class Engineering:
    """Engineering outputs of a study (see the module docstring); per-set arrays are
    (set, EHL sample), in study order."""

    lift: np.ndarray  #: s at the EHL samples [m]
    lift_velocity: np.ndarray  #: s' = ds/dθ at the EHL samples [m/rad]
    friction_torque: np.ndarray  #: (set, sample) [N m]
    drive_torque: np.ndarray  #: (set, sample) [N m]
    hertz_pressure: np.ndarray  #: (set, sample) [Pa], NaN where unloaded
    cam_angle_deg: np.ndarray  #: kinematics grid (cam degrees)
    kinematics: dict  #: lift [m], velocity [m/s], acceleration [m/s²], radius [m]
    table: dict | None  #: table points: angle_deg, lift [m], residual [m]; None: no table
    surge: dict
    scalars: dict = field(default_factory=dict)  #: per set name: summary scalars


def engineering_outputs(study) -> Engineering:
    """The :class:`Engineering` outputs of a :class:`~tribodyn.workflow.cycle.CycleStudy`."""
    case, inp = study.case, study.inputs
    built = build(case)
    cam = built.cam
    rb = float(cam.base_radius)
    w = case.cam_speed
    period = 2.0 * math.pi / w
    s, s1, _, tf, td = set_torques(study, rb)
    ph = []
    scalars = {}
    for res, t_f, t_d in zip(study.sets, tf, td):
        e = reduced_modulus(built.set(res.name).surface.bodies)
        load = np.where(res.loaded, inp.contact_force, np.nan) / inp.width
        ph.append(np.sqrt(load * e / (2.0 * math.pi * inp.radius)))
        energy = cycle_integral(t_f, inp.crank_angle)
        L = res.loaded & res.converged
        scalars[res.name] = {
            "mean_friction_torque_Nm": energy / (2.0 * math.pi),
            "max_friction_torque_Nm": _nan_peak(t_f, signed=False),
            "peak_drive_torque_Nm": _nan_peak(t_d),
            "friction_energy_per_cycle_from_torque_J": energy,
            "mean_friction_power_from_torque_W": energy / period,
            "max_hertz_pressure_Pa": float(np.nanmax(ph[-1]))
            if np.isfinite(ph[-1]).any()
            else None,
            "max_ehl_pressure_Pa": float(np.nanmax(res.max_pressure[L])) if L.any() else None,
        }
    theta = np.radians(np.arange(0.0, 360.0, 0.5))
    ls, l1, l2 = cam.derivatives(theta)
    kin = {"lift": ls, "velocity": l1 * w, "acceleration": l2 * w * w, "radius": rb + ls + l2}
    table = None
    if isinstance(cam, TabulatedCam):
        fitted = cam.derivatives(np.asarray(cam.angle))[0]
        table = {
            "angle_deg": np.degrees(np.asarray(cam.angle)),
            "lift": np.asarray(cam.lift_table),
            "residual": np.asarray(cam.lift_table) - fitted,
        }
    return Engineering(
        lift=s,
        lift_velocity=s1,
        friction_torque=tf,
        drive_torque=td,
        hertz_pressure=np.array(ph),
        cam_angle_deg=np.degrees(theta),
        kinematics=kin,
        table=table,
        surge=surge_spectrum(cam, built.valvetrain, w),
        scalars=scalars,
    )


def _nan_peak(values, *, signed: bool = True) -> float | None:
    """The largest value (``signed``: the value of largest magnitude, with its sign) of
    the known (not NaN) ``values``; None if none is known."""
    v = np.asarray(values, float)
    known = v[~np.isnan(v)]
    if known.size == 0:
        return None
    return float(known[np.argmax(np.abs(known))] if signed else known.max())


def oil_as_used(case) -> dict:
    """The oil the study of ``case`` (a Case or BuiltCase) used (at the inlet): μ₀
    [Pa s], α [1/Pa], ρ₀ [kg/m³], inlet temperature [°C] (None: not given, the viscosity
    was given directly), its laws."""
    built = as_built(case)
    lub = built.lubricant
    c = built.case.lubricant_config
    return {
        "oil": c.oil,
        "inlet_temperature_C": c.inlet_temperature_c,
        "viscosity_Pa_s": float(lub.viscosity),
        "pressure_viscosity_1_Pa": float(lub.pressure_viscosity),
        "density_kg_m3": float(lub.density),
        "eyring_stress_Pa": float(lub.eyring_stress),
        "limiting_shear_coefficient": float(lub.limiting_shear_coefficient),
        "viscosity_model": lub.viscosity_model,
        "compressible": bool(lub.compressible),
        "from_datasheet": bool(c.datasheet),
    }


#: RMS profile slope √m₂ below which a Greenwood–Tripp roughness is "smoother in slope
#: than ground steel": half the slope of the default surface law's typical spectrum
#: (σ 0.2 µm, physics.typical: √m₂ ≈ 0.06), the low end of its short-cutoff range.
SMOOTH_SLOPE = 0.03


def _typical_surface_share(s, lam: float, w: float, b: float) -> float:
    """Load share p_a/p_mean at λ of the default surface law (a self-affine surface with
    the set's σ and the typical spectrum,
    :func:`~tribodyn.config.measured_surface.typical_surface_law`) at the pair's surface
    E'; p_mean = w/(2b)."""
    from ..config.measured_surface import typical_surface_law

    law = typical_surface_law(s.roughness.rms, s.bodies)
    p = law.reduced_modulus * float(law.pressure_ratio(np.array([lam]))[0][0])
    return min(1.0, p * 2.0 * b / w)


def typical_surface_laws(case) -> list:
    """The default surface laws :func:`plausibility_warnings` may compare the
    Greenwood–Tripp sets of ``case`` (a Case or BuiltCase) with, one per such set
    (cached: computing them ahead, e.g. at ``tribodyn warmup``, keeps them off a run)."""
    from ..config.measured_surface import typical_surface_law

    return [
        typical_surface_law(s.roughness.rms, s.bodies)
        for s in as_built(case).surface_sets
        if s.roughness is not None and s.roughness.law is None
    ]


def plausibility_warnings(study) -> list[str]:
    """Inputs and results that are physically suspicious for the asperity law in use,
    each with what it affects and what to change:

    * Greenwood–Tripp sets only: ηβσ outside :data:`MEASURED_ETA_BETA_SIGMA` (measured
      engineering surfaces; Greenwood & Williamson 1966, McCool 1986).
    * Greenwood–Tripp sets only: λ = h_min/σ < 1 while the asperities carry less than a
      tenth of what the default surface law (a self-affine surface with the set's σ and
      the typical spectrum of :mod:`tribodyn.physics.typical`) carries there: the share
      p_a/p_mean, p_mean = w/(2b) of the Hertz contact. The warning gives the RMS slope
      that the set's η, β, σ imply (:attr:`~tribodyn.Roughness.implied_rms_slope`).
    * Any law: λ < 0.1 while the asperities carry less than half of the load: a film
      thinner than a tenth of the roughness cannot carry most of the load on real
      surfaces (a rule of thumb, flagged as such).
    """
    built, inp = build(study.case), study.inputs
    lo, hi = MEASURED_ETA_BETA_SIGMA
    out = []
    for res in study.sets:
        s = built.set(res.name).surface
        r = s.roughness
        assert r is not None  # a case's surface sets are rough
        gt = r.law is None
        ebs = r.roughness_parameter
        if gt and not lo <= ebs <= hi:
            out.append(
                f"{res.name}: roughness ηβσ = {ebs:.2g} is outside {lo:g}–{hi:g}, the range "
                "of measured engineering surfaces (Greenwood & Williamson 1966, McCool "
                "1986): the asperity load, boundary friction and friction energy of this "
                f"set are {'too low' if ebs < lo else 'too high'} if the surface is real; "
                "check asperity_density, summit_radius and rms of its roughness (from a "
                "profile: tribodyn topography), or use the surface law (remove "
                'asperity_model = "greenwood_tripp")'
            )
        ok = res.loaded & res.converged & np.isfinite(res.lambda_ratio)
        if not ok.any():
            continue
        i = int(np.flatnonzero(ok)[np.argmin(res.lambda_ratio[ok])])
        lam = float(res.lambda_ratio[i])
        if lam >= 1.0:
            continue
        share = float(res.asperity_load[i] / max(inp.contact_force[i], 1e-12))
        e = reduced_modulus(s.bodies)
        w = inp.contact_force[i] / inp.width
        b = math.sqrt(8.0 * w * inp.radius[i] / (math.pi * e))
        where = f"{res.name}: at λ = {lam:.2g} ({inp.crank_angle[i]:.0f}° crank)"
        # the share of the surface law is at most 1: a share of 0.1 or more needs no law
        if gt and share < 0.1:
            ref = _typical_surface_share(s, lam, w, b)
            if share < 0.1 * ref:
                slope = r.implied_rms_slope
                smooth = (
                    f"; its ηβσ = {ebs:.2g} and σ/β = {r.rms / r.summit_radius:.2g} imply an "
                    f"RMS slope of {slope:.2g} (Nayak/McCool), smoother than ground steel"
                    if slope < SMOOTH_SLOPE
                    else ""
                )
                out.append(
                    f"{where} the asperities carry {share * 100:.2g} % of the load with "
                    f"Greenwood–Tripp; the surface law of a typical ground surface with the "
                    f"same σ carries {ref * 100:.3g} % there{smooth}: the boundary friction "
                    "and asperity load of this set are likely far too low. Use the surface "
                    'law (remove asperity_model = "greenwood_tripp", or give '
                    "measured_surface from a measured map)"
                )
                continue
        if lam < 0.1 and share < 0.5:
            out.append(
                f"{where} the film is thinner than a tenth of the roughness, yet the "
                f"asperities carry only {share * 100:.2g} % of the load: real surfaces "
                "carry most of the load there (a rule of thumb), so the boundary friction "
                "and asperity load near this angle are likely too low and the film too "
                "optimistic; check the roughness rms of the set and its surface (a "
                + (
                    'measured_surface, or the surface law in place of asperity_model = "greenwood_tripp")'
                    if gt
                    else "measured_surface from a measured map)"
                )
            )
    return out
