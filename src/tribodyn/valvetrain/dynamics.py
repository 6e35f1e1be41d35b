"""Time integration of the valvetrain over engine cycles (the solver layer).

:func:`simulate_valvetrain` starts from static equilibrium on the base circle (spring
preload carried by the valve seat, zero-force cam and tappet contacts), integrates
``cycles`` engine cycles (one engine cycle = 720° crank = one cam revolution) with a stiff
solver and an analytic Jacobian, and presents the last cycle (720°–1440° for two cycles)
on a uniform crank-angle grid. Loss of cam contact (jump), valve bounce and the seating
velocity are located with the solver's event functions, so they are not limited to the
output grid. Solver failures are reported through ``converged=False`` and ``message``;
arrays are never silently filled with NaN (they are empty on failure).
"""

from __future__ import annotations

import math
import time as _time
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TypedDict

import numpy as np
from scipy.integrate import solve_ivp

from .._validation import InputError, check_real
from ..physics import limits as L
from ..physics import typical_engine
from .cams import CamProfile
from .compiled import CompiledLumped, compiled_model, integrate_compiled
from .flexible import FlexibleValvetrain
from .kinematics import rpm_to_cam_speed
from .model import ContactLawError, lumped_energies
from .parameters import ValvetrainParameters
from .system import ValvetrainSystem, system_class
from .tribology import AnalyticTribology, Frictionless, TribologyModel

__all__ = ["ValvetrainResult", "simulate_valvetrain", "resolve_tribology"]


