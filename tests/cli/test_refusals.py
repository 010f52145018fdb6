"""Issue 19, "the same refusals everywhere": the one table of physical ranges, checks before work.

The command-line cases (exit 2, one line naming the option, the value and the rule) are in
`test_bad_input_corpus.py`; here: the table itself, the ends of its ranges, the design file
loader, that the mission's export options are refused before any planning (and only when the
Slocum writer itself would refuse them), and the progress reports of the long mission phases.
"""

from __future__ import annotations

import math
import os
import pathlib
from typing import Any

import numpy as np
import pytest

import glideplan
from glideplan.errors import InvalidParameterError
from glideplan.validation import PHYSICAL_RANGES, check_physical, check_physical_array

GPX = pathlib.Path(glideplan.__file__).parent / "missions" / "data" / "buzzards_bay.gpx"


def test_every_range_states_its_unit_and_reason() -> None:
    """Each entry: low < high, a reason to show, and the rule names both ends and the unit."""
    assert PHYSICAL_RANGES
    for kind, r in PHYSICAL_RANGES.items():
        assert r.low < r.high, kind
        assert r.reason.strip(), kind
        rule = r.rule()
        assert f"{r.low:g}, {r.high:g}" in rule and r.unit in rule and r.reason in rule, kind


@pytest.mark.parametrize("kind", sorted(PHYSICAL_RANGES))
def test_range_ends(kind: str) -> None:
    """The closed ends pass, an open low end and anything beyond either end is refused."""
    r = PHYSICAL_RANGES[kind]
    assert check_physical("x", r.high, kind) == r.high
    if r.low_open:
        with pytest.raises(InvalidParameterError, match=r"must lie in \("):
            check_physical("x", r.low, kind)
    else:
        assert check_physical("x", r.low, kind) == r.low
    span = r.high - r.low
    for bad in (r.low - 0.01 * span, r.high + 0.01 * span, 1e300, -1e300, math.nan, math.inf):
        with pytest.raises(InvalidParameterError) as info:
            check_physical("--flag", bad, kind)
        assert info.value.name == "--flag"
    with pytest.raises(InvalidParameterError) as info:
        check_physical_array("arr", np.array([r.high, r.high + span]), kind)
    assert info.value.value == r.high + span  # the first entry out of range is shown


def test_known_absurd_inputs_are_refused() -> None:
    """The issue's examples: altitude 1e300 m, MC 1e6 m/s, gravity 1e300, speed 1e9 m/s."""
    for name, value, kind in (
        ("--from altitude", 1e300, "altitude"),
        ("--mc", 1e6, "mc"),
        ("gravity_m_s2", 1e300, "gravity"),
        ("--speed", 1e9, "speed"),
        ("--arrival-heading", 1e300, "heading"),
    ):
        with pytest.raises(InvalidParameterError, match="must lie in"):
            check_physical(name, value, kind)


def test_design_defaults_lie_in_their_ranges() -> None:
    """The shipped design parameters (VTUG, FX23DV, Seaglider-like) load back unchanged."""
    from glideplan.design.params import (
        PHYSICAL_KINDS,
        DesignParameters,
        dumps_parameters,
        loads_parameters,
        parameters_to_dict,
    )

    default = DesignParameters()
    assert parameters_to_dict(loads_parameters(dumps_parameters(default))) == (
        parameters_to_dict(default)
    )
    data = parameters_to_dict(default)
    for key, kind in PHYSICAL_KINDS.items():
        section, field = key.split(".")
        assert field in data[section], key  # the table names real fields
        assert kind in PHYSICAL_RANGES, key


