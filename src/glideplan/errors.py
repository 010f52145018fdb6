"""Exceptions raised by glideplan; all subclass built-ins so callers can catch broadly."""

from __future__ import annotations

from typing import Any

__all__ = ["InvalidParameterError", "PlanningError", "ResultsFileError"]


class InvalidParameterError(ValueError):
    """A parameter broke a rule; the message names the parameter, its value and the rule."""

    def __init__(self, name: str, value: Any, rule: str) -> None:
        self.name = name
        self.value = value
        self.rule = rule
        super().__init__(f"{name}={_short(value)}: {rule}")


class PlanningError(RuntimeError):
    """A planner could not return a verified path for a well-posed problem."""


class ResultsFileError(ValueError):
    """A results or parameter file is unreadable, corrupt or does not match the request."""


def _short(value: Any) -> str:
    """The value as the message shows it: text (often a file name) whole up to 240 characters,
    else with its middle elided so that both ends stay readable; other values up to 80."""
    text = repr(value)
    limit = 240 if isinstance(value, str) else 80
    if len(text) <= limit:
        return text
    if isinstance(value, str):
        half = (limit - 3) // 2
        return text[:half] + "..." + text[-half:]
    return text[: limit - 3] + "..."
