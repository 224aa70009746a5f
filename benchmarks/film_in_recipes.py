"""Would the rig recipes lose anything without the EHL film? (prints figures; not a test)

Without the film the lanes run about three times faster (docs/performance.md, "The film in the
lanes") and `datasets/cwru-rig.toml` generates about 1.8 times faster, so issue 17's speed
target asks whether the recipes need it. Each recipe is generated twice from the same seed,
once as shipped (`ehl = true`) and once with `ehl = false`, so that every drawn case has a
twin that differs only by the film; then

1. a forest tells the film's signals from their dry twins on the scale-free features (the
   realism gauge's set, context columns left out) with a case-level split (both twins of a
   case in the same fold): ROC AUC, 0.5 when the film leaves no trace a feature sees;
2. `cmtool train`'s model for the rig recipes (extra trees, evidence+scale-free, classes
   weighed, faulty signals below -10 dB fault SNR left out) is trained on the dry or the
   lubricated twin of one draw and scored on another draw (the other rig, or the CWRU recipe
   with seed 777): balanced accuracy, mean of three seeds.

Generate (FOLDER/NAME; about 10 minutes on 2 cores):

    for r in cwru-rig mfpt-rig; do
      cp datasets/$r.toml $r-ehl.toml; sed 's/^ehl = true/ehl = false/' $r.toml > $r-dry.toml
    done
    sed 's/^seed = 6205/seed = 777/' cwru-rig-ehl.toml > cwru777-ehl.toml
    sed 's/^seed = 6205/seed = 777/' cwru-rig-dry.toml > cwru777-dry.toml
    for n in cwru-rig-ehl cwru-rig-dry mfpt-rig-ehl mfpt-rig-dry cwru777-ehl cwru777-dry; do
      cmtool generate $n.toml --out FOLDER/$n --workers 2
    done

Run: .venv/bin/python benchmarks/film_in_recipes.py FOLDER
"""

import sys
from pathlib import Path

import numpy as np
from sklearn.ensemble import RandomForestClassifier
from sklearn.metrics import roc_auc_score
from sklearn.model_selection import GroupKFold

from cmtool.datasets import read_dataset
from cmtool.realism import CONTEXT_UNITS
from features import FeatureExtractor, feature_units

sys.path.insert(0, str(Path(__file__).resolve().parent))
from cross_domain import (  # noqa: E402
    CACHE,
    LABELS,
    MIN_FAULT_SNR_DB,
    extra_trees_score,
    feature_table,
)

NAMES = ("cwru-rig-ehl", "cwru-rig-dry", "mfpt-rig-ehl", "mfpt-rig-dry", "cwru777-ehl")
NAMES += ("cwru777-dry",)


def _table(name, frame, feature_set):
    return feature_table(name, frame, feature_set)


def main(folder: Path) -> None:
    CACHE.mkdir(parents=True, exist_ok=True)
    frames = {n: read_dataset(folder / n) for n in NAMES}
    free = {n: _table(n, f, "scale-free") for n, f in frames.items()}
    both = {n: np.hstack([_table(n, f, "evidence"), free[n]]) for n, f in frames.items()}
    extractor = FeatureExtractor(feature_set="scale-free").fit(frames[NAMES[0]])
    units = feature_units(extractor.faults, extractor.n_harmonics)
    names = list(extractor.get_feature_names_out())
    columns = [i for i, name in enumerate(names) if units.get(name) not in CONTEXT_UNITS]
    print("1. film against dry twins, scale-free features, case-level 5-fold split")
    for lubricated in ("cwru-rig-ehl", "mfpt-rig-ehl", "cwru777-ehl"):
        dry = lubricated.replace("-ehl", "-dry")
        labels = frames[lubricated]["label"].to_numpy()
        for part in ("all", "healthy", "faults"):
            rows = np.ones(labels.size, bool) if part == "all" else (labels == "healthy")
            rows = ~rows if part == "faults" else rows
            X = np.vstack([free[lubricated][rows][:, columns], free[dry][rows][:, columns]])
            y = np.r_[np.zeros(rows.sum()), np.ones(rows.sum())]
            groups = np.r_[np.arange(rows.sum()), np.arange(rows.sum())]
            scores = np.zeros(y.size)
            for train, test in GroupKFold(5).split(X, y, groups):
                forest = RandomForestClassifier(300, class_weight="balanced", random_state=0)
                scores[test] = forest.fit(X[train], y[train]).predict_proba(X[test])[:, 1]
            forest = RandomForestClassifier(300, random_state=0).fit(X, y)
            ranked = sorted(
                zip([names[i] for i in columns], forest.feature_importances_, strict=True),
                key=lambda item: -item[1],
            )[:3]
            print(
                f"  {lubricated} vs dry, {part} ({rows.sum()} twins): AUC "
                f"{roc_auc_score(y, scores):.3f}; most telling "
                + ", ".join(f"{name} {value:.3f}" for name, value in ranked)
            )
    print("2. extra trees (evidence+scale-free) trained dry or lubricated, balanced accuracy")
    keep = {n: ~(f["fault_snr_db"].to_numpy() < MIN_FAULT_SNR_DB) for n, f in frames.items()}
    pairs = [
        (train, test)
        for test in ("mfpt-rig-ehl", "cwru777-ehl", "mfpt-rig-dry", "cwru777-dry")
        for train in ("cwru-rig-ehl", "cwru-rig-dry")
    ]
    pairs += [(t, s) for s in ("cwru777-ehl", "cwru777-dry") for t in NAMES[2:4]]
    for train, test in pairs:
        score, recall, accuracies = extra_trees_score(
            both[train][keep[train]],
            frames[train]["label"].to_numpy()[keep[train]],
            both[test][keep[test]],
            frames[test]["label"].to_numpy()[keep[test]],
        )
        print(
            f"  {train:13s} -> {test:13s} {score:.3f} (seeds "
            + " ".join(f"{a:.3f}" for a in accuracies)
            + "; recall: "
            + ", ".join(f"{k} {r:.2f}" for k, r in zip(LABELS, recall, strict=True))
            + ")"
        )


if __name__ == "__main__":
    main(Path(sys.argv[1]))
