"""The plan summary table (`glideplan plan ...` without `--json`) states the unit of each row."""

from __future__ import annotations

import io
import math
import re

from glideplan import Pose, plan
from glideplan.vehicles import LoadFactorGlider


def _rows(table_text: str) -> dict[str, tuple[str, str]]:
    """{quantity: (value, unit)} from a Rich table printed as text."""
    rows = {}
    for line in table_text.splitlines():
        cells = [c.strip() for c in re.split(r"[│┃]", line)[1:-1]]
        if len(cells) == 3:
            rows[cells[0]] = (cells[1], cells[2])
    return rows


def test_dubins_time_table_gives_cost_in_seconds_and_length_in_metres(run_cli):
    """`plan dubins --time`: the cost is a time (s), the length m, the duration s; the values
    are the JSON's (hand check: LSL from (0,0,0) to (4,3,90 deg), R0 = 1, v = 2: the cost is
    the length / v)."""
    args = ("plan", "dubins", "--goal", "4", "3", "90", "--radius", "1", "--speed", "2")
    code, out, _ = run_cli(*args, "--time")
    assert code == 0
    rows = _rows(out)
    assert rows["quantity"] == ("value", "unit")
    assert rows["cost"][1] == "s" and rows["duration"][1] == "s"
    assert rows["length"][1] == "m" and rows["endpoint error (position)"][1] == "m"
    assert rows["endpoint error (heading)"][1] == "deg"
    assert math.isclose(float(rows["cost"][0]), float(rows["length"][0]) / 2.0, rel_tol=1e-5)
    code, out, _ = run_cli(*args)
    assert code == 0 and _rows(out)["cost"][1] == "m"


def test_load_factor_table_is_in_reference_units():
    """The nondimensional load-factor glider (chapter 6) reports l_ref = V_ref^2/g and
    t_ref = V_ref/g, not m and s. Start = goal keeps it cheap (no IPOPT solve): `plan()`
    returns the documented zero-length solved path."""
    from rich.console import Console

    from glideplan.cli.common import _solution_table

    pose = Pose(1.0, 2.0, 0.3)
    sol = plan(pose, pose, LoadFactorGlider(), "altitude", "direct")
    text = io.StringIO()
    Console(file=text, width=100).print(_solution_table(sol, sol.to_dict()))
    rows = _rows(text.getvalue())
    assert rows["cost"] == ("0", "l_ref")
    assert rows["length"][1] == "l_ref" and rows["duration"][1] == "t_ref"
