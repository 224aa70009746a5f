"""``cmtool bench``: detectors over a labelled dataset, scored as a detection study is.

Datasets: a ``cmtool generate`` folder (``data/*.parquet``), or a folder of recordings with a
``MANIFEST.csv`` (columns ``file``, ``sampling_rate_hz``, ``shaft_rpm``, ``fault_location``, and
``bearing`` or ``dataset``; ``channel_variable`` is used when present: the layout of
``../shared/data``; a ``tacho_channel`` gives the speed, ``order_track`` resamples, as in
``cmtool diagnose``).

Detectors (:data:`BUILTIN_DETECTORS`), each giving a label and a continuous score per fault
(``outer race``, ``inner race``, ``ball``; larger means more evidence):

- ``envelope``: the rule detector of ``cmtool diagnose``: envelope analysis of the random
  part in the band it selects (score: each fault's envelope line over the detection threshold
  [dB]; the name it has had since the first ``cmtool bench``);
- ``fixed_band_ses``: the squared envelope spectrum of a fixed band, fs/8 to 3 fs/8 (score:
  the mean power of the fault rate's first three lines over the local floor [dB]);
- ``cpw_ses``: cepstral pre-whitening, then the squared envelope spectrum of the whole band;
- ``spectral_kurtosis``: the fast kurtogram's largest spectral kurtosis (one score for every
  fault: it tells impulsive from not, not which fault);
- ``kurtosis``, ``crest_factor``: time statistics of the raw signal (likewise);
- ``model`` and ``combined`` with ``--model``: the model's class probabilities and the
  verdict of ``diagnose --model`` (pooled probabilities).

User plug-ins ``module:function`` are called as ``f(x, fs, rpm, bearing)`` with the signal
(1-D array), its sample rate [Hz], the shaft speed [rpm] and the bearing's name (a catalog
name, or the name a manifest's geometry gives; a plug-in with a ``geometry`` parameter, or
``**kwargs``, also gets ``geometry=``, the :class:`generators.BearingGeometry`), and
return either a label (``healthy``, ``outer race``, ``inner race``, ``ball``; the score is then
1 for the named fault, 0 otherwise) or a mapping ``{"label": ..., "scores": {"outer race":
s1, "inner race": s2, "ball": s3}}``.

Metrics (never on a model's own training signals unless ``--allow-training-data``, and then
every output says in-sample): per detector and fault, the ROC of that fault's signals against
the healthy ones and its area; the detection probability at false-alarm rates 1e-2 and 1e-3,
thresholds set on the healthy signals alone (NaN when fewer than 1 / rate of them: such a
rate cannot be measured); the detection probability at 1e-2 against the fault SNR and every
other factor the dataset varies, in ordered bins with Wilson 95 % intervals.
"""

from __future__ import annotations

import importlib
import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from features.transformer import WarningRelay, keeping_warnings
from generators import BearingGeometry, characteristic_frequencies
from generators import bearing as catalog_bearing

from .bench_scores import (  # noqa: F401 (moved in stop 56, still exported here)
    CLASS_ORDER,
    FACTORS,
    FAULT_CLASSES,
    PFA_LEVELS,
    SCORE_COLUMNS,
    SNR_BIN_DB,
    SNR_BIN_ORIGIN_DB,
    by_factor,
    confusion_frame,
    confusion_plot_name,
    confusion_tables,
    plot_pd_vs_snr,
    plot_roc,
    score_column,
    score_summary,
    summarise,
    threshold_at_pfa,
    wilson_interval,
    write_report,
)
from .diagnose import CANONICAL, FAULTS, diagnose_signal
from .inputs import checked_frame, checked_workers
from .manifest import read_manifest
from .speeds import manifest_record

__all__ = [
    "BUILTIN_DETECTORS",
    "FAULT_CLASSES",
    "PFA_LEVELS",
    "CANONICAL",
    "DetectorOutput",
    "load_callable",
    "run_bench",
    "summarise",
    "score_summary",
    "by_factor",
    "confusion_tables",
    "confusion_frame",
    "confusion_plot_name",
    "CLASS_ORDER",
    "wilson_interval",
    "threshold_at_pfa",
    "plot_roc",
    "plot_pd_vs_snr",
    "write_report",
]

