"""`glide final --cup/--tsk`: waypoint elevations are ground elevations, not the glider's
altitude.

Reference: the SeeYou CUP format (Naviter, field 6 `elev`: the waypoint's elevation, a number
with a unit) and XCSoar's task reader (a task `Waypoint`'s `altitude` attribute becomes the
waypoint's elevation). The goal is a field on the ground at ELEV_M; the start is the glider's
position in the air, whose ground elevation glideplan does not know: the start is written with
an empty `elev` / no `altitude`, and its altitude in the description. Files are read back with
aerofiles' SeeYou reader (and the standard XML parser for .tsk: aerofiles has no XCSoar
reader).
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import pytest

from glideplan.errors import InvalidParameterError
from glideplan.sailplane import TaskPoint


def test_cli_writes_ground_elevations(run_cli, dg_file, tmp_path):
    """Start at 1500 m above a point of unknown ground elevation, goal field at 420 m."""
    from aerofiles.seeyou import Reader

    cup, tsk = tmp_path / "g.cup", tmp_path / "g.tsk"
    code, _, err = run_cli("glide", "final", "--polar", str(dg_file), "--from", "47.0", "8.0",
                           "1500", "--to", "47.15", "8.05", "420", "--cup", str(cup),
                           "--tsk", str(tsk))  # fmt: skip
    assert code == 0, err
    with open(cup) as fp:
        data = Reader().read(fp)
    wps = {w["name"]: w for w in data["waypoints"]}
    assert wps["GOAL"]["elevation"] == {"value": 420.0, "unit": "m"}
    assert wps["START"]["elevation"]["value"] is None  # unknown, not 1500 m of ground
    assert "1500 m" in wps["START"]["description"]
    assert wps["START"]["latitude"] == pytest.approx(47.0, abs=1e-5)
    (task,) = data["tasks"]
    assert task["waypoints"] == ["START", "START", "GOAL", "GOAL"]

    points = ET.parse(tsk).getroot().findall("Point")
    start, goal = (p.find("Waypoint") for p in points)
    assert start is not None and goal is not None
    assert start.get("altitude") is None and "1500 m" in (start.get("comment") or "")
    assert goal.get("altitude") is not None and math.isclose(float(goal.get("altitude")), 420.0)


@pytest.mark.parametrize("bad", [math.nan, math.inf])
def test_a_non_finite_elevation_is_refused(bad):
    with pytest.raises(InvalidParameterError, match="GOAL elevation"):
        TaskPoint("GOAL", 47.0, 8.0, bad)
