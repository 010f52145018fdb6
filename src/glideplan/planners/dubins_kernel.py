"""The one Dubins kernel: each word's closed form, written once, for floats or arrays of any dtype.

Dissertation section 2.7 (eq. 2.11: LSL, LSR, RSL, RSR, RLR, LRL), closed forms of
REFERENCE_NOTES section 4.2 (Shkel & Lumelsky 2001) in circle-centre form. For a unit radius,
a start at the origin with heading 0 and a goal (x, y, psi), the start circles are centred at
(0, +-1), the goal circles at (x -+ sin psi, y +- cos psi), and every word follows from the
vector V between the two circle centres it uses:

- LSL / RSR: straight length |V|, straight heading phi = atan2(V);
- LSR / RSL: straight length p = sqrt(|V|^2 - 4), heading atan2(V) +- atan2(2, p);
- LRL / RLR: middle arc 2 pi - acos(1 - |V|^2 / 8) (needs |V| <= 4).

Each word function returns its segment lengths (t, p, q) and a feasibility margin (feasible
where the margin is >= 0). The arithmetic comes from an `Ops` bundle: `MATH` (Python floats,
for scalar root polishing), `NUMPY64` and `NUMPY32` (arrays; float32 stays float32). The
callers — `segment_table` (per-segment lengths), `word_totals` (total lengths of the six
words) and `missions.leg_costs` (K x K heading matrices) — are thin wrappers around them.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from glideplan.pose import TWO_PI

__all__ = [
    "DIRECTIONS",
    "MATH",
    "NUMPY32",
    "NUMPY64",
    "WORDS",
    "WORD_FUNCTIONS",
    "Ops",
    "compiled_min_lengths",
    "mod_2pi_snapped",
    "ops_for",
    "segment_table",
    "shortest_word",
    "word_segments",
    "word_totals",
]

WORDS: tuple[str, ...] = ("LSL", "LSR", "RSL", "RSR", "RLR", "LRL")
"""The Dubins candidate set (eq. 2.11); indices into it are the `word_index` of results."""

DIRECTIONS: dict[str, tuple[int, int, int]] = {
    "LSL": (1, 0, 1),
    "LSR": (1, 0, -1),
    "RSL": (-1, 0, 1),
    "RSR": (-1, 0, -1),
    "RLR": (-1, 1, -1),
    "LRL": (1, -1, 1),
}
"""Turn directions (+1 left, -1 right, 0 straight) of each word's three segments."""

_INV_2PI = 1.0 / TWO_PI
_CHUNK = 32768


@dataclass(frozen=True)
class Ops:
    """Elementary functions and tolerances of one number type (floats, float64/32 arrays).

    `snap`: angles within `snap` turns below a multiple of 2 pi count as that multiple (a
    heading change of -1e-17 rad from rounding is a zero-length arc, not a full circle);
    `feas`: words whose squared straight length (or CCC cosine) misses feasibility by
    rounding only are feasible.
    """

    sin: Callable[[Any], Any]
    cos: Callable[[Any], Any]
    atan2: Callable[[Any, Any], Any]
    sqrt: Callable[[Any], Any]
    acos: Callable[[Any], Any]
    floor: Callable[[Any], Any]
    relu: Callable[[Any], Any]
    clip1: Callable[[Any], Any]
    mod: Callable[[Any], Any]
    snap: float
    feas: float


def _mod_with(floor: Callable[[Any], Any], snap: float) -> Callable[[Any], Any]:
    """Angles modulo 2 pi in [-2 pi snap, 2 pi - 2 pi snap) (rounding noise below 0 kept)."""

    def mod(a: Any) -> Any:
        return a - TWO_PI * floor(a * _INV_2PI + snap)

    return mod


def _array_mod_with(snap: float) -> Callable[[Any], Any]:
    """`_mod_with(np.floor, snap)` with one temporary array (the arrays' hot loop)."""

    def mod(a: Any) -> Any:
        out = a * _INV_2PI
        if not isinstance(out, np.ndarray):
            return a - TWO_PI * np.floor(out + snap)
        out += snap
        np.floor(out, out=out)
        out *= -TWO_PI
        out += a
        return out

    return mod


