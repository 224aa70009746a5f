"""Discrete/random separation variants against waviness read as a local fault (prints figures).

Issue 18: the rule detector calls most wavy bearings faulty (docs/diagnosis.md, "Waviness read
as a local fault"). This runs the rule with ``features.fault_evidence``'s separation replaced
by a variant, on the cases of ``benchmarks/sweep_waviness_verdicts.py`` (1 um of inner-race
waviness N_w = 9 and ball waviness N_w = 2, three rigs, 900-3600 rpm, 12 and 25.6 kHz, 5 %
noise), 60 clean healthy runs and 45 pits with 1 % slip (clean and in noise 3 x the RMS) of
``benchmarks/sweep_rule_detector.py``'s grids, and counts the right verdicts. It also prints
where in the record the shipped separation's residue of a wavy signal lies (RMS per tenth of
the record, as a fraction of the signal's RMS; the noise is 0.05). Nothing here is shipped;
no threshold is chosen on it.

Variants (``--variants``, any of):

- ``shipped``: ``features.separate_discrete`` as it is;
- ``drs``: then Antoni and Randall's (2004) frequency-domain discrete/random separation: the
  filter that predicts the record from itself 0.1 s earlier (0.125 s Hann segments, 75 %
  overlap) removes what is predictable;
- ``mirror``: the bin editing on the record followed by its mirror image (no wrap-around
  discontinuity, so a line's leakage falls as 1/k^2), the threshold raised to 13.8 dB for the
  mirror's half-normal bins (the same one edit in a thousand noise bins);
- ``trim``: the shipped separation, the first and last tenth of the record dropped;
- ``percentile``: the line threshold against the 20th percentile of the neighbourhood
  instead of its median (a floor between dense lines), 14.9 dB (one noise bin in a thousand).

Run: .venv/bin/python benchmarks/separation_variants.py [--variants shipped drs ...]
"""

from __future__ import annotations

import argparse
import itertools
import time
from collections import Counter

import numpy as np
from scipy import ndimage

import features.evidence as evidence
from cmtool.diagnose import diagnose_signal
from features.separation import INSTRUMENT_FLOOR_DB, NEIGHBOURS, remove_periodic
from generators import (
    LocalizedDefect,
    OperatingCondition,
    Rig,
    SimulationSettings,
    Waviness,
    bearing,
    characteristic_frequencies,
    simulate,
)

CHANNEL = "housing_acceleration_y"
RIGS = {
    "default": Rig(),
    "light": Rig(housing_mass=0.8, pedestal_stiffness=2e7),
    "heavy": Rig(housing_mass=6.0, pedestal_stiffness=2e8, shaft_mass=2.5),
}
BEARINGS = ("6205", "6203", "6305", "6002", "6308", "mfpt")
VERDICT = {"inner": "inner race", "outer": "outer race", "ball": "ball"}
SHIPPED = evidence.separate_discrete


def cases() -> list[dict]:
    """The simulated cases: kind, bearing, rpm, fs, signal, the right verdict."""
    out = []
    noise = np.random.default_rng(18)
    for surface, order in (("inner", 9), ("ball", 2)):
        for rig, rpm, fs in itertools.product(
            RIGS.values(), (900, 1500, 2400, 3600), (12e3, 25.6e3)
        ):
            settings = SimulationSettings(fs=fs, duration=1.0, channels=(CHANNEL,))
            op = OperatingCondition.from_rpm(rpm, 500.0)
            wavy = Waviness(surface=surface, order=order, amplitude=1e-6)
            x = simulate(bearing("6205"), op, wavy, rig=rig, settings=settings, random_state=3)
            x = x[CHANNEL] + noise.normal(0.0, 0.05 * np.std(x[CHANNEL]), x[CHANNEL].size)
            out.append(
                dict(kind=f"wavy {surface}", name="6205", rpm=rpm, fs=fs, x=x, right="healthy")
            )
    grid = list(
        itertools.product(
            BEARINGS, (600, 1200, 1797, 3000, 6000), (100.0, 500.0, 2000.0), (12e3, 25.6e3, 48e3)
        )
    )
    np.random.default_rng(1).shuffle(grid)
    for name, rpm, load, fs in grid[:60]:
        settings = SimulationSettings(fs=fs, duration=1.0, channels=(CHANNEL,))
        x = simulate(bearing(name), OperatingCondition.from_rpm(rpm, load), settings=settings)[
            CHANNEL
        ]
        out.append(dict(kind="healthy", name=name, rpm=rpm, fs=fs, x=x, right="healthy"))
    grid = list(
        itertools.product(
            BEARINGS, (600, 1200, 1797, 3000), (200.0, 1000.0), (12e3, 25.6e3, 48e3), VERDICT
        )
    )
    np.random.default_rng(3).shuffle(grid)
    for i, (name, rpm, load, fs, surface) in enumerate(grid[:45]):
        settings = SimulationSettings(fs=fs, duration=1.0, channels=(CHANNEL,))
        op = OperatingCondition.from_rpm(rpm, load, random_slip=0.01, ball_jitter=0.005)
        pit = LocalizedDefect(surface=surface, length=0.3e-3, depth=0.1e-3)
        x = simulate(bearing(name), op, pit, settings=settings, random_state=i)[CHANNEL]
        out.append(dict(kind="pit", name=name, rpm=rpm, fs=fs, x=x, right=VERDICT[surface]))
        noisy = x + np.random.default_rng(i).normal(0.0, 3.0 * np.std(x), x.size)
        out.append(
            dict(
                kind="pit, noise 3 x RMS",
                name=name,
                rpm=rpm,
                fs=fs,
                x=noisy,
                right=VERDICT[surface],
            )
        )
    return out


