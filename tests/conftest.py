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


@pytest.fixture(scope="session")
def small_dataset():
    """The committed ``datasets/small`` (read once per session)."""
    from cmtool.datasets import read_dataset

    return read_dataset(pathlib.Path(__file__).resolve().parents[1] / "datasets" / "small")


@pytest.fixture(scope="session")
def small_bundle(small_dataset):
    """``cmtool train``'s defaults on ``datasets/small`` (trained once per session: the
    diagnosis tests and the small target share it)."""
    from cmtool.classifier import train

    recipe = pathlib.Path(__file__).resolve().parents[1] / "datasets" / "small" / "recipe.toml"
    return train(small_dataset, recipe=recipe.read_text())