MATH = Ops(
    math.sin,
    math.cos,
    math.atan2,
    math.sqrt,
    math.acos,
    math.floor,
    lambda a: max(a, 0.0),
    lambda c: min(max(c, -1.0), 1.0),
    _mod_with(math.floor, 1e-11),
    1e-11,
    1e-10,
)


def _numpy_ops(dtype: type[np.floating[Any]], snap: float, feas: float) -> Ops:
    """Array `Ops` whose constants keep arrays of `dtype` in that precision."""
    zero, one = dtype(0.0), dtype(1.0)
    return Ops(
        np.sin,
        np.cos,
        np.arctan2,
        np.sqrt,
        np.arccos,
        np.floor,
        lambda a: np.maximum(a, zero),
        lambda c: np.clip(c, -one, one),
        _array_mod_with(snap),
        snap,
        feas,
    )


NUMPY64 = _numpy_ops(np.float64, 1e-11, 1e-10)
NUMPY32 = _numpy_ops(np.float32, 2e-6, 1e-5)


def ops_for(dtype: Any) -> Ops:
    """The array `Ops` of a floating dtype (float64 or float32)."""
    dt = np.dtype(dtype)
    if dt == np.float64:
        return NUMPY64
    if dt == np.float32:
        return NUMPY32
    raise TypeError(f"no Dubins kernel for dtype {dt}")


def mod_2pi_snapped(a: np.ndarray) -> np.ndarray:
    """Angles to [-2 pi * 1e-11, 2 pi - 2 pi * 1e-11) (mod 2 pi; rounding noise below 0 kept)."""
    return np.asarray(NUMPY64.mod(a))


# ----- the six words: (x, y, psi, sin psi, cos psi, ops) -> (t, p, q, margin) ---------------
# The order of the sums in V is deliberate: y + cos psi - 1 cancels exactly at the end of a
# pure turn (tests/dubins/test_dubins_words.py::test_pure_turns), (y - 1) + cos psi does not.

Word = tuple[Any, Any, Any, Any]


def _lsl(x: Any, y: Any, psi: Any, sp: Any, cp: Any, o: Ops) -> Word:
    vx, vy = x - sp, y + cp - 1.0  # start left circle (0, 1) to goal left circle
    phi = o.atan2(vy, vx)
    return o.mod(phi), o.sqrt(vx * vx + vy * vy), o.mod(psi - phi), 1.0


def _rsr(x: Any, y: Any, psi: Any, sp: Any, cp: Any, o: Ops) -> Word:
    vx, vy = x + sp, y - cp + 1.0  # start right circle (0, -1) to goal right circle
    phi = o.atan2(vy, vx)
    return o.mod(-phi), o.sqrt(vx * vx + vy * vy), o.mod(phi - psi), 1.0


def _lsr(x: Any, y: Any, psi: Any, sp: Any, cp: Any, o: Ops) -> Word:
    vx, vy = x + sp, y - cp - 1.0  # left to right circle: internal tangent
    p2 = vx * vx + vy * vy - 4.0
    p = o.sqrt(o.relu(p2))
    phi = o.atan2(vy * p + 2.0 * vx, vx * p - 2.0 * vy)
    return o.mod(phi), p, o.mod(phi - psi), p2 + o.feas


def _rsl(x: Any, y: Any, psi: Any, sp: Any, cp: Any, o: Ops) -> Word:
    vx, vy = x - sp, y + cp + 1.0  # right to left circle
    p2 = vx * vx + vy * vy - 4.0
    p = o.sqrt(o.relu(p2))
    phi = o.atan2(vy * p - 2.0 * vx, vx * p + 2.0 * vy)
    return o.mod(-phi), p, o.mod(psi - phi), p2 + o.feas


def _rlr(x: Any, y: Any, psi: Any, sp: Any, cp: Any, o: Ops) -> Word:
    vx, vy = x + sp, y - cp + 1.0  # both right circles, |V| <= 4
    c = 1.0 - 0.125 * (vx * vx + vy * vy)
    pm = TWO_PI - o.acos(o.clip1(c))
    t = o.mod(0.5 * pm - o.atan2(vy, vx))
    return t, pm, o.mod(pm - t - psi), c + 1.0 + o.feas


