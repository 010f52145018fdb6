"""Compiled tables of the chapter 6 extremals as orbits of a pendulum-like system (numba).

With the adjoint (lx, ly) = -2 p1 P (cos alpha, sin alpha) and phi = psi - alpha, the
canonical system of `load_factor_kernel` in arc length s reads (G* as there)

    phi' = k*(w),   w' = P sin phi,   xi' = cos phi,   eta' = sin phi,
    H = 0:  G*(w) = P cos phi,

(xi, eta) the coordinates along and across the line of heading alpha. So w = P (eta - eta_c)
(the curvature is a function of the distance to a fixed line, as for Euler's elastica) and
the extremals are the level curves G*(w) = P cos phi of a pendulum: *rotations* for P < 1
(one turn direction, the heading monotone: L..., R...), *librations* for P > 1 (the heading
swings around alpha + pi with inflections at w = 0) and the separatrix P = 1 through the
wings-level saddle (w = 0, phi = 0): turn - wings level - turn, reached only as P -> 1.

For a goal (xg, yg, psig), the start (phi0 = -alpha, w0 = s0 W(P cos alpha)) and the goal
(phig = psig - alpha, wg = sg W(P cos phig)) lie on the same orbit. The lateral condition is
algebraic, e1 = (wg - w0) / P - eta_g(alpha) = 0; the along-line one,
e2 = xi(goal) - xi(start) - xi_g(alpha) = 0, is a difference of one orbit's tabulated
quadrature. So each P of a grid gives the alpha roots of e1 and e2 along them; sign changes of
e2 between neighbouring P bracket an extremal to the goal (word: start and goal branches s0,
sg and the number j of whole periods between them), which `refine` then solves.

Why this module is long: (about 600 lines, over the usual 500) the tables, the root scan,
the bracket searches and their solvers are numba kernels calling each other's private
helpers; split across modules, numba's per-file cache would keep stale copies of the helpers
a caller compiled in.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from glideplan.planners.load_factor_kernel import _g, _speed, crossed, kappa_of, w_of_g_star

__all__ = ["brackets", "build_tables", "ends", "refine", "refine_z", "search"]

TWO_PI = 2.0 * math.pi
NCOL = 10  # phi, w, xi, c, t and their s-derivatives


@njit(cache=True)
def _orhs(y: np.ndarray, p: float, prm: np.ndarray, out: np.ndarray) -> None:
    """(phi, w, xi, eta, cost / 2 p1, t)' on the orbit of modulus p."""
    k = kappa_of(y[1], prm)
    out[0] = k
    out[1] = p * math.sin(y[0])
    out[2] = math.cos(y[0])
    out[3] = math.sin(y[0])
    out[4] = _g(k, prm)
    out[5] = 1.0 / _speed(k, prm)


@njit(cache=True)
def _ork4(y: np.ndarray, h: float, p: float, prm: np.ndarray, ws: np.ndarray) -> None:
    k1, k2, k3, k4, tmp = ws[0], ws[1], ws[2], ws[3], ws[4]
    _orhs(y, p, prm, k1)
    for i in range(6):
        tmp[i] = y[i] + 0.5 * h * k1[i]
    _orhs(tmp, p, prm, k2)
    for i in range(6):
        tmp[i] = y[i] + 0.5 * h * k2[i]
    _orhs(tmp, p, prm, k3)
    for i in range(6):
        tmp[i] = y[i] + h * k3[i]
    _orhs(tmp, p, prm, k4)
    for i in range(6):
        y[i] += h * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]) / 6.0


@njit(cache=True)
def _ostep(y: np.ndarray, h: float, p: float, prm: np.ndarray, ws: np.ndarray) -> None:
    """One RK4 step, redone in 32 sub-steps where w crosses or grazes a kink of k*(w)."""
    save = ws[5]
    save[:] = y
    _ork4(y, h, p, prm, ws)
    if crossed(save[1], y[1], p * math.sin(save[0]), p * math.sin(y[0]), h, prm):
        y[:] = save
        for _ in range(32):
            _ork4(y, h / 32.0, p, prm, ws)


