"""Flying a piecewise-linear control history exactly, and re-timing it to end at the goal."""

from __future__ import annotations

import math

import numpy as np

from glideplan.pose import Pose

__all__ = ["fly_controls", "retime"]

_GL6_X, _GL6_W = np.polynomial.legendre.leggauss(6)


def fly_controls(
    t: np.ndarray,
    speed: np.ndarray,
    turn_rate: np.ndarray,
    start: Pose = Pose(),
    drift: tuple[float, float] = (0.0, 0.0),
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Integrate x' = v cos psi + wx, y' = v sin psi + wy, psi' = u (drift (wx, wy) in m/s,
    zero by default) for piecewise-linear controls.

    The heading is exact (piecewise quadratic); positions use 6-point Gauss-Legendre per
    piece. Returns x, y, heading at the nodes `t`.
    """
    dt = np.diff(t)
    v0, v1 = speed[:-1], speed[1:]
    u0, u1 = turn_rate[:-1], turn_rate[1:]
    dpsi = dt * 0.5 * (u0 + u1)
    psi = start.heading + np.concatenate([[0.0], np.cumsum(dpsi)])
    s = 0.5 * (_GL6_X + 1.0)  # nodes on [0, 1]
    wq = 0.5 * _GL6_W
    ps = psi[:-1, None] + dt[:, None] * (u0[:, None] * s + 0.5 * (u1 - u0)[:, None] * s**2)
    vs = v0[:, None] + (v1 - v0)[:, None] * s
    dx = dt * ((vs * np.cos(ps)) @ wq)
    dy = dt * ((vs * np.sin(ps)) @ wq)
    x = start.x + np.concatenate([[0.0], np.cumsum(dx)]) + drift[0] * (t - t[0])
    y = start.y + np.concatenate([[0.0], np.cumsum(dy)]) + drift[1] * (t - t[0])
    return x, y, psi


def retime(
    t: np.ndarray,
    speed: np.ndarray,
    turn_rate: np.ndarray,
    target: np.ndarray,
    *,
    length_scale: float = 1.0,
    pieces: int = 8,
    max_stretch: float = 0.05,
    tol: float = 1e-12,
    drift: tuple[float, float] = (0.0, 0.0),
) -> tuple[np.ndarray, float, bool]:
    """Re-time a control history so that, flown exactly, it ends at `target` (x, y, psi).

    The node values of the controls are kept (so every control stays admissible: bounds and
    nonlinear constraints hold exactly as before); only the time spent between nodes is
    stretched by a factor r_p, constant on each of `pieces` consecutive groups of nodes.
    `scipy.optimize.least_squares` (trust region, from r = 1) solves end(r) = target. Returns
    the new node times, max |r_p - 1| and whether it converged within `max_stretch`.
    """
    dt = np.diff(t)
    n = dt.size
    K = max(1, min(int(pieces), n))
    group = np.minimum((np.arange(n) * K) // n, K - 1)
    scale = np.array([length_scale, length_scale, 1.0])

    def end(r: np.ndarray) -> np.ndarray:
        tt = np.concatenate([[0.0], np.cumsum(dt * r[group])])
        x, y, psi = fly_controls(tt, speed, turn_rate, drift=drift)
        return (np.array([x[-1], y[-1], psi[-1]]) - target) / scale

    from scipy.optimize import least_squares  # imported where used (start-up time)

    # 3 equations, K unknowns: SciPy's trust-region least squares from r = 1 (no stretch)
    # takes the small steps of a minimum-norm Newton iteration and stops at a zero residual
    eps = float(np.finfo(float).eps)
    fit = least_squares(end, np.ones(K), method="trf", xtol=eps, ftol=eps, gtol=eps)
    r = fit.x
    if np.any(r <= 0.0):
        return t, math.inf, False
    e = end(r)
    tt = np.concatenate([[0.0], np.cumsum(dt * r[group])])
    stretch = float(np.max(np.abs(r - 1.0)))
    return tt, stretch, bool(np.max(np.abs(e)) < 1e3 * tol and stretch <= max_stretch)
