"""The package hops of ``tribodyn run``'s data path (prints JSON). Not a timed test.

    python benchmarks/trace_data_path.py [CASE] [--out DIR]

Runs ``tribodyn run CASE -o DIR --workers 1`` in this process (the surface sets then run
in this process too, so every call is seen) under a profile hook that records, for each
call of a tribodyn function, the package of the caller and of the callee. A package is
the first part of the module path below ``tribodyn`` (``cli``, ``config``, ``workflow``,
``output``, ``contact``, ``valvetrain``, ``physics``, ``topography``); the top-level
helper modules (thread limits, input checks, safe writing) are transparent: a call
through them counts as a call from their caller. Reported:

- ``edges``: every caller package → callee package pair seen, with its call count;
- ``hops`` / ``chain``: the longest chain of package changes on one call stack (the
  stack's packages with repeats of the same package merged), i.e. how many packages
  the case's data passes through on its deepest way down;
- ``hops_without_callbacks`` / ``path``: the same with callbacks folded: where a
  package comes back on the stack (an executor or solver calling a function that a
  higher layer handed it: a task, a progress report, a film law), the stack is cut back
  to that package's first place, so only the way down counts;
- ``upward``: caller → callee pairs against the layer order (physics → contact,
  valvetrain, topography → config → cycle → workflow → output → cli), i.e. callbacks;
- ``config_after_build``: calls of ``tribodyn.config`` functions from outside
  ``config`` after the case was first built (validated), by callee: the studies going
  back to the case for objects or data after the build.

Slow (every Python call is hooked): about three times the run's own time.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import threading
from collections import Counter
from pathlib import Path

ROOT = "tribodyn"
#: The layer of each package, lowest first (docs/architecture.md).
LAYERS = {
    "physics": 0,
    "contact": 1,
    "valvetrain": 1,
    "topography": 1,
    "config": 2,
    "cycle": 3,
    "workflow": 4,
    "output": 5,
    "cli": 6,
}


def package(module: str | None) -> str | None:
    """The tribodyn package of a module name (None outside tribodyn)."""
    if not module or not (module == ROOT or module.startswith(ROOT + ".")):
        return None
    parts = module.split(".")
    if len(parts) < 3:  # tribodyn or a top-level helper (_threads, _validation): transparent
        return None
    return parts[1]


def _transparent(frame) -> bool:
    name = frame.f_globals.get("__name__") or ""
    return name.startswith(ROOT + ".") and name.count(".") == 1


class Tracer:
    """Profile hook: package edges, the deepest package chain, config builds after build."""

    def __init__(self) -> None:
        self.edges: Counter[str] = Counter()
        self.chain: list[str] = []
        self.path: list[str] = []
        self.after_build: Counter[str] = Counter()
        self.built = False
        self.stack: list[str] = []  # merged package stack of the current thread

    def __call__(self, frame, event, arg):
        if event == "call":
            pkg = package(frame.f_globals.get("__name__"))
            if pkg is None:
                return
            caller = frame.f_back
            while caller is not None and _transparent(caller):
                caller = caller.f_back
            cpkg = package(caller.f_globals.get("__name__")) if caller is not None else None
            if cpkg is not None and cpkg != pkg:
                self.edges[f"{cpkg} -> {pkg}"] += 1
                if pkg == "config" and self.built:
                    self.after_build[f"{frame.f_code.co_qualname}"] += 1
            self._enter(frame, pkg)
        elif event == "return" and frame.f_code.co_name in {"build", "collect"}:
            if frame.f_globals.get("__name__") == "tribodyn.config.build":
                self.built = True

    def _enter(self, frame, pkg: str) -> None:
        stack = []
        f = frame
        while f is not None:
            p = package(f.f_globals.get("__name__"))
            if p is not None and (not stack or stack[-1] != p):
                stack.append(p)
            f = f.f_back
        stack.reverse()
        if len(stack) > len(self.chain):
            self.chain = stack
        folded: list[str] = []
        for p in stack:
            folded = folded[: folded.index(p) + 1] if p in folded else [*folded, p]
        if len(folded) > len(self.path):
            self.path = folded


def _upward(edge: str) -> bool:
    caller, callee = edge.split(" -> ")
    return LAYERS.get(caller, -1) < LAYERS.get(callee, -1)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("case", nargs="?", default=None)
    ap.add_argument("--out", default=None)
    args = ap.parse_args()
    from typer.main import get_command

    from tribodyn.cli.app import app

    out = Path(args.out or tempfile.mkdtemp(prefix="trace-")) / "run"
    argv = ["run", "-o", str(out), "--workers", "1", "--quiet"]
    if args.case:
        argv.insert(1, args.case)
    tracer = Tracer()
    threading.setprofile(tracer)
    sys.setprofile(tracer)
    try:
        get_command(app).main(argv, standalone_mode=False)
    finally:
        sys.setprofile(None)
        threading.setprofile(None)  # type: ignore[arg-type]
    print(
        json.dumps(
            {
                "hops": len(tracer.chain) - 1,
                "chain": tracer.chain,
                "edges": dict(tracer.edges.most_common()),
                "distinct_edges": len(tracer.edges),
                "hops_without_callbacks": len(tracer.path) - 1,
                "path": tracer.path,
                "upward": sorted(e for e in tracer.edges if _upward(e)),
                "config_after_build": dict(tracer.after_build.most_common()),
            },
            indent=1,
        )
    )


if __name__ == "__main__":
    main()
