"""Route files in (CSV, GPX, KML/KMZ, GeoJSON) and mission files out (GIS and vehicle formats)."""

from glideplan.formats.antimeridian import split_at_antimeridian, wrap_longitude
from glideplan.formats.ddmm import ddmm_to_degrees, degrees_to_ddmm
from glideplan.formats.export import EXPORT_FORMATS, ExportOptions, export_mission, parse_formats
from glideplan.formats.readers import ROUTE_EXTENSIONS, read_route
from glideplan.formats.tracks import (
    geojson_line,
    kml_line,
    write_track_geojson,
    write_track_gpx,
    write_track_kml,
)

__all__ = [
    "EXPORT_FORMATS",
    "ROUTE_EXTENSIONS",
    "ExportOptions",
    "ddmm_to_degrees",
    "degrees_to_ddmm",
    "export_mission",
    "geojson_line",
    "kml_line",
    "parse_formats",
    "read_route",
    "split_at_antimeridian",
    "wrap_longitude",
    "write_track_geojson",
    "write_track_gpx",
    "write_track_kml",
]
