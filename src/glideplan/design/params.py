"""Design parameter sets: a frozen bundle of the chapter 7 inputs, read from and written to TOML.

Every field carries its SI unit in its name (`max_pressure_pa`, `diameter_m`, ...). A TOML
file may instead give a field in an edge unit by swapping the suffix, e.g.
`max_pressure_psi = 3442`, `internal_volume_in3 = 183`, `max_volume_l = 5`,
`diameter_in = 9`, `empty_mass_lb = 8.6`, `temperature_degc = 20`; it is converted to SI on
load. Unknown sections or keys, bad values (a boolean or text where a number is expected:
TOML `true` is not 1.0), malformed TOML and files that are not UTF-8 text raise
`InvalidParameterError` naming the field (`section.key`) or the file.

A file may give only some fields; the others keep the defaults of `DesignParameters()`.
`defaulted_fields` lists them (the CLI prints them as a warning, so nothing is silent).
"""

from __future__ import annotations

import dataclasses
import pathlib
import tomllib
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import tomli_w

from glideplan.design.buoyancy import VTUG_BLADDER, VTUG_HULL, Bladder, Hull
from glideplan.design.gas import FRESH_WATER, FX23DV, Environment, Tank
from glideplan.design.glide import SEAGLIDER_LIKE, DragPolar
from glideplan.design.positioning import LBLConfig
from glideplan.design.trim import VTUG_TRIM, TrimLayout
from glideplan.errors import InvalidParameterError
from glideplan.units import (
    celsius_to_kelvin,
    deg_to_rad,
    feet_to_m,
    inch3_to_m3,
    inch_to_m,
    kmh_to_ms,
    lb_to_kg,
    litre_to_m3,
    psi_to_pa,
)

__all__ = [
    "DesignParameters",
    "defaulted_fields",
    "dumps_parameters",
    "load_parameters",
    "loads_parameters",
    "parameters_from_dict",
    "parameters_to_dict",
    "read_parameter_text",
    "save_parameters",
]


@dataclass(frozen=True)
class DesignParameters:
    """All chapter 7 design inputs; defaults are the VTUG / FX23DV / Seaglider-like examples."""

    environment: Environment = FRESH_WATER
    tank: Tank = FX23DV
    bladder: Bladder = VTUG_BLADDER
    hull: Hull = VTUG_HULL
    trim: TrimLayout = VTUG_TRIM
    glide: DragPolar = SEAGLIDER_LIKE
    lbl: LBLConfig = dataclasses.field(default_factory=LBLConfig)

    def __post_init__(self) -> None:
        for f in dataclasses.fields(self):
            if not isinstance(getattr(self, f.name), _SECTIONS[f.name]):
                raise InvalidParameterError(
                    f.name, getattr(self, f.name), f"must be a {_SECTIONS[f.name].__name__}"
                )

    def replace(self, **changes: Any) -> DesignParameters:
        """A copy with whole sections replaced."""
        return dataclasses.replace(self, **changes)


_SECTIONS: dict[str, type] = {
    "environment": Environment,
    "tank": Tank,
    "bladder": Bladder,
    "hull": Hull,
    "trim": TrimLayout,
    "glide": DragPolar,
    "lbl": LBLConfig,
}


def _scale(k: float) -> Callable[[Any], Any]:
    return lambda v: np.asarray(v, dtype=float) * k


# edge suffix -> (SI suffix, converter)
_EDGE_UNITS: dict[str, tuple[str, Callable[[Any], Any]]] = {
    "_psi": ("_pa", psi_to_pa),
    "_kpa": ("_pa", _scale(1e3)),
    "_l": ("_m3", litre_to_m3),
    "_in3": ("_m3", inch3_to_m3),
    "_in": ("_m", inch_to_m),
    "_ft": ("_m", feet_to_m),
    "_lb": ("_kg", lb_to_kg),
    "_deg": ("_rad", deg_to_rad),
    "_kmh": ("_m_s", kmh_to_ms),
    "_degc": ("_k", celsius_to_kelvin),
}


def _to_plain(value: Any) -> Any:
    arr = np.asarray(value)
    if arr.ndim == 0:
        return arr.item()
    return arr.tolist()


def _contains_bool(value: Any) -> bool:
    if isinstance(value, bool):
        return True
    if isinstance(value, (list, tuple)):
        return any(_contains_bool(v) for v in value)
    return False


def _check_type(section: str, key: str, field_type: str, value: Any) -> None:
    """Text where the field is text, numbers (never booleans) everywhere else."""
    if field_type == "str":
        if not isinstance(value, str):
            raise InvalidParameterError(f"{section}.{key}", value, "must be text")
        return
    if _contains_bool(value):
        raise InvalidParameterError(
            f"{section}.{key}", value, "must be a number, not a boolean (true/false)"
        )


