"""Classical fault-detection statistics: one continuous score per fault rate, or per signal.

The reference detectors a benchmark compares against (Randall and Antoni 2011; Borghesani
et al. 2013 for cepstral pre-whitening; Antoni 2006 for the kurtogram):

- :func:`envelope_scores`: the squared envelope spectrum (SES) of a fixed band, the lines at
  each fault rate and its harmonics against the SES's local median;
- the same after cepstral pre-whitening over the whole band (``prewhitening=True``,
  ``band=None``): :func:`cpw_envelope_scores`;
- :func:`spectral_kurtosis_score`: the largest spectral kurtosis of the fast kurtogram, a
  statistic of impulsiveness that names no fault;
- :func:`time_scores`: kurtosis and crest factor of the raw signal.

Scores grow with the evidence of a fault; thresholds belong to whoever uses them (a benchmark
sets them on healthy signals for a false-alarm rate).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from ._validate import FeatureError, check_count, check_fs, check_rates, check_record
from .envelope import envelope_spectrum, kurtogram
from .evidence import slip_line

__all__ = [
    "FIXED_BAND",
    "SES_HARMONICS",
    "envelope_scores",
    "cpw_envelope_scores",
    "spectral_kurtosis_score",
    "time_scores",
]

#: The fixed demodulation band of :func:`envelope_scores`, as fractions of fs: from fs/8 (above
#: the shaft, gear and structural lines of the low range) to 3 fs/8 (below the anti-alias
#: filter's roll-off at fs/2.56); where the high-frequency resonances of a machine ring.
FIXED_BAND = (1.0 / 8.0, 3.0 / 8.0)
#: Harmonics of each fault rate whose SES lines make a score.
SES_HARMONICS = 3


def _ses_line_scores(
    freqs: np.ndarray, amp: np.ndarray, rates: Mapping[str, float], harmonics: int
) -> dict[str, float]:
    """Per rate: the mean power of its first harmonics' lines over the local floor [dB].

    Each line is searched within the slip of real bearings (:func:`features.slip_line`); a
    harmonic beyond the spectrum counts as 0 dB (no evidence).
    """
    harmonics = check_count("harmonics", harmonics)
    scores = {}
    for key, rate in rates.items():
        rate = float(rate)
        if not rate > 0 or not math.isfinite(rate):
            raise FeatureError(f"fault_frequencies[{key!r}] = {rate!r} must be a positive number")
        powers = [10 ** (slip_line(freqs, amp, k * rate)[0] / 10) for k in range(1, harmonics + 1)]
        scores[key] = 10 * math.log10(float(np.mean(powers)))
    return scores


def envelope_scores(
    x: np.ndarray,
    fs: float,
    fault_frequencies: Mapping[str, float],
    *,
    band: tuple[float, float] | None = None,
    prewhitening: bool = False,
    harmonics: int = SES_HARMONICS,
) -> dict[str, float]:
    """Squared-envelope-spectrum scores of fault rates in a fixed band.

    Parameters
    ----------
    x : array_like, 1-D
        Signal [U].
    fs : float
        Sample rate [Hz].
    fault_frequencies : mapping of str to float
        Fault rates [Hz], e.g. ``{"bpfo": 107.4, "bpfi": 162.2, "two_bsf": 141.2}``.
    band : (float, float), optional
        Demodulation band [Hz]; default ``FIXED_BAND`` x fs.
    prewhitening : bool
        Cepstral pre-whitening before demodulation.
    harmonics : int
        Harmonics of each rate in the score.

    Returns
    -------
    dict of str to float
        Per rate, the mean power ratio of its first ``harmonics`` SES lines over the SES's
        local median [dB]; about 0-3 dB without a fault (the median of a noise spectrum's
        neighbourhood sits below its mean), growing with the fault's periodic impacts.

    Examples
    --------
    >>> import numpy as np
    >>> fs = 12000.0; t = np.arange(24000) / fs
    >>> rng = np.random.default_rng(0)
    >>> impacts = (np.sin(2 * np.pi * 100.0 * t) > 0.995) * 1.0
    >>> ringing = np.convolve(impacts, np.exp(-np.arange(60) / 10) * np.sin(np.arange(60)))
    >>> x = ringing[: t.size] + 0.1 * rng.standard_normal(t.size)
    >>> s = envelope_scores(x, fs, {"bpfo": 100.0, "bpfi": 137.0})
    >>> s["bpfo"] > 20 > s["bpfi"]
    True
    """
    x = check_record(x, function="envelope_scores", min_length=64)
    fs = check_fs(fs)
    fault_frequencies = check_rates("fault_frequencies", fault_frequencies, fs=fs)
    if band is None:
        band = (FIXED_BAND[0] * fs, FIXED_BAND[1] * fs)
    freqs, amp = envelope_spectrum(x, fs, band=band, method="squared", prewhitening=prewhitening)
    return _ses_line_scores(freqs, amp, fault_frequencies, harmonics)


def cpw_envelope_scores(
    x: np.ndarray, fs: float, fault_frequencies: Mapping[str, float], *, harmonics: int = 3
) -> dict[str, float]:
    """Cepstral pre-whitening, then the squared envelope spectrum of the whole band.

    Pre-whitening (unit magnitude spectrum, phase kept) removes the discrete lines and the
    transfer path's colour at once, so no band has to be chosen (Borghesani et al. 2013).
    Scores as :func:`envelope_scores`.

    Parameters
    ----------
    x : array_like, 1-D
        Signal [U].
    fs : float
        Sample rate [Hz].
    fault_frequencies : mapping of str to float
        Fault rates [Hz], e.g. ``{"bpfo": 107.4, "bpfi": 162.2}``.
    harmonics : int
        Harmonics of each rate in the score.

    Returns
    -------
    dict of str to float
        Per rate, the mean power ratio of its first ``harmonics`` lines in the pre-whitened
        signal's squared envelope spectrum over the spectrum's local median [dB].

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> s = cpw_envelope_scores(rng.standard_normal(24000), 12000.0, {"bpfo": 107.0})
    >>> bool(abs(s["bpfo"]) < 10)
    True
    """
    fs = check_fs(fs)
    return envelope_scores(
        x, fs, fault_frequencies, band=(0.0, fs / 2), prewhitening=True, harmonics=harmonics
    )


def spectral_kurtosis_score(x: np.ndarray, fs: float, *, nlevel: int = 4) -> float:
    """The largest spectral kurtosis of the fast kurtogram (0 for Gaussian noise).

    Parameters
    ----------
    x : array_like, 1-D
        Signal [U].
    fs : float
        Sample rate [Hz].
    nlevel : int
        Levels of the kurtogram (1 .. 12; :func:`features.kurtogram`).

    Returns
    -------
    float
        The spectral kurtosis of the kurtogram's selected band (dimensionless).

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> bool(spectral_kurtosis_score(rng.standard_normal(24000), 12000.0) < 1)
    True
    """
    return float(kurtogram(x, fs, nlevel=nlevel).kurtosis)


def time_scores(x: np.ndarray) -> dict[str, float]:
    """Kurtosis (3 for Gaussian noise) and crest factor (peak over RMS) of the raw signal.

    Parameters
    ----------
    x : array_like, 1-D
        Signal [U], at least 4 samples.

    Returns
    -------
    dict of str to float
        ``kurtosis`` and ``crest_factor`` of the signal less its mean (dimensionless); both 0
        for a constant signal.

    Examples
    --------
    >>> import numpy as np
    >>> s = time_scores(np.sin(np.linspace(0, 200 * np.pi, 10000)))
    >>> round(s["kurtosis"], 2), round(s["crest_factor"], 3)
    (1.5, 1.414)
    """
    x = check_record(x, function="time_scores", min_length=4)
    y = x - x.mean()
    rms = float(np.sqrt(np.mean(y**2)))
    if rms == 0:
        return {"kurtosis": 0.0, "crest_factor": 0.0}
    return {
        "kurtosis": float(np.mean(y**4) / rms**4),
        "crest_factor": float(np.max(np.abs(y)) / rms),
    }
