"""Voids (no-data samples) in a DEM: refuse them, or fill them from their neighbours.

`nearest`: each void takes the value of the nearest valid sample (Euclidean in index space,
scipy.ndimage.distance_transform_edt). `linear`: piecewise-linear interpolation over a
Delaunay triangulation of the valid samples bordering the voids (scipy griddata); voids
outside their convex hull (at a tile's edge) fall back to `nearest`.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError

__all__ = ["VOID_MODES", "fill_voids"]

VOID_MODES = ("refuse", "nearest", "linear")


def fill_voids(
    z: NDArray[np.floating], void: NDArray[np.bool_], mode: str, source: str
) -> tuple[NDArray[np.float32], str | None]:
    """(z with voids filled, a warning or None). `mode` in VOID_MODES; `refuse` raises
    `InvalidParameterError` naming `source` when there is a void."""
    if mode not in VOID_MODES:
        raise InvalidParameterError("voids", mode, f"must be one of {', '.join(VOID_MODES)}")
    out = np.asarray(z, dtype=np.float32).copy()
    n = int(void.sum())
    if n == 0:
        return out, None
    if mode == "refuse":
        raise InvalidParameterError(
            source, f"{n} void(s)",
            "the terrain has voids (no-data samples); fill them (voids='nearest' or 'linear', "
            "--fill-voids) or use a void-filled DEM")
    if n == void.size:
        raise InvalidParameterError(source, "all voids", "the terrain has no valid sample")
    from scipy.ndimage import binary_dilation, distance_transform_edt

    idx = distance_transform_edt(void, return_distances=False, return_indices=True)
    nearest = out[idx[0], idx[1]]
    if mode == "nearest":
        out[void] = nearest[void]
    else:
        from scipy.interpolate import griddata

        ring = binary_dilation(void, iterations=2) & ~void
        pts = np.argwhere(ring)
        holes = np.argwhere(void)
        vals = griddata(pts, out[ring], holes, method="linear")
        vals = np.where(np.isfinite(vals), vals, nearest[void])
        out[void] = vals
    frac = 100.0 * n / void.size
    return out, f"{source}: filled {n} void sample(s) ({frac:.3g} %) by {mode} interpolation"
