"""`glideplan reproduce`: the index.json schema, verdicts that follow from their numbers,
failing figures (exit 1), bad --only lists (exit 2), file names, no solvers in figures/."""

import json
import math
import pathlib
import re

import pytest

from glideplan.figures import load_all
from glideplan.figures.registry import Comparison, FigureReport, Printed, reproducible

CHEAP = "fig2.2,fig4.1,fig5.1,table5.2,fig7.3,fig7.7"
ROW_KEYS = {
    "quantity", "unit", "ours", "dissertation", "dissertation_source", "reference",
    "reference_source", "tolerance", "verdict", "note",
}  # fmt: skip
FIGURES = pathlib.Path(__file__).parents[2] / "src" / "glideplan" / "figures"


def _expected_verdict(row: dict) -> str:
    """The rule of issue 10, written out again independently of the library."""
    ours, printed, tol = row["ours"], row["dissertation"], row["tolerance"]
    if printed is None:
        return "not printed"
    if isinstance(printed, str) or isinstance(ours, str):
        return "agrees" if ours == printed else "differs"
    if ours is None or not math.isfinite(ours):
        return "differs"
    return "agrees" if abs(ours - printed) <= tol else "differs"


@pytest.fixture(scope="module")
def index(tmp_path_factory):
    from glideplan.cli.app import main

    out = tmp_path_factory.mktemp("reproduce")
    assert main(["reproduce", "--only", CHEAP, "--out", str(out)]) == 0
    return out, json.loads((out / "index.json").read_text())


def test_index_schema(index):
    _, doc = index
    assert set(doc) == {"figures"}
    assert list(doc["figures"]) == CHEAP.split(",")
    for fid, fig in doc["figures"].items():
        assert set(fig) == {"title", "files", "status", "rows"}, fid
        assert fig["status"] == "computed" and fig["rows"], fid
        for row in fig["rows"]:
            assert set(row) == ROW_KEYS
            for key in ("ours", "dissertation", "reference"):
                assert row[key] is None or isinstance(row[key], (int, float, str)), (fid, row)
                assert not isinstance(row[key], bool)
            if row["dissertation"] is not None:
                assert row["dissertation_source"], row
                if not isinstance(row["dissertation"], str):
                    assert row["tolerance"] is not None and row["tolerance"] >= 0
            if row["reference"] is not None:
                assert row["reference_source"], row


def test_every_verdict_follows_from_its_numbers(index):
    _, doc = index
    counts = {"agrees": 0, "differs": 0, "not printed": 0}
    for fig in doc["figures"].values():
        for row in fig["rows"]:
            assert row["verdict"] == _expected_verdict(row), row
            counts[row["verdict"]] += 1
            if row["verdict"] == "differs":
                assert row["note"].strip(), row
    assert min(counts.values()) > 0, counts  # the cheap set exercises all three


def test_index_md_is_rendered_from_the_same_rows(index):
    out, doc = index
    text = (out / "index.md").read_text()
    for fig in doc["figures"].values():
        for row in fig["rows"]:
            assert row["quantity"].replace("|", "\\|") in text
    total = sum(len(f["rows"]) for f in doc["figures"].values())
    assert f"Rows: {total};" in text


def test_output_files_named_one_way(index):
    """Every file is `<id with _ for .>[_what].<ext>` (fig7_17.png, fig4_7_candidates.png)."""
    out, doc = index
    for fid, fig in doc["figures"].items():
        stem = fid.replace(".", "_")
        for name in fig["files"]:
            assert re.fullmatch(rf"{stem}(_[a-z0-9_]+)?\.(png|csv|md)", name), name
            assert (out / name).stat().st_size > 0


@pytest.fixture
def broken_figures(monkeypatch):
    """Two temporary figures: one raises, one returns a 'differs' row with no note."""
    from glideplan.figures import registry

    load_all()
    figures = dict(registry._FIGURES)
    monkeypatch.setattr(registry, "_FIGURES", figures)

    @reproducible("fig99.1", title="always fails", dissertation="none")
    def _fails(out_dir, *, full=False):
        raise RuntimeError("solver diverged")

    @reproducible("fig99.2", title="untold difference", dissertation="none")
    def _untold(out_dir, *, full=False):
        return FigureReport(rows=(Comparison("x", 2.0, dissertation=1.0,
                                             dissertation_source="s", tolerance=0.1),))  # fmt: skip

    return figures


def test_a_failing_figure_exits_1_and_is_named(broken_figures, run_cli, tmp_path):
    code, out, err = run_cli("reproduce", "--only", "fig99.1,fig2.2,fig99.2", "--out",
                             str(tmp_path))  # fmt: skip
    assert code == 1
    lines = [ln for ln in err.splitlines() if ln.startswith("glideplan: error:")]
    assert len(lines) == 1 and "fig99.1" in lines[0] and "solver diverged" in lines[0]
    assert "fig99.2" in lines[0] and "say why" in lines[0]
    assert "Traceback" not in err
    doc = json.loads((tmp_path / "index.json").read_text())
    assert doc["figures"]["fig99.1"]["status"].startswith("failed: RuntimeError")
    assert doc["figures"]["fig99.1"]["rows"] == []
    assert doc["figures"]["fig2.2"]["status"] == "computed"
    assert "wrote 1 figure of 3 figures to" in out


def test_summary_counts_figures_and_tables_apart():
    """The summary line names figures and tables by their ids (fig... / table...), with the
    singular for one: `--only fig2.2,table4.3` wrote "1 figure and 1 table"."""
    from glideplan.cli.reproduce import _count_kinds
    from glideplan.figures import get_figure, load_all

    load_all()
    specs = [get_figure(i) for i in ("fig2.2", "table4.3", "fig3.1", "table5.2")]
    assert _count_kinds(specs[:2]) == "1 figure and 1 table"
    assert _count_kinds(specs) == "2 figures and 2 tables"
    assert _count_kinds(specs[1:2]) == "1 table"
    assert _count_kinds([]) == "0 figures"


@pytest.mark.parametrize(
    ("only", "needle"),
    [("", "empty list"), (",,", "empty list"), (" , ", "empty list"), ("fig9.9", "unknown")],
)
def test_bad_only_lists(cli_error, tmp_path, only, needle):
    line = cli_error("reproduce", "--only", only, "--out", str(tmp_path))
    assert needle in line and "fig2.2" in line  # names the ids that exist
    assert not (tmp_path / "index.md").exists()


def test_figures_hold_no_solvers():
    """Optimisations and root finders live in the library (studies/, planners/, design/)."""
    banned = ("scipy.optimize", "minimize(", "brentq", "least_squares", "solve_ivp", "casadi",
              "import scipy.integrate")  # fmt: skip
    for path in FIGURES.glob("*.py"):
        text = path.read_text()
        for word in banned:
            assert word not in text, f"{path.name} uses {word}"


def test_printed_values_are_data_with_a_source():
    """Every chapter module keeps the dissertation's numbers as `Printed` data (module
    constants), and no row types a verdict word of its own."""
    load_all()
    for path in FIGURES.glob("ch*.py"):
        text = path.read_text()
        for typed in ('"consistent"', '"ok"', "rounded up", "(falls)", "~6 %", "1.41x",
                      "at 1.67 L", "2.5 L / 10 s"):  # fmt: skip
            assert typed not in text, f"{path.name}: {typed}"
    assert Printed("31.1", "section 7.2").value == 31.1
