"""False alarms of the rule detector's band selection on Gaussian noise, against the nominal.

For records of white Gaussian noise (1 s and 5 s at 12 kHz, three fault rates), the fraction
whose best envelope line (``features.select_band``, every candidate band) reaches the threshold
``features.detection_threshold_db`` set for a false-alarm probability p per rate. The union
bound over the three rates gives at most 3 p. This is how ``CALIBRATION_DB`` was measured.

Run: .venv/bin/python benchmarks/calibrate_detection.py [trials]
"""

import sys
import time

import numpy as np

from features.separation import detection_threshold_db, select_band

FS = 12000.0
RATES = {"bpfo": 107.4, "bpfi": 162.2, "two_bsf": 141.2}


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
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 2000)