@dataclass
class ValvetrainResult:
    """Valvetrain response over the presented engine cycle (arrays over crank angle).

    Kinematic inputs (from the cam): cam_lift s, lift_velocity s', lift_acceleration s'',
    radius_of_curvature R, contact_offset e, entrainment_speed u_e, sliding_speed u_s.
    Dynamic outputs: contact_force F_c (total over the width, incl. damping),
    elastic_contact_force P, series_film h (implicit coupling; 0 when explicit; with the
    film as a state h, the film itself in ``tribology_report["film_thickness"]``), tappet
    displacement/velocity/acceleration, valve_lift (from the seat contact position;
    slightly negative when pressed into the seat), valve velocity/acceleration,
    seat_force, tappet_valve_force, spring_force (on the valve), spring_support_force (on
    the head), friction_force F_f at the contact, bore_friction_force (signed, on the
    tappet), cam_torque = F_c e + F_f (r_b + s) [N·m], friction_power = F_f u_s [W].
    Energy [J] from the start of the presented cycle: cam_work and dissipated_energy
    (integrated with the motion), kinetic_energy and elastic_energy (relative to static
    equilibrium); ``energy`` holds the cycle balance W = ΔT + ΔU + D and its residual.
    Units SI; crank_angle in degrees, cam_angle in rad, time in s from the run start.

    Events (presented cycle, crank degrees): ``jumps`` — contact-loss intervals while the
    cam lifts (s > jump_lift_threshold) as (start, end); ``bounces`` — valve lift-offs
    from the seat when the cam is not opening, as (start, end, max lift [m]);
    ``seating_velocity`` — |valve velocity| at the first closing seat impact [m/s];
    ``seatings`` — all (crank angle, valve velocity) seat impacts.
    """

    converged: bool
    message: str
    engine_speed: float
    cam_speed: float
    params: ValvetrainParameters | FlexibleValvetrain
    cam: CamProfile
    tribology: str
    jumps: list = field(default_factory=list)
    bounces: list = field(default_factory=list)
    seatings: list = field(default_factory=list)
    seating_velocity: float = float("nan")
    energy: dict = field(default_factory=dict)
    tribology_report: dict = field(default_factory=dict)
    stats: dict = field(default_factory=dict)
    time: np.ndarray = field(default_factory=lambda: np.empty(0))
    crank_angle: np.ndarray = field(default_factory=lambda: np.empty(0))
    cam_angle: np.ndarray = field(default_factory=lambda: np.empty(0))
    cam_lift: np.ndarray = field(default_factory=lambda: np.empty(0))
    lift_velocity: np.ndarray = field(default_factory=lambda: np.empty(0))
    lift_acceleration: np.ndarray = field(default_factory=lambda: np.empty(0))
    radius_of_curvature: np.ndarray = field(default_factory=lambda: np.empty(0))
    contact_offset: np.ndarray = field(default_factory=lambda: np.empty(0))
    entrainment_speed: np.ndarray = field(default_factory=lambda: np.empty(0))
    sliding_speed: np.ndarray = field(default_factory=lambda: np.empty(0))
    contact_force: np.ndarray = field(default_factory=lambda: np.empty(0))
    elastic_contact_force: np.ndarray = field(default_factory=lambda: np.empty(0))
    series_film: np.ndarray = field(default_factory=lambda: np.empty(0))
    tappet_displacement: np.ndarray = field(default_factory=lambda: np.empty(0))
    tappet_velocity: np.ndarray = field(default_factory=lambda: np.empty(0))
    tappet_acceleration: np.ndarray = field(default_factory=lambda: np.empty(0))
    valve_lift: np.ndarray = field(default_factory=lambda: np.empty(0))
    valve_velocity: np.ndarray = field(default_factory=lambda: np.empty(0))
    valve_acceleration: np.ndarray = field(default_factory=lambda: np.empty(0))
    seat_force: np.ndarray = field(default_factory=lambda: np.empty(0))
    tappet_valve_force: np.ndarray = field(default_factory=lambda: np.empty(0))
    spring_force: np.ndarray = field(default_factory=lambda: np.empty(0))
    spring_support_force: np.ndarray = field(default_factory=lambda: np.empty(0))
    friction_force: np.ndarray = field(default_factory=lambda: np.empty(0))
    bore_friction_force: np.ndarray = field(default_factory=lambda: np.empty(0))
    cam_torque: np.ndarray = field(default_factory=lambda: np.empty(0))
    friction_power: np.ndarray = field(default_factory=lambda: np.empty(0))
    cam_work: np.ndarray = field(default_factory=lambda: np.empty(0))
    dissipated_energy: np.ndarray = field(default_factory=lambda: np.empty(0))
    kinetic_energy: np.ndarray = field(default_factory=lambda: np.empty(0))
    elastic_energy: np.ndarray = field(default_factory=lambda: np.empty(0))
    jump_lift_threshold: float = 10e-6

    @property
    def jump(self) -> bool:
        """True if the cam contact was lost while the cam was lifting."""
        return len(self.jumps) > 0

    @property
    def valve_bounce(self) -> bool:
        return len(self.bounces) > 0

    def event_mask(self) -> np.ndarray:
        """Samples inside the lift event (cam lift > jump_lift_threshold)."""
        return self.cam_lift > self.jump_lift_threshold

    @property
    def separation(self) -> np.ndarray:
        """Follower lift minus cam lift where positive (the tappet off the cam) [m]."""
        return np.maximum(self.tappet_displacement - self.cam_lift, 0.0)

    def jump_summary(self) -> dict:
        """The valve jump in numbers: contact-loss intervals [crank deg], their total,
        the maximum separation (tappet lift − cam lift) [m] and its crank angle."""
        sep = self.separation
        k = int(np.argmax(sep)) if sep.size else 0
        return {
            "jump": self.jump,
            "contact_loss_crank_deg": [[float(a), float(b)] for a, b in self.jumps],
            "contact_lost_deg": float(sum(b - a for a, b in self.jumps)),
            "max_separation_m": float(sep[k]) if sep.size else 0.0,
            "max_separation_crank_deg": float(self.crank_angle[k]) if sep.size else None,
        }

    def summary(self) -> dict:
        """Key numbers of the presented cycle (plain floats; JSON-ready)."""
        if not self.converged:
            return {"converged": False, "message": self.message}
        ev = self.event_mask()
        dt = np.gradient(self.time)
        return {
            "converged": True,
            "engine_speed_rpm": self.engine_speed,
            "tribology": self.tribology,
            "peak_contact_force_N": float(self.contact_force.max()),
            "peak_contact_force_crank_deg": float(self.crank_angle[self.contact_force.argmax()]),
            "min_contact_force_in_event_N": float(self.contact_force[ev].min())
            if ev.any()
            else float("nan"),
            "entrainment_speed_range_m_s": [
                float(self.entrainment_speed.min()),
                float(self.entrainment_speed.max()),
            ],
            "min_radius_of_curvature_m": float(self.radius_of_curvature.min()),
            "max_valve_lift_m": float(self.valve_lift.max()),
            "max_seat_force_N": float(self.seat_force.max()),
            "peak_cam_torque_Nm": float(np.abs(self.cam_torque).max()),
            "friction_energy_per_cycle_J": float(np.sum(self.friction_power * dt)),
            "jump": self.jump,
            "jumps_crank_deg": [list(map(float, j)) for j in self.jumps],
            "max_separation_m": self.jump_summary()["max_separation_m"],
            "valve_bounce": self.valve_bounce,
            "seating_velocity_m_s": float(self.seating_velocity),
            "energy_residual_rel": float(self.energy.get("relative_residual", float("nan"))),
        }


