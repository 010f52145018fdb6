"""Independent verification: integrate the equations of motion along a path's controls.

The kinematics x' = v cos psi, y' = v sin psi, psi' = u (eqs. 2.1, 4.1, 5.1-5.3, 6.13-6.15)
are integrated from the path's start pose using only the speed and turn-rate histories the
segments report, never their closed-form positions. On a segment whose controls are constant
(straights and arcs) the heading is exactly psi0 + u t and the positions are the quadratures
x(T) = x0 + int_0^T (v cos(psi0 + u t) + wx) dt (likewise y), evaluated with composite
Gauss-Legendre rules (NumPy) on pieces turning at most pi/4, whose error is below 1e-15 of
the piece length; this keeps SciPy out of the start-up of a Dubins plan. On a segment whose
controls are piecewise linear between its breakpoints (a direct method's `Sampled` nodes)
the heading is exact on each interval, psi(s) = psi_i + u_i s + (u_{i+1} - u_i) s^2 / (2 h),
and x, y are Gauss-Legendre quadratures of v cos psi, v sin psi per interval (split so each
piece turns at most pi/4), vectorised over the intervals. Other segments are integrated with
SciPy's DOP853 per breakpoint interval (imported when needed). The difference
between the integrated end state and the goal is the endpoint error every solution carries.
Every segment reports the steady uniform wind or current it is flown in as
`drift = (wx, wy)` (m/s; zero for most), which is added to the velocity (eq. A.4 with no
unknown part).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from glideplan.objectives import get_objective
from glideplan.path import Path
from glideplan.pose import TWO_PI, Pose, wrap_to_pi
from glideplan.segments import Segment

__all__ = ["EndpointError", "IntegratedPath", "endpoint_error", "integrate_path"]


@dataclass(frozen=True)
class EndpointError:
    """Distance (m) and absolute heading difference (rad) between integrated end and goal."""

    position: float
    heading: float

    @property
    def max(self) -> float:
        """The larger of the two (a single number for tolerances)."""
        return max(self.position, self.heading)

    def to_dict(self) -> dict[str, float]:
        return {"position": self.position, "heading": self.heading, "max": self.max}


@dataclass(frozen=True)
class IntegratedPath:
    """The end pose and accumulated cost from integrating a path's controls."""

    end: Pose
    cost: float | None


def _constant_controls(seg: Segment, rate: Any) -> tuple[float, float, float] | None:
    """(speed, turn rate, cost rate) when the segment's controls are constant, else None."""
    if not seg.constant_controls:
        return None
    v, u = seg.controls(np.array([0.0, 0.5 * seg.duration, seg.duration]))
    if np.ptp(v) > 1e-12 * abs(v[0]) or np.ptp(u) > 1e-12 * max(1.0, abs(u[0])):
        return None  # the segment's claim does not hold: integrate its controls as given
    r = float(rate(v[:1], u[:1])[0]) if rate is not None else 0.0
    return float(v[0]), float(u[0]), r


_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(16)


def _integrate_constant(
    state: np.ndarray, duration: float, controls: tuple[float, float, float], drift: np.ndarray
) -> np.ndarray:
    """Advance [x, y, heading, cost] over `duration` (s) under constant controls.

    psi(t) = psi0 + u t; x and y are Gauss-Legendre quadratures of v cos psi and v sin psi
    over pieces turning at most pi/4 (16 nodes each: exact to rounding), plus the drift
    w t. Whole turns of the heading add nothing to the air-relative displacement, so only
    the last partial turn is integrated (bounded work for any duration).
    """
    v, u, r = controls
    turn = abs(u) * duration
    rest = duration - (math.floor(turn / TWO_PI) * TWO_PI / abs(u) if u != 0.0 else 0.0)
    pieces = max(1, math.ceil(abs(u) * rest / (0.25 * math.pi)))
    edges = np.linspace(0.0, rest, pieces + 1)
    half = 0.5 * np.diff(edges)
    nodes = (0.5 * (edges[:-1] + edges[1:]))[:, None] + half[:, None] * _GL_NODES[None, :]
    psi = state[2] + u * nodes
    weights = half[:, None] * _GL_WEIGHTS[None, :]
    dx = float(np.sum(weights * v * np.cos(psi))) + drift[0] * duration
    dy = float(np.sum(weights * v * np.sin(psi))) + drift[1] * duration
    return np.array(
        [state[0] + dx, state[1] + dy, state[2] + u * duration, state[3] + r * duration]
    )


