"""A spall's length from its entry and exit events, on simulated datasets of known sizes.

Each inner-race, outer-race or ball record is given to ``cmtool.severity.spall_size`` with
its own class as the verdict (what `cmtool diagnose` does after a right verdict), each healthy
record as all three (an estimate there is a false one). Printed per dataset and class: records,
estimates given, the share whose interval holds the true length, the median
|log10(estimate / true)|, and the estimates given for spalls of 1.5 mm or more at a fault
SNR of 20 dB or more; a CSV of every record with ``--csv``.

The development and test draws of docs/diagnosis.md "Severity" are the rig recipes with the
conditions replaced by race spalls or ball spalls (lengths 0.5-4 mm, depths 10-100 um,
600-3600 rpm, fault SNR 0-30 dB; the balls' spin axes drifting by 0-0.2 rad/s) and the rig
recipes' own pits; the recipes are written out by ``--recipes DIR``:

    .venv/bin/python benchmarks/severity_entry_exit.py --recipes recipes
    for r in recipes/*.toml; do cmtool generate $r --out data/$(basename $r .toml); done
    .venv/bin/python benchmarks/severity_entry_exit.py data/spall-cwru-rig ...
"""

from __future__ import annotations

import argparse
import re
from pathlib import Path

import numpy as np
import pandas as pd
from joblib import Parallel, delayed

from cmtool.datasets import read_dataset
from cmtool.severity import spall_size
from generators import bearing, characteristic_frequencies

ROOT = Path(__file__).resolve().parent.parent
VERDICT = {"inner": "inner race", "outer": "outer race", "ball": "ball"}

SNR_RANGE = "fault_snr_db = { min = 0, max = 30 }"
POSITION = "position_rad = { min = -3.14159, max = 3.14159 }\n"
SPALL_CONDITIONS = """
[[conditions]]
label = "{race}"
surface = "{race}"
defect = "localized"
length_m = {{ min = 0.5e-3, max = 4e-3 }}
depth_m = {{ min = 10e-6, max = 100e-6 }}
{position}count = 80
"""
BALL_CONDITIONS = """
[[conditions]]
label = "ball"
surface = "ball"
defect = "localized"
length_m = { min = 0.5e-3, max = 4e-3 }
depth_m = { min = 10e-6, max = 100e-6 }
axis_drift_rad_s = { min = 0, max = 0.2 }
count = 80
"""


def write_recipes(folder: Path) -> None:
    """The test draws' recipes (seeds 7121-7128): spalls through the rigs' chains, rig pits."""
    folder.mkdir(parents=True, exist_ok=True)
    draws = (
        ("spall", "cwru-rig", "[48000, 96000]", 7121),
        ("spall", "mfpt-rig", "[48828, 97656]", 7122),
        ("spall", "cwru-rig", "[12000]", 7123),
        ("ball-spall", "cwru-rig", "[48000, 96000]", 7126),
        ("ball-spall", "mfpt-rig", "[48828, 97656]", 7127),
        ("ball-spall", "cwru-rig", "[12000]", 7128),
    )
    for kind, rig, rates, seed in draws:
        text = (ROOT / "datasets" / f"{rig}.toml").read_text()
        name = f"{kind}-{rig}" + ("-12k" if rates == "[12000]" else "")
        text = re.sub(r'^name = ".*"', f'name = "{name}"', text, flags=re.M)
        text = re.sub(r"^seed = .*$", f"seed = {seed}", text, flags=re.M)
        text = re.sub(r"^fs_hz = .*$", f"fs_hz = {rates}", text, flags=re.M)
        text = re.sub(r"^rpm = .*$", "rpm = { min = 600, max = 3600 }", text, flags=re.M)
        text = re.sub(
            r"^fault_snr_db = .*$", "fault_snr_db = { min = 0, max = 30 }", text, flags=re.M
        )
        text = text[: text.index("[[conditions]]")]
        if kind == "ball-spall":
            text += BALL_CONDITIONS
        for race in ("inner", "outer") if kind == "spall" else ():
            position = (
                "position_rad = { min = -3.14159, max = 3.14159 }\n" if race == "outer" else ""
            )
            text += SPALL_CONDITIONS.format(race=race, position=position)
        (folder / f"{name}.toml").write_text(text)
    for rig, seed in (("cwru-rig", 7124), ("mfpt-rig", 7125)):
        text = (ROOT / "datasets" / f"{rig}.toml").read_text()
        text = re.sub(r'^name = ".*"', f'name = "pits-{rig}"', text, flags=re.M)
        text = re.sub(r"^seed = .*$", f"seed = {seed}", text, flags=re.M)
        text = re.sub(
            r"^fault_snr_db = .*$", "fault_snr_db = { min = 0, max = 30 }", text, flags=re.M
        )
        text = re.sub(r"^count = \d+", "count = 40", text, flags=re.M)
        (folder / f"pits-{rig}.toml").write_text(text)


