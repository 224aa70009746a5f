"""Amplitude spectrum, power spectral density and frequency-domain integration.

Conventions follow ``scipy.signal``: signal ``x``, sample rate ``fs`` [Hz], keyword-only
options, ``axis=-1``, and ``(frequencies, values)`` out.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import signal as sp_signal

from . import _windows
from ._validate import (
    FeatureError,
    check_band,
    check_count,
    check_fs,
    check_positive,
    check_record,
    check_signal,
    check_whole,
)

__all__ = [
    "acceleration_from_velocity",
    "amplitude_spectrum",
    "peak_offset_bins",
    "band_rms",
    "power_spectral_density",
    "integrate_spectrum",
    "integrate_signal",
]


def peak_offset_bins(amplitude: np.ndarray, k: int) -> float:
    """Where a spectral line peaks relative to its largest bin ``k`` [bins], in (-0.5, 0.5).

    A parabola through the log amplitudes of bin ``k`` and its two neighbours (exact for a
    Gaussian main lobe, within a few hundredths of a bin for a Hann window's); 0 where the
    three do not bend down. ``k`` must have a neighbour on each side.

    Parameters
    ----------
    amplitude : array_like, 1-D
        Amplitude (or power) spectrum [U], positive.
    k : int
        The line's largest bin, 1 .. len(amplitude) - 2.

    Returns
    -------
    float
        The peak's offset from bin ``k`` [bins].
    """
    if not 1 <= k <= len(amplitude) - 2:
        raise FeatureError(
            f"k = {k} is outside the allowed range [1, {len(amplitude) - 2}] (a bin with a "
            "neighbour on each side)"
        )
    left, mid, right = (math.log(max(float(v), 1e-300)) for v in amplitude[k - 1 : k + 2])
    curvature = left - 2.0 * mid + right
    return 0.5 * (left - right) / curvature if curvature < 0 else 0.0


def amplitude_spectrum(
    x: np.ndarray,
    fs: float,
    *,
    window: str = "hann",
    detrend: str | bool = "constant",
    nperseg: int | None = None,
    scaling: str = "peak",
    axis: int = -1,
) -> tuple[np.ndarray, np.ndarray]:
    """One-sided amplitude spectrum, scaled so that a tone of amplitude A reads A.

    Parameters
    ----------
    x : array_like
        Signal (any unit U) along ``axis``.
    fs : float
        Sample rate [Hz].
    window : str
        Window name understood by ``scipy.signal.get_window`` (``"hann"``, ``"flattop"``, ...).
        The amplitude is corrected for the window's coherent gain.
    detrend : {"constant", "linear", False}
        Trend removed before the transform.
    nperseg : int, optional
        Segment length for averaging (Welch-style average of the magnitudes over 50 %
        overlapping segments); ``None`` transforms the whole record (resolution fs / n).
    scaling : {"peak", "rms"}
        Peak amplitude (A for A cos) or RMS (A / sqrt 2).
    axis : int
        Time axis.

    Returns
    -------
    frequencies : ndarray
        Frequencies [Hz].
    amplitude : ndarray
        Amplitude [U] (peak or RMS), same shape as ``x`` with ``axis`` replaced by frequency.

    Examples
    --------
    >>> import numpy as np
    >>> fs = 1000.0; t = np.arange(1000) / fs
    >>> f, a = amplitude_spectrum(2.0 * np.cos(2 * np.pi * 50 * t), fs)
    >>> round(float(a[50]), 6)
    2.0
    """
    x = check_signal(x, min_length=4, axis=axis)
    fs = check_fs(fs)
    if scaling not in ("peak", "rms"):
        raise FeatureError(f"scaling = {scaling!r} is not one of 'peak', 'rms'")
    x = np.moveaxis(x, axis, -1)
    n = x.shape[-1]
    if nperseg is None:
        nperseg = n
    nperseg = check_whole("nperseg", nperseg, low=4, high=n)
    win = _windows.get_window(window, nperseg)
    step = max(nperseg // 2, 1)
    starts = range(0, n - nperseg + 1, step)
    acc = None
    count = len(starts)
    for s in starts:
        seg = x[..., s : s + nperseg]
        if detrend:
            seg = sp_signal.detrend(seg, type=detrend, axis=-1)
        mag = np.abs(np.fft.rfft(seg * win, axis=-1))
        acc = mag if acc is None else acc + mag
    amp = acc / count * 2.0 / win.sum()
    amp[..., 0] /= 2.0
    if nperseg % 2 == 0:
        amp[..., -1] /= 2.0
    if scaling == "rms":
        amp = amp / np.sqrt(2.0)
    freqs = np.fft.rfftfreq(nperseg, 1.0 / fs)
    return freqs, np.moveaxis(amp, -1, axis)


def power_spectral_density(
    x: np.ndarray,
    fs: float,
    *,
    window: str = "hann",
    nperseg: int | None = None,
    detrend: str | bool = "constant",
    axis: int = -1,
) -> tuple[np.ndarray, np.ndarray]:
    """Welch power spectral density [U^2/Hz] (``scipy.signal.welch``, one-sided).

    Parameters
    ----------
    x : array_like
        Signal.
    fs : float
        Sample rate [Hz].
    window : str
        Window name.
    nperseg : int, optional
        Segment length; default min(n, 4096).
    detrend : {"constant", "linear", False}
        Trend removed from each segment.
    axis : int
        Time axis.

    Returns
    -------
    frequencies, psd : ndarray
        Frequencies [Hz] and PSD [U^2/Hz].
    """
    x = check_signal(x, min_length=4, axis=axis)
    fs = check_fs(fs)
    n = x.shape[axis]
    nperseg = min(n, 4096) if nperseg is None else check_whole("nperseg", nperseg, low=4, high=n)
    return sp_signal.welch(x, fs=fs, window=window, nperseg=nperseg, detrend=detrend, axis=axis)


def integrate_spectrum(
    frequencies: np.ndarray, spectrum: np.ndarray, *, low_cut: float = 2.0, order: int = 1
) -> np.ndarray:
    """Integrate an amplitude spectrum ``order`` times: divide by (2 pi f)^order.

    Bins below ``low_cut`` [Hz] are set to zero (the 1/f gain would blow up noise and drift).
    Acceleration [m/s^2] -> velocity [m/s] with ``order=1``.

    Parameters
    ----------
    frequencies : array_like, 1-D
        The spectrum's frequencies [Hz].
    spectrum : array_like
        Amplitude spectrum [U], its last axis along ``frequencies``.
    low_cut : float
        Bins below it are zeroed [Hz], > 0.
    order : int
        1 for velocity from acceleration, 2 for displacement.

    Returns
    -------
    ndarray
        The integrated spectrum [U s^order], shaped as ``spectrum``.
    """
    low_cut = check_positive("low_cut", low_cut, unit="Hz")
    order = check_count("order", order)
    f = np.asarray(frequencies, dtype=float)
    out = np.zeros_like(np.asarray(spectrum, dtype=float))
    keep = f >= low_cut
    out[..., keep] = np.asarray(spectrum)[..., keep] / (2 * np.pi * f[keep]) ** order
    return out


def integrate_signal(
    x: np.ndarray, fs: float, *, low_cut: float = 2.0, order: int = 1, axis: int = -1
) -> np.ndarray:
    """Integrate a time signal in the frequency domain (acceleration -> velocity).

    Divides the FFT by (j 2 pi f)^order and zeroes bins below ``low_cut`` [Hz] (a high-pass
    that removes the drift an integration of noise and offsets would produce).

    Parameters
    ----------
    x : array_like
        Signal [U].
    fs : float
        Sample rate [Hz].
    low_cut : float
        Low-frequency cut-off [Hz].
    order : int
        1 for velocity from acceleration, 2 for displacement.
    axis : int
        Time axis.

    Returns
    -------
    ndarray
        Integrated signal [U s^order].
    """
    x = check_signal(x, min_length=4, axis=axis)
    fs = check_fs(fs)
    low_cut = check_positive("low_cut", low_cut, unit="Hz")
    order = check_count("order", order)
    if low_cut >= fs / 2:
        raise FeatureError(
            f"low_cut = {low_cut:g} Hz is outside the allowed range (0, {fs / 2:g}) Hz"
        )
    x = np.moveaxis(x, axis, -1)
    n = x.shape[-1]
    spec = np.fft.rfft(x, axis=-1)
    f = np.fft.rfftfreq(n, 1.0 / fs)
    gain = np.zeros_like(f, dtype=complex)
    keep = f >= low_cut
    gain[keep] = 1.0 / (2j * np.pi * f[keep]) ** order
    y = np.fft.irfft(spec * gain, n=n, axis=-1)
    return np.moveaxis(y, -1, axis)


#: The velocity bands bearing makers test new bearings in (ISO 15242-1): low, medium, high [Hz].
ISO_15242_BANDS = {"low": (50.0, 300.0), "medium": (300.0, 1800.0), "high": (1800.0, 10000.0)}


def acceleration_from_velocity(velocity: np.ndarray, fs: float) -> np.ndarray:
    """The acceleration of a velocity record: its derivative, exact at every frequency.

    A discrete Fourier transform differentiates the record's periodic extension, which
    jumps at the wrap unless the record holds whole periods: a jump would come out as an
    impulse there. So a straight line is taken out first, the one that makes the sample
    after the last (extrapolated by the mean of the two end slopes) equal the first: the
    line's derivative is a constant, the acceleration's mean, which carries no vibration.
    Then each frequency's bin is multiplied by j 2 pi f. The inverse of
    :func:`velocity_band_rms`'s integration: the velocity bands of the result are those of
    the record without that line.

    Parameters
    ----------
    velocity : array_like, 1-D
        Velocity [U] (mm/s gives mm/s^2).
    fs : float
        Sample rate [Hz].

    Returns
    -------
    numpy.ndarray
        Acceleration [U / s], as many samples, zero mean.

    Examples
    --------
    >>> import numpy as np
    >>> fs = 12000.0; t = np.arange(12000) / fs
    >>> a = acceleration_from_velocity(np.sin(2 * np.pi * 100 * t), fs)  # amplitude 628
    >>> float(np.max(np.abs(a - 2 * np.pi * 100 * np.cos(2 * np.pi * 100 * t)))) < 1.0
    True
    """
    v = check_record(
        velocity, function="acceleration_from_velocity", name="velocity", min_length=16
    )
    fs = check_fs(fs)
    n = v.size
    v = v - v.mean()
    after_last = v[-1] + 0.5 * ((v[1] - v[0]) + (v[-1] - v[-2]))
    v = v - (after_last - v[0]) * np.arange(n) / n  # the wrap's jump, spread as a line
    spec = np.fft.rfft(v) * (2j * np.pi * np.fft.rfftfreq(n, 1.0 / fs))
    if n % 2 == 0:
        spec[-1] = 0.0  # the Nyquist bin of a real record has no derivative's phase
    a = np.fft.irfft(spec, n)
    return a - a.mean()


def velocity_band_rms(
    acceleration: np.ndarray, fs: float, bands: dict[str, tuple[float, float]] | None = None
) -> dict[str, float]:
    """RMS velocity in frequency bands, from an acceleration signal (ISO 15242 by default).

    Parameters
    ----------
    acceleration : array_like, 1-D
        Acceleration [U] (m/s^2 gives m/s; g gives g s).
    fs : float
        Sample rate [Hz].
    bands : dict of str to (float, float), optional
        Band edges [Hz]; default ``ISO_15242_BANDS``. A band reaching above fs/2 is cut there;
        one starting above it is NaN.

    Returns
    -------
    dict of str to float
        RMS velocity per band [U s].

    Examples
    --------
    >>> import numpy as np
    >>> fs = 25600.0; t = np.arange(25600) / fs
    >>> a = 2 * np.pi * 1000 * np.cos(2 * np.pi * 1000 * t)  # velocity sin(2 pi 1000 t)
    >>> round(velocity_band_rms(a, fs)["medium"], 4)
    0.7071
    """
    x = check_record(acceleration, function="velocity_band_rms", name="acceleration", min_length=16)
    fs = check_fs(fs)
    bands = ISO_15242_BANDS if bands is None else bands
    n = x.size
    spec = np.fft.rfft(x - x.mean())
    f = np.fft.rfftfreq(n, 1.0 / fs)
    velocity = np.zeros_like(spec)
    velocity[1:] = spec[1:] / (2j * np.pi * f[1:])
    power = _power_per_bin(velocity, n)
    out = {}
    for name, band in bands.items():
        try:
            low, high = (float(v) for v in band)
        except (TypeError, ValueError):
            raise FeatureError(
                f"bands[{name!r}] = {band!r} is not a (low, high) pair in Hz"
            ) from None
        if not (math.isfinite(high) and 0.0 <= low < high):
            raise FeatureError(
                f"bands[{name!r}] = ({low:g}, {high:g}) Hz is outside the allowed range: "
                "0 <= low < high, finite"
            )
        if low >= fs / 2:
            out[name] = float("nan")
            continue
        sel = _bins_in_band(f.size, fs / n, low, min(high, fs / 2))
        out[name] = float(np.sqrt(np.sum(power[sel])))
    return out


#: A bin this close to a band's edge [bins] lies on it: a rate read from a time column
#: (12000 Hz as 11999.99998, 1.7e-9 off) moves the bins at 300 and 1800 Hz of a 2 s record
#: by 1e-6 and 6e-6 bins (a time column to microseconds: up to 1e-6 relative, 0.02 bins
#: at 10 kHz), which must not take one out of the band and the next in.
EDGE_TOLERANCE_BINS = 0.05


def _bins_in_band(count: int, df: float, low: float, high: float, nyquist: bool = False):
    """The bins k x ``df`` (k < ``count``) with low <= f < high (and the last if ``nyquist``)."""
    k = np.arange(count)
    inside = (k >= math.ceil(low / df - EDGE_TOLERANCE_BINS)) & (
        k < math.ceil(high / df - EDGE_TOLERANCE_BINS)
    )
    if nyquist:
        inside[-1] = True
    return inside


def _power_per_bin(spec: np.ndarray, n: int) -> np.ndarray:
    """One-sided power per bin of an ``rfft`` of ``n`` samples (Parseval: sums to the MS)."""
    power = 2.0 * np.abs(spec) ** 2 / n**2
    power[0] /= 2.0
    if n % 2 == 0:
        power[-1] /= 2.0
    return power


def band_rms(x: np.ndarray, fs: float, band: tuple[float, float]) -> float:
    """RMS of a signal in a frequency band (Parseval over the record's DFT bins).

    Parameters
    ----------
    x : array_like, 1-D
        Signal [U].
    fs : float
        Sample rate [Hz].
    band : (float, float)
        Band edges [Hz], 0 <= low < high <= fs/2; bins with low <= f < high count (the
        Nyquist bin too when high = fs/2).

    Returns
    -------
    float
        RMS in the band [U].

    Examples
    --------
    >>> import numpy as np
    >>> fs = 1000.0; t = np.arange(1000) / fs
    >>> x = 2 * np.cos(2 * np.pi * 100 * t) + np.cos(2 * np.pi * 300 * t)
    >>> round(band_rms(x, fs, (50, 150)), 4)  # 2 / sqrt(2)
    1.4142
    """
    x = check_record(x, function="band_rms", min_length=2)
    fs = check_fs(fs)
    low, high = check_band(band, fs)
    n = x.size
    power = _power_per_bin(np.fft.rfft(x), n)
    inside = _bins_in_band(power.size, fs / n, low, high, nyquist=high >= fs / 2)
    return float(np.sqrt(np.sum(power[inside])))
