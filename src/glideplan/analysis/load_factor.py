"""Chapter 6 analysis: control set, extremal controls, hodograph, polars, arc classification.

Pure functions of a `LoadFactorGlider` (nondimensional units, see its module docstring).
Arc length s is the independent variable here, as in the dissertation: curvature
psi' = sqrt(n^2 - 1) / v^2 (6.15) and sink per unit length f0 = p1 (v^2 + n^2 / v^2) (6.22).

- control set Omega (6.20), manoeuvre corridor between the stall boundary n = p2 v^2 and the
  best-glide locus n = v^2, extremal locus v^4 + n^2 = 2 (6.35), its intersection with the
  stall boundary v_lim = (2 / (1 + p2^2))^(1/4), and the corner (v_c, n_max) (Fig 6.3);
- the hodograph, the image of Omega under (f_psi, f0) (6.29, Figs 6.4-6.5);
- turn polar f0(v) for constant n (Fig 6.7) and the doghouse plot psi'(v) (Fig 6.8);
- speed along the extremal locus for a given p3 (6.41-6.44, Fig 6.9) and load factor along
  the stall boundary (6.49-6.50, Fig 6.10);
- the best constant-radius turn (the extremal locus is exactly the minimum of f0 for a
  given curvature; clipped by the stall boundary), used for initial guesses;
- classification of a control history into wings-level, extremal-locus, stall-boundary and
  corner arcs (Fig 6.11(c)).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from glideplan.errors import InvalidParameterError
from glideplan.validation import check_positive
from glideplan.vehicles.load_factor_glider import LoadFactorGlider
from glideplan.words import run_word

__all__ = [
    "ARC_CLASSES",
    "ArcClassification",
    "Curve",
    "best_turn",
    "classify_controls",
    "control_set",
    "corner",
    "doghouse",
    "extremal_locus",
    "hodograph",
    "locus_speed_history",
    "locus_speed_history_numeric",
    "locus_stall_intersection",
    "stall_load_factor_history",
    "turn_polar",
]

ARC_CLASSES = ("corner", "stall", "wings_level", "locus", "other")


@dataclass(frozen=True)
class Curve:
    """A named curve in some plane (x, y arrays) with its label for plots."""

    name: str
    x: np.ndarray
    y: np.ndarray
    label: str = ""


# ----- control set and its special curves (Fig 6.3) ------------------------------------------
def locus_stall_intersection(glider: LoadFactorGlider) -> tuple[float, float]:
    """(v_lim, n_lim): the extremal locus meets the stall boundary, v_lim = (2/(1+p2^2))^(1/4)."""
    v = (2.0 / (1.0 + glider.p2**2)) ** 0.25
    return v, math.sqrt(2.0 - v**4)


def corner(glider: LoadFactorGlider) -> tuple[float, float]:
    """(v_c, n_max): stall and maximum load factor both active (6.51)."""
    return glider.corner_speed, glider.n_limit


def extremal_locus(glider: LoadFactorGlider, n_points: int = 200) -> Curve:
    """The interior extremal locus v^4 + n^2 = 2 (6.35), from the stall boundary to (1, 1)."""
    v_lim, _ = locus_stall_intersection(glider)
    v = np.linspace(v_lim, 1.0, n_points)
    return Curve("extremal_locus", v, np.sqrt(2.0 - v**4), "extremal locus v^4 + n^2 = 2")


def control_set(glider: LoadFactorGlider, n_points: int = 200) -> dict[str, Curve]:
    """Boundaries of Omega (6.20), the manoeuvre corridor and the special curves (Fig 6.3)."""
    g = glider
    vc, nm = corner(g)
    v_st = np.linspace(g.v_min, vc, n_points)
    v_top = np.linspace(vc, g.v_max, n_points)
    n_right = np.linspace(1.0, nm, n_points)
    v_bot = np.linspace(g.v_min, g.v_max, n_points)
    v_glide = np.linspace(1.0, math.sqrt(nm), n_points)
    corridor_v = np.concatenate([v_st, [math.sqrt(nm)], v_glide[::-1], [g.v_min]])
    corridor_n = np.concatenate([g.p2 * v_st**2, [nm], v_glide[::-1] ** 2, [1.0]])
    return {
        "stall": Curve("stall", v_st, g.p2 * v_st**2, "stall boundary n = p2 v^2"),
        "max_load": Curve("max_load", v_top, np.full_like(v_top, nm), "n = n_max"),
        "max_speed": Curve("max_speed", np.full_like(n_right, g.v_max), n_right, "v = v_max"),
        "wings_level": Curve("wings_level", v_bot, np.ones_like(v_bot), "wings level n = 1"),
        "best_glide": Curve("best_glide", v_glide, v_glide**2, "best glide n = v^2"),
        "corridor": Curve("corridor", corridor_v, corridor_n, "manoeuvre corridor"),
        "extremal_locus": extremal_locus(g, n_points),
    }


# ----- rates -----------------------------------------------------------------------------------
def _rates(glider: LoadFactorGlider, v: np.ndarray, n: np.ndarray) -> tuple[np.ndarray, ...]:
    curvature = np.sqrt(np.maximum(n**2 - 1.0, 0.0)) / v**2
    return curvature, glider.sink_per_length(v, n)


def hodograph(glider: LoadFactorGlider, n_points: int = 120) -> dict[str, Any]:
    """Image of Omega under (f_psi, f0) = (+-sqrt(n^2-1)/v^2, p1 (v^2 + n^2/v^2)) (6.29).

    Returns sampled interior points (`points`: (k, 2) with turn rate and sink rate, both
    turn directions) and the images of each boundary curve of `control_set` (right half;
    mirror for left), as `Curve`s in the (f_psi, f0) plane.
    """
    g = glider
    _, nm = corner(g)
    vv, nn = np.meshgrid(np.linspace(g.v_min, g.v_max, n_points), np.linspace(1.0, nm, n_points))
    ok = g.admissible(vv, nn)
    k, f0 = _rates(g, vv[ok], nn[ok])
    pts = np.concatenate([np.stack([k, f0], -1), np.stack([-k, f0], -1)])
    curves = {}
    for name, c in control_set(g, n_points).items():
        if name in ("corridor", "best_glide"):
            continue
        kk, ff = _rates(g, c.x, c.y)
        curves[name] = Curve(name, kk, ff, c.label)
    return {"points": pts, "curves": curves}


def _constant_load_factor_curves(
    glider: LoadFactorGlider,
    load_factors: ArrayLike,
    n_points: int,
    value: Callable[[np.ndarray, float], np.ndarray],
) -> dict[str, Curve]:
    """`value(v, n)` versus speed for each load factor n <= n_limit, from its stall speed
    sqrt(n / p2) to v_max (the constant-n lines of Figs 6.7 and 6.8)."""
    out = {}
    for n in np.asarray(load_factors, dtype=float):
        if n > glider.n_limit + 1e-12:
            continue
        v = np.linspace(math.sqrt(n / glider.p2), glider.v_max, n_points)
        out[f"n={n:g}"] = Curve(f"n={n:g}", v, value(v, n), f"n = {n:g}")
    return out


def turn_polar(
    glider: LoadFactorGlider, load_factors: ArrayLike = (1.0, 1.25, 1.5, 1.75, 2.0), n_points=200
) -> dict[str, Curve]:
    """Sink per unit length f0 versus speed for constant load factors (Fig 6.7).

    Each curve starts at the stall speed for its n; "best_glide" is the locus n = v^2 of
    minimum f0 for a given n (where f0 = 2 p1 n).
    """
    g = glider
    out = _constant_load_factor_curves(g, load_factors, n_points, g.sink_per_length)
    v = np.linspace(1.0, math.sqrt(g.n_limit), n_points)
    out["best_glide"] = Curve("best_glide", v, g.sink_per_length(v, v**2), "n = v^2")
    return out


def doghouse(
    glider: LoadFactorGlider, load_factors: ArrayLike = (1.25, 1.5, 1.75, 2.0), n_points=200
) -> dict[str, Curve]:
    """Turn rate per unit length psi' = sqrt(n^2 - 1)/v^2 versus speed (Fig 6.8).

    Constant load-factor lines from their stall speed to v_max, and the stall boundary up to
    the corner (the best turn rate at the corner speed v_c).
    """
    g = glider
    out = _constant_load_factor_curves(
        g, load_factors, n_points, lambda v, n: math.sqrt(n**2 - 1.0) / v**2
    )
    v = np.linspace(g.v_min, g.corner_speed, n_points)
    n = g.p2 * v**2
    out["stall"] = Curve("stall", v, np.sqrt(np.maximum(n**2 - 1, 0.0)) / v**2, "stall boundary")
    return out


# ----- extremal arcs (6.38-6.50) ---------------------------------------------------------------
def locus_speed_history(
    glider: LoadFactorGlider, p3: float, s: ArrayLike | None = None, n_points: int = 200
) -> tuple[np.ndarray, np.ndarray, float]:
    """Speed along the extremal locus from v_lim (s = 0) to v = 1 (s = s1), eqs. (6.41)-(6.44).

    Closed form of (6.43): with A = exp(C - s) = sqrt(p3^2 - v^4) + sqrt(1 - v^4),
    sqrt(1 - v^4) = (A - (p3^2 - 1)/A) / 2. Requires p3 > 1 (s1 -> inf as p3 -> 1).
    Returns (s, v, s1).
    """
    p3 = check_positive("p3", p3)
    if p3 <= 1.0:
        raise InvalidParameterError("p3", p3, "must be > 1 on the extremal locus (6.44)")
    v_lim, _ = locus_stall_intersection(glider)
    nu_lim = v_lim**4
    C = math.log(math.sqrt(p3**2 - nu_lim) + math.sqrt(1.0 - nu_lim))
    s1 = C - 0.5 * math.log(p3**2 - 1.0)  # (6.44)
    ss = np.linspace(0.0, s1, n_points) if s is None else np.clip(np.asarray(s, float), 0, s1)
    A = np.exp(C - ss)
    b = np.clip(0.5 * (A - (p3**2 - 1.0) / A), 0.0, 1.0)
    return ss, (1.0 - b**2) ** 0.25, s1


def locus_speed_history_numeric(glider: LoadFactorGlider, p3: float, s: ArrayLike) -> np.ndarray:
    """(6.41) integrated numerically from v_lim (a check of the closed form)."""
    from scipy.integrate import solve_ivp  # imported where used (start-up time)

    v_lim, _ = locus_stall_intersection(glider)
    ss = np.asarray(s, dtype=float)

    def rhs(_s: float, y: np.ndarray) -> np.ndarray:
        v = y[0]
        val = max(p3**2 - v**4, 0.0) * max(1.0 - v**4, 0.0)
        return np.array([math.sqrt(val) / (2.0 * v**3)])

    sol = solve_ivp(rhs, (0.0, float(ss[-1])), [v_lim], t_eval=ss, rtol=1e-10, atol=1e-12)
    return sol.y[0]


def stall_load_factor_history(
    glider: LoadFactorGlider, p3: float, s_max: float = 3.0, n_points: int = 300
) -> dict[str, np.ndarray | float | bool]:
    """Load factor along the stall boundary for a given p3, eqs. (6.49)-(6.50) (Fig 6.10).

    Heading psi = 0 at n = n_lim fixes theta through (6.49); then psi' = p2 sqrt(1 - 1/n^2)
    (6.50) is integrated with n(psi) from the cubic n (n^2 - 2) = 2 p2 p3 cos(psi - theta) /
    (1 + p2^2) (monotone for n >= 1). Stops at the corner (n = n_max), when n returns to n_lim
    or at s_max. Returns s, n, psi, theta and whether the corner was reached.
    """
    from scipy.integrate import solve_ivp  # imported where used (start-up time)

    g = glider
    p3 = check_positive("p3", p3)
    p2 = g.p2
    _, n_lim = locus_stall_intersection(g)
    k = 2.0 * p2 * p3 / (1.0 + p2**2)
    c0 = n_lim * (n_lim**2 - 2.0) / k
    if abs(c0) > 1.0:
        raise InvalidParameterError("p3", p3, f"too small: needs p3 >= {abs(c0) * p3:.4g}")
    # psi - theta starts in (pi, 3 pi/2) so that cos(psi - theta), hence n, increases
    theta = -(2.0 * math.pi - math.acos(c0))

    def n_of(psi: float) -> float:
        q = k * math.cos(psi - theta)
        roots = np.roots([1.0, 0.0, -2.0, -q])
        real = roots[np.abs(roots.imag) < 1e-9].real
        return float(np.max(real))

    def rhs(_s: float, y: np.ndarray) -> np.ndarray:
        n = min(n_of(y[0]), g.n_limit)
        return np.array([p2 * math.sqrt(max(1.0 - 1.0 / n**2, 0.0))])

    def at_corner(_s: float, y: np.ndarray) -> float:
        return n_of(y[0]) - g.n_limit

    at_corner.terminal = True  # type: ignore[attr-defined]

    # n returns to n_lim when psi - theta = 2 pi + (2 pi - (psi0 - theta)): symmetric about 2 pi
    psi_back = 2.0 * (2.0 * math.pi + theta)

    def returned(_s: float, y: np.ndarray) -> float:
        return y[0] - psi_back

    returned.terminal = True  # type: ignore[attr-defined]
    ss = np.linspace(0.0, s_max, n_points)
    sol = solve_ivp(
        rhs, (0.0, s_max), [0.0], events=[at_corner, returned], dense_output=True, rtol=1e-10
    )
    s_end = float(sol.t[-1])
    ss = ss[ss <= s_end]
    if ss[-1] < s_end:
        ss = np.append(ss, s_end)
    psi = sol.sol(ss)[0]
    n = np.array([min(n_of(p), g.n_limit) for p in psi])
    reached = bool(sol.t_events[0].size > 0)
    return {"s": ss, "n": n, "psi": psi, "theta": theta, "corner": reached}


def best_turn(glider: LoadFactorGlider, radius: float) -> tuple[float, float]:
    """(v, n) that turn at constant `radius` with the least altitude loss per unit length.

    Minimising f0 = p1 (v^2 + (1 + kappa^2 v^4)/v^2) for curvature kappa = 1/radius gives
    v^4 = 1/(1 + kappa^2), which lies on the extremal locus v^4 + n^2 = 2; when that violates
    the stall boundary the best turn is on it, v^4 = 1/(p2^2 - kappa^2). Radii below the
    corner radius are not attainable (InvalidParameterError).
    """
    r = check_positive("radius", radius)
    g = glider
    if r < g.corner_radius * (1.0 - 1e-12):
        raise InvalidParameterError(
            "radius", radius, f"must be >= the corner radius {g.corner_radius:.6g}"
        )
    kappa = 1.0 / r
    v = (1.0 + kappa**2) ** -0.25
    n = math.sqrt(1.0 + kappa**2 * v**4)
    if n > g.p2 * v**2:
        v = (g.p2**2 - kappa**2) ** -0.25
        n = min(g.p2 * v**2, g.n_limit)
    return v, n


# ----- classification of a solved control history (Fig 6.11(c)) --------------------------------
@dataclass(frozen=True, eq=False)
class ArcClassification:
    """Which parts of a control history lie on which extremal (residual below a tolerance).

    `labels` per sample (one of ARC_CLASSES), `fractions` of arc length per class, `arcs`
    (runs of equal class and turn direction with their arc-length span) and `word`
    (the run letters, e.g. "L-R" for the turn directions of the significant runs).
    """

    s: np.ndarray
    speed: np.ndarray
    load_factor: np.ndarray
    direction: np.ndarray
    labels: np.ndarray
    fractions: dict[str, float]
    arcs: tuple[dict[str, Any], ...]
    turn_word: str
    tolerance: float
    residuals: dict[str, np.ndarray] = field(default_factory=dict)

    @property
    def reaches_corner(self) -> bool:
        return self.fractions.get("corner", 0.0) > 0.0

    def to_dict(self) -> dict[str, Any]:
        return {
            "tolerance": self.tolerance,
            "fractions": self.fractions,
            "reaches_corner": self.reaches_corner,
            "turn_word": self.turn_word,
            "arcs": list(self.arcs),
        }


def classify_controls(
    glider: LoadFactorGlider,
    s: ArrayLike,
    speed: ArrayLike,
    load_factor: ArrayLike,
    direction: ArrayLike | None = None,
    *,
    tol: float = 2e-3,
    min_turn_length: float = 0.05,
) -> ArcClassification:
    """Label each sample: corner, stall boundary, wings level, extremal locus or other.

    Residuals (dimensionless): corner |n - n_max| and stall |n - p2 v^2| / n; wings level
    |n - 1|; locus |v^4 + n^2 - 2| / 2. A sample takes the first class (in ARC_CLASSES
    order) whose residuals are all below `tol`. Turn-direction runs shorter than
    `min_turn_length` (arc length) are merged into their neighbours for `turn_word`.
    """
    g = glider
    ss = np.asarray(s, dtype=float)
    v = np.asarray(speed, dtype=float)
    n = np.asarray(load_factor, dtype=float)
    d = np.sign(np.asarray(direction, dtype=float)) if direction is not None else np.ones_like(v)
    r_stall = np.abs(n - g.p2 * v**2) / n
    r_corner = np.maximum(np.abs(n - g.n_limit), r_stall)
    r_level = np.abs(n - 1.0)
    r_locus = np.abs(v**4 + n**2 - 2.0) / 2.0
    labels = np.full(v.shape, "other", dtype=object)
    for name, r in (
        ("locus", r_locus),
        ("wings_level", r_level),
        ("stall", r_stall),
        ("corner", r_corner),
    ):
        labels = np.where(r < tol, name, labels)
    # arc-length weights: half the neighbouring spacings
    ds = np.diff(ss)
    w = np.zeros_like(ss)
    w[:-1] += 0.5 * ds
    w[1:] += 0.5 * ds
    total = float(np.sum(w)) or 1.0
    fractions = {c: float(np.sum(w[labels == c]) / total) for c in ARC_CLASSES}
    turn = np.where(labels == "wings_level", 0.0, d)
    arcs: list[dict[str, Any]] = []
    start = 0
    for i in range(1, ss.size + 1):
        if i == ss.size or labels[i] != labels[start] or turn[i] != turn[start]:
            arcs.append(
                {
                    "kind": str(labels[start]),
                    "direction": {1.0: "L", -1.0: "R", 0.0: "S"}[float(turn[start])],
                    "s_start": float(ss[start]),
                    "s_end": float(ss[min(i, ss.size - 1)]),
                }
            )
            start = i
    return ArcClassification(
        s=ss,
        speed=v,
        load_factor=n,
        direction=d,
        labels=labels,
        fractions=fractions,
        arcs=tuple(arcs),
        turn_word=_turn_word(ss, d, n, min_turn_length),
        tolerance=tol,
        residuals={"stall": r_stall, "corner": r_corner, "wings_level": r_level, "locus": r_locus},
    )


def _turn_word(s: np.ndarray, d: np.ndarray, n: np.ndarray, min_len: float) -> str:
    """Turn letters of runs of the turn direction (banked samples only), short runs dropped."""
    banked = (n > 1.0 + 1e-6)[:-1]
    letters = np.where(d[:-1] > 0, "L", "R")[banked]
    return "-".join(run_word(letters, np.diff(s)[banked], min_weight=min_len))
