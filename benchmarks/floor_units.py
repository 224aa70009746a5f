"""The rule's margin in three units of the same record (stop 74; docs/diagnosis.md, "Verdicts
the instrument floor decides").

The separation adds a white floor 50 dB under the record's RMS before it looks for lines
(``features.instrument_floor.INSTRUMENT_FLOOR_DB``). Until stop 76 it was drawn from a generator
seeded by the record's first 64 samples, so the same record in m/s^2, in g and in mm/s^2 got
three draws and margins up to 5 dB apart; since then it is one draw per record length, scaled
to the record, and only where the record has no floor of its own. For five
simulated 6205 records (5 um clearance, 12 kHz, 1 s: perfect, ball form errors, a 9-lobe inner
and outer race, noise-free and with white noise at 5 % of the RMS) this prints the rule's
verdict and margin over its threshold [dB] in each unit.

Run: .venv/bin/python benchmarks/floor_units.py
"""

import numpy as np

from cmtool.diagnose import diagnose_signal
from generators import (
    OperatingCondition,
    SimulationSettings,
    Waviness,
    bearing,
    form_waviness,
    simulate,
)

CHANNEL = "housing_acceleration_y"
UNITS = {"m/s^2": 1.0, "g": 1.0 / 9.80665, "mm/s^2": 1000.0}


def main() -> None:
    g = bearing("6205", radial_internal_clearance=5e-6)
    settings = SimulationSettings(fs=12000.0, duration=1.0, channels=(CHANNEL,))
    cases = [
        ("perfect", 1797, 100.0, None),
        ("ball form 0.1 um", 1797, 400.0, form_waviness(9, 0.0, 0.0, 1e-7)),
        ("inner N_w = 9, 1 um", 1200, 300.0, Waviness(surface="inner", order=9, amplitude=1e-6)),
        ("perfect", 2400, 800.0, None),
        ("outer N_w = 9, 1 um", 1500, 500.0, Waviness(surface="outer", order=9, amplitude=1e-6)),
    ]
    spread = []
    for name, rpm, load, defects in cases:
        op = OperatingCondition.from_rpm(rpm, load)
        x = simulate(g, op, defects, settings=settings, random_state=2)[CHANNEL]
        for noise in (0.0, 0.05):
            y = x + np.random.default_rng(1).normal(0.0, noise * np.std(x), x.size)
            reads = []
            for scale in UNITS.values():
                d = diagnose_signal(scale * y, 12000.0, rpm, g, waviness=False)
                margin = max(c["evidence_db"] - d.threshold_db for c in d.candidates)
                reads.append((d.verdict, margin))
            margins = [m for _, m in reads]
            spread.append(max(margins) - min(margins))
            shown = " | ".join(f"{u}: {v} {m:+.2f}" for u, (v, m) in zip(UNITS, reads, strict=True))
            print(f"{name:20s} {rpm} rpm {load:4.0f} N noise {noise:.2f}: {shown}")
    print(f"largest spread of the margin between units: {max(spread):.1e} dB")


if __name__ == "__main__":
    main()
