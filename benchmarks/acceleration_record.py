"""Accelerations from the velocity record against the record's own acceleration column.

For a run recorded at q times the output rate, the output acceleration can be the record's
acceleration column through the anti-alias FIR (until stop 46: the record point-samples the
run's acceleration, and what lies near multiples of the record rate folds into the band) or
the velocity column through the same FIR and a differentiator (from stop 46: the folded part
is smaller by the line's frequency over the folded content's). Both are computed from one
run's raw records (``oversample=1`` at q fs: the same records and step as the default run)
and compared with the velocity path of the same run at a sixteenth of the step: the relative
error in the octave bands from 500 Hz (``generators.accuracy.band_error``) and at BPFO x 1-3
and BPFI (Hann-weighted Fourier sums). Four cases: a 0.53 x 0.28 mm outer-race pit at 12 and
48 kHz, a healthy bearing at 12 kHz, outer-race waviness N_w = 18 at 25.6 kHz (film on).

Last, at step starts alone (records at 48 kHz on a 1/48,000 s step: no interpolation, the same
aliasing in run and reference), how far the velocity record and the acceleration column are
from a run at an eighth of the step in 3 kHz-0.45 fs: what RK4 makes of the force's
high-frequency content (the velocity integrates it, the column evaluates it at the state).

Run: .venv/bin/python benchmarks/acceleration_record.py   (about a minute)
"""

import numpy as np

from generators import (
    LocalizedDefect,
    OperatingCondition,
    Scene,
    SimulationSettings,
    Waviness,
    bearing,
    characteristic_frequencies,
    simulate,
)
from generators.accuracy import band_error
from generators.decimation import decimation_taps

GEOMETRY = bearing("6205")
PIT = LocalizedDefect(surface="outer", length=0.53e-3, depth=0.28e-3)
CASES = {
    "outer pit, 12 kHz": (12000.0, 4, 1797, 400.0, PIT, None),
    "outer pit, 48 kHz": (48000.0, 2, 1797, 400.0, PIT, None),
    "healthy, 12 kHz": (12000.0, 4, 1200, 500.0, None, None),
    "healthy, 48 kHz": (48000.0, 2, 1200, 500.0, None, None),
    "outer waviness 18, 25.6 kHz": (
        25600.0,
        4,
        1797,
        500.0,
        Waviness(surface="outer", order=18, amplitude=1e-6),
        Scene(),
    ),
}


def raw_records(fs, q, rpm, load, defect, scene, step=None):
    """Acceleration and velocity (y) records at q fs, and the step used [s]."""
    settings = SimulationSettings(
        fs=fs * q,
        duration=1.0,
        oversample=1,
        step=step,
        channels=("housing_acceleration_y", "housing_velocity_y"),
    )
    kwargs = {} if scene is None else {"scene": scene}
    op = OperatingCondition.from_rpm(rpm, load)
    r = simulate(GEOMETRY, op, defect, settings=settings, random_state=2, **kwargs)
    step_used = r.parameters["integrator_stats"]["step_s"]
    return r["housing_acceleration_y"], r["housing_velocity_y"], step_used


def filtered(x, taps, q):
    """Zero-phase FIR then every q-th sample (ends reflected; they are cut below)."""
    pad = taps.size
    y = np.convolve(np.pad(x, pad, mode="reflect"), taps, mode="same")[pad:-pad]
    return y[::q][100:-100]


def amplitude(x, fs, f):
    t = np.arange(x.size) / fs
    w = np.hanning(x.size)
    return 2.0 * abs(np.sum(x * w * np.exp(-2j * np.pi * f * t))) / np.sum(w)


def main() -> None:
    for name, (fs, q, rpm, load, defect, scene) in CASES.items():
        rates = characteristic_frequencies(GEOMETRY, rpm / 60.0)
        lines = {"BPFO": rates.bpfo, "2 BPFO": 2 * rates.bpfo, "3 BPFO": 3 * rates.bpfo}
        lines["BPFI"] = rates.bpfi
        record_dt = 1.0 / (fs * q)
        low_pass = decimation_taps(q)
        derivative = decimation_taps(q, derivative=True)
        accel, velocity, step = raw_records(fs, q, rpm, load, defect, scene)
        _, fine_velocity, fine_step = raw_records(fs, q, rpm, load, defect, scene, step / 16)
        reference = filtered(fine_velocity, derivative, q) / record_dt
        paths = {
            "acceleration column": filtered(accel, low_pass, q),
            "velocity derivative": filtered(velocity, derivative, q) / record_dt,
        }
        ref_lines = {k: amplitude(reference, fs, f) for k, f in lines.items()}
        print(
            f"{name} (step {step:.3g} s, records at {fs * q / 1e3:g} kHz; reference step "
            f"{fine_step:.3g} s); reference lines [m/s^2]: "
            + ", ".join(f"{k} {v:.2e}" for k, v in ref_lines.items())
        )
        for label, x in paths.items():
            errors = [
                abs(amplitude(x, fs, f) - ref_lines[k]) / ref_lines[k] for k, f in lines.items()
            ]
            print(
                f"  {label:20s} octave bands {band_error(x, reference, fs=fs):.2e}; lines "
                + ", ".join(f"{k} {e:.1e}" for k, e in zip(lines, errors, strict=True))
            )

    step_starts()


def step_starts() -> None:
    """Velocity record against acceleration column at step starts, 3 kHz-0.45 fs (healthy)."""
    fs = 48000.0
    runs = {}
    for step in (1.0 / fs, 1.0 / fs / 8):
        settings = SimulationSettings(
            fs=fs,
            duration=1.0,
            oversample=1,
            step=step,
            channels=("housing_velocity_y", "housing_acceleration_y"),
        )
        r = simulate(GEOMETRY, OperatingCondition.from_rpm(1200, 500.0), None, settings=settings)
        runs[step] = (r["housing_velocity_y"], r["housing_acceleration_y"])
    (v, a), (v_ref, a_ref) = runs.values()
    f = np.fft.rfftfreq(v.size, 1.0 / fs)
    band = (f >= 3000.0) & (f <= 0.45 * fs)
    w = np.hanning(v.size)

    def relative(x, ref):
        x_f, ref_f = np.fft.rfft(x * w)[band], np.fft.rfft(ref * w)[band]
        return np.sqrt(np.sum(np.abs(x_f - ref_f) ** 2) / np.sum(np.abs(ref_f) ** 2))

    print(
        "healthy, 1200 rpm, 500 N, at step starts (1/48,000 s against an eighth), 3 kHz-0.45 fs: "
        f"velocity record {relative(v, v_ref):.2e}, acceleration column {relative(a, a_ref):.2e}"
    )


if __name__ == "__main__":
    main()
