"""The route map's layers over its figure: the current arrows coloured by speed with their
key, the isochrones with their labels, the route (and a route not verified, dashed) and the
vehicle at the slider's time. Each function adds its glyphs and returns their data sources.
"""

from __future__ import annotations

from typing import Any

from bokeh.models import ColumnDataSource

__all__ = ["current_layer", "isochrone_layer", "route_layers"]


def current_layer(fig: Any) -> Any:
    """Current arrows (segments and heads) coloured by speed, with the colour key: the
    arrows' source and the colour mapper (its `high` follows the field)."""
    arrow_src = ColumnDataSource(
        {"x0": [], "y0": [], "x1": [], "y1": [], "angle": [], "speed": []}
    )
    # current speed coloured (cividis: ordered, colour-blind safe) with its key at the right
    from bokeh.models import LinearColorMapper
    from bokeh.models.annotations import ColorBar
    from bokeh.palettes import Cividis256

    speed_mapper = LinearColorMapper(palette=Cividis256[::-1][40:], low=0.0, high=1.0)
    colour = {"field": "speed", "transform": speed_mapper}
    fig.segment(
        "x0",
        "y0",
        "x1",
        "y1",
        source=arrow_src,
        line_color=colour,
        line_alpha=0.8,
        line_width=1.6,
        legend_label="current",
    )
    fig.scatter(
        "x1",
        "y1",
        source=arrow_src,
        marker="triangle",
        size=6,
        angle="angle",
        fill_color=colour,
        line_color=colour,
        fill_alpha=0.8,
        line_alpha=0.8,
    )
    fig.add_layout(
        ColorBar(color_mapper=speed_mapper, title="current (m/s)", width=10,
                 title_text_font_size="11px", major_label_text_font_size="10px"),
        "right",
    )
    return arrow_src, speed_mapper


def isochrone_layer(fig: Any) -> Any:
    """Isochrones (dashed) and their labels: the two sources."""
    iso_src = ColumnDataSource({"xs": [], "ys": [], "label": []})
    fig.multi_line(
        "xs",
        "ys",
        source=iso_src,
        line_color="#8e44ad",
        line_alpha=0.55,
        line_width=1.3,
        line_dash="dashed",
        legend_label="isochrones",
    )
    iso_label_src = ColumnDataSource({"x": [], "y": [], "text": []})
    fig.text(
        "x",
        "y",
        "text",
        source=iso_label_src,
        text_font_size="10px",
        text_color="#6c3483",
        text_baseline="middle",
    )
    return iso_src, iso_label_src


def route_layers(fig: Any) -> Any:
    """The route, a route the re-integration did not confirm (dashed, muted, labelled) and
    the vehicle at the slider's time: the three sources."""
    route_src = ColumnDataSource({"x": [], "y": []}, name="gp-answer")
    fig.line(
        "x",
        "y",
        source=route_src,
        line_color="#1f5fa8",
        line_width=3.5,
        legend_label="route",
    )
    # a route the re-integration did not confirm: dashed, muted and labelled as such
    unverified_src = ColumnDataSource({"x": [], "y": []})
    fig.line(
        "x",
        "y",
        source=unverified_src,
        line_color="#b9770e",
        line_width=3,
        line_dash="dashed",
        line_alpha=0.75,
        legend_label="route (not verified)",
    )
    vehicle_src = ColumnDataSource({"x": [], "y": [], "text": []})
    fig.scatter("x", "y", source=vehicle_src, marker="diamond", size=16,
                fill_color="#f39c12", line_color="#1b2733", line_width=1.5,
                legend_label="vehicle at the slider's time")
    fig.text("x", "y", "text", source=vehicle_src, x_offset=10, y_offset=10,
             text_font_size="11px", text_color="#1b2733")
    return route_src, unverified_src, vehicle_src
