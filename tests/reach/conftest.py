"""Fixtures of the glide-reach tests: a polar, small synthetic terrains written as files."""

import pathlib

import numpy as np
import pytest

POLARS = pathlib.Path(__file__).resolve().parents[1] / "data" / "polars"


@pytest.fixture(scope="session")
def polar():
    """DG-1001M polar of dissertation eq. (5.26) (tests/data/polars)."""
    from glideplan.sailplane import polar_from_file, read_plr

    return polar_from_file(read_plr(POLARS / "DG-1001M_ch5.plr"))


@pytest.fixture(scope="session")
def polar_file() -> pathlib.Path:
    return POLARS / "DG-1001M_ch5.plr"


def flat_terrain(n: int = 121, south: float = 46.0, west: float = 7.0, span_lat: float = 0.6,
                 span_lon: float = 0.8, elevation: float = 0.0):
    from glideplan.terrain import Terrain

    lat = south + span_lat * np.arange(n) / (n - 1)
    lon = west + span_lon * np.arange(n) / (n - 1)
    return Terrain(lat, lon, np.full((n, n), elevation, dtype=np.float32))
