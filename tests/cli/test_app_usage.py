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


def test_comma_separated_values_say_what_the_option_got(cli_error) -> None:
    """`--from 30.45,-39.8 --to 30.45 -38.2`: --from swallows `--to`, and `-38.2` then read as
    an option gave "No such option: -3"; now the multi-value message, with the hint."""
    line = cli_error("route", "--example", "double-gyre", "--from", "30.45,-39.8", "--to",
                     "30.45", "-38.2", "--speed", "0.5")
    assert line == ("glideplan: error: --from needs 2 values (lat lon), got 1 (30.45,-39.8) "
                    "before --to; separate the values by spaces, not commas")
    line = cli_error("plan", "dubins", "--goal", "4,3,90", "--radius", "1")
    assert line.endswith("got 1 (4,3,90) before --radius; separate the values by spaces, "
                         "not commas")


def test_negative_numbers_are_values_not_option_names(run_cli) -> None:
    """`--goal 4 -3 -90` is a goal below the x axis heading south, not a missing value."""
    code, out, err = run_cli(
        "plan", "dubins", "--goal", "4", "-3", "-90", "--radius", "1", "--json"
    )
    assert code == 0, err
    goal = json.loads(out)["goal"]
    assert (goal["x"], goal["y"]) == (4.0, -3.0)
