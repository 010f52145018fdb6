"""What users see: warnings, help text, path figures, and start = goal over every planner."""

from __future__ import annotations

import dataclasses
import math
import re
from typing import Any

import pytest

from glideplan import Pose, plan, registered_planners
from glideplan.vehicles import (
    DubinsCar,
    DubinsCarInWind,
    LoadFactorGlider,
    QuadraticPolarGlider,
    VariableSpeedCar,
    dg1001m,
)


def _sailplane() -> Any:
    from glideplan.vehicles.sailplane import dg1001m_sailplane

    return dg1001m_sailplane(wind=(3.0 * math.cos(math.radians(30.0)),
                                   3.0 * math.sin(math.radians(30.0))))


EXAMPLES: dict[str, Any] = {
    DubinsCar.__name__: DubinsCar,
    DubinsCarInWind.__name__: lambda: DubinsCarInWind(
        1.0, 1.0, (0.3 * math.cos(0.5), 0.3 * math.sin(0.5))),
    VariableSpeedCar.__name__: VariableSpeedCar,
    QuadraticPolarGlider.__name__: dg1001m,
    LoadFactorGlider.__name__: LoadFactorGlider,
    "Sailplane": _sailplane,
}
SPECS = [s for s in registered_planners() if s.function.__module__.startswith("glideplan.")]


@pytest.mark.parametrize("spec", SPECS, ids=[f"{s.name}-{s.objective}-{s.method}" for s in SPECS])
@pytest.mark.parametrize("turns", [0, 1, -2])
def test_start_equal_to_goal_is_a_solved_zero_length_path(spec, turns):
    """The behaviour `plan()` documents, identical for every registered planner: start = goal
    (headings equal modulo 2 pi) gives status solved, cost 0, a path of length 0 that ends
    at the goal (endpoint error exactly 0), without calling the planner."""
    assert spec.vehicle.__name__ in EXAMPLES, f"add an example vehicle for {spec.name}"
    vehicle = EXAMPLES[spec.vehicle.__name__]()
    start = Pose(12.5, -3.0, 0.7)
    goal = Pose(12.5, -3.0, 0.7 + 2 * math.pi * turns)
    sol = plan(start, goal, vehicle, spec.objective, spec.method)
    assert sol.ok and sol.planner == spec.name
    assert sol.cost == 0.0 and sol.path is not None and sol.path.length == 0.0
    assert sol.endpoint_error is not None and sol.endpoint_error.max == 0.0
    assert sol.word == "" and "goal is the start" in sol.message
    assert sol.to_dict()["cost"] == 0.0


def test_a_goal_just_off_the_start_is_planned(run_cli):
    """Only coincident poses take the shortcut: 1e-3 m away the planner runs (cost > 0)."""
    code, out, _ = run_cli("plan", "dubins", "--goal", "0.001", "0", "0", "--radius", "1")
    assert code == 0 and "0.001" in out


def test_solution_warnings_print_one_line_each(run_cli, monkeypatch):
    """`Solution.warnings` reach stderr as `glideplan: warning: ...`, stdout stays JSON."""
    import json

    import glideplan.planning as planning

    real = planning.plan

    def plan_with_warnings(*args: Any, **kwargs: Any) -> Any:
        sol = real(*args, **kwargs)
        return dataclasses.replace(sol, warnings=("first thing", "second\nthing"))

    monkeypatch.setattr(planning, "plan", plan_with_warnings)
    code, out, err = run_cli("plan", "dubins", "--goal", "4", "3", "90", "--radius", "1", "--json")
    assert code == 0
    assert err.splitlines() == [
        "glideplan: warning: first thing",
        "glideplan: warning: second thing",
    ]
    assert json.loads(out)["warnings"] == ["first thing", "second\nthing"]


HELP_COMMANDS = [
    ["--help"],
    ["plan", "dubins", "--help"],
    ["plan", "time-optimal", "--help"],
    ["plan", "wind", "--help"],
    ["plan", "min-altitude", "--help"],
    ["plan", "load-factor", "--help"],
    ["design", "init", "--help"],
    ["design", "valve", "--help"],
]


