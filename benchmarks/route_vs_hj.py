"""Routing on the double gyre: glideplan's whole route against hj_reachability's solve (issue 18).

Run: `.venv/bin/python benchmarks/route_vs_hj.py [--spacings 1000,500] [--reference 250]`.
Needs the bench extras (`jax`, `hj-reachability`); without them the peer rows say so.

Problem (the one `benchmarks/route.py` uses): the time-periodic double gyre (L = 150 km,
max 0.4 m/s) sampled like a forecast file (48 levels 3 h apart, 0.02 deg), a vehicle at 0.5
m/s through the water from 30.25 N 39.75 W to 31.05 N 38.82 W, departing at t = 0.

- glideplan: `glideplan.routing.route(field, start, goal, 0.5, resolution=h)`, the whole
  pipeline (grid, front, backtrack, refinement, verification through the field), wall time.
- hj_reachability (accuracy "high": WENO3 + TVD-RK3, Lax-Friedrichs dissipation, CFL 0.75):
  the forward reachable set of a start disk (the same 10-cell disk), phi_t + max_u grad phi .
  (c(x, t) + u) = 0 with |u| <= V, on a plane grid of spacing h in the azimuthal-equidistant
  plane about the start covering the same box, the current sampled at the nodes and linear
  in time between the 48 levels. Stepped to output times every (T_est / 400) and stopped once
  phi(goal) <= 0 (arrival interpolated linearly in time between outputs). Timed warm (after a
  compile run on the same shapes) and cold.
- Reference arrival: glideplan's route at the `--reference` spacing, refined and verified
  (its heading controls flown through the field end within the tolerance); its Zermelo
  extremal is independent of the grid, so it is the converged answer both are measured against.
"""

from __future__ import annotations

import argparse
import math
import pathlib
import sys
import time
from typing import Any

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).parent))

from route import GOAL, SPEED, START, gridded_gyre

from glideplan.fields import GriddedField
from glideplan.geodesy import LocalProjection
from glideplan.routing import route


def ours(field: GriddedField, spacing: float) -> dict[str, Any]:
    t0 = time.perf_counter()
    r = route(field, START, GOAL, SPEED, resolution=spacing)
    wall = time.perf_counter() - t0
    return {"wall": wall, "T": r.duration_s, "grid_T": r.grid_duration_s,
            "status": str(r.status), "stats": dict(r.stats)}


def _box(spacing: float) -> tuple[np.ndarray, np.ndarray, LocalProjection, tuple[float, float]]:
    proj = LocalProjection(*START)
    gx, gy = (float(a) for a in proj.to_local(*GOAL))
    dist = math.hypot(gx, gy)
    pad = 0.5 * dist
    x0, x1 = min(0.0, gx) - pad, max(0.0, gx) + pad
    y0, y1 = min(0.0, gy) - pad, max(0.0, gy) + pad
    xs = np.arange(math.floor(x0 / spacing), math.ceil(x1 / spacing) + 1) * spacing
    ys = np.arange(math.floor(y0 / spacing), math.ceil(y1 / spacing) + 1) * spacing
    return xs, ys, proj, (gx, gy)


