"""`glideplan route --ensemble GLOB` and `--depart-range START END HOURS` (called by cli.route).

Parsing and output only: the work is `glideplan.routing.ensemble` / `routing.departures`.
Exit 0 when a route to fly exists (an ensemble: some member route arrives through some
member; a range: some departure is solved), 1 when none, 2 for bad input.
"""

from __future__ import annotations

import json
import pathlib
from typing import Any, NoReturn

import typer

__all__ = ["corridor_geojson", "run"]


def corridor_geojson(res: Any) -> dict[str, Any]:
    """FeatureCollection: each member's track (kind member), the chosen route (kind route), the
    envelope (a Polygon, kind corridor), start and goal (Points)."""
    from glideplan.formats.antimeridian import wrap_longitude
    from glideplan.formats.tracks import geojson_line

    feats: list[dict[str, Any]] = []
    for i, r in enumerate(res.routes):
        if r.track.size >= 2:
            feats.append({"type": "Feature", "geometry": geojson_line(r.lat, r.lon),
                          "properties": {"kind": "member", "member": i, "file": res.members[i],
                                         "status": r.status.value,
                                         "duration_s": r.duration_s}})
    chosen = res.chosen_route
    if chosen is not None:
        feats.append({"type": "Feature", "geometry": geojson_line(chosen.lat, chosen.lon),
                      "properties": {"kind": "route", "member": res.chosen,
                                     "p_arrival": res.chosen_p_arrival,
                                     "duration_s": chosen.duration_s}})
    if res.envelope is not None:
        lat, lon = res.envelope
        ring = [[float(wrap_longitude(b)), float(a)] for a, b in zip(lat, lon, strict=True)]
        feats.append({"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [ring]},
                      "properties": {"kind": "corridor", "members": len(res.routes)}})
    s, g = res.routes[0].start, res.routes[0].goal
    for name, p in (("start", s), ("goal", g)):
        feats.append({"type": "Feature", "properties": {"kind": name},
                      "geometry": {"type": "Point",
                                   "coordinates": [float(wrap_longitude(p[1])), float(p[0])]}})
    return {"type": "FeatureCollection", "features": feats}


def _settings(resolution: float | None, land_clearance: float | None,
              max_duration: float | None) -> Any:
    from glideplan.routing import RouteSettings
    from glideplan.routing.ensemble import BATCH_CELLS

    return RouteSettings(resolution=resolution, land_clearance_m=land_clearance,
                         max_duration=None if max_duration is None else max_duration * 3600.0,
                         cells=BATCH_CELLS)


def _departures(depart_range: tuple[str, str, float], flow: Any) -> Any:
    from glideplan.cli.route import check_depart, parse_depart
    from glideplan.errors import InvalidParameterError
    from glideplan.routing.departures import departure_times

    try:
        a, b = parse_depart(depart_range[0]), parse_depart(depart_range[1])
    except InvalidParameterError as exc:
        raise InvalidParameterError("--depart-range", exc.value, exc.rule) from None
    times = departure_times(a, b, float(depart_range[2]))
    for t in (times[0], times[-1]):
        try:
            check_depart(flow, t)
        except InvalidParameterError as exc:
            raise InvalidParameterError("--depart-range", exc.value, exc.rule) from None
    return times


def _open(opts: dict[str, Any]) -> tuple[list[Any], list[str]]:
    """The member fields (--ensemble) or the one field (--field / --example)."""
    from glideplan.cli.common import check_input_file, flag_names, usage_error
    from glideplan.errors import InvalidParameterError

    if opts["ensemble"] is not None:
        if opts["field"] is not None or opts["example"] is not None:
            usage_error("give --ensemble GLOB or --field/--example, not both")
        from glideplan.routing.ensemble import expand_members, open_members

        paths = expand_members(opts["ensemble"])
        with flag_names(field="--ensemble", members="--ensemble",
                        depth_range="--depth-range"):
            return open_members(paths, opts["depth_range"])
    if opts["example"] is not None:
        from glideplan.cli.route import _EXAMPLES
        from glideplan.fields import double_gyre

        if opts["example"] not in _EXAMPLES:
            raise InvalidParameterError("--example", opts["example"],
                                        f"must be one of {_EXAMPLES}")
        return [double_gyre()], [f"example {opts['example']}"]
    if opts["field"] is None:
        usage_error("give --field FILE, --example NAME or --ensemble GLOB")
    from glideplan.fields import open_field

    for p in opts["field"]:
        check_input_file(p, "--field")
    with flag_names(field="--field", depth_range="--depth-range"):
        return [open_field(opts["field"], depth_range=opts["depth_range"])], [
            ", ".join(str(p) for p in opts["field"])]


