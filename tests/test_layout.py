"""Design checks of the package layout: the paper's numbers live in one module and only
its comparison add-on uses it, and the layers import only downwards (physics →
contact/valvetrain/topography → config → cycle → workflow → output → cli)."""

import ast
import inspect
from pathlib import Path

import pytest

from conftest import case_builders
from tribodyn import paper

SRC = Path(__file__).resolve().parents[1] / "src" / "tribodyn"

#: Numbers that are the paper's (Tables 4–7, Figs. 5/6): they must appear as literals only
#: in tribodyn/paper.py (docstrings and comments may quote them).
PAPER_NUMBERS = {
    paper.STEEL["boundary_shear_coefficient"],
    paper.DLC["boundary_shear_coefficient"],
    paper.WCC["boundary_shear_coefficient"],
    paper.CAM_WIDTH,
    paper.STEEL["E"],
    paper.DLC["E"],
    paper.WCC["E"],
    paper.LUBRICANT["viscosity"],
    paper.LUBRICANT["pressure_viscosity"],
    paper.FIG5["load_total"],
    paper.FIG5["entrainment_speed"],
    paper.SPRING_RATE,
    paper.SPRING_MASS,
    paper.VALVE_MASS,
    paper.LUBRICANT["eyring_stress"],
    paper.CAM_MAX_LIFT,
    *(v for r in paper.ROUGHNESS.values() for v in r.values()),
}


#: Coincidences: the same number with another meaning (file, value): reason.
COINCIDENCES = {
    ("physics/regimes.py", 0.54): "exponent of G in Dowson & Higginson's film formula",
    ("output/figures/cycle.py", 0.012): "share of the axis width within which labels merge",
    ("physics/typical_engine.py", 210e9): "the typical modulus of steel, with its source",
    ("physics/typical.py", 2e6): "low end of the typical range of the Eyring stress",
    ("physics/typical.py", 0.07): "typical boundary friction coefficients",
}


def _modules():
    return sorted(p for p in SRC.rglob("*.py"))


def _numeric_literals(tree):
    for node in ast.walk(tree):
        if (
            isinstance(node, ast.Constant)
            and isinstance(node.value, (int, float))
            and not isinstance(node.value, bool)
        ):
            yield node


def test_paper_numbers_are_defined_once():
    """The literals 0.185, 0.012, 210e9, … occur in code only in paper.py."""
    found = []
    for path in _modules():
        if path.name == "paper.py" and path.parent == SRC:
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in _numeric_literals(tree):
            rel = str(path.relative_to(SRC))
            if float(node.value) in PAPER_NUMBERS and (rel, node.value) not in COINCIDENCES:
                found.append(f"{path.relative_to(SRC)}:{node.lineno}: {node.value!r}")
    assert not found, "paper numbers outside paper.py:\n" + "\n".join(found)


def test_the_check_sees_a_literal(tmp_path):
    """The scan above is able to fail: it finds 0.185 in a code line."""
    tree = ast.parse("x = 0.185  # ς of steel\n")
    assert [n.value for n in _numeric_literals(tree)] == [0.185]


#: The modules that may import tribodyn.paper: the paper's comparison add-on, with why.
#: Everything else (physics, valvetrain, EHL and case-file defaults) takes typical values
#: of tribodyn.physics.typical or requires the input; the paper's own values are stated
#: in its bundled case files (cases/andreou2023*.toml).
PAPER_USERS = {
    "paper.py": "the paper's numbers themselves",
    "output/report_claims.py": "the claims table: the paper's headline claims",
    "workflow/coating_study.py": "the coating study at the conditions of Figs. 5 and 6",
    "output/figures/coating.py": "Figs. 5 and 6 (conditions of a run without the study)",
    "cli/contact.py": "single contacts at the paper's case and Figs. 5/6 conditions",
    "workflow/postprocess.py": "the claims: the 41 % film gain and the coatings compared",
}


def _paper_imports(path: Path, text: str | None = None) -> list[int]:
    """Lines of ``path`` (or of ``text`` placed there) that import tribodyn.paper."""
    return [
        ln
        for mod, ln in _imports(path, text)
        if mod == "tribodyn.paper" or mod.startswith("tribodyn.paper.")
    ]


