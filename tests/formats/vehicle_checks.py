"""Independent checkers of the Slocum goto-list and Seaglider targets rules (FORMATS.md).

Written from the format notes, not from glideplan's writers: they parse the text files on
their own and decode DDMM.MMMM with their own arithmetic.
"""

from __future__ import annotations

import pathlib
import re


def ddmm(text: str) -> float:
    """Degrees of a DDMM.MMMM number; minutes must be in [0, 60)."""
    v = float(text)
    a = abs(v)
    deg = int(a // 100)
    minutes = a - deg * 100
    assert 0.0 <= minutes < 60.0, f"minutes {minutes} out of range in {text}"
    return -(deg + minutes / 60.0) if v < 0 else deg + minutes / 60.0


def check_slocum(path: pathlib.Path) -> list[tuple[float, float]]:
    """Parse a goto_lNN.ma file, check its rules, return [(lat, lon)] in file order."""
    assert re.fullmatch(r"goto_l\d\d\.ma", path.name), path.name
    text = path.read_text(encoding="ascii")
    lines = text.splitlines()
    assert lines[0].strip() == "behavior_name=goto_list"
    body = [ln.split("#", 1)[0].strip() for ln in lines]
    i0, i1 = body.index("<start:b_arg>"), body.index("<end:b_arg>")
    args = {}
    for ln in body[i0 + 1 : i1]:
        if ln:
            m = re.fullmatch(r"b_arg:\s+(\w+)\((\w+)\)\s+(-?[\d.]+)", ln)
            assert m, ln
            args[m.group(1)] = float(m.group(3))
    w0, w1 = body.index("<start:waypoints>"), body.index("<end:waypoints>")
    pts = []
    for ln in body[w0 + 1 : w1]:
        if ln:
            lon_s, lat_s = ln.split()
            lon, lat = ddmm(lon_s), ddmm(lat_s)
            assert -90 <= lat <= 90 and -180 <= lon <= 180
            pts.append((lat, lon))
    assert args["num_waypoints"] == len(pts), "num_waypoints must equal the waypoint lines"
    assert args["num_legs_to_run"] in (-2, -1) or args["num_legs_to_run"] > 0
    assert args["list_stop_when"] == 7 and args["list_when_wpt_dist"] > 0
    assert -2 <= args["initial_wpt"] < len(pts)
    return pts


def check_seaglider(path: pathlib.Path) -> dict[str, tuple[float, float, str]]:
    """Parse a targets file, check its rules, return name -> (lat, lon, goto) in order."""
    raw = path.read_bytes()
    assert all(b < 128 for b in raw), "targets must be ASCII"
    out: dict[str, tuple[float, float, str]] = {}
    for ln in raw.decode().splitlines():
        if not ln.strip() or ln.lstrip().startswith("/"):
            continue
        name, *fields = ln.split()
        kv = dict(f.split("=", 1) for f in fields)
        assert set(kv) >= {"lat", "lon", "radius", "goto"}, ln
        assert name not in out, f"duplicate target {name}"
        assert float(kv["radius"]) > 0
        out[name] = (ddmm(kv["lat"]), ddmm(kv["lon"]), kv["goto"])
    for name, (_, _, goto) in out.items():
        assert goto in out, f"{name} goes to undefined target {goto}"
    last = list(out)[-1]
    assert out[last][2] == last, "the last target goes to itself"
    return out
