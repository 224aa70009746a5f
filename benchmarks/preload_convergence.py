"""Why a preloaded healthy bearing's band does not converge at practical RK4 steps (stop 36).

A 6205 at 1797 rpm and 300 N, `shaft+housing`, 12 kHz, recorded at 4 fs: the housing
acceleration's RMS and its octave-band difference (``generators.accuracy.band_error``) from a
run at a sixteenth of the record interval, at record_dt x 2^k (k = 1, 0, -1, -2), with -8 um
of clearance (every ball loaded) and +5 um, dry and with the film. With every ball loaded the
ball set's stiffness hardly changes with the cage angle, the vibration is ten orders under the
static force balance, and RK4's error at practical steps exceeds it (docs/performance.md,
the recipes' error bound).

Run: .venv/bin/python benchmarks/preload_convergence.py
"""

import numpy as np

from generators import OperatingCondition, Scene, SimulationSettings, bearing, simulate
from generators.accuracy import band_error

FS = 12000.0
RECORD_DT = 1.0 / (FS * 4)
CHANNEL = "housing_acceleration_y"


def main() -> None:
    op = OperatingCondition.from_rpm(1797, 300.0)
    print("clearance [um] | film | RMS [m/s^2] | band difference at 42, 21, 10, 5.2 us")
    for clearance in (-8e-6, 5e-6):
        for ehl in (False, True):
            geometry = bearing("6205", radial_internal_clearance=clearance)
            scene = Scene(level="shaft+housing", ehl=ehl)

            def run(step, geometry=geometry, scene=scene):
                settings = SimulationSettings(
                    fs=FS, duration=0.5, channels=(CHANNEL,), step=step, oversample=4
                )
                return simulate(geometry, op, scene=scene, settings=settings)[CHANNEL]

            reference = run(RECORD_DT / 16)
            errors = [band_error(reference, run(RECORD_DT * 2.0**k), FS) for k in (1, 0, -1, -2)]
            print(
                f"{clearance * 1e6:+.0f} | {'ehl' if ehl else 'dry'} | {np.std(reference):.2e} | "
                + ", ".join(f"{e:.2g}" for e in errors)
            )


if __name__ == "__main__":
    main()
