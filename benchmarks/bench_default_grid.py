"""The default RK4 step at 12 and 48 kHz, off the record grid and on it (prints a table).

At 12 kHz (records at 4 x fs) and 48 kHz (2 x fs) a record interval is 20.83 us (or half of
it), and the default 2e-5 s step lies off that grid: records fall between step starts at a
drifting phase and sample each step's Hermite interpolant, whose images fold into the band.
Shortening the step onto the grid would cost 28-92 % more steps; since stop 39 the default
grows by 4.2 % instead, to 1/48,000 s (``generators.steps.DEFAULT_ALIGN_LONGEST``). This runs
a 6205 at 500 N (the default ``shaft+housing`` scene with EHL, no slip) healthy at 1200, 1797
and 3000 rpm and with a 0.3 mm outer-race pit at 1797 rpm, 1 s, at 2e-5 s (off the grid) and
1/48,000 s (on it), and prints the relative spectral error against a 2.5 us run recorded the
same way below 1 kHz, in 1-3 kHz and in 3 kHz-0.45 fs (Hann-windowed spectra) and the best of
three times of a run on one core.

Run: .venv/bin/python benchmarks/bench_default_grid.py
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

from generators import (
    LocalizedDefect,
    OperatingCondition,
    SimulationSettings,
    bearing,
    simulate,
)

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_step_band import _band_errors  # noqa: E402  (the same three bands)

CHANNEL = "housing_acceleration_y"


def main() -> None:
    geometry = bearing("6205")
    pit = LocalizedDefect(surface="outer", length=0.3e-3, depth=0.1e-3)
    print("fs [Hz] | case | step [us] | < 1 kHz | 1-3 kHz | 3 kHz-0.45 fs | run [ms]")
    print("---|---|---|---|---|---|---")
    for fs in (12000.0, 48000.0):
        for rpm, defect in ((1200, None), (1797, None), (3000, None), (1797, pit)):
            op = OperatingCondition.from_rpm(rpm, 500.0, random_slip=0.0)

            def run(step, fs=fs, op=op, defect=defect):
                settings = SimulationSettings(fs=fs, duration=1.0, channels=(CHANNEL,), step=step)
                start = time.perf_counter()
                x = simulate(geometry, op, defect, settings=settings, random_state=1)[CHANNEL]
                return x, time.perf_counter() - start

            reference, _ = run(2.5e-6)
            case = f"{rpm} rpm " + ("0.3 mm outer pit" if defect else "healthy")
            for step in (2e-5, 1.0 / 48000.0):
                x, _ = run(step)
                seconds = min(run(step)[1] for _ in range(3))
                errors = " | ".join(f"{e:.2e}" for e in _band_errors(x, reference, fs))
                print(f"{fs:.0f} | {case} | {step * 1e6:.2f} | {errors} | {seconds * 1e3:.1f}")


if __name__ == "__main__":
    main()
