"""Is the rule's band deterministic? The phase coherence of its lines between record halves.

Issue 18: a wavy bearing's vibration is deterministic, a pit's impacts with random slip are
not. docs/diagnosis.md ("Waviness read as a local fault") names the next test to try, one
that does not need every lattice line resolved: whether the band's content keeps its phase
from one half of the record to the other. For each record this takes the rule's band
(``cmtool.diagnose.diagnose_signal``) and its random part (``features.separate_discrete``
with the rule's fundamentals and lattice offsets), picks the ``TOP`` strongest local maxima
in the band of the two halves' summed Hann periodograms (picked from the halves, not from the
whole record: the whole record's peaks are where the halves happen to add in phase, which
biases any test towards coherence), refines each by parabolic interpolation, and computes

    C = sum Re(B conj(A) exp(-2 pi i f h / fs)) / sum |A| |B|

with A and B each half's Hann-windowed transform at the line's frequency f and h the half's
length. A deterministic line gives C = 1; noise gives C about 0 (standard deviation about
1 / sqrt(2 TOP)).

Cases: ``inner`` and ``ball``: benchmarks/sweep_waviness_verdicts.py's 24 cases (1 um of
inner-race waviness of order 9, or ball waviness of order 2; three rigs, 900-3600 rpm, 12 and
25.6 kHz, 500 N, 5 % noise); ``pits``: benchmarks/sweep_rule_detector.py's first N pits (0.3
mm, 1 % slip, 0.005 rad jitter) at a noise multiple of the RMS; ``noise``: 20 records of
white noise at 12 kHz. It measures; no threshold is chosen on it.

Run: .venv/bin/python benchmarks/halves_coherence.py {inner,ball,pits,noise} [--pits N]
[--noise LEVEL]
"""

import argparse
import itertools

import numpy as np
from scipy.ndimage import median_filter
from sweep_rule_detector import (  # the sweeps' cases (benchmarks/ on the path)
    BEARINGS,
    RATES,
    VERDICT,
)
from sweep_waviness_verdicts import CHANNEL, RIGS

from cmtool.diagnose import diagnose_signal
from features.lattice import inner_race_lattice_offsets
from features.separation import separate_discrete
from generators import (
    LocalizedDefect,
    OperatingCondition,
    SimulationSettings,
    Waviness,
    bearing,
    characteristic_frequencies,
    simulate,
)

TOP = 20  # lines per record
PADDING = 8  # zero padding of the halves' periodograms


def halves_coherence(random_part: np.ndarray, fs: float, band: tuple[float, float]) -> float:
    """C of the ``TOP`` strongest lines of ``random_part`` in ``band`` [Hz] (NaN: none)."""
    half = random_part.size // 2
    first, second = random_part[:half], random_part[half : 2 * half]
    window = np.hanning(half)
    power = (
        np.abs(np.fft.rfft(first * window, PADDING * half)) ** 2
        + np.abs(np.fft.rfft(second * window, PADDING * half)) ** 2
    )
    freqs = np.fft.rfftfreq(PADDING * half, 1.0 / fs)
    lo, hi = np.searchsorted(freqs, band[0]), np.searchsorted(freqs, band[1])
    seg = power[lo:hi]
    if seg.size < 5 * PADDING:
        return float("nan")
    floor = median_filter(seg, size=25 * PADDING + 1, mode="nearest")
    peaks = np.flatnonzero((seg[1:-1] > seg[:-2]) & (seg[1:-1] >= seg[2:])) + 1
    peaks = peaks[seg[peaks] > floor[peaks]]
    peaks = peaks[np.argsort(seg[peaks])[::-1]][:TOP]
    if peaks.size == 0:
        return float("nan")
    a, b, c = (np.log(seg[peaks + k]) for k in (-1, 0, 1))
    lines = freqs[lo + peaks] + 0.5 * (a - c) / (a - 2 * b + c) * fs / (PADDING * half)
    kernel = np.exp(-2j * np.pi * np.outer(lines, np.arange(half) / fs))
    first_at, second_at = kernel @ (window * first), kernel @ (window * second)
    turn = np.exp(-2j * np.pi * lines * half / fs)
    together = np.real(second_at * np.conj(first_at) * turn).sum()
    return float(together / np.sum(np.abs(first_at) * np.abs(second_at)))


