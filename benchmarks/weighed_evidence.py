"""The rule's weighed evidence per fault as three more features: the simulated cross-domain check
with and without them (stop 78, measured and not shipped: docs/realism.md 6).

The columns tried, ``evidence_<fault>_weighed_db`` for the outer race, inner race and ball, are
each fault's weighed evidence over the rule's detection threshold
(``features.fault_evidence(...).combined[fault]["evidence_db"]`` minus ``threshold_db``): its
line family with the lines another fault accounts for left out. On the MFPT bearing a ball
pit's 2 x BSF - FTF line lies 1.1 % under BPFI, inside BPFI's slip window, so the raw
``evidence_bpfi_h1_snr`` of a ball pit is high there and a model trained on the CWRU rig
(where no ball line comes near BPFI) can read it as an inner race.

For every ordered pair of the datasets given, ``benchmarks/cross_domain.py``'s random forest
(classes weighed as ``cmtool train`` weighs them) is trained on one and scored on the other,
on ``cmtool train``'s default feature set as shipped and with the three columns appended,
faults under ``MIN_FAULT_SNR_DB`` left out on both sides.

Run (after generating the datasets, as in ``benchmarks/cross_domain.py``):
    .venv/bin/python benchmarks/weighed_evidence.py data/cwru-rig data/mfpt-rig [data/universal]
"""

import argparse
import sys
from concurrent.futures import ProcessPoolExecutor
from itertools import permutations
from pathlib import Path

import numpy as np
from sklearn.ensemble import RandomForestClassifier
from sklearn.metrics import balanced_accuracy_score, confusion_matrix, recall_score
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import StandardScaler

from cmtool import classifier
from cmtool.datasets import read_dataset
from features import fault_evidence

sys.path.insert(0, str(Path(__file__).resolve().parent))
from cross_domain import LABELS, MIN_FAULT_SNR_DB, feature_table  # noqa: E402

FAULTS = ("bpfo", "bpfi", "two_bsf")


def _weighed(args) -> list[float]:
    """One signal's weighed evidence over the threshold per fault [dB]."""
    x, fs, rates = args
    found = fault_evidence(x, fs, rates)
    return [found.combined[fault]["evidence_db"] - found.threshold_db for fault in FAULTS]


def weighed_columns(frame) -> np.ndarray:
    """The three columns for a dataset's signals, shape (signals, 3) [dB]."""
    args = [
        (
            np.asarray(row.signal, dtype=float),
            float(row.fs_hz),
            {
                "bpfo": row.bpfo_hz,
                "bpfi": row.bpfi_hz,
                "two_bsf": row.two_bsf_hz,
                "shaft": row.shaft_frequency_hz,
                "ftf": row.ftf_hz,
            },
        )
        for row in frame.itertuples()
    ]
    with ProcessPoolExecutor(2) as pool:
        return np.array(list(pool.map(_weighed, args, chunksize=8)))


def main(paths: list[str]) -> None:
    frames = {Path(p).name: read_dataset(p) for p in paths}
    shipped, weighed, keep = {}, {}, {}
    for name, frame in frames.items():
        shipped[name] = feature_table(name, frame, classifier.DEFAULT_FEATURE_SET)
        weighed[name] = np.hstack([shipped[name], weighed_columns(frame)])
        keep[name] = ~(frame["fault_snr_db"].to_numpy() < MIN_FAULT_SNR_DB)
    for title, tables in (("shipped", shipped), ("with the weighed evidence", weighed)):
        scores = []
        for a, b in permutations(frames, 2):
            model = make_pipeline(
                StandardScaler(),
                RandomForestClassifier(
                    n_estimators=300, random_state=0, class_weight=classifier.CLASS_WEIGHT
                ),
            )
            model.fit(tables[a][keep[a]], frames[a]["label"].to_numpy()[keep[a]])
            predicted = model.predict(tables[b][keep[b]])
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
    main(parser.parse_args().datasets)
