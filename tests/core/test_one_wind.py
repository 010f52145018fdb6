"""Issue 26, one wind value: inside the library a wind (or steady current) is the (east, north)
vector in m/s it blows TOWARDS; compass "from" degrees only at the edges, converted by
`glideplan.units.wind_from_compass` / `wind_to_compass` and nothing else.

Reference (closed form): a wind FROM compass bearing b at speed s blows towards b + 180 deg,
(east, north) = -s (sin b, cos b); FROM 270 deg (west) at 10 m/s is (+10, 0), FROM 0 deg
(north) is (0, -10). Each entry (`plan wind`, `mission plan --wind`, `glide final --wind`,
`glide reach --wind`, `glide turnback --wind`, the Python API) is given the same compass wind
and must hand the library that vector (recorded where the library receives it).
"""

from __future__ import annotations

import json
import math
import pathlib

import pytest

from glideplan.units import wind_from_compass, wind_to_compass

POLAR = pathlib.Path(__file__).parents[1] / "data" / "polars" / "DG-1001M_ch5.plr"
GPX = pathlib.Path(__file__).parents[2] / "src/glideplan/missions/data/buzzards_bay.gpx"
TOL = 1e-12  # the closed form's own round-off (sin/cos of 270 deg: ~1e-16 relative)


@pytest.mark.parametrize(("speed", "from_deg", "east", "north"), [
    (10.0, 270.0, 10.0, 0.0),    # from the west: towards the east
    (10.0, 0.0, 0.0, -10.0),     # from the north: towards the south
    (10.0, 90.0, -10.0, 0.0),    # from the east
    (4.0, 225.0, 4.0 * math.sqrt(0.5), 4.0 * math.sqrt(0.5)),  # from the south-west
    (0.0, 123.0, 0.0, 0.0),      # calm
])
def test_compass_to_vector_closed_form(speed, from_deg, east, north):
    assert wind_from_compass(speed, from_deg) == pytest.approx((east, north), abs=TOL)
    back = wind_to_compass(east, north)
    assert back[0] == pytest.approx(speed, abs=TOL)
    if speed > 0:  # the direction reads back as given (a calm has direction 0)
        assert back[1] == pytest.approx(from_deg % 360.0, abs=1e-9)


def test_edges_refuse_like_the_table():
    """A wind speed beyond `PHYSICAL_RANGES["wind_speed"]` or a NaN direction is refused,
    naming the edge's own parameter."""
    from glideplan.errors import InvalidParameterError

    with pytest.raises(InvalidParameterError, match=r"--wind speed=200.0: must lie in \[0, 150\]"):
        wind_from_compass(200.0, 270.0, param="--wind")
    with pytest.raises(InvalidParameterError, match="wind direction"):
        wind_from_compass(5.0, math.nan)


class _Seen(Exception):
    """Raised by a recorder once the library has been handed its wind (nothing is planned)."""


def _record(monkeypatch, module, name, pick):
    """Replace `module.name` by a recorder of `pick(*args, **kwargs)` (the wind it is handed)."""
    seen: list[tuple[float, float]] = []

    def recorder(*args, **kwargs):
        seen.append(tuple(float(c) for c in pick(*args, **kwargs)))
        raise _Seen

    monkeypatch.setattr(module, name, recorder)
    return seen


def _expect(seen):
    assert len(seen) == 1
    assert seen[0] == pytest.approx((10.0, 0.0), abs=TOL)


def test_plan_wind_cli(monkeypatch, run_cli):
    """`plan wind --wind 10 270` (compass FROM, as every --wind): the vehicle's wind and the
    solution's JSON are (+10, 0)."""
    code, out, err = run_cli("plan", "wind", "--goal", "400", "300", "90", "--speed", "20",
                             "--radius", "50", "--wind", "10", "270", "--json")
    assert code == 0, err
    data = json.loads(out)
    assert data["vehicle"]["wind"] == pytest.approx([10.0, 0.0], abs=TOL)
    assert (data["wind"]["east"], data["wind"]["north"]) == pytest.approx(
        (10.0, 0.0), abs=TOL)
    import glideplan.planning

    seen = _record(monkeypatch, glideplan.planning, "plan", lambda s, g, v, *a, **k: v.wind)
    run_cli("plan", "wind", "--goal", "400", "300", "90", "--speed", "20", "--radius", "50",
            "--wind", "10", "270")
    _expect(seen)


def test_mission_plan_cli(monkeypatch, run_cli):
    import glideplan.missions

    seen = _record(monkeypatch, glideplan.missions, "plan_mission",
                   lambda *a, **k: k["wind"])
    run_cli("mission", "plan", str(GPX), "--speed", "20", "--radius", "150", "--wind", "10",
            "270")
    _expect(seen)


def test_glide_final_cli(monkeypatch, run_cli):
    import glideplan.sailplane.request

    seen = _record(monkeypatch, glideplan.sailplane.request, "final_glide",
                   lambda *a, **k: k["wind"])
    run_cli("glide", "final", "--polar", str(POLAR), "--from", "47.0", "8.0", "1500", "--to",
            "47.2", "8.1", "450", "--wind", "10", "270")
    _expect(seen)


@pytest.mark.parametrize(("command", "function"), [("reach", "glide_reach"),
                                                    ("turnback", "turnback")])
def test_glide_reach_and_turnback_cli(monkeypatch, run_cli, command, function):
    import glideplan.reach

    seen = _record(monkeypatch, glideplan.reach, function, lambda *a, **k: k["wind"])
    run_cli("glide", command, "--example", "ridge", "--wind", "10", "270")
    _expect(seen)


def test_python_api_takes_the_vector():
    """Every vehicle, planner and product of the Python API holds the vector it is given."""
    from glideplan import DubinsCarInWind
    from glideplan.reach import Glide
    from glideplan.sailplane import polar_from_file, read_plr
    from glideplan.simulation import SteadyDisturbance
    from glideplan.vehicles.sailplane import Sailplane

    w = wind_from_compass(10.0, 270.0)
    polar = polar_from_file(read_plr(POLAR))
    for held in (DubinsCarInWind(20.0, 50.0, wind=w).wind, Sailplane(polar, wind=w).wind,
                 Glide(polar, wind=w).wind, tuple(SteadyDisturbance(w).velocity(1)[0])):
        assert tuple(held) == pytest.approx((10.0, 0.0), abs=TOL)


def test_final_glide_and_mission_read_the_vector_back_as_compass():
    """The JSON edge of `final_glide` and `plan_mission` says the compass wind given."""
    from glideplan.missions import Route, plan_mission
    from glideplan.sailplane import final_glide, polar_from_file, read_plr

    w = wind_from_compass(10.0, 270.0)
    polar = polar_from_file(read_plr(POLAR))
    fg = final_glide(polar, (47.0, 8.0, 1500.0), (47.2, 8.1, 450.0), wind=w)
    assert fg.wind == pytest.approx((10.0, 0.0), abs=TOL)
    assert fg.to_dict()["wind"] == {"speed_ms": pytest.approx(10.0), "from_deg": 270.0}
    r = Route.from_local(["a", "b"], [0.0, 800.0], [0.0, 300.0])
    mp = plan_mission(r, speed=20.0, radius=150.0, objective="time", wind=w, headings=8)
    assert mp.wind_vector == pytest.approx((10.0, 0.0), abs=TOL)
    assert mp.to_dict()["wind"] == {"speed": 10.0, "from_deg": 270.0}
