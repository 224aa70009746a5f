"""The demodulation band for envelope analysis, chosen by the fault rates.

:func:`select_band` chooses the demodulation band for given fault rates: of the bands of the
kurtogram's 1/3-binary tree at least ``min_bandwidth`` wide (a band narrower than a fault's
modulation cannot show it), the one whose envelope spectrum shows a fault rate highest above
its local floor. Choosing among N bands raises the chance that noise alone reaches a threshold,
so :func:`detection_threshold_db` gives the threshold that keeps the false-alarm probability per
fault at ``FALSE_ALARM`` whatever N is.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from . import _windows
from ._validate import (
    FeatureError,
    check_count,
    check_fs,
    check_positive,
    check_rates,
    check_record,
)
from .false_alarm import FLOOR_BINS, SEARCHED_BINS, detection_threshold_db

__all__ = [
    "ANALYSER_RATIO",
    "BAND_FLOOR_FACTOR",
    "BandSelection",
    "candidate_bands",
    "fault_band",
    "select_band",
]

#: Sample rate over the highest frequency analysed (the analyser convention fs = 2.56 f_max).
ANALYSER_RATIO = 2.56


def candidate_bands(
    fs: float,
    n: int,
    *,
    min_bandwidth: float,
    nlevel: int = 6,
    max_frequency: float | None = None,
    min_frequency: float = 0.0,
) -> list[tuple[float, float]]:
    """The bands of the kurtogram's 1/3-binary tree that are at least ``min_bandwidth`` wide.

    Bands reaching above ``max_frequency`` are cut there, bands starting below
    ``min_frequency`` start there (and either is dropped when then too narrow); when no band
    is left above ``min_frequency``, the tree without it.

    Parameters
    ----------
    fs : float
        Sample rate [Hz].
    n : int
        Record length [samples] (a band holds at least 64 bins).
    min_bandwidth : float
        Narrowest band [Hz].
    nlevel : int
        Deepest level (level k has 2^k bands; the 1/3 levels 3 x 2^(k-1)).
    max_frequency : float, optional
        Highest frequency analysed [Hz]; default ``fs / ANALYSER_RATIO``, the alias-free
        span of an analyser (what lies above has been through the anti-alias filter's
        transition band).
    min_frequency : float
        Lowest frequency a band may hold [Hz] (default 0).

    Returns
    -------
    list of (float, float)
        (low, high) [Hz], widest first.
    """
    fs = check_fs(fs)
    n = check_count("n", n)
    min_bandwidth = check_positive("min_bandwidth", min_bandwidth, unit="Hz")
    nlevel = check_count("nlevel", nlevel, low=1, high=12)
    top = (
        fs / ANALYSER_RATIO
        if max_frequency is None
        else check_positive("max_frequency", max_frequency, unit="Hz")
    )
    min_frequency = float(min_frequency)
    if not 0.0 <= min_frequency < top:
        raise FeatureError(
            f"min_frequency = {min_frequency!r} Hz is outside the allowed range [0, {top:g}) Hz"
        )
    splits = [1]
    for k in range(1, int(nlevel) + 1):
        splits += [2**k, 3 * 2 ** (k - 1)]
    out = []
    for nb in sorted(set(splits)):
        bw = fs / 2 / nb
        if bw < min_bandwidth or bw * n / fs < 64:
            continue
        for b in range(nb):
            low, high = max(b * bw, min_frequency), min((b + 1) * bw, top)
            if high - low >= min_bandwidth and (low, high) not in out:
                out.append((low, high))
    if not out and min_frequency > 0.0:
        return candidate_bands(
            fs, n, min_bandwidth=min_bandwidth, nlevel=nlevel, max_frequency=max_frequency
        )
    if not out:
        out = [(0.0, top)]
    return out


@dataclass(frozen=True)
class BandSelection:
    """The band :func:`select_band` chose, and what it saw in every candidate.

    Attributes
    ----------
    band : (float, float)
        Chosen band [Hz].
    score_db : float
        Its best envelope line-to-floor ratio at a fault rate [dB].
    rate : str
        The fault rate that gave it.
    bands : list of (float, float)
        Every candidate band [Hz].
    scores_db : ndarray, shape (len(bands), len(rates))
        Line-to-floor ratio per band and rate [dB].
    rates : tuple of str
        Names of the rates (columns of ``scores_db``).
    searched_bins, floor_bins : int
        Most bins searched for a line and fewest bins of a floor (the threshold's inputs).
    """

    band: tuple[float, float]
    score_db: float
    rate: str
    bands: list[tuple[float, float]]
    scores_db: np.ndarray
    rates: tuple[str, ...]
    searched_bins: int = SEARCHED_BINS
    floor_bins: int | None = None

    @property
    def threshold_db(self) -> float:
        """Threshold for a false alarm of ``FALSE_ALARM`` per rate over every band searched."""
        return detection_threshold_db(
            len(self.bands), searched_bins=self.searched_bins, floor_bins=self.floor_bins
        )


def _band_envelope_spectrum(spec: np.ndarray, df: float, low: float, high: float):
    """Envelope spectrum of one band from the record's FFT bins (decimated analytic signal)."""
    i0, i1 = int(math.ceil(low / df)), int(math.floor(high / df))
    m = i1 - i0 + 1
    weights = _windows.tukey(m, 0.25) if m > 2 else np.ones(m)
    z = np.fft.ifft(spec[i0 : i1 + 1] * weights)  # analytic band signal at rate m * df
    env = np.abs(z)
    env = env - env.mean()
    amp = np.abs(np.fft.rfft(env * _windows.hanning(m)))
    return np.arange(amp.size) * df, amp


def _ratio_db(freqs: np.ndarray, amp: np.ndarray, line: float) -> tuple[float, int, int]:
    """A line's peak over the median of its neighbourhood [dB], bins searched, floor bins."""
    df = freqs[1] - freqs[0]
    hw = max(1.5 * df, 0.005 * line)
    reach = max(0.1 * line, FLOOR_BINS * df, hw)
    # only the bins within reach of the line can be selected (a uniform grid): the masks on
    # that slice, two bins wider each side than rounding could move its ends
    lo = max(0, int(math.floor((line - reach - freqs[0]) / df)) - 2)
    hi = min(freqs.size, max(lo, int(math.ceil((line + reach - freqs[0]) / df)) + 3))
    near = np.abs(freqs[lo:hi] - line)
    amp = amp[lo:hi]
    sel = near <= hw
    window = (near <= max(0.1 * line, FLOOR_BINS * df)) & ~(near <= 2 * hw)
    if not sel.any() or window.sum() < 3 or line + hw > freqs[-1]:
        return 0.0, 1, 3
    floor = float(np.median(amp[window]))
    peak = float(amp[sel].max())
    ratio = 20.0 * math.log10(peak / floor) if peak > 0 and floor > 0 else 0.0
    return ratio, int(sel.sum()), int(window.sum())


def _ratio_db_bands(
    spectra: Sequence[tuple[np.ndarray, np.ndarray]], df: float, line: float
) -> list[tuple[float, int, int]]:
    """:func:`_ratio_db` of one line in every band's envelope spectrum, to the same bits.

    Every band's envelope spectrum lies on the same grid, k x ``df`` from 0 Hz
    (:func:`_band_envelope_spectrum`), so the bins within reach of the line, and which of
    them are searched and which are the floor, are the same in each band long enough to hold
    them all: their peaks and medians are taken in one pass over the stacked bins (a median
    along an axis is the 1-D median of each row); a band too short for that is measured
    alone.
    """
    out: list[tuple[float, int, int] | None] = [None] * len(spectra)
    hw = max(1.5 * df, 0.005 * line)
    reach = max(0.1 * line, FLOOR_BINS * df, hw)
    lo = max(0, int(math.floor((line - reach) / df)) - 2)
    hi = max(lo, int(math.ceil((line + reach) / df)) + 3)
    # a band that holds bins lo .. hi - 1 reaches past line + reach >= line + hw, and its
    # bins within hw (at least 1.5 bins each side) and its floor's (50 bins or more each
    # side) are never too few: _ratio_db's answer for a missing line cannot arise there
    whole = [i for i, (freqs, _) in enumerate(spectra) if freqs.size >= hi]
    if whole:
        near = np.abs(np.arange(lo, hi) * df - line)
        sel = near <= hw
        window = (near <= max(0.1 * line, FLOOR_BINS * df)) & ~(near <= 2 * hw)
        stacked = np.stack([spectra[i][1][lo:hi] for i in whole])
        floors = np.median(stacked[:, window], axis=1)
        peaks = stacked[:, sel].max(axis=1)
        searched, floor_bins = int(sel.sum()), int(window.sum())
        for i, peak, floor in zip(whole, peaks.tolist(), floors.tolist(), strict=True):
            ratio = 20.0 * math.log10(peak / floor) if peak > 0 and floor > 0 else 0.0
            out[i] = (ratio, searched, floor_bins)
    for i, (freqs, amp) in enumerate(spectra):
        if out[i] is None:
            out[i] = _ratio_db(freqs, amp, line)
    return out  # type: ignore[return-value]


def select_band(
    x: np.ndarray,
    fs: float,
    rates: Mapping[str, float],
    *,
    min_bandwidth: float | None = None,
    nlevel: int = 6,
    min_frequency: float = 0.0,
    floors: Mapping[str, float] | None = None,
) -> BandSelection:
    """The demodulation band where the envelope shows one of ``rates`` most clearly.

    Parameters
    ----------
    x : array_like, 1-D
        Signal [U] (best its random part, :func:`separate_discrete`).
    fs : float
        Sample rate [Hz].
    rates : mapping of str to float
        Fault rates to look for [Hz] (e.g. ``{"bpfo": 107.4, "bpfi": 162.2}``).
    min_bandwidth : float, optional
        Narrowest band [Hz]; default 3 x the fastest rate (the carrier, its first sidebands
        and a margin), at most fs / 4.
    nlevel : int
        Depth of the band tree.
    min_frequency : float
        Lowest frequency a band may hold [Hz]: bands starting below start there (default 0,
        the whole tree; the rule's :func:`fault_band` starts at 3 x the fastest rate, the
        highest envelope line weighed: docs/diagnosis.md, "Bands from 0 Hz").
    floors : mapping of str to float, optional
        Per rate, the lowest band start [Hz] at which that rate is scored (its score in lower
        bands is not counted; ``scores_db`` holds -inf there). For a slow rate whose line
        the machine's low-frequency lines can make by beating with each other in a band
        from 0 Hz: :func:`fault_band` scores the cage rate only from 3 x the fastest fault
        rate up.

    Returns
    -------
    BandSelection
        The chosen band, its score, and the scores of every candidate.
    """
    x = check_record(x, function="select_band", min_length=64)
    fs = check_fs(fs)
    checked = check_rates("rates", rates, fs=fs, allow_empty=False)
    names = tuple(checked)
    values = np.array([checked[k] for k in names])
    if min_bandwidth is None:
        min_bandwidth = min(3.0 * float(values.max()), fs / 4)
    bands = candidate_bands(
        fs, x.size, min_bandwidth=min_bandwidth, nlevel=nlevel, min_frequency=min_frequency
    )
    n = x.size
    spec = np.fft.fft((x - x.mean()) * _windows.tukey(n, 0.05))
    df = fs / n
    spectra = [_band_envelope_spectrum(spec, df, low, high) for low, high in bands]
    scores = np.zeros((len(bands), len(names)))
    searched, floor = 1, None
    for j, r in enumerate(values):
        for i, (ratio, bins, floor_bins) in enumerate(_ratio_db_bands(spectra, df, r)):
            scores[i, j] = ratio
            searched = max(searched, bins)
            floor = floor_bins if floor is None else min(floor, floor_bins)
    for name, lowest in (floors or {}).items():
        if name not in names:
            raise FeatureError(f"floors names {name!r}, which is not one of the rates {names}")
        starts = np.array([low for low, _ in bands])
        scores[starts < lowest, names.index(name)] = -np.inf
    if not np.isfinite(scores).any():
        raise FeatureError(f"floors = {dict(floors or {})} leave no band to score a rate in")
    i, j = np.unravel_index(int(np.argmax(scores)), scores.shape)
    return BandSelection(
        band=(float(bands[i][0]), float(bands[i][1])),
        score_db=float(scores[i, j]),
        rate=names[j],
        bands=bands,
        scores_db=scores,
        rates=names,
        searched_bins=searched,
        floor_bins=floor,
    )


#: The rule's bands start at this many times the fastest fault rate or higher (the highest
#: envelope line weighed): a band that holds the fault rates themselves has no carrier, its
#: "envelope" mixes the machine's low-frequency lines, whose beats can fall on a fault rate
#: or on the cage rate (docs/diagnosis.md, "Bands from 0 Hz" and "The cage rate chooses the
#: ball's band").
BAND_FLOOR_FACTOR = 3.0


def fault_band(
    random_part: np.ndarray,
    fs: float,
    rates: Mapping[str, float],
    cage_rate: float | None = None,
    *,
    nlevel: int = 6,
    min_frequency: float | None = None,
) -> BandSelection:
    """The band ``cmtool diagnose`` and :func:`features.fault_evidence` demodulate.

    :func:`select_band` over the fault ``rates`` and, when ``cage_rate`` is given, the cage
    rate as one more: a ball pit strikes only while its ball crosses the load zone, once per
    cage revolution, so its impacts come in bursts whose cage-rate line can stand where the
    slip-smeared 2 x BSF does not (Randall and Antoni 2011). Every band starts at
    ``BAND_FLOOR_FACTOR`` x the fastest fault rate or higher, and the cage rate is scored
    only there whatever ``min_frequency`` says.

    Parameters
    ----------
    random_part : array_like, 1-D
        The signal's random part [U] (:func:`separate_discrete`).
    fs : float
        Sample rate [Hz].
    rates : mapping of str to float
        Fault rates [Hz] (``bpfo``, ``bpfi``, ``two_bsf``).
    cage_rate : float, optional
        The cage rate (FTF) [Hz].
    nlevel : int
        Depth of the band tree.
    min_frequency : float, optional
        Lowest frequency a band may hold [Hz] (:func:`select_band`); default
        ``BAND_FLOOR_FACTOR`` x the fastest fault rate (0: the whole tree, as before stop 44).

    Returns
    -------
    BandSelection
        As :func:`select_band`; with ``cage_rate``, ``rates`` ends with ``"ftf"``.
    """
    floor = BAND_FLOOR_FACTOR * max(float(v) for v in rates.values())
    min_frequency = floor if min_frequency is None else min_frequency
    if cage_rate is None:
        return select_band(random_part, fs, rates, nlevel=nlevel, min_frequency=min_frequency)
    return select_band(
        random_part,
        fs,
        {**rates, "ftf": cage_rate},
        nlevel=nlevel,
        min_frequency=min_frequency,
        floors={"ftf": floor},
    )
