"""The compiled synthesis path: kernel tables per speed ratio and `Extremal`s from the kernels.

`solve(goal, rho, key)` returns what `solvers.solve_all(goal, rho, (key,))[key]` returns (the
same extremals, in the same order, to rounding) with the root finding, range checks and
end-point checks done by the numba kernels of `_jit`; only the extremals that reach the goal
become Python objects. `reach_distance` is `fixed_turn_rate.reach_distance` compiled. The
NumPy reference stays in `solvers` / `fixed_turn_rate` (`synthesis.COMPILED = False`).
Importing this module imports numba (it is imported on first use by `synthesis`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np

from glideplan.planners.min_time import _jit
from glideplan.planners.min_time.solvers import Extremal, _stack, piece_moves
from glideplan.planners.min_time.table import CandidateType, conditions, long_form

__all__ = ["reach_distance", "solve"]

PI = math.pi
_KIND = {"u1": _jit.U1, "u2": _jit.U2, "a": _jit.A, "L": _jit.L_KIND}
_LABEL = {"S": 0, "B": 1, "C": 2}

Template = tuple[tuple[str, int, int], ...]


@dataclass(frozen=True, eq=False)
class _Tables:
    """Contiguous kernel inputs of one solver key and speed ratio (see `_jit.tst`/`rigid`)."""

    items: tuple[tuple[CandidateType, str, str], ...]
    templates: tuple[Template, ...]
    geo: np.ndarray
    lab: np.ndarray
    dirs: np.ndarray
    kind: np.ndarray
    nmov: np.ndarray
    w: np.ndarray | None = None
    coef: np.ndarray | None = None
    degree: np.ndarray | None = None
    vcx: np.ndarray | None = None
    vcy: np.ndarray | None = None


def _template(ctype: CandidateType, first: str, last: str) -> Template:
    """The branch's moves with symbolic amounts: (label, direction, amount kind)."""
    d1, d2 = ctype.directions[0], ctype.directions[-1]
    middle: list[tuple[str, int, Any]] = []
    if ctype.straight:
        middle = [("S", 0, "L")]
    d = -d1
    for _ in range(ctype.interior):
        middle += piece_moves("T", "interior", d, None, "a")
        d = -d
    moves = piece_moves(first, "first", d1, "u1", "a") + middle
    moves += piece_moves(last, "last", d2, "u2", "a")
    return tuple((lab, d, _jit.PI_KIND if x == PI else _KIND[x]) for lab, d, x in moves)


@lru_cache(maxsize=64)
def _tables(key: str, rho: float) -> _Tables:
    st = _stack(key, rho)
    templates = tuple(_template(*item) for item in st.items)
    nb, width = len(templates), max(len(t) for t in templates)
    lab = np.zeros((nb, width), dtype=np.int64)
    dirs = np.zeros((nb, width))
    kind = np.zeros((nb, width), dtype=np.int64)
    for i, tpl in enumerate(templates):
        lab[i, : len(tpl)] = [_LABEL[m[0]] for m in tpl]
        dirs[i, : len(tpl)] = [m[1] for m in tpl]
        kind[i, : len(tpl)] = [m[2] for m in tpl]
    cols = [st.d1, st.d2, st.r_first, st.r_last, st.hi_first, st.hi_last,
            st.h10[:, 0], st.h10[:, 1], st.he[:, 0], st.he[:, 1]]  # fmt: skip
    common: dict[str, Any] = dict(
        items=st.items, templates=templates, lab=lab, dirs=dirs, kind=kind,
        nmov=np.array([len(t) for t in templates], dtype=np.int64),
    )  # fmt: skip
    if st.w is not None:
        return _Tables(**common, geo=np.ascontiguousarray(np.stack(cols, axis=1)),
                       w=np.ascontiguousarray(st.w))  # fmt: skip
    assert st.coef is not None and st.vcoef is not None and st.degree is not None
    geo = np.stack([*cols, st.eta[:, 0], st.eta[:, 1]], axis=1)
    top = int(st.degree.max())
    return _Tables(
        **common,
        geo=np.ascontiguousarray(geo),
        coef=np.ascontiguousarray(st.coef[:, : top + 1]),
        degree=st.degree.astype(np.int64),
        vcx=np.ascontiguousarray(st.vcoef[:, :, 0]),
        vcy=np.ascontiguousarray(st.vcoef[:, :, 1]),
    )


def _extremal(tb: _Tables, row: int, vals: tuple[float, ...], cost: float, err: float,
              extra: dict[str, Any], rho: float) -> Extremal:
    """`solvers._finish` for a solution the kernel checked: moves, parameters, conditions."""
    ctype, first, last = tb.items[row]
    moves = tuple((lab, d, vals[k]) for lab, d, k in tb.templates[row])
    turns = long_form(ctype, first, last, vals[0], vals[1], vals[2])
    params = {"first": first, "last": last, "u1": vals[0], "u2": vals[1], **extra}
    return Extremal(ctype, moves, cost, params, conditions(ctype, turns, rho), err)