def _integrate_piecewise_linear(
    state: np.ndarray, seg: Segment, rate: Any, drift: np.ndarray
) -> np.ndarray:
    """Advance [x, y, heading, cost] over a segment with controls linear between breakpoints.

    On interval i (length h, local time s) v = v_i + dv s / h and u = u_i + du s / h, so
    psi(s) = psi_i + u_i s + du s^2 / (2 h) exactly and psi_{i+1} = psi_i + h (u_i + u_{i+1}) / 2.
    x' = v cos psi, y' = v sin psi (and the cost rate r(v, u)) are integrated by 16-node
    Gauss-Legendre rules on sub-pieces turning at most pi/4 each (every interval split into
    the same number of pieces), vectorised over all intervals.
    """
    t = seg.breakpoints()
    h = np.diff(t)
    v, u = seg.controls(t)
    dpsi = 0.5 * h * (u[:-1] + u[1:])
    psi0 = state[2] + np.concatenate([[0.0], np.cumsum(dpsi[:-1])])
    max_turn = float(np.max(np.maximum(np.abs(u[:-1]), np.abs(u[1:])) * h))
    pieces = max(1, math.ceil(max_turn / (0.25 * math.pi)))
    edges = np.linspace(0.0, 1.0, pieces + 1)
    # fraction of each interval at the quadrature nodes: (pieces * 16,), weights summing to 1
    frac = (0.5 * (edges[:-1] + edges[1:]))[:, None] + (0.5 / pieces) * _GL_NODES[None, :]
    frac = frac.ravel()
    wts = np.tile((0.5 / pieces) * _GL_WEIGHTS, pieces)
    s = h[:, None] * frac[None, :]  # (intervals, nodes) local times
    du = (u[1:] - u[:-1])[:, None]
    vs = v[:-1, None] + (v[1:] - v[:-1])[:, None] * frac[None, :]
    us = u[:-1, None] + du * frac[None, :]
    psi = psi0[:, None] + u[:-1, None] * s + 0.5 * du * frac[None, :] * s
    w = h[:, None] * wts[None, :]
    dx = float(np.sum(w * vs * np.cos(psi))) + drift[0] * seg.duration
    dy = float(np.sum(w * vs * np.sin(psi))) + drift[1] * seg.duration
    cost = 0.0
    if rate is not None:
        cost = float(np.sum(w * np.asarray(rate(vs.ravel(), us.ravel())).reshape(vs.shape)))
    return np.array([state[0] + dx, state[1] + dy, state[2] + float(np.sum(dpsi)), state[3] + cost])


def integrate_path(
    path: Path, objective: str | None = None, *, rtol: float = 1e-11, atol: float = 1e-12
) -> IntegratedPath:
    """Integrate the kinematics (and optionally the cost rate) along the path's controls."""
    rate = get_objective(objective).rate_for(path.vehicle) if objective else None
    state = np.array([path.start.x, path.start.y, path.start.heading, 0.0])
    for seg in path.segments:
        if seg.duration <= 0.0:
            continue
        wx, wy = (float(c) for c in seg.drift)
        fixed = _constant_controls(seg, rate)
        if fixed is not None:
            state = _integrate_constant(state, seg.duration, fixed, np.array([wx, wy]))
            continue
        if seg.piecewise_linear_controls:
            state = _integrate_piecewise_linear(state, seg, rate, np.array([wx, wy]))
            continue
        from scipy.integrate import solve_ivp  # only segments with varying controls need it

        def rhs(
            t: float, z: np.ndarray, seg: Segment = seg, wx: float = wx, wy: float = wy
        ) -> list[float]:
            v, u = seg.controls(np.array([t]))
            r = float(rate(v, u)[0]) if rate is not None else 0.0
            return [v[0] * math.cos(z[2]) + wx, v[0] * math.sin(z[2]) + wy, u[0], r]

        for a, b in itertools.pairwise(seg.breakpoints()):
            if b <= a:
                continue
            sol = solve_ivp(rhs, (a, b), state, method="DOP853", rtol=rtol, atol=atol)
            if not sol.success:  # pragma: no cover - DOP853 on smooth bounded fields
                raise RuntimeError(f"integration failed: {sol.message}")
            state = sol.y[:, -1]
    end = Pose(float(state[0]), float(state[1]), float(state[2]))
    return IntegratedPath(end=end, cost=float(state[3]) if rate is not None else None)


def endpoint_error(path: Path, goal: Pose) -> EndpointError:
    """Integrate the path's controls and compare the end with `goal` (heading modulo 2 pi)."""
    end = integrate_path(path).end
    return EndpointError(
        position=end.distance_to(goal),
        heading=abs(float(wrap_to_pi(goal.heading - end.heading))),
    )
