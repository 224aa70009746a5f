"""How discrete is the "random part" that the rule detector demodulates? Pits against waviness.

A local fault's impacts jitter (random slip), so at the resonances where they ring their
spectrum should be continuous; a wavy or healthy bearing's vibration is deterministic, a
spectrum of lines. ``features.separate_discrete`` removes lines before envelope analysis. This
measures what is left in the band the detector chooses, by the discreteness index

    D = mean / median of the Hann-windowed power spectrum's bins in the band

(Gaussian noise: 1/ln 2 = 1.44; a spectrum of lines over a low floor: far more), for

- pits: 0.3 mm long, 0.1 mm deep, on each surface, 6205/6002/6308 at 600, 1797 and 3000 rpm,
  500 N, 1.2 % random slip, 0.005 rad pocket jitter, 25.6 kHz, with white noise of
  ``--noise`` x the RMS (0: the simulation's own 50 dB instrument floor only);
- inner-race waviness N_w = 9 (1 um) through the three rigs of
  benchmarks/sweep_waviness_verdicts.py (24 cases, 5 % noise);

with the slip model's cage components as the recipe has them or as given (``--components``,
``--band`` in multiples of the cage frequency, ``--spacing``: the module constants of
``generators.packing``). It prints D's median and maximum, how many exceed ``--gate``, the
verdicts, and what a gate "healthy when D > gate" would do. It measures; it chooses nothing.

Run: .venv/bin/python benchmarks/slip_discreteness.py [--noise 0 1] [--components 48
--band 0.02 4.5 --spacing linear]
"""

from __future__ import annotations

import argparse
import itertools
import sys
from pathlib import Path

import numpy as np

import generators.packing as packing
from cmtool.diagnose import diagnose_signal
from features.evidence import fault_evidence
from generators import (
    LocalizedDefect,
    OperatingCondition,
    SimulationSettings,
    Waviness,
    bearing,
    characteristic_frequencies,
    simulate,
)

sys.path.insert(0, str(Path(__file__).resolve().parent))
from sweep_waviness_verdicts import RIGS  # noqa: E402

CHANNEL = "housing_acceleration_y"
VERDICT = {"outer": "outer race", "inner": "inner race", "ball": "ball"}


def discreteness(x: np.ndarray, fs: float, band: tuple[float, float]) -> float:
    """Mean over median of the power spectrum's bins in ``band`` [Hz] (noise: 1.44)."""
    power = np.abs(np.fft.rfft(x * np.hanning(x.size))) ** 2
    freqs = np.fft.rfftfreq(x.size, 1.0 / fs)
    sel = (freqs >= max(band[0], 5.0)) & (freqs <= band[1])
    return float(power[sel].mean() / np.median(power[sel]))


def judge(g, x: np.ndarray, fs: float, rpm: float) -> tuple[float, str]:
    f = characteristic_frequencies(g, rpm / 60.0)
    ctx = {"bpfo": f.bpfo, "bpfi": f.bpfi, "two_bsf": f.two_bsf, "shaft": f.shaft, "ftf": f.ftf}
    evidence = fault_evidence(x, fs, ctx)
    d = discreteness(evidence.random_part, fs, evidence.selection.band)
    return d, diagnose_signal(x, fs, rpm, g).verdict


def report(name: str, rows: list[tuple[float, str, str]], gate: float) -> None:
    d = np.array([r[0] for r in rows])
    right = sum(v == t for _, v, t in rows)
    gated = sum(("healthy" if di > gate else v) == t for di, v, t in rows)
    print(
        f"{name}: D median {np.median(d):.2f}, max {d.max():.1f}, {int((d > gate).sum())}/"
        f"{len(rows)} over {gate:g}; right {right}/{len(rows)}, with the gate {gated}/{len(rows)}"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--noise", type=float, nargs="+", default=[0.0, 1.0])
    parser.add_argument("--components", type=int, default=packing.SLIP_COMPONENTS)
    parser.add_argument("--band", type=float, nargs=2, default=packing.SLIP_BAND)
    parser.add_argument("--spacing", choices=("log", "linear"), default=packing.SLIP_SPACING)
    parser.add_argument("--gate", type=float, default=4.0)
    args = parser.parse_args()
    packing.SLIP_COMPONENTS = args.components
    packing.SLIP_BAND = tuple(args.band)
    packing.SLIP_SPACING = args.spacing
    print(f"slip: {args.components} cage components, {args.spacing} over {args.band} x f_c")
    fs = 25600.0
    settings = SimulationSettings(fs=fs, duration=1.0, channels=(CHANNEL,))
    grid = list(itertools.product(("6205", "6002", "6308"), (600, 1797, 3000), VERDICT))
    pits = []
    for i, (name, rpm, surface) in enumerate(grid):
        g = bearing(name)
        op = OperatingCondition.from_rpm(rpm, 500.0, random_slip=0.012, ball_jitter=0.005)
        pit = LocalizedDefect(surface=surface, length=0.3e-3, depth=0.1e-3)
        pits.append((g, rpm, surface, simulate(g, op, pit, settings=settings, random_state=i)))
    for level in args.noise:
        rows = []
        for i, (g, rpm, surface, result) in enumerate(pits):
            x = result[CHANNEL]
            if level > 0:
                x = x + np.random.default_rng(i).normal(0.0, level * np.std(x), x.size)
            rows.append((*judge(g, x, fs, rpm), VERDICT[surface]))
        report(f"pits, noise {level:g} x RMS", rows, args.gate)
    g = bearing("6205")
    noise = np.random.default_rng(18)
    rows = []
    for (_, rig), rpm, rate in itertools.product(
        RIGS.items(), (900, 1500, 2400, 3600), (12000.0, 25600.0)
    ):
        st = SimulationSettings(fs=rate, duration=1.0, channels=(CHANNEL,))
        wavy = Waviness(surface="inner", order=9, amplitude=1e-6)
        op = OperatingCondition.from_rpm(rpm, 500.0)
        x = simulate(g, op, wavy, rig=rig, settings=st, random_state=3)[CHANNEL]
        x = x + noise.normal(0.0, 0.05 * np.std(x), x.size)
        rows.append((*judge(g, x, rate, rpm), "healthy"))
    report("inner-race waviness N_w = 9, noise 5 %", rows, args.gate)


if __name__ == "__main__":
    main()
