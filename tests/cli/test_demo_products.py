"""`make demo` shows the products: route, mission, final glide and glide reach (issue 19).

Each product runs through the one outcome contract (`glideplan.results.Outcome`): a frozen
result with `status`, `ok`, `message`, `to_dict()` (the JSON the demo writes) and `plot()`,
and meets its reference: the straight line with crab angle (a feasible route, so the optimum
is not slower), the heading heuristics (same legs), the straight final glide (a lower bound on
the altitude loss to an arrival heading), and the closed form (altitude - ground - safety
height) x (L/D)max of a glide over flat ground in still air (the field's arrival altitude to
1 m; the footprint's radius within three grid cells).
"""

from __future__ import annotations

import dataclasses
import json
import math

import pytest

from glideplan.demos.products import POLAR_FILE, PRODUCTS, available_products, run_product
from glideplan.results import Outcome


def test_the_products_are_the_four_of_the_issue() -> None:
    assert [p.key for p in PRODUCTS] == ["route", "mission", "final_glide", "glide_reach"]
    assert POLAR_FILE.is_file()  # the polar ships with the package (demos/data)


@pytest.mark.parametrize("key", [p.key for p in available_products()])
def test_product_meets_its_reference(key: str, tmp_path) -> None:
    case = next(p for p in PRODUCTS if p.key == key)
    run = run_product(case, tmp_path, plots=True)
    result = run.result
    assert isinstance(result, Outcome)
    assert dataclasses.is_dataclass(result)
    with pytest.raises(dataclasses.FrozenInstanceError):
        result.message = "changed"  # type: ignore[misc]
    assert result.ok and run.status == "solved", result.message
    assert run.check.met, (run.check.numbers, run.check.reference)
    data = json.loads((tmp_path / f"{key}.json").read_text())
    assert data["status"] == result.status.value and data["message"] == result.message
    import matplotlib.image  # the figure `plot()` drew, read back by Matplotlib

    image = matplotlib.image.imread(tmp_path / f"{key}.png")
    assert run.figure == str(tmp_path / f"{key}.png") and min(image.shape[:2]) > 200


def test_demo_report_lists_every_product(run_cli, tmp_path, monkeypatch) -> None:
    """`glideplan demo` (dissertation cases left out here for time): the report's products
    section has one row per product with its status, reference and check."""
    import glideplan.demos

    monkeypatch.setattr(glideplan.demos, "demo_cases", lambda: [])
    keep = [p for p in available_products() if p.key != "route"]  # left out: the hook's row
    monkeypatch.setattr("glideplan.demos.products.available_products", lambda: tuple(keep))
    code, _, err = run_cli("demo", "--out", str(tmp_path), "--no-plots")
    assert code == 0, err
    report = (tmp_path / "report.md").read_text()
    section = report[report.index("## Products") :]
    for case in keep:
        row = next(line for line in section.splitlines() if line.startswith(f"| {case.name} |"))
        cells = [c.strip() for c in row.strip("|").split("|")]
        assert cells[2] == "solved" and cells[5] == "met", row
    assert "Not run (not available in this build): route: double gyre" in section
    assert math.isfinite(float(section.split("|")[-2]))  # the seconds column of the last row
