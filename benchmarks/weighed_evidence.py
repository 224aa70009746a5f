"""The rule's weighed evidence per fault as features: the simulated cross-domain check with and
without them (stop 78, docs/realism.md 6).

``evidence_<fault>_weighed_db`` (``features.EVIDENCE_NAMES`` since stop 78) is the fault's
weighed evidence over the rule's detection threshold: its line family with the lines another
fault accounts for left out. On the MFPT bearing a ball pit's 2 x BSF - FTF line lies 1.1 %
under BPFI, inside BPFI's slip window, so the raw ``evidence_bpfi_h1_snr`` of a ball pit is
high there and a model trained on the CWRU rig (where no ball line comes near BPFI) can read
it as an inner race.

For every ordered pair of the datasets given, a classifier is trained on one and scored on the
other, on ``cmtool train``'s default feature set as shipped and with the three columns dropped
(the same table), faults under ``MIN_FAULT_SNR_DB`` left out on both sides. The classifier is
``benchmarks/cross_domain.py``'s: the one the datasets' recipes name (extra trees for the rig
recipes, on which the columns were judged), or with ``--classifier NAME`` another of ``cmtool
train``'s candidates (``random_forest``: this script's default until stop 79).

Run (after generating the datasets, as in ``benchmarks/cross_domain.py``):
    .venv/bin/python benchmarks/weighed_evidence.py data/cwru-rig data/mfpt-rig [data/universal]
    [--classifier random_forest]
"""

import argparse
import sys
from itertools import permutations
from pathlib import Path

import numpy as np
from sklearn.metrics import balanced_accuracy_score, confusion_matrix, recall_score
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import StandardScaler

from cmtool import classifier
from cmtool.datasets import read_dataset
from features import FeatureExtractor

sys.path.insert(0, str(Path(__file__).resolve().parent))
from cross_domain import LABELS, MIN_FAULT_SNR_DB, feature_table, recipes_classifier  # noqa: E402

WEIGHED = tuple(f"evidence_{fault}_weighed_db" for fault in ("bpfo", "bpfi", "two_bsf"))


def main(paths: list[str], model_name: str | None = None) -> None:
    frames = {Path(p).name: read_dataset(p) for p in paths}
    feature_set = classifier.DEFAULT_FEATURE_SET
    model_name = model_name or recipes_classifier([Path(p) for p in paths])
    tables, keep = {}, {}
    for name, frame in frames.items():
        tables[name] = feature_table(name, frame, feature_set)
        keep[name] = ~(frame["fault_snr_db"].to_numpy() < MIN_FAULT_SNR_DB)
    names = list(FeatureExtractor(feature_set=feature_set).fit(frame).feature_names_out_)
    if not set(WEIGHED) <= set(names):
        raise SystemExit(f"the default set {feature_set!r} has no {WEIGHED}")
    without = [i for i, column in enumerate(names) if column not in WEIGHED]
    for title, columns in (("without the weighed evidence", without), ("shipped", None)):
        scores = []
        for a, b in permutations(frames, 2):
            estimator = classifier.candidate_classifiers(0)[model_name]
            model = make_pipeline(StandardScaler(), estimator)
            train, test = tables[a][keep[a]], tables[b][keep[b]]
            if columns is not None:
                train, test = train[:, columns], test[:, columns]
            model.fit(train, frames[a]["label"].to_numpy()[keep[a]])
            predicted = model.predict(test)
            truth = frames[b]["label"].to_numpy()[keep[b]]
            scores.append(balanced_accuracy_score(truth, predicted))
            recall = recall_score(truth, predicted, labels=LABELS, average=None)
            matrix = confusion_matrix(truth, predicted, labels=LABELS).tolist()
            print(
                f"{title}, {a} -> {b}: {scores[-1]:.3f} (recall "
                + ", ".join(f"{k} {r:.2f}" for k, r in zip(LABELS, recall, strict=True))
                + f"; rows {LABELS}: {matrix})",
                flush=True,
            )
        print(f"{title}, mean of {len(scores)}: {np.mean(scores):.3f}", flush=True)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("datasets", nargs="+", help="dataset folders of different rig recipes")
    parser.add_argument(
        "--classifier",
        choices=sorted(classifier.candidate_classifiers()),
        help="this cmtool train candidate instead of the one the datasets' recipes name",
    )
    args = parser.parse_args()
    main(args.datasets, args.classifier)
