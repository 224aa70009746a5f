"""Can the stated shaft speed be checked against the shaft's own lines? (measured, not shipped)

The rule searches each fault line from 2 % below to 0.5 % above its kinematic rate, so a
stated speed more than 0.5 % below the true one puts every fault line outside its window;
the CWRU rig's speeds were written down by hand (../shared/rigs.md) and users often give a
motor's nameplate speed. This estimates the shaft rate from the plain spectrum's harmonic
family near the stated one: spectral peaks at least 10 dB over a 101-bin running median
(Hann window, interpolated), peaks within 1.5 bins or 0.2 % of a 50 or 60 Hz multiple
dropped (mains), candidates p / k within +/- 5 % of the stated rate, the candidate whose
harmonics 1-10 meet the most peaks (1x among them; ties by the least squared deviation),
refined by least squares over its matched peaks. On datasets whose speeds are exact it
prints how often the estimate departs from the stated speed by more than 0.5 % (a check
that would then "correct" a right speed), and the most common such estimates.

docs/diagnosis.md, "The stated speed against the shaft's lines": in 1 s records of the
CWRU-rig recipe the usable shaft lines are 1x and 3x (2x, 4x and 5x lie within a bin of 60,
120 and 150 Hz), the 3x merges with the fan-end 6203's BPFO (3.05 x the shaft rate) and the
6203's BPFI (4.95 x) poses as the 5x of a shaft 1 % slower.

Run: .venv/bin/python benchmarks/speed_check.py DATASET [DATASET ...]
"""

from __future__ import annotations

import collections
import sys
from concurrent.futures import ThreadPoolExecutor

import numpy as np
from scipy import ndimage

from cmtool.datasets import read_dataset

SEARCH = 0.05
HARMONICS = 10
LINE_DB = 10.0
MIN_LINES = 2
DEPARTURE = 0.005


def spectral_peaks(x: np.ndarray, fs: float, top_hz: float) -> tuple[np.ndarray, float]:
    """Interpolated frequencies [Hz] of the lines >= LINE_DB over their floor, mains dropped."""
    x = np.asarray(x, dtype=float) - np.mean(x)
    amp = np.abs(np.fft.rfft(x * np.hanning(x.size)))
    df = fs / x.size
    m = min(amp.size, int(top_hz / df) + 60)
    amp = amp[:m]
    floor = ndimage.median_filter(amp, size=101, mode="nearest")
    ratio = 20 * np.log10(np.maximum(amp, 1e-300) / np.maximum(floor, 1e-300))
    log = np.log(np.maximum(amp, 1e-300))
    i = np.arange(1, m - 1)
    i = i[(amp[i] > amp[i - 1]) & (amp[i] >= amp[i + 1]) & (ratio[i] >= LINE_DB)]
    a, b, c = log[i - 1], log[i], log[i + 1]
    den = np.where(a - 2 * b + c != 0, a - 2 * b + c, 1.0)
    f = (i + np.where(a - 2 * b + c != 0, 0.5 * (a - c) / den, 0.0)) * df
    keep = np.ones(f.size, dtype=bool)
    for mains in (50.0, 60.0):
        order = np.round(f / mains)
        keep &= ~((order >= 1) & (np.abs(f - mains * order) <= np.maximum(1.5 * df, 0.002 * f)))
    return f[keep], df


def shaft_rate(x: np.ndarray, fs: float, stated: float) -> float | None:
    """The shaft rate [Hz] the spectrum's harmonic family gives near ``stated``, or None."""
    top = min(fs / 2.56, HARMONICS * stated * (1 + SEARCH))
    peaks, df = spectral_peaks(x, fs, top)
    peaks = peaks[peaks <= top]
    best = None
    for p in peaks:
        for k in range(1, HARMONICS + 1):
            candidate = p / k
            if not stated * (1 - SEARCH) <= candidate <= stated * (1 + SEARCH):
                continue
            orders, found = [], []
            for h in range(1, HARMONICS + 1):
                if h * candidate > top:
                    break
                near = np.flatnonzero(
                    np.abs(peaks - h * candidate) <= 0.35 * df + 5e-4 * h * candidate
                )
                if near.size:
                    orders.append(h)
                    found.append(peaks[near[0]])
            if 1 not in orders or len(orders) < MIN_LINES:
                continue
            h, f = np.array(orders, dtype=float), np.array(found)
            rate = float(np.sum(h * f) / np.sum(h * h))
            key = (len(orders), -float(np.sum((f - h * rate) ** 2)))
            if best is None or key > best[0]:
                best = (key, rate)
    return None if best is None else best[1]


def main(paths: list[str]) -> None:
    for path in paths:
        frame = read_dataset(path)

        def one(row):
            stated = row.rpm / 60.0
            rate = shaft_rate(np.asarray(row.signal, dtype=float), row.fs_hz, stated)
            return row.rpm, row.fs_hz, rate, stated

        with ThreadPoolExecutor(2) as pool:
            out = list(pool.map(one, frame.itertuples(index=False)))
        off = [
            (rpm, fs, round(rate * 60, 1))
            for rpm, fs, rate, s in out
            if rate and abs(rate / s - 1) > DEPARTURE
        ]
        found = sum(rate is not None for _, _, rate, _ in out)
        print(
            f"{path}: {len(out)} signals, a family found in {found}, "
            f"departing > 0.5 % in {len(off)}"
        )
        for (rpm, fs, estimate), count in collections.Counter(off).most_common(5):
            print(f"  stated {rpm:g} rpm at {fs:g} Hz -> {estimate:g} rpm: {count}")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