def test_design_file_out_of_range_names_the_key() -> None:
    from glideplan.design.params import loads_parameters

    with pytest.raises(InvalidParameterError) as info:
        loads_parameters("[environment]\ngravity_m_s2 = 1e300\n")
    assert info.value.name == "environment.gravity_m_s2"
    assert "must lie in [0.1, 100] m/s^2" in info.value.rule
    with pytest.raises(InvalidParameterError) as info:
        loads_parameters("[hull]\ndiameter_in = 1e9\n")
    assert info.value.name == "hull.diameter_in"  # the key as the file spells it
    assert "as diameter_m = 2.54e+07" in info.value.rule  # 1e9 in = 2.54e7 m


def test_export_options_refused_before_planning(run_cli, error_line, tmp_path, monkeypatch):
    """Slocum numbering that cannot work stops the command before the plan is computed."""
    import glideplan.missions

    def must_not_plan(*args, **kwargs):
        raise AssertionError("planned although the export options cannot work")

    monkeypatch.setattr(glideplan.missions, "plan_mission", must_not_plan)
    out = tmp_path / "m"
    code, _, err = run_cli(
        "mission", "plan", str(GPX), "--speed", "0.3", "--radius", "150", "--export", str(out),
        "--formats", "slocum", "--goto-number", "95", "--max-goto-waypoints", "2",
    )  # fmt: skip
    assert code == 2
    assert error_line(err).startswith("glideplan: error: --goto-number=95: 8 waypoints")
    assert not out.exists()  # nothing written


def test_upfront_slocum_refusal_agrees_with_the_writer() -> None:
    """Options refused before planning are refused by the Slocum writer on the planned legs
    (the straight-leg list keeps every waypoint: the up-front count is a lower bound).
    """
    from glideplan.cli.mission import check_export_options
    from glideplan.formats import ExportOptions, read_route
    from glideplan.formats.vehicle_files import write_slocum_goto
    from glideplan.missions import plan_mission, straight_leg_list

    route = read_route(GPX)
    mission = plan_mission(route, speed=0.3, radius=150.0, headings=36)
    legs = straight_leg_list(mission, 50.0)
    assert len(legs.names) >= route.n
    for per_file in (2, 3, 4):
        files_min = max(1, math.ceil((route.n - 1) / (per_file - 1)))
        for goto in (99 - files_min + 1, 99 - files_min + 2):
            options = ExportOptions(goto_number=goto, max_goto_waypoints=per_file)
            try:
                check_export_options(("slocum",), options, route.n)
            except InvalidParameterError:
                assert goto == 99 - files_min + 2
                with pytest.raises(InvalidParameterError, match="goto files would need"):
                    write_slocum_goto(
                        legs, pathlib.Path("/nonexistent"), goto_number=goto, max_waypoints=per_file
                    )
            else:
                assert goto == 99 - files_min + 1


def test_mission_reports_its_long_phases_in_order() -> None:
    """`plan_mission(progress=...)`: one report per DP leg, the refinement, one per leg."""
    from glideplan.formats import read_route
    from glideplan.missions import plan_mission

    route = read_route(GPX)
    calls: list[tuple[str, int, int]] = []
    plan_mission(route, speed=0.3, radius=150.0, headings=36, progress=lambda *a: calls.append(a))
    n = route.n - 1
    heads = [c for c in calls if c[0] == "headings"]
    legs = [c for c in calls if c[0] == "legs"]
    assert heads == [("headings", i, n) for i in range(1, n + 1)]
    assert legs == [("legs", i, n) for i in range(1, n + 1)]
    phases = [c[0] for c in calls]
    assert phases.index("refine") > phases.index("headings")
    assert phases.index("legs") > max(i for i, p in enumerate(phases) if p == "refine")


def test_phase_progress_is_quiet_for_short_phases_and_never_silent_for_long(capsys) -> None:
    """Off a terminal: nothing for a phase under the delay, one note line for a longer one."""
    from glideplan.cli.common import _PhaseProgress

    now = [0.0]
    progress = _PhaseProgress({"headings": "choosing the headings"}, delay=2.0)
    progress.clock = lambda: now[0]
    progress.last = progress.start = 0.0
    progress.terminal = False
    for i in range(1, 4):  # 0.5 s per step: 1.5 s in all, under the delay
        now[0] += 0.5
        progress("legs", i, 3)
    assert capsys.readouterr().err == ""
    for i in range(1, 11):  # 0.5 s per step: 5 s in all
        now[0] += 0.5
        progress("headings", i, 10)
    progress.close()
    err = capsys.readouterr().err.splitlines()
    assert err == ["glideplan: note: choosing the headings: 4/10 after 2 s"]


