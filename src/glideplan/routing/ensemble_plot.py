"""Figures of an ensemble (corridor, envelope, arrival times) and of a departure range.

`ensemble_figure`: left, the members' tracks (thin), their envelope (shaded), the chosen route
(bold) and start/goal, on longitude / latitude axes with a km east as long as a km north;
right, the histogram of the members' arrival durations (h) with P10, P50, P90 and the duration
limit, the unreachable members counted in the title. `departure_figure`: duration (h) against
departure (one field), or P50 with the P10-P90 band and p_arrival on a second axis (an
ensemble), the best departure marked. Matplotlib is imported inside the functions.
"""

from __future__ import annotations

import math
import pathlib
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from glideplan.routing.departures import DepartureResult
    from glideplan.routing.ensemble import EnsembleResult

__all__ = ["departure_figure", "ensemble_figure", "plot_departures", "plot_ensemble"]


def _corridor(ax: Any, res: EnsembleResult) -> None:
    from glideplan.routing.plot import frame_scales

    ref = res.routes[0].start[1]

    def unwrap(lon: Any) -> Any:
        return ref + np.mod(np.asarray(lon, dtype=float) - ref + 180.0, 360.0) - 180.0

    if res.envelope is not None:
        ax.fill(unwrap(res.envelope[1]), res.envelope[0], color="tab:blue", alpha=0.18,
                lw=0, label="corridor (envelope of the members' tracks)")
    first = True
    for i, r in enumerate(res.routes):
        if r.track.size < 2 or i == res.chosen:
            continue
        ax.plot(unwrap(r.lon), r.lat, color="tab:blue", lw=0.7, alpha=0.6,
                label="member routes" if first else None)
        first = False
    chosen = res.chosen_route
    if chosen is not None:
        ax.plot(unwrap(chosen.lon), chosen.lat, color="k", lw=2.2,
                label=f"route to fly (member {res.chosen}, p = {res.chosen_p_arrival:.2f})")
    s, g = res.routes[0].start, res.routes[0].goal
    ax.plot(unwrap(s[1]), s[0], "o", color="tab:green", ms=8, label="start")
    ax.plot(unwrap(g[1]), g[0], "*", color="tab:red", ms=12, label="goal")
    m_lat, m_lon = frame_scales(0.5 * (s[0] + g[0]), 0.5 * (s[1] + g[1]))
    lats = np.concatenate([[s[0], g[0]]] + [r.lat for r in res.routes if r.track.size])
    lons = unwrap(np.concatenate([[s[1], g[1]]] + [r.lon for r in res.routes if r.track.size]))
    # a frame at least 40 % as tall as wide (in km) with a 10 % margin: flat corridors show
    w_km = max(float(np.ptp(lons)) * m_lon, float(np.ptp(lats)) * m_lat, 1.0) / 1000.0
    half_lat = max(0.5 * float(np.ptp(lats)) * m_lat / 1000.0, 0.2 * w_km) * 1.1 * 1000 / m_lat
    half_lon = max(0.5 * float(np.ptp(lons)) * m_lon / 1000.0, 0.2 * w_km) * 1.1 * 1000 / m_lon
    c_lat, c_lon = 0.5 * (lats.min() + lats.max()), 0.5 * (lons.min() + lons.max())
    ax.set_xlim(c_lon - half_lon, c_lon + half_lon)
    ax.set_ylim(c_lat - half_lat, c_lat + half_lat)
    ax.set_aspect(m_lat / m_lon, adjustable="box")
    ax.ticklabel_format(useOffset=False)
    ax.set_xlabel("longitude (deg)")
    ax.set_ylabel("latitude (deg)")
    ax.legend(loc="upper left", bbox_to_anchor=(0.0, -0.2), fontsize=8, frameon=False)


