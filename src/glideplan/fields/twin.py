"""An identical-twin ocean: a small equivalent-barotropic QG model (NumPy FFTs), truth, forecasts.

The model (doubly periodic, pseudo-spectral, 2/3 dealiased, RK4 in time):

    dq/dt + J(psi, q) + beta dpsi/dx = F(x, y) - mu lap(psi) - nu_8 lap^4 (lap psi)
    q = lap(psi) - psi / Ld^2,   u = -dpsi/dy,  v = dpsi/dx

with a steady random forcing F in a band of wavenumbers (the same in every run: the forecast
model is the truth's model), linear drag mu and a scale-selective filter standing in for
nu_8. It is spun up from rest until statistically steady, and its velocity then has eddies of
the forcing scale that drift, merge and shed.

The twin experiment (`write_twin`): the truth is one run; a forecast issued on day k starts from
the truth on day k plus a perturbation (a random field with the truth's spectrum, of relative
RMS `perturbation`, growing like every error in a turbulent flow) and runs `lead_days` days.
Its vector RMS error |u_f - u_t|_rms / |u_t|_rms grows from `perturbation` at issue towards
sqrt(2) (uncorrelated fields): `forecast_skill` measures it. Files are CF NetCDF on a regular
lat/lon grid (uo/vo in m/s, time in hours since the epoch); forecasts carry
`forecast_reference_time` as a variable and as a global attribute, as operational ones do.
"""

from __future__ import annotations

import math
import pathlib
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.geodesy import EARTH_RADIUS_M  # the one Earth radius

__all__ = ["QGModel", "TwinConfig", "TwinFiles", "forecast_skill", "twin_missions", "write_twin"]

FloatArray = NDArray[np.float64]
DAY = 86400.0


@dataclass(frozen=True)
class TwinConfig:
    """The twin's model and files. n: grid points per side; step_deg: grid spacing (deg; 1/12
    deg like operational 1/12 deg models); centre (lat, lon) deg; ld_m: deformation radius;
    beta (1/(m s)); drag_days: 1/mu; forcing_k: band of forcing wavenumbers (cycles per domain);
    u_rms: the truth's RMS speed (m/s, the flow is rescaled to it after spin-up); dt_s: model
    step; out_h: output interval (h); days: truth length; forecasts: number of daily forecasts
    (issued at day 0, 1, ...); lead_days: forecast length; perturbation: relative RMS of the
    initial error; seed."""

    n: int = 64
    step_deg: float = 1.0 / 12.0
    centre: tuple[float, float] = (30.0, -60.0)
    ld_m: float = 20_000.0
    beta: float = 1.6e-11
    drag_days: float = 30.0
    forcing_k: tuple[float, float] = (10.0, 14.0)
    u_rms: float = 0.2
    dt_s: float = 1800.0
    out_h: float = 3.0
    days: float = 14.0
    forecasts: int = 10
    lead_days: float = 5.0
    perturbation: float = 0.21
    spinup_days: float = 80.0
    seed: int = 1

    def __post_init__(self) -> None:
        if not (isinstance(self.n, int) and self.n >= 16 and self.n % 2 == 0):
            raise InvalidParameterError("n", self.n, "must be an even integer >= 16")
        for name in ("step_deg", "ld_m", "drag_days", "u_rms", "dt_s", "out_h", "days",
                     "lead_days"):
            val = getattr(self, name)
            if not (math.isfinite(val) and val > 0):
                raise InvalidParameterError(name, val, "must be finite and > 0")
        if self.forecasts < 0 or self.forecasts > self.days:
            raise InvalidParameterError("forecasts", self.forecasts,
                                        f"must be in 0..days ({self.days:g})")


