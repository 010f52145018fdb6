"""Chapter 7 `reproduce` figures: the numbers in their rows, checked by hand computations.

Reference values are hand computations from the printed inputs (Table 7.3: 3,442 psi,
183 in^3; Table 7.2: +-2,500 cc in 10 s; fresh water at 293.15 K) and closed forms; each
tolerance follows from the arithmetic (floating point) or the figure's grid step.
"""

import math

import pytest

from glideplan.figures import get_figure, load_all, run_figure

IDS = ["fig7.3", "fig7.4", "fig7.6", "fig7.7", "fig7.8", "fig7.17", "fig7.27"]
PSI = 6894.757293168361
R = 8.314  # J/(mol K), as printed with (7.1)
P_TANK = 3442 * PSI
V_TANK = 183 * 0.0254**3


@pytest.fixture(scope="module")
def reports(tmp_path_factory):
    load_all()
    out = tmp_path_factory.mktemp("ch7")
    return out, {fid: run_figure(get_figure(fid), out) for fid in IDS}


def rows(reports, fid):
    return {r.quantity: r for r in reports[1][fid].rows}


def test_every_figure_writes_its_png(reports):
    out, reps = reports
    for fid, rep in reps.items():
        assert rep.files == (fid.replace(".", "_") + ".png",)
        assert (out / rep.files[0]).read_bytes()[:4] == b"\x89PNG"


def test_fig7_3_tank_air_and_the_temperature_31_1_mol_needs(reports):
    from glideplan.design import FRESH_WATER

    r = rows(reports, "fig7.3")
    t = FRESH_WATER.temperature_k
    n_room = P_TANK * V_TANK / (R * t)  # (7.1) by hand: 29.2 mol
    row = r["air in the FX23DV tank (3442 psi, 183 in^3) at room temperature"]
    assert row.ours == pytest.approx(n_room, rel=1e-6)
    assert row.verdict == "differs" and row.dissertation == 31.1 and row.tolerance == 0.05
    t_311 = P_TANK * V_TANK / (R * 31.1)  # the temperature that gives 31.1 mol
    assert f"{t_311:.1f} K" in row.note and t_311 == pytest.approx(275.2, abs=0.05)


def test_fig7_3_dives_and_table_7_1(reports):
    from glideplan.design import FRESH_WATER

    r = rows(reports, "fig7.3")

    def dives(v_l, z):  # N = p_t V_t / (p_amb V), independent of T
        return P_TANK * V_TANK / (float(FRESH_WATER.ambient_pressure_pa(z)) * v_l * 1e-3)

    row = r["dives at 5 L, 100 m (fresh water)"]
    assert row.ours == pytest.approx(dives(5, 100), rel=1e-9) and row.verdict == "agrees"
    assert row.ours == pytest.approx(13.15, abs=0.01)
    for (v_l, z), printed in (((5, 100), 11), ((3, 100), 21), ((5, 50), 19), ((3, 50), 35)):
        row = r[f"Table 7.1 dives to {z:g} m at {v_l:g} L (ideal)"]
        assert row.ours == pytest.approx(dives(v_l, z), rel=1e-9)
        assert row.dissertation == printed and row.verdict == "differs"


def test_fig7_3_transfer_rate_and_piston_force(reports):
    r = rows(reports, "fig7.3")
    rate = r["buoyancy transfer rate, -2,500 to +2,500 cc in 10 s"]
    assert rate.ours == 500.0 and rate.dissertation == 167.0 and rate.verdict == "differs"
    assert "1.67 L" in rate.note  # 167 cc/s x 10 s, computed in the figure
    force = r["force on an 8 in piston face at 100 m exceeds 8,000 lbf"]
    area = math.pi * (8 * 0.0254) ** 2 / 4
    from glideplan.design import SEA_WATER

    p100 = float(SEA_WATER.ambient_pressure_pa(100.0))  # absolute
    assert force.ours == ("yes" if p100 * area / 4.4482216152605 > 8000 else "no")


def test_fig7_4_symmetry_and_air_weight(reports):
    r = rows(reports, "fig7.4")
    assert r["tank air weight, full (31.1 mol)"].ours == pytest.approx(
        31.1 * 0.02897 / 0.45359237, rel=1e-9
    )
    assert r["net weight, full tank, 0 L + 5 L (symmetry)"].ours == pytest.approx(0.0, abs=1e-9)
    # empty tank: +2.5 L of water (5.5 lb) plus the air weight (2 lb) = 7.5 lb
    assert r["net weight, empty tank, 5 L"].ours == pytest.approx(7.50, abs=0.01)


def test_fig7_6_contour_and_threshold(reports):
    r = rows(reports, "fig7.6")
    assert r["highest 0.2-mol contour level below n(5 L, 100 m)"].verdict == "agrees"
    thr = r["smallest V at 100 m that reaches 5 L before the surface"]
    assert 0.0 < thr.ours < 5.0 and "assumed" in thr.note
    assert "assumed" in reports[1]["fig7.6"].notes


def test_fig7_7_peak_inflation_at_two_thirds_of_neutral(reports):
    """ndot ~ (1 - s) sqrt(s) with s the deflated fraction: largest at s = 1/3, i.e. at
    2/3 of the neutral 2.5 L; the figure samples 401 volumes (step 0.0125 L)."""
    r = rows(reports, "fig7.7")
    peak = r["bladder volume at the peak inflation rate"]
    assert peak.ours == pytest.approx(2.5 * 2 / 3, abs=0.0125)
    assert all(row.verdict == "agrees" for q, row in r.items() if "within" in q or "peaks" in q)


def test_fig7_8_trend_and_choked_scaling(reports):
    r = rows(reports, "fig7.8")
    trend = r["deflator C_v with depth (5 L)"]
    assert trend.ours == "falls" and trend.verdict == "differs"
    ratio = r["inflator C_v ratio 500 / 3000 psia"]
    assert ratio.ours == pytest.approx(6.0, rel=1e-6)  # choked flow: C_v ~ 1 / p1
    assert "assumed" in reports[1]["fig7.8"].notes


def test_fig7_17_top_speed_and_alpha_lines(reports):
    r = rows(reports, "fig7.17")
    top = r["top forward speed at 2.5 L"]
    assert abs(top.ours - 1.75) < 0.175  # stand-in polar: within 10 % of the printed value
    assert r["constant-alpha lines are straight through the origin"].ours == "yes"


def test_fig7_27_inputs_and_errors(reports):
    r = rows(reports, "fig7.27")
    pings = r["pings answered"]
    assert abs(pings.ours - 75.0) < 3 * 0.47  # binomial: 8505 pings at p = 0.75
    with_bias = r["mean position error, least squares"].ours
    without = r["mean position error without the sound-speed error"].ours
    assert without < with_bias  # the 2.2 % sound-speed error dominates
