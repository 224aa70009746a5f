"""The contacts' onset at the load zone's edges: the rule on the cases it misreads, with and
without the film's entrainment at light load (stop 73; docs/model.md 4.6, docs/diagnosis.md
"Form errors read as a local fault").

Without entrainment a lubricated contact's force starts with a kink where the rigid approach
reaches the film; form errors and waviness make the balls' entries jitter, and the kinks'
broadband ringing then reads as a local fault. For each ``Rig.film_entrainment_factor`` given
(default 0 and 1) this runs the cases of the two strict xfails of
``tests/tests_cmtool/test_diagnosis.py`` and prints the rule's verdict and its margin over the
threshold [dB]:

- a 6205 with 5 um of clearance, 1797 rpm, 100 and 400 N, 12 kHz, 1 s: perfect, with 0.1 um
  of inner-race form error (order Z) and with 0.1 um on the balls (order 2), each noise-free
  and with white noise at 5 % of its RMS;
- a 9-lobe inner race (1 um, 500 N, 5 % noise) at 900 rpm, 25.6 kHz and 1500 rpm, 12 kHz.

Run: .venv/bin/python benchmarks/entry_kink.py [FACTOR ...]
"""

import sys
import time

import numpy as np

from cmtool.diagnose import diagnose_signal
from generators import (
    OperatingCondition,
    Rig,
    SimulationSettings,
    Waviness,
    bearing,
    form_waviness,
    simulate,
)

CHANNEL = "housing_acceleration_y"


def _margin(d) -> float:
    return max(c["evidence_db"] - d.threshold_db for c in d.candidates)


def run(factor: float) -> None:
    rig = Rig(film_entrainment_factor=factor)
    start = time.perf_counter()
    g = bearing("6205", radial_internal_clearance=5e-6)
    settings = SimulationSettings(fs=12000.0, duration=1.0, channels=(CHANNEL,))
    forms = {
        "perfect": None,
        "inner form": form_waviness(9, 1e-7, 0.0, 0.0),
        "ball form": form_waviness(9, 0.0, 0.0, 1e-7),
    }
    for load in (100.0, 400.0):
        op = OperatingCondition.from_rpm(1797, load)
        for name, form in forms.items():
            x = simulate(g, op, form, rig=rig, settings=settings, random_state=2)[CHANNEL]
            for noise in (0.0, 0.05):
                y = x + np.random.default_rng(1).normal(0.0, noise * np.std(x), x.size)
                d = diagnose_signal(y, 12000.0, 1797, g, waviness=False)
                print(
                    f"  {name:10s} {load:5.0f} N, noise {noise:.2f}: {d.verdict:10s} "
                    f"{_margin(d):+6.1f} dB (RMS {np.std(x):.2e} m/s^2)"
                )
    g = bearing("6205")
    noise = np.random.default_rng(18)
    for rpm, fs in ((900, 25600.0), (1500, 12000.0)):
        settings = SimulationSettings(fs=fs, duration=1.0, channels=(CHANNEL,))
        wav = Waviness(surface="inner", order=9, amplitude=1e-6)
        op = OperatingCondition.from_rpm(rpm, 500.0)
        x = simulate(g, op, wav, rig=rig, settings=settings, random_state=3)[CHANNEL]
        x = x + noise.normal(0.0, 0.05 * np.std(x), x.size)
        d = diagnose_signal(x, fs, rpm, g)
        print(f"  wavy inner race, {rpm} rpm: {d.verdict} {_margin(d):+.1f} dB")
    print(f"  ({time.perf_counter() - start:.0f} s)")


if __name__ == "__main__":
    for factor in [float(a) for a in sys.argv[1:]] or [0.0, 1.0]:
        print(f"film_entrainment_factor = {factor:g}")
        run(factor)
