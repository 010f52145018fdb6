"""Route files in (CSV, GPX, KML, GeoJSON) and mission files out (GIS and vehicle formats)."""

from glideplan.formats.ddmm import ddmm_to_degrees, degrees_to_ddmm
from glideplan.formats.export import EXPORT_FORMATS, ExportOptions, export_mission, parse_formats
from glideplan.formats.readers import ROUTE_EXTENSIONS, read_route

__all__ = [
    "EXPORT_FORMATS",
    "ROUTE_EXTENSIONS",
    "ExportOptions",
    "ddmm_to_degrees",
    "degrees_to_ddmm",
    "export_mission",
    "parse_formats",
    "read_route",
]
