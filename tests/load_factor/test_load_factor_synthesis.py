"""The chapter 6 synthesis (extremals of the necessary conditions, found by shooting).

References: the hodograph's lower boundary G against `best_turn`'s f0 (the analysis module,
an independent minimisation); a straight glide ahead in closed form (2 p1 d, v = n = 1);
examples 6.12 and 6.13 against the independent collocation costs of
`test_load_factor_planner.py` (0.26256, 0.20926, printed to 5 decimals from collocations
converged to ~1e-4, hence "within 1e-4"); every returned path verified by `plan()`.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from glideplan import LoadFactorGlider, Pose, Status, plan
from glideplan.analysis.load_factor import best_turn
from glideplan.planners.load_factor_kernel import g_star, kappa_of, w_of_g_star
from glideplan.planners.load_factor_synthesis import kernel_parameters

G = LoadFactorGlider()
PRM = kernel_parameters(G)


def _g(k: float) -> float:
    """G(k) = f0 / (2 p1) of the best constant turn, from the analysis module."""
    v, n = best_turn(G, 1.0 / k)
    return (v**2 + n**2 / v**2) / 2.0


def test_kernel_parameters_match_the_corner_and_the_locus_stall_intersection():
    p2, _a, k_lim, k_c, w_lim, w_c = PRM
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


def test_example_6_13_reaches_the_corner_like_fig_6_13():
    sol = plan(Pose(), Pose(1.1, 2.0, 0.0), G, method="synthesis")
    fr = sol.extras["arcs"]["fractions"]
    assert fr["corner"] > 0.8 and fr["stall"] > 0.1  # the seed's 84 % at the corner


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