@njit(cache=True)
def _herm(f0: float, f1: float, d0: float, d1: float, h: float, t: float) -> float:
    t2 = t * t
    t3 = t2 * t
    return (
        (2.0 * t3 - 3.0 * t2 + 1.0) * f0
        + (t3 - 2.0 * t2 + t) * h * d0
        + (-2.0 * t3 + 3.0 * t2) * f1
        + (t3 - t2) * h * d1
    )


@njit(cache=True)
def _record(tab: np.ndarray, i: int, y: np.ndarray, p: float, prm: np.ndarray, d: np.ndarray):
    _orhs(y, p, prm, d)
    tab[i, 0], tab[i, 1], tab[i, 2], tab[i, 3], tab[i, 4] = y[0], y[1], y[2], y[4], y[5]
    tab[i, 5], tab[i, 6], tab[i, 7], tab[i, 8], tab[i, 9] = d[0], d[1], d[2], d[4], d[5]


@njit(cache=True)
def orbit_table(p: float, h: float, prm: np.ndarray, max_len: float) -> np.ndarray:
    """One period (rotation, P < 1, from phi = 0 to 2 pi, turning left) or the half period
    with w >= 0 (libration, P > 1, from phi = acos(1/P) to 2 pi - acos(1/P)), every h."""
    nmax = int(max_len / h) + 2
    tab = np.zeros((nmax, NCOL))
    ws = np.zeros((6, 6))
    y = np.zeros(6)
    rot = p < 1.0
    if rot:
        y[1] = w_of_g_star(p, prm)
    else:
        y[0] = math.acos(1.0 / p)
    d = np.zeros(6)
    _record(tab, 0, y, p, prm, d)
    i = 0
    while i < nmax - 1:
        _ostep(y, h, p, prm, ws)
        i += 1
        _record(tab, i, y, p, prm, d)
        if (rot and y[0] >= TWO_PI) or (not rot and y[1] < 0.0):
            break
    return tab[: i + 1]


@njit(cache=True)
def _hroot(tab: np.ndarray, i: int, col: int, h: float, target: float) -> float:
    """tau in [0, 1] where the Hermite cubic of column col on [i, i + 1] equals target."""
    lo, hi = 0.0, 1.0
    f0, f1, d0, d1 = tab[i, col], tab[i + 1, col], tab[i, col + 5], tab[i + 1, col + 5]
    up = f1 >= f0
    for _ in range(48):
        mid = 0.5 * (lo + hi)
        if (_herm(f0, f1, d0, d1, h, mid) < target) == up:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


@njit(cache=True)
def _at(tab: np.ndarray, i: int, t: float, h: float, out: np.ndarray) -> None:
    """(s, xi, c, t) at node i + t."""
    out[0] = (i + t) * h
    for k in range(3):
        c = 2 + k
        out[1 + k] = _herm(tab[i, c], tab[i + 1, c], tab[i, c + 5], tab[i + 1, c + 5], h, t)


@njit(cache=True)
def _lookup(tab: np.ndarray, h: float, key: float, out: np.ndarray) -> None:
    """(s, xi, c, t) where phi (non-decreasing in the table) equals key (clamped)."""
    n = tab.shape[0]
    if key <= tab[0, 0]:
        _at(tab, 0, 0.0, h, out)
        return
    if key >= tab[n - 1, 0]:
        _at(tab, n - 2, 1.0, h, out)
        return
    lo, hi = 0, n - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if tab[mid, 0] <= key:
            lo = mid
        else:
            hi = mid
    _at(tab, lo, _hroot(tab, lo, 0, h, key), h, out)