def _histogram(ax: Any, res: EnsembleResult) -> None:
    d = res.durations
    h = d[np.isfinite(d)] / 3600.0
    if h.size:
        ax.hist(h, bins=max(5, min(30, h.size)), color="tab:blue", alpha=0.6,
                label="members' routes")
    for q, style in ((0.1, ":"), (0.5, "-"), (0.9, "--")):
        v = res.quantile_h(q)
        if v is not None:
            ax.axvline(v, color="k", ls=style, lw=1.2, label=f"P{round(q * 100)} {v:.1f} h")
    if res.max_duration_s is not None:
        ax.axvline(res.max_duration_s / 3600.0, color="tab:red", lw=1.5,
                   label=f"limit {res.max_duration_s / 3600.0:.1f} h")
    ax.set_xlabel("arrival after departure (h)")
    ax.set_ylabel("members")
    ax.legend(fontsize=8)


def ensemble_figure(res: EnsembleResult, **_: Any) -> Any:
    """The corridor and the arrival-time distribution (module docstring)."""
    import matplotlib.pyplot as plt

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12.0, 6.0),
                                 gridspec_kw={"width_ratios": [1.4, 1.0]})
    _corridor(a1, res)
    _histogram(a2, res)
    n = len(res.routes)
    unreached = int(np.sum(~np.isfinite(res.durations)))
    fig.suptitle(f"Ensemble of {n} members: p_arrival = {res.p_arrival:.2f} "
                 f"({unreached} not reaching the goal); {res.message}", fontsize=10)
    fig.subplots_adjust(bottom=0.25, wspace=0.3)
    return fig


def plot_ensemble(res: EnsembleResult, filename: str | pathlib.Path) -> pathlib.Path:
    """Draw `ensemble_figure` to `filename`."""
    from glideplan.plotting import save_figure

    return pathlib.Path(save_figure(ensemble_figure(res), pathlib.Path(filename), tight=False))


def _hours_since(deps: Any) -> tuple[np.ndarray, str]:
    d = np.asarray(deps)
    if np.issubdtype(d.dtype, np.datetime64):
        return (d - d[0]) / np.timedelta64(1, "h"), f"departure (h after {str(d[0])[:16]}Z)"
    return (d.astype(float) - float(d[0])) / 3600.0, "departure (h after the first)"


def departure_figure(res: DepartureResult, ax: Any = None, **_: Any) -> Any:
    """Duration against departure, the best departure marked (module docstring)."""
    import matplotlib.pyplot as plt

    if ax is None:
        fig, ax = plt.subplots(figsize=(8.0, 5.0))
    else:
        fig = ax.figure
    x, label = _hours_since(res.departures)
    y = res.durations_s / 3600.0
    y = np.where(np.isfinite(y), y, np.nan)
    if res.ensembles:
        lo = np.array([_nan(e.quantile_h(0.1)) for e in res.ensembles])
        hi = np.array([_nan(e.quantile_h(0.9)) for e in res.ensembles])
        ax.fill_between(x, lo, hi, color="tab:blue", alpha=0.2, label="P10-P90 over members")
        ax.plot(x, y, "o-", color="tab:blue", label="P50 over members")
        ax2 = ax.twinx()
        ax2.plot(x, [e.p_arrival for e in res.ensembles], "s--", color="tab:green", ms=4)
        ax2.set_ylabel("p_arrival", color="tab:green")
        ax2.set_ylim(-0.05, 1.05)
    else:
        ax.plot(x, y, "o-", color="tab:blue", label="route duration")
        miss = ~np.isfinite(y)
        if miss.any():
            ax.plot(x[miss], np.zeros(int(miss.sum())), "x", color="tab:red",
                    label="no route")
    if res.best is not None:
        ax.plot(x[res.best], y[res.best], "*", color="tab:red", ms=16,
                label=f"best departure ({y[res.best]:.2f} h)")
    ax.set_xlabel(label)
    ax.set_ylabel("duration (h)")
    ax.set_title(f"Duration against departure: {res.message}", fontsize=10)
    ax.legend(fontsize=8, loc="best")
    ax.grid(alpha=0.3)
    return fig


def _nan(v: float | None) -> float:
    return math.nan if v is None else v


def plot_departures(res: DepartureResult, filename: str | pathlib.Path) -> pathlib.Path:
    """Draw `departure_figure` to `filename`."""
    from glideplan.plotting import save_figure

    return pathlib.Path(save_figure(departure_figure(res), pathlib.Path(filename), tight=False))
