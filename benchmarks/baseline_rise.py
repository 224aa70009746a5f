"""Local faults against a healthy baseline of the same machine (docs/diagnosis.md, "Local
faults against a baseline"): how far each fault's margin rises over the baseline's.

Simulated only. Healthy 6205 (5 um clearance), 6203 (5 um) and MFPT-rig bearings carrying 0.1
um form errors (``generators.form_waviness``: inner race, balls, or 0.05 um on both), 12 kHz,
1 s, white noise at 5 and 50 % of the RMS. Each record is diagnosed against a baseline of the
same bearing (the same form errors) at 1.2 x the load and 1.005 x the speed with fresh noise;
then the same bearing with a 0.3 mm x 0.1 mm pit on the outer race, the inner race or a ball (1
% random slip, 0.005 rad of pocket jitter) against the same baseline.

- set A (1797 and 1200 rpm, 100 and 400 N, noise seed 1): what ``BASELINE_RISE_DB`` was
  chosen on (the largest rise of a healthy record the rule calls faulty, the next whole dB
  and 3 dB more);
- set B (1500 and 2400 rpm, 200 and 800 N, noise seed 2): what it was judged on.

Run: .venv/bin/python benchmarks/baseline_rise.py [A|B] [--verbose]   (about 30 s a set)
"""

import itertools
import sys

import numpy as np

from cmtool.baseline import BASELINE_RISE_DB
from cmtool.diagnose import diagnose_signal
from generators import (
    LocalizedDefect,
    OperatingCondition,
    SimulationSettings,
    bearing,
    form_waviness,
    simulate,
)

CHANNEL = "housing_acceleration_y"
FS = 12000.0
SETS = {
    "A": {"seed": 1, "speeds": (1797, 1200), "loads": (100.0, 400.0)},
    "B": {"seed": 2, "speeds": (1500, 2400), "loads": (200.0, 800.0)},
}
FORMS = {"inner": (1e-7, 0.0, 0.0), "ball": (0.0, 0.0, 1e-7), "both": (5e-8, 0.0, 5e-8)}
VERDICT = {"outer": "outer race", "inner": "inner race", "ball": "ball"}


def _signal(g, rpm, load, form, state, pit=None):
    slip = {"random_slip": 0.01, "ball_jitter": 0.005} if pit else {}
    op = OperatingCondition.from_rpm(rpm, load, **slip)
    defects = list(form_waviness(g.ball_count, *FORMS[form])) + ([pit] if pit else [])
    settings = SimulationSettings(fs=FS, duration=1.0, channels=(CHANNEL,))
    return simulate(g, op, defects, settings=settings, random_state=state)[CHANNEL]


def _margins(d):
    return {c["fault"]: c["evidence_db"] - d.threshold_db for c in d.candidates}


def main(name: str, verbose: bool) -> None:
    spec = SETS[name]
    noise = np.random.default_rng(spec["seed"])
    healthy_rises, healthy_faulty, healthy_kept, pits_right, pits_kept = [], 0, 0, 0, 0
    cases = itertools.product(
        ("6205", "6203", "mfpt"), spec["speeds"], spec["loads"], FORMS, (0.05, 0.5)
    )
    for i, (brg, rpm, load, form, level) in enumerate(cases):
        g = bearing(brg) if brg == "mfpt" else bearing(brg, radial_internal_clearance=5e-6)
        base = _signal(g, rpm * 1.005, load * 1.2, form, i)
        base = base + noise.normal(0.0, level * base.std(), base.size)
        record = _signal(g, rpm, load, form, i)
        record = record + noise.normal(0.0, level * record.std(), record.size)
        alone = diagnose_signal(record, FS, rpm, g, waviness=False)
        against = diagnose_signal(record, FS, rpm, g, waviness=False, baseline=base)
        b = _margins(diagnose_signal(base, FS, rpm, g, waviness=False))
        m = _margins(alone)
        if alone.verdict != "healthy":
            healthy_faulty += 1
            healthy_rises.append(m[alone.verdict] - b[alone.verdict])
        healthy_kept += against.verdict == "healthy"
        if verbose:
            print(
                f"healthy {brg} {rpm} {load:g} {form} {level}: {alone.verdict} -> {against.verdict}"
            )
        for surface in ("outer", "inner", "ball"):
            pit = LocalizedDefect(surface=surface, length=0.3e-3, depth=0.1e-3)
            x = _signal(g, rpm, load, form, i, pit)
            x = x + noise.normal(0.0, level * x.std(), x.size)
            right = diagnose_signal(x, FS, rpm, g, waviness=False).verdict == VERDICT[surface]
            if right:
                pits_right += 1
                with_base = diagnose_signal(x, FS, rpm, g, waviness=False, baseline=base)
                pits_kept += with_base.verdict == VERDICT[surface]
                if verbose and with_base.verdict != VERDICT[surface]:
                    print(f"  pit {surface} lost against the baseline: {with_base.basis}")
    total = len(spec["speeds"]) * len(spec["loads"]) * len(FORMS) * 2 * 3
    print(
        f"set {name}: {total} healthy records with form errors, {healthy_faulty} called "
        "faulty alone"
    )
    print(f"  their rise over the baseline: at most {max(healthy_rises):.1f} dB")
    print(
        f"  called healthy against the baseline ({BASELINE_RISE_DB:g} dB): {healthy_kept}/{total}"
    )
    print(
        f"  pits right alone: {pits_right}/{3 * total}; still right against the baseline: "
        f"{pits_kept}/{pits_right} ({pits_kept / max(pits_right, 1):.3f})"
    )


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    main(args[0] if args else "A", "--verbose" in sys.argv)
