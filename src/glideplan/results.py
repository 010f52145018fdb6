"""The outcome contract every product shares: `Outcome` (status, ok, message, to_dict, plot).

Every result a command can print (`Solution`, routes, missions, final glides, glide reach,
turn-back points) is a frozen dataclass built by keyword that satisfies `Outcome`:

- `status: Status` -- one vocabulary (`glideplan.solution.Status`); JSON carries its value;
- `ok: bool` -- `status is Status.SOLVED`;
- `message: str` -- one line saying what happened and, when not ok, why;
- `warnings: tuple[str, ...]` -- what a user must see even when ok;
- `to_dict() -> dict` -- exactly the JSON object of the command's `--json`;
- `plot(ax=None, **kw)` -- a Matplotlib figure of the result (imports Matplotlib lazily).

Tracks are one type, `glideplan.track.Track`.
"""

from __future__ import annotations

from typing import Any, Protocol, runtime_checkable

from glideplan.solution import Status

__all__ = ["Outcome", "OutcomeBase", "Status"]


@runtime_checkable
class Outcome(Protocol):
    """What every result object offers (module docstring)."""

    status: Status
    message: str

    @property
    def ok(self) -> bool: ...

    def to_dict(self) -> dict[str, Any]: ...

    def plot(self, ax: Any = None, **kwargs: Any) -> Any: ...


class OutcomeBase:
    """Mixin of the result dataclasses: `status` given as a `Status` or its value is stored as
    the `Status` (an unknown word raises ValueError), and `ok` is `status is Status.SOLVED`."""

    status: Status

    def __post_init__(self) -> None:
        object.__setattr__(self, "status", Status(self.status))

    @property
    def ok(self) -> bool:
        return self.status is Status.SOLVED
