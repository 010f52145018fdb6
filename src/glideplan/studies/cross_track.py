"""The Monte Carlo study of Fig 3.4: final cross-track error versus planning radius.

Dissertation §3.4; REFERENCE_NOTES §1.1. For each disturbance bound eps and planning radius
R_plan (in units of R0 = v / u_max), Dubins paths are planned with R_plan from the origin to
random goals (uniform in a square of side 8 R0 centred on the start, final heading drawn from
{0, 2 pi/3, pi}) and flown in closed loop (`glideplan.simulation`) under

- the steady case: a constant wind of magnitude eps v towards a uniformly random direction;
- the unsteady case: Dryden gusts with RMS magnitude eps v, saturated at eps v (times the
  sensitivity factor `gust_scale` f on the RMS, default 1: the literal reading).

The planner knows nothing of the disturbance. Each (case, eps, R_plan) point is the mean final
cross-track error / R0 over its samples; runs that never cross the finish line are failures,
counted separately.

Work units are (case, eps, chunk of samples) with every R_plan: one vectorised simulation of
chunk x len(r_plan) vehicles; the R_plan values of one sample share its goal and disturbance
realisation (common random numbers, so the curves are smooth in R_plan). A unit's random
numbers come from `SeedSequence(seed, spawn_key=(unit index,))`, so results do not depend on
execution order, interruptions or the backend. Results go to `DIR/samples.sqlite` as units
finish (`glideplan.studies.store`) and the summary to `DIR/summary.json`.
"""

from __future__ import annotations

import json
import math
import pathlib
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.simulation.closed_loop import FollowerSettings, follow_paths
from glideplan.simulation.disturbances import DrydenTurbulence, SteadyDisturbance
from glideplan.simulation.guidance import PathArrays
from glideplan.studies.runner import RunReport, run_units
from glideplan.studies.store import ResultsStore
from glideplan.validation import check_in_range, check_positive

__all__ = [
    "CASES",
    "MAX_DT_FRACTION",
    "CrossTrackConfig",
    "CrossTrackResult",
    "knee",
    "run_cross_track_study",
    "simulate_unit",
    "summarise",
]

CASES = ("steady", "unsteady")
DEFAULT_EPS = (0.25, 0.5, 0.75, 0.95)
DEFAULT_R_PLAN = tuple(round(1.0 + 0.1 * i, 10) for i in range(31))
DEFAULT_PSI1 = (0.0, 2.0 * math.pi / 3.0, math.pi)
# Largest simulation step as a fraction of 1/u_max, the time to turn one radian: the
# bang-bang turn-rate control must switch many times within a turn.
MAX_DT_FRACTION = 0.1
STORE_NAME = "samples.sqlite"
SUMMARY_NAME = "summary.json"
_COLUMNS = (
    ("unit", "INTEGER"),
    ("case_name", "TEXT"),
    ("eps", "REAL"),
    ("r_plan", "REAL"),
    ("sample", "INTEGER"),
    ("goal_x", "REAL"),
    ("goal_y", "REAL"),
    ("goal_heading", "REAL"),
    ("wind_direction", "REAL"),
    ("error", "REAL"),
    ("crossed", "INTEGER"),
    ("time", "REAL"),
)
_KEY = ("case_name", "eps", "r_plan", "sample")


def _floats(name: str, values: Sequence[float]) -> tuple[float, ...]:
    try:
        out = tuple(float(v) for v in values)
    except (TypeError, ValueError):
        raise InvalidParameterError(name, values, "must be a list of numbers") from None
    if not out:
        raise InvalidParameterError(name, values, "needs at least one value")
    if len(set(out)) != len(out):
        raise InvalidParameterError(name, values, "must not repeat a value")
    return out


def _setting(name: str, value: Any) -> Any:
    if name == "feedforward" or isinstance(value, bool):
        return bool(value)
    if value is None:
        return None
    try:
        return float(value)
    except (TypeError, ValueError):
        raise InvalidParameterError(name, value, "must be a number") from None


