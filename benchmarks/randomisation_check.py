"""Does a model need a factor drawn that a recipe kept fixed? (prints figures; not a test)

A rig recipe's factor that the rig's publisher leaves open is drawn per case (domain
randomisation, issue 17) when a model trained with it drawn loses nothing on draws without it.
Each rig recipe is generated in two variants from the same seed (every other draw the same),
BASE and DRAWN, and the CWRU-rig recipe again with seed 777: extra trees (``cmtool train``'s
model for the rig recipes, evidence+scale-free, classes weighed, faulty signals below -10 dB
fault SNR left out, three seeds) trained on either variant and scored on either, over three
directions: CWRU -> MFPT, MFPT -> CWRU777, CWRU -> CWRU777.

Stop 40's two checks (docs/realism.md 5): the load's direction from the sensor
(``ehl``: the recipes as they were; ``ang``: ``operating.load_angle_deg = { min = -180, max =
180 }``) and the rig's structure (``str``: ``ang`` plus, under ``[model]``, ``shaft_mass_kg =
{ min = 1, max = 5 }``, ``housing_mass_kg = { min = 1, max = 20 }``, ``pedestal_stiffness_n_m
= { min = 2e7, max = 2e8 }``). Stop 41's: the dashpots as damping ratios (``zeta``: ``str``
plus ``housing_damping_ratio = { min = 0.02, max = 0.08 }`` and ``shaft_damping_ratio = { min
= 0.02, max = 0.05 }`` under ``[model]``, as the recipes now draw them). Stop 42's: the
rotor's broadband excitation (``b3``: the recipes as stop 41 left them; ``b5``: ``b3`` plus
``rotor_force_db = { min = -10, max = 10 }`` under ``[background]``, as they now draw it).
Stop 80's: the film at light load (``e0``: the recipes as shipped; ``e1``: ``film_entrainment_factor
= 1.0`` under ``[model]``, the flooded bound of docs/model.md 4.6; measured, not drawn). Stop
81's: the same factor drawn per case (``ed``: ``film_entrainment_factor = { min = 0, max = 1 }``
under ``[model]``; measured, not shipped: docs/realism.md 5), then on a grid (``eg``:
``film_entrainment_factor = [0, 0.25, 0.5, 0.75, 1]``, fresh seeds; shipped).

Run: .venv/bin/python benchmarks/randomisation_check.py FOLDER [BASE DRAWN] (default: ehl
ang), FOLDER holding cwru-rig-V, mfpt-rig-V and cwru777-V for both variants V, each from
``cmtool generate``.
"""

import sys
from pathlib import Path

import numpy as np

from cmtool import classifier
from cmtool.datasets import read_dataset

sys.path.insert(0, str(Path(__file__).resolve().parent))
from cross_domain import (  # noqa: E402
    CACHE,
    MIN_FAULT_SNR_DB,
    feature_table,
    print_cell,
)

DIRECTIONS = (("cwru-rig", "mfpt-rig"), ("mfpt-rig", "cwru777"), ("cwru-rig", "cwru777"))


def _table(name, frame):
    parts = classifier.DEFAULT_FEATURE_SET.split("+")
    return np.hstack([feature_table(name, frame, part) for part in parts])


def main(folder: Path, base: str, drawn: str) -> None:
    CACHE.mkdir(parents=True, exist_ok=True)
    frames, tables = {}, {}
    for rig in ("cwru-rig", "mfpt-rig", "cwru777"):
        for variant in (base, drawn):
            name = f"{rig}-{variant}"
            frames[name] = read_dataset(folder / name)
            tables[name] = _table(name, frames[name])
    keep = {n: ~(f["fault_snr_db"].to_numpy() < MIN_FAULT_SNR_DB) for n, f in frames.items()}
    for test_variant in (drawn, base):
        for train_variant in (base, drawn):
            means = []
            for train_rig, test_rig in DIRECTIONS:
                train, test = f"{train_rig}-{train_variant}", f"{test_rig}-{test_variant}"
                score, _ = print_cell(
                    f"{train} -> {test}",
                    tables[train][keep[train]],
                    frames[train]["label"].to_numpy()[keep[train]],
                    tables[test][keep[test]],
                    frames[test]["label"].to_numpy()[keep[test]],
                )
                means.append(score)
            print(f"trained {train_variant}, tested {test_variant}: mean {np.mean(means):.3f}\n")


if __name__ == "__main__":
    variants = sys.argv[2:4] if len(sys.argv) >= 4 else ["ehl", "ang"]
    main(Path(sys.argv[1]), *variants)
