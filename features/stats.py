"""Time-domain statistics of a vibration signal."""

from __future__ import annotations

import numpy as np

from ._validate import check_signal

__all__ = ["time_statistics", "TIME_STATISTICS"]

#: Names and units (U: the signal's unit) of :func:`time_statistics`.
TIME_STATISTICS = {
    "rms": "U",
    "peak": "U",
    "peak_to_peak": "U",
    "crest_factor": "-",
    "kurtosis": "-",
    "skewness": "-",
    "shape_factor": "-",
    "impulse_factor": "-",
    "clearance_factor": "-",
}


def time_statistics(x: np.ndarray, *, axis: int = -1) -> dict[str, np.ndarray | float]:
    """RMS, peak, crest factor, kurtosis, skewness, shape, impulse and clearance factors.

    The mean is removed first. Kurtosis is the normalised fourth moment (3 for a Gaussian, 1.5
    for a sine), the convention of condition monitoring.

    Parameters
    ----------
    x : array_like
        Signal [U].
    axis : int
        Time axis.

    Returns
    -------
    dict
        Keys of ``TIME_STATISTICS``; floats for a 1-D signal, arrays otherwise.
    """
    x = check_signal(x, min_length=2)
    x = x - x.mean(axis=axis, keepdims=True)
    a = np.abs(x)
    x2 = x * x  # the moments from one square (x**3 and x**4 would call the general power)
    m2 = np.mean(x2, axis=axis)
    rms = np.sqrt(m2)
    peak = a.max(axis=axis)
    mean_abs = a.mean(axis=axis)
    tiny = np.finfo(float).tiny
    safe_m2 = np.maximum(m2, tiny)
    out = {
        "rms": rms,
        "peak": peak,
        "peak_to_peak": np.ptp(x, axis=axis),
        "crest_factor": peak / np.maximum(rms, tiny),
        # 0 for a constant signal (tiny**2 underflows to 0: 0 / 0), as crest factor and the rest
        "kurtosis": _ratio(np.mean(x2 * x2, axis=axis), safe_m2**2, m2 > 0),
        "skewness": _ratio(np.mean(x2 * x, axis=axis), safe_m2**1.5, m2 > 0),
        "shape_factor": rms / np.maximum(mean_abs, tiny),
        "impulse_factor": peak / np.maximum(mean_abs, tiny),
        "clearance_factor": peak / np.maximum(np.mean(np.sqrt(a), axis=axis) ** 2, tiny),
    }
    if x.ndim == 1:
        return {k: float(v) for k, v in out.items()}
    return out


def _ratio(numerator: np.ndarray, denominator: np.ndarray, where: np.ndarray) -> np.ndarray:
    """``numerator / denominator`` where ``where``, else 0."""
    return np.divide(numerator, denominator, out=np.zeros(np.shape(numerator)), where=where)