def resolve_tribology(
    tribology, params: ValvetrainParameters | FlexibleValvetrain
) -> TribologyModel:
    """Map ``"explicit"`` / None / a model to a :class:`TribologyModel`."""
    if tribology is None or tribology == "none":
        return Frictionless()
    if isinstance(tribology, str):
        if tribology == "explicit":
            return AnalyticTribology(width=params.cam_width)
        raise InputError(
            f"tribology must be 'explicit', None or a TribologyModel (got {tribology!r})"
        )
    if not isinstance(tribology, TribologyModel):
        raise InputError(
            f"tribology must be 'explicit', None or a TribologyModel (got "
            f"{type(tribology).__name__})"
        )
    w = getattr(tribology, "width", None)  # a law for a given contact width [m]
    if w is not None and abs(w - params.cam_width) > 1e-12:
        raise InputError(f"tribology width {w:g} m differs from cam_width {params.cam_width:g} m")
    return tribology


def _check_atol(atol, size: int) -> float | np.ndarray:
    """A scalar or one value per state (``size``), each inside L.DYNAMICS_ATOL."""
    if np.ndim(atol) == 0:
        return L.DYNAMICS_ATOL.check("atol", atol)
    a = np.asarray(atol)
    if a.ndim != 1 or a.size != size:
        raise InputError(
            f"atol must be a number or {size} numbers (one per state), got shape {a.shape}"
        )
    return np.array([L.DYNAMICS_ATOL.check(f"atol[{i}]", v) for i, v in enumerate(a.tolist())])


