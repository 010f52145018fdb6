"""Compiled (numba) RK4 of Zermelo's state-costate system on the sphere (`routing.zermelo`).

The same equations and bilinear sampling as `zermelo._rhs` / `WindowCurrents.points`: the
current and its cell-wise derivatives (per radian of latitude/longitude) at a point are the
bilinear blend of the four nodes of its cell, linear in time between the levels given.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["fly"]


@njit(cache=True)
def _sample(levels: np.ndarray, times: np.ndarray, steady: bool, t: float, lat_r: float,
            lon_r: float, lat0: float, lon0: float, dlat: float, dlon: float, ny: int, nx: int,
            periodic: bool, centre: float, out: np.ndarray) -> bool:
    """u, du/dphi, du/dlam, v, dv/dphi, dv/dlam into `out`; False off the window or on NaN."""
    lat = math.degrees(lat_r)
    lon = math.degrees(lon_r)
    lon = centre - ((centre - lon + 180.0) % 360.0) + 180.0
    fi = (lat - lat0) / math.degrees(dlat)
    fj = (lon - lon0) / math.degrees(dlon)
    if periodic:
        fj = fj % nx
    if not (fi >= 0.0 and fi <= ny - 1 and fj >= 0.0 and fj <= (nx if periodic else nx - 1)):
        return False
    i = min(int(fi), ny - 2)
    j = int(fj)
    if not periodic:
        j = min(j, nx - 2)
    wy = fi - i
    wx = fj - j
    j1 = (j + 1) % nx if periodic else j + 1
    k = 0
    w = 0.0
    if not steady:
        nl = times.size
        if t <= times[0]:
            k = 0
            w = 0.0
        elif t >= times[nl - 1]:
            k = nl - 2
            w = 1.0
        else:
            while k < nl - 2 and times[k + 1] <= t:
                k += 1
            w = (t - times[k]) / (times[k + 1] - times[k])
    i00 = i * nx + j
    i01 = i * nx + j1
    i10 = (i + 1) * nx + j
    i11 = (i + 1) * nx + j1
    for c in range(2):
        c00 = levels[k, c, i00]
        c01 = levels[k, c, i01]
        c10 = levels[k, c, i10]
        c11 = levels[k, c, i11]
        if not steady and w > 0.0:
            c00 = (1 - w) * c00 + w * levels[k + 1, c, i00]
            c01 = (1 - w) * c01 + w * levels[k + 1, c, i01]
            c10 = (1 - w) * c10 + w * levels[k + 1, c, i10]
            c11 = (1 - w) * c11 + w * levels[k + 1, c, i11]
        val = (1 - wy) * ((1 - wx) * c00 + wx * c01) + wy * ((1 - wx) * c10 + wx * c11)
        if val != val:
            return False
        out[3 * c] = val
        out[3 * c + 1] = ((1 - wx) * (c10 - c00) + wx * (c11 - c01)) / dlat
        out[3 * c + 2] = ((1 - wy) * (c01 - c00) + wy * (c11 - c10)) / dlon
    return True


@njit(cache=True)
def _rhs(z: np.ndarray, t: float, speed: float, R: float, levels: np.ndarray,
         times: np.ndarray, steady: bool, lat0: float, lon0: float, dlat: float, dlon: float,
         ny: int, nx: int, periodic: bool, centre: float, buf: np.ndarray,
         dz: np.ndarray) -> bool:
    phi, lam, qp, ql = z[0], z[1], z[2], z[3]
    if not _sample(levels, times, steady, t, phi, lam, lat0, lon0, dlat, dlon, ny, nx,
                   periodic, centre, buf):
        return False
    u, u_phi, u_lam, v, v_phi, v_lam = buf[0], buf[1], buf[2], buf[3], buf[4], buf[5]
    c = math.cos(phi)
    chi = math.atan2(ql / c, qp)
    sc, cc = math.sin(chi), math.cos(chi)
    dz[0] = (speed * cc + v) / R
    dz[1] = (speed * sc + u) / (R * c)
    dz[2] = -(qp * v_phi / R + ql * u_phi / (R * c) + ql * (speed * sc + u) * math.sin(phi)
              / (R * c * c))
    dz[3] = -(qp * v_lam / R + ql * u_lam / (R * c))
    return True


@njit(cache=True)
def fly(levels: np.ndarray, times: np.ndarray, steady: bool, lat0: float, lon0: float,
        dlat: float, dlon: float, ny: int, nx: int, periodic: bool, centre: float,
        speed: float, t0: float, duration: float, phi0: float, lam0: float,
        chi0: np.ndarray, steps: int, R: float) -> tuple[np.ndarray, int]:
    """RK4 states (steps + 1, 4, m) of each initial heading; rows after the first NaN are
    not valid (the count of valid rows is returned)."""
    m = chi0.size
    out = np.empty((steps + 1, 4, m))
    buf = np.empty(6)
    z = np.empty(4)
    k1 = np.empty(4)
    k2 = np.empty(4)
    k3 = np.empty(4)
    k4 = np.empty(4)
    tmp = np.empty(4)
    dt = duration / steps
    valid = steps + 1
    for col in range(m):
        z[0] = phi0
        z[1] = lam0
        z[2] = math.cos(chi0[col])
        z[3] = math.sin(chi0[col]) * math.cos(phi0)
        out[0, :, col] = z
        for s in range(steps):
            t = t0 + s * dt
            ok = _rhs(z, t, speed, R, levels, times, steady, lat0, lon0, dlat, dlon, ny, nx,
                      periodic, centre, buf, k1)
            for q in range(4):
                tmp[q] = z[q] + 0.5 * dt * k1[q]
            ok = ok and _rhs(tmp, t + 0.5 * dt, speed, R, levels, times, steady, lat0, lon0,
                             dlat, dlon, ny, nx, periodic, centre, buf, k2)
            for q in range(4):
                tmp[q] = z[q] + 0.5 * dt * k2[q]
            ok = ok and _rhs(tmp, t + 0.5 * dt, speed, R, levels, times, steady, lat0, lon0,
                             dlat, dlon, ny, nx, periodic, centre, buf, k3)
            for q in range(4):
                tmp[q] = z[q] + dt * k3[q]
            ok = ok and _rhs(tmp, t + dt, speed, R, levels, times, steady, lat0, lon0, dlat,
                             dlon, ny, nx, periodic, centre, buf, k4)
            if not ok:
                valid = min(valid, s + 1)
                break
            for q in range(4):
                z[q] = z[q] + dt / 6.0 * (k1[q] + 2 * k2[q] + 2 * k3[q] + k4[q])
            nrm = math.hypot(z[2], z[3] / math.cos(z[0]))
            z[2] /= nrm
            z[3] /= nrm
            out[s + 1, :, col] = z
    return out, valid
