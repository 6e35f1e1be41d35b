"""``tribodyn view``: one self-contained interactive HTML page comparing any mix of run,
engine and sweep result folders.

The page opens offline: the Bokeh library is embedded once, inline, and every figure's
data with it (float32, traces of more than 1500 samples thinned). It shows, in order:
the results compared; the coating verdict of each folder (friction energy of every set
against its reference set, negative = less); the summary numbers side by side with the
differences against the first column; overlays over crank angle (torque, film, λ,
pressure, contact and friction force, power) of every set of every run, an engine's
per-camshaft torques and power, a sweep's friction loss against its axes with the
coatings' change and heat maps; how the inputs differ (unified diff of the case files);
the warnings. A script measures the figures' drawing time in the browser and writes it
into the page (``data-rendered``, ``data-draw-ms`` of ``<body>``).

Reads results.nc/sweep.nc, summary.json and case.toml only (:mod:`.explorer_data`).
"""

from __future__ import annotations

import difflib
import html
import json
import math
import re
from collections.abc import Sequence
from pathlib import Path

from .._json import dumps
from .._safe_write import atomic_write
from .._typing import PathLike
from .._validation import InputError
from .explorer_data import Result, load_result, unique_labels
from .explorer_plots import (
    LINE_STYLE,
    LineFigure,
    Styles,
    engine_figures,
    run_figures,
    sweep_figures,
)
from .report_engine import ENGINE_PARTS, shaft_peaks

__all__ = [
    "add_interactive",
    "build_page",
    "interactive_block",
    "summary_rows",
    "verdicts",
    "write_page",
    "write_report_html",
]

#: Summary numbers of a run's set: (key, label, unit, scale).
RUN_ROWS = (
    ("friction_energy_per_cycle_J", "friction energy per cycle", "J", 1.0),
    ("mean_friction_torque_Nm", "mean friction torque", "N·m", 1.0),
    ("max_friction_torque_Nm", "max friction torque", "N·m", 1.0),
    ("mean_friction_power_W", "mean friction power", "W", 1.0),
    ("peak_drive_torque_Nm", "peak camshaft drive torque", "N·m", 1.0),
    ("min_film_m", "minimum film h_min", "µm", 1e6),
    ("max_central_film_m", "max central film h_c", "µm", 1e6),
    ("min_lambda", "minimum λ = h_min/σ", "", 1.0),
    ("max_hertz_pressure_Pa", "max Hertz pressure p_h", "MPa", 1e-6),
    ("max_ehl_pressure_Pa", "max EHL pressure", "MPa", 1e-6),
    ("max_boundary_friction_N", "max boundary friction", "N", 1.0),
    ("max_viscous_friction_N", "max viscous friction", "N", 1.0),
    ("failed_steps", "failed EHL steps", "", 1.0),
)
#: Summary numbers of an engine's set (``engine.surface_sets.<set>``).
ENGINE_ROWS = (
    ("engine_friction_energy_per_cycle_J", "valvetrain friction energy per cycle", "J", 1.0),
    ("valvetrain_friction_mep_Pa", "valvetrain friction MEP", "kPa", 1e-3),
    ("mean_friction_power_W", "mean friction power", "W", 1.0),
    ("mean_friction_torque_Nm", "mean friction torque, sum of the camshafts", "N·m", 1.0),
    ("peak_camshaft_drive_torque_Nm", "peak drive torque of the camshafts summed", "N·m", 1.0),
)


def _num(v) -> float | None:
    if isinstance(v, bool) or not isinstance(v, int | float):
        return None
    return float(v) if math.isfinite(v) else None


def _fmt(v: float | None, digits: int = 4) -> str:
    if v is None:
        return "–"
    if v == 0 or 1e-3 <= abs(v) < 1e6:
        return f"{v:.{digits}g}"
    return f"{v:.{digits - 1}e}"


