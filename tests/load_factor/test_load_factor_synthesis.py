"""The chapter 6 synthesis (extremals of the necessary conditions as tabulated orbits).

References: the hodograph's lower boundary G against `best_turn`'s f0 (the analysis module,
an independent minimisation); G*'s inverse against the Newton solution; the first integral
G*(w) = P cos phi along a tabulated orbit (the table is integrated without using it); the
P -> 0 rotation is the circle of curvature k*(W(0)) (closed form); a straight glide ahead in
closed form (2 p1 d, v = n = 1); the seed's examples against the independent collocation
costs of `test_load_factor_planner.py` (0.36138, 0.26256, 0.20926, to 5 decimals, hence
"within 1e-4"); four random goals whose optimum lies on a fold of the search or where an
inflection is born, against the direct method's costs printed here (IPOPT, collocation
converged to about 1e-6 relative: the synthesis must not be above them by 1e-4 relative);
every returned path verified by `plan()`.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from glideplan import LoadFactorGlider, Pose, Status, plan
from glideplan.analysis.load_factor import best_turn
from glideplan.planners.load_factor_kernel import (
    g_star,
    kappa_newton,
    kappa_of,
    w_newton,
    w_of_g_star,
)
from glideplan.planners.load_factor_orbits import orbit_table, period_info
from glideplan.planners.load_factor_synthesis import dubins_bound, kernel_parameters

G = LoadFactorGlider()
PRM = kernel_parameters(G)


def _g(k: float) -> float:
    """G(k) = f0 / (2 p1) of the best constant turn, from the analysis module."""
    v, n = best_turn(G, 1.0 / k)
    return (v**2 + n**2 / v**2) / 2.0


def test_kernel_parameters_match_the_corner_and_the_locus_stall_intersection():
    p2, _a, k_lim, k_c, w_lim, w_c = PRM[:6]
    assert k_c == pytest.approx(1.0 / G.corner_radius, rel=1e-12)
    v, n = best_turn(G, 1.0 / k_lim)  # on both the locus and the stall boundary
    assert v**4 + n**2 == pytest.approx(2.0, rel=1e-12)
    assert n == pytest.approx(p2 * v**2, rel=1e-12)
    assert 0.0 < w_lim < w_c


@pytest.mark.parametrize("k", [0.3, 0.9, 1.2, 1.45])
def test_kappa_of_inverts_the_slope_of_the_hodograph_boundary(k):
    """k*(w) solves G'(k) = w: check with a central difference of the analysis's G."""
    h = 1e-6
    slope = (_g(k + h) - _g(k - h)) / (2 * h)
    assert kappa_of(slope, PRM) == pytest.approx(k, rel=1e-6)
    assert kappa_of(-slope, PRM) == pytest.approx(-k, rel=1e-6)
    assert kappa_of(10.0, PRM) == PRM[3]  # saturated: the corner


@pytest.mark.parametrize("w", [0.0, 0.4, 1.5, 3.0, 8.0])
def test_g_star_is_the_minimum_of_g_minus_w_k_and_w_of_g_star_inverts_it(w):
    ks = np.linspace(1e-6, PRM[3], 4001)
    brute = min(_g(k) - w * k for k in ks)
    assert g_star(w, PRM) == pytest.approx(brute, abs=1e-6)
    assert w_of_g_star(g_star(w, PRM), PRM) == pytest.approx(w, abs=1e-9)


def test_the_tabulated_inverses_match_newtons_method():
    """The Hermite tables of k*(w) and W(q) on the stall part against Newton (1e-10)."""
    ws = np.linspace(PRM[4], PRM[5], 1001)
    assert max(abs(kappa_of(w, PRM) - kappa_newton(w, PRM[:6])) for w in ws) < 1e-10
    qs = np.linspace(PRM[7], PRM[6], 1001)
    assert max(abs(w_of_g_star(q, PRM) - w_newton(q, PRM[:6])) for q in qs) < 1e-10


@pytest.mark.parametrize("p", [0.3, 0.99, 1.01, 4.0])
def test_orbit_tables_keep_the_first_integral(p):
    """G*(w) = P cos phi (H = 0) holds along the integrated orbit to the accuracy of RK4 at
    the table's step (~(h P)^4: the tables only seed the search, the polish is finer)."""
    tab = orbit_table(p, 0.025, PRM, 200.0)
    drift = [abs(g_star(w, PRM) - p * math.cos(phi)) for phi, w in tab[:, :2]]
    assert max(drift) < 1e-6 * max(1.0, p)


def test_a_small_modulus_rotation_is_the_circle_of_curvature_k_star_of_w0():
    """P -> 0: w stays at W(0), so the orbit is a circle: period 2 pi / k*(W(0))."""
    p = 1e-4
    period = period_info(orbit_table(p, 0.01, PRM, 200.0), p, 0.01)[0]
    kappa0 = kappa_of(w_of_g_star(0.0, PRM), PRM)
    assert period == pytest.approx(2.0 * math.pi / kappa0, rel=1e-3)


