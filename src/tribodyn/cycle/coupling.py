"""Implicit coupling of the valvetrain dynamics and the numerical (transient) EHL.

The paper's "implicit" model solves the EHL inside the multi-body dynamics, so that the
film acts in series with the contact stiffness and the EHL friction acts on the bodies.
Here the two are coupled by waveform relaxation, which converges to the same coupled
solution:

1. dynamics with a film model (initially none: the explicit run) → F(t), u_e, u_s, R;
2. transient EHL along the presented cycle → central film h_E(t), friction F_f(t);
3. dynamics again with the film thickness h as a state, in series with the contact
   stiffness (valvetrain ``FilmStateTribology``):
   F_c = F_ent(h; u_e, R, r(t)) + F_sq(h, ḣ), the load of a steady entraining film
   (Martin + Moes elastic-piezoviscous, bounded by the oil supply h_s =
   ``numerics.coupling_supply_film``) plus the rigid-cylinder squeeze film, and the EHL
   friction coefficient μ_k(t) = F_f/F; repeat until the contact force stops changing.

What is iterated is only a correction r_k of the reduced film model towards the
transient EHL at its samples (:func:`film_correction_from_ehl`: the factor on the
model's flooded film for which its entraining film carries F_k + D ḣ_E at the EHL's film
h_E), and μ_k. Between the samples the film's physics (entrainment, squeeze, supply)
shapes the force; r varies slowly and is interpolated in ln r. The film separates the
surfaces from metal contact, the explicit run's zero-lash datum (δ_el = δ_kin + h). Off
the lobe the tappet rides on the film, which lifts it off metal contact and so preloads
the valvetrain chain with tens of N (like a hydraulic lash adjuster's preload): the
valve opens a fraction of a degree earlier and closes later than in the explicit run.
The opening ramp squeezes the film while it picks up the load; after seating it
recovers.

Limits (measured; docs/convergence.md):

- h_s is an assumed supply (default 10 µm); it bounds the film (the base-circle film is
  1.35–1.63 µm at 4000 rpm, 1.12–1.35 µm at h_s = 3 µm), and the valve timing moves by
  0.01° when h_s doubles from 10 to 20 µm (tested: < 0.1°); a lash or an adjuster's
  own preload is not modelled: the datum is zero lash;
- the squeeze film is full-Sommerfeld, so it also resists separation, which cavitation
  would limit;
- the squeeze film is isoviscous: near u_e = 0 (the nose of a flat tappet) the EHL's
  piezoviscous squeeze holds a film the reduced model lets collapse; samples whose
  correction would exceed a factor CORRECTION_LIMIT are left out and r is interpolated
  across them;
- where u_e or R step (a ramp-less cam's step of acceleration) the entraining load at
  the current film jumps by orders of magnitude; the film then thickens at its transport
  limit (``FilmStateTribology.growth_limit``: oil carried from the supply's meniscus,
  0.16–0.18 m/s at 6000 rpm on a 9 mm / 140° cam), over about 0.35°, and presses the tappet
  up (190–330 N above the explicit run at 940.25°, 3000–6000 rpm); without the limit it grew
  within 0.02° and the force through it spiked to 2e5–7e5 N, which diverged the coupling;
  that limit is a transport estimate, not checked against a measured film response;
- the converged force still depends a little on the EHL sample interval: the same EHL
  at every 4° or 8° moves it by 3.3 N RMS over the event (21 N max; peak 650 N) at
  4000 rpm, against 11 N (47 N) with the earlier linearised film law; halving the EHL
  step of the whole coupling (4° → 2°) moves it by 4.7 N RMS (24 N max), against
  11.7 N (42 N) before — that includes the EHL's own time discretisation.

The EHL of the presented cycle drives both simulated cycles (the tables are periodic
in the cam angle).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..config.build import as_built
from ..physics.materials import reduced_modulus
from ..valvetrain.dynamics import ValvetrainResult, simulate_valvetrain
from ..valvetrain.tribology import FilmStateTribology
from .driver import CycleInputs, SetCycleResult, ehl_for_set
from .film_laws import film_state_tribology, state_from_vector, state_vector

__all__ = [
    "film_state_tribology",
    "CouplingIteration",
    "CouplingResult",
    "run_coupling",
    "RELAXATION",
    "ANDERSON_MEMORY",
    "AndersonMixer",
    "COUPLING_RMS_TOL",
    "COUPLING_MAX_TOL",
    "DIVERGENCE_FACTOR",
    "valve_timing",
    "diagnose_coupling",
    "implicit_vs_explicit_metrics",
]

#: Mixing of the film/friction tables between coupling iterations (Anderson β) …
RELAXATION = 0.5
#: … and the number of earlier iterations the Anderson step combines.
ANDERSON_MEMORY = 2
#: Coupling converged: change of the contact force between iterations, relative to its
#: peak, below these in RMS over the cam event and in maximum (the maximum sits at the
#: valve-closing impact, whose timing is the last to settle).
COUPLING_RMS_TOL = 5e-3
COUPLING_MAX_TOL = 5e-2
#: The coupling stops as diverging when the RMS change exceeds this multiple of the
#: smallest change so far; a coupling that does not converge reports the iterate with the
#: smallest change.
DIVERGENCE_FACTOR = 20.0


@dataclass
class CouplingIteration:
    """Change of the contact force from one coupling iteration to the next [N]."""

    iteration: int
    rms_force_change_N: float
    max_force_change_N: float


@dataclass
class CouplingResult:
    """The implicit coupling of one surface set: the implicit dynamics (None if disabled
    or failed; without convergence, the iterate whose force changed least), the
    per-iteration history, convergence, a message and the run time."""

    converged: bool = False
    message: str = "implicit coupling disabled"
    history: list[CouplingIteration] = field(default_factory=list)
    implicit: ValvetrainResult | None = None
    runtime_s: float = 0.0

    def to_dict(self) -> dict:
        """JSON-ready summary (without the dynamics)."""
        return {
            "converged": self.converged,
            "message": self.message,
            "history": [vars(h) for h in self.history],
            "runtime_s": self.runtime_s,
        }


class AndersonMixer:
    """Anderson acceleration (Walker & Ni, SIAM J. Numer. Anal. 49 (2011) 1715) of the
    fixed point x = G(x) of the film/friction tables, with mixing β and memory m:

        f_k = G(x_k) − x_k,  γ = argmin |f_k − ΔF γ|,
        x_{k+1} = x_k + β f_k − (ΔX + β ΔF) γ

    (ΔX, ΔF: differences of the last m iterates and residuals). With m = 0 it is the
    under-relaxed iteration x_{k+1} = x_k + β f_k. The components (h_k, c_k, F_k, μ_k) are
    scaled by their largest magnitudes so that they weigh alike."""

    def __init__(self, beta: float = RELAXATION, memory: int = ANDERSON_MEMORY):
        self.beta, self.m = float(beta), int(memory)
        self.x: list[np.ndarray] = []
        self.f: list[np.ndarray] = []

    def __call__(self, x, gx):
        f = gx - x
        self.x.append(x)
        self.f.append(f)
        self.x, self.f = self.x[-(self.m + 1) :], self.f[-(self.m + 1) :]
        new = x + self.beta * f
        if len(self.f) > 1:
            dF = np.diff(np.array(self.f), axis=0).T
            dX = np.diff(np.array(self.x), axis=0).T
            gamma, *_ = np.linalg.lstsq(dF, f, rcond=1e-10)
            if np.all(np.isfinite(gamma)):
                new = new - (dX + self.beta * dF) @ gamma
        return new


def diagnose_coupling(
    changes: list[np.ndarray],
    history: list[CouplingIteration],
    loaded: np.ndarray,
    f_peak: float,
    crank: np.ndarray | None = None,
    reported: CouplingIteration | None = None,
) -> str:
    """Why a coupling did not converge, what that leaves uncertain and what to change.

    ``changes`` are the contact-force changes d_k = F_k − F_{k−1} on the output samples,
    ``loaded`` marks the cam event, ``crank`` (optional) the samples' crank angles [°] to
    say where the largest change sits; ``reported`` the iteration whose dynamics are
    reported (default the last), whose change bounds their uncertainty. Classified, in
    this order:

    - *chatter*: more than half of the last change's Σd² lies outside the cam event (the
      tappet lightly loaded on the film off the lobe, e.g. after seating, impacting
      again and again); the loaded event is then determined better than the last change;
    - *divergence*: the RMS change grew in each of the last two iterations (or by the
      DIVERGENCE_FACTOR over its smallest value);
    - *oscillation*: successive changes point against each other (cosine of d_k and
      d_{k−1} below −0.5) without shrinking by half: the iterate flips between two states,
      typically two timings of the valve-closing impact;
    - *slow contraction*: otherwise; the number of further iterations is estimated from
      the last contraction ratio q = r_k / r_{k−1} as ln(tol / r_k) / ln q."""
    rms = [h.rms_force_change_N for h in history]
    last = reported if reported is not None else history[-1]
    d = changes[-1]
    tol = COUPLING_RMS_TOL * f_peak
    total = float(np.sum(d**2))
    outside = float(np.sum(d[~loaded] ** 2)) / total if total > 0 else 0.0
    where = "at the valve-closing impact and after it"
    if crank is not None:
        k = int(np.argmax(np.abs(d)))
        where = f"largest at {crank[k]:.1f}° crank ({abs(d[k]):.0f} N)"
    uncertain = (
        f"the implicit dynamics (Figs. 8–10 and the implicit-vs-explicit metrics) are "
        f"uncertain by about the change of the reported iteration {last.iteration} (RMS "
        f"{last.rms_force_change_N:.2f} N, max "
        f"{last.max_force_change_N:.1f} N); the EHL results of every surface set follow the "
        f"explicit dynamics and are not affected"
    )
    if outside > 0.5:
        return (
            f"chatter: {100 * outside:.0f} % of the last change lies outside the cam event "
            f"(the lightly loaded tappet impacting on the film off the cam lobe); "
            f"{uncertain}, mostly outside the event ({where}): the RMS difference over "
            f"the event and the valve timing shifts are usable, the maximum and peak force "
            f"differences are not. More iterations do not remove repeated impacts; compare "
            f"the explicit runs only (numerics.implicit_coupling = false) where the "
            f"impacts matter"
        )
    if (len(rms) >= 3 and rms[-1] > rms[-2] > rms[-3]) or rms[-1] > DIVERGENCE_FACTOR * min(rms):
        return (
            f"divergence: the RMS change grew to {rms[-1]:.3g} N (smallest {min(rms):.3g} N); "
            f"{uncertain}, {where}. Use finer EHL time steps (numerics.crank_step_deg), "
            f"or compare explicit runs only (numerics.implicit_coupling = false)"
        )
    if len(changes) >= 2:
        a, b = changes[-1], changes[-2]
        nab = float(np.linalg.norm(a) * np.linalg.norm(b))
        cos = float(a @ b) / nab if nab > 0 else 0.0
        if cos < -0.5 and rms[-1] > 0.5 * rms[-2]:
            return (
                f"oscillation: successive changes point against each other (cosine "
                f"{cos:.2f}) and do not shrink; {uncertain}, {where}. The iterate flips "
                f"between two timings of the closing impact: use finer EHL time steps "
                f"(numerics.crank_step_deg) there"
            )
    q = rms[-1] / rms[-2] if len(rms) >= 2 and rms[-2] > 0 else math.nan
    more = (
        f" (about {math.ceil(math.log(tol / rms[-1]) / math.log(q))} more at the last "
        f"contraction ratio {q:.2f})"
        if 0 < q < 1 and rms[-1] > tol
        else ""
    )
    return (
        f"slow contraction: the changes shrink but not below the tolerance; {uncertain}, "
        f"{where}. Allow more iterations (numerics.coupling_iterations){more}"
    )


def run_coupling(
    case,
    surface_set,
    dynamics: ValvetrainResult,
    inputs: CycleInputs,
    first: SetCycleResult,
) -> CouplingResult:
    """Implicit coupling for one surface set of a case (Case or BuiltCase), starting
    from its EHL (``first``) on the explicit dynamics and their cycle ``inputs``.

    Stops when the contact force changes by less than COUPLING_RMS_TOL (RMS over the
    event) and COUPLING_MAX_TOL (max) of its peak, after ``numerics.coupling_iterations``,
    or as diverging when the RMS change exceeds DIVERGENCE_FACTOR times the smallest so
    far; without convergence the iterate with the smallest change is reported, and the
    message says which."""
    t0 = time.perf_counter()
    built = as_built(case)
    case = built.case
    n = case.numerics
    out = CouplingResult()
    if not n.implicit_coupling:
        return out
    s = surface_set
    lub = built.lubricant
    e_prime = reduced_modulus(s.bodies)
    period = 2.0 * math.pi / case.cam_speed
    ev = dynamics.event_mask()
    f_peak = float(dynamics.contact_force.max())
    supply = n.coupling_supply_film
    prev, ehl, inp = dynamics, first, inputs
    table: FilmStateTribology | None = None
    mixer, scale = AndersonMixer(), None
    best = None  # (iteration, RMS change, dynamics) with the smallest change
    msg = f"not converged in {n.coupling_iterations} iterations"
    changes: list[np.ndarray] = []
    for k in range(1, n.coupling_iterations + 1):
        g = film_state_tribology(  # the supply film checked at load (the case file)
            inp, ehl, lub, e_prime, period, case.width, supply_film=supply, checked=("supply_film",)
        )
        if table is None:
            table = g
        else:
            x_old = state_vector(table)
            if g.time.size != table.time.size or np.any(g.time != table.time):
                # onto the same samples
                x_old = np.concatenate(
                    [np.interp(g.time, table.time, v) for v in np.split(x_old, 2)]
                )
            if scale is None:
                n_t = g.time.size
                lg, mg = np.split(state_vector(g), 2)
                scale = np.repeat([max(np.abs(lg).max(), 1e-3), max(mg.max(), 1e-300)], n_t)
            table = state_from_vector(
                scale * mixer(x_old / scale, state_vector(g) / scale), g, period
            )
        new = simulate_valvetrain(
            built.cam, built.valvetrain, tribology=table, **built.dynamics_options
        )
        if not new.converged:
            msg = f"implicit dynamics failed at iteration {k}: {new.message}"
            break
        d = new.contact_force - prev.contact_force
        changes.append(d)
        rms = float(np.sqrt(np.mean(d[ev] ** 2))) if ev.any() else float(np.abs(d).max())
        mx = float(np.abs(d).max())
        out.history.append(CouplingIteration(k, rms, mx))
        out.implicit = new
        prev = new
        if best is None or rms < best[1]:
            best = (k, rms, new)
        if k > 1 and rms > DIVERGENCE_FACTOR * best[1] and rms > COUPLING_RMS_TOL * f_peak:
            msg = (
                f"diverging at iteration {k} (RMS change {rms:.3g} N against "
                f"{best[1]:.3g} N at iteration {best[0]})"
            )
            break
        if rms < COUPLING_RMS_TOL * f_peak and mx < COUPLING_MAX_TOL * f_peak:
            out.converged = True
            msg = (
                f"converged in {k} iteration{'s' if k != 1 else ''} (last change of the "
                f"contact force: RMS "
                f"{rms:.2f} N, max {mx:.1f} N)"
            )
            break
        if k < n.coupling_iterations:
            inp = CycleInputs.from_dynamics(new, n.crank_step_deg, case.width)
            ehl = ehl_for_set(built, s, inp, film_law_only=True)
    if not out.converged and out.history:
        last = out.history[-1]
        msg += (
            f" (last change of the contact force: RMS {last.rms_force_change_N:.2f} N, "
            f"max {last.max_force_change_N:.1f} N)"
        )
        if best is not None and best[0] != last.iteration:
            # report the most self-consistent iterate, not a diverged one
            out.implicit = best[2]
            msg += f"; the implicit run reported is iteration {best[0]}'s (smallest change)"
        shown = out.history[best[0] - 1] if best is not None else None
        msg += "; " + diagnose_coupling(
            changes, out.history, ev, f_peak, prev.crank_angle, reported=shown
        )
    out.message = msg
    out.runtime_s = time.perf_counter() - t0
    return out


def valve_timing(result: ValvetrainResult) -> tuple[float, float]:
    """(opening, closing) crank angles [°] of the valve's main event: where the valve lift
    (measured from the seat contact, negative when pressed into the seat) last rises
    through 0 before its peak and first falls through 0 after it, located by linear
    interpolation between output samples (NaN where there is no such crossing). Both are
    continuous functions of the motion, unlike the crank angle of the largest force
    difference, which jumps between impacts."""
    lift, crank = result.valve_lift, result.crank_angle
    k = int(np.argmax(lift))

    def cross(i):  # zero of the interpolant between samples i and i + 1
        a, b = lift[i], lift[i + 1]
        return float(crank[i] + (crank[i + 1] - crank[i]) * a / (a - b))

    up = np.flatnonzero((lift[:k] <= 0.0) & (lift[1 : k + 1] > 0.0))
    down = np.flatnonzero((lift[k:-1] > 0.0) & (lift[k + 1 :] <= 0.0)) + k
    return (cross(up[-1]) if up.size else math.nan, cross(down[0]) if down.size else math.nan)


def implicit_vs_explicit_metrics(explicit: ValvetrainResult, implicit: ValvetrainResult) -> dict:
    """Difference of the implicit from the explicit dynamics (percentages of the explicit
    peak contact force F̂; the implicit run interpolated onto the explicit crank angles):

    - ``max_contact_force_diff_pct`` = max|F_i − F_e| / F̂ (the paper's Figs. 8–10 metric).
      It sits at the valve-closing impact, where the force falls by several hundred N
      within a fraction of a degree, so it measures mostly the shift of that impact
      (≈ 0.2 % of F̂ per 0.01°) and moves with round-off and the coupling tolerance;
    - ``rms_contact_force_diff_pct`` = RMS of F_i − F_e over the cam event (cam lift above
      the jump threshold) / F̂: an integral, insensitive to where single impacts fall;
    - ``peak_contact_force_diff_pct`` = (max F_i − max F_e) / F̂;
    - ``valve_opening_shift_deg``, ``valve_closing_shift_deg``: implicit minus explicit
      crank angle of the valve lift-off and of the first seating after the peak
      (:func:`valve_timing`);
    - ``max_velocity_diff_pct`` = max|v_i − v_e| / max|v_e| of the tappet velocity.

    NaN where the reference is zero (a train thrown off the cam carries no force)."""
    crank = explicit.crank_angle
    fe = explicit.contact_force
    fi = np.interp(crank, implicit.crank_angle, implicit.contact_force)
    vi = np.interp(crank, implicit.crank_angle, implicit.tappet_velocity)
    peak = float(fe.max())
    peak = peak if peak > 0.0 else math.nan  # no load at all: no percentages
    vmax = float(np.abs(explicit.tappet_velocity).max())
    vmax = vmax if vmax > 0.0 else math.nan
    dF = np.abs(fi - fe)
    dv = np.abs(vi - explicit.tappet_velocity)
    ev = explicit.event_mask()
    rms = float(np.sqrt(np.mean((fi - fe)[ev] ** 2))) if ev.any() else math.nan
    (o_e, c_e), (o_i, c_i) = valve_timing(explicit), valve_timing(implicit)
    return {
        "max_contact_force_diff_pct": float(dF.max() / peak * 100),
        "max_contact_force_diff_crank_deg": float(crank[dF.argmax()]),
        "rms_contact_force_diff_pct": rms / peak * 100,
        "peak_contact_force_diff_pct": float((implicit.contact_force.max() - peak) / peak * 100),
        "valve_opening_shift_deg": o_i - o_e,
        "valve_closing_shift_deg": c_i - c_e,
        "max_velocity_diff_pct": float(dv.max() / vmax * 100),
        "max_velocity_diff_crank_deg": float(crank[dv.argmax()]),
    }
