"""Severity from the band profile of a fault's envelope lines (issue 18; stop 48, not shipped).

The hypothesis: a pit of length L in the rolling direction unloads and strikes a ball over a
passage time L / v (v the rolling surface speed, the same on both races and the ball for a
deep groove bearing: v = omega_shaft (D^2 - d^2) / (4 D)), so the fault's force falls off above
about v / L. In a band of the random part, the envelope's lines at the fault rate stand over
the band's floor by the fault's power over the background's there, and when the background's
forces pass through the same structure as the pit's, that ratio cancels the path. Its profile
across bands would then fall where v / L says, whatever the structure rings like.

For each visible pit of a dataset (fault SNR >= -10 dB, as ``cmtool train`` keeps them), the
random part (``features.separate_discrete``, the shaft and ball-pass series) is demodulated in
half-overlapping bands (4 x the fault rate or a third of the band's lower edge wide, whichever
is wider, from 3 x the fault rate to 0.4 fs), and each band's excess line power (line over the
median of +-20 % around it, minus one, at 1x, 2x and 3x the fault rate within -2/+0.5 %) is
its profile. Two estimators of log10 L: one constant per class over log10(v / f25), f25 the
band where a quarter of the profile's excess lies below; and a random forest on the profile
sampled at frequencies normalised by v (f x 1 mm / v), scaled to its largest band. Printed per
class: within each dataset (5-fold) and from one to the other, the mean absolute error in
log10, the median baseline's, and R^2. The bar written before the run (docs/diagnosis.md,
Severity) asked for R^2 >= 0.3 both ways across rigs and >= 0.4 within each, for both races.
Last, per recipe and class, the constant's offset on records of the same rate (48 and 48.8
kHz): if the profile followed v / L alone it would be the same on both rigs.

Run (profiles cached beside the datasets, about a minute each on two cores):
    cmtool generate datasets/cwru-rig.toml --out data/cwru-rig --workers 2
    cmtool generate datasets/mfpt-rig.toml --out data/mfpt-rig --workers 2
    .venv/bin/python benchmarks/severity_profile.py data/cwru-rig data/mfpt-rig
"""

from __future__ import annotations

import argparse
import pickle
import sys
from itertools import permutations
from pathlib import Path

import numpy as np
from joblib import Parallel, delayed
from sklearn.ensemble import RandomForestRegressor
from sklearn.model_selection import KFold

from cmtool.datasets import read_dataset
from features import separate_discrete
from generators import bearing

sys.path.insert(0, str(Path(__file__).resolve().parent))
from severity_regression import _scores  # noqa: E402  (the same scores as stop 33's table)

MIN_FAULT_SNR_DB = -10.0
CLASSES = ("inner", "outer", "ball")
RATE_COLUMN = {"inner": "bpfi_hz", "outer": "bpfo_hz", "ball": "two_bsf_hz"}
#: the forest's profile grid: frequency x 1 mm / v (a 1 mm pit's passages per second / 1 Hz)
NORMALISED_GRID = np.geomspace(0.3, 40.0, 24)


def rolling_speed(name: str, rpm: float) -> float:
    """Rolling surface speed v [m/s] of a deep groove bearing's contacts relative to the cage."""
    geometry = bearing(name)
    pitch, ball = geometry.pitch_diameter, geometry.ball_diameter
    return 2.0 * np.pi * rpm / 60.0 * (pitch**2 - ball**2) / (4.0 * pitch)


def excess_line_power(x: np.ndarray, fs: float, band: tuple[float, float], rate: float) -> float:
    """Sum over 1x-3x ``rate`` of the squared envelope's line over its local median, minus one."""
    spectrum = np.fft.fft(x)
    frequency = np.fft.fftfreq(x.size, 1.0 / fs)
    inside = (frequency >= band[0]) & (frequency <= band[1])
    squared = np.abs(np.fft.ifft(np.where(inside, 2.0 * spectrum, 0.0))) ** 2
    squared -= squared.mean()
    power = np.abs(np.fft.rfft(squared * np.hanning(squared.size))) ** 2
    f_env = np.fft.rfftfreq(squared.size, 1.0 / fs)
    total = 0.0
    for k in (1, 2, 3):
        line = power[(f_env >= 0.98 * k * rate) & (f_env <= 1.005 * k * rate)].max()
        floor = np.median(power[(f_env >= 0.8 * k * rate) & (f_env <= 1.2 * k * rate)])
        total += max(line / floor - 1.0, 0.0)
    return total


