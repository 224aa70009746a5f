"""Does the labelled fault SNR say how visible a fault is? (prints figures; not a test)

Issue 17 asks for a fault SNR that governs visibility. For each of three envelope detectors of
``cmtool bench`` (``envelope``: the rule of ``cmtool diagnose``; ``fixed_band_ses`` and
``cpw_ses``: two that are not ours), the ROC area of the dataset's ``fault_snr_db`` as a
predictor of "the detector names the right fault", over the faulty signals above -20 dB (a
pit the races touch); 0.5: the label says nothing, 1: every found fault is labelled louder
than every missed one. Also the rule's recall per class at fault SNR >= -10 dB and on the
healthy signals, and how many of the faults above -20 dB stand out most in an octave that
starts below 1 kHz (docs/realism.md 3 and 4).

Run (docs/realism.md 4):
    cmtool generate datasets/cwru-rig.toml --out data/cwru-rig --workers 2
    cmtool bench data/cwru-rig --workers 2 --out data/bench-cwru-rig
    .venv/bin/python benchmarks/fault_snr_auc.py data/cwru-rig data/bench-cwru-rig
"""

import sys
from pathlib import Path

import pandas as pd
from sklearn.metrics import roc_auc_score

from cmtool.datasets import read_dataset

DETECTORS = ("envelope", "fixed_band_ses", "cpw_ses")
MIN_TOUCHED_DB = -20.0
MIN_VISIBLE_DB = -10.0


def _hits(frame: pd.DataFrame) -> pd.Series:
    """Whether each verdict names the signal's class (``inner`` and ``inner race`` agree)."""
    pairs = zip(frame["verdict"].astype(str), frame["label"], strict=True)
    return pd.Series([v.split()[0] == lab.split()[0] for v, lab in pairs], index=frame.index)


def main(dataset: Path, bench: Path) -> None:
    meta = read_dataset(dataset).drop(columns=["signal"])
    results = pd.read_csv(bench / "results.csv")
    aucs = {}
    for detector in DETECTORS:
        rows = results[results["detector"] == detector][["id", "verdict"]]
        frame = meta.merge(rows, on="id")
        frame["hit"] = _hits(frame)
        faulty = frame[(frame["label"] != "healthy") & (frame["fault_snr_db"] > MIN_TOUCHED_DB)]
        aucs[detector] = roc_auc_score(faulty["hit"], faulty["fault_snr_db"])
        if detector == "envelope":
            healthy = frame[frame["label"] == "healthy"]
            visible = faulty[faulty["fault_snr_db"] >= MIN_VISIBLE_DB]
            recall = visible.groupby("label")["hit"].agg(["mean", "size"])
            print(
                f"rule: healthy {healthy['hit'].mean():.3f} of {len(healthy)}; faults at "
                f">= {MIN_VISIBLE_DB:.0f} dB: "
                + ", ".join(
                    f"{k} {r['mean']:.3f} of {int(r['size'])}" for k, r in recall.iterrows()
                )
            )
    print(
        f"{dataset.name}: ROC AUC of fault_snr_db for the right fault ({len(faulty)} faulty "
        "signals above -20 dB): "
        + ", ".join(f"{k} {v:.3f}" for k, v in aucs.items())
        + f"; mean {sum(aucs.values()) / len(aucs):.3f}"
    )
    low = int((faulty["fault_band_low_hz"] < 1000.0).sum())
    print(f"octave where the fault stands out starts below 1 kHz: {low} of {len(faulty)}")


if __name__ == "__main__":
    main(Path(sys.argv[1]), Path(sys.argv[2]))