@dataclass(frozen=True)
class CrossTrackConfig:
    """Every setting of the study (defaults: the dissertation's, §3.4).

    eps: disturbance bounds delta_max / v, each in [0, 1); r_plan: planning radii / R0, >= 1
    is the dissertation's range (> 0 allowed); samples: goals per point; cases: "steady",
    "unsteady" or both; seed: master seed; speed v (m/s) and max_turn_rate u_max (rad/s);
    square: side of the goal square / R0; psi1: final headings (rad); chunk: samples per
    work unit; dryden_scale_length: L (m); gust_scale: sensitivity factor f on the Dryden RMS
    (f eps v; saturation stays eps v; 1 = the dissertation's model as stated); follower:
    guidance and integration settings (their dt must be at most `MAX_DT_FRACTION / u_max`).
    """

    eps: tuple[float, ...] = DEFAULT_EPS
    r_plan: tuple[float, ...] = DEFAULT_R_PLAN
    samples: int = 900
    cases: tuple[str, ...] = CASES
    seed: int = 0
    speed: float = 20.0
    max_turn_rate: float = 0.3
    square: float = 8.0
    psi1: tuple[float, ...] = DEFAULT_PSI1
    chunk: int = 100
    dryden_scale_length: float = 263.0
    gust_scale: float = 1.0
    follower: dict[str, float] = field(default_factory=dict)

    def __post_init__(self) -> None:
        eps = _floats("eps", self.eps)
        for e in eps:
            check_in_range("eps", e, 0.0, 1.0, high_open=True)
        r_plan = _floats("r_plan", self.r_plan)
        for r in r_plan:
            check_positive("r_plan", r)
        cases = tuple(str(c) for c in self.cases)
        if not cases or any(c not in CASES for c in cases) or len(set(cases)) != len(cases):
            raise InvalidParameterError("case", self.cases, "must be steady, unsteady or both")
        for name in ("samples", "chunk"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
                raise InvalidParameterError(name, value, "must be an integer >= 1")
        if isinstance(self.seed, bool) or not isinstance(self.seed, (int, np.integer)):
            raise InvalidParameterError("seed", self.seed, "must be an integer >= 0")
        if self.seed < 0:
            raise InvalidParameterError("seed", self.seed, "must be an integer >= 0")
        object.__setattr__(self, "eps", eps)
        object.__setattr__(self, "r_plan", r_plan)
        object.__setattr__(self, "cases", cases)
        object.__setattr__(self, "samples", int(self.samples))
        object.__setattr__(self, "chunk", int(self.chunk))
        object.__setattr__(self, "seed", int(self.seed))
        object.__setattr__(self, "speed", check_positive("speed", self.speed))
        object.__setattr__(self, "max_turn_rate", check_positive("u_max", self.max_turn_rate))
        object.__setattr__(self, "square", check_positive("square", self.square))
        object.__setattr__(self, "psi1", _floats("psi1", self.psi1))
        object.__setattr__(
            self,
            "dryden_scale_length",
            check_positive("dryden_scale_length", self.dryden_scale_length),
        )
        object.__setattr__(self, "gust_scale", check_positive("gust_scale", self.gust_scale))
        follower = {k: _setting(k, v) for k, v in dict(self.follower).items()}
        settings = self.follower_settings_for(follower)  # validates the names and values
        dt_max = MAX_DT_FRACTION / self.max_turn_rate
        if settings.dt > dt_max:
            raise InvalidParameterError(
                "dt",
                settings.dt,
                f"must be <= {MAX_DT_FRACTION:g} / u_max = {dt_max:.3g} s, a tenth of the time "
                f"1/u_max = {1 / self.max_turn_rate:.3g} s to turn one radian",
            )
        object.__setattr__(self, "follower", follower)

    def follower_settings_for(self, follower: dict[str, Any] | None = None) -> FollowerSettings:
        extra: dict[str, Any] = dict(self.follower if follower is None else follower)
        try:
            return FollowerSettings(speed=self.speed, max_turn_rate=self.max_turn_rate, **extra)
        except TypeError:
            known = "lookahead, gamma, boundary_layer, dt, timeout_factor, feedforward"
            raise InvalidParameterError("follower", extra, f"known settings: {known}") from None

    @property
    def follower_settings(self) -> FollowerSettings:
        return self.follower_settings_for()

    @property
    def min_radius(self) -> float:
        """R0 = v / u_max (m)."""
        return self.speed / self.max_turn_rate

    def to_dict(self) -> dict[str, Any]:
        """The configuration as stored with the results (includes the seed)."""
        out = asdict(self)
        fs = asdict(self.follower_settings)
        out["follower"] = fs
        if out["gust_scale"] == 1.0:  # files written before the option existed still resume
            del out["gust_scale"]
        for k in ("eps", "r_plan", "cases", "psi1"):
            out[k] = list(out[k])
        return out

    def units(self) -> list[Unit]:
        """The work units, in their fixed order (the index seeds each unit)."""
        out: list[Unit] = []
        for case in self.cases:
            for eps in self.eps:
                for first in range(0, self.samples, self.chunk):
                    count = min(self.chunk, self.samples - first)
                    out.append(Unit(len(out), case, eps, first, count, self))
        return out

    @property
    def runs(self) -> int:
        """Closed-loop runs in the whole study."""
        return len(self.cases) * len(self.eps) * len(self.r_plan) * self.samples


@dataclass(frozen=True)
class Unit:
    """One work unit: `count` samples starting at `first` of one (case, eps), every R_plan."""

    index: int
    case: str
    eps: float
    first: int
    count: int
    config: CrossTrackConfig

    @property
    def runs(self) -> int:
        return self.count * len(self.config.r_plan)


def simulate_unit(unit: Unit) -> dict[str, np.ndarray]:
    """Run one work unit (module docstring); arrays over (r_plan, sample) flattened."""
    cfg = unit.config
    rng = np.random.default_rng(np.random.SeedSequence(cfg.seed, spawn_key=(unit.index,)))
    r0 = cfg.min_radius
    n = unit.count
    half = 0.5 * cfg.square
    xy = rng.uniform(-half, half, size=(n, 2))
    psi1 = np.asarray(cfg.psi1)[rng.integers(0, len(cfg.psi1), size=n)]
    wind_dir = rng.uniform(0.0, 2.0 * math.pi, size=n)
    goals = np.column_stack([xy * r0, psi1])
    r_plan = np.asarray(cfg.r_plan)
    nr = r_plan.size
    paths = PathArrays.dubins(np.tile(goals, (nr, 1)), np.repeat(r_plan * r0, n))
    rows = np.tile(np.arange(n), nr)
    settings = cfg.follower_settings
    bound = unit.eps * cfg.speed
    if unit.case == "steady":
        towards = np.column_stack([bound * np.cos(wind_dir), bound * np.sin(wind_dir)])
        stream = SteadyDisturbance(towards).stream(n, settings.dt)
    else:
        model = DrydenTurbulence(
            sigma=bound,
            scale_length=cfg.dryden_scale_length,
            airspeed=cfg.speed,
            saturation=bound,
            gust_scale=cfg.gust_scale,
        )
        stream = model.stream(n, settings.dt, rng)
    res = follow_paths(paths, stream, rows=rows, settings=settings, disturbance_bound=bound)
    return {
        "r_plan": np.repeat(r_plan, n),
        "sample": np.tile(np.arange(unit.first, unit.first + n), nr),
        "goal": np.tile(np.column_stack([xy, psi1]), (nr, 1)),
        "wind_direction": np.tile(wind_dir if unit.case == "steady" else np.full(n, np.nan), nr),
        "error": res.error / r0,
        "crossed": res.crossed,
        "time": res.time,
    }


def _rows(units: list[Unit]):
    def rows_of(i: int, out: dict[str, np.ndarray]) -> list[tuple[Any, ...]]:
        u = units[i]
        err = [None if not math.isfinite(e) else float(e) for e in out["error"]]
        wd = [None if not math.isfinite(w) else float(w) for w in out["wind_direction"]]
        return [
            (
                i,
                u.case,
                u.eps,
                float(out["r_plan"][j]),
                int(out["sample"][j]),
                float(out["goal"][j, 0]),
                float(out["goal"][j, 1]),
                float(out["goal"][j, 2]),
                wd[j],
                err[j],
                int(out["crossed"][j]),
                float(out["time"][j]),
            )
            for j in range(out["error"].size)
        ]

    return rows_of


def summarise(store: ResultsStore) -> list[dict[str, Any]]:
    """One record per (case, eps, r_plan): samples, mean/std of the error / R0 over the runs
    that crossed the finish line, and failures (runs that never crossed)."""
    rows = store.query(
        "SELECT case_name, eps, r_plan, COUNT(*), SUM(1 - crossed), "
        "AVG(error), AVG(error * error) FROM results "
        "GROUP BY case_name, eps, r_plan ORDER BY case_name, eps, r_plan"
    )
    out = []
    for case, eps, r_plan, count, failures, mean, mean_sq in rows:
        crossed = count - failures
        if crossed > 1 and mean is not None:
            var = max(0.0, (mean_sq - mean * mean) * crossed / (crossed - 1))
            std = math.sqrt(var)
        else:
            std = None
        out.append(
            {
                "case": case,
                "eps": eps,
                "r_plan": r_plan,
                "samples": int(count),
                "mean_error": mean,
                "std_error": std,
                "failures": int(failures),
            }
        )
    return out


def knee(r_plan: Sequence[float], mean_error: Sequence[float], fraction: float = 0.1) -> float:
    """The knee of a decreasing error curve: the smallest R_plan whose mean error lies within
    `fraction` of the curve's total drop above its minimum (the start of the plateau)."""
    r = np.asarray(r_plan, dtype=float)
    e = np.asarray(mean_error, dtype=float)
    ok = np.isfinite(e)
    r, e = r[ok], e[ok]
    if r.size == 0:
        return math.nan
    order = np.argsort(r)
    r, e = r[order], e[order]
    lo, hi = float(e.min()), float(e.max())
    within = e <= lo + fraction * (hi - lo)
    return float(r[np.argmax(within)])


@dataclass(frozen=True)
class CrossTrackResult:
    """The summary records, the knee of each (case, eps) curve, where the files are, timing."""

    summary: list[dict[str, Any]]
    knees: dict[str, dict[float, float]]
    directory: pathlib.Path
    report: RunReport


def knees_of(summary: list[dict[str, Any]]) -> dict[str, dict[float, float]]:
    """Knee R_plan of each (case, eps) curve of a summary."""
    out: dict[str, dict[float, float]] = {}
    for case in sorted({s["case"] for s in summary}):
        out[case] = {}
        for eps in sorted({s["eps"] for s in summary if s["case"] == case}):
            pts = [s for s in summary if s["case"] == case and s["eps"] == eps]
            out[case][eps] = knee(
                [p["r_plan"] for p in pts],
                [math.nan if p["mean_error"] is None else p["mean_error"] for p in pts],
            )
    return out


def run_cross_track_study(
    out_dir: str | pathlib.Path,
    config: CrossTrackConfig | None = None,
    *,
    scheduler: str | None = None,
    processes: int | None = None,
    progress: bool = True,
    wave: int | None = None,
) -> CrossTrackResult:
    """Run (or resume) the study into `out_dir` and write `summary.json` (module docstring).

    Units already in `out_dir/samples.sqlite` are not run again; a results file written with
    another configuration raises `ResultsFileError`.
    """
    cfg = config or CrossTrackConfig()
    directory = pathlib.Path(out_dir)
    if directory.exists() and not directory.is_dir():
        raise InvalidParameterError("out", str(directory), "must be a directory")
    directory.mkdir(parents=True, exist_ok=True)
    units = cfg.units()
    with ResultsStore(
        directory / STORE_NAME, cfg.to_dict(), kind="cross-track", columns=_COLUMNS, key=_KEY
    ) as store:
        report = run_units(
            simulate_unit,
            units,
            store,
            _rows(units),
            weight=lambda u: float(u.runs),
            scheduler=scheduler,
            processes=processes,
            progress=progress,
            wave=wave,
            label="cross-track study",
        )
        summary = summarise(store)
    (directory / SUMMARY_NAME).write_text(json.dumps(summary, indent=2) + "\n")
    return CrossTrackResult(summary, knees_of(summary), directory, report)
