"""The rule on short records, with and without the ball's cage-rate lines (stop 57).

docs/diagnosis.md, "Cage lines in short records". Each record of a dataset (healthy signals
and faults at fault SNR >= -10 dB) is diagnosed whole and cut to its first 0.5 s and 0.25 s
(``--lengths``), with the cage lines always weighed (``MIN_CAGE_REVOLUTIONS = 0``, the rule
before stop 57) and as shipped (weighed only in records of at least
``features.evidence.MIN_CAGE_REVOLUTIONS`` cage revolutions); prints each class's recall and
the balanced accuracy per length and rule, and how many whole-record verdicts differ.

``--periods 20,30`` cuts each record to that many periods of its slowest fault rate instead
(stop 58, docs/diagnosis.md "Records of few periods"; a 6205 at 1797 rpm: 20 periods of BPFO
are 0.19 s).

Run (about 40 s for a CWRU-rig draw and 100 s for an MFPT-rig one on two workers):
    cmtool generate datasets/cwru-rig.toml --out data/cwru-rig --workers 2
    .venv/bin/python benchmarks/short_records.py data/cwru-rig [--lengths 1,0.5,0.25]
    .venv/bin/python benchmarks/short_records.py data/cwru-rig --periods 20,30
"""

import argparse
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pandas as pd

import features.evidence as fe
from cmtool.datasets import read_dataset
from cmtool.diagnose import diagnose_signal
from cmtool.inputs import checked_geometry
from cmtool.pooling import CANONICAL
from generators import characteristic_frequencies

RULES = {"always": 0.0, "shipped": fe.MIN_CAGE_REVOLUTIONS}
COLUMNS = ["id", "signal", "fs_hz", "rpm", "bearing", "label", "fault_snr_db"]


def _samples(record: dict, length: float, periods: bool) -> int:
    """Samples in the first ``length`` s, or ``length`` periods of the slowest fault rate."""
    if not periods:
        return int(round(length * record["fs_hz"]))
    rates = characteristic_frequencies(checked_geometry(record["bearing"]), record["rpm"] / 60)
    slowest = min(rates.bpfo, rates.bpfi, rates.two_bsf)
    return int(np.ceil(length / slowest * record["fs_hz"]))


def _verdicts(args: tuple[dict, tuple[float, ...], bool]) -> list:
    record, lengths, periods = args
    x = np.asarray(record["signal"], float)
    out = [record["id"], CANONICAL[record["label"]]]
    for length in lengths:
        cut = x[: _samples(record, length, periods)]
        for revolutions in RULES.values():
            fe.MIN_CAGE_REVOLUTIONS = revolutions
            d = diagnose_signal(
                cut, record["fs_hz"], record["rpm"], record["bearing"], waviness=False
            )
            out.append(d.verdict)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("datasets", nargs="+")
    parser.add_argument("--lengths", default="1,0.5,0.25", help="record lengths [s]")
    parser.add_argument(
        "--periods", help="record lengths in periods of the slowest fault rate (not --lengths)"
    )
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    periods = args.periods is not None
    lengths = tuple(float(v) for v in (args.periods or args.lengths).split(","))
    unit = "periods" if periods else "s"
    columns = [f"{s:g} {unit} {rule}" for s in lengths for rule in RULES]
    for path in args.datasets:
        start = time.perf_counter()
        frame = read_dataset(path)
        frame = frame[(frame.label == "healthy") | (frame.fault_snr_db >= -10)]
        jobs = [(r, lengths, periods) for r in frame[COLUMNS].to_dict("records")]
        with ProcessPoolExecutor(args.workers) as pool:
            rows = list(pool.map(_verdicts, jobs, chunksize=2))
        table = pd.DataFrame(rows, columns=["id", "truth", *columns])
        print(f"{path}: {len(table)} records, {time.perf_counter() - start:.0f} s")
        for column in columns:
            recall = (table.truth == table[column]).groupby(table.truth).mean()
            cells = " ".join(f"{k} {v:.3f}" for k, v in recall.items())
            print(f"  {column:16s} {cells} balanced {recall.mean():.4f}")
        for length in lengths:
            a, b = (f"{length:g} {unit} {rule}" for rule in RULES)
            print(f"  {length:g} {unit}: verdicts that differ {int((table[a] != table[b]).sum())}")


if __name__ == "__main__":
    main()
