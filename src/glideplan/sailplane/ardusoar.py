"""ArduPilot soaring (ArduSoar) polar parameters fitted to a sailplane polar, and their file.

ArduSoar models the sink rate as sink(V, phi) = V (CD0 / CL + B CL / cos^2 phi) with
CL = K / V^2 and K = 2 m g / (rho S) (FORMATS.md), i.e. in level flight

    sink(V) = (CD0 / K) V^3 + (B K) / V,

linear in (CD0, B) once K is fixed by the mass m, the wing area S and sea-level density
rho = 1.225 kg/m^3. CD0 and B are fitted by linear least squares to the quadratic polar at
`samples` speeds spread evenly over its speed range [v_min, v_max]; the fit's worst absolute
sink error over those speeds is reported. The parameter file has one `NAME value` line per
parameter, as pymavlink's `mavparm.MAVParmDict.load` reads.
"""

from __future__ import annotations

import pathlib
from dataclasses import dataclass

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.validation import check_positive
from glideplan.vehicles.sailplane_polar import GRAVITY, SailplanePolar

__all__ = ["RHO_SEA_LEVEL", "ArduSoarFit", "ardusoar_sink", "fit_ardusoar", "write_parm"]

RHO_SEA_LEVEL = 1.225  # kg/m^3, ISA


@dataclass(frozen=True)
class ArduSoarFit:
    """SOAR_POLAR_CD0, SOAR_POLAR_B, SOAR_POLAR_K and the fit's worst sink error (m/s)."""

    cd0: float
    b: float
    k: float
    max_sink_error: float
    rms_sink_error: float
    speed_range: tuple[float, float]

    def params(self) -> dict[str, float]:
        return {"SOAR_POLAR_CD0": self.cd0, "SOAR_POLAR_B": self.b, "SOAR_POLAR_K": self.k}


def ardusoar_sink(
    speed: np.ndarray, cd0: float, b: float, k: float, bank: float | np.ndarray = 0.0
) -> np.ndarray:
    """ArduSoar's sink rate V (CD0 / CL + B CL / cos^2 phi), CL = K / V^2 (m/s)."""
    v = np.asarray(speed, dtype=float)
    cl = k / v**2
    return v * (cd0 / cl + b * cl / np.cos(bank) ** 2)


def fit_ardusoar(
    polar: SailplanePolar, wing_area_m2: float | None = None, *, samples: int = 200
) -> ArduSoarFit:
    """Least-squares CD0 and B for the polar at its mass; K = 2 m g / (rho S)."""
    area = wing_area_m2 if wing_area_m2 is not None else polar.wing_area_m2
    if area is None:
        raise InvalidParameterError(
            "wing area", None, "the polar file gives none: pass --wing-area (m^2)"
        )
    s = check_positive("wing area", area)
    k = 2.0 * polar.mass_kg * GRAVITY / (RHO_SEA_LEVEL * s)
    v = np.linspace(polar.v_min, polar.v_max, int(samples))
    w = polar.sink(v)
    A = np.stack([v**3 / k, k / v], axis=-1)
    (cd0, b), *_ = np.linalg.lstsq(A, w, rcond=None)
    err = A @ np.array([cd0, b]) - w
    if not (cd0 > 0.0 and b > 0.0):
        raise InvalidParameterError(
            "polar",
            polar.name,
            f"the ArduSoar fit gives CD0={cd0:.4g}, B={b:.4g}: both must be > 0",
        )
    return ArduSoarFit(
        cd0=float(cd0),
        b=float(b),
        k=float(k),
        max_sink_error=float(np.max(np.abs(err))),
        rms_sink_error=float(np.sqrt(np.mean(err**2))),
        speed_range=(float(v[0]), float(v[-1])),
    )


def write_parm(fit: ArduSoarFit, path: str | pathlib.Path, *, comment: str = "") -> None:
    """Write `NAME value` lines (and `#` comment lines) for ArduPilot / pymavlink."""
    lines = [f"# {line}" for line in comment.splitlines() if line.strip()]
    lines += [f"{name} {value:.8g}" for name, value in fit.params().items()]
    pathlib.Path(path).write_text("\n".join(lines) + "\n")
