"""The one outcome contract (issue 26, "Checks that must hold"), checked on the code itself:

- every public result type is a subclass of `glideplan.results.Outcome` and none redefines
  `ok` (it is `status is Status.SOLVED`, written once);
- every `Status` member carries a sentence and an exit code (0 for the solved and the
  candidate-only members, 1 for every other outcome), every `Reason` member a sentence;
- every product command, when it fails, prints one valid JSON object with `--json` and exits
  with its status's code (one `glideplan: error:` line on stderr, no traceback).

The expectations are the documented rules (`glideplan.results`, `glideplan.cli.emit`), not
recorded output.
"""

from __future__ import annotations

import dataclasses
import importlib
import json
import math
import pathlib

import pytest

from glideplan.results import Outcome, Reason, Status

RESULT_TYPES = (
    ("glideplan.solution", "Solution"),
    ("glideplan.routing.result", "RouteResult"),
    ("glideplan.missions.plan", "MissionPlan"),
    ("glideplan.missions.field_mission", "FieldMission"),
    ("glideplan.sailplane.request", "FinalGlide"),
    ("glideplan.reach.result", "ReachResult"),
    ("glideplan.reach.turnback", "TurnbackResult"),
    ("glideplan.routing.glider", "GliderFollow"),
    ("glideplan.routing.glider", "TrochoidChain"),
    ("glideplan.routing.departures", "DepartureResult"),
    ("glideplan.routing.ensemble", "EnsembleResult"),
    ("glideplan.routing.replay", "ReplayResult"),
    ("glideplan.planners.direct.results", "DirectResult"),
)
POLAR = pathlib.Path(__file__).parents[1] / "data" / "polars" / "DG-1001M_ch5.plr"


def _all_subclasses(cls: type) -> list[type]:
    out = []
    for sub in cls.__subclasses__():
        out += [sub, *_all_subclasses(sub)]
    return out


@pytest.mark.parametrize(("module", "name"), RESULT_TYPES)
def test_every_public_result_is_an_outcome(module, name):
    cls = getattr(importlib.import_module(module), name)
    assert issubclass(cls, Outcome), name
    assert cls.__dataclass_params__.frozen, f"{name}: frozen"
    assert all(f.kw_only for f in dataclasses.fields(cls)), f"{name}: keyword-only"


def test_no_outcome_redefines_ok():
    """`ok` lives in `Outcome` only: no subclass (nor a mixin in its MRO) defines it."""
    for module, _ in RESULT_TYPES:
        importlib.import_module(module)
    subclasses = _all_subclasses(Outcome)
    assert len(subclasses) >= len(RESULT_TYPES)
    for cls in subclasses:
        for base in cls.__mro__:
            if base is not Outcome:
                assert "ok" not in vars(base), f"{cls.__name__}: {base.__name__} defines ok"


def test_status_from_its_string_and_ok_once():
    """A status given as its string is the `Status` member; `ok` follows it; an empty message
    is the status's sentence and the reason's."""
    from glideplan.routing.glider import TrochoidChain

    chain = TrochoidChain(status="infeasible", residual_ratio=1.2, feasible_radius_m=None,
                          reason="no_feasible_radius")
    assert chain.status is Status.INFEASIBLE and chain.reason is Reason.NO_FEASIBLE_RADIUS
    assert not chain.ok
    assert chain.message == (f"{Status.INFEASIBLE.sentence}: "
                             f"{Reason.NO_FEASIBLE_RADIUS.sentence}")
    d = chain.to_dict()
    assert {k: d[k] for k in ("status", "ok", "reason")} == {
        "status": "infeasible", "ok": False, "reason": "no_feasible_radius"}
    with pytest.raises(ValueError):
        TrochoidChain(status="fine", residual_ratio=0.1, feasible_radius_m=None)


def test_every_status_has_a_sentence_and_an_exit_code():
    zero = {Status.SOLVED, Status.FEASIBLE, Status.LOCAL}
    for member in Status:
        assert isinstance(member.sentence, str) and len(member.sentence) > 10, member
        assert member.exit_code == (0 if member in zero else 1), member
        assert Status(member.value) is member and member == member.value
    for reason in Reason:
        assert isinstance(reason.sentence, str) and len(reason.sentence) > 10, reason


