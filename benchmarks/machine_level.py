"""A recipe's absolute level: the same recipe with and without ``machine_velocity_mm_s``.

``[sensor] machine_velocity_mm_s`` (docs/realism.md 2, stop 83) scales each record of the
realistic chain so that its healthy machine (the healthy bearing and the background at the
sensor's place) has the drawn overall velocity in ISO 10816's band; the factor comes from a
generator of its own, so the same recipe without the key draws every other value alike and its
records differ by that factor alone. This generates both at one seed and reports:

- per class, the records' overall velocity [mm/s] (ISO 10816's band, as ``cmtool diagnose``
  reads it: ``features.velocity_band_rms``) and acceleration RMS [g], with the key; the
  healthy signals' overall velocity against the value drawn for them (largest relative error),
  and the faults' over it (how much a fault raises the overall level);
- how far each record with the key is from a multiple of the record without it (the largest
  residue over the RMS: the float32 rounding of the files, some 1e-8);
- the rule's verdicts (``diagnose_signal``, ``waviness=False``) on the healthy signals and the
  faults at fault SNR >= ``MIN_FAULT_SNR_DB``, with and without, and every record whose
  verdict changed (the rule reads ratios only: none should).

Run (about 2 minutes for the CWRU rig and 4 for the MFPT rig on two cores):
    .venv/bin/python benchmarks/machine_level.py datasets/cwru-rig.toml --seed 8301
    .venv/bin/python benchmarks/machine_level.py datasets/mfpt-rig.toml --seed 8302
"""

import argparse
import json
import re
import tempfile
import tomllib
from collections import Counter
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np
from electronic_floor import generate_both  # benchmarks/ on the path

import features
from cmtool.diagnose import diagnose_signal

MIN_FAULT_SNR_DB = -10.0
NAMES = {"healthy": "healthy", "inner": "inner race", "outer": "outer race", "ball": "ball"}
G = 9.80665  # standard gravity [m/s^2]


def _without_key(text: str) -> str:
    """The recipe's text without its ``machine_velocity_mm_s`` line."""
    kept = [ln for ln in text.splitlines() if not ln.startswith("machine_velocity_mm_s")]
    if len(kept) == len(text.splitlines()):
        raise SystemExit("the recipe has no [sensor] machine_velocity_mm_s line to compare without")
    return "\n".join(kept) + "\n"


def _verdict(args: tuple) -> str:
    signal, fs, rpm, name = args
    return diagnose_signal(np.asarray(signal, float), fs, rpm, name, waviness=False).verdict


def rule_verdicts(frame, workers: int) -> dict[int, tuple[str, str]]:
    """Per kept record: its label and the rule's verdict."""
    kept = [
        (i, row)
        for i, row in enumerate(frame.itertuples())
        if row.label == "healthy" or row.fault_snr_db >= MIN_FAULT_SNR_DB
    ]
    jobs = [(row.signal, float(row.fs_hz), float(row.rpm), row.bearing) for _, row in kept]
    with ProcessPoolExecutor(workers) as pool:
        verdicts = list(pool.map(_verdict, jobs, chunksize=4))
    return {i: (row.label, v) for (i, row), v in zip(kept, verdicts, strict=True)}


def _overall_mm_s(row) -> float:
    band = (2.0 if row.rpm <= 600.0 else 10.0, 1000.0)
    x = np.asarray(row.signal, float)
    return 1e3 * features.velocity_band_rms(x, float(row.fs_hz), {"overall": band})["overall"]


def report_verdicts(verdicts: dict, titles: dict[str, str]) -> None:
    """Print each run's right verdicts per class and the records whose verdict changed.

    ``verdicts`` maps "with" and "without" to ``rule_verdicts``'s {record: (label, verdict)};
    ``titles`` names the two runs, in the order printed.
    """
    for name, title in titles.items():
        right, total = Counter(), Counter()
        for label, verdict in verdicts[name].values():
            total[label] += 1
            right[label] += NAMES[label] == verdict
        print(
            f"  {title}: right {sum(right.values())}/{len(verdicts[name])} ("
            + ", ".join(f"{label} {right[label]}/{total[label]}" for label in sorted(total))
            + ")"
        )
    changed = [i for i in verdicts["with"] if verdicts["with"][i][1] != verdicts["without"][i][1]]
    print(f"  verdicts changed: {len(changed)}")
    for i in changed:
        label, before = verdicts["without"][i]
        print(f"    record {i} ({label}): {before} -> {verdicts['with'][i][1]}")


def main(recipe: Path, seed: int, workers: int) -> None:
    text = re.sub(r"(?m)^seed = \d+", f"seed = {seed}", recipe.read_text())  # as cage_slip.py
    tomllib.loads(text)  # a readable recipe before anything is generated
    with tempfile.TemporaryDirectory() as tmp:
        frames = generate_both(text, _without_key(text), Path(tmp), workers)
        frames = {name: frame.sort_values("index") for name, frame in frames.items()}
        verdicts = {name: rule_verdicts(frame, workers) for name, frame in frames.items()}
    with_key, without = frames["with"], frames["without"]
    print(f"{recipe.name}, seed {seed}: {len(with_key)} records, {len(verdicts['with'])} kept")
    velocity = np.array([_overall_mm_s(row) for row in with_key.itertuples()])
    rms_g = np.array([np.std(np.asarray(s, float)) / G for s in with_key["signal"]])
    labels = with_key["label"].to_numpy()
    for label in sorted(set(labels)):
        v, a = velocity[labels == label], rms_g[labels == label]
        print(
            f"  {label}: overall velocity median {np.median(v):.3g} mm/s ({v.min():.3g}-"
            f"{v.max():.3g}); acceleration RMS median {np.median(a):.3g} g ({a.min():.3g}-"
            f"{a.max():.3g})"
        )
    drawn = np.array([json.loads(c)["machine_velocity_mm_s"] for c in with_key["chain"]])
    healthy = labels == "healthy"
    error = np.abs(velocity[healthy] / drawn[healthy] - 1.0)
    print(f"  healthy: overall velocity against the value drawn, largest error {error.max():.2e}")
    rise = velocity[~healthy] / drawn[~healthy]
    print(
        f"  faults: overall velocity over the value drawn, median {np.median(rise):.4f}, "
        f"90th percentile {np.percentile(rise, 90):.4f}, largest {rise.max():.3f}"
    )
    residue = []
    for a, b in zip(without["signal"], with_key["signal"], strict=True):
        a, b = np.asarray(a, float), np.asarray(b, float)
        factor = np.dot(a, b) / np.dot(a, a)
        residue.append(np.std(b - factor * a) / np.std(b))
    print(f"  records with the key over a multiple of those without: residue <= {max(residue):.1e}")
    report_verdicts(verdicts, {"without": "without the key", "with": "with the key"})


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("recipe", type=Path, help="a recipe with [sensor] machine_velocity_mm_s")
    parser.add_argument("--seed", type=int, required=True, help="the recipe's seed for both runs")
    parser.add_argument("--workers", type=int, default=2, help="generation and rule workers")
    args = parser.parse_args()
    main(args.recipe, args.seed, args.workers)
