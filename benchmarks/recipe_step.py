"""A rig recipe at a longer RK4 step: accuracy against a reference step, the rule's verdicts.

The rig recipes run `shaft+housing` with the film by RK4 at the scene's default step (2e-5 s
or the stability step, docs/model.md 7); near a local defect the steps are split
(``generators.steps.DEFECT_STEPS``). Stop 85 measured ``[model] step_s = 4e-5`` against a bar
and kept the default (docs/performance.md, "Speed"). This generates the recipe as given and at
``--step`` (a step [s], or ``default``: the scene's own) at one seed and compares, on every
record:

- how far each record at the step lies from the record as given (relative L2 difference
  of the written signals, per class and sample rate: median, 90th percentile, largest);
- with ``--reference R``: the same recipe at ``step_s = R`` too, and both runs' errors
  against it (relative L2 error per record; the faults' ``fault_snr_db`` labels within 0.1 dB
  of the reference's);
- the rule's verdicts (``diagnose_signal``, ``waviness=False``) on the healthy signals and
  the faults at fault SNR >= ``MIN_FAULT_SNR_DB``, both ways, and every record whose verdict
  changed.

With ``--score-on DATASET ...`` a model of ``cmtool train``'s default feature set (extra
trees over three seeds, ``benchmarks/cross_domain.print_cell``) is trained on each run's kept
records and scored on each dataset folder given (a fresh draw of this rig and of another).

``--fraction F`` cuts every condition's count to that fraction (a quicker draw);
``--keep DIR`` keeps the datasets in DIR/shipped (as given), DIR/step and DIR/reference (for
``benchmarks/cross_domain.py``). The rate each run generated at is printed too (two workers;
to compare rates, ``bench_generate_rig.py --step S --alternate N``).

Run (about 3 minutes a rig on two cores; with a reference of 1e-5 s, about twice that):
    .venv/bin/python benchmarks/recipe_step.py datasets/cwru-rig.toml --seed 8511 --step 4e-5
    .venv/bin/python benchmarks/recipe_step.py datasets/cwru-rig.toml --seed 8501 --step 4e-5 \
        --reference 1e-5 --fraction 0.25
    .venv/bin/python benchmarks/recipe_step.py datasets/cwru-rig.toml --seed 8511 --step 4e-5 \
        --score-on data/cwru-rig-8513 data/mfpt-rig-8512
"""

import argparse
import re
import tempfile
import time
import tomllib
from pathlib import Path

import numpy as np
from cross_domain import feature_table, print_cell  # benchmarks/ on the path
from machine_level import MIN_FAULT_SNR_DB, report_verdicts, rule_verdicts

from cmtool.classifier import DEFAULT_FEATURE_SET
from cmtool.datasets import generate_dataset, read_dataset


def with_step(text: str, step: float | None) -> str:
    """The recipe's text at ``step_s = step`` in its ``[model]`` table (``None``: without
    ``step_s``, at the scene's default step); a ``step_s`` it sets is replaced."""
    if re.search(r"(?m)^error_bound\s*=", text):
        raise SystemExit("the recipe sets an error_bound: its steps are the bound's")
    text = re.sub(r"(?m)^step_s\s*=.*\n", "", text)
    if step is None:
        return text
    if not re.search(r"(?m)^\[model\]\s*$", text):
        raise SystemExit("the recipe has no [model] table to give the step")
    return re.sub(r"(?m)^\[model\]\s*$", f"[model]\nstep_s = {step!r}", text, count=1)


def with_fraction(text: str, fraction: float) -> str:
    """The recipe's text with every condition's count cut to ``fraction`` (at least 1)."""
    return re.sub(
        r"(?m)^count = (\d+)", lambda m: f"count = {max(1, round(int(m[1]) * fraction))}", text
    )


def relative_errors(frame, reference) -> np.ndarray:
    """Per record: ||x - x_ref|| / ||x_ref|| of the written signals (the same cases, in order)."""
    out = []
    for a, b in zip(frame.itertuples(), reference.itertuples(), strict=True):
        if (a.index, a.label) != (b.index, b.label):
            raise SystemExit(f"record {a.index} ({a.label}) is not the reference's {b.index}")
        x, y = np.asarray(a.signal, float), np.asarray(b.signal, float)
        out.append(np.linalg.norm(x - y) / max(np.linalg.norm(y), 1e-300))
    return np.array(out)


def report_errors(title: str, frame, errors: np.ndarray) -> None:
    """Print the errors' median, 90th percentile and largest, overall and per class and rate."""
    print(
        f"  {title}: median {np.median(errors):.2e}, 90th percentile "
        f"{np.percentile(errors, 90):.2e}, largest {errors.max():.2e} over {errors.size} records"
    )
    groups = frame.assign(error=errors).groupby(["label", "fs_hz"])["error"]
    for (label, fs), values in groups:
        print(
            f"    {label:8s} {fs:8.0f} Hz: median {values.median():.2e}, 90th percentile "
            f"{values.quantile(0.9):.2e}, largest {values.max():.2e} ({values.size})"
        )