class QGModel:
    """The equivalent-barotropic QG model on an nx x ny periodic grid of spacings dx, dy (m)."""

    def __init__(self, cfg: TwinConfig) -> None:
        n = cfg.n
        lat0 = math.radians(cfg.centre[0])
        self.dy = EARTH_RADIUS_M * math.radians(cfg.step_deg)
        self.dx = self.dy * math.cos(lat0)
        self.cfg = cfg
        kx = 2 * np.pi * np.fft.rfftfreq(n, self.dx)
        ky = 2 * np.pi * np.fft.fftfreq(n, self.dy)
        self.kx, self.ky = np.meshgrid(kx, ky)
        self.k2 = self.kx ** 2 + self.ky ** 2
        self.inv = -(self.k2 + 1.0 / cfg.ld_m ** 2)  # q_hat = inv * psi_hat
        # 2/3 dealiasing and an exponential filter on the highest wavenumbers (pyqg-like)
        kmax_x, kmax_y = np.pi / self.dx, np.pi / self.dy
        frac = np.sqrt((self.kx / kmax_x) ** 2 + (self.ky / kmax_y) ** 2)
        self.dealias = (np.abs(self.kx) < 2 / 3 * kmax_x) & (np.abs(self.ky) < 2 / 3 * kmax_y)
        self.filter = np.where(frac > 0.65, np.exp(-23.6 * (frac - 0.65) ** 4), 1.0)
        rng = np.random.default_rng(cfg.seed)
        cycles = np.sqrt((self.kx * n * self.dx / (2 * np.pi)) ** 2
                         + (self.ky * n * self.dy / (2 * np.pi)) ** 2)
        band = (cycles >= cfg.forcing_k[0]) & (cycles <= cfg.forcing_k[1])
        phase = np.exp(2j * np.pi * rng.random(self.k2.shape))
        self.forcing = np.where(band, phase, 0.0) * 1e-12 * n * n
        self.mu = 1.0 / (cfg.drag_days * DAY)

    def velocity(self, qh: NDArray[np.complex128]) -> tuple[FloatArray, FloatArray]:
        """(u, v) on the grid (m/s): u = -dpsi/dy, v = dpsi/dx."""
        ph = qh / self.inv
        n = self.cfg.n
        return (np.fft.irfft2(-1j * self.ky * ph, s=(n, n)),
                np.fft.irfft2(1j * self.kx * ph, s=(n, n)))

    def _rhs(self, qh: NDArray[np.complex128], scale: float) -> NDArray[np.complex128]:
        n = self.cfg.n
        ph = qh / self.inv
        u = np.fft.irfft2(-1j * self.ky * ph, s=(n, n))
        v = np.fft.irfft2(1j * self.kx * ph, s=(n, n))
        qx = np.fft.irfft2(1j * self.kx * qh, s=(n, n))
        qy = np.fft.irfft2(1j * self.ky * qh, s=(n, n))
        adv = np.fft.rfft2(u * qx + v * qy) * self.dealias
        beta = 1j * self.kx * ph * self.cfg.beta
        drag = self.mu * (-self.k2 * ph)
        return -adv - beta - drag + scale * self.forcing

    def run(self, qh: NDArray[np.complex128], seconds: float,
            every_s: float | None = None, scale: float = 1.0) -> tuple[
                NDArray[np.complex128], list[NDArray[np.complex128]]]:
        """Integrate `seconds` (RK4 + filter); return the final state and, with `every_s`, the
        states at 0, every_s, 2 every_s, ... (inclusive of the end when it falls on one)."""
        dt = self.cfg.dt_s
        steps = round(seconds / dt)
        keep = round(every_s / dt) if every_s else 0
        out = [qh.copy()] if keep else []
        for i in range(steps):
            k1 = self._rhs(qh, scale)
            k2 = self._rhs(qh + 0.5 * dt * k1, scale)
            k3 = self._rhs(qh + 0.5 * dt * k2, scale)
            k4 = self._rhs(qh + dt * k3, scale)
            qh = (qh + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)) * self.filter
            if keep and (i + 1) % keep == 0:
                out.append(qh.copy())
        return qh, out

    def rms_speed(self, qh: NDArray[np.complex128]) -> float:
        u, v = self.velocity(qh)
        return float(np.sqrt(np.mean(u * u + v * v)))


