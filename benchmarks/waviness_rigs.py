"""Race waviness read without a baseline, through rigs other than the model's (issue 18).

docs/diagnosis.md, "Race waviness without a baseline": healthy bearings at 200, 500 and 2000
N and race waviness at 500 N (outer N_w = 9, 2 um and 18, 1 um; inner N_w = 10, 1 um and 8,
0.5 um), each through three rigs (the model's default, a 0.8 kg housing on 2e7 N/m, a 6 kg
housing on 2e8 N/m with a 2.5 kg shaft), at 1200, 1800 and 3000 rpm, 1 s at 25.6 kHz, white
noise of 10 % of the signal's RMS (``--noise``; 0: the noise-free records), diagnosed with
the load unknown (assumed 500 N). Prints per case what the diagnosis reads and the counts:
healthy cases without a hint, wavy cases with the right surface and order.

Run: .venv/bin/python benchmarks/waviness_rigs.py [--noise 0.1]
"""

import argparse
import itertools

import numpy as np

from cmtool.diagnose import diagnose_signal
from generators import OperatingCondition, Rig, SimulationSettings, Waviness, bearing, simulate

CHANNEL = "housing_acceleration_y"
FS = 25600.0
RIGS = {
    "default": Rig(),
    "light": Rig(housing_mass=0.8, pedestal_stiffness=2e7),
    "heavy": Rig(housing_mass=6.0, pedestal_stiffness=2e8, shaft_mass=2.5),
}
WAVY = (
    Waviness(surface="outer", order=9, amplitude=2e-6),
    Waviness(surface="outer", order=18, amplitude=1e-6),
    Waviness(surface="inner", order=10, amplitude=1e-6),
    Waviness(surface="inner", order=8, amplitude=0.5e-6),
)


def _read(x: np.ndarray, rpm: float, geometry, rng: np.random.Generator, noise: float):
    x = x + rng.normal(0.0, noise * np.std(x), x.size)
    return diagnose_signal(x, FS, rpm, geometry)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--noise", type=float, default=0.1, help="noise RMS over the signal's")
    noise = parser.parse_args(argv).noise
    geometry = bearing("6205")
    settings = SimulationSettings(fs=FS, duration=1.0, channels=(CHANNEL,))
    rng = np.random.default_rng(39)
    healthy_right = healthy_total = wavy_right = wavy_total = 0
    for (rig_name, rig), rpm in itertools.product(RIGS.items(), (1200.0, 1800.0, 3000.0)):
        for load in (200.0, 500.0, 2000.0):
            op = OperatingCondition.from_rpm(rpm, load)
            x = simulate(geometry, op, rig=rig, settings=settings)[CHANNEL]
            d = _read(x, rpm, geometry, rng, noise)
            healthy_total += 1
            healthy_right += d.waviness is None
            print(f"healthy {rig_name} {rpm:g} rpm {load:g} N: {d.verdict}, hint {d.waviness}")
        op = OperatingCondition.from_rpm(rpm, 500.0)
        for wav in WAVY:
            x = simulate(geometry, op, wav, rig=rig, settings=settings)[CHANNEL]
            d = _read(x, rpm, geometry, rng, noise)
            hint = d.waviness or {}
            right = hint.get("surface") == wav.surface and hint.get("order") == wav.order
            wavy_total += 1
            wavy_right += right
            print(
                f"{wav.surface} N_w={wav.order} {rig_name} {rpm:g} rpm: {d.verdict}, hint "
                f"{hint.get('surface')} {hint.get('order')} ({'right' if right else 'not read'})"
            )
    print(f"healthy without a hint: {healthy_right} of {healthy_total}")
    print(f"waviness read with the right surface and order: {wavy_right} of {wavy_total}")


if __name__ == "__main__":
    main()
