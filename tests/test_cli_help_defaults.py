"""Every default that a command's ``--help`` states is the value the command uses.

For every command of the application (enumerated from the typer app), the help of each
option and argument is rendered as ``--help`` shows it; the values it states as defaults
are read from the text and compared with what the command uses when the option is not
given: the JSON of ``tribodyn contact`` (solved without the option), the case ``tribodyn
run`` loads, the constants the topography analysis applies, or the option's own default
(what click passes).

A stated default is a clause that starts at "default", "typical" or "paper" and runs to
the end of its parenthesis or sentence, or a parenthesis that is only a number ("(0.055)",
"(850, assumed)"). A clause is cut into pieces at commas and semicolons; a piece that names
a context of the option ("--oil", "dry", "dlc", …) is compared with the value used in that
context, and the pieces after it inherit it.
"""

from __future__ import annotations

import functools
import io
import math
import re
from contextlib import redirect_stdout

import pytest
import typer

from tribodyn.cli import app

# ----------------------------------------------------------------------------- parsing
_NUM = r"[-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?"
_NUMBER = re.compile(rf"(?<![\w.\-–/=])({_NUM})(?:\s*[–-]\s*({_NUM}))?(?![\w.])\s*(µm|mm|MPa|GPa)?")
_SCALE = {None: 1.0, "µm": 1e-6, "mm": 1e-3, "MPa": 1e6, "GPa": 1e9}
#: references, not values
_REFERENCES = re.compile(r"\b(?:Tables?|Eqs?\.|Figs?\.)\s*\d+(?:\s*[–-]\s*\d+)?")
_KEYWORD = re.compile(r"(?i)\b(?:default|typical|paper)\b")
_LONE_NUMBER = re.compile(rf"\(\s*{_NUM}\s*(?:,[^()]*)?\)")


def _clause(text: str, start: int) -> str:
    """``text`` from ``start`` to the end of the enclosing parenthesis or sentence."""
    depth = 0
    for i in range(start, len(text)):
        c = text[i]
        if c in "([":
            depth += 1
        elif c in ")]":
            depth -= 1
            if depth < 0:
                return text[start:i]
        elif c == "." and depth == 0 and (i + 1 == len(text) or text[i + 1].isspace()):
            return text[start:i]
    return text[start:]


def stated_clauses(text: str) -> list[str]:
    """The clauses of ``text`` that state a default (module docstring)."""
    text = _REFERENCES.sub("", text)
    out = [_clause(text, m.start()) for m in _KEYWORD.finditer(text)]
    out += [m.group(0) for m in _LONE_NUMBER.finditer(text)]
    return out


def stated_values(clause: str, contexts) -> list[tuple[str, float, str]]:
    """(context, value, piece) of every number of ``clause``; the context is the last of
    ``contexts`` named in its piece or an earlier one ("" if none)."""
    out = []
    ctx = ""
    for piece in re.split(r"[,;]\s+", clause):
        named = [(piece.find(k), k) for k in contexts if k and k in piece]
        if named:
            ctx = max(named)[1]
        for m in _NUMBER.finditer(piece):
            scale = _SCALE[m.group(3)]
            for g in (m.group(1), m.group(2)):
                if g is not None:
                    out.append((ctx, float(g) * scale, piece))
    return out


def test_the_parser_reads_the_old_statements():
    """The forms the help texts used (and use) are read as stated defaults."""
    ctx = {"": 0, "--oil": 0}
    old = "τ_E [Pa] (the case's; paper 2e+06; with --oil the typical 5e+06)."
    got = [v[:2] for c in stated_clauses(old) for v in stated_values(c, ctx)]
    assert got == [("", 2e6), ("--oil", 5e6), ("", 5e6)]
    assert [stated_values(c, {"": 0}) for c in stated_clauses("μ₀ [Pa·s] (0.055).")] == [
        [("", 0.055, "(0.055)")]
    ]
    band = stated_clauses("Default: the paper's 0.25–250 µm clipped (see Table 4).")
    assert [v[1] for c in band for v in stated_values(c, {"": 0})] == pytest.approx(
        [0.25e-6, 250e-6, 0.25e-6, 250e-6]
    )
    assert stated_clauses("the port (0: any free port); e.g. 200; tcp://host:8786") == []


# ----------------------------------------------------------------------------- helps
def _commands() -> dict:
    return dict(typer.main.get_command(app).commands)  # type: ignore[attr-defined]


@functools.cache
def rendered_params() -> dict:
    """(command, parameter) → the parameter, its help as ``--help`` renders it."""
    out = {}
    for name, cmd in _commands().items():
        ctx = cmd.context_class(cmd, info_name=name)
        with ctx, redirect_stdout(io.StringIO()):
            cmd.get_help(ctx)  # renders the help as --help does
        for p in cmd.params:
            if p.name != "help":
                out[(name, p.name)] = p
    return out