def test_only_the_comparison_add_on_imports_the_paper():
    """No physics, valvetrain, EHL, case-file or output default comes from the paper."""
    found = []
    for path in _modules():
        rel = path.relative_to(SRC).as_posix()
        if rel not in PAPER_USERS and (lines := _paper_imports(path)):
            found.append(f"{rel}: line {', '.join(map(str, lines))}")
    assert not found, "modules outside the comparison add-on import the paper:\n" + "\n".join(found)


def test_the_paper_import_check_sees_each_form():
    """The scan above is able to fail: it finds relative, absolute and member imports."""
    probe = SRC / "config" / "probe.py"  # not written: the text is parsed as if there
    for text in (
        "from .. import paper\n",
        "from ..paper import STEEL\n",
        "import tribodyn.paper\n",
    ):
        assert _paper_imports(probe, text) == [1], text
    assert _paper_imports(probe, "from ..physics import typical\n") == []


#: Layer of each top-level part; a module may import only from its own layer or below.
LAYERS = {
    "paper": 0,
    "_validation": 0,
    "_version": 0,
    "_typing": 0,
    "_system": 0,
    "_threads": 0,
    "_user_files": 0,
    "_json": 0,
    "_safe_write": 0,
    "physics": 1,
    "contact": 2,
    "valvetrain": 2,
    "topography": 2,
    "config": 3,
    "cycle": 4,
    "workflow": 5,
    "output": 6,
    "cli": 7,
    "__init__": 7,
    "__main__": 8,
}


def _part(module: str) -> str:
    return module.split(".")[1] if module.count(".") >= 1 else "__init__"


def _imports(path: Path, text: str | None = None):
    """(module, line) of each tribodyn import of ``path`` (or of ``text`` placed there)."""
    rel = path.relative_to(SRC.parent).with_suffix("")
    pkg = list(rel.parts[:-1]) if path.name != "__init__.py" else list(rel.parts[:-1])
    tree = ast.parse(path.read_text(encoding="utf-8") if text is None else text)
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = pkg[: len(pkg) - node.level + 1]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module or ""
            if mod.startswith("tribodyn"):
                names = [mod] if node.module else [f"{mod}.{a.name}" for a in node.names]
                yield from ((n, node.lineno) for n in names)
        elif isinstance(node, ast.Import):
            for a in node.names:
                if a.name.startswith("tribodyn"):
                    yield a.name, node.lineno


@pytest.mark.parametrize("path", _modules(), ids=lambda p: str(p.relative_to(SRC)))
def test_imports_only_downwards(path):
    rel = ".".join(path.relative_to(SRC.parent).with_suffix("").parts)
    own = LAYERS[_part(rel)] if path.parent != SRC else LAYERS.get(path.stem, LAYERS["cli"])
    bad = [
        f"line {ln}: {mod}"
        for mod, ln in _imports(path)
        if mod.count(".") >= 1 and LAYERS.get(_part(mod), 0) > own
    ]
    assert not bad, f"{rel} imports upwards: {bad}"


def test_the_layer_check_sees_an_import():
    """config/case.py imports the EHL options (downwards); the check finds that import."""
    mods = {m for m, _ in _imports(SRC / "config" / "case.py")}
    assert any(m.startswith("tribodyn.contact.ehl") for m in mods)


#: The layers above the cycle machinery (tribodyn.cycle): the studies and what shows them.
ABOVE_CYCLE = ("workflow", "output", "cli")


def _study_imports(path: Path, text: str | None = None) -> list[str]:
    """``line: module`` of each import of ``path`` (or of ``text`` placed there) from a
    layer above the cycle machinery, at module level or inside a function."""
    hits = sorted((ln, mod) for mod, ln in _imports(path, text) if _part(mod) in ABOVE_CYCLE)
    return [f"{ln}: {mod}" for ln, mod in hits]


