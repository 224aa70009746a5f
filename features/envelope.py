"""Envelope analysis: band-pass demodulation, envelope spectrum, fast kurtogram.

* The band-pass is zero-phase and done in the frequency domain: the FFT bins of the band get a
  Tukey (cosine-tapered, alpha 0.25) weight, the negative frequencies are dropped, and the
  inverse FFT is the analytic band signal z. The envelope is |z| (``"hilbert"``) or |z|^2
  (``"squared"``, Randall and Antoni's squared envelope).
* The band is chosen, when not given, by the fast kurtogram of Antoni (2007, MSSP 21:108-124):
  the 1/3-binary tree of bands (level k splits [0, fs/2] into 2^k bands, the 1/3 levels into
  3 * 2^(k-1)), with the spectral kurtosis of each band's complex envelope
  K = <|c|^4> / <|c|^2>^2 - 2 (zero for Gaussian noise). Each band's complex envelope is
  computed from its FFT bins only (decimated), so the whole kurtogram costs about one FFT per
  level.
* Cepstral pre-whitening (Randall et al. 2011): X -> X / |X| removes discrete tones and the
  transfer path before the envelope.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
from scipy import fft as sp_fft

from . import _windows
from ._validate import (
    FeatureError,
    check_band,
    check_count,
    check_fs,
    check_positive,
    check_rates,
    check_record,
    check_signal,
)
from .band_selection import fault_band
from .lattice import inner_race_lattice_offsets
from .separation import separate_discrete
from .spectra import amplitude_spectrum

__all__ = ["KurtogramResult", "kurtogram", "envelope", "envelope_spectrum", "prewhiten"]

TUKEY_ALPHA = 0.25
#: Fraction of the record tapered (half at each end) before the kurtogram's FFT.
EDGE_TAPER = 0.05


@dataclass(frozen=True)
class KurtogramResult:
    """The fast kurtogram and the band it selects.

    Attributes
    ----------
    center_frequency : float
        Centre of the band with the largest spectral kurtosis [Hz].
    bandwidth : float
        Its width [Hz].
    kurtosis : float
        Its spectral kurtosis [-] (0 for Gaussian noise).
    level : float
        Tree level of the band (k or k + 0.6 for the 1/3 levels, as in Antoni's plot).
    levels : ndarray, shape (L,)
        Levels of the rows of ``matrix``.
    matrix : ndarray, shape (L, B)
        Spectral kurtosis per level (rows) on a common grid of B frequency cells over
        [0, fs/2] (each band repeated over the cells it covers), for plotting.
    fs : float
        Sample rate [Hz].
    """

    center_frequency: float
    bandwidth: float
    kurtosis: float
    level: float
    levels: np.ndarray
    matrix: np.ndarray
    fs: float

    @property
    def band(self) -> tuple[float, float]:
        """The selected band (low, high) [Hz], within [0, fs/2]."""
        low = max(self.center_frequency - self.bandwidth / 2, 0.0)
        high = min(self.center_frequency + self.bandwidth / 2, self.fs / 2)
        return (low, high)


def prewhiten(x: np.ndarray, *, axis: int = -1) -> np.ndarray:
    """Cepstral pre-whitening: unit magnitude spectrum, phase kept (Randall et al. 2011).

    Parameters
    ----------
    x : array_like
        Signal [U], at least 4 samples; its mean is removed first.
    axis : int
        Time axis.

    Returns
    -------
    ndarray
        The pre-whitened signal, shaped as ``x`` (dimensionless: every bin of its spectrum
        but the zero-frequency one has magnitude 1).
    """
    x = check_signal(x, min_length=4)
    spec = np.fft.rfft(x - np.mean(x, axis=axis, keepdims=True), axis=axis)
    mag = np.abs(spec)
    floor = 1e-12 * np.max(mag, axis=axis, keepdims=True) + 1e-300
    return np.fft.irfft(spec / np.maximum(mag, floor), n=x.shape[axis], axis=axis)


def _band_weights(freqs: np.ndarray, low: float, high: float) -> np.ndarray:
    w = np.zeros_like(freqs)
    inside = (freqs >= low) & (freqs <= high)
    m = int(inside.sum())
    if m:
        w[inside] = _windows.tukey(m, TUKEY_ALPHA) if m > 2 else 1.0
    return w


def envelope(
    x: np.ndarray,
    fs: float,
    *,
    band: tuple[float, float] | None = None,
    method: str = "hilbert",
    prewhitening: bool = False,
) -> np.ndarray:
    """Envelope of the band-passed signal (zero-phase FFT band-pass and analytic signal).

    Parameters
    ----------
    x : array_like, 1-D
        Signal [U].
    fs : float
        Sample rate [Hz].
    band : (float, float), optional
        Band-pass edges [Hz]; ``None`` uses the whole band (0, fs/2).
    method : {"hilbert", "squared"}
        |z| [U] or |z|^2 [U^2].
    prewhitening : bool
        Apply cepstral pre-whitening first.

    Returns
    -------
    ndarray
        Envelope, same length as ``x``.
    """
    x = check_record(x, function="envelope", min_length=8)
    fs = check_fs(fs)
    if method not in ("hilbert", "squared"):
        raise FeatureError(f"method = {method!r} is not one of 'hilbert', 'squared'")
    low, high = (0.0, fs / 2) if band is None else check_band(band, fs)
    if prewhitening:
        x = prewhiten(x)
    n = x.size
    spec = np.fft.fft(x - x.mean())
    freqs = np.fft.fftfreq(n, 1.0 / fs)
    weights = _band_weights(np.abs(freqs), low, high) * (freqs > 0) * 2.0
    if band is None:
        weights = np.where(freqs > 0, 2.0, 0.0)
    z = np.fft.ifft(spec * weights)
    env = np.abs(z)
    return env**2 if method == "squared" else env


def envelope_spectrum(
    x: np.ndarray,
    fs: float,
    *,
    band: tuple[float, float] | None = None,
    method: str = "hilbert",
    prewhitening: bool = False,
    window: str = "hann",
    nlevel: int = 6,
    return_band: bool = False,
    fault_frequencies: Mapping[str, float] | None = None,
) -> tuple[np.ndarray, np.ndarray] | tuple[np.ndarray, np.ndarray, tuple[float, float]]:
    """Amplitude spectrum of the envelope of ``x`` in a band (chosen automatically if None).

    Parameters
    ----------
    x : array_like, 1-D
        Signal [U].
    fs : float
        Sample rate [Hz].
    band : (float, float), optional
        Demodulation band [Hz]. ``None`` with ``fault_frequencies``: the band ``cmtool
        diagnose`` uses (periodic parts and discrete lines removed by
        :func:`features.separate_discrete`, then :func:`features.select_band` for the rates
        ``bpfo``, ``bpfi``, ``two_bsf`` given and the cage rate, bands at least 3 x the
        fastest rate wide and from 3 x it up: ``features.band_selection.fault_band``; the cage
        rate is ``ftf`` or, without it, shaft x BPFO / (BPFO + BPFI));
        ``None`` without: the band of largest spectral kurtosis (:func:`kurtogram`).
    method : {"hilbert", "squared"}
        Envelope |z| or squared envelope |z|^2.
    prewhitening : bool
        Cepstral pre-whitening before demodulation.
    window : str
        Window of the envelope spectrum (the envelope's mean is removed first).
    nlevel : int
        Kurtogram depth when ``band`` is None.
    return_band : bool
        Also return the band used ``(low, high)`` [Hz].
    fault_frequencies : mapping of str to float, optional
        Fault rates to look for [Hz], e.g. ``{"bpfo": 107.4, "bpfi": 162.2, "two_bsf": 141.2,
        "shaft": 29.95, "ftf": 11.9}`` (only used to choose the band; with ``shaft`` and
        ``bpfo`` their harmonics are removed first, exactly as ``cmtool diagnose`` does).

    Returns
    -------
    frequencies : ndarray
        [Hz].
    amplitude : ndarray
        Peak amplitude of the envelope's components [U] (or [U^2] for ``"squared"``).
    band : (float, float)
        Only with ``return_band=True``.

    Examples
    --------
    >>> import numpy as np
    >>> fs = 20000.0; t = np.arange(20000) / fs
    >>> x = (1 + 0.5 * np.cos(2 * np.pi * 100 * t)) * np.cos(2 * np.pi * 3000 * t)
    >>> f, a = envelope_spectrum(x, fs, band=(2000, 4000))
    >>> round(float(a[100]), 3)
    0.5
    """
    x = check_record(x, function="envelope_spectrum", min_length=8)
    fs = check_fs(fs)
    if fault_frequencies is not None:
        fault_frequencies = check_rates("fault_frequencies", fault_frequencies, fs=fs)
    if prewhitening:
        x = prewhiten(x)
    if band is None and fault_frequencies:
        rates = {k: v for k, v in fault_frequencies.items() if k in ("bpfo", "bpfi", "two_bsf")}
        periodic = tuple(fault_frequencies[k] for k in ("shaft", "bpfo") if k in fault_frequencies)
        lattice = ()
        if len(periodic) == 2 and "bpfi" in fault_frequencies:  # as fault_evidence fits it
            lattice = inner_race_lattice_offsets(
                fault_frequencies["bpfo"], fault_frequencies["bpfi"]
            )
        x = separate_discrete(x, fs, fundamentals=periodic, lattice=lattice)
        cage = fault_frequencies.get("ftf")
        if cage is None and all(k in fault_frequencies for k in ("shaft", "bpfo", "bpfi")):
            # BPFO = Z x FTF and BPFO + BPFI = Z x the shaft rate, whatever the geometry
            f = fault_frequencies
            cage = f["shaft"] * f["bpfo"] / (f["bpfo"] + f["bpfi"])
        cage = cage if rates else None
        selection = fault_band(x, fs, rates or fault_frequencies, cage, nlevel=nlevel)
        band = selection.band
        from . import evidence  # imports this module: here, not at the top

        if evidence.EVIDENCE_BANDS > 1 and len(rates) == 3 and "shaft" in fault_frequencies:
            # every rate the rule weighs: its band, the one of the bands the line ranks
            # highest where the weighed evidence stands highest (best_band_evidence)
            ctx = {**fault_frequencies, "ftf": cage}
            band = evidence.best_band_evidence(x, fs, ctx, selection).selection.band
    elif band is None:
        band = kurtogram(x, fs, nlevel=nlevel).band
    env = envelope(x, fs, band=band, method=method)
    freqs, amp = amplitude_spectrum(env, fs, window=window, detrend="constant")
    return (freqs, amp, tuple(band)) if return_band else (freqs, amp)


def _level_kurtosis(spec: np.ndarray, df: float, bandwidth: float, nb: int) -> np.ndarray:
    """Spectral kurtosis of the complex envelopes of the ``nb`` bands of one level.

    All bands of a level hold the same number of FFT bins m, so they are cut out as one
    (nb, m) block, tapered and inverse transformed in one call (decimated complex envelopes).
    """
    m = int(bandwidth / df)
    if m < 8:
        return np.zeros(nb)
    starts = np.round(np.arange(nb) * bandwidth / df).astype(int)
    idx = np.minimum(starts[:, None] + np.arange(m)[None, :], spec.size - 1)
    seg = spec[idx] * _windows.tukey(m, TUKEY_ALPHA)
    c = sp_fft.ifft(seg, sp_fft.next_fast_len(m), axis=1)
    p = c.real**2 + c.imag**2
    mean = p.mean(axis=1)
    safe = np.where(mean > 0, mean, 1.0)
    return np.where(mean > 0, (p * p).mean(axis=1) / safe**2 - 2.0, 0.0)


def kurtogram(
    x: np.ndarray, fs: float, *, nlevel: int = 6, min_bandwidth: float | None = None
) -> KurtogramResult:
    """Fast kurtogram (Antoni 2007): the band of largest spectral kurtosis.

    Parameters
    ----------
    x : array_like, 1-D
        Signal.
    fs : float
        Sample rate [Hz].
    nlevel : int
        Number of binary levels (1 .. 12); level k has 2^k bands of width fs / 2^(k+1).
    min_bandwidth : float, optional
        Smallest band considered [Hz]; default 24 fs / n, 24 bins of the record's
        spectrum (24 Hz for a one-second record).

    Returns
    -------
    KurtogramResult
        Selected centre frequency and bandwidth [Hz], its kurtosis, and the kurtogram matrix.
    """
    x = check_record(x, function="kurtogram", min_length=64)
    fs = check_fs(fs)
    nlevel = check_count("nlevel", nlevel, low=1, high=12)
    if min_bandwidth is not None:
        min_bandwidth = check_positive("min_bandwidth", min_bandwidth, unit="Hz")
    n = x.size
    # the FFT treats the record as circular: a record that ends where it did not start has a
    # jump at the seam, a broadband impulse that dominates the kurtosis of quiet bands (e.g.
    # above an anti-alias filter's cut-off); tapered edges remove it
    spec = sp_fft.rfft((x - x.mean()) * _windows.tukey(n, EDGE_TAPER))
    df = fs / n
    min_bw = 3.0 * fs / n * 8 if min_bandwidth is None else float(min_bandwidth)
    cells = 3 * 2 ** (int(nlevel) - 1) * 2
    levels, rows = [], []
    best = (-np.inf, 0.0, fs / 2, 0.0)
    splits = [(0.0, 1)]
    for k in range(1, int(nlevel) + 1):
        splits.append((k, 2**k))
        splits.append((k + 0.6, 3 * 2 ** (k - 1)))
    for level, nb in splits:
        bw = fs / 2 / nb
        if bw < min_bw:
            continue
        kurt = _level_kurtosis(spec, df, bw, nb)
        row = (
            np.repeat(kurt, cells // nb)
            if cells % nb == 0
            else np.interp((np.arange(cells) + 0.5) / cells * nb - 0.5, np.arange(nb), kurt)
        )
        b = int(np.argmax(kurt))
        if kurt[b] > best[0]:
            best = (float(kurt[b]), (b + 0.5) * bw, bw, level)
        levels.append(level)
        rows.append(row)
    kurt, center, bw, level = best
    return KurtogramResult(
        center_frequency=float(center),
        bandwidth=float(bw),
        kurtosis=float(kurt),
        level=float(level),
        levels=np.array(levels),
        matrix=np.array(rows),
        fs=fs,
    )
