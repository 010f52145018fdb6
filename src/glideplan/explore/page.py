"""The explorer's page of one browser session: the plane planners' page (`app.Explorer`) or a
map mode (route, mission, reach), switched in place, with one browser history entry per
planner switch (Back returns to the previous planner's page) and the viewport tag for phones.
"""

from __future__ import annotations

from typing import Any

import panel as pn

from glideplan.explore.app import Explorer
from glideplan.explore.catalog import Catalog, build_catalog
from glideplan.explore.layout import MAP_MODES, ROOT_CSS
from glideplan.explore.state import state_to_query

__all__ = ["create_page"]

# The page's frame: a viewport tag for phones and the layout's media rules. Wide screens
# put the controls (320 px) left of the result strip and the plot, whose height is the
# window's less the header and the strip (so the x axis stays above the fold); below
# 760 px (a phone) the strip and the plot come first, about as tall as wide, the controls
# below them (flex `order`).
VIEWPORT_TEMPLATE = """{% extends base %}
{% block preamble %}{{ super() }}
<meta name="viewport" content="width=device-width, initial-scale=1">
{% endblock %}"""


_HISTORY_JS = """
if (!window._gp_popstate) {  // Back/Forward between planners: load that page
  window._gp_popstate = true;
  window.addEventListener('popstate', () => window.location.reload());
}
const q = cb_obj.tags[0];
if (q) window.history.pushState(null, '', window.location.pathname + q);
"""


class _History:
    """One browser history entry per planner switch: `push(query)` adds it (the page's own
    address updates then replace it as the user edits, drags and zooms); Back reloads the
    previous planner's page."""

    def __init__(self) -> None:
        from bokeh.models import CustomJS
        from bokeh.models.widgets import Div

        self.model = Div(text="", visible=False, tags=[])
        self.model.js_on_change("tags", CustomJS(code=_HISTORY_JS))
        self.pane = pn.pane.Bokeh(self.model, visible=False, margin=0)
        self.count = 0

    def push(self, query: str) -> None:
        self.count += 1
        self.model.tags = [query, self.count]

    def arm(self) -> None:
        """Listen for Back/Forward (once the page has loaded), adding no entry."""
        self.push("")


def create_page(catalog: Catalog | None = None, **map_kw: Any) -> pn.viewable.Viewable:
    """The page of one session, its state read from the URL query (`planner=route` is the
    route map; `map_kw` go to it: the field file of `explore --field`)."""
    args = pn.state.session_args or {}
    query = {
        k: v[0].decode() if isinstance(v[0], bytes) else str(v[0]) for k, v in args.items() if v
    }
    catalog = catalog or build_catalog()
    from glideplan.explore.worker import local_dist

    local_dist(pn.state.curdoc)  # before any model is made: every style sheet local
    root = pn.Column(sizing_mode="stretch_width", margin=0, stylesheets=[ROOT_CSS])
    pages: dict[str, Any] = {}

    history = _History()

    def switch(key: str) -> None:
        show(key, {"planner": key})
        history.push(f"?planner={key}")

    def show(mode: str, q: dict[str, str]) -> None:
        if "current" in pages:  # the page left behind: its running work is cancelled
            pages["current"]._closed = True
        if mode == "route":
            from glideplan.explore.route_page import RoutePage

            page: Any = RoutePage(q, field_path=map_kw.get("field_path"))
        elif mode == "mission":
            from glideplan.explore.mission_page import MissionPage

            page = MissionPage(q, route_path=map_kw.get("route_path"))
        elif mode == "reach":
            from glideplan.explore.reach_page import ReachPage

            page = ReachPage(q)
        else:
            page = Explorer(catalog, q)
        page.on_mode = lambda key: switch(key)
        if isinstance(page, Explorer):
            # the entry holds the new planner's whole link: its answer (and the address it
            # sets) comes in the same message as the switch, before this entry is pushed
            page.on_switch = lambda st: history.push("?" + state_to_query(catalog, st))
        pages["current"] = page
        root.objects = [page.layout, history.pane]
        page.push_url()

    asked = query.get("planner", "")
    show(asked if asked in MAP_MODES.values() else "plane", query)
    def loaded() -> None:
        from glideplan.explore.worker import local_styles, resend_data

        pages["current"].push_url()
        page = pages["current"]  # an answer whose delivery was lost, held as the others
        page._held(page.deliver_pending)
        resend_data(pn.state.curdoc)  # an answer that came while the page was built
        history.arm()
        local_styles(pn.state.curdoc)

    pn.state.onload(loaded)
    doc = pn.state.curdoc
    if doc is not None:
        import jinja2

        doc.template = jinja2.Template(VIEWPORT_TEMPLATE)
    return root
