"""Input checks shared by the feature functions (messages name parameter, value and range)."""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

#: Largest sample magnitude a record may hold: the features take samples to the fourth power
#: (kurtosis, spectral kurtosis) and sum them, which overflows float64 (1.8e308) beyond about
#: 1e75 for a record of a billion samples; 1e60 leaves room. Any vibration record in any unit
#: lies far under it: a larger value is a wrong unit or a corrupt file.
MAX_ABS_SAMPLE = 1e60


class FeatureError(ValueError):
    """Bad input to a feature function (the message names the parameter and the valid range)."""


def check_signal(x: object, *, name: str = "x", min_length: int = 2, axis: int = -1) -> np.ndarray:
    """Return ``x`` as float64 with at least ``min_length`` finite samples on its last axis.

    A complex ``x`` is refused (its imaginary part would be dropped without a word), and so is
    one with a sample larger than ``MAX_ABS_SAMPLE`` in magnitude.
    """
    if np.iscomplexobj(x):
        raise FeatureError(
            f"{name} is complex (dtype {np.asarray(x).dtype}); a vibration record is real: "
            "give its real part (an analytic signal's envelope is its absolute value)"
        )
    arr = np.asarray(x, dtype=np.float64)
    if arr.ndim == 0:
        raise FeatureError(
            f"{name} is a scalar; expected a signal with at least {min_length} samples"
        )
    if arr.shape[axis] < min_length:
        layout = (
            "" if arr.ndim == 1 else f" along its last axis (shape {arr.shape}: a signal a row)"
        )
        raise FeatureError(
            f"{name} has {arr.shape[axis]} samples{layout}; at least {min_length} are needed"
        )
    if not np.all(np.isfinite(arr)):
        bad = int(np.count_nonzero(~np.isfinite(arr)))
        raise FeatureError(f"{name} contains {bad} non-finite values (NaN or inf)")
    largest = max(float(arr.max()), -float(arr.min())) if arr.size else 0.0  # no |x| copy
    if largest > MAX_ABS_SAMPLE:
        raise FeatureError(
            f"{name} holds a sample of magnitude {largest:.3g}, outside the allowed range "
            f"|{name}| <= {MAX_ABS_SAMPLE:g} (fourth powers of it overflow float64): a wrong "
            "unit or a corrupt file"
        )
    return arr


def check_record(x: object, *, function: str, name: str = "x", min_length: int = 2) -> np.ndarray:
    """:func:`check_signal` for a function that takes one record: ``x`` must be 1-D."""
    arr = check_signal(x, name=name, min_length=min_length)
    if arr.ndim != 1:
        raise FeatureError(
            f"{name} has shape {arr.shape}; {function} takes a 1-D signal (one record)"
        )
    return arr


def check_fs(fs: object) -> float:
    """Return the sample rate [Hz] as a positive finite float."""
    try:
        v = float(fs)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise FeatureError(f"fs = {fs!r} is not a number; allowed range (0, inf) Hz") from None
    if not math.isfinite(v) or v <= 0:
        raise FeatureError(f"fs = {fs!r} Hz is outside the allowed range (0, inf) Hz")
    return v


def check_positive(name: str, value: object, *, unit: str = "") -> float:
    """Return ``value`` as a positive finite float."""
    try:
        v = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise FeatureError(f"{name} = {value!r} is not a number") from None
    if not math.isfinite(v) or v <= 0:
        raise FeatureError(
            f"{name} = {value!r} {unit} is outside the allowed range (0, inf) {unit}"
        )
    return v


def check_count(name: str, value: object, *, low: int = 1, high: int | None = None) -> int:
    """Return ``value`` as an int in ``[low, high]`` (a float or a bool is refused)."""
    allowed = f"[{low}, {'inf' if high is None else high}]"
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise FeatureError(f"{name} = {value!r} is not an integer; allowed range {allowed}")
    v = int(value)
    if v < low or (high is not None and v > high):
        raise FeatureError(f"{name} = {v} is outside the allowed range {allowed}")
    return v


def check_whole(name: str, value: object, *, low: int = 1, high: int | None = None) -> int:
    """:func:`check_count`, a float taken too if it is a whole number (``5.0``)."""
    if isinstance(value, (float, np.floating)):
        if not (math.isfinite(value) and float(value).is_integer()):
            allowed = f"[{low}, {'inf' if high is None else high}]"
            raise FeatureError(f"{name} = {value!r} is not a whole number; allowed range {allowed}")
        value = int(value)
    return check_count(name, value, low=low, high=high)


def check_band(band: object, fs: float) -> tuple[float, float]:
    """Return a (low, high) band [Hz] with 0 <= low < high <= fs/2."""
    try:
        low, high = (float(b) for b in band)  # type: ignore[union-attr]
    except (TypeError, ValueError):
        raise FeatureError(f"band = {band!r} is not a (low, high) pair in Hz") from None
    if not (0.0 <= low < high <= fs / 2):
        raise FeatureError(
            f"band = ({low:g}, {high:g}) Hz is outside the allowed range: 0 <= low < high <= "
            f"fs/2 = {fs / 2:g} Hz"
        )
    return low, high


def check_rates(
    name: str, rates: object, *, fs: float | None = None, allow_empty: bool = True
) -> dict[str, float]:
    """Return a mapping of names to rates [Hz] as floats, each positive and finite.

    Parameters
    ----------
    name : str
        The parameter's name in messages (``fault_frequencies``, ``rates``).
    rates : mapping of str to float
        The rates [Hz].
    fs : float, optional
        Sample rate [Hz]: when given, each rate must lie under fs/2 (a spectrum of the record
        holds nothing above it).
    allow_empty : bool
        Whether an empty mapping is allowed.

    Returns
    -------
    dict of str to float
        The rates [Hz], in the mapping's order.
    """
    if not isinstance(rates, Mapping):
        raise FeatureError(
            f"{name} = {rates!r:.80} is not a mapping of names to rates in Hz "
            "(e.g. {'bpfo': 107.4, 'bpfi': 162.2})"
        )
    if not rates and not allow_empty:
        raise FeatureError(f"{name} is empty: give at least one rate in Hz")
    out = {}
    for key, value in rates.items():
        rate = check_positive(f"{name}[{key!r}]", value, unit="Hz")
        if fs is not None and rate >= fs / 2:
            raise FeatureError(
                f"{name}[{key!r}] = {rate:g} Hz is outside the allowed range (0, fs/2 = "
                f"{fs / 2:g}) Hz"
            )
        out[key] = rate
    return out
