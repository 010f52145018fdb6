"""Figures and GeoJSON of a replay: the flown track over the truth, the plans, the baselines."""

from __future__ import annotations

import json
import pathlib
from typing import Any

import numpy as np

from glideplan.routing.replay import ReplayResult

__all__ = ["plot_replay", "replay_figure", "write_replay_geojson"]


def _box(res: ReplayResult, truth: Any) -> tuple[float, float, float, float]:
    lats = [res.flight.lat, *(b.lat for b in res.baselines.values())]
    lons = [res.flight.lon, *(b.lon for b in res.baselines.values())]
    la, lo = np.concatenate(lats), np.concatenate(lons)
    pad_la = 0.15 * max(np.ptp(la), 0.2)
    pad_lo = 0.15 * max(np.ptp(lo), 0.2)
    box = [la.min() - pad_la, la.max() + pad_la, lo.min() - pad_lo, lo.max() + pad_lo]
    ext = getattr(truth, "extent", None)
    if ext is not None and not ext.periodic:
        box = [max(box[0], ext.lat_min), min(box[1], ext.lat_max),
               max(box[2], ext.lon_min), min(box[3], ext.lon_max)]
    return box[0], box[1], box[2], box[3]


def replay_figure(res: ReplayResult, truth: Any, ax: Any = None) -> Any:
    """The flown track over the truth's current speed (mean over the flight) and arrows at
    departure; each plan drawn from where it was made; hindsight, plan_once and naive."""
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(8, 7))
    la0, la1, lo0, lo1 = _box(res, truth)
    lat = np.linspace(la0, la1, 60)
    lon = np.linspace(lo0, lo1, 60)
    LA, LO = np.meshgrid(lat, lon, indexing="ij")
    epoch = truth.epoch
    t0 = float((res.mission.depart - epoch) / np.timedelta64(1, "s")) if epoch is not None \
        else 0.0
    t_end = t0 + float(res.flight.t[-1])
    speeds = []
    for t in np.linspace(t0, t_end, 5):
        u, v = truth.velocity(np.full(LA.shape, t), LA, LO)
        speeds.append(np.hypot(u, v))
    mesh = ax.pcolormesh(lon, lat, np.nanmean(speeds, axis=0), cmap="Blues", shading="auto")
    plt.colorbar(mesh, ax=ax, label="truth current speed, mean over the flight (m/s)")
    u, v = truth.velocity(np.full(LA.shape, t0), LA, LO)
    k = slice(None, None, 4)
    ax.quiver(LO[k, k], LA[k, k], u[k, k], v[k, k], color="0.35", width=0.002)
    for i, p in enumerate(res.flight.plans):
        if p.lat.size:
            ax.plot(p.lon, p.lat, "--", lw=0.9, color=plt.cm.autumn(i / max(1, len(
                res.flight.plans))), label="plans (where made)" if i == 0 else None)
    styles = {"hindsight": ("k", ":", "hindsight (planned on the truth)"),
              "plan_once": ("0.5", "-.", "plan_once"), "naive": ("0.6", "-", "naive")}
    for name, (c, ls, label) in styles.items():
        b = res.baselines[name]
        ax.plot(b.lon, b.lat, ls, color=c, lw=1.2, label=f"{label}: {_h(b.duration_s)}")
    f = res.flight
    ax.plot(f.lon, f.lat, "-", color="crimson", lw=2.2, label=f"replay (flown): "
            f"{_h(f.duration_s)}")
    for p in f.plans:
        j = int(np.clip(np.searchsorted(f.t, p.time_s), 0, f.t.size - 1))
        ax.plot(f.lon[j], f.lat[j], "o", color="crimson", ms=4)
    ax.plot(res.mission.start[1], res.mission.start[0], "ks", ms=7)
    ax.plot(res.mission.goal[1], res.mission.goal[0], "k*", ms=12)
    ax.set_xlabel("longitude (deg)")
    ax.set_ylabel("latitude (deg)")
    ax.set_title(f"replay: {f.status}, {len(f.plans)} plans")
    ax.set_aspect(1.0 / max(np.cos(np.radians(0.5 * (la0 + la1))), 0.1))
    ax.legend(loc="best", fontsize=8)
    return ax


def _h(s: float | None) -> str:
    return "not reached" if s is None else f"{s / 3600:.1f} h"


def plot_replay(res: ReplayResult, truth: Any, path: str | pathlib.Path) -> pathlib.Path:
    """Draw `replay_figure` to a file."""
    from glideplan.plotting import save_figure

    ax = replay_figure(res, truth)
    return pathlib.Path(save_figure(ax.figure, pathlib.Path(path)))


def write_replay_geojson(res: ReplayResult, path: str | pathlib.Path) -> pathlib.Path:
    """A FeatureCollection: the flown track (kind "flown"), each plan (kind "plan", with the
    time it was made and its forecast) and the baselines (kind "baseline")."""
    from glideplan.formats.tracks import geojson_line

    feats = [{"type": "Feature", "geometry": geojson_line(res.flight.lat, res.flight.lon),
              "properties": {"kind": "flown", "status": res.flight.status,
                             "duration_s": res.flight.duration_s}}]
    for p in res.flight.plans:
        if p.lat.size >= 2:
            feats.append({"type": "Feature", "geometry": geojson_line(p.lat, p.lon),
                          "properties": {"kind": "plan", **p.to_dict()}})
    for name, b in res.baselines.items():
        if b.lat.size >= 2:
            feats.append({"type": "Feature", "geometry": geojson_line(b.lat, b.lon),
                          "properties": {"kind": "baseline", "name": name, **b.summary()}})
    out = pathlib.Path(path)
    out.write_text(json.dumps({"type": "FeatureCollection", "features": feats}, indent=1,
                              allow_nan=False) + "\n", encoding="utf-8")
    return out