def band_profile(row) -> dict:
    """One signal's bands [Hz], their excess line power and its context."""
    x = np.asarray(row["signal"], dtype=float)
    fs, rate = float(row["fs_hz"]), float(row[RATE_COLUMN[row["label"]]])
    random_part = separate_discrete(x, fs, fundamentals=(row["shaft_frequency_hz"], row["bpfo_hz"]))
    bands, low = [], max(3.0 * rate, 300.0)
    while True:
        width = max(4.0 * rate, low / 3.0)
        if low + width > 0.4 * fs:
            break
        bands.append((low, low + width))
        low += width / 2.0
    excess = np.array([excess_line_power(random_part, fs, b, rate) for b in bands])
    return {
        "label": row["label"],
        "length_m": float(row["defect_length_m"]),
        "fs_hz": fs,
        "speed_m_s": rolling_speed(row["bearing"], float(row["rpm"])),
        "centres_hz": np.array([0.5 * (a + b) for a, b in bands]),
        "excess": excess,
    }


def _profiles(path: Path) -> list[dict]:
    cached = path.parent / f"{path.name}-severity-profiles.pkl"
    if cached.is_file():
        return pickle.loads(cached.read_bytes())
    frame = read_dataset(path)
    faults = frame[(frame["label"] != "healthy") & (frame["fault_snr_db"] >= MIN_FAULT_SNR_DB)]
    rows = [row for _, row in faults.iterrows()]
    profiles = Parallel(n_jobs=2)(delayed(band_profile)(row) for row in rows)
    cached.write_bytes(pickle.dumps(profiles))
    return profiles


def quartile_frequency(profile: dict) -> float:
    """The band centre [Hz] below which a quarter of the profile's excess lies."""
    cumulative = np.cumsum(profile["excess"]) / profile["excess"].sum()
    return float(np.interp(0.25, cumulative, profile["centres_hz"]))


def normalised_profile(profile: dict) -> np.ndarray:
    """The profile on :data:`NORMALISED_GRID` scaled to its largest band (-1 outside), and the
    log10 of the highest normalised frequency the record reaches."""
    u = profile["centres_hz"] * 1e-3 / profile["speed_m_s"]
    scaled = profile["excess"] / profile["excess"].max()
    sampled = np.interp(NORMALISED_GRID, u, scaled)
    sampled[(NORMALISED_GRID > u.max()) | (NORMALISED_GRID < u.min())] = -1.0
    return np.concatenate([sampled, [np.log10(u.max())]])


def _forest() -> RandomForestRegressor:
    return RandomForestRegressor(n_estimators=300, min_samples_leaf=3, random_state=0, n_jobs=2)


def main(paths: list[str]) -> None:
    data, rates_by_key = {}, {}
    for p in paths:
        profiles = [q for q in _profiles(Path(p)) if q["excess"].sum() > 0.0]
        for label in CLASSES:
            chosen = [q for q in profiles if q["label"] == label]
            y = np.log10([q["length_m"] for q in chosen])
            quartile = np.log10([q["speed_m_s"] / quartile_frequency(q) for q in chosen])
            table = np.array([normalised_profile(q) for q in chosen])
            data[Path(p).name, label] = (table, y, quartile)
            rates_by_key[Path(p).name, label] = np.array([q["fs_hz"] for q in chosen])
    names = [Path(p).name for p in paths]
    header = "class | trained on -> scored on | signals | estimator | MAE log10 | median baseline"
    print(f"| {header} | R^2 |")
    print("|---|---|---|---|---|---|---|")
    for label in CLASSES:
        for name in names:
            table, y, quartile = data[name, label]
            forest, constant = np.empty_like(y), np.empty_like(y)
            for train, test in KFold(5, shuffle=True, random_state=0).split(y):
                forest[test] = _forest().fit(table[train], y[train]).predict(table[test])
                constant[test] = quartile[test] + np.median(y[train] - quartile[train])
            for estimator, predicted in (("forest", forest), ("v / f25", constant)):
                scores = _scores(y, predicted, y)
                print(f"| {label} | {name} (5-fold) | {y.size} | {estimator} | {scores} |")
        for a, b in permutations(names, 2):
            (table_a, y_a, quartile_a), (table_b, y_b, quartile_b) = data[a, label], data[b, label]
            forest = _forest().fit(table_a, y_a).predict(table_b)
            constant = quartile_b + np.median(y_a - quartile_a)
            for estimator, predicted in (("forest", forest), ("v / f25", constant)):
                scores = _scores(y_b, predicted, y_a)
                print(f"| {label} | {a} -> {b} | {y_b.size} | {estimator} | {scores} |")
    # the constant's offset per recipe on records of the same rate (40-60 kHz: 48 and 48.8 kHz)
    for (name, label), (_, y, quartile) in data.items():
        rates = rates_by_key[name, label]
        same = (rates > 40e3) & (rates < 60e3)
        offset = float(np.median(y[same] - quartile[same]))
        print(f"{name} {label}: log10 L - log10(v / f25) at 40-60 kHz, median {offset:.2f}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("datasets", nargs="+", help="dataset folders of rig recipes")
    main(parser.parse_args().datasets)
