"""The depth dimension of a field file: the layer mean over a depth range, or the level
nearest the surface (`glideplan.fields.io`, "Depth" in its docstring).

With `depth_range=(z0, z1)` (m, positive down) the field is averaged over the layer by the
trapezoidal rule on the file's depth levels (profile interpolated linearly at z0 and z1):
ubar = (1 / (z1 - z0)) * integral_{z0}^{z1} u(z) dz; above the first level the top level's
value is held constant to the surface. Nodes with water at the top level but no layer mean
are where the range reaches below the sea floor (`GriddedField.nodata`). ROMS s-levels have
no fixed depths: only their top level is read.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from glideplan.errors import InvalidParameterError

__all__ = ["DEPTH_NAMES", "S_LEVELS", "depth_average", "reduce_vertical"]

DEPTH_NAMES = ("depth", "lev", "z", "deptht", "depthu", "depthv", "level")
S_LEVELS = ("s_rho", "s_w")
_DEPTH = DEPTH_NAMES
_S_LEVELS = S_LEVELS


def depth_average(profile: np.ndarray, depths: np.ndarray, z0: float, z1: float) -> np.ndarray:
    """Trapezoidal layer mean over [z0, z1] (m, positive down) along axis 0 of `profile`.

    ubar = (1/(z1-z0)) sum_k (z_{k+1} - z_k) (u_k + u_{k+1}) / 2 over the levels inside the
    layer, with the profile linearly interpolated at z0 and z1. Above the first level z_1 the
    profile is held at u_1 (to the surface, z0 >= 0): the layer [0, z_1] adds z_1 u_1. NaN
    anywhere in the layer (below the sea floor, land) gives NaN.
    """
    z = np.asarray(depths, dtype=float).reshape(-1)
    order = np.argsort(z)
    z = z[order]
    prof = np.asarray(profile, dtype=float)[order]
    if not (np.isfinite(z0) and np.isfinite(z1) and z0 < z1):
        raise InvalidParameterError("depth_range", (z0, z1), "needs Z0 < Z1 (m, positive down)")
    if z0 < 0.0:
        raise InvalidParameterError(
            "depth_range", (z0, z1), "depths are metres below the surface (Z0 >= 0)"
        )
    if z1 > z[-1] + 1e-9:
        raise InvalidParameterError(
            "depth_range", (z0, z1),
            f"below the file's deepest level {z[-1]:g} m (depth levels {z[0]:g}..{z[-1]:g} m)",
        )
    if z0 < z[0]:  # constant extrapolation to the surface only
        z = np.concatenate([[z0], z])
        prof = np.concatenate([prof[:1], prof], axis=0)

    def at(zq: float) -> np.ndarray:
        k = int(np.clip(np.searchsorted(z, zq, side="right") - 1, 0, z.size - 2))
        w = (zq - z[k]) / (z[k + 1] - z[k])
        if w <= 0.0:
            return prof[k]
        if w >= 1.0:
            return prof[k + 1]
        return (1.0 - w) * prof[k] + w * prof[k + 1]

    inner = (z > z0) & (z < z1)
    zs = np.concatenate([[z0], z[inner], [z1]])
    vals = np.concatenate([at(z0)[None], prof[inner], at(z1)[None]], axis=0)
    dz = np.diff(zs).reshape((-1,) + (1,) * (vals.ndim - 1))
    return (0.5 * dz * (vals[1:] + vals[:-1])).sum(axis=0) / (z1 - z0)


def reduce_vertical(ds: Any, d: Any, depth_range: tuple[float, float] | None, info: dict[str, Any],
              warnings: list[str]) -> Any:
    """Reduce the depth (or ROMS s-level) dimension: layer mean or the level nearest 0 m."""
    for sname in _S_LEVELS:
        if sname in d.dims:
            if depth_range is not None:
                raise InvalidParameterError(
                    "depth_range", depth_range,
                    f"the file has terrain-following levels ({sname}) without fixed depths: "
                    "interpolate it to depth levels first, or omit the depth range to use the "
                    "top level",
                )
            s = np.asarray(d[sname].values if sname in d.coords else np.arange(d.sizes[sname]),
                           dtype=float)
            k = int(np.argmax(s))
            info["depth_m"] = 0.0
            info["level"] = f"top {sname} level ({s[k]:g})"
            return d.isel({sname: k}, drop=True)
    depth_n = None
    for n in list(_DEPTH) + [str(c) for c in d.coords]:
        if n in d.coords and d[n].ndim == 1 and d[n].dims[0] in d.dims and (
                n in _DEPTH or d[n].attrs.get("positive") in ("down", "up")
                or d[n].attrs.get("axis") == "Z"):
            depth_n = n
            break
    if depth_n is None:
        if depth_range is not None:
            raise InvalidParameterError("depth_range", depth_range,
                                        "the field has no depth levels")
        return d
    depths = np.abs(np.asarray(d[depth_n].values, dtype=float))
    zdim = d[depth_n].dims[0]
    d = d.transpose(zdim, ...)
    if depth_range is None:
        k = int(np.argmin(depths))
        info["depth_m"] = float(depths[k])
        return d.isel({zdim: k}, drop=True)
    z0, z1 = float(depth_range[0]), float(depth_range[1])
    vals = depth_average(np.asarray(d.values, dtype=float), depths, z0, z1)
    info["depth_average_m"] = [z0, z1]
    # nodes with water at the top level but no layer mean: the range reaches the sea floor
    top_ok = np.isfinite(np.asarray(d.isel({zdim: int(np.argmin(depths))}).values, dtype=float))
    info["_floor"] = d.isel({zdim: 0}, drop=True).copy(data=top_ok & ~np.isfinite(vals))
    top = float(np.min(depths))
    if np.isfinite(z0) and z0 < top:
        text = (f"depth range {z0:g}..{z1:g} m starts above the file's first level {top:g} m: "
                f"the top level's value is used from {z0:g} to {top:g} m (held constant to "
                "the surface)")
        if text not in warnings:
            warnings.append(text)
    return d.isel({zdim: 0}, drop=True).copy(data=vals)