def _one(
    signal: np.ndarray, fs: float, name: str, rpm: float, verdict: str, load_n: float | None
) -> dict:
    geometry = bearing(name)
    freqs = characteristic_frequencies(geometry, rpm / 60.0)
    signal = np.asarray(signal, dtype=float)
    return spall_size(signal, fs, verdict, geometry, freqs, load_n=load_n)[0]


def evaluate(path: str, workers: int, load_factor: float | None = None) -> pd.DataFrame:
    """Every fault record as its own class, every healthy record as each of the three; with
    ``load_factor``, each given its radial load times it."""
    data = read_dataset(path)
    jobs, rows = [], []
    for _, r in data.iterrows():
        for race in list(VERDICT) if r.label == "healthy" else [r.label]:
            load = None if load_factor is None else load_factor * r.radial_load_n
            jobs.append(delayed(_one)(r.signal, r.fs_hz, r.bearing, r.rpm, VERDICT[race], load))
            rows.append(
                {
                    "dataset": Path(path).name,
                    "label": r.label,
                    "as": race,
                    "length_mm": 1e3 * r.defect_length_m if r.label != "healthy" else np.nan,
                    "fault_snr_db": r.fault_snr_db,
                    "fs_hz": r.fs_hz,
                    "rpm": r.rpm,
                }
            )
    results = Parallel(n_jobs=workers)(jobs)
    for row, size in zip(rows, results, strict=True):
        row["estimated"] = size["estimated"]
        row["estimate_mm"] = size.get("length_mm", np.nan)
        low, high = size.get("interval_mm", (np.nan, np.nan))
        row["low_mm"], row["high_mm"] = low, high
    table = pd.DataFrame(rows)
    table["covered"] = (table.low_mm <= table.length_mm) & (table.length_mm <= table.high_mm)
    table["width_mm"] = table.high_mm - table.low_mm
    return table


def _log_error(given: pd.DataFrame) -> float:
    return float(np.median(np.abs(np.log10(given.estimate_mm / given.length_mm))))


def summary(table: pd.DataFrame) -> None:
    """Per dataset and class (a healthy record per class it was run as); then the bars'
    figures over the spall and pit draws, races and balls apart."""
    print(
        "dataset | class (run as) | records | estimated | interval holds | "
        "median |log10 ratio| | estimated of >= 1.5 mm at >= 20 dB"
    )
    for (name, label, run_as), g in table.groupby(["dataset", "label", "as"], sort=False):
        given = g[g.estimated]
        holds = f"{given.covered.mean():.2f}" if len(given) else "-"
        error = f"{_log_error(given):.3f}" if len(given) else "-"
        big = g[(g.length_mm >= 1.5) & (g.fault_snr_db >= 20)]
        shown = label if label == run_as else f"{label} ({run_as})"
        print(
            f"{name} | {shown} | {len(g)} | {len(given)} | {holds} | {error} | "
            f"{int(big.estimated.sum())}/{len(big)}"
        )
    for classes, what in ((("inner", "outer"), "races"), (("ball",), "balls")):
        spalls = table[table.dataset.str.contains("spall") & table.label.isin(classes)]
        pits = table[table.dataset.str.startswith("pits") & table.label.isin(classes)]
        healthy = table[(table.label == "healthy") & table["as"].isin(classes)]
        given = spalls[spalls.estimated]
        big = spalls[(spalls.length_mm >= 1.5) & (spalls.fault_snr_db >= 20)]
        if len(given):
            print(
                f"{what}, spalls: {len(given)} estimates of {len(spalls)}; the interval holds "
                f"the length for {given.covered.mean():.3f}; median |log10 ratio| "
                f"{_log_error(given):.4f}; median interval width {given.width_mm.median():.3f} "
                f"mm; estimated {big.estimated.mean():.3f} of {len(big)} spalls >= 1.5 mm at "
                ">= 20 dB"
            )
        if len(pits):
            wrong = pits.estimated & ~pits.covered
            print(
                f"{what}, rig pits: {int(pits.estimated.sum())} estimates of {len(pits)}, "
                f"{int(wrong.sum())} missing the size ({wrong.mean():.3f} of the records)"
            )
        if len(healthy):
            print(
                f"{what}, healthy records run as one: {int(healthy.estimated.sum())} "
                f"estimates of {len(healthy)}"
            )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("datasets", nargs="*", help="dataset folders")
    parser.add_argument("--recipes", help="write the test draws' recipes to this folder")
    parser.add_argument("--csv", help="every record's estimate to this CSV")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument(
        "--load-factor",
        type=float,
        help="give each record its radial load times this (the load-aware interval)",
    )
    args = parser.parse_args()
    if args.recipes:
        write_recipes(Path(args.recipes))
    if not args.datasets:
        return
    table = pd.concat(
        [evaluate(p, args.workers, args.load_factor) for p in args.datasets], ignore_index=True
    )
    if args.csv:
        table.to_csv(args.csv, index=False)
    summary(table)


if __name__ == "__main__":
    main()
