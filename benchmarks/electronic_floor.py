"""What the electronics' own noise changes: a rig recipe with and without ``electronic_floor_db``.

``[sensor] electronic_floor_db`` (docs/realism.md 2, stop 77) adds the sensor's and the
recorder's white noise after the mounted resonance, from a generator of its own, so a recipe
with the key and the same recipe without it draw every other value of each case alike. This
generates both at one seed and compares, on the healthy signals and the faults at fault SNR
>= ``MIN_FAULT_SNR_DB`` (the faults ``cmtool train`` learns from):

- the rule's verdicts (``diagnose_signal``, ``waviness=False``) per class, with and without,
  and every record whose verdict changed;
- how many records the rule adds its instrument floor to, per sample rate (the separation's
  floor, 50 dB under the RMS, goes to records without a floor of their own 20 dB over it);
- how much the electronics raise the power in each fault's band (where the fault SNR label is
  measured, before the sensor): median, 90th percentile and largest rise [dB].

Run (about 1 minute for the CWRU rig and 3 for the MFPT rig on two cores):
    .venv/bin/python benchmarks/electronic_floor.py datasets/cwru-rig.toml --seed 7701
    .venv/bin/python benchmarks/electronic_floor.py datasets/mfpt-rig.toml --seed 7702
"""

import argparse
import re
import tempfile
import tomllib
from collections import Counter
from pathlib import Path

import numpy as np
from scipy import signal as sp_signal

from cmtool.datasets import generate_dataset, read_dataset
from cmtool.diagnose import diagnose_signal

MIN_FAULT_SNR_DB = -10.0
NAMES = {"healthy": "healthy", "inner": "inner race", "outer": "outer race", "ball": "ball"}


def _without_key(text: str) -> str:
    """The recipe's text without its ``electronic_floor_db`` line."""
    kept = [line for line in text.splitlines() if not line.startswith("electronic_floor_db")]
    if len(kept) == len(text.splitlines()):
        raise SystemExit("the recipe has no [sensor] electronic_floor_db line to compare without")
    return "\n".join(kept) + "\n"


def _rule(frame) -> dict[int, tuple[str, str, bool]]:
    """Per kept record: its label, the rule's verdict and whether the rule added its floor."""
    out = {}
    for i, row in enumerate(frame.itertuples()):
        if row.label != "healthy" and not row.fault_snr_db >= MIN_FAULT_SNR_DB:
            continue
        d = diagnose_signal(
            np.asarray(row.signal, float),
            float(row.fs_hz),
            float(row.rpm),
            row.bearing,
            waviness=False,
        )
        out[i] = (row.label, d.verdict, d.assumptions["instrument_floor"].startswith("added"))
    return out


def _band_rise_db(without, with_key) -> np.ndarray:
    """Per kept fault: the rise of its fault band's power [dB] the electronics make."""
    rise = []
    for a, b in zip(without.itertuples(), with_key.itertuples(), strict=True):
        if a.label == "healthy" or not a.fault_snr_db >= MIN_FAULT_SNR_DB:
            continue
        f, pa = sp_signal.welch(np.asarray(a.signal, float), float(a.fs_hz), nperseg=1024)
        _, pb = sp_signal.welch(np.asarray(b.signal, float), float(a.fs_hz), nperseg=1024)
        band = (f >= a.fault_band_low_hz) & (f <= a.fault_band_high_hz)
        rise.append(10.0 * np.log10(pb[band].sum() / pa[band].sum()))
    return np.array(rise)


def generate_both(text: str, without: str, folder: Path, workers: int) -> dict:
    """A recipe's text and the same without a key, generated in ``folder``: their frames."""
    frames = {}
    for name, body in (("without", without), ("with", text)):
        path = folder / f"{name}.toml"
        path.write_text(body)
        generate_dataset(path, folder / name, workers=workers)
        frames[name] = read_dataset(folder / name)
    return frames


def main(recipe: Path, seed: int, workers: int) -> None:
    text = re.sub(r"(?m)^seed = \d+", f"seed = {seed}", recipe.read_text())  # as cage_slip.py
    tomllib.loads(text)  # a readable recipe before anything is generated
    with tempfile.TemporaryDirectory() as tmp:
        frames = generate_both(text, _without_key(text), Path(tmp), workers)
        rates = frames["with"]["fs_hz"].to_numpy()
        verdicts = {name: _rule(frame) for name, frame in frames.items()}
        rise = _band_rise_db(frames["without"], frames["with"])
    print(f"{recipe.name}, seed {seed}: {len(verdicts['with'])} records kept")
    for name, rule in verdicts.items():
        right, total = Counter(), Counter()
        for label, verdict, _ in rule.values():
            total[label] += 1
            right[label] += NAMES[label] == verdict
        floors = Counter(float(rates[i]) for i, (_, _, added) in rule.items() if added)
        kept = Counter(float(rates[i]) for i in rule)
        print(
            f"  {name} the key: right {sum(right.values())}/{len(rule)} ("
            + ", ".join(f"{label} {right[label]}/{total[label]}" for label in sorted(total))
            + "); the rule's floor added: "
            + ", ".join(f"{fs:.0f} Hz {floors[fs]}/{kept[fs]}" for fs in sorted(kept))
        )
    changed = [i for i in verdicts["with"] if verdicts["with"][i][1] != verdicts["without"][i][1]]
    print(f"  verdicts changed: {len(changed)}")
    for i in changed:
        label, before, _ = verdicts["without"][i]
        print(f"    record {i} ({label}): {before} -> {verdicts['with'][i][1]}")
    print(
        f"  fault-band power rise over {rise.size} faults: median {np.median(rise):.3f} dB, "
        f"90th percentile {np.percentile(rise, 90):.3f} dB, largest {rise.max():.3f} dB"
    )


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("recipe", type=Path, help="a recipe with [sensor] electronic_floor_db")
    parser.add_argument("--seed", type=int, required=True, help="the recipe's seed for both runs")
    parser.add_argument("--workers", type=int, default=2, help="generation workers")
    args = parser.parse_args()
    main(args.recipe, args.seed, args.workers)
