"""Window arrays, computed once per (window, length).

Spectra of many equal-length records otherwise spend a tenth of their time rebuilding the same
Hann and Tukey tapers.
"""

from __future__ import annotations

import functools

import numpy as np
from scipy import signal as sp_signal


@functools.lru_cache(maxsize=64)
def get_window(window: str | tuple, n: int) -> np.ndarray:
    """``scipy.signal.get_window(window, n)``, cached and read-only."""
    w = sp_signal.get_window(window, n)
    w.flags.writeable = False
    return w


@functools.lru_cache(maxsize=64)
def tukey(n: int, alpha: float) -> np.ndarray:
    """``scipy.signal.windows.tukey(n, alpha)``, cached and read-only."""
    w = sp_signal.windows.tukey(n, alpha)
    w.flags.writeable = False
    return w


@functools.lru_cache(maxsize=64)
def hanning(n: int) -> np.ndarray:
    """``numpy.hanning(n)``, cached and read-only."""
    w = np.hanning(n)
    w.flags.writeable = False
    return w
