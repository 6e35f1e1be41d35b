"""No silent garbage: a non-physical film is never converged, results outside the model's
validity carry warnings, a huge transient step ends in bounded time, bad case files and
absurd valvetrains are reported with the key named."""

import json
import math
import re
import time

import numpy as np
import pytest
from typer.testing import CliRunner

from ehl_cases import OIL_055 as OIL
from ehl_cases import PAIR, ROUGH, counted_advances
from tribodyn import (
    InputError,
    TransientEHL,
    solve_dry_contact,
    solve_ehl,
)
from tribodyn.cli import app
from tribodyn.config import load_case
from tribodyn.config.build import build
from tribodyn.contact.ehl.validity import MAX_ASPECT_RATIO

runner = CliRunner()


# ----------------------------------------------------------------------------- EHL validity
@pytest.mark.parametrize("rough", [None, ROUGH])
def test_negative_film_is_never_converged(rough):
    # 1e9 N/m on a 10 mm steel cylinder: Hertz b = 0.33 m ≫ R; the last iterate has h < 0
    r = solve_ehl(1e9, 0.01, 2.0, 3.0, PAIR, OIL, rough, n=256)
    assert r.min_film <= 0.0
    assert r.converged is False
    assert r.message.startswith("non-physical film: h_min =")


def test_film_much_larger_than_the_radius_is_flagged():
    r = solve_ehl(1e-3, 0.01, 2.0, 3.0, PAIR, OIL)
    assert r.converged and r.central_film > 0.01  # a film of metres on R = 10 mm
    assert any("thin-film approximation" in w for w in r.warnings)
    assert any("load-carrying zone" in w for w in r.warnings)
    assert "; warning: film h_c" in r.message


def _zone(r) -> float:
    """max |x| of the zone carrying the central 98 % of ∫(p + p_a) dx (trapezoids)."""
    q = r.pressure + (r.asperity_pressure if r.asperity_pressure is not None else 0.0)
    c = np.concatenate([[0.0], np.cumsum(0.5 * (q[1:] + q[:-1]) * np.diff(r.x))])
    c /= c[-1]
    return max(abs(np.interp(0.01, c, r.x)), abs(np.interp(0.99, c, r.x)))


@pytest.mark.parametrize("load, speed", [(5000.0, 5.0), (3000.0, 8.0)])
def test_the_parabolic_gap_is_flagged_by_its_error_at_the_zone_edge(load, speed):
    """A light load on R = 17 mm (a base circle): b ≪ R, and the inlet carries the load
    over a zone of 0.1–0.3 R. The circle exceeds the parabola x²/(2R) by x⁴/(8R³), i.e.
    (x/R)²/4 of it: flagged only beyond 1 %, with that error quoted."""
    R = 0.017
    r = solve_ehl(load, R, speed, 1.0, PAIR, OIL)
    assert r.converged
    zone = _zone(r) / R
    error = 0.25 * zone**2
    b = math.sqrt(8.0 * load * R / (math.pi * 210e9 / (1.0 - 0.3**2)))  # Hertz, steel
    assert zone > 0.1 and b < 0.01 * R
    flagged = [w for w in r.warnings if "load-carrying zone" in w]
    assert bool(flagged) == (error > 0.01)
    assert not any("Hertz half-width" in w for w in r.warnings)
    if flagged:
        m = re.search(r"reaches ([\d.]+) R .* falls short of the circle by ([\d.]+) %", flagged[0])
        assert m, flagged[0]
        assert float(m.group(1)) == pytest.approx(zone, rel=0.01)
        assert float(m.group(2)) == pytest.approx(100 * error, rel=0.03)


def test_inertia_is_flagged_at_absurd_speeds():
    r = solve_ehl(1.0, 0.01, 1e3, 1e3, PAIR, OIL)  # the fastest allowed, a light load
    text = " ".join(r.warnings)
    assert "thin-film" in text and "modified Reynolds number" in text


def test_ordinary_contacts_carry_no_validity_warning():
    """The paper's Fig. 5 point and a heavily loaded nose: inside every limit."""
    for w, R, u in ((633 / 0.012, 0.01, 15.31), (5e4, 0.003, 2.0)):
        r = solve_ehl(w, R, u, 1.0, PAIR, OIL, ROUGH)
        assert r.converged and not r.warnings, r.warnings
        hc, b = r.central_film, math.sqrt(8 * w * R / (math.pi * 2.3077e11))
        assert hc / max(b, math.sqrt(2 * R * hc)) < MAX_ASPECT_RATIO


