"""Missions as outcomes: `to_dict()` is the `--json` object of `mission plan`, the wind is one
(east, north) vector inside the library, field warnings reach the user, and figures across the
antimeridian are drawn in a frame centred on the route."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from glideplan.errors import InvalidParameterError
from glideplan.missions import Route, plan_mission
from glideplan.units import wind_from_compass

TIMINGS = ("dp_seconds", "refine_seconds", "legs_seconds")  # wall-clock: differ run to run


def _without_timings(d):
    return d | {"stats": {k: v for k, v in d["stats"].items() if k not in TIMINGS}}


def _local_route(tmp_path):
    p = tmp_path / "r.csv"
    p.write_text("name,x,y,heading_deg\na,0,0,0\nb,600,400,\nc,1200,0,\n")
    return p


def test_to_dict_is_the_cli_json(run_cli, tmp_path):
    """The CLI prints the library's `to_dict()` and adds only `files`: the same object (bar
    the wall-clock timings) from `plan_mission` called directly, the compass `--wind 0.2 270`
    given to the library as the vector it stands for, (0.2, 0) m/s (a west wind blows east)."""
    from glideplan.formats import read_route
    from glideplan.jsonio import to_json

    p = _local_route(tmp_path)
    code, stdout, err = run_cli("mission", "plan", str(p), "--speed", "1", "--radius", "100",
                                "--wind", "0.2", "270", "--headings", "8", "--json")
    assert code == 0, err
    cli = json.loads(stdout)
    vector = wind_from_compass(0.2, 270.0)  # the CLI's conversion at its edge ...
    assert vector == pytest.approx((0.2, 0.0), abs=1e-15)  # ... (0.2, 0) up to rounding
    plan = plan_mission(read_route(p), speed=1.0, radius=100.0, objective="time",
                        wind=vector, headings=8)
    lib = json.loads(to_json(plan.to_dict()))
    assert set(cli) - set(lib) == {"files"} and cli["files"] == {}
    # the same computation in one process: equal, not merely close
    assert _without_timings(lib) == _without_timings({k: v for k, v in cli.items()
                                                      if k != "files"})


def test_to_dict_carries_the_track_and_straight_legs():
    """`to_dict()` alone describes the plan: the track (x/y of a local route, through every
    waypoint) and the default straight-leg list (the CLI's 50 m deviation)."""
    r = Route.from_local(["a", "b", "c"], [0.0, 600.0, 1200.0], [0.0, 400.0, 0.0],
                         [0.0, math.nan, math.nan])
    d = plan_mission(r, speed=1.0, radius=100.0, headings=8).to_dict()
    assert set(d["track"]) == {"x", "y"}
    x, y = np.array(d["track"]["x"]), np.array(d["track"]["y"])
    for wx, wy in zip(r.x, r.y, strict=True):
        assert np.min(np.hypot(x - wx, y - wy)) < 1e-3
    sl = d["stats"]["straight_legs"]
    assert sl["tolerance_m"] == 50.0 and sl["max_deviation_m"] <= 50.0


def test_wind_vector_is_the_compass_wind_it_stands_for():
    """Hand derivation: a wind of 0.2 m/s FROM the north (compass 0) moves the air south,
    (east, north) = (0, -0.2). `wind=` and its older name `wind_vector=` take the same vector
    and plan the same mission; the JSON (the edge) reads the wind back in compass form."""
    r = Route.from_local(["a", "b", "c"], [0.0, 600.0, 1200.0], [0.0, 400.0, 0.0],
                         [0.0, math.nan, math.nan])
    by_vector = plan_mission(r, speed=1.0, radius=150.0, objective="time",
                             wind_vector=(0.0, -0.2), headings=8)
    by_compass = plan_mission(r, speed=1.0, radius=150.0, objective="time",
                              wind=wind_from_compass(0.2, 0.0), headings=8)
    assert by_vector.ok and by_compass.ok
    assert by_vector.total_duration_s == pytest.approx(by_compass.total_duration_s, rel=1e-12)
    np.testing.assert_allclose(by_vector.headings, by_compass.headings, atol=1e-12)
    assert by_compass.wind_vector == pytest.approx((0.0, -0.2), abs=1e-15)
    assert by_vector.to_dict()["wind"] == {"speed": 0.2, "from_deg": 0.0}
    with pytest.raises(InvalidParameterError, match="wind"):
        plan_mission(r, speed=1.0, radius=150.0, objective="time", wind=(0.0, -0.2),
                     wind_vector=(0.0, -0.2))
    with pytest.raises(InvalidParameterError, match="wind_vector"):
        plan_mission(r, speed=1.0, radius=150.0, objective="time",
                     wind_vector=(math.nan, 0.0))
    u, v = wind_from_compass(0.2, 0.0)
    assert (u, v) == pytest.approx((0.0, -0.2), abs=1e-15)


def test_mission_figure_across_the_antimeridian():
    """Near Fiji, waypoints at 179.985 E .. 179.975 W (a 0.04 deg span): the figure's x-extent
    is the track's own span (its longitudes made continuous by np.unwrap, an independent
    construction), not ~360 deg; the waypoints are drawn at their longitudes unwrapped about
    the route's centre, and the ticks read -180..180."""
    import matplotlib.pyplot as plt

    from glideplan.missions.plot import plot_mission

    route = Route.from_geographic(["Suva", "Seam", "Taveuni", "Lau"],
                                  [-17.0, -16.99, -16.97, -16.96],
                                  [179.985, -179.995, -179.99, -179.975],
                                  [0.0, np.nan, 90.0, np.nan])
    plan = plan_mission(route, speed=1.0, radius=300.0)
    assert plan.ok
    fig = plot_mission(plan)
    try:
        ax = fig.axes[0]
        line = next(ln for ln in ax.get_lines() if ln.get_label() == "planned track")
        x = np.asarray(line.get_xdata(), dtype=float)
        tr = plan.track()
        _, lon = route.projection.to_geographic(tr.x, tr.y)
        ref = np.degrees(np.unwrap(np.radians(lon)))
        assert np.ptp(x) == pytest.approx(np.ptp(ref), abs=1e-9)
        assert np.ptp(x) < 0.1  # the route's own span (0.04 deg of waypoints, 300 m turns)
        lo, hi = ax.get_xlim()
        assert hi - lo < 0.2
        wp = next(ln for ln in ax.get_lines() if ln.get_label() == "waypoints")
        np.testing.assert_allclose(wp.get_xdata(), [179.985, 180.005, 180.01, 180.025],
                                   atol=1e-9)
        fig.canvas.draw()
        labels = [t.get_text() for t in ax.get_xticklabels() if t.get_text()]
        assert labels and all(-180.0 <= float(t.replace("\N{MINUS SIGN}", "-")) <= 180.0
                              for t in labels)
    finally:
        plt.close(fig)


@pytest.fixture(scope="module")
def steady_file(tmp_path_factory):
    """A Copernicus-like file with ONE time step: read as a steady field, with the reader's
    warning that it is held constant in time."""
    from glideplan.fields.synthetic import copernicus_dataset

    lat = np.linspace(29.7, 30.2, 26)
    lon = np.linspace(-40.4, -39.7, 36)
    times = np.array([np.datetime64("2026-01-01T00:00", "ns")])
    shape = (1, 1, lat.size, lon.size)
    path = tmp_path_factory.mktemp("steady") / "steady.nc"
    copernicus_dataset(lat, lon, times, [0.5], np.full(shape, 0.1),
                       np.zeros(shape)).to_netcdf(path)
    return path


def test_field_warnings_reach_the_user(run_cli, tmp_path, steady_file):
    """The field's warnings (`FlowField.warnings`) are printed as `glideplan: warning:` lines
    and listed in the JSON's `warnings`, as is a given heading the router does not enforce."""
    from glideplan.fields import open_field

    expected = open_field(steady_file).warnings
    assert any("held constant" in w for w in expected)  # what the reader says of this file
    route = tmp_path / "r.csv"
    route.write_text("name,lat,lon,heading_deg\nA,29.9,-40.2,45\nB,30.0,-40.1,\n")
    code, stdout, err = run_cli("mission", "plan", str(route), "--speed", "0.5", "--radius",
                                "100", "--field", str(steady_file), "--json")
    assert code == 0, err
    d = json.loads(stdout)
    assert d["status"] == "solved"
    for w in expected:
        assert w in d["warnings"]
        assert f"glideplan: warning: {' '.join(w.split())}" in err
    assert any("heading given at A is not enforced" in w for w in d["warnings"])
    assert "heading given at A is not enforced" in err


def test_unreachable_field_mission_to_dict():
    """A 0.3 m/s current east against a 0.2 m/s vehicle whose goal lies west: the reachable
    set drifts east faster than it spreads (|c| > V: every reachable velocity points east), so
    the leg is UNREACHABLE, the mission too; its JSON has no track, names the leg, and carries
    the field's warnings."""
    from glideplan.fields import GriddedField
    from glideplan.jsonio import to_json
    from glideplan.missions import plan_mission_in_field
    from glideplan.solution import Status

    lat = np.linspace(29.7, 30.2, 26)
    lon = np.linspace(-40.4, -39.7, 36)
    u = np.full((1, lat.size, lon.size), 0.3)
    flow = GriddedField(times=np.array([0.0]), lat=lat, lon=lon, u=u, v=np.zeros_like(u),
                        warnings=("the field is a test",))
    r = Route.from_geographic(["A", "B"], [29.95, 29.95], [-39.85, -40.2])
    mission = plan_mission_in_field(r, flow, speed=0.2, resolution=1000.0)
    assert mission.status is Status.UNREACHABLE and not mission.ok
    d = json.loads(to_json(mission.to_dict()))
    assert d["status"] == "unreachable" and d["track"] is None
    assert d["message"].startswith("leg 1 (A -> B)")
    assert d["legs"][0]["status"] == "unreachable"
    assert "the field is a test" in d["warnings"]


def test_reader_warnings_are_in_the_mission_json(run_cli, tmp_path):
    """A GeoJSON feature with null geometry is skipped with a warning: the warning is printed
    once and is in `--json` `warnings` too (the JSON is the whole answer)."""
    gj = tmp_path / "r.geojson"
    gj.write_text(json.dumps({"type": "FeatureCollection", "features": [
        {"type": "Feature", "geometry": None, "properties": {}},
        {"type": "Feature", "properties": {}, "geometry": {
            "type": "LineString", "coordinates": [[-70.70, 41.50], [-70.68, 41.51],
                                                  [-70.66, 41.50]]}}]}))
    code, out, err = run_cli("mission", "plan", str(gj), "--speed", "0.3", "--radius", "150",
                             "--json")
    assert code == 0, err
    warned = [w for w in json.loads(out)["warnings"] if "null" in w]
    assert len(warned) == 1
    assert err.count("null") == 1
