"""The entry and exit events of a spall: the time a rolling element takes to cross it.

A ball that rolls over a spall unloads where it enters it and is struck where it leaves it
(Sawalhi and Randall, "Vibration response of spalled rolling element bearings: observations,
simulations and signal processing techniques to track the spall size", MSSP 25 (2011)). The
two events are a passage time apart; the structure rings after each, so they are read where
its ringing is removed: the record's random part (:func:`features.separate_discrete`) through
a linear-prediction (AR) error filter, which is causal, so that each event becomes a short
burst at its own start and nothing precedes it (a zero-phase whitening puts precursors before
every impact, which read as entries). The squared envelope is averaged over the fault's
impacts, aligned on each impact, and the entry is the earliest clear peak before it.

docs/diagnosis.md, "Severity", gives the measurements the constants were set on (simulated
spalls through the rig recipes' chains, not recordings) and what converts the spacing into a
length (``cmtool.severity``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view
from scipy import signal as sp_signal
from scipy.linalg import solve_toeplitz

from ._validate import FeatureError, check_fs, check_positive, check_record
from .separation import separate_discrete

#: AR (prediction-error) filter order [s of the record's samples], clipped to AR_ORDER_LIMITS
AR_ORDER_S = 1e-3
AR_ORDER_LIMITS = (8, 200)
#: causal high-pass ahead of the envelope [Hz] (the shaft's and the machine's low orders out)
HIGH_PASS_HZ = 1000.0
#: smoothing of the squared envelope [s]
SMOOTHING_S = 0.05e-3
#: impacts: one peak per this fraction of the fault period; the weakest share dropped
PEAK_SPACING = 0.7
WEAKEST_DROPPED = 0.3
#: the averaged span before an impact: at most this fraction of the fault period
SPAN_PERIODS = 0.8
#: template realignment: rounds and the largest shift [s]; the span after the impact [s]
REALIGN_ROUNDS = 2
REALIGN_SHIFT_S = 0.3e-3
AFTER_S = 0.5e-3
#: an entry: robust z over the average's median above ENTRY_Z, the average back under GAP_Z
#: between it and the impact, no nearer than the guard (the impact's own width)
ENTRY_Z = 6.0
GAP_Z = 2.0
GUARD_S = 0.1e-3
GUARD_CYCLES = 2.0
#: the odd and the even impacts' averages must each place the entry within this [s]
SPLIT_TOLERANCE_S = 0.1e-3
#: fewest impacts averaged
MIN_IMPACTS = 6


@dataclass(frozen=True)
class EntryExit:
    """The entry-exit spacing of a local fault's impacts.

    Attributes
    ----------
    resolved : bool
        An entry event was found, stable in the odd and the even impacts' averages.
    spacing_s : float
        Time from the entry event to the impact [s] (NaN when not resolved).
    split_s : float
        Largest difference of the odd or the even impacts' spacing from ``spacing_s`` [s].
    entry_z : float
        The entry's robust z (its height over the average's median, in scaled MADs).
    impacts : int
        Impacts averaged.
    reason : str
        Why nothing was resolved ("" when resolved).
    average : numpy.ndarray
        The averaged squared envelope before the impact (last sample: the impact) [U^2].
    """

    resolved: bool
    spacing_s: float
    split_s: float
    entry_z: float
    impacts: int
    reason: str
    average: np.ndarray


def ar_prediction_error(x: np.ndarray, order: int) -> np.ndarray:
    """The error of an order-``order`` linear predictor fitted to ``x`` (Yule-Walker).

    Parameters
    ----------
    x : array_like, 1-D
        Signal [U]; its mean is removed.
    order : int
        Predictor order [samples], less than the record's length.

    Returns
    -------
    ndarray
        The causal prediction error [U]: the signal with its predictable ringing removed.

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> e = rng.standard_normal(20000)
    >>> x = np.zeros_like(e)
    >>> for i in range(2, e.size):  # an AR(2) resonance driven by white noise
    ...     x[i] = 1.6 * x[i - 1] - 0.9 * x[i - 2] + e[i]
    >>> bool(np.std(ar_prediction_error(x, 2)[2:] - e[2:]) < 0.05)
    True
    """
    x = check_record(x, function="ar_prediction_error", min_length=4)
    if not 1 <= order < x.size:
        raise FeatureError(f"order = {order} is outside the allowed range [1, {x.size - 1}]")
    x = x - x.mean()
    spectrum = np.fft.rfft(x, 2 * x.size)
    autocorrelation = np.fft.irfft(np.abs(spectrum) ** 2)[: order + 1] / x.size
    if autocorrelation[0] <= 0.0:
        return x
    coefficients = solve_toeplitz(autocorrelation[:order], autocorrelation[1 : order + 1])
    return sp_signal.lfilter(np.concatenate([[1.0], -coefficients]), [1.0], x)


def _whitened_envelope(rest: np.ndarray, fs: float) -> np.ndarray:
    order = int(max(AR_ORDER_LIMITS[0], min(AR_ORDER_LIMITS[1], AR_ORDER_S * fs)))
    y = ar_prediction_error(rest, order)
    y = sp_signal.sosfilt(sp_signal.butter(4, HIGH_PASS_HZ, "highpass", fs=fs, output="sos"), y)
    e = np.abs(sp_signal.hilbert(y)) ** 2
    width = max(1, int(SMOOTHING_S * fs))
    return np.convolve(e, np.ones(width) / width, mode="same")


def _realign(e: np.ndarray, peaks: np.ndarray, span: int, after: int, shift: int) -> np.ndarray:
    """Each impact moved to where it matches the average impact best (two rounds)."""
    length = span + after + 1
    for _ in range(REALIGN_ROUNDS):
        template = np.mean([e[p - span : p + after + 1] for p in peaks], axis=0)
        template = template - template.mean()
        moved = []
        for p in peaks:
            windows = sliding_window_view(e[p - shift - span : p + shift + after + 1], length)
            score = (windows - windows.mean(axis=1, keepdims=True)) @ template
            moved.append(p + int(np.argmax(score)) - shift)
        peaks = np.array(moved)
        peaks = peaks[(peaks > span + 2 * shift) & (peaks < e.size - after - 2 * shift)]
    return peaks


def _entry(average: np.ndarray, fs: float) -> tuple[float, float]:
    """Spacing [s] from the earliest clear peak before the impact, and its z (NaN, 0: none)."""
    span = average.size - 1
    median = np.median(average)
    mad = 1.4826 * np.median(np.abs(average - median))
    z = (average - median) / max(mad, 1e-300)
    guard = int(max(GUARD_S, GUARD_CYCLES / (0.4 * fs - HIGH_PASS_HZ)) * fs)
    if span - guard < 3:
        return math.nan, 0.0
    peaks, _ = sp_signal.find_peaks(z[: span - guard])
    for p in peaks[z[peaks] > ENTRY_Z]:  # earliest first
        if np.min(z[p:span]) < GAP_Z:
            return (span - p) / fs, float(z[p])
    return math.nan, 0.0


def entry_exit_spacing(
    x: np.ndarray,
    fs: float,
    *,
    fault_rate: float,
    shaft_rate: float,
    ball_pass_rate: float,
    max_span_s: float,
    random_part: np.ndarray | None = None,
) -> EntryExit:
    """Time between a spall's entry and exit events, averaged over the fault's impacts.

    Parameters
    ----------
    x : array_like, 1-D
        Acceleration [U], at least 0.1 s.
    fs : float
        Sample rate [Hz]; at least 4 kHz (the envelope is read above 1 kHz).
    fault_rate : float
        The fault's impact rate [Hz] (BPFO for the outer race, BPFI for the inner race).
    shaft_rate, ball_pass_rate : float
        The shaft's rate and the ball-pass rate (BPFO) [Hz]: their harmonics are removed first.
    max_span_s : float
        Longest spacing searched [s] (at most ``SPAN_PERIODS`` fault periods are).
    random_part : array_like, optional
        ``x``'s random part when already separated at the shaft and ball-pass rates
        (``features.separate_discrete``, e.g. ``Evidence.random_part``) [U]: not separated
        again.

    Returns
    -------
    EntryExit
        The spacing, how stable it is between the odd and the even impacts, and why nothing
        was resolved when nothing was.

    Raises
    ------
    FeatureError
        A rate, the span or the sample rate is not positive, or ``fs`` is under 4 kHz.
    """
    fs = check_fs(fs)
    x = check_record(x, function="entry_exit_spacing", min_length=8)
    for name, value in (
        ("fault_rate", fault_rate),
        ("shaft_rate", shaft_rate),
        ("ball_pass_rate", ball_pass_rate),
    ):
        check_positive(name, value, unit="Hz")
    check_positive("max_span_s", max_span_s, unit="s")
    if fs < 4.0 * HIGH_PASS_HZ:
        raise FeatureError(f"fs = {fs:g} Hz is outside the allowed range [4000, inf) Hz")
    if random_part is None:
        random_part = separate_discrete(x, fs, fundamentals=(shaft_rate, ball_pass_rate))
    elif np.shape(random_part) != x.shape:
        raise FeatureError(
            f"random_part has shape {np.shape(random_part)}; x's shape {x.shape} is needed"
        )
    e = _whitened_envelope(np.asarray(random_part, dtype=np.float64), fs)
    period = 1.0 / fault_rate
    peaks, _ = sp_signal.find_peaks(e, distance=max(1, int(PEAK_SPACING * period * fs)))
    span = int(min(max_span_s, SPAN_PERIODS * period) * fs)
    after, shift = int(AFTER_S * fs), int(REALIGN_SHIFT_S * fs)
    peaks = peaks[(peaks > span + shift) & (peaks < e.size - after - shift)]
    empty = np.zeros(0)
    if peaks.size < MIN_IMPACTS:
        why = f"{peaks.size} impacts in the record, fewer than {MIN_IMPACTS}"
        return EntryExit(False, math.nan, math.nan, 0.0, int(peaks.size), why, empty)
    heights = e[peaks]
    peaks = peaks[heights >= np.quantile(heights, WEAKEST_DROPPED)]
    peaks = _realign(e, peaks, span, after, shift)
    centre = np.mean([e[p - shift : p + shift + 1] for p in peaks], axis=0)
    peaks = peaks + int(np.argmax(centre)) - shift
    segments = np.array([e[p - span : p + 1] for p in peaks])
    average = segments.mean(axis=0)
    spacing, z = _entry(average, fs)
    if math.isnan(spacing):
        why = "no entry event stands clear of the averaged envelope before the impact"
        return EntryExit(False, math.nan, math.nan, 0.0, int(peaks.size), why, average)
    split = [_entry(segments[half::2].mean(axis=0), fs)[0] for half in (0, 1)]
    differences = [abs(s - spacing) for s in split]
    if any(math.isnan(d) for d in differences) or max(differences) > SPLIT_TOLERANCE_S:
        why = "the odd and the even impacts do not place the entry event alike"
        return EntryExit(False, math.nan, math.nan, z, int(peaks.size), why, average)
    return EntryExit(True, spacing, max(differences), z, int(peaks.size), "", average)
