"""Fault bands and band metrics, in the style of MATLAB's bearingFaultBands / faultBandMetrics.

The functions take characteristic frequencies as numbers: ``features`` knows nothing of the
bearing physics (``cmtool`` computes the frequencies with ``generators.kinematics``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import pandas as pd

from ._validate import FeatureError, check_count, check_positive, check_rates, check_whole

__all__ = [
    "line_snr",
    "band_amplitude",
    "harmonic_amplitudes",
    "fault_bands",
    "band_metrics",
    "BAND_METRIC_COLUMNS",
]

#: Half width of the noise-floor window around a line, relative to the line's frequency.
FLOOR_WINDOW = 0.10


def line_snr(
    frequencies: np.ndarray,
    spectrum: np.ndarray,
    center: float,
    *,
    half_width: float,
    guard: float = 2.0,
) -> tuple[float, float, float]:
    """A spectral line over its local noise floor: the one line measure of the toolkit.

    Used by the feature table (``spectrum_*_snr``, ``envelope_*_snr``) and by ``cmtool
    diagnose``'s waviness lines, each with its own half width.

    Parameters
    ----------
    frequencies : ndarray
        Bin frequencies [Hz], uniform and increasing.
    spectrum : ndarray
        Amplitude spectrum [U], one value per bin.
    center : float
        Line frequency [Hz].
    half_width : float
        Half width of the search band [Hz] (at least one bin is searched).
    guard : float
        The floor leaves out ``guard`` half widths either side of the line [-].

    Returns
    -------
    snr_db, peak, floor : float
        The band's peak over the median of the spectrum within ``FLOOR_WINDOW * center``
        (at least 10 bins) of the line, outside the guard [dB]; the peak [U]; the floor [U].
        All 0 when the band reaches past the spectrum's end.

    Examples
    --------
    >>> f = np.arange(0.0, 500.0, 0.5)
    >>> a = np.full(f.size, 0.01)
    >>> a[200] = 1.0  # a line at 100 Hz, 40 dB over the floor
    >>> [round(v, 2) for v in line_snr(f, a, 100.0, half_width=1.0)]
    [40.0, 1.0, 0.01]
    """
    f = np.asarray(frequencies, dtype=float)
    s = np.asarray(spectrum, dtype=float)
    half_width = check_positive("half_width", half_width, unit="Hz")
    if not math.isfinite(center):
        raise FeatureError(f"center = {center!r} Hz is not a finite frequency")
    df = f[1] - f[0]
    hw = max(half_width, df)
    reach = max(FLOOR_WINDOW * center, 10 * df)
    # only the bins within reach of the line can be selected: on the uniform grid they lie in
    # one slice (two bins' margin for rounding), and the tests below run on it alone (the
    # same bins as over the whole spectrum, in the same order: the same results, a tenth of
    # the work for a spectrum of 12,800 bins)
    extent = max(reach, hw)
    lo = min(f.size, max(0, int(math.floor((center - extent - f[0]) / df)) - 2))
    hi = min(f.size, max(lo, int(math.ceil((center + extent - f[0]) / df)) + 3))
    near = np.abs(f[lo:hi] - center)
    s = s[lo:hi]
    line = near <= hw
    if not line.any() or center + hw > f[-1]:
        return 0.0, 0.0, 0.0
    peak = float(s[line].max())
    window = (near <= reach) & ~(near <= guard * hw)
    floor = float(np.median(s[window])) if window.any() else 0.0
    tiny = 1e-300
    snr = float(20.0 * np.log10(max(peak, tiny) / max(floor, tiny))) if peak > 0 else 0.0
    return snr, peak, floor


#: Columns of :func:`band_metrics`.
BAND_METRIC_COLUMNS = (
    "band",
    "fault",
    "harmonic",
    "sideband",
    "center_hz",
    "low_hz",
    "high_hz",
    "peak_amplitude",
    "peak_frequency_hz",
    "band_power",
)


def band_amplitude(
    frequencies: np.ndarray, spectrum: np.ndarray, center: float, *, half_width: float
) -> float | np.ndarray:
    """Largest spectrum value within ``center +/- half_width`` [Hz] (last axis is frequency).

    Parameters
    ----------
    frequencies : ndarray
        Bin frequencies [Hz], increasing.
    spectrum : ndarray
        Amplitude spectrum [U]; the last axis matches ``frequencies``.
    center : float
        Band centre [Hz].
    half_width : float
        Half band width [Hz]; at least half a bin is always searched.

    Returns
    -------
    float or ndarray
        Peak amplitude in the band [U]; 0 where the band lies outside the spectrum.
    """
    f = np.asarray(frequencies, dtype=float)
    s = np.asarray(spectrum, dtype=float)
    half_width = check_positive("half_width", half_width, unit="Hz")
    if not math.isfinite(center):
        raise FeatureError(f"center = {center!r} Hz is not a finite frequency")
    df = f[1] - f[0] if f.size > 1 else 1.0
    hw = max(half_width, 0.5 * df)
    mask = (f >= center - hw) & (f <= center + hw)
    if not mask.any():
        out = np.zeros(s.shape[:-1])
        return float(out) if out.ndim == 0 else out
    out = s[..., mask].max(axis=-1)
    return float(out) if np.ndim(out) == 0 else out


def harmonic_amplitudes(
    frequencies: np.ndarray,
    spectrum: np.ndarray,
    fundamental: float,
    *,
    n_harmonics: int = 3,
    half_width: float,
) -> np.ndarray:
    """Peak amplitude at 1x .. n_harmonics x ``fundamental`` [U], shape (..., n_harmonics).

    Parameters
    ----------
    frequencies : ndarray
        Bin frequencies [Hz], increasing.
    spectrum : ndarray
        Amplitude spectrum [U]; the last axis matches ``frequencies``.
    fundamental : float
        The series' fundamental [Hz], > 0.
    n_harmonics : int
        Harmonics measured.
    half_width : float
        Half band width searched about each harmonic [Hz] (:func:`band_amplitude`).

    Returns
    -------
    ndarray
        Each harmonic's peak amplitude [U] (0 beyond the spectrum), harmonics on the last
        axis.
    """
    fundamental = check_positive("fundamental", fundamental, unit="Hz")
    n_harmonics = check_count("n_harmonics", n_harmonics)
    return np.stack(
        [
            np.asarray(
                band_amplitude(frequencies, spectrum, h * fundamental, half_width=half_width)
            )
            for h in range(1, int(n_harmonics) + 1)
        ],
        axis=-1,
    )


def fault_bands(
    fault_frequencies: Mapping[str, float],
    *,
    n_harmonics: int = 3,
    sidebands: Mapping[str, float] | None = None,
    n_sidebands: int = 1,
    width: float | None = None,
    relative_width: float = 0.02,
    shaft_frequency: float | None = None,
    domain: str = "frequency",
) -> pd.DataFrame:
    """Frequency bands at the harmonics of fault frequencies, with sidebands.

    Parameters
    ----------
    fault_frequencies : mapping of str to float
        Fault name -> fundamental [Hz], e.g. ``{"bpfo": 107.4, "bpfi": 162.2, "two_bsf": 141.2}``.
    n_harmonics : int
        Harmonics 1 .. n of each fault.
    sidebands : mapping of str to float, optional
        Fault name -> sideband spacing [Hz] (e.g. ``{"bpfi": f_shaft, "two_bsf": ftf}``); faults
        not listed get no sidebands.
    n_sidebands : int
        Sidebands -n .. n around each harmonic.
    width : float, optional
        Band width [Hz]; default ``relative_width`` times the fundamental.
    relative_width : float
        Band width as a fraction of the fundamental when ``width`` is None.
    shaft_frequency : float, optional
        Shaft frequency [Hz]; required when ``domain="order"``.
    domain : {"frequency", "order"}
        Report the band edges in Hz or in shaft orders.

    Returns
    -------
    DataFrame
        Columns ``band, fault, harmonic, sideband, center_hz, low_hz, high_hz`` (and ``center``,
        ``low``, ``high`` in orders when ``domain="order"``).
    """
    if domain not in ("frequency", "order"):
        raise FeatureError(f"domain = {domain!r} is not one of 'frequency', 'order'")
    if domain == "order":
        if shaft_frequency is None:
            raise FeatureError("shaft_frequency is required when domain = 'order'")
        shaft_frequency = check_positive("shaft_frequency", shaft_frequency, unit="Hz")
    n_harmonics = check_whole("n_harmonics", n_harmonics)
    n_sidebands = check_whole("n_sidebands", n_sidebands, low=0)
    sidebands = {
        fault: None if not spacing else check_positive(f"sidebands[{fault!r}]", spacing, unit="Hz")
        for fault, spacing in dict(sidebands or {}).items()
    }
    rows = []
    for fault, f0 in check_rates("fault_frequencies", fault_frequencies).items():
        bw = width if width is not None else relative_width * f0
        bw = check_positive("width", bw, unit="Hz")
        spacing = sidebands.get(fault)
        sb_range = range(-int(n_sidebands), int(n_sidebands) + 1) if spacing else (0,)
        for h in range(1, int(n_harmonics) + 1):
            for sb in sb_range:
                center = h * f0 + sb * (spacing or 0.0)
                if center - bw / 2 <= 0:
                    continue
                name = f"{fault}_{h}x" + (f"_{'+' if sb > 0 else '-'}{abs(sb)}sb" if sb else "")
                rows.append((name, fault, h, sb, center, center - bw / 2, center + bw / 2))
    df = pd.DataFrame(
        rows, columns=["band", "fault", "harmonic", "sideband", "center_hz", "low_hz", "high_hz"]
    )
    if domain == "order":
        for col in ("center", "low", "high"):
            df[col] = df[f"{col}_hz"] / shaft_frequency
    return df


def band_metrics(
    frequencies: np.ndarray, spectrum: np.ndarray, bands: pd.DataFrame
) -> pd.DataFrame:
    """Peak amplitude, peak frequency and power of each band (faultBandMetrics style).

    Parameters
    ----------
    frequencies : ndarray
        Bin frequencies [Hz].
    spectrum : ndarray, 1-D
        Amplitude spectrum [U] (peak scaling).
    bands : DataFrame
        Output of :func:`fault_bands` (needs ``band, fault, harmonic, sideband, center_hz,
        low_hz, high_hz``).

    Returns
    -------
    DataFrame
        One row per band, columns ``BAND_METRIC_COLUMNS``; ``band_power`` is the sum of the
        mean-square values of the bins in the band [U^2] (A^2 / 2 per tone). A last row named
        ``total`` sums the band powers and takes the largest peak.
    """
    if not hasattr(bands, "itertuples"):
        raise FeatureError(
            f"bands is a {type(bands).__name__}; give the DataFrame of features.fault_bands"
        )
    f = np.asarray(frequencies, dtype=float)
    s = np.asarray(spectrum, dtype=float)
    if s.ndim != 1 or s.shape != f.shape:
        raise FeatureError(
            f"spectrum has shape {s.shape}; expected a 1-D spectrum matching frequencies {f.shape}"
        )
    df = f[1] - f[0]
    out = []
    for row in bands.itertuples(index=False):
        lo, hi = row.low_hz, row.high_hz
        if hi - lo < df:  # at least one bin
            lo, hi = row.center_hz - df / 2, row.center_hz + df / 2
        mask = (f >= lo) & (f <= hi)
        if mask.any():
            seg = s[mask]
            k = int(np.argmax(seg))
            peak, fpeak, power = float(seg[k]), float(f[mask][k]), float(np.sum(seg**2) / 2)
        else:
            peak, fpeak, power = 0.0, float("nan"), 0.0
        out.append(
            (
                row.band,
                row.fault,
                row.harmonic,
                row.sideband,
                row.center_hz,
                row.low_hz,
                row.high_hz,
                peak,
                fpeak,
                power,
            )
        )
    res = pd.DataFrame(out, columns=list(BAND_METRIC_COLUMNS))
    if len(res):
        k = int(res["peak_amplitude"].values.argmax())
        total = (
            "total",
            "all",
            0,
            0,
            float("nan"),
            float("nan"),
            float("nan"),
            float(res["peak_amplitude"].max()),
            float(res["peak_frequency_hz"].iloc[k]),
            float(res["band_power"].sum()),
        )
        res = pd.concat([res, pd.DataFrame([total], columns=res.columns)], ignore_index=True)
    return res
