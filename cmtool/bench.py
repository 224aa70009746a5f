"""``cmtool bench``: run detectors over a labelled dataset and report how well they do.

Datasets: a ``cmtool generate`` folder (``data/*.parquet``), or a folder of recordings with a
``MANIFEST.csv`` (columns ``file``, ``sampling_rate_hz``, ``shaft_rpm``, ``fault_location``, and
``bearing`` or ``dataset``; ``channel_variable`` is used when present: the layout of
``../shared/data``).

Detectors: ``envelope`` (the rule-based detector of ``cmtool diagnose``), ``model`` (a trained
model) and ``combined`` (both pooled: the verdict of ``diagnose --model``), and any user
callable ``module:function`` with signature ``f(x, fs, rpm, bearing) -> label`` (labels
``healthy``, ``inner race``, ``outer race``, ``ball``).

Metrics per detector: detection rate (faulty signals called faulty), false-alarm rate (healthy
signals called faulty), correct-fault-first rate (faulty signals whose first verdict is their
fault) and accuracy; and the same by SNR, waviness amplitude, speed and load where the
dataset has them.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pandas as pd

from generators import bearing as catalog_bearing

from .diagnose import CANONICAL, diagnose_signal
from .io import read_recording

__all__ = ["run_bench", "summarise", "CANONICAL", "load_callable", "plot_bench"]

MANIFEST_BEARINGS = {"CWRU": "6205", "MFPT": "mfpt"}
GROUP_COLUMNS = (
    "snr_db",
    "fault_snr_db",
    "waviness_amplitude_m",
    "defect_length_m",
    "defect_depth_m",
    "rpm",
    "radial_load_n",
)


def load_callable(spec: str) -> Callable:
    """Import ``module:function``."""
    if ":" not in spec:
        raise ValueError(f"--detector {spec!r}: expected module:function")
    module, name = spec.split(":", 1)
    fn = getattr(importlib.import_module(module), name, None)
    if not callable(fn):
        raise ValueError(f"--detector {spec!r}: {name!r} is not a callable of {module!r}")
    return fn


def _records(path: Path, bearing_default: str, allow_incomplete: bool = False):
    """Yield (id, x, fs, rpm, bearing, label, metadata) for every signal of a dataset."""
    manifest = path / "MANIFEST.csv"
    if manifest.is_file():
        rows = pd.read_csv(manifest)
        for _, row in rows.iterrows():
            var = row.get("channel_variable")
            variable = var if isinstance(var, str) and "." not in var else None
            x, _ = read_recording(path / row["file"], variable=variable)
            brg = (
                row.get("bearing")
                if isinstance(row.get("bearing"), str)
                else MANIFEST_BEARINGS.get(str(row.get("dataset")), bearing_default)
            )
            yield (
                str(row["file"]),
                x,
                float(row["sampling_rate_hz"]),
                float(row["shaft_rpm"]),
                brg,
                CANONICAL.get(str(row["fault_location"]).lower(), "unknown"),
                {},
            )
        return
    from .datasets import read_dataset

    frame = read_dataset(path, allow_incomplete=allow_incomplete)
    for _, row in frame.iterrows():
        meta = {c: row[c] for c in GROUP_COLUMNS if c in row and pd.notna(row[c])}
        yield (
            row["id"],
            np.asarray(row["signal"], dtype=float),
            float(row["fs_hz"]),
            float(row["rpm"]),
            row["bearing"],
            CANONICAL.get(row["label"], row["label"]),
            meta,
        )


def run_bench(
    path: str | Path,
    *,
    model=None,
    detectors: dict[str, Callable] | None = None,
    bearing: str = "6205",
    progress=None,
    allow_incomplete: bool = False,
) -> pd.DataFrame:
    """One row per (signal, detector): true label, verdict and the grouping columns."""
    path = Path(path)
    detectors = dict(detectors or {})
    rows = []
    records = list(_records(path, bearing, allow_incomplete))
    for i, (sid, x, fs, rpm, brg, label, meta) in enumerate(records):
        geometry = catalog_bearing(brg)
        d = diagnose_signal(x, fs, rpm, geometry, model=model)
        verdicts = {"envelope": d.rule_verdict["label"]}
        if model is not None:
            verdicts["model"] = CANONICAL.get(d.model_verdict["label"], d.model_verdict["label"])
            verdicts["combined"] = d.verdict
        for name, fn in detectors.items():
            verdicts[name] = CANONICAL.get(str(fn(x, fs, rpm, brg)), str(fn(x, fs, rpm, brg)))
        for name, verdict in verdicts.items():
            rows.append({"id": sid, "detector": name, "label": label, "verdict": verdict, **meta})
        if progress:
            progress(i + 1, len(records))
    return pd.DataFrame(rows)


def _rates(group: pd.DataFrame) -> pd.Series:
    faulty = group["label"] != "healthy"
    healthy = ~faulty
    called = group["verdict"] != "healthy"
    return pd.Series(
        {
            "signals": len(group),
            "detection_rate": float(called[faulty].mean()) if faulty.any() else np.nan,
            "false_alarm_rate": float(called[healthy].mean()) if healthy.any() else np.nan,
            "correct_fault_first_rate": float((group["verdict"] == group["label"])[faulty].mean())
            if faulty.any()
            else np.nan,
            "accuracy": float((group["verdict"] == group["label"]).mean()),
        }
    )


def summarise(results: pd.DataFrame, *, bins: int = 3) -> dict[str, pd.DataFrame]:
    """Rates per detector, and per detector and binned group column."""
    out = {"overall": results.groupby("detector")[["label", "verdict"]].apply(_rates)}
    for col in GROUP_COLUMNS:
        if col not in results.columns or results[col].nunique() < 2:
            continue
        values = results[col]
        binned = (
            pd.qcut(values, q=min(bins, values.nunique()), duplicates="drop")
            if values.nunique() > bins
            else values
        )
        frame = results.assign(**{f"{col}_bin": binned.astype(str)})
        out[col] = frame.groupby(["detector", f"{col}_bin"])[["label", "verdict"]].apply(_rates)
    return out


def plot_bench(summary: dict[str, pd.DataFrame], out: Path) -> list[Path]:
    """Bar plots of the rates per detector, overall and by each group column."""
    from .plots import plt

    out.mkdir(parents=True, exist_ok=True)
    paths = []
    for name, table in summary.items():
        fig, ax = plt.subplots(figsize=(9, 4), dpi=110)
        table[["detection_rate", "false_alarm_rate", "correct_fault_first_rate"]].plot.bar(
            ax=ax, rot=30
        )
        ax.set_ylim(0, 1.05)
        ax.set_title(f"detector benchmark: {name}")
        ax.grid(alpha=0.3, axis="y")
        fig.tight_layout()
        path = out / f"bench_{name}.png"
        fig.savefig(path)
        plt.close(fig)
        paths.append(path)
    return paths
