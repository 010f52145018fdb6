"""The products in the main job: a route, a mission, a final glide and a glide reach.

Each runs through the one outcome contract (`glideplan.results.Outcome`: `status`, `ok`,
`message`, `to_dict()`, `plot()`) and is held to a reference it must meet:

- route on the double gyre (`glideplan.routing.route`, `glideplan.fields.examples`): the
  straight line with the crab angle is a feasible path, so the optimal route is not slower;
- mission (`glideplan.missions.plan_mission`) on the shipped GPX survey: the optimised headings
  are not worse than the best of two heading heuristics with the same legs;
- final glide (`glideplan.final_glide`) on the shipped DG-1001M polar (dissertation eq. 5.26)
  to an arrival heading in a wind: the straight final glide to the goal, which ignores the
  heading, needs no more altitude, so it is a lower bound;
- glide reach (`glideplan.glide_reach`) over flat synthetic terrain in still air: the reach
  radius is (altitude - terrain - safety height) x the best glide ratio (closed form).

`PRODUCTS` lists them in order; `run_product(case, out, plots)` runs one and returns a
`ProductRun` (the result, the numbers shown, the reference and whether it is met, the files).
"""

from __future__ import annotations

import math
import pathlib
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

__all__ = [
    "POLAR_FILE",
    "PRODUCTS",
    "ProductCase",
    "ProductCheck",
    "ProductRun",
    "available_products",
    "run_product",
]

DATA = pathlib.Path(__file__).parent / "data"
POLAR_FILE = DATA / "DG-1001M_ch5.plr"
MISSION_FILE = pathlib.Path(__file__).parents[1] / "missions" / "data" / "buzzards_bay.gpx"


@dataclass(frozen=True)
class ProductCheck:
    """What a product run shows: its numbers (label, text), the reference, whether it is met,
    and the files it wrote besides the JSON and the figure."""

    numbers: tuple[tuple[str, str], ...]
    reference: str
    met: bool
    files: tuple[str, ...] = ()


@dataclass(frozen=True)
class ProductCase:
    """One product: a name, where its inputs come from, and how to run and check it.

    `run(out_dir)` returns the result (an `Outcome`), `check(result, out_dir)` the
    `ProductCheck`; `plot_kwargs(result)` the keywords of its `plot()` (e.g. the field).
    """

    key: str
    name: str
    source: str
    run: Callable[[pathlib.Path], Any]
    check: Callable[[Any, pathlib.Path], ProductCheck]
    plot_kwargs: Callable[[Any], dict[str, Any]] | None = None


@dataclass(frozen=True)
class ProductRun:
    """A product's outcome in the demo: the result, its check, the time and the files."""

    case: ProductCase
    result: Any
    check: ProductCheck
    seconds: float
    figure: str | None
    json_file: str

    @property
    def ok(self) -> bool:
        return bool(self.result.ok and self.check.met)

    @property
    def status(self) -> str:
        return str(self.result.status.value)


def run_product(case: ProductCase, out: pathlib.Path, plots: bool = True) -> ProductRun:
    """Run `case` in `out` (made if missing): the result's JSON (`to_dict()`) and figure."""
    from glideplan.jsonio import write_json

    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    result = case.run(out)
    seconds = time.perf_counter() - t0
    check = case.check(result, out)
    json_file = out / f"{case.key}.json"
    write_json(result.to_dict(), json_file)
    figure = None
    if plots:
        from glideplan.plotting import save_figure

        kwargs = case.plot_kwargs(result) if case.plot_kwargs else {}
        figure = str(save_figure(result.plot(**kwargs), str(out / f"{case.key}.png")))
    return ProductRun(case, result, check, seconds, figure, str(json_file))


# ---- route on the double gyre ----------------------------------------------------------------

ROUTE_FROM = (30.3, -39.8)  # lat, lon (deg): inside the 200 km x 100 km gyre box
ROUTE_TO = (30.6, -39.3)
ROUTE_SPEED = 0.5  # m/s through the water, the gyre's currents reach 0.3 m/s
ROUTE_RESOLUTION = 3000.0  # m


def _gyre() -> Any:
    from glideplan.fields.examples import double_gyre

    return double_gyre()


def _route(out: pathlib.Path) -> Any:
    from glideplan.routing import route

    return route(_gyre(), ROUTE_FROM, ROUTE_TO, ROUTE_SPEED, resolution=ROUTE_RESOLUTION)


