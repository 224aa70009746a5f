"""Simulated cross-domain check: which feature set carries over from one rig to another.

Decided before any look at recordings (issue 17): for every pair of datasets (A, B) generated
from different rig recipes (other bearing, speed, sample rates, structural modes, sensor,
background), a classifier is trained on A and scored on B, per feature set. The feature set
with the best mean balanced accuracy over the ordered pairs becomes ``cmtool train``'s default.
The classifier is the one ``cmtool train`` keeps for them: the one their recipes name in
``[training] classifier`` (extra trees after a scaler for the rig recipes), else a random forest
(until stop 79 the forest was the check's classifier for every dataset; ``--classifier
random_forest`` gives its figures). Its choice is not tuned here. A union set
(``evidence+scale-free``) is the columns of its parts.

Faulty signals whose fault SNR (where their impacts ring) is below ``MIN_FAULT_SNR_DB`` are
left out on both sides, as ``cmtool train`` leaves them out by default: a label that says a
fault is there when nothing in the signal can show it (a pit outside the load zone) teaches a
model to call quiet machines faulty, and scores a detector on what no detector can see.

The classes are weighed as ``cmtool train`` weighs them (``cmtool.classifier.CLASS_WEIGHT``);
``--class-weight none`` compares it unweighted, and ``--classifiers`` runs every
candidate of ``cmtool train`` on the default feature set, ``--classifier NAME`` one of them on
every set in place of the recipe's.

Run (after generating the datasets; feature tables are cached in CACHE):
    cmtool generate datasets/cwru-rig.toml --out data/cwru-rig --workers 2
    cmtool generate datasets/mfpt-rig.toml --out data/mfpt-rig --workers 2
    .venv/bin/python benchmarks/cross_domain.py data/cwru-rig data/mfpt-rig
    [--class-weight none] [--classifiers | --classifier random_forest]
"""

import argparse
import hashlib
import time
from itertools import permutations
from pathlib import Path

import numpy as np
from sklearn.metrics import balanced_accuracy_score, confusion_matrix, recall_score
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import StandardScaler

from cmtool import classifier
from cmtool.datasets import read_dataset
from features import FEATURE_SETS, FeatureExtractor

MIN_FAULT_SNR_DB = -10.0
CACHE = Path(".cache/cross_domain")


def _digest(frame) -> str:
    """A digest of a dataset's signals and labels: the cache key of its feature tables (until
    stop 37 the key was the folder's name and row count, so a regenerated dataset of the same
    size read the features of the one before)."""
    digest = hashlib.sha1()
    for label, signal in zip(frame["label"], frame["signal"], strict=True):
        digest.update(str(label).encode())
        digest.update(np.ascontiguousarray(signal).tobytes())
    return digest.hexdigest()[:16]


def feature_table(name: str, frame, feature_set: str) -> np.ndarray:
    """A dataset's feature table, from ``CACHE`` where it holds one for these signals and these
    columns (the key has both: until stop 78 it had the signals only, so a table cached before
    a feature set gained columns was read after it)."""
    CACHE.mkdir(parents=True, exist_ok=True)
    ext = FeatureExtractor(feature_set=feature_set, n_jobs=2).fit(frame)
    columns = hashlib.sha1("\n".join(ext.feature_names_out_).encode()).hexdigest()[:8]
    cached = CACHE / f"{name}-{feature_set}-{_digest(frame)}-{columns}.npy"
    if cached.is_file():
        return np.load(cached)
    table = ext.transform(frame)
    np.save(cached, table)
    return table


def recipes_classifier(folders: list[Path]) -> str:
    """The classifier ``cmtool train`` keeps for these datasets: the one their recipes name in
    ``[training] classifier``, the same for all (``random_forest``, the check's classifier until
    stop 79, where none names one); a ``SystemExit`` where they name different ones."""
    named = {
        classifier.recipe_classifier(recipe.read_text()) if recipe.is_file() else None
        for recipe in (folder / "recipe.toml" for folder in folders)
    }
    if len(named) > 1:
        raise SystemExit(
            f"the recipes name different classifiers {sorted(map(str, named))}: "
            "choose one with --classifier"
        )
    return named.pop() or "random_forest"


