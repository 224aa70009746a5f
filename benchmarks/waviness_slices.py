"""Where a wavy inner race's lines lie, and what fitting them does to the rule (stop 72;
docs/diagnosis.md, "Waviness read as a local fault": measured, not shipped).

A wavy inner race of order N_w under a radial load excites its contacts at N_w (f_s - f_c)
per ball, weighed by each ball's load, which the stationary load zone makes a function of
the ball's angle; summed over the Z balls only the load zone's orders p = N_w + q Z survive,
so the lines lie at N_w f_s + q BPFO, and the Hertz law's curvature adds k N_w f_s + q BPFO
(k = 2, 3, ...): BPFO-spaced combs offset from the ball-pass series by k N_w f_s, the lattice's
slices m = k N_w, not the whole lattice m f_s + n BPFO. For N_w = Z, k N_w f_s = k (BPFI +
BPFO), so the slices are k BPFI + n BPFO, whose beats in the envelope are at BPFO.

``--lines RPM FS`` simulates the stop-31 case (6205, inner race N_w = 9, 1 um, 500 N, no noise)
and prints the record's strongest lines with the (m, n) of m f_s + n BPFO nearest each
(ambiguous assignments, |m| in the hundreds, are the resolution's, not lines of the slice),
then the strongest left after the slices k <= K are fitted with the shaft's and ball pass's
series. Otherwise the MODE is applied in place of the separation's harmonic fit
(``features.separation.remove_harmonics``, so that the instrument floor added next is the
shipped one) and the rule is run on ``benchmarks/sweep_waviness_verdicts.py``'s 24 wavy cases
and, with ``--pits``, on ``benchmarks/sweep_rule_detector.py``'s first 40 healthy runs and 45
pits, clean and in noise 3 x the RMS:

- ``before``: the separation before stop 72 (no slices);
- ``shipped``: the separation as shipped since stop 72 (``features.lattice``: the series
  offset by +/- k BPFI, k <= 6, each fitted where ``held_offsets`` finds it held);
- ``slices K``: the slices m = +/- k Z, k = 1 .. K, fitted jointly with the two series;
- ``gated K``: each of those slices fitted only where its comb's Hann-weighted power on the
  record, after the shipped fit, exceeds ``GATE`` times the median of 24 combs of the same
  spacing at offsets (j + 0.5) BPFO / 24 (what the random part puts on any comb): the
  exploration ``shipped`` came from (the same slices, the comb read by chirp-z transforms);
- ``gated-all M``: the same for every slice |m| <= M;
- ``orders K``: the shipped gate and joint fit with the series k BPFI + n BPFO, k <= K,
  offered (``features.lattice.inner_race_lattice_offsets(..., orders=K)``; stop 73).

Run: .venv/bin/python benchmarks/waviness_slices.py [MODE [K]] [--order N] [--pits] |
--lines RPM FS
"""

import argparse
import itertools
import math
import sys
import time
from collections import Counter

import numpy as np
from lattice_separation import OffsetFamily, remove_lines
from scipy.signal import find_peaks
from sweep_waviness_verdicts import CHANNEL, RIGS  # the sweep's cases (benchmarks/ on the path)

import features
import features.evidence as evidence
import features.separation as separation
from cmtool.diagnose import diagnose_signal
from generators import (
    OperatingCondition,
    SimulationSettings,
    Waviness,
    bearing,
    characteristic_frequencies,
    simulate,
)

#: A slice is fitted where its comb holds this many times the null combs' median power.
GATE = 4.0


def comb_power(r: np.ndarray, fs: float, spacing: float, offset: float) -> float:
    """Hann-weighted power of ``r`` on the comb offset + k spacing below fs / 2 [U^2]."""
    n = r.size
    margin = separation.COUPLED_BINS * fs / n
    kmin = math.floor((margin - offset) / spacing) + 1
    kmax = math.floor((0.5 * fs - margin - offset) / spacing)
    weights = np.hanning(n) / np.hanning(n).sum()
    family = OffsetFamily(n, spacing, offset, kmin, kmax - kmin + 1, fs)
    return float(np.sum(np.abs(family.analyse(r, weights)) ** 2))


def patch(mode: str, size: int, chosen: list[int]) -> None:
    """Put ``mode`` in place of the shipped separation (see the module's text)."""
    if mode == "shipped":
        shipped_held = separation.held_offsets

        def held(residue, fs, spacing, offsets):
            out = shipped_held(residue, fs, spacing, offsets)
            chosen.append(len(out))
            return out

        separation.held_offsets = held
        return
    if mode == "orders":  # the shipped gate and fit, the series k <= size offered
        lattice = sys.modules["features.lattice"]
        shipped_held = separation.held_offsets

        def offered(bpfo, bpfi, orders=size):
            return lattice.inner_race_lattice_offsets(bpfo, bpfi, orders)

        def held(residue, fs, spacing, offsets):
            out = shipped_held(residue, fs, spacing, offsets)
            chosen.append(len(out))
            return out

        evidence.inner_race_lattice_offsets = offered
        evidence.inner_race_lattice_orders = lambda orders=size: lattice.inner_race_lattice_orders(
            orders
        )
        sys.modules["features.envelope"].inner_race_lattice_offsets = offered
        separation.held_offsets = held
        return
    evidence.inner_race_lattice_offsets = lambda *args, **kwargs: ()  # no slices offered
    evidence.inner_race_lattice_orders = lambda *args, **kwargs: ()
    if mode == "before":
        return
    shipped_harmonics = separation.remove_harmonics
    shipped_evidence = evidence.fault_evidence
    balls = {}

    def fault_evidence(x, fs, fault_frequencies):
        f = fault_frequencies
        balls["z"] = int(round((f["bpfi"] + f["bpfo"]) / f["shaft"]))
        return shipped_evidence(x, fs, fault_frequencies)

    def fit(x, fs, fundamentals=(), offsets=()):
        if len(fundamentals) != 2:
            return shipped_harmonics(x, fs, fundamentals, offsets)
        shaft, bpfo = fundamentals
        z = balls["z"]
        if mode == "gated-all":
            slices = [s * m for m in range(1, size + 1) for s in (1, -1)]
        else:
            slices = [s * k * z for k in range(1, size + 1) for s in (1, -1)]
        if mode.startswith("gated"):
            r = shipped_harmonics(x, fs, fundamentals)
            null = np.median([comb_power(r, fs, bpfo, (j + 0.5) * bpfo / 24) for j in range(24)])
            slices = [
                m for m in slices if comb_power(r, fs, bpfo, (m * shaft) % bpfo) > GATE * null
            ]
            chosen.append(len(slices))
            if not slices:
                return r
        families = [(shaft, 0.0), (bpfo, 0.0)] + [(bpfo, (m * shaft) % bpfo) for m in slices]
        return remove_lines(x, fs, families)

    separation.remove_harmonics = fit
    features.fault_evidence = fault_evidence


