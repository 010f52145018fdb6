"""The known-wind first-root kernel: F_W on many virtual targets, and the cells where it crosses.

Dissertation section 3.2 and appendix A (REFERENCE_NOTES 3.4). In units where R = 1 and the
airspeed v = 1, a convected Dubins path of word W arrives at the smallest root of

    F_W(tau) = L_W(start -> g(tau)) - tau,   g(tau) = (goal - w tau, psi_goal),

for the six words W. Both the planner (`glideplan.planners.wind`, one query: a grid of tau,
then Brent's method in each candidate cell) and the mission costs
(`glideplan.missions.wind_costs`, thousands of queries: a march in steps, then batched
bisection) evaluate F_W with `word_residuals` and find the candidate cells with
`crossing_cells`, written once here.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from glideplan.planners.dubins import dubins_word_lengths
from glideplan.pose import TWO_PI

__all__ = ["crossing_cells", "word_residuals"]

FloatArray = NDArray[np.float64]


def word_residuals(start: FloatArray, goal: FloatArray, wind: FloatArray,
                   tau: FloatArray) -> FloatArray:
    """F_W(tau) of the six words, `(m, 6)` (NaN where a word does not exist), for `(m, 3)`
    start and goal poses (or one of each, `(1, 3)`; units of R), the wind `w` (units of v)
    and times `tau` `(m,)`.

    The goal's virtual target g(tau) = (goal - w tau, psi_goal); `dubins_word_lengths` is the
    Dubins kernel (eq. 2.11) on arrays.
    """
    target = np.array(np.broadcast_to(goal, (tau.shape[0], 3)))  # one goal for many tau
    target[:, 0] -= wind[0] * tau
    target[:, 1] -= wind[1] * tau
    return dubins_word_lengths(start, target, 1.0) - tau[:, None]


def crossing_cells(fa: FloatArray, fb: FloatArray) -> NDArray[np.bool_]:
    """Cells [a, b] (rows) of each word (columns) where F_W may have a root: F_W(a) > 0 and, on
    the branch through F_W(a), F_W(b) <= 0.

    L_W jumps by multiples of 2 pi where an arc wraps through a full turn; within a cell the
    branch through the left end is F_W(b) unwrapped relative to F_W(a). A word that ends or
    starts inside the cell (NaN at one end) may have its root next to that boundary.
    """
    with np.errstate(invalid="ignore"):
        jumps = np.round((fb - fa) / TWO_PI)
        cross = (fa > 0.0) & ((fb - TWO_PI * jumps <= 0.0) | (fb <= 0.0) | np.isnan(fb))
        cross |= np.isnan(fa) & (fb <= 0.0)
    return np.asarray(cross)
