"""Envelope lines at BPFI - BPFO and 2 BPFO - BPFI: do they tell a wavy inner race from a pit?

Issue 18's open case (docs/diagnosis.md, "Waviness read as a local fault"): an inner race of Z
lobes puts lines on the lattice k BPFI + n BPFO, and where a 1 s record cannot resolve its
slices their leftovers beat at n BPFO in the envelope, which the rule reads as an outer-race
fault. The same leftovers also beat at the lattice's other low differences, BPFI - BPFO and
2 BPFO - BPFI, which no single local fault's line family holds: a candidate test (stop 83).
For each case this prints the rule's verdict and margin over its threshold, the envelope's
line-to-floor ratio at the two differences (searched for a ball-pass rate from 0.5 % above to
2 % below its kinematic one, in the rule's band), their false-alarm probability (the lesser
line's, times two), ``BEAT`` where it is under the rule's 1e-4, and the lattice slices held.

Modes (each prints a line per case and a count):
- ``wavy SURFACE ORDER``: 1 um of waviness through the three rigs of
  ``benchmarks/sweep_waviness_verdicts.py`` at 900-3600 rpm, 12 and 25.6 kHz, 5 % noise;
- ``pits COUNT``: ``benchmarks/sweep_rule_detector.py``'s pits (0.3 mm, 1 % slip), noise-free
  and in noise 3 x the RMS;
- ``healthy COUNT``: its clean healthy runs.

Run: .venv/bin/python benchmarks/lattice_beats.py wavy inner 9 (about 1 minute; pits 90:
about 6 minutes)
"""

import itertools
import sys
from collections import Counter

import numpy as np
from sweep_waviness_verdicts import CHANNEL, RIGS  # the sweep's cases (benchmarks/ on the path)

import features
from cmtool.diagnose import diagnose_signal
from features.evidence import slip_line
from features.false_alarm import FALSE_ALARM, line_false_alarm
from generators import (
    LocalizedDefect,
    OperatingCondition,
    SimulationSettings,
    Waviness,
    bearing,
    characteristic_frequencies,
    simulate,
)

SLIP = (-0.005, 0.02)  # the ball-pass rate from 0.5 % above to 2 % below its kinematic one
BEARINGS = ("6205", "6203", "6305", "6002", "6308", "mfpt")
RATES = (12000.0, 25600.0, 48000.0)


def beat_lines(x: np.ndarray, fs: float, rpm: float, geometry):
    """The rule's evidence, and the envelope's lines at BPFI - BPFO and 2 BPFO - BPFI."""
    f = characteristic_frequencies(geometry, rpm / 60.0)
    ctx = {"bpfo": f.bpfo, "bpfi": f.bpfi, "two_bsf": f.two_bsf, "shaft": f.shaft, "ftf": f.ftf}
    evidence = features.fault_evidence(x, fs, ctx)
    ef, ea = evidence.envelope_frequencies, evidence.envelope_amplitude
    z_fs = f.bpfo + f.bpfi  # Z times the shaft rate
    lines = []
    for a, b in ((-2, 1), (3, -1)):  # a BPFO + b Z fs: BPFI - BPFO, 2 BPFO - BPFI
        ends = [a * f.bpfo * (1 - s) + b * z_fs for s in SLIP]
        centre = a * f.bpfo + b * z_fs
        low, high = min(ends), max(ends)
        if centre < 0:
            low, high, centre = -high, -low, -centre
        if low < 3 * (ef[1] - ef[0]):
            lines.append((0.0, 1.0, centre))  # too near 0 Hz for this record
            continue
        search = ((centre - low) / centre, (high - centre) / centre)
        ratio, found, searched, floor = slip_line(ef, ea, centre, search=search)
        lines.append((ratio, min(1.0, line_false_alarm(ratio, searched, floor)), found))
    return evidence, lines, min(1.0, 2.0 * min(p for _, p, _ in lines))


