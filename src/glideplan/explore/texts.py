"""The explorer's HTML: its style sheet, the result strip, the candidates table, messages.

Test hooks: the optimal cost is in `gp-cost` (10 significant digits), the word in `gp-word`,
the method that answered in `gp-method`,
each message in `gp-error`, the busy note in `gp-busy`.
"""

from __future__ import annotations

import html
from typing import Any

import panel as pn

from glideplan.explore.solve import View, cost_unit

__all__ = ["PAGE_CSS", "FastHtml", "error_html", "html_pane", "strip_html", "table_html"]

PAGE_CSS = """
:host { font-family: system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; }
.gp-strip { display: flex; flex-wrap: wrap; gap: 6px 22px; align-items: baseline;
  padding: 8px 12px; background: #f4f7fb; border: 1px solid #d6e0ec; border-radius: 6px; }
.gp-item { display: flex; flex-direction: column; }
.gp-item .gp-k { font-size: 11px; color: #5b6b7b; text-transform: uppercase;
  letter-spacing: .04em; }
.gp-item .gp-v { font-size: 17px; color: #1b2733; font-variant-numeric: tabular-nums; }
.gp-cost, .gp-word { font-weight: 600; }
.gp-small { font-size: 13px !important; color: #3b4a59 !important; }
.gp-status-bad { color: #b03a2e !important; }
.gp-warn { font-size: 12.5px !important; color: #8a5a00 !important; max-width: 46em; }
.gp-error { color: #b03a2e; font-size: 12.5px; line-height: 1.3; margin: -2px 0 4px 2px; }
.gp-stale .gp-v { opacity: .45; }
.gp-stale { background: repeating-linear-gradient(-45deg, #f4f7fb, #f4f7fb 8px, #e9eff7 8px,
  #e9eff7 16px); }
.gp-computing { align-self: center; }
.gp-busy { color: #1f5fa8; font-size: 13px; font-weight: 600; }
.gp-busy::before { content: ""; display: inline-block; width: 10px; height: 10px;
  margin-right: 6px; border: 2px solid #1f5fa8; border-right-color: transparent;
  border-radius: 50%; animation: gp-spin .8s linear infinite; vertical-align: -1px; }
@keyframes gp-spin { to { transform: rotate(360deg); } }
.gp-table-wrap { max-height: 260px; overflow-y: auto; border: 1px solid #d6e0ec;
  border-radius: 6px; }
.gp-table { border-collapse: collapse; width: 100%; font-size: 13px;
  font-variant-numeric: tabular-nums; }
.gp-table th { position: sticky; top: 0; background: #eef3f9; text-align: left;
  padding: 4px 8px; color: #3b4a59; }
.gp-table td { padding: 3px 8px; border-top: 1px solid #edf1f6; }
.gp-table tr.gp-opt td { background: #e4efff; font-weight: 600; color: #1f5fa8; }
.gp-help { font-size: 12px; color: #5b6b7b; line-height: 1.35; }
.gp-title { font-size: 20px; font-weight: 650; color: #fff; }
.gp-sub { font-size: 12.5px; color: #d8e4f2; }
"""


def html_pane(text: str = "", **kw: Any) -> pn.pane.HTML:
    return pn.pane.HTML(text, stylesheets=[PAGE_CSS], margin=(0, 5), **kw)


def error_html(message: str) -> str:
    return f'<div class="gp-error">{html.escape(message)}</div>' if message else ""


def table_html(cands: dict[str, list[Any]]) -> str:
    """The candidates table: rank, word, family, cost and status (optimal first)."""
    rows = []
    for i in range(len(cands["word"])):
        cls = ' class="gp-opt"' if cands["status"][i] == "optimal" else ""
        cells = (
            cands["rank"][i],
            cands["word"][i],
            cands["family"][i],
            cands["cost_text"][i] or "&ndash;",
            cands["status"][i],
        )
        rows.append(
            f"<tr{cls}>"
            + "".join(f"<td>{html.escape(str(c)) if c != '&ndash;' else c}</td>" for c in cells)
            + "</tr>"
        )
    head = "".join(f"<th>{h}</th>" for h in ("#", "word", "family", "cost", "status"))
    return (
        '<div class="gp-help"><b>Candidates</b> (hover a grey path for its word and cost)</div>'
        f'<div class="gp-table-wrap"><table class="gp-table"><thead><tr>{head}</tr></thead>'
        f"<tbody>{''.join(rows)}</tbody></table></div>"
    )


