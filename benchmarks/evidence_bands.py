"""The rule with its band chosen by the weighed evidence of K bands, against one band (stop 68).

docs/diagnosis.md, "The band chosen by the weighed evidence". Each record of a dataset
(healthy signals and faults at fault SNR >= -10 dB) is diagnosed with
``features.evidence.EVIDENCE_BANDS = 1`` (as shipped) and ``= K`` (``--bands``, default 6),
both in the same worker, their order alternated from record to record, each call timed;
prints each class's recall and the balanced accuracy for both, the verdicts the K-band rule
turns wrong and right, the healthy records either calls faulty, and the ratio of the two
rules' summed times. Since stop 68 the K-band rule counts the family's test once per band
weighed (``features.evidence.combine_lines``); ``--uncounted`` gives stop 56's and the first
stop-68 bar's rule (the factor 2 whatever K).

Run (about 35 s for a 1 s CWRU-rig draw, 2-4 minutes for an MFPT-rig one, 10-30 minutes for
10 s or 6 s records, on two workers):
    cmtool generate datasets/cwru-rig.toml --out data/cwru-rig --workers 2
    .venv/bin/python benchmarks/evidence_bands.py data/cwru-rig [--bands 6] [--uncounted]
The stop-68 draws: the recipes with ``seed`` 6800-6804 (bar 1, ``--uncounted``) and
6810-6814 (bar 2), ``duration_s = 10.0`` (CWRU rig) and ``6.0`` (MFPT rig) for the long ones.
"""

import argparse
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np

import features.evidence as fe
from cmtool.datasets import read_dataset
from cmtool.diagnose import diagnose_signal
from cmtool.pooling import CANONICAL

CLASSES = ("healthy", "inner race", "outer race", "ball")
COLUMNS = ["id", "signal", "fs_hz", "rpm", "bearing", "label", "fault_snr_db"]


def _setup(uncounted: bool) -> None:
    """In each worker: with ``uncounted``, every family weighed as one band's (factor 2)."""
    if uncounted:
        weigh = fe._weigh  # looked up by name inside features.evidence at each call

        def _weigh_once(family, n_bands, searched, floor, bands_weighed=1):
            return weigh(family, n_bands, searched, floor, 1)

        fe._weigh = _weigh_once


def _verdicts(args: tuple[int, dict, int]) -> tuple:
    index, record, bands = args
    x = np.asarray(record["signal"], float)
    out = {}
    for k in (1, bands) if index % 2 == 0 else (bands, 1):
        fe.EVIDENCE_BANDS = k
        start = time.perf_counter()
        d = diagnose_signal(x, record["fs_hz"], record["rpm"], record["bearing"], waviness=False)
        out[k] = (d.rule_verdict["label"], time.perf_counter() - start)
    return record["id"], CANONICAL[record["label"]], out[1], out[bands]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dataset", help="a dataset folder (cmtool generate)")
    parser.add_argument("--bands", type=int, default=6, help="K, the bands weighed (default 6)")
    parser.add_argument("--uncounted", action="store_true", help="the factor 2 whatever K")
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    frame = read_dataset(args.dataset)
    frame = frame[~(frame["fault_snr_db"].to_numpy() < -10)][COLUMNS]
    jobs = [(i, r._asdict(), args.bands) for i, r in enumerate(frame.itertuples(index=False))]
    with ProcessPoolExecutor(args.workers, initializer=_setup, initargs=(args.uncounted,)) as pool:
        rows = list(pool.map(_verdicts, jobs, chunksize=4))
    labels = np.array([label for _, label, _, _ in rows])
    one = np.array([v for _, _, (v, _), _ in rows])
    many = np.array([v for _, _, _, (v, _) in rows])

    def recall(verdicts, label):
        chosen = labels == label
        return int((verdicts[chosen] == label).sum()), int(chosen.sum())

    balanced = {}
    for name, verdicts in (("1 band", one), (f"{args.bands} bands", many)):
        parts = [(c, *recall(verdicts, c)) for c in CLASSES if (labels == c).any()]
        balanced[name] = float(np.mean([right / n for _, right, n in parts]))
        print(
            f"{name}: balanced {balanced[name]:.3f}; "
            + ", ".join(f"{c} {right}/{n}" for c, right, n in parts)
        )
    worse = int(((one == labels) & (many != labels)).sum())
    better = int(((one != labels) & (many == labels)).sum())
    healthy = labels == "healthy"
    t_one = sum(t for _, _, (_, t), _ in rows)
    t_many = sum(t for _, _, _, (_, t) in rows)
    print(
        f"{len(rows)} records: gain {balanced[f'{args.bands} bands'] - balanced['1 band']:+.3f}; "
        f"verdicts turned wrong {worse}, right {better}; healthy called faulty "
        f"{int((one[healthy] != 'healthy').sum())} -> {int((many[healthy] != 'healthy').sum())}; "
        f"time {t_one:.0f} -> {t_many:.0f} s ({t_many / t_one:.2f} x)"
    )


if __name__ == "__main__":
    main()
