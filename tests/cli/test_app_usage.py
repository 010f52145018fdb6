"""Usage messages of `glideplan.cli.app.main`: help printed once, multi-value options explained.

References are the documented rules: no arguments or a group alone print the help (exit 0),
once; an option taking several values that swallows the next option's name says how many
values it got before that name (a negative number is a value, not an option name).
"""

from __future__ import annotations

import json

import pytest


@pytest.mark.parametrize("argv", [(), ("plan",), ("glide",)])
def test_no_arguments_print_the_help_once(run_cli, argv: tuple[str, ...]) -> None:
    code, out, err = run_cli(*argv)
    assert code == 0, err
    assert out.count("Usage:") == 1, out


def test_option_that_takes_the_next_option_says_what_it_got(cli_error) -> None:
    line = cli_error("plan", "dubins", "--goal", "4", "3", "--radius", "1")
    assert line == (
        "glideplan: error: --goal needs 3 values (x y heading_deg), got 2 (4 3) before --radius"
    )
    line = cli_error("plan", "dubins", "--goal", "4", "--radius", "1")
    assert line.endswith("got 1 (4) before --radius")


def test_negative_numbers_are_values_not_option_names(run_cli) -> None:
    """`--goal 4 -3 -90` is a goal below the x axis heading south, not a missing value."""
    code, out, err = run_cli(
        "plan", "dubins", "--goal", "4", "-3", "-90", "--radius", "1", "--json"
    )
    assert code == 0, err
    goal = json.loads(out)["goal"]
    assert (goal["x"], goal["y"]) == (4.0, -3.0)