def _route_check(r: Any, out: pathlib.Path) -> ProductCheck:
    straight = r.straight_line_duration_s
    numbers = (
        ("duration", f"{r.duration_s / 3600:.2f} h"),
        ("distance", f"{r.distance_m / 1000:.1f} km"),
        ("endpoint error", f"{r.endpoint_error_m:.1f} m (tolerance {r.endpoint_tolerance_m:g} m)"),
        ("method", str(r.method)),
    )
    met = bool(
        r.ok
        and straight is not None
        and math.isfinite(straight)
        and r.duration_s <= straight * (1 + 1e-9)
        and r.endpoint_error_m <= r.endpoint_tolerance_m
    )
    ref = f"<= {straight / 3600:.2f} h straight line" if straight is not None else "-"
    return ProductCheck(numbers, ref, met)


# ---- mission on the shipped GPX survey -------------------------------------------------------


def _mission(out: pathlib.Path) -> Any:
    from glideplan.formats import read_route
    from glideplan.missions import plan_mission

    return plan_mission(read_route(MISSION_FILE), speed=0.3, radius=300.0)


def _mission_check(mission: Any, out: pathlib.Path) -> ProductCheck:
    from glideplan.formats import ExportOptions, export_mission, parse_formats
    from glideplan.missions import (
        StillAirCost,
        bisector_headings,
        headings_cost,
        point_at_next_headings,
    )

    route = mission.route
    files, _ = export_mission(
        mission, out, parse_formats(None),
        ExportOptions(acceptance_radius=100.0, name="buzzards_bay"),
    )  # fmt: skip
    cost = StillAirCost(route.points, mission.radius)
    best = min(
        headings_cost(cost, f(route.points, route.headings))[0]
        for f in (point_at_next_headings, bisector_headings)
    )
    errors = [
        leg.solution.endpoint_error.max
        for leg in mission.legs
        if leg.solution.endpoint_error is not None
    ]
    numbers = (
        ("length", f"{mission.total_length_m:.1f} m"),
        ("legs", " ".join(leg.word for leg in mission.legs)),
        ("endpoint error", f"{max(errors):.1e} m" if errors else "-"),
    )
    met = bool(mission.ok and math.isfinite(mission.total_length_m)
               and mission.total_length_m <= best * (1 + 1e-9))  # fmt: skip
    paths = [p for v in files.values() for p in ([v] if isinstance(v, str) else v)]
    return ProductCheck(
        numbers, f"<= {best:.1f} m heading heuristics", met,
        tuple(pathlib.Path(p).name for p in paths),
    )  # fmt: skip


# ---- final glide on the shipped polar ----------------------------------------------------------

GLIDE_FROM = (47.0, 8.0, 1500.0)  # lat, lon (deg), altitude (m)
GLIDE_TO = (47.15, 8.12, 450.0)  # lat, lon (deg), elevation (m)
GLIDE_WIND = (8.0, 270.0)  # m/s, compass FROM (deg): a west wind
GLIDE_ARRIVAL_HEADING = 270.0  # compass (deg): land into the wind


def _polar() -> Any:
    from glideplan.sailplane import polar_from_file, read_plr

    return polar_from_file(read_plr(POLAR_FILE))


def _final(out: pathlib.Path) -> Any:
    from glideplan import final_glide
    from glideplan.units import wind_from_compass

    return final_glide(
        _polar(), GLIDE_FROM, GLIDE_TO, wind=wind_from_compass(*GLIDE_WIND),
        arrival_heading=GLIDE_ARRIVAL_HEADING,
    )  # fmt: skip


def _final_check(g: Any, out: pathlib.Path) -> ProductCheck:
    data = g.to_dict()
    straight = (data.get("straight") or {}).get("altitude_loss_m")
    error = (data.get("endpoint_error") or {}).get("max")
    loss = g.altitude_loss_m
    numbers = (
        ("altitude loss", f"{loss:.0f} m" if loss is not None else "-"),
        ("required", f"{g.altitude_required_m:.0f} m" if g.altitude_required_m else "-"),
        ("margin", f"{g.arrival_margin_m:.0f} m" if g.arrival_margin_m is not None else "-"),
        ("path", str(data.get("word", ""))),
        ("endpoint error", f"{error:.1e} m" if error is not None else "-"),
    )
    met = bool(loss is not None and straight is not None and loss >= straight * (1 - 1e-9))
    ref = f">= {straight:.0f} m straight glide" if straight is not None else "-"
    return ProductCheck(numbers, ref, met)