def wavy_sweep(order: int) -> Counter:
    """The rule's verdicts on sweep_waviness_verdicts.py's 24 cases (inner race, 1 um)."""
    g = bearing("6205")
    noise = np.random.default_rng(18)
    verdicts = Counter()
    for (name, rig), rpm, fs in itertools.product(
        RIGS.items(), (900, 1500, 2400, 3600), (12000.0, 25600.0)
    ):
        settings = SimulationSettings(fs=fs, duration=1.0, channels=(CHANNEL,))
        wav = Waviness(surface="inner", order=order, amplitude=1e-6)
        op = OperatingCondition.from_rpm(rpm, 500.0)
        x = simulate(g, op, wav, rig=rig, settings=settings, random_state=3)[CHANNEL]
        x = x + noise.normal(0.0, 0.05 * np.std(x), x.size)
        d = diagnose_signal(x, fs, rpm, g)
        margin = max(c["evidence_db"] for c in d.candidates) - d.threshold_db
        print(f"  {name} {rpm} rpm {fs:.0f} Hz: {d.verdict} ({margin:+.1f} dB)")
        verdicts[d.verdict] += 1
    return verdicts


def strongest_lines(x: np.ndarray, fs: float, shaft: float, bpfo: float, count: int) -> None:
    """Print the ``count`` strongest peaks of x's Hann spectrum with their nearest (m, n)."""
    n = x.size
    window = np.hanning(n)
    amplitude = np.abs(np.fft.rfft((x - x.mean()) * window, 8 * n)) * 2 / window.sum()
    f = np.fft.rfftfreq(8 * n, 1 / fs)
    peaks, _ = find_peaks(amplitude, distance=8)
    for i in peaks[np.argsort(amplitude[peaks])[::-1][:count]]:
        m, q = min(
            ((round((f[i] - q * bpfo) / shaft), q) for q in range(-60, 61)),
            key=lambda mq: abs(f[i] - mq[0] * shaft - mq[1] * bpfo),
        )
        print(f"  {f[i]:9.2f} Hz  {amplitude[i]:.2e}  m = {m:4d}, n = {q:4d}")


def lines(rpm: float, fs: float, size: int) -> None:
    g = bearing("6205")
    settings = SimulationSettings(fs=fs, duration=1.0, channels=(CHANNEL,))
    wav = Waviness(surface="inner", order=9, amplitude=1e-6)
    x = simulate(g, OperatingCondition.from_rpm(rpm, 500.0), wav, settings=settings)[CHANNEL]
    rates = characteristic_frequencies(g, rpm / 60.0)
    print(f"6205, inner race N_w = 9, 1 um, {rpm:g} rpm, 500 N, {fs:g} Hz: the strongest lines")
    strongest_lines(x, fs, rates.shaft, rates.bpfo, 25)
    families = [(rates.shaft, 0.0), (rates.bpfo, 0.0)] + [
        (rates.bpfo, (s * k * 9 * rates.shaft) % rates.bpfo)
        for k in range(1, size + 1)
        for s in (1, -1)
    ]
    rest = remove_lines(x, fs, families)
    share = np.std(rest) / np.std(x)
    print(f"left after the series and the slices k <= {size}: {share:.3f} of the RMS")
    strongest_lines(rest, fs, rates.shaft, rates.bpfo, 10)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mode", nargs="?", default="shipped")
    parser.add_argument("size", nargs="?", type=int, default=6)
    parser.add_argument("--order", type=int, default=9, help="inner-race waviness order")
    parser.add_argument("--pits", action="store_true")
    parser.add_argument("--lines", nargs=2, type=float, metavar=("RPM", "FS"))
    args = parser.parse_args()
    if args.lines:
        lines(args.lines[0], args.lines[1], args.size)
        return
    chosen: list[int] = []
    patch(args.mode, args.size, chosen)
    start = time.perf_counter()
    verdicts = wavy_sweep(args.order)
    print(f"{args.mode} {args.size}: wavy inner race N_w = {args.order}: {dict(verdicts)}")
    if args.pits:
        import sweep_rule_detector

        sweep_rule_detector.healthy(40)
        sweep_rule_detector.pits(45, [0.0, 3.0])
    if chosen:
        print(f"slices fitted per record: {Counter(chosen)}")
    print(f"{time.perf_counter() - start:.0f} s")


if __name__ == "__main__":
    main()
