"""A route is "solved" only when its controls, flown through the field, reach the goal.

The acceptance rule (`glideplan.routing.route` module docstring): the heading controls
integrated through the field itself end within `endpoint_tolerance_m` = one routing-grid
spacing of the goal, in the water and in the field; a route that misses by more is
"not_verified" (not ok, CLI exit 1). The double gyre (Shadden et al. 2005) at 0.1-0.2 m/s,
slower than its 0.3 m/s current, is the case where open-loop controls drift far off.
"""

from __future__ import annotations

import itertools
import json
import math

import numpy as np
import pytest

import glideplan.routing
from glideplan.fields import double_gyre
from glideplan.routing import route
from glideplan.routing.sphere import EARTH_RADIUS_M, gc_distance

START, GOAL = (30.45, -39.8), (30.45, -38.2)


def _fly(result, fld, speed: float) -> float:
    """Independent re-integration (DOP853, rtol 1e-10, not verify's RK45) of the reported
    heading controls through the field on the sphere: dlat/dt = (V cos chi + v) / R,
    dlon/dt = (V sin chi + u) / (R cos lat), chi the compass heading linear in time between
    track nodes (integrated node to node: a held leg's heading switches within a
    millisecond at its vertex); returns the great-circle distance (m) from the goal where it
    ends."""
    from scipy.integrate import solve_ivp

    chi = np.unwrap(np.radians(np.asarray(result.heading_deg, dtype=float)))
    t = result.depart_s + result.t
    R = EARTH_RADIUS_M

    def rhs(s, z):
        u, v = fld.velocity(s, math.degrees(z[0]), math.degrees(z[1]))
        h = float(np.interp(s, t, chi))
        return [(speed * math.cos(h) + float(v)) / R,
                (speed * math.sin(h) + float(u)) / (R * math.cos(z[0]))]

    z = np.radians(START)
    for a, b in itertools.pairwise(t):
        if b <= a:
            continue
        sol = solve_ivp(rhs, (a, b), z, method="DOP853", rtol=1e-10, atol=1e-12,
                        max_step=(t[-1] - t[0]) / 200.0)
        assert sol.success
        z = sol.y[:, -1]
    lat, lon = np.degrees(z)
    return float(gc_distance(lat, lon, *GOAL))


def test_a_grid_route_that_misses_by_more_than_a_cell_is_rescued_or_not_verified():
    """0.1 m/s, 60 cells, no refinement: the grid route's open-loop controls end further
    from the goal than the cell. Either the characteristic tracked in closed loop verifies
    (solved, saying the others missed; its published controls re-integrated independently
    land where the verification says, within 1 %: measured 417.01 m both) or the status is
    "not_verified" (not ok), the message says why and a reported finite miss is reproduced
    by an independent integration within 1 %."""
    fld = double_gyre()
    r = route(fld, START, GOAL, 0.1, cells=60, refine=False)
    assert r.endpoint_tolerance_m == pytest.approx(r.stats["spacing_m"], rel=1e-12)
    d = r.to_dict()
    assert d["status"] == r.status and d["endpoint_tolerance_m"] == r.endpoint_tolerance_m
    if r.status == "solved":
        assert r.method == "characteristic-tracked" and "others missed" in r.message
        assert r.endpoint_error_m <= r.endpoint_tolerance_m
        assert _fly(r, fld, 0.1) == pytest.approx(r.endpoint_error_m, rel=1e-2, abs=1.0)
        return
    assert r.status == "not_verified" and not r.ok
    assert "verification" in r.message
    if math.isfinite(r.endpoint_error_m):
        assert r.endpoint_error_m > r.endpoint_tolerance_m
        assert f"{r.endpoint_error_m:.3g} m" in r.message
        assert _fly(r, fld, 0.1) == pytest.approx(r.endpoint_error_m, rel=1e-2)


def test_a_solved_route_verifies_independently():
    """0.2 m/s, 60 cells: solved, the verified endpoint error within the cell, and the
    reported controls re-integrated independently land there too (within 1 % or 1 m)."""
    fld = double_gyre()
    r = route(fld, START, GOAL, 0.2, cells=60)
    assert r.status == "solved", r.message
    assert r.endpoint_error_m is not None and r.endpoint_tolerance_m is not None
    assert r.endpoint_error_m <= r.endpoint_tolerance_m
    assert _fly(r, fld, 0.2) == pytest.approx(r.endpoint_error_m, rel=1e-2, abs=1.0)


def test_cli_states_the_tolerance_and_exits_1_when_unverified(run_cli, monkeypatch):
    """`glideplan route --example double-gyre ... --speed 0.1 --json` (the walkthrough case):
    solved with endpoint_error_m <= endpoint_tolerance_m = the grid spacing. Forced
    not verified (no refinement, 60 cells), the command prints
    `glideplan: error: route: not_verified: ...` on one line and exits 1."""
    args = ("route", "--example", "double-gyre", "--from", "30.45", "-39.8", "--to", "30.45",
            "-38.2", "--speed", "0.1")
    code, out, err = run_cli(*args, "--json")
    assert code == 0, err
    data = json.loads(out)
    assert data["status"] == "solved"
    assert data["endpoint_tolerance_m"] == pytest.approx(data["stats"]["spacing_m"], rel=1e-12)
    assert data["endpoint_error_m"] <= data["endpoint_tolerance_m"]

    real = glideplan.routing.route
    monkeypatch.setattr(glideplan.routing, "route",
                        lambda *a, **k: real(*a, **k, refine=False, cells=60))
    # without refinement the tracked characteristic now rescues it: not tried here
    monkeypatch.setattr("glideplan.routing.extract.rescue", lambda *a, **k: None)
    code, out, err = run_cli(*args)
    assert code == 1
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("glideplan: error: route: not_verified: ")
    assert "status: not_verified" in out