def report(tag: str, x: np.ndarray, fs: float, rpm: float, geometry, seen: Counter) -> None:
    evidence, lines, p = beat_lines(x, fs, rpm, geometry)
    verdict = diagnose_signal(x, fs, rpm, geometry, waviness=False).verdict
    margin = max(v["evidence_db"] for v in evidence.combined.values()) - evidence.threshold_db
    beat = p < FALSE_ALARM
    seen[(verdict != "healthy", beat)] += 1
    shown = " ".join(f"{r:5.1f} dB at {f:.1f} Hz" for r, _, f in lines)
    print(
        f"{tag:46s} {verdict:10s} {margin:+6.1f} dB; lines {shown}; p {p:.1e} "
        f"{'BEAT' if beat else '    '} held {list(evidence.lattice_orders)}",
        flush=True,
    )


def wavy(surface: str, order: int, seen: Counter) -> None:
    g = bearing("6205")
    noise = np.random.default_rng(18)
    for (name, rig), rpm, fs in itertools.product(
        RIGS.items(), (900, 1500, 2400, 3600), (12000.0, 25600.0)
    ):
        settings = SimulationSettings(fs=fs, duration=1.0, channels=(CHANNEL,))
        op = OperatingCondition.from_rpm(rpm, 500.0)
        wav = Waviness(surface=surface, order=order, amplitude=1e-6)
        x = simulate(g, op, wav, rig=rig, settings=settings, random_state=3)[CHANNEL]
        x = x + noise.normal(0.0, 0.05 * np.std(x), x.size)
        report(f"wavy {surface} {order} {name} {rpm} rpm {fs:.0f} Hz", x, fs, rpm, g, seen)


def pits(count: int, seen: Counter) -> None:
    grid = list(
        itertools.product(
            BEARINGS, (600, 1200, 1797, 3000), (200.0, 1000.0), RATES, ("inner", "outer", "ball")
        )
    )
    np.random.default_rng(3).shuffle(grid)  # the draw of sweep_rule_detector.py
    for i, (name, rpm, load, fs, surface) in enumerate(grid[:count]):
        g = bearing(name)
        settings = SimulationSettings(fs=fs, duration=1.0, channels=(CHANNEL,))
        op = OperatingCondition.from_rpm(rpm, load, random_slip=0.01, ball_jitter=0.005)
        pit = LocalizedDefect(surface=surface, length=0.3e-3, depth=0.1e-3)
        x = simulate(g, op, pit, settings=settings, random_state=i)[CHANNEL]
        for level in (0.0, 3.0):
            noisy = x + np.random.default_rng(i).normal(0.0, level * np.std(x), x.size)
            tag = f"pit {surface} {name} {rpm} rpm {load:.0f} N {fs:.0f} Hz noise {level:g}"
            report(tag, x if level == 0 else noisy, fs, rpm, g, seen)


def healthy(count: int, seen: Counter) -> None:
    grid = list(
        itertools.product(BEARINGS, (600, 1200, 1797, 3000, 6000), (100.0, 500.0, 2000.0), RATES)
    )
    np.random.default_rng(1).shuffle(grid)  # the draw of sweep_rule_detector.py
    for name, rpm, load, fs in grid[:count]:
        g = bearing(name)
        settings = SimulationSettings(fs=fs, duration=1.0, channels=(CHANNEL,))
        x = simulate(g, OperatingCondition.from_rpm(rpm, load), settings=settings)[CHANNEL]
        report(f"healthy {name} {rpm} rpm {load:.0f} N {fs:.0f} Hz", x, fs, rpm, g, seen)


if __name__ == "__main__":
    seen: Counter = Counter()
    mode = sys.argv[1] if len(sys.argv) > 1 else ""
    if mode == "wavy" and len(sys.argv) == 4:
        wavy(sys.argv[2], int(sys.argv[3]), seen)
    elif mode in ("pits", "healthy") and len(sys.argv) == 3:
        {"pits": pits, "healthy": healthy}[mode](int(sys.argv[2]), seen)
    else:
        raise SystemExit(__doc__)
    fault_beat, fault_plain = seen[(True, True)], seen[(True, False)]
    healthy_beat, healthy_plain = seen[(False, True)], seen[(False, False)]
    print(
        f"called a fault: with BEAT {fault_beat}, without {fault_plain}; "
        f"called healthy: with BEAT {healthy_beat}, without {healthy_plain}"
    )