def strip_html(view: View, stale: bool = False) -> str:
    """The result strip: cost, word, family, status, endpoint error, planner time.

    The cost's header names the objective and its unit from the planner (not from the
    result: an error keeps it); `stale` greys the values and says "computing" while a newer
    state is being planned.
    """
    objective = view.entry.objective if view.entry else ""
    unit = cost_unit(view.entry)
    header = ", ".join(t for t in (objective, unit) if t)
    status = html.escape(view.status or "")
    bad = "" if view.ok else " gp-status-bad"

    def item(k: str, v: str, cls: str = "") -> str:
        return (
            f'<div class="gp-item"><span class="gp-k">{k}</span>'
            f'<span class="gp-v {cls}">{v}</span></div>'
        )

    busy = (
        '<div class="gp-item gp-computing"><span class="gp-busy">computing&hellip;</span></div>'
        if stale
        else ""
    )
    return (
        f'<div class="gp-strip{" gp-stale" if stale else ""}">'
        + item(f"cost ({header})" if header else "cost", html.escape(view.cost_text), "gp-cost")
        + item("word", html.escape(view.word) or "&ndash;", "gp-word")
        + item("family", html.escape(view.family) or "&ndash;", "gp-family")
        + item("status", status, "gp-small gp-status" + bad)
        + item("method", html.escape(view.method_text) or "&ndash;", "gp-small gp-method")
        + item("endpoint error", html.escape(view.endpoint_text), "gp-small gp-endpoint")
        + item("time", html.escape(view.time_text), "gp-small gp-time")
        + busy
        + "</div>"
    )


class FastHtml:
    """HTML shown in a Bokeh `Div` and updated without re-laying out the page.

    `.object = text` (as Panel's HTML pane) changes one column of a small data source; in the
    browser a callback writes it into the Div's element (and, silently, into its `text`), so
    a new result costs one innerHTML, not Bokeh's re-render and layout pass of the page.
    """

    def __init__(self, text: str = "", **kw: Any) -> None:
        from bokeh.models import ColumnDataSource, CustomJS
        from bokeh.models.widgets import Div

        self.src = ColumnDataSource({"html": [text]})
        self.model = Div(
            text=text,
            stylesheets=[PAGE_CSS],
            sizing_mode="stretch_width",
            margin=(0, 5),
            tags=[self.src],
            **kw,
        )
        self.src.js_on_change("data", CustomJS(args={"div": self.model}, code=_FAST_HTML_JS))
        self.pane = pn.pane.Bokeh(self.model, sizing_mode="stretch_width")
        self._text = text

    @property
    def object(self) -> str:
        return self._text

    @object.setter
    def object(self, text: str) -> None:
        if text != self._text:
            self._text = text
            if self.model.document is None:  # not shown yet: the page is built with it
                self.model.text = text
            self.src.data = {"html": [text]}

    def sync(self) -> None:
        """Put the latest text into the Div itself (once the page is shown: a result that
        arrived while the browser was still building the page never reached it)."""
        if self.model.text != self._text:
            self.model.text = self._text


_FAST_HTML_JS = """
const html = cb_obj.data.html[0];
let view = null;
for (const root of Bokeh.index.roots) {
  const stack = [root];
  while (stack.length && view == null) {
    const v = stack.pop();
    if (v.model === div) { view = v; break; }
    for (const c of (v.child_views || [])) stack.push(c);
  }
  if (view != null) break;
}
if (view != null && view.markup_el != null) {
  div.setv({text: html}, {silent: true});
  view.markup_el.innerHTML = html;
} else {
  div.text = html;
}
"""
