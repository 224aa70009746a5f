"""How a model trained on 1 s signals should weigh the segments of a longer record (stop 54:
docs/realism.md 6, "Long records").

``cmtool diagnose --model`` cuts a record into segments of the model's signal length
(``cmtool.pooling.model_verdict``); until stop 54 it averaged their class probabilities.
Real records are longer than the recipes' 1 s signals (CWRU 10 s, MFPT 3-6 s), and a ball
pit whose spin axis drifts is struck in some seconds and not in others. This scores each
model on long draws of the rig recipes (healthy signals and faults at fault SNR >= -10 dB),
combining the segments three ways:

- ``mean``: the mean over all segments (before stop 54);
- ``most faulty``: the probabilities of the segment whose P(healthy) is least (a fault that
  shows in any segment makes the record faulty);
- ``vote``: ``cmtool.pooling.segment_probabilities``, shipped in stop 54: the record is
  faulty when more segments read a local fault than the model's own false-alarm rate
  explains, P(Binomial(n, p0) >= k) <= ``SEGMENT_FALSE_ALARM``, p0 the model's out-of-fold
  share of healthy training signals it called a fault, at least one over their number; its
  probabilities the mean over those k segments, else the mean over all.

Prints balanced accuracy over the four classes and recall per class.

Run (after generating the long draws, e.g. datasets/cwru-rig.toml with ``duration_s = 10.0``
and another seed, and training the models with ``cmtool train``):
.venv/bin/python benchmarks/segment_pooling.py --models M1.skops M2.skops --data DATA1 DATA2
"""

from __future__ import annotations

import argparse
import copy

import numpy as np
import pandas as pd

from cmtool.classifier import load_model
from cmtool.datasets import read_dataset
from cmtool.pooling import healthy_false_alarm, segment_probabilities
from features.transformer import CONTEXT_COLUMNS

CLASSES = ("healthy", "inner", "outer", "ball")


def segments(frame: pd.DataFrame, seconds: float) -> tuple[pd.DataFrame, np.ndarray]:
    """Every record cut into segments of ``seconds`` (as ``model_verdict`` cuts it), with its
    context columns, and the record index of each segment."""
    rows, owner = [], []
    columns = [c for c in CONTEXT_COLUMNS.values() if c in frame.columns]
    for index, (_, r) in enumerate(frame.iterrows()):
        x = np.asarray(r["signal"], dtype=float)
        n = int(round(seconds * r["fs_hz"]))
        count = x.size // n if n > 0 else 0
        parts = [x[i * n : (i + 1) * n] for i in range(count)] if count >= 2 else [x]
        for part in parts:
            rows.append({"signal": part, **{c: r[c] for c in columns}})
            owner.append(index)
    return pd.DataFrame(rows), np.array(owner)


def combine(
    proba: np.ndarray, owner: np.ndarray, classes: list[str], how: str, bundle: dict
) -> list[str]:
    healthy = classes.index("healthy")
    rate = healthy_false_alarm(bundle)
    out = []
    for record in np.unique(owner):
        p = proba[owner == record]
        if how == "mean":
            row = p.mean(axis=0)
        elif how == "most faulty":
            row = p[int(np.argmin(p[:, healthy]))]
        else:  # vote: what cmtool.pooling.model_verdict does since stop 54
            row = segment_probabilities(p, classes, bundle.get("class_kinds"), rate)[0]
        out.append(classes[int(np.argmax(row))])
    return out


def main(models: list[str], data: list[str]) -> None:
    bundles = [load_model(m) for m in models]
    for name, bundle in zip(models, bundles, strict=True):
        print(f"{name}: p0 = {healthy_false_alarm(bundle):.4f}")
    for path in data:
        frame = read_dataset(path)
        frame = frame[(frame["label"] == "healthy") | (frame["fault_snr_db"] >= -10)]
        frame = frame.reset_index(drop=True)
        tables: dict[str, tuple] = {}  # the feature table, once per extractor and length
        for name, bundle in zip(models, bundles, strict=True):
            pipeline = bundle["pipeline"]
            seconds = bundle.get("signal_duration_s") or 1.0
            key = f"{seconds} {sorted(pipeline[0].get_params().items())}"
            if key not in tables:
                table, owner = segments(frame, seconds)
                extractor = copy.copy(pipeline[0])
                extractor.n_jobs = 2
                tables[key] = (table, owner, extractor.transform(table))
            table, owner, features = tables[key]
            proba = pipeline[1:].predict_proba(features)
            classes = [str(c) for c in pipeline.classes_]
            truth = frame["label"].to_numpy()
            for how in ("mean", "most faulty", "vote"):
                verdicts = np.array(combine(proba, owner, classes, how, bundle))
                recall = {c: float(np.mean(verdicts[truth == c] == c)) for c in CLASSES}
                print(
                    f"{path} ({len(frame)} records, {len(table)} segments), {name}, {how}: "
                    f"balanced accuracy {np.mean(list(recall.values())):.3f}; "
                    + ", ".join(f"{c} {v:.3f}" for c, v in recall.items()),
                    flush=True,
                )


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--models", nargs="+", required=True)
    parser.add_argument("--data", nargs="+", required=True)
    args = parser.parse_args()
    main(args.models, args.data)