#: Built-in detectors, in the order of the outputs.
BUILTIN_DETECTORS = (
    "envelope",
    "fixed_band_ses",
    "cpw_ses",
    "spectral_kurtosis",
    "kurtosis",
    "crest_factor",
)
#: The columns the benchmark reads of a dataset's signals (the factors it breaks figures
#: down by are read where present).
BENCH_COLUMNS = ("id", "signal", "fs_hz", "rpm", "bearing", "label")
#: Nominal labels of the fault-blind statistics (the ROC and Pd use the scores, not these):
#: spectral kurtosis above 1, kurtosis above 4 (Gaussian: 0 and 3), crest factor above 6.
BLIND_LIMITS = {"spectral_kurtosis": 1.0, "kurtosis": 4.0, "crest_factor": 6.0}
#: Nominal line threshold of the envelope detectors' labels [dB] (as the rule detector's).
ENVELOPE_LABEL_DB = 10.0


def load_from_sensor_deg(load_angle_rad: float, direction: str) -> float:
    """Angle between the radial load's line and the sensor's axis [deg], 0 to 90.

    0: the sensor looks along the load (the recipes' default); 90: across it.

    Parameters
    ----------
    load_angle_rad : float
        The load's direction from the x axis [rad] (the dataset's ``load_angle_rad``).
    direction : {"x", "y"}
        The sensor's axis.

    Returns
    -------
    float
        The angle [deg].

    Examples
    --------
    >>> round(load_from_sensor_deg(-math.pi / 2, "y"), 6), round(load_from_sensor_deg(0.0, "y"), 6)
    (0.0, 90.0)
    """
    along = math.sin(load_angle_rad) if direction == "y" else math.cos(load_angle_rad)
    return math.degrees(math.acos(min(1.0, abs(along))))


@dataclass(frozen=True)
class DetectorOutput:
    """A detector's answer on one signal: a label and one score per fault (larger: likelier)."""

    label: str
    scores: dict[str, float]


def load_callable(spec: str) -> Callable:
    """Import ``module:function``.

    Parameters
    ----------
    spec : str
        ``module:function`` (``cmtool bench --detector``).

    Returns
    -------
    callable
        The function.

    Raises
    ------
    ValueError
        When ``spec`` has no colon, or the module or the function cannot be found.
    """
    if ":" not in spec:
        raise ValueError(f"--detector {spec!r}: expected module:function")
    module, name = spec.split(":", 1)
    try:
        imported = importlib.import_module(module)
    except ImportError as err:
        raise ValueError(f"--detector {spec!r}: cannot import {module!r} ({err})") from None
    fn = getattr(imported, name, None)
    if not callable(fn):
        raise ValueError(f"--detector {spec!r}: {name!r} is not a callable of {module!r}")
    return fn


def _takes_geometry(fn: Callable) -> bool:
    """Whether a plug-in accepts a ``geometry`` keyword (then it gets the BearingGeometry)."""
    import inspect

    try:
        parameters = inspect.signature(fn).parameters
    except (TypeError, ValueError):  # a builtin without a signature
        return False
    return "geometry" in parameters or any(
        p.kind is inspect.Parameter.VAR_KEYWORD for p in parameters.values()
    )


def _as_output(value: object, spec: str, signal_id: object = None) -> DetectorOutput:
    """A plug-in's return value as a DetectorOutput (the contract in the module docstring).

    Raises
    ------
    ValueError
        The value breaks the contract: a label not among healthy and the three faults, a
        mapping without ``label`` or ``scores``, a score that is missing, not a number or not
        finite; the message names the detector, the signal and what it returned.
    """
    if isinstance(value, DetectorOutput):
        return value
    where = f"detector {spec}" + ("" if signal_id is None else f" on signal {signal_id!r}")
    labels = ("healthy", *FAULT_CLASSES)

    def label_of(raw: object) -> str:
        label = CANONICAL.get(str(raw).lower()) if isinstance(raw, str) else None
        if label not in labels:
            raise ValueError(
                f"{where} returned the label {raw!r}; a label is one of {', '.join(labels)}"
            )
        return label

    if isinstance(value, Mapping):
        if "label" not in value or "scores" not in value:
            raise ValueError(f"{where}: a mapping must hold 'label' and 'scores'")
        label = label_of(value["label"])
        scores = {}
        for key, raw in dict(value["scores"]).items():
            try:
                score = float(raw)
            except (TypeError, ValueError):
                score = math.nan
            if not math.isfinite(score):
                raise ValueError(f"{where}: the score of {key!r} is {raw!r}, not a finite number")
            scores[CANONICAL.get(str(key).lower(), str(key))] = score
        missing = [f for f in FAULT_CLASSES if f not in scores]
        if missing:
            raise ValueError(f"{where}: scores miss {', '.join(missing)}")
        return DetectorOutput(label, scores)
    label = label_of(value)
    return DetectorOutput(label, {f: float(f == label) for f in FAULT_CLASSES})


