"""Route files with per-vertex UTC times (issue 26): GeoJSON, KML, GPX, CSV, each read back by
its own reader (json, fastkml, gpxpy, csv; GPSBabel when installed), one vertex per position.

References: a held-heading route is written by the router with each inner vertex twice
(`routing.phases._held`, SWITCH_S apart): the files must hold each position once with the
time the vehicle reaches it. Times are checked against the route's own numbers: the last
vertex's time is the route's `arrive` (depart + duration_s, computed by `RouteResult`, not by
the writers), and the vertex times are depart + the track's t.
"""

from __future__ import annotations

import csv
import datetime as dt
import json
import shutil
import subprocess

import numpy as np
import pytest

from glideplan.formats.route_export import export_route, route_vertices
from glideplan.routing.phases import _held
from glideplan.routing.result import RouteResult
from glideplan.track import Track

DEPART = np.datetime64("2026-03-01T06:00:00", "ms")


def _result(t, lat, lon, chi, depart=DEPART) -> RouteResult:
    """A solved route whose track is the router's held-heading representation."""
    c = _held("grid", np.asarray(t, float), np.asarray(lat, float), np.asarray(lon, float),
              np.asarray(chi, float), 0.0)
    z = np.zeros(c.t.size)
    track = Track(t=c.t, x=z, y=z, heading=np.pi / 2 - c.chi, lat=c.lat, lon=c.lon)
    return RouteResult(status="solved", depart=depart, duration_s=float(c.t[-1]),
                       distance_m=1.0, track=track, method="grid")


def _iso(depart, seconds: float) -> str:
    return str(depart + np.timedelta64(round(seconds * 1e3), "ms")) + "Z"


@pytest.fixture
def held():
    """Four vertices, three legs of 1000, 1500 and 500 s (headings 10, 80, 170 deg)."""
    return _result([0.0, 1000.0, 2500.0, 3000.0], [44.0, 44.1, 44.12, 44.0],
                   [-9.0, -8.98, -8.8, -8.79], np.radians([10.0, 80.0, 170.0, 170.0]))


def test_vertices_once_with_arrival_time_and_leaving_heading(held):
    """The track has 6 samples (2 inner vertices doubled); the vertices are the 4 positions,
    each with the time it is reached and the course of the leg leaving it."""
    assert held.track.size == 6
    v = route_vertices(held)
    np.testing.assert_array_equal(v.t_s, [0.0, 1000.0, 2500.0, 3000.0])
    np.testing.assert_allclose(v.heading_deg[:3], [10.0, 80.0, 170.0])
    assert v.times[-1] == str(held.arrive) + "Z" == "2026-03-01T06:50:00.000Z"


