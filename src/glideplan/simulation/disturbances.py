"""Velocity disturbances for the disturbed car (3.2): steady uniform wind and Dryden gusts.

A disturbance is a recipe; `stream(rows, dt, rng)` starts an independent realisation for
`rows` vehicles (or samples) and returns a `DisturbanceStream` whose `next()` gives the
disturbance velocity (rows, 2) in m/s for the next time step. Everything is vectorised
across rows and driven by an explicit `numpy.random.Generator` (no global random state).

Dryden turbulence (dissertation §3.4; Gage 2003; MIL-F-8785C longitudinal spectrum
Phi(Omega) = sigma_c^2 (2 L / pi) / (1 + (L Omega)^2)): each horizontal inertial component is
a stationary Gauss-Markov process with autocorrelation sigma_c^2 exp(-V tau / L), the Dryden
longitudinal correlation for a vehicle flying at airspeed V through a frozen field. It is
stepped with the exact AR(1) recursion g[k+1] = a g[k] + sigma_c sqrt(1 - a^2) eta[k],
a = exp(-V dt / L) (REFERENCE_NOTES §2.3), which has the exact variance and correlation for
any dt (no sqrt(pi / dt) noise-normalisation pitfall). sigma is the RMS of the gust
magnitude, so each component has sigma_c = sigma / sqrt(2) (unless `per_component`). The
vector is saturated at |delta| <= saturation (the dissertation's eps v) after the filter.

`gust_scale` f (default 1) is a sensitivity option, not part of the dissertation's model: the
RMS becomes f sigma while the saturation stays as given. The literal reading of §3.4
(sigma = eps v) is f = 1; f = 1/sqrt(pi) is the slip of unit-intensity white noise, and
f = 0.3-0.4 brings the Fig 3.4(b) curves under the dissertation's axis.

A disturbance that depends on where the vehicle is and when (a current or wind field) is a
`FieldDisturbance(velocity)`: its stream is a `PositionalStream`, whose `at(t, x, y, rows)`
the simulator calls once per step with every flying vehicle's position (vectorised), giving
delta = velocity(t0 + t, x, y). NaN components mean "undefined here" (off a field, on land):
the simulator stops those vehicles.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike

from glideplan.errors import InvalidParameterError
from glideplan.validation import check_finite_array, check_nonnegative, check_positive

__all__ = [
    "DisturbanceStream",
    "DrydenTurbulence",
    "FieldDisturbance",
    "PositionalStream",
    "SteadyDisturbance",
    "saturate",
]


class DisturbanceStream(Protocol):
    """One realisation of a disturbance for `rows` vehicles, stepped once per time step."""

    @property
    def rows(self) -> int:
        """Number of vehicles (rows) of the realisation."""
        ...

    def next(self) -> np.ndarray:
        """Disturbance velocity (rows, 2) in m/s over the next step."""
        ...


def saturate(vectors: np.ndarray, limit: float | np.ndarray) -> np.ndarray:
    """Scale each row vector (..., 2) down to magnitude <= limit (m/s); others unchanged."""
    mag = np.hypot(vectors[..., 0], vectors[..., 1])
    lim = np.asarray(limit, dtype=float)
    scale = np.where(mag > lim, lim / np.where(mag > 0.0, mag, 1.0), 1.0)
    return vectors * scale[..., None]


@dataclass(frozen=True, eq=False)
class _ConstantStream:
    velocity: np.ndarray

    @property
    def rows(self) -> int:
        return int(self.velocity.shape[0])

    def next(self) -> np.ndarray:
        return self.velocity


@dataclass(frozen=True, eq=False)
class SteadyDisturbance:
    """A constant uniform disturbance: the (east, north) velocity `wind` (m/s, the direction it
    blows TOWARDS; `glideplan.units.WindEN`), shape (2,) for every row or (rows, 2)."""

    wind: ArrayLike

    def __post_init__(self) -> None:
        wind = check_finite_array("wind", self.wind, last_dim=2)
        if wind.ndim > 2:
            raise InvalidParameterError("wind", wind.shape, "must have shape (2,) or (rows, 2)")
        object.__setattr__(self, "wind", wind)

    def velocity(self, rows: int) -> np.ndarray:
        """The constant velocity (rows, 2) in m/s."""
        try:
            return np.broadcast_to(np.asarray(self.wind).reshape(-1, 2), (rows, 2)).copy()
        except ValueError:
            raise InvalidParameterError(
                "rows", rows, "must match the number of wind values"
            ) from None

    def stream(
        self, rows: int, dt: float, rng: np.random.Generator | None = None
    ) -> DisturbanceStream:
        return _ConstantStream(self.velocity(rows))


class _DrydenStream:
    def __init__(self, model: DrydenTurbulence, rows: int, dt: float, rng: np.random.Generator):
        self.rows = rows
        self._rng = rng
        self._a = math.exp(-model.airspeed * dt / model.scale_length)
        self._sigma_c = model.component_sigma
        self._b = self._sigma_c * math.sqrt(max(0.0, 1.0 - self._a * self._a))
        self._limit = model.saturation
        # stationary start: each component ~ N(0, sigma_c^2)
        self._g = self._sigma_c * rng.standard_normal((rows, 2))
        self._first = True

    def next(self) -> np.ndarray:
        if self._first:
            self._first = False
        else:
            self._g *= self._a
            self._g += self._b * self._rng.standard_normal((self.rows, 2))
        if self._limit is None:
            return self._g.copy()
        return saturate(self._g, self._limit)


def _generator(rng: object) -> np.random.Generator:
    if isinstance(rng, np.random.Generator):
        return rng
    if isinstance(rng, np.random.SeedSequence) or (
        isinstance(rng, (int, np.integer)) and not isinstance(rng, bool) and rng >= 0
    ):
        return np.random.default_rng(rng)
    raise InvalidParameterError(
        "rng", rng, "must be a numpy.random.Generator or a seed (int >= 0, SeedSequence)"
    )


@dataclass(frozen=True)
class DrydenTurbulence:
    """Horizontal Dryden gusts (see module docstring).

    sigma: RMS of the gust magnitude (m/s), before saturation; scale_length: L (m), default
    263 m (MIL-F-8785C low altitude at h = 100 m, REFERENCE_NOTES §2.2); airspeed: V (m/s);
    saturation: bound on |delta| (m/s), None for none; per_component: sigma is the RMS of each
    component instead of the magnitude; gust_scale: sensitivity factor f > 0 on the RMS (the
    gusts have RMS f sigma; the saturation is unchanged), 1 for the model as stated.
    """

    sigma: float
    scale_length: float = 263.0
    airspeed: float = 20.0
    saturation: float | None = None
    per_component: bool = False
    gust_scale: float = 1.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "sigma", check_nonnegative("sigma", self.sigma))
        object.__setattr__(self, "scale_length", check_positive("scale_length", self.scale_length))
        object.__setattr__(self, "airspeed", check_positive("airspeed", self.airspeed))
        object.__setattr__(self, "gust_scale", check_positive("gust_scale", self.gust_scale))
        if self.saturation is not None:
            object.__setattr__(self, "saturation", check_nonnegative("saturation", self.saturation))

    @property
    def component_sigma(self) -> float:
        """RMS of each inertial component (m/s), the gust scale included."""
        rms = self.gust_scale * self.sigma
        return rms if self.per_component else rms / math.sqrt(2.0)

    @property
    def correlation_time(self) -> float:
        """L / V (s): the components' autocorrelation is sigma_c^2 exp(-tau V / L)."""
        return self.scale_length / self.airspeed

    def autocorrelation(self, lag: ArrayLike) -> np.ndarray:
        """Model autocorrelation of each component (before saturation) at time lags (s)."""
        tau = np.abs(np.asarray(lag, dtype=float))
        return self.component_sigma**2 * np.exp(-tau / self.correlation_time)

    def stream(
        self, rows: int, dt: float, rng: np.random.Generator | int | np.random.SeedSequence
    ) -> DisturbanceStream:
        """Start a realisation for `rows` rows with time step dt (s), drawn from `rng` (a
        Generator, or a seed: an int >= 0 or a SeedSequence)."""
        check_positive("dt", dt)
        return _DrydenStream(self, int(rows), float(dt), _generator(rng))

    def sample(
        self, steps: int, rows: int, dt: float, rng: np.random.Generator | int
    ) -> np.ndarray:
        """A realisation as an array (steps, rows, 2) in m/s (for analysis and tests)."""
        s = self.stream(rows, dt, rng)
        return np.stack([s.next() for _ in range(int(steps))])


