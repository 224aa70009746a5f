"""Does a cage's mean slip, which the rig recipes do not draw, cost the models and the rule?

A ball bearing's cage runs slower than its kinematic speed (traction at the loaded contacts
against drag): BPFO, the cage rate and the ball's spin lie lower than calculated by the slip
s, and BPFI higher by s BPFO / BPFI (``generators.characteristic_frequencies``,
``OperatingCondition.cage_slip``). The rig recipes draw the cage speed's fluctuation
(``random_slip``) but no mean slip, so every simulated fault sits at its kinematic rate. This
generates a recipe's training draw and two check draws of another seed, one as the recipe is
and one with ``[operating] cage_slip`` drawn from 0 to ``--slip`` (the same cases otherwise:
the slip is drawn last), trains ``cmtool train``'s default model on the training draw as it is
and on the training draw with the same slip, and prints each model's recall per class on both
check draws (healthy signals and faults at fault SNR >= -10 dB, ``cmtool evaluate``'s default)
and the rule's (``cmtool bench``'s ``envelope`` detector, which is ``cmtool diagnose``'s rule).
Simulation only; docs/realism.md 1.

Run: .venv/bin/python benchmarks/cage_slip.py [RECIPE] --out FOLDER [--slip 0.015]
     [--check-seed 777] [--workers 2]
"""

from __future__ import annotations

import argparse
import json
import re
import subprocess
import sys
from pathlib import Path

import pandas as pd

VERDICT = {"healthy": "healthy", "inner": "inner race", "outer": "outer race", "ball": "ball"}


def _cmtool(*args: str) -> None:
    subprocess.run([sys.executable, "-m", "cmtool", *args], check=True, stdout=subprocess.DEVNULL)


def _variant(text: str, out: Path, name: str, seed: int | None, slip: float | None) -> Path:
    """The recipe with another seed and/or a drawn mean cage slip, written to OUT/NAME.toml."""
    if seed is not None:
        text = re.sub(r"(?m)^seed = \d+", f"seed = {seed}", text)
    if slip is not None:
        text = text.replace(
            "[operating]\n", f"[operating]\ncage_slip = {{ min = 0, max = {slip} }}\n", 1
        )
    path = out / f"{name}.toml"
    path.write_text(text)
    return path


def _rule_recall(bench: Path) -> dict[str, float]:
    """Recall per class of the rule's verdicts on healthy signals and visible faults."""
    r = pd.read_csv(bench / "results.csv")
    r = r[(r.detector == "envelope") & ((r.label == "healthy") | (r.fault_snr_db >= -10))]
    return {
        label: float((group.verdict == VERDICT.get(label, label)).mean())
        for label, group in r.groupby("label")
    }


def _line(name: str, recall: dict[str, float]) -> str:
    balanced = sum(recall.values()) / len(recall)
    shown = " ".join(f"{k} {v:.3f}" for k, v in sorted(recall.items()))
    return f"  {name:34s} balanced {balanced:.3f}  ({shown})"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("recipe", nargs="?", default="datasets/cwru-rig.toml")
    parser.add_argument("--out", required=True, type=Path)
    parser.add_argument("--slip", type=float, default=0.015)
    parser.add_argument("--check-seed", type=int, default=777)
    parser.add_argument("--workers", default="2")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    text = Path(args.recipe).read_text()
    recipes = {
        "train": _variant(text, args.out, "train", None, None),
        "train-slip": _variant(text, args.out, "train-slip", None, args.slip),
        "check": _variant(text, args.out, "check", args.check_seed, None),
        "check-slip": _variant(text, args.out, "check-slip", args.check_seed, args.slip),
    }
    for name, recipe in recipes.items():
        if not (args.out / name / "_dataset.json").exists():
            _cmtool(
                "generate", str(recipe), "--out", str(args.out / name), "--workers", args.workers
            )
    for name in ("train", "train-slip"):
        model = args.out / f"{name}.skops"
        if not model.exists():
            _cmtool("train", str(args.out / name), "--out", str(model), "--workers", args.workers)
    print(f"{args.recipe}, cage slip drawn from 0 to {args.slip}; recall per class, visible faults")
    for check in ("check", "check-slip"):
        print(f"{check} (seed {args.check_seed}):")
        for name in ("train", "train-slip"):
            folder = args.out / f"eval-{name}-on-{check}"
            _cmtool(
                "evaluate", str(args.out / f"{name}.skops"), str(args.out / check),
                "--out", str(folder), "--workers", args.workers,
            )  # fmt: skip
            per_class = json.loads((folder / "evaluation.json").read_text())["per_class"]
            recall = {k: v["recall"] for k, v in per_class.items() if k in VERDICT}
            print(_line(f"model trained on {name}", recall))
        bench = args.out / f"bench-{check}"
        if not (bench / "results.csv").exists():
            _cmtool("bench", str(args.out / check), "--out", str(bench), "--workers", args.workers)
        print(_line("rule", _rule_recall(bench)))


if __name__ == "__main__":
    main()
