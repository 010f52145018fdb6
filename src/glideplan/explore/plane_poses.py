"""The plane page's draggable start and goal: their points and heading handles drawn from the
state, drags and drops turned into new poses (a live re-plan while a point is dragged), and
the view's range (a square around the poses, grown to hold what is drawn). A mixin of
`app.Explorer`, which owns the state, the figures and the inputs named below.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import numpy as np

from glideplan.explore.figures import GOAL, POINT_COLUMNS, START, PlanFigures, empty_points
from glideplan.explore.solve import View
from glideplan.explore.state import ExploreState, format_pose, parse_pose_text

__all__ = ["PoseHandles"]


class PoseHandles:
    """Poses drawn and dragged on `figs` (see the module docstring)."""

    state: ExploreState
    figs: PlanFigures
    pose_inputs: dict[str, Any]
    _syncing: bool
    _drawn: dict[tuple[str, str], tuple[float, float]]
    _dragging: tuple[str, str, float, float] | None

    @property
    def entry(self) -> Any:
        raise NotImplementedError

    def set_state(self, state: ExploreState) -> None:
        raise NotImplementedError

    # ----- dragging ---------------------------------------------------------------------------
    def _poses(self) -> dict[str, tuple[float, float, float] | None]:
        out: dict[str, tuple[float, float, float] | None] = {}
        for name in ("start", "goal"):
            try:
                p = parse_pose_text(getattr(self.state, name), name)
                out[name] = (p.x, p.y, p.heading)
            except ValueError:
                out[name] = None
        return out

    def _handle_length(self) -> float:
        x0, x1, _, _ = self.figs.box()
        return 0.12 * (x1 - x0)

    def _draw_poses(self) -> None:
        poses = self._poses()
        h = self._handle_length()
        pts = empty_points()
        labels: dict[str, list[Any]] = {"x": [], "y": [], "name": [], "c": []}
        seg: dict[str, list[Any]] = {"x0": [], "y0": [], "x1": [], "y1": [], "c": []}
        last = getattr(self, "_last_poses", {})
        for name, colour in (("start", START), ("goal", GOAL)):
            # an unreadable pose keeps its last point: the sources keep their length (the
            # draggable points' renderer threw BokehJS's "RangeError: Offset is outside the
            # bounds of the DataView" on every later change once rows went missing)
            p = poses[name] if poses[name] is not None else last.get(name)
            if p is None or not all(math.isfinite(v) for v in p):
                continue
            last[name] = p
            hx, hy = p[0] + h * math.cos(p[2]), p[1] + h * math.sin(p[2])
            for row in (
                (p[0], p[1], name, "pose", colour, colour, 15),
                (hx, hy, name, "handle", colour, "white", 11),
            ):
                for k, v in zip(POINT_COLUMNS, row, strict=True):
                    pts[k].append(v)
            for k, v in zip(("x", "y", "name", "c"), (p[0], p[1], name, colour), strict=True):
                labels[k].append(v)
            for k, v in zip(
                ("x0", "y0", "x1", "y1", "c"), (p[0], p[1], hx, hy, colour), strict=True
            ):
                seg[k].append(v)
        self._last_poses = last
        self._drawn = {
            (n, r): (x, y)
            for x, y, n, r in zip(pts["x"], pts["y"], pts["name"], pts["role"], strict=True)
        }
        self._syncing = True
        try:
            self.figs.points_src.data = pts
            self.figs.labels_src.data = labels
            self.figs.heading_src.data = seg
        finally:
            self._syncing = False

    def _snap(self, v: float) -> float:
        q = 10.0 ** math.floor(math.log10(max(self.entry.length_scale, 1e-12))) * 1e-3
        return float(f"{round(v / q) * q:.10g}")

    def _on_pan_start(self, event: Any) -> None:
        """Which point a drag holds: the drawn point nearest the pointer (within 3% of the view)."""
        x0, x1, _, _ = self.figs.box()
        best = min(
            self._drawn.items(),
            key=lambda kv: math.dist(kv[1], (event.x, event.y)),
            default=None,
        )
        if best is not None and math.dist(best[1], (event.x, event.y)) <= 0.03 * (x1 - x0):
            (name, role), (px, py) = best
            self._dragging = (name, role, px - event.x, py - event.y)

    def _on_pan(self, event: Any) -> None:
        if self._dragging is None:
            return
        name, role, dx, dy = self._dragging
        self._drag_to(name, role, event.x + dx, event.y + dy)

    def _on_pan_end(self, event: Any) -> None:
        self._dragging = None

    def _drag_to(self, name: str, role: str, x: float, y: float) -> None:
        p = self._poses()[name]
        if role == "pose" or p is None:
            self._move_pose(name, x, y, None)
        else:
            self._move_pose(name, p[0], p[1], math.degrees(math.atan2(y - p[1], x - p[0])))

    def _move_pose(self, name: str, x: float, y: float, heading_deg: float | None) -> None:
        old = self._poses()[name]
        if heading_deg is None:
            heading_deg = math.degrees(old[2]) if old is not None else 0.0
        text = format_pose(self._snap(x), self._snap(y), round(heading_deg, 2))
        self._syncing = True
        try:
            self.pose_inputs[name].value = text
        finally:
            self._syncing = False
        self.set_state(_with_pose(self.state, name, text))

    def _on_points(self, attr: str, old: Any, new: Any) -> None:
        """A drag ended: a moved pose keeps its heading, a moved handle turns its pose."""
        if self._syncing:
            return
        if self._dragging is not None:
            # the drop: live updates moved the state, but the browser's points are the truth
            self._dragging = None
        rows = zip(
            new.get("x", []),
            new.get("y", []),
            new.get("name", []),
            new.get("role", []),
            strict=False,
        )
        moved = [
            (n, r, float(x), float(y))
            for x, y, n, r in rows
            if (n, r) in self._drawn and math.dist((x, y), self._drawn[(n, r)]) > 1e-12
        ]
        if len(new.get("x", [])) != len(self._drawn) or not moved:
            self._draw_poses()  # a deleted point comes back
            return
        name, role, x, y = next((m for m in moved if m[1] == "pose"), moved[0])
        self._drag_to(name, role, x, y)

    # ----- view range -------------------------------------------------------------------------
    def _points(self) -> np.ndarray:
        pts = [p[:2] for p in self._poses().values() if p is not None]
        return np.array(pts, dtype=float).reshape(-1, 2)

    def _reset_ranges(self) -> None:
        """A square view around the start and goal with room for turns."""
        pts = self._points()
        scale = self.entry.length_scale
        if pts.size == 0:
            pts = np.zeros((1, 2))
        lo, hi = pts.min(axis=0) - 3.0 * scale, pts.max(axis=0) + 3.0 * scale
        self.figs.set_square(lo, hi)

    def _expand_ranges(self, view: View) -> None:
        """Grow the view (square, 8 % margin) to hold everything drawn: the path, the air
        path, the shown candidates and the poses."""
        parts = [(view.path["x"], view.path["y"])]
        if view.air_path is not None:
            parts.append((view.air_path["x"], view.air_path["y"]))
        if self.state.candidates and view.candidates:
            parts += list(zip(view.candidates["xs"], view.candidates["ys"], strict=True))
        pts = self._points()
        parts.append((pts[:, 0], pts[:, 1]))
        xs = np.concatenate([np.asarray(p[0], dtype=float) for p in parts])
        ys = np.concatenate([np.asarray(p[1], dtype=float) for p in parts])
        keep = np.isfinite(xs) & np.isfinite(ys)
        xs, ys = xs[keep], ys[keep]
        if len(xs) == 0:
            return
        bx0, bx1, by0, by1 = self.figs.box()
        lo = np.array([min(xs.min(), bx0), min(ys.min(), by0)])
        hi = np.array([max(xs.max(), bx1), max(ys.max(), by1)])
        inside = xs.min() >= bx0 and xs.max() <= bx1 and ys.min() >= by0 and ys.max() <= by1
        if not inside:
            pad = 0.08 * float(np.max(hi - lo))
            self.figs.set_square(lo - pad, hi + pad)
            self._draw_poses()


def _with_pose(state: ExploreState, name: str, text: str) -> ExploreState:
    return replace(state, start=text) if name == "start" else replace(state, goal=text)
