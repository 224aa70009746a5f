"""``cmtool demo``: the main job on the embedded default scene.

Simulates the default 6205 scene (1800 rpm, 500 N, MODEL.md 6.3 rig) healthy and with outer-race
waviness of order N_w = N_b = 9, writes both signals, plots their housing-velocity spectra with
the characteristic frequencies marked, and prints the band amplitudes at BPFO.
"""

from __future__ import annotations

import time
from pathlib import Path

import features
from generators import (
    OperatingCondition,
    Scene,
    SimulationSettings,
    Waviness,
    bearing,
    simulate,
)

from .cli import waviness_markers
from .io import write_signal
from .plots import plot_kurtogram, plot_spectrum

__all__ = ["run_demo"]


def run_demo(out: Path) -> int:
    """Run the demo, writing into ``out``; returns 0."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    geometry = bearing("6205")
    operating = OperatingCondition.from_rpm(1800, 500.0)
    settings = SimulationSettings(fs=25600.0, duration=1.0, settle_time=0.2)
    scene = Scene(level="shaft+housing", ehl=True)
    cases = {
        "healthy": [],
        "outer_waviness_nw9": [Waviness(surface="outer", order=9, amplitude=1e-6)],
    }
    print(
        f"cmtool demo: {geometry.name}, {operating.rpm:g} rpm, {operating.radial_load:g} N, "
        f"scene {scene.label}, {settings.duration:g} s at {settings.fs:g} Hz"
    )
    for name, defects in cases.items():
        t0 = time.perf_counter()
        result = simulate(
            geometry, operating, defects, scene=scene, settings=settings, random_state=0
        )
        wall = time.perf_counter() - t0
        signal_path = write_signal(result, out / f"{name}.parquet")
        freqs, amp = features.amplitude_spectrum(result["housing_velocity_y"], result.fs)
        bpfo = result.frequencies.bpfo
        level = features.band_amplitude(freqs, amp, bpfo, half_width=1.5) * 1e3
        plot_path = plot_spectrum(
            freqs,
            amp * 1e3,
            out / f"{name}_spectrum.png",
            title=f"{name}: housing velocity (y) spectrum, peak [mm/s]",
            ylabel="velocity [mm/s]",
            markers=waviness_markers(result, defects),
        )
        accel = result["housing_acceleration_y"]
        kg = features.kurtogram(accel, result.fs, nlevel=6)
        ef, ea = features.envelope_spectrum(accel, result.fs, band=kg.band)
        env_path = plot_spectrum(
            ef,
            ea,
            out / f"{name}_envelope.png",
            title=f"{name}: envelope spectrum of the housing acceleration (y), band "
            f"{kg.band[0]:.0f}-{kg.band[1]:.0f} Hz",
            ylabel="envelope [m/s^2]",
            markers=waviness_markers(result, defects),
            fmax=1000.0,
        )
        kg_path = plot_kurtogram(kg, out / f"{name}_kurtogram.png", title=name)
        print(f"  {name:<20s} BPFO {bpfo:7.2f} Hz: {level:.4f} mm/s  ({wall:.2f} s wall)")
        print(f"    signal    {signal_path}")
        print(f"    spectrum  {plot_path}")
        print(f"    envelope  {env_path}")
        print(f"    kurtogram {kg_path}")
    return 0