def simulate_valvetrain(
    cam: CamProfile,
    params: ValvetrainParameters | FlexibleValvetrain | None = None,
    *,
    engine_speed: float = typical_engine.ENGINE_SPEED.value,
    tribology: TribologyModel | str | None = "explicit",
    cycles: int = 2,
    output_step: float = 0.25,
    method: str = "LSODA",
    rtol: float = 1e-6,
    atol: float | Sequence[float] | np.ndarray | None = None,
    max_step: float = 1.0,
    start_angle: float = 0.0,
    jump_lift_threshold: float = 10e-6,
) -> ValvetrainResult:
    """Simulate the single valvetrain and present its last engine cycle.

    Parameters
    ----------
    cam : cam profile (checked against ``params.tappet_radius``).
    params : :class:`ValvetrainParameters` (default: paper Table 7 + assumed values), or a
        :class:`~tribodyn.valvetrain.flexible.FlexibleValvetrain` (Craig–Bampton bodies,
        camshaft compliance; same outputs, valve = its seat face).
    engine_speed : [rpm], in (0, 50 000] (L.ENGINE_SPEED); the cam turns at half of it
        (default: the typical :data:`~tribodyn.physics.typical_engine.ENGINE_SPEED`).
    tribology : ``"explicit"`` (default, :class:`AnalyticTribology` over the cam width),
        None (frictionless), or any :class:`TribologyModel` (a model with a film law gives
        the implicit coupling).
    cycles : engine cycles to integrate, 1–50; the last one is presented.
    output_step : crank-angle spacing of the output [deg], in (0, 5].
    method : ``"LSODA"`` (default), ``"Radau"`` or ``"BDF"`` (solve_ivp, analytic Jacobian).
    rtol, atol : solver tolerances, rtol in (0, 0.1), atol in (0, 0.01] (scalar or one per
        state; default: 1e-10 m on displacements, 1e-6 m/s on velocities, 1e-6 J on the
        energy accumulators, 1e-10 m on the film state of a
        :class:`~tribodyn.valvetrain.tribology.FilmStateTribology`).
    max_step : largest step [crank deg], in (0, 10].
    start_angle : cam angle at t = 0 [rad]; must lie on the base circle.
    jump_lift_threshold : cam lift above which a contact loss counts as a jump [m],
        in (0, 1 mm].

    Notes
    -----
    The ranges are those of the case file (:mod:`tribodyn.physics.limits`); a value
    outside raises :class:`~tribodyn.InputError` naming the argument and its range.
    """
    if not isinstance(cam, CamProfile):
        raise InputError(f"cam must be a CamProfile (got {type(cam).__name__})")
    params = ValvetrainParameters() if params is None else params
    system = system_class(params)
    # the case file's ranges (physics.limits), checked before any work is done
    w = rpm_to_cam_speed(engine_speed)
    cycles = L.DYNAMICS_CYCLES.check("cycles", cycles)
    output_step = L.OUTPUT_STEP.check("output_step", output_step)
    rtol = L.DYNAMICS_RTOL.check("rtol", rtol)
    max_step = L.MAX_STEP.check("max_step", max_step)
    jump_lift_threshold = L.JUMP_LIFT_THRESHOLD.check("jump_lift_threshold", jump_lift_threshold)
    start_angle = check_real("start_angle", start_angle, "rad")
    if method not in ("LSODA", "Radau", "BDF"):
        raise InputError(f"method must be 'LSODA', 'Radau' or 'BDF' (got {method!r})")
    cam.check(params.tappet_radius)
    trib = resolve_tribology(tribology, params)

    model = system(cam, params, w, trib, start_angle=start_angle)
    n = model.n
    T_cycle = 2.0 * math.pi / w  # one engine cycle = one cam revolution
    t_end = cycles * T_cycle
    crank0 = 720.0 * (cycles - 1)
    n_out = int(round(720.0 / output_step)) + 1
    crank = crank0 + np.linspace(0.0, 720.0, n_out)
    t_eval = np.radians(crank) / (2.0 * w)
    t_eval[-1] = min(t_eval[-1], t_end)
    if atol is None:
        abs_tol: float | np.ndarray = np.concatenate(
            [np.full(n, 1e-10), np.full(n, 1e-6), [1e-6, 1e-6], [1e-10] * model.film_state]
        )
    else:
        abs_tol = _check_atol(atol, 2 * n + 2 + model.film_state)
    hmax = math.radians(max_step) / (2.0 * w)
    base = _Header(
        engine_speed=float(engine_speed),
        cam_speed=w,
        params=params,
        cam=cam,
        tribology=trib.name,
        jump_lift_threshold=jump_lift_threshold,
    )
    run = _integrate(
        model, method, t_eval, t_end, cycles, output_step, rtol, abs_tol, hmax, jump_lift_threshold
    )
    if isinstance(run, str):
        return ValvetrainResult(**base, converged=False, message=run)
    if run.failure is not None:
        return ValvetrainResult(**base, converged=False, stats=run.stats, message=run.failure)
    try:
        res = _sample(model, run, t_eval, crank, base)
    except ContactLawError as exc:
        msg = f"output evaluation failed: {exc}"
        return ValvetrainResult(**base, converged=False, stats=run.stats, message=msg)
    _energy_balance(res, run.Y, n, w)
    _events(res, model, run, (cycles - 1) * T_cycle, t_end)
    return res


class _Header(TypedDict):
    """The fields of :class:`ValvetrainResult` known before the integration."""

    engine_speed: float
    cam_speed: float
    params: ValvetrainParameters | FlexibleValvetrain
    cam: CamProfile
    tribology: str
    jump_lift_threshold: float