def report_labels(title: str, frame, reference) -> None:
    """Print how many finite fault SNR labels lie within 0.1 dB of the reference's."""
    a, b = frame["fault_snr_db"].to_numpy(), reference["fault_snr_db"].to_numpy()
    finite = np.isfinite(a) & np.isfinite(b)
    close = np.abs(a[finite] - b[finite]) <= 0.1
    both_inf = int(np.sum(np.isinf(a) & np.isinf(b)))
    print(
        f"  {title}: fault SNR labels within 0.1 dB of the reference's {close.sum()}/"
        f"{finite.sum()} ({close.mean():.3f}); untouched in both {both_inf}, "
        f"largest difference {np.abs(a[finite] - b[finite]).max():.2f} dB"
    )


def generate(name: str, text: str, folder: Path, workers: int):
    """Generate ``text`` into ``folder / name``; its frame in record order, and the rate."""
    path = folder / f"{name}.toml"
    path.write_text(text)
    start = time.perf_counter()
    summary = generate_dataset(path, folder / name, workers=workers)
    seconds = time.perf_counter() - start
    done = summary["written"] + summary["failed"]
    print(
        f"  {name}: {done} signals in {seconds:.1f} s ({done / seconds:.1f}/s), "
        f"{summary['failed']} failed"
    )
    return read_dataset(folder / name).sort_values("index").reset_index(drop=True)


def kept_table(name: str, frame) -> tuple[np.ndarray, np.ndarray]:
    """The default feature set's table and labels of a frame's healthy records and faults at
    fault SNR >= ``MIN_FAULT_SNR_DB`` (what ``cmtool train`` keeps)."""
    keep = ~(frame["fault_snr_db"].to_numpy() < MIN_FAULT_SNR_DB)
    parts = [feature_table(name, frame, part) for part in DEFAULT_FEATURE_SET.split("+")]
    return np.hstack(parts)[keep], frame["label"].to_numpy()[keep]


def report_scores(frames: dict, titles: dict, folders: list[Path]) -> None:
    """Print each run's model scored on each dataset folder, and its mean."""
    print(f"  models on {DEFAULT_FEATURE_SET}, trained on each run's kept records:")
    tests = {str(folder): kept_table(folder.name, read_dataset(folder)) for folder in folders}
    for name, frame in frames.items():
        train = kept_table(f"recipe-step-{name}", frame)
        scores = [
            print_cell(f"    {titles[name]} -> {test}", *train, *table)[0]
            for test, table in tests.items()
        ]
        print(f"    {titles[name]}: mean {np.mean(scores):.3f}")


def step_value(value: str) -> float | None:
    """A step [s] from the command line; ``default``: the scene's own (``None``)."""
    return None if value == "default" else float(value)


def step_name(step: float | None) -> str:
    """How a step is printed."""
    return "the default step" if step is None else f"step_s {step:g}"


def main(args: argparse.Namespace) -> None:
    text = re.sub(r"(?m)^seed = \d+", f"seed = {args.seed}", args.recipe.read_text())
    if args.fraction < 1.0:
        text = with_fraction(text, args.fraction)
    tomllib.loads(text)  # a readable recipe before anything is generated
    print(f"{args.recipe.name}, seed {args.seed}: {step_name(args.step)} against as given")
    with tempfile.TemporaryDirectory() as tmp:
        folder = args.keep or Path(tmp)
        folder.mkdir(parents=True, exist_ok=True)
        frames = {
            "shipped": generate("shipped", text, folder, args.workers),
            "step": generate("step", with_step(text, args.step), folder, args.workers),
        }
        if args.reference is not None:  # (a step given, not the default)
            reference = generate("reference", with_step(text, args.reference), folder, args.workers)
        verdicts = {
            "without": rule_verdicts(frames["shipped"], args.workers),
            "with": rule_verdicts(frames["step"], args.workers),
        }
    shipped, step = frames["shipped"], frames["step"]
    report_errors(
        f"{step_name(args.step)} against as given", shipped, relative_errors(step, shipped)
    )
    if args.reference is not None:
        for name, title in (("shipped", "as given"), ("step", step_name(args.step))):
            errors = relative_errors(frames[name], reference)
            report_errors(f"{title} against {step_name(args.reference)}", reference, errors)
            report_labels(title, frames[name], reference)
    print(
        f"  the rule, on {len(verdicts['with'])} kept records (fault SNR >= "
        f"{MIN_FAULT_SNR_DB:g} dB and healthy):"
    )
    report_verdicts(verdicts, {"without": "as given", "with": step_name(args.step)})
    if args.score_on:
        report_scores(frames, {"shipped": "as given", "step": step_name(args.step)}, args.score_on)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("recipe", type=Path, help="a recipe without error_bound")
    parser.add_argument("--seed", type=int, required=True, help="the recipe's seed for all runs")
    parser.add_argument(
        "--step", type=step_value, required=True, help="the RK4 step [s] or 'default'"
    )
    parser.add_argument("--reference", type=step_value, help="a reference RK4 step [s], e.g. 1e-5")
    parser.add_argument("--fraction", type=float, default=1.0, help="counts cut to this share")
    parser.add_argument("--workers", type=int, default=2, help="generation and rule workers")
    parser.add_argument("--keep", type=Path, help="keep the datasets in this (new) folder")
    parser.add_argument(
        "--score-on", type=Path, nargs="+", help="dataset folders to score each run's model on"
    )
    main(parser.parse_args())
