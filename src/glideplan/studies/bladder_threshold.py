"""The open-loop bladder threshold of Fig 7.6 and the elastic curve it would need (section 7.2).

The dissertation states that bladders holding more than about 0.8 L at 100 m expand to 5 L
before the surface. With an elastic curve p_blad(V), the threshold is the volume at 100 m of
the air that fills the bladder to V_max at the surface (7.5). Its fitted curve (Fig 7.5b) is
unpublished, so glideplan's curve is assumed; `elastic_scale_for_threshold` finds the factor
on that curve's coefficients that reproduces a stated threshold (a root of one equation).
"""

from __future__ import annotations

from glideplan.design import Bladder, Environment, bladder_moles, equilibrium_volume_m3

__all__ = ["elastic_scale_for_threshold", "scaled", "threshold_volume_m3"]


def threshold_volume_m3(
    bladder: Bladder, environment: Environment, depth_m: float = 100.0
) -> float:
    """Largest volume at `depth_m` whose air stays below V_max at the surface (m^3)."""
    n_surface_full = float(bladder_moles(bladder, bladder.max_volume_m3, 0.0, environment))
    return float(equilibrium_volume_m3(bladder, n_surface_full, depth_m, environment))


def scaled(bladder: Bladder, factor: float) -> Bladder:
    """The bladder with its elastic coefficients multiplied by `factor`."""
    return Bladder(
        bladder.max_volume_m3,
        bladder.neutral_volume_m3,
        tuple(factor * c for c in bladder.elastic_coefficients_pa),
    )


def elastic_scale_for_threshold(
    bladder: Bladder,
    environment: Environment,
    target_m3: float,
    bracket: tuple[float, float] = (1.0, 100.0),
) -> float | None:
    """Factor k on the elastic coefficients giving `threshold_volume_m3 = target_m3` (brentq
    in `bracket`), or None when the bracket holds no root."""
    from scipy.optimize import brentq

    def gap(k: float) -> float:
        return threshold_volume_m3(scaled(bladder, k), environment) - target_m3

    lo, hi = bracket
    if gap(lo) * gap(hi) > 0.0:
        return None
    return float(brentq(gap, lo, hi))