def _labelled(scores: dict[str, float], limit: float) -> DetectorOutput:
    best = max(scores, key=scores.get)
    return DetectorOutput(best if scores[best] > limit else "healthy", scores)


def builtin_outputs(
    x: np.ndarray, fs: float, rpm: float, bearing: str | BearingGeometry, *, model: Any = None
) -> dict[str, DetectorOutput]:
    """Every built-in detector on one signal (``model``/``combined`` when a model is given).

    Parameters
    ----------
    x : ndarray
        The signal [U].
    fs : float
        Sample rate [Hz].
    rpm : float
        Shaft speed [rev/min].
    bearing : str or BearingGeometry
        Catalog name or geometry.
    model : dict, optional
        A model bundle (``cmtool train``).

    Returns
    -------
    dict of str to DetectorOutput
        ``envelope`` (the rule: margins over its threshold [dB]), ``fixed_band_ses`` and
        ``cpw_ses`` [dB], ``spectral_kurtosis``, ``kurtosis`` and ``crest_factor``, and with a
        model ``model`` and ``combined`` (probabilities).
    """
    from features.detectors import (
        cpw_envelope_scores,
        envelope_scores,
        spectral_kurtosis_score,
        time_scores,
    )

    geometry = catalog_bearing(bearing) if isinstance(bearing, str) else bearing
    freqs = characteristic_frequencies(geometry, rpm / 60.0)
    rates = {fault: getattr(freqs, key) for fault, key in FAULTS.items()}
    d = diagnose_signal(x, fs, rpm, geometry, model=model, waviness=False, severity=False)
    margins = {c["fault"]: c["evidence_db"] - d.threshold_db for c in d.candidates}
    out = {"envelope": DetectorOutput(d.rule_verdict["label"], margins)}
    ses = envelope_scores(x, fs, rates)
    out["fixed_band_ses"] = _labelled(ses, ENVELOPE_LABEL_DB)
    out["cpw_ses"] = _labelled(cpw_envelope_scores(x, fs, rates), ENVELOPE_LABEL_DB)
    blind = {"spectral_kurtosis": spectral_kurtosis_score(x, fs), **time_scores(x)}
    for name, value in blind.items():
        label = "fault" if value > BLIND_LIMITS[name] else "healthy"
        out[name] = DetectorOutput(label, dict.fromkeys(FAULT_CLASSES, value))
    if model is not None:
        probabilities = {
            CANONICAL.get(str(k), str(k)): float(v)
            for k, v in (d.model_verdict.get("probabilities") or {}).items()
        }
        label = CANONICAL.get(d.model_verdict["label"], d.model_verdict["label"])
        out["model"] = DetectorOutput(
            label, {f: probabilities.get(f, float(f == label)) for f in FAULT_CLASSES}
        )
        pooled = getattr(d, "probabilities", None) or {}
        out["combined"] = DetectorOutput(
            d.verdict, {f: float(pooled.get(f, float(f == d.verdict))) for f in FAULT_CLASSES}
        )
    return out


def _records(path: Path, bearing_default: str, allow_incomplete: bool = False):
    """Yield (id, x, fs, rpm, bearing, label, metadata) for every signal of a dataset."""
    if (path / "MANIFEST.csv").is_file():
        for entry in read_manifest(path, labelled=True, bearing_default=bearing_default):
            x, rpm = manifest_record(entry)  # the tacho's speed where the entry names one
            meta = {"bearing": entry.bearing, "fs_hz": entry.fs_hz, "rig": entry.rig}
            yield (
                entry.file,
                x,
                entry.fs_hz,
                rpm,
                entry.bearing_or_geometry,
                entry.label,
                meta,
            )
        return
    from .datasets import read_dataset

    frame = read_dataset(path, allow_incomplete=allow_incomplete)
    frame = checked_frame(frame, str(path), BENCH_COLUMNS, "cmtool generate")
    for _, row in frame.iterrows():
        meta = {c: row[c] for c in FACTORS if c in row and pd.notna(row[c])}
        meta["rig"] = row["bearing"]
        if pd.notna(row.get("load_angle_rad", math.nan)) and row.get("direction") in ("x", "y"):
            meta["load_from_sensor_deg"] = load_from_sensor_deg(
                float(row["load_angle_rad"]), row["direction"]
            )
        yield (
            row["id"],
            np.asarray(row["signal"], dtype=float),
            float(row["fs_hz"]),
            float(row["rpm"]),
            row["bearing"],
            CANONICAL.get(row["label"], row["label"]),
            meta,
        )


