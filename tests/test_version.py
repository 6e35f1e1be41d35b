"""The version lives in one place and reaches the CLI, the package and the results."""

import importlib.metadata
import re

from typer.testing import CliRunner

import tribodyn
from tribodyn._version import __version__
from tribodyn.cli import app


def test_version_is_one_string_everywhere():
    assert re.fullmatch(r"\d+\.\d+\.\d+", __version__)
    assert tribodyn.__version__ == __version__
    assert importlib.metadata.version("tribodyn") == __version__


def test_cli_prints_the_version():
    res = CliRunner().invoke(app, ["--version"])
    assert res.exit_code == 0
    assert res.output.strip() == f"tribodyn {__version__}"


def test_changelog_has_a_section_for_this_version():
    from pathlib import Path

    text = (Path(__file__).parents[1] / "CHANGELOG.md").read_text(encoding="utf-8")
    assert re.search(rf"^## \[{re.escape(__version__)}\] - \d{{4}}-\d{{2}}-\d{{2}}$", text, re.M)
