"""How much of a fault SNR's "rest" is the healthy bearing? (prints figures; not a test)

The recipes' fault SNR (docs/realism.md 4) is the fault signature's power over everything else
in the octave where the fault stands out most: the healthy bearing's own vibration, the
machine's background and the noise. The rule removes a healthy bearing's periodic part
before its envelope analysis (the shaft and ball-pass harmonics, docs/diagnosis.md), so where
that part fills the octave, the same label leaves the fault more over what the rule sees.
A film at light load (``film_entrainment_factor``, docs/model.md 4.6) takes the dry onset's
ringing out of the healthy bearing, so the share differs with it.

For every touched pit of a recipe (regenerated case by case, the dataset's own rows), this
prints, by class and by the film's entrainment:

- the label (``fault_snr_db``) and the fault's ratio over the background alone (the same band,
  the same Welch powers: ``generators.measurement.band_power``), and their difference [dB];
- how well each predicts that the rule names the right fault (ROC AUC over the touched pits).

Run (docs/realism.md 5):
    .venv/bin/python benchmarks/fault_snr_rest.py datasets/mfpt-rig.toml [ROWS.csv]

(``ROWS.csv``: every pit's row, for a closer look.)
"""

import json
import sys
from unittest import mock

import numpy as np
import pandas as pd
from sklearn.metrics import roc_auc_score

import generators.synthesis as synthesis
from cmtool.datasets import load_recipe
from cmtool.diagnose import diagnose_signal
from generators import bearing
from generators.cases import expand_cases
from generators.measurement import band_power

VERDICT = {"inner": "inner race", "outer": "outer race", "ball": "ball"}
COLUMNS = (
    "label",
    "case",
    "film_entrainment_factor",
    "fault_snr_db",
    "over_background_db",
    "found",
)


def pit_rows(recipe_path: str) -> pd.DataFrame:
    """One row per touched pit: its label, its ratio over the background, the rule's hit."""
    recipe, _ = load_recipe(recipe_path)
    seen: dict = {}
    transfer, powers = synthesis.transfer_path, synthesis.fault_band_powers

    def keep_healthy(x, fs, modes):
        out = transfer(x, fs, modes)
        seen["healthy"] = out[1] if np.ndim(out) == 2 else out
        return out

    def keep_rest(signature, rest, fs):
        band, own, total = powers(signature, rest, fs)
        background = rest - seen["healthy"]
        seen.update(band=band, own=own, background=band_power(background, fs, band))
        return band, own, total

    rows = []
    with (
        mock.patch.object(synthesis, "transfer_path", keep_healthy),
        mock.patch.object(synthesis, "fault_band_powers", keep_rest),
    ):
        for case in expand_cases(recipe):
            if case.label not in VERDICT:
                continue
            seen.clear()
            row = synthesis.generate_case(recipe, case)
            if row.get("error") or "own" not in seen or not np.isfinite(row["fault_snr_db"]):
                continue  # diverged, or a pit the races never touch
            gain = json.loads(row["chain"])["fault_gain"]
            d = diagnose_signal(
                np.asarray(row["signal"], dtype=float),
                row["fs_hz"],
                row["rpm"],
                bearing(case.bearing),
                waviness=False,
                severity=False,
            )
            over_background = gain * gain * seen["own"] / max(seen["background"], 1e-300)
            rows.append(
                {
                    "label": case.label,
                    "case": case.index,
                    "film_entrainment_factor": row["film_entrainment_factor"],
                    "fault_snr_db": row["fault_snr_db"],
                    "over_background_db": 10.0 * np.log10(max(over_background, 1e-300)),
                    "found": d.rule_verdict["label"] == VERDICT[case.label],
                }
            )
    frame = pd.DataFrame(rows, columns=[*COLUMNS])
    frame["difference_db"] = frame["over_background_db"] - frame["fault_snr_db"]
    return frame


def _auc(found: pd.Series, score: pd.Series) -> float:
    return float(roc_auc_score(found, score)) if found.nunique() == 2 else float("nan")


def main(recipe_path: str, out_csv: str | None = None) -> None:
    frame = pit_rows(recipe_path)
    if out_csv:
        frame.to_csv(out_csv, index=False)
    print(f"{recipe_path}: {len(frame)} touched pits")
    if frame.empty:
        return  # a recipe without local defects, or none the races touch
    print("class   pits  found  AUC label  AUC over background  median difference [dB]")
    for name, group in [("all", frame), *frame.groupby("label")]:
        print(
            f"{name:6s} {len(group):5d}  {group.found.mean():.3f}  "
            f"{_auc(group.found, group.fault_snr_db):9.3f}  "
            f"{_auc(group.found, group.over_background_db):19.3f}  "
            f"{group.difference_db.median():6.1f}"
        )
    visible = frame[frame.fault_snr_db >= -10.0]
    if frame["film_entrainment_factor"].notna().any():
        print("\nmedian difference [dB], faults at fault SNR >= -10 dB, by film entrainment:")
        table = visible.groupby(["label", "film_entrainment_factor"]).difference_db.median()
        print(table.unstack().round(1).to_string())
    print("\nlargest differences (faults at fault SNR >= -10 dB):")
    print(visible.nlargest(8, "difference_db").round(2).to_string())


if __name__ == "__main__":
    main(*sys.argv[1:3])
