"""Files the vehicles fly: Slocum goto lists, Seaglider targets, QGC WPL 110 and QGC .plan.

All take the straight-leg waypoint list (`missions.straight_legs`), whose straight legs stay
within the stated deviation of the planned track. Formats per ../shared/FORMATS.md:

- Slocum `goto_lNN.ma`: longitude then latitude in DDMM.MMMM; at most `max_waypoints` per
  file, consecutive files share their boundary waypoint (numbered NN, NN+1, ...).
- Seaglider `targets`: `NAME lat=DDMM.MMMM lon=DDDMM.MMMM radius=R goto=NEXT`, the last
  target goes to itself; names unique, ASCII.
- QGC WPL 110: tab-separated, 12 fields; item 0 is home (the first waypoint, frame 0), then
  NAV_WAYPOINT (16) items in frame 3 (altitude relative to home) with p2 the acceptance radius.
- QGC `.plan` (JSON): the same mission items as SimpleItems; NaN written as null. The format
  has no time field: each item's ETA (and the list point's name) goes in an extra key
  `"glideplan": {"name", "eta_s", "eta"}` of the item. QGroundControl's reader
  (`MissionItem::load` / `SimpleMissionItem::load`) validates only the keys it knows and
  ignores the rest, so the file still loads (QGC drops the key when it saves the plan again).
  QGC WPL 110 has no place at all: QGC rejects any line that is not 12 tab-separated fields.
"""

from __future__ import annotations

import json
import math
import pathlib
import re
from typing import Any

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.formats.ddmm import degrees_to_ddmm
from glideplan.missions.straight_legs import StraightLegList
from glideplan.track import iso_times

__all__ = ["write_qgc_plan", "write_qgc_wpl", "write_seaglider_targets", "write_slocum_goto"]

NAV_WAYPOINT = 16
FRAME_GLOBAL = 0
FRAME_RELATIVE_ALT = 3


def _latlon(legs: StraightLegList) -> tuple[list[float], list[float]]:
    assert legs.lat is not None and legs.lon is not None
    return [float(v) for v in legs.lat], [float(v) for v in legs.lon]


def write_slocum_goto(
    legs: StraightLegList,
    out_dir: pathlib.Path,
    *,
    goto_number: int = 10,
    max_waypoints: int = 8,
    acceptance_radius: float = 100.0,
    mission_name: str = "mission",
    depart: np.datetime64 | None = None,
) -> list[pathlib.Path]:
    """`goto_lNN.ma` files (NN = goto_number, +1, ...) holding the waypoint list in order;
    each waypoint's comment gives its name and ETA (after departure; UTC with `depart`)."""
    if not isinstance(max_waypoints, int) or max_waypoints < 2:
        raise InvalidParameterError("max-goto-waypoints", max_waypoints, "must be an integer >= 2")
    lat, lon = _latlon(legs)
    n = len(lat)
    step = max_waypoints - 1
    chunks = [(i, min(n, i + max_waypoints)) for i in range(0, max(1, n - 1), step)]
    last = goto_number + len(chunks) - 1
    if not (0 <= goto_number and last <= 99):
        raise InvalidParameterError(
            "goto-number", goto_number,
            f"the {len(chunks)} goto files would need numbers {goto_number}..{last}: "
            "use 0..99 (raise --max-goto-waypoints to need fewer files)")
    paths = []
    for k, (i, j) in enumerate(chunks):
        nn = goto_number + k
        lines = [
            "behavior_name=goto_list",
            f"# goto_l{nn:02d}.ma written by glideplan: {mission_name}, part {k + 1} of "
            f"{len(chunks)}",
            f"# waypoints {i + 1}..{j} of {n}; straight legs within "
            f"{legs.tolerance_m:g} m of the planned track",
        ]
        if k + 1 < len(chunks):
            lines.append(f"# continue with goto_l{nn + 1:02d}.ma (it starts at this file's last "
                         "waypoint)")
        lines += [
            "<start:b_arg>",
            "    b_arg: num_legs_to_run(nodim) -2     # traverse the list once",
            "    b_arg: start_when(enum) 0            # immediately",
            "    b_arg: list_stop_when(enum) 7        # when within list_when_wpt_dist",
            f"    b_arg: list_when_wpt_dist(m) {acceptance_radius:g}",
            "    b_arg: initial_wpt(enum) 0           # start with the first waypoint",
            f"    b_arg: num_waypoints(nodim) {j - i}",
            "<end:b_arg>",
            "<start:waypoints>",
            "# LONGITUDE LATITUDE",
        ]
        for q in range(i, j):
            lines.append(f"{degrees_to_ddmm(lon[q]):>12s} {degrees_to_ddmm(lat[q]):>11s}"
                         f"    # {_ascii(legs.names[q])}{_eta(legs, q, depart)}")
        lines += ["<end:waypoints>", ""]
        path = out_dir / f"goto_l{nn:02d}.ma"
        path.write_text("\n".join(lines), encoding="ascii")
        paths.append(path)
    return paths


def _eta(legs: StraightLegList, i: int, depart: np.datetime64 | None) -> str:
    """" ETA +HH:MM:SS" (and " 2026-...Z" with `depart`) of list point i; "" without ETAs."""
    if not legs.eta_s.size:
        return ""
    m, sec = divmod(round(float(legs.eta_s[i])), 60)
    h, m = divmod(m, 60)
    when = iso_times(depart, legs.eta_s[i])[0]
    return f" ETA +{h:02d}:{m:02d}:{sec:02d}" + ("" if when is None else f" {when}")


