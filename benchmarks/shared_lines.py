"""The rule's and the pooled verdicts on simulated datasets, and the faults also "DETECTED".

For each dataset (healthy signals and the faults at fault SNR >= -10 dB), ``diagnose_signal``
with the model: verdict accuracy of the rule and of the pooled verdict (per class), the pooled
confidence's expected calibration error, the share of right fault verdicts that report
another fault detected too, and the rule probability of the true class (mean, log loss).
docs/diagnosis.md "A line two faults share counts for one". Simulated datasets only.

Run: .venv/bin/python benchmarks/shared_lines.py MODEL.skops DATASET [DATASET ...]
"""

from __future__ import annotations

import sys

import numpy as np


def main(model_path: str, datasets: list[str]) -> None:
    from _diagnosed import diagnosed

    from cmtool.classifier import expected_calibration_error, load_model
    from cmtool.datasets import read_dataset
    from cmtool.diagnose import rule_probabilities

    model = load_model(model_path)
    for dataset in datasets:
        frame = read_dataset(dataset)
        truth, rule, pooled, others, p_true = [], [], [], [], []
        for label, d in diagnosed(model, frame, visible_only=True):
            truth.append(label)
            rule.append((d.rule_verdict["label"], d.rule_verdict["confidence"]))
            pooled.append((d.verdict, d.confidence))
            others.append(
                sum(c["detected"] and c["fault"] != d.rule_verdict["label"] for c in d.candidates)
            )
            p_true.append(rule_probabilities(d.candidates).get(label, 0.0))
        truth = np.array(truth)
        print(f"{dataset}: {len(truth)} signals")
        for name, pairs in (("rule", rule), ("pooled", pooled)):
            verdict = np.array([v for v, _ in pairs])
            confidence = np.array([c for _, c in pairs], dtype=float)
            right = verdict == truth
            per = ", ".join(f"{k} {np.mean(right[truth == k]):.3f}" for k in sorted(set(truth)))
            ece = expected_calibration_error(confidence, right)
            print(f"  {name}: accuracy {right.mean():.3f} ({per}); ECE {ece:.3f}")
        rule_verdict = np.array([v for v, _ in rule])
        right_fault = (truth != "healthy") & (rule_verdict == truth)
        also = np.array(others)[right_fault] > 0
        print(
            f"  right fault verdicts with another fault also DETECTED: {also.sum()} of "
            f"{right_fault.sum()} ({also.mean():.3f})"
        )
        p = np.clip(np.array(p_true), 1e-9, 1.0)
        print(
            f"  rule probability of the true class: mean {p.mean():.3f}, "
            f"log loss {-np.log(p).mean():.3f}"
        )


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2:])
