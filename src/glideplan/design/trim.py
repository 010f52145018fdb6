"""Static pitch trim with a translating moving mass: CG, CB and equilibrium pitch (7.9-7.14).

Sign convention (the extracted (7.9), (7.10) and (7.13) mix signs; one convention is used
here): stations l are measured forward from the tail (m); weights act down and buoyancies up,
both given as positive magnitudes; the moving mass hangs z_MM > 0 below the centreline; the
pitch angle theta is positive nose-up. Lift and drag are neglected, as in section 7.3.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from glideplan.design.gas import FRESH_WATER, Environment
from glideplan.errors import InvalidParameterError
from glideplan.validation import (
    check_fields,
    check_finite,
    check_nonnegative,
    check_positive,
    scalar_or_array,
)
from glideplan.validation import check_finite_array as finite_array
from glideplan.validation import check_nonnegative_array as nonnegative_array

__all__ = [
    "VTUG_TRIM",
    "TrimLayout",
    "centre_of_buoyancy_m",
    "centre_of_gravity_m",
    "equilibrium_pitch_rad",
    "net_vertical_force_n",
    "pitch_range_rad",
]

_REFERENCES = ("centre_of_buoyancy", "tail")


@dataclass(frozen=True)
class TrimLayout:
    """Masses, displaced volumes and their stations (m from the tail) for pitch trim (Fig 7.12)."""

    moving_mass_kg: float = 10.0
    moving_mass_offset_m: float = 0.05
    moving_mass_min_station_m: float = 0.80
    moving_mass_max_station_m: float = 1.00
    tank_mass_kg: float = 4.8
    tank_station_m: float = 0.95
    body_mass_kg: float = 35.2
    body_station_m: float = 1.0104
    body_volume_m3: float = 0.0475
    body_buoyancy_station_m: float = 0.95
    bladder_station_m: float = 1.60

    def __post_init__(self) -> None:
        check_fields(
            self, check_positive, ("moving_mass_kg", "moving_mass_offset_m", "body_volume_m3")
        )
        check_fields(self, check_nonnegative, ("tank_mass_kg", "body_mass_kg"))
        check_fields(
            self,
            check_finite,
            (
                "moving_mass_min_station_m",
                "moving_mass_max_station_m",
                "tank_station_m",
                "body_station_m",
                "body_buoyancy_station_m",
                "bladder_station_m",
            ),
        )
        if self.moving_mass_min_station_m > self.moving_mass_max_station_m:
            raise InvalidParameterError(
                "moving_mass_min_station_m",
                self.moving_mass_min_station_m,
                f"must be <= moving_mass_max_station_m={self.moving_mass_max_station_m:g}",
            )

    @property
    def total_mass_kg(self) -> float:
        """W_MM + W_T + W_RB over g (kg)."""
        return self.moving_mass_kg + self.tank_mass_kg + self.body_mass_kg


# Illustrative VTUG-like layout (about 50 kg, 1.9 m body). The dissertation gives no mass
# breakdown; these values only make the example glider neutral at 2.5 L of bladder.
VTUG_TRIM = TrimLayout()


def centre_of_gravity_m(
    layout: TrimLayout, moving_mass_station_m: ArrayLike, tank_mass_kg: ArrayLike | None = None
) -> tuple[np.ndarray | float, float | np.ndarray]:
    """Centre of gravity (CG_x, CG_z) in m from the tail and below the centreline (7.11, 7.12)."""
    l_mm = finite_array("moving_mass_station_m", moving_mass_station_m)
    m_t = (
        layout.tank_mass_kg
        if tank_mass_kg is None
        else nonnegative_array("tank_mass_kg", tank_mass_kg)
    )
    m_tot = layout.moving_mass_kg + m_t + layout.body_mass_kg
    mx = (
        l_mm * layout.moving_mass_kg
        + layout.tank_station_m * m_t
        + layout.body_station_m * layout.body_mass_kg
    )
    cgx = mx / m_tot
    cgz = layout.moving_mass_offset_m * layout.moving_mass_kg / m_tot
    return scalar_or_array(np.asarray(cgx)), scalar_or_array(np.asarray(cgz))


def centre_of_buoyancy_m(layout: TrimLayout, bladder_volume_m3: ArrayLike) -> np.ndarray | float:
    """Centre of buoyancy CB_x in m from the tail (7.13; CB_z = 0 by 7.14).

    CB_x = (l_RB B_RB + l_BE B_BE) / (B_RB + B_BE); the extracted (7.13) has W_BE for B_BE.
    The water density cancels, so volumes stand in for buoyancies.
    """
    v = nonnegative_array("bladder_volume_m3", bladder_volume_m3)
    num = layout.body_buoyancy_station_m * layout.body_volume_m3 + layout.bladder_station_m * v
    return scalar_or_array(num / (layout.body_volume_m3 + v))


def net_vertical_force_n(
    layout: TrimLayout,
    bladder_volume_m3: ArrayLike,
    environment: Environment = FRESH_WATER,
    tank_mass_kg: ArrayLike | None = None,
) -> np.ndarray | float:
    """Residual of (7.9): buoyancy minus weight, B_RB + B_BE - (W_MM + W_T + W_RB), in N."""
    v = nonnegative_array("bladder_volume_m3", bladder_volume_m3)
    m_t = (
        layout.tank_mass_kg
        if tank_mass_kg is None
        else nonnegative_array("tank_mass_kg", tank_mass_kg)
    )
    g = environment.gravity_m_s2
    b = environment.specific_weight_n_m3 * (layout.body_volume_m3 + v)
    w = (layout.moving_mass_kg + m_t + layout.body_mass_kg) * g
    return scalar_or_array(np.asarray(b - w))


def equilibrium_pitch_rad(
    layout: TrimLayout,
    moving_mass_station_m: ArrayLike,
    bladder_volume_m3: ArrayLike,
    environment: Environment = FRESH_WATER,
    *,
    tank_mass_kg: ArrayLike | None = None,
    reference: str = "centre_of_buoyancy",
) -> np.ndarray | float:
    """Equilibrium pitch angle theta (rad, + nose-up) for a moving-mass station (7.10-7.14).

    Moments about the tail of the weights and buoyancies, divided by cos(theta), give (7.10):
    (l_MM + z_MM tan theta) W_MM + l_T W_T + l_RB W_RB - l_B B_RB - l_BE B_BE = 0.
    `reference="tail"` solves (7.10) as printed. The default takes moments about the centre
    of buoyancy (the net weight, carried by lift and drag, is assumed to act there), which
    gives tan theta = (CB_x - CG_x) / CG_z and agrees with (7.10) whenever (7.9) holds.
    """
    if reference not in _REFERENCES:
        raise InvalidParameterError("reference", reference, f"must be one of {_REFERENCES}")
    l_mm = finite_array("moving_mass_station_m", moving_mass_station_m)
    v = nonnegative_array("bladder_volume_m3", bladder_volume_m3)
    if reference == "centre_of_buoyancy":
        cgx, cgz = centre_of_gravity_m(layout, l_mm, tank_mass_kg)
        cbx = centre_of_buoyancy_m(layout, v)
        return scalar_or_array(np.arctan2(np.asarray(cbx) - cgx, cgz))
    m_t = (
        layout.tank_mass_kg
        if tank_mass_kg is None
        else nonnegative_array("tank_mass_kg", tank_mass_kg)
    )
    rho = environment.water_density_kg_m3
    # Moments in kg m (g cancels): weights +, buoyancies -.
    moment = (
        l_mm * layout.moving_mass_kg
        + layout.tank_station_m * m_t
        + layout.body_station_m * layout.body_mass_kg
        - layout.body_buoyancy_station_m * rho * layout.body_volume_m3
        - layout.bladder_station_m * rho * v
    )
    return scalar_or_array(
        np.arctan(-moment / (layout.moving_mass_offset_m * layout.moving_mass_kg))
    )


def pitch_range_rad(
    layout: TrimLayout,
    bladder_volume_m3: ArrayLike,
    environment: Environment = FRESH_WATER,
    *,
    tank_mass_kg: ArrayLike | None = None,
) -> tuple[np.ndarray | float, np.ndarray | float]:
    """Pitch angles (rad) at the aft and forward ends of the moving-mass travel (section 7.3)."""
    aft = equilibrium_pitch_rad(
        layout,
        layout.moving_mass_min_station_m,
        bladder_volume_m3,
        environment,
        tank_mass_kg=tank_mass_kg,
    )
    fwd = equilibrium_pitch_rad(
        layout,
        layout.moving_mass_max_station_m,
        bladder_volume_m3,
        environment,
        tank_mass_kg=tank_mass_kg,
    )
    return aft, fwd
