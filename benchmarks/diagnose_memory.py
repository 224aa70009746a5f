"""Time and peak memory of one diagnosis against the record's length (docs/diagnosis.md,
"Records that cannot be diagnosed as they are").

White noise at 48 kHz, a 6205 at 1800 rpm, the rule alone (``diagnose_signal``); the peak is
what tracemalloc sees numpy allocate during the call (the record itself excluded). A record
longer than ``cmtool.diagnose.MAX_RECORD_SAMPLES`` is diagnosed on its first part, so its
figures are that part's.

Run: .venv/bin/python benchmarks/diagnose_memory.py [seconds ...]   (default 10 60 87.4 120)
"""

import sys
import time
import tracemalloc

import numpy as np

from cmtool.diagnose import MAX_RECORD_SAMPLES, diagnose_signal

FS = 48000.0


def main(durations: list[float]) -> None:
    rng = np.random.default_rng(0)
    print(f"MAX_RECORD_SAMPLES = {MAX_RECORD_SAMPLES} ({MAX_RECORD_SAMPLES / FS:.1f} s at 48 kHz)")
    for seconds in durations:
        x = rng.standard_normal(round(seconds * FS))
        tracemalloc.start()
        start = time.perf_counter()
        d = diagnose_signal(x, FS, 1800.0, "6205")
        elapsed = time.perf_counter() - start
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        analysed = d.assumptions["samples"]
        print(
            f"{seconds:7.1f} s ({x.size} samples): {elapsed:5.1f} s, peak {peak / 1e6:6.0f} MB, "
            f"{peak / analysed:4.0f} bytes per analysed sample ({analysed} analysed)"
        )


if __name__ == "__main__":
    main([float(a) for a in sys.argv[1:]] or [10.0, 60.0, 87.4, 120.0])
