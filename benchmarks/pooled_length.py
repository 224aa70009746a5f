"""How ``diagnose --model`` should weigh the rule against a model on a long record (stop 55:
docs/realism.md 6, "Long records").

The rule reads the whole record; a model trained on 1 s signals reads a record of T seconds
as T segments and combines them into one segment's opinion
(``cmtool.pooling.segment_probabilities``). Until stop 55 the pooled verdict weighed the two
alike on every record, sqrt(p_rule p_model); since stop 55 by the signal each rests on,
p_rule^(n/(n+1)) p_model^(1/(n+1)), n the model's segments (``pool_probabilities``). This
scores, on long draws of the rig recipes (healthy signals and faults at fault SNR >= -10 dB):

- ``rule``: ``cmtool diagnose`` without a model;
- ``pooled, equal weights``: the pool before stop 55 (n taken as 1);
- ``pooled, weighed by length``: the shipped pool;

each with balanced accuracy over the four classes, recall per class, and the expected
calibration error (10 bins) of the verdict's confidence.

Run (after generating the long draws, e.g. datasets/cwru-rig.toml with ``duration_s = 10.0``
and another seed, and training the models with ``cmtool train``):
.venv/bin/python benchmarks/pooled_length.py --models M1.skops M2.skops --data DATA1 DATA2
"""

from __future__ import annotations

import argparse
import copy
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from cmtool.classifier import load_model
from cmtool.datasets import read_dataset
from cmtool.diagnose import diagnose_signal
from cmtool.pooling import CANONICAL, combine_verdicts, model_verdict
from generators import bearing, characteristic_frequencies

FORMS = ("rule", "pooled, equal weights", "pooled, weighed by length")
_BUNDLES: list[dict] = []


def _load(models: list[str]) -> None:
    _BUNDLES[:] = [load_model(m) for m in models]


def verdicts(record: dict) -> list[list[tuple[str, float]]]:
    """One record's (verdict, confidence) per model and form."""
    x = np.asarray(record["signal"], dtype=float)
    rule = diagnose_signal(x, record["fs_hz"], record["rpm"], record["bearing"])
    freqs = characteristic_frequencies(bearing(record["bearing"]), record["rpm"] / 60.0)
    out = []
    for bundle in _BUNDLES:
        found = model_verdict(bundle, x, record["fs_hz"], freqs, {})
        row = [(rule.verdict, rule.confidence)]
        for segments in (1, found.get("segments", 1)):
            pooled = copy.copy(rule)
            pooled.rule_verdict = dict(rule.rule_verdict)
            pooled.model_verdict = {**found, "segments": segments}
            combine_verdicts(pooled)
            row.append((pooled.verdict, pooled.confidence))
        out.append(row)
    return out


def expected_calibration_error(confidence: np.ndarray, right: np.ndarray) -> float:
    """|accuracy - mean confidence| over 10 equal-width bins, weighted by their share."""
    bins = np.clip((confidence * 10).astype(int), 0, 9)
    return float(
        sum(
            abs(right[bins == b].mean() - confidence[bins == b].mean()) * np.mean(bins == b)
            for b in range(10)
            if np.any(bins == b)
        )
    )


def main(models: list[str], data: list[str], workers: int) -> None:
    columns = ["signal", "fs_hz", "rpm", "bearing", "label"]
    for path in data:
        frame = read_dataset(path)
        frame = frame[(frame["label"] == "healthy") | (frame["fault_snr_db"] >= -10)]
        records = frame[columns].to_dict("records")
        with ProcessPoolExecutor(workers, initializer=_load, initargs=(models,)) as pool:
            rows = list(pool.map(verdicts, records, chunksize=4))
        truth = np.array([CANONICAL[r["label"]] for r in records])
        for m, name in enumerate(models):
            for f, form in enumerate(FORMS):
                said = np.array([row[m][f][0] for row in rows])
                confidence = np.array([row[m][f][1] for row in rows], dtype=float)
                recall = {c: float(np.mean(said[truth == c] == c)) for c in np.unique(truth)}
                ece = expected_calibration_error(confidence, said == truth)
                print(
                    f"{path} ({len(records)} records), {name}, {form}: balanced accuracy "
                    f"{np.mean(list(recall.values())):.3f}; "
                    + ", ".join(f"{c} {v:.3f}" for c, v in recall.items())
                    + f"; ECE {ece:.3f} (mean confidence {confidence.mean():.3f})",
                    flush=True,
                )


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--models", nargs="+", required=True)
    parser.add_argument("--data", nargs="+", required=True)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    main(args.models, args.data, args.workers)