def _section_kwargs(section: str, table: Any) -> dict[str, Any]:
    cls = _SECTIONS[section]
    if not isinstance(table, Mapping):
        raise InvalidParameterError(section, table, "must be a TOML table ([section])")
    types = {f.name: str(f.type) for f in dataclasses.fields(cls)}
    names = set(types)
    kwargs: dict[str, Any] = {}
    for key, value in table.items():
        field, val = key, value
        _check_type(section, key, types.get(key, "float"), value)
        if key not in names:
            for edge, (si, conv) in _EDGE_UNITS.items():
                if key.endswith(edge) and key[: -len(edge)] + si in names:
                    field = key[: -len(edge)] + si
                    try:
                        val = _to_plain(conv(value))
                    except (TypeError, ValueError):
                        raise InvalidParameterError(
                            f"{section}.{key}", value, "must be a number or list of numbers"
                        ) from None
                    break
            else:
                raise InvalidParameterError(
                    f"{section}.{key}", value, f"unknown key; expected one of {sorted(names)}"
                )
        if field in kwargs:
            raise InvalidParameterError(f"{section}.{key}", value, f"duplicates {section}.{field}")
        kwargs[field] = val
    return kwargs


# Each numeric field -> its kind in `glideplan.validation.PHYSICAL_RANGES`: a file's value
# outside the range (gravity_m_s2 = 1e300) is refused naming `section.key` before any work.
PHYSICAL_KINDS: Mapping[str, str] = {
    "environment.water_density_kg_m3": "water_density",
    "environment.gravity_m_s2": "gravity",
    "environment.atmospheric_pressure_pa": "pressure",
    "environment.temperature_k": "temperature",
    "tank.max_pressure_pa": "pressure",
    "tank.internal_volume_m3": "volume",
    "tank.empty_mass_kg": "mass",
    "bladder.max_volume_m3": "volume",
    "bladder.neutral_volume_m3": "volume",
    "bladder.elastic_coefficients_pa": "pressure_coefficient",
    "hull.dry_mass_kg": "mass",
    "hull.diameter_m": "length",
    "hull.drag_coefficient": "coefficient",
    "trim.moving_mass_kg": "mass",
    "trim.moving_mass_offset_m": "station",
    "trim.moving_mass_min_station_m": "station",
    "trim.moving_mass_max_station_m": "station",
    "trim.tank_mass_kg": "mass",
    "trim.tank_station_m": "station",
    "trim.body_mass_kg": "mass",
    "trim.body_station_m": "station",
    "trim.body_volume_m3": "volume",
    "trim.body_buoyancy_station_m": "station",
    "trim.bladder_station_m": "station",
    "glide.zero_lift_drag_coefficient": "coefficient",
    "glide.induced_drag_factor": "coefficient",
    "glide.lift_slope_per_rad": "coefficient",
    "glide.reference_area_m2": "area",
    "lbl.beacons_m": "position",
    "lbl.beacon_depth_m": "depth",
    "lbl.receiver_depth_m": "depth",
    "lbl.range_noise_std_m": "distance",
    "lbl.sound_speed_assumed_m_s": "sound_speed",
    "lbl.sound_speed_true_m_s": "sound_speed",
}


def _check_physical(section: str, kwargs: Mapping[str, Any], table: Mapping[str, Any]) -> None:
    """The numbers a file's `table` gives (converted to SI in `kwargs`) against their range.

    Only numbers are checked here (text, booleans and shapes are the section's own checks);
    the error names the key as the file spells it (`environment.gravity_m_s2`).
    """
    from glideplan.validation import check_physical_array

    for key, raw in table.items():
        field = _given_field(section, key)
        kind = PHYSICAL_KINDS.get(f"{section}.{field}")
        value = kwargs.get(field)
        if kind is None or isinstance(value, str):
            continue
        try:
            arr = np.asarray(value, dtype=float)
        except (TypeError, ValueError):
            continue  # not numbers: the section's constructor says so
        try:
            check_physical_array(f"{section}.{key}", arr, kind)
        except InvalidParameterError as exc:
            if key == field:
                raise
            shown = raw if np.ndim(raw) == 0 else exc.value
            raise InvalidParameterError(
                f"{section}.{key}", shown, f"as {field} = {exc.value:.6g}: {exc.rule}"
            ) from None


def _build(section: str, kwargs: dict[str, Any]) -> Any:
    cls = _SECTIONS[section]
    try:
        return cls(**kwargs)
    except InvalidParameterError as exc:
        raise InvalidParameterError(f"{section}.{exc.name}", exc.value, exc.rule) from None
    except (TypeError, ValueError) as exc:
        raise InvalidParameterError(section, kwargs, f"bad values: {exc}") from None


