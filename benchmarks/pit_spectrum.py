"""Where a simulated pit puts its vibration: the signature's spectrum by band (prints figures).

A 6205 with 5 um of clearance at 1797 rpm and 300 N, 1 % random slip, an outer-race pit 20 um
deep at the load zone's centre, 0.18, 0.53 and 1.5 mm long; 0.5 s at 48 kHz after 0.1 s of
settling, the film on. The signature is the housing's acceleration with the pit minus without
(same seed); printed: the share of its Welch power (1,024-sample segments) in each band, the
frequency of its peak, its RMS over the healthy bearing's, for the massless-ball scene of the
recipes (``shaft+housing``) and the scene with ball masses (``full``). Measured CWRU fault
records are demodulated at structural resonances of 2.5 kHz and more; what these shares say
about the simulated pits is in docs/realism.md 4 (stop 41).

Run: .venv/bin/python benchmarks/pit_spectrum.py
"""

import time

import numpy as np

from generators import (
    LocalizedDefect,
    OperatingCondition,
    Scene,
    SimulationSettings,
    bearing,
    simulate,
)
from generators.measurement import _welch

BANDS = {
    "<1k": (0.0, 1e3),
    "1-2k": (1e3, 2e3),
    "2-5k": (2e3, 5e3),
    "5-10k": (5e3, 1e4),
    ">10k": (1e4, 2.4e4),
}


def main() -> None:
    geometry = bearing("6205", radial_internal_clearance=5e-6)
    fs = 48000.0
    operating = OperatingCondition.from_rpm(1797, 300.0, random_slip=0.01)
    settings = SimulationSettings(
        fs=fs, duration=0.5, settle_time=0.1, channels=("housing_acceleration_y",)
    )
    for level in ("shaft+housing", "full"):
        scene = Scene(level=level, ehl=True)
        for length in (0.18e-3, 0.53e-3, 1.5e-3):
            pit = LocalizedDefect(surface="outer", length=length, depth=20e-6, position=-np.pi / 2)
            start = time.perf_counter()
            runs = [
                simulate(geometry, operating, d, scene=scene, settings=settings, random_state=1)
                for d in (pit, None)
            ]
            seconds = time.perf_counter() - start
            faulty, healthy = (r["housing_acceleration_y"] for r in runs)
            f, psd = _welch(faulty - healthy, fs, 1024)
            shares = {
                name: float(psd[(f >= lo) & (f < hi)].sum() / psd.sum())
                for name, (lo, hi) in BANDS.items()
            }
            print(
                f"{level:13s} {length * 1e3:4.2f} mm: "
                + ", ".join(f"{k} {v:.3f}" for k, v in shares.items())
                + f"; peak {f[np.argmax(psd)]:.0f} Hz; RMS over the healthy bearing's "
                f"{np.std(faulty - healthy) / np.std(healthy):.0f} ({seconds:.1f} s)"
            )


if __name__ == "__main__":
    main()
