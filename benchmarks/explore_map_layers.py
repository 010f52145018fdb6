"""What the explorer's map layers cost (issue 27): the reach page at the DEM's own grid
against the 700 m pooled grid, the relief and contours, and the land/coast per view.

Run: `python benchmarks/explore_map_layers.py` (about a minute). Prints the one-off costs of
the relief image (and its bytes), the contours, and `land_shapes` for the mission's, a
1 x 1 deg and a 20 x 15 deg view; then per start the native and pooled reach CPU times (s of
the process: the machine is shared) and the reachable landables of both. The first call of
each kind (compiling) is not timed.
"""

from __future__ import annotations

import statistics
import time

STARTS = [  # drags of the glider over the ridge example (lat, lon, alt m)
    (46.5, 7.4, 1800.0), (46.45, 7.35, 1500.0), (46.55, 7.45, 2200.0),
    (46.6, 7.3, 1700.0), (46.5, 7.65, 1600.0),
]


def _reach() -> None:
    from glideplan.cli.glide import _polar
    from glideplan.geodesy import wind_from_to_vector
    from glideplan.reach import glide_reach
    from glideplan.reach.examples import example

    ex = example("ridge")
    polar = _polar(ex.polar_file, None, 0.0, 0.0, "--polar")
    wind = wind_from_to_vector(4.0, 250.0)

    def run(start: tuple[float, float, float], res: float | None) -> tuple[float, int]:
        t = time.process_time()  # CPU s of the process (the machine is shared)
        r = glide_reach(ex.terrain, start, polar, landables=ex.landables, mc=0.0, wind=wind,
                        safety_height=300.0, resolution_m=res)
        return time.process_time() - t, sum(p.reachable for p in r.points)

    run(STARTS[0], None)
    run(STARTS[0], 700.0)
    native, pooled = [], []
    for s in STARTS:
        (tn, nn), (tp, np_) = run(s, None), run(s, 700.0)
        native.append(tn)
        pooled.append(tp)
        print(f"start {s}: native {tn:.2f} s ({nn} reachable), 700 m {tp:.2f} s ({np_})")
    print(f"reach median: native {statistics.median(native):.2f} s (max {max(native):.2f}), "
          f"700 m {statistics.median(pooled):.2f} s (max {max(pooled):.2f})")


def _layers() -> None:
    import numpy as np

    from glideplan.explore.land import land_shapes
    from glideplan.explore.relief import contour_levels, contour_lines, relief_rgba
    from glideplan.reach.examples import example

    t = example("ridge").terrain
    t0 = time.perf_counter()
    image, step = relief_rgba(t)
    t1 = time.perf_counter()
    z = np.asarray(t.z, dtype=float)
    lines, labels = contour_lines(t, contour_levels(float(np.nanmin(z)), float(np.nanmax(z))))
    t2 = time.perf_counter()
    print(f"relief {image.shape} (stride {step}, {image.nbytes / 1e6:.2f} MB) {t1 - t0:.2f} s; "
          f"contours {len(lines['xs'])} lines, {len(labels['x'])} labels {t2 - t1:.2f} s")
    land_shapes(-71.0, 41.4, -70.7, 41.6)  # the data's one-off load
    for name, box in (("mission 3x3 views", (-71.06, 41.36, -70.71, 41.65)),
                      ("1 x 1 deg", (-71.5, 41.0, -70.5, 42.0)),
                      ("20 x 15 deg", (-80.0, 30.0, -60.0, 45.0))):
        t0 = time.perf_counter()
        polys, coast = land_shapes(*box)
        n = sum(len(r) for p in polys["xs"] for r in p[0])
        print(f"land {name}: {time.perf_counter() - t0:.3f} s, {len(polys['xs'])} polygons, "
              f"{n} polygon points, {coast['x'].size} coast points")


if __name__ == "__main__":
    _layers()
    _reach()