@dataclass
class _Run:
    """States on the presented cycle's grid (Y, one column per sample), the located seat
    and contact events (times and states), solver statistics and, on failure, why."""

    Y: np.ndarray
    t_seat: np.ndarray
    y_seat: np.ndarray
    t_con: np.ndarray
    y_con: np.ndarray
    stats: dict
    compiled: CompiledLumped | None = None
    failure: str | None = None


def _integrate(
    model: ValvetrainSystem,
    method: str,
    t_eval: np.ndarray,
    t_end: float,
    cycles: int,
    output_step: float,
    rtol: float,
    atol,
    hmax: float,
    thr: float,
) -> _Run | str:
    """Integrate from static equilibrium to t_end: the compiled backend (one LSODA call)
    where the model has one and LSODA is asked for, else solve_ivp with the analytic
    Jacobian. Seat contact and cam-contact gap are event functions. Returns the run, or a
    message if the solver raised before giving statistics."""
    cam, w = model.cam, model.w
    lobe = model.lobe_angle
    empty = np.empty(0)

    def ev_seat(t, y):
        return y[1] - model.d_seat

    def ev_contact(t, y):
        """Zero-force gap of the cam contact, frozen at the threshold lift on the base
        circle so that a floating zero-lash tappet does not trigger events there."""
        s, _, s2 = cam.scalar_derivatives(lobe(t, y))
        h0 = 0.0
        if model.film_state:
            h0 = y[2 * model.n + 2]
        elif model.has_film:
            rb = cam.base_radius
            h0 = model.film(t, 0.0, 0.5 * w * (rb + s + 2.0 * s2), rb + s + s2)[0]
        return max(s, thr) - y[0] + h0

    # backend: the compiled right-hand side where the model has one (LSODA), else solve_ivp
    cm = compiled_model(model) if (method == "LSODA" and model.compilable) else None
    if cm is not None:  # compiled right-hand side, whole run in one LSODA call
        k_out = int(round(720.0 * cycles / output_step))
        t_grid = np.linspace(0.0, t_end, k_out + 1)
        t_grid[-t_eval.size :] = t_eval  # the presented cycle on the same points

        def grid_events(T, Y):
            s = cm.lift(T)
            if model.film_state:
                h0 = Y[2 * model.n + 2]
            else:
                h0 = model.trib.film(T, np.zeros_like(T), 0.0, 1.0)[0] if model.has_film else 0.0
            return np.vstack([Y[1] - model.d_seat, np.maximum(s, thr) - Y[0] + h0])

        Yall, t_evs, y_evs, stats, fail = integrate_compiled(
            cm, t_grid, rtol, atol, hmax, [ev_seat, ev_contact], grid_events
        )
        if fail is not None:
            return _Run(empty, empty, empty, empty, empty, stats, cm, f"solver failed: {fail}")
        (t_seat, t_con), (y_seat, y_con) = t_evs, y_evs
        return _Run(Yall[:, -t_eval.size :], t_seat, y_seat, t_con, y_con, stats, cm)
    wall = _time.perf_counter()
    try:
        sol = solve_ivp(
            model.rhs,
            (0.0, t_end),
            model.static_state(),
            method=method,
            t_eval=t_eval,
            jac=model.jacobian,
            rtol=rtol,
            atol=atol,
            max_step=hmax,
            events=[ev_seat, ev_contact],
        )
    except (ContactLawError, FloatingPointError, ValueError, ZeroDivisionError) as exc:
        return f"solver failed: {exc}"
    wall = _time.perf_counter() - wall
    stats = dict(
        nfev=int(sol.nfev), njev=int(sol.njev), nlu=int(sol.nlu), wall_time_s=wall, method=method
    )
    if sol.status != 0:
        t_fail = float(sol.t[-1]) if len(sol.t) else 0.0  # t_eval may hold no point yet
        msg = f"solver failed at t = {t_fail:.6g} s: {sol.message}"
        return _Run(empty, empty, empty, empty, empty, stats, None, msg)
    if sol.y.shape[1] != t_eval.size or not np.all(np.isfinite(sol.y)):
        msg = "solver returned incomplete or non-finite output"
        return _Run(empty, empty, empty, empty, empty, stats, None, msg)
    t_seat, y_seat = sol.t_events[0], sol.y_events[0]
    t_con, y_con = sol.t_events[1], sol.y_events[1]
    return _Run(sol.y, t_seat, y_seat, t_con, y_con, stats)


