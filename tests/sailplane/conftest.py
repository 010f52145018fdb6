"""Fixtures of the sailplane tests: the polar fixtures of tests/data/polars."""

import pathlib

import pytest

FIXTURES = pathlib.Path(__file__).resolve().parents[1] / "data" / "polars"


@pytest.fixture
def fixtures_dir() -> pathlib.Path:
    return FIXTURES


@pytest.fixture
def dg_file() -> pathlib.Path:
    """DG-1001M polar of dissertation eq. (5.26), sampled at 80, 105, 150 km/h."""
    return FIXTURES / "DG-1001M_ch5.plr"


@pytest.fixture
def dg_polar(dg_file):
    from glideplan.sailplane import polar_from_file, read_plr

    return polar_from_file(read_plr(dg_file))
