"""`Status`: the one outcome vocabulary, each member with its sentence and exit code.

A leaf module (imports nothing of glideplan) so that `glideplan.solution` and
`glideplan.results` both re-export it.
"""

from __future__ import annotations

from enum import StrEnum

__all__ = ["Status"]


class Status(StrEnum):
    """Outcome of a planning request, of one candidate, or of one numerical solve.

    The one status vocabulary of the library (a `StrEnum`: members compare equal to their
    strings, which is what `--json` prints). Each member carries its `sentence` (what it means,
    the default `message` of an `Outcome`) and its `exit_code` (the CLI's exit status: 0 solved
    and the candidate-only FEASIBLE/LOCAL, 1 every other outcome; 2 is bad input and 3 an
    internal error, neither of which is a status).

    A `Solution` is SOLVED, NO_PATH, NOT_VERIFIED or SOLVER_FAILED; a `Candidate` is FEASIBLE,
    INFEASIBLE, LOCAL or FAILED; a direct solve (`glideplan.planners.direct.DirectResult`) is
    SOLVED or FAILED. The products above `plan()` (`glideplan.results`) use the same members:
    a route is SOLVED, UNREACHABLE or NOT_VERIFIED; following a flyable path SOLVED, LOST or
    INFEASIBLE (no feasible radius); a trochoid chain SOLVED or INFEASIBLE; a mission SOLVED or
    the status of its first leg that is not (NO_PATH, NOT_VERIFIED, SOLVER_FAILED,
    UNREACHABLE); a final glide SOLVED (arrives at or above the safety height), BELOW_GLIDE or
    UNREACHABLE. Why an outcome is not SOLVED is its `reason` (`glideplan.results.Reason`).
    """

    _sentence: str
    _exit_code: int

    def __new__(cls, value: str, sentence: str = "", exit_code: int = 1) -> Status:
        obj = str.__new__(cls, value)
        obj._value_ = value
        obj._sentence = sentence
        obj._exit_code = exit_code
        return obj

    @property
    def sentence(self) -> str:
        """What the status means, in one sentence (the default message of an outcome)."""
        return self._sentence

    @property
    def exit_code(self) -> int:
        """The CLI's exit status for this outcome: 0 solved, 1 any other outcome."""
        return self._exit_code

    SOLVED = "solved", "a path was found and verified by integration", 0
    NO_PATH = "no_path", "no candidate path satisfies the boundary conditions", 1
    NOT_VERIFIED = "not_verified", (
        "a path was found but integrating the vehicle's motion along its controls does not "
        "reach the goal"), 1
    SOLVER_FAILED = "solver_failed", "the numerical solver did not converge", 1
    FEASIBLE = "feasible", "a candidate path that reaches the goal", 0
    INFEASIBLE = "infeasible", "no path of this kind exists for this problem", 1
    LOCAL = "local", "a converged start of a multi-start solve that is not the best", 0
    FAILED = "failed", "one numerical solve did not converge", 1
    # Products above plan() (routes, missions, glides, reach; see glideplan.results):
    UNREACHABLE = "unreachable", "the goal is out of reach", 1
    LOST = "lost", "the closed-loop follower did not reach the goal", 1
    BELOW_GLIDE = "below_glide", (
        "the glide reaches the goal but arrives below the safety height"), 1