@njit(cache=True)
def period_info(tab: np.ndarray, p: float, h: float) -> np.ndarray:
    """(T, Xi, C, t) over one whole period (a libration: twice its tabulated half)."""
    out = np.zeros(4)
    n = tab.shape[0]
    if p < 1.0:
        _lookup(tab, h, TWO_PI, out)
    else:  # the half period ends where w returns to 0
        _at(tab, n - 2, _hroot(tab, n - 2, 1, h, 0.0), h, out)
        out *= 2.0
    return out


@njit(cache=True)
def _position(tab, p, h, half, phi, sgn, out) -> None:
    """(u, xi, c, t) from the table's origin to the orbit point of heading phi, branch sgn."""
    pm = phi % TWO_PI
    if p < 1.0:
        key = pm if sgn > 0 else (TWO_PI - pm) % TWO_PI
        _lookup(tab, h, key, out)
    elif sgn > 0:
        _lookup(tab, h, pm, out)
    else:
        _lookup(tab, h, TWO_PI - pm, out)
        for k in range(4):
            out[k] += half[k]


@njit(cache=True)
def build_tables(ps: np.ndarray, h: float, prm: np.ndarray, max_len: float):
    """All orbit tables stacked: (rows, offsets, period info (K, 4))."""
    k = ps.size
    tabs = []
    info = np.zeros((k, 4))
    off = np.zeros(k + 1, dtype=np.int64)
    for i in range(k):
        t = orbit_table(ps[i], h, prm, max_len)
        tabs.append(t)
        info[i] = period_info(t, ps[i], h)
        off[i + 1] = off[i] + t.shape[0]
    rows = np.zeros((off[k], NCOL))
    for i in range(k):
        rows[off[i] : off[i + 1]] = tabs[i]
    return rows, off, info


@njit(cache=True)
def _e1(alpha, p, s0, sg, xg, yg, psig, prm) -> float:
    """The lateral mismatch (wg - w0) / P - eta_g(alpha); NaN where no orbit of P passes."""
    q0 = p * math.cos(alpha)
    qg = p * math.cos(psig - alpha)
    if q0 > 1.0 + 1e-13 or qg > 1.0 + 1e-13:
        return math.nan
    w0 = s0 * w_of_g_star(q0, prm)
    wg = sg * w_of_g_star(qg, prm)
    return (wg - w0) / p - (-math.sin(alpha) * xg + math.cos(alpha) * yg)


@njit(cache=True)
def _alpha_nodes(p: float, psig: float, n: int) -> np.ndarray:
    """A uniform grid of line headings, refined where the start or the goal sits near the
    wings-level saddle (windows of width sqrt|1 - P|) and at the librations' edges."""
    b = math.sqrt(2.0 * abs(1.0 - p))
    extra = np.array([0.5, 1.0, 1.5, 2.5, 4.0, 7.0])
    out = np.zeros(n + 4 * extra.size + 4)
    for i in range(n):
        out[i] = TWO_PI * i / n
    m = n
    for c in (0.0, psig):
        for e in extra:
            out[m] = c + e * b
            out[m + 1] = c - e * b
            m += 2
        if p > 1.0:
            out[m] = c + math.acos(1.0 / p)
            out[m + 1] = c - math.acos(1.0 / p)
            m += 2
    return np.sort(out[:m] % TWO_PI)


@njit(cache=True)
def _root(a, fa, b, fb, p, s0, sg, xg, yg, psig, prm) -> float:
    """Illinois regula falsi for e1 on [a, b] (fa fb <= 0)."""
    for _ in range(80):
        c = (a * fb - b * fa) / (fb - fa) if fb != fa else 0.5 * (a + b)
        fc = _e1(c, p, s0, sg, xg, yg, psig, prm)
        if math.isnan(fc):
            return math.nan
        if abs(fc) < 1e-14 or abs(b - a) < 1e-14:
            return c
        if fc * fb < 0.0:
            a, fa = b, fb
        else:
            fa *= 0.5
        b, fb = c, fc
    return b


