"""How far a recipe's records move when its film tables move by roundoff (prints figures).

A dataset regenerates byte for byte on one machine; on another processor, or with another
libm, the same code rounds differently (numba compiles for the host; numpy's transcendental
functions may take other vector paths), and datasets/README says what that did to `small/`
(its last float32 bits). Whether a recipe's records stay that close depends on whether the
runs amplify a difference in the last bits. This generates a recipe (at one seed, every
condition's count cut to ``--fraction``, one worker) twice: as it is, and with the film
tables that ``generators.packing.with_film_tables`` appends to every case's parameter vector
multiplied by 1 + ``--epsilon`` x a standard normal draw per entry (a fixed generator): a
perturbation of the size another machine's rounding of those tables makes. It prints, per
class, how many records changed at all and by more than 1e-6 in relative L2, their 90th
percentile and largest change, how many of those over 1e-6 are preloaded and whether their
change grows along the record (a divergence that grows is chaos; one that does not was set
at the start), the fault SNR labels' largest change (over the pits touched, at -20 dB or
more, and over all), and the rule's verdicts (``diagnose_signal``, ``waviness=False``) on
the healthy records and the faults at fault SNR >= ``MIN_FAULT_SNR_DB`` both ways. A recipe
without the film (``ehl = false``) is not perturbed at all, and says so.

Run (docs/performance.md, "Speed", stop 86; about a minute a recipe):
    .venv/bin/python benchmarks/roundoff_sensitivity.py datasets/cwru-rig.toml --seed 8601
    .venv/bin/python benchmarks/roundoff_sensitivity.py datasets/mfpt-rig.toml --seed 8602
"""

from __future__ import annotations

import argparse
import re
import tempfile
from pathlib import Path

import numpy as np
from machine_level import MIN_FAULT_SNR_DB, rule_verdicts  # benchmarks/ on the path
from recipe_step import generate, relative_errors, with_fraction

import generators.packing as packing
import generators.prepared as prepared

#: Fault SNR labels under this [dB] belong to pits the races barely touch, whose difference
#: from the healthy twin is at the integration's own noise (docs/benchmark.md 1).
TOUCHED_DB = -20.0


def perturbed_tables(epsilon: float, seed: int = 86):
    """A ``with_film_tables`` whose appended tables are scaled by 1 + epsilon x N(0, 1)."""
    rng = np.random.default_rng(seed)
    original = packing.with_film_tables

    def with_tables(p: np.ndarray) -> np.ndarray:
        out = original(p)
        n = p.size
        out[n:] *= 1.0 + epsilon * rng.standard_normal(out.size - n)
        return out

    return with_tables


def _tenths_growth(x, y) -> float:
    """RMS of x - y over the record's last tenth, over that of its first tenth."""
    d = np.asarray(x, float) - np.asarray(y, float)
    n = d.size // 10
    first = np.sqrt(np.mean(d[:n] ** 2))
    return float(np.sqrt(np.mean(d[-n:] ** 2)) / first) if first > 0 else float("nan")


def main(args: argparse.Namespace) -> None:
    text = re.sub(r"(?m)^seed = \d+", f"seed = {args.seed}", args.recipe.read_text())
    if args.fraction < 1.0:
        text = with_fraction(text, args.fraction)
    print(
        f"{args.recipe.name}, seed {args.seed}, fraction {args.fraction}, epsilon {args.epsilon:g}"
    )
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        plain = generate("as-is", text, folder, 1)
        calls = []
        perturb = perturbed_tables(args.epsilon)

        def counted(p):
            calls.append(1)
            return perturb(p)

        prepared.with_film_tables = counted
        try:
            moved = generate("perturbed", text, folder, 1)
        finally:
            prepared.with_film_tables = packing.with_film_tables
        if not calls:
            print("  the recipe builds no film tables: nothing perturbed")
            return
        verdicts = {"as-is": rule_verdicts(plain, 2), "perturbed": rule_verdicts(moved, 2)}
    errors = relative_errors(moved, plain)
    frame = plain.assign(error=errors)
    print(f"  {len(calls)} film tables perturbed; records (relative L2 change):")
    for label, group in frame.groupby("label"):
        e = group["error"]
        print(
            f"    {label:8s} {e.size:4d}: changed {int((e > 0).sum()):4d}, over 1e-6 "
            f"{int((e > 1e-6).sum()):4d}, 90th percentile {e.quantile(0.9):.2e}, "
            f"largest {e.max():.2e}"
        )
    over = frame[frame["error"] > 1e-6]
    if len(over):
        preloaded = int((over["radial_internal_clearance_m"] < 0).sum())
        growth = [_tenths_growth(plain["signal"][i], moved["signal"][i]) for i in over.index]
        loads = over["radial_load_n"].median(), frame["radial_load_n"].median()
        print(
            f"    of those over 1e-6: {preloaded} preloaded (operating clearance < 0; all "
            f"records {int((frame['radial_internal_clearance_m'] < 0).sum())}), radial load "
            f"median {loads[0]:.0f} N (all {loads[1]:.0f} N); the change in the record's last "
            f"tenth over its first: median {np.median(growth):.2f}"
        )
    a, b = plain["fault_snr_db"].to_numpy(), moved["fault_snr_db"].to_numpy()
    finite = np.isfinite(a) & np.isfinite(b)
    touched = finite & (np.minimum(a, b) >= TOUCHED_DB)
    if not finite.any():
        print("  no fault SNR labels (a recipe without local defects)")
    else:
        largest = np.abs(a[finite] - b[finite]).max()
        largest_touched = np.abs(a[touched] - b[touched]).max() if touched.any() else 0.0
        print(
            f"  fault SNR labels: largest change {largest_touched:.3g} dB over the "
            f"{touched.sum()} at {TOUCHED_DB:g} dB or more, {largest:.3g} dB over all "
            f"{finite.sum()} finite; the untouched (-inf) the same: "
            f"{bool(np.array_equal(np.isinf(a), np.isinf(b)))}"
        )
    changed = [k for k in verdicts["as-is"] if verdicts["as-is"][k] != verdicts["perturbed"][k]]
    print(
        f"  the rule on {len(verdicts['as-is'])} kept records (fault SNR >= "
        f"{MIN_FAULT_SNR_DB:g} dB and healthy): {len(changed)} verdicts changed {changed}"
    )


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("recipe", type=Path)
    parser.add_argument("--seed", type=int, required=True, help="the recipe's seed")
    parser.add_argument("--fraction", type=float, default=0.25, help="counts cut to this share")
    parser.add_argument(
        "--epsilon", type=float, default=2e-15, help="relative size of the tables' perturbation"
    )
    main(parser.parse_args())
