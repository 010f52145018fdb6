"""The route and final-glide figures read on their own (issue 11, "What users see").

References: the figures' contract — the title states the problem (field, water speed, start,
goal, departure / polar, distance, bearing, MacCready, wind) and the answer with the result's
own numbers; legends and the current-arrow key lie outside the data axes (window extents
compared after a draw); the route's aspect gives equal ground distances; land (NaN) is shaded
where the field has no data; the wind arrow points where the wind blows. Hand derivations are
given where a number is checked.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from glideplan.fields import UniformField, open_field
from glideplan.fields.synthetic import copernicus_dataset
from glideplan.geodesy import LocalProjection
from glideplan.routing.route import RouteResult

T0 = np.datetime64("2026-03-01T00:00", "ns")
TIMES = T0 + np.arange(31) * np.timedelta64(3600, "s")
LAT = np.linspace(44.0, 45.0, 21)
LON = np.linspace(-9.0, -8.0, 21)
START, GOAL = (44.5, -8.9), (44.5, -8.5)
WGS84_E2 = 0.00669437999014  # first eccentricity squared


def _box(artist, fig):
    return artist.get_window_extent(fig.canvas.get_renderer())


def _outside(box, axes_box) -> bool:
    return box.x1 <= axes_box.x0 or box.x0 >= axes_box.x1 or box.y1 <= axes_box.y0 \
        or box.y0 >= axes_box.y1


@pytest.fixture(scope="module")
def land_route(tmp_path_factory):
    """A 0.1 m/s eastward current with a NaN block (land) north of the start-goal line."""
    from glideplan.routing import route

    u = np.full((TIMES.size, 1, LAT.size, LON.size), 0.1)
    u[:, :, 11:14, 5:8] = np.nan  # lat 44.55-44.65, lon -8.75--8.65
    path = tmp_path_factory.mktemp("route_fig") / "cur.nc"
    copernicus_dataset(LAT, LON, TIMES, [0.5], u, np.where(np.isnan(u), np.nan, 0.0)).to_netcdf(
        path)
    fld = open_field(path)
    result = route(fld, START, GOAL, 0.4, depart=np.datetime64("2026-03-01T06:00"),
                   resolution=1500)
    assert result.ok, result.message
    return result, fld


def test_route_title_states_problem_and_answer(land_route):
    """The title carries the field's file name, the water speed, start and goal, the departure
    and the result's duration (h), distance (km), endpoint error (m) and, when the straight
    line is blocked, says so."""
    import matplotlib.pyplot as plt

    from glideplan.routing.plot import route_figure

    r, fld = land_route
    fig = route_figure(r, fld, speed=0.4, start=START, goal=GOAL)
    title = fig.axes[0].get_title(loc="left")
    plt.close(fig)
    flat = " ".join(title.split())
    for text in ("cur.nc", "water speed 0.4 m/s", "from 44.5°N 8.9°W", "to 44.5°N 8.5°W",
                 "departing 2026-03-01T06:00Z", f"solved: {r.duration_s / 3600:.2f} h",
                 f"over {r.distance_m / 1000:.4g} km",
                 f"endpoint error {r.endpoint_error_m:.3g} m"):
        assert text in flat, (text, flat)
    if r.straight_line_duration_s is None:
        assert "no straight-line crossing" in flat
    else:
        assert f"crabbing {r.straight_line_duration_s / 3600:.2f} h" in flat


def test_route_legend_key_outside_and_land_shaded(land_route):
    """Legend and quiver key lie outside the axes; the legend names the current's time; the
    shaded land contains the NaN block as the router sees it (44.57 N, 8.7 W) and not open
    water south of the line (44.45 N, 8.7 W); the aspect is the WGS84 ratio of a degree of
    latitude to one of longitude at the frame's mean latitude, by hand
    (1 - e^2) / ((1 - e^2 sin^2 phi) cos phi), within 1e-4 (the plot measures geodesic
    lengths of 0.1-degree steps)."""
    import matplotlib.pyplot as plt
    from matplotlib.quiver import QuiverKey

    from glideplan.routing.plot import _LAND_COLOUR, route_figure

    r, fld = land_route
    fig = route_figure(r, fld, speed=0.4, start=START, goal=GOAL)
    ax = fig.axes[0]
    fig.canvas.draw()
    axes_box = _box(ax, fig)
    legend = ax.get_legend()
    assert legend is not None and _outside(_box(legend, fig), axes_box)
    texts = [t.get_text() for t in legend.get_texts()]
    assert "current at departure, 2026-03-01T06:00Z" in texts
    assert "land (no current data)" in texts
    assert any(t.startswith("start, heading") for t in texts)
    keys = [a for a in ax.artists if isinstance(a, QuiverKey)]
    assert len(keys) == 1 and keys[0].text.get_text().endswith("m/s")
    assert _outside(_box(keys[0], fig), axes_box)
    land = [c for c in ax.collections if hasattr(c, "levels")]
    assert land, "no land contour"
    paths = land[0].get_paths()
    assert np.allclose(land[0].get_facecolor()[0][:3],
                       [int(_LAND_COLOUR[i:i + 2], 16) / 255 for i in (1, 3, 5)])
    assert any(p.contains_point((-8.7, 44.57)) for p in paths)
    assert not any(p.contains_point((-8.7, 44.45)) for p in paths)
    phi = math.radians(0.5 * sum(ax.get_ylim()))
    expected = (1 - WGS84_E2) / ((1 - WGS84_E2 * math.sin(phi) ** 2) * math.cos(phi))
    assert ax.get_aspect() == pytest.approx(expected, rel=1e-4)
    plt.close(fig)


def _hand_route(speed: float, heading_deg: float, current: tuple[float, float]) -> RouteResult:
    """A straight route built by hand: ground velocity = V (sin h, cos h) + c, positions in
    the aeqd plane about START (pyproj), 2 h in 10-min steps."""
    t = np.arange(0.0, 7201.0, 600.0)
    h = math.radians(heading_deg)
    x = (speed * math.sin(h) + current[0]) * t
    y = (speed * math.cos(h) + current[1]) * t
    lat, lon = LocalProjection(*START).to_geographic(x, y)
    from glideplan.track import Track

    track = Track(t, x, y, np.full(t.size, math.pi / 2 - h), lat=lat, lon=lon)
    return RouteResult(
        status="solved", depart=np.datetime64("2026-03-01T06:00", "ms"), depart_s=0.0,
        duration_s=float(t[-1]), distance_m=float(np.hypot(x[-1], y[-1])), track=track,
        endpoint_error_m=1.5, straight_line_duration_s=9000.0, method="grid",
        field_info={"kind": "uniform"},
    )


def test_water_speed_is_recovered_from_the_track():
    """V = |v_ground - c| by construction (V = 0.7 m/s, heading 60 deg, c = (0.1, 0.05) m/s);
    recovered within 1e-3 relative (the local metres-per-degree scale vs. the aeqd plane over
    ~6 km). The title then says the speed came from the track and compares with the straight
    line: 1 - 7200 / 9000 = 20% less time."""
    import matplotlib.pyplot as plt

    from glideplan.routing.plot import route_figure, water_speed_from_track

    fld = UniformField(0.1, 0.05)
    r = _hand_route(0.7, 60.0, (0.1, 0.05))
    assert water_speed_from_track(r, fld) == pytest.approx(0.7, rel=1e-3)
    fig = route_figure(r, fld)
    title = " ".join(fig.axes[0].get_title(loc="left").split())
    plt.close(fig)
    assert "water speed 0.7 m/s (from the track)" in title
    assert "2.00 h" in title and "crabbing 2.50 h" in title and "20% less time" in title
    assert "endpoint error 1.5 m" in title


def test_unreachable_route_title_says_so(tmp_path):
    """No track: the title says unreachable with the router's message, and the frame is the
    field's extent when no start or goal is given."""
    import matplotlib.pyplot as plt

    from glideplan.routing.plot import route_figure

    fld = UniformField(0.0, 0.0)
    msg = "the goal is not reachable by 2026-03-03T00:00:00Z: the reachable set came within 4511 m"
    r = RouteResult(status="unreachable", best_distance_m=4511.0,
                    field_info={"kind": "uniform"}, message=msg)
    fig = route_figure(r, fld, speed=0.5, start=START, goal=GOAL)
    title = " ".join(fig.axes[0].get_title(loc="left").split())
    plt.close(fig)
    assert f"unreachable: {msg}" in title and "solved" not in title