def test_a_straight_glide_ahead_costs_2_p1_d():
    sol = plan(Pose(), Pose(5.0, 0.0, 0.0), G, method="synthesis")
    assert sol.status is Status.SOLVED and sol.extras["answered_by"] == "synthesis"
    assert sol.cost == pytest.approx(2.0 * G.p1 * 5.0, rel=1e-9)
    assert sol.extras["arcs"]["fractions"]["wings_level"] == pytest.approx(1.0)


@pytest.mark.parametrize(
    "goal, ref, word",
    [
        ((-2.0, 4.0, 7 * math.pi / 4), 0.36138, "L"),
        ((0.0, -0.5, math.pi), 0.26256, "LRL"),
        ((1.1, 2.0, 0.0), 0.20926, "LR"),
    ],
)
def test_the_seed_examples_match_the_independent_collocation(goal, ref, word):
    sol = plan(Pose(), Pose(*goal), G, method="synthesis")
    assert sol.status is Status.SOLVED and sol.extras["answered_by"] == "synthesis"
    assert abs(sol.cost - ref) <= 1e-4
    assert sol.word == word
    assert sol.endpoint_error.position < 1e-6
    assert sol.cost <= sol.extras["dubins_bound"]


@pytest.mark.parametrize(
    "goal, direct",
    [
        ((-2.645, -1.802, 5.026), 0.29906652),  # RL on a fold of the root curves
        ((0.071, 0.064, 1.484), 0.25607564),  # LRL where two inflections are born
        ((2.2529393807623883, 1.538660110683944, 2.7094775719810213), 0.17803666),  # RL
        ((0.09495881521509375, 0.10888884466533, 4.731428336896716), 0.25169040),  # RLR
        # root curves born and dying between two tabulated moduli: no bracket sees them,
        # Newton shooting from the search rows finds them (direct costs: the quiet-machine
        # run of benchmarks/load_factor_vs_direct.py, seed 1, random049/166/189/193)
        ((2.6877175990916644, 0.2562952316225413, 0.9364963505070206), 0.106727),  # RL
        ((2.9180007964558943, 1.7534626949801124, 2.6490132772286668), 0.194438),  # RL
        ((0.42629801554088687, -0.03407965055826079, 1.297392092294023), 0.264748),  # LR
        ((-1.403264851742152, 0.4235861487393766, 2.314008829991801), 0.244368),  # RL
    ],
)
def test_hard_random_goals_are_at_or_below_the_direct_method(goal, direct):
    sol = plan(Pose(), Pose(*goal), G, method="synthesis")
    assert sol.status is Status.SOLVED and sol.extras["answered_by"] == "synthesis"
    assert sol.cost <= direct * (1.0 + 1e-4)


def test_example_6_13_reaches_the_corner_like_fig_6_13():
    sol = plan(Pose(), Pose(1.1, 2.0, 0.0), G, method="synthesis")
    fr = sol.extras["arcs"]["fractions"]
    assert fr["corner"] > 0.8 and fr["stall"] > 0.1  # the seed's 84 % at the corner


def test_the_dubins_bound_is_a_flyable_cost():
    """The bound is a Dubins path flown with the best turn: at least the straight-line
    glide (2 p1 d) and, for a goal straight ahead, exactly it."""
    bound, word = dubins_bound(G, Pose(3.0, 4.0, 1.0))
    assert bound >= 2.0 * G.p1 * 5.0 and word
    assert dubins_bound(G, Pose(5.0, 0.0, 0.0))[0] == pytest.approx(2.0 * G.p1 * 5.0)


def test_no_candidate_is_said_and_the_direct_method_answers():
    glider = LoadFactorGlider(n_max=1.1)  # corner below the locus-stall intersection
    assert kernel_parameters(glider) is None
    sol = plan(Pose(), Pose(3.0, 1.0, 0.5), glider, method="synthesis")
    assert sol.extras["answered_by"] == "direct"
    assert "no candidate" in sol.message
    assert sol.status is Status.SOLVED


def test_cli_method_synthesis_matches_the_example_and_a_bad_method_exits_2(capsys):
    from glideplan.cli.app import main

    argv = ["plan", "load-factor", "--goal", "1.1", "2", "0", "--method", "synthesis", "--json"]
    assert main(argv) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["planner"] == "load-factor-synthesis" and data["status"] == "solved"
    assert data["cost"] == pytest.approx(0.20926, abs=1e-4)
    assert data["arcs"]["reaches_corner"] is True
    assert main(["plan", "load-factor", "--goal", "1", "2", "0", "--method", "bogus"]) == 2
    assert "--method" in capsys.readouterr().err