@njit(cache=True)
def _linked(w1: int, w2: int, al: float, p: float, psig: float, prm: np.ndarray) -> bool:
    """Whether a root of word w1 at alpha can continue as one of word w2 at a neighbouring
    P: the same word, or (librations) the start's (goal's) branch flipped where the start
    (goal) is near an inflection, w0 (wg) small."""
    if w1 == w2:
        return True
    if p <= 1.0:
        return False
    x = w1 ^ w2
    if x == 1:
        return w_of_g_star(p * math.cos(al), prm) < 0.3
    if x == 2:
        return w_of_g_star(p * math.cos(psig - al), prm) < 0.3
    return False


@njit(cache=True)
def _push(rows: np.ndarray, n: int, vals: np.ndarray) -> np.ndarray:
    if n == rows.shape[0]:
        grown = np.zeros((2 * n, rows.shape[1]))
        grown[:n] = rows
        rows = grown
    rows[n] = vals
    return rows


@njit(cache=True)
def search(rows_t, off, info, ps, h, prm, xg, yg, psig, lmax, n_alpha):
    """For every tabulated P, word (s0, sg) and root alpha of e1, the extremals of up to
    lmax: rows (k, word, j, alpha, e2, L, C = cost / 2 p1, t, T)."""
    out = np.zeros((256, 9))
    m = 0
    a0 = np.zeros(4)
    ag = np.zeros(4)
    half = np.zeros(4)
    vals = np.zeros(9)
    for k in range(ps.size):
        p = ps[k]
        tab = rows_t[off[k] : off[k + 1]]
        half[:] = 0.5 * info[k]
        period = info[k, 0]
        nodes = _alpha_nodes(p, psig, n_alpha)
        nn = nodes.size
        for word in range(4):
            s0 = 1.0 if word % 2 == 0 else -1.0
            sg = 1.0 if word < 2 else -1.0
            if p < 1.0 and s0 != sg:
                continue
            f = np.empty(nn)
            for i in range(nn):
                f[i] = _e1(nodes[i], p, s0, sg, xg, yg, psig, prm)
            for i in range(nn):
                i2 = (i + 1) % nn
                a, b = nodes[i], nodes[i2] + (TWO_PI if i2 == 0 else 0.0)
                fa, fb = f[i], f[i2]
                if math.isnan(fa) or math.isnan(fb) or fa * fb > 0.0 or b - a <= 0.0:
                    continue
                if math.isnan(_e1(0.5 * (a + b), p, s0, sg, xg, yg, psig, prm)):
                    continue
                if fa == 0.0 and i > 0:
                    continue  # counted with the interval ending there
                al = _root(a, fa, b, fb, p, s0, sg, xg, yg, psig, prm)
                if math.isnan(al):
                    continue
                al = al % TWO_PI
                _position(tab, p, h, half, -al, s0, a0)
                _position(tab, p, h, half, psig - al, sg, ag)
                du = ag[0] - a0[0]
                dxi, dc, dt = ag[1] - a0[1], ag[2] - a0[2], ag[3] - a0[3]
                if du < 0.0:
                    du += period
                    dxi += info[k, 1]
                    dc += info[k, 2]
                    dt += info[k, 3]
                xi_g = math.cos(al) * xg + math.sin(al) * yg
                j = 0
                while du <= lmax:
                    if du > 1e-9:
                        vals[0], vals[1], vals[2], vals[3] = k, word, j, al
                        vals[4], vals[5], vals[6], vals[7] = dxi - xi_g, du, dc, dt
                        vals[8] = period
                        out = _push(out, m, vals)
                        m += 1
                    du += period
                    dxi += info[k, 1]
                    dc += info[k, 2]
                    dt += info[k, 3]
                    j += 1
    return out[:m]


