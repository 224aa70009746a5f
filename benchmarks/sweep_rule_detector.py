"""The rule detector on clean simulations across the catalog: healthy bearings and pits.

Issue 18 asks that 95 % or more of simulated healthy bearings be called healthy while
simulated pits stay detected. The suite checks a fixed grid of 24 healthy runs
(``tests/tests_cmtool/test_diagnosis.py``); this draws more of the same grid and also runs
pits, so a change to the detector can be weighed on both sides.

- healthy: every catalog bearing x 600, 1200, 1797, 3000, 6000 rpm x 100, 500, 2000 N x 12,
  25.6, 48 kHz, noise-free, ``simulate``'s defaults; a random draw of ``--healthy`` cases;
- pits: 0.3 mm long, 0.1 mm deep, on the inner race, outer race or a ball, with 1 % random
  slip and 0.005 rad of ball jitter, 600-3000 rpm, 200 and 1000 N, the same rates, white
  noise at each ``--noise`` multiple of the signal's RMS; ``--pits`` cases.

``--entrainment F`` runs every case with ``Rig.film_entrainment_factor`` F (docs/model.md 4.6;
stop 73).

Run: .venv/bin/python benchmarks/sweep_rule_detector.py [--healthy 120] [--pits 90]
[--noise 0 3 4] [--entrainment 1]
"""

import argparse
import itertools
from collections import Counter

import numpy as np

from cmtool.diagnose import diagnose_signal
from generators import (
    LocalizedDefect,
    OperatingCondition,
    Rig,
    SimulationSettings,
    bearing,
    simulate,
)

BEARINGS = ("6205", "6203", "6305", "6002", "6308", "mfpt")
RATES = (12000.0, 25600.0, 48000.0)
CHANNEL = "housing_acceleration_y"
VERDICT = {"inner": "inner race", "outer": "outer race", "ball": "ball"}
ENTRAINMENT = [0.0]  # Rig.film_entrainment_factor of every run (--entrainment)


def _run(name, rpm, load, fs, defects=(), random_state=None, **operating):
    g = bearing(name)
    settings = SimulationSettings(fs=fs, duration=1.0, channels=(CHANNEL,))
    op = OperatingCondition.from_rpm(rpm, load, **operating)
    rig = Rig(film_entrainment_factor=ENTRAINMENT[0])
    x = simulate(g, op, *defects, rig=rig, settings=settings, random_state=random_state)
    return g, x[CHANNEL]


def healthy(count: int) -> None:
    grid = list(
        itertools.product(BEARINGS, (600, 1200, 1797, 3000, 6000), (100.0, 500.0, 2000.0), RATES)
    )
    np.random.default_rng(1).shuffle(grid)
    wrong = []
    for name, rpm, load, fs in grid[:count]:
        g, x = _run(name, rpm, load, fs)
        verdict = diagnose_signal(x, fs, rpm, g).verdict
        if verdict != "healthy":
            wrong.append((name, rpm, load, fs, verdict))
    done = min(count, len(grid))
    print(f"healthy: {done - len(wrong)}/{done} called healthy")
    for case in wrong:
        print("  not healthy:", case)


def pits(count: int, noise: list[float]) -> None:
    grid = list(
        itertools.product(BEARINGS, (600, 1200, 1797, 3000), (200.0, 1000.0), RATES, VERDICT)
    )
    np.random.default_rng(3).shuffle(grid)
    for level in noise:
        found, runs = Counter(), Counter()
        for i, (name, rpm, load, fs, surface) in enumerate(grid[:count]):
            pit = LocalizedDefect(surface=surface, length=0.3e-3, depth=0.1e-3)
            g, x = _run(
                name, rpm, load, fs, (pit,), random_state=i, random_slip=0.01, ball_jitter=0.005
            )
            if level > 0:
                x = x + np.random.default_rng(i).normal(0.0, level * np.std(x), x.size)
            runs[surface] += 1
            found[surface] += diagnose_signal(x, fs, rpm, g).verdict == VERDICT[surface]
        shown = ", ".join(f"{s} {found[s]}/{runs[s]}" for s in VERDICT)
        print(f"pits, noise {level:g} x RMS: {sum(found.values())}/{sum(runs.values())} ({shown})")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--healthy", type=int, default=120)
    parser.add_argument("--pits", type=int, default=90)
    parser.add_argument("--noise", type=float, nargs="+", default=[0.0, 3.0, 4.0])
    parser.add_argument("--entrainment", type=float, default=0.0, help="film entrainment [-]")
    args = parser.parse_args()
    ENTRAINMENT[0] = args.entrainment
    healthy(args.healthy)
    pits(args.pits, args.noise)
