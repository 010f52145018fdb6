"""The outcome contract every product shares: `Outcome` (status, ok, message, reason, to_dict,
plot), `Status` (`glideplan.solution`) and `Reason`.

Every result a command can print (`Solution`, routes, missions, final glides, glide reach,
turn-back points, following, replays, ensembles, direct solves) is a frozen, keyword-only
dataclass that subclasses `Outcome`:

- `status: Status` -- one vocabulary; a status's string is converted once, here; each member
  carries its sentence and its exit code (`Status.sentence`, `Status.exit_code`);
- `ok: bool` -- `status is Status.SOLVED` (defined here only);
- `message: str` -- one line saying what happened and, when not ok, why ("" is filled from the
  status's sentence and the reason's);
- `warnings: tuple[str, ...]` -- what a user must see even when ok;
- `reason: Reason | None` -- why the outcome is what it is (one enum for every product: the
  route's stop, the follower's loss, the turn-back's limit, a solver's failure, ...);
- `to_dict() -> dict` -- exactly the JSON object of the command's `--json` (the base keys
  status, ok, message, warnings, reason; subclasses add theirs: `{**super().to_dict(), ...}`);
- `plot(ax=None, **kw)` -- a Matplotlib `Figure` of the result (imports Matplotlib lazily).

An ordinary failure is a status, never an exception; bad input raises
`glideplan.errors.InvalidParameterError` (CLI exit 2). The CLI prints every outcome through
`glideplan.cli.emit.emit`. Tracks are one type, `glideplan.track.Track`.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from enum import StrEnum
from typing import TYPE_CHECKING, Any

from glideplan.status import Status

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["BAD_INPUT", "Outcome", "Reason", "Status", "as_figure", "no_outcome_dict"]


class Reason(StrEnum):
    """Why an outcome is what it is (mostly: why it is not SOLVED); each member carries its
    `sentence`. The union of the products' former side vocabularies (route
    `unreachable_reason`, replay reasons, the follower's losses, turn-back limits, solver
    failures, final-glide headwinds)."""

    _sentence: str

    def __new__(cls, value: str, sentence: str = "") -> Reason:
        obj = str.__new__(cls, value)
        obj._value_ = value
        obj._sentence = sentence
        return obj

    @property
    def sentence(self) -> str:
        """What the reason means, in one sentence."""
        return self._sentence

    # routes (glideplan.routing) and replays (glideplan.routing.replay)
    FRONT_STOPPED = "front_stopped", "the reachable set stopped growing before the goal"
    FIELD_EXTENT = "field_extent", "the reachable set reached the field's edge without the goal"
    TIME_SPAN = "time_span", "the field's last time came before the goal was reached"
    MAX_DURATION = "max_duration", "the longest allowed duration came before the goal"
    WINDOW_LIMIT = "window_limit", "the search window would exceed the node budget"
    OUTSIDE_DRIFT_CONE = "outside_drift_cone", (
        "the goal lies outside the set the current and the vehicle's speed can reach at all")
    POLAR_LIMIT = "polar_limit", "the way passes beyond the router's +-85 deg latitude limit"
    MISSING_DATA = "missing_data", "the field has no data (all NaN) at a time the front needs"
    AGROUND = "aground", "the vehicle ran aground (the current is undefined there: land)"
    # following a flyable path (glideplan.routing.glider)
    LAND = "land", "the vehicle reached land"
    LEFT_FIELD = "left_field", "the vehicle left the field"
    TIMEOUT = "timeout", "the follower ran out of time before the goal"
    NO_FEASIBLE_RADIUS = "no_feasible_radius", (
        "no turn radius is feasible: the disturbance is as fast as the vehicle")
    # solvers (plan(), direct transcriptions)
    SOLVER = "solver", "the numerical solver (IPOPT) did not converge"
    # glides (final glide, reach, turn-back)
    HEADWIND = "headwind", "no airspeed makes progress against the wind"
    BELOW_SAFETY_HEIGHT = "below_safety_height", (
        "the glide arrives below the goal's elevation plus the safety height")
    HOME_OUT_OF_REACH = "home_out_of_reach", "home is out of reach already at the start"
    GLIDE_HOME = "glide_home", "the straight glide home limits how far out one can fly"
    OUTBOUND_TERRAIN = "outbound_terrain", "the outbound glide meets terrain + clearance first"
    TERRAIN_EDGE = "terrain_edge", "the outbound glide reaches the terrain's edge"
    TERRAIN_ON_THE_WAY_HOME = "terrain_on_the_way_home", "terrain on the way home limits it"
    SEARCH_BUDGET = "search_budget", "the search stopped at its step budget"
    # missions
    LEG_FAILED = "leg_failed", "a leg of the mission has no verified path"


@dataclass(frozen=True, kw_only=True, eq=False)
class Outcome:
    """The base of every public result (module docstring)."""

    status: Status
    message: str = ""
    warnings: tuple[str, ...] = ()
    reason: Reason | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "status", Status(self.status))
        if self.reason is not None:
            object.__setattr__(self, "reason", Reason(self.reason))
        object.__setattr__(self, "warnings", tuple(self.warnings))
        if not self.message:
            object.__setattr__(self, "message", default_message(self.status, self.reason))

    @property
    def ok(self) -> bool:
        """True when the status is SOLVED."""
        return self.status is Status.SOLVED

    def to_dict(self) -> dict[str, Any]:
        """The base keys of every `--json` object: status, ok, message, warnings, reason."""
        return {
            "status": self.status.value,
            "ok": self.ok,
            "message": self.message,
            "warnings": list(self.warnings),
            "reason": None if self.reason is None else self.reason.value,
        }

    def plot(self, ax: Any = None, **kwargs: Any) -> Figure:
        """A figure of the outcome; the base draws the status and message as text."""
        from glideplan.outcome_plot import plot_outcome_text

        return plot_outcome_text(self, ax=ax, **kwargs)


#: What the explorer shows for an input it refuses (the CLI's exit 2): not a `Status`.
BAD_INPUT = "bad input"


def no_outcome_dict(message: str, errors: Mapping[str, str] | None = None) -> dict[str, Any]:
    """The JSON when there is no outcome because the input was refused (the explorer's
    downloads): the base keys with status None (no `Status`: bad input is exit 2, not an
    outcome), the one-line message and the errors by input name."""
    out: dict[str, Any] = {"status": None, "ok": False, "message": message, "warnings": [],
                           "reason": None}
    if errors is not None:
        out["errors"] = dict(errors)
    return out


def default_message(status: Status, reason: Reason | None) -> str:
    """The status's sentence, and the reason's when there is one."""
    text = status.sentence
    if reason is not None and reason.sentence:
        text = f"{text}: {reason.sentence}" if text else reason.sentence
    return text


def as_figure(drawn: Any) -> Figure:
    """The Figure of what a drawing function returned (a Figure, an Axes, or axes)."""
    from matplotlib.figure import Figure

    if isinstance(drawn, Figure):
        return drawn
    if isinstance(drawn, (tuple, list)) or hasattr(drawn, "flat"):
        first = next(iter(getattr(drawn, "flat", drawn)))
        return as_figure(first)
    fig = drawn.figure
    while not isinstance(fig, Figure):  # a SubFigure: its parent
        fig = fig.figure
    return fig
