"""``simulate`` of one signal at its defaults, healthy and wavy (prints figures; not a test).

The call a user makes first: a 6205 at 1800 rpm and 500 N, the ``shaft`` scene (dry), 1 s at
25.6 kHz after 0.1 s of settling, the default RK4 step; healthy and with 1 um of outer-race
waviness (N_w = 9), one channel and all twelve. Best of ``--repeat`` calls (default 7) after
a warm-up, in ms per call and per simulated second. This host's speed drifts: compare figures
of runs made back to back (docs/performance.md, "Speed").

Run: .venv/bin/python benchmarks/bench_simulate.py [--repeat K]
"""

from __future__ import annotations

import argparse
import math
import time

from generators import (
    OperatingCondition,
    Scene,
    SimulationSettings,
    Waviness,
    bearing,
    simulate,
)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    args = parser.parse_args()
    geometry = bearing("6205")
    operating = OperatingCondition.from_rpm(1800, 500.0)
    scene = Scene(level="shaft", ehl=False)
    wavy = Waviness(surface="outer", order=9, amplitude=1e-6)
    for name, defects in (("healthy", ()), ("outer waviness N_w = 9", (wavy,))):
        for channels in (("housing_velocity_y",), None):
            extra = {} if channels is None else {"channels": channels}
            settings = SimulationSettings(fs=25600.0, duration=1.0, settle_time=0.1, **extra)
            simulate(geometry, operating, *defects, scene=scene, settings=settings)
            best = math.inf
            for _ in range(args.repeat):
                start = time.perf_counter()
                simulate(geometry, operating, *defects, scene=scene, settings=settings)
                best = min(best, time.perf_counter() - start)
            label = "one channel" if channels else "all channels"
            print(
                f"{name:24s} {label:12s}: {best * 1e3:6.2f} ms a call, "
                f"{best / 1.1 * 1e3:6.2f} ms per simulated second"
            )


if __name__ == "__main__":
    main()
