"""The chirp-z transform on the unit circle, set up from its phases (stop 90).

:class:`ChirpZ` evaluates a record's transform at m equally spaced frequencies (Bluestein's
algorithm, as :class:`scipy.signal.CZT`) in O((n + m) log(n + m)): the harmonic families'
projections and sums of :mod:`features.separation` and the zero-padded spectrum's bins
around the shaft rate of :mod:`features.speed`.
"""

from __future__ import annotations

import numpy as np
from scipy import fft as sp_fft

__all__ = ["ChirpZ", "unit_phasor"]


def unit_phasor(turns: np.ndarray) -> np.ndarray:
    """exp(2 pi i turns), from the fraction of a turn (the whole turns dropped exactly).

    Parameters
    ----------
    turns : ndarray
        Phases [turns].

    Returns
    -------
    ndarray of complex
        The unit phasors.
    """
    return np.exp(2j * np.pi * (turns - np.round(turns)))


class ChirpZ:
    """The chirp-z transform on the unit circle (Bluestein), as :class:`scipy.signal.CZT`.

    ``X_j = sum_k x_k exp(-2 pi i a k) exp(2 pi i w j k)`` for j = 0 .. m - 1, the points
    ``exp(2 pi i (a + j w))``, with w and a in turns per sample. SciPy's class raises its
    complex w and a to a power at every sample (w^(k^2/2), a^-k), a complex logarithm and
    exponential each: setting a transform up took 8-12 ms for a 1 s record at 25.6 kHz, ten
    times as long as applying it (1.1 ms). Here the chirps come from their phases: 1.7-2.1
    ms, and the same sums to 1e-10 of their largest (tests/tests_features/test_separation.py,
    as SciPy's; the phase's rounding at k^2 / 2 ~ 3e8 turns x f0 / fs).

    Parameters
    ----------
    n : int
        Length of the records transformed [samples].
    m : int
        Number of points evaluated.
    w_turns : float
        Spacing of the points [turns per sample: frequency / fs].
    a_turns : float
        The first point [turns per sample].
    """

    def __init__(self, n: int, m: int, w_turns: float, a_turns: float) -> None:
        k = np.arange(max(m, n), dtype=float)
        half_square = 0.5 * k * k  # exact below 2^53
        chirp = unit_phasor(w_turns * half_square)  # w^(k^2 / 2)
        self._pre = unit_phasor(w_turns * half_square[:n] - a_turns * k[:n])  # a^-k w^(k^2/2)
        self._nfft = sp_fft.next_fast_len(n + m - 1)
        inverse = np.conj(np.concatenate((chirp[n - 1 : 0 : -1], chirp[:m])))  # w^-(k^2/2)
        self._filter = sp_fft.fft(inverse, self._nfft)
        self._post = chirp[:m]
        self._take = slice(n - 1, n + m - 1)
        self.n, self.m = n, m

    def __call__(self, x: np.ndarray) -> np.ndarray:
        """The transform of ``x`` (length ``n``) at the ``m`` points."""
        if x.shape[-1] != self.n:
            raise ValueError(f"the transform is set up for {self.n} samples, not {x.shape[-1]}")
        y = sp_fft.ifft(self._filter * sp_fft.fft(x * self._pre, self._nfft))
        return y[..., self._take] * self._post
