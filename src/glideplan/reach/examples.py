"""Built-in glide-reach scenarios, runnable without terrain files (`--example ridge`).

"ridge": one synthetic SRTM3 tile, N46E007 (46-47 N, 7-8 E; 1201 x 1201 samples, 3
arc-seconds, int16 metres as an .hgt holds them), a flat valley floor at FLOOR_M = 500 m
between two ranges:

- the west range: a crest along lon WEST_CREST_LON over the whole tile, WEST_CREST_M high;
- the ridge: a straight crest from RIDGE_SOUTH to RIDGE_NORTH (on lon 7.55), RIDGE_CREST_M
  = 3000 m high, higher than the start altitude, so no glide crosses it.

Each range falls from its crest to the floor over FLANK_M (horizontal metres) with a cosine
profile of the distance d to its crest line (a segment for the ridge: rounded ends),

    z = FLOOR_M + (crest - FLOOR_M) (1 + cos(pi d / FLANK_M)) / 2   for d < FLANK_M,

and z = FLOOR_M beyond (distances in the local plane at START's latitude: x = R cos(lat0)
dlon, y = R dlat). The glider is at START, 1500 m MSL over the valley; five fields (all at
the floor's elevation) lie in the valley and behind the ridge. Polar: the DG-1001M of the
dissertation (eq. 5.26, `demos/data/DG-1001M_ch5.plr`); wind 6 m/s from 250 deg; MC 0;
safety height 300 m; front grid 700 m (the whole example runs in a few seconds).

`example("ridge")` -> `ReachExample`; `write_example(ex, directory)` writes the tile, the
fields as SeeYou .cup and the polar (the CLI prints the equivalent command line).
"""

from __future__ import annotations

import math
import pathlib
from dataclasses import dataclass
from functools import cache

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.reach.problem import Landable
from glideplan.terrain.grid import EARTH_RADIUS_M, Terrain

__all__ = [
    "EXAMPLES",
    "FLANK_M",
    "FLOOR_M",
    "RIDGE_CREST_M",
    "RIDGE_NORTH",
    "RIDGE_SOUTH",
    "START",
    "WEST_CREST_LON",
    "WEST_CREST_M",
    "ReachExample",
    "example",
    "ridge_elevation",
    "write_example",
]

EXAMPLES = ("ridge",)

POLAR_FILE = pathlib.Path(__file__).resolve().parents[1] / "demos" / "data" / "DG-1001M_ch5.plr"

FLOOR_M = 500.0
RIDGE_CREST_M = 3000.0
RIDGE_SOUTH = (46.40, 7.55)  # (lat, lon) deg: the ridge's crest line, south end
RIDGE_NORTH = (46.62, 7.55)  # north end
WEST_CREST_LON = 7.20
WEST_CREST_M = 2800.0
FLANK_M = 2500.0  # horizontal distance from crest to valley floor (m)
START = (46.50, 7.40, 1500.0)  # (lat, lon deg, altitude m MSL)
TILE = "N46E007.hgt"
SAMPLES = 1201  # SRTM3: 3 arc-seconds


def _dm(deg: int, minutes: float) -> float:
    """Degrees from whole degrees and minutes (the fields sit on whole 0.001 minutes, the
    resolution of a .cup position, so a written file reads back to the same floats)."""
    return deg + minutes / 60.0


#: The fields, in the .cup file's order: (name, code, lat, lon); all at FLOOR_M.
FIELDS = (
    ("Valley Home", "VHOME", _dm(46, 28.0), _dm(7, 23.0)),    # in the valley, 4 km SW
    ("Valley North", "VNORTH", _dm(46, 40.0), _dm(7, 25.0)),  # in the valley, 19 km N
    ("Behind North", "BNORTH", _dm(46, 34.0), _dm(7, 40.0)),  # behind the ridge, round its N end
    ("Behind South", "BSOUTH", _dm(46, 24.0), _dm(7, 40.0)),  # behind the ridge, round its S end
    ("Far East", "FEAST", _dm(46, 27.0), _dm(7, 55.0)),       # behind the ridge, far beyond
)


@dataclass(frozen=True, eq=False)
class ReachExample:
    """A runnable scenario: terrain, fields, start (lat, lon, altitude m MSL), polar file,
    wind (speed m/s, FROM compass deg), MC (m/s), safety height (m), front grid spacing (m),
    and for `turnback` a course (compass deg) and the home field."""

    name: str
    description: str
    terrain: Terrain
    tile_name: str
    landables: tuple[Landable, ...]
    start: tuple[float, float, float]
    polar_file: pathlib.Path
    wind_speed_ms: float
    wind_from_deg: float
    mc: float
    safety_height: float
    resolution_m: float
    course_deg: float
    home: Landable


