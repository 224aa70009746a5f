"""How the pooled verdict of ``diagnose --model`` depends on the rule's weight in the pooling.

For each signal of a simulated dataset (healthy signals and faults at fault SNR >= -10 dB):
the rule's probabilities (``cmtool.diagnose.rule_probabilities``) and the model's; then for w
from 0 (the model alone) to 1 (the rule alone) the most probable class of p_rule^w p_model^(1-w)
(``diagnose`` pools with w = 0.5): accuracy, balanced accuracy, log loss and recall per class.
docs/diagnosis.md "A line two faults share counts for one". Simulated datasets only.

Run: .venv/bin/python benchmarks/pooling_weight.py MODEL.skops DATASET
"""

from __future__ import annotations

import math
import sys

import numpy as np

FLOOR = 1e-6  # as cmtool.diagnose.pool_probabilities
WEIGHTS = (0.0, 0.3, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0)


def pooled(rule: dict, model: dict, w: float) -> dict:
    score = {
        k: math.exp(
            w * math.log(max(rule.get(k, 0.0), FLOOR))
            + (1 - w) * math.log(max(model.get(k, 0.0), FLOOR))
        )
        for k in rule
    }
    total = sum(score.values())
    return {k: v / total for k, v in score.items()}


def main(model_path: str, dataset: str) -> None:
    from _diagnosed import diagnosed

    from cmtool.classifier import load_model
    from cmtool.datasets import read_dataset
    from cmtool.diagnose import rule_probabilities, verdict_probabilities

    model = load_model(model_path)
    frame = read_dataset(dataset)
    rows = [
        (
            label,
            rule_probabilities(d.candidates),
            verdict_probabilities(d.model_verdict["probabilities"]),
        )
        for label, d in diagnosed(model, frame, visible_only=True)
    ]
    truth = np.array([t for t, _, _ in rows])
    classes = sorted(set(truth))
    print(f"{dataset}: {len(rows)} signals, model {model_path}")
    for w in WEIGHTS:
        verdicts, losses = [], []
        for t, rule, model_p in rows:
            p = pooled(rule, model_p, w)
            verdicts.append(max(p, key=p.get))
            losses.append(-math.log(max(p.get(t, 0.0), 1e-9)))
        right = np.array(verdicts) == truth
        recall = [right[truth == c].mean() for c in classes]
        per = ", ".join(f"{c} {r:.2f}" for c, r in zip(classes, recall, strict=True))
        print(
            f"  w = {w:.1f}: accuracy {right.mean():.3f}, balanced {np.mean(recall):.3f}, "
            f"log loss {np.mean(losses):.3f} ({per})"
        )


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
