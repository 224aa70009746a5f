"""The rule detector on simulated race and ball waviness: is waviness called a local fault?

Issue 18: waviness is no local fault; its lines are deterministic (the rolling elements meet
the same lobes every turn), a pit's impacts are not (random slip). This runs waviness of a
given surface and order, 1 um, through three rigs (the model's default, a light and a heavy
housing), at 900, 1500, 2400 and 3600 rpm, 500 N, 12 and 25.6 kHz, with white noise of 5 %
of the signal's RMS, and counts the verdicts. No threshold is chosen on it: it measures.

``--entrainment F`` runs every case with ``Rig.film_entrainment_factor`` F (docs/model.md 4.6;
stop 73).

Run: .venv/bin/python benchmarks/sweep_waviness_verdicts.py [--surface inner --order 9]
[--entrainment 1]
"""

import argparse
import dataclasses
import itertools
import time
from collections import Counter

import numpy as np

from cmtool.diagnose import diagnose_signal
from generators import OperatingCondition, Rig, SimulationSettings, Waviness, bearing, simulate

CHANNEL = "housing_acceleration_y"
RIGS = {
    "default": Rig(),
    "light": Rig(housing_mass=0.8, pedestal_stiffness=2e7),
    "heavy": Rig(housing_mass=6.0, pedestal_stiffness=2e8, shaft_mass=2.5),
}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--surface", default="inner", choices=("inner", "outer", "ball"))
    parser.add_argument("--order", type=int, default=9)
    parser.add_argument("--amplitude", type=float, default=1e-6, help="[m]")
    parser.add_argument("--bearing", default="6205")
    parser.add_argument("--entrainment", type=float, default=0.0, help="film entrainment [-]")
    args = parser.parse_args()
    g = bearing(args.bearing)
    noise = np.random.default_rng(18)
    verdicts = Counter()
    seconds = 0.0
    for (rig_name, rig), rpm, fs in itertools.product(
        RIGS.items(), (900, 1500, 2400, 3600), (12000.0, 25600.0)
    ):
        settings = SimulationSettings(fs=fs, duration=1.0, channels=(CHANNEL,))
        op = OperatingCondition.from_rpm(rpm, 500.0)
        wav = Waviness(surface=args.surface, order=args.order, amplitude=args.amplitude)
        rig = dataclasses.replace(rig, film_entrainment_factor=args.entrainment)
        x = simulate(g, op, wav, rig=rig, settings=settings, random_state=3)[CHANNEL]
        x = x + noise.normal(0.0, 0.05 * np.std(x), x.size)
        start = time.perf_counter()
        d = diagnose_signal(x, fs, rpm, g)
        seconds += time.perf_counter() - start
        verdicts[d.verdict] += 1
        if d.verdict != "healthy":
            print(f"  {rig_name} {rpm} rpm {fs:.0f} Hz: {d.verdict} ({d.confidence:.2f})")
    total = sum(verdicts.values())
    print(
        f"{args.surface} waviness order {args.order}, {args.amplitude * 1e6:g} um: "
        f"{verdicts['healthy']}/{total} healthy {dict(verdicts)}; "
        f"diagnosis {seconds / total:.2f} s per record"
    )


if __name__ == "__main__":
    main()