def parameters_from_dict(data: Mapping[str, Any]) -> DesignParameters:
    """Build `DesignParameters` from nested mappings; missing sections and keys keep defaults."""
    if not isinstance(data, Mapping):
        raise InvalidParameterError("parameters", data, "must be a mapping of sections")
    unknown = sorted(set(data) - set(_SECTIONS))
    if unknown:
        raise InvalidParameterError(
            unknown[0], data[unknown[0]], f"unknown section; expected one of {sorted(_SECTIONS)}"
        )
    defaults = DesignParameters()
    sections: dict[str, Any] = {}
    for name in _SECTIONS:
        if name in data:
            base = dataclasses.asdict(getattr(defaults, name))
            given = _section_kwargs(name, data[name])
            base.update(given)
            sections[name] = _build(name, base)  # the section's own rules first (sign, shape)
            _check_physical(name, given, data[name])
    return DesignParameters(**sections)


def _given_field(section: str, key: str) -> str:
    """The SI field a TOML key sets (`max_volume_l` -> `max_volume_m3`)."""
    names = {f.name for f in dataclasses.fields(_SECTIONS[section])}
    if key in names:
        return key
    for edge, (si, _) in _EDGE_UNITS.items():
        if key.endswith(edge) and key[: -len(edge)] + si in names:
            return key[: -len(edge)] + si
    return key


def defaulted_fields(data: Mapping[str, Any]) -> tuple[str, ...]:
    """`section.field` of every parameter that `data` (parsed TOML) leaves at its default."""
    out: list[str] = []
    for section, cls in _SECTIONS.items():
        table = data.get(section, {}) if isinstance(data, Mapping) else {}
        given = {_given_field(section, k) for k in table} if isinstance(table, Mapping) else set()
        out += [f"{section}.{f.name}" for f in dataclasses.fields(cls) if f.name not in given]
    return tuple(out)


def parameters_to_dict(params: DesignParameters) -> dict[str, dict[str, Any]]:
    """Nested plain dict (SI field names) of a parameter set, ready for TOML or JSON."""
    out: dict[str, dict[str, Any]] = {}
    for name in _SECTIONS:
        section = dataclasses.asdict(getattr(params, name))
        out[name] = {k: _to_plain(v) if not isinstance(v, str) else v for k, v in section.items()}
    return out


def loads_parameters(text: str, source: str = "<string>") -> DesignParameters:
    """Parse TOML text into `DesignParameters`; malformed TOML raises naming `source`."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InvalidParameterError(source, "TOML", f"is not valid TOML: {exc}") from None
    return parameters_from_dict(data)


def read_parameter_text(path: str | pathlib.Path) -> str:
    """The text of a TOML parameter file; a missing, unreadable or binary file is refused."""
    p = pathlib.Path(path)
    try:
        raw = p.read_bytes()
    except OSError as exc:
        raise InvalidParameterError("params", str(p), f"cannot be read: {exc.strerror}") from None
    try:
        if b"\x00" in raw:
            raise UnicodeDecodeError("utf-8", raw, raw.index(b"\x00"), raw.index(b"\x00") + 1, "")
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InvalidParameterError(
            "params",
            str(p),
            f"is not a TOML text file (not UTF-8 text: byte {raw[exc.start]:#04x} at offset "
            f"{exc.start})",
        ) from None


def load_parameters(path: str | pathlib.Path) -> DesignParameters:
    """Read a TOML parameter file (fields it does not give keep their defaults)."""
    p = pathlib.Path(path)
    return loads_parameters(read_parameter_text(p), source=str(p))


_HEADER = """\
# glideplan design parameters (Wolek 2015, chapter 7). SI units, named in each key.
# A key may use an edge unit instead by swapping its suffix, e.g. max_pressure_psi = 3442,
# internal_volume_in3 = 183, max_volume_l = 5, diameter_in = 9, empty_mass_lb = 8.6.
# bladder.elastic_coefficients_pa: c_k of p_blad(V) = sum_k c_k (V / V_max)^k (illustrative).
"""


def dumps_parameters(params: DesignParameters, *, header: bool = True) -> str:
    """TOML text for a parameter set (with an explanatory comment header)."""
    body = tomli_w.dumps(parameters_to_dict(params))
    return (_HEADER + "\n" + body) if header else body


def save_parameters(params: DesignParameters, path: str | pathlib.Path) -> pathlib.Path:
    """Write a parameter set to a TOML file and return its path."""
    p = pathlib.Path(path)
    p.write_text(dumps_parameters(params), encoding="utf-8")
    return p
