"""The do-nothing check: run the solver tests with each solver's iteration replaced by one
that returns its starting state as converged (see tests/do_nothing.py), and list the tests
that call that solver and still pass. A good suite lists none.

    python tests/check_do_nothing.py              # all solvers
    python tests/check_do_nothing.py ehl          # one of them

Prints one JSON object: per solver, the tests run, the tests that used the solver, and the
names of those that still passed. Exit status 1 if any did.
"""

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
#: the test files of each solver
FILES = {
    "dry": ["test_dry_contact.py"],
    "ehl": [
        "test_ehl_formulas.py",
        "test_ehl_hydrodynamic.py",
        "test_ehl_mixed_coated.py",
        "test_ehl_transient.py",
        "test_ehl_errors.py",
        "test_ehl_references.py",
    ],
    "dynamics": ["test_valvetrain_dynamics.py", "test_valvetrain_compiled.py"],
    "thermal": ["test_thermal_ehl.py"],
    "coupling": ["test_coupling.py", "test_coupling_metric.py", "test_coupling_offlobe.py"],
}


#: Tests that call the solver but check what happens around it, not its answer; they pass
#: with a do-nothing solver by design and are listed separately, with the reason.
EXEMPT = {
    "tests/test_valvetrain_dynamics.py::test_solver_failure_is_reported_not_hidden": (
        "a film law that raises must be reported as a failed run: the error comes from the "
        "film law, whatever the integrator does"
    ),
    **{
        f"tests/test_ehl_errors.py::test_corners_of_the_allowed_range_end_honestly[{case}]": (
            "at the corners of the allowed ranges an honest 'not converged' with a message is an "
            "accepted answer: the test checks that the solver never returns a converged garbage "
            "film there, which a do-nothing solver does not do either"
        )
        for case in ("0.001-1000000.0-5e-324", "1000000000.0-1e-06-1000.0")
    },
    "tests/test_thermal_ehl.py::test_isothermal_limit_reproduces_the_isothermal_solver": (
        "the isothermal limit (no heating, or near-infinite conductivities) is the answer "
        "of an energy solve that leaves the inlet temperature unchanged; the heating is "
        "checked by the other thermal tests"
    ),
    "tests/test_ehl_transient.py::test_warmup_compiles_the_fallback_variants": (
        "checks that the warm-up compiles every argument type of the kernels that a march "
        "reaches, not the march's answer; the films are checked by the other transient tests"
    ),
    **{
        "tests/test_ehl_transient.py::test_compiled_evaluation_equals_the_lubricants_methods"
        f"[{asperities}-{oil}]": (
            "compares two evaluations of the residual at the same iterate (compiled and "
            "through the lubricant's methods), whichever iterate the solver returns"
        )
        for asperities in ("greenwood_tripp", "law", "smooth")
        for oil in ("roelands", "barus", "incompressible")
    },
    "tests/test_coupling.py::test_a_coupling_started_at_its_fixed_point_stays_there": (
        "a coupling restarted at its own fixed point must stop at once, which a coupling "
        "that does nothing also does; the other coupling tests check that it moves"
    ),
}


def check(solver: str) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        report = Path(tmp) / "report.jsonl"
        env = dict(
            os.environ,
            TRIBODYN_DO_NOTHING=solver,
            TRIBODYN_DO_NOTHING_REPORT=str(report),
            PYTHONPATH=os.pathsep.join([str(HERE), os.environ.get("PYTHONPATH", "")]),
        )
        cmd = [
            sys.executable,
            "-m",
            "pytest",
            "-q",
            "-p",
            "do_nothing",
            "-p",
            "no:cacheprovider",
            "--timeout=600",
            *(str(HERE / f) for f in FILES[solver]),
        ]
        subprocess.run(cmd, cwd=HERE.parent, env=env, capture_output=True, text=True)
        rows = (
            [json.loads(line) for line in report.read_text().splitlines()]
            if report.exists()
            else []
        )
    used = [r for r in rows if r["solver_called"]]
    return {
        "tests": len(rows),
        "using_the_solver": len(used),
        "still_pass": sorted(r["test"] for r in used if r["passed"] and r["test"] not in EXEMPT),
        "exempt": {r["test"]: EXEMPT[r["test"]] for r in used if r["test"] in EXEMPT},
    }


def main(argv):
    solvers = argv or list(FILES)
    out = {s: check(s) for s in solvers}
    print(json.dumps(out, indent=2))
    return 1 if any(v["still_pass"] for v in out.values()) else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
