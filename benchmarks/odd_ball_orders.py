"""How much ball waviness of each order changes the housing's vibration, with and without
ball masses (docs/model.md 2.1, generators.content).

1 um of ball waviness of orders 1-9 on a 6205 at 1800 rpm, 500 N, 0.5 s at 12 kHz (each
ball's phase drawn, seed 0; other draws move the figures by tens of per cent): the RMS
of the difference from the healthy record over the healthy record's RMS, in the ``shaft``
scene (no ball masses: odd orders exactly 0) and in ``full`` (the balls' inertia).
Run: ``.venv/bin/python benchmarks/odd_ball_orders.py``.
"""

import numpy as np

from generators import OperatingCondition, Scene, SimulationSettings, Waviness, bearing, simulate


def main() -> None:
    g, op = bearing("6205"), OperatingCondition.from_rpm(1800, 500)
    settings = SimulationSettings(fs=12000, duration=0.5, channels=("housing_acceleration_y",))
    print("order  " + "  ".join(f"{k:>7d}" for k in range(1, 10)))
    for level in ("shaft", "full"):
        scene = Scene(level=level)
        healthy = simulate(g, op, None, settings=settings, scene=scene, random_state=0)[
            "housing_acceleration_y"
        ]
        changes = []
        for order in range(1, 10):
            wavy = simulate(
                g,
                op,
                [Waviness(surface="ball", order=order, amplitude=1e-6)],
                settings=settings,
                scene=scene,
                random_state=0,
            )["housing_acceleration_y"]
            changes.append(100.0 * np.std(wavy - healthy) / np.std(healthy))
        print(f"{level:<6s} " + "  ".join(f"{c:6.2f}%" for c in changes))


if __name__ == "__main__":
    main()
