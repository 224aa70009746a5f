"""A waviness check on fault verdicts, measured and not shipped (prints figures).

Issue 18: a wavy bearing's lattice of lines leaks into the random part and is read as a local
fault (docs/diagnosis.md, "Waviness read as a local fault"). The check tried in stop 39 puts a
rule-detector fault verdict down to race waviness when

1. ``cmtool.waviness`` reports a waviness line (as it does on healthy verdicts) that the record
   can tell from the mains (not within two bins or 0.3 % of a harmonic of 50 or 60 Hz), and
2. in the envelope's band, above the waviness lines' own range (3 BPFI + 3 f_s), the lines
   that the separation's line editing took stand at least 0 dB over the random part it left
   (the shaft's and the ball pass's harmonic series, fitted first, count for neither side).

It counts the right verdicts without and with the check on the simulated cases of
``benchmarks/separation_variants.py`` (48 wavy, 60 healthy, 45 pits clean and in noise 3 x the
RMS) and, when given, on generated datasets (every signal; changed verdicts are printed).
``--no-mains`` and ``--no-floor`` drop condition 1's mains test or condition 2's low-order
floor. Not shipped: in the measured-data tests it turned three CWRU fault records healthy.
``--cross-family`` (stop 47) applies it only to "outer race" verdicts and only for waviness
read on the inner race (whose lattice m f_s + n BPFO beats at n BPFO in the envelope): wavy
inner races 5 -> 23/24 healthy, wavy balls 2 -> 6/24, no pit or healthy case and none of the
rig recipes' 1,400 signals changed; not shipped either: in the measured-data tests it turned
the CWRU OR007@6 outer-race record healthy (docs/diagnosis.md, "Waviness read as a local
fault").

Run: .venv/bin/python benchmarks/waviness_check.py [--no-mains] [--no-floor] [--cross-family]
     [DATASET ...]
(for example after ``cmtool generate datasets/cwru-rig.toml --out data/cwru-rig``)
"""

from __future__ import annotations

import argparse
import sys
import time
from collections import Counter
from pathlib import Path

import numpy as np

from cmtool.diagnose import _race_waviness, diagnose_signal
from cmtool.waviness import mains_harmonic_near
from features import discrete_over_random_db
from generators import bearing, characteristic_frequencies

sys.path.insert(0, str(Path(__file__).resolve().parent))
from separation_variants import cases  # noqa: E402

VERDICT = {"healthy": "healthy", "inner": "inner race", "outer": "outer race", "ball": "ball"}
EXPLAINS_FAULT_DB = 0.0


def checked_verdict(
    x, fs, rpm, name, *, mains=True, floor=True, cross_family=False
) -> tuple[str, str, dict]:
    """(verdict without the check, with it, what the check found).

    ``cross_family`` (stop 47): only an "outer race" verdict, and only for waviness read on
    the inner race (whose lattice m f_s + n BPFO beats at n BPFO in the envelope)."""
    g = bearing(name)
    freqs = characteristic_frequencies(g, rpm / 60.0)
    d = diagnose_signal(x, fs, rpm, g, waviness=False)
    if d.verdict == "healthy" or (cross_family and d.verdict != "outer race"):
        return d.verdict, d.verdict, {}
    found = _race_waviness(d, g, freqs, rpm, fs, x.size / fs, None, None, None)
    if found is None or (cross_family and found["surface"] != "inner"):
        return d.verdict, d.verdict, {}
    if mains and mains_harmonic_near(found["line_hz"], fs / x.size) is not None:
        return d.verdict, d.verdict, {"mains": found["line_hz"]}
    low = max(d.band_hz[0], 3.0 * max(freqs.bpfi, freqs.bpfo) + 3.0 * freqs.shaft if floor else 0)
    if low >= d.band_hz[1]:
        return d.verdict, d.verdict, {"below": low}
    excess = discrete_over_random_db(x, fs, (low, d.band_hz[1]), (freqs.shaft, freqs.bpfo))
    found = dict(found, band_lines_over_random_db=round(excess, 1))
    return d.verdict, ("healthy" if excess >= EXPLAINS_FAULT_DB else d.verdict), found


def _count(items, **options) -> None:
    """items: (kind, bearing, rpm, fs, signal, right verdict)."""
    before, after, total, changed = Counter(), Counter(), Counter(), 0
    start = time.perf_counter()
    for kind, name, rpm, fs, x, right in items:
        off, on, found = checked_verdict(np.asarray(x, float), fs, rpm, name, **options)
        total[kind] += 1
        before[kind] += off == right
        after[kind] += on == right
        if on != off:
            changed += 1
            if not kind.startswith("wavy"):
                print(f"  {kind} {name} {rpm:g} rpm {fs:g} Hz: {off} -> {on} {found}")
    shown = ", ".join(f"{k} {before[k]} -> {after[k]}/{total[k]}" for k in total)
    seconds = time.perf_counter() - start
    print(f"right verdicts without -> with the check: {shown}; {changed} changed ({seconds:.0f} s)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("datasets", nargs="*")
    parser.add_argument("--no-mains", action="store_true")
    parser.add_argument("--no-floor", action="store_true")
    parser.add_argument("--cross-family", action="store_true")
    args = parser.parse_args()
    options = {
        "mains": not args.no_mains,
        "floor": not args.no_floor,
        "cross_family": args.cross_family,
    }
    sims = [(c["kind"], c["name"], c["rpm"], c["fs"], c["x"], c["right"]) for c in cases()]
    print("simulated sweep (benchmarks/separation_variants.py cases):")
    _count(sims, **options)
    from cmtool.datasets import read_dataset

    for path in args.datasets:
        frame = read_dataset(path)
        print(f"{path}:")
        _count(
            (
                (r["label"], r["bearing"], r["rpm"], r["fs_hz"], r["signal"], VERDICT[r["label"]])
                for _, r in frame.iterrows()
            ),
            **options,
        )


if __name__ == "__main__":
    main()
