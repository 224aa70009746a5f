"""The feature table: one row of named features per signal, from the signal and its context.

Context = sample rate, shaft frequency and fault frequencies (numbers, from the caller: this
package does not know the bearing physics). The amplitude spectrum, the kurtogram and the
envelope spectrum are computed once per signal and shared by every feature that uses them.

Feature names and units (U = unit of the signal, dB = 20 log10 of a ratio):

* time statistics (``features.stats.TIME_STATISTICS``);
* ``spectrum_<fault>_h<k>`` [U], ``spectrum_<fault>_h<k>_snr`` [dB]: peak of the amplitude
  spectrum within +/- ``half_width`` of k x fault, and its ratio to the local noise floor (median
  of the spectrum within +/- 10 % of the line, the line's own bins excluded);
* ``envelope_<fault>_h<k>`` [U], ``envelope_<fault>_h<k>_snr`` [dB]: the same on the envelope
  spectrum of the band chosen by the kurtogram (or given);
* ``envelope_<fault>_sideband_snr`` [dB]: mean SNR of the first lower and upper sidebands of
  the fundamental (spacing: shaft frequency for ``bpfi``, cage frequency for ``two_bsf``);
* ``spectrum_<fault>_h<k>_sideband_snr`` [dB]: largest SNR in the amplitude spectrum among the
  sidebands k x fault +/- m x spacing, m = 1 .. ``SPECTRUM_SIDEBANDS`` (waviness of the inner
  race puts its lines at q BPFI + (N_w - qZ) f_s, of the balls at 2p BSF +/- FTF: docs/model.md
  2.1);
* the kurtogram band is at least ``MIN_BAND_FACTOR`` times the fastest fault rate wide;
* ``spectrum_<fault>_max_snr`` [dB]: the largest of the fault's spectrum SNRs above (its
  harmonics and, where defined, their sidebands): one number per fault family;
* ``kurtogram_kurtosis`` [-], ``kurtogram_center_rel`` [-] (centre / (fs/2)),
  ``kurtogram_bandwidth_rel`` [-] (bandwidth / (fs/2));
* ``shaft_frequency`` [Hz]: the context's shaft frequency (0 when not given). A classifier
  needs it to know what a healthy bearing looks like at that speed: the varying-compliance
  lines at q x BPFO, which outer-race waviness also excites, change with speed through the
  housing's transfer function (docs/model.md 2.1).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ._validate import (
    FeatureError,
    check_count,
    check_fs,
    check_positive,
    check_rates,
    check_record,
    check_whole,
)
from .bands import line_snr
from .envelope import KurtogramResult, envelope, kurtogram
from .spectra import amplitude_spectrum
from .stats import TIME_STATISTICS, time_statistics

__all__ = [
    "Spectra",
    "compute_spectra",
    "extract_features",
    "feature_names",
    "feature_units",
    "DEFAULT_FAULTS",
    "SIDEBAND_SPACING",
]

#: Fault frequencies a feature table uses by default (keys of the context mapping).
DEFAULT_FAULTS = ("bpfo", "bpfi", "two_bsf", "ftf")
#: Sideband spacing per fault: the context key that gives it.
SIDEBAND_SPACING = {"bpfi": "shaft", "two_bsf": "ftf"}
#: Sidebands searched per harmonic in the amplitude spectrum.
SPECTRUM_SIDEBANDS = 1
#: The kurtogram may only choose bands at least this many times wider than the fastest fault
#: rate measured: the demodulation band must pass a fault's carrier with its first sidebands
#: (+/- f_fault) and some margin, or the envelope cannot show the fault rate.
MIN_BAND_FACTOR = 3.0


@dataclass(frozen=True)
class Spectra:
    """Spectra of one signal, computed once and shared by the features.

    Attributes
    ----------
    frequencies, amplitude : ndarray
        Amplitude spectrum [Hz], [U].
    envelope_frequencies, envelope_amplitude : ndarray
        Envelope spectrum [Hz], [U].
    band : (float, float)
        Demodulation band [Hz].
    kurtogram : KurtogramResult or None
        The kurtogram when it chose the band.
    """

    frequencies: np.ndarray
    amplitude: np.ndarray
    envelope_frequencies: np.ndarray
    envelope_amplitude: np.ndarray
    band: tuple[float, float]
    kurtogram: KurtogramResult | None


def compute_spectra(
    x: np.ndarray,
    fs: float,
    *,
    band: tuple[float, float] | None = None,
    nlevel: int = 6,
    min_bandwidth: float | None = None,
) -> Spectra:
    """Amplitude spectrum, kurtogram (if ``band`` is None) and envelope spectrum of ``x``.

    Parameters
    ----------
    x : array_like, 1-D
        Signal [U], at least 64 samples.
    fs : float
        Sample rate [Hz].
    band : (float, float), optional
        Demodulation band [Hz]; default the fast kurtogram's band.
    nlevel : int
        Levels of the kurtogram (1 .. 12), when it chooses the band.
    min_bandwidth : float, optional
        The kurtogram's narrowest band [Hz] (:func:`features.kurtogram`).

    Returns
    -------
    Spectra
        The amplitude and envelope spectra [Hz], [U], the band [Hz] and the kurtogram (None
        when ``band`` was given).
    """
    x = check_record(x, function="compute_spectra", min_length=64)
    fs = check_fs(fs)
    freqs, amp = amplitude_spectrum(x, fs)
    kg = None
    if band is None:
        kg = kurtogram(x, fs, nlevel=nlevel, min_bandwidth=min_bandwidth)
        band = kg.band
    env = envelope(x, fs, band=band)
    ef, ea = amplitude_spectrum(env, fs)
    return Spectra(freqs, amp, ef, ea, (float(band[0]), float(band[1])), kg)


def feature_names(faults: Sequence[str] = DEFAULT_FAULTS, n_harmonics: int = 3) -> list[str]:
    """Names of the features of :func:`extract_features`, in order.

    Parameters
    ----------
    faults : sequence of str
        The fault rates measured (keys of ``fault_frequencies``: ``bpfo``, ``bpfi``,
        ``two_bsf``, ``ftf``, ...).
    n_harmonics : int
        Harmonics per rate.

    Returns
    -------
    list of str
        The names, in the order of :func:`extract_features`' values.
    """
    n_harmonics = check_whole("n_harmonics", n_harmonics)
    names = list(TIME_STATISTICS)
    for kind in ("spectrum", "envelope"):
        for fault in faults:
            for k in range(1, n_harmonics + 1):
                names += [f"{kind}_{fault}_h{k}", f"{kind}_{fault}_h{k}_snr"]
    names += [f"envelope_{f}_sideband_snr" for f in faults if f in SIDEBAND_SPACING]
    names += [
        f"spectrum_{f}_h{k}_sideband_snr"
        for f in faults
        if f in SIDEBAND_SPACING
        for k in range(1, n_harmonics + 1)
    ]
    names += [f"spectrum_{f}_max_snr" for f in faults]
    names += ["kurtogram_kurtosis", "kurtogram_center_rel", "kurtogram_bandwidth_rel"]
    names += ["shaft_frequency"]
    return names


def feature_units(faults: Sequence[str] = DEFAULT_FAULTS, n_harmonics: int = 3) -> dict[str, str]:
    """Unit of each feature ("U" is the signal's unit).

    Parameters
    ----------
    faults : sequence of str
        The fault rates measured, as for :func:`feature_names`.
    n_harmonics : int
        Harmonics per rate.

    Returns
    -------
    dict of str to str
        Per feature name, its unit: ``"U"`` (the signal's), ``"dB"``, ``"Hz"`` or ``"-"``
        (dimensionless).
    """
    units = {}
    for name in feature_names(faults, n_harmonics):
        if name in TIME_STATISTICS:
            units[name] = TIME_STATISTICS[name]
        elif name.endswith("_snr"):
            units[name] = "dB"
        elif name.startswith("kurtogram"):
            units[name] = "-"
        elif name == "shaft_frequency":
            units[name] = "Hz"
        else:
            units[name] = "U"
    return units


def extract_features(
    x: np.ndarray,
    fs: float,
    *,
    fault_frequencies: Mapping[str, float],
    shaft_frequency: float | None = None,
    faults: Sequence[str] = DEFAULT_FAULTS,
    n_harmonics: int = 3,
    half_width: float | None = None,
    spectra: Spectra | None = None,
    band: tuple[float, float] | None = None,
) -> dict[str, float]:
    """One row of features for a signal (see the module docstring for names and units).

    Parameters
    ----------
    x : array_like, 1-D
        Signal [U].
    fs : float
        Sample rate [Hz].
    fault_frequencies : mapping of str to float
        Context: must contain every name in ``faults`` [Hz] (e.g. ``ftf, bpfo, bpfi,
        two_bsf``); ``shaft`` may be given here or as ``shaft_frequency``.
    shaft_frequency : float, optional
        Shaft frequency [Hz].
    faults : sequence of str
        Fault frequencies to measure.
    n_harmonics : int
        Harmonics per fault.
    half_width : float, optional
        Search half-width around each line [Hz]; default max(1.5 bins, 0.5 % of the line).
    spectra : Spectra, optional
        Precomputed spectra (librosa's y-or-S idea); computed here if not given.
    band : (float, float), optional
        Demodulation band [Hz]; default chosen by the kurtogram.

    Returns
    -------
    dict of str to float
        Features in the order of :func:`feature_names`.
    """
    fs = check_fs(fs)
    n_harmonics = check_count("n_harmonics", n_harmonics)
    if not isinstance(fault_frequencies, Mapping):
        check_rates("fault_frequencies", fault_frequencies)  # refuses it by name
    context = dict(fault_frequencies)
    if shaft_frequency is not None:
        context["shaft"] = shaft_frequency
    for name in faults:
        if name not in context:
            raise FeatureError(f"fault_frequencies has no {name!r}; it needs {list(faults)}")
        check_positive(f"fault_frequencies[{name!r}]", context[name], unit="Hz")
    x = check_record(x, function="extract_features", min_length=64)
    if spectra is None:
        fastest = max(float(context[f]) for f in faults)
        spectra = compute_spectra(
            x, fs, band=band, min_bandwidth=min(MIN_BAND_FACTOR * fastest, fs / 4)
        )
    out: dict[str, float] = dict(time_statistics(x))
    df = spectra.frequencies[1] - spectra.frequencies[0]
    for kind, freqs, spec in (
        ("spectrum", spectra.frequencies, spectra.amplitude),
        ("envelope", spectra.envelope_frequencies, spectra.envelope_amplitude),
    ):
        for fault in faults:
            f0 = float(context[fault])
            for k in range(1, n_harmonics + 1):
                hw = half_width if half_width is not None else max(1.5 * df, 0.005 * k * f0)
                snr, peak, _ = line_snr(freqs, spec, k * f0, half_width=hw)
                out[f"{kind}_{fault}_h{k}"] = peak
                out[f"{kind}_{fault}_h{k}_snr"] = snr
    for fault in faults:
        if fault not in SIDEBAND_SPACING:
            continue
        spacing = context.get(SIDEBAND_SPACING[fault])
        f0 = float(context[fault])
        if spacing is None or spacing <= 0:
            out[f"envelope_{fault}_sideband_snr"] = 0.0
            continue
        hw = half_width if half_width is not None else max(1.5 * df, 0.005 * f0)
        snrs = []
        for sign in (-1, 1):
            snr, _, _ = line_snr(
                spectra.envelope_frequencies,
                spectra.envelope_amplitude,
                f0 + sign * spacing,
                half_width=hw,
            )
            snrs.append(snr)
        out[f"envelope_{fault}_sideband_snr"] = float(np.mean(snrs))
    for fault in faults:
        if fault not in SIDEBAND_SPACING:
            continue
        spacing = context.get(SIDEBAND_SPACING[fault])
        f0 = float(context[fault])
        for k in range(1, n_harmonics + 1):
            best = 0.0
            if spacing is not None and spacing > 0:
                hw = half_width if half_width is not None else max(1.5 * df, 0.003 * k * f0)
                for m in range(1, SPECTRUM_SIDEBANDS + 1):
                    for sign in (-1, 1):
                        line = k * f0 + sign * m * spacing
                        if line <= 0:
                            continue
                        snr, _, _ = line_snr(
                            spectra.frequencies, spectra.amplitude, line, half_width=hw
                        )
                        best = max(best, snr)
            out[f"spectrum_{fault}_h{k}_sideband_snr"] = best
    for fault in faults:
        keys = [f"spectrum_{fault}_h{k}_snr" for k in range(1, n_harmonics + 1)]
        keys += [
            f"spectrum_{fault}_h{k}_sideband_snr"
            for k in range(1, n_harmonics + 1)
            if fault in SIDEBAND_SPACING
        ]
        out[f"spectrum_{fault}_max_snr"] = max(out[k] for k in keys)
    low, high = spectra.band
    kg = spectra.kurtogram
    out["kurtogram_kurtosis"] = kg.kurtosis if kg is not None else 0.0
    out["kurtogram_center_rel"] = (low + high) / fs
    out["kurtogram_bandwidth_rel"] = (high - low) / (fs / 2)
    out["shaft_frequency"] = float(context.get("shaft", 0.0))
    return out