def test_plot_returns_a_figure_and_honours_ax():
    """`plot()` is a Figure (the base draws the message); given `ax`, the figure is ax's."""
    import matplotlib.pyplot as plt
    from matplotlib.figure import Figure

    from glideplan.routing.glider import TrochoidChain

    chain = TrochoidChain(status="infeasible", residual_ratio=1.2, feasible_radius_m=None)
    fig = Outcome.plot(chain)
    assert isinstance(fig, Figure)
    plt.close(fig)
    own, ax = plt.subplots()
    assert Outcome.plot(chain, ax=ax) is own
    plt.close(own)


def test_final_glide_plot_honours_ax():
    """`FinalGlide.plot(ax=...)` draws into the given axes' figure (it used to ignore ax)."""
    import matplotlib.pyplot as plt

    import glideplan
    from glideplan.vehicles.sailplane import dg1001m_sailplane

    res = glideplan.final_glide(dg1001m_sailplane().polar, (47.0, 8.0, 1500.0),
                                (47.05, 8.0, 400.0))
    own, ax = plt.subplots()
    assert res.plot(ax=ax) is own
    plt.close(own)
    fig = res.plot()
    assert fig is not own and len(fig.axes) >= 2
    plt.close(fig)


def _failed_solution(*args, **kwargs):
    """A `plan()` that finds no path (the planner's ordinary failure)."""
    from glideplan.pose import Pose
    from glideplan.solution import Solution
    from glideplan.vehicles.dubins_car import DubinsCar

    return Solution(status=Status.NO_PATH, planner="dubins", objective="length",
                    start=Pose(0, 0, 0), goal=Pose(4, 3, math.pi / 2),
                    vehicle=DubinsCar(turn_radius=1.0), path=None, cost=math.inf)


GLIDE = ("glide", "final", "--polar", str(POLAR), "--from", "47.0", "8.0")
FAILURES = {
    "plan dubins: no_path": (("plan", "dubins", "--goal", "4", "3", "90", "--radius", "1"),
                             "no_path", _failed_solution),
    "route: unreachable": (("route", "--example", "double-gyre", "--from", "30.45", "-39.8",
                            "--to", "30.45", "-38.5", "--speed", "0.5", "--max-duration",
                            "0.5"), "unreachable", None),
    "glide final: unreachable": ((*GLIDE, "1500", "--to", "47.2", "8.1", "450", "--wind", "80",
                                  "270"), "unreachable", None),
    "glide final: below_glide": ((*GLIDE, "800", "--to", "47.2", "8.1", "450"), "below_glide",
                                 None),
    "glide turnback: unreachable": (("glide", "turnback", "--polar", str(POLAR), "--from",
                                     "47.0", "8.0", "500", "--course", "90", "--home", "47.0",
                                     "7.9", "450"), "unreachable", None),
}


@pytest.mark.parametrize("name", sorted(FAILURES))
def test_a_failure_prints_json_and_exits_with_its_status_code(name, run_cli, monkeypatch):
    argv, status, patch = FAILURES[name]
    if patch is not None:
        monkeypatch.setattr("glideplan.planning.plan", patch)
    code, out, err = run_cli(*argv, "--json")
    data = json.loads(out)
    assert data["status"] == status and data["ok"] is False and data["message"]
    # README "Exit codes": every JSON object starts with the same keys
    assert list(data)[:5] == ["status", "ok", "message", "warnings", "reason"]
    assert code == Status(status).exit_code == 1
    errors = [line for line in err.splitlines() if line.startswith("glideplan: error:")]
    assert len(errors) == 1 and f": {status}: " in errors[0] and "Traceback" not in err
    # the human form exits the same way
    code_text, _, _ = run_cli(*argv)
    assert code_text == code