def _lrl(x: Any, y: Any, psi: Any, sp: Any, cp: Any, o: Ops) -> Word:
    vx, vy = x - sp, y + cp - 1.0  # both left circles
    c = 1.0 - 0.125 * (vx * vx + vy * vy)
    pm = TWO_PI - o.acos(o.clip1(c))
    t = o.mod(o.atan2(vy, vx) + 0.5 * pm)
    return t, pm, o.mod(psi - t + pm), c + 1.0 + o.feas


WORD_FUNCTIONS: tuple[Callable[[Any, Any, Any, Any, Any, Ops], Word], ...] = (
    _lsl,
    _lsr,
    _rsl,
    _rsr,
    _rlr,
    _lrl,
)
"""The word formulas in the order of `dubins.WORDS` (LSL, LSR, RSL, RSR, RLR, LRL)."""


def _zero_turn(o: Ops) -> float:
    return 2.0 * TWO_PI * o.snap  # turns shorter than this (rad, unit radius) are rounding


_MATH_MOD = MATH.mod
_MATH_ZERO = _zero_turn(MATH)


# ----- wrappers ------------------------------------------------------------------------------


def word_segments(k: int, x: float, y: float, psi: float) -> tuple[float, float, float] | None:
    """Segment lengths (t, p, q) of word k to the goal (x, y, psi), unit radius; None infeasible.

    Scalar (Python floats): the form used where one word is evaluated many times in a row
    (root polishing of the wind planner).
    """
    psi = _MATH_MOD(psi)
    t, p, q, margin = WORD_FUNCTIONS[k](x, y, psi, math.sin(psi), math.cos(psi), MATH)
    if margin < 0.0:
        return None
    return (0.0 if t < _MATH_ZERO else t), p, (0.0 if q < _MATH_ZERO else q)


def segment_table(x: np.ndarray, y: np.ndarray, psi: np.ndarray) -> np.ndarray:
    """Segment lengths (t, p, q) of the six words for unit radius: `(..., 6, 3)`, NaN infeasible.

    `psi` must already be reduced by `mod_2pi_snapped`.
    """
    o = NUMPY64
    sp, cp = np.sin(psi), np.cos(psi)
    out = np.empty((*np.shape(x), 6, 3))
    for k, fn in enumerate(WORD_FUNCTIONS):
        t, p, q, margin = fn(x, y, psi, sp, cp, o)
        out[..., k, 0] = t
        out[..., k, 1] = p
        out[..., k, 2] = q
        out[..., k, :][np.asarray(margin) < 0.0] = np.nan
    turns = out[..., [0, 2]]
    turns[np.abs(turns) < _zero_turn(o)] = 0.0
    out[..., [0, 2]] = turns
    np.maximum(out, 0.0, out=out, where=~np.isnan(out))
    return out


