"""Which local-defect runs of the `full` scene diverge at RK4's default step (stop 87).

The default step is RK4's stability limit at the static start (generators.steps). A pit can
knock a ball into firmer contact than that start has, whose faster radial mode the step no
longer resolves. Runs 720 short simulations: 6205 and 6002, 600-12,000 rpm, 0-200 N, pits of
0.3 and 1 mm by 20 and 50 um on the outer race, the inner race and a ball (on its rolling
circle), dry and with the film, 12 kHz, 0.05 s, `full` scene. It prints how many diverged and
how many were integrated again at a shorter step (``generators.StepShortenedWarning``), with
the cases of the latter.

Run: .venv/bin/python benchmarks/default_step_divergence.py   (about a minute)
"""

import itertools
import warnings

from generators import (
    LocalizedDefect,
    OperatingCondition,
    Scene,
    SimulationDivergedError,
    SimulationSettings,
    StepShortenedWarning,
    bearing,
    simulate,
)

GRID = itertools.product(
    ["6205", "6002"],
    [600, 1800, 3600, 6000, 12000],
    [0.0, 10.0, 50.0, 200.0],
    [(0.3e-3, 20e-6), (1e-3, 20e-6), (1e-3, 50e-6)],
    [False, True],
    ["ball", "outer", "inner"],
)


def main() -> None:
    settings = SimulationSettings(
        fs=12000.0, duration=0.05, settle_time=0.01, channels=("housing_acceleration_y",)
    )
    runs, diverged, shortened = 0, [], []
    for name, rpm, load, (length, depth), ehl, surface in GRID:
        case = (name, rpm, load, length, depth, "film" if ehl else "dry", surface)
        pit = LocalizedDefect(surface=surface, length=length, depth=depth)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                simulate(
                    bearing(name),
                    OperatingCondition.from_rpm(rpm, load),
                    pit,
                    scene=Scene(level="full", ehl=ehl),
                    settings=settings,
                    random_state=1,
                )
            except SimulationDivergedError:
                diverged.append(case)
        if any(issubclass(w.category, StepShortenedWarning) for w in caught):
            shortened.append(case)
        runs += 1
    print(f"{runs} runs: {len(diverged)} diverged, {len(shortened)} integrated again shorter")
    print("bearing, rpm, load [N], pit length and depth [m], film, surface:")
    for case in shortened:
        print("  shorter:", case)
    for case in diverged:
        print("  diverged:", case)


if __name__ == "__main__":
    main()
