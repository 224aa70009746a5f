"""Speed and memory of the tachometer's speed and of order tracking on long records.

``features.shaft_rate_from_tacho`` and ``features.order_track`` on records of 10 and 60 s at
12 and 48 kHz (a shaft ramping 28 -> 31 Hz over a minute, noise for the vibration): the time
of each and the peak memory tracemalloc sees during order tracking, against the record's
own size. Run: ``.venv/bin/python benchmarks/bench_order_track.py``.
"""

import time
import tracemalloc

import numpy as np

import features


def main() -> None:
    print("record          tacho [s]  order_track [s]  peak [MB]  record [MB]")
    for seconds, fs in ((10.0, 12000.0), (10.0, 48000.0), (60.0, 12000.0), (60.0, 48000.0)):
        n = int(seconds * fs)
        t = np.arange(n) / fs
        phase = np.cumsum(28.0 + 0.05 * t) / fs
        tacho = np.where(phase % 1.0 < 0.05, 5.0, 0.0)
        x = np.random.default_rng(0).standard_normal(n)
        del t, phase
        start = time.perf_counter()
        speed = features.shaft_rate_from_tacho(tacho, fs)
        tacho_s = time.perf_counter() - start
        tracemalloc.start()
        start = time.perf_counter()
        features.order_track(x, fs, speed)
        track_s = time.perf_counter() - start
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        print(
            f"{seconds:4.0f} s {fs / 1000:4.0f} kHz  {tacho_s:9.3f}  {track_s:15.3f}  "
            f"{peak / 1e6:9.0f}  {x.nbytes / 1e6:11.0f}"
        )


if __name__ == "__main__":
    main()
