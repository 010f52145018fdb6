"""Meta-test (issue 19): the planner registry, the CLI, the explorer and `PLANNER_MODULES` agree.

As python-control's keyword test keeps its API honest, this one keeps the four lists of
planners in step, in both directions:

- every registered planner's module is listed in `glideplan.planners.PLANNER_MODULES` under its
  vehicle model, and every listed module registers a planner for that model;
- every registered planner is an entry of the explorer's catalogue (`glideplan.explore.catalog`)
  and every entry is a registered planner;
- every registered planner is reached by a command-line invocation of `CLI_CASES`: the command
  is run with `glideplan.planning.plan` replaced by a recorder, and the planner that `plan()`
  would choose for the recorded (vehicle, objective, method) is the one expected; every
  `glideplan plan` subcommand appears in `CLI_CASES`;
- every command and every option or argument of the CLI has help text.

A planner added without its CLI command, explorer entry or module listing fails here.
"""

from __future__ import annotations

import importlib
import pathlib
from typing import Any

import pytest

from glideplan import registered_planners
from glideplan.errors import PlanningError

POLAR = pathlib.Path(__file__).parent / "data" / "polars" / "DG-1001M_ch5.plr"

# (planner name, objective) -> a command line that must plan with exactly that planner
CLI_CASES: dict[tuple[str, str], tuple[str, ...]] = {
    ("dubins", "length"): ("plan", "dubins", "--goal", "4", "3", "90", "--radius", "1"),
    ("dubins", "time"): ("plan", "dubins", "--goal", "4", "3", "90", "--radius", "1", "--time"),
    ("wind", "time"): (
        "plan", "wind", "--goal", "4", "3", "90", "--speed", "1", "--radius", "1",
        "--wind", "0.5", "270",
    ),
    ("min_altitude", "altitude"): ("plan", "min-altitude", "--goal", "400", "300", "90"),
    ("min_altitude_direct", "altitude"): (
        "plan", "min-altitude", "--goal", "400", "300", "90", "--method", "direct",
    ),
    ("time-optimal", "time"): (
        "plan", "time-optimal", "--goal", "0", "2", "120", "--v-min", "0.3", "--v-max", "1",
        "--u-max", "1",
    ),
    ("time-optimal-direct", "time"): (
        "plan", "time-optimal", "--goal", "0", "2", "120", "--v-min", "0.3", "--v-max", "1",
        "--u-max", "1", "--method", "direct",
    ),
    ("load-factor", "altitude"): ("plan", "load-factor", "--goal", "1", "2", "0"),
    ("load-factor-synthesis", "altitude"): (
        "plan", "load-factor", "--goal", "1", "2", "0", "--method", "synthesis"
    ),
    ("final_glide", "altitude"): (
        "glide", "final", "--polar", str(POLAR), "--from", "47.0", "8.0", "1500", "--to",
        "47.02", "8.01", "450", "--arrival-heading", "90", "--start-heading", "0",
    ),
}  # fmt: skip


def _specs() -> list[Any]:
    """The package's own planners (tests may register others)."""
    return [s for s in registered_planners() if s.function.__module__.startswith("glideplan.")]


def test_registry_and_planner_modules_agree() -> None:
    """Each planner's module is listed for its vehicle model; each listed module registers."""
    from glideplan.planners import PLANNER_MODULES

    specs = _specs()
    for s in specs:
        listed = PLANNER_MODULES.get(s.vehicle.__name__, ())
        modules = [f"glideplan.planners.{m}" for m in listed]
        here = s.function.__module__
        assert any(here == m or here.startswith(m + ".") for m in modules), (
            f"planner {s.name!r} ({here}) is not listed in PLANNER_MODULES"
            f"[{s.vehicle.__name__!r}] = {listed}"
        )
    for model, names in PLANNER_MODULES.items():
        assert names, model
        for name in names:
            module = f"glideplan.planners.{name}"
            importlib.import_module(module)
            served = [
                s for s in specs
                if s.vehicle.__name__ == model
                and (s.function.__module__ == module
                     or s.function.__module__.startswith(module + "."))
            ]  # fmt: skip
            assert served, f"PLANNER_MODULES[{model!r}] lists {name!r}, which registers nothing"


def test_registry_and_explorer_catalogue_agree() -> None:
    from glideplan.explore.catalog import build_catalog, planner_key

    registered = {(planner_key(s.name), s.objective, s.method) for s in _specs()}
    entries = [e for e in build_catalog().entries
               if e.spec.function.__module__.startswith("glideplan.")]  # tests register others
    listed = {(planner_key(e.spec.name), e.spec.objective, e.spec.method) for e in entries}
    assert listed >= registered, f"no explorer entry for {sorted(registered - listed)}"
    extra = {k for k in listed - registered}
    assert not extra, f"explorer entries without a registered planner: {sorted(extra)}"
    assert len({e.key for e in entries}) == len(entries)  # one entry per planner


def test_every_cli_case_reaches_its_planner(run_cli, monkeypatch) -> None:
    """Run each command with `plan()` recording its request: the planner it selects is the one
    the case names, and together the cases reach every registered planner."""
    import glideplan.planning as planning

    seen: list[tuple[str, str]] = []

    def record(start, goal, vehicle, objective=None, method=None, **kwargs):
        spec = planning.find_planner(vehicle, objective or vehicle.default_objective, method)
        seen.append((spec.name, spec.objective))
        raise PlanningError("recorded")

    monkeypatch.setattr(planning, "plan", record)
    registered = {(s.name, s.objective) for s in _specs()}
    assert set(CLI_CASES) == registered, (
        f"planners without a CLI case: {sorted(registered - set(CLI_CASES))}; "
        f"cases without a planner: {sorted(set(CLI_CASES) - registered)}"
    )
    for key, argv in CLI_CASES.items():
        seen.clear()
        code, _, err = run_cli(*argv)
        assert code == 1 and "recorded" in err, (key, code, err)
        assert seen == [key], f"{' '.join(argv[:2])} planned with {seen}, expected {key}"


def _commands() -> list[tuple[list[str], Any]]:
    from glideplan.cli.app import _click_command, load_commands

    load_commands()
    out: list[tuple[list[str], Any]] = []

    def walk(command: Any, path: list[str]) -> None:
        subs = getattr(command, "commands", None)
        if subs:
            for name, sub in subs.items():
                walk(sub, [*path, name])
        else:
            out.append((path, command))

    walk(_click_command(), [])
    return out


def test_every_plan_command_has_a_cli_case() -> None:
    commands = {path[1] for path, _ in _commands() if path[0] == "plan"}
    covered = {argv[1] for argv in CLI_CASES.values() if argv[0] == "plan"}
    assert commands == covered, f"plan commands without a case: {sorted(commands - covered)}"


@pytest.mark.parametrize("path", [" ".join(p) for p, _ in _commands()])
def test_every_option_is_documented(path: str) -> None:
    """Each command has a help text and so has each of its options and arguments."""
    command = dict((" ".join(p), c) for p, c in _commands())[path]
    assert (command.help or "").strip(), f"{path}: no help text"
    for param in command.params:
        text = getattr(param, "help", None) or ""
        assert text.strip(), f"{path} {'/'.join(param.opts)}: no help text"
