"""The segment scan on long records of slow machines: segments of 20 or 40 fault periods.

A record whose whole envelope spectrum shows no fault is scanned in segments of
``max(SCAN_SEGMENT_S, N / slowest fault rate)`` (``cmtool.rule.segment_scan``). On a
machine whose slowest fault rate is under 40 Hz a 1 s segment holds fewer than
``TRUSTED_RATE_PERIODS``, where stop 58 measured more false alarms on short records. This
diagnoses every record of a dataset whole (healthy signals and faults at fault SNR >= -10
dB) three ways: without the scan, with segments of at least 20 periods (N = 20) and with
segments of at least 40 (N = 40), and prints each class's recall and the false alarms.

Run (docs/diagnosis.md, "Long records of slow machines"):
    cmtool generate RECIPE --out data/slow --workers 2   # e.g. cwru-rig.toml at 250-550 rpm, 8 s
    .venv/bin/python benchmarks/slow_long_records.py data/slow
"""

import argparse
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pandas as pd

import cmtool.diagnose as D
import cmtool.rule as R
from cmtool.datasets import read_dataset
from cmtool.pooling import CANONICAL

COLUMNS = ["id", "signal", "fs_hz", "rpm", "bearing", "label", "fault_snr_db"]
SHIPPED_SCAN = D.segment_scan


VARIANTS = {"no scan": None, "20 periods": 20, "40 periods": 40}


def _verdicts(record: dict) -> list:
    x = np.asarray(record["signal"], float)
    out = [record["id"], CANONICAL[record["label"]], record["rpm"]]
    shipped = R.SCAN_SEGMENT_PERIODS  # set where ``segment_scan`` reads it (cmtool.rule)
    for periods in VARIANTS.values():
        D.segment_scan = (lambda *a: None) if periods is None else SHIPPED_SCAN
        R.SCAN_SEGMENT_PERIODS = shipped if periods is None else periods
        d = D.diagnose_signal(x, record["fs_hz"], record["rpm"], record["bearing"], waviness=False)
        scan = d.segment_scan
        out += [d.verdict, 0 if scan is None else scan["segments"]]
    R.SCAN_SEGMENT_PERIODS = shipped
    D.segment_scan = SHIPPED_SCAN
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("datasets", nargs="+")
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    columns = []
    for v in VARIANTS:
        columns += [v, f"{v} segments"]
    for path in args.datasets:
        start = time.perf_counter()
        frame = read_dataset(path)
        frame = frame[(frame.label == "healthy") | (frame.fault_snr_db >= -10)]
        jobs = frame[COLUMNS].to_dict("records")
        with ProcessPoolExecutor(args.workers) as pool:
            rows = list(pool.map(_verdicts, jobs, chunksize=2))
        table = pd.DataFrame(rows, columns=["id", "truth", "rpm", *columns])
        print(f"{path}: {len(table)} records, {time.perf_counter() - start:.0f} s")
        healthy = table[table.truth == "healthy"]
        for v in VARIANTS:
            recall = (table.truth == table[v]).groupby(table.truth).mean()
            cells = " ".join(f"{k} {r:.3f}" for k, r in recall.items())
            alarms = int((healthy[v] != "healthy").sum())
            segments = table[f"{v} segments"]
            scanned = segments[segments > 0]
            seg = f"{scanned.min():.0f}-{scanned.max():.0f}" if scanned.size else "-"
            print(
                f"  {v:11s} {cells} balanced {recall.mean():.4f} | healthy called faulty "
                f"{alarms}/{len(healthy)} | segments {seg}"
            )
        by_rpm = healthy.groupby("rpm")
        for v in VARIANTS:
            cells = " ".join(
                f"{rpm:g}: {int((g[v] != 'healthy').sum())}/{len(g)}" for rpm, g in by_rpm
            )
            print(f"  false alarms by rpm, {v}: {cells}")


if __name__ == "__main__":
    main()
