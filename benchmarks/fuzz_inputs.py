"""Fuzz: bad and extreme inputs thrown at the Python API and the command line.

Every input is classified as

* ``handled`` — a bad input rejected with :class:`tribodyn.InputError` (API) or exit code 2
  and a message (CLI); an extreme but valid input giving a result that is either not
  converged (and says why) or converged with a physical film and a warning where the model
  does not apply;
* ``traceback`` — any other exception (API), or a CLI run that ends in an exception;
* ``garbage`` — a bad input accepted silently, a result that says converged with a
  non-positive or non-finite film, a film outside the thin-film range without a warning,
  a message naming an internal quantity instead of the user's argument, or a CLI that
  starts computing before refusing its output folder;
* ``hang`` — an input that takes longer than the per-input time limit (``LIMIT_S``);
* ``lost`` — a user's file (kept beside the inputs) deleted or changed.

Besides wrong types and out-of-range values the inputs include deeply nested TOML, ints
beyond the float range, denormal and huge loads, radii and speeds, junk ``--scheduler``
files and addresses, case and sweep files with a byte-order mark, a too long ``-o`` name,
a sweep of 10⁶ points (dry run), topography maps beyond the size limit, datasheet oils
at 223 K, and result folders with files tribodyn did not write (planted links, a figure
linking to a private file, modes 0700/2770 on a re-run, another command's folder, stale-
looking folders of someone else's, ``-o`` a link, ``--resume`` with another sweep, a
Latin-1 report.md, a foreign netCDF, 1100 levels of nesting, a folder named like the
marker).

Prints JSON: totals, counts per group and the first offending cases. The goal is
0 tracebacks, 0 hangs, 0 garbage, 0 lost files. Run: ``python benchmarks/fuzz_inputs.py``
(under a minute to a few minutes, with the machine's load).
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import os
import signal
import sys
import tempfile
import time
import traceback
import warnings
from pathlib import Path

import numpy as np

warnings.filterwarnings("ignore")

from typer.testing import CliRunner  # noqa: E402

import tribodyn  # noqa: E402
from tribodyn import (  # noqa: E402
    Body,
    Coating,
    EHLOptions,
    InputError,
    Lubricant,
    Material,
    Roughness,
    TransientEHL,
    greenwood_tripp,
    hertz_line_contact,
    solve_dry_contact,
    solve_ehl,
)
from tribodyn.cli import app  # noqa: E402
from tribodyn.config import schema  # noqa: E402
from tribodyn.physics import limits as L  # noqa: E402
from tribodyn.valvetrain import ValvetrainParameters  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
STEEL = Material(210e9, 0.3)
PAIR = (Body(STEEL), Body(STEEL))
OIL = Lubricant(0.055, 1.05e-8)
ROUGH = Roughness(2.7e9, 0.347e-6, 0.217e-6)
WRONG_TYPES = [None, "1", "abc", [1.0, 2.0], {}, 1j, object(), True, np.True_, np.complex128(1)]
HUGE_INTS = [10**400, -(10**400), 10**5000]
NON_FINITE = [float("nan"), float("inf"), -float("inf")]

OUTCOMES = ("handled", "traceback", "garbage", "hang", "lost")
results = dict.fromkeys(OUTCOMES, 0)
groups: dict[str, dict] = {}
examples: dict[str, list] = {k: [] for k in OUTCOMES if k != "handled"}
#: per-input time limit [s]: an input that takes longer counts as a hang
LIMIT_S = 60
#: the same for an input that runs a whole (coarse) study: about 40 s of CPU, so a
#: shared machine may take twice that; still a bound that a hang cannot pass
STUDY_LIMIT_S = 240
#: words of internal quantities that a message about a user's argument must not show
INTERNAL = ("dx must", "pressure_viscosity must be >= 0", "h_ref", "p_ref")


class Hang(BaseException):
    """Raised by the alarm when an input exceeds LIMIT_S."""


@contextlib.contextmanager
def time_limit(seconds: float = LIMIT_S):
    def alarm(signum, frame):
        raise Hang()

    old = signal.signal(signal.SIGALRM, alarm)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


def record(group: str, outcome: str, case: str) -> None:
    results[outcome] += 1
    g = groups.setdefault(group, dict.fromkeys(OUTCOMES, 0))
    g[outcome] += 1
    if outcome != "handled" and len(examples[outcome]) < 25:
        examples[outcome].append(f"{group}: {case}")


def expect_input_error(group: str, case: str, call, names: str | None = None) -> None:
    """InputError expected (naming ``names`` if given, and no internal quantity)."""
    try:
        with time_limit():
            call()
    except Hang:
        record(group, "hang", f"{case}: more than {LIMIT_S} s")
    except InputError as exc:
        msg = str(exc)
        internal = [w for w in INTERNAL if names is None or not w.startswith(names)]
        if any(w in msg for w in internal) or (names is not None and names not in msg):
            record(group, "garbage", f"{case}: message does not name {names}: {msg[:200]}")
        else:
            record(group, "handled", case)
    except Exception as exc:
        record(group, "traceback", f"{case} -> {type(exc).__name__}: {exc}"[:300])
    else:
        record(group, "garbage", f"{case} accepted")


def _short(v) -> str:
    if isinstance(v, int) and not isinstance(v, bool) and abs(v) > 10**20:
        return f"{'-' if v < 0 else ''}10**{len(str(abs(v))) - 1 if abs(v) < 10**4000 else 5000}"
    return f"{v!r:.20}"


def outside(limit) -> list:
    vals = []
    for b, shift in ((limit.gt, 0.0), (limit.lt, 0.0)):
        if b is not None:
            vals.append(b + shift)
    if limit.ge is not None:
        vals.append(limit.ge - max(abs(limit.ge) * 1e-3, 1e-3))
    if limit.le is not None:
        vals.append(limit.le * 10 if limit.le > 0 else limit.le + 1)
    return vals


# ----------------------------------------------------------------------------- 1 constructors
def fuzz_constructors() -> None:
    specs = {
        "Material": (Material, {"E": (210e9, L.YOUNGS_MODULUS), "nu": (0.3, L.POISSON_RATIO)}),
        "Coating": (
            Coating,
            {
                "E": (175e9, L.YOUNGS_MODULUS),
                "nu": (0.3, L.POISSON_RATIO),
                "thickness": (4e-6, L.COATING_THICKNESS),
            },
        ),
        "Lubricant": (
            Lubricant,
            {
                "viscosity": (0.055, L.VISCOSITY),
                "pressure_viscosity": (1e-8, L.PRESSURE_VISCOSITY),
                "density": (850.0, L.DENSITY),
                "eyring_stress": (2e6, L.EYRING_STRESS),
                "limiting_shear_coefficient": (0.08, L.LIMITING_SHEAR_COEFFICIENT),
                "limiting_shear_stress": (0.0, L.LIMITING_SHEAR_STRESS),
            },
        ),
        "Roughness": (
            Roughness,
            {
                "asperity_density": (1e10, L.ASPERITY_DENSITY),
                "rms": (3e-7, L.ROUGHNESS_RMS),
                "summit_radius": (1e-6, L.SUMMIT_RADIUS),
            },
        ),
        "EHLOptions": (
            EHLOptions,
            {
                "n": (256, L.EHL_NODES),
                "inlet": (4.0, L.DOMAIN_HALF_WIDTHS),
                "outlet": (1.75, L.DOMAIN_HALF_WIDTHS),
                "inlet_rigid": (4.0, L.DOMAIN_RIGID_LENGTHS),
                "inlet_truncation": (0.005, L.INLET_TRUNCATION),
                "tol": (1e-9, L.NEWTON_TOL),
                "max_iter": (60, L.NEWTON_MAX_ITER),
                "boundary_shear_coefficient": (0.185, L.BOUNDARY_SHEAR_COEFFICIENT),
            },
        ),
        "ValvetrainParameters": (
            ValvetrainParameters,
            {
                name: (getattr(ValvetrainParameters(), name), lim)
                for name, lim in __import__(
                    "tribodyn.valvetrain.parameters", fromlist=["_LIMITS"]
                )._LIMITS.items()
            },
        ),
        "hertz_line_contact": (
            hertz_line_contact,
            {
                "load": (1e4, L.Limit(gt=0.0)),
                "radius": (0.01, L.Limit(gt=0.0)),
                "reduced_modulus": (2.3e11, L.Limit(gt=0.0)),
            },
        ),
    }
    none_ok = {
        ("EHLOptions", "n"),
        ("ValvetrainParameters", "contact_stiffness"),
        ("ValvetrainParameters", "camshaft_stiffness"),
    }
    for name, (build, fields) in specs.items():
        kw = {k: v for k, (v, _) in fields.items() if v is not None}
        for arg, (_, limit) in fields.items():
            bads = WRONG_TYPES + NON_FINITE + HUGE_INTS + outside(limit)
            for bad in bads:
                if bad is None and (name, arg) in none_ok:
                    continue
                expect_input_error(
                    "api constructors",
                    f"{name}({arg}={_short(bad)})",
                    lambda: build(**{**kw, arg: bad}),
                    names=arg,
                )
    # flags, choices and objects
    for case, call in [
        ("Lubricant(compressible='no')", lambda: Lubricant(0.05, 1e-8, compressible="no")),
        ("Lubricant(viscosity_model='x')", lambda: Lubricant(0.05, 1e-8, viscosity_model="x")),
        ("Roughness(method='x')", lambda: Roughness(1e10, 3e-7, 1e-6, method="x")),
        ("EHLOptions(elastic='no')", lambda: EHLOptions(elastic="no")),
        ("EHLOptions(viscous_model=1)", lambda: EHLOptions(viscous_model=1)),
        ("EHLOptions(time_order=3)", lambda: EHLOptions(time_order=3)),
        ("Body('steel')", lambda: Body("steel")),
        ("Body(STEEL, coating=STEEL)", lambda: Body(STEEL, coating=STEEL)),
        ("TransientEHL(max_substeps='a')", lambda: TransientEHL(PAIR, OIL, max_substeps="a")),
        ("TransientEHL(max_substeps=-1)", lambda: TransientEHL(PAIR, OIL, max_substeps=-1)),
        ("TransientEHL(max_substeps=99)", lambda: TransientEHL(PAIR, OIL, max_substeps=99)),
        ("TransientEHL(n=8192)", lambda: TransientEHL(PAIR, OIL, n=8192)),
        ("TransientEHL(bodies=None)", lambda: TransientEHL(None, OIL)),
        ("TransientEHL(lubricant='oil')", lambda: TransientEHL(PAIR, "oil")),
        (
            "TransientEHL.step before start",
            lambda: TransientEHL(PAIR, OIL).step(1e-5, 1e4, 0.01, 1, 0),
        ),
        ("greenwood_tripp(1e6, 1)", lambda: greenwood_tripp(1e6, 1.0)),
        ("greenwood_tripp(2.5, '1')", lambda: greenwood_tripp(2.5, "1")),
        ("greenwood_tripp(-1, 1)", lambda: greenwood_tripp(-1, 1.0)),
        ("greenwood_tripp(2.5, nan)", lambda: greenwood_tripp(2.5, float("nan"))),
        ("greenwood_tripp(2.5, [1, inf])", lambda: greenwood_tripp(2.5, [1.0, math.inf])),
        ("greenwood_tripp(1.5, 1, 'paper')", lambda: greenwood_tripp(1.5, 1.0, "paper")),
        ("greenwood_tripp(2, 1, None)", lambda: greenwood_tripp(2, 1.0, None)),
        (
            "ValvetrainParameters(spring_masses=2.5)",
            lambda: ValvetrainParameters(spring_masses=2.5),
        ),
        ("ValvetrainParameters().replace(x=1)", lambda: ValvetrainParameters().replace(x=1)),
    ]:
        expect_input_error("api constructors", case, call)


# ----------------------------------------------------------------------------- 2 solver args
def fuzz_solver_arguments() -> None:
    base = dict(load=1e4, radius=0.01, entrainment_speed=1.0, sliding_speed=0.5)
    for arg in base:
        bads = WRONG_TYPES + NON_FINITE
        if arg in ("load", "radius"):
            bads = bads + [0.0, -1.0]
        if arg == "entrainment_speed":
            bads = bads + [0.0]
        for bad in bads:
            kw = {**base, arg: bad}
            expect_input_error(
                "api solver arguments",
                f"solve_ehl({arg}={bad!r:.20})",
                lambda kw=kw: solve_ehl(bodies=PAIR, lubricant=OIL, n=128, **kw),
            )
    for case, call in [
        ("solve_ehl(bodies=None)", lambda: solve_ehl(1e4, 0.01, 1, 0, None, OIL)),
        ("solve_ehl(bodies=(Body,))", lambda: solve_ehl(1e4, 0.01, 1, 0, (PAIR[0],), OIL)),
        ("solve_ehl(lubricant=None)", lambda: solve_ehl(1e4, 0.01, 1, 0, PAIR, None)),
        ("solve_ehl(roughness=0.3e-6)", lambda: solve_ehl(1e4, 0.01, 1, 0, PAIR, OIL, 3e-7)),
        ("solve_ehl(n='x')", lambda: solve_ehl(1e4, 0.01, 1, 0, PAIR, OIL, n="x")),
        ("solve_ehl(n=10)", lambda: solve_ehl(1e4, 0.01, 1, 0, PAIR, OIL, n=10)),
        ("solve_ehl(nonsense=1)", lambda: solve_ehl(1e4, 0.01, 1, 0, PAIR, OIL, nonsense=1)),
        ("solve_dry_contact(n='x')", lambda: solve_dry_contact(1e4, 0.01, PAIR, n="x")),
        ("solve_dry_contact(load=-1)", lambda: solve_dry_contact(-1, 0.01, PAIR)),
        ("solve_dry_contact(domain=0.5)", lambda: solve_dry_contact(1e4, 0.01, PAIR, domain=0.5)),
        ("solve_dry_contact(bodies=1)", lambda: solve_dry_contact(1e4, 0.01, 1)),
        ("TransientEHL.step(dt=0)", lambda: _started().step(0.0, 1e4, 0.01, 1.0, 0.0)),
        ("TransientEHL.step(dt='a')", lambda: _started().step("a", 1e4, 0.01, 1.0, 0.0)),
        ("TransientEHL.step(load=nan)", lambda: _started().step(1e-5, math.nan, 0.01, 1.0, 0)),
        (
            "TransientEHL.start_film(film=-1)",
            lambda: TransientEHL(PAIR, OIL).start_film(-1.0, 1e4, 0.01),
        ),
    ]:
        expect_input_error("api solver arguments", case, call)


_STARTED = None


def _started():
    global _STARTED
    if _STARTED is None:
        _STARTED = TransientEHL(PAIR, OIL, n=128)
        _STARTED.start_steady(1e4, 0.01, 1.0, 0.0)
    return _STARTED


# ----------------------------------------------------------------------------- 3 extreme solves
def check_solution(group, case, res, radius=None) -> None:
    film = np.asarray(res.film if hasattr(res, "film") else [1.0])
    if res.converged:
        bad = (not np.all(np.isfinite(film))) or np.any(film <= 0)
        if hasattr(res, "central_film") and radius is not None and not bad:
            if res.central_film > 0.02 * radius and not res.warnings:
                bad = True
        if bad:
            record(group, "garbage", f"{case}: converged with h_c = {res.central_film:.3g}")
            return
    elif not res.message:
        record(group, "garbage", f"{case}: not converged without a message")
        return
    record(group, "handled", case)


def fuzz_extreme_solves() -> None:
    loads = [1e-3, 1.0, 1e3, 1e6, 1e8, 1e9, 1e10]
    speeds = [1e-3, 1.0, 1e3, 1e6, -1e6]
    for w in loads:
        for ue in speeds:
            case = f"solve_ehl(w={w:g}, R=0.01, ue={ue:g})"
            try:
                r = solve_ehl(w, 0.01, ue, ue, PAIR, OIL, ROUGH, n=128, max_iter=30)
            except InputError:
                record("api extreme solves", "handled", case)
            except Exception as exc:
                record("api extreme solves", "traceback", f"{case} -> {exc!r}"[:300])
            else:
                check_solution("api extreme solves", case, r, 0.01)
    for R in (1e-6, 1e-4, 1.0, 100.0):
        case = f"solve_ehl(w=1e4, R={R:g})"
        try:
            r = solve_ehl(1e4, R, 2.0, 1.0, PAIR, OIL, n=128, max_iter=30)
            check_solution("api extreme solves", case, r, R)
        except InputError:
            record("api extreme solves", "handled", case)
        except Exception as exc:
            record("api extreme solves", "traceback", f"{case} -> {exc!r}"[:300])
    for w in (1e-3, 1e4, 1e9, 1e12):
        case = f"solve_dry_contact(w={w:g})"
        try:
            r = solve_dry_contact(w, 0.01, PAIR, n=128)
            record(
                "api extreme solves", "handled" if (r.converged or r.message) else "garbage", case
            )
        except InputError:
            record("api extreme solves", "handled", case)
        except Exception as exc:
            record("api extreme solves", "traceback", f"{case} -> {exc!r}"[:300])
    for w1 in (4e6, 4e8, 1.0):  # huge transient steps: bounded effort
        case = f"TransientEHL.step 4e4 -> {w1:g}"
        t0 = time.perf_counter()
        try:
            tr = TransientEHL(PAIR, OIL, ROUGH, n=128)
            tr.start_steady(4e4, 0.01, 2.0, 3.0)
            r = tr.step(1e-4, w1, 0.01, 2.0, 3.0)
            if time.perf_counter() - t0 > 120:
                record("api extreme solves", "garbage", f"{case}: took > 120 s")
            else:
                check_solution("api extreme solves", case, r, 0.01)
        except Exception as exc:
            record("api extreme solves", "traceback", f"{case} -> {exc!r}"[:300])


# ----------------------------------------------------------------------------- CLI helpers
runner = CliRunner()


#: a user's files that no input may delete or change: path → content
KEEP: dict[Path, bytes] = {}


def lost_files() -> list[str]:
    return [str(p) for p, c in KEEP.items() if not p.is_file() or p.read_bytes() != c]


def cli(group: str, args: list[str], expect=(2,), check=None, seconds: float = LIMIT_S) -> None:
    """Run the command line with ``args``; ``seconds`` bounds it (a whole study that
    computes, such as the weak-spring runs, gets a longer bound than a refusal)."""
    case = "tribodyn " + " ".join(a if len(a) <= 60 else a[:20] + "…" for a in args)
    try:
        with time_limit(seconds):
            r = runner.invoke(app, args, catch_exceptions=True)
    except Hang:
        record(group, "hang", f"{case}: more than {seconds:g} s")
        return
    except Exception as exc:
        record(group, "traceback", f"{case} -> {exc!r}"[:300])
        return
    gone = lost_files()
    if gone:
        record(group, "lost", f"{case}: {', '.join(gone)}")
        for p in list(KEEP):
            if str(p) in gone:
                KEEP.pop(p)
        return
    if r.exception is not None and not isinstance(r.exception, SystemExit):
        tb = "".join(traceback.format_exception(r.exception))[-300:]
        record(group, "traceback", f"{case} -> {tb}")
        return
    if "Traceback" in r.output:
        record(group, "traceback", f"{case} -> traceback in the output")
        return
    if r.exit_code not in expect:
        record(
            group, "garbage", f"{case}: exit {r.exit_code}, expected {expect}: {r.output[-200:]}"
        )
        return
    if check is not None:
        problem = check(r)
        if problem:
            record(group, "garbage", f"{case}: {problem}")
            return
    record(group, "handled", case)


def no_bad_film(r):
    try:
        out = json.loads(r.stdout)
    except ValueError:
        return None
    h = out.get("central_film_m")
    if h is not None and (not math.isfinite(h) or h <= 0):
        return f"prints a non-physical film {h}"
    if (
        out.get("converged")
        and h is not None
        and h > 0.02 * out["radius_m"]
        and not out.get("warnings")
    ):
        return "a film beyond the thin-film range without a warning"
    return None


# ----------------------------------------------------------------------------- 4 contact CLI
def fuzz_contact_cli() -> None:
    ok = ["--load", "633", "--radius", "0.01", "--ue", "5"]
    numeric = [
        "--load",
        "--radius",
        "--ue",
        "--us",
        "--width",
        "--load-per-length",
        "--viscosity",
        "--pressure-viscosity",
        "--density",
        "--eyring-stress",
        "--limiting-shear-coefficient",
        "--coating-thickness",
        "--shear-coefficient",
        "--n",
    ]
    for opt in numeric:
        for bad in ("abc", "nan", "inf", "-1", "0", "1e400", ""):
            if opt in ("--ue", "--us") and bad in ("-1", "0", "1e400"):
                continue
            args = [a for a in ok]
            if opt in args:
                args[args.index(opt) + 1] = bad
            else:
                args += [opt, bad]
                if opt == "--load-per-length":
                    args = [a for a in args if a not in ("--load", "633")]
                if opt == "--coating-thickness":
                    args += ["--coating-material", "dlc"]
            zero_ok = bad == "0" and opt in (
                "--shear-coefficient",
                "--pressure-viscosity",
                "--limiting-shear-coefficient",
            )
            cli(
                "contact cli",
                ["contact", *args],
                expect=(0,) if zero_ok else (2,),
                check=no_bad_film,
            )
    for extra in (
        ["--coating", "1,2"],
        ["--coating", "a,b,c"],
        ["--coating", "175e9,0.6,4e-6"],
        ["--coating", "1e-30,0.3,4e-6"],
        ["--roughness", "1e9,1.0,1e-6"],
        ["--roughness", "x"],
        ["--roughness", "1e9,-1,1e-6"],
        ["--surface-set", "nope"],
        ["--coating-material", "gold", "--coating-thickness", "1e-6"],
        ["--viscosity-model", "bogus"],
        ["--viscous-model", "x"],
        ["--case", "/nonexistent.toml"],
        ["--case", str(REPO)],
        ["--dry", "--us", "0"],
        ["--dry", "--ue", "3"],
        ["--coating", "175e9,0.3,4e-6", "--coating-material", "dlc"],
        ["--surface-set", "wcc_4um", "--roughness", "1e9,1e-7,1e-6"],
    ):
        cli("contact cli", ["contact", *ok, *extra], check=no_bad_film)
    cli("contact cli", ["contact", "--radius", "0.01", "--ue", "5"])  # no load
    cli("contact cli", ["contact", "--load", "633", "--ue", "5"])  # no radius
    cli("contact cli", ["contact", "--load", "633", "--radius", "0.01"])  # no speed
    for args, expect in (
        (["--load", "1e7", "--radius", "1e-4", "--ue", "2", "--us", "1"], (0, 1)),
        (["--load-per-length", "1", "--radius", "0.01", "--ue", "1e3", "--us", "1e3"], (0, 1)),
        (["--load", "1e-3", "--radius", "0.01", "--ue", "2"], (0, 1)),
        (["--load-per-length", "1e-3", "--radius", "0.01", "--ue", "2"], (0, 1)),
        (["--dry", "--load", "1e7", "--radius", "1e-4"], (0, 1)),
        # beyond limits.LINE_LOAD and SURFACE_SPEED: refused
        (["--load", "1e9", "--radius", "0.01", "--ue", "2", "--us", "1"], (2,)),
        (["--load", "633", "--radius", "0.01", "--ue", "1e6", "--us", "1e6"], (2,)),
        (["--dry", "--load", "1e9", "--radius", "0.01"], (2,)),
    ):
        cli(
            "contact cli extremes",
            ["contact", *args, "--n", "256", "--json"],
            expect=expect,
            check=no_bad_film,
        )


# ----------------------------------------------------------------------------- 5 topography CLI
def fuzz_topography_cli(tmp: Path) -> None:
    data = REPO / "tests" / "data" / "topography"
    junk = {
        "empty.x3p": b"",
        "text.opd": b"hello world\n" * 10,
        "zeros.sur": b"\0" * 600,
        "random.dat": bytes(np.random.default_rng(0).integers(0, 256, 2000, dtype=np.uint8)),
        "random.plu": bytes(np.random.default_rng(1).integers(0, 256, 900, dtype=np.uint8)),
        "bad.sdf": b"aISO-1.0\nManufacID = x\n*\n1 2 3\n*\n",
        "bad.nc": b"CDF\x01" + b"\0" * 50,
        "notazip.x3p": b"PK\x03\x04" + b"\0" * 100,
    }
    for name, content in junk.items():
        (tmp / name).write_bytes(content)
        cli("topography cli", ["topography", str(tmp / name)])
    if data.is_dir():
        for f in sorted(data.glob("surface.*")) + sorted(data.glob("profile.*")):
            raw = f.read_bytes()
            for cut in (50, 600, len(raw) // 2, len(raw) - 5):
                t = tmp / f"trunc{cut}_{f.name}"
                t.write_bytes(raw[:cut])
                cli("topography cli", ["topography", str(t)])
        good = str(data / "surface.x3p")
        for extra in (
            ["--band", "-1", "1"],
            ["--band", "1e-5", "1e-6"],
            ["--band", "nan", "1"],
            ["--band", "0.1e-6", "10e-6"],
            ["--band", "1e-6", "1"],
            ["--filter", "box"],
            ["--detrend", "cubic"],
            ["--method", "x"],
            ["--min-defined", "2"],
            ["--min-defined", "0.99"],
            ["--channel", "7"],
            ["--unit", "furlong"],
            ["--size", "-1", "1"],
            ["--figure", str(tmp)],
            ["--figure", str(tmp / "f.tmp")],
            ["--figure", "/proc/f.png"],
        ):
            cli("topography cli", ["topography", good, *extra])
        cli(
            "topography cli valid",
            ["topography", good, "--figure", str(tmp / "new" / "dir" / "f.png")],
            expect=(0,),
        )
        for args in ([good, good], [str(data / "profile.sdf")], [good, str(data / "profile.sur")]):
            cli("topography cli valid", ["topography", *args], expect=(0,))
    cli("topography cli", ["topography"])
    cli("topography cli", ["topography", "a", "b", "c"])
    cli("topography cli", ["topography", str(tmp / "missing.x3p")])
    cli("topography cli", ["topography", str(tmp)])
    for extra in (
        ["--grid", "4"],
        ["--pixel", "-1"],
        ["--rms", "0"],
        ["--hurst", "2"],
        ["--cutoffs", "1e-6", "1e-7"],
    ):
        cli("topography cli", ["topography", str(tmp / "syn.x3p"), "--synthetic", *extra])
    cli(
        "topography cli",
        [
            "topography",
            str(tmp / "nodir" / "syn.x3p"),
            "--synthetic",
            "--grid",
            "64",
            "--cutoffs",
            "1e-6",
            "4e-6",
        ],
        expect=(0, 2),
    )


# ----------------------------------------------------------------------------- 6 run CLI
def fuzz_run_cli(tmp: Path) -> None:
    import tribodyn.workflow.cycle as cycle

    def must_not_run(*a, **k):
        raise RuntimeError("the study started although its input or output was bad")

    original = cycle.run_cycle_study
    cycle.run_cycle_study = must_not_run
    try:

        def bad_case(name: str, content: bytes | str, key: str | None) -> None:
            p = tmp / f"{name}.toml"
            p.write_bytes(content if isinstance(content, bytes) else content.encode())

            def check(r):
                text = " ".join(r.output.split())
                return None if key is None or key in text else f"message does not name {key}"

            cli("run cli case files", ["run", str(p), "-o", str(tmp / "out")], check=check)

        models = {
            "engine": schema.Engine,
            "valvetrain": schema.Valvetrain,
            "lubricant": schema.LubricantConfig,
            "numerics": schema.Numerics,
        }
        for section, model in models.items():
            for field, fi in model.model_fields.items():
                bounds = {
                    k: getattr(m, k)
                    for m in fi.metadata
                    for k in ("gt", "ge", "lt", "le")
                    if getattr(m, k, None) is not None
                }
                ann = str(fi.annotation)
                if not bounds or "float" not in ann and "int" not in ann:
                    continue
                for k, v in bounds.items():
                    bad = {"gt": v, "ge": v - 1, "lt": v, "le": v * 10 + 1}[k]
                    if "int" in ann and "float" not in ann:
                        bad = int(bad) if math.isfinite(bad) else 10**9
                    bad_case(
                        f"{section}-{field}-{k}",
                        f"[{section}]\n{field} = {bad!r}\n",
                        f"{section}.{field}",
                    )
                bad_case(
                    f"{section}-{field}-str", f"[{section}]\n{field} = 'x'\n", f"{section}.{field}"
                )
        for name, content, key in [
            ("latin1", "[engine]\nspeed_rpm = 2000\n# Öl\n".encode("latin-1"), "UTF-8"),
            ("utf16", "[engine]\nspeed_rpm = 2000\n".encode("utf-16"), "UTF-8"),
            ("binary", bytes(range(256)) * 8, "UTF-8"),
            ("nul", b"\0" * 100, "TOML"),
            ("syntax", "[engine\n", "TOML"),
            ("unknown", "[engine]\nspeed = 3\n", "engine.speed"),
            (
                "absurd-stiffness",
                "[valvetrain]\ncontact_stiffness = 1e30\n",
                "valvetrain.contact_stiffness",
            ),
            ("absurd-mass", "[valvetrain]\nvalve_mass = 1e6\n", "valvetrain.valve_mass"),
            ("table-missing", "[cam]\ntype = 'table'\npath = 'nope.csv'\n", "cam.path"),
            ("nan", "[lubricant]\nviscosity = nan\n", "lubricant.viscosity"),
            ("sets-empty", "surface_sets = []\n", "surface_sets"),
        ]:
            bad_case(name, content, key)
        cli("run cli case files", ["run", str(tmp / "missing.toml")])
        cli("run cli case files", ["run", str(tmp)])
        # bad output locations with a valid case: refused before anything is computed
        (tmp / "afile").write_text("keep")
        (tmp / "foreign").mkdir(exist_ok=True)
        (tmp / "foreign" / "x").write_text("keep")
        for out in (tmp / "afile", tmp / "foreign", tmp / "afile" / "sub", Path("/proc/x")):
            cli("run cli output", ["run", "-o", str(out), "-q"])
        for opt in (["-j", "abc"], ["-j", "-3"], ["--bogus"]):
            cli("run cli output", ["run", *opt, "-o", str(tmp / "new")], expect=(2,))
    finally:
        cycle.run_cycle_study = original


# ----------------------------------------------------------------------------- 7 new kinds
def fuzz_extreme_kinds(tmp: Path) -> None:
    """Nested TOML, huge ints, denormal/huge operating points, junk schedulers, BOM,
    long names, huge sweeps, large maps and cold datasheet oils."""
    from tribodyn.config import Case, load_case
    from tribodyn.config.sweep import load_sweep
    from tribodyn.physics.oils import OILS
    from tribodyn.physics.thermal_oil import ThermalLubricant

    keep = tmp / "user_notes.txt"
    keep.write_text("a user's file")
    KEEP[keep] = keep.read_bytes()
    g = "nested toml"
    nested = {
        "arrays": "a = " + "[" * 5000 + "]" * 5000,
        "inline": "a = " + "{b = " * 3000 + "1" + "}" * 3000,
        "dotted": "a" + ".b" * 5000 + " = 1",
        "header": "[" + ".".join(["t"] * 5000) + "]\nx = 1\n",
        "arrays40": "[engine]\nspeed_rpm = " + "[" * 40 + "1" + "]" * 40,
    }
    for name, text in nested.items():
        f = tmp / f"nested_{name}.toml"
        f.write_text(text)
        expect_input_error(g, f"load_case(nested {name})", lambda f=f: load_case(f), "nested")
        expect_input_error(g, f"load_sweep(nested {name})", lambda f=f: load_sweep(f), "nested")
        cli(g, ["run", str(f), "-o", str(tmp / "out_nested")])
        cli(g, ["sweep", str(f), "-o", str(tmp / "out_nested"), "--dry-run"])
    deep: dict = {}
    for _ in range(3000):
        deep = {"x": deep}
    expect_input_error(g, "Case.from_dict(3000 levels)", lambda: Case.from_dict({"a": deep}))

    g = "operating point"
    pair_args = dict(bodies=PAIR, lubricant=OIL, n=64, max_iter=10)
    for arg, bad in [
        ("load", 5e-324),
        ("load", 1e-300),
        ("load", 1e300),
        ("load", 10**400),
        ("radius", 5e-324),
        ("radius", 1e300),
        ("entrainment_speed", 1e300),
        ("entrainment_speed", -1e300),
        ("sliding_speed", 1e300),
    ]:
        kw = {**dict(load=1e4, radius=0.01, entrainment_speed=1.0, sliding_speed=0.5), arg: bad}
        expect_input_error(
            g, f"solve_ehl({arg}={_short(bad)})", lambda kw=kw: solve_ehl(**kw, **pair_args), arg
        )
        expect_input_error(
            g,
            f"TransientEHL.start_steady({arg}={_short(bad)})",
            lambda kw=kw: TransientEHL(PAIR, OIL, n=64).start_steady(**kw),
            arg,
        )
        if arg in ("load", "radius"):
            expect_input_error(
                g,
                f"solve_dry_contact({arg}={_short(bad)})",
                lambda kw=kw: solve_dry_contact(kw["load"], kw["radius"], PAIR, n=64),
                arg,
            )

    g = "scheduler"
    junk = tmp / "junk_scheduler"
    junk.write_text("garbage")
    badjson = tmp / "bad_scheduler.json"
    badjson.write_text('{"address": 5}')
    for address in (str(junk), str(badjson), str(tmp), "garbage", "tcp://", "ucx://a:1"):
        for cmd in (["run"], ["sweep", "andreou2023_dynamics"]):
            cli(g, [*cmd, "-o", str(tmp / "out_sched"), "--scheduler", address, "-q"])

    g = "byte-order mark"
    bom_case = tmp / "bom_case.toml"
    bom_case.write_bytes("\ufeff[engine]\nspeed_rpm = 2000\n".encode())
    bom_sweep = tmp / "bom_sweep.toml"
    bom_sweep.write_bytes(
        "\ufeff[sweep]\nmode = 'dynamics'\n[[axes]]\npath = 'engine.speed_rpm'\n"
        "values = [2000, 3000]\n".encode()
    )
    for case, call, ok in [
        ("load_case(BOM)", lambda: load_case(bom_case).engine.speed_rpm == 2000, True),
        ("load_sweep(BOM)", lambda: load_sweep(bom_sweep).n_points == 2, True),
    ]:
        try:
            with time_limit():
                good = call()
            record(g, "handled" if good == ok else "garbage", case)
        except Exception as exc:
            record(g, "traceback", f"{case} -> {type(exc).__name__}: {exc}"[:300])

    g = "long -o name"
    for out in (tmp / ("x" * 300), tmp / ("y" * 200) / ("z" * 200)):
        cli(g, ["topography", str(out) + ".x3p", "--synthetic", "--grid", "32"])
        cli(g, ["sweep", "andreou2023_dynamics", "-o", str(out), "--scheduler", str(junk)])

    g = "huge sweep"
    big = tmp / "million.toml"
    big.write_text(
        "[sweep]\nmode = 'dynamics'\n"
        "[[axes]]\npath = 'engine.speed_rpm'\nstart = 1000\nstop = 7000\nnum = 1000\n"
        "[[axes]]\npath = 'valvetrain.spring_preload'\nstart = 200\nstop = 300\nnum = 1000\n"
    )
    cli(g, ["sweep", str(big), "-o", str(tmp / "out_big"), "--dry-run"], expect=(0,))
    too_big = tmp / "too_many.toml"
    too_big.write_text(
        "[[axes]]\npath = 'engine.speed_rpm'\nstart = 1000\nstop = 7000\nnum = 2000\n"
        "[[axes]]\npath = 'valvetrain.spring_preload'\nstart = 200\nstop = 300\nnum = 1000\n"
    )
    cli(g, ["sweep", str(too_big), "-o", str(tmp / "out_big"), "--dry-run"])
    out_of_range = tmp / "long_axis.toml"
    out_of_range.write_text(
        "[[axes]]\npath = 'engine.speed_rpm'\nstart = 1000\nstop = 70000\nnum = 100000\n"
    )
    cli(g, ["sweep", str(out_of_range), "-o", str(tmp / "out_big"), "--dry-run"])

    g = "large maps"
    for grid in ("5000", "100000"):
        cli(g, ["topography", str(tmp / f"syn{grid}.x3p"), "--synthetic", "--grid", grid])
    from tribodyn.topography import synthetic_surface

    for shape in ((4097, 4096), (10**400, 16), (1e9, 1e9)):
        expect_input_error(
            g, f"synthetic_surface({_short(shape[0])})", lambda s=shape: synthetic_surface(s)
        )

    g = "cold oils"
    for grade, sheet in OILS.items():
        sheet = {k: v for k, v in sheet.items() if k != "description"}
        for T in (200.0, 223.15, 233.15, 600.0):
            case = f"ThermalLubricant({grade}, {T:g} K)"
            try:
                with time_limit():
                    oil = ThermalLubricant(inlet_temperature=T, **sheet)
                    alpha = oil.inlet_pressure_viscosity
                    oil.isothermal()
                ok = math.isfinite(alpha) and alpha > 0
                record(g, "handled" if ok else "garbage", f"{case}: α = {alpha:.3g}")
            except InputError as exc:
                good = str(exc).startswith("inlet_temperature")
                record(g, "handled" if good else "garbage", f"{case}: {exc}"[:250])
            except Exception as exc:
                record(g, "traceback", f"{case} -> {type(exc).__name__}: {exc}"[:300])


# ----------------------------------------------------------------------------- 8 users' files
def fuzz_user_files(tmp: Path) -> None:
    """Users' files as they come: calibration data in other encodings, with a BOM, with
    decimal commas, repeated rows, a viscosity in mPa·s; pipes and devices where a file
    is expected (DATA, cam.path, a case file, the result-folder marker); a NUL in cam.path;
    a --label that would inject TOML."""
    from tribodyn.config import Case
    from tribodyn.output.result_folder import MARKER, _marker_info
    from tribodyn.workflow.calibration import (
        CalibrationSetup,
        FrictionData,
        model_friction,
    )

    g = "users' files"
    d = tmp / "user_files"
    d.mkdir()
    # the calibration guide's contact and oil; a Stribeck curve (slide-to-roll 0.2) and a
    # traction curve at its top speed, with 0.001 noise
    sigma, beta = 0.3e-6, 0.3e-3
    setup = CalibrationSetup(
        radius=0.01,
        lubricant=OIL.__class__(0.02, 2e-8),
        roughness=Roughness(0.15 / (beta * sigma), sigma, beta),
    )
    truth = {
        "boundary_shear_coefficient": 0.11,
        "eyring_stress": 3e6,
        "limiting_shear_coefficient": 0.025,
    }

    def measured(lo, hi):
        ue = np.r_[np.geomspace(lo, hi, 14), np.full(14, hi)]
        us = np.r_[0.2 * ue[:14], np.geomspace(hi / 1000, 2 * hi, 14)]
        w = np.full(ue.size, 2e5)
        mu = model_friction(setup, FrictionData(ue, us, w, np.zeros(ue.size)), **truth)
        mu = mu + np.random.default_rng(0).normal(0.0, 0.001, mu.size)
        return ue, us / ue, mu

    def csv_text(pts, sep=",", decimal="."):
        rows = [
            "# twin disc, R = 10 mm, 200 kN/m, 90 °C",
            sep.join(("entrainment_speed", "slide_roll_ratio", "friction_coefficient")),
        ]
        rows += [sep.join(f"{v:.9g}".replace(".", decimal) for v in r) for r in zip(*pts)]
        return "\n".join(rows) + "\n"

    args = [
        "--radius",
        "0.01",
        "--load",
        "2e5",
        "--pressure-viscosity",
        "2e-8",
        "--rms",
        "0.3e-6",
        "--roughness-parameter",
        "0.15",
    ]
    pts = measured(1e-3, 0.2)
    ref = d / "utf8.csv"
    ref.write_text(csv_text(pts), encoding="utf-8")
    r = runner.invoke(app, ["calibrate", str(ref), *args, "--viscosity", "0.02", "--json"])
    want = json.loads(r.stdout)["values"] if r.exit_code == 0 else None

    def same_fit(res):
        try:
            got = json.loads(res.stdout)["values"]
        except (ValueError, KeyError):
            return "no JSON result"
        return None if got == want else f"another fit than the UTF-8 file: {got} vs {want}"

    text = csv_text(pts)
    for name, raw in {
        "cp1252.csv": text.encode("cp1252"),
        "latin1.csv": text.encode("latin-1"),
        "utf16.csv": text.encode("utf-16"),
        "utf16be.csv": b"\xfe\xff" + text.encode("utf-16-be"),
        "excel_bom.csv": b"\xef\xbb\xbf" + text.encode("utf-8"),
        "semicolon_decimal_comma.csv": csv_text(pts, ";", ",").encode("cp1252"),
    }.items():
        (d / name).write_bytes(raw)
        cli(
            f"{g}: encodings",
            ["calibrate", str(d / name), *args, "--viscosity", "0.02", "--json"],
            expect=(0,),
            check=same_fit,
        )

    def says(*words):
        def check(res):
            flat = " ".join(res.output.split())
            missing = [w for w in words if w not in flat]
            return f"message lacks {missing}: {flat[-200:]}" if missing else None

        return check

    (d / "decimal_comma.csv").write_text(csv_text(pts, ",", ","))
    cli(
        f"{g}: decimal commas",
        ["calibrate", str(d / "decimal_comma.csv"), *args, "--viscosity", "0.02"],
        check=says("decimal commas"),
    )
    rows = text.splitlines()
    (d / "repeated.csv").write_text(text + "\n".join(rows[2:8]) + "\n")

    def counted_once(res):
        out = json.loads(res.stdout)
        if out["n_points"] != len(pts[0]):
            return f"{out['n_points']} points fitted, {len(pts[0])} distinct"
        return None if any("repeat" in w for w in out.get("warnings", [])) else "no warning"

    cli(
        f"{g}: repeated rows",
        ["calibrate", str(d / "repeated.csv"), *args, "--viscosity", "0.02", "--json"],
        expect=(0,),
        check=counted_once,
    )
    # viscosity in mPa·s given as Pa·s (×1000): not converged, the viscosity named
    fixed = [
        "--fit",
        "boundary_shear_coefficient",
        "--fix",
        "eyring_stress=3e6",
        "--fix",
        "limiting_shear_coefficient=0.025",
    ]
    cli(
        f"{g}: viscosity x1000",
        ["calibrate", str(ref), *args, "--viscosity", "20", *fixed],
        expect=(1,),
        check=says("viscosity", "1000×"),
    )
    low = d / "low_speed.csv"
    low.write_text(csv_text(measured(1e-5, 0.01)))
    cli(
        f"{g}: viscosity x1000",
        ["calibrate", str(low), *args, "--viscosity", "20"],
        expect=(1,),
        check=says("viscosity"),
    )
    cli(
        f"{g}: label",
        [
            "calibrate",
            str(ref),
            *args,
            "--viscosity",
            "0.02",
            "--label",
            "pair\n[numerics]\nn = 1\n",
        ],
        check=says("--label"),
    )
    # pipes and devices where a file is expected
    specials = []
    if hasattr(os, "mkfifo"):
        for name in ("pipe.csv", "pipe.toml"):
            os.mkfifo(d / name)
        specials.append(d / "pipe.csv")
        cli(
            f"{g}: pipe",
            ["run", str(d / "pipe.toml"), "-o", str(d / "out")],
            check=says("named pipe"),
        )
    if Path("/dev/zero").exists():
        specials.append(Path("/dev/zero"))
    for p in specials:
        cli(
            f"{g}: pipe or device",
            ["calibrate", str(p), *args, "--viscosity", "0.02"],
            check=says("DATA"),
        )
        expect_input_error(
            f"{g}: pipe or device",
            f"cam.path = {p}",
            lambda p=p: Case.from_toml_string(f"[cam]\ntype = 'table'\npath = '{p}'\n", base_dir=d),
            names="cam.path",
        )
        folder = d / f"results_{p.stem}"
        folder.mkdir()
        if p.name == "pipe.csv":
            os.mkfifo(folder / MARKER)
        else:
            (folder / MARKER).symlink_to(p)
        case = f"result-folder marker = {p}"
        try:
            with time_limit():
                info = _marker_info(folder)
            record(g, "handled" if info == {} else "garbage", f"{case}: {info!r:.80}")
        except Hang:
            record(g, "hang", f"{case}: more than {LIMIT_S} s")
        except Exception as exc:
            record(g, "traceback", f"{case} -> {type(exc).__name__}: {exc}"[:300])
    expect_input_error(
        f"{g}: NUL in a path",
        "cam.path with a NUL",
        lambda: Case.from_dict({"cam": {"type": "table", "path": "lift\x00.csv"}}, base_dir=d),
        names="cam.path",
    )


def fuzz_engine_inputs(tmp: Path) -> None:
    """The engine study's inputs and the weak spring: lobe changes naming a shared key in
    another spelling or renaming a surface set, a lobe's own cam table (copied with the
    results), a tappet-rotation offset beyond the face, absurd displacement and bore, a
    spring that lets the valve jump (handled only if the run completes and reports the
    separation); the stress API's ranges and size guards; float32 grids, 0-d arrays and
    arrays as sweep-axis values. Coarse numerics; one engine computation in all."""
    import shutil

    from tribodyn.config import SweepSpec, load_case
    from tribodyn.config.case import CASES_DIR, to_toml
    from tribodyn.config.paths import set_path
    from tribodyn.physics.stress import StressOperator, subsurface_stress

    g = "engine inputs"
    quick = {
        "numerics.crank_step_deg": 5.0,
        "numerics.n": 128,
        "numerics.implicit_coupling": False,
        "numerics.output_step_deg": 1.0,
        "numerics.workers": 1,
    }
    engine = {
        "engine.cylinders": 4,
        "engine.displacement": 0.0016,
        "engine.intake": {"centre_angle_deg": 470.0},
        "engine.exhaust": {"centre_angle_deg": 250.0},
    }
    paper = load_case()
    one_set = {**quick, "surface_sets": paper.to_dict()["surface_sets"][:1]}
    base = paper.updated({**one_set, **engine}).to_dict(resolve_paths=True)

    def write(name: str, changes: dict, data: dict | None = None) -> Path:
        d = json.loads(json.dumps(data if data is not None else base))
        for k, v in changes.items():
            set_path(d, k, v)
        p = tmp / f"engine_{name}.toml"
        p.write_text(to_toml(d), encoding="utf-8")
        return p

    def names(key: str):
        return lambda r: None if key in " ".join(r.output.split()) else f"does not name {key}"

    def refused(name: str, changes: dict, key: str, command: str = "engine") -> None:
        p = write(name, changes)
        cli(g, [command, str(p), "-o", str(tmp / f"out_{name}"), "-j", "1"], check=names(key))

    exhaust = {"centre_angle_deg": 250.0}
    for i, key in enumerate(['"engine".speed_rpm', " engine.speed_rpm", '"numerics".n']):
        value = 256 if key.endswith(".n") else 6000.0
        changes = {"engine.exhaust": {**exhaust, "changes": {key: value}}}
        refused(f"shared{i}", changes, "engine.exhaust.changes")
    rename = {"engine.exhaust": {**exhaust, "changes": {"surface_sets[0].name": "other"}}}
    refused("rename", rename, "engine.exhaust.changes")
    refused("displacement", {"engine.displacement": 5e-324}, "engine.displacement")
    refused("bore", {"engine.auxiliary": {"bore_diameter": 1e-6}}, "engine.auxiliary.bore_diameter")
    single = paper.updated(one_set).to_dict(resolve_paths=True)
    p = write("offset", {"tappet_rotation": {"speed_ratio": 0.05, "cam_offset": 0.049}}, single)
    cli(
        g, ["run", str(p), "-o", str(tmp / "out_offset")], check=names("tappet_rotation.cam_offset")
    )

    # a lobe's own cam table: copied into inputs/, the written case names the copy (one
    # engine computation, also checked for strict JSON and the engine's speed)
    src = tmp / "table_case"
    (src / "tables").mkdir(parents=True, exist_ok=True)
    for n in ("cam1.csv", "cam2.csv"):
        shutil.copy(CASES_DIR / "example_cam_lift.csv", src / "tables" / n)
    table = load_case("example_table_cam")
    data = table.updated({**quick, "surface_sets": table.to_dict()["surface_sets"][:1], **engine})
    d = data.to_dict()
    d["cam"]["path"] = "tables/cam1.csv"
    d["engine"]["exhaust"]["changes"] = {"cam.path": "tables/cam2.csv"}
    (src / "engine.toml").write_text(to_toml(d), encoding="utf-8")
    out = tmp / "out_table"

    def table_copied(r):
        from tribodyn.config import Case

        def refuse(token):
            raise ValueError(f"non-standard JSON token {token}")

        summ = json.loads((out / "summary.json").read_text(), parse_constant=refuse)
        if summ["engine"]["speed_rpm"] != 3000.0:
            return "summary speed is not the case's"
        moved = tmp / "out_table_moved"
        shutil.move(out, moved)
        shutil.rmtree(src)  # the original tables are gone
        try:
            lobe = Case.from_toml(moved / "case.toml").engine_lobe_case("exhaust")
        except InputError as exc:
            return f"the moved result folder does not run: {exc}"[:250]
        if lobe.cam_table_path != moved / "inputs" / "cam2.csv":
            return f"the exhaust lobe reads {lobe.cam_table_path}, not its copy in inputs/"
        return None

    cli(g, ["engine", str(src / "engine.toml"), "-o", str(out), "-j", "1"], (0,), table_copied)

    # weak springs: thrown off the cam (1 N, 1 N/m) and a realistic one too weak for 5000 rpm
    for name, changes in (
        ("thrown", {"valvetrain.spring_preload": 1.0, "valvetrain.spring_rate": 1.0}),
        (
            "weak5000",
            {
                "valvetrain.spring_preload": 100.0,
                "valvetrain.spring_rate": 1e4,
                "engine.speed_rpm": 5000.0,
            },
        ),
    ):
        p = write(f"spring_{name}", changes, single)
        o = tmp / f"out_spring_{name}"

        def reports_jump(r, o=o):
            j = json.loads((o / "summary.json").read_text()).get("valve_jump") or {}
            text = (o / "report.md").read_text(encoding="utf-8")
            ok = j.get("jump") and (j.get("max_separation_m") or 0) > 0
            if not ok or "## Valve jump (contact loss)" not in text:
                return "the jump is not reported (valve_jump in summary.json, report.md)"
            return None

        cli(
            g,
            ["run", str(p), "-o", str(o), "-j", "1", "-q", "--no-compare-paper"],
            (0,),
            reports_jump,
            seconds=STUDY_LIMIT_S,
        )

    # the stress API: physical ranges and size guards (before allocating)
    x = np.linspace(-1e-3, 1e-3, 201)
    p0 = np.maximum(1e9 * (1.0 - (x / 5e-4) ** 2), 0.0)
    coated = Body(STEEL, Coating(175e9, 0.3, 4e-6))
    for case, call, name in (
        ("p = 1e300", lambda: subsurface_stress(x, p0 * 1e291, 0 * x, PAIR[0], [1e-4]), "pressure"),
        ("z = 1e300", lambda: subsurface_stress(x, p0, 0 * x, PAIR[0], [1e300]), "depths"),
        (
            "x spacing 1e-15, coated",
            lambda: subsurface_stress(x * 1e-10, p0, 0 * x, coated, [1e-6]),
            "spacing of x",
        ),
        ("1e6 nodes", lambda: StressOperator(10**6, 1e-6, PAIR[0], [1e-6]), "nodes of x"),
        (
            "1e5 depths",
            lambda: StressOperator(201, 1e-5, PAIR[0], np.linspace(0, 1e-3, 10**5)),
            "len(depths)",
        ),
    ):
        expect_input_error(g, f"subsurface stress {case}", call, name)

    def accepted(case: str, call) -> None:
        try:
            with time_limit():
                ok = call()
        except Hang:
            record(g, "hang", case)
        except InputError as exc:
            record(g, "garbage", f"{case}: refused: {exc}"[:250])
        except Exception as exc:
            record(g, "traceback", f"{case} -> {type(exc).__name__}: {exc}"[:300])
        else:
            record(g, "handled" if ok else "garbage", case)

    x32 = x.astype(np.float32)
    accepted(
        "float32 linspace x",
        lambda: np.isfinite(
            subsurface_stress(x32, p0, 0 * x, PAIR[0], [1e-4]).max_von_mises_substrate.value
        ),
    )
    accepted("0-d array E, nu", lambda: Material(np.array(210e9), np.array(0.3)).E == 210e9)
    for case, form in (
        ("array values", "values = [[1000.0, 2000.0]]"),
        ("array start", "start = [1000.0]\nstop = 2000.0\nnum = 3"),
    ):
        text = f'[[axes]]\npath = "engine.speed_rpm"\n{form}\n'
        expect_input_error(
            g,
            f"sweep axis {case}",
            lambda t=text: SweepSpec.from_toml_string(t),
            "axis engine.speed_rpm",
        )


def fuzz_result_files(tmp: Path) -> None:
    """Files tribodyn did not write: links planted in a result folder, a figure that
    links to a private file, modes and groups on a re-run, another command's folder, stale-
    looking folders of someone else's, ``-o`` a link, ``--resume`` with another sweep, a
    report.md in Latin-1, a folder that cannot be written, a foreign netCDF, deep nesting,
    a folder named like the marker. Runs use a stand-in study (the real writer, no
    computation, no figures)."""
    import base64
    import subprocess
    from types import SimpleNamespace

    import xarray as xr

    import tribodyn.output.report as report
    import tribodyn.output.writer as writer
    import tribodyn.workflow.cycle as cycle
    import tribodyn.workflow.sweep as sweep
    from tribodyn._safe_write import make_dirs, remove_tree

    g = "result files"
    base = tmp / "result-files"
    base.mkdir()
    calls: list = []
    summary = {"surface_sets": {}, "implicit_vs_explicit": {}, "warnings": [], "runtime_s": 0}
    small = xr.Dataset({"central_film": ("crank", [1e-7, 2e-7])}, coords={"crank": [0.0, 1.0]})

    def study(case, **kw):
        calls.append(case)
        return SimpleNamespace(case=case, analyse=lambda: SimpleNamespace(summary=summary))

    def no_sweep(*a, **k):
        calls.append("sweep")
        raise SystemExit(0)

    saved = (cycle.run_cycle_study, writer.study_to_dataset, report.write_report, sweep.run_sweep)
    saved_tempdir = tempfile.tempdir
    tempfile.tempdir = str(base)  # a rescue folder, if any, stays in here
    cycle.run_cycle_study = study
    writer.study_to_dataset = lambda s: small
    report.write_report = lambda s, ds, figs, path: Path(path).write_text("report")
    sweep.run_sweep = no_sweep

    def run(out, expect=(0,), check=None):
        cli(g, ["run", "-o", str(out), "-q"], expect=expect, check=check)

    def not_started(n):
        return lambda r: None if len(calls) == n else "computed before refusing"

    def dead_pid() -> int:
        p = subprocess.Popen([sys.executable, "-c", "pass"])
        p.wait()
        return p.pid

    def results(folder: Path) -> Path:  # a cycle study's results.nc, report, figure
        folder.mkdir()
        xr.Dataset(
            {"central_film": (("surface_set", "ehl_crank"), [[1e-7, 2e-7]])},
            coords={"ehl_crank": [0.0, 1.0], "crank_angle": [0.0, 1.0], "surface_set": ["a"]},
        ).to_netcdf(folder / "results.nc", engine="h5netcdf")
        (folder / "report.md").write_text("# r\n\n![f](fig05_dry_pressure.png)\n")
        (folder / "fig05_dry_pressure.png").write_bytes(b"\x89PNG")
        own = {f.name: writer._sha256(f) for f in folder.iterdir()}
        writer.mark_folder(folder, own, {"kind": "run"})
        return folder

    try:
        # export through planted links; a user's file under the old fixed temporary name
        res = results(base / "shared")
        victim = base / "victim.txt"
        victim.write_bytes(b"precious")
        KEEP[victim] = b"precious"
        (res / "traces.csv.tmp").symlink_to("../victim.txt")
        (res / "report.html.tmp").write_bytes(b"mine")
        KEEP[res / "report.html.tmp"] = b"mine"
        cli(g, ["export", str(res)], expect=(0,))
        # a figure replaced by a link to a private file
        secret = base / "secret.png"
        secret.write_bytes(b"private " * 16)
        (res / "fig05_dry_pressure.png").unlink()
        (res / "fig05_dry_pressure.png").symlink_to(secret)

        def no_secret(r):
            page = (res / "report.html").read_text()
            leaked = base64.b64encode(secret.read_bytes()).decode()[:40] in page
            return "a private file embedded in report.html" if leaked else None

        cli(g, ["export", str(res)], expect=(0,), check=no_secret)
        # a report.md in Latin-1, a folder that cannot be written, a foreign netCDF
        (res / "report.md").write_bytes("# Bericht\n\nÖl\n".encode("latin-1"))
        cli(g, ["export", str(res)], expect=(0, 2))
        cli(g, ["export", str(res), "-o", "/proc/tribodyn-export"], expect=(1, 2))
        foreign = base / "foreign"
        foreign.mkdir()
        xr.Dataset(coords={"ehl_crank": [0.0], "crank_angle": [0.0]}).to_netcdf(
            foreign / "results.nc", engine="h5netcdf"
        )
        cli(g, ["export", str(foreign)])

        # a re-run keeps the modes and group of the folder and of the user's folders
        out = base / "res"
        run(out)
        (out / "private").mkdir()
        (out / "private" / "notes.txt").write_bytes(b"mine")
        KEEP[out / "private" / "notes.txt"] = b"mine"
        os.chmod(out / "private", 0o700)
        gid = os.getegid() if os.geteuid() != 0 else 4242
        os.chown(out, -1, gid)
        os.chmod(out, 0o2770)

        def modes_kept(r):
            m, p = os.stat(out), os.stat(out / "private")
            if (m.st_mode & 0o7777, m.st_gid, p.st_mode & 0o7777) != (0o2770, gid, 0o700):
                return (
                    f"modes not kept: folder {m.st_mode & 0o7777:o} group {m.st_gid}, "
                    f"private/ {p.st_mode & 0o7777:o}"
                )
            return None

        run(out, check=modes_kept)
        # another command's folder: run -o a sweep's; a sweep into a run's
        sw = base / "sw"
        (sw / "points").mkdir(parents=True)
        (sw / "points" / "0a1b.nc").write_bytes(b"point")
        (sw / "sweep.nc").write_bytes(b"sweep")
        KEEP[sw / "points" / "0a1b.nc"] = b"point"
        KEEP[sw / "sweep.nc"] = b"sweep"
        writer.mark_folder(sw, {"sweep.nc": writer._sha256(sw / "sweep.nc")}, {"kind": "sweep"})
        run(sw, expect=(2,), check=not_started(len(calls)))
        cli(g, ["sweep", "andreou2023_dynamics", "-o", str(out), "-q"])
        # --resume with another sweep file
        for p in [p for p in KEEP if sw in p.parents]:
            KEEP.pop(p)
        remove_tree(sw, ignore_errors=True)
        (sw / "points").mkdir(parents=True)
        (sw / "sweep.nc").write_bytes(b"sweep")
        KEEP[sw / "sweep.nc"] = b"sweep"
        info = {"kind": "sweep", "sweep": "andreou2023_speed", "sweep_mode": "study"}
        writer.mark_folder(sw, {"sweep.nc": writer._sha256(sw / "sweep.nc")}, info)
        cli(g, ["sweep", "andreou2023_dynamics", "-o", str(sw), "--resume", "-q"])
        # folders of someone else's named like stale temporaries
        mine = base / f".res.tmp-{dead_pid()}-mine"
        backup = base / ".res.tmp-backup"
        for d in (mine, backup):
            d.mkdir()
            (d / "data.txt").write_bytes(b"mine")
            KEEP[d / "data.txt"] = b"mine"
        hour_ago = time.time() - 7200
        os.utime(backup, (hour_ago, hour_ago))
        run(out)
        # -o a link to a result folder: the link stays, its folder gets the results
        link = base / "link"
        link.symlink_to(out)

        def link_kept(r):
            if not link.is_symlink():
                return "the link was replaced by a folder"
            left = [p.name for p in base.iterdir() if p.name.startswith(".link.")]
            return f"left {left}" if left else None

        run(link, check=link_kept)
        # a folder named like the marker; a home folder with a stray marker
        legacy = base / "legacy"
        legacy.mkdir()
        for f in ("results.nc", "summary.json", "case.toml"):
            (legacy / f).write_text("x")
        (legacy / ".tribodyn-results").mkdir()
        (legacy / ".tribodyn-results" / "mine.txt").write_bytes(b"mine")
        KEEP[legacy / ".tribodyn-results" / "mine.txt"] = b"mine"
        run(legacy, expect=(2,), check=not_started(len(calls)))
        home = base / "home"
        run(home)
        (home / ".bashrc").write_bytes(b"mine")
        KEEP[home / ".bashrc"] = b"mine"
        old_home = os.environ.get("HOME")
        os.environ["HOME"] = str(home)
        try:
            run(home, expect=(2,))
        finally:
            if old_home is None:
                os.environ.pop("HOME", None)
            else:
                os.environ["HOME"] = old_home
        # a user's folder nested 1100 levels deep in a result folder
        deep = out / Path(*["d"] * 1100)
        make_dirs(deep)
        (deep / "note.txt").write_bytes(b"deep")
        KEEP[deep / "note.txt"] = b"deep"
        run(out, expect=(0, 2))
    finally:
        cycle.run_cycle_study, writer.study_to_dataset, report.write_report = saved[:3]
        sweep.run_sweep = saved[3]
        tempfile.tempdir = saved_tempdir
        for p in list(KEEP):
            if base in p.parents:
                KEEP.pop(p)
        remove_tree(base, ignore_errors=True)  # any depth (shutil.rmtree recurses)


def main() -> None:
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        sink = io.StringIO()
        with contextlib.redirect_stderr(sink):
            fuzz_constructors()
            fuzz_solver_arguments()
            fuzz_extreme_solves()
            fuzz_contact_cli()
            fuzz_topography_cli(tmp)
            fuzz_run_cli(tmp)
            fuzz_extreme_kinds(tmp)
            fuzz_user_files(tmp)
            fuzz_engine_inputs(tmp)
            fuzz_result_files(tmp)
    total = sum(results.values())
    print(
        json.dumps(
            {
                "benchmark": "fuzz_inputs",
                "tribodyn": tribodyn.__version__,
                "inputs": total,
                **results,
                "groups": groups,
                "examples": examples,
                "runtime_s": round(time.perf_counter() - t0, 1),
            },
            indent=2,
            ensure_ascii=False,
        )
    )


if __name__ == "__main__":
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    sys.exit(main())