def _floored(x: np.ndarray, fs: float, fundamentals, lattice=()) -> np.ndarray:
    """The shipped separation's first two steps: harmonics removed, the instrument floor added."""
    y = remove_periodic(x, fs, fundamentals, lattice)
    seed = np.frombuffer(np.ascontiguousarray(x[:64], dtype=float).tobytes(), np.uint32)
    floor = np.std(x) * 10.0 ** (-INSTRUMENT_FLOOR_DB / 20.0)
    return y + np.random.default_rng(seed).normal(0.0, floor, x.size)


def _edit(spec: np.ndarray, floor: np.ndarray, ratio: float) -> np.ndarray:
    lines = np.abs(spec) > ratio * floor
    for _ in range(NEIGHBOURS):
        lines[1:] |= lines[:-1].copy()
        lines[:-1] |= lines[1:].copy()
    lines[0] = True
    return np.where(lines, 0.0, spec)


def drs(x, fs, fundamentals=(), lattice=(), delay_s=0.1, segment_s=0.125):
    """Shipped separation, then frequency-domain DRS (Antoni and Randall 2004)."""
    y = SHIPPED(x, fs, fundamentals=fundamentals, lattice=lattice)
    n, seg, delay = y.size, int(round(segment_s * fs)), int(round(delay_s * fs))
    window = np.hanning(seg)
    cross = np.zeros(seg // 2 + 1, complex)
    power = np.zeros(seg // 2 + 1)
    for i in range(delay, n - seg + 1, seg // 4):
        now = np.fft.rfft(window * y[i : i + seg])
        before = np.fft.rfft(window * y[i - delay : i - delay + seg])
        cross += now * np.conj(before)
        power += np.abs(before) ** 2
    h = np.roll(np.fft.irfft(cross / np.maximum(power, 1e-300), seg), seg // 2) * window
    full = np.convolve(y, h)
    index = np.arange(n) - delay + seg // 2
    predicted = np.where(
        (index >= 0) & (index < full.size), full[np.clip(index, 0, full.size - 1)], 0.0
    )
    return y - predicted


def mirror(x, fs, fundamentals=(), lattice=()):
    """Bin editing of the record and its mirror image, 13.8 dB over the median."""
    y = _floored(x, fs, fundamentals, lattice)
    y = y - y.mean()
    z = np.concatenate([y, y[::-1]])
    spec = np.fft.rfft(z)
    bins = max(21, int(round(20.0 * z.size / fs))) | 1
    floor = ndimage.median_filter(np.abs(spec), size=bins, mode="nearest")
    return np.fft.irfft(_edit(spec, floor, 10 ** (13.8 / 20)), z.size)[: y.size]


def trim(x, fs, fundamentals=(), lattice=()):
    """The shipped separation without the record's first and last tenth."""
    y = SHIPPED(x, fs, fundamentals=fundamentals, lattice=lattice)
    return y[y.size // 10 : y.size - y.size // 10]


def percentile(x, fs, fundamentals=(), lattice=()):
    """Bin editing against the 20th percentile of the neighbourhood, 14.9 dB over it."""
    y = _floored(x, fs, fundamentals, lattice)
    spec = np.fft.rfft(y - y.mean())
    bins = max(21, int(round(20.0 * y.size / fs))) | 1
    floor = ndimage.percentile_filter(np.abs(spec), 20, size=bins, mode="nearest")
    ratio = np.sqrt(-2 * np.log(1e-3)) / np.sqrt(-2 * np.log(0.8))
    return np.fft.irfft(_edit(spec, floor, ratio), y.size)


VARIANTS = {
    "shipped": SHIPPED,
    "drs": drs,
    "mirror": mirror,
    "trim": trim,
    "percentile": percentile,
}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--variants", nargs="+", default=list(VARIANTS), choices=list(VARIANTS))
    args = parser.parse_args()
    signals = cases()
    print("where the shipped separation's residue of a wavy signal lies (RMS per tenth / RMS):")
    for case in signals[:24:6]:
        f = characteristic_frequencies(bearing(case["name"]), case["rpm"] / 60.0)
        rest = SHIPPED(case["x"], case["fs"], fundamentals=(case["rpm"] / 60.0, f.bpfo))
        tenths = " ".join(f"{np.std(t) / np.std(case['x']):.2f}" for t in np.array_split(rest, 10))
        print(f"  {case['kind']} {case['rpm']} rpm {case['fs']:.0f} Hz: {tenths}")
    for name in args.variants:
        evidence.separate_discrete = VARIANTS[name]
        right, total = Counter(), Counter()
        start = time.perf_counter()
        for case in signals:
            verdict = diagnose_signal(
                case["x"], case["fs"], case["rpm"], bearing(case["name"])
            ).verdict
            total[case["kind"]] += 1
            right[case["kind"]] += verdict == case["right"]
        seconds = (time.perf_counter() - start) / len(signals)
        shown = ", ".join(f"{kind} {right[kind]}/{total[kind]}" for kind in total)
        print(f"{name:10s}: {shown} ({seconds:.2f} s a record)")
    evidence.separate_discrete = SHIPPED


if __name__ == "__main__":
    main()
