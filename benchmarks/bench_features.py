"""Feature extraction speed (prints figures; not a test).

Run: ``.venv/bin/python benchmarks/bench_features.py``. Targets: all features of a 1 s,
25.6 kHz signal in under 20 ms; a batch of 1,000 such signals in 5 s or less on two cores
(issue 22; it was 10 s).
"""

from __future__ import annotations

import sys
import time

import numpy as np

import features as F

FS = 25600.0
CTX = {"shaft": 30.0, "ftf": 11.93, "bpfo": 107.36, "bpfi": 162.19, "two_bsf": 141.17}


def main() -> int:
    rng = np.random.default_rng(0)
    x = rng.standard_normal(int(FS))
    F.extract_features(x, FS, fault_frequencies=CTX)
    t0 = time.perf_counter()
    for _ in range(50):
        F.extract_features(x, FS, fault_frequencies=CTX)
    single = (time.perf_counter() - t0) / 50
    print(
        f"all {len(F.feature_names())} features of a 1 s, 25.6 kHz signal: "
        f"{single * 1e3:.1f} ms (target < 20 ms)"
    )
    batch = rng.standard_normal((1000, int(FS)))
    for n_jobs in (1, -1):
        ext = F.FeatureExtractor(fs=FS, fault_frequencies=CTX, n_jobs=n_jobs).fit(batch)
        t0 = time.perf_counter()
        table = ext.transform(batch)
        wall = time.perf_counter() - t0
        print(
            f"batch of 1000 signals, n_jobs={n_jobs}: {wall:.1f} s (target on two cores: "
            f"<= 5 s), table {table.shape}"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