def solve(goal: np.ndarray, rho: float, key: str) -> list[Extremal]:
    """Every extremal of the solver key ("TST", "TTTT", "supplementary", "interiorM")."""
    goal = np.ascontiguousarray(goal, dtype=float)
    tb, rows, out = _kernel_costs(goal, rho, key)
    if key == "TST":
        return [
            _extremal(tb, row, (u1, u2, PI / 2, PI, length), cost, err, {"L": length}, rho)
            for row, (length, u1, u2, cost, err) in zip(rows.tolist(), out.tolist(), strict=True)
        ]
    found = []
    seen: set[tuple[int, float]] = set()
    for row, (a, u1, u2, cost, err) in zip(rows.tolist(), out.tolist(), strict=True):
        branch = (row, round(a, 9))
        if branch in seen:
            continue
        seen.add(branch)
        found.append(_extremal(tb, row, (u1, u2, a, PI, 0.0), cost, err, {"a": a}, rho))
    return found


def reach_distance(gp: np.ndarray, delta: float) -> tuple[float, float]:
    """`fixed_turn_rate.reach_distance` (96 samples, then bounded Brent), compiled."""
    from glideplan.planners.min_time.fixed_turn_rate import _SAMPLES

    dist, omega = _jit.reach(float(gp[0]), float(gp[1]), float(delta), _SAMPLES)
    return float(dist), float(omega)


def _kernel_costs(goal: np.ndarray, rho: float, key: str) -> tuple[_Tables, np.ndarray, np.ndarray]:
    """The kernel's rows and (param, u1, u2, cost, end error) of one key, no objects built."""
    tb = _tables(key, float(rho))
    nb = len(tb.items)
    if key == "TST":
        assert tb.w is not None
        rows = np.empty(2 * nb, dtype=np.int64)
        out = np.empty((2 * nb, 5))
        n = _jit.tst(goal, rho, tb.w, tb.geo, tb.lab, tb.dirs, tb.kind, tb.nmov, rows, out)
        return tb, rows[:n], out[:n]
    assert tb.coef is not None and tb.degree is not None
    assert tb.vcx is not None and tb.vcy is not None
    cap = nb * 2 * (tb.coef.shape[1] - 1)
    rows = np.empty(cap, dtype=np.int64)
    out = np.empty((cap, 5))
    n = _jit.rigid(goal, rho, tb.coef, tb.degree, tb.vcx, tb.vcy, tb.geo, tb.lab, tb.dirs,
                   tb.kind, tb.nmov, rows, out)  # fmt: skip
    return tb, rows[:n], out[:n]


def best_extremal(goal: np.ndarray, rho: float, dubins: list[Extremal]) -> Extremal | None:
    """`synthesize(goal, rho).best` (0 < rho < 1) without the losing candidates' objects.

    The candidates are taken in `synthesize`'s order (TTTT, TST, umax, Dubins, the
    supplementary types) and a later one wins only when strictly cheaper, as `min` over that
    list does; a Gamma_umax path is built (and checked) only when it would win. `dubins`:
    the goal's Gamma_Dubins extremals. Returns None when rigid sequences with more than three
    interior turns could still win (best cost above 4 pi): the caller runs `synthesize`.
    """
    from glideplan.planners.min_time.fixed_turn_rate import fixed_turn_rate_cost
    from glideplan.planners.min_time.table import SUPPLEMENTARY_MAX_INTERIOR

    goal = np.ascontiguousarray(goal, dtype=float)
    best_cost, best = math.inf, None
    for key in ("TTTT", "TST"):
        tb, rows, out = _kernel_costs(goal, rho, key)
        if len(rows) and out[:, 3].min() < best_cost:
            i = int(np.argmin(out[:, 3]))
            best_cost, best = float(out[i, 3]), (tb, i, rows, out, key)
    ext: Extremal | None = None
    for d in (1, -1):  # Gamma_umax: heading change delta + 2 pi k, checked only if cheaper
        cost = fixed_turn_rate_cost(goal, rho, d, reach=reach_distance)
        if cost is not None and cost < best_cost:
            found = _umax(goal, rho, d)  # built and checked (None if it misses the goal)
            if found is not None:
                best_cost, best, ext = found.cost, None, found
    for e in dubins:
        if e.cost < best_cost:
            best_cost, best, ext = e.cost, None, e
    tb, rows, out = _kernel_costs(goal, rho, "supplementary")
    if len(rows) and out[:, 3].min() < best_cost:
        i = int(np.argmin(out[:, 3]))
        best_cost, best = float(out[i, 3]), (tb, i, rows, out, "supplementary")
    if (SUPPLEMENTARY_MAX_INTERIOR + 1) * PI < best_cost:
        return None
    if best is None:
        return ext
    tb, i, rows, out, key = best
    p, u1, u2, cost, err = out[i].tolist()
    if key == "TST":
        return _extremal(tb, int(rows[i]), (u1, u2, PI / 2, PI, p), cost, err, {"L": p}, rho)
    return _extremal(tb, int(rows[i]), (u1, u2, p, PI, 0.0), cost, err, {"a": p}, rho)


def _umax(goal: np.ndarray, rho: float, d: int) -> Extremal | None:
    """The Gamma_umax extremal of `synthesis._umax_extremals` for direction d, if any."""
    from glideplan.planners.min_time.synthesis import _umax_extremals
    from glideplan.planners.min_time.table import CANDIDATE_TYPES

    types = [t for t in CANDIDATE_TYPES if t.group == "umax" and t.directions[0] == d]
    found = _umax_extremals(types, goal, rho, compiled=True)
    return found[0] if found else None