def _ascii(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9_]+", "_", name).strip("_") or "WP"


def _unique_names(names: tuple[str, ...]) -> list[str]:
    out: list[str] = []
    seen: set[str] = set()
    for i, name in enumerate(names):
        base = _ascii(name)
        cand, k = base, 1
        while cand in seen:
            k += 1
            cand = f"{base}_{k}"
        seen.add(cand)
        out.append(cand if cand else f"WP{i + 1:02d}")
    return out


def write_seaglider_targets(
    legs: StraightLegList,
    path: pathlib.Path,
    *,
    acceptance_radius: float = 100.0,
    mission_name: str = "mission",
    depart: np.datetime64 | None = None,
) -> pathlib.Path:
    """A Seaglider `targets` file: each target goes to the next, the last to itself; a
    comment line before each gives its ETA (after departure; UTC with `depart`)."""
    lat, lon = _latlon(legs)
    names = _unique_names(legs.names)
    lines = [
        f"/ Targets file for {_ascii(mission_name)} written by glideplan",
        f"/ {len(names)} targets; straight legs within {legs.tolerance_m:g} m of the plan",
    ]
    for i, name in enumerate(names):
        nxt = names[min(i + 1, len(names) - 1)]
        if legs.eta_s.size:
            lines.append(f"/ {name}{_eta(legs, i, depart)}")
        lines.append(
            f"{name} lat={degrees_to_ddmm(lat[i])} lon={degrees_to_ddmm(lon[i])} "
            f"radius={acceptance_radius:g} goto={nxt}"
        )
    path.write_text("\n".join(lines) + "\n", encoding="ascii")
    return path


def _finite(v: float) -> float | None:
    """v, or None (JSON null) if it is not finite."""
    return v if math.isfinite(v) else None


def _items(legs: StraightLegList, altitude: float, acceptance_radius: float) -> list[
    tuple[float, float, float, float]
]:
    lat, lon = _latlon(legs)
    return [(a, b, altitude, acceptance_radius) for a, b in zip(lat, lon, strict=True)]


def write_qgc_wpl(
    legs: StraightLegList,
    path: pathlib.Path,
    *,
    altitude: float = 50.0,
    acceptance_radius: float = 100.0,
) -> pathlib.Path:
    """QGC WPL 110: home (the first waypoint), then one NAV_WAYPOINT per list point."""
    lat, lon = _latlon(legs)
    rows = ["QGC WPL 110"]
    rows.append("\t".join(
        ["0", "1", str(FRAME_GLOBAL), str(NAV_WAYPOINT), "0", "0", "0", "0",
         f"{lat[0]:.8f}", f"{lon[0]:.8f}", "0.000000", "1"]))
    for seq, (a, b, alt, acc) in enumerate(_items(legs, altitude, acceptance_radius), start=1):
        rows.append("\t".join(
            [str(seq), "0", str(FRAME_RELATIVE_ALT), str(NAV_WAYPOINT), "0", f"{acc:g}", "0",
             "0", f"{a:.8f}", f"{b:.8f}", f"{alt:.6f}", "1"]))
    path.write_text("\n".join(rows) + "\n", encoding="ascii")
    return path


def write_qgc_plan(
    legs: StraightLegList,
    path: pathlib.Path,
    *,
    altitude: float = 50.0,
    acceptance_radius: float = 100.0,
    cruise_speed: float = 15.0,
    depart: np.datetime64 | None = None,
) -> pathlib.Path:
    """QGroundControl `.plan` JSON (mission v2, ArduPilot firmware, fixed wing); each item
    carries its ETA (s after departure; UTC with `depart`) in its `glideplan` key."""
    lat, lon = _latlon(legs)
    items: list[dict[str, Any]] = []
    etas = legs.eta_s if legs.eta_s.size else None
    when = iso_times(depart, etas) if etas is not None else []
    for k, (a, b, alt, acc) in enumerate(_items(legs, altitude, acceptance_radius), start=1):
        extra = {} if etas is None else {"glideplan": {
            "name": legs.names[k - 1], "eta_s": _finite(float(etas[k - 1])),
            "eta": when[k - 1]}}
        items.append({
            "AMSLAltAboveTerrain": None,
            "Altitude": alt,
            "AltitudeMode": 1,
            "autoContinue": True,
            "command": NAV_WAYPOINT,
            "doJumpId": k,
            "frame": FRAME_RELATIVE_ALT,
            "params": [0, acc, 0, None, a, b, alt],
            "type": "SimpleItem",
            **extra,
        })
    doc = {
        "fileType": "Plan",
        "version": 1,
        "groundStation": "QGroundControl",
        "mission": {
            "version": 2,
            "firmwareType": 3,
            "vehicleType": 1,
            "cruiseSpeed": cruise_speed,
            "hoverSpeed": cruise_speed,
            "plannedHomePosition": [lat[0], lon[0], 0],
            "items": items,
        },
        "geoFence": {"version": 2, "polygons": [], "circles": []},
        "rallyPoints": {"version": 2, "points": []},
    }
    text = json.dumps(doc, indent=2, allow_nan=False)
    if any(isinstance(v, float) and not math.isfinite(v) for v in (lat + lon)):
        raise InvalidParameterError("qgc-plan", "NaN", "coordinates must be finite")
    path.write_text(text + "\n", encoding="ascii")
    return path
