"""How the explorer shows the vehicles' fields: degrees at the edge, units, readable names."""

from __future__ import annotations

from collections.abc import Mapping

__all__ = ["CAPTION_NAMES", "DEGREE_FIELDS", "FIELD_UNITS"]

# Fields entered in degrees at the page's edge (radians inside).
DEGREE_FIELDS = frozenset({"bank_max"})
# Units shown in the page's labels, by the last part of a field's name ("" = a pure number).
# "speed" marks a speed (m/s, or units of V_ref for a nondimensional vehicle), "length" a length.
FIELD_UNITS: Mapping[str, str] = {
    "speed": "speed",
    "v_min": "speed",
    "v_max": "speed",
    "v_stall": "speed",
    "turn_radius": "length",
    "u_max": "rad/s",
    "turn_rate_max": "rad/s",
    "bank_max": "deg",
    "mass_kg": "kg",
    "reference_mass_kg": "kg",
    "wing_area_m2": "m²",
    "bugs_pct": "%",
    "max_ballast_l": "L",
    "mc": "m/s",
    "disturbance_ratio": "ratio W/V",
    "l_over_d_max": "ratio",
    "n_max": "g",
    "mesh_tol": "relative",
    "classification_tol": "relative",
}
# Readable names for option names where the plain words are not enough.
CAPTION_NAMES: Mapping[str, str] = {
    "l_over_d": "(L/D) max",
    "n_max": "load factor max",
    "u_max": "turn rate max",
    "v_stall": "v stall",
    "polar_mass_kg": "polar mass",
    "polar_reference_mass_kg": "polar reference mass",
    "polar_wing_area_m2": "polar wing area",
    "polar_bugs_pct": "polar bugs",
    "polar_max_ballast_l": "polar max ballast",
}
