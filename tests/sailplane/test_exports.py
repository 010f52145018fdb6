"""Files for other tools, read back by those tools' own readers: ArduPilot .parm (pymavlink),
SeeYou .cup (aerofiles), XCSoar .tsk (written by aerofiles; aerofiles has no XCSoar reader, so
the XML is parsed with the standard library)."""

import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from scipy.optimize import least_squares

from glideplan.sailplane import (
    TaskPoint,
    ardusoar_sink,
    fit_ardusoar,
    write_cup_task,
    write_parm,
    write_tsk_task,
)
from glideplan.sailplane.ardusoar import RHO_SEA_LEVEL


def test_ardusoar_fit_is_the_least_squares_optimum(dg_polar):
    """K = 2 m g / (rho S) by definition; CD0 and B agree with SciPy's nonlinear least
    squares from another start (an independent solver of the same problem)."""
    fit = fit_ardusoar(dg_polar)
    assert fit.k == pytest.approx(2 * 614.0 * 9.80665 / (RHO_SEA_LEVEL * 17.53))
    v = np.linspace(dg_polar.v_min, dg_polar.v_max, 200)
    w = dg_polar.sink(v)
    ref = least_squares(lambda q: ardusoar_sink(v, q[0], q[1], fit.k) - w, x0=[0.05, 0.05])
    assert fit.cd0 == pytest.approx(ref.x[0], rel=1e-6)
    assert fit.b == pytest.approx(ref.x[1], rel=1e-6)
    err = np.abs(ardusoar_sink(v, fit.cd0, fit.b, fit.k) - w)
    assert fit.max_sink_error == pytest.approx(err.max(), rel=1e-9)
    assert fit.max_sink_error < 0.1  # the cubic + 1/V model follows a sailplane polar closely


def test_parm_file_read_back_by_pymavlink(dg_polar, tmp_path):
    from pymavlink import mavparm

    fit = fit_ardusoar(dg_polar)
    path = tmp_path / "soar.parm"
    write_parm(fit, path, comment="DG-1001M\nsecond line")
    parms = mavparm.MAVParmDict()
    assert parms.load(str(path)) is not False
    for name, value in fit.params().items():
        assert parms[name] == pytest.approx(value, rel=1e-7)
    assert set(parms) == {"SOAR_POLAR_CD0", "SOAR_POLAR_B", "SOAR_POLAR_K"}


def test_cup_task_read_back_by_aerofiles(tmp_path):
    from aerofiles.seeyou import Reader

    a = TaskPoint("Start point", 47.123456, 8.654321, 1500.0)
    b = TaskPoint("Goal field", -33.5, -70.25, 450.0)
    path = tmp_path / "glide.cup"
    write_cup_task(path, a, b, description="final glide")
    with open(path) as fp:
        data = Reader().read(fp)
    wps = {w["name"]: w for w in data["waypoints"]}
    for p in (a, b):
        w = wps[p.name]
        # .cup stores minutes with 3 decimals: 0.0005' = 1e-5 deg
        assert w["latitude"] == pytest.approx(p.lat, abs=1e-5)
        assert w["longitude"] == pytest.approx(p.lon, abs=1e-5)
        assert w["elevation"]["value"] == pytest.approx(p.elevation)
    (task,) = data["tasks"]
    assert task["name"] == "final glide"
    assert task["waypoints"] == [a.name, a.name, b.name, b.name]


def test_tsk_task_is_valid_xml_with_the_two_points(tmp_path):
    a = TaskPoint("START", 47.0, 8.0, 1500.0)
    b = TaskPoint("GOAL", 47.2, 8.1, 450.0)
    path = tmp_path / "glide.tsk"
    write_tsk_task(path, a, b)
    root = ET.parse(path).getroot()
    assert root.tag == "Task"
    points = root.findall("Point")
    assert [p.get("type") for p in points] == ["Start", "Finish"]
    for p, ref in zip(points, (a, b), strict=True):
        loc = p.find("Waypoint/Location")
        assert loc is not None
        assert math.isclose(float(loc.get("latitude")), ref.lat)
        assert math.isclose(float(loc.get("longitude")), ref.lon)
        assert p.find("ObservationZone").get("type") == "Cylinder"
