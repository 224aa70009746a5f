"""The bearing's own form-error lines in the rig recipes: what a model gains and loses.

docs/realism.md 9. Two rig recipes, each generated as shipped ("plain") and with
``[background] form_inner_db`` and ``form_ball_db`` ("form"); ``cmtool train``'s model for the
rig recipes (extra trees after a scaler, classes weighed, three seeds) on the default feature
set, trained on one rig recipe's draw and scored on the other's, both directions, healthy
signals and faults at fault SNR >= -10 dB (as ``cmtool train`` keeps them):

- plain -> plain: the shipped recipes;
- form -> form: both with the lines;
- form -> plain: a model trained with the lines on bearings without them;
- plain -> form: a model trained on perfect bearings meeting the lines.

Run (the "form" recipes are copies of the rig recipes with the two keys under
``[background]``, e.g. ``form_inner_db = { min = -20, max = 10 }`` and ``form_ball_db = { min =
-30, max = 0 }``):
    cmtool generate datasets/cwru-rig.toml --out data/cwru-plain --workers 2  (and mfpt-rig)
    cmtool generate cwru-form.toml --out data/cwru-form --workers 2           (and mfpt)
    .venv/bin/python benchmarks/form_lines.py data/cwru-plain data/mfpt-plain \\
        data/cwru-form data/mfpt-form
"""

import sys
from pathlib import Path

import numpy as np
from cross_domain import CACHE, MIN_FAULT_SNR_DB, feature_table, print_cell

from cmtool import classifier
from cmtool.datasets import read_dataset


def _table(path: str):
    frame = read_dataset(path)
    keep = ~(frame["fault_snr_db"].to_numpy() < MIN_FAULT_SNR_DB)
    CACHE.mkdir(parents=True, exist_ok=True)
    table = feature_table(Path(path).name, frame, classifier.DEFAULT_FEATURE_SET)
    return table[keep], frame["label"].to_numpy()[keep]


def main(plain_a: str, plain_b: str, form_a: str, form_b: str) -> None:
    data = {
        ("plain", "a"): _table(plain_a),
        ("plain", "b"): _table(plain_b),
        ("form", "a"): _table(form_a),
        ("form", "b"): _table(form_b),
    }
    for train, test in (("plain", "plain"), ("form", "form"), ("form", "plain"), ("plain", "form")):
        scores = []
        for a, b in (("a", "b"), ("b", "a")):
            title = f"{train} {a} -> {test} {b}"
            score, _ = print_cell(title, *data[train, a], *data[test, b])
            scores.append(score)
        print(f"{train} -> {test}, mean of both directions: {np.mean(scores):.3f}", flush=True)


if __name__ == "__main__":
    main(*sys.argv[1:5])