def _help_text(p) -> str:
    parts = [getattr(p, "help", None), getattr(p, "rich_help_panel", None)]
    shown = getattr(p, "show_default", None)
    if isinstance(shown, str):  # typer's "[default: (text)]"
        parts.append(f"[default: {shown}]")
    elif shown and p.default is not None and not isinstance(p.default, bool):
        d = p.default
        parts.append(f"[default: {', '.join(map(str, d)) if isinstance(d, (tuple, list)) else d}]")
    return " ".join(x for x in parts if x)


# ----------------------------------------------------------------------------- used values
@functools.cache
def contact_runs() -> dict[str, dict]:
    """``tribodyn contact`` solved with only the required options (and one context option)."""
    from tribodyn.cli.contact import compute_contact

    base = dict(load=633.0, radius=0.01, ue=5.0)
    runs = {
        "": compute_contact(**base),
        "dry": compute_contact(load=633.0, radius=0.01, dry=True),
        "--oil": compute_contact(**base, oil="5W-30", inlet_temperature=90.0),
    }
    for m in ("dlc", "wcc"):
        runs[m] = compute_contact(**base, coating_material=m, coating_thickness=4e-6)
    return runs


def _contact(key: str, *contexts: str):
    return lambda: {c: contact_runs()[c][key] for c in ("", *contexts)}


def _default_case():
    from tribodyn.config import load_case

    return load_case()


def _contact_case_name() -> str:
    from pathlib import Path

    path = contact_runs()[""]["case"]
    return Path(path).stem if path else "(schema defaults, no case)"


def _grid_n():
    from tribodyn.contact.ehl.grid import N_MAX_AUTO

    ehl = {contact_runs()[""]["grid_points"], _default_case().numerics.n}
    return {"": ehl, "EHL": ehl, "refined": N_MAX_AUTO, "dry": contact_runs()["dry"]["grid_points"]}


def _band():
    from tribodyn.physics import typical

    return {"": {typical.FILTER_SHORT_WAVELENGTH.value, typical.FILTER_LONG_WAVELENGTH.value}}


def _min_defined():
    from tribodyn.topography.analysis import MIN_SUMMITS

    return {"": 0.0, "summits": MIN_SUMMITS}


def _synthetic(*names: str):
    """The defaults of ``synthetic_surface`` that an option of ``--synthetic`` leaves."""

    def used():
        import inspect

        from tribodyn.topography.synthetic import synthetic_surface

        p = inspect.signature(synthetic_surface).parameters
        values = [v for n in names for v in _flat(p[n].default)]
        return {"": set(values)}

    return used


def _flat(value) -> list:
    return list(value) if isinstance(value, tuple) else [value]


def _typical(name: str):
    def used():
        from tribodyn.physics import typical

        return {"": getattr(typical, name).value}

    return used


#: (command, parameter) → the values used without the option, by context ("" none). An
#: option with a default of its own (not None) uses it; these are the others, and the
#: defaults that name their source.
USED = {
    ("contact", "width"): _contact("width_m"),
    ("contact", "us"): _contact("sliding_speed_m_per_s"),
    ("contact", "shear_coefficient"): lambda: {
        "": contact_runs()[""]["boundary_shear_coefficient"],
        "steel": contact_runs()[""]["boundary_shear_coefficient"],
        "dlc": contact_runs()["dlc"]["boundary_shear_coefficient"],
        "wcc": contact_runs()["wcc"]["boundary_shear_coefficient"],
        "τ₀": contact_runs()[""]["boundary_shear_strength_Pa"],
    },
    ("contact", "viscosity"): _contact("viscosity_Pa_s"),
    ("contact", "pressure_viscosity"): _contact("pressure_viscosity_per_Pa"),
    ("contact", "density"): _contact("density_kg_per_m3"),
    ("contact", "eyring_stress"): _contact("eyring_stress_Pa", "--oil"),
    ("contact", "limiting_shear_coefficient"): _contact("limiting_shear_coefficient", "--oil"),
    ("contact", "viscosity_model"): _contact("viscosity_model"),
    ("contact", "viscous_model"): _contact("viscous_model"),
    ("contact", "limiting_shear"): lambda: {
        "": "on" if contact_runs()[""]["limiting_shear"] else "off"
    },
    ("contact", "n"): _grid_n,
    ("run", "workers"): lambda: {"": _default_case().numerics.workers},
    ("figures", "workers"): lambda: {"": _figure_workers()},
    ("topography", "band"): _band,
    ("topography", "min_defined"): _min_defined,
    ("topography", "grid"): _synthetic("nb_grid_pts"),
    ("topography", "pixel"): _synthetic("pixel_size"),
    ("topography", "rms"): _synthetic("rms"),
    ("topography", "hurst"): _synthetic("hurst"),
    ("topography", "cutoffs"): _synthetic("short_cutoff", "long_cutoff"),
    ("calibrate", "roughness_parameter"): _typical("ROUGHNESS_PARAMETER"),
    ("calibrate", "rms_to_radius"): _typical("RMS_TO_SUMMIT_RADIUS"),
}


