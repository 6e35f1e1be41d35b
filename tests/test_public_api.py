"""The public API is typed: every parameter and return of the functions and classes that
the packages export carries an annotation (mypy checks them in `make test`)."""

import importlib
import inspect

import pytest

MODULES = [
    "tribodyn",
    "tribodyn.config",
    "tribodyn.workflow.cycle",
    "tribodyn.workflow.sweep",
    "tribodyn.output",
    "tribodyn.valvetrain",
    "tribodyn.topography",
]


def _public_callables():
    for m in MODULES:
        mod = importlib.import_module(m)
        for name in getattr(mod, "__all__", []):
            obj = getattr(mod, name)
            if inspect.isclass(obj):
                if "__init__" in obj.__dict__ and not hasattr(obj, "__dataclass_fields__"):
                    yield f"{m}.{name}", obj.__init__, False
            elif inspect.isfunction(obj):
                yield f"{m}.{name}", obj, True


@pytest.mark.parametrize(
    "name, fn, check_return",
    list(_public_callables()),
    ids=lambda v: v if isinstance(v, str) else "",
)
def test_public_signature_is_annotated(name, fn, check_return):
    sig = inspect.signature(fn)
    missing = [
        p.name
        for p in sig.parameters.values()
        if p.annotation is inspect.Parameter.empty
        and p.name not in ("self", "cls")
        and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)
    ]
    assert not missing, f"{name}: parameters without a type: {missing}"
    if check_return:
        assert sig.return_annotation is not inspect.Signature.empty, f"{name}: no return type"


def test_subpackages_are_attributes_of_the_package():
    """``import tribodyn; tribodyn.physics`` works (the subpackage is imported on first
    use); ``cli`` is not imported that way (it sets the BLAS thread environment)."""
    import os
    import subprocess
    import sys

    code = (
        "import sys, tribodyn\n"
        "names = ['config', 'contact', 'cycle', 'output', 'physics', 'topography',"
        " 'valvetrain', 'workflow']\n"
        "print([getattr(tribodyn, n).__name__ == 'tribodyn.' + n for n in names])\n"
        "print(hasattr(tribodyn, 'cli'), 'tribodyn.cli' in sys.modules)\n"
    )
    src = os.path.join(os.path.dirname(__file__), "..", "src")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([src, os.environ.get("PYTHONPATH", "")]))
    r = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120
    )
    assert r.returncode == 0, r.stderr
    assert r.stdout.split("\n")[:2] == [str([True] * 8), "False False"]
