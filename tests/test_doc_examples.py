"""The Python examples of the README and the documentation run, so they cannot rot.

Every ```python block of README.md and docs/**/*.md is executed; the blocks of one file
run in order in one namespace (as a reader would paste them), in a fresh working folder
that holds a ``results/`` folder of a (reduced) ``tribodyn run``. A block whose first
line is ``# name.py`` is a script: it is written to that file and run in a subprocess
(Dask starts worker processes by importing the script). A block preceded by
``<!-- docs-test: skip (reason) -->`` is not run; the reason must be given.

``load_case()`` without arguments returns the paper case at the reduced resolution of
``conftest.REDUCED`` here, so that the README's full study runs in test time; the code
path is the same.
"""

import re
import shutil
import subprocess
import sys
from pathlib import Path

import matplotlib
import pytest

import tribodyn.config
from conftest import REDUCED

matplotlib.use("Agg")

ROOT = Path(__file__).resolve().parents[1]
FILES = [ROOT / "README.md"] + sorted(
    p for p in (ROOT / "docs").rglob("*.md") if "_build" not in p.parts
)
FENCE = re.compile(r"^```python[^\n]*\n(.*?)^```", re.S | re.M)
SKIP = re.compile(r"<!--\s*docs-test:\s*skip\s*\((.+?)\)\s*-->\s*$")


def blocks(path: Path) -> list[tuple[int, str, str | None]]:
    """(line, code, skip reason) of the python blocks of a Markdown file."""
    text = path.read_text(encoding="utf-8")
    out = []
    for m in FENCE.finditer(text):
        line = text.count("\n", 0, m.start()) + 1
        before = text[: m.start()].rstrip("\n").rsplit("\n", 1)[-1]
        skip = SKIP.search(before)
        out.append((line, m.group(1), skip.group(1) if skip else None))
    return out


FILES_WITH_CODE = [p for p in FILES if blocks(p)]


def test_every_skip_has_a_reason_and_most_blocks_run():
    all_blocks = [b for p in FILES for b in blocks(p)]
    skipped = [b for b in all_blocks if b[2] is not None]
    assert all(reason.strip() for *_, reason in skipped)
    assert len(all_blocks) >= 15 and len(skipped) <= len(all_blocks) // 3


@pytest.mark.parametrize("path", FILES_WITH_CODE, ids=lambda p: str(p.relative_to(ROOT)))
def test_examples_run(path, tmp_path, monkeypatch, reduced_results):
    shutil.copytree(reduced_results, tmp_path / "results")
    monkeypatch.chdir(tmp_path)
    real_load_case = tribodyn.config.load_case

    def load_case(path=None, *args, **kwargs):
        case = real_load_case(path, *args, **kwargs)
        return case.updated(REDUCED) if path is None else case

    monkeypatch.setattr(tribodyn.config, "load_case", load_case)
    namespace: dict = {"__name__": "__main__"}
    for line, code, skip in blocks(path):
        if skip is not None:
            continue
        first = code.splitlines()[0].strip()
        script = re.fullmatch(r"#\s*([\w\-]+\.py)", first)
        if script:
            (tmp_path / script.group(1)).write_text(code, encoding="utf-8")
            r = subprocess.run(
                [sys.executable, script.group(1)],
                cwd=tmp_path,
                capture_output=True,
                text=True,
                timeout=600,
            )
            assert r.returncode == 0, f"{path.name}:{line}\n{r.stdout}\n{r.stderr}"
            continue
        try:
            exec(compile(code, f"{path.name}:{line}", "exec"), namespace)
        except Exception as exc:  # name the block that failed
            raise AssertionError(f"example at {path.name}:{line} failed: {exc!r}") from exc
