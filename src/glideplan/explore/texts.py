"""The explorer's HTML: its style sheet, the result strip, the candidates table, messages.

Test hooks: the optimal cost is in `gp-cost` (10 significant digits), the word in `gp-word`,
each message in `gp-error`, the busy note in `gp-busy`.
"""

from __future__ import annotations

import html
from typing import Any

import panel as pn

from glideplan.explore.solve import View

__all__ = ["PAGE_CSS", "error_html", "html_pane", "strip_html", "table_html"]

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
.gp-error { color: #b03a2e; font-size: 12.5px; line-height: 1.3; margin: -2px 0 4px 2px; }
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


def strip_html(view: View) -> str:
    """The result strip: cost, word, family, status, endpoint error, planner time."""
    unit = (
        {"length": "m", "time": "s", "altitude": "m"}.get(view.entry.objective, "")
        if view.entry
        else ""
    )
    if not view.units and view.entry is not None and view.entry.objective != "time":
        unit = "(nondim.)"
    objective = view.entry.objective if view.entry else ""
    status = html.escape(view.status or "")
    bad = "" if view.ok else " gp-status-bad"

    def item(k: str, v: str, cls: str = "") -> str:
        return (
            f'<div class="gp-item"><span class="gp-k">{k}</span>'
            f'<span class="gp-v {cls}">{v}</span></div>'
        )

    return (
        '<div class="gp-strip">'
        + item(f"cost ({objective}, {unit})", html.escape(view.cost_text), "gp-cost")
        + item("word", html.escape(view.word) or "&ndash;", "gp-word")
        + item("family", html.escape(view.family) or "&ndash;", "gp-family")
        + item("status", status, "gp-small gp-status" + bad)
        + item("endpoint error", html.escape(view.endpoint_text), "gp-small gp-endpoint")
        + item("time", html.escape(view.time_text), "gp-small gp-time")
        + "</div>"
    )
