"""Throughput of the built-in detectors of ``cmtool bench`` (issue 20: 10,000 signals through
six detectors within 10 minutes on two cores).

Each worker makes its signals from a seed (healthy noise through a resonance, or the same
with impacts at a bearing's outer-race rate and random spacing: the cost does not depend on
the content) and runs every built-in detector on them, as ``cmtool bench --workers 2`` does
on a dataset; the parquet read of a dataset is left out (under 1 % of the time).

Run: python benchmarks/bench_detectors.py [signals] [fs_hz]   (default 10000 at 12000 Hz)
"""

from __future__ import annotations

import sys
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np


def _signal(seed: int, fs: float) -> np.ndarray:
    from scipy import signal as sp_signal

    rng = np.random.default_rng(seed)
    n = int(fs)
    x = rng.standard_normal(n)
    if seed % 2:
        times = np.cumsum(rng.normal(1 / 107.5, 0.01 / 107.5, 120))
        idx = (times[times < n / fs] * fs).astype(int)
        x[idx] += 8.0
    b, a = sp_signal.iirpeak(0.3 * fs, 10.0, fs)
    return sp_signal.lfilter(b, a, x)


def _run(args: tuple[int, float]) -> int:
    from cmtool.bench import builtin_outputs

    seed, fs = args
    return len(builtin_outputs(_signal(seed, fs), fs, 1797.0, "6205"))


def main() -> None:
    signals = int(sys.argv[1]) if len(sys.argv) > 1 else 10000
    fs = float(sys.argv[2]) if len(sys.argv) > 2 else 12000.0
    workers = 2
    with ProcessPoolExecutor(workers) as pool:
        list(pool.map(_run, [(s, fs) for s in range(2 * workers)]))  # imports and compiles
        start = time.perf_counter()
        outputs = sum(pool.map(_run, [(s, fs) for s in range(signals)], chunksize=32))
        elapsed = time.perf_counter() - start
    detectors = outputs // signals
    print(
        f"{signals} signals of 1 s at {fs / 1e3:g} kHz through {detectors} detectors on "
        f"{workers} workers: {elapsed:.1f} s ({signals / elapsed:.1f} signals/s; target: "
        f"10,000 in 600 s = 16.7 signals/s)"
    )


if __name__ == "__main__":
    main()