def test_route_files_read_back_by_their_readers(held, tmp_path):
    import gpxpy
    from fastkml import kml

    files = {f: tmp_path / f"r.{f}" for f in ("geojson", "kml", "gpx", "csv")}
    written = export_route(held, files)
    assert set(written) == set(files)
    want = [_iso(DEPART, s) for s in (0.0, 1000.0, 2500.0, 3000.0)]
    lat = [44.0, 44.1, 44.12, 44.0]

    doc = json.loads(files["geojson"].read_text())
    line = doc["features"][0]
    assert line["geometry"]["type"] == "LineString"
    assert len(line["geometry"]["coordinates"]) == 4  # was 6: every inner vertex twice
    assert line["properties"]["coordTimes"] == want
    assert line["properties"]["arrive"] == str(held.arrive) + "Z"
    points = [f for f in doc["features"] if f["properties"]["kind"] == "vertex"]
    assert [p["properties"]["time"] for p in points] == want

    k = kml.KML.from_string(files["kml"].read_bytes())
    doc_k = k.features[0]
    marks = list(doc_k.features)
    stamps = [p.times.timestamp.dt for p in marks[1:]]
    assert [s.replace(tzinfo=None) for s in stamps] == [
        dt.datetime.fromisoformat(w[:-1]) for w in want]
    assert len(marks[0].geometry.coords) == 4

    gpx = gpxpy.parse(files["gpx"].read_text())
    pts = gpx.tracks[0].segments[0].points
    assert [p.latitude for p in pts] == pytest.approx(lat)
    assert [p.time.isoformat().replace("+00:00", "") + "Z" for p in pts] == [
        w.replace(".000Z", "Z") for w in want]

    with files["csv"].open(newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert [r["time_utc"] for r in rows] == want
    assert [float(r["lat"]) for r in rows] == pytest.approx(lat)


@pytest.mark.skipif(shutil.which("gpsbabel") is None, reason="gpsbabel not installed")
@pytest.mark.parametrize(("fmt", "kind"), [("gpx", "-t"), ("kml", "-w")])
def test_gpsbabel_reads_the_times(held, tmp_path, fmt, kind):
    """GPSBabel (independent C++ reader): GPX track points and KML timestamped Points."""
    path = tmp_path / f"r.{fmt}"
    export_route(held, {fmt: path})
    out = subprocess.run(["gpsbabel", kind, "-i", fmt, "-f", str(path), "-o", "unicsv", "-F",
                          "-"], capture_output=True, text=True, check=True, timeout=30).stdout
    rows = list(csv.DictReader(out.splitlines()))
    assert len(rows) == 4
    assert rows[-1]["Date"] == "2026/03/01" and rows[-1]["Time"].startswith("06:50:00")
    assert rows[1]["Time"].startswith("06:16:40")  # 06:00 + 1000 s


def test_antimeridian_split_times_interpolated(tmp_path):
    """Along the equator 179 E -> 179 W in 2000 s at a constant rate: the split line's
    crossing point at 180 is reached at 1000 s (closed form: half the longitude)."""
    r = _result([0.0, 2000.0], [0.0, 0.0], [179.0, 181.0], np.radians([90.0, 90.0]))
    path = tmp_path / "r.geojson"
    export_route(r, {"geojson": path})
    line = json.loads(path.read_text())["features"][0]
    assert line["geometry"]["type"] == "MultiLineString"
    times = line["properties"]["coordTimes"]
    assert [len(p) for p in times] == [len(p) for p in line["geometry"]["coordinates"]]
    assert times == [[_iso(DEPART, 0.0), _iso(DEPART, 1000.0)],
                     [_iso(DEPART, 1000.0), _iso(DEPART, 2000.0)]]


def test_no_calendar_writes_t_s_and_warns(tmp_path):
    from glideplan.formats.route_export import route_export_warnings

    r = _result([0.0, 100.0], [0.0, 0.01], [0.0, 0.0], [0.0, 0.0], depart=None)
    path = tmp_path / "r.csv"
    export_route(r, {"csv": path})
    with path.open(newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert [r_["time_utc"] for r_ in rows] == ["", ""]
    assert [float(r_["t_s"]) for r_ in rows] == [0.0, 100.0]
    assert "no UTC times" in route_export_warnings(r)[0]


def test_route_cli_writes_all_four_with_times(run_cli, tmp_path):
    """`glideplan route --geojson --kml --gpx --csv` on a steady field: each file's last time
    is the JSON's `arrive`, the first its `depart`, and no position repeats."""
    from glideplan.fields.synthetic import copernicus_dataset

    times = np.datetime64("2026-03-01T00:00", "ns") + np.arange(49) * np.timedelta64(3600, "s")
    lat, lon = np.linspace(44.0, 45.0, 11), np.linspace(-9.0, -8.0, 11)
    u = np.full((times.size, 1, lat.size, lon.size), 0.1)
    field = tmp_path / "cur.nc"
    copernicus_dataset(lat, lon, times, [0.5], u, 0.0 * u).to_netcdf(field)
    files = {f: tmp_path / f"r.{f}" for f in ("geojson", "kml", "gpx", "csv")}
    code, out, _ = run_cli("route", "--field", str(field), "--from", "44.5", "-8.9", "--to",
                             "44.6", "-8.5", "--speed", "0.4", "--depart", "2026-03-01T06:00Z",
                             "--resolution", "3000", "--json",
                             *[a for f, p in files.items() for a in (f"--{f}", str(p))])
    assert code == 0, out
    data = json.loads(out)
    with files["csv"].open(newline="") as fh:
        rows = list(csv.DictReader(fh))
    arrive = np.datetime64(data["arrive"][:-1], "ms")  # whole seconds in the JSON
    last = np.datetime64(rows[-1]["time_utc"][:-1], "ms")
    assert abs(last - arrive) <= np.timedelta64(500, "ms")
    assert float(rows[-1]["t_s"]) == pytest.approx(data["duration_s"], abs=1e-3)
    assert rows[0]["time_utc"] == "2026-03-01T06:00:00.000Z"
    pos = [(r["lat"], r["lon"]) for r in rows]
    assert len(set(pos)) == len(pos)
    line = json.loads(files["geojson"].read_text())["features"][0]
    assert line["properties"]["coordTimes"] == [r["time_utc"] for r in rows]