def main(
    paths: list[str], class_weight: str | None, all_classifiers: bool, model: str | None = None
) -> None:
    frames = {Path(p).name: read_dataset(p) for p in paths}
    sets = (classifier.DEFAULT_FEATURE_SET,) if all_classifiers else FEATURE_SETS
    tables: dict[tuple[str, str], np.ndarray] = {}
    CACHE.mkdir(parents=True, exist_ok=True)
    # a union set is the columns of its parts: compute those first
    needed = {part for feature_set in sets for part in feature_set.split("+")} | set(sets)
    for feature_set in (f for f in FEATURE_SETS if f in needed):
        start = time.perf_counter()
        for name, frame in frames.items():
            if "+" in feature_set:  # a union: the columns of its parts, in order
                parts = [tables[part, name] for part in feature_set.split("+")]
                tables[feature_set, name] = np.hstack(parts)
                continue
            tables[feature_set, name] = feature_table(name, frame, feature_set)
        print(f"features {feature_set}: {time.perf_counter() - start:.0f} s")
    keep = {
        name: ~(frame["fault_snr_db"].to_numpy() < MIN_FAULT_SNR_DB)
        for name, frame in frames.items()
    }
    for name, mask in keep.items():
        print(
            f"{name}: {int(mask.sum())} of {mask.size} signals kept (fault SNR >= "
            f"{MIN_FAULT_SNR_DB:g} dB or healthy)"
        )
    print()
    print(
        "| feature set | "
        + " | ".join(f"{a} -> {b}" for a, b in permutations(frames, 2))
        + " | mean |"
    )
    print("|---|" + "---|" * (len(frames) * (len(frames) - 1) + 1))
    labels = sorted(set.union(*(set(f["label"]) for f in frames.values())))
    if all_classifiers:
        models = classifier.candidate_classifiers(0, class_weight)
    else:  # one of cmtool train's candidates on every feature set
        model = model or recipes_classifier([Path(p) for p in paths])
        models = {model: classifier.candidate_classifiers(0, class_weight)[model]}
    for feature_set in sets:
        for name, estimator in models.items():
            scores = []
            for a, b in permutations(frames, 2):
                fitted = make_pipeline(StandardScaler(), estimator)
                fitted.fit(tables[feature_set, a][keep[a]], frames[a]["label"].to_numpy()[keep[a]])
                predicted = fitted.predict(tables[feature_set, b][keep[b]])
                truth = frames[b]["label"].to_numpy()[keep[b]]
                scores.append(balanced_accuracy_score(truth, predicted))
                recall = recall_score(truth, predicted, labels=labels, average=None)
                print(f"  ({feature_set}, {name}, {a} -> {b}: rows {labels}):")
                print("  " + str(confusion_matrix(truth, predicted, labels=labels).tolist()))
                pairs = zip(labels, recall, strict=True)
                print("  recall " + ", ".join(f"{k} {r:.2f}" for k, r in pairs))
            cells = " | ".join(f"{s:.3f}" for s in scores)
            print(f"| {feature_set}, {name} | {cells} | {np.mean(scores):.3f} |")


#: The classes in the order recall is reported.
LABELS = ["ball", "healthy", "inner", "outer"]


def extra_trees_score(train_x, train_y, test_x, test_y, seeds: int = 3):
    """``cmtool train``'s model for the rig recipes (extra trees after a scaler, classes
    weighed) trained on one table and scored on another, over ``seeds`` seeds.

    Returns (mean balanced accuracy, mean recall per ``LABELS`` class, one accuracy a seed).
    """
    accuracy, recall = [], []
    for seed in range(seeds):
        model = make_pipeline(
            StandardScaler(),
            classifier.candidate_classifiers(seed, classifier.CLASS_WEIGHT)["extra_trees"],
        )
        predicted = model.fit(train_x, train_y).predict(test_x)
        accuracy.append(balanced_accuracy_score(test_y, predicted))
        recall.append(recall_score(test_y, predicted, labels=LABELS, average=None))
    return float(np.mean(accuracy)), np.mean(recall, axis=0), accuracy


def print_cell(title, train_x, train_y, test_x, test_y):
    """:func:`extra_trees_score` of one train -> test cell, printed as ``title: score (recall
    per class)``; returns (mean balanced accuracy, mean recall per ``LABELS`` class)."""
    score, recall, _ = extra_trees_score(train_x, train_y, test_x, test_y)
    per_class = ", ".join(f"{k} {r:.2f}" for k, r in zip(LABELS, recall, strict=True))
    print(f"{title}: {score:.3f} (recall {per_class})", flush=True)
    return score, recall


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("datasets", nargs="+", help="dataset folders of different rig recipes")
    parser.add_argument(
        "--class-weight", choices=("balanced", "none"), default=classifier.CLASS_WEIGHT or "none"
    )
    parser.add_argument(
        "--classifiers", action="store_true", help="every cmtool train candidate, default set"
    )
    parser.add_argument(
        "--classifier",
        choices=sorted(classifier.candidate_classifiers()),
        help="every feature set with this cmtool train candidate instead of the one the "
        "datasets' recipes name",
    )
    args = parser.parse_args()
    weight = None if args.class_weight == "none" else args.class_weight
    main(args.datasets, weight, args.classifiers, args.classifier)