_COLS = ("s", "s1", "s2", "R", "ue", "us", "Fc", "P", "film", "Ftv", "Fs", "Fb")


def _sample(
    model: ValvetrainSystem, run: _Run, t_eval: np.ndarray, crank: np.ndarray, base: _Header
) -> ValvetrainResult:
    """Forces, kinematics, friction and energies at every output sample (the compiled
    backend's vectorised outputs, or the model's ``evaluate`` sample by sample)."""
    Y, n, w, trib, cam = run.Y, model.n, model.w, model.trib, model.cam
    m = t_eval.size
    cols = {k: np.empty(m) for k in _COLS + ("acc_t", "acc_v", "F0s", "FNs", "T", "U")}
    cm = run.compiled
    if cm is not None:
        f = cm.outputs(t_eval, Y)
        for k in _COLS + ("acc_t", "acc_v", "F0s", "FNs"):
            cols[k][:] = f[k]
        cols["T"][:], cols["U"][:] = lumped_energies(model, Y, f["P"])
    else:
        for i in range(m):
            f = model.evaluate(t_eval[i], Y[:, i])
            for k in _COLS:
                cols[k][i] = f[k]
            cols["acc_t"][i] = f["acc"][0]
            cols["acc_v"][i] = f["acc"][1]
            cols["F0s"][i] = f["Fseg"][0]
            cols["FNs"][i] = f["Fseg"][-1]
            cols["T"][i], cols["U"][i] = model.energy(t_eval[i], Y[:, i], f)
    Ff = np.asarray(
        trib.friction(t_eval, cols["Fc"], cols["ue"], cols["us"], cols["R"]), dtype=float
    ) * np.ones(m)
    report = {
        k: np.broadcast_to(np.asarray(v), (m,)).copy()
        for k, v in trib.report(t_eval, cols["Fc"], cols["ue"], cols["us"], cols["R"]).items()
    }
    if model.film_state:  # the film state itself [m]
        report["film_thickness"] = Y[2 * n + 2].copy()
    rb = cam.base_radius
    note = None  # flexible spring: a clash its reduction cannot see
    unresolved = model.unresolved_clash(Y)
    if unresolved > 0.0:
        note = (
            f"coil clash in a spring segment reduced to modes (overlap "
            f"{unresolved * 1e6:.3g} µm): raise the spring's clash_margin"
        )
    return ValvetrainResult(
        **base,
        converged=True,
        message="ok" if note is None else f"ok; warning: {note}",
        stats=run.stats,
        tribology_report=report,
        time=t_eval,
        crank_angle=crank,
        cam_angle=model.theta0 + w * t_eval,
        cam_lift=cols["s"],
        lift_velocity=cols["s1"],
        lift_acceleration=cols["s2"],
        radius_of_curvature=cols["R"],
        contact_offset=cols["s1"].copy(),
        entrainment_speed=cols["ue"],
        sliding_speed=cols["us"],
        contact_force=cols["Fc"],
        elastic_contact_force=cols["P"],
        series_film=cols["film"],
        tappet_displacement=Y[0].copy(),
        tappet_velocity=Y[n].copy(),
        tappet_acceleration=cols["acc_t"],
        valve_lift=Y[1] - model.d_seat,
        valve_velocity=Y[n + 1].copy(),
        valve_acceleration=cols["acc_v"],
        seat_force=cols["Fs"],
        tappet_valve_force=cols["Ftv"],
        spring_force=cols["F0s"],
        spring_support_force=cols["FNs"],
        friction_force=Ff,
        bore_friction_force=-cols["Fb"],
        cam_torque=cols["Fc"] * cols["s1"] + Ff * (rb + cols["s"]),
        friction_power=Ff * cols["us"],
        kinetic_energy=cols["T"],
        elastic_energy=cols["U"],
    )


