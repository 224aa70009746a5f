"""How much clipping the rule detector's verdict survives (issue 18: warnings become errors
where the answer cannot be trusted).

Each signal of a simulated dataset (its healthy signals and the faults at fault SNR >= -10 dB)
is clipped symmetrically at the level that puts a share q of its samples at full scale, and
``diagnose_signal`` (the rule, no model) is run on it; printed per q: the share of signals
whose verdict differs from the unclipped signal's, the healthy signals' false alarms, and the
right verdicts (the first row, q = 0, is the unclipped signals'). Simulated datasets only.

Run: .venv/bin/python benchmarks/clipping.py DATASET [--workers 2]
"""

from __future__ import annotations

import argparse
from concurrent.futures import ProcessPoolExecutor

import numpy as np

SHARES = (0.0, 0.001, 0.003, 0.01, 0.03, 0.1, 0.3)


def clipped(x: np.ndarray, share: float) -> np.ndarray:
    """x clipped at +/- the level that puts ``share`` of its samples at full scale."""
    if share <= 0.0:
        return x
    level = float(np.quantile(np.abs(x), 1.0 - share))
    return np.clip(x, -level, level)


def _verdicts(row: tuple) -> list[str]:
    from cmtool.diagnose import diagnose_signal

    x, fs, rpm, bearing = row
    return [
        diagnose_signal(clipped(x, q), fs, rpm, bearing, waviness=False).verdict for q in SHARES
    ]


def main() -> None:
    from cmtool.classifier import MIN_FAULT_SNR_DB, visible_faults
    from cmtool.datasets import read_dataset
    from cmtool.diagnose import CANONICAL

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dataset")
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    frame = read_dataset(args.dataset)
    frame = frame[visible_faults(frame, MIN_FAULT_SNR_DB).to_numpy()].reset_index(drop=True)
    rows = [
        (np.asarray(r.signal, dtype=float), r.fs_hz, r.rpm, r.bearing) for r in frame.itertuples()
    ]
    with ProcessPoolExecutor(args.workers) as pool:
        table = np.array(list(pool.map(_verdicts, rows, chunksize=8)))
    truth = np.array([CANONICAL[label] for label in frame["label"]])
    healthy = truth == "healthy"
    print(f"{args.dataset}: {len(truth)} signals ({int(healthy.sum())} healthy)")
    for j, q in enumerate(SHARES):
        v = table[:, j]
        found = np.mean(v[~healthy] == truth[~healthy])
        print(
            f"  clipped share {q:5.3f}: verdict changed {np.mean(v != table[:, 0]):.3f}, "
            f"healthy false alarms {np.mean(v[healthy] != 'healthy'):.3f}, right "
            f"{np.mean(v == truth):.3f} (faults found {found:.3f})"
        )


if __name__ == "__main__":
    main()
