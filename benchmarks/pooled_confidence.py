"""Calibration of diagnose's verdicts with a model: rule, model and pooled (issue 18).

For every signal of a labelled dataset, ``diagnose_signal`` with the model: accuracy per
class and overall, mean confidence and expected calibration error (10 bins) of the rule's,
the model's and the pooled verdict. Simulated datasets only (never ../shared/data: that is
for tests and reporting).

Run: .venv/bin/python benchmarks/pooled_confidence.py MODEL.skops DATASET
(e.g. a model from ``cmtool train`` on ``datasets/cwru-rig.toml`` and a dataset generated from
the same recipe with another seed).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np


def main(model_path: str, dataset: str) -> None:
    from _diagnosed import diagnosed

    from cmtool.classifier import expected_calibration_error, load_model
    from cmtool.datasets import read_dataset
    from cmtool.diagnose import CANONICAL

    model = load_model(model_path)
    frame = read_dataset(dataset)
    truth, sources = [], {"pooled": [], "rule": [], "model": []}
    for label, d in diagnosed(model, frame):
        truth.append(label)
        probabilities = d.model_verdict["probabilities"]
        label = CANONICAL.get(d.model_verdict["label"], d.model_verdict["label"])
        sources["pooled"].append((d.verdict, d.confidence))
        sources["rule"].append((d.rule_verdict["label"], d.rule_verdict["confidence"]))
        sources["model"].append((label, max(probabilities.values())))
    truth = np.array(truth)
    print(f"{len(truth)} signals of {Path(dataset).name}, model {Path(model_path).name}")
    for name, pairs in sources.items():
        verdict = np.array([v for v, _ in pairs])
        confidence = np.array([c for _, c in pairs], dtype=float)
        right = verdict == truth
        per_class = ", ".join(f"{k} {np.mean(right[truth == k]):.2f}" for k in sorted(set(truth)))
        print(
            f"{name}: accuracy {right.mean():.3f} ({per_class}); mean confidence "
            f"{confidence.mean():.3f}, ECE {expected_calibration_error(confidence, right):.3f}"
        )


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
