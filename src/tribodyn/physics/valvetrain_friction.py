"""Auxiliary friction of a direct-acting valvetrain: the tappet in its bore, the camshaft
journal bearings and the valve stem in its guide (beside the cam–tappet contact).

Each loss is a friction force or torque and its camshaft torque T = P/ω (P the friction
power, ω the cam speed), so that it adds to the cam–tappet contact's camshaft torque
like for like with a motored-engine measurement.

**Tappet in its bore** (bucket of diameter D, guided length L_g, radial clearance c,
lower bore edge a above the face). On the tappet act the cam's normal force W at the
offset e = s' = ds/dθ from the axis, the cam's friction −F_f (F_f signed as in
:func:`tribodyn.workflow.engineering.camshaft_torque`: its camshaft torque is
F_f (r_b + s)) in the face plane, the axial valve force on the axis, and the bore's edge
reactions N_a (lower edge) and N_b (upper edge) of a bucket tilted in its clearance.
Force and moment balance in the plane of the cam:

    N_b = (W e − a F_f) / L_g,        N_a = F_f − N_b                        [N]

The axial bore friction is boundary friction at the edges plus Couette shear of the film
in the clearance (Petroff, concentric):

    F_bore = μ_b (|N_a| + |N_b|) + η π D L_g |v| / c,   v = ω s'             [N]

and its camshaft torque T_bore = F_bore |v| / ω = F_bore |s'|. Measured on a direct-acting
bucket: about 13 % of the cam/tappet/bore friction torque at 250 cam rpm, decreasing with
speed, largest near ±40° cam where the side load is largest (Pieprzak, Willermet & Dailey,
SAE 902086, 1990).

**Camshaft journal bearings** (short-bearing theory, Ocvirk 1952; e.g. Hamrock,
*Fundamentals of Fluid Film Lubrication*, 1994, ch. 10; journal radius R, length L,
radial clearance c, surface speed U = ωR, eccentricity ratio ε). Half-Sommerfeld load
capacity and attitude angle φ:

    W = η U L³ ε / (4 c² (1 − ε²)²) · √(16 ε² + π² (1 − ε²)),
    tan φ = π √(1 − ε²) / (4 ε)

and the journal's friction torque (Couette shear over the full film, plus the pressure
term ε c W sin φ / 2):

    T_j = 2 π η ω R³ L / (c √(1 − ε²)) + ε c W sin φ / 2                     [N m]

which at ε → 0 is Petroff's torque 2 π η ω R³ L / c. The bearing loads come from the
lobes: each lobe's contact force (and friction) is shared by the two bearings either side
of it by the lever rule (quasi-static, rigid camshaft).

**Valve stem in its guide** (stem diameter d, guide length L_s, radial clearance c_s):
Couette shear plus boundary friction at an (assumed) side load N_s,

    F_stem = η π d L_s |v| / c_s + μ_s N_s,   T_stem = F_stem |s'|

(the bucket takes the cam's side load, so N_s is small in a direct-acting valvetrain).

Couette shear of a thin annulus: η π D L v / c is the c ≪ D limit of the exact
2 π η L v / ln(R_o/R_i) (Stokes flow between coaxial cylinders in axial motion).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validation import InputError, check_nonnegative, check_positive, check_range

__all__ = [
    "BoreGeometry",
    "JournalGeometry",
    "GuideGeometry",
    "tappet_side_loads",
    "tappet_bore_friction",
    "annulus_couette_force",
    "short_bearing_load",
    "short_bearing_eccentricity",
    "short_bearing_torque",
    "journal_bearing_loads",
    "valve_guide_friction",
]


def _check_part(part: str, geometry, lengths, thin_film_of: str | None = None) -> None:
    """Checks of a lubricated part's geometry (messages name ``part``): the ``lengths``
    [m] positive; a friction coefficient, if it has one, in [0, 1]; with ``thin_film_of``,
    the radial clearance below 5 % of that length (a thin film)."""
    for k in lengths:
        check_positive(f"{part} {k}", getattr(geometry, k), "m")
    if hasattr(geometry, "friction_coefficient"):
        check_range(f"{part} friction_coefficient", geometry.friction_coefficient, 0.0, 1.0)
    if thin_film_of is not None and geometry.clearance >= 0.05 * getattr(geometry, thin_film_of):
        raise InputError(f"{part} clearance must be below 5 % of the {thin_film_of} (a thin film)")


@dataclass(frozen=True)
class BoreGeometry:
    """Tappet bore: diameter D [m], guided length L_g [m], radial clearance c [m], lower
    edge a above the face [m], boundary friction coefficient μ_b [-]."""

    diameter: float
    guided_length: float
    clearance: float
    edge_offset: float = 0.0
    friction_coefficient: float = 0.1

    def __post_init__(self):
        _check_part("bore", self, ("diameter", "guided_length", "clearance"), "diameter")
        check_nonnegative("bore edge_offset", self.edge_offset, "m")


@dataclass(frozen=True)
class JournalGeometry:
    """Camshaft journal bearing: radius R [m], length L [m], radial clearance c [m]."""

    radius: float
    length: float
    clearance: float

    def __post_init__(self):
        _check_part("journal", self, ("radius", "length", "clearance"), "radius")


@dataclass(frozen=True)
class GuideGeometry:
    """Valve guide: stem diameter d [m], guide length L_s [m], radial clearance c_s [m],
    boundary friction coefficient μ_s [-] and side load N_s [N] (assumed)."""

    stem_diameter: float
    length: float
    clearance: float
    friction_coefficient: float = 0.1
    side_load: float = 0.0

    def __post_init__(self):
        _check_part("guide", self, ("stem_diameter", "length", "clearance"))
        check_nonnegative("guide side_load", self.side_load, "N")


def annulus_couette_force(viscosity, diameter, length, clearance, velocity):
    """Thin-film (Petroff) Couette drag η π D L |v| / c [N] of a rod of diameter D in a
    sleeve of radial clearance c over the length L, sliding axially at v."""
    return viscosity * math.pi * diameter * length * np.abs(velocity) / clearance


def tappet_side_loads(contact_force, friction, lift_velocity, geometry: BoreGeometry):
    """(N_a, N_b) [N]: the bore's edge reactions on a bucket (module docstring) from the
    cam's normal force W [N], its signed friction F_f [N] (NaN, unknown: NaN loads) and
    s' = e [m/rad]."""
    w = np.asarray(contact_force, float)
    f = np.asarray(friction, float)
    e = np.asarray(lift_velocity, float)
    nb = (w * e - geometry.edge_offset * f) / geometry.guided_length
    return f - nb, nb


