"""The rule detector's confidence is calibrated (issue 18): on simulated signals it has not
seen (the detector-bench recipe with a third seed), its mean confidence matches its accuracy."""

import re
from pathlib import Path

import numpy as np
import pytest

from cmtool.datasets import generate_dataset, read_dataset
from cmtool.diagnose import CANONICAL, diagnose_signal

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def fresh(tmp_path_factory):
    text = (REPO / "datasets" / "detector-bench.toml").read_text()
    text = re.sub(r"^seed = \d+", "seed = 27182", text, flags=re.MULTILINE)
    text = text.replace("count = 1000", "count = 66").replace("count = 400", "count = 27")
    tmp = tmp_path_factory.mktemp("fresh")
    recipe = tmp / "recipe.toml"
    recipe.write_text(text)
    generate_dataset(recipe, tmp / "data", workers=2)
    return read_dataset(tmp / "data")


def test_mean_confidence_matches_accuracy_on_unseen_simulations(fresh):
    correct, confidence = [], []
    for _, row in fresh.iterrows():
        x = np.asarray(row["signal"])
        # the verdict and its confidence only (race waviness, judged on healthy verdicts
        # after them, changes neither and runs five healthy simulations each)
        d = diagnose_signal(x, row["fs_hz"], row["rpm"], row["bearing"], waviness=False)
        correct.append(d.verdict == CANONICAL[row["label"]])
        confidence.append(d.confidence)
    correct, confidence = np.array(correct), np.array(confidence)
    n = correct.size
    assert n == 147
    # 147 signals: the accuracy's standard error is ~0.04; 0.12 is three of them. The former
    # 3 dB logistic was over-confident by 0.18 on the benchmark (0.857 against 0.674)
    assert abs(confidence.mean() - correct.mean()) < 0.12, (confidence.mean(), correct.mean())
    # and confident answers are the right ones more often than unsure ones
    sure = confidence >= np.median(confidence)
    assert correct[sure].mean() > correct[~sure].mean()
