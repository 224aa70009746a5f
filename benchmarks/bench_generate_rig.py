"""Generation rate of the rig recipes with the realistic chain (issue 17's target: 200/s).

Each recipe is generated whole (700 signals, 400 of them ball pits, most never met by the
races; cwru-rig: 12 and 48 kHz, mfpt-rig: 48.8 and 97.7 kHz; local defects with slip, each
with its healthy twin) on two workers, timed from the call to the last file; the rate is
printed with the single-core yardstick of bench_generate.py's host note in mind.

With ``--entrainment E`` every case carries the film's entrainment at light load E (the
recipe's ``[model] film_entrainment_factor = E`` in place of what it draws, docs/model.md 4.6;
``--entrainment 0``: none): what the option costs. With ``--dry`` the recipe runs without its
film (``[model] ehl = false``, no entrainment): what the lubricant costs (docs/performance.md,
stop 82: a model trained on the dry recipe scores within 0.011 of it on lubricated draws).
With ``--step S`` the recipe runs RK4 at ``[model] step_s = S`` (``--step default``: at the
scene's own step, as the rig recipes run; docs/performance.md, "Speed", stop 85;
benchmarks/recipe_step.py measures what the step changes).

With ``--alternate N`` each recipe runs as it ships and with the options given, in turn, N
times each, and the medians' ratio is printed (the host's load moves single runs by 20 % and
more: docs/performance.md, "Speed", stop 85).

Run: .venv/bin/python benchmarks/bench_generate_rig.py [recipe ...] [--entrainment E | --dry]
    [--step S] [--alternate N]
"""

import argparse
import re
import statistics
import tempfile
import time
from pathlib import Path

from recipe_step import step_value, with_step  # benchmarks/ on the path

from cmtool.datasets import generate_dataset

REPO = Path(__file__).resolve().parents[1]


def variant_text(
    name: str, entrainment: float | None = None, dry: bool = False, step: str | None = None
) -> str:
    """The recipe ``datasets/NAME.toml``'s text with the options given (as it ships: none)."""
    recipe = REPO / "datasets" / f"{name}.toml"
    text = recipe.read_text()
    if step is not None:
        text = with_step(text, step_value(step))
    if dry:
        text = re.sub(r"^film_entrainment_factor\s*=.*\n", "", text, flags=re.M)
        text, given = re.subn(r"^ehl\s*=\s*true\s*$", "ehl = false", text, flags=re.M)
        if not given:
            raise SystemExit(f"{recipe}: no `ehl = true` under [model] to take away")
    elif entrainment is not None:
        if "[model]\n" not in text:
            raise SystemExit(f"{recipe}: no [model] table to give the entrainment")
        text, given = re.subn(  # a recipe that draws it gets the value instead
            r"^film_entrainment_factor\s*=.*$",
            f"film_entrainment_factor = {entrainment}",
            text,
            flags=re.M,
        )
        if not given:
            text = text.replace(
                "[model]\n", f"[model]\nfilm_entrainment_factor = {entrainment}\n", 1
            )
    return text


def rate(name: str, text: str, title: str = "") -> float:
    """Generate the recipe ``text`` whole on two workers; print and return its rate [1/s]."""
    with tempfile.TemporaryDirectory() as tmp:
        recipe = Path(tmp) / f"{name}.toml"
        recipe.write_text(text)
        start = time.perf_counter()
        summary = generate_dataset(recipe, Path(tmp) / name, workers=2)
        seconds = time.perf_counter() - start
    done = summary["written"] + summary["failed"]
    print(
        f"{name}{title}: {done} signals in {seconds:.1f} s on 2 workers: {done / seconds:.1f} "
        f"per second ({summary['failed']} failed)",
        flush=True,
    )
    return done / seconds


def main(
    recipes: list[str],
    entrainment: float | None = None,
    dry: bool = False,
    step: str | None = None,
    alternate: int = 0,
) -> None:
    """Each recipe's rate with the options given; with ``alternate`` N, the recipe as it ships
    and with the options N times each, in turn, and the medians' ratio."""
    for name in recipes or ["cwru-rig", "mfpt-rig"]:
        text = variant_text(name, entrainment, dry, step)
        if not alternate:
            rate(name, text)
            continue
        shipped = (REPO / "datasets" / f"{name}.toml").read_text()
        rates: dict[str, list[float]] = {"as it ships": [], "with the options": []}
        for _ in range(alternate):
            rates["as it ships"].append(rate(name, shipped, " as it ships"))
            rates["with the options"].append(rate(name, text, " with the options"))
        medians = {k: statistics.median(v) for k, v in rates.items()}
        print(
            f"{name}: median {medians['as it ships']:.1f} per second as it ships, "
            f"{medians['with the options']:.1f} with the options over {alternate} turns: "
            f"{medians['with the options'] / medians['as it ships']:.2f} times"
        )


def _turns(value: str) -> int:
    """``--alternate``'s count: at least one turn."""
    if int(value) < 1:
        raise argparse.ArgumentTypeError(f"{value}: at least 1 turn")
    return int(value)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("recipes", nargs="*", help="names in datasets/ (cwru-rig, mfpt-rig)")
    film = parser.add_mutually_exclusive_group()  # a dry recipe has no film to entrain
    film.add_argument("--entrainment", type=float, help="film_entrainment_factor for every case")
    film.add_argument("--dry", action="store_true", help="ehl = false, no entrainment")
    parser.add_argument("--step", help="[model] step_s [s], or 'default'")
    parser.add_argument("--alternate", type=_turns, default=0, help="turns as shipped and not")
    args = parser.parse_args()
    main(args.recipes, args.entrainment, args.dry, args.step, args.alternate)
