"""What a reader sees in the figures: the title states problem and answer, axes carry units,
paths are drawn with equal aspect, start and goal are marked, and no legend covers the data.

The references are the figures' own contract (issue 11, "What users see"): a legend's box
must lie outside every data axes of its figure (window extents compared after a draw), and
the numbers printed in a title must be the solution's.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from glideplan.planning import plan
from glideplan.pose import Pose
from glideplan.vehicles.dubins_car import DubinsCar


def _extent(artist, fig):
    return artist.get_window_extent(fig.canvas.get_renderer())


def _overlaps(a, b) -> bool:
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


def _assert_legends_outside(fig) -> list[str]:
    """Every legend of `fig` lies outside every (non-inset) axes and off every axis label;
    returns the legend texts."""
    fig.canvas.draw()
    axes = [ax for ax in fig.axes if ax.get_label() != "<inset>"]
    texts: list[str] = []
    legends = [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None]
    assert legends, "the figure has no legend"
    for legend in legends:
        box = _extent(legend, fig)
        for ax in axes:
            assert not _overlaps(box, _extent(ax, fig)), (
                f"legend {[t.get_text() for t in legend.get_texts()][:2]} covers "
                f"axes {ax.get_title()!r}"
            )
            for label in (ax.xaxis.label, ax.yaxis.label):
                if label.get_text():
                    assert not _overlaps(box, _extent(label, fig)), (
                        f"legend covers the axis label {label.get_text()!r}"
                    )
        texts += [t.get_text() for t in legend.get_texts()]
    return texts


def test_min_altitude_figure_states_the_problem_and_legend_is_below_the_paths():
    """`plan min-altitude --plot` (Figs 5.5-5.7): title with vehicle, goal in R_stf, word,
    family and altitude loss in m; path axes in R_stf with equal aspect; start and goal
    marked; the legend below the path axes, outside every axes."""
    from glideplan.figures.ch5 import plan_example, solution_figure

    sol = plan_example("fig5.5")
    fig = solution_figure(sol)
    title = fig.get_suptitle()
    assert "glider (quadratic polar)" in title
    assert "goal (0, 1) R_stf, 120 deg" in title
    assert f"optimal word {sol.word}, family {sol.family}" in title
    assert f"altitude loss {sol.cost:.4g} m" in title
    path_ax = fig.axes[0]
    assert path_ax.get_xlabel().startswith("x / R_stf") and "m)" in path_ax.get_xlabel()
    assert path_ax.get_ylabel() == "y / R_stf"
    assert path_ax.get_aspect() == 1.0
    assert fig.axes[1].get_ylabel() == "turn rate u (rad/s)"
    assert fig.axes[2].get_ylabel() == "speed v (km/h)"
    texts = _assert_legends_outside(fig)
    assert f"optimal {sol.family} {sol.word}, {sol.cost:.2f} m" in texts
    assert {"start (heading)", "goal (heading)"} <= set(texts)
    assert sum(t.startswith("candidate ") for t in texts) >= 2
    import matplotlib.pyplot as plt

    plt.close(fig)
    from glideplan.plotting import plot_solution  # the demo's figure of the same solution

    ax = plot_solution(sol, candidates=True)
    assert f"altitude loss {sol.cost:.5g} m" in ax.get_title(loc="left")
    plt.close(ax.get_figure())


@pytest.mark.parametrize("goal", [(1.1, 2.0, 0.0), (0.0, -0.5, math.pi)])
def test_load_factor_figure_states_the_problem_and_no_legend_covers_omega(goal):
    """`plan load-factor --plot` (Figs 6.13 tall, 6.12 wide): lengths in l_ref, speeds in
    V_ref, the word and family in title and legend, and none of the three legends inside
    any panel or on an axis label (the legend of panel (c) covered the control set before)."""
    from glideplan.figures.ch6 import solution_figure, solve_example

    sol = solve_example(goal)
    assert sol.ok
    fig = solution_figure(sol, "fig6.x")
    title = fig.get_suptitle()
    assert title.startswith("fig6.x\n") and "load-factor glider" in title
    heading = math.degrees(goal[2])
    assert f"goal ({goal[0]:.4g}, {goal[1]:.4g}) l_ref, {heading:.4g} deg" in title
    assert f"optimal word {sol.word}, family {sol.family}" in title
    assert f"altitude loss {sol.cost:.5g} l_ref" in title
    a1, a2, a3 = fig.axes
    assert a1.get_xlabel() == "arc length s / l_ref"
    assert (a2.get_xlabel(), a2.get_ylabel()) == ("x / l_ref", "y / l_ref")
    assert a2.get_aspect() == 1.0
    assert a3.get_xlabel() == "speed v / V_ref"
    texts = _assert_legends_outside(fig)
    assert any(t.startswith(f"optimal {sol.word} ({sol.family})") for t in texts)
    assert {"start (heading)", "goal (heading)"} <= set(texts)
    import matplotlib.pyplot as plt

    plt.close(fig)


def test_demo_heading_is_the_first_title_line():
    """`glideplan demo` names the example above the problem statement."""
    import matplotlib.pyplot as plt

    from glideplan.plotting import plot_solution

    sol = plan(Pose(0, 0, 0), Pose(-3, 2, -math.pi / 2), DubinsCar(1.0, 1.0))
    ax = plot_solution(sol, heading="Dubins Fig 2.2(a) (section 2.3)")
    lines = ax.get_title(loc="left").split("\n")
    assert lines[0] == "Dubins Fig 2.2(a) (section 2.3)"
    assert lines[1].startswith("dubins (length): Dubins car")
    assert "goal (-3, 2) m, 270 deg" in lines[2]  # headings printed in [0, 360) deg
    plt.close(ax.get_figure())


def test_mission_figure_title_units_and_legend_outside():
    """The mission figure: route, waypoint count, speed, turn radius and total in the title;
    degrees on geographic axes; no "given heading" entry when every heading was chosen; the
    legend right of the axes."""
    import pathlib

    import matplotlib.pyplot as plt

    import glideplan.missions as missions_pkg
    from glideplan.formats import read_route
    from glideplan.missions import plan_mission
    from glideplan.missions.plot import plot_mission

    gpx = pathlib.Path(missions_pkg.__file__).parent / "data" / "buzzards_bay.gpx"
    mission = plan_mission(read_route(gpx), speed=0.3, radius=300.0)
    fig = plot_mission(mission)
    ax = fig.axes[0]
    title = ax.get_title(loc="left")
    assert "buzzards_bay.gpx: 8 waypoints" in title and "R = 300 m" in title
    assert f"total {mission.total_length_m:.0f} m" in title
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("longitude (deg E)", "latitude (deg N)")
    texts = _assert_legends_outside(fig)
    assert "chosen heading (compass deg)" in texts
    assert not any(t.startswith("given heading") for t in texts)
    plt.close(fig)


def test_mission_figure_draws_a_km_east_as_long_as_a_km_north():
    """Equal ground scale on lon/lat axes: pixels per metre along the east-west leg L1W ->
    L1E and along the north-south leg L1E -> L2E agree within 0.1 %. Reference: the WGS84
    geodesic lengths of the two legs (`geodesic_distance_bearing`, an independent pyproj
    computation), and the drawn waypoints' pixel positions. The tolerance: the aspect is taken
    at the track's mid-latitude, 0.0045 deg from the legs, where the length of a degree of
    longitude changes by ~tan(lat) * 7.9e-5 rad = 7e-5; the spherical 1 / cos(lat) misses
    the WGS84 ratio by 0.4 % (so a figure with that aspect fails), and an unset aspect by
    ~25 %. The km scales on the top and right axes read the same metres."""
    import pathlib

    import matplotlib.pyplot as plt

    import glideplan.missions as missions_pkg
    from glideplan.formats import read_route
    from glideplan.geodesy import geodesic_distance_bearing
    from glideplan.missions import plan_mission
    from glideplan.missions.plot import plot_mission

    gpx = pathlib.Path(missions_pkg.__file__).parent / "data" / "buzzards_bay.gpx"
    route = read_route(gpx)
    fig = plot_mission(plan_mission(route, speed=0.3, radius=150.0))
    ax = fig.axes[0]
    fig.canvas.draw()
    names = list(route.names)
    i, j, k = names.index("L1W"), names.index("L1E"), names.index("L2E")
    assert route.lat is not None and route.lon is not None
    lat, lon = np.asarray(route.lat), np.asarray(route.lon)
    assert abs(lat[i] - lat[j]) < 1e-9 and abs(lon[j] - lon[k]) < 1e-9  # E-W, then N-S
    metres, _ = geodesic_distance_bearing(lat[[i, j]], lon[[i, j]], lat[[j, k]], lon[[j, k]])
    px = ax.transData.transform(np.column_stack([lon[[i, j, k]], lat[[i, j, k]]]))
    east_px_per_m = abs(px[1, 0] - px[0, 0]) / metres[0]
    north_px_per_m = abs(px[2, 1] - px[1, 1]) / metres[1]
    assert east_px_per_m == pytest.approx(north_px_per_m, rel=1e-3)
    top = [c for c in ax.child_axes if "km east" in c.get_xlabel()]
    right = [c for c in ax.child_axes if "km north" in c.get_ylabel()]
    assert len(top) == 1 and len(right) == 1
    east_km = top[0].transData.inverted().transform(px[[0, 1]])[:, 0]
    north_km = right[0].transData.inverted().transform(px[[1, 2]])[:, 1]
    plt.close(fig)
    assert float(east_km[1] - east_km[0]) * 1000.0 == pytest.approx(metres[0], rel=1e-3)
    assert float(north_km[1] - north_km[0]) * 1000.0 == pytest.approx(metres[1], rel=1e-3)


def test_final_glide_summary_is_computed_from_the_profile():
    """The glide figure's answer line: loss = start - arrival, margin = arrival - (goal
    elevation + safety height), by hand: 1500 - 1018 = 482, 1018 - (450 + 300) = +268."""
    from glideplan.sailplane.request import FinalGlideDrawing

    d = FinalGlideDrawing(
        x=np.array([0.0, 1000.0]), y=np.array([0.0, 0.0]), distance=np.array([0.0, 1000.0]),
        altitude=np.array([1500.0, 1018.0]), goal_elevation=450.0, safety_height=300.0,
        title="t",
    )
    from glideplan.sailplane.plot import glide_summary

    text = glide_summary(d)
    assert "altitude loss 482 m" in text and "arrival 1018 m" in text
    assert "margin +268 m" in text
    unreachable = FinalGlideDrawing(
        x=d.x, y=d.y, distance=d.distance, altitude=np.array([1500.0, np.nan]),
        goal_elevation=450.0, safety_height=300.0, title="t",
    )
    assert glide_summary(unreachable).startswith("goal unreachable")


@pytest.mark.parametrize("arrival", [None, 190.0])
def test_final_glide_figure_is_written(tmp_path, arrival):
    """`glide final --plot` writes a PNG wider than tall (two panels, legends below)."""
    import matplotlib.image

    from glideplan.sailplane.plot import draw_final_glide
    from glideplan.sailplane.request import FinalGlideDrawing

    x = np.linspace(0.0, 8000.0, 20)
    d = FinalGlideDrawing(
        x=x, y=0.5 * x, distance=np.hypot(x, 0.5 * x),
        altitude=np.linspace(1500.0, 900.0, 20), goal_elevation=450.0, safety_height=300.0,
        title="test glide" if arrival is None else f"test glide, arrival {arrival:.0f} deg",
    )
    out = tmp_path / "g.png"
    draw_final_glide(d, out)
    h, w = matplotlib.image.imread(out).shape[:2]
    assert w > h


def test_candidates_that_draw_the_optimal_curve_are_drawn_once():
    """Straight downwind (section 3.2, T = 10 / 1.3 by hand): LSL, LSR, RSL, RSR all have
    zero-length turns and draw the same segment; the legend shows the optimal once, says how
    many coincide, and marks no switch point (there is no turn)."""
    import matplotlib.pyplot as plt

    from glideplan.plotting import plot_solution
    from glideplan.vehicles.dubins_car_in_wind import DubinsCarInWind

    car = DubinsCarInWind(speed=1.0, turn_radius=1.0, wind=(0.3, 0.0))
    sol = plan(Pose(), Pose(10.0, 0.0, 0.0), car)
    assert sol.cost == pytest.approx(10.0 / 1.3, rel=1e-9) and sol.word == "S"
    same = [c for c in sol.candidates if c.feasible and c.path is not None]
    ax = plot_solution(sol, candidates=True)
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    assert not any(t.startswith("candidate ") for t in texts)
    assert f"({len(same) - 1} more candidates coincide with one drawn)" in texts
    assert "switch point" not in texts
    plt.close(ax.get_figure())
