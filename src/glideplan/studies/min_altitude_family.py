"""The best BBB path of the dissertation's family B for the DG-1001M examples (section 5.9).

The dissertation's family B keeps the speed unclipped, lambda <= v_ms - v_stall (Lemma
5.7.6); our synthesis also admits B arcs clipped at v_stall. Restricted to the
dissertation's family, the best BBB path is found by constrained optimisation (C.22) from
the best BBB candidate of a `Solution`: this reproduces the dissertation's printed gain.
"""

from __future__ import annotations

import math

import numpy as np

from glideplan.solution import Solution
from glideplan.vehicles.quadratic_polar_glider import QuadraticPolarGlider

__all__ = ["dissertation_family_bbb"]


def dissertation_family_bbb(solution: Solution) -> float | None:
    """Best BBB path of the dissertation's family for the solution's goal: unclipped speed
    (lambda <= v_ms - v_stall, Lemma 5.7.6), the middle arc symmetric about theta but its
    angle free (no H = 0), by SLSQP from the best BBB candidate (C.22). Altitude loss (m)."""
    from scipy.optimize import minimize

    from glideplan.planners.min_altitude import Kernel

    g = solution.vehicle
    assert isinstance(g, QuadraticPolarGlider)
    bbb = [c for c in solution.candidates if c.family == "BBB" and c.path is not None]
    if not bbb:
        return None
    angles = np.abs(np.array(bbb[0].info["angles"], dtype=float))
    mirror = bbb[0].info["angles"][0] < 0  # solve the first-turn-L mirror image
    local = solution.goal.relative_to(solution.start)
    gx, gy, gh = (
        local.x,
        (-local.y if mirror else local.y),
        (-local.heading if mirror else local.heading),
    )
    kern, u, lam_max = Kernel.of(g), g.u_max, g.v_ms - g.v_stall

    def evaluate(p: np.ndarray) -> tuple[complex, float]:
        a1, beta, a3, lam = p
        phi = np.array([beta / 2, beta / 2 - a1, -beta / 2, -beta / 2 + a3])
        P, W, _ = kern.primitives(phi, lam)
        z = np.exp(1j * (a1 - beta / 2)) * ((P[0] - P[1]) + (P[0] - P[2]) + (P[3] - P[2])) / u
        return z, float(((W[0] - W[1]) + (W[0] - W[2]) + (W[3] - W[2])) / u)

    def bc(p: np.ndarray) -> np.ndarray:
        z, _ = evaluate(p)
        d = p[0] - p[1] + p[2] - gh
        scale = g.radius_stf
        return np.array(
            [(z.real - gx) / scale, (z.imag - gy) / scale, math.sin(d), 1 - math.cos(d)]
        )

    p0 = np.array([*angles, lam_max])
    res = minimize(
        lambda p: evaluate(p)[1],
        p0,
        method="SLSQP",
        constraints=[{"type": "eq", "fun": lambda p: bc(p)[:3]}],
        bounds=[(0, 2 * math.pi)] * 3 + [(0, lam_max)],
        options={"maxiter": 500, "ftol": 1e-12},
    )
    if not res.success or np.max(np.abs(bc(res.x))) > 1e-8:
        return None
    return float(res.fun)