def test_readme_documents_the_table() -> None:
    """The README's "Input ranges" table is `PHYSICAL_RANGES`, row for row."""
    readme = pathlib.Path(__file__).parents[2] / "README.md"
    if not readme.is_file():
        pytest.skip("README.md not beside the tests (installed package)")
    text = readme.read_text()
    section = text[text.index("### Input ranges") :]
    section = section[: section.index("\n## ")]  # up to the next section
    rows = [line for line in section.splitlines() if line.startswith("| `")]
    documented = {}
    for row in rows:
        kind, bounds, unit, reason = (c.strip() for c in row.strip("|").split("|"))
        documented[kind.strip("`")] = (bounds, unit, reason)
    expected = {
        k: (f"{'(' if r.low_open else '['}{r.low:g}, {r.high:g}]", r.unit or "-", r.reason)
        for k, r in PHYSICAL_RANGES.items()
    }
    assert documented == expected


def test_export_directory_under_a_file_is_refused_before_planning(
    run_cli, error_line, tmp_path, monkeypatch
) -> None:
    import glideplan.missions

    def must_not_plan(*args, **kwargs):
        raise AssertionError("planned although the export directory cannot be made")

    monkeypatch.setattr(glideplan.missions, "plan_mission", must_not_plan)
    blocker = tmp_path / "a_file"
    blocker.write_text("x")
    target = blocker / "mission"
    code, _, err = run_cli(
        "mission", "plan", str(GPX), "--speed", "0.3", "--radius", "150", "--export", str(target)
    )
    assert code == 2
    assert error_line(err) == (
        f"glideplan: error: --export='{target}': '{blocker}' is a file, not a directory"
    )


@pytest.mark.skipif(
    not hasattr(os, "geteuid") or os.geteuid() == 0, reason="root may write into any directory"
)
def test_export_directory_not_writable(run_cli, error_line, tmp_path) -> None:
    locked = tmp_path / "locked"
    locked.mkdir(mode=0o500)
    code, _, err = run_cli(
        "mission", "plan", str(GPX), "--speed", "0.3", "--radius", "150",
        "--export", str(locked / "m"),
    )  # fmt: skip
    assert code == 2
    assert error_line(err).endswith(f"directory '{locked}' is not writable")


def test_phase_progress_draws_a_bar_on_a_terminal(monkeypatch) -> None:
    """On a terminal: a Rich bar (`glideplan.progress.start_progress_bar`) once a phase has
    run `delay` seconds, updated to each step's count, stopped when the phase ends."""
    import glideplan.progress
    from glideplan.cli.common import _PhaseProgress

    events: list[tuple[Any, ...]] = []

    class Bar:
        def update(self, task: int, completed: int) -> None:
            events.append(("update", completed))

        def stop(self) -> None:
            events.append(("stop",))

    def start(description: str, total: float) -> tuple[Bar, int]:
        events.append(("start", description, total))
        return Bar(), 0

    monkeypatch.setattr(glideplan.progress, "start_progress_bar", start)
    now = [0.0]
    progress = _PhaseProgress({"legs": "verifying the legs"}, delay=2.0)
    progress.clock = lambda: now[0]
    progress.last = progress.start = 0.0
    progress.terminal = True
    for i in range(1, 7):  # 1 s per step
        now[0] += 1.0
        progress("legs", i, 6)
    progress.close()
    assert events == [
        ("start", "verifying the legs", 6),
        *(("update", i) for i in range(2, 7)),
        ("stop",),
    ]
