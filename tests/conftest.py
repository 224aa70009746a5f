"""Shared fixtures: seeded rng, location of the measured recordings in ../shared/data."""

from __future__ import annotations

import pathlib

import numpy as np
import pytest

REPO = pathlib.Path(__file__).resolve().parents[1]
SHARED_DATA = REPO.parent / "shared" / "data"


@pytest.fixture
def rng() -> np.random.Generator:
    return np.random.default_rng(440)


@pytest.fixture
def shared_data() -> pathlib.Path:
    if not (SHARED_DATA / "MANIFEST.csv").is_file():
        pytest.skip("../shared/data is absent (a fresh clone alone has no measured recordings)")
    return SHARED_DATA