def hj_route(field: GriddedField, spacing: float, t_est: float, warm: bool) -> dict[str, Any]:
    """hj_reachability's forward reachable set to the goal (module docstring)."""
    import hj_reachability as hj
    import jax
    import jax.numpy as jnp

    jax.config.update("jax_enable_x64", True)
    xs, ys, proj, (gx, gy) = _box(spacing)
    XX, YY = np.meshgrid(xs, ys, indexing="ij")  # hj grids are (x, y) indexed
    lat, lon = proj.to_geographic(XX, YY)
    lat1, lon1 = proj.to_geographic(XX, YY + 10.0)
    lat2, lon2 = proj.to_geographic(XX + 10.0, YY)
    # local north direction: d(lat)/dy, east: d(lon)/dx -- rotate (u east, v north) into (x, y)
    nx_, ny_ = proj.to_local(lat + 1e-4, lon)
    x0_, y0_ = proj.to_local(lat, lon)
    nvec = np.stack([nx_ - x0_, ny_ - y0_])
    nvec /= np.hypot(*nvec)
    evec = np.stack([nvec[1], -nvec[0]])
    del lat1, lon1, lat2, lon2
    times = field.times
    cur = np.empty((times.size, xs.size, ys.size, 2))
    for k, t in enumerate(times):
        u, v = field.velocity(t, lat, lon)
        u, v = np.nan_to_num(u), np.nan_to_num(v)
        cur[k, ..., 0] = u * evec[0] + v * nvec[0]
        cur[k, ..., 1] = u * evec[1] + v * nvec[1]
    cur_j = jnp.asarray(cur)
    times_j = jnp.asarray(times)
    origin = jnp.array([xs[0], ys[0]])
    h = spacing

    class Zermelo(hj.ControlAndDisturbanceAffineDynamics):
        def __init__(self) -> None:
            super().__init__("max", "min", hj.sets.Ball(jnp.zeros(2), SPEED),
                             hj.sets.Ball(jnp.zeros(1), 0.0))

        def open_loop_dynamics(self, state: Any, time: Any) -> Any:
            ij = jnp.round((state - origin) / h).astype(jnp.int32)
            k = jnp.clip(jnp.searchsorted(times_j, time, side="right") - 1, 0, times_j.size - 2)
            w = jnp.clip((time - times_j[k]) / (times_j[k + 1] - times_j[k]), 0.0, 1.0)
            return (1 - w) * cur_j[k, ij[0], ij[1]] + w * cur_j[k + 1, ij[0], ij[1]]

        def control_jacobian(self, state: Any, time: Any) -> Any:
            return jnp.eye(2)

        def disturbance_jacobian(self, state: Any, time: Any) -> Any:
            return jnp.zeros((2, 1))

    grid = hj.Grid.from_lattice_parameters_and_boundary_conditions(
        hj.sets.Box(np.array([xs[0], ys[0]]), np.array([xs[-1], ys[-1]])), (xs.size, ys.size))
    r0 = min(10.0 * spacing, 0.3 * math.hypot(gx, gy))
    tau0 = r0 / SPEED
    # the exact start set at tau0 (as glideplan's): the disk of radius r0 about c tau0, c the
    # current at the start averaged over [0, tau0]
    c0 = 0.5 * (cur[0, round(-xs[0] / h), round(-ys[0] / h)]
                + (cur[0] + (cur[1] - cur[0]) * min(tau0 / (times[1] - times[0]), 1.0))[
                    round(-xs[0] / h), round(-ys[0] / h)])
    values = jnp.asarray(np.hypot(XX - c0[0] * tau0, YY - c0[1] * tau0) - r0)
    settings = hj.SolverSettings.with_accuracy("high")
    dyn = Zermelo()
    gi = round((gx - xs[0]) / h)
    gj = round((gy - ys[0]) / h)
    wx = (gx - xs[gi]) / h
    wy = (gy - ys[gj]) / h

    def at_goal(v: Any) -> float:
        v = np.asarray(v)
        i0 = gi if wx >= 0 else gi - 1
        j0 = gj if wy >= 0 else gj - 1
        fx = (gx - xs[i0]) / h
        fy = (gy - ys[j0]) / h
        return float((1 - fx) * ((1 - fy) * v[i0, j0] + fy * v[i0, j0 + 1])
                     + fx * ((1 - fy) * v[i0 + 1, j0] + fy * v[i0 + 1, j0 + 1]))

    def run() -> tuple[float | None, float]:
        t = tau0
        v = values
        dt_out = t_est / 400.0
        old = at_goal(v)
        start = time.perf_counter()
        arrival = None
        while t < times[-1]:
            t_next = min(t + dt_out, float(times[-1]))
            v = hj.step(settings, dyn, grid, t, v, t_next, progress_bar=False)
            new = at_goal(v)
            if new <= 0.0:
                arrival = t + (t_next - t) * old / (old - new) if old > 0 else t_next
                break
            old, t = new, t_next
        return arrival, time.perf_counter() - start

    cold_arr, cold = run()
    out: dict[str, Any] = {"cold": cold, "T": cold_arr, "shape": (xs.size, ys.size)}
    if warm:
        arr, wall = run()
        out.update(warm=wall, T=arr)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spacings", default="1000,500", help="routing spacings (m), comma-separated")
    ap.add_argument("--reference", type=float, default=250.0, help="reference spacing (m)")
    ap.add_argument("--no-peer", action="store_true", help="skip hj_reachability")
    args = ap.parse_args()
    field = gridded_gyre()
    spacings = [float(s) for s in args.spacings.split(",")]
    print("# Route on the double gyre: glideplan vs hj_reachability\n")
    ref = ours(field, args.reference)
    T_ref = ref["T"]
    print(f"reference: glideplan at {args.reference:g} m, status {ref['status']}, "
          f"arrival {T_ref:.1f} s ({ref['wall']:.1f} s to compute)\n")
    rows = []
    for h in spacings:
        o = ours(field, h)
        peer: dict[str, Any] = {}
        if not args.no_peer:
            try:
                peer = hj_route(field, h, T_ref, warm=True)
            except ImportError as exc:
                peer = {"error": f"not installed ({exc.name})"}
        rows.append((h, o, peer))
    print("| spacing | glideplan route (s) | its arrival error (grid front) "
          "| hj_reachability solve warm / cold (s) | its arrival error | speed-up (warm) |")
    print("|---|---|---|---|---|---|")
    for h, o, p in rows:
        err = abs(o["T"] - T_ref) / T_ref if o["T"] else math.nan
        gerr = abs(o["grid_T"] - T_ref) / T_ref if o["grid_T"] else math.nan
        if "warm" in p:
            perr = abs(p["T"] - T_ref) / T_ref if p["T"] else math.nan
            print(f"| {h:g} m | {o['wall']:.2f} | {err:.2e} ({gerr:.2e}) "
                  f"| {p['warm']:.2f} / {p['cold']:.2f} | {perr:.2e} "
                  f"| {p['warm'] / o['wall']:.1f}x |")
        else:
            print(f"| {h:g} m | {o['wall']:.2f} | {err:.2e} ({gerr:.2e}) "
                  f"| {p.get('error', 'skipped')} | | |")
    print("\nphases (s):")
    for h, o, _ in rows:
        st = {k: v for k, v in o["stats"].items() if k.endswith("_s")}
        print(f"- {h:g} m: {st}; grid arrival {o['grid_T']}")
    print("\npeer figures: hj_reachability 0.7.0 (jax, CPU) measured in this run, same process,"
          " same field samples, same box.")


if __name__ == "__main__":
    main()
