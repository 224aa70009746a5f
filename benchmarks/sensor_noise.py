"""The sensor's own noise in absolute units: a rig recipe as shipped and with that noise.

``[sensor] sensor_noise_density`` (docs/realism.md 2, stop 84) adds the accelerometer's own
white noise after its mounted resonance at a drawn spectral density [m/s^2/sqrt(Hz)], which
the vibration's level does not move, from a generator of its own. In the shipped recipes one
relative floor, ``electronic_floor_db`` -65 to -45 dB under the sensor's output, stands for
the sensor's and the recorder's noise together. This generates the recipe as shipped and the
same with the sensor's noise apart (``sensor_noise_density`` 1e-5 to 4e-5 m/s^2/sqrt(Hz),
1-4 ug/sqrt(Hz), and ``electronic_floor_db`` the recorder's alone, -74 to -56 dB) at one seed
and compares, on the healthy signals and the faults at fault SNR >= ``MIN_FAULT_SNR_DB``:

- the rule's verdicts (``diagnose_signal``, ``waviness=False``) per class, both ways, and the
  records whose verdict changed;
- the rise of each fault's band power [dB] (where the fault SNR label is measured, before the
  sensor): median, 90th percentile, largest, and the share of faults under 1 dB;
- where the noise stands: the drawn noise's RMS over the record's RMS [dB], per sample rate.

With ``--keep DIR`` both datasets stay in DIR/shipped and DIR/sensor-noise (for
``benchmarks/cross_domain.py``).

Run (about 3 minutes for the CWRU rig and 5 for the MFPT rig on two cores):
    .venv/bin/python benchmarks/sensor_noise.py datasets/cwru-rig.toml --seed 8411
    .venv/bin/python benchmarks/sensor_noise.py datasets/mfpt-rig.toml --seed 8412
"""

import argparse
import json
import re
import tempfile
import tomllib
from pathlib import Path

import numpy as np
from electronic_floor import _band_rise_db, generate_both  # benchmarks/ on the path
from machine_level import report_verdicts, rule_verdicts

SENSOR_NOISE = "sensor_noise_density = { min = 1e-5, max = 4e-5 }"  # 1-4 ug/sqrt(Hz)
RECORDER_FLOOR = "electronic_floor_db = { min = -74, max = -56 }"  # a 16-bit recorder's


def _with_sensor_noise(text: str) -> str:
    """The recipe's text with the sensor's noise apart: absolute, and the recorder's floor."""
    if re.search(r"(?m)^sensor_noise_density", text):
        raise SystemExit("the recipe has [sensor] sensor_noise_density already")
    if not re.search(r"(?m)^machine_velocity_mm_s", text):
        raise SystemExit("the recipe has no [sensor] machine_velocity_mm_s (an absolute level)")
    if not re.search(r"(?m)^electronic_floor_db", text):
        raise SystemExit("the recipe has no [sensor] electronic_floor_db line to split")
    return re.sub(r"(?m)^electronic_floor_db.*$", f"{SENSOR_NOISE}\n{RECORDER_FLOOR}", text)


def main(recipe: Path, seed: int, workers: int, keep: Path | None) -> None:
    text = re.sub(r"(?m)^seed = \d+", f"seed = {seed}", recipe.read_text())
    tomllib.loads(text)  # a readable recipe before anything is generated
    with tempfile.TemporaryDirectory() as tmp:
        folder = keep or Path(tmp)
        folder.mkdir(parents=True, exist_ok=True)
        frames = generate_both(_with_sensor_noise(text), text, folder, workers)
        frames = {name: frame.sort_values("index") for name, frame in frames.items()}
        verdicts = {name: rule_verdicts(frame, workers) for name, frame in frames.items()}
        if keep is not None:
            (keep / "without").rename(keep / "shipped")
            (keep / "with").rename(keep / "sensor-noise")
    noisy, shipped = frames["with"], frames["without"]
    print(f"{recipe.name}, seed {seed}: {len(shipped)} records, {len(verdicts['with'])} kept")
    report_verdicts(verdicts, {"without": "as shipped", "with": "with the sensor's noise"})
    rise = _band_rise_db(shipped, noisy)
    print(
        f"  fault-band power rise over {rise.size} faults: median {np.median(rise):.3f} dB, "
        f"90th percentile {np.percentile(rise, 90):.3f} dB, largest {rise.max():.3f} dB, "
        f"under 1 dB {np.mean(rise <= 1.0):.3f}"
    )
    ratio = {}
    for row in noisy.itertuples():
        chain = json.loads(row.chain)
        level = np.std(np.asarray(row.signal, float))
        ratio.setdefault(float(row.fs_hz), []).append(
            20.0 * np.log10(chain["sensor_noise_rms"] / level)
        )
    for fs, values in sorted(ratio.items()):
        q = np.percentile(values, [5, 50, 95])
        print(
            f"  {fs:.0f} Hz: sensor noise over the record's RMS, median {q[1]:.1f} dB "
            f"(5-95 %: {q[0]:.1f} to {q[2]:.1f})"
        )


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "recipe", type=Path, help="a recipe with machine_velocity_mm_s and electronic_floor_db"
    )
    parser.add_argument("--seed", type=int, required=True, help="the recipe's seed for both runs")
    parser.add_argument("--workers", type=int, default=2, help="generation and rule workers")
    parser.add_argument("--keep", type=Path, help="keep both datasets in this (new) folder")
    args = parser.parse_args()
    main(args.recipe, args.seed, args.workers, args.keep)