def _figure_workers() -> int:
    from tribodyn.output.figures_folder import figure_workers

    return figure_workers()


#: command → the bundled case it uses where none is given (a help text that names a
#: bundled case must name this one)
CASE_USED = {
    "contact": _contact_case_name,
    "run": lambda: _default_case().name,
}

#: options whose default comes from the default case: their help must state it
MUST_STATE = {
    ("contact", name)
    for name in (
        "width",
        "shear_coefficient",
        "viscosity",
        "pressure_viscosity",
        "density",
        "eyring_stress",
        "limiting_shear_coefficient",
        "viscosity_model",
        "viscous_model",
        "limiting_shear",
        "n",
    )
}


def _same(stated: float, used) -> bool:
    values = used if isinstance(used, set) else {used}
    return any(
        isinstance(u, (int, float))
        and not isinstance(u, bool)
        and math.isclose(stated, u, rel_tol=1e-5, abs_tol=1e-300)
        for u in values
    )


def test_every_command_is_checked():
    """The table names only existing commands and parameters, and the app's commands
    are the expected ones (a new command gets its help checked too)."""
    params = rendered_params()
    assert {"run", "sweep", "contact", "engine", "topography", "calibrate", "export",
            "view", "warmup"} <= set(_commands())  # fmt: skip
    assert set(USED) <= set(params)
    assert MUST_STATE <= set(params)


@pytest.mark.parametrize("command", sorted(_commands()))
def test_stated_defaults_are_the_used_ones(command):
    """Every number a help text states as a default is the value the command uses
    without the option (in the context the text names)."""
    from tribodyn.config import bundled_cases

    bundled = set(bundled_cases())
    wrong = []
    for (cmd, name), p in rendered_params().items():
        if cmd != command:
            continue
        text = _help_text(p)
        clauses = stated_clauses(text)
        if (cmd, name) in USED:
            used = USED[(cmd, name)]()
        elif p.default is not None and not callable(p.default):
            d = p.default
            used = {"": set(d) if isinstance(d, (tuple, list)) else d}
        else:
            used = None
        if (cmd, name) in MUST_STATE and not clauses:
            wrong.append(f"{cmd} {name}: states no default ({text!r})")
        for clause in clauses:
            for case in bundled & set(re.findall(r"[\w.]+", clause)):
                uses = CASE_USED[cmd]() if cmd in CASE_USED else "no bundled case"
                if case != uses:
                    wrong.append(f"{cmd} {name}: names the case {case}, uses {uses}")
            values = stated_values(clause, used or {"": None})
            if values and used is None:
                wrong.append(f"{cmd} {name}: states {clause!r}, but the test has no used value")
                continue
            for ctx, v, piece in values:
                if not _same(v, used.get(ctx, used[""])):
                    wrong.append(f"{cmd} {name}: states {piece!r} ({ctx or 'no context'}), "
                                 f"uses {used.get(ctx, used[''])!r}")  # fmt: skip
        words = [u for u in (used or {}).values() if isinstance(u, str)]
        own = [c for c in stated_clauses(p.help or "") if c.lower().startswith("default")]
        if own and words and not any(re.search(rf"\b{w}\b", c) for c in own for w in words):
            wrong.append(f"{cmd} {name}: states {own!r}, uses {words[0]!r}")
    assert not wrong, "\n".join(wrong)


def test_the_case_keys_the_help_names_exist():
    """A help text that points to "the case's <section.key>" names a key of the case."""
    from tribodyn.config.paths import find_paths

    data = _default_case().model_dump(by_alias=True)
    missing = []
    for (cmd, name), p in rendered_params().items():
        for key in re.findall(r"the case's ([a-z_]+\.[a-z_]+)", _help_text(p)):
            if not find_paths(data, key):
                missing.append(f"{cmd} {name}: {key}")
    assert not missing


@pytest.mark.parametrize("command", sorted(_commands()))
def test_help_is_rendered_with_its_values_filled_in(command):
    """``tribodyn COMMAND --help`` prints (exit 0) with no placeholder left unfilled."""
    from typer.testing import CliRunner

    r = CliRunner().invoke(app, [command, "--help"], env={"COLUMNS": "200"})
    assert r.exit_code == 0, r.output
    text = "\n".join(ln for ln in r.output.splitlines() if "Usage:" not in ln)
    assert not re.findall(r"\{\w+(?::[^}]*)?\}", text)  # typer writes {arg} in "Usage:"
