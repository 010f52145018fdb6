"""Draw a route over its field (Matplotlib, imported inside; no plotting in the algorithms)."""

from __future__ import annotations

import pathlib
from typing import Any

import numpy as np

from glideplan.fields.field import FlowField
from glideplan.routing.route import RouteResult

__all__ = ["plot_route"]


def plot_route(result: RouteResult, field_: FlowField, filename: str | pathlib.Path,
               arrows: int = 25) -> pathlib.Path:
    """Track (lon, lat) over the field's current at departure (quiver; land shaded)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 5))
    ext = field_.extent
    if result.lat.size:
        la0, la1 = float(result.lat.min()), float(result.lat.max())
        lo0, lo1 = float(result.lon.min()), float(result.lon.max())
        pad_la, pad_lo = max(0.3 * (la1 - la0), 0.05), max(0.3 * (lo1 - lo0), 0.05)
        la0, la1, lo0, lo1 = la0 - pad_la, la1 + pad_la, lo0 - pad_lo, lo1 + pad_lo
    else:
        la0, la1, lo0, lo1 = -1.0, 1.0, -1.0, 1.0
    centre = 0.0 if ext is None else 0.5 * (ext.lon_min + ext.lon_max)

    def frame(lon_deg: Any) -> Any:  # the field's longitude frame (0..360 or -180..180)
        return centre + np.mod(np.asarray(lon_deg) - centre + 180.0, 360.0) - 180.0

    if ext is not None:
        la0, la1 = max(la0, ext.lat_min), min(la1, ext.lat_max)
        lo0, lo1 = max(float(frame(lo0)), ext.lon_min), min(float(frame(lo1)), ext.lon_max)
    lat = np.linspace(la0, la1, arrows)
    lon = np.linspace(lo0, lo1, arrows)
    LA, LO = np.meshgrid(lat, lon, indexing="ij")
    try:
        u, v = field_.velocity(result.depart_s, LA, LO)
        land = ~np.isfinite(u)
        if np.any(land):
            ax.contourf(LO, LA, land.astype(float), levels=[0.5, 1.5], colors=["0.8"])
        ax.quiver(LO, LA, np.where(land, 0, u), np.where(land, 0, v), color="0.5")
    except ValueError:  # a field that cannot be drawn here: draw the track alone
        pass
    kwargs: dict[str, Any] = {"color": "C3", "lw": 2, "label": f"route ({result.method})"}
    if result.lat.size:
        lon_t = frame(result.lon)
        ax.plot(lon_t, result.lat, **kwargs)
        ax.plot(lon_t[0], result.lat[0], "go", label="start")
        ax.plot(lon_t[-1], result.lat[-1], "ks", label="goal")
    title = result.status if result.duration_s is None else (
        f"{result.status}: {result.duration_s / 3600:.2f} h")
    ax.set(xlabel="longitude (deg)", ylabel="latitude (deg)", title=title)
    ax.legend(loc="best")
    path = pathlib.Path(filename)
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path
