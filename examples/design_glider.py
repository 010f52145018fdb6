"""Size a pneumatic underwater glider the way chapter 7 of Wolek (2015) does.

Run:  python examples/design_glider.py
Writes `my_glider.toml` (edit it and pass it to `glideplan design ... --params`) into
$GLIDEPLAN_OUT or the current directory.
"""

import math
import os
import pathlib

import numpy as np

from glideplan import design
from glideplan.units import litre_to_m3, pa_to_psi, psi_to_pa

out = pathlib.Path(os.environ.get("GLIDEPLAN_OUT", "."))
env = design.FRESH_WATER

# 1. How much air is in the scuba tank, and how many 5 L dives to 100 m does it give?
tank = design.FX23DV
print(f"{tank.name}: {tank.moles(env.temperature_k):.1f} mol of air at {env.temperature_k} K")
for v_l, z in [(5, 100), (3, 100), (5, 50)]:
    n = design.number_of_dives(tank, litre_to_m3(v_l), z, env)
    print(f"  {v_l} L at {z:3d} m: {n:5.1f} dives (ideal gas, fresh water)")

# 2. How fast does the glider sink or rise, and what valve does that need (C_D = 0.1)?
bladder, hull = design.VTUG_BLADDER, design.VTUG_HULL
v, zdot, ndot = design.exchange_rate_sweep(bladder, hull, env)
print(f"fastest ascent {-zdot.min():.2f} m/s needs {-ndot.min():.3f} mol/s exhausted")
cv_def = design.deflator_cv(bladder, hull, 5e-3, 100.0, env)
cv_inf = np.max(design.inflator_cv(bladder, hull, np.linspace(0, 2.4e-3, 25), psi_to_pa(500.0)))
print(f"deflator C_v at 5 L, 100 m: {cv_def:.2f}; inflator C_v at 500 psia: {cv_inf:.4f}")

# 3. Pitch range of the moving mass with the bladder at neutral.
aft, fwd = design.pitch_range_rad(design.VTUG_TRIM, bladder.neutral_volume_m3, env)
print(f"pitch range: {math.degrees(fwd):+.0f} .. {math.degrees(aft):+.0f} deg")

# 4. Glide performance of a Seaglider-like hull with +-2.5 L.
sea = design.SEA_WATER
u, g = design.max_forward_speed(design.SEAGLIDER_LIKE, sea.specific_weight_n_m3 * 2.5e-3, sea)
print(f"top forward speed {u:.2f} m/s at a {math.degrees(g):.0f} deg glide (dissertation: ~1.75)")

# 5. Acoustic positioning: a lawn-mower survey with 3 beacons and 75 % ping replies.
cfg = design.LBLConfig(range_noise_std_m=3.0, ping_success_probability=0.75)
track = design.lawnmower_track((300.0, 900.0), (500.0, 900.0), swaths=7, step_m=5.0)
stats = design.simulate_survey(cfg, track, rng=np.random.default_rng(0)).statistics
print(
    f"LBL: {100 * stats.ping_success_fraction:.0f} % replies, {stats.fixes} fixes, "
    f"mean error {stats.mean_error_m:.1f} m"
)

# 6. Save the whole parameter set (with a bigger 4 L bladder) for the CLI.
params = design.DesignParameters(bladder=design.Bladder(max_volume_m3=4e-3, neutral_volume_m3=2e-3))
path = design.save_parameters(params, out / "my_glider.toml")
print(f"wrote {path}; try: glideplan design dives --params {path.name}")
print(f"(tank pressure {pa_to_psi(tank.max_pressure_pa):.0f} psi)")