def test_the_cycle_machinery_imports_no_study():
    """tribodyn.cycle (the EHL pass along the cycle, its methods, the coupling, the task
    runner) sits below the studies: none of its modules imports workflow, output or cli,
    not even inside a function."""
    paths = sorted((SRC / "cycle").glob("*.py"))
    assert len(paths) >= 7
    found = [f"{p.name}:{hit}" for p in paths for hit in _study_imports(p)]
    assert not found, "tribodyn.cycle imports a study layer:\n" + "\n".join(found)


def test_the_cycle_check_sees_a_study_import():
    """The scan above is able to fail: it finds a function-level relative import of a
    study and an absolute one of the output, not one of config."""
    probe = SRC / "cycle" / "probe.py"  # not written: the text is parsed as if there
    text = (
        "from ..config.build import as_built\n"
        "def f():\n"
        "    from ..workflow.postprocess import analyse\n"
        "import tribodyn.output.dataset\n"
    )
    assert _study_imports(probe, text) == [
        "3: tribodyn.workflow.postprocess",
        "4: tribodyn.output.dataset",
    ]


def _import_circle(graph: dict[str, set[str]]) -> list[str]:
    """A circle of ``graph`` (module → modules it imports) as [a, b, …, a], or []."""
    state: dict[str, int] = {}  # 1: on the current path, 2: done

    def visit(m: str, path: list[str]) -> list[str]:
        state[m] = 1
        for n in sorted(graph.get(m, ())):
            if state.get(n) == 1:
                return [*path[path.index(n) :], n]
            if n not in state and (found := visit(n, [*path, n])):
                return found
        state[m] = 2
        return []

    for m in sorted(graph):
        if m not in state and (found := visit(m, [m])):
            return found
    return []


def test_the_cycle_modules_import_each_other_without_a_circle():
    """The study variants (cycle.methods) import the thermal one; no module of tribodyn.cycle
    imports another that imports it back, not even inside a function."""
    graph = {
        f"tribodyn.cycle.{p.stem}": {
            ".".join(m.split(".")[:3]) for m, _ in _imports(p) if m.startswith("tribodyn.cycle.")
        }
        for p in (SRC / "cycle").glob("*.py")
    }
    assert "tribodyn.cycle.thermal" in graph["tribodyn.cycle.methods"]
    assert not (circle := _import_circle(graph)), " → ".join(circle)


def _runtime_imports(path: Path, text: str | None = None, typed: bool = False) -> set[str]:
    """The tribodyn modules ``path`` imports when it runs (at module level or inside a
    function; ``from .pkg import mod`` counts ``pkg.mod``); imports only for type checking
    are left out unless ``typed``."""
    source = path.read_text(encoding="utf-8") if text is None else text
    tree = ast.parse(source)
    typing_only = {
        id(sub)
        for node in ast.walk(tree)
        if not typed and isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test)
        for stmt in node.body
        for sub in ast.walk(stmt)
    }
    pkg = _module_name(path).split(".")
    pkg = pkg if path.name == "__init__.py" else pkg[:-1]
    out = set()
    for node in ast.walk(tree):
        if id(node) in typing_only:
            continue
        if isinstance(node, ast.ImportFrom):
            base = ".".join(pkg[: len(pkg) - node.level + 1]) if node.level else ""
            mod = ".".join(x for x in (base, node.module) if x)
            names = [f"{mod}.{a.name}" for a in node.names]
        elif isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        else:
            continue
        for name in names:
            while name not in MODULES and "." in name:  # an imported class or function
                name = name.rsplit(".", 1)[0]
            if name in MODULES:
                out.add(name)
    return out


def _module_name(path: Path) -> str:
    parts = path.relative_to(SRC.parent).with_suffix("").parts
    return ".".join(parts[:-1] if path.name == "__init__.py" else parts)


MODULES = {_module_name(p): p for p in _modules()}


def test_no_module_imports_one_that_imports_it_back():
    """No import circle in the package, even through an import inside a function: a
    module that needs another's function either owns it or gets it passed."""
    graph = {name: {m for m in _runtime_imports(p) if m != name} for name, p in MODULES.items()}
    assert not (circle := _import_circle(graph)), " → ".join(circle)