def test_dry_contact_beyond_hertz_is_flagged():
    r = solve_dry_contact(1e9, 0.01, PAIR, n=256)
    assert any("half-width" in w for w in r.warnings)
    assert any("GPa exceeds 4 GPa" in w for w in r.warnings)
    assert not solve_dry_contact(633 / 0.012, 0.01, PAIR, n=256).warnings


# ----------------------------------------------------------------------------- transient effort
@pytest.mark.parametrize("n", [128, 256])
def test_hundredfold_load_step_ends_in_bounded_effort(n):
    """4e4 → 4e6 N/m in one step: sub-stepped along a linear ramp (at most 2^max_substeps
    equal sub-steps, halved on failure) in bounded effort, converged with a positive film
    or reported as not converged, with a warning about the coarse step."""
    tr = TransientEHL(PAIR, OIL, ROUGH, n=n)
    tr.start_steady(4e4, 0.01, 2.0, 3.0)
    with counted_advances() as calls:
        t0 = time.perf_counter()
        r = tr.step(1e-4, 4e6, 0.01, 2.0, 3.0)
        elapsed = time.perf_counter() - t0
    k = tr.max_substeps
    # ≤ 2^k marks, ≤ 2k + 1 failures each followed by ≤ k + 1 successes before the next
    # mark, and one final attempt
    assert len(calls) <= 2**k + (2 * k + 1) * (k + 2) + 1
    assert elapsed < 120
    assert tr.time == pytest.approx(1e-4)
    if r.converged:
        assert r.min_film > 0 and np.all(np.isfinite(r.pressure)) and r.load == 4e6
    assert any("changed by a factor 100 within one step" in w for w in r.warnings)


def test_a_step_that_cannot_converge_gives_up():
    tr = TransientEHL(PAIR, OIL, ROUGH, n=128, max_iter=2, max_substeps=2)
    tr.start_steady(4e4, 0.01, 2.0, 3.0)
    with counted_advances() as calls:
        r = tr.step(1e-4, 4e6, 0.01, 2.0, 3.0)
    assert r.converged is False and "gave up" in r.message
    assert len(calls) <= 2**2 + (2 * 2 + 1) * (2 + 2) + 1
    assert tr.time == pytest.approx(1e-4)  # the march stays on time


def test_small_steps_are_not_split():
    tr = TransientEHL(PAIR, OIL, ROUGH, n=256)
    tr.start_steady(4e4, 0.01, 2.0, 3.0)
    r = tr.step(1e-5, 6e4, 0.01, 2.0, 3.0)
    assert r.converged and "sub-steps" not in r.message


# ----------------------------------------------------------------------------- tribodyn contact
def contact(*args):
    return runner.invoke(app, ["contact", *args])


@pytest.mark.parametrize("extra", [["--ue", "1"], ["--us", "2"], ["--us", "0"]])
def test_dry_with_speeds_is_an_error(extra):
    r = contact("--dry", "--load", "633", "--radius", "0.01", *extra)
    assert r.exit_code == 2 and "dry contact takes no entrainment or sliding speed" in r.output


def test_cli_prints_no_negative_film():
    r = contact(
        "--load", "1e7", "--radius", "1e-4", "--ue", "2", "--us", "1", "--n", "256", "--json"
    )
    assert r.exit_code == 1
    out = json.loads(r.stdout)
    assert out["converged"] is False and out["message"].startswith("non-physical film")
    assert out["central_film_m"] is None and out["min_film_m"] is None
    assert out["friction_N"] is None


def test_cli_warns_outside_the_models_validity():
    light = ("--load-per-length", "1", "--radius", "0.01")
    r = contact("--ue", "1e3", "--us", "1e3", *light, "--json")
    assert r.exit_code == 0
    out = json.loads(r.stdout)
    assert out["converged"] and len(out["warnings"]) >= 2
    r = contact("--ue", "1e3", "--us", "1e3", *light)
    text = " ".join(r.stdout.split())
    assert "warning: film h_c" in text and "Reynolds' thin-film approximation" in text


# ----------------------------------------------------------------------------- case files
@pytest.mark.parametrize(
    "content, what",
    [
        ("[engine]\nspeed_rpm = 2000\n# Motorölviskosität\n".encode("latin-1"), "not UTF-8"),
        ("[engine]\nspeed_rpm = 2000\n".encode("utf-16"), "not UTF-8"),
        (bytes(range(256)) * 4, "not UTF-8"),
        (b"\x00\x00\x00\x00" * 64, "TOML syntax error"),
    ],
)
def test_undecodable_case_files_are_input_errors(tmp_path, content, what):
    path = tmp_path / "case.toml"
    path.write_bytes(content)
    with pytest.raises(InputError, match=what):
        load_case(path)
    r = runner.invoke(app, ["run", str(path), "-o", str(tmp_path / "out")])
    assert r.exit_code == 2 and what in " ".join(r.output.split())
    assert r.exception is None or isinstance(r.exception, SystemExit)
    assert not (tmp_path / "out").exists()