@runtime_checkable
class PositionalStream(Protocol):
    """A disturbance evaluated at each vehicle's position and time (a current or wind field)."""

    @property
    def rows(self) -> int:
        """Number of vehicles (rows) of the realisation."""
        ...

    def at(self, t: float, x: np.ndarray, y: np.ndarray, rows: np.ndarray) -> np.ndarray:
        """Disturbance velocity (n, 2) in m/s over the step starting at time t (s) for vehicles
        at (x, y) (n,) in m, which use realisation rows `rows` (n,); NaN where undefined."""
        ...


#: velocity(t, x, y) -> (u, v): the disturbance (m/s, local axes) at time t (s) and local
#: positions x, y (m), arrays of one shape; NaN where it is undefined.
VelocityFunction = Callable[[float, np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]


@dataclass(frozen=True, eq=False)
class _FieldStream:
    model: FieldDisturbance
    rows: int

    def at(self, t: float, x: np.ndarray, y: np.ndarray, rows: np.ndarray) -> np.ndarray:
        u, v = self.model.velocity(self.model.t0 + t, x, y)
        out = np.empty((np.shape(x)[0], 2))
        out[:, 0], out[:, 1] = u, v
        return out


@dataclass(frozen=True, eq=False)
class FieldDisturbance:
    """A disturbance that varies in space and time: delta = velocity(t0 + t, x, y) (m/s) at
    each vehicle's position (m, the simulator's plane) and the simulation time t (s) plus the
    offset t0 (s, e.g. the departure time in the field's clock). The same field for every row."""

    velocity: VelocityFunction
    t0: float = 0.0

    def __post_init__(self) -> None:
        if not callable(self.velocity):
            raise InvalidParameterError("velocity", self.velocity, "must be callable")
        if not math.isfinite(self.t0):
            raise InvalidParameterError("t0", self.t0, "must be finite (s)")

    def stream(
        self, rows: int, dt: float, rng: np.random.Generator | None = None
    ) -> PositionalStream:
        """A stream for `rows` vehicles (deterministic: dt and rng are not used)."""
        return _FieldStream(self, int(rows))
