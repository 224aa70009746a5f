"""The anti-alias decimation: scipy's resample_poly against generators.decimation's kernel.

Both give the same bits (tests/tests_generators/test_decimation.py); this prints their times
on the record shapes the toolkit decimates, best of 20 calls on one core:

- ``simulate`` at its defaults: 12 channels, 1.1 s at 25.6 kHz recorded at 2 x fs, columns
  of the state record (the four accelerations are their velocities' derivatives: the FIR
  convolved with the differentiator, ``decimation_taps(2, derivative=True)``);
- a block of 16 lanes of ``cmtool generate`` at 12 kHz recorded at 4 x fs (rows).

Run: .venv/bin/python benchmarks/bench_decimation.py
"""

import time

import numpy as np
from scipy import signal as sp_signal

from generators.decimation import (
    CHANNEL_COLUMNS,
    VELOCITY_OF,
    decimate,
    decimate_rows,
    decimation_taps,
)


def best_ms(fn, repeat=20):
    fn()
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return 1e3 * min(times)


def main() -> None:
    rng = np.random.default_rng(0)
    n = int(1.1 * 25600) * 2
    state = rng.normal(size=(n, 8))
    accel = rng.normal(size=(n, 4))
    channels = list(CHANNEL_COLUMNS)
    record_dt = 1.0 / (2 * 25600.0)
    plain = [c for c in channels if c not in VELOCITY_OF]
    velocities = [CHANNEL_COLUMNS[VELOCITY_OF[c]][1] for c in channels if c in VELOCITY_OF]
    derivative = decimation_taps(2, derivative=True)

    def scipy_columns():
        block = np.stack([(state, accel)[w][:, c] for w, c in map(CHANNEL_COLUMNS.get, plain)])
        out = sp_signal.resample_poly(block, 1, 2, axis=1, padtype="line")
        rates = state[:, velocities].T
        slopes = sp_signal.resample_poly(rates, 1, 2, axis=1, window=derivative, padtype="line")
        return out, slopes / record_dt

    old = best_ms(scipy_columns)
    new = best_ms(lambda: decimate(state, accel, 2, channels, record_dt))
    print(
        f"simulate's record, 12 channels x {n} samples, factor 2: scipy {old:.2f} ms, kernel "
        f"{new:.2f} ms ({old / new:.1f}x)"
    )
    rows = rng.normal(size=(16, int(1.1 * 12000) * 4))
    old = best_ms(lambda: sp_signal.resample_poly(rows, 1, 4, axis=1, padtype="line"))
    new = best_ms(lambda: decimate_rows(rows, 4))
    print(
        f"a lane block, 16 rows x {rows.shape[1]} samples, factor 4: scipy {old:.2f} ms, "
        f"kernel {new:.2f} ms ({old / new:.1f}x)"
    )


if __name__ == "__main__":
    main()
