"""Why a preloaded healthy bearing's band does not converge at practical RK4 steps (stops 36, 87).

A 6205 at 1797 rpm and 300 N, `shaft+housing`, 12 kHz, recorded at 4 fs: the housing
acceleration's RMS and its octave-band difference (``generators.accuracy.band_error``) from a
run at a sixteenth of the record interval, at record_dt x 2^k (k = 1, 0, -1, -2), with -8 um
of clearance (every ball loaded) and +5 um, dry and with the film. With every ball loaded the
ball set's stiffness hardly changes with the cage angle, the vibration is ten orders under the
static force balance, and the band's content does not shrink with the step.

``--rounding`` (stop 87) says what that content is: for each step, the RMS above 500 Hz and
its three strongest lines, as frequencies and as fractions of the step rate 1 / h. Truncation
error would lie on the bearing's own lines (ball-pass harmonics) and fall as h^4; what a
preloaded run holds there keeps its level at every step and moves to simple fractions of the
step rate: the rounding of the state and the contact laws, whose displacements carry the
static deflection (micrometres) to float64's 1e-16 of it.

``--map`` (stop 87) prints, over the rig recipes' loads and negative clearances, the healthy
bearing's housing RMS at the default step (6205, 1797 rpm, `shaft+housing` with the film,
12 kHz, 0.5 s) and how much of it, through a two-mode path like the recipes' (1.5 and 3 kHz),
changes between the default step and 5 us: where every ball stays loaded the record at the
sensor is mostly rounding (docs/performance.md, "Speed", stop 87).

``--recipe RECIPE [--seed S] [--fraction F]`` (stop 87) generates a draw of a recipe (one
worker, in a temporary folder) and prints, for the cases where every ball stays loaded (the
boundary of ``--map``: clearance under -L / 50 um at L newtons) and for the others, how many
there are and the healthy part's RMS before and after the structural path (the chain's
``reference``, which every background level is drawn relative to).

Run: .venv/bin/python benchmarks/preload_convergence.py [--rounding] [--map]
    [--recipe datasets/cwru-rig.toml --seed 8701 --fraction 0.5]
"""

import argparse
import re
import sys
import tempfile
from pathlib import Path

import numpy as np
from recipe_step import with_fraction  # benchmarks/ on the path

from cmtool.datasets import generate_dataset
from generators import OperatingCondition, Scene, SimulationSettings, bearing, simulate, synthesis
from generators.accuracy import band_error
from generators.measurement import StructuralMode, transfer_path

FS = 12000.0
RECORD_DT = 1.0 / (FS * 4)
CHANNEL = "housing_acceleration_y"
#: A path like the rig recipes' (2-4 modes of 0.8-10 kHz, damping 0.01-0.08, gains -12-0 dB).
PATH = (
    StructuralMode(frequency=3000.0, damping=0.04, gain=1.0),
    StructuralMode(frequency=1500.0, damping=0.04, gain=0.5),
)


def record(clearance: float, load: float, ehl: bool, step: float | None, **kwargs) -> np.ndarray:
    """The healthy 6205's housing acceleration [m/s^2] at 1797 rpm, 12 kHz, `shaft+housing`."""
    geometry = bearing("6205", radial_internal_clearance=clearance)
    settings = SimulationSettings(
        fs=FS, duration=kwargs.pop("duration", 0.5), channels=(CHANNEL,), step=step, **kwargs
    )
    op = OperatingCondition.from_rpm(1797, load)
    return simulate(geometry, op, scene=Scene(level="shaft+housing", ehl=ehl), settings=settings)[
        CHANNEL
    ]


def convergence() -> None:
    """Stop 36's table: the octave-band differences from a run at a sixteenth of the step."""
    print("clearance [um] | film | RMS [m/s^2] | band difference at 42, 21, 10, 5.2 us")
    for clearance in (-8e-6, 5e-6):
        for ehl in (False, True):

            def run(step, clearance=clearance, ehl=ehl):
                return record(clearance, 300.0, ehl, step, oversample=4)

            reference = run(RECORD_DT / 16)
            errors = [band_error(reference, run(RECORD_DT * 2.0**k), FS) for k in (1, 0, -1, -2)]
            print(
                f"{clearance * 1e6:+.0f} | {'ehl' if ehl else 'dry'} | {np.std(reference):.2e} | "
                + ", ".join(f"{e:.2g}" for e in errors)
            )


def rounding() -> None:
    """The band above 500 Hz at four steps: its RMS and strongest lines (stop 87)."""
    print("clearance [um] | step [us] | RMS > 500 Hz [m/s^2] | strongest lines [Hz] (x step rate)")
    for clearance in (-8e-6, 5e-6):
        for step in (None, 1e-5, 5e-6, 1.25e-6):
            x = record(clearance, 300.0, False, step, duration=2.0)
            window = np.hanning(x.size)
            amplitude = np.abs(np.fft.rfft((x - x.mean()) * window)) * 2.0 / window.sum()
            f = np.fft.rfftfreq(x.size, 1.0 / FS)
            band = f > 500.0
            peaks = (
                np.flatnonzero(
                    band[1:-1]
                    & (amplitude[1:-1] >= amplitude[:-2])
                    & (amplitude[1:-1] > amplitude[2:])
                )
                + 1
            )
            strongest = peaks[np.argsort(amplitude[peaks])[::-1][:3]]
            h = step if step is not None else _default_step(clearance)
            lines = ", ".join(f"{f[i]:.1f} ({f[i] * h:.5f})" for i in strongest)
            rms = np.sqrt(np.sum(amplitude[band] ** 2) / 2.0)
            print(f"{clearance * 1e6:+.0f} | {h * 1e6:.3g} | {rms:.2e} | {lines}")


