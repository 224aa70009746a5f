"""False-alarm statistics of spectral lines over Gaussian noise.

A line in an envelope or plain spectrum is the largest of a few searched bins over the median
of its neighbourhood. For Gaussian noise the bins are Rayleigh distributed, and the floor's
median is itself a random variable: :func:`detection_threshold_db` gives the ratio that noise
exceeds with a given probability when a line is searched in N bands (union bound),
:func:`line_false_alarm` and :func:`plain_line_false_alarm` the probability of a given ratio,
and :func:`ratio_for_false_alarm` puts a probability back on the threshold's dB scale. Moved
out of :mod:`features.separation` unchanged in stop 56; ``features.separation`` still exports
every name.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from ._validate import FeatureError, check_whole

__all__ = [
    "CALIBRATION_DB",
    "FALSE_ALARM",
    "FLOOR_BINS",
    "SEARCHED_BINS",
    "detection_threshold_db",
    "line_false_alarm",
    "plain_line_false_alarm",
    "ratio_for_false_alarm",
]

#: False-alarm probability per fault and record that the detection threshold keeps.
FALSE_ALARM = 1e-4
#: Bins searched per line of the envelope spectrum (the line's width and the slip of real
#: bearings): the multiplicity in the threshold.
SEARCHED_BINS = 5
#: Measured on Gaussian noise (``benchmarks/calibrate_detection.py``): the Rayleigh model of
#: these bins, with the floor's median as a random variable, puts false alarms about four
#: times too low (the bins of a Hann-windowed envelope spectrum are neither independent nor quite
#: Rayleigh); 1 dB more brings the measured rate to the nominal one at 1e-2 and 1e-3.
CALIBRATION_DB = 1.0
#: A line's floor is the median of the envelope spectrum within +/- 10 % of it, and at least
#: this many bins each side: with fewer, the median's own scatter makes false alarms.
FLOOR_BINS = 50
#: Median of a Rayleigh variable over its scale.
_RAYLEIGH_MEDIAN = math.sqrt(2.0 * math.log(2.0))


def _independent_floor_bins(floor_bins: int) -> int:
    """Independent values among a floor's bins: about half of them, at least 3.

    A Hann-windowed spectrum's neighbouring bins are correlated (equivalent noise bandwidth
    1.5 bins).
    """
    return max(3, int(floor_bins) // 2)


@functools.lru_cache(maxsize=64)
def _median_density(floor_bins: int) -> tuple[np.ndarray, np.ndarray]:
    """Grid x [sigma] and the density of the median of ``floor_bins`` Rayleigh bins on it."""
    x = np.linspace(1e-6, 8.0, 4001)
    cdf = -np.expm1(-0.5 * x * x)
    pdf = x * np.exp(-0.5 * x * x)
    r = (floor_bins + 1) // 2
    log_norm = math.lgamma(floor_bins + 1) - math.lgamma(r) - math.lgamma(floor_bins - r + 1)
    with np.errstate(divide="ignore"):
        log_density = (
            log_norm + (r - 1) * np.log(cdf) + (floor_bins - r) * np.log1p(-cdf) + np.log(pdf)
        )
    density = np.exp(log_density)
    x.flags.writeable = density.flags.writeable = False
    return x, density


#: Beyond this k x (the line over the floor's median, in Rayleigh scales) exp(-(k x)^2 / 2)
#: is exactly 0.0 in float64 (it underflows below exp(-745.2)), and so is the exceedance
#: term of :func:`_exceedance`.
_UNDERFLOW_KX = math.sqrt(1500.0)
#: Values of k taken together in :func:`_exceedance` (rows of one array).
_K_BLOCK = 20


def _exceedance(k, searched_bins: int, floor_bins: int):
    """P(max of ``searched_bins`` Rayleigh bins > k x the median of ``floor_bins`` others).

    ``k`` a float or an array of them (the result has its shape). The integral over the
    median's density is a sum over its grid. A term whose exp(-(k x)^2 / 2) underflows is
    exactly +0.0, so it is left at zero instead of computed: each row is still summed whole
    (the same length and the same pairwise summation), so the result is the same to the bit
    as evaluating every term, in a third to a half of the time for the ratios the evidence
    reads (docs/performance.md, stop 91).
    """
    x, density = _median_density(floor_bins)
    k = np.asarray(k, dtype=float)
    flat = np.atleast_1d(k).ravel()
    out = np.empty(flat.size)
    order = np.argsort(flat, kind="stable")  # blocks of similar k share their reach in x
    for start in range(0, flat.size, _K_BLOCK):
        rows = order[start : start + _K_BLOCK]
        kk = flat[rows, None]
        smallest = float(kk.min())
        # grid points whose k x can stay under the cut-off for the block's smallest k
        reach = x.size if smallest <= 0.0 else int(np.searchsorted(x, _UNDERFLOW_KX / smallest))
        reach = min(x.size, reach + 1)
        above = np.zeros((kk.shape[0], x.size))
        xs = x[:reach]
        above[:, :reach] = -np.expm1(searched_bins * np.log1p(-np.exp(-0.5 * (kk * xs) ** 2)))
        out[rows] = np.sum(above * density, axis=1) * (x[1] - x[0])
    return float(out[0]) if k.ndim == 0 else out.reshape(k.shape)


@functools.lru_cache(maxsize=1024)  # a bisection of 60 steps; the same bands recur
def detection_threshold_db(
    n_bands: int,
    false_alarm: float = FALSE_ALARM,
    searched_bins: int = SEARCHED_BINS,
    floor_bins: int | None = None,
) -> float:
    """Envelope line-to-floor ratio [dB] that noise exceeds with probability ``false_alarm``.

    For Gaussian noise the envelope spectrum's bins are Rayleigh. A line is the largest of
    ``searched_bins`` bins, its floor the median of ``floor_bins`` other bins (itself a random
    variable: with few bins its low values dominate the false alarms), and it is looked for in
    each of ``n_bands`` bands (union bound). ``floor_bins=None`` takes the median as known
    (P = searched_bins n_bands exp(-(1.177 k)^2 / 2)).

    Parameters
    ----------
    n_bands : int
        Bands the line was searched in.
    false_alarm : float
        Wanted probability per fault and record.
    searched_bins : int
        Bins searched for the line in each band.
    floor_bins : int, optional
        Bins whose median is the floor.

    Returns
    -------
    float
        20 log10 k plus ``CALIBRATION_DB`` [dB] (12.9 dB for one band of five bins at 1e-4
        with a known median).
    """
    n_bands = check_whole("n_bands", n_bands)
    if not 0.0 < false_alarm < 1.0:
        raise FeatureError(f"false_alarm = {false_alarm} is outside the allowed range (0, 1)")
    searched_bins = check_whole("searched_bins", searched_bins)
    k = math.sqrt(2.0 * math.log(searched_bins * n_bands / false_alarm)) / _RAYLEIGH_MEDIAN
    if floor_bins is None:
        return 20.0 * math.log10(k) + CALIBRATION_DB
    floor_bins = check_whole("floor_bins", floor_bins, low=3)
    floor_bins = _independent_floor_bins(floor_bins)
    target = false_alarm / n_bands
    low, high = 1.0, 4.0 * k
    for _ in range(60):  # bisection on log k: the exceedance falls monotonically with k
        mid = math.sqrt(low * high)
        if _exceedance(mid * _RAYLEIGH_MEDIAN, searched_bins, floor_bins) > target:
            low = mid
        else:
            high = mid
    return 20.0 * math.log10(high) + CALIBRATION_DB


#: Ratios [dB] of the tabulated exceedance curve of :func:`line_false_alarm`, and the
#: smallest probability it resolves (below it a line's evidence is saturated).
_CURVE_DB = np.arange(0.0, 60.0 + 1e-9, 0.05)
_SMALLEST_P = 1e-300


@functools.lru_cache(maxsize=64)
def _log_exceedance_curve(searched_bins: int, floor_bins: int) -> np.ndarray:
    """The log of P(noise line >= r) on ``_CURVE_DB``, modelled as the threshold is."""
    k = 10.0 ** ((_CURVE_DB - CALIBRATION_DB) / 20.0) * _RAYLEIGH_MEDIAN
    p = _exceedance(k, searched_bins, _independent_floor_bins(floor_bins))
    return np.log(np.clip(p, _SMALLEST_P, 1.0))


def line_false_alarm(ratio_db: float, searched_bins: int, floor_bins: int) -> float:
    """Probability that Gaussian noise alone gives a line this high, in one band.

    The same model as :func:`detection_threshold_db` (Rayleigh bins, the floor a median of
    ``floor_bins`` correlated bins, ``CALIBRATION_DB``), so that a fundamental at that
    threshold has ``line_false_alarm(threshold) x n_bands = false_alarm``.

    Parameters
    ----------
    ratio_db : float
        The line's peak over the median of its neighbourhood [dB].
    searched_bins, floor_bins : int
        Bins searched for the line; bins of the floor's median.

    Returns
    -------
    float
        P in [1e-300, 1].
    """
    if ratio_db <= 0.0:
        return 1.0
    k = 10.0 ** ((ratio_db - CALIBRATION_DB) / 20.0) * _RAYLEIGH_MEDIAN
    return _exceedance_clipped(k, searched_bins, floor_bins)


def _exceedance_clipped(k: float, searched_bins: int, floor_bins: int) -> float:
    """:func:`_exceedance` of a line k x its floor's median, clipped to [``_SMALLEST_P``, 1].

    Half the floor's bins count as independent. Evaluated directly: a curve per bin count
    would be built for every harmonic and sideband, each searched over its own number of bins.
    """
    p = _exceedance(k, max(1, int(searched_bins)), _independent_floor_bins(floor_bins))
    return float(min(1.0, max(p, _SMALLEST_P)))


def plain_line_false_alarm(ratio_db: float, searched_bins: int, floor_bins: int) -> float:
    """Probability that Gaussian noise alone gives a plain-spectrum line this high.

    For a Hann-windowed amplitude spectrum (:func:`features.amplitude_spectrum`) the bins of
    Gaussian noise are Rayleigh: the line is the largest of ``searched_bins`` of them (union
    bound), its floor the median of ``floor_bins`` others, half of them independent (the
    window's neighbouring bins are correlated), and the ratio is taken as it is measured (the
    envelope's model, :func:`line_false_alarm`, carries a calibration of its own). On white
    noise (6205 candidates at 12 kHz, 1 and 10 s records) the rate measured was 0.36-0.88 of
    this probability from 1e-1 to 1e-3 (``benchmarks/waviness_noise.py``).

    Parameters
    ----------
    ratio_db : float
        The line's peak over the median of its neighbourhood [dB] (:func:`features.line_snr`).
    searched_bins, floor_bins : int
        Bins searched for the line; bins of the floor's median.

    Returns
    -------
    float
        P in [1e-300, 1].

    Examples
    --------
    >>> round(plain_line_false_alarm(12.0, 3, 200), 5)  # 12 dB, 3 bins, a well-known floor
    0.00016
    """
    if ratio_db <= 0.0:
        return 1.0
    return _exceedance_clipped(10.0 ** (ratio_db / 20.0), searched_bins, floor_bins)


def ratio_for_false_alarm(
    false_alarm: float, n_bands: int, searched_bins: int, floor_bins: int
) -> float:
    """The line ratio [dB] whose false-alarm probability over ``n_bands`` bands is ``false_alarm``.

    The inverse of ``n_bands x`` :func:`line_false_alarm`: it puts the evidence of several
    lines, combined into one probability, on the scale of :func:`detection_threshold_db`
    (at most ``_CURVE_DB[-1]``).

    Parameters
    ----------
    false_alarm : float
        The probability, in (0, 1].
    n_bands : int
        The bands searched.
    searched_bins, floor_bins : int
        The bins a line is searched in, and those its floor is the median of.

    Returns
    -------
    float
        The line's ratio to its floor [dB].
    """
    curve = _log_exceedance_curve(max(1, int(searched_bins)), max(3, int(floor_bins)))
    target = math.log(max(false_alarm, _SMALLEST_P)) - math.log(max(1, n_bands))
    # the curve falls with the ratio: interpolate on the reversed arrays
    return float(np.interp(target, curve[::-1], _CURVE_DB[::-1]))