#: The type-only imports that still close a circle: the built case names the Case that
#: builds it during its validation, the input origins name the Case they read (which
#: carries its given keys with them).
TYPED_CIRCLE_EDGES = {
    ("tribodyn.config.build", "tribodyn.config.case"),
    ("tribodyn.config.origins", "tribodyn.config.case"),
}


def test_no_circle_through_type_only_imports_either():
    """The same with the imports for type checking counted (but the edges named in
    TYPED_CIRCLE_EDGES): a type is owned by a module below its users, or read through a
    protocol."""
    graph = {
        name: {
            m
            for m in _runtime_imports(p, typed=True)
            if m != name and (name, m) not in TYPED_CIRCLE_EDGES
        }
        for name, p in MODULES.items()
    }
    assert not (circle := _import_circle(graph)), " → ".join(circle)
    for a, b in TYPED_CIRCLE_EDGES:  # each named edge still exists and is type-only
        assert b in _runtime_imports(MODULES[a], typed=True)
        assert b not in _runtime_imports(MODULES[a])


def test_the_package_circle_check_sees_an_import_inside_a_function():
    profile = SRC / "topography" / "profile.py"
    text = profile.read_text(encoding="utf-8") + "\n\ndef _f():\n    from .analysis import x\n"
    assert "tribodyn.topography.analysis" in _runtime_imports(profile, text)
    typed = "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from .analysis import x\n"
    assert "tribodyn.topography.analysis" not in _runtime_imports(profile, typed)
    assert "tribodyn.topography.analysis" in _runtime_imports(profile, typed, typed=True)


def test_the_circle_check_sees_a_circle():
    """The check above is able to fail: it finds a → b → a behind a third module."""
    assert _import_circle({"c": {"a"}, "a": {"b"}, "b": {"a"}}) == ["a", "b", "a"]
    assert _import_circle({"a": {"b"}, "b": set()}) == []


def _case_builder_mixins():
    """The classes :class:`~tribodyn.config.Case` inherits its builders from."""
    from tribodyn.config import Case

    return [c for c in Case.__mro__[1:] if c.__name__.endswith("Builders")]


def _builder_calls(tree) -> list[str]:
    """``line: call`` of each call of a Case's private constructor
    (``conftest.case_builders``) in ``tree``."""
    builders = case_builders()
    return [
        f"{node.lineno}: {ast.unparse(node.func)}"
        for node in ast.walk(tree)
        if isinstance(node, ast.Call)
        and isinstance(node.func, ast.Attribute)
        and node.func.attr in builders
    ]


def test_case_builders_are_declared():
    """The Case has no public builders (``build(case)`` returns the objects); its private
    constructors (``_new_*``, ``_build_*``) are those the builder scans look for."""
    from tribodyn.config import Case

    classes = [Case, *_case_builder_mixins()]
    assert len(classes) >= 4
    public = {n for c in classes[1:] for n, v in vars(c).items() if inspect.isfunction(v)}
    assert not {n for n in public if n[0] != "_"}
    assert {"_build_cam", "_build_set", "_new_lubricant", "_new_thermal_bodies"} <= (
        case_builders()
    )


def test_studies_read_the_built_case():
    """Outside config no code calls a Case builder: the studies and commands build a case
    once (``build(case)``) and read its BuiltCase; output reads the results."""
    found = []
    for path in _modules():
        rel = path.relative_to(SRC)
        if rel.parts[0] == "config":
            continue
        found += [f"{rel}:{c}" for c in _builder_calls(ast.parse(path.read_text("utf-8")))]
    assert not found, f"{len(found)} Case builder calls:\n" + "\n".join(found)


def test_the_builder_check_sees_a_call():
    """The scan above is able to fail: it finds builders called on a case, not the
    built case's own methods."""
    text = (
        "lub = case._new_lubricant()\n"
        "s = built.set('x').surface\n"
        "t = built.analytic_tribology('x')\n"
        "t = self.case._new_analytic_tribology(s, lub)\n"
        "b = c._new_thermal_bodies(s)\n"
    )
    assert _builder_calls(ast.parse(text)) == [
        "1: case._new_lubricant",
        "4: self.case._new_analytic_tribology",
        "5: c._new_thermal_bodies",
    ]
