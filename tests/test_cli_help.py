"""``--help`` shows each command's description as paragraphs wrapped to the terminal: a
line ends early only where its paragraph ends (or in an indented example), never where
the docstring's source line happened to end."""

from __future__ import annotations

import pytest
import typer
from typer.testing import CliRunner

from tribodyn.cli import app

COMMANDS = sorted(typer.main.get_group(app).commands)


def _help(args: list[str], columns: int) -> list[str]:
    r = CliRunner().invoke(app, [*args, "--help"], env={"COLUMNS": str(columns)})
    assert r.exit_code == 0, r.output
    return r.output.splitlines()


def _description(lines: list[str]) -> list[str]:
    """The lines between ``Usage:`` and the first panel (the command's description)."""
    start = next(i for i, ln in enumerate(lines) if "Usage:" in ln) + 1
    end = next((i for i, ln in enumerate(lines) if ln.startswith("╭")), len(lines))
    return [ln.rstrip() for ln in lines[start:end]]


def early_breaks(lines: list[str], columns: int) -> list[str]:
    """Lines of a prose paragraph that end although the next word would have fitted
    (with a margin of a few columns for the help's padding)."""
    out = []
    for line, after in zip(lines, lines[1:]):
        prose = line.strip() and after.strip() and not line.startswith("   ")
        if prose and len(line) + 1 + len(after.split()[0]) <= columns - 4:
            out.append(f"{line!r} / {after!r}")
    return out


def test_the_run_description_is_one_paragraph_per_line_on_a_wide_terminal():
    lines = _help(["run"], 200)
    assert any("(self-contained, with interactive traces)" in ln for ln in lines)
    assert any("Exit codes: 0 done, 1 study or writing failed" in ln for ln in lines)


def _summaries(lines: list[str]) -> tuple[list[list[str]], int]:
    """The commands' summaries in the ``Commands`` panel of ``tribodyn --help`` (each a
    list of lines) and the width of their column."""
    start = next(i for i, ln in enumerate(lines) if ln.startswith("╭─ Commands"))
    rows = [ln.strip().strip("│") for ln in lines[start + 1 :]]
    rows = rows[: next(i for i, ln in enumerate(rows) if ln.startswith("╰"))]
    name = rows[0].split()[0]
    col = rows[0].index(rows[0].split()[1], len(name) + 1)  # where the summaries start
    summaries: list[list[str]] = []
    for row in rows:
        if row[:col].strip():  # a command's first row
            summaries.append([])
        summaries[-1].append(" " + row[col:].rstrip())
    return summaries, len(rows[0]) - col


@pytest.mark.parametrize("command", [None, *COMMANDS])
def test_help_paragraphs_fill_their_lines(command):
    """At 80 columns no description line (nor a command's summary in ``tribodyn
    --help``) breaks before the terminal's width."""
    lines = _help([] if command is None else [command], 80)
    assert not early_breaks(_description(lines), 80)
    if command is None:
        summaries, width = _summaries(lines)
        assert len(summaries) == len(COMMANDS)
        for summary in summaries:
            assert not early_breaks(summary, width)


def test_the_check_finds_an_early_break():
    assert early_breaks([" report.html (self-contained, with", " interactive traces)"], 80)
    assert not early_breaks([" " + "x" * 72, " with"], 80)  # "with" would not fit
    assert not early_breaks([" the end of a paragraph.", "", " The next"], 80)
    assert not early_breaks(["   tribodyn contact --dry", "   --coating-thickness 4e-6"], 80)