def verdicts(r: Result) -> list[str]:
    """One line per coated set of a run or engine: whether it lowers the friction energy
    per cycle against the reference set and by how much (negative = less). A
    ``coating_verdict`` in the set's summary is used as it is."""
    ref = r.reference
    if r.kind not in ("run", "engine") or ref is None:
        return []
    key = (
        "engine_friction_energy_per_cycle_J"
        if r.kind == "engine"
        else ("friction_energy_per_cycle_J")
    )
    what = "valvetrain friction energy (FMEP)" if r.kind == "engine" else "friction energy"
    e0 = _num(r.set_summary(ref).get(key))
    out = []
    for s in r.sets:
        if s == ref:
            continue
        d = r.set_summary(s)
        given = d.get("coating_verdict")
        if isinstance(given, str) and given:
            out.append(f"{r.labels.get(s, s)}: {given}")
            continue
        if isinstance(given, dict) and given.get("sentence"):
            out.append(str(given["sentence"]))
            continue
        e = _num(d.get(key))
        if e is None or e0 is None or e0 == 0:
            out.append(f"{r.labels.get(s, s)}: no {what} to compare")
            continue
        pct = 100.0 * (e / e0 - 1.0)
        word = "lowers" if pct < 0 else "does not lower"
        out.append(
            f"{r.labels.get(s, s)} {word} the {what}: "
            + f"{pct:+.2f} %".replace("-", "−")
            + f" against {r.labels.get(ref, ref)} ({_fmt(e)} J vs {_fmt(e0)} J per cycle)"
        )
    return out


def _engine_peaks(r: Result) -> dict[str, dict[str, float]]:
    """Peak |drive torque| per camshaft and set (:func:`~.report_engine.shaft_peaks`)."""
    peaks = shaft_peaks(r.ds)
    if peaks is None:
        return {}
    shafts = [str(c) for c in r.ds["camshaft"].values]
    return {s: dict(zip(shafts, map(float, peaks[i]))) for i, s in enumerate(r.sets)}


def summary_rows(results: list[Result], kind: str) -> tuple[list[str], list[list]]:
    """(column headers, rows) of the summary numbers of the results of ``kind``: a column
    per (result, set), each row ``[label, unit, value, …]`` (values scaled, None where
    absent)."""
    cols = [(r, s) for r in results if r.kind == kind for s in r.sets]
    heads = [f"{r.label} · {r.labels.get(s, s)}" for r, s in cols]
    spec = RUN_ROWS if kind == "run" else ENGINE_ROWS
    rows: list[list] = []
    for key, label, unit, scale in spec:
        vals = [_num(r.set_summary(s).get(key)) for r, s in cols]
        if any(v is not None for v in vals):
            rows.append([label, unit, *[None if v is None else v * scale for v in vals]])
    if kind == "engine":
        peaks = {id(r): _engine_peaks(r) for r, _ in cols}
        shafts = sorted({c for r, s in cols for c in peaks[id(r)].get(s, {})}, reverse=True)
        rows += [
            [
                f"peak drive torque, {c} camshaft",
                "N·m",
                *[peaks[id(r)].get(s, {}).get(c) for r, s in cols],
            ]
            for c in shafts
        ]
        for part, _ in ENGINE_PARTS:
            vals = [
                _num(r.set_summary(s).get("friction_energy_per_cycle_J", {}).get(part))
                for r, s in cols
            ]
            if any(v is not None for v in vals):
                rows.append([f"friction energy: {part.replace('_', '–', 1)}", "J", *vals])
    return heads, rows


def _table_html(heads, rows) -> str:
    h = ["<table class='num'><tr><th>quantity</th><th>unit</th>"]
    h += [f"<th>{html.escape(c)}</th>" for c in heads]
    h.append("</tr>")
    for label, unit, *vals in rows:
        h.append(f"<tr><td>{html.escape(label)}</td><td>{html.escape(unit)}</td>")
        v0 = vals[0] if vals else None
        for k, v in enumerate(vals):
            cell = _fmt(v)
            if k and v is not None and v0 not in (None, 0):
                cell += f" <span class='d'>({100.0 * (v / v0 - 1.0):+.1f} %)</span>"
            h.append(f"<td>{cell.replace('-', '−')}</td>")
        h.append("</tr>")
    h.append("</table>")
    return "".join(h)