def test_a_failed_mission_prints_json_and_names_the_leg(run_cli, monkeypatch, tmp_path):
    """A mission whose leg has no path: the JSON is printed (it used to raise before
    printing), status and reason are the leg's, the message names the leg; exit 1."""
    route = tmp_path / "r.csv"
    route.write_text("name,x,y\na,0,0\nb,800,300\nc,900,-500\n", encoding="utf-8")
    monkeypatch.setattr("glideplan.planning.plan", _failed_solution)
    code, out, err = run_cli("mission", "plan", str(route), "--speed", "1", "--radius", "150",
                             "--json")
    data = json.loads(out)
    assert code == 1, err
    assert data["status"] == "no_path" and data["reason"] == "leg_failed"
    assert data["message"].startswith("leg 1 (a -> b)") and data["track"] is None
    assert data["files"] == {}


def test_emit_exit_codes_follow_the_status():
    """`emit` raises typer.Exit with the status's code, for each status."""
    import typer

    from glideplan.cli.emit import emit
    from glideplan.routing.glider import TrochoidChain

    for status in Status:
        chain = TrochoidChain(status=status, residual_ratio=0.1, feasible_radius_m=None)
        with pytest.raises(typer.Exit) as exc:
            emit(chain, json=True)
        assert exc.value.exit_code == status.exit_code


def test_final_glide_plan_failure_is_a_status(monkeypatch):
    """`final_glide` to an arrival heading whose plan fails returns the plan's status with a
    message saying so (it used to raise PlanningError): an ordinary failure is a status."""
    import glideplan
    from glideplan.pose import Pose
    from glideplan.solution import Solution
    from glideplan.vehicles.sailplane import dg1001m_sailplane

    def failed(*args, **kwargs):
        return Solution(status=Status.SOLVER_FAILED, planner="final_glide", objective="altitude",
                        start=Pose(0, 0, 0), goal=Pose(1, 0, 0), vehicle=args[2], path=None,
                        cost=math.inf, message="IPOPT did not converge", reason="solver")

    monkeypatch.setattr("glideplan.planning.plan", failed)
    res = glideplan.final_glide(dg1001m_sailplane().polar, (47.0, 8.0, 1500.0),
                                (47.05, 8.0, 400.0), arrival_heading=90.0)
    assert res.status is Status.SOLVER_FAILED and res.reason is Reason.SOLVER
    assert "IPOPT did not converge" in res.message and res.altitude_loss_m is None
    d = res.to_dict()
    assert d["status"] == "solver_failed" and d["ok"] is False


# --- every other product command (issue 26: "for every product command, a failure prints
# valid JSON and exits with the status's code") ---------------------------------------------

PLANS = {
    "plan wind": ("plan", "wind", "--goal", "400", "300", "90", "--speed", "20", "--radius",
                  "50", "--wind", "5", "270"),
    "plan time-optimal": ("plan", "time-optimal", "--goal", "4", "3", "90", "--v-min", "0.3",
                          "--v-max", "1", "--u-max", "1"),
    "plan min-altitude": ("plan", "min-altitude", "--goal", "400", "300", "90"),
    "plan load-factor": ("plan", "load-factor", "--goal", "400", "300", "90"),
}


def _one_failure(run_cli, argv, status, what):
    """--json: one JSON object with the status, exit = the status's code, one error line
    naming the product and the status; the human form exits the same."""
    code, out, err = run_cli(*argv, "--json")
    assert "Traceback" not in err, err
    data = json.loads(out)
    assert data["status"] == status and data["ok"] is False and data["message"], data
    assert code == Status(status).exit_code == 1, err
    errors = [line for line in err.splitlines() if line.startswith("glideplan: error:")]
    assert len(errors) == 1 and f"{what}: {status}: " in errors[0], err
    code_text, _, err_text = run_cli(*argv)
    assert code_text == code and "Traceback" not in err_text, err_text
    return data


@pytest.mark.parametrize("name", sorted(PLANS))
def test_every_plan_command_fails_with_json_and_its_code(name, run_cli, monkeypatch):
    """Each `plan` planner, its `plan()` patched to the ordinary no_path failure."""
    monkeypatch.setattr("glideplan.planning.plan", _failed_solution)
    _one_failure(run_cli, PLANS[name], "no_path", "")