# ---- glide reach over flat terrain -------------------------------------------------------------

REACH_FROM = (46.5, 8.0, 1500.0)  # lat, lon (deg), altitude (m)
REACH_GROUND = 500.0  # m: flat synthetic terrain
REACH_SAFETY = 300.0  # m
REACH_LANDABLE = (46.65, 8.15)  # lat, lon (deg): a field about 20 km north-east


def _flat_terrain() -> Any:
    import numpy as np

    from glideplan.terrain.grid import Terrain

    lat = np.linspace(46.0, 47.0, 81)  # +-55 km north-south, +-38 km east-west of the start
    lon = np.linspace(7.5, 8.5, 81)
    z = np.full((lat.size, lon.size), REACH_GROUND)
    return Terrain(lat=lat, lon=lon, z=z, sources=("flat synthetic terrain, 500 m",))


def _reach(out: pathlib.Path) -> Any:
    from glideplan import glide_reach
    from glideplan.reach import Landable

    field = Landable("FIELD", *REACH_LANDABLE, REACH_GROUND)
    return glide_reach(
        _flat_terrain(), REACH_FROM, _polar(), landables=[field], safety_height=REACH_SAFETY
    )


def _reach_check(r: Any, out: pathlib.Path) -> ProductCheck:
    """The footprint's area against the disk of radius (h - ground - safety) x (L/D)max."""
    polar = _polar()
    radius = (REACH_FROM[2] - REACH_GROUND - REACH_SAFETY) * polar.best_glide_ratio
    area = float(r.footprint_area_km2())
    numbers: tuple[tuple[str, str], ...] = (
        ("footprint", f"{area:.0f} km^2"),
        ("radius (equal area)", f"{math.sqrt(area / math.pi):.1f} km"),
        ("grid", f"{r.resolution_m:.0f} m"),
    )
    # the front's footprint on a grid of spacing h: its radius within a few cells of the disk's
    cells = 3 * r.resolution_m / 1000
    met = bool(r.ok and abs(math.sqrt(area / math.pi) - radius / 1000) <= cells)
    # the field's verified straight glide: arrival altitude h - d / (L/D)max (1 m: rounding)
    point = r.points[0]
    if point.arrival_altitude_m is None or point.distance_m is None:
        return ProductCheck(numbers, "the field is not reachable", False)
    expected = REACH_FROM[2] - point.distance_m / polar.best_glide_ratio
    numbers += ((f"{point.landable.name} arrival", f"{point.arrival_altitude_m:.1f} m"),)
    met = met and point.verified and abs(point.arrival_altitude_m - expected) <= 1.0
    return ProductCheck(
        numbers, f"{radius / 1000:.1f} km radius, field {expected:.1f} m: h - d / (L/D)max", met
    )


def _reach_available() -> bool:
    """The glide-reach hook: the product runs when `glideplan.glide_reach` exists."""
    import glideplan

    try:
        return callable(glideplan.glide_reach)
    except AttributeError:
        return False


PRODUCTS: tuple[ProductCase, ...] = (
    ProductCase(
        "route", "route: double gyre, 0.5 m/s",
        "fields.examples.double_gyre (Shadden et al. 2005); straight line with crab angle",
        _route, _route_check, lambda r: {"flow": _gyre()},
    ),
    ProductCase(
        "mission", "mission: GPX lawn-mower survey, 8 waypoints",
        "missions/data/buzzards_bay.gpx; heading heuristics", _mission, _mission_check,
    ),
    ProductCase(
        "final_glide", "final glide: DG-1001M, arrival heading 270°, wind 8 m/s",
        "demos/data/DG-1001M_ch5.plr (eq. 5.26); straight final glide (lower bound)",
        _final, _final_check,
    ),
    ProductCase(
        "glide_reach", "glide reach: flat terrain, still air",
        "synthetic 500 m plain, DG-1001M_ch5.plr; closed form h x (L/D)max",
        _reach, _reach_check,
    ),
)  # fmt: skip


def available_products() -> tuple[ProductCase, ...]:
    """`PRODUCTS` without the glide reach while `glideplan.glide_reach` has not landed."""
    return tuple(p for p in PRODUCTS if p.key != "glide_reach" or _reach_available())