def _glide(arrival: float | None, wind: tuple[float, float] | None):
    from glideplan.sailplane import polar_from_file, read_plr
    from glideplan.sailplane.request import final_glide
    from glideplan.units import wind_from_compass

    polar = polar_from_file(read_plr("tests/data/polars/DG-1001M_ch5.plr"))
    res = final_glide(polar, (47.0, 8.0, 1500.0), (47.2, 8.1, 450.0), mc=1.0,
                      wind=None if wind is None else wind_from_compass(*wind),
                      arrival_heading=arrival)
    return res.to_dict(), res.drawing


def _wind_annotations(ax):
    """(label texts, arrow directions in display points) of the wind annotations of `ax`."""
    texts = [c.get_text() for c in ax.texts if c.get_text().startswith("wind")]
    arrows = [-np.asarray(c.xyann, dtype=float) for c in ax.texts
              if c.get_text() == "" and c.arrow_patch is not None
              and c.arrow_patch.get_edgecolor()[:3] == pytest.approx((0.122, 0.467, 0.706),
                                                                     abs=2e-3)]
    return texts, arrows


@pytest.mark.parametrize("arrival", [190.0, None])
def test_glide_figure_shows_the_wind(arrival):
    """The wind travels in the drawing data (8 m/s from 270 deg) to the title and to an arrow
    on the ground-track panel that points east (a wind from 270 deg blows towards 090: display
    direction (1, 0)), away from the track; the title states bearing, MC and the answer; the
    legends lie below the panels."""
    import matplotlib.pyplot as plt

    from glideplan.sailplane.plot import final_glide_figure

    data, d = _glide(arrival, (8.0, 270.0))
    assert d.wind == pytest.approx((8.0, 0.0), abs=1e-12)  # from 270 deg: towards the east
    fig = final_glide_figure(d)
    title = fig.get_suptitle()
    assert "wind 8 m/s from 270°" in title
    assert f"bearing {data['bearing_deg']:.0f}°" in title and "MC 1 m/s" in title
    assert f"altitude loss {data['altitude_loss_m']:.0f} m" in title
    if arrival is not None:
        assert f"arrival heading 190° (path {data['word']}" in title
    track_ax = fig.axes[0]
    texts, arrows = _wind_annotations(track_ax)
    assert texts == ["wind 8 m/s\nfrom 270°"]
    assert len(arrows) == 1
    direction = arrows[0] / np.linalg.norm(arrows[0])
    assert direction == pytest.approx([1.0, 0.0], abs=1e-9)
    # the arrow sits in a corner at least 0.2 of the panel away from every track point
    ann = next(c for c in track_ax.texts if c.get_text().startswith("wind"))
    pts = track_ax.transAxes.inverted().transform(
        track_ax.transData.transform(np.column_stack([d.x / 1000, d.y / 1000])))
    assert float(np.min(np.hypot(*(pts - np.asarray(ann.xy)).T))) > 0.2
    fig.canvas.draw()
    for ax in fig.axes[:2]:
        assert ax.get_legend() is not None
        assert _box(ax.get_legend(), fig).y1 <= _box(ax, fig).y0
    plt.close(fig)


