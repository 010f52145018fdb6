"""Initial guesses for the engine: Dubins paths flown at chosen speeds (section 2.7)."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence

from glideplan.path import Path
from glideplan.planners.dubins import WORDS, dubins_path
from glideplan.pose import Pose
from glideplan.segments import Arc, Segment, Straight
from glideplan.validation import check_positive

__all__ = ["dubins_guesses", "respeed"]


def respeed(path: Path, arc_speed: float, straight_speed: float) -> Path:
    """The same geometry with arcs flown at `arc_speed` and straights at `straight_speed`.

    Zero-length pieces are dropped (a path keeps at least one segment).
    """
    segs: list[Segment] = []
    for seg in path.segments:
        if seg.length <= 0.0:
            continue
        if isinstance(seg, Arc):
            segs.append(Arc(seg.start, seg.angle, seg.radius, seg.direction, arc_speed, seg.label))
        elif isinstance(seg, Straight):
            segs.append(Straight(seg.start, seg.length_m, straight_speed, seg.label))
        else:
            segs.append(seg)
    return Path(tuple(segs) or path.segments[:1])


def dubins_guesses(
    goal: Pose,
    radii: Iterable[float],
    *,
    arc_speed: float | Callable[[float], float] = 1.0,
    straight_speed: float = 1.0,
    words: Sequence[str] = WORDS,
) -> list[Path]:
    """Dubins paths from the origin to `goal` for each radius and feasible word.

    Arcs are flown at `arc_speed` (a number, or a function of the radius) and straights at
    `straight_speed`; the order (radius-major, then `words`) is deterministic.
    """
    out: list[Path] = []
    for radius in radii:
        r = check_positive("radius", radius)
        va = check_positive("arc_speed", arc_speed(r) if callable(arc_speed) else arc_speed)
        vs = check_positive("straight_speed", straight_speed)
        for word in words:
            path = dubins_path(Pose(), goal, r, 1.0, word=word)
            if path is not None and path.length > 0.0:
                out.append(respeed(path, va, vs))
    return out
