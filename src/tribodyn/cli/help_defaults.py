"""Defaults that ``--help`` states, taken from the objects the command uses.

An option whose default is not a literal of the command line (the default case's value,
the solver's grid, a typical value) writes ``{name}`` in its help, its panel title or the
command's docstring. The command's class (:func:`stating`) fills the placeholders in from
its resolver when the help is shown, so the text quotes what the command uses, and
importing the command line stays cheap (a resolver may load a case).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from typer.core import TyperCommand

__all__ = ["StatedDefaultsCommand", "stating"]


class StatedDefaultsCommand(TyperCommand):
    """A command whose help texts hold ``{name}`` placeholders of :meth:`defaults`."""

    @staticmethod
    def defaults() -> Mapping[str, Any]:  # pragma: no cover - replaced by stating()
        return {}

    def fill_help(self) -> None:
        """Replace the placeholders of the command's and its parameters' help (once)."""
        if getattr(self, "_filled", False):
            return
        values = self.defaults()
        if self.help:
            self.help = self.help.format_map(values)
        for p in self.params:
            text = getattr(p, "help", None)
            if text:
                p.help = text.format_map(values)  # type: ignore[attr-defined]
            panel = getattr(p, "rich_help_panel", None)
            if panel:
                p.rich_help_panel = panel.format_map(values)  # type: ignore[attr-defined]
        self._filled = True

    def format_help(self, ctx: Any, formatter: Any) -> None:
        self.fill_help()
        super().format_help(ctx, formatter)


def stating(defaults: Callable[[], Mapping[str, Any]]) -> type[StatedDefaultsCommand]:
    """The command class whose help quotes ``defaults()`` (``cls=`` of ``app.command``)."""
    return type(
        "StatedDefaultsCommand", (StatedDefaultsCommand,), {"defaults": staticmethod(defaults)}
    )
