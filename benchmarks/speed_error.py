"""The rule's verdicts when the speed given is off, and the speed the spectrum's 1x line shows.

docs/diagnosis.md, "The speed the rates come from". Each record of a dataset (healthy
signals and faults at fault SNR >= -10 dB) is diagnosed with the speed given ``--errors``
off its own (given = true x (1 + error)), the rates from the speed given (``--speed-source``,
default ``given``); prints each class's recall per error. Then the
1x line is read from each record's spectrum about each of those speeds
(``features.shaft_rate_from_spectrum``): how often it is found, its largest error against
the true speed, and how often diagnose's warning (``cmtool.diagnose.SPEED_WARNING``) would
fire.

Run (about 3 minutes for a CWRU-rig draw on two workers):
    cmtool generate datasets/cwru-rig.toml --out data/cwru-rig --workers 2
    .venv/bin/python benchmarks/speed_error.py data/cwru-rig [--errors=-0.04,-0.02,0,0.02]
        [--warning 0.01] [--speed-source auto]
"""

import argparse
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pandas as pd

from cmtool.datasets import read_dataset
from cmtool.diagnose import SPEED_SOURCES, SPEED_WARNING, diagnose_signal
from cmtool.pooling import CANONICAL
from features import shaft_rate_from_spectrum

COLUMNS = ["id", "signal", "fs_hz", "rpm", "bearing", "label"]


def _run(args: tuple[dict, tuple[float, ...], str]) -> list:
    record, errors, source = args
    x = np.asarray(record["signal"], float)
    true_hz = record["rpm"] / 60.0
    out = [record["id"], CANONICAL[record["label"]]]
    for error in errors:
        given = record["rpm"] * (1.0 + error)
        out.append(
            diagnose_signal(
                x, record["fs_hz"], given, record["bearing"], waviness=False, speed_source=source
            ).verdict
        )
        estimate = shaft_rate_from_spectrum(x, record["fs_hz"], given / 60.0)
        out += [estimate.found, estimate.rate_hz / true_hz - 1.0, abs(estimate.deviation)]
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("datasets", nargs="+")
    parser.add_argument("--errors", default="-0.04,-0.02,-0.01,0,0.01,0.02,0.04")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument(
        "--speed-source",
        default="given",
        choices=SPEED_SOURCES,
        help="diagnose's speed source (default given: the cost of the speed given being off; "
        "auto, diagnose's default, takes the 1x line's speed beyond SPEED_CORRECTION)",
    )
    parser.add_argument(
        "--warning",
        type=float,
        default=SPEED_WARNING,
        help=f"the relative deviation warned of (default diagnose's, {SPEED_WARNING})",
    )
    args = parser.parse_args()
    errors = tuple(float(v) for v in args.errors.split(","))
    columns = []
    for e in errors:
        columns += [f"{e:+.2%}", f"{e:+.2%} found", f"{e:+.2%} error", f"{e:+.2%} deviation"]
    for path in args.datasets:
        frame = read_dataset(path)
        frame = frame[(frame.label == "healthy") | (frame.fault_snr_db >= -10)]
        jobs = [(r, errors, args.speed_source) for r in frame[COLUMNS].to_dict("records")]
        with ProcessPoolExecutor(args.workers) as pool:
            rows = list(pool.map(_run, jobs, chunksize=4))
        table = pd.DataFrame(rows, columns=["id", "truth", *columns])
        print(f"{path}: {len(table)} records")
        for e in errors:
            c = f"{e:+.2%}"
            recall = (table.truth == table[c]).groupby(table.truth).mean()
            found = table[f"{c} found"]
            worst = table.loc[found, f"{c} error"].abs().max() if found.any() else float("nan")
            warned = (found & (table[f"{c} deviation"] > args.warning)).mean()
            cells = " ".join(f"{k} {v:.2f}" for k, v in recall.items())
            print(
                f"  speed given {c:>6s}: {cells} | 1x line found {found.mean():.3f}, "
                f"largest error {100 * worst:.3f} %, warned {warned:.3f}"
            )


if __name__ == "__main__":
    main()
