"""A trained model's balanced accuracy on what a dataset's signals show (prints figures).

Scores a model (``cmtool train``) on a dataset's healthy signals and its faults at fault SNR
>= -10 dB (``cmtool.classifier.visible_faults``: below it nothing in a signal shows the
fault its label names; ``cmtool evaluate`` scores every signal), with each class's recall.
Used for the simulated proxies of issue 17's universal model (docs/realism.md 6).

Run: .venv/bin/python benchmarks/score_visible.py MODEL DATASET [DATASET ...]
"""

import sys

from sklearn.metrics import balanced_accuracy_score

from cmtool.classifier import MIN_FAULT_SNR_DB, load_model, visible_faults
from cmtool.datasets import read_dataset


def main(model: str, paths: list[str]) -> None:
    bundle = load_model(model)
    for path in paths:
        frame = read_dataset(path)
        frame = frame[visible_faults(frame, MIN_FAULT_SNR_DB).to_numpy()]
        truth = frame["label"].astype(str).to_numpy()
        predicted = bundle["pipeline"].predict(frame)
        recall = ", ".join(
            f"{c} {(predicted[truth == c] == c).mean():.2f}" for c in sorted(set(truth))
        )
        print(
            f"{path}: {len(frame)} signals, balanced accuracy "
            f"{balanced_accuracy_score(truth, predicted):.3f} ({recall})"
        )


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2:])
