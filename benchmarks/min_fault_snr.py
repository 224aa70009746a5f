"""Which faulty signals should ``cmtool train`` leave out? (prints figures; not a test)

``cmtool train --min-fault-snr`` (default ``cmtool.classifier.MIN_FAULT_SNR_DB``) drops
faulty training signals whose labelled fault SNR is below it: their label names a fault that
nothing in them shows. Extra trees (``cmtool train``'s model for the rig recipes,
evidence+scale-free, three seeds) are trained with the threshold at each of THRESHOLDS and
scored on a fixed population, the healthy signals and the faults at or above -10 dB, over
randomisation_check's three cells (CWRU -> MFPT, MFPT -> CWRU777, CWRU -> CWRU777).

Run: .venv/bin/python benchmarks/min_fault_snr.py FOLDER VARIANT, FOLDER holding
cwru-rig-VARIANT, mfpt-rig-VARIANT and cwru777-VARIANT (randomisation_check.py's docstring
says how to generate them).
"""

import sys
from pathlib import Path

import numpy as np

from cmtool.datasets import read_dataset

sys.path.insert(0, str(Path(__file__).resolve().parent))
from cross_domain import CACHE, LABELS, print_cell  # noqa: E402
from randomisation_check import DIRECTIONS, _table  # noqa: E402

THRESHOLDS = (-15.0, -10.0, -5.0, 0.0)
SCORED_FROM_DB = -10.0


def main(folder: Path, variant: str) -> None:
    CACHE.mkdir(parents=True, exist_ok=True)
    frames, tables = {}, {}
    for rig in ("cwru-rig", "mfpt-rig", "cwru777"):
        frames[rig] = read_dataset(folder / f"{rig}-{variant}")
        tables[rig] = _table(f"{rig}-{variant}", frames[rig])
    labels = {rig: f["label"].to_numpy() for rig, f in frames.items()}
    snr = {rig: f["fault_snr_db"].to_numpy() for rig, f in frames.items()}
    for threshold in THRESHOLDS:
        means, worst_healthy = [], 1.0
        for train, test in DIRECTIONS:
            fit = ~(snr[train] < threshold)  # NaN (healthy) kept
            scored = ~(snr[test] < SCORED_FROM_DB)
            accuracy, recall = print_cell(
                f"  >= {threshold:g} dB ({int(fit.sum())} training signals), {train} -> {test}",
                tables[train][fit],
                labels[train][fit],
                tables[test][scored],
                labels[test][scored],
            )
            means.append(accuracy)
            worst_healthy = min(worst_healthy, float(recall[LABELS.index("healthy")]))
        print(
            f"training faults >= {threshold:g} dB: mean {np.mean(means):.3f}, "
            f"least healthy recall {worst_healthy:.2f}"
        )


if __name__ == "__main__":
    main(Path(sys.argv[1]), sys.argv[2])
