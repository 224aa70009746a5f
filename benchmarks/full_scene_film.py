"""Scene ``full`` with its film on the healthy sweep's cases: chatter, periodicity, verdicts.

Draws the cases of ``benchmarks/sweep_healthy_extremes.py`` (seeds 6901-6906 by default,
60 each) and runs those of scene ``full`` with the film (``--dry``: without): 1 s, noise-free,
with the contact loads recorded. Prints per case the outer contacts' load-zone transitions
per second (loads over 0.1 N, all balls) against a steady load zone's 2 Z FTF, the share of
the housing's RMS that is not periodic at the ball pass (harmonics of the run's BPFO fitted
to the record), and the rule's verdict (``diagnose_signal`` with the load given); then the
verdicts counted. docs/model.md 7.4 quotes it (stop 71: the film between ball and race apart).

Run: .venv/bin/python benchmarks/full_scene_film.py [--seeds 6901-6906] [--dry] [--max-rpm R]
"""

from __future__ import annotations

import argparse
import json
import warnings
from collections import Counter

import numpy as np
from joblib import Parallel, delayed
from sweep_healthy_extremes import draw

from cmtool.diagnose import diagnose_signal
from generators import OperatingCondition, Scene, SimulationSettings, bearing, simulate

#: a contact counts as loaded over this force [N] (the film's push apart is smaller)
LOADED_N = 0.1


def not_periodic_share(x: np.ndarray, fs: float, bpfo: float) -> float:
    """RMS of what harmonics of ``bpfo`` [Hz] up to 0.45 fs leave of ``x``, over its RMS."""
    t = np.arange(x.size) / fs
    phase = 2 * np.pi * np.outer(t, np.arange(1, int(0.45 * fs // bpfo) + 1) * bpfo)
    basis = np.hstack([np.cos(phase), np.sin(phase), np.ones((x.size, 1))])
    rest = x - basis @ np.linalg.lstsq(basis, x, rcond=None)[0]
    return float(np.std(rest) / np.std(x))


def run(case: dict) -> dict:
    """One case's transitions per second, non-periodic share and verdict."""
    warnings.simplefilter("ignore")  # loads over C0r are warned of; drawn on purpose
    g = bearing(case["name"], radial_internal_clearance=case["clearance"])
    settings = SimulationSettings(
        fs=case["fs"],
        duration=1.0,
        channels=("housing_acceleration_y",),
        record_contact_loads=True,
    )
    op = OperatingCondition.from_rpm(case["rpm"], case["load"])
    r = simulate(g, op, scene=Scene(level="full", ehl=case["ehl"]), settings=settings)
    x = r["housing_acceleration_y"]
    loaded = (r.contact_loads[:, 1, :] > LOADED_N).astype(int)
    try:
        verdict = diagnose_signal(x, case["fs"], case["rpm"], g, load_n=case["load"]).verdict
    except ValueError:  # too short for the slowest fault rate
        verdict = "refused"
    return {
        **case,
        "transitions_per_s": int(np.abs(np.diff(loaded, axis=0)).sum()),
        "steady_per_s": round(2 * g.ball_count * r.frequencies.ftf, 1),
        "not_periodic": round(not_periodic_share(x, r.fs, r.frequencies.bpfo), 4),
        "verdict": verdict,
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", default="6901-6906", help="first-last seed of the sweep")
    parser.add_argument("--runs", type=int, default=60, help="cases drawn per seed")
    parser.add_argument("--dry", action="store_true", help="the dry runs instead")
    parser.add_argument("--max-rpm", type=float, default=float("inf"))
    args = parser.parse_args(argv)
    first, last = (int(s) for s in args.seeds.split("-"))
    cases = []
    for seed in range(first, last + 1):
        rng = np.random.default_rng(seed)
        for _ in range(args.runs):
            case = draw(rng)
            if case["level"] == "full" and case["ehl"] != args.dry and case["rpm"] <= args.max_rpm:
                cases.append({**case, "seed": seed})
    rows = Parallel(n_jobs=2)(delayed(run)(case) for case in cases)
    for row in rows:
        print(json.dumps(row))
    print(dict(Counter(row["verdict"] for row in rows)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