def tappet_bore_friction(
    contact_force, friction, lift_velocity, cam_speed: float, viscosity, geometry: BoreGeometry
):
    """Tappet–bore friction: returns ``(F_bore [N], T_bore [N m], P_bore [W])``, the
    axial friction force magnitude, its camshaft torque F_bore |s'| and power F_bore |v|
    (module docstring). ``viscosity``: η of the oil in the clearance [Pa s]."""
    na, nb = tappet_side_loads(contact_force, friction, lift_velocity, geometry)
    s1 = np.abs(np.asarray(lift_velocity, float))
    v = cam_speed * s1
    g = geometry
    fb = g.friction_coefficient * (np.abs(na) + np.abs(nb)) + annulus_couette_force(
        viscosity, g.diameter, g.guided_length, g.clearance, v
    )
    return fb, fb * s1, fb * v


def short_bearing_load(eps, viscosity, geometry: JournalGeometry, cam_speed: float):
    """Ocvirk short-bearing load capacity W(ε) [N] and attitude angle φ [rad]."""
    e = np.asarray(eps, float)
    g = geometry
    u = cam_speed * g.radius
    q = 1.0 - e * e
    w = viscosity * u * g.length**3 * e / (4.0 * g.clearance**2 * q * q)
    w = w * np.sqrt(16.0 * e * e + math.pi**2 * q)
    phi = np.arctan2(math.pi * np.sqrt(q), 4.0 * e)
    return w, phi


def short_bearing_eccentricity(load, viscosity, geometry: JournalGeometry, cam_speed: float):
    """ε solving W(ε) = |load| (W is monotonic in ε ∈ [0, 1); bisection to 1e-12); NaN
    where the load is unknown (NaN)."""
    target = np.abs(np.asarray(load, float))
    lo = np.zeros_like(target)
    hi = np.full_like(target, 1.0 - 1e-12)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        w, _ = short_bearing_load(mid, viscosity, geometry, cam_speed)
        big = w > target
        hi = np.where(big, mid, hi)
        lo = np.where(big, lo, mid)
    return np.where(np.isnan(target), np.nan, 0.5 * (lo + hi))


def short_bearing_torque(load, viscosity, geometry: JournalGeometry, cam_speed: float):
    """Friction torque T_j [N m] of a short journal bearing under ``load`` [N] (module
    docstring); returns ``(T_j, ε)``."""
    eps = short_bearing_eccentricity(load, viscosity, geometry, cam_speed)
    g = geometry
    w, phi = short_bearing_load(eps, viscosity, geometry, cam_speed)
    couette = 2.0 * math.pi * viscosity * cam_speed * g.radius**3 * g.length
    couette = couette / (g.clearance * np.sqrt(1.0 - eps * eps))
    return couette + 0.5 * eps * g.clearance * w * np.sin(phi), eps


def journal_bearing_loads(lobe_forces, lobe_positions, bearing_positions):
    """Bearing loads [N] from lobe forces by the lever rule on a statically determinate
    span: each lobe at axial position z_k is carried by the two bearings either side of
    it in proportion to its distance from the other one.

    ``lobe_forces``: (lobe, sample, 2) force vectors in the cam plane (normal force along
    the tappet axis, friction across it); positions in m, bearings sorted. Returns
    (bearing, sample) load magnitudes."""
    f = np.asarray(lobe_forces, float)
    zb = np.asarray(bearing_positions, float)
    if zb.ndim != 1 or zb.size < 2 or np.any(np.diff(zb) <= 0):
        raise InputError("bearing positions must be at least two increasing values")
    out = np.zeros((zb.size,) + f.shape[1:])
    for k, z in enumerate(np.asarray(lobe_positions, float)):
        if not zb[0] <= z <= zb[-1]:
            raise InputError(f"lobe position {z} m lies outside the bearings")
        j = min(int(np.searchsorted(zb, z, side="right")) - 1, zb.size - 2)
        t = (z - zb[j]) / (zb[j + 1] - zb[j])
        out[j] += (1.0 - t) * f[k]
        out[j + 1] += t * f[k]
    return np.linalg.norm(out, axis=-1)


def valve_guide_friction(lift_velocity, cam_speed: float, viscosity, geometry: GuideGeometry):
    """Valve stem friction: ``(F_stem [N], T_stem [N m], P_stem [W])`` (module
    docstring)."""
    s1 = np.abs(np.asarray(lift_velocity, float))
    v = cam_speed * s1
    g = geometry
    f = annulus_couette_force(viscosity, g.stem_diameter, g.length, g.clearance, v)
    f = f + g.friction_coefficient * g.side_load * (v > 0)
    return f, f * s1, f * v
