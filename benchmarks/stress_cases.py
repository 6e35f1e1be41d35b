"""Coating integrity of the paper's case and of an own high-load case (prints the report
section and writes the stress maps). Not a timed test.

    python benchmarks/stress_cases.py [OUT_DIR]

Runs the cycle study of ``andreou2023`` and of ``benchmarks/stress_high_load.toml``
(sharper nose, stiffer spring, hot thin oil, rougher pair, 4500 rpm, with DLC 2 µm),
without the implicit coupling (the stresses use the explicit dynamics' EHL pass), and
prints for each the closest failure mode per surface set, where, when and its margin.
"""

import json
import sys
from pathlib import Path

import tribodyn  # noqa: F401  (one BLAS thread, before numpy loads)
from tribodyn.config import load_case
from tribodyn.output.dataset import study_to_dataset
from tribodyn.output.figures.stress import stress_maps
from tribodyn.output.report_stress import stress_section
from tribodyn.workflow.cycle import run_cycle_study

HERE = Path(__file__).resolve().parent


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("stress_cases_out")
    out.mkdir(parents=True, exist_ok=True)
    for path in (None, HERE / "stress_high_load.toml"):
        case = load_case(path).updated({"numerics.implicit_coupling": False})
        study = run_cycle_study(case, workers=2)
        summ = study.analyse().summary
        print(f"# {case.name}\n")
        print("\n".join(stress_section(summ)))
        rows = {
            n: {
                k: e.get(k)
                for k in (
                    "stress_closest_failure",
                    "min_safety_factor",
                    "safety_factors",
                    "asperity_scale_estimate",
                )
            }
            for n, e in summ["surface_sets"].items()
        }
        (out / f"{case.name}_stress.json").write_text(json.dumps(rows, indent=2))
        png = stress_maps(study_to_dataset(study), out / f"{case.name}_stress_map.png")
        print(f"stress map: {png}\n")


if __name__ == "__main__":
    main()