@njit(cache=True)
def brackets(rows: np.ndarray, ps: np.ndarray, psig: float, prm: np.ndarray) -> np.ndarray:
    """Sign changes of e2 between the same root at neighbouring P (same kind; the nearest
    root of a `_linked` word): rows (row a, row b, interpolated C), cheapest first."""
    m = rows.shape[0]
    out = np.zeros((64, 3))
    c = 0
    vals = np.zeros(3)
    start = 0
    while start < m:
        k = rows[start, 0]
        end = start
        while end < m and rows[end, 0] == k:
            end += 1
        nxt = end
        while nxt < m and rows[nxt, 0] == k + 1:
            nxt += 1
        ki = int(k)
        if end < m and rows[end, 0] == k + 1 and (ps[ki] < 1.0) == (ps[ki + 1] < 1.0):
            for r in range(start, end):
                best, arg = 1e300, -1
                w1 = int(rows[r, 1])
                for r2 in range(end, nxt):
                    w2 = int(rows[r2, 1])
                    if not _linked(w1, w2, rows[r, 3], ps[ki], psig, prm):
                        continue
                    da = abs((rows[r2, 3] - rows[r, 3] + math.pi) % TWO_PI - math.pi)
                    score = da + 0.05 * abs(rows[r2, 5] - rows[r, 5])
                    if da < 0.5 and score < best:
                        best, arg = score, r2
                if arg < 0:
                    continue
                ea, eb = rows[r, 4], rows[arg, 4]
                if ea * eb > 0.0:
                    continue
                tol = max(1.0, 0.3 * min(rows[r, 8], rows[arg, 8]))
                if abs(rows[r, 5] - rows[arg, 5]) > tol:
                    continue
                f = ea / (ea - eb) if ea != eb else 0.5
                vals[0], vals[1] = r, arg
                vals[2] = rows[r, 6] + f * (rows[arg, 6] - rows[r, 6])
                out = _push(out, c, vals)
                c += 1
        start = end
    out = out[:c]
    return out[np.argsort(out[:, 2])]


@njit(cache=True)
def pass_state(alpha, p, s0, sg, target, psig, h, lmax, prm) -> np.ndarray:
    """Fly the orbit from the start (phi = -alpha, w0 = s0 W(P cos alpha)) to its pass of
    heading psig with turn direction sg nearest arc length `target`: (s, xi, eta, C, t, ok)."""
    out = np.zeros(6)
    cur = np.zeros(6)
    ws = np.zeros((6, 6))
    y = np.zeros(6)
    y[0] = -alpha
    y[1] = s0 * w_of_g_star(p * math.cos(alpha), prm)
    yp = np.zeros(6)
    d0 = np.zeros(6)
    d1 = np.zeros(6)
    phig = psig - alpha
    fl = math.floor((y[0] - phig) / TWO_PI)
    n = int(lmax / h) + 1
    for i in range(n):
        yp[:] = y
        _ostep(y, h, p, prm, ws)
        f2 = math.floor((y[0] - phig) / TWO_PI)
        hit = (sg > 0.0 and f2 > fl) or (sg < 0.0 and f2 < fl)
        level = phig + TWO_PI * (f2 if f2 > fl else fl)
        fl = f2
        if not hit:
            continue
        _orhs(yp, p, prm, d0)
        _orhs(y, p, prm, d1)
        lo, hi = 0.0, 1.0
        up = y[0] >= yp[0]
        for _ in range(48):
            mid = 0.5 * (lo + hi)
            if (_herm(yp[0], y[0], d0[0], d1[0], h, mid) < level) == up:
                lo = mid
            else:
                hi = mid
        t = 0.5 * (lo + hi)
        cur[0] = (i + t) * h
        for c, col in ((1, 2), (2, 3), (3, 4), (4, 5)):
            cur[c] = _herm(yp[col], y[col], d0[col], d1[col], h, t)
        cur[5] = 1.0
        if out[5] == 0.0 or abs(cur[0] - target) < abs(out[0] - target):
            out[:] = cur
        if cur[0] > target:
            break
    return out