def measured(tag: str, g, x: np.ndarray, fs: float, rpm: float) -> tuple[str, float]:
    d = diagnose_signal(x, fs, rpm, g, waviness=False)
    rates = characteristic_frequencies(g, rpm / 60.0)
    random_part = separate_discrete(
        x,
        fs,
        fundamentals=(rates.shaft, rates.bpfo),
        lattice=inner_race_lattice_offsets(rates.bpfo, rates.bpfi),
    )
    value = halves_coherence(random_part, fs, d.band_hz)
    band = f"{d.band_hz[0]:.0f}-{d.band_hz[1]:.0f} Hz"
    print(f"{tag:44s} {d.verdict:11s} {band:>14s}  C = {value:+.2f}", flush=True)
    return d.verdict, value


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cases", choices=("inner", "ball", "pits", "noise"))
    parser.add_argument("--pits", type=int, default=45)
    parser.add_argument("--noise", type=float, default=0.0, help="pits: noise x RMS")
    args = parser.parse_args()
    results = []
    if args.cases in ("inner", "ball"):
        g = bearing("6205")
        order = 9 if args.cases == "inner" else 2
        noise = np.random.default_rng(18)
        for (name, rig), rpm, fs in itertools.product(
            RIGS.items(), (900, 1500, 2400, 3600), (12000.0, 25600.0)
        ):
            settings = SimulationSettings(fs=fs, duration=1.0, channels=(CHANNEL,))
            wavy = Waviness(surface=args.cases, order=order, amplitude=1e-6)
            op = OperatingCondition.from_rpm(rpm, 500.0)
            x = simulate(g, op, wavy, rig=rig, settings=settings, random_state=3)[CHANNEL]
            x = x + noise.normal(0.0, 0.05 * np.std(x), x.size)
            results.append(
                measured(f"wavy {args.cases} {name} {rpm} rpm {fs:.0f} Hz", g, x, fs, rpm)
            )
    elif args.cases == "pits":
        grid = list(
            itertools.product(
                BEARINGS,
                (600, 1200, 1797, 3000),
                (200.0, 1000.0),
                RATES,
                VERDICT,
            )
        )
        np.random.default_rng(3).shuffle(grid)
        for i, (name, rpm, load, fs, surface) in enumerate(grid[: args.pits]):
            g = bearing(name)
            settings = SimulationSettings(fs=fs, duration=1.0, channels=(CHANNEL,))
            op = OperatingCondition.from_rpm(rpm, load, random_slip=0.01, ball_jitter=0.005)
            pit = LocalizedDefect(surface=surface, length=0.3e-3, depth=0.1e-3)
            x = simulate(g, op, pit, settings=settings, random_state=i)[CHANNEL]
            if args.noise > 0:
                x = x + np.random.default_rng(i).normal(0.0, args.noise * np.std(x), x.size)
            tag = f"pit {surface} {name} {rpm} rpm {load:.0f} N {fs:.0f} Hz"
            results.append(measured(tag, g, x, fs, rpm))
    else:
        g = bearing("6205")
        for i in range(20):
            x = np.random.default_rng(100 + i).standard_normal(12000)
            results.append(measured(f"noise {i}", g, x, 12000.0, 1797.0))
    values = np.array([v for _, v in results])
    faulty = np.array([v for verdict, v in results if verdict != "healthy"])
    quantiles = (0.0, 0.1, 0.5, 0.9, 1.0)
    spread = np.round(np.nanquantile(values, quantiles), 2)
    print(f"C, all {values.size}: quantiles {quantiles}: {spread}")
    if faulty.size:
        print(
            f"C, the {faulty.size} not called healthy: {faulty.min():+.2f} to {faulty.max():+.2f}"
        )


if __name__ == "__main__":
    main()
