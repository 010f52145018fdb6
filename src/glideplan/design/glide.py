"""Steady gliding performance from a parabolic drag polar: the spider plot (7.15-7.20; Fig 7.17).

Net weight W~ = |B - W| (N) drives the glide; gamma is the flight-path angle below the
horizontal (rad), u the forward (horizontal) speed and w the depth rate (m/s).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import minimize_scalar

from glideplan.design.gas import SEA_WATER, Environment
from glideplan.errors import InvalidParameterError
from glideplan.validation import check_fields, check_positive, scalar_or_array
from glideplan.validation import check_finite_array as finite_array
from glideplan.validation import check_positive_array as positive_array

__all__ = [
    "SEAGLIDER_LIKE",
    "DragPolar",
    "SpiderPlot",
    "angle_of_attack_rad",
    "glide_speed_m_s",
    "glide_velocity_m_s",
    "lift_coefficient",
    "max_forward_speed",
    "spider_plot",
]

_BRANCHES = ("low_lift", "high_lift")


@dataclass(frozen=True)
class DragPolar:
    """Parabolic drag polar C_D = C_D0 + K C_L^2, lift slope C_L_alpha (1/rad), area S (m^2)."""

    zero_lift_drag_coefficient: float = 0.002
    induced_drag_factor: float = 0.75
    lift_slope_per_rad: float = 0.2
    reference_area_m2: float = 3.24
    name: str = "custom"

    def __post_init__(self) -> None:
        check_fields(
            self,
            check_positive,
            (
                "zero_lift_drag_coefficient",
                "induced_drag_factor",
                "lift_slope_per_rad",
                "reference_area_m2",
            ),
        )
        if not isinstance(self.name, str):
            raise InvalidParameterError("name", self.name, "must be a string")

    @property
    def min_glide_angle_rad(self) -> float:
        """Shallowest glide gamma_min = atan(2 sqrt(K C_D0)) (after 7.19)."""
        return math.atan(
            2.0 * math.sqrt(self.induced_drag_factor * self.zero_lift_drag_coefficient)
        )


def _seaglider_like() -> DragPolar:
    # Eriksen et al. (2001) Seaglider model L = a alpha q l^2, D = (b q^-1/4 + c alpha^2) q l^2
    # (alpha in degrees) with typical a = 0.0036/deg, b = 0.0098, c = 9.8e-6/deg^2, l = 1.8 m,
    # rewritten as a parabolic polar on S = l^2 with q^-1/4 frozen at 1 m/s in sea water.
    # Techy et al. (2010a), the dissertation's source, is not available: this is a stand-in.
    a_per_rad = 0.0036 * 180.0 / math.pi
    c_per_rad2 = 9.8e-6 * (180.0 / math.pi) ** 2
    q_ref = 0.5 * 1025.0 * 1.0**2
    return DragPolar(
        zero_lift_drag_coefficient=0.0098 * q_ref**-0.25,
        induced_drag_factor=c_per_rad2 / a_per_rad**2,
        lift_slope_per_rad=a_per_rad,
        reference_area_m2=1.8**2,
        name="Seaglider-like (Eriksen et al. 2001 coefficients)",
    )


SEAGLIDER_LIKE = _seaglider_like()


def lift_coefficient(
    polar: DragPolar, gamma_rad: ArrayLike, branch: str = "low_lift"
) -> np.ndarray | float:
    """C_L(gamma) from tan gamma = (C_D0 + K C_L^2) / C_L (7.19), for gamma in [gamma_min, pi/2].

    `branch="low_lift"` is the fast root [tan g - sqrt(tan^2 g - 4 K C_D0)] / (2K) (C_L -> 0 in a
    vertical dive); `"high_lift"` the slow root with the + sign.
    """
    if branch not in _BRANCHES:
        raise InvalidParameterError("branch", branch, f"must be one of {_BRANCHES}")
    g = finite_array("gamma_rad", gamma_rad)
    g_min = polar.min_glide_angle_rad
    if np.any(g < g_min * (1.0 - 1e-12)) or np.any(g > math.pi / 2):
        raise InvalidParameterError(
            "gamma_rad",
            float(np.min(g)) if np.any(g < g_min) else float(np.max(g)),
            f"must lie in [gamma_min={g_min:.6g}, pi/2] (no real C_L outside)",
        )
    k, cd0 = polar.induced_drag_factor, polar.zero_lift_drag_coefficient
    cos_g, sin_g = np.cos(g), np.sin(g)
    # (7.19) times cos g stays finite at pi/2: K C_L^2 cos g - C_L sin g + C_D0 cos g = 0.
    disc = np.sqrt(np.maximum(sin_g**2 - 4.0 * k * cd0 * cos_g**2, 0.0))
    if branch == "low_lift":
        cl = 2.0 * cd0 * cos_g / (sin_g + disc)  # rationalised: no cancellation
    else:
        cl = (sin_g + disc) / (2.0 * k * cos_g)  # unbounded as gamma -> pi/2 (stall side)
    return scalar_or_array(cl)


def angle_of_attack_rad(polar: DragPolar, lift_coefficient_value: ArrayLike) -> np.ndarray | float:
    """Angle of attack alpha = C_L / C_L_alpha (rad) for the linear lift curve."""
    cl = finite_array("lift_coefficient", lift_coefficient_value)
    return scalar_or_array(cl / polar.lift_slope_per_rad)


def glide_speed_m_s(
    polar: DragPolar,
    gamma_rad: ArrayLike,
    net_weight: ArrayLike,
    environment: Environment = SEA_WATER,
    branch: str = "low_lift",
) -> np.ndarray | float:
    """Steady glide speed V (m/s) for flight-path angle gamma and net weight W~ (N) (7.15, 7.20).

    Uses the drag balance D = W~ sin gamma, V = sqrt(2 W~ sin g / (rho S (C_D0 + K C_L^2))),
    which equals (7.20), V = sqrt(2 W~ cos g / (rho S C_L)), and stays finite at gamma = pi/2.
    """
    w = positive_array("net_weight", net_weight)
    cl = np.asarray(lift_coefficient(polar, gamma_rad, branch))
    g = np.asarray(gamma_rad, dtype=float)
    cd = polar.zero_lift_drag_coefficient + polar.induced_drag_factor * cl**2
    rho_s = environment.water_density_kg_m3 * polar.reference_area_m2
    return scalar_or_array(np.sqrt(2.0 * w * np.sin(g) / (rho_s * cd)))


def glide_velocity_m_s(
    polar: DragPolar,
    gamma_rad: ArrayLike,
    net_weight: ArrayLike,
    environment: Environment = SEA_WATER,
    branch: str = "low_lift",
) -> tuple[np.ndarray | float, np.ndarray | float]:
    """Forward speed u = V cos gamma and depth rate w = V sin gamma (m/s) (7.17, 7.18, 7.20)."""
    v = np.asarray(glide_speed_m_s(polar, gamma_rad, net_weight, environment, branch))
    g = np.asarray(gamma_rad, dtype=float)
    return scalar_or_array(v * np.cos(g)), scalar_or_array(v * np.sin(g))


def max_forward_speed(
    polar: DragPolar, net_weight: float, environment: Environment = SEA_WATER
) -> tuple[float, float]:
    """Top forward speed u_max (m/s) and its flight-path angle (rad), low-lift branch (7.20)."""
    w = check_positive("net_weight", net_weight)
    g_min = polar.min_glide_angle_rad

    def neg_u(g: float) -> float:
        return -float(glide_velocity_m_s(polar, g, w, environment)[0])

    res = minimize_scalar(
        neg_u, bounds=(g_min, math.pi / 2), method="bounded", options={"xatol": 1e-10}
    )
    return -float(res.fun), float(res.x)


@dataclass(frozen=True)
class SpiderPlot:
    """Spider-plot data (Fig 7.17): speed curves per net buoyancy plus constant-gamma/alpha lines.

    `forward_m_s[i, j]`, `depth_rate_m_s[i, j]` for volume i and gamma_sweep j; the constant
    lines map each angle (rad) to `(forward_m_s, depth_rate_m_s)` arrays over the volumes.
    """

    volumes_m3: np.ndarray
    gamma_sweep_rad: np.ndarray
    forward_m_s: np.ndarray
    depth_rate_m_s: np.ndarray
    gamma_lines: dict[float, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict)
    alpha_lines: dict[float, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict)


def spider_plot(
    polar: DragPolar,
    volumes_m3: ArrayLike,
    environment: Environment = SEA_WATER,
    *,
    gammas_rad: ArrayLike = (),
    alphas_rad: ArrayLike = (),
    num: int = 200,
) -> SpiderPlot:
    """Forward speed vs depth rate, gamma in [gamma_min, pi/2], per net buoyancy volume (7.20).

    `volumes_m3` are net buoyancy volumes |V - V_neutral| (W~ = rho g V). Constant-alpha
    lines use C_L = C_L_alpha alpha, hence a fixed gamma from (7.19): for a parabolic polar
    they are straight lines through the origin, like the constant-gamma lines.
    """
    v = positive_array("volumes_m3", volumes_m3).ravel()
    if int(num) < 2:
        raise InvalidParameterError("num", num, "must be >= 2")
    w = environment.specific_weight_n_m3 * v
    g = np.linspace(polar.min_glide_angle_rad, math.pi / 2, int(num))
    u, d = glide_velocity_m_s(polar, g[None, :], w[:, None], environment)
    gamma_lines = {}
    for gl in finite_array("gammas_rad", gammas_rad).ravel():
        ul, dl = glide_velocity_m_s(polar, np.full(v.shape, gl), w, environment)
        gamma_lines[float(gl)] = (np.asarray(ul), np.asarray(dl))
    alpha_lines = {}
    rho_s = environment.water_density_kg_m3 * polar.reference_area_m2
    for al in positive_array("alphas_rad", alphas_rad).ravel():
        cl = polar.lift_slope_per_rad * float(al)
        ga = math.atan((polar.zero_lift_drag_coefficient + polar.induced_drag_factor * cl**2) / cl)
        speed = np.sqrt(2.0 * w * math.cos(ga) / (rho_s * cl))  # (7.20)
        alpha_lines[float(al)] = (speed * math.cos(ga), speed * math.sin(ga))
    return SpiderPlot(v, g, np.asarray(u), np.asarray(d), gamma_lines, alpha_lines)
