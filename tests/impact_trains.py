"""Test signals: a local fault's impact train ringing through one structural mode.

A spall is struck once per passage at a fault rate, each impact a little early or late (the
balls' random slip, 1-2 % of the period; Ho and Randall 2000), and each rings down through the
structure's mode: the signal envelope analysis is built for (docs/diagnosis.md). Several tests
build it; they share this so that each says only what it changes.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from scipy import signal as sp_signal


def ringing_impact_train(
    rate_hz: float,
    fs: float,
    n: int,
    rng: np.random.Generator,
    *,
    jitter: float = 0.01,
    strength: Callable[[np.ndarray], np.ndarray] | None = None,
    mode_hz: float = 3000.0,
    quality: float = 15.0,
) -> np.ndarray:
    """Impacts at ``rate_hz`` with random jitter, rung through one mode (no noise added).

    Parameters
    ----------
    rate_hz : float
        The impacts' mean rate [Hz] (a fault rate: BPFO, BPFI, ...).
    fs : float
        Sample rate [Hz].
    n : int
        Samples.
    rng : numpy.random.Generator
        Draws each impact's time offset, one normal draw per impact (a caller's later draws
        follow these).
    jitter : float
        Standard deviation of an impact's offset from its nominal time, as a fraction of the
        period (0.01: 1 % slip).
    strength : callable, optional
        Each impact's strength as a function of its time [s] (default 1: a fault in the load
        zone all the time, an outer race's).
    mode_hz, quality : float
        The ringing mode's frequency [Hz] and quality factor (``scipy.signal.iirpeak``).

    Returns
    -------
    numpy.ndarray
        ``n`` samples [arbitrary unit].
    """
    times = np.arange(0.0, n / fs, 1 / rate_hz)
    times = times + rng.normal(0.0, jitter / rate_hz, times.size)
    impacts = np.zeros(n)
    impacts[np.clip((times * fs).astype(int), 0, n - 1)] = (
        1.0 if strength is None else strength(times)
    )
    return sp_signal.lfilter(*sp_signal.iirpeak(mode_hz, quality, fs), impacts)
