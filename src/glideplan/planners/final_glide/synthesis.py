"""Chapter 5's BSB family with drift: a synthesis for the small-bank sailplane in steady wind.

For the chapter 5 model (sink w(v) independent of the turn, |u| <= u_max; `Sailplane` with
`turning_polar=False` and `turn_rate_max`) in a steady wind w, the Hamiltonian over ground is

    H = w(v) + eta v cos(theta - psi) + eta (w . e_theta) + eta_psi u,

so the wind only adds the constant eta W_theta (W_theta = w . e_theta) to chapter 5's (5.11):
the minimising speed is still v = v_ms - lam cos(psi - theta) (5.16, clipped) with
lam = eta / 2a, B arcs turn at u_max, and S arcs fly psi = theta + pi. H = 0 on S
(eta = 2a v_S + b) now gives the wind-corrected speed to fly along the straight,

    a v_S^2 - 2 a W_theta v_S - (c + b W_theta) = 0,  v_S = W + sqrt(W^2 + (c + b W) / a),

with W = W_theta the headwind along the straight's heading (MacCready's speed in a headwind),
and lam = v_S - v_ms. A BSB candidate is fixed by theta and the straight's air length l:
the first arc turns from the start heading to theta + pi, the last from theta + pi to the
goal heading (directions d1, d2 = L/R), and the ground end point is
E(theta) + l (e_S + w / v_S) with E the arcs' air displacements plus w times their duration.
The goal lies on that line for the roots of one scalar function of theta (the cross product
with the line's direction), bracketed on a grid and polished by Brent's method; l follows.
Only BSB (the family of far goals, section 5.9) is synthesised here; the direct method
remains the solver for near goals and the check.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from glideplan.path import Path
from glideplan.planners.final_glide.segment import DriftingSegment
from glideplan.planners.min_altitude.extremals import b_arc_change, b_arc_segments
from glideplan.pose import Pose, mod_2pi
from glideplan.segments import Segment, Straight
from glideplan.vehicles.quadratic_polar_glider import QuadraticPolarGlider

__all__ = ["BSBDrift", "bsb_with_drift", "straight_speed"]

_GRID = 720


@dataclass(frozen=True)
class BSBDrift:
    """One BSB candidate in wind: orientation word, adjoint direction theta (rad), straight
    air length (m) and speed (m/s), lam (m/s), altitude loss (m) and path (ground)."""

    word: str
    theta: float
    length: float
    speed: float
    lam: float
    cost: float
    path: Path


def straight_speed(glider: QuadraticPolarGlider, headwind: np.ndarray) -> np.ndarray:
    """v_S = W + sqrt(W^2 + (c + b W) / a) for headwind W along the straight (NaN if none)."""
    W = np.asarray(headwind, dtype=float)
    disc = W**2 + (glider.c + glider.b * W) / glider.a
    return np.where(disc > 0.0, W + np.sqrt(np.where(disc > 0.0, disc, 0.0)), np.nan)


def _pieces(theta: np.ndarray, goal: Pose, glider: QuadraticPolarGlider, wind, d1: int, d2: int):
    wx, wy = wind
    W = wx * np.cos(theta) + wy * np.sin(theta)
    vs = straight_speed(glider, W)
    lam = vs - glider.v_ms
    ok = np.isfinite(vs) & (vs > glider.v_stall) & (vs <= glider.v_max) & (lam >= 0.0)
    lam_s = np.where(ok, lam, 0.0)
    vs_s = np.where(ok, vs, glider.v_stf)
    psi_s = theta + math.pi
    delta1 = d1 * mod_2pi(d1 * psi_s)
    delta2 = d2 * mod_2pi(d2 * (goal.heading - psi_s))
    c1 = b_arc_change(0.0, delta1, theta, lam_s, glider)
    c2 = b_arc_change(psi_s, delta2, theta, lam_s, glider)
    t_arcs = c1.dt + c2.dt
    ex = c1.dx + c2.dx + wx * t_arcs
    ey = c1.dy + c2.dy + wy * t_arcs
    dx = np.cos(psi_s) + wx / vs_s
    dy = np.sin(psi_s) + wy / vs_s
    gx, gy = goal.x - ex, goal.y - ey
    norm = np.hypot(dx, dy)
    cross = (gx * dy - gy * dx) / norm
    length = (gx * dx + gy * dy) / norm**2
    cost = c1.dh + c2.dh + length * glider.sink_rate(vs_s, 0.0) / vs_s
    return ok, cross, length, cost, delta1, delta2, vs_s, lam_s


def bsb_with_drift(
    goal: Pose, glider: QuadraticPolarGlider, wind: tuple[float, float]
) -> list[BSBDrift]:
    """Every BSB candidate from the origin (heading 0) to `goal` in `wind`, cheapest first."""
    thetas = np.linspace(-math.pi, math.pi, _GRID + 1)
    out: list[BSBDrift] = []
    for d1 in (1, -1):
        for d2 in (1, -1):
            ok, f, _, _, de1, de2, _, _ = _pieces(thetas, goal, glider, wind, d1, d2)
            jump = (np.abs(np.diff(de1)) > math.pi) | (np.abs(np.diff(de2)) > math.pi)
            cells = np.nonzero(ok[:-1] & ok[1:] & ~jump & (np.sign(f[:-1]) != np.sign(f[1:])))[0]
            for i in cells:

                def fn(th: float, d1: int = d1, d2: int = d2) -> float:
                    return float(_pieces(np.array([th]), goal, glider, wind, d1, d2)[1][0])

                try:
                    th = brentq(fn, thetas[i], thetas[i + 1], xtol=1e-14, rtol=1e-14)
                except ValueError:
                    continue
                res = _pieces(np.array([th]), goal, glider, wind, d1, d2)
                okk, _, ell, cost, dl1, dl2, vs, lam = (np.ravel(q)[0] for q in res)
                if not okk or ell < 0.0:
                    continue
                word = ("L" if d1 > 0 else "R") + "S" + ("L" if d2 > 0 else "R")
                path = _path(
                    float(th),
                    float(dl1),
                    float(ell),
                    float(dl2),
                    float(vs),
                    float(lam),
                    glider,
                    wind,
                )
                out.append(
                    BSBDrift(word, float(th), float(ell), float(vs), float(lam), float(cost), path)
                )
    return sorted(out, key=lambda c: c.cost)


def _path(
    theta: float,
    delta1: float,
    length: float,
    delta2: float,
    vs: float,
    lam: float,
    glider: QuadraticPolarGlider,
    wind: tuple[float, float],
) -> Path:
    """The candidate over ground: air-frame B/S/B pieces each wrapped with the drift."""
    drift = (float(wind[0]), float(wind[1]))
    segs: list[Segment] = []
    pose = Pose()

    def add(air: list[Segment]) -> None:
        nonlocal pose
        for piece in air:
            shift = Pose(pose.x - piece.start.x, pose.y - piece.start.y, 0.0)
            seg = DriftingSegment(piece.transformed(shift), drift)
            segs.append(seg)
            pose = seg.end

    d1 = 1 if delta1 >= 0 else -1
    d2 = 1 if delta2 >= 0 else -1
    add(b_arc_segments(pose, d1, abs(delta1), lam, theta, glider))
    if length > 0.0:
        add([Straight(pose, length, vs)])
    add(b_arc_segments(pose, d2, abs(delta2), lam, theta, glider))
    return Path(tuple(segs))
