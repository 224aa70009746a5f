"""A pit's lines at its own rate in the plain spectrum, with and without random slip.

The realism gauge finds the measured records' plain-spectrum lines at BPFI and 2 x BSF far
above the simulated ones (docs/realism.md 7). This prints, for a noise-free simulated pit with
no measurement chain (6205, 1797 rpm, 400 N, 12 kHz, 2 s, outer race, 0.53 x 0.28 mm), the
Hann-window amplitude at BPFO x 1, 2, 3 and the median over +/- 15 Hz around each (the floor),
for no slip, `random_slip` 0.002 and 0.01, and `ball_jitter` 0.005 rad alone, and the pit's
strongest harmonic up to 4 kHz for scale. Simulation only.

Run: .venv/bin/python benchmarks/pit_plain_lines.py [--fs 48000]  (the run's sample rate [Hz])
"""

import argparse

import numpy as np

import features
from generators import (
    LocalizedDefect,
    OperatingCondition,
    SimulationSettings,
    bearing,
    characteristic_frequencies,
    simulate,
)

CASES = (
    ("no slip", {}),
    ("random_slip 0.002", {"random_slip": 0.002}),
    ("random_slip 0.01", {"random_slip": 0.01}),
    ("ball_jitter 0.005 rad", {"ball_jitter": 0.005}),
)


def main(fs: float) -> None:
    geometry = bearing("6205")
    bpfo = characteristic_frequencies(geometry, 1797 / 60).bpfo
    pit = LocalizedDefect(surface="outer", length=0.53e-3, depth=0.28e-3)
    settings = SimulationSettings(fs=fs, duration=2.0, channels=("housing_acceleration_y",))
    for name, randomness in CASES:
        op = OperatingCondition.from_rpm(1797, 400.0, **randomness)
        x = simulate(geometry, op, pit, settings=settings, random_state=2)
        freqs, amp = features.amplitude_spectrum(x["housing_acceleration_y"], fs)
        parts = []
        for k in (1, 2, 3):
            near = np.abs(freqs - k * bpfo) < 15.0
            line = amp[np.argmin(np.abs(freqs - k * bpfo))]
            parts.append(f"{k}x line {line:.2e} floor {np.median(amp[near]):.2e}")
        harmonics = [amp[np.argmin(np.abs(freqs - k * bpfo))] for k in range(1, int(4000 / bpfo))]
        print(
            f"{name}: " + "; ".join(parts) + f"; strongest harmonic {max(harmonics):.2e} "
            f"(m/s^2, RMS {np.std(x['housing_acceleration_y']):.1f})"
        )


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fs", type=float, default=12000.0)
    main(parser.parse_args().fs)
