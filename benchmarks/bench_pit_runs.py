"""What a local defect costs the one-signal RK4 kernel (prints figures; not a test).

The runs the rig recipes cannot put in the SIMD lanes: a 6205 with 5 um of clearance at 1797
rpm and 400 N, `shaft+housing` with EHL, 12 kHz, 1 s after 0.1 s of settling, healthy and with
a 0.3 mm pit (0.1 mm deep) on the outer race, the inner race or a ball, with 1 % random slip
and 0.005 rad of pocket jitter, and the outer-race pit without slip. Each run is prepared once
and integrated ``--repeat`` times (default 5) after a warm-up; the best time in ms is printed
with a hash of the signal, so that a change meant to keep the bytes can be checked too
(docs/performance.md, "Faulty runs and the chain").

Run: .venv/bin/python benchmarks/bench_pit_runs.py [--repeat K] [--fs HZ]
"""

from __future__ import annotations

import argparse
import hashlib
import time

import numpy as np

from generators import LocalizedDefect, OperatingCondition, SimulationSettings, bearing
from generators.model import integrate, prepare

CHANNEL = "housing_acceleration_y"


def main(repeat: int, fs: float) -> None:
    geometry = bearing("6205", radial_internal_clearance=5e-6)
    slipping = OperatingCondition.from_rpm(1797, 400.0, random_slip=0.01, ball_jitter=0.005)
    steady = OperatingCondition.from_rpm(1797, 400.0)
    cases = [
        ("healthy", steady, None),
        ("outer race, slip", slipping, LocalizedDefect(surface="outer", length=3e-4, depth=1e-4)),
        (
            "inner race, slip",
            slipping,
            LocalizedDefect(surface="inner", length=3e-4, depth=1e-4, position=0.3),
        ),
        (
            "ball, slip",
            slipping,
            LocalizedDefect(surface="ball", length=3e-4, depth=1e-4, position=0.3, axis_drift=0.1),
        ),
        (
            "outer race, no slip",
            steady,
            LocalizedDefect(surface="outer", length=1.8e-4, depth=5e-5),
        ),
    ]
    settings = SimulationSettings(fs=fs, duration=1.0, channels=(CHANNEL,))
    print(f"# one-signal RK4, 6205, 1797 rpm, 400 N, {fs:g} Hz, 1.1 s simulated; best of {repeat}")
    for name, operating, defect in cases:
        prep = prepare(geometry, operating, defect, settings=settings, random_state=5)
        signal = integrate(prep)[CHANNEL]  # warm-up (and the kernels from numba's cache)
        times = []
        for _ in range(repeat):
            start = time.perf_counter()
            integrate(prep)
            times.append(time.perf_counter() - start)
        digest = hashlib.sha256(np.ascontiguousarray(signal).tobytes()).hexdigest()[:12]
        print(f"{name:<22s} {min(times) * 1e3:7.1f} ms   signal {digest}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--fs", type=float, default=12000.0)
    args = parser.parse_args()
    main(args.repeat, args.fs)