def _energy_balance(res: ValvetrainResult, Y: np.ndarray, n: int, w: float) -> None:
    """Cycle balance W = ΔT + ΔU + D of the presented cycle, from the integrated cam-work
    and dissipation accumulators (state entries 2n, 2n + 1), and its residual."""
    res.cam_work = Y[2 * n] - Y[2 * n, 0]
    res.dissipated_energy = Y[2 * n + 1] - Y[2 * n + 1, 0]
    T, U = res.kinetic_energy, res.elastic_energy
    W = res.cam_work[-1]
    D = res.dissipated_energy[-1]
    resid = W - (T[-1] - T[0] + U[-1] - U[0] + D)
    gross = float(np.sum(np.abs(res.cam_torque * w) * np.gradient(res.time)))
    res.energy = dict(
        cam_work=W,
        kinetic_change=T[-1] - T[0],
        elastic_change=U[-1] - U[0],
        dissipation=D,
        residual=resid,
        relative_residual=resid / max(abs(W), gross, 1e-300),
        gross_cam_work=gross,
    )


def _events(
    res: ValvetrainResult, model: ValvetrainSystem, run: _Run, t0_pres: float, t_end: float
) -> None:
    """Seatings, seating velocity, valve bounces and jumps of the presented cycle
    [t0_pres, t_end] from the located seat and contact events."""
    cam, w, n, thr = model.cam, model.w, model.n, res.jump_lift_threshold
    t_eval = res.time

    def crank_of(t):
        return float(math.degrees(2.0 * w * t))

    in_win = lambda t: t0_pres - 1e-12 <= t <= t_end + 1e-12  # noqa: E731
    seat_ev = [(t, y[n + 1]) for t, y in zip(run.t_seat, run.y_seat)]  # (t, v_valve)
    impacts = [(t, v) for t, v in seat_ev if in_win(t) and v < 0.0]
    res.seatings = [(crank_of(t), v) for t, v in impacts]
    # First closing seating after the valve's peak in the presented cycle (none: the event
    # wraps past the cycle end, take the first one in the window).
    t_peak = t_eval[int(np.argmax(res.valve_lift))]
    closing = [(t, v) for t, v in impacts if t > t_peak] or impacts
    if closing:
        res.seating_velocity = float(abs(closing[0][1]))
    # Bounces: lift-offs while the cam is not on its opening flank.
    liftoffs = [t for t, v in seat_ev if in_win(t) and v > 0.0]
    seat_times = sorted(t for t, v in seat_ev if v < 0.0)
    for t in liftoffs:
        s1 = cam.scalar_derivatives(model.theta0 + w * t)[1]
        if s1 > 0.0:
            continue
        t_back = next((ts for ts in seat_times if ts > t), t_end)
        msk = (t_eval >= t) & (t_eval <= t_back)
        hmax_b = float(res.valve_lift[msk].max()) if msk.any() else 0.0
        res.bounces.append((crank_of(t), crank_of(t_back), max(hmax_b, 0.0)))
    # Jumps: contact lost while the cam lifts (direction from the gap rate ω s' − v_t).
    losses: list[float] = []
    regains: list[float] = []
    for t, y in zip(run.t_con, run.y_con):
        s, s1, _ = cam.scalar_derivatives(model.theta0 + w * t)
        rate = (w * s1 if s > thr else 0.0) - y[n]
        (losses if rate < 0.0 else regains).append(t)
    for t in losses:
        if not in_win(t):
            continue
        t_back = next((tr for tr in regains if tr > t), t_end)
        res.jumps.append((crank_of(t), crank_of(min(t_back, t_end))))
    # A loss that began before the window and persists into it.
    pre = [t for t in losses if t < t0_pres]
    if pre:
        t_back = next((tr for tr in regains if tr > pre[-1]), t_end)
        if t_back > t0_pres:
            res.jumps.insert(0, (crank_of(t0_pres), crank_of(min(t_back, t_end))))
