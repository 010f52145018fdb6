"""The explorer's layout pieces shared by the plane page (`app`) and the map pages
(`map_page`): the CSS of the wrapping flex layout, the map modes, the immediate text box and
the `view=` link parser. Both import from here, so neither imports the other for them.
"""

from __future__ import annotations

import math

import panel as pn

__all__ = ["BODY_CSS", "LAYOUT_CSS", "MAIN_CSS", "MAP_MODES", "NOT_BUSY", "PLOT_CSS", "RIGHT_CSS",
           "ROOT_CSS", "SIDEBAR_CSS", "SIDE_WIDTH"]

# The layout: the sidebar (controls) and the main column (plot, results) wrap; below
# 760 px the plot comes first (above the controls) and is then about as tall as wide.
SIDE_WIDTH = 320
LAYOUT_CSS = """
:host { width: 100%; max-width: 100vw; }
"""
SIDEBAR_CSS = f"""
:host {{ flex: 0 0 {SIDE_WIDTH}px; width: {SIDE_WIDTH}px; }}
@media (max-width: 760px) {{ :host {{ flex: 1 1 100%; width: calc(100vw - 16px) !important; }} }}
"""
MAIN_CSS = """
:host { flex: 1 1 600px; min-width: 0; }
@media (max-width: 760px) { :host { width: calc(100vw - 16px) !important; flex: 1 1 100%;
  order: -1; } }
"""
BODY_CSS = """
:host { width: 100%; }
"""
PLOT_CSS = """
:host { flex: 1 1 420px; min-width: 260px; height: max(300px, calc(100vh - 160px)) !important; }
@media (max-width: 760px) { :host { flex: 0 0 auto; width: calc(100vw - 24px) !important;
  height: min(calc(100vw - 24px), 80vh) !important; } }
"""
RIGHT_CSS = """
:host { flex: 0 1 420px; min-width: 280px; }
@media (max-width: 760px) { :host { width: calc(100vw - 24px) !important; min-width: 0;
  flex: 0 0 auto; } }
"""
ROOT_CSS = """
:host { overflow-x: hidden; max-width: 100vw; }
"""



# The map modes offered beside the planners (label -> key); `create_page` switches to them.
MAP_MODES: dict[str, str] = {
    "Route through currents or winds (lat/lon map)": "route",
    "Mission: waypoints of a route file (lat/lon map)": "mission",
    "Glide reach over terrain in wind (lat/lon map)": "reach",
}


# A widget's value change skips Panel's global busy counter (`pn.state.busy`, unused by these
# pages): its bookkeeping (`edit_readonly` on `pn.state`, ~400 parameter writes) cost 0.85 of
# 1.27 ms CPU per typed value (measured at load 21).
NOT_BUSY = ["value", "value_input"]


class _TextInput(pn.widgets.TextInput):
    """A text box whose entered value reaches the server at once (Panel waits 50 ms)."""

    _debounce = 0
    _busy__ignore = NOT_BUSY


def _parse_view(text: str | None) -> tuple[float, float, float, float] | None:
    """`view=x0,y0,x1,y1` of a link (the zoom), or None when absent or not four finite
    numbers with x0 < x1 and y0 < y1."""
    if not text:
        return None
    try:
        x0, y0, x1, y1 = (float(v) for v in text.split(","))
    except ValueError:
        return None
    ok = all(math.isfinite(v) for v in (x0, y0, x1, y1)) and x0 < x1 and y0 < y1
    return (x0, y0, x1, y1) if ok else None
