"""Severity from features: is a pit's size in what the feature table sees? (issue 18)

For each fault class, a random forest regresses log10 of the pit's length in the rolling
direction (``defect_length_m``) on the 73 features of ``features.FeatureExtractor`` ("all"),
on the faulty signals of the rig recipes that a detector can see (fault SNR >= -10 dB, as
``cmtool train`` keeps them): within one recipe (5-fold cross-validation) and from one recipe to
the other. Printed per class: the mean absolute error in log10 (and as a factor), the same
for the baseline that always answers the training set's median length, and R^2 (0: no better
than the mean; negative: worse). A feature table that carries the size would beat the
baseline within a recipe first.

Run (feature tables are cached beside the datasets, about a minute each):
    cmtool generate datasets/cwru-rig.toml --out data/cwru-rig --workers 2
    cmtool generate datasets/mfpt-rig.toml --out data/mfpt-rig --workers 2
    .venv/bin/python benchmarks/severity_regression.py data/cwru-rig data/mfpt-rig
"""

from __future__ import annotations

import argparse
from itertools import permutations
from pathlib import Path

import numpy as np
from sklearn.ensemble import RandomForestRegressor
from sklearn.model_selection import KFold, cross_val_predict

from cmtool.datasets import read_dataset
from features import FeatureExtractor

MIN_FAULT_SNR_DB = -10.0
CLASSES = ("inner", "outer", "ball")


def _table(path: Path, frame) -> np.ndarray:
    cached = path.parent / f"{path.name}-features-all-{len(frame)}.npy"
    if cached.is_file():
        return np.load(cached)
    table = FeatureExtractor(feature_set="all", n_jobs=2).fit(frame).transform(frame)
    np.save(cached, table)
    return table


def _scores(truth: np.ndarray, predicted: np.ndarray, training: np.ndarray) -> str:
    error = float(np.mean(np.abs(predicted - truth)))
    baseline = float(np.mean(np.abs(np.median(training) - truth)))
    r2 = 1.0 - np.sum((predicted - truth) ** 2) / np.sum((truth - truth.mean()) ** 2)
    return f"{error:.3f} (x{10**error:.2f}) | {baseline:.3f} (x{10**baseline:.2f}) | {r2:.2f}"


def _forest() -> RandomForestRegressor:
    return RandomForestRegressor(n_estimators=300, random_state=0, n_jobs=2)


def main(paths: list[str]) -> None:
    data = {}
    for p in paths:
        path = Path(p)
        frame = read_dataset(path)
        table = np.nan_to_num(_table(path, frame))
        for label in CLASSES:
            visible = frame["fault_snr_db"] >= MIN_FAULT_SNR_DB
            keep = ((frame["label"] == label) & visible).to_numpy()
            y = np.log10(frame["defect_length_m"].to_numpy()[keep])
            data[path.name, label] = (table[keep], y)
    names = [Path(p).name for p in paths]
    print("| class | trained on -> scored on | signals | MAE log10 | median baseline | R^2 |")
    print("|---|---|---|---|---|---|")
    for label in CLASSES:
        for name in names:
            X, y = data[name, label]
            folds = KFold(5, shuffle=True, random_state=0)
            predicted = cross_val_predict(_forest(), X, y, cv=folds)
            print(f"| {label} | {name} (5-fold) | {y.size} | {_scores(y, predicted, y)} |")
        for a, b in permutations(names, 2):
            (Xa, ya), (Xb, yb) = data[a, label], data[b, label]
            predicted = _forest().fit(Xa, ya).predict(Xb)
            print(f"| {label} | {a} -> {b} | {yb.size} | {_scores(yb, predicted, ya)} |")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("datasets", nargs="+", help="dataset folders of rig recipes")
    main(parser.parse_args().datasets)
