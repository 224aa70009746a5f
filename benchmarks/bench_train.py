"""Wall time of ``cmtool train``'s work on one and on two workers, and the same model.

``cmtool.classifier.train`` computes each signal's features and the rule detector's evidence
for the pooled calibration in one pass (one ``fault_evidence`` serves both), then fits the
models (each candidate on each grouped fold, the kept one without each end of the speed and
load ranges and on everything; ``cmtool.fits``, since stop 89), each in ``workers``
processes. This trains on a dataset with each worker count, prints the wall time, and
checks that the bundles agree (scores, out-of-fold predictions, calibration, probabilities
on the dataset's first signals). Default dataset: ``datasets/small``; docs/performance.md
(Speed, stop 43) quotes the universal recipe's stop-42 draw (``cmtool generate
datasets/universal.toml --out DATA``).

Run: .venv/bin/python benchmarks/bench_train.py [DATASET] [--workers 1 2]
"""

import argparse
import time
from pathlib import Path

import numpy as np

from cmtool.classifier import train
from cmtool.datasets import read_dataset

REPO = Path(__file__).resolve().parents[1]
COMPARED = ("scores", "cv_predictions", "pooled_calibration", "extrapolation", "feature_names")


def main(dataset: Path, workers: list[int]) -> None:
    frame = read_dataset(dataset)
    recipe = (dataset / "recipe.toml").read_text() if (dataset / "recipe.toml").is_file() else ""
    probe = frame.head(32)
    first = None
    for count in workers:
        start = time.perf_counter()
        bundle = train(frame, recipe=recipe, workers=count)
        seconds = time.perf_counter() - start
        proba = bundle["pipeline"].predict_proba(probe)
        same = ""
        if first is None:
            first = (bundle, proba)
        else:
            equal = all(first[0][k] == bundle[k] for k in COMPARED)
            equal = equal and np.array_equal(first[1], proba)
            same = f"; the same model as on {workers[0]}: {equal}"
        print(f"{dataset.name}: {len(frame)} signals, {count} worker(s): {seconds:.1f} s{same}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dataset", nargs="?", default=str(REPO / "datasets" / "small"))
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    args = parser.parse_args()
    main(Path(args.dataset), args.workers)