@njit(cache=True)
def _word_signs(word: int) -> tuple[float, float]:
    return (1.0 if word % 2 == 0 else -1.0), (1.0 if word < 2 else -1.0)


@njit(cache=True)
def refine(ra, rb, ps, xg, yg, psig, h, lmax, prm) -> np.ndarray:
    """Solve e1 = e2 = 0 between two search rows at neighbouring P (`refine_z`)."""
    pa, pb = ps[int(ra[0])], ps[int(rb[0])]
    za, zb = math.log(abs(1.0 - pa)), math.log(abs(1.0 - pb))
    return refine_z(za, zb, pa > 1.0, ra, rb, xg, yg, psig, h, lmax, prm)


@njit(cache=True)
def refine_z(za, zb, lib, ra, rb, xg, yg, psig, h, lmax, prm) -> np.ndarray:
    """Solve e1 = e2 = 0 for z = log|1 - P| in [za, zb] (regula falsi; at each P the root
    alpha of e1 near the interpolated one, of either row's word: a root crosses from one word
    to the other where the start or the goal is an inflection; e2 by flying the orbit to the
    pass nearest the interpolated length): (alpha, P, L, C, t, w0, |e2|, ok)."""
    out = np.zeros(8)
    fa, fb = ra[4], rb[4]
    aa, ab = ra[3], rb[3]
    la, lb = ra[5], rb[5]
    z, al, p, s0 = za, aa, 1.0, 1.0
    st = np.zeros(6)
    for _ in range(60):
        z = (za * fb - zb * fa) / (fb - fa) if fb != fa else 0.5 * (za + zb)
        p = 1.0 + math.exp(z) if lib else 1.0 - math.exp(z)
        frac = (z - za) / (zb - za) if zb != za else 0.5
        guess = aa + ((ab - aa + math.pi) % TWO_PI - math.pi) * frac
        s0, sg = _word_signs(int(ra[1]))
        al = _near_root(guess, p, s0, sg, xg, yg, psig, prm, 0.6, True)
        if math.isnan(al) and rb[1] != ra[1]:
            s0, sg = _word_signs(int(rb[1]))
            al = _near_root(guess, p, s0, sg, xg, yg, psig, prm, 0.6, True)
        if math.isnan(al):
            return out
        st = pass_state(al, p, s0, sg, la + (lb - la) * frac, psig, h, lmax, prm)
        if st[5] == 0.0:
            return out
        fz = st[1] - (math.cos(al) * xg + math.sin(al) * yg)
        if abs(fz) < 1e-11 or abs(zb - za) < 1e-13:
            break
        if fz * fb < 0.0:
            za, fa, aa, la = zb, fb, ab, lb
        else:
            fa *= 0.5
        zb, fb, ab, lb = z, fz, al, st[0]
    out[0], out[1], out[2], out[3], out[4] = al % TWO_PI, p, st[0], st[3], st[4]
    out[5] = s0 * w_of_g_star(p * math.cos(al), prm)
    out[6] = abs(st[1] - (math.cos(al) * xg + math.sin(al) * yg))
    out[7] = 1.0
    return out