def case_diff(a: Result, b: Result, max_lines: int = 300) -> str:
    """Unified diff of two results' case files (empty if they are the same)."""
    if a.case_text == b.case_text:
        return ""
    lines = list(
        difflib.unified_diff(
            a.case_text.splitlines(),
            b.case_text.splitlines(),
            fromfile=f"{a.label}/case.toml",
            tofile=f"{b.label}/case.toml",
            lineterm="",
            n=1,
        )
    )
    lines = [ln for ln in lines if not ln.startswith(("-#", "+#"))]  # header comments
    if len(lines) > max_lines:
        lines = lines[:max_lines] + [f"… {len(lines) - max_lines} more lines"]
    return "\n".join(lines)


_CSS = """
body{font-family:sans-serif;max-width:1250px;margin:1.5em auto;padding:0 1em;color:#222;
line-height:1.4}
table{border-collapse:collapse;margin:.6em 0;font-size:88%}
th,td{border:1px solid #bbb;padding:2px 6px;vertical-align:top}
th{background:#eee}td{white-space:nowrap}.d{color:#666;font-size:90%}
pre{background:#f6f6f6;padding:.6em;overflow-x:auto;font-size:82%}
.fig{margin:.8em 0}
"""


def bokeh_js() -> str:
    """The Bokeh library as inline ``<script>`` elements (no network): BokehJS and its
    plotting API (which draws the :class:`~.explorer_plots.LineFigure`)."""
    from bokeh.resources import Resources

    return Resources(mode="inline", components=["bokeh", "bokeh-api"]).render_js()


class _Embedder:
    """Collects the figures of a page and writes their target divs and the script that
    draws them: the line figures as their samples and styles (BokehJS builds them, in
    one document: shared zoom ranges need one), the other figures as one Bokeh
    document."""

    def __init__(self, prefix: str = "tdv"):
        self.prefix = prefix
        self.figs: list = []

    def divs(self, figs) -> str:
        """Target divs of ``figs`` (in the order they are added)."""
        start = len(self.figs)
        self.figs += figs
        ids = range(start, len(self.figs))
        return "\n".join(f"<div class='fig' id='{self.prefix}{k}'></div>" for k in ids)

    def _lines(self) -> dict:
        """The line figures: their specs, target ids, shared ranges and the styles."""
        lines = [(k, f) for k, f in enumerate(self.figs) if isinstance(f, LineFigure)]
        return {
            "style": LINE_STYLE,
            "ranges": {f.x_range[0]: list(f.x_range[1:]) for _, f in lines if f.x_range},
            "figures": [f.spec() for _, f in lines],
            "targets": [f"{self.prefix}{k}" for k, _ in lines],
        }

    def _models(self) -> dict:
        """The other figures as one Bokeh document (``docs``, ``items``; empty without)."""
        roots = {
            f: f"{self.prefix}{k}" for k, f in enumerate(self.figs) if not isinstance(f, LineFigure)
        }
        if not roots:
            return {"docs": {}, "items": []}
        from bokeh.core.json_encoder import serialize_json
        from bokeh.core.types import ID
        from bokeh.document import Document
        from bokeh.embed.util import RenderItem

        doc = Document()
        with doc.models.freeze():  # its models collected once, not again at every root
            for f in roots:
                doc.add_root(f)
        item = RenderItem(docid=ID(self.prefix), roots={f: ID(i) for f, i in roots.items()})
        docs = {self.prefix: doc.to_json(deferred=False)}
        return json.loads(_stable_ids(serialize_json({"docs": docs, "items": [item.to_json()]})))

    def script(self) -> str:
        """The figures' data and the drawing script (empty without figures)."""
        if not self.figs:
            return ""
        data = {**self._models(), "lines": self._lines()}
        text = dumps(data, ensure_ascii=False, separators=(",", ":"))
        text = text.replace("</", "<\\/")
        return (
            f"<script type='application/json' id='{self.prefix}data'>{text}</script>\n"
            + _DRAW
            % {"data": f"{self.prefix}data", "time": f"{self.prefix}time", "n": len(self.figs)}
        )