def _local_xy(lat: NDArray[np.float64], lon: NDArray[np.float64]
              ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Local plane (m) about START: x = R cos(lat0) (lon - lon0), y = R (lat - lat0)."""
    c = math.cos(math.radians(START[0]))
    return (EARTH_RADIUS_M * c * np.radians(lon - START[1]),
            EARTH_RADIUS_M * np.radians(lat - START[0]))


def _flank(d: NDArray[np.float64], crest: float) -> NDArray[np.float64]:
    """Cosine flank: crest at d = 0, FLOOR_M from d = FLANK_M on."""
    s = np.clip(d / FLANK_M, 0.0, 1.0)
    return FLOOR_M + (crest - FLOOR_M) * 0.5 * (1.0 + np.cos(np.pi * s))


def ridge_elevation(lat: NDArray[np.float64], lon: NDArray[np.float64]) -> NDArray[np.float64]:
    """The "ridge" terrain (m MSL) at (lat, lon) degrees, before rounding to whole metres
    (module docstring)."""
    la, lo = np.broadcast_arrays(np.asarray(lat, dtype=float), np.asarray(lon, dtype=float))
    x, y = _local_xy(la, lo)
    ax, ay = _local_xy(np.array(RIDGE_SOUTH[0]), np.array(RIDGE_SOUTH[1]))
    bx, by = _local_xy(np.array(RIDGE_NORTH[0]), np.array(RIDGE_NORTH[1]))
    ex, ey = bx - ax, by - ay
    t = np.clip(((x - ax) * ex + (y - ay) * ey) / (ex * ex + ey * ey), 0.0, 1.0)
    d_ridge = np.hypot(x - ax - t * ex, y - ay - t * ey)
    wx, _ = _local_xy(np.array(START[0]), np.array(WEST_CREST_LON))
    d_west = np.abs(x - wx)
    return np.maximum(_flank(d_ridge, RIDGE_CREST_M), _flank(d_west, WEST_CREST_M))


@cache
def _ridge_terrain() -> Terrain:
    """The tile as `read_hgt` returns it (same lat/lon nodes, int16 metres as float32)."""
    step = 1.0 / (SAMPLES - 1)
    lat = 46.0 + step * np.arange(SAMPLES)
    lon = 7.0 + step * np.arange(SAMPLES)
    lat[-1], lon[-1] = 47.0, 8.0
    la, lo = np.meshgrid(lat, lon, indexing="ij")
    z = np.round(ridge_elevation(la, lo)).astype(np.int16).astype(np.float32)
    return Terrain(np.asarray(lat, dtype=np.float64), np.asarray(lon, dtype=np.float64), z,
                   (f"example ridge ({TILE})",))


def example(name: str) -> ReachExample:
    """The built-in scenario `name` (one of EXAMPLES)."""
    if name not in EXAMPLES:
        raise InvalidParameterError("example", name, f"must be one of {', '.join(EXAMPLES)}")
    fields = tuple(Landable(n, la, lo, FLOOR_M, 2, c) for n, c, la, lo in FIELDS)
    return ReachExample(
        name="ridge",
        description=("synthetic SRTM3 tile N46E007: a 500 m valley floor, a 3000 m ridge "
                     "(46.40-46.62 N on 7.55 E) between the glider and three of the five "
                     "fields, a 2800 m range on 7.20 E"),
        terrain=_ridge_terrain(),
        tile_name=TILE,
        landables=fields,
        start=START,
        polar_file=POLAR_FILE,
        wind_speed_ms=6.0,
        wind_from_deg=250.0,
        mc=0.0,
        safety_height=300.0,
        resolution_m=700.0,
        course_deg=30.0,
        home=fields[0],
    )


def write_example(ex: ReachExample, directory: str | pathlib.Path
                  ) -> tuple[pathlib.Path, pathlib.Path, pathlib.Path]:
    """Write the example's tile (.hgt, `write_hgt`), fields (SeeYou .cup, aerofiles) and
    polar (.plr, a copy) into `directory` (created if missing); returns the three paths."""
    import shutil

    from glideplan.reach.landables import write_cup_landables
    from glideplan.terrain.hgt import write_hgt

    d = pathlib.Path(directory)
    if d.exists() and not d.is_dir():
        raise InvalidParameterError("directory", str(d), "exists and is not a directory")
    if not d.parent.is_dir():
        raise InvalidParameterError("directory", str(d),
                                    f"its parent {str(d.parent)!r} does not exist")
    d.mkdir(exist_ok=True)
    tile = write_hgt(d / ex.tile_name, np.asarray(ex.terrain.z, dtype=float))
    cup = write_cup_landables(d / "fields.cup", list(ex.landables))
    polar = d / ex.polar_file.name
    shutil.copyfile(ex.polar_file, polar)
    return tile, cup, polar
