"""The pass a max-pooled (coarser, `--resolution`) reach grid closes, named in a warning.

The native search (`reach.native`) runs on the unpooled crop too (~0.7 s per SRTM3 tile).
A node it reaches is lost to the pooling when its nearest pooled node admits the native
loss L there (L <= B_pooled = ALT - z_pooled - clearance: not merely a node beside steep
terrain that its pooled cell's samples shut out) but the pooled search does not reach that
node, or reaches it losing more than MORE_REL x L + `slack_m` (the pooled node's offset: two
pooled cells over the best glide ratio): the way there is closed, or goes round.

The lost node chosen: among those DEEP pooled cells or more beyond every pooled node reached
(cut off, not at the margin of the pooled reach) the one with the least L (the first cut
off: "closes"), else the one with the largest relative excess ("narrows"). Along its native
path from the start (the parents, and the straight line from the start to the first of
them: straight glides and seeds have none) the pooled grid closes the nodes with
L - B_pooled > 0; the pass is the highest terrain among them (the saddle the path crosses;
the middle of a flat col floor), reported with L - B_pooled there (how far the pooled
terrain stands above the glide). Landables whose nearest native node is lost (and reached
natively with the arrival height to spare) are named with it.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

#: Altitude lost on the pooled grid beyond the native loss, relative, that marks a node
#: cut off (the pooled search is conservative by a few %: `reach.native`, max-pooling).
MORE_REL = 0.1
#: Pooled cells beyond the pooled grid's reach that make a node cut off (behind a closure).
DEEP = 2.0
#: The start of the warning (the generic note on pooling begins "the terrain is max-pooled").
PASS_WARNING = "the --resolution"


def _pooled_index(fine: Any, pooled: Any, i: NDArray[np.intp], j: NDArray[np.intp]
                  ) -> tuple[NDArray[np.intp], NDArray[np.intp]]:
    """The nearest pooled node (row, column) of fine nodes (i, j)."""
    la = fine.lat[i]
    lo = fine.lon[j]
    pi = np.clip(np.rint((la - pooled.lat[0]) / pooled.dlat), 0, pooled.shape[0] - 1)
    pj = np.clip(np.rint((lo - pooled.lon[0]) / pooled.dlon), 0, pooled.shape[1] - 1)
    return pi.astype(np.intp), pj.astype(np.intp)


def _straight_nodes(fine: Any, start: tuple[float, float, float], node: int
                    ) -> NDArray[np.intp]:
    """The fine nodes nearest the straight line from the start to `node` (a seed or a node
    of a straight glide from the start: its parents stop there), at half-cell steps, without
    `node` itself."""
    nx = fine.shape[1]
    la1, lo1 = float(fine.lat[node // nx]), float(fine.lon[node % nx])
    n = int(max(abs(la1 - start[0]) / fine.dlat, abs(lo1 - start[1]) / fine.dlon) * 2) + 1
    s = np.linspace(0.0, 1.0, n + 1)[:-1]
    i = np.rint((start[0] + s * (la1 - start[0]) - fine.lat[0]) / fine.dlat)
    j = np.rint((start[1] + s * (lo1 - start[1]) - fine.lon[0]) / fine.dlon)
    k = (np.clip(i, 0, fine.shape[0] - 1) * nx + np.clip(j, 0, nx - 1)).astype(np.intp)
    keep = np.concatenate([[True], k[1:] != k[:-1]]) & (k != node)
    return k[keep]


def closed_pass(fine: Any, pooled: Any, pooled_loss: FloatArray, native: Any,
                start: tuple[float, float, float], clearance: float, landables: Sequence[Any] = (),
                arrival_height: float = 0.0, slack_m: float = 0.0
                ) -> tuple[float, float, float, list[str], bool] | None:
    """(lat, lon of the pass, metres the pooled terrain closes it by, names of landables
    lost: reached natively arriving `arrival_height` above them, whether the pooled grid
    reaches the node chosen at all) for the pooled grid's search `pooled_loss` against the
    `native` search on `fine` (module docstring), or None when the pooled grid loses no node."""
    ny, nx = fine.shape
    alt = start[2]
    ii, jj = np.nonzero(np.isfinite(native.loss))
    pi, pj = _pooled_index(fine, pooled, ii, jj)
    zpool = np.asarray(pooled.z, dtype=float)
    # lost although the node's own pooled cell admits it at the native loss: the way there
    # is closed (not merely a node beside steep terrain its pooled cell's samples shut out)
    admits = native.loss[ii, jj] <= alt - zpool[pi, pj] - clearance
    more = pooled_loss[pi, pj] - native.loss[ii, jj]  # inf: not reached on the pooled grid
    lost = admits & (more > MORE_REL * native.loss[ii, jj] + slack_m)
    if not lost.any():
        return None
    loss = native.loss[ii[lost], jj[lost]]
    from scipy.ndimage import distance_transform_edt

    # cut off: DEEP pooled cells or more beyond every pooled node reached (not a node at the
    # margin of the pooled reach)
    depth = distance_transform_edt(~np.isfinite(pooled_loss))[pi, pj]
    closed = depth[lost] >= DEEP
    # a node the pooled grid does not reach at all first, else the largest relative excess
    key = np.where(closed, loss, np.inf) if closed.any() else -more[lost] / np.maximum(loss, 1.0)
    k = int(np.argmin(key))
    node = int(ii[lost][k]) * nx + int(jj[lost][k])
    path = []
    while node >= 0:
        path.append(node)
        node = int(native.parent[node])
    idx = np.concatenate([_straight_nodes(fine, start, path[-1]),
                          np.array(path[::-1], dtype=np.intp)])
    pi, pj = _pooled_index(fine, pooled, idx // nx, idx % nx)
    zp = zpool[pi, pj]
    b_pooled = alt - np.where(np.isfinite(zp), zp, np.inf) - clearance
    over = np.nan_to_num(native.loss.ravel()[idx], posinf=-np.inf) - b_pooled
    zn = np.asarray(fine.z, dtype=float).ravel()[idx]
    shut = over > 0
    if not shut.any():
        shut = over >= np.max(over)
    top = np.max(np.where(shut, zn, -np.inf))
    tied = np.flatnonzero(shut & (zn >= top - 1.0))  # a flat col floor: its middle
    m = int(tied[tied.size // 2])
    lat, lon = float(fine.lat[idx[m] // nx]), float(fine.lon[idx[m] % nx])
    names = []
    lost_map = np.zeros((ny, nx), dtype=bool)
    lost_map[ii[lost], jj[lost]] = True
    for lnd in landables:
        i = round((lnd.lat - fine.lat[0]) / fine.dlat)
        j = round((lnd.lon - fine.lon[0]) / fine.dlon)
        if (0 <= i < ny and 0 <= j < nx and lost_map[i, j]
                and alt - native.loss[i, j] >= lnd.elevation_m + arrival_height):
            names.append(str(lnd.name))
    return lat, lon, float(over[m]), names, bool(closed.any())


def pass_warning(resolution: float, native_spacing: float, found: tuple[
        float, float, float, list[str], bool]) -> str:
    """The warning text for `closed_pass`'s answer."""
    lat, lon, by, names, closed = found
    lon = (lon + 180.0) % 360.0 - 180.0
    what = "closes" if closed else "narrows"
    text = (f"{PASS_WARNING} {resolution:.0f} m grid {what} a pass near {lat:.4f}, "
            f"{lon:.4f} that the terrain's own {native_spacing:.0f} m grid keeps open (its "
            f"pooled terrain stands {by:.0f} m above the glide through it): ground beyond it "
            + ("is reached only at the terrain's resolution" if closed else
               "costs more altitude on the coarse grid"))
    if names:
        text += (" (reachable only through it at the native resolution: " if closed else
                 " (landables beyond it: ") + ", ".join(names) + ")"
    return text