def _stable_ids(text: str) -> str:
    """Bokeh's model ids (``"p1234"``, a per-process counter) numbered in order of
    appearance: the same figures give the same page in any process."""
    ids: dict[str, str] = {}

    def sub(m: re.Match) -> str:
        return '"' + ids.setdefault(m.group(1), f"p{len(ids) + 1}") + '"'

    return re.sub(r'"(p\d+)"', sub, text)


#: Draws a page's figures: the Bokeh document of the other figures, and the line
#: figures built from their specs (``LineFigure``: columns unpacked from gzip'd float32,
#: a renderer per trace with its one glyph, the legend beside the plot); then writes the
#: drawing time into the page (``data-rendered``, ``data-draw-ms`` of ``<body>``).
_DRAW = """<script>
(function(){
  const d = JSON.parse(document.getElementById('%(data)s').textContent);
  const t0 = performance.now();
  async function column(b64) {
    const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    const s = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('gzip'));
    return new Float32Array(await new Response(s).arrayBuffer());
  }
  async function figure(f, st, ranges) {
    const opts = {...st.figure, title: f.title, x_axis_label: f.x_label, y_axis_label: f.y_label};
    if (f.x_range != null) opts.x_range = ranges[f.x_range];
    const p = Bokeh.Plotting.figure(opts);
    p.title.text_font_size = st.title_size;
    p.add_tools(new Bokeh.HoverTool(st.hover));
    const sources = [];
    for (const c of f.columns) {
      const data = {};
      for (const [k, v] of Object.entries(c)) data[k] = await column(v);
      sources.push(new Bokeh.ColumnDataSource({data}));
    }
    const every = new Bokeh.AllIndices(), items = new Map();
    for (const [g, name, colour, dash, width, markers] of f.traces) {
      const line = {line_color: colour, line_dash: dash, line_width: width};
      const glyphs = [new Bokeh.Line({x: {field: 'x'}, y: {field: name}, ...line})];
      if (markers) glyphs.push(new Bokeh.Scatter({x: {field: 'x'}, y: {field: name},
        size: st.marker_size, line_color: colour, fill_color: colour, hatch_color: colour}));
      for (const glyph of glyphs) {
        const r = new Bokeh.GlyphRenderer({data_source: sources[g], glyph, name,
          view: new Bokeh.CDSView({filter: every})});
        p.add_renderers(r);
        items.set(name, [...(items.get(name) ?? []), r]);
      }
    }
    if (items.size) {
      const its = [...items].map(([label, renderers]) =>
        new Bokeh.LegendItem({label: {value: label}, renderers}));
      p.add_layout(new Bokeh.Legend({...st.legend, items: its}), 'right');
      p.width = st.figure.width + st.legend_width;
    }
    return p;
  }
  async function lines(l) {
    if (!l.figures.length) return;
    const ranges = {};
    for (const [k, [start, end]] of Object.entries(l.ranges)) ranges[k] = new Bokeh.Range1d({start, end});
    const figs = [];
    for (const f of l.figures) figs.push(await figure(f, l.style, ranges));
    const doc = new Bokeh.Document();
    for (const p of figs) doc.add_root(p);
    const els = l.targets.map((id) => document.getElementById(id));
    await Bokeh.embed.add_document_standalone(doc, els[0], els);
  }
  const drawn = [lines(d.lines)];
  if (d.items.length) drawn.push(Bokeh.embed.embed_items(d.docs, d.items));
  Promise.all(drawn).then(() => {
    requestAnimationFrame(() => setTimeout(() => {
      const ms = performance.now() - t0, b = document.body;
      b.dataset.rendered = String(Number(b.dataset.rendered || 0) + %(n)d);
      b.dataset.drawMs = ms.toFixed(0);
      const el = document.getElementById('%(time)s');
      if (el) el.textContent = '%(n)d figures drawn in ' + ms.toFixed(0) + ' ms';
    }, 0));
  }).catch(e => { document.body.dataset.error = String(e); console.error(e); });
})();
</script>"""


