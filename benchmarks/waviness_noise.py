"""Race-waviness hints on Gaussian noise: how often the line tests pass where there is no line.

``cmtool diagnose`` reads race waviness from 24 candidate lines of the plain spectrum
(``cmtool.waviness``): a candidate passes at ``WAVINESS_SNR_DB`` (12 dB) over its local floor,
whatever the number of candidates and of bins searched. For white Gaussian noise records of a
6205 at 12 kHz, 1 s and 10 s, at 1797 and 1200 rpm, this prints the fraction of records in
which some candidate passes that test (the healthy model's test, which noise passes at the
lines a healthy bearing has not, left out), and the fraction that would also pass a
false-alarm test of BUDGET per record: each candidate's probability from the rule detector's
Rayleigh model (``features.separation.line_false_alarm`` with the bins ``features.line_snr``
searches and takes the floor from), times the number of candidates (stop 48: measured, not
shipped; docs/diagnosis.md, "Waviness hints on noise").

Run: .venv/bin/python benchmarks/waviness_noise.py [RECORDS [SEED [BUDGET]]]
     (defaults 4000, 4848, 2.5e-4)
"""

import sys

import numpy as np

import features
from cmtool.waviness import WAVINESS_SNR_DB, _line, candidate_lines
from generators import bearing
from generators.kinematics import characteristic_frequencies

FS = 12000.0


def rayleigh_false_alarm(f: np.ndarray, line: float, snr_db: float) -> float:
    """The rule's model of a line ``snr_db`` over its floor, with cmtool.waviness's bins."""
    df = float(f[1] - f[0])
    half_width = max(1.5 * df, 0.003 * line, df)
    reach = max(features.bands.FLOOR_WINDOW * line, 10.0 * df)
    near = np.abs(f - line)
    searched = int(np.count_nonzero(near <= half_width))
    floor = int(np.count_nonzero((near <= reach) & ~(near <= 3.0 * half_width)))
    return features.separation.line_false_alarm(snr_db, max(1, searched), max(3, floor))


def main(records: int, seed: int, budget: float) -> None:
    geometry = bearing("6205")
    rng = np.random.default_rng(seed)
    for seconds in (1.0, 10.0):
        for rpm in (1797.0, 1200.0):
            freqs = characteristic_frequencies(geometry, rpm / 60.0)
            alone = both = 0
            for _ in range(records):
                f, a = features.amplitude_spectrum(rng.standard_normal(int(FS * seconds)), FS)
                lines = [c.frequency for c in candidate_lines(freqs, geometry.ball_count)]
                lines = [line for line in lines if 0 < line < f[-1]]
                snrs = [(line, _line(f, a, line)[0]) for line in lines]
                passing = [(line, snr) for line, snr in snrs if snr >= WAVINESS_SNR_DB]
                alone += bool(passing)
                both += any(
                    rayleigh_false_alarm(f, line, snr) * len(lines) <= budget
                    for line, snr in passing
                )
            print(
                f"{seconds:g} s, {rpm:g} rpm, {records} noise records: a candidate passes "
                f"{WAVINESS_SNR_DB:g} dB in {alone / records:.4f}; with the false-alarm test "
                f"at {budget:g} per record too in {both / records:.4f}"
            )


if __name__ == "__main__":
    args = sys.argv[1:]
    main(
        int(args[0]) if args else 4000,
        int(args[1]) if len(args) > 1 else 4848,
        float(args[2]) if len(args) > 2 else 2.5e-4,
    )
