"""Issue 8's accuracy target on the small recipe: >= 98 % on held-out operating points.

Healthy / inner / outer / ball waviness at SNR 10 dB (``datasets/small.toml``), accuracy by
grouped cross-validation (no speed/load point in both train and test), the best candidate
kept as ``cmtool train`` does. Checked on the committed dataset (seed 2026) and on a fresh
generation with another seed, so that the figure is not one lucky draw of orders, amplitudes
and noise. 0.98 of 192 signals allows three errors.
"""

from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
TARGET = 0.98

pytestmark = pytest.mark.validation


def _best_grouped_accuracy(frame):
    from cmtool.classifier import train

    bundle = train(frame)
    print({k: round(v, 3) for k, v in bundle["scores"].items()}, bundle["extrapolation"])
    return bundle["scores"][bundle["best"]]


def test_committed_small_dataset_meets_the_target(small_bundle):
    # the session's training of cmtool train's defaults on datasets/small (tests/conftest.py)
    print({k: round(v, 3) for k, v in small_bundle["scores"].items()})
    assert small_bundle["scores"][small_bundle["best"]] >= TARGET


def test_small_recipe_with_another_seed_meets_the_target(tmp_path):
    from cmtool.datasets import generate_dataset, read_dataset

    text = (REPO / "datasets" / "small.toml").read_text()
    assert "seed = 2026" in text
    recipe = tmp_path / "small.toml"
    recipe.write_text(text.replace("seed = 2026", "seed = 2031"))
    generate_dataset(recipe, tmp_path / "data", workers=2)
    frame = read_dataset(tmp_path / "data")
    assert len(frame) == 192
    assert _best_grouped_accuracy(frame) >= TARGET
