"""Does fitting the bearing's line lattice before envelope analysis stop form errors from
reading as local faults? (docs/diagnosis.md, "Form errors read as a local fault"; measured,
not shipped.)

The rule detector's separation fits the shaft's and the ball pass's harmonic series
(``features.separation.remove_harmonics``). A wavy inner race or ball also makes lines off
those series: k f_s -/+ q BPFO (inner race, docs/model.md 2.1) and 2 p f_b + n f_c (balls).
This script fits those lattices too (offset harmonic families, the same Hann-weighted joint
least squares) before the separation's line editing, and runs the rule
(``cmtool.diagnose.diagnose_signal``) on a dataset's healthy signals and its faults at fault
SNR >= -10 dB, printing per class the share of right verdicts (``ok``) and of any fault
called (``det``).

Modes: ``none`` (the shipped separation), ``shaft`` (+ f_s series offset by +/- q BPFO, q = 1,
2), ``cage`` (+ f_c series offset by p 2 f_b, p = 1, 2), ``all`` (both), ``bpfo`` (+ BPFO
series offset by +/- k f_s, k = 1, 2: the ball-pass train modulated by the shaft angle),
``bpfo+cage`` (and the f_c series, plain and offset by +/- 2 f_b).

``DATASET`` ``clean`` runs instead the four noise-free cases of
``tests/tests_cmtool/test_diagnosis.py::test_a_healthy_bearing_with_form_errors_is_no_local_fault``
(6205, 1797 rpm, clearance 5 um, 100 and 400 N, 0.1 um on the inner race or on the balls) and
prints each verdict with its margin over the threshold [dB].

Run: .venv/bin/python benchmarks/lattice_separation.py DATASET|clean MODE
"""

import math
import sys
import time

import numpy as np
from scipy import signal as sp_signal
from scipy.sparse import linalg as sparse_linalg

import features
import features.evidence as evidence
import features.separation as separation
from cmtool.datasets import read_dataset
from cmtool.diagnose import diagnose_signal

LABELS = {"healthy": "healthy", "inner": "inner race", "outer": "outer race", "ball": "ball"}


class OffsetFamily:
    """Lines offset + k f0, k = kmin .. kmin + count - 1: a chirp-z pair as in remove_harmonics."""

    def __init__(self, n: int, f0: float, offset: float, kmin: int, count: int, fs: float):
        step = np.exp(2j * np.pi * f0 / fs)
        first = np.exp(2j * np.pi * (offset + kmin * f0) / fs)
        self.analysis = sp_signal.CZT(n, m=count, w=1 / step, a=first)
        self.synthesis = sp_signal.CZT(count, m=n, w=step, a=1.0)
        self.ramp = first ** np.arange(n)

    def analyse(self, y, weights):
        return self.analysis(weights * y)

    def synthesise(self, amplitudes):
        return np.real(self.synthesis(amplitudes) * self.ramp)


def remove_lines(x: np.ndarray, fs: float, families: list[tuple[float, float]]) -> np.ndarray:
    """x minus the joint Hann-weighted fit of every (f0, offset) family below fs/2."""
    y = x - x.mean()
    n = y.size
    margin = separation.COUPLED_BINS * fs / n
    transforms, lines = [], []
    for f0, offset in families:
        # a plain series from its first harmonic, as remove_harmonics fits it; an offset
        # series from its first line a coupling width above 0 Hz
        kmin = 1 if offset == 0.0 else math.floor((margin - offset) / f0) + 1
        kmax = math.floor((0.5 * fs - margin - offset) / f0)
        if f0 * n / fs < 4 or kmax < kmin:
            continue
        transforms.append(OffsetFamily(n, f0, offset, kmin, kmax - kmin + 1, fs))
        lines.append(offset + f0 * np.arange(kmin, kmax + 1))
    if not transforms:
        return y
    weights = np.hanning(n) / np.hanning(n).sum()
    solve = sparse_linalg.splu(separation._hann_gram(np.concatenate(lines) / fs, n)).solve
    splits = np.cumsum([line.size for line in lines])[:-1]
    total, moved = np.zeros(n), math.inf
    scale = float(np.sqrt(np.sum(weights * y * y))) or 1.0
    for _ in range(separation.MAX_PASSES):
        projections = np.concatenate([t.analyse(y - total, weights) for t in transforms])
        amplitudes = np.split(2.0 * solve(projections), splits)
        fit = sum(t.synthesise(a) for t, a in zip(transforms, amplitudes, strict=True))
        step = float(np.sqrt(np.sum(weights * fit * fit))) / scale
        if step >= moved:
            break
        total, moved = total + fit, step
        if step < separation.SETTLED:
            break
    return y - total


