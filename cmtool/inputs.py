"""The checks :func:`cmtool.diagnose.diagnose_signal` makes of what a Python caller gives it.

The command line checks its own options; these name the Python parameters, their values and
what is allowed, before any work.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
import pandas as pd

from generators import BearingGeometry, ParameterError, bearing

__all__ = [
    "checked_record",
    "checked_rate",
    "checked_geometry",
    "checked_model",
    "checked_frame",
    "check_record_lengths",
]


def checked_record(x: Any, name: str = "x") -> np.ndarray:
    """One record as a 1-D float array (a single row or column is taken as one record).

    Parameters
    ----------
    x : array_like
        The record [its unit].
    name : str
        Its name in an error message.

    Returns
    -------
    ndarray
        1-D, float.

    Raises
    ------
    ValueError
        Not numbers, empty, or several records (the message gives the shape).
    """
    try:
        arr = np.asarray(x, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} is not an array of numbers") from None
    if arr.ndim > 1 and sum(n > 1 for n in arr.shape) <= 1:
        arr = arr.ravel()  # one row or one column
    if arr.ndim != 1:
        raise ValueError(
            f"{name} has shape {arr.shape}: give one record (1-D); for one channel of a file "
            "use cmtool.read_recording(path, channel=N)"
        )
    if arr.size == 0:
        raise ValueError(f"{name} is empty: nothing to diagnose")
    return arr


def checked_rate(fs: Any, name: str = "fs") -> float:
    """A sample rate [Hz]: a finite number above 0.

    Parameters
    ----------
    fs : object
        The rate given [Hz].
    name : str
        Its name in an error message.

    Returns
    -------
    float

    Raises
    ------
    generators.ParameterError
        Not a number, not finite, or not above 0 (naming it and the range).
    """
    try:
        value = float(fs)
    except (TypeError, ValueError):
        raise ParameterError(
            f"{name} = {fs!r} is not a number; allowed range (0, inf) Hz"
        ) from None
    if not (math.isfinite(value) and value > 0.0):
        raise ParameterError(f"{name} = {fs!r} Hz is outside the allowed range (0, inf) Hz")
    return value


def checked_geometry(geometry: Any) -> BearingGeometry:
    """A catalog name or a :class:`generators.BearingGeometry`, as the geometry.

    Parameters
    ----------
    geometry : str or BearingGeometry
        A catalog name (``generators.bearing``) or a geometry.

    Returns
    -------
    BearingGeometry

    Raises
    ------
    generators.ParameterError
        Neither, or a name not in the catalog.
    """
    if isinstance(geometry, BearingGeometry):
        return geometry
    if isinstance(geometry, str):
        return bearing(geometry)
    raise ParameterError(
        f"geometry = {geometry!r} is neither a catalog name (a str such as '6205') nor a "
        "generators.BearingGeometry"
    )


def checked_model(model: Any) -> Any:
    """A model: a bundle of ``cmtool train`` (``cmtool.classifier.load_model``), or None.

    A fitted scikit-learn pipeline is taken too.

    Parameters
    ----------
    model : dict, fitted pipeline or None
        The model given.

    Returns
    -------
    dict, fitted pipeline or None
        ``model``, checked.

    Raises
    ------
    ValueError
        A dict without a ``pipeline``, or an object that cannot predict.
    """
    if model is None:
        return None
    if isinstance(model, dict):
        if "pipeline" not in model:
            raise ValueError(
                f"model has no 'pipeline' (keys {sorted(model)[:6]}): give the bundle "
                "cmtool.classifier.load_model returns for a file of `cmtool train`"
            )
        return model
    if not (hasattr(model, "predict_proba") or hasattr(model, "predict")):
        raise ValueError(
            f"model = {type(model).__name__} is not a model bundle or a fitted pipeline"
        )
    return model


def checked_context_extra(extra: Any, model: Any) -> dict:
    """Further context columns for a model (``diagnose_signal``'s ``context_extra``), checked.

    The columns the rule and a cmtool model share (the sample rate and the bearing's rates)
    come from ``fs``, the speed and the bearing, and are never replaced; a cmtool model's
    features read no other column, so for one any key would be silently ignored and is
    refused. A pipeline of one's own may read further columns: they are passed to it.

    Parameters
    ----------
    extra : mapping or None
        Column name -> value.
    model : dict, fitted pipeline or None
        The model (:func:`checked_model`).

    Returns
    -------
    dict
        ``extra`` as a dict (empty for None).

    Raises
    ------
    ValueError
        Not a mapping; given without a model; a key that would replace a computed column; a
        key a cmtool model does not read.
    """
    from features import CONTEXT_COLUMNS, FeatureExtractor

    if extra is None:
        return {}
    if not hasattr(extra, "keys"):
        raise ValueError(f"context_extra = {extra!r} is not a mapping of column name to value")
    extra = dict(extra)
    if not extra:
        return extra
    if model is None:
        raise ValueError(
            f"context_extra = {extra!r} gives a model further columns, and no model is given"
        )
    computed = {"signal", "bsf_hz", *CONTEXT_COLUMNS.values()}
    for key in sorted(map(str, extra)):
        if key in computed:
            raise ValueError(
                f"context_extra[{key!r}] would replace a column computed from fs, rpm and the "
                "bearing (the rule's rates and the model's must be the same): give those instead"
            )
    pipeline = model["pipeline"] if isinstance(model, dict) else model
    steps = getattr(pipeline, "steps", None)
    if steps and isinstance(steps[0][1], FeatureExtractor):
        raise ValueError(
            f"context_extra[{sorted(map(str, extra))[0]!r}]: a cmtool model's features read no "
            f"column but the signal and {', '.join(sorted(computed - {'signal'}))}, all "
            "computed here; context_extra is for a pipeline of one's own that reads more"
        )
    return extra


def checked_workers(workers: Any, name: str = "workers") -> int:
    """A count of worker processes or threads: an integer of at least 1.

    Parameters
    ----------
    workers : object
        The count given.
    name : str
        Its name in an error message.

    Returns
    -------
    int

    Raises
    ------
    generators.ParameterError
        Not an integer, or below 1 (naming it and the range).
    """
    from generators.params import check_int

    return check_int(name, workers, low=1)


def checked_frame(frame: Any, name: str, columns: Sequence[str], source: str) -> Any:
    """A table of signals with the columns a function reads.

    Parameters
    ----------
    frame : object
        The table given.
    name : str
        Its name in an error message.
    columns : sequence of str
        The columns it must have.
    source : str
        What makes such a table, for the message (``cmtool.datasets.read_dataset``).

    Returns
    -------
    pandas.DataFrame
        ``frame``.

    Raises
    ------
    ValueError
        When ``frame`` is not a table, lacks a column (naming every one missing), or, where
        ``columns`` holds ``signal``, one of its signals holds a NaN or an infinity (named).
    """
    if not hasattr(frame, "columns") or not hasattr(frame, "iloc"):
        raise ValueError(f"{name} is a {type(frame).__name__}, not a DataFrame ({source})")
    missing = [c for c in columns if c not in frame.columns]
    if missing:
        noun = "column" if len(missing) == 1 else "columns"
        raise ValueError(
            f"{name} has no {noun} {', '.join(map(repr, missing))} ({source} gives every one)"
        )
    if "signal" in columns:  # one bad signal named, rather than a feature's error about "x"
        for position, signal in enumerate(frame["signal"]):
            values = np.asarray(signal, dtype=float)
            bad = values.size - int(np.count_nonzero(np.isfinite(values)))
            if bad:
                raise ValueError(
                    f"{name}: {_which_signal(frame, position)} has {bad} non-finite values "
                    f"(NaN or inf) of {values.size}: mend or leave out that signal"
                )
    return frame


#: The columns a signal's length is judged by (:func:`check_record_lengths`).
_LENGTH_COLUMNS = ("signal", "fs_hz", "bpfo_hz", "bpfi_hz", "two_bsf_hz")


def check_record_lengths(frame: pd.DataFrame, name: str = "frame") -> None:
    """Refuse a table holding a signal too short to tell its bearing's fault rates apart.

    The diagnosis's own bound (``cmtool.rule.MIN_RATE_PERIODS`` periods of the slowest of
    BPFO, BPFI and 2 x BSF), applied to every signal of a table the features of a model are
    computed on, where the table has the signals' rates [Hz] (a dataset has).

    Parameters
    ----------
    frame : pandas.DataFrame
        Signals with ``fs_hz`` [Hz] and ``bpfo_hz``, ``bpfi_hz``, ``two_bsf_hz`` [Hz].
    name : str
        What to call the table in the error.

    Raises
    ------
    ValueError
        Naming the first signal too short (its id and row), its length and the one needed.
    """
    from .rule import MIN_RATE_PERIODS

    if not set(_LENGTH_COLUMNS) <= set(frame.columns) or not len(frame):
        return
    samples = frame["signal"].map(len).to_numpy(dtype=float)
    fs = frame["fs_hz"].to_numpy(dtype=float)
    slowest = frame[["bpfo_hz", "bpfi_hz", "two_bsf_hz"]].min(axis=1).to_numpy(dtype=float)
    short = np.flatnonzero(samples / fs * slowest < MIN_RATE_PERIODS)
    if short.size:
        row = int(short[0])
        needed = MIN_RATE_PERIODS / slowest[row]
        raise ValueError(
            f"{name}: {_which_signal(frame, row)} is {samples[row] / fs[row]:.3g} s long "
            f"({samples[row]:.0f} samples at {fs[row]:g} Hz; {short.size} of {len(frame)} "
            f"signals as short); telling the fault rates apart needs at least "
            f"{MIN_RATE_PERIODS} periods of the slowest ({slowest[row]:.1f} Hz): "
            f"{needed:.3g} s"
        )


def _which_signal(frame: pd.DataFrame, row: int) -> str:
    """A signal of a table as an error names it: by its id, else its recording, and row."""
    if "id" in frame.columns:
        return f"signal {frame['id'].iloc[row]!r} (row {row})"
    if "group" in frame.columns:  # a segment of a recording (cmtool.realism)
        return f"a segment of {frame['group'].iloc[row]!r} (row {row})"
    return f"the signal at row {row}"