def test_glide_wind_arrow_direction_and_calm():
    """A wind from 045 deg blows towards 225 deg: display direction (-1, -1) / sqrt 2 on the
    equal-aspect east/north panel; with no wind the title says "no wind" and no arrow is drawn."""
    import matplotlib.pyplot as plt

    from glideplan.sailplane.plot import final_glide_figure
    from glideplan.sailplane.request import FinalGlideDrawing
    from glideplan.units import wind_from_compass

    x = np.linspace(0.0, 8000.0, 20)
    base = {"x": x, "y": 0.5 * x, "distance": np.hypot(x, 0.5 * x),
            "altitude": np.linspace(1500.0, 900.0, 20), "goal_elevation": 450.0,
            "safety_height": 300.0, "title": "test glide"}
    fig = final_glide_figure(FinalGlideDrawing(**base, wind=wind_from_compass(5.0, 45.0)))
    texts, arrows = _wind_annotations(fig.axes[0])
    assert texts == ["wind 5 m/s\nfrom 45°"] and "wind 5 m/s from 45°" in fig.get_suptitle()
    assert arrows[0] / np.linalg.norm(arrows[0]) == pytest.approx(
        [-math.sqrt(0.5), -math.sqrt(0.5)], abs=1e-9)
    plt.close(fig)
    fig = final_glide_figure(FinalGlideDrawing(**base))
    texts, arrows = _wind_annotations(fig.axes[0])
    assert "no wind" in fig.get_suptitle() and texts == [] and arrows == []
    plt.close(fig)


def test_glide_unreachable_keeps_the_start_altitude():
    """A 60 m/s headwind (from the goal's bearing, 19 deg) beats every airspeed of the polar:
    the figure says unreachable, shows the start altitude 1500 m, and still shows the wind."""
    import matplotlib.pyplot as plt

    from glideplan.sailplane.plot import final_glide_figure

    data, d = _glide(None, (60.0, 19.0))
    assert data["status"] == "unreachable" and data["altitude_loss_m"] is None
    assert d.altitude[0] == 1500.0 and np.isnan(d.altitude[-1])
    fig = final_glide_figure(d)
    title = fig.get_suptitle()
    assert "goal unreachable in this wind; start 1500 m" in title
    assert "wind 60 m/s from 19°" in title
    plt.close(fig)