# A uniform current of 1 m/s towards the east over a 1 x 1 degree box on the equator: a
# vehicle of 0.5 m/s bound west cannot stem it (the goal is outside its drift cone), and
# eastwards it needs D / (V + W) = 0.5 deg x 111.2 km / 1.5 m/s ~ 10 h, far beyond a 0.1 h
# --max-duration: two closed-form reasons to be unreachable, each named by the product.
T0 = "2026-03-01T00:00Z"


@pytest.fixture(scope="module")
def current_files(tmp_path_factory):
    import numpy as np

    from glideplan.fields.synthetic import copernicus_dataset

    d = tmp_path_factory.mktemp("contract_fields")
    lat = np.arange(-0.5, 0.5 + 1e-9, 0.05)
    lon = np.arange(0.0, 1.0 + 1e-9, 0.05)
    times = np.datetime64("2026-03-01T00:00", "ns") + np.arange(25) * np.timedelta64(3600, "s")
    shape = (times.size, 1, lat.size, lon.size)
    for i in range(2):
        copernicus_dataset(lat, lon, times, [0.494], np.ones(shape),
                           np.zeros(shape)).to_netcdf(d / f"member_{i}.nc")
    return d


ROUTE = ("--from", "0", "0.1", "--to", "0", "0.6", "--speed", "0.5", "--resolution", "2000")


def test_route_ensemble_failure(current_files, run_cli):
    argv = ("route", "--ensemble", str(current_files / "member_*.nc"), *ROUTE, "--workers",
            "1", "--max-duration", "0.1")
    data = _one_failure(run_cli, argv, "unreachable", "route")
    assert data["ensemble"]["p_arrival"] == 0.0


def test_route_depart_range_failure(current_files, run_cli):
    argv = ("route", "--field", str(current_files / "member_0.nc"), "--depart-range", T0,
            "2026-03-01T04:00Z", "4", *ROUTE, "--workers", "1", "--max-duration", "0.1")
    data = _one_failure(run_cli, argv, "unreachable", "route")
    assert all(row["status"] == "unreachable" for row in data["departures"])


def test_route_replay_failure(current_files, run_cli):
    f = str(current_files / "member_0.nc")
    argv = ("route", "replay", "--truth", f, "--forecasts", f, *ROUTE, "--depart", T0,
            "--max-duration", "0.1")
    data = _one_failure(run_cli, argv, "unreachable", "route replay")
    assert data["reason"] == "max_duration"


def test_field_mission_failure(current_files, run_cli, tmp_path):
    """A field mission whose leg runs against a current faster than the vehicle: the leg's
    status and reason (outside the drift cone), exit 1; the waypoint never reached has no ETA
    (null, not "NaTZ")."""
    route = tmp_path / "r.csv"
    route.write_text("name,lat,lon\nA,0,0.6\nB,0,0.1\n", encoding="utf-8")
    argv = ("mission", "plan", str(route), "--speed", "0.5", "--radius", "10", "--field",
            str(current_files / "member_0.nc"), "--depart", T0)
    data = _one_failure(run_cli, argv, "unreachable", "mission")
    assert data["reason"] == "outside_drift_cone" and data["message"].startswith("leg 1 (A -> B)")
    assert data["waypoints"][1]["eta_s"] is None and data["waypoints"][1]["eta"] is None


def test_glide_reach_failure_goes_through_the_contract(run_cli, monkeypatch):
    """`glide reach` has no failure of its own (the reachable set always exists: it is solved
    even when empty); a ReachResult whose status is not solved -- the library's answer
    patched -- is printed and exits like every other product's."""
    import glideplan.reach

    real = glideplan.reach.glide_reach

    def failed(*args, **kwargs):
        return dataclasses.replace(real(*args, **kwargs), status=Status.UNREACHABLE,
                                   message="no landable reachable")

    monkeypatch.setattr(glideplan.reach, "glide_reach", failed)
    argv = ("glide", "reach", "--example", "ridge", "--resolution", "1500")
    _one_failure(run_cli, argv, "unreachable", "reach")
