"""Valve flow coefficient C_v for the inflator and deflator from the gas-flow formula (7.8).

(7.8) is the Swagelok form in US customary units: q in standard ft^3/min (60 degF, 14.696
psia), pressures in psia, temperature in degR, N = 22.67. The flow is choked when the outlet
pressure falls below half the inlet pressure; then q = 0.471 N C_v p1 sqrt(1 / (G T1)), the
value (7.8) reaches at dp = p1 / 2. The SI wrappers convert at the edge.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from glideplan.design.buoyancy import (
    Bladder,
    Hull,
    air_exchange_rate_mol_s,
    terminal_depth_rate_m_s,
)
from glideplan.design.gas import FRESH_WATER, R_GAS_J_PER_MOL_K, Environment
from glideplan.errors import InvalidParameterError
from glideplan.units import pa_to_psi
from glideplan.validation import check_finite_array as finite_array
from glideplan.validation import check_nonnegative_array as nonnegative_array
from glideplan.validation import check_positive, scalar_or_array
from glideplan.validation import check_positive_array as positive_array

__all__ = [
    "ASSUMED_BLADDER_CURVE_NOTE",
    "N_SWAGELOK",
    "STANDARD_PRESSURE_PA",
    "STANDARD_TEMPERATURE_K",
    "deflator_cv",
    "flow_coefficient",
    "gas_flow_scfm",
    "inflator_cv",
    "kelvin_to_rankine",
    "molar_flow_to_scfm",
    "required_cv",
    "scfm_to_molar_flow",
]

ASSUMED_BLADDER_CURVE_NOTE = (
    "the bladder pressure curve p_blad(V) is assumed (unpublished; Fig 7.5b gives only its "
    "shape): valve sizes that depend on it (the deflator's dp = p_blad(V), the inflator's "
    "p2 = p_amb + p_blad(V)) are illustrative"
)
"""Say this wherever a result uses `Bladder.elastic_pressure_pa` (the default curve)."""
N_SWAGELOK = 22.67  # (7.8): q in std ft^3/min, p in psia, T in degR
STANDARD_TEMPERATURE_K = 288.7056  # 60 degF
STANDARD_PRESSURE_PA = 101_325.0  # 14.696 psia
_FT3_M3 = 0.0254**3 * 1728.0
_CHOKE_FACTOR = (2.0 / 3.0) * np.sqrt(0.5)  # (1 - 2/3 * 1/2) sqrt(1/2) = 0.4714
_MODES = ("auto", "never")


def kelvin_to_rankine(t_k: ArrayLike) -> np.ndarray | float:
    """Absolute temperature in K to degR (x 1.8)."""
    return scalar_or_array(positive_array("temperature_k", t_k) * 1.8)


def molar_flow_to_scfm(ndot_mol_s: ArrayLike) -> np.ndarray | float:
    """Molar flow (mol/s) to standard ft^3/min at 60 degF and 14.696 psia (q = n M / rho_std)."""
    ndot = finite_array("ndot_mol_s", ndot_mol_s)
    v_m3 = R_GAS_J_PER_MOL_K * STANDARD_TEMPERATURE_K / STANDARD_PRESSURE_PA  # m^3/mol
    return scalar_or_array(ndot * v_m3 / _FT3_M3 * 60.0)


def scfm_to_molar_flow(q_scfm: ArrayLike) -> np.ndarray | float:
    """Standard ft^3/min (60 degF, 14.696 psia) to molar flow in mol/s."""
    q = finite_array("q_scfm", q_scfm)
    v_m3 = R_GAS_J_PER_MOL_K * STANDARD_TEMPERATURE_K / STANDARD_PRESSURE_PA
    return scalar_or_array(q / 60.0 * _FT3_M3 / v_m3)


def _pressure_factor(p1: np.ndarray, p2: np.ndarray, sg: np.ndarray, t1: np.ndarray, choked: str):
    """q / (N C_v) in (7.8) (psia, degR); choked branch past p2 < p1/2 when `choked='auto'`."""
    dp = p1 - p2
    subsonic = p1 * (1.0 - 2.0 * dp / (3.0 * p1)) * np.sqrt(dp / (p1 * sg * t1))
    if choked == "never":
        return subsonic
    return np.where(p2 < 0.5 * p1, _CHOKE_FACTOR * p1 / np.sqrt(sg * t1), subsonic)


def _flow_factor(
    inlet_pressure_psia: ArrayLike,
    outlet_pressure_psia: ArrayLike,
    temperature_rankine: ArrayLike,
    specific_gravity: float,
    choked: str,
) -> np.ndarray:
    """q / (N C_v) of (7.8) after checking pressures (psia), temperature (degR), sg and mode."""
    p1, p2 = _check_pressures(inlet_pressure_psia, outlet_pressure_psia, "psia")
    t1 = positive_array("temperature_rankine", temperature_rankine)
    sg = check_positive("specific_gravity", specific_gravity)
    return _pressure_factor(p1, p2, np.asarray(sg), t1, _check_mode(choked))


def _check_mode(choked: str) -> str:
    if choked not in _MODES:
        raise InvalidParameterError("choked", choked, f"must be one of {', '.join(_MODES)}")
    return choked


def _check_pressures(p1: ArrayLike, p2: ArrayLike, unit: str) -> tuple[np.ndarray, np.ndarray]:
    a = positive_array(f"inlet_pressure_{unit}", p1)
    b = positive_array(f"outlet_pressure_{unit}", p2)
    a, b = np.broadcast_arrays(a, b)
    if np.any(a <= b):
        bad = float(a[a <= b].flat[0])
        raise InvalidParameterError(
            f"inlet_pressure_{unit}",
            bad,
            f"must exceed outlet_pressure_{unit} (no flow otherwise)",
        )
    return a, b


def gas_flow_scfm(
    cv: ArrayLike,
    inlet_pressure_psia: ArrayLike,
    outlet_pressure_psia: ArrayLike,
    temperature_rankine: ArrayLike,
    specific_gravity: float = 1.0,
    *,
    choked: str = "auto",
) -> np.ndarray | float:
    """Gas flow q (std ft^3/min) through a valve of coefficient C_v (7.8; choked when p2 < p1/2).

    `choked="never"` applies (7.8) as printed even past the choking point.
    """
    c = positive_array("cv", cv)
    f = _flow_factor(
        inlet_pressure_psia, outlet_pressure_psia, temperature_rankine, specific_gravity, choked
    )
    return scalar_or_array(N_SWAGELOK * c * f)


def flow_coefficient(
    q_scfm: ArrayLike,
    inlet_pressure_psia: ArrayLike,
    outlet_pressure_psia: ArrayLike,
    temperature_rankine: ArrayLike,
    specific_gravity: float = 1.0,
    *,
    choked: str = "auto",
) -> np.ndarray | float:
    """Valve flow coefficient C_v that passes q std ft^3/min: (7.8) solved for C_v."""
    q = finite_array("q_scfm", q_scfm)
    if np.any(q < 0.0):
        raise InvalidParameterError("q_scfm", float(np.min(q)), "must be >= 0")
    f = _flow_factor(
        inlet_pressure_psia, outlet_pressure_psia, temperature_rankine, specific_gravity, choked
    )
    return scalar_or_array(q / (N_SWAGELOK * f))


def required_cv(
    ndot_mol_s: ArrayLike,
    inlet_pressure_pa: ArrayLike,
    outlet_pressure_pa: ArrayLike,
    temperature_k: ArrayLike,
    specific_gravity: float = 1.0,
    *,
    choked: str = "auto",
) -> np.ndarray | float:
    """C_v for a molar air flow (sign ignored) between absolute pressures; mol/s, Pa, K (7.8)."""
    ndot = np.abs(finite_array("ndot_mol_s", ndot_mol_s))
    p1, p2 = _check_pressures(inlet_pressure_pa, outlet_pressure_pa, "pa")
    return flow_coefficient(
        molar_flow_to_scfm(ndot),
        pa_to_psi(p1),
        pa_to_psi(p2),
        kelvin_to_rankine(temperature_k),
        specific_gravity,
        choked=choked,
    )


def _hold_rate_mol_s(
    bladder: Bladder, hull: Hull, volume_m3: np.ndarray, environment: Environment, cd: float | None
) -> np.ndarray:
    """|ndot| (7.6) at the terminal depth rate (7.7) for net weight rho g (V - V_neutral)."""
    c = hull.drag_coefficient if cd is None else cd
    w = bladder.net_weight_n(volume_m3, environment)
    zdot = terminal_depth_rate_m_s(w, hull.cross_section_m2, c, environment)
    return np.abs(np.asarray(air_exchange_rate_mol_s(volume_m3, zdot, environment)))


def deflator_cv(
    bladder: Bladder,
    hull: Hull,
    volume_m3: ArrayLike,
    depth_m: ArrayLike,
    environment: Environment = FRESH_WATER,
    *,
    drag_coefficient: float | None = None,
    choked: str = "auto",
) -> np.ndarray | float:
    """Deflator C_v that holds V during the fastest ascent at depth z (7.6-7.8; Fig 7.8a).

    Inlet p1 = p_amb + p_blad(V), outlet p2 = p_amb (dp = p_blad(V)); V must exceed the neutral
    volume (the glider rises) and p_blad(V) must be > 0.
    """
    v = positive_array("volume_m3", volume_m3)
    if np.any(v <= bladder.neutral_volume_m3):
        raise InvalidParameterError(
            "volume_m3",
            float(np.min(v)),
            f"must exceed neutral_volume_m3={bladder.neutral_volume_m3:g} (ascent)",
        )
    p2 = np.asarray(environment.ambient_pressure_pa(depth_m))
    p1 = p2 + np.asarray(bladder.elastic_pressure_pa(v))
    ndot = _hold_rate_mol_s(bladder, hull, v, environment, drag_coefficient)
    return required_cv(ndot, p1, p2, environment.temperature_k, choked=choked)


def inflator_cv(
    bladder: Bladder,
    hull: Hull,
    volume_m3: ArrayLike,
    tank_pressure_pa: ArrayLike,
    environment: Environment = FRESH_WATER,
    *,
    depth_m: float = 0.0,
    drag_coefficient: float | None = None,
    choked: str = "auto",
) -> np.ndarray | float:
    """Inflator C_v from the tank that holds V during the fastest descent (7.6-7.8; Fig 7.8b).

    Inlet p1 = tank pressure, outlet p2 = p_amb(depth) + p_blad(V) (the depth hardly matters:
    p1 >> p2). Raises `InvalidParameterError` if the tank pressure does not exceed p2.
    `choked="never"` reproduces the dissertation's use of (7.8) without the choked branch.
    """
    v = nonnegative_array("volume_m3", volume_m3)
    if np.any(v >= bladder.neutral_volume_m3):
        raise InvalidParameterError(
            "volume_m3",
            float(np.max(v)),
            f"must be < neutral_volume_m3={bladder.neutral_volume_m3:g} (descent)",
        )
    p2 = np.asarray(environment.ambient_pressure_pa(depth_m)) + np.asarray(
        bladder.elastic_pressure_pa(v)
    )
    p1 = positive_array("tank_pressure_pa", tank_pressure_pa)
    if np.any(p1 <= np.max(p2)):
        raise InvalidParameterError(
            "tank_pressure_pa",
            float(np.min(p1)),
            f"must exceed the bladder pressure {float(np.max(p2)):.4g} Pa (cannot inflate)",
        )
    ndot = _hold_rate_mol_s(bladder, hull, v, environment, drag_coefficient)
    return required_cv(ndot, p1, p2, environment.temperature_k, choked=choked)
