"""The chain's path as a transmissibility instead of band-passes: does a pit's rate show? (stop 48)

The recipes carry the model's housing acceleration to the sensor through
``generators.measurement.transfer_path``: a sum of second-order band-passes of unit peak gain,
which pass nothing at 0 Hz and, at a 6205's BPFI (162 Hz), 2 zeta f / f_n of a mode at f_n
(-30 to -70 dB for modes at 0.8-10 kHz with 1-8 % damping). Between two points of one
structure the path is a transmissibility: unity below the first flexible mode (the sensor
moves with the housing), resonant at each mode, falling above. This generates a recipe with
each mode's band-pass replaced by (2 zeta w s + w^2) / (s^2 + 2 zeta w s + w^2), weighted by
its gain over the gains' sum (unity at 0 Hz), the machine's background forces still through
the band-passes, and prints ``benchmarks/plain_lines.py``'s medians for it: if the missing
plain-spectrum lines at a pit's own rate (docs/realism.md 7) were the path's doing, the
inner-race pits' ``spectrum_bpfi_h1_snr`` would rise from its 0.5 dB. An exploration: the
recipes keep the band-passes.

Run: .venv/bin/python benchmarks/chain_transmissibility.py datasets/cwru-rig.toml OUT
then compare with .venv/bin/python benchmarks/plain_lines.py on the recipe as shipped.
"""

import sys
from pathlib import Path

import numpy as np

import generators.synthesis
from cmtool.datasets import generate_dataset
from generators import measurement

sys.path.insert(0, str(Path(__file__).resolve().parent))
import plain_lines  # noqa: E402


def transmissibility_path(x: np.ndarray, fs: float, modes) -> np.ndarray:
    """Unity at 0 Hz, resonant at each mode (weights gain / sum of gains)."""
    x = np.asarray(x, dtype=float)
    kept = [m for m in modes if m.frequency < 0.45 * fs]
    if not kept:
        return x.copy()
    sections = []
    for mode in kept:
        w = measurement._prewarped(mode.frequency, fs)
        coefficients = (2.0 * mode.damping * w, w * w)  # numerator and denominator alike
        sections.append(measurement._bilinear_biquad(coefficients, coefficients, fs))
    gains = np.array([mode.gain for mode in kept])
    return measurement._causal(np.stack(sections), x, fs, gains / gains.sum())


def main(recipe: str, out: str) -> None:
    # the bearing's signal only: machine_background keeps measurement.transfer_path
    generators.synthesis.transfer_path = transmissibility_path
    generate_dataset(Path(recipe), Path(out), workers=2)
    plain_lines.main([out])


if __name__ == "__main__":
    main(*sys.argv[1:3])