# one worker process's state (set by _init_worker)
_WORKER: dict = {}


def _init_worker(model, specs: tuple[str, ...]) -> None:
    _WORKER["model"] = model
    _WORKER["detectors"] = {spec: load_callable(spec) for spec in specs}


def _signal_rows_kept(record) -> tuple[list[dict], list]:
    """:func:`_signal_rows` in a worker process, with the warnings it raised."""
    return keeping_warnings(_signal_rows, record)


def _signal_rows(record) -> list[dict]:
    sid, x, fs, rpm, brg, label, meta = record
    outputs = builtin_outputs(x, fs, rpm, brg, model=_WORKER.get("model"))
    for spec, fn in _WORKER.get("detectors", {}).items():
        extra = {}
        if _takes_geometry(fn):  # a bearing not in the catalog has a name only its rows know
            extra["geometry"] = catalog_bearing(brg) if isinstance(brg, str) else brg
        try:
            value = fn(x, fs, rpm, getattr(brg, "name", brg), **extra)
        except Exception as err:  # the user's code: say which detector and signal, go no further
            raise ValueError(
                f"detector {spec} failed on signal {sid!r}: {type(err).__name__}: {err} (call "
                "it on that signal alone for the traceback)"
            ) from err
        outputs[spec] = _as_output(value, spec, sid)
    rows = []
    for name, output in outputs.items():
        row = {"id": sid, "detector": name, "label": label, "verdict": output.label, **meta}
        row.update({score_column(f): float(output.scores[f]) for f in FAULT_CLASSES})
        rows.append(row)
    return rows


def run_bench(
    path: str | Path,
    *,
    model: Any = None,
    detectors: Mapping[str, Callable] | Iterable[str] | None = None,
    bearing: str = "6205",
    progress: Callable[[int, int], None] | None = None,
    allow_incomplete: bool = False,
    workers: int = 1,
) -> pd.DataFrame:
    """Every detector on every signal: one row per (signal, detector).

    Parameters
    ----------
    path : str or Path
        A dataset folder or a folder of recordings with ``MANIFEST.csv``.
    model : Pipeline, optional
        A trained model (adds the ``model`` and ``combined`` detectors).
    detectors : mapping of name to callable, or iterable of ``module:function``, optional
        User detectors (the contract in the module docstring); with ``workers > 1`` give
        ``module:function`` strings (each worker imports them).
    bearing : str
        Bearing of manifest rows that do not say.
    progress : callable, optional
        Called with (signals done, signals in all).
    allow_incomplete : bool
        Read a dataset whose generation did not finish.
    workers : int
        Processes (each runs whole signals), at least 1.

    Returns
    -------
    DataFrame
        Columns ``id``, ``detector``, ``label``, ``verdict``, ``score_outer_race``,
        ``score_inner_race``, ``score_ball`` and the dataset's factors (``fault_snr_db``,
        ``rpm``, ``radial_load_n``, ``defect_length_m``, ..., ``bearing``, ``fs_hz``).
    """
    workers = checked_workers(workers)
    path = Path(path)
    records = list(_records(path, bearing, allow_incomplete))
    specs: tuple[str, ...] = ()
    if isinstance(detectors, Mapping):
        callables = dict(detectors)
    else:
        specs = tuple(detectors or ())
        callables = {}
    rows: list[dict] = []
    if workers > 1 and not callables:
        from concurrent.futures import ProcessPoolExecutor

        with ProcessPoolExecutor(
            max_workers=workers, initializer=_init_worker, initargs=(model, specs)
        ) as pool:
            chunk = max(1, min(32, len(records) // (8 * workers) or 1))
            relay = WarningRelay()  # a worker's warnings, here and once
            done = pool.map(_signal_rows_kept, records, chunksize=chunk)
            for i, (signal_rows, caught) in enumerate(done):
                relay(caught)
                rows.extend(signal_rows)
                if progress:
                    progress(i + 1, len(records))
    else:
        _init_worker(model, specs)
        _WORKER["detectors"].update(callables)
        try:
            for i, record in enumerate(records):
                rows.extend(_signal_rows(record))
                if progress:
                    progress(i + 1, len(records))
        finally:
            _WORKER.clear()
    return pd.DataFrame(rows)
