"""Can a spall's size be read from the model's signal? The entry-exit echo in the cepstrum.

Issue 18 asks for a fault's size with an uncertainty (Sawalhi and Randall 2011: the entry and
exit events of a spall). In the model a ball over a floor-reaching spall has two kinks of equal
size in its path, where it reaches the floor and where it meets the far edge,
T = (L - 2 e) / v apart (e = sqrt(2 R_x H - H^2) from each edge, v the contact's speed over the
defective surface); a bridged pit has one. Two equal events T apart multiply the spectrum by
|1 + exp(-i w T)|, whose log has a ripple of period 1/T: a peak at quefrency T in the real
cepstrum, whatever the structure's response. This simulates spalls of known size at 48 kHz
with slip and noise at half the RMS and prints the predicted T beside the five largest peaks
of the cepstrum of the band 0.5 kHz - 0.45 fs, of the raw signal and of its random part
(``features.separate_discrete``). It measures; nothing in the package uses it.

Run: .venv/bin/python benchmarks/severity_cepstrum.py
"""

from __future__ import annotations

import math

import numpy as np

from features.evidence import fault_evidence
from generators import (
    LocalizedDefect,
    OperatingCondition,
    SimulationSettings,
    bearing,
    characteristic_frequencies,
    simulate,
)
from generators.defects import defect_path

CASES = (  # surface, length [m], depth [m], rpm
    ("outer", 2e-3, 20e-6, 1797),
    ("outer", 1.5e-3, 10e-6, 1200),
    ("inner", 2e-3, 20e-6, 1797),
    ("outer", 0.53e-3, 0.28e-3, 1797),  # a CWRU-size pit: bridged, one kink
)


def predicted_spacing(g, defect: LocalizedDefect, rpm: float) -> tuple[float, bool]:
    """Time between the kinks where the ball reaches and leaves a spall's floor [s]."""
    path = defect_path(g, defect)
    rx = path.bridge_radius_outer if defect.surface == "outer" else path.bridge_radius_inner
    f = characteristic_frequencies(g, rpm / 60.0)
    cage, shaft = 2 * math.pi * f.ftf, 2 * math.pi * f.shaft
    speed = (cage if defect.surface == "outer" else abs(cage - shaft)) * path.surface_radius
    if path.bridged:
        return 0.0, True
    edge = math.sqrt(2 * rx * defect.depth - defect.depth**2)
    return (defect.length - 2 * edge) / speed, False


def cepstral_peaks(x: np.ndarray, fs: float, count: int = 5) -> list[float]:
    """Quefrencies [s] of the largest peaks of the band's real cepstrum, 0.15-3 ms."""
    spectrum = np.fft.rfft(x * np.hanning(x.size))
    freqs = np.fft.rfftfreq(x.size, 1.0 / fs)
    band = (freqs >= 500.0) & (freqs <= 0.45 * fs)
    log = np.log(np.abs(spectrum[band]) + 1e-300)
    log -= log.mean()
    cepstrum = np.fft.irfft(log * np.hanning(log.size))
    quefrency = np.arange(cepstrum.size) / (cepstrum.size * (freqs[1] - freqs[0]))
    window = (quefrency > 0.15e-3) & (quefrency < 3e-3)
    order = np.argsort(cepstrum[window])[::-1][:count]
    return [float(quefrency[window][i]) for i in order]


def main() -> None:
    g = bearing("6205")
    fs = 48000.0
    settings = SimulationSettings(fs=fs, duration=1.0, channels=("housing_acceleration_y",))
    for surface, length, depth, rpm in CASES:
        defect = LocalizedDefect(surface=surface, length=length, depth=depth)
        op = OperatingCondition.from_rpm(rpm, 1000.0, random_slip=0.012, ball_jitter=0.005)
        x = simulate(g, op, defect, settings=settings, random_state=1)["housing_acceleration_y"]
        x = x + np.random.default_rng(0).normal(0.0, 0.5 * np.std(x), x.size)
        spacing, bridged = predicted_spacing(g, defect, rpm)
        f = characteristic_frequencies(g, rpm / 60.0)
        ctx = {"bpfo": f.bpfo, "bpfi": f.bpfi, "two_bsf": f.two_bsf, "shaft": f.shaft}
        random_part = fault_evidence(x, fs, {**ctx, "ftf": f.ftf}).random_part
        print(
            f"{surface} spall {length * 1e3:.2f} mm x {depth * 1e6:.0f} um at {rpm} rpm: "
            + ("bridged (one kink)" if bridged else f"predicted {spacing * 1e3:.3f} ms")
        )
        for name, signal in (("raw", x), ("random part", random_part)):
            peaks = ", ".join(f"{q * 1e3:.3f}" for q in cepstral_peaks(signal, fs))
            print(f"  cepstral peaks of the {name} [ms]: {peaks}")


if __name__ == "__main__":
    main()
