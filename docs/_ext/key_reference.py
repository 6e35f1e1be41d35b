"""Sphinx directive ``key-reference``: the case-file or sweep-file keys from the schema.

Usage (MyST)::

    ```{key-reference} case
    ```

renders one table per TOML section with each key's type, default, unit, allowed range and
description, read from :mod:`tribodyn.config.reference` at build time.
"""

from __future__ import annotations

from docutils import nodes
from sphinx.util.docutils import SphinxDirective

from tribodyn.config import Case
from tribodyn.config.reference import key_reference
from tribodyn.config.sweep import SweepFile

_SOURCES = {"case": Case, "sweep": SweepFile}


_HEADER = ("key", "type", "default", "unit", "allowed", "description")
_WIDTHS = (16, 14, 11, 7, 18, 34)


def _cell(text: str, literal: bool = False) -> nodes.entry:
    para = nodes.paragraph()
    if text:
        para += nodes.literal(text, text) if literal else nodes.Text(text)
    return nodes.entry("", para)


def _table(rows) -> nodes.table:
    table = nodes.table(classes=["key-reference"])
    group = nodes.tgroup(cols=len(_HEADER))
    table += group
    for w in _WIDTHS:
        group += nodes.colspec(colwidth=w)
    head = nodes.thead()
    head += nodes.row("", *(_cell(h) for h in _HEADER))
    group += head
    body = nodes.tbody()
    for r in rows:
        body += nodes.row(
            "",
            _cell(r.key, literal=True),
            _cell(r.type),
            _cell(r.default, literal=bool(r.default) and r.default != "(table)"),
            _cell(r.unit),
            _cell(r.allowed.replace("`", "")),
            _cell(r.description),
        )
    group += body
    return table


class KeyReference(SphinxDirective):
    required_arguments = 1
    has_content = False

    def run(self) -> list[nodes.Node]:
        which = self.arguments[0]
        if which not in _SOURCES:
            raise self.error(f"key-reference: unknown file kind {which!r} (case, sweep)")
        sections: dict[str, list] = {}
        for row in key_reference(_SOURCES[which]):
            sections.setdefault(row.section, []).append(row)
        out: list[nodes.Node] = []
        for section, rows in sections.items():
            title = f"[{section}]" if section else "top level"
            out.append(nodes.rubric(title, title))
            out.append(_table(rows))
        return out


def setup(app):
    app.add_directive("key-reference", KeyReference)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
