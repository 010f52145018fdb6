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
- Gamma_TTTT: |V(a)|^2 - |K2 - K1|^2 is a trigonometric polynomial of degree <= 2 in a
  (checked numerically to degree 4); all its roots come from one polynomial eigenvalue solve.
h1 then follows from the angle between V and K2 - K1, and u1, u2 from h1 (each within a range
shorter than 2 pi, hence unique). The result is every extremal of the type, deterministically.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from glideplan.planners.min_time.geometry import compose, normal, rotate
from glideplan.planners.min_time.table import CandidateType, conditions, long_form

__all__ = [
    "Extremal",
    "piece_moves",
    "solve_flexible",
    "solve_rigid",
    "solve_type",
    "trig_roots",
]

PI = math.pi
TWO_PI = 2.0 * PI
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


def _last_geometry(
    kind: str, d: int, a: np.ndarray, rho: float, goal: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """K2 (centre of the goal arc), z1 (Z - K2 in the h2 frame), h2 at u2 = 0."""
    zero = np.zeros_like(a)
    moves = piece_moves(kind, "last", d, zero, a)
    p, he = compose(moves, rho, a.shape)
    rl = _radius(moves[-1][0], rho)
    k2_local = p + d * rl * normal(he)
    z1 = np.array([0.0, float(d)]) - k2_local
    k2 = goal[:2] + d * rl * normal(np.array(goal[2]))
    return k2, z1, goal[2] - he


def _middle(m: int, d1: int, a: np.ndarray, rho: float) -> tuple[np.ndarray, np.ndarray]:
    """Pose displacement (sigma, eta) of m interior turns after a reversal from direction d1."""
    moves: list[tuple[str, int, Any]] = []
    d = -d1
    for _ in range(m):
        moves += piece_moves("T", "interior", d, None, a)
        d = -d
    return compose(moves, rho, a.shape)


def _in_range(u: float, hi: float, lo_open: bool = False) -> float | None:
    """u (mod 2 pi) inside [0, hi] (or (0, hi]), clipped; None when outside."""
    u = u % TWO_PI
    if u > TWO_PI - _RANGE_TOL:
        u -= TWO_PI
    if u < -_RANGE_TOL or u > hi + _RANGE_TOL:
        return None
    u = min(max(u, 0.0), hi)
    if lo_open and u <= 0.0:
        return None
    return u


def _piece_range(kind: str, a: float) -> float:
    return PI if kind in ("CB", "BC") else a


def _finish(
    ctype: CandidateType,
    first: str,
    last: str,
    d1: int,
    d2: int,
    u1: float,
    u2: float,
    a: float,
    middle: list[tuple[str, int, Any]],
    rho: float,
    goal: np.ndarray,
    extra: dict[str, Any],
) -> Extremal | None:
    moves = (
        piece_moves(first, "first", d1, u1, a)
        + middle
        + piece_moves(last, "last", d2, u2, a)
    )
    moves_f: tuple[Move, ...] = tuple((lab, d, float(x)) for lab, d, x in moves)
    p, h = compose(moves_f, rho, ())
    dh = (float(h) - goal[2] + PI) % TWO_PI - PI
    err = max(float(np.hypot(*(p - goal[:2]))), abs(dh))
    if err > _END_TOL:
        return None
    cost = sum(x for _, _, x in moves_f)
    turns = long_form(ctype, first, last, u1, u2, a)
    params = {"first": first, "last": last, "u1": u1, "u2": u2, **extra}
    return Extremal(ctype, moves_f, cost, params, conditions(ctype, turns, rho), err)


def solve_flexible(
    ctype: CandidateType, first: str, last: str, goal: np.ndarray, rho: float
) -> list[Extremal]:
    """All Gamma_TST extremals T S T of one type and orientation (closed form in L)."""
    d1, d2 = ctype.directions
    a = np.array(PI / 2)
    k1, a1, h10 = _first_geometry(first, d1, a, rho)
    k2, z1, h20 = _last_geometry(last, d2, a, rho, goal)
    w = a1 + (d2 - d1) * _EY - z1
    dk = k2 - k1
    dist2 = float(dk @ dk)
    disc = dist2 - float(w[1]) ** 2
    if disc < -1e-12:
        return []
    root = math.sqrt(max(disc, 0.0))
    out: list[Extremal] = []
    for sign in ((1.0,) if root == 0.0 else (1.0, -1.0)):
        length = -float(w[0]) + sign * root
        if length < -1e-10:
            continue
        length = max(length, 0.0)
        v = w + np.array([length, 0.0])
        if dist2 < 1e-24 and float(v @ v) < 1e-24:
            continue  # degenerate: coincident circles, any h1 works (measure-zero goals)
        h1 = math.atan2(dk[1], dk[0]) - math.atan2(v[1], v[0])
        u1 = _in_range(d1 * (h1 - float(h10)), _piece_range(first, PI / 2))
        u2 = _in_range(d2 * (float(h20) - h1), _piece_range(last, PI / 2))
        if u1 is None or u2 is None:
            continue
        sol = _finish(
            ctype, first, last, d1, d2, u1, u2, PI / 2, [("S", 0, length)], rho, goal,
            {"L": length},
        )
        if sol is not None:
            out.append(sol)
    return out


def trig_roots(samples: np.ndarray, tol: float = 1e-12) -> np.ndarray:
    """Real roots in [0, 2 pi) of a trigonometric polynomial given by equispaced samples.

    With N samples on [0, 2 pi) the polynomial's degree K must be < N/2. Writing z = e^{ia},
    z^K f(a) is an ordinary polynomial of degree 2K; its roots on the unit circle are the real
    roots of f (tangential ones included), found together by one companion-matrix solve.
    """
    n = samples.size
    coef = np.fft.rfft(samples) / n
    scale = float(np.max(np.abs(coef)))
    if scale == 0.0:
        return np.empty(0)
    big = np.nonzero(np.abs(coef) > tol * scale)[0]
    deg = int(big.max())
    if deg >= n // 2:
        raise ArithmeticError("trigonometric degree too high for the sample count")
    if deg == 0:
        return np.empty(0)
    c = coef[: deg + 1]
    # highest power first: z^{2K} ... z^0 with coefficient of z^{K+k} = c_k, z^{K-k} = conj(c_k)
    poly = np.concatenate([c[::-1], np.conj(c[1:])])
    z = np.roots(poly)
    z = z[np.abs(np.abs(z) - 1.0) < 1e-4]
    a = np.mod(np.angle(z), TWO_PI)
    # Newton polish on the trigonometric polynomial itself
    k = np.arange(deg + 1)
    for _ in range(3):
        e = np.exp(1j * np.outer(a, k))
        f = 2.0 * np.real(e @ c) - np.real(c[0])
        df = 2.0 * np.real((1j * k * e) @ c)
        step = np.where(np.abs(df) > 1e-14 * scale, f / np.where(df == 0, 1.0, df), 0.0)
        a = np.mod(a - step, TWO_PI)
    return np.unique(np.round(a, 12))


_RIGID_SAMPLES = 16


def solve_rigid(
    ctype: CandidateType, first: str, last: str, goal: np.ndarray, rho: float
) -> list[Extremal]:
    """All Gamma_TTTT extremals of one type and orientation (roots of |V(a)|^2 = |K2-K1|^2)."""
    d1 = ctype.directions[0]
    d2 = ctype.directions[-1]
    m = ctype.interior

    def pieces(a: np.ndarray) -> tuple[np.ndarray, ...]:
        k1, a1, h10 = _first_geometry(first, d1, a, rho)
        k2, z1, h20 = _last_geometry(last, d2, a, rho, goal)
        sigma, eta = _middle(m, d1, a, rho)
        v = a1 - d1 * _EY + sigma + d2 * normal(eta) - rotate(eta, z1)
        return k1, k2, v, h10, h20, eta

    grid = np.arange(_RIGID_SAMPLES) * (TWO_PI / _RIGID_SAMPLES)
    k1, k2, v, *_ = pieces(grid)
    dk = k2 - k1
    f = np.sum(v * v, axis=-1) - float(dk @ dk)
    roots = trig_roots(f)
    roots = roots[(roots >= 0.0) & (roots <= PI / 2)]
    out: list[Extremal] = []
    if roots.size == 0:
        return out
    k1, k2, v, h10, h20, eta = pieces(roots)
    dk = k2 - k1
    for i, a in enumerate(roots):
        vi = v[i]
        if float(vi @ vi) < 1e-24:
            continue
        h1 = math.atan2(dk[1], dk[0]) - math.atan2(vi[1], vi[0])
        h2 = h1 + float(eta[i])
        u1 = _in_range(d1 * (h1 - float(h10[i])), _piece_range(first, float(a)))
        u2 = _in_range(d2 * (float(h20[i]) - h2), _piece_range(last, float(a)))
        if u1 is None or u2 is None:
            continue
        middle: list[tuple[str, int, Any]] = []
        d = -d1
        for _ in range(m):
            middle += piece_moves("T", "interior", d, None, float(a))
            d = -d
        sol = _finish(
            ctype, first, last, d1, d2, u1, u2, float(a), middle, rho, goal, {"a": float(a)}
        )
        if sol is not None:
            out.append(sol)
    return out


def solve_type(ctype: CandidateType, goal: np.ndarray, rho: float) -> list[Extremal]:
    """Every extremal of a Gamma_TST or Gamma_TTTT type (all its branches) for a goal."""
    solver = solve_flexible if ctype.group == "TST" else solve_rigid
    out: list[Extremal] = []
    for first, last in ctype.branches:
        out.extend(solver(ctype, first, last, goal, rho))
    return out