@njit(cache=True)
def _near_root(guess, p, s0, sg, xg, yg, psig, prm, radius, edges) -> float:
    """The root of e1 within `radius` of guess nearest to it (samples denser near guess, and
    with `edges` at the domain's edges where the start or the goal is an inflection; the
    guess itself may lie outside the domain of P); NaN if none."""
    n = 16
    a = np.zeros(2 * n + 5)
    for j in range(-n, n + 1):
        a[j + n] = guess + radius * (j / n) * abs(j / n)
    m = 2 * n + 1
    if edges and p > 1.0:
        b = math.acos(1.0 / p)
        for c in (b, -b, psig - b, psig + b):
            d = (c - guess + math.pi) % TWO_PI - math.pi
            if abs(d) < radius:
                a[m] = guess + d
                m += 1
    a = np.sort(a[:m])
    best, out = 1e300, math.nan
    a_prev, f_prev = 0.0, math.nan
    for j in range(m):
        f = _e1(a[j], p, s0, sg, xg, yg, psig, prm)
        if not math.isnan(f) and not math.isnan(f_prev) and f * f_prev <= 0.0:
            mid = 0.5 * (a[j] + a_prev)
            if abs(mid - guess) < best and not math.isnan(_e1(mid, p, s0, sg, xg, yg, psig, prm)):
                best = abs(mid - guess)
                out = _root(a_prev, f_prev, a[j], f, p, s0, sg, xg, yg, psig, prm)
        a_prev, f_prev = a[j], f
    return out


@njit(cache=True)
def ends(rows, ps, xg, yg, psig, h, lmax, prm, c_max) -> np.ndarray:
    """Roots that end between neighbouring P (a fold, or the start or goal reaching an
    inflection; roots of rows costing at most c_max, continued by no root of the same word
    or, for librations, a word with one branch flipped): each is followed to its end by
    bisection in z = log|1 - P|, and where e2
    changes sign on the way the bracket is returned as two pseudo-rows (z, word, j, alpha,
    e2, L, C, t, T) at its ends: rows (za, zb, lib, row a..., row b...)."""
    m = rows.shape[0]
    out = np.zeros((16, 21))
    c = 0
    vals = np.zeros(21)
    first = np.full(ps.size + 1, m, dtype=np.int64)  # rows are sorted by k
    for r in range(m - 1, -1, -1):
        first[int(rows[r, 0])] = r
    for k in range(ps.size - 1, -1, -1):
        first[k] = min(first[k], first[k + 1])
    for r in range(m):
        if rows[r, 6] > c_max:
            continue
        k = int(rows[r, 0])
        word = int(rows[r, 1])
        s0, sg = _word_signs(word)
        lib = ps[k] > 1.0
        for kn in (k - 1, k + 1):
            if not (0 <= kn < ps.size and (ps[kn] > 1.0) == lib):
                continue
            cont = False
            for r2 in range(first[kn], first[kn + 1]):
                if _linked(word, int(rows[r2, 1]), rows[r, 3], ps[k], psig, prm):
                    da = abs((rows[r2, 3] - rows[r, 3] + math.pi) % TWO_PI - math.pi)
                    cont = cont or da < 0.5
            if cont:
                continue
            zlo, zhi = math.log(abs(1.0 - ps[k])), math.log(abs(1.0 - ps[kn]))
            al = rows[r, 3]
            for _ in range(18):  # the end to 4e-6 of the grid step: enough to bracket
                zm = 0.5 * (zlo + zhi)
                pm = 1.0 + math.exp(zm) if lib else 1.0 - math.exp(zm)
                am = _near_root(al, pm, s0, sg, xg, yg, psig, prm, 0.25, False)
                if math.isnan(am):
                    zhi = zm
                else:
                    zlo, al = zm, am
            pe = 1.0 + math.exp(zlo) if lib else 1.0 - math.exp(zlo)
            st = pass_state(al, pe, s0, sg, rows[r, 5], psig, h, lmax, prm)
            if st[5] == 0.0:
                continue
            e2 = st[1] - (math.cos(al) * xg + math.sin(al) * yg)
            if e2 * rows[r, 4] > 0.0:
                continue
            vals[0] = math.log(abs(1.0 - ps[k]))
            vals[1] = zlo
            vals[2] = 1.0 if lib else 0.0
            vals[3:12] = rows[r]
            vals[12:21] = rows[r]
            vals[15], vals[16], vals[17], vals[18] = al, e2, st[0], st[3]
            out = _push(out, c, vals)
            c += 1
    return out[:c]