def shortest_word(table: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The optimal word of each query of a `segment_table` `(..., 6, 3)` (ties to the first
    word in `WORDS`): total length `(...)`, word index `(...)`, segment lengths `(..., 3)`."""
    totals = np.where(np.isnan(table[..., 0]), np.inf, table.sum(axis=-1))
    idx = np.argmin(totals, axis=-1)
    seg = np.take_along_axis(table, idx[..., None, None], axis=-2)[..., 0, :]
    length = np.take_along_axis(totals, idx[..., None], axis=-1)[..., 0]
    return length, idx, seg


def _total(t: np.ndarray, p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """t + p + q with turns below zero by rounding counted as zero (in place in t)."""
    np.maximum(t, 0.0, out=t)
    t += p
    t += np.maximum(q, 0.0, out=q)
    return t


def word_totals(x: np.ndarray, y: np.ndarray, psi: Any, sp: Any, cp: Any, o: Ops) -> list[Any]:
    """Total lengths t + p + q of the six words (unit radius; inf where infeasible).

    Broadcasts over its arguments (arrays of any shapes, dtype of `o`); `psi` reduced by
    `o.mod`, `sp`, `cp` its sine and cosine. Turns below zero by rounding count as zero. The
    CCC words are evaluated only where their circle centres are at most 4 apart, and
    gathered first when those points are few (far from the start).
    """
    shape = np.broadcast_shapes(np.shape(x), np.shape(y), np.shape(psi))
    out: list[Any] = []
    for fn in WORD_FUNCTIONS[:4]:
        t, p, q, margin = fn(x, y, psi, sp, cp, o)
        tot = _total(t, p, q)
        if fn is _lsr or fn is _rsl:
            np.copyto(tot, np.inf, where=margin < 0.0)
        out.append(np.broadcast_to(tot, shape))
    for fn, right in ((_rlr, True), (_lrl, False)):
        # |V|^2 of the word's circle pair, as in the word functions
        vx, vy = (x + sp, y - cp + 1.0) if right else (x - sp, y + cp - 1.0)
        near = np.broadcast_to(vx * vx + vy * vy <= 16.0 + 8.0 * o.feas, shape).ravel()
        idx = np.flatnonzero(near)
        tot = np.full(shape, np.inf, dtype=np.result_type(x, y, psi))
        if 4 * idx.size < near.size:  # few: evaluate where needed only
            if idx.size:
                xs, ys, ps, ss, cs = (
                    np.broadcast_to(a, shape).ravel()[idx] for a in (x, y, psi, sp, cp)
                )
                tot.ravel()[idx] = _total(*fn(xs, ys, ps, ss, cs, o)[:3])
        else:  # most: evaluate everywhere, mask after
            np.copyto(tot, _total(*fn(x, y, psi, sp, cp, o)[:3]), where=near.reshape(shape))
        out.append(tot)
    return out


def flat_word_totals(start: np.ndarray, goal: np.ndarray, radius: np.ndarray) -> np.ndarray:
    """Total lengths `(6, m)` (units of R, inf infeasible) for flat `(m, 3)` poses, in chunks."""
    m = start.shape[0]
    tot = np.empty((6, m))
    inv = 1.0 / radius
    scalar = inv.ndim == 0
    o = NUMPY64
    for i in range(0, m, _CHUNK):
        j = min(m, i + _CHUNK)
        s, g = start[i:j], goal[i:j]
        c0, s0 = np.cos(s[:, 2]), np.sin(s[:, 2])
        dx, dy = g[:, 0] - s[:, 0], g[:, 1] - s[:, 1]
        r = inv if scalar else inv[i:j]
        x = (c0 * dx + s0 * dy) * r
        y = (c0 * dy - s0 * dx) * r
        psi = o.mod(g[:, 2] - s[:, 2])
        tot[:, i:j] = word_totals(x, y, psi, np.sin(psi), np.cos(psi), o)
    return tot


# ----- the compiled kernel (numba): the heading DP's and the benchmark's -----------------------

def _jit() -> Any:
    """The compiled module, or None when numba cannot be imported."""
    try:
        from glideplan.planners import _dubins_jit
    except ImportError:  # pragma: no cover - numba is a dependency
        return None
    return _dubins_jit


def compiled_min_lengths(
    start: np.ndarray, goal: np.ndarray, radius: np.ndarray, *, index: bool = True
) -> tuple[np.ndarray, np.ndarray]:
    """Shortest total (units of R) and word index of flat `(m, 3)` poses, compiled.

    The same lengths as the minimum of `flat_word_totals` (to ~1e-15 relative; ties to the
    first word); `radius` scalar or `(m,)`. Vectorised polynomial trigonometry, with the
    queries near a snap, a tie or a degenerate case recomputed by the scalar kernel
    (`planners._dubins_simd`). With `index=False` the word indices stay floats (no
    conversion pass over the batch).
    """
    from glideplan.planners import _dubins_simd

    m = start.shape[0]
    out = np.empty(m)
    word = np.empty(m)
    inv = np.ascontiguousarray(np.atleast_1d(1.0 / np.asarray(radius, dtype=float)))
    _dubins_simd.flat_min_lengths(np.ascontiguousarray(start, dtype=float),
                                  np.ascontiguousarray(goal, dtype=float), inv, out, word)
    return out, (word.astype(np.intp) if index else word)
