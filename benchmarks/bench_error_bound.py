"""The error-bound step (issue 22) across bearings, speeds, loads, scenes and defects.

For each case: the step chosen for a 1 % bound on the characteristic line amplitudes and the
spectrum in octave bands above 500 Hz, its estimated error, the true error (the larger of the
two) against the same run at a step 16 times shorter than the chosen one (and at most 2.5 us),
the default step's true error, and the wall time of the bounded run (first call, pilots
included; second call, cached) against the default run.

Run: .venv/bin/python benchmarks/bench_error_bound.py [bound]
"""

from __future__ import annotations

import sys
import time

from generators import (
    LocalizedDefect,
    OperatingCondition,
    Scene,
    SimulationSettings,
    Waviness,
    bearing,
    simulate,
)
from generators.accuracy import _lines, band_error, line_error
from generators.prepared import prepare

FS = 25600.0
CASES = [
    # bearing, rpm, load [N], scene, defect
    ("6203", 600, 200.0, Scene(), Waviness(surface="inner", order=8, amplitude=0.5e-6)),
    ("6205", 1797, 900.0, Scene(), Waviness(surface="outer", order=18, amplitude=1e-6)),
    ("6308", 3600, 3000.0, Scene(), Waviness(surface="outer", order=8, amplitude=2e-6)),
    ("6002", 6000, 100.0, Scene(), Waviness(surface="ball", order=2, amplitude=0.3e-6)),
    ("6205", 1200, 500.0, Scene(level="shaft", ehl=False), None),
    (
        "6305",
        2400,
        1500.0,
        Scene(level="shaft", ehl=False),
        Waviness(surface="inner", order=6, amplitude=1e-6),
    ),
    ("6205", 1797, 500.0, Scene(), LocalizedDefect(surface="inner", length=0.53e-3, depth=0.28e-3)),
    ("6203", 3000, 300.0, Scene(), LocalizedDefect(surface="outer", length=2e-3, depth=30e-6)),
    ("6205", 900, 1000.0, Scene(level="full"), Waviness(surface="outer", order=9, amplitude=1e-6)),
]


def _run(name, rpm, load, scene, defect, **settings):
    s = SimulationSettings(fs=FS, duration=0.5, channels=("housing_acceleration_y",), **settings)
    start = time.perf_counter()
    op = OperatingCondition.from_rpm(rpm, load)
    # seeded: ball-waviness phases are drawn per call otherwise (another bearing each time)
    r = simulate(bearing(name), op, defect, scene=scene, settings=s, random_state=7)
    return r, time.perf_counter() - start


def main(bound: float = 0.01) -> None:
    print(f"bound {bound:g}; 0.5 s at {FS:g} Hz after 0.1 s settling")
    header = (
        "case | step [s] | default step [s] | estimated | true | default's true | "
        "bounded run first/cached [s] | default run [s]"
    )
    print(header)
    held = 0
    for name, rpm, load, scene, defect in CASES:
        op = OperatingCondition.from_rpm(rpm, load)
        lines = _lines(prepare(bearing(name), op, defect, scene=scene, random_state=7))
        bounded, first = _run(name, rpm, load, scene, defect, error_bound=bound)
        _, cached = _run(name, rpm, load, scene, defect, error_bound=bound)
        default, t_default = _run(name, rpm, load, scene, defect)
        stats = bounded.parameters["integrator_stats"]
        fine = min(stats["step_s"], default.parameters["integrator_stats"]["step_s"]) / 16
        reference, _ = _run(name, rpm, load, scene, defect, step=min(fine, 2.5e-6))
        y = reference["housing_acceleration_y"]
        x, x_default = bounded["housing_acceleration_y"], default["housing_acceleration_y"]
        true = max(line_error(y, x, FS, lines), band_error(y, x, FS))
        true_default = max(line_error(y, x_default, FS, lines), band_error(y, x_default, FS))
        held += true <= bound
        kind = "healthy" if defect is None else f"{type(defect).__name__} {defect.surface}"
        print(
            f"{name} {rpm} rpm {load:g} N {scene.level}/{'ehl' if scene.ehl else 'dry'} {kind} | "
            f"{stats['step_s']:.3g} | {default.parameters['integrator_stats']['step_s']:.3g} | "
            f"{stats['line_error_estimate']:.2g} | {true:.2g} | {true_default:.2g} | "
            f"{first:.2f}/{cached:.2f} | {t_default:.2f}"
        )
    print(f"bound held in {held} of {len(CASES)} cases")


if __name__ == "__main__":
    main(float(sys.argv[1]) if len(sys.argv) > 1 else 0.01)