def _default_step(clearance: float) -> float:
    """The step the scene takes by default [s] (the run's ``integrator_stats``)."""
    geometry = bearing("6205", radial_internal_clearance=clearance)
    settings = SimulationSettings(fs=FS, duration=0.05, channels=(CHANNEL,))
    op = OperatingCondition.from_rpm(1797, 300.0)
    result = simulate(
        geometry, op, scene=Scene(level="shaft+housing", ehl=False), settings=settings
    )
    return float(result.parameters["integrator_stats"]["step_s"])


def preload_map() -> None:
    """Over the rig recipes' loads and negative clearances: RMS, and the share that is rounding."""
    clearances = (-10, -8, -6, -4, -2, -1)
    print(
        "load [N] | per clearance [um] "
        + ", ".join(str(c) for c in clearances)
        + ": housing RMS [m/s^2] / at the sensor, change from the default step to 5 us"
    )
    for load in (50.0, 100.0, 200.0, 350.0, 500.0):
        cells = []
        for clearance in clearances:
            default, fine = (record(clearance * 1e-6, load, True, step) for step in (None, 5e-6))
            at_default, at_fine = (transfer_path(x, FS, PATH) for x in (default, fine))
            change = np.std(at_default - at_fine) / max(np.std(at_fine), 1e-300)
            cells.append(f"{np.std(default):.0e} / {change:.0e}")
        print(f"{load:.0f} | " + " | ".join(cells))


def all_loaded(clearance_m: float, load_n: float) -> bool:
    """Whether every ball stays loaded, by ``--map``'s boundary (a 6205 at 1797 rpm)."""
    return clearance_m * 1e6 < -load_n / 50.0


def recipe_references(recipe: Path, seed: int | None, fraction: float) -> None:
    """A recipe draw's healthy parts before and after the path, every ball loaded or not."""
    rows = []
    through = synthesis.transfer_path

    def recorded(x, fs, modes):  # the chain's call: the healthy record is the last row
        out = through(x, fs, modes)
        caller = sys._getframe(1)
        if caller.f_code.co_name == "_finish_realistic":
            case = caller.f_locals["job"].case
            before, after = np.atleast_2d(x)[-1], np.atleast_2d(out)[-1]
            rows.append(
                (
                    case.index,
                    all_loaded(case.clearance_m or 0.0, case.radial_load_n),
                    float(np.sqrt(np.mean(before**2))),
                    float(np.sqrt(np.mean(after**2))),
                )
            )
        return out

    text = recipe.read_text()
    if seed is not None:
        text = re.sub(r"(?m)^seed = \d+", f"seed = {seed}", text)
    text = with_fraction(text, fraction)
    synthesis.transfer_path = recorded
    try:
        with tempfile.TemporaryDirectory() as folder:
            path = Path(folder) / recipe.name
            path.write_text(text)
            generate_dataset(path, Path(folder) / "out", workers=1)
    finally:
        synthesis.transfer_path = through
    cases = {row[0]: row[1:] for row in rows}
    print(
        f"{recipe} (seed {'as given' if seed is None else seed}, fraction {fraction:g}): "
        f"{len(cases)} cases"
    )
    print(
        "every ball loaded | cases | healthy RMS at the bearing ; at the sensor [m/s^2]: "
        "min, median, max"
    )
    for loaded in (True, False):
        values = np.array([v[1:] for v in cases.values() if v[0] == loaded])
        if values.size == 0:
            print(f"{loaded} | 0 |")
            continue
        spans = [
            f"{np.min(column):.1e}, {np.median(column):.1e}, {np.max(column):.1e}"
            for column in values.T
        ]
        print(f"{loaded} | {len(values)} | " + " ; ".join(spans))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounding", action="store_true", help="the band's content per step")
    parser.add_argument("--map", action="store_true", help="over the rig recipes' loads")
    parser.add_argument("--recipe", type=Path, help="a recipe whose draw to look at")
    parser.add_argument("--seed", type=int, help="the recipe's seed instead of its own")
    parser.add_argument("--fraction", type=float, default=0.5, help="of each condition's count")
    args = parser.parse_args()
    if args.recipe is not None:
        recipe_references(args.recipe, args.seed, args.fraction)
    if not (args.rounding or args.map or args.recipe is not None):
        convergence()
    if args.rounding:
        rounding()
    if args.map:
        preload_map()


if __name__ == "__main__":
    main()
