"""False alarms of the rule detector's band selection on Gaussian noise, against the nominal.

For records of white Gaussian noise (1 s and 5 s at 12 kHz, three fault rates), the fraction
whose best envelope line (``features.select_band``, every candidate band) reaches the threshold
``features.detection_threshold_db`` set for a false-alarm probability p per rate. The union
bound over the three rates gives at most 3 p. This is how ``CALIBRATION_DB`` was measured.

Then the same for the combined line evidence of ``features.fault_evidence`` (fundamental,
harmonics and sidebands weighed by Fisher's method, issue 18): the fraction of records in
which any fault's combined false-alarm probability is at most p, against 3 p, beside the
fundamental alone.

Run: .venv/bin/python benchmarks/calibrate_detection.py [trials] [--combined-only]
[--seed N] [--seconds 1,5]  (the combined evidence's noise: seed 2 by default; stop 45 added
10,000 records as ``5000 --combined-only --seconds 1 --seed 3`` and ``--seed 4``)
"""

import argparse
import time

import numpy as np

from features.evidence import fault_evidence
from features.separation import detection_threshold_db, select_band

FS = 12000.0
RATES = {"bpfo": 107.4, "bpfi": 162.2, "two_bsf": 141.2}
CONTEXT = {**RATES, "shaft": 29.95, "ftf": 11.9}


def combined(trials: int, seed: int = 2, lengths: tuple[float, ...] = (1.0, 5.0)) -> None:
    """False alarms of the combined evidence (and of the fundamental alone) on noise."""
    rng = np.random.default_rng(seed)
    for seconds in lengths:
        start = time.perf_counter()
        found = [
            fault_evidence(rng.standard_normal(int(seconds * FS)), FS, CONTEXT)
            for _ in range(trials)
        ]
        per_fault = np.array([[v["false_alarm"] for v in e.combined.values()] for e in found])
        family = per_fault.min(axis=1)
        alone = np.array([min(v["lines"][0][2] for v in e.combined.values()) for e in found])
        faults = list(found[0].combined)
        print(
            f"combined evidence, {seconds:g} s records, {trials} trials "
            f"({time.perf_counter() - start:.0f} s):"
        )
        for p in (1e-1, 1e-2, 1e-3):
            print(
                f"  p = {p:g}: combined {np.mean(family <= p):.4f}, fundamental alone "
                f"{np.mean(alone <= p):.4f} (bound {3 * p:g}); records per fault: "
                + ", ".join(
                    f"{name} {int(np.sum(per_fault[:, i] <= p))}" for i, name in enumerate(faults)
                )
            )


def main(trials: int = 2000) -> None:
    rng = np.random.default_rng(1)
    for seconds in (1.0, 5.0):
        start = time.perf_counter()
        runs = [
            select_band(rng.standard_normal(int(seconds * FS)), FS, RATES) for _ in range(trials)
        ]
        scores = np.array([r.score_db for r in runs])
        first = runs[0]
        print(f"{seconds:g} s records, {trials} trials ({time.perf_counter() - start:.0f} s):")
        for p in (1e-1, 1e-2, 1e-3, 1e-4):
            threshold = detection_threshold_db(
                len(first.bands), p, searched_bins=first.searched_bins, floor_bins=first.floor_bins
            )
            rate = float(np.mean(scores >= threshold))
            print(
                f"  p = {p:g}: threshold {threshold:5.2f} dB, measured {rate:.4f} (bound {3 * p:g})"
            )


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("trials", type=int, nargs="?", default=2000)
    parser.add_argument("--combined-only", action="store_true")
    parser.add_argument("--seed", type=int, default=2, help="the combined evidence's noise")
    parser.add_argument("--seconds", default="1,5", help="record lengths [s], comma-separated")
    args = parser.parse_args()
    if not args.combined_only:
        main(args.trials)
    combined(args.trials, args.seed, tuple(float(v) for v in args.seconds.split(",")))