def interactive_block(results: list[Result], prefix: str = "tdv") -> tuple[str, int]:
    """The overlays of ``results`` as HTML to place in a page that already holds
    :func:`bokeh_js` (e.g. a report): (html, number of figures)."""
    styles = Styles()
    figs = run_figures(results, styles) + engine_figures(results, styles)
    figs += sweep_figures(results, styles)
    emb = _Embedder(prefix)
    divs = emb.divs(figs)
    return f"{divs}\n<p class='d' id='{prefix}time'></p>\n{emb.script()}", len(figs)


def add_interactive(page: str, folder: PathLike, label: str | None = None, ds=None) -> str:
    """A report page (:func:`~tribodyn.output.export.report_html`) with the interactive
    traces of the result in ``folder`` (as ``tribodyn view`` draws them) before its
    figures: the Bokeh library inline in the head. The page is returned unchanged if
    the folder has no traces to draw (or no results the explorer can read). ``ds``: the
    Dataset of the folder's results.nc if it is in memory (:func:`load_result`)."""
    try:
        r = load_result(folder, label, ds)
    except InputError:
        return page
    if label is None:
        r.label = str(r.summary.get("case") or r.label)
    block, n = interactive_block([r], prefix="rep")
    if not n:
        return page
    section = (
        "<h2>Interactive traces</h2>\n<p class='d'>Drag to pan, box or wheel zoom, hover "
        "for values, click a legend entry to hide its trace.</p>\n" + block + "\n"
    )
    at = page.find("<h2>Figures</h2>")
    at = at if at >= 0 else page.rfind("</body>")
    page = page[:at] + section + page[at:]
    return page.replace("</head>", bokeh_js() + "\n</head>", 1)


def write_report_html(
    markdown_text: str,
    folder: PathLike,
    path: PathLike | None = None,
    skipped: list[str] | None = None,
    ds=None,
) -> Path:
    """Write ``path`` (default ``folder/report.html``): report.md rendered with its
    figures embedded (:func:`~tribodyn.output.export.report_html`: only regular files of
    ``folder``; the others are appended to ``skipped``) and the interactive traces of the
    result in ``folder`` (:func:`add_interactive`, named by the case; ``ds``: its
    results.nc's Dataset if in memory); written by
    :func:`~tribodyn._safe_write.atomic_write`. The same files give the same bytes."""
    from .export import report_html

    folder = Path(folder)
    page = add_interactive(report_html(markdown_text, folder, skipped), folder, ds=ds)
    return atomic_write(Path(path) if path is not None else folder / "report.html", page)