def run(**opts: Any) -> None:
    """Run the ensemble and/or departure-range route (options as `glideplan route`'s)."""
    import sys

    from glideplan.cli.common import flag_names, usage_error
    from glideplan.cli.route import check_depart, parse_depart
    from glideplan.errors import InvalidParameterError

    for flag, key in (("--radius", "radius"), ("--kml", "kml")):
        if opts.get(key) is not None:
            usage_error(f"{flag} is not available with --ensemble or --depart-range")
    if opts["depart"] is not None and opts["depart_range"] is not None:
        usage_error("give --depart or --depart-range, not both")
    if opts["workers"] is not None and opts["workers"] < 1:
        raise InvalidParameterError("--workers", opts["workers"], "must be >= 1")
    fields, names = _open(opts)
    depart_range = opts["depart_range"]
    times = _departures(depart_range, fields[0]) if depart_range is not None else None
    when = check_depart(fields[0], parse_depart(opts["depart"])) if times is None else None
    settings = _settings(opts["resolution"], opts["land_clearance"], opts["max_duration"])
    batch = {"scheduler": opts["scheduler"], "processes": opts["workers"],
             "progress": sys.stderr.isatty()}
    names_map = {"from": "--from", "to": "--to", "speed": "--speed",
                 "resolution": "--resolution", "land_clearance_m": "--land-clearance",
                 "max_duration": "--max-duration", "scheduler": "--scheduler",
                 "processes": "--workers", "members": "--ensemble"}
    args = (opts["from_"], opts["to"], opts["speed"])
    with flag_names(**names_map):
        if times is not None:
            from glideplan.routing.departures import route_departures

            res: Any = route_departures(fields, *args, list(times), settings=settings,
                                        ensemble=opts["ensemble"] is not None, names=names,
                                        **batch)
        else:
            from glideplan.routing.ensemble import route_ensemble

            res = route_ensemble(fields, *args, when, settings=settings, names=names, **batch)
    _emit(res, opts, times is not None)


def _emit(res: Any, opts: dict[str, Any], ranged: bool) -> NoReturn:
    """The extra files (the corridor figure of a range, --geojson), then `cli.emit.emit`."""
    from glideplan.cli.emit import emit

    exports = _write_files(res, opts, ranged)
    emit(res, json=opts["json_out"], plot=opts["plot"], exports=exports or None,
         summary=lambda r: _print(r.to_dict(), ranged), save_kw={"tight": False},
         what="route")


def _write_files(res: Any, opts: dict[str, Any], ranged: bool) -> dict[str, pathlib.Path]:
    exports: dict[str, pathlib.Path] = {}
    out = res.to_dict()
    ens = None
    if ranged and res.ensembles and res.best is not None:
        ens = res.ensembles[res.best]
    elif not ranged:
        ens = res
    if opts["plot"] is not None and ranged and ens is not None:
        from glideplan.routing.ensemble_plot import plot_ensemble

        extra = opts["plot"].with_name(opts["plot"].stem + "_corridor" + opts["plot"].suffix)
        plot_ensemble(ens, extra)
        exports["corridor"] = extra
    if opts["geojson"] is not None:
        path: pathlib.Path = opts["geojson"]
        if ens is not None:
            data = corridor_geojson(ens)
        else:
            best = res.routes[res.best] if res.best is not None else None
            from glideplan.formats.tracks import geojson_line

            data = {"type": "FeatureCollection", "features": [] if best is None or
                    best.track.size < 2 else [{"type": "Feature",
                                               "geometry": geojson_line(best.lat, best.lon),
                                               "properties": {"kind": "route",
                                                              "depart": out["best_departure"],
                                                              "duration_s": best.duration_s}}]}
        path.write_text(json.dumps(data, indent=1, allow_nan=False) + "\n", encoding="utf-8")
        exports["geojson"] = path
    return exports


def _hours(v: float | None) -> str:
    return "n/a" if v is None else f"{v:.2f} h"


def _print(out: dict[str, Any], ranged: bool) -> None:
    if ranged:
        typer.echo(f"{'departure':22} " + ("p_arr   P10      P50      P90" if "p50_h" in
                   (out["departures"][0] if out["departures"] else {}) else "status        "
                   "duration"))
        for row in out["departures"]:
            if "p50_h" in row:
                typer.echo(f"{row['depart']:22} {row['p_arrival']:.2f}  "
                           f"{_hours(row['p10_h']):8} {_hours(row['p50_h']):8} "
                           f"{_hours(row['p90_h']):8}")
            else:
                d = row["duration_s"]
                typer.echo(f"{row['depart']:22} {row['status']:13} "
                           f"{_hours(None if d is None else d / 3600.0)}")
        typer.echo(f"best departure: {out['best_departure']}")
    e = out.get("ensemble")
    if e is not None:
        typer.echo(f"ensemble: {e['members']} members, p_arrival {e['p_arrival']:.2f}, "
                   f"P10 {_hours(e['p10_h'])}, P50 {_hours(e['p50_h'])}, "
                   f"P90 {_hours(e['p90_h'])}")
        c = e["chosen"]
        if c is not None:
            typer.echo(f"route to fly: member {c['member']} ({c['file']}), arrives in "
                       f"{c['p_arrival']:.2f} of the members flown in closed loop")
    typer.echo(f"status: {out['status']}: {out['message']}")
