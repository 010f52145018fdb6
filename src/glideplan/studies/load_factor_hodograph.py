"""The extremal control of chapter 6 for a given adjoint, by dense search over Omega (6.20).

`hc_minimiser(glider, lam, grid)` minimises H_c / eta0 = f0 - lam f_psi (section 6.5) over the
control set by evaluating a grid in the box coordinates (6.53)-(6.54) (bank angle phi and
speed fraction vbar, squared spacing dense near the stall boundary), so that the stall
boundary and the corner are grid points. Figures 6.4 and 6.5 use it as an independent check
of the closed forms (6.36), (6.37) and (6.47).
"""

from __future__ import annotations

import numpy as np

from glideplan.vehicles.load_factor_glider import LoadFactorGlider

__all__ = ["hc_minimiser"]


def hc_minimiser(glider: LoadFactorGlider, lam: float, grid: int) -> tuple[float, float]:
    """(v, n) minimising f0 - lam f_psi over Omega (turning left) on a grid x grid search."""
    vbar, phi = np.meshgrid(
        np.linspace(0.0, 1.0, grid) ** 2, np.linspace(0.0, glider.max_bank, grid)
    )
    n = 1.0 / np.cos(phi)
    v = np.sqrt(n / glider.p2) * (1.0 - vbar) + glider.v_max * vbar
    h = glider.sink_per_length(v, n) - lam * np.sqrt(np.maximum(n**2 - 1, 0)) / v**2
    i = np.unravel_index(np.argmin(h), h.shape)
    return float(v[i]), float(n[i])
