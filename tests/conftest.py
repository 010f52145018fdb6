"""Shared test configuration: strict numerics and a non-interactive Matplotlib backend."""

import os

import numpy as np
import pytest

os.environ.setdefault("MPLBACKEND", "Agg")


@pytest.fixture(autouse=True)
def _strict_numpy():
    """Floating-point warnings (overflow, invalid, divide) are errors in every test."""
    with np.errstate(all="raise", under="ignore"):
        yield
