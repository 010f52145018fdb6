"""Solve each candidate type of (4.26) for every extremal meeting the boundary conditions.

Normalised units (R = 1, u_max = 1, rho = r/R, see `geometry`). The start is the origin.

Derivation (section 4.3 with H = 0). With eta = eta0 * lam, the Hamiltonian (4.12) vanishes
along a normal extremal, which on a left B arc gives eta_psi/eta0 = -1 - lam cos(psi - theta)
and on a left C arc eta_psi/eta0 = -1 - rho lam cos(psi - theta) (mirror for right turns).
The speed switch |eta_psi| = eta0/u_max (4.15) therefore happens where cos(psi - theta) = 0 on
both arcs: C is flown while cos(psi - theta) > 0, B while cos(psi - theta) < 0, so an uncut C
arc subtends exactly pi. The turn direction reverses where eta_psi = 0, i.e. where
cos(psi - theta) = -1/lam:

- lam > 1 (rigid turns, Gamma_TTTT): reversals at psi - theta = +-(pi/2 + a) with
  a = asin(1/lam) in (0, pi/2); every interior turn is B^a C^pi B^a and the B arcs on
  both sides of a reversal equal a;
- lam = 1 (flexible turns, Gamma_TST): S is flown at psi = theta + pi; the B arc next to S
  is pi/2 whenever a C arc follows;
- lam < 1: no reversal; the turn rate is fixed (Gamma_umax). With eta = 0 the speed is
  singular (H = 0 for every speed), every profile with the same heading change costs the same.

Solving a type. Let A be the centre of the last B circle of the first piece and Z the centre
of the first B circle of the last piece. Varying the first piece's free angle u1 rotates
everything after it about the centre K1 of the first arc, and likewise for the last piece
about the goal circle K2, so A = K1 + Rot(h1) a1 and Z = K2 + Rot(h2) z1 with h1, h2 the
headings at the pieces' inner ends. The middle (a straight of length L, or m interior turns)
is a rigid displacement in the frame of h1, which gives

    K2 - K1 = Rot(h1) V,   V = a1 - d1 e_y + sigma + d2 Rot(eta) e_y - Rot(eta) z1,

with (sigma, eta) the middle's pose displacement. Taking norms removes h1:
- Gamma_TST: V = W + L e_x, so |V| = |K2 - K1| is a quadratic in L (closed form);
- Gamma_TTTT: |V(a)|^2 - |K2 - K1|^2 is a trigonometric polynomial of degree <= 2 in a (its
  Fourier coefficients come from 16 samples, exact to degree 7, and the degree is checked);
  all its roots in [0, pi/2] come from one batched companion-matrix eigenvalue solve.
The goal enters only through K2 - K1, so V(a) is precomputed once per speed ratio.
h1 then follows from the angle between V and K2 - K1, and u1, u2 from h1 (each within a range
shorter than 2 pi, hence unique). The result is every extremal of the type, deterministically.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

import numpy as np

from glideplan.planners.min_time.geometry import compose, normal, rotate
from glideplan.planners.min_time.table import (
    CANDIDATE_TYPES,
    SUPPLEMENTARY_TYPES,
    CandidateType,
    conditions,
    long_form,
    rigid_types,
)
from glideplan.pose import TWO_PI, mod_2pi, wrap_to_pi

__all__ = [
    "Extremal",
    "piece_moves",
    "solve_all",
    "solve_type",
    "trig_roots",
]

PI = math.pi
_EY = np.array([0.0, 1.0])
_RANGE_TOL = 1e-9  # how far outside a parameter range a root may fall and be clipped
_END_TOL = 1e-8  # normalised endpoint error accepted for a solution

Move = tuple[str, int, float]


@dataclass(frozen=True)
class Extremal:
    """A solution of one candidate type in normalised units: moves, cost and parameters."""

    ctype: CandidateType
    moves: tuple[Move, ...]
    cost: float
    params: dict[str, Any] = field(default_factory=dict)
    conditions: dict[str, bool] = field(default_factory=dict)
    end_error: float = 0.0

    @property
    def family(self) -> str:
        return "".join(m[0] for m in self.moves)


def piece_moves(kind: str, where: str, d: int, u: Any, a: Any) -> list[tuple[str, int, Any]]:
    """Moves of a boundary piece ("first" or "last") or an interior turn ("T")."""
    if where == "first":
        table = {
            "B": [("B", u)],
            "CB": [("C", u), ("B", a)],
            "BCB": [("B", u), ("C", PI), ("B", a)],
        }
    elif where == "last":
        table = {
            "B": [("B", u)],
            "BC": [("B", a), ("C", u)],
            "BCB": [("B", a), ("C", PI), ("B", u)],
        }
    else:
        table = {"T": [("B", a), ("C", PI), ("B", a)]}
    return [(label, d, amount) for label, amount in table[kind]]


def _radius(label: str, rho: float) -> float:
    return 1.0 if label == "B" else rho


def _first_geometry(
    kind: str, d: int, a: np.ndarray, rho: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """K1 (centre of the first arc), a1 (A - K1 in the h1 frame), h1 at u1 = 0."""
    zero = np.zeros_like(a)
    moves = piece_moves(kind, "first", d, zero, a)
    p, h = compose(moves, rho, a.shape)
    k1 = np.array([0.0, d * _radius(moves[0][0], rho)])
    a_center = p + d * normal(h)
    return k1, rotate(-h, a_center - k1), h


def _middle(m: int, d1: int, a: np.ndarray, rho: float) -> tuple[np.ndarray, np.ndarray]:
    """Pose displacement (sigma, eta) of m interior turns after a reversal from direction d1."""
    moves: list[tuple[str, int, Any]] = []
    d = -d1
    for _ in range(m):
        moves += piece_moves("T", "interior", d, None, a)
        d = -d
    return compose(moves, rho, a.shape)


def _finish(
    ctype: CandidateType,
    first: str,
    last: str,
    u1: float,
    u2: float,
    a: float,
    middle: list[tuple[str, int, Any]],
    rho: float,
    goal: np.ndarray,
    extra: dict[str, Any],
) -> Extremal | None:
    """The extremal of type `ctype` with end pieces `first`/`last` and the given middle moves,
    or None when it misses the goal by more than the end tolerance."""
    d1, d2 = ctype.directions[0], ctype.directions[-1]
    moves = piece_moves(first, "first", d1, u1, a) + middle + piece_moves(last, "last", d2, u2, a)
    moves_f: tuple[Move, ...] = tuple((lab, d, float(x)) for lab, d, x in moves)
    p, h = compose(moves_f, rho, ())
    dh = float(wrap_to_pi(float(h) - goal[2]))
    err = max(float(np.hypot(*(p - goal[:2]))), abs(dh))
    if err > _END_TOL:
        return None
    cost = sum(x for _, _, x in moves_f)
    turns = long_form(ctype, first, last, u1, u2, a)
    params = {"first": first, "last": last, "u1": u1, "u2": u2, **extra}
    return Extremal(ctype, moves_f, cost, params, conditions(ctype, turns, rho), err)


def _last_local(kind: str, d: int, a: np.ndarray, rho: float) -> tuple[np.ndarray, np.ndarray]:
    """z1 (Z - K2 in the frame of the piece's entry heading) and the piece's heading change."""
    zero = np.zeros_like(a)
    moves = piece_moves(kind, "last", d, zero, a)
    p, he = compose(moves, rho, a.shape)
    k2_local = p + d * _radius(moves[-1][0], rho) * normal(he)
    return np.array([0.0, float(d)]) - k2_local, he


def _v_of_a(
    ctype: CandidateType, first: str, last: str, a: np.ndarray, rho: float
) -> tuple[np.ndarray, ...]:
    """V(a), h1 at u1 = 0, the last piece's heading change and the middle's, at angles a."""
    d1, d2 = ctype.directions[0], ctype.directions[-1]
    _, a1, h10 = _first_geometry(first, d1, a, rho)
    z1, he = _last_local(last, d2, a, rho)
    if ctype.straight:
        sigma, eta = np.zeros((*a.shape, 2)), np.zeros(a.shape)
        v = a1 + (d2 - d1) * _EY - z1  # + L e_x, added by the caller
    else:
        sigma, eta = _middle(ctype.interior, d1, a, rho)
        v = a1 - d1 * _EY + sigma + d2 * normal(eta) - rotate(eta, z1)
    return v, h10, he, eta


_SAMPLES = 16  # samples per period for the Fourier coefficients (degrees < 8 exact)


@dataclass(frozen=True, eq=False)
class _Stack:
    """Goal-independent geometry of every branch of one group, stacked, for one rho.

    Branch i is (ctype, first piece, last piece). K1 = (0, d1 r_first) is the centre of the
    first arc; the goal arc's centre is K2 = goal + d2 r_last n(psi1). Headings that depend on
    a are affine in it: h1(u1 = 0) = h10[:, 0] + h10[:, 1] a, likewise `he` (heading change of
    the last piece at u2 = 0) and `eta` (of the middle). Gamma_TST: `w` = V at L = 0. Gamma_TTTT:
    `coef` = Fourier coefficients c_0..c_K of |V(a)|^2, `vcoef` those of V's components.
    """

    items: tuple[tuple[CandidateType, str, str], ...]
    d1: np.ndarray
    d2: np.ndarray
    r_first: np.ndarray
    r_last: np.ndarray
    hi_first: np.ndarray  # upper end of u1's range: pi for "CB", else a (coded as -1)
    hi_last: np.ndarray
    h10: np.ndarray
    he: np.ndarray
    eta: np.ndarray
    w: np.ndarray | None = None
    coef: np.ndarray | None = None
    vcoef: np.ndarray | None = None
    degree: np.ndarray | None = None


def _affine(values0: np.ndarray, values1: np.ndarray) -> np.ndarray:
    return np.stack([values0, values1 - values0], axis=-1)


def _types_for(key: str) -> tuple[CandidateType, ...]:
    """The candidate types behind a solver key: "TST", "TTTT" (those of (4.26)),
    "supplementary" (`SUPPLEMENTARY_TYPES`) or "interiorM" (rigid, M interior turns)."""
    if key in ("TST", "TTTT"):
        return tuple(t for t in CANDIDATE_TYPES if t.group == key)
    if key == "supplementary":
        return SUPPLEMENTARY_TYPES
    if key.startswith("interior"):
        return rigid_types(int(key[len("interior") :]))
    raise KeyError(key)


@lru_cache(maxsize=64)
def _stack(key: str, rho: float) -> _Stack:
    group = "TST" if key == "TST" else "TTTT"
    items = tuple((t, first, last) for t in _types_for(key) for first, last in t.branches)
    d1 = np.array([t.directions[0] for t, _, _ in items], dtype=float)
    d2 = np.array([t.directions[-1] for t, _, _ in items], dtype=float)
    r_first = np.array([rho if f == "CB" else 1.0 for _, f, _ in items])
    r_last = np.array([rho if la == "BC" else 1.0 for _, _, la in items])
    hi_first = np.array([PI if f == "CB" else -1.0 for _, f, _ in items])
    hi_last = np.array([PI if la == "BC" else -1.0 for _, _, la in items])
    zero, one = np.zeros(1), np.ones(1)
    h10, he, eta = [], [], []
    for t, f, la in items:
        g0 = _v_of_a(t, f, la, zero, rho)
        g1 = _v_of_a(t, f, la, one, rho)
        h10.append(_affine(g0[1][0], g1[1][0]))
        he.append(_affine(g0[2][0], g1[2][0]))
        eta.append(_affine(g0[3][0], g1[3][0]))
    common: dict[str, Any] = dict(
        items=items,
        d1=d1,
        d2=d2,
        r_first=r_first,
        r_last=r_last,
        hi_first=hi_first,
        hi_last=hi_last,
        h10=np.array(h10),
        he=np.array(he),
        eta=np.array(eta),
    )
    if group == "TST":
        half = np.full(1, PI / 2)
        w = np.array([_v_of_a(t, f, la, half, rho)[0][0] for t, f, la in items])
        return _Stack(**common, w=w)
    grid = np.arange(_SAMPLES) * (TWO_PI / _SAMPLES)
    vs = np.array([_v_of_a(t, f, la, grid, rho)[0] for t, f, la in items])  # (nb, S, 2)
    coef = np.fft.rfft(np.sum(vs * vs, axis=-1), axis=-1) / _SAMPLES
    vcoef = np.fft.rfft(vs, axis=1) / _SAMPLES  # (nb, S/2+1, 2)
    scale = np.max(np.abs(coef), axis=-1, keepdims=True)
    big = np.abs(coef) > 1e-10 * scale
    degree = np.array([int(np.nonzero(row)[0].max()) for row in big])
    if np.any(degree >= _SAMPLES // 2 - 1):  # pragma: no cover - degree is at most 2
        raise ArithmeticError("trigonometric degree too high for the sample count")
    return _Stack(**common, coef=coef, vcoef=vcoef, degree=degree)


def _goal_offsets(st: _Stack, goal: np.ndarray) -> np.ndarray:
    """K2 - K1 for every branch, shape (nb, 2)."""
    n = np.array([-math.sin(goal[2]), math.cos(goal[2])])
    k2 = goal[:2] + (st.d2 * st.r_last)[:, None] * n
    k2[:, 1] -= st.d1 * st.r_first
    return k2


def _wrap_range(u: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """u mod 2 pi clipped into [0, hi] (within tolerance) and the mask of those inside."""
    u = np.asarray(mod_2pi(u))
    u = np.where(u > TWO_PI - _RANGE_TOL, u - TWO_PI, u)
    ok = (u >= -_RANGE_TOL) & (u <= hi + _RANGE_TOL)
    return np.clip(u, 0.0, hi), ok


def _trig_eval(coef: np.ndarray, a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """f(a) = c_0 + 2 Re sum_{k>=1} c_k e^{ika} and f'(a), row-wise (coef (n, K+1), a (n,))."""
    k = np.arange(coef.shape[-1])
    e = np.exp(1j * a[:, None] * k)
    f = 2.0 * np.real(np.sum(e * coef, axis=-1)) - np.real(coef[:, 0])
    df = 2.0 * np.real(np.sum(1j * k * e * coef, axis=-1))
    return f, df


def _coef_roots_batch(coef: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Real roots in [0, 2 pi) of rows of trigonometric coefficients of one degree K >= 1.

    z^K f(e^{ia}) is a polynomial of degree 2K whose unit-circle roots are the real roots of f
    (tangential ones included); one batched companion eigenvalue solve finds them all.
    Returns (row index, root) arrays.
    """
    n, kp1 = coef.shape
    deg = kp1 - 1
    poly = np.concatenate([coef[:, ::-1], np.conj(coef[:, 1:])], axis=1)  # highest first
    lead = poly[:, :1]
    monic = poly[:, 1:] / lead
    m = 2 * deg
    comp = np.zeros((n, m, m), dtype=complex)
    comp[:, 0, :] = -monic
    if m > 1:
        idx = np.arange(m - 1)
        comp[:, idx + 1, idx] = 1.0
    z = np.linalg.eigvals(comp)
    rows = np.repeat(np.arange(n), m)
    z = z.ravel()
    keep = np.abs(np.abs(z) - 1.0) < 1e-4
    rows, a = rows[keep], np.asarray(mod_2pi(np.angle(z[keep])))
    scale = np.max(np.abs(coef), axis=-1)[rows]
    for _ in range(3):  # Newton polish on f itself
        f, df = _trig_eval(coef[rows], a)
        safe = np.abs(df) > 1e-14 * scale
        a = np.asarray(mod_2pi(a - np.where(safe, f / np.where(safe, df, 1.0), 0.0)))
    return rows, a


def _solve_tst(goal: np.ndarray, rho: float, key: str = "TST") -> list[Extremal]:
    """All Gamma_TST extremals T S T: per branch a quadratic in L (closed form)."""
    st = _stack("TST", rho)
    assert st.w is not None
    dk = _goal_offsets(st, goal)
    dist2 = np.sum(dk * dk, axis=-1)
    disc = dist2 - st.w[:, 1] ** 2
    root = np.sqrt(np.maximum(disc, 0.0))
    rows = np.concatenate([np.arange(len(st.items))] * 2)
    length = np.concatenate([-st.w[:, 0] + root, -st.w[:, 0] - root])
    ok = np.concatenate([disc >= -1e-12] * 2) & (length >= -1e-10)
    ok[len(st.items) :] &= root > 0.0  # one solution when the discriminant vanishes
    rows, length = rows[ok], np.maximum(length[ok], 0.0)
    vx, vy = st.w[rows, 0] + length, st.w[rows, 1]
    h1 = np.arctan2(dk[rows, 1], dk[rows, 0]) - np.arctan2(vy, vx)
    u1, ok1 = _wrap_range(
        st.d1[rows] * (h1 - st.h10[rows, 0] - st.h10[rows, 1] * PI / 2),
        np.where(st.hi_first[rows] > 0, PI, PI / 2),
    )
    he = st.he[rows, 0] + st.he[rows, 1] * PI / 2
    u2, ok2 = _wrap_range(
        st.d2[rows] * (goal[2] - he - h1), np.where(st.hi_last[rows] > 0, PI, PI / 2)
    )
    good = ok1 & ok2 & ((vx * vx + vy * vy > 1e-24) | (dist2[rows] > 1e-24))
    out = []
    for i in np.nonzero(good)[0]:
        t, first, last = st.items[rows[i]]
        li = float(length[i])
        sol = _finish(
            t, first, last, float(u1[i]), float(u2[i]), PI / 2, [("S", 0, li)], rho, goal, {"L": li}
        )
        if sol is not None:
            out.append(sol)
    return out


def _solve_tttt(goal: np.ndarray, rho: float, key: str = "TTTT") -> list[Extremal]:
    """All rigid extremals of the types behind `key`: roots a in [0, pi/2] of
    |V(a)|^2 = |K2 - K1|^2."""
    st = _stack(key, rho)
    assert st.coef is not None and st.vcoef is not None and st.degree is not None
    dk = _goal_offsets(st, goal)
    coef = st.coef.copy()
    coef[:, 0] -= np.sum(dk * dk, axis=-1)
    rows_all, roots_all = [], []
    for deg in np.unique(st.degree):
        if deg == 0:
            continue
        sel = np.nonzero(st.degree == deg)[0]
        r, a = _coef_roots_batch(coef[sel, : deg + 1])
        rows_all.append(sel[r])
        roots_all.append(a)
    if not rows_all:
        return []
    rows, a = np.concatenate(rows_all), np.concatenate(roots_all)
    inside = (a >= -1e-12) & (a <= PI / 2 + 1e-12)
    rows, a = rows[inside], np.clip(a[inside], 0.0, PI / 2)
    vx, _ = _trig_eval(st.vcoef[rows, :, 0], a)
    vy, _ = _trig_eval(st.vcoef[rows, :, 1], a)
    h1 = np.arctan2(dk[rows, 1], dk[rows, 0]) - np.arctan2(vy, vx)
    h2 = h1 + st.eta[rows, 0] + st.eta[rows, 1] * a
    h10 = st.h10[rows, 0] + st.h10[rows, 1] * a
    he = st.he[rows, 0] + st.he[rows, 1] * a
    u1, ok1 = _wrap_range(st.d1[rows] * (h1 - h10), np.where(st.hi_first[rows] > 0, PI, a))
    u2, ok2 = _wrap_range(st.d2[rows] * (goal[2] - he - h2), np.where(st.hi_last[rows] > 0, PI, a))
    good = ok1 & ok2 & (vx * vx + vy * vy > 1e-24)
    out = []
    seen: set[tuple[int, float]] = set()
    for i in np.nonzero(good)[0]:
        branch = (int(rows[i]), round(float(a[i]), 9))
        if branch in seen:
            continue
        seen.add(branch)
        t, first, last = st.items[rows[i]]
        ai = float(a[i])
        middle: list[tuple[str, int, Any]] = []
        d = -t.directions[0]
        for _ in range(t.interior):
            middle += piece_moves("T", "interior", d, None, ai)
            d = -d
        sol = _finish(t, first, last, float(u1[i]), float(u2[i]), ai, middle, rho, goal, {"a": ai})
        if sol is not None:
            out.append(sol)
    return out


def trig_roots(samples: np.ndarray, tol: float = 1e-12) -> np.ndarray:
    """Real roots in [0, 2 pi) of a trigonometric polynomial given by equispaced samples.

    With N samples on [0, 2 pi) the polynomial's degree K must be < N/2 - 1. Writing
    z = e^{ia}, z^K f(a) is an ordinary polynomial of degree 2K; its roots on the unit circle
    are the real roots of f (tangential ones included), found by one companion-matrix solve.
    """
    n = samples.size
    coef = np.fft.rfft(samples) / n
    scale = float(np.max(np.abs(coef)))
    if scale == 0.0:
        return np.empty(0)
    big = np.nonzero(np.abs(coef) > tol * scale)[0]
    deg = int(big.max())
    if deg >= n // 2 - 1:
        raise ArithmeticError("trigonometric degree too high for the sample count")
    if deg == 0:
        return np.empty(0)
    _, a = _coef_roots_batch(coef[None, : deg + 1])
    return np.unique(np.round(a, 12))


def solve_all(
    goal: np.ndarray, rho: float, groups: tuple[str, ...] = ("TST", "TTTT")
) -> dict[str, list[Extremal]]:
    """Every extremal of the Gamma_TST / Gamma_TTTT types for a normalised goal, by key.

    Keys: "TST", "TTTT" (the types of (4.26)), "supplementary" (`SUPPLEMENTARY_TYPES`),
    "interiorM" (every rigid sequence with M interior turns).
    """
    goal = np.asarray(goal, dtype=float)
    return {k: (_solve_tst if k == "TST" else _solve_tttt)(goal, float(rho), k) for k in groups}


def solve_type(ctype: CandidateType, goal: np.ndarray, rho: float) -> list[Extremal]:
    """Every extremal of one Gamma_TST or Gamma_TTTT type (all its branches) for a goal."""
    return [e for e in solve_all(goal, rho, (ctype.group,))[ctype.group] if e.ctype is ctype]