def build_page(paths: Sequence[PathLike], labels: Sequence[str] | None = None) -> tuple[str, int]:
    """The page (module docstring) of the result folders ``paths``: (html, number of
    figures). ``labels``: names of the results (default: their folder names)."""
    paths = [Path(p) for p in paths]
    if not paths:
        raise InputError("RESULT: give at least one result folder")
    labels = labels or unique_labels(paths)
    results = [load_result(p, lab) for p, lab in zip(paths, labels)]
    esc = html.escape
    body = [
        "<h1>tribodyn: results compared</h1>",
        "<table><tr><th>result</th><th>kind</th><th>case</th><th>folder</th></tr>",
    ]
    for r in results:
        case = r.summary.get("case") or r.ds.attrs.get("title", "")
        speed = r.summary.get("engine_speed_rpm") or r.summary.get("engine", {}).get("speed_rpm")
        extra = f", {speed:g} rpm" if isinstance(speed, int | float) else ""
        body.append(
            f"<tr><td>{esc(r.label)}</td><td>{r.kind}</td><td>{esc(str(case))}{extra}"
            f"</td><td>{esc(str(r.path))}</td></tr>"
        )
    body.append("</table>")
    lines = [(r, v) for r in results for v in verdicts(r)]
    if lines:
        body.append(
            "<h2>Coating verdict</h2><p>Friction energy per cycle of each coated set "
            "against its folder's reference set (negative = less friction).</p><ul>"
        )
        body += [f"<li><b>{esc(r.label)}</b>: {esc(v)}</li>" for r, v in lines]
        body.append("</ul>")
    for kind, title in (("run", "Summary numbers: runs"), ("engine", "Summary numbers: engines")):
        heads, rows = summary_rows(results, kind)
        if heads and rows:
            body.append(f"<h2>{title}</h2><p>Differences in % against the first column.</p>")
            body.append(_table_html(heads, rows))
    styles = Styles()
    sections = (
        ("Traces over crank angle: runs", run_figures(results, styles)),
        ("Camshafts of the engines", engine_figures(results, styles)),
        ("Sweeps", sweep_figures(results, styles)),
    )
    emb = _Embedder("f")
    hint = (
        "<p class='d'>Drag to pan, box or wheel zoom (tool bar), hover for values, "
        "click a legend entry to hide its trace.</p>"
    )
    for title, figs in sections:
        if not figs:
            continue
        body += [f"<h2>{title}</h2>", hint, emb.divs(figs)]
    if len(results) > 1:
        body.append("<h2>Inputs: how the cases differ</h2>")
    for b in results[1:]:
        a = next(r for r in results if r.kind == b.kind)
        if a is b:
            continue
        d = case_diff(a, b)
        head = f"{esc(b.label)} against {esc(a.label)}"
        body.append(
            f"<details open><summary>{head}</summary><pre>{esc(d)}</pre></details>"
            if d
            else f"<p>{head}: the same case file.</p>"
        )
    warn = [(r, w) for r in results for w in _warnings(r)]
    if warn:
        body.append("<h2>Warnings</h2><ul>")
        body += [f"<li><b>{esc(r.label)}</b>: {esc(w)}</li>" for r, w in warn]
        body.append("</ul>")
    body.append("<p class='d' id='ftime'></p>")
    page = (
        "<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'>"
        "<title>tribodyn view</title>"
        f"<style>{_CSS}</style>\n{bokeh_js()}\n</head>\n<body>\n"
        + "\n".join(body)
        + "\n"
        + emb.script()
        + "\n</body></html>\n"
    )
    return page, len(emb.figs)


def _warnings(r: Result) -> list[str]:
    w = r.summary.get("warnings")
    if isinstance(w, list):
        return [str(x) for x in w]
    raw = r.ds.attrs.get("warnings")
    if isinstance(raw, str) and raw:
        try:
            v = json.loads(raw)
            return [str(x) for x in v] if isinstance(v, list) else [raw]
        except json.JSONDecodeError:
            return [raw]
    return []


def default_page_path(folder: Path = Path(".")) -> Path:
    """``tribodyn_view.html`` in ``folder``, or the first free ``tribodyn_view-N.html``."""
    p = folder / "tribodyn_view.html"
    k = 2
    while p.exists():
        p = folder / f"tribodyn_view-{k}.html"
        k += 1
    return p


def write_page(text: str, path: PathLike, *, force: bool = False) -> Path:
    """Write ``text`` to ``path`` atomically: into a new temporary file in the same
    folder, then renamed into place. An existing ``path`` is refused
    (:class:`InputError`) unless ``force``; without it the final step links the file
    into place, so a file that appears meanwhile is not replaced either."""
    path = Path(path)
    if path.is_dir():
        raise InputError(f"-o/--out {str(path)!r} is a folder; give the page's file name")
    if path.exists() and not force:
        raise InputError(
            f"-o/--out {str(path)!r} exists; give another name or --force to replace it"
        )
    if not path.parent.is_dir():
        raise InputError(f"-o/--out {str(path)!r}: the folder {str(path.parent)!r} does not exist")
    try:
        atomic_write(path, text, replace=force)
    except FileExistsError:
        raise InputError(f"-o/--out {str(path)!r} appeared while writing; not replaced") from None
    return path
