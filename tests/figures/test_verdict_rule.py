"""The one comparison row type: verdicts computed from the numbers, tolerances from printing."""

import math

import pytest

from glideplan.errors import InvalidParameterError
from glideplan.figures.registry import Comparison, Printed, compare, half_unit, verdict


@pytest.mark.parametrize(
    ("text", "tol"),
    [("31.1", 0.05), ("13", 0.5), ("2.875", 0.0005), ("8,000", 0.5), ("0.12", 0.005)],
)
def test_half_a_unit_of_the_last_printed_digit(text, tol):
    assert half_unit(text) == pytest.approx(tol)
    assert Printed(text, "somewhere").tolerance == pytest.approx(tol)


def test_stated_tolerance_overrides_the_printed_precision():
    assert Printed("2", "section x: about twice", tolerance=0.25).tolerance == 0.25


@pytest.mark.parametrize(
    ("ours", "printed", "tol", "expected"),
    [
        (2.8747, 2.875, 0.0005, "agrees"),  # |d| = 3e-4
        (2.8744, 2.875, 0.0005, "differs"),  # |d| = 6e-4
        (2.875, 2.875, 0.0, "agrees"),
        (math.nan, 1.0, 0.5, "differs"),
        (None, 1.0, 0.5, "differs"),
        (1.0, None, None, "not printed"),
        ("BBB RLR", "BBB RLR", None, "agrees"),
        ("BSB LSL", "BSB LSR", None, "differs"),
        ("yes", None, None, "not printed"),
    ],
)
def test_verdict(ours, printed, tol, expected):
    assert verdict(ours, printed, tol) == expected


def test_numbers_need_a_tolerance():
    with pytest.raises(InvalidParameterError, match="tolerance"):
        verdict(1.0, 1.0, None)


def test_a_row_that_differs_must_say_why():
    with pytest.raises(InvalidParameterError, match="say why"):
        compare("x", 12.0, Printed("11", "Table 7.1"))
    row = compare("x", 12.0, Printed("11", "Table 7.1"), note="computed: 12 = 24 / 2")
    assert row.verdict == "differs" and row.tolerance == 0.5


def test_row_cells_are_numbers_words_or_null():
    import numpy as np

    row = compare("n", np.float64(29.2), Printed("31.1", "section 7.2", "mol"), note="T")
    d = row.to_dict()
    assert type(d["ours"]) is float and d["dissertation"] == 31.1 and d["unit"] == "mol"
    assert d["dissertation_source"] == "section 7.2" and d["verdict"] == "differs"
    with pytest.raises(InvalidParameterError, match="yes/no"):
        Comparison("flag", True)
    with pytest.raises(InvalidParameterError, match="source"):
        Comparison("x", 1.0, dissertation=1.0, tolerance=0.1)
    with pytest.raises(InvalidParameterError, match="source"):
        Comparison("x", 1.0, reference=1.0)


def test_verdict_is_not_a_field_that_can_be_written():
    with pytest.raises(TypeError):
        Comparison("x", 1.0, verdict="agrees")  # type: ignore[call-arg]
