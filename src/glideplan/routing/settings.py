"""`RouteSettings`: the knobs of `route()`, frozen (like hj_reachability's `SolverSettings`).

resolution: routing-grid spacing h (m) at the route's mean latitude; None: the start-goal
distance over `cells` (about 250 cells across it). land_clearance_m: routes keep at least this
distance from land (m), measured from the field's own land (NaN) nodes; None: the default,
one field cell's diagonal for a gridded field with land (the field's linear interpolation
reads NaN within one cell of a land node; the route keeps the clearance at the land mask's
resolution, `routing.coast`; plus one grid spacing where it cannot: a window round the whole
circle), else one grid spacing. cfl: the front's Courant number. max_duration: give up after
this long (s; default: the field's time span, or 10 x the still-water time for a steady
field). refine: try Zermelo shooting on the sphere in open water. endpoint_tolerance_cells:
a route is solved when its controls, flown through the field, end within this many grid
spacings of the goal.
margin: the first routing window is the start-goal box grown by margin x distance (plus 10
cells) on each side; it grows when the front reaches its edge. progress: Rich progress on
stderr for the front (after ~2 s).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from glideplan.errors import InvalidParameterError

__all__ = ["RouteSettings"]

#: The widest land clearance a route may ask for (m): `PHYSICAL_RANGES["clearance"]`.
MAX_LAND_CLEARANCE_M = 100_000.0
_KINDS = {"resolution": "distance", "land_clearance_m": "clearance", "max_duration": "duration"}


@dataclass(frozen=True)
class RouteSettings:
    """Settings of `route()` (module docstring for each)."""

    resolution: float | None = None
    land_clearance_m: float | None = None
    cfl: float = 0.5
    max_duration: float | None = None
    refine: bool = True
    cells: int = 250
    margin: float = 0.3
    endpoint_tolerance_cells: float = 1.0
    progress: bool = False
    max_nodes: int = 6_000_000

    def __post_init__(self) -> None:
        from glideplan.validation import check_physical

        for name, kind in _KINDS.items():  # validation.PHYSICAL_RANGES, the one table
            if getattr(self, name) is not None:
                check_physical(name, getattr(self, name), kind)
        if not (math.isfinite(self.cfl) and 0 < self.cfl <= 1):
            raise InvalidParameterError("cfl", self.cfl, "must be in (0, 1]")
        if not (isinstance(self.cells, int) and self.cells >= 8):
            raise InvalidParameterError("cells", self.cells, "must be an integer >= 8")
        if not (math.isfinite(self.margin) and self.margin >= 0):
            raise InvalidParameterError("margin", self.margin, "must be finite and >= 0")
        if not (math.isfinite(self.endpoint_tolerance_cells)
                and self.endpoint_tolerance_cells > 0):
            raise InvalidParameterError("endpoint_tolerance_cells",
                                        self.endpoint_tolerance_cells, "must be > 0")
