"""Race verdicts put down to an inner race's lattice by its envelope's combination lines
(stop 54, measured, not shipped: docs/diagnosis.md, "Waviness read as a local fault").

A wavy inner race puts lines on the lattice m f_s + n BPFO into the demodulation band; their
envelope beats at the lattice's differences: BPFO and BPFI (read as race faults) and also
their sum BPFI + BPFO (= Z f_s) and difference |BPFI - BPFO|, which a pit's impacts do not
make. The check: those two lines, searched as the rule searches a fault line
(``features.slip_line``), combined by Fisher's method (``features.evidence.combine_lines``);
at a probability under noise of ``FALSE_ALARM`` (1e-4) or less, the race candidates of the
chosen form are not detected (confidence 0) and the verdict is the next detected candidate
or healthy. Form 1 demotes an "outer race" candidate only, form 2 an "inner race" one too.

Prints, with the check off and in each form: the verdicts on 1 um of inner-race waviness
N_w = 9 (``benchmarks/sweep_waviness_verdicts.py``'s 24 cases: three rigs, 900-3600 rpm, 12
and 25.6 kHz, 500 N, noise 5 % of the RMS), and on 0.18, 0.36 and 0.53 mm outer- and
inner-race pits (1 % slip) on a bearing with the same waviness, 900, 1500 and 1797 rpm, 12
kHz (a pit must stay found when the race is also wavy).

Run: .venv/bin/python benchmarks/lattice_lines.py  (about a minute)
"""

from __future__ import annotations

import itertools
from collections import Counter

import numpy as np
from sweep_waviness_verdicts import CHANNEL, RIGS  # the sweep's cases (benchmarks/ on the path)

import cmtool.diagnose as diagnose
import cmtool.rule as rule
from features.evidence import combine_lines, slip_line
from features.separation import FALSE_ALARM, line_false_alarm
from generators import (
    LocalizedDefect,
    OperatingCondition,
    SimulationSettings,
    Waviness,
    bearing,
    simulate,
)

FORMS = {"check off": (), "form 1": ("outer race",), "form 2": ("outer race", "inner race")}
SHIPPED_CANDIDATES = diagnose.rule_candidates


def lattice_probability(freqs: np.ndarray, amp: np.ndarray, bpfo: float, bpfi: float) -> float:
    """Fisher probability under noise of the envelope lines at BPFI + BPFO and |BPFI - BPFO|."""
    probabilities = []
    for rate in (bpfi + bpfo, abs(bpfi - bpfo)):
        ratio, _, bins, floor = slip_line(freqs, amp, rate)
        probabilities.append(line_false_alarm(ratio, bins, floor))
    return combine_lines(probabilities, probabilities[0])[1]


def with_lattice(races: tuple[str, ...]):
    """``rule_candidates`` with the race candidates the lattice explains demoted (moved after
    the others, so that the verdict reads the strongest one left)."""

    def rule_candidates(evidence, ctx):
        candidates = SHIPPED_CANDIDATES(evidence, ctx)
        p = lattice_probability(
            evidence.envelope_frequencies, evidence.envelope_amplitude, ctx["bpfo"], ctx["bpfi"]
        )
        if not races or p > FALSE_ALARM:
            return candidates
        for c in candidates:
            if c["fault"] in races:
                c["detected"], c["confidence"], c["lattice"] = False, 0.0, p
        return sorted(candidates, key=lambda c: "lattice" in c)

    return rule_candidates


def main() -> None:
    g = bearing("6205")
    for form, races in FORMS.items():
        # where diagnose_signal and where the segment scan (cmtool.rule) look it up
        diagnose.rule_candidates = rule.rule_candidates = with_lattice(races)
        noise = np.random.default_rng(18)
        wavy = Counter()
        for (_, rig), rpm, fs in itertools.product(
            RIGS.items(), (900, 1500, 2400, 3600), (12000.0, 25600.0)
        ):
            settings = SimulationSettings(fs=fs, duration=1.0, channels=(CHANNEL,))
            op = OperatingCondition.from_rpm(rpm, 500.0)
            wav = Waviness(surface="inner", order=9, amplitude=1e-6)
            x = simulate(g, op, wav, rig=rig, settings=settings, random_state=3)[CHANNEL]
            x = x + noise.normal(0.0, 0.05 * np.std(x), x.size)
            wavy[diagnose.diagnose_signal(x, fs, rpm, g).verdict] += 1
        print(f"{form}: inner-race waviness N_w = 9, 1 um: {dict(wavy)}")
        for surface in ("outer", "inner"):
            verdicts = Counter()
            for length, rpm in itertools.product((0.18e-3, 0.36e-3, 0.53e-3), (900, 1500, 1797)):
                settings = SimulationSettings(fs=12000.0, duration=1.0, channels=(CHANNEL,))
                op = OperatingCondition.from_rpm(rpm, 500.0, random_slip=0.01)
                defects = [
                    LocalizedDefect(surface=surface, length=length, depth=0.1e-3),
                    Waviness(surface="inner", order=9, amplitude=1e-6),
                ]
                x = simulate(g, op, defects, settings=settings, random_state=3)[CHANNEL]
                x = x + noise.normal(0.0, 0.05 * np.std(x), x.size)
                verdicts[diagnose.diagnose_signal(x, 12000.0, rpm, g).verdict] += 1
            print(f"  {surface}-race pits on the wavy bearing: {dict(verdicts)}")
    diagnose.rule_candidates = rule.rule_candidates = SHIPPED_CANDIDATES


if __name__ == "__main__":
    main()
