"""The dissertation's printed values kept in the figure modules appear in its text."""

import pathlib
import re
from collections.abc import Iterator

import pytest

from glideplan.figures.registry import Printed

TEXT = pathlib.Path(__file__).parents[3] / "shared" / "dissertation"
MODULES = ("ch2", "ch3", "ch3_following", "ch4", "ch4_grids", "ch5", "ch6", "ch6_examples", "ch7",
           "ch7_glide_positioning")  # fmt: skip


def _printed(value: object) -> Iterator[Printed]:
    if isinstance(value, Printed):
        yield value
    elif isinstance(value, dict):
        for v in value.values():
            yield from _printed(v)
    elif isinstance(value, (tuple, list)):
        for v in value:
            yield from _printed(v)


def _all_printed() -> list[tuple[str, Printed]]:
    import importlib

    out = []
    for name in MODULES:
        mod = importlib.import_module(f"glideplan.figures.{name}")
        for attr, value in vars(mod).items():
            if attr.isupper():
                out += [(f"{name}.{attr}", p) for p in _printed(value)]
    return out


def test_every_printed_value_names_its_source():
    found = _all_printed()
    assert len(found) > 40
    for where, p in found:
        assert re.search(r"(section|Table|Fig|\(\d\.\d+\))", p.source), (where, p)
        if not p.word:
            assert p.tolerance is not None and p.tolerance > 0, (where, p)


@pytest.mark.skipif(not TEXT.is_dir(), reason="needs ../shared/dissertation (not in a clone)")
def test_printed_numbers_occur_in_the_dissertation():
    text = (TEXT / "optimal-paths-in-gliding-flight.txt").read_text()
    from glideplan.figures.ch4 import TABLE_4_3

    numbers = {p.text for _, p in _all_printed() if not p.word}
    numbers |= {value for *_, value in TABLE_4_3}
    missing = sorted(
        n for n in numbers if not re.search(rf"(?<![\d.]){re.escape(n)}(?![\d])", text)
    )
    assert not missing, missing
