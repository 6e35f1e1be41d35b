"""The output package only reads results: no module under ``tribodyn/output`` builds or
loads a case, calls a case's builders, imports a solver or a physical law (of
``tribodyn.physics`` it may read constants, UPPER_CASE names, such as the spread of an
assumed wear coefficient). What a figure or the report needs is computed in the study
and stored in the results (checked on the source with ``ast``, so that a new violation
fails here and not only in review)."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import tribodyn
from conftest import case_builders

CASE_BUILDERS = case_builders()  # the case's constructors

OUTPUT = Path(tribodyn.__file__).parent / "output"

#: calls that build or load a case
CASE_LOADERS = frozenset({"load_case", "Case"})
CASE_CONSTRUCTORS = frozenset({"from_dict", "from_toml_string", "from_toml"})
#: modules whose import means solving or building: a module named here or inside it
SOLVER_MODULES = (
    "tribodyn.contact",
    "tribodyn.valvetrain.dynamics",
    "tribodyn.physics.stress",
    "tribodyn.physics.hertz",
    "tribodyn.topography.load_separation",
    "tribodyn.topography.analysis",
    "tribodyn.topography.composite",
    "tribodyn.config.build",
    "tribodyn.cycle",
    "tribodyn.workflow.stress_map",
    # the laws the figures draw: their maps and curves are computed with the results
    "tribodyn.physics.regimes",
    "tribodyn.topography.height_statistics",
)
#: physics, of which output may read constants (UPPER_CASE names) but call no law
PHYSICS = "tribodyn.physics"
#: functions that compute a study's results, wherever they are imported from
SOLVER_FUNCTIONS = frozenset(
    {
        "run_cycle_study",
        "stress_for_set",
        "stress_along_cycle",
        "stress_map",
        "plausibility_warnings",
        "engineering_outputs",
        "synthetic_load_separation",
        "subsurface_stress",
        "dry_coating_study",
        "ehl_coating_study",
        "dry_hertz_reference",
        "hertz_line_contact",
    }
)
SOLVER_PREFIXES = ("solve_", "simulate_")


def _absolute(module: str | None, level: int, package: str) -> str:
    """The absolute name of a (relative) import in ``package``."""
    if level == 0:
        return module or ""
    parts = package.split(".")[: len(package.split(".")) - level + 1]
    return ".".join(parts + ([module] if module else []))


def _in(module: str, prefixes) -> bool:
    return any(module == p or module.startswith(p + ".") for p in prefixes)


def _solver_name(name: str) -> bool:
    return name in SOLVER_FUNCTIONS or name.startswith(SOLVER_PREFIXES)


def _holds_case(node: ast.expr) -> bool:
    """``case``, ``study.case``, ``self.base_case``, …: an expression naming a case."""
    name = node.id if isinstance(node, ast.Name) else getattr(node, "attr", "")
    return "case" in name.lower()


def violations(path: Path, package: str) -> list[str]:
    """Every line of module ``path`` (in ``package``) that builds, loads or solves."""
    tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
    config_names: set[str] = set()  # names imported from tribodyn.config (its build)
    out = []

    def bad(node, what):
        out.append(f"{path.name}:{node.lineno}: {what}")

    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            mod = _absolute(node.module, node.level, package)
            for a in node.names:
                full = f"{mod}.{a.name}"
                if _in(mod, SOLVER_MODULES) or _in(full, SOLVER_MODULES):
                    bad(node, f"imports {full}")
                elif _solver_name(a.name):
                    bad(node, f"imports the solver {full}")
                elif _in(mod, (PHYSICS,)) and not a.name.isupper():
                    bad(node, f"imports the physics {full}")
                if _in(mod, ("tribodyn.config",)):
                    config_names.add(a.asname or a.name)
        elif isinstance(node, ast.Import):
            for a in node.names:
                if _in(a.name, (*SOLVER_MODULES, PHYSICS)):
                    bad(node, f"imports {a.name}")
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        f = node.func
        if isinstance(f, ast.Name):
            if f.id in CASE_LOADERS or (f.id == "build" and f.id in config_names):
                bad(node, f"calls {f.id}()")
            elif _solver_name(f.id):
                bad(node, f"calls the solver {f.id}()")
        elif isinstance(f, ast.Attribute):
            if f.attr in CASE_BUILDERS and _holds_case(f.value):
                bad(node, f"calls the case builder .{f.attr}()")
            elif f.attr in CASE_CONSTRUCTORS and _holds_case(f.value):
                bad(node, f"builds a case: .{f.attr}()")
            elif f.attr == "build" and isinstance(f.value, ast.Name) and "build" in f.value.id:
                bad(node, "calls config.build.build()")
            elif _solver_name(f.attr):
                bad(node, f"calls the solver .{f.attr}()")
    return out


def all_violations(root: Path = OUTPUT) -> list[str]:
    """:func:`violations` of every module under ``root`` (the package tribodyn.output)."""
    found = []
    for path in sorted(root.rglob("*.py")):
        rel = path.relative_to(root.parent).with_suffix("")
        package = "tribodyn." + ".".join(rel.parts[:-1])  # an __init__'s is its own
        found += [f"{rel.parent}/{v}" for v in violations(path, package)]
    return found


def test_output_modules_only_read_results():
    found = all_violations()
    assert not found, "output/ must only read stored results:\n" + "\n".join(found)


def test_the_check_finds_each_kind_of_violation(tmp_path):
    src = tmp_path / "m.py"
    src.write_text(
        "from ..contact.stress import profile_surface_loads\n"
        "from ..config.build import build\n"
        "from ..workflow.engineering import plausibility_warnings\n"
        "import tribodyn.valvetrain.dynamics\n"
        "from ..physics.regimes import REGIMES, lubrication_regime\n"
        "from ..topography.height_statistics import gaussian_pdf\n"
        "from ..physics.materials import reduced_modulus\n"
        "from ..physics import friction\n"
        "from ..physics.strength import WEAR_COEFFICIENT_SPREAD\n"  # a constant: fine
        "from ..topography.results import PairAnalysis\n"  # a result type: fine
        "def f(study, ds):\n"
        "    study.case._new_lubricant()\n"
        "    case._build_set(cfg)\n"
        "    Case.from_dict({})\n"
        "    load_case()\n"
        "    build(study.case)\n"
        "    solve_transient(ds)\n"
        "    ds.attrs.get('case_toml')\n"  # reading: fine
        "    study.labels.get('a')\n",
        encoding="utf-8",
    )
    found = violations(src, "tribodyn.output")
    assert len(found) == 15, found


def test_the_inputs_as_used_are_the_case_files_numbers():
    """What the report reads instead of building the case: the case file's numbers."""
    import math
    import tomllib

    from tribodyn.config import load_case
    from tribodyn.config.build import build
    from tribodyn.config.case import bundled_cases
    from tribodyn.workflow.inputs_as_used import inputs_as_used

    raw = tomllib.loads(bundled_cases()["andreou2023"].read_text(encoding="utf-8"))
    used = inputs_as_used(build(load_case()))
    assert used.cam_base_radius == raw["cam"]["base_radius"]
    assert used.thermal_oil is None  # an isothermal case
    assert list(used.surfaces) == [s["name"] for s in raw["surface_sets"]]
    for s in raw["surface_sets"]:
        u, r = used.surfaces[s["name"]], s["roughness"]
        ebs = r["asperity_density"] * r["summit_radius"] * r["rms"]
        assert u["rms_m"] == r["rms"] and u["greenwood_tripp"]
        assert u["roughness_parameter"] == pytest.approx(ebs, rel=1e-12)
        assert u["roughness_factor"] == pytest.approx(
            ebs**2 * math.sqrt(r["rms"] / r["summit_radius"]), rel=1e-12
        )
        assert u["coating_thickness_m"] == s.get("coating_thickness")
        assert u["coating_material"] == s.get("coating")
