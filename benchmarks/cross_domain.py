"""Simulated cross-domain check: which feature set carries over from one rig to another.

Decided before any look at recordings (issue 17): for every pair of datasets (A, B) generated
from different rig recipes (other bearing, speed, sample rates, structural modes, sensor,
background), a classifier is trained on A and scored on B, per feature set. The feature set
with the best mean balanced accuracy over the ordered pairs becomes ``cmtool train``'s default.
The classifier is the one ``cmtool train`` keeps most often (a random forest after a scaler);
its choice is not tuned here.

Run (after generating the datasets):
    cmtool generate datasets/cwru-rig.toml --out data/cwru-rig --workers 2
    cmtool generate datasets/mfpt-rig.toml --out data/mfpt-rig --workers 2
    .venv/bin/python benchmarks/cross_domain.py data/cwru-rig data/mfpt-rig
"""

import sys
import time
from itertools import permutations
from pathlib import Path

import numpy as np
from sklearn.ensemble import RandomForestClassifier
from sklearn.metrics import balanced_accuracy_score, confusion_matrix
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import StandardScaler

from cmtool.datasets import read_dataset
from features import FEATURE_SETS, FeatureExtractor


def main(paths: list[str]) -> None:
    frames = {Path(p).name: read_dataset(p) for p in paths}
    tables: dict[tuple[str, str], np.ndarray] = {}
    for feature_set in FEATURE_SETS:
        start = time.perf_counter()
        for name, frame in frames.items():
            ext = FeatureExtractor(feature_set=feature_set, n_jobs=2).fit(frame)
            tables[feature_set, name] = ext.transform(frame)
        print(f"features {feature_set}: {time.perf_counter() - start:.0f} s")
    print()
    print(
        "| feature set | "
        + " | ".join(f"{a} -> {b}" for a, b in permutations(frames, 2))
        + " | mean |"
    )
    print("|---|" + "---|" * (len(frames) * (len(frames) - 1) + 1))
    labels = sorted(set.union(*(set(f["label"]) for f in frames.values())))
    for feature_set in FEATURE_SETS:
        scores = []
        for a, b in permutations(frames, 2):
            model = make_pipeline(
                StandardScaler(), RandomForestClassifier(n_estimators=300, random_state=0)
            )
            model.fit(tables[feature_set, a], frames[a]["label"].to_numpy())
            predicted = model.predict(tables[feature_set, b])
            truth = frames[b]["label"].to_numpy()
            scores.append(balanced_accuracy_score(truth, predicted))
            if feature_set == "evidence":
                print(f"  ({feature_set} {a} -> {b} confusion, rows {labels}):")
                print("  " + str(confusion_matrix(truth, predicted, labels=labels).tolist()))
        cells = " | ".join(f"{s:.3f}" for s in scores)
        print(f"| {feature_set} | {cells} | {np.mean(scores):.3f} |")


if __name__ == "__main__":
    main(sys.argv[1:])
