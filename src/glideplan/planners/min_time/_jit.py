"""Compiled (numba) kernels of the chapter 4 synthesis: every extremal's parameters and cost.

The same formulas, in the same order of operations, as the NumPy reference
(`solvers._solve_tst`, `solvers._solve_tttt`, `solvers._finish`, `geometry.compose` and
`fixed_turn_rate.reach_distance`), one goal at a time, with no Python objects per candidate:

- `tst`: Gamma_TST, per branch the closed-form quadratic in L (4.18-4.19 with H = 0);
- `rigid`: Gamma_TTTT and the rigid supplementary types, per branch the real roots in
  [0, pi/2] of |V(a)|^2 - |K2 - K1|^2 (a trigonometric polynomial of degree <= 2). The
  reference takes the roots z of z^K f(e^{ia}) from a companion-matrix eigenvalue solve;
  here an Aberth-Ehrlich iteration finds the same 2K roots, then the same filter
  (| |z| - 1 | < 1e-4) and three Newton steps on f itself make the angles converge to the
  same values (to rounding);
- `reach`: Gamma_umax, max over omega of (w . g' - h(omega)) by the 96-sample scan and
  SciPy's bounded Brent method (`minimize_scalar(method="bounded")`, ported step by step).

Each extremal is checked by composing its moves from the origin (`_compose`: the arcs'
centres as in `geometry.compose`) and kept when it ends within 1e-8 of the goal. Outputs
are flat arrays; `compiled` turns the survivors into `Extremal`s. Serial (one goal per call,
the batch runner parallelises over processes); imported lazily (importing it imports numba).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["reach", "rigid", "tst"]

PI = math.pi
TWO_PI = 2.0 * math.pi
_RANGE_TOL = 1e-9
_END_TOL = 1e-8
# amount kinds of a move template: the free parameters u1, u2, a, the constant pi, L
U1, U2, A, PI_KIND, L_KIND = 0, 1, 2, 3, 4


@njit(cache=True)
def _mod_2pi(a: float) -> float:
    out = a % TWO_PI
    return 0.0 if out >= TWO_PI else out


@njit(cache=True)
def _wrap_range(u: float, hi: float) -> tuple[float, bool]:
    """`solvers._wrap_range` for one value: u mod 2 pi clipped into [0, hi], and inside?"""
    u = _mod_2pi(u)
    if u > TWO_PI - _RANGE_TOL:
        u = u - TWO_PI
    ok = u >= -_RANGE_TOL and u <= hi + _RANGE_TOL
    return min(max(u, 0.0), hi), ok


@njit(cache=True)
def _compose(lab: np.ndarray, dirs: np.ndarray, kind: np.ndarray, n: int, par: np.ndarray,
             rho: float) -> tuple[float, float, float, float]:
    """End (x, y, heading) of a move template from the origin and its cost (sum of amounts).

    Move j: label lab[j] (0 S, 1 B radius 1, 2 C radius rho), direction dirs[j], amount
    par[kind[j]]; `geometry.compose` step by step.
    """
    px = 0.0
    py = 0.0
    h = 0.0
    sh, ch = 0.0, 1.0  # sin and cos of h, kept from one move to the next
    cost = 0.0
    for j in range(n):
        x = par[kind[j]]
        cost += x
        if lab[j] == 0:
            px = px + x * ch
            py = py + x * sh
            continue
        dr = dirs[j] * (1.0 if lab[j] == 1 else rho)
        cx = px + dr * -sh
        cy = py + dr * ch
        h = h + dirs[j] * x
        sh, ch = math.sin(h), math.cos(h)
        px = cx - dr * -sh
        py = cy - dr * ch
    return px, py, h, cost


@njit(cache=True)
def _end_error(px: float, py: float, h: float, goal: np.ndarray) -> float:
    dh = (h - goal[2] + PI) % TWO_PI - PI
    return max(math.hypot(px - goal[0], py - goal[1]), abs(dh))


@njit(cache=True)
def _offsets(goal: np.ndarray, d1: float, d2: float, r_first: float,
             r_last: float) -> tuple[float, float]:
    """K2 - K1 of one branch (`solvers._goal_offsets`)."""
    s = d2 * r_last
    return goal[0] + s * -math.sin(goal[2]), (goal[1] + s * math.cos(goal[2])) - d1 * r_first


@njit(cache=True)
def tst(goal: np.ndarray, rho: float, w: np.ndarray, geo: np.ndarray, lab: np.ndarray,
        dirs: np.ndarray, kind: np.ndarray, nmov: np.ndarray, rows: np.ndarray,
        out: np.ndarray) -> int:
    """Gamma_TST extremals of one goal: (row, L, u1, u2, cost, end error) in `rows`/`out`.

    `geo[i]` = (d1, d2, r_first, r_last, hi_first, hi_last, h10_0, h10_1, he_0, he_1); the
    "+ root" solutions of every branch come first, then the "- root" ones (as the reference).
    """
    nb = w.shape[0]
    par = np.zeros(5)
    par[A] = PI / 2
    par[PI_KIND] = PI
    count = 0
    for sign in range(2):
        for i in range(nb):
            d1, d2 = geo[i, 0], geo[i, 1]
            dkx, dky = _offsets(goal, d1, d2, geo[i, 2], geo[i, 3])
            dist2 = dkx * dkx + dky * dky
            disc = dist2 - w[i, 1] ** 2
            root = math.sqrt(max(disc, 0.0))
            length = -w[i, 0] + root if sign == 0 else -w[i, 0] - root
            if not (disc >= -1e-12 and length >= -1e-10) or (sign == 1 and not root > 0.0):
                continue
            length = max(length, 0.0)
            vx, vy = w[i, 0] + length, w[i, 1]
            h1 = math.atan2(dky, dkx) - math.atan2(vy, vx)
            u1, ok1 = _wrap_range(d1 * (h1 - geo[i, 6] - geo[i, 7] * PI / 2),
                                  PI if geo[i, 4] > 0 else PI / 2)
            he = geo[i, 8] + geo[i, 9] * PI / 2
            u2, ok2 = _wrap_range(d2 * (goal[2] - he - h1), PI if geo[i, 5] > 0 else PI / 2)
            if not (ok1 and ok2 and (vx * vx + vy * vy > 1e-24 or dist2 > 1e-24)):
                continue
            par[U1], par[U2], par[L_KIND] = u1, u2, length
            px, py, h, cost = _compose(lab[i], dirs[i], kind[i], nmov[i], par, rho)
            err = _end_error(px, py, h, goal)
            if err > _END_TOL:
                continue
            rows[count] = i
            out[count, 0], out[count, 1], out[count, 2] = length, u1, u2
            out[count, 3], out[count, 4] = cost, err
            count += 1
    return count


@njit(cache=True)
def _poly_roots(poly: np.ndarray, z: np.ndarray) -> None:
    """All roots of sum poly[k] z^(m-k) (highest first, m = len - 1) into z: Aberth-Ehrlich.

    The starting points lie on a circle of radius 1.3: on the unit circle itself the
    iteration of these self-inversive polynomials (roots in pairs z, 1/conj z) wanders for
    ~20-30 sweeps; from radius 1.3 it converges in ~5 (9 at most on 40,000 random branches).
    """
    m = poly.size - 1
    for i in range(m):
        t = 0.4 + TWO_PI * i / m
        z[i] = complex(1.3 * math.cos(t), 1.3 * math.sin(t))
    settled = False
    for _ in range(100):
        moved = 0.0
        for i in range(m):  # real arithmetic: numba's complex division is slow
            zr, zi = z[i].real, z[i].imag
            pr, pi_ = poly[0].real, poly[0].imag
            dr = di = 0.0
            for k in range(1, m + 1):
                dr, di = dr * zr - di * zi + pr, dr * zi + di * zr + pi_
                pr, pi_ = pr * zr - pi_ * zi + poly[k].real, pr * zi + pi_ * zr + poly[k].imag
            if pr == 0.0 and pi_ == 0.0:
                continue
            den = dr * dr + di * di
            if den == 0.0:
                wr, wi = pr, pi_
            else:
                wr, wi = (pr * dr + pi_ * di) / den, (pi_ * dr - pr * di) / den  # p / p'
            sr = si = 0.0
            for j in range(m):
                if j != i:
                    ur, ui = zr - z[j].real, zi - z[j].imag
                    q = ur * ur + ui * ui
                    sr += ur / q
                    si -= ui / q
            # step = w / (1 - w s)
            br, bi = 1.0 - (wr * sr - wi * si), -(wr * si + wi * sr)
            q = br * br + bi * bi
            tr, ti = (wr * br + wi * bi) / q, (wi * br - wr * bi) / q
            z[i] = complex(zr - tr, zi - ti)
            moved = max(moved, (tr * tr + ti * ti) / max(zr * zr + zi * zi, 1e-300))
        if settled:
            break
        settled = moved < 1e-24  # (relative step)^2; cubic convergence: one more sweep


@njit(cache=True)
def _trig(coef: np.ndarray, n: int, a: float) -> tuple[float, float]:
    """f(a) = c_0 + 2 Re sum_{k>=1} c_k e^{ika} and f'(a) over the first n coefficients
    (e^{ika} by recurrence from e^{ia})."""
    e1 = complex(math.cos(a), math.sin(a))
    e = 1.0 + 0j
    s = 0j
    ds = 0j
    for k in range(n):
        s += e * coef[k]
        ds += 1j * k * e * coef[k]
        e = e * e1
    return 2.0 * s.real - coef[0].real, 2.0 * ds.real


@njit(cache=True)
def _roots_in_range(c: np.ndarray, deg: int, poly: np.ndarray, z: np.ndarray,
                    found: np.ndarray) -> int:
    """Real roots in [0, pi/2] of the trigonometric polynomial c_0..c_deg (`solvers.
    _coef_roots_batch` and the range filter of `_solve_tttt`), in root order."""
    m = 2 * deg
    for k in range(deg + 1):
        poly[k] = c[deg - k]
    for k in range(1, deg + 1):
        poly[deg + k] = c[k].conjugate()
    _poly_roots(poly[: m + 1], z[:m])
    scale = 0.0
    for k in range(deg + 1):
        scale = max(scale, abs(c[k]))
    n = 0
    for r in range(m):
        if not abs(abs(z[r]) - 1.0) < 1e-4:
            continue
        a = _mod_2pi(math.atan2(z[r].imag, z[r].real))
        for _ in range(3):  # Newton polish on f itself
            f, df = _trig(c, deg + 1, a)
            a = _mod_2pi(a - (f / df if abs(df) > 1e-14 * scale else 0.0))
        prev = np.inf
        for _ in range(60):  # then on while the steps shrink: a double root (where Newton
            f, df = _trig(c, deg + 1, a)  # only halves the error) converges too
            if not abs(df) > 1e-14 * scale:
                break
            step = f / df
            if not (1e-16 < abs(step) < prev):
                break
            a = _mod_2pi(a - step)
            prev = abs(step)
        if a >= -1e-12 and a <= PI / 2 + 1e-12:
            found[n] = min(max(a, 0.0), PI / 2)
            n += 1
    return n


@njit(cache=True)
def rigid(goal: np.ndarray, rho: float, coef: np.ndarray, degree: np.ndarray,
          vcx: np.ndarray, vcy: np.ndarray, geo: np.ndarray, lab: np.ndarray,
          dirs: np.ndarray, kind: np.ndarray, nmov: np.ndarray, rows: np.ndarray,
          out: np.ndarray) -> int:
    """Rigid extremals of one goal: (row, a, u1, u2, cost, end error) in `rows`/`out`.

    `coef[i]` = Fourier coefficients of |V(a)|^2 (degree `degree[i]`), `vcx`, `vcy` those
    of V's components; `geo[i]` = (d1, d2, r_first, r_last, hi_first, hi_last, h10_0, h10_1,
    he_0, he_1, eta_0, eta_1). Branches by increasing degree, then in table order.
    """
    nb = coef.shape[0]
    width = coef.shape[1]
    c = np.empty(width, dtype=np.complex128)
    poly = np.empty(2 * width - 1, dtype=np.complex128)
    z = np.empty(2 * width - 2, dtype=np.complex128)
    found = np.empty(2 * width - 2)
    par = np.zeros(5)
    par[PI_KIND] = PI
    top = 0
    for i in range(nb):
        top = max(top, degree[i])
    count = 0
    for deg in range(1, top + 1):
        for i in range(nb):
            if degree[i] != deg:
                continue
            d1, d2 = geo[i, 0], geo[i, 1]
            dkx, dky = _offsets(goal, d1, d2, geo[i, 2], geo[i, 3])
            for k in range(deg + 1):
                c[k] = coef[i, k]
            c[0] = c[0] - (dkx * dkx + dky * dky)
            n = _roots_in_range(c, deg, poly, z, found)
            for r in range(n):
                a = found[r]
                vx = _trig(vcx[i], vcx.shape[1], a)[0]
                vy = _trig(vcy[i], vcy.shape[1], a)[0]
                h1 = math.atan2(dky, dkx) - math.atan2(vy, vx)
                h2 = h1 + geo[i, 10] + geo[i, 11] * a
                u1, ok1 = _wrap_range(d1 * (h1 - (geo[i, 6] + geo[i, 7] * a)),
                                      PI if geo[i, 4] > 0 else a)
                u2, ok2 = _wrap_range(d2 * (goal[2] - (geo[i, 8] + geo[i, 9] * a) - h2),
                                      PI if geo[i, 5] > 0 else a)
                if not (ok1 and ok2 and vx * vx + vy * vy > 1e-24):
                    continue
                par[U1], par[U2], par[A] = u1, u2, a
                px, py, h, cost = _compose(lab[i], dirs[i], kind[i], nmov[i], par, rho)
                err = _end_error(px, py, h, goal)
                if err > _END_TOL:
                    continue
                rows[count] = i
                out[count, 0], out[count, 1], out[count, 2] = a, u1, u2
                out[count, 3], out[count, 4] = cost, err
                count += 1
    return count


@njit(cache=True)
def _g(x: float) -> float:
    """`fixed_turn_rate._cos_plus_integral` for one value."""
    n = math.floor(x / TWO_PI)
    r = x - TWO_PI * n
    return 2.0 * n + (1.0 - math.cos(min(r, PI)) if r < PI else 2.0)


@njit(cache=True)
def _phi(w: float, gx: float, gy: float, delta: float) -> float:
    return gx * math.cos(w) + gy * math.sin(w) - (_g(delta - w + PI / 2) - _g(-w + PI / 2))


@njit(cache=True)
def _bounded_min(gx: float, gy: float, delta: float, x1: float, x2: float,
                 xatol: float) -> tuple[float, float]:
    """SciPy's `_minimize_scalar_bounded` of -phi on [x1, x2] (maxiter 500): (xf, fx)."""
    sqrt_eps = math.sqrt(2.2e-16)
    golden_mean = 0.5 * (3.0 - math.sqrt(5.0))
    a, b = x1, x2
    fulc = a + golden_mean * (b - a)
    nfc, xf = fulc, fulc
    rat = e = 0.0
    x = xf
    fx = -_phi(x, gx, gy, delta)
    num = 1
    ffulc = fnfc = fx
    xm = 0.5 * (a + b)
    tol1 = sqrt_eps * abs(xf) + xatol / 3.0
    tol2 = 2.0 * tol1
    while abs(xf - xm) > (tol2 - 0.5 * (b - a)):
        golden = True
        if abs(e) > tol1:
            golden = False
            r = (xf - nfc) * (fx - ffulc)
            q = (xf - fulc) * (fx - fnfc)
            p = (xf - fulc) * q - (xf - nfc) * r
            q = 2.0 * (q - r)
            if q > 0.0:
                p = -p
            q = abs(q)
            r = e
            e = rat
            if abs(p) < abs(0.5 * q * r) and p > q * (a - xf) and p < q * (b - xf):
                rat = (p + 0.0) / q
                x = xf + rat
                if (x - a) < tol2 or (b - x) < tol2:
                    d = xm - xf
                    rat = tol1 * (1.0 if d >= 0 else -1.0)  # np.sign(d) + (d == 0)
            else:
                golden = True
        if golden:
            e = (a - xf) if xf >= xm else (b - xf)
            rat = golden_mean * e
        si = 1.0 if rat >= 0 else -1.0  # np.sign(rat) + (rat == 0)
        x = xf + si * max(abs(rat), tol1)
        fu = -_phi(x, gx, gy, delta)
        num += 1
        if fu <= fx:
            if x >= xf:
                a = xf
            else:
                b = xf
            fulc, ffulc = nfc, fnfc
            nfc, fnfc = xf, fx
            xf, fx = x, fu
        else:
            if x < xf:
                a = x
            else:
                b = x
            if fu <= fnfc or nfc == xf:
                fulc, ffulc = nfc, fnfc
                nfc, fnfc = x, fu
            elif fu <= ffulc or fulc == xf or fulc == nfc:
                fulc, ffulc = x, fu
        xm = 0.5 * (a + b)
        tol1 = sqrt_eps * abs(xf) + xatol / 3.0
        tol2 = 2.0 * tol1
        if num >= 500:
            break
    return xf, fx


@njit(cache=True)
def reach(gx: float, gy: float, delta: float, samples: int) -> tuple[float, float]:
    """`fixed_turn_rate.reach_distance`: max over omega of (w . g' - h(omega)), maximiser."""
    step = TWO_PI / samples
    best = -np.inf
    i = 0
    for k in range(samples):
        v = _phi(k * step, gx, gy, delta)
        if v > best:
            best, i = v, k
    om = i * step
    xf, fx = _bounded_min(gx, gy, delta, om - step, om + step, 1e-12)
    if -fx >= best:
        return -fx, xf
    return best, om