def spun_up(model: QGModel) -> tuple[NDArray[np.complex128], float]:
    """A statistically steady state, rescaled (with the forcing) to the configured RMS speed:
    (q_hat, forcing scale). Rescaling q by a and the forcing by a^2 keeps a solution a solution
    only up to time rescaling; we spin up again for 20 days after rescaling."""
    cfg = model.cfg
    rng = np.random.default_rng(cfg.seed + 1)
    qh = np.fft.rfft2(rng.standard_normal((cfg.n, cfg.n)) * 1e-7) * model.dealias
    scale = 1.0
    for _ in range(4):
        qh, _ = model.run(qh, cfg.spinup_days / 4 * DAY, scale=scale)
        a = cfg.u_rms / max(model.rms_speed(qh), 1e-12)
        qh, scale = qh * a, scale * a * a
    qh, _ = model.run(qh, 20 * DAY, scale=scale)
    return qh, scale


def perturb(model: QGModel, qh: NDArray[np.complex128], relative: float,
            rng: np.random.Generator) -> NDArray[np.complex128]:
    """q_hat plus a random-phase field with the same spectrum, of relative velocity RMS."""
    phase = np.exp(2j * np.pi * rng.random(qh.shape))
    noise = qh * phase
    u0 = model.rms_speed(qh)
    un = model.rms_speed(noise)
    return qh + noise * (relative * u0 / max(un, 1e-12))


@dataclass(frozen=True)
class TwinFiles:
    """What `write_twin` wrote: the truth file, the forecast files (by issue day), the forecast
    skill (vector RMS error relative to the truth's RMS speed, by lead day)."""

    truth: pathlib.Path
    forecasts: tuple[pathlib.Path, ...]
    skill: dict[str, float]
    lat: tuple[float, float]
    lon: tuple[float, float]
    epoch: str


def _grid(cfg: TwinConfig) -> tuple[FloatArray, FloatArray]:
    idx = np.arange(cfg.n, dtype=float) - (cfg.n - 1) / 2
    return (np.asarray(cfg.centre[0] + idx * cfg.step_deg, dtype=float),
            np.asarray(cfg.centre[1] + idx * cfg.step_deg, dtype=float))


def _write(path: pathlib.Path, cfg: TwinConfig, model: QGModel, states: Sequence[Any],
           t0_h: float, epoch: np.datetime64, issue_h: float | None) -> None:
    """One CF NetCDF file of the states (every out_h hours from t0_h)."""
    import xarray as xr

    lat, lon = _grid(cfg)
    uv = [model.velocity(s) for s in states]
    u = np.stack([a for a, _ in uv]).astype(np.float32)
    v = np.stack([b for _, b in uv]).astype(np.float32)
    hours = t0_h + cfg.out_h * np.arange(len(states))
    times = epoch + (hours * 3600).astype("timedelta64[s]")
    dims = ("time", "latitude", "longitude")
    data: dict[str, Any] = {
        "uo": (dims, u, {"standard_name": "eastward_sea_water_velocity", "units": "m s-1"}),
        "vo": (dims, v, {"standard_name": "northward_sea_water_velocity", "units": "m s-1"})}
    attrs = {"Conventions": "CF-1.8", "title": "glideplan twin experiment (QG model)",
             "source": "glideplan.fields.twin"}
    if issue_h is not None:
        ref = epoch + np.timedelta64(round(issue_h * 3600), "s")
        data["forecast_reference_time"] = ((), ref.astype("datetime64[ns]"),
                                           {"standard_name": "forecast_reference_time"})
        attrs["forecast_reference_time"] = str(ref) + "Z"
    ds = xr.Dataset(data, coords={
        "time": ("time", times.astype("datetime64[ns]")),
        "latitude": ("latitude", lat, {"units": "degrees_north"}),
        "longitude": ("longitude", lon, {"units": "degrees_east"})}, attrs=attrs)
    enc = {"time": {"units": f"hours since {str(epoch)[:19]}"}}
    if issue_h is not None:
        enc["forecast_reference_time"] = {"units": f"hours since {str(epoch)[:19]}"}
    ds.to_netcdf(path, encoding=enc)


def _error(model: QGModel, a: NDArray[np.complex128], b: NDArray[np.complex128]) -> float:
    ua, va = model.velocity(a)
    ub, vb = model.velocity(b)
    return float(np.sqrt(np.mean((ua - ub) ** 2 + (va - vb) ** 2))
                 / np.sqrt(np.mean(ua ** 2 + va ** 2)))


