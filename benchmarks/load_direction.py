"""Does the model need the load's direction drawn? (prints figures; not a test)

The rigs' publishers do not say where the radial load points relative to the accelerometer (at
12 o'clock on the CWRU motor housing; the MFPT sensor's mounting is not published), and CWRU's
own words put the load zone at 3 o'clock (../shared/rigs.md). Until stop 40 the recipes put
the load along the sensor's axis. Each rig recipe is generated as shipped and with
``operating.load_angle_deg = { min = -180, max = 180 }`` under ``[operating]`` (same seed:
every other draw the same), and the CWRU-rig recipe again with seed 777. Extra trees (``cmtool
train``'s model for the rig recipes, evidence+scale-free, classes weighed, faulty signals below
-10 dB fault SNR left out, three seeds) trained on either and scored on either, over three
directions: CWRU -> MFPT, MFPT -> CWRU777, CWRU -> CWRU777.

Run: .venv/bin/python benchmarks/load_direction.py FOLDER, with FOLDER holding cwru-rig-ehl,
mfpt-rig-ehl, cwru777-ehl (the recipes as shipped before stop 40) and cwru-rig-ang,
mfpt-rig-ang, cwru777-ang (with the load's direction drawn), each from ``cmtool generate``.
"""

import sys
from pathlib import Path

import numpy as np
from sklearn.metrics import balanced_accuracy_score, recall_score
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import StandardScaler

from cmtool import classifier
from cmtool.datasets import read_dataset
from features import FeatureExtractor

sys.path.insert(0, str(Path(__file__).resolve().parent))
from cross_domain import CACHE, MIN_FAULT_SNR_DB, _digest  # noqa: E402

LABELS = ["ball", "healthy", "inner", "outer"]
DIRECTIONS = (("cwru-rig", "mfpt-rig"), ("mfpt-rig", "cwru777"), ("cwru-rig", "cwru777"))


def _table(name, frame):
    parts = []
    for feature_set in classifier.DEFAULT_FEATURE_SET.split("+"):
        cached = CACHE / f"{name}-{feature_set}-{_digest(frame)}.npy"
        if not cached.is_file():
            extractor = FeatureExtractor(feature_set=feature_set, n_jobs=2).fit(frame)
            np.save(cached, extractor.transform(frame))
        parts.append(np.load(cached))
    return np.hstack(parts)


def main(folder: Path) -> None:
    CACHE.mkdir(parents=True, exist_ok=True)
    frames, tables = {}, {}
    for rig in ("cwru-rig", "mfpt-rig", "cwru777"):
        for variant in ("ehl", "ang"):
            name = f"{rig}-{variant}"
            frames[name] = read_dataset(folder / name)
            tables[name] = _table(name, frames[name])
    keep = {n: ~(f["fault_snr_db"].to_numpy() < MIN_FAULT_SNR_DB) for n, f in frames.items()}
    for test_variant in ("ang", "ehl"):
        for train_variant in ("ehl", "ang"):
            means = []
            for train_rig, test_rig in DIRECTIONS:
                train, test = f"{train_rig}-{train_variant}", f"{test_rig}-{test_variant}"
                accuracy, recall = [], []
                for seed in range(3):
                    weight = classifier.CLASS_WEIGHT
                    model = make_pipeline(
                        StandardScaler(),
                        classifier.candidate_classifiers(seed, weight)["extra_trees"],
                    )
                    model.fit(tables[train][keep[train]], frames[train]["label"][keep[train]])
                    predicted = model.predict(tables[test][keep[test]])
                    truth = frames[test]["label"].to_numpy()[keep[test]]
                    accuracy.append(balanced_accuracy_score(truth, predicted))
                    recall.append(recall_score(truth, predicted, labels=LABELS, average=None))
                means.append(np.mean(accuracy))
                per_class = zip(LABELS, np.mean(recall, axis=0), strict=True)
                print(
                    f"{train} -> {test}: {np.mean(accuracy):.3f} (recall "
                    + ", ".join(f"{k} {r:.2f}" for k, r in per_class)
                    + ")",
                    flush=True,
                )
            print(f"trained {train_variant}, tested {test_variant}: mean {np.mean(means):.3f}\n")


if __name__ == "__main__":
    main(Path(sys.argv[1]))
