"""Sphinx configuration of the tribodyn documentation site.

Sphinx with the PyData theme and MyST: the pages are Markdown (as the existing docs and the
README are), the API reference comes from the docstrings through autodoc, and the
case-file and sweep-file key references are generated from the pydantic schema by the
local ``key_reference`` extension, so they cannot drift from the validator.

Math is rendered in the browser by MathJax 3 served from the site itself (the files of the
``django-static-mathjax`` package, copied into ``_static/mathjax``): the site needs no
network.
"""

import re
import shutil
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))

from tribodyn import __version__  # noqa: E402

project = "tribodyn"
author = "tribodyn developers"
copyright = "2026, tribodyn developers"
version = release = __version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "key_reference",
]
source_suffix = {".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build"]

myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3

napoleon_numpy_docstring = True
napoleon_google_docstring = False
napoleon_use_rtype = False

autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": False}
# numpy's and pydantic's own docstrings are not ours to check
nitpicky = False

html_theme = "pydata_sphinx_theme"
html_title = f"tribodyn {__version__}"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "footer_start": ["copyright"],
    "footer_end": [],
    "secondary_sidebar_items": {"reference/*": []},
}
html_static_path = ["_static"]
# MathJax from the docs extra's django-static-mathjax (MathJax 3, Apache-2.0), not a CDN:
# the combined TeX→HTML script, its fonts and the TeX extensions it loads on demand
mathjax_path = "mathjax/tex-chtml.js"
_MATHJAX_PARTS = ("tex-chtml.js", "input", "output/chtml", "ui", "a11y", "adaptors")


def _mathjax_source() -> Path:
    try:
        import mathjax  # django-static-mathjax
    except ImportError as exc:
        raise RuntimeError(
            "the documentation serves MathJax itself: pip install -e '.[docs]' "
            "(django-static-mathjax)"
        ) from exc
    return Path(mathjax.__file__).parent / "static" / "mathjax" / "es5"


def _copy_mathjax(app, exc):
    if exc is not None or app.builder.format != "html":
        return
    src, dst = _mathjax_source(), Path(app.outdir) / "_static" / "mathjax"
    for part in _MATHJAX_PARTS:
        s, d = src / part, dst / part
        d.parent.mkdir(parents=True, exist_ok=True)
        if s.is_dir():
            shutil.copytree(s, d, dirs_exist_ok=True)
        else:
            shutil.copy2(s, d)

html_css_files = ["tribodyn.css"]
# no left sidebar: the navigation bar holds the site's sections; tables get the width
html_sidebars = {"**": []}


_TERM = re.compile(r"^([A-Za-z_*][\w*, .]*?) : (\S.*)$")


def _docstring_to_rst(app, what, name, obj, options, lines):
    """Render tribodyn's docstring conventions as reStructuredText.

    Runs after napoleon (which turns numpy-style ``Parameters`` sections into fields):
    ``|x|`` is an absolute value, not a substitution; other underlined headings become
    rubrics; ``name : description`` lines with indented continuations become definition
    lists.
    """
    out: list[str] = []
    in_list = False
    i = 0
    while i < len(lines):
        line = lines[i]
        if "|" in line:  # escape outside ``literals``
            parts = line.split("``")
            line = "``".join(p if k % 2 else p.replace("|", "\\|") for k, p in enumerate(parts))
        nxt = lines[i + 1] if i + 1 < len(lines) else ""
        if line.strip() and not line.startswith(" ") and re.fullmatch(r"-{3,}|={3,}", nxt):
            out += ["", f".. rubric:: {line.strip()}", ""]
            in_list = False
            i += 2
            continue
        m = _TERM.match(line) if not line.startswith((" ", ":", "..")) else None
        if m:
            if out and out[-1].strip() and not in_list:
                out.append("")
            out += [m.group(1), f"    {m.group(2)}"]
            in_list = True
        elif in_list and line.startswith(" "):
            out.append("    " + line.strip())
        else:
            if in_list and line.strip():
                out.append("")
            in_list = False
            out.append(line)
        i += 1
    lines[:] = out


def setup(app):
    app.connect("autodoc-process-docstring", _docstring_to_rst, priority=600)
    _mathjax_source()  # fail early, before building, if MathJax is not installed
    app.connect("build-finished", _copy_mathjax)