@pytest.mark.parametrize("argv", HELP_COMMANDS, ids=" ".join)
def test_help_has_no_bool_placeholder(run_cli, argv):
    code, out, _ = run_cli(*argv)
    assert code == 0
    assert "<bool>" not in out


def test_design_init_shows_file_and_plan_shows_pose_metavars(run_cli):
    _, out, _ = run_cli("design", "init", "--help")
    assert "FILE" in out and "{file}" not in out
    _, out, _ = run_cli("plan", "dubins", "--help")
    assert "X Y HEADING_DEG" in out and "<float,float,float>" not in out
    assert "--debug" in run_cli("--help")[1]


def test_help_paragraphs_are_not_broken_mid_sentence(run_cli):
    """The docstring's second paragraph (two source lines) is reflowed as one paragraph."""
    import os

    os.environ["COLUMNS"] = "200"
    try:
        _, out, _ = run_cli("plan", "time-optimal", "--help")
    finally:
        del os.environ["COLUMNS"]
    # "... cornering turns at v_min on" ends a source line; "r = v_min/u_max" starts the next
    assert re.search(r"cornering turns at v_min on r = v_min/u_max", out), out


def test_u_max_is_the_turn_rate_option_of_every_plan_command(run_cli):
    for cmd in ("time-optimal", "min-altitude"):
        _, out, _ = run_cli("plan", cmd, "--help")
        assert "--u-max" in out and "--umax" not in out


def test_plot_figure_states_the_problem_and_keeps_the_legend_outside(tmp_path):
    """The path figure: title with vehicle, goal, word and cost with unit; axes in m; equal
    aspect; the legend's box to the right of the axes (it never covers the data)."""
    import matplotlib

    matplotlib.use("Agg")
    from glideplan.plotting import plot_solution, save_figure

    sol = plan(Pose(0, 0, 0), Pose(4, 3, math.pi / 2), DubinsCar(1.0, 1.0))
    ax = plot_solution(sol, candidates=True)
    fig = ax.get_figure()
    fig.canvas.draw()
    title = ax.get_title(loc="left")
    assert "Dubins car" in title and "R0 = 1 m" in title
    assert "goal (4, 3) m, 90 deg" in title
    assert f"optimal word {sol.word}, family {sol.family}" in title
    assert f"{sol.cost:.5g} m" in title
    assert ax.get_xlabel() == "x (m)" and ax.get_ylabel() == "y (m)"
    assert ax.get_aspect() == 1.0
    legend = ax.get_legend()
    texts = [t.get_text() for t in legend.get_texts()]
    assert any(t.startswith(f"optimal {sol.word} ({sol.family})") for t in texts)
    feasible = sum(c.feasible for c in sol.candidates)
    assert sum(t.startswith("candidate ") for t in texts) == feasible - 1 == 4
    assert {"start (heading)", "goal (heading)"} <= set(texts)
    renderer = fig.canvas.get_renderer()
    assert legend.get_window_extent(renderer).x0 >= ax.get_window_extent(renderer).x1
    out = tmp_path / "f.png"
    save_figure(ax, str(out))
    import matplotlib.image

    h, w = matplotlib.image.imread(out).shape[:2]
    assert w > h  # the legend column is inside the saved image, to the right


def test_nondimensional_glider_figure_uses_l_ref():
    from glideplan.plotting import cost_unit, length_unit

    g = LoadFactorGlider()
    assert length_unit(g) == "l_ref" and cost_unit("altitude", g) == "l_ref"
    assert length_unit(dg1001m()) == "m" and cost_unit("time", VariableSpeedCar()) == "s"


def test_design_valve_says_the_bladder_curve_is_assumed(run_cli):
    """Issue 10 sec. 3: the valve sizes rest on an unpublished p_blad(V), and say so."""
    import json

    from glideplan.design.valves import ASSUMED_BLADDER_CURVE_NOTE

    assert "assumed" in ASSUMED_BLADDER_CURVE_NOTE and "p_blad(V)" in ASSUMED_BLADDER_CURVE_NOTE
    code, out, _ = run_cli("design", "valve", "--json")
    assert code == 0 and json.loads(out)["note"] == ASSUMED_BLADDER_CURVE_NOTE
    code, out, _ = run_cli("design", "valve", "--volume-l", "1")
    assert code == 0 and "assumed (unpublished" in " ".join(out.split())