def test_dynamics_failure_is_reported_not_raised(monkeypatch):
    """A stiff integrator that gives up before the first output point (as LSODA did at a
    contact stiffness of 1e30 N/m) returns converged=False with its message."""
    from types import SimpleNamespace

    from tribodyn.valvetrain import dynamics, simulate_valvetrain

    case = load_case()
    fail = SimpleNamespace(
        status=-1,
        t=np.empty(0),
        y=np.empty((0, 0)),
        nfev=10,
        njev=1,
        nlu=1,
        message="Repeated convergence failures",
    )
    monkeypatch.setattr(dynamics, "solve_ivp", lambda *a, **k: fail)
    monkeypatch.setattr(dynamics, "compiled_model", lambda model: None)  # the solve_ivp path
    r = simulate_valvetrain(build(case).cam, build(case).valvetrain, engine_speed=3000)
    assert r.converged is False
    assert "solver failed at t = 0 s: Repeated convergence failures" in r.message


def test_compiled_dynamics_failure_is_reported_not_raised(monkeypatch):
    """The compiled path: an LSODA run that gives up returns converged=False with
    ODEPACK's message, and no arrays."""
    from tribodyn.valvetrain import compiled, simulate_valvetrain

    case = load_case()

    def failing(f, y0, t, **kw):
        info = {"nfe": np.array([10]), "nje": np.array([1]), "message": "Repeated error test"}
        return np.zeros((len(t), len(y0))), info

    monkeypatch.setattr(compiled, "odeint", failing)
    r = simulate_valvetrain(build(case).cam, build(case).valvetrain, engine_speed=3000)
    assert r.converged is False
    assert "LSODA failed: Repeated error test" in r.message
    assert r.contact_force.size == 0


def _explicit_dynamics(changes: dict):
    """(built case, explicit dynamics with the uncoated set's tribology) of the bundled
    case with ``changes``."""
    from tribodyn.valvetrain import simulate_valvetrain

    built = build(load_case().updated(changes))
    dyn = simulate_valvetrain(
        built.cam,
        built.valvetrain,
        tribology=built.analytic_tribology("uncoated"),
        **built.dynamics_options,
    )
    return built, dyn


def test_valve_jump_off_the_lobe_is_told_apart_from_the_event():
    """A weak spring at high speed: the tappet leaves the cam in the event and keeps
    bouncing on the base circle. The warning splits the lost crank angle between the two,
    as counted independently on the dynamics' samples."""
    import re

    from tribodyn.workflow.cycle import _jump_warning

    built, dyn = _explicit_dynamics(
        {
            "engine.speed_rpm": 6000.0,
            "valvetrain.spring_preload": 60.0,
            "valvetrain.spring_rate": 12000.0,
        }
    )
    assert dyn.converged and dyn.jump
    text = _jump_warning(dyn, built)
    m = re.search(r"for ([\d.]+)° crank, (\d+)° of the (\d+)° cam event and (\d+)° outside", text)
    assert m, text
    lost, inside, _, outside = map(float, m.groups())
    crank = dyn.crank_angle
    step = crank[1] - crank[0]
    off = np.zeros(crank.size, dtype=bool)
    for a, b in dyn.jumps:
        off |= (crank >= a) & (crank <= b)
    ev = dyn.event_mask()
    slack = (len(dyn.jumps) + 2) * step + 1.0  # sample edges of each interval, rounding
    assert inside == pytest.approx((off & ev).sum() * step, abs=slack)
    assert outside == pytest.approx((off & ~ev).sum() * step, abs=slack)
    assert outside > 100.0  # it bounces on the base circle for a long stretch
    assert inside + outside == pytest.approx(lost, abs=1.0)


def test_valve_jump_is_reported_clearly():
    """A 1 kg valve (allowed, heavy) on the paper's spring leaves the cam: the study warns
    with the share of the event lost."""
    from tribodyn.workflow.cycle import _jump_warning

    built, dyn = _explicit_dynamics({"valvetrain.valve_mass": 1.0})
    assert dyn.converged and dyn.jump
    text = _jump_warning(dyn, built)
    assert "loses contact with the cam (valve jump)" in text
    assert "does not follow the cam" in text
