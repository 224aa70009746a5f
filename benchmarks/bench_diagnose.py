"""Diagnosis speed: the rule's evidence, a diagnosis and its report (prints figures, not a test).

What an analyst waits for per recording (``cmtool diagnose FILE --report DIR``, or a folder of
them): ``features.fault_evidence`` (separation, band selection, weighed lines), the whole
``diagnose_signal`` (evidence, plain-spectrum and waviness checks, speed check, segment scan)
and ``write_report`` (its plots and text). The records: a 6205 at 1797 rpm, impacts at BPFO
with 1 % jitter ringing at 3 kHz in white noise, 1 and 10 s at 12 kHz and 1 s at 48 kHz; the
median of ``--repeats`` runs after one warm-up. Each run is a recording at a speed not
diagnosed before: the harmonic families' transforms that ``features.separation`` keeps for
the next record of the same length, rate and speed are dropped before it (``--kept`` keeps
them, as for a dataset's signals at repeated operating points).

Run: ``.venv/bin/python benchmarks/bench_diagnose.py [--repeats 5]``
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from scipy import signal as sp_signal

import features
from cmtool.diagnose import diagnose_signal, rule_context, write_report
from features import separation
from generators import bearing, characteristic_frequencies

RPM = 1797.0


def _record(fs: float, seconds: float, rng: np.random.Generator) -> np.ndarray:
    """Impacts at BPFO (1 % jitter) ringing at 3 kHz, white noise at the impacts' RMS."""
    n = round(fs * seconds)
    bpfo = characteristic_frequencies(bearing("6205"), RPM / 60.0).bpfo
    times = np.arange(0.0, seconds, 1.0 / bpfo)
    times = times + rng.normal(0.0, 0.01 / bpfo, times.size)
    x = np.zeros(n)
    x[np.clip((times * fs).astype(int), 0, n - 1)] = 1.0
    x = sp_signal.lfilter(*sp_signal.iirpeak(3000.0, 15.0, fs), x)
    return x + np.std(x) * rng.standard_normal(n)


def _median_time(run, repeats: int, kept: bool = False) -> float:
    run()  # warm-up: first-call imports
    times = []
    for _ in range(repeats):
        if not kept:  # a new speed: no family's transforms set up yet (a private cache)
            separation._transform_cache.clear()
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return float(np.median(times))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument(
        "--kept", action="store_true", help="keep the transforms between runs (same speed)"
    )
    args = parser.parse_args(argv)
    rng = np.random.default_rng(0)
    geometry = bearing("6205")
    print(f"{'record':<16s} {'fault_evidence':>15s} {'diagnose_signal':>16s} {'write_report':>13s}")
    with tempfile.TemporaryDirectory() as tmp:
        for fs, seconds in ((12000.0, 1.0), (12000.0, 10.0), (48000.0, 1.0)):
            x = _record(fs, seconds, rng)
            _, freqs, ctx, _ = rule_context(x, fs, RPM, geometry)
            ctx = {**ctx, "ftf": freqs.ftf}
            evidence = _median_time(
                lambda x=x, fs=fs, ctx=ctx: features.fault_evidence(x, fs, ctx),
                args.repeats,
                args.kept,
            )
            diagnosis = diagnose_signal(x, fs, RPM, geometry)
            whole = _median_time(
                lambda x=x, fs=fs: diagnose_signal(x, fs, RPM, geometry), args.repeats, args.kept
            )
            out = Path(tmp) / f"{fs:g}-{seconds:g}"
            report = _median_time(
                lambda x=x, fs=fs, d=diagnosis, out=out: write_report(
                    d, out, title="bench", x=x, fs=fs
                ),
                args.repeats,
            )
            label = f"{seconds:g} s at {fs / 1e3:g} kHz"
            print(
                f"{label:<16s} {evidence * 1e3:>12.1f} ms {whole * 1e3:>13.1f} ms "
                f"{report * 1e3:>10.0f} ms  (verdict {diagnosis.verdict})"
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
