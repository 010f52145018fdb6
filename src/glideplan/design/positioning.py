"""Static acoustic long-baseline (LBL) position fixes and a survey simulation (sec 7.6, Fig 7.27).

The receiver depth is known from its pressure sensor, so slant ranges are reduced to
horizontal ranges rho_i = sqrt(r_i^2 - (z - z_i)^2) and the fix is solved in the plane from
three or more non-collinear beacons:

- algebraic (linearised): subtracting beacon 1's circle from the others gives
  2 (b_1 - b_i)^T p = rho_i^2 - rho_1^2 - |b_i|^2 + |b_1|^2, solved by least squares;
- least squares: min_p sum_i (|p - b_i| - rho_i)^2 by Gauss-Newton from the algebraic fix.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from glideplan.errors import InvalidParameterError
from glideplan.validation import check_fields, check_nonnegative, check_positive, scalar_or_array
from glideplan.validation import check_finite_array as finite_array
from glideplan.validation import check_probability as probability

__all__ = [
    "ErrorStatistics",
    "LBLConfig",
    "SurveyResult",
    "check_beacon_geometry",
    "dilution_of_precision",
    "error_statistics",
    "fix_algebraic",
    "fix_least_squares",
    "fix_position",
    "horizontal_ranges_m",
    "lawnmower_track",
    "simulate_survey",
]

_METHODS = ("least_squares", "algebraic")
_COLLINEAR_RTOL = 1e-6


def _beacons(beacons_m: ArrayLike) -> np.ndarray:
    b = finite_array("beacons_m", beacons_m)
    if b.ndim != 2 or b.shape[1] != 2:
        raise InvalidParameterError("beacons_m", b.shape, "must have shape (m, 2): x, y in metres")
    return b


def _is_collinear(b: np.ndarray) -> bool:
    s = np.linalg.svd(b - b.mean(axis=0), compute_uv=False)
    return bool(s[-1] <= _COLLINEAR_RTOL * max(s[0], 1e-300))


def check_beacon_geometry(beacons_m: ArrayLike) -> np.ndarray:
    """Return the beacons as an (m, 2) array; raise unless m >= 3 and they are not collinear.

    With collinear beacons a planar fix is ambiguous (its mirror image about the line fits
    equally well), so it is an error rather than a silently wrong answer.
    """
    b = _beacons(beacons_m)
    if b.shape[0] < 3:
        raise InvalidParameterError("beacons_m", b.shape[0], "need at least 3 beacons for a fix")
    if _is_collinear(b):
        raise InvalidParameterError(
            "beacons_m",
            b.tolist(),
            "beacons are collinear: the fix is ambiguous (mirror image about their line)",
        )
    return b


def horizontal_ranges_m(
    slant_ranges_m: ArrayLike, receiver_depth_m: ArrayLike, beacon_depth_m: ArrayLike
) -> np.ndarray | float:
    """Horizontal ranges sqrt(r^2 - (z - z_b)^2) (m); ranges shorter than the depth gap give 0.

    NaN slant ranges (dropped pings) stay NaN.
    """
    r = np.asarray(slant_ranges_m, dtype=float)
    if np.any(r[np.isfinite(r)] < 0.0) or np.any(np.isinf(r)):
        raise InvalidParameterError("slant_ranges_m", "array", "must be >= 0, finite or NaN")
    dz = finite_array("receiver_depth_m", receiver_depth_m) - finite_array(
        "beacon_depth_m", beacon_depth_m
    )
    with np.errstate(invalid="ignore"):
        return scalar_or_array(np.sqrt(np.maximum(r**2 - dz**2, 0.0)))


def _ranges(ranges_m: ArrayLike, m: int) -> np.ndarray:
    r = finite_array("ranges_m", ranges_m)
    if r.ndim == 0 or r.shape[-1] != m:
        raise InvalidParameterError("ranges_m", r.shape, f"last axis must match {m} beacons")
    if np.any(r < 0.0):
        raise InvalidParameterError("ranges_m", float(np.min(r)), "must be >= 0")
    return r


def fix_algebraic(beacons_m: ArrayLike, ranges_m: ArrayLike) -> np.ndarray:
    """Linearised LBL fix (..., 2) from horizontal ranges (..., m) to m >= 3 beacons (sec 7.6)."""
    b = check_beacon_geometry(beacons_m)
    r = _ranges(ranges_m, b.shape[0])
    return _algebraic(b, r)


def _algebraic(b: np.ndarray, r: np.ndarray) -> np.ndarray:
    # Work relative to the beacon centroid so the normal equations are well scaled.
    c = b.mean(axis=0)
    bc = b - c
    a = 2.0 * (bc[0] - bc[1:])  # (m-1, 2)
    sq = np.sum(bc**2, axis=1)
    d = r[..., 1:] ** 2 - r[..., :1] ** 2 - sq[1:] + sq[0]  # (..., m-1)
    return d @ np.linalg.pinv(a).T + c


def fix_least_squares(
    beacons_m: ArrayLike,
    ranges_m: ArrayLike,
    initial_m: ArrayLike | None = None,
    *,
    iterations: int = 50,
) -> np.ndarray:
    """Nonlinear least-squares LBL fix min sum (|p - b_i| - rho_i)^2 (Gauss-Newton), shape (..., 2).

    Starts from `initial_m` or the algebraic fix; vectorised over leading axes of `ranges_m`.
    """
    b = check_beacon_geometry(beacons_m)
    r = _ranges(ranges_m, b.shape[0])
    p0 = _algebraic(b, r) if initial_m is None else finite_array("initial_m", initial_m)
    return _gauss_newton(b, r, np.broadcast_to(p0, (*r.shape[:-1], 2)), int(iterations))


def _gauss_newton(b: np.ndarray, r: np.ndarray, p0: np.ndarray, iterations: int) -> np.ndarray:
    p = np.array(p0, dtype=float)
    scale = float(np.max(np.ptp(b, axis=0))) + 1.0
    for _ in range(iterations):
        diff = p[..., None, :] - b  # (..., m, 2)
        dist = np.maximum(np.linalg.norm(diff, axis=-1), 1e-12 * scale)
        jac = diff / dist[..., None]
        res = dist - r
        jtj = np.einsum("...mi,...mj->...ij", jac, jac)
        jtj = jtj + 1e-12 * np.eye(2)  # tiny damping: finite step at degenerate points
        jtr = np.einsum("...mi,...m->...i", jac, res)
        step = np.linalg.solve(jtj, jtr[..., None])[..., 0]
        p = p - step
        if np.max(np.abs(step), initial=0.0) < 1e-12 * scale:
            break
    return p


def fix_position(
    beacons_m: ArrayLike, ranges_m: ArrayLike, method: str = "least_squares"
) -> np.ndarray:
    """LBL fixes (..., 2) from ranges (..., m) where NaN marks a dropped ping.

    Each fix uses the beacons that answered; it is NaN where fewer than 3 answered or the
    answering beacons are collinear. `method` is "least_squares" or "algebraic".
    """
    if method not in _METHODS:
        raise InvalidParameterError("method", method, f"must be one of {_METHODS}")
    b = _beacons(beacons_m)
    if b.shape[0] < 3:
        raise InvalidParameterError("beacons_m", b.shape[0], "need at least 3 beacons for a fix")
    r = np.asarray(ranges_m, dtype=float)
    if r.ndim == 0 or r.shape[-1] != b.shape[0]:
        raise InvalidParameterError(
            "ranges_m", r.shape, f"last axis must match {b.shape[0]} beacons"
        )
    if np.any(np.isinf(r)) or np.any(r[np.isfinite(r)] < 0.0):
        raise InvalidParameterError("ranges_m", "array", "must be >= 0, finite or NaN")
    flat = r.reshape(-1, b.shape[0])
    out = np.full((flat.shape[0], 2), np.nan)
    answered = np.isfinite(flat)
    # One vectorised solve per pattern of answering beacons (at most 2^m patterns).
    patterns, inverse = np.unique(answered, axis=0, return_inverse=True)
    for k, mask in enumerate(patterns):
        if mask.sum() < 3 or _is_collinear(b[mask]):
            continue
        rows = np.flatnonzero(inverse.ravel() == k)
        sub = flat[np.ix_(rows, np.flatnonzero(mask))]
        est = _algebraic(b[mask], sub)
        if method == "least_squares":
            est = _gauss_newton(b[mask], sub, est, 50)
        out[rows] = est
    return out.reshape((*r.shape[:-1], 2))


def dilution_of_precision(beacons_m: ArrayLike, position_m: ArrayLike) -> np.ndarray | float:
    """Horizontal dilution of precision sqrt(trace((J^T J)^-1)) at `position_m` (..., 2).

    Position error RMS is about HDOP times the range noise standard deviation.
    """
    b = check_beacon_geometry(beacons_m)
    p = finite_array("position_m", position_m)
    diff = p[..., None, :] - b
    jac = diff / np.maximum(np.linalg.norm(diff, axis=-1), 1e-12)[..., None]
    jtj = np.einsum("...mi,...mj->...ij", jac, jac)
    return scalar_or_array(np.sqrt(np.trace(np.linalg.inv(jtj), axis1=-2, axis2=-1)))


@dataclass(frozen=True)
class LBLConfig:
    """LBL network and ping model: beacon positions (m), depths, range noise and ping success."""

    beacons_m: tuple[tuple[float, float], ...] = ((400.0, 600.0), (800.0, 620.0), (600.0, 880.0))
    beacon_depth_m: float = 4.572  # transducers at 15 ft (section 7.7)
    receiver_depth_m: float = 1.524  # glider transducer at 5 ft
    range_noise_std_m: float = 6.0
    ping_success_probability: float = 0.75
    sound_speed_assumed_m_s: float = 1480.0
    sound_speed_true_m_s: float = 1480.0
    method: str = "least_squares"

    def __post_init__(self) -> None:
        b = check_beacon_geometry(self.beacons_m)
        object.__setattr__(self, "beacons_m", tuple((float(x), float(y)) for x, y in b))
        check_fields(
            self, check_nonnegative, ("beacon_depth_m", "receiver_depth_m", "range_noise_std_m")
        )
        check_fields(self, check_positive, ("sound_speed_assumed_m_s", "sound_speed_true_m_s"))
        object.__setattr__(
            self,
            "ping_success_probability",
            probability("ping_success_probability", self.ping_success_probability),
        )
        if self.method not in _METHODS:
            raise InvalidParameterError("method", self.method, f"must be one of {_METHODS}")


@dataclass(frozen=True)
class ErrorStatistics:
    """Summary of a survey: ping success, fix availability and horizontal position error (m)."""

    pings: int
    ping_success_fraction: float
    epochs: int
    fixes: int
    fix_fraction: float
    mean_error_m: float
    median_error_m: float
    rms_error_m: float
    p95_error_m: float
    max_error_m: float

    def to_dict(self) -> dict[str, float | int]:
        """Plain dict for JSON output."""
        return dict(self.__dict__)


@dataclass(frozen=True)
class SurveyResult:
    """Simulated survey: true track, measured horizontal ranges (NaN = no reply), fixes, errors."""

    track_m: np.ndarray
    ranges_m: np.ndarray
    answered: np.ndarray
    estimates_m: np.ndarray
    errors_m: np.ndarray
    statistics: ErrorStatistics


def lawnmower_track(
    x_range_m: tuple[float, float],
    y_range_m: tuple[float, float],
    swaths: int,
    step_m: float,
) -> np.ndarray:
    """North-south lawn-mower track (n, 2) over a rectangle, points every `step_m` (Fig 7.26)."""
    x0, x1 = (float(v) for v in finite_array("x_range_m", x_range_m))
    y0, y1 = (float(v) for v in finite_array("y_range_m", y_range_m))
    if not (x1 > x0 and y1 > y0):
        raise InvalidParameterError("x_range_m", (x0, x1, y0, y1), "ranges must be increasing")
    if int(swaths) < 1:
        raise InvalidParameterError("swaths", swaths, "must be >= 1")
    step = check_positive("step_m", step_m)
    xs = np.linspace(x0, x1, int(swaths))
    n_leg = max(int(np.ceil((y1 - y0) / step)), 1) + 1
    ys = np.linspace(y0, y1, n_leg)
    legs = [
        np.column_stack([np.full(n_leg, x), ys if i % 2 == 0 else ys[::-1]])
        for i, x in enumerate(xs)
    ]
    return np.concatenate(legs)


def error_statistics(answered: ArrayLike, errors_m: ArrayLike) -> ErrorStatistics:
    """Ping success fraction, fix fraction and error mean/median/RMS/95th percentile/max (m)."""
    ans = np.asarray(answered, dtype=bool)
    err = np.asarray(errors_m, dtype=float)
    ok = err[np.isfinite(err)]
    nan = float("nan")
    return ErrorStatistics(
        pings=int(ans.size),
        ping_success_fraction=float(ans.mean()) if ans.size else nan,
        epochs=int(err.size),
        fixes=int(ok.size),
        fix_fraction=float(ok.size / err.size) if err.size else nan,
        mean_error_m=float(ok.mean()) if ok.size else nan,
        median_error_m=float(np.median(ok)) if ok.size else nan,
        rms_error_m=float(np.sqrt(np.mean(ok**2))) if ok.size else nan,
        p95_error_m=float(np.percentile(ok, 95)) if ok.size else nan,
        max_error_m=float(ok.max()) if ok.size else nan,
    )


def simulate_survey(
    config: LBLConfig, track_m: ArrayLike, rng: np.random.Generator | int
) -> SurveyResult:
    """Ping every beacon from each track point, drop replies at random, add range noise, fix.

    Measured slant range = true range x (assumed / true sound speed) + N(0, sigma^2); each
    reply arrives with probability `ping_success_probability`. `rng` is a NumPy Generator or
    an integer seed (no global random state).
    """
    gen = rng if isinstance(rng, np.random.Generator) else np.random.default_rng(int(rng))
    track = finite_array("track_m", track_m)
    if track.ndim != 2 or track.shape[1] != 2:
        raise InvalidParameterError("track_m", track.shape, "must have shape (n, 2)")
    b = np.asarray(config.beacons_m)
    dz = config.receiver_depth_m - config.beacon_depth_m
    slant = np.sqrt(np.sum((track[:, None, :] - b) ** 2, axis=-1) + dz**2)
    bias = config.sound_speed_assumed_m_s / config.sound_speed_true_m_s
    measured = slant * bias + gen.normal(0.0, config.range_noise_std_m, slant.shape)
    measured = np.abs(measured)  # a travel time is never negative
    answered = gen.random(slant.shape) < config.ping_success_probability
    measured = np.where(answered, measured, np.nan)
    ranges = np.asarray(
        horizontal_ranges_m(measured, config.receiver_depth_m, config.beacon_depth_m)
    )
    est = fix_position(b, ranges, config.method)
    err = np.linalg.norm(est - track, axis=-1)
    return SurveyResult(track, ranges, answered, est, err, error_statistics(answered, err))