def write_twin(out_dir: str | pathlib.Path, config: TwinConfig | None = None,
               epoch: str = "2026-03-01T00:00") -> TwinFiles:
    """Write truth.nc and forecasts/fc_DDD.nc into `out_dir` (module docstring)."""
    cfg = config or TwinConfig()
    out = pathlib.Path(out_dir)
    (out / "forecasts").mkdir(parents=True, exist_ok=True)
    ep = np.datetime64(epoch, "s")
    model = QGModel(cfg)
    q0, scale = spun_up(model)
    every = cfg.out_h * 3600.0
    _, truth = model.run(q0, cfg.days * DAY, every_s=every, scale=scale)
    _write(out / "truth.nc", cfg, model, truth, 0.0, ep, None)
    per_day = round(DAY / every)
    rng = np.random.default_rng(cfg.seed + 2)
    paths: list[pathlib.Path] = []
    errs: dict[int, list[float]] = {}
    for d in range(cfg.forecasts):
        start = truth[d * per_day]
        q = perturb(model, start, cfg.perturbation, rng)
        _, states = model.run(q, cfg.lead_days * DAY, every_s=every, scale=scale)
        path = out / "forecasts" / f"fc_{d:03d}.nc"
        _write(path, cfg, model, states, d * 24.0, ep, d * 24.0)
        paths.append(path)
        for lead in range(int(cfg.lead_days) + 1):
            k = d * per_day + lead * per_day
            if k < len(truth) and lead * per_day < len(states):
                errs.setdefault(lead, []).append(_error(model, truth[k], states[lead * per_day]))
    lat, lon = _grid(cfg)
    skill = {f"day_{k}": float(np.mean(v)) for k, v in sorted(errs.items())}
    return TwinFiles(out / "truth.nc", tuple(paths), skill, (float(lat[0]), float(lat[-1])),
                     (float(lon[0]), float(lon[-1])), str(ep) + "Z")


def forecast_skill(cfg: TwinConfig | None = None) -> dict[str, float]:
    """Mean vector RMS error by lead day of the twin's forecasts (no files written)."""
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        return write_twin(tmp, replace(cfg or TwinConfig(), forecasts=3, days=6.0)).skill


def twin_missions(files: TwinFiles, n: int, seed: int = 0, speed: float = 0.5,
                  distance_km: tuple[float, float] = (150.0, 300.0),
                  slack: tuple[float, float] = (0.9, 1.15), max_hours: float = 192.0,
                  goal_radius_m: float = 2000.0, depart_days: tuple[float, float] = (0.0, 5.0),
                  margin_deg: float = 0.4) -> list[dict[str, Any]]:
    """n random missions in the twin's box (rows of missions.csv): start and goal `margin_deg`
    inside it, `distance_km` apart; the time limit is the still-water time d / V times a
    factor drawn from `slack` (tight limits are where knowing the currents matters), at most
    `max_hours`; departure a whole hour drawn from `depart_days` after the truth's start."""
    from glideplan.routing.sphere import destination, gc_distance

    rng = np.random.default_rng(seed)
    la0, la1 = files.lat[0] + margin_deg, files.lat[1] - margin_deg
    lo0, lo1 = files.lon[0] + margin_deg, files.lon[1] - margin_deg
    ep = np.datetime64(files.epoch.rstrip("Z"), "s")
    out: list[dict[str, Any]] = []
    while len(out) < n:
        a = (rng.uniform(la0, la1), rng.uniform(lo0, lo1))
        d = rng.uniform(*distance_km) * 1e3
        la, lo = destination(a[0], a[1], rng.uniform(0, 2 * np.pi), d)
        if not (la0 <= la <= la1 and lo0 <= lo <= lo1):
            continue
        hours = min(max_hours, float(gc_distance(a[0], a[1], la, lo)) / speed / 3600.0
                    * rng.uniform(*slack))
        dep = ep + np.timedelta64(int(rng.uniform(*depart_days) * 24), "h")
        out.append({"id": f"m{len(out):03d}", "start_lat": round(float(a[0]), 5),
                    "start_lon": round(float(a[1]), 5), "goal_lat": round(float(la), 5),
                    "goal_lon": round(float(lo), 5), "depart": str(dep) + "Z",
                    "speed_mps": speed, "goal_radius_m": goal_radius_m,
                    "max_hours": round(hours, 3)})
    return out