def main(path: str, mode: str) -> None:
    rates: dict[str, float] = {}
    shipped_harmonics = separation.remove_harmonics
    shipped_evidence = evidence.fault_evidence

    def separate(x, fs, fundamentals=(), offsets=()):
        # in place of the separation's harmonic fit, so that the instrument floor it adds next
        # is scaled to the record's RMS as shipped (until stop 72 the lattice was fitted before
        # the whole separation, whose floor then lay 50 dB under the fit's residue instead)
        if mode == "none" or len(fundamentals) != 2:
            return shipped_harmonics(x, fs, fundamentals, offsets)
        shaft, bpfo = fundamentals
        # the shipped fit's series, with the inner race's lattice slices it holds (stop 72)
        families = [(shaft, 0.0), (bpfo, 0.0)] + [(bpfo, o) for o in offsets]
        if mode in ("shaft", "all"):
            families += [(shaft, (s * q * bpfo) % shaft) for q in (1, 2) for s in (1, -1)]
        if mode in ("cage", "all"):
            families += [(rates["ftf"], (p * rates["two_bsf"]) % rates["ftf"]) for p in (1, 2)]
        if mode.startswith("bpfo"):
            # the ball-pass train modulated by the shaft angle: n BPFO +/- k f_s, k = 1, 2
            families += [(bpfo, (s * k * shaft) % bpfo) for k in (1, 2) for s in (1, -1)]
        if mode == "bpfo+cage":
            # each ball's own events at the cage rate, modulated by its spin
            ftf, two_bsf = rates["ftf"], rates["two_bsf"]
            families += [(ftf, 0.0)] + [(ftf, (s * two_bsf) % ftf) for s in (1, -1)]
        return remove_lines(x, fs, families)

    def fault_evidence(x, fs, fault_frequencies):
        rates.update(fault_frequencies)
        return shipped_evidence(x, fs, fault_frequencies)

    separation.remove_harmonics = separate
    features.fault_evidence = fault_evidence
    if path == "clean":
        print(mode, "clean:", " ".join(_clean_verdicts()))
        return
    frame = read_dataset(path)
    frame = frame[(frame["label"] == "healthy") | (frame["fault_snr_db"] >= -10)]
    start = time.perf_counter()
    verdicts = [
        diagnose_signal(
            np.asarray(r.signal, float), r.fs_hz, r.rpm, r.bearing, waviness=False
        ).rule_verdict["label"]
        for r in frame.itertuples()
    ]
    frame = frame.assign(
        ok=np.array(verdicts) == frame["label"].map(LABELS).to_numpy(),
        det=np.array(verdicts) != "healthy",
    )
    print(f"{mode} {path}: {len(frame)} signals, {time.perf_counter() - start:.0f} s")
    print(frame.groupby("label")[["ok", "det"]].mean().round(3).to_string())


def _clean_verdicts() -> list[str]:
    from generators import (
        OperatingCondition,
        SimulationSettings,
        bearing,
        form_waviness,
        simulate,
    )

    g = bearing("6205", radial_internal_clearance=5e-6)
    settings = SimulationSettings(fs=12000.0, duration=1.0, channels=("housing_acceleration_y",))
    out = []
    for load in (100.0, 400.0):
        op = OperatingCondition.from_rpm(1797, load)
        for form in (form_waviness(9, 1e-7, 0.0, 0.0), form_waviness(9, 0.0, 0.0, 1e-7)):
            x = simulate(g, op, form, settings=settings, random_state=2)["housing_acceleration_y"]
            d = diagnose_signal(x, 12000.0, 1797, g, waviness=False)
            best = max(d.candidates, key=lambda c: c["evidence_db"])
            out.append(f"{d.rule_verdict['label']}({best['evidence_db'] - d.threshold_db:+.1f})")
    return out


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
