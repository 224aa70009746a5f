"""The improved envelope spectrum as ``cmtool bench`` detectors: measured, not shipped (stop 86).

The improved envelope spectrum (IES; Abboud and Antoni, "Order-frequency analysis of machine
signals", MSSP 2017) is the spectral coherence of a signal integrated over the spectral
frequency: each carrier band's squared envelope spectrum normalised by that band's own power,
then averaged over the bands, so that every band where a fault's impacts ring weighs alike
and no band has to be chosen. Its spectral coherence is estimated here by the cyclic
modulation spectrum (the same reference): a Hann short-time transform of ``nw`` samples, hop
``nw / 4``; in each carrier bin from 3 x the fastest fault rate (where the rule's bands start)
up to fs/2.56 (the analyser span) the DFT over time of the bin's power, divided by its mean
(the coherence at cyclic frequency alpha), its magnitude averaged over the bins. A carrier bin
passes modulations up to about its bandwidth, so ``nw`` is the largest power of two with
fs / nw >= ``factor`` x the fastest fault rate (factor 4: the third harmonic of the fastest
rate and its sidebands pass). The scores are ``cmtool bench``'s for the squared envelope
spectrum detectors: the mean power of the first three lines of each fault rate over the local
median, each searched within the slip (``features.detectors``); the label, as theirs, names
the best-scoring fault over 10 dB (the benchmark's figures at fixed false-alarm rates set
their own thresholds on the healthy signals).

Variants (each a detector ``f(x, fs, rpm, bearing)``): ``raw`` the signal as recorded; ``cpw``
after cepstral pre-whitening (``features.prewhiten``, as the built-in ``cpw_ses``);
``separated`` after the rule's separation of the shaft's and the ball pass's harmonics and
the discrete lines (``features.separate_discrete``); ``cpw_narrow`` and ``cpw_wide`` as ``cpw``
with factor 2 and 8.

Run (docs/benchmark.md, "The improved envelope spectrum"; about 2 minutes a run on two cores):
    cmtool generate datasets/detector-bench.toml --out out/detector-bench --workers 2
    PYTHONPATH=benchmarks .venv/bin/cmtool bench out/detector-bench --workers 2 \
        --detector improved_envelope:raw --detector improved_envelope:cpw \
        --detector improved_envelope:separated --out out/ies-bench
"""

from __future__ import annotations

import math

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

from features import prewhiten, separate_discrete
from features.detectors import _ses_line_scores
from generators import bearing as catalog_bearing
from generators import characteristic_frequencies

#: ``cmtool bench``'s fault classes and the rate each is scored at.
FAULT_RATES = {"outer race": "bpfo", "inner race": "bpfi", "ball": "two_bsf"}
#: A detector's label names the best fault when its score exceeds this [dB] (as the SES
#: detectors of ``cmtool bench``).
LABEL_DB = 10.0


def improved_envelope_spectrum(
    x: np.ndarray, fs: float, fastest_rate: float, factor: float = 4.0
) -> tuple[np.ndarray, np.ndarray]:
    """The improved envelope spectrum by the cyclic modulation spectrum.

    Parameters
    ----------
    x : array_like, 1-D
        Signal [U].
    fs : float
        Sample rate [Hz].
    fastest_rate : float
        The fastest fault rate [Hz]: the carrier bins start at 3 x it, and the window's
        bandwidth is at least ``factor`` x it.
    factor : float
        The carrier bins' spacing fs / nw over ``fastest_rate`` (at least).

    Returns
    -------
    alpha : ndarray
        Cyclic frequencies [Hz], from 0 in steps of 1 / (frames x hop / fs).
    ies : ndarray
        The spectral coherence's magnitude averaged over the carrier bins [-] (1 at 0 Hz).
    """
    x = np.asarray(x, dtype=float)
    x = x - x.mean()
    nw = max(8, 2 ** math.floor(math.log2(fs / (factor * fastest_rate))))
    hop = max(1, nw // 4)
    frames = sliding_window_view(x, nw)[::hop] * np.hanning(nw)
    power = np.abs(np.fft.rfft(frames, axis=1)) ** 2
    carriers = np.fft.rfftfreq(nw, 1.0 / fs)
    keep = (carriers >= 3.0 * fastest_rate) & (carriers <= fs / 2.56)
    if not keep.any():
        keep = carriers > 0
    cyclic = np.fft.rfft(power[:, keep], axis=0)
    coherence = np.abs(cyclic) / np.maximum(cyclic[0].real, 1e-300)
    return np.fft.rfftfreq(power.shape[0], hop / fs), coherence.mean(axis=1)


def _scores(y: np.ndarray, fs: float, rpm: float, bearing, factor: float = 4.0) -> dict:
    geometry = catalog_bearing(bearing) if isinstance(bearing, str) else bearing
    rates_hz = characteristic_frequencies(geometry, rpm / 60.0)
    rates = {fault: getattr(rates_hz, key) for fault, key in FAULT_RATES.items()}
    alpha, ies = improved_envelope_spectrum(y, fs, max(rates.values()), factor)
    scores = _ses_line_scores(alpha[1:], ies[1:], rates, 3)
    best = max(scores, key=scores.get)
    return {"label": best if scores[best] > LABEL_DB else "healthy", "scores": scores}


def raw(x, fs, rpm, bearing) -> dict:
    """The IES of the signal as recorded."""
    return _scores(np.asarray(x, dtype=float), fs, rpm, bearing)


def cpw(x, fs, rpm, bearing) -> dict:
    """The IES after cepstral pre-whitening."""
    return _scores(prewhiten(np.asarray(x, dtype=float)), fs, rpm, bearing)


def cpw_narrow(x, fs, rpm, bearing) -> dict:
    """As :func:`cpw`, carrier bins at least 2 x the fastest rate apart."""
    return _scores(prewhiten(np.asarray(x, dtype=float)), fs, rpm, bearing, factor=2.0)


def cpw_wide(x, fs, rpm, bearing) -> dict:
    """As :func:`cpw`, carrier bins at least 8 x the fastest rate apart."""
    return _scores(prewhiten(np.asarray(x, dtype=float)), fs, rpm, bearing, factor=8.0)


def separated(x, fs, rpm, bearing) -> dict:
    """The IES of the rule's random part (shaft and ball-pass harmonics, discrete lines)."""
    geometry = catalog_bearing(bearing) if isinstance(bearing, str) else bearing
    rates_hz = characteristic_frequencies(geometry, rpm / 60.0)
    y = separate_discrete(
        np.asarray(x, dtype=float), fs, fundamentals=(rates_hz.shaft, rates_hz.bpfo)
    )
    return _scores(y, fs, rpm, bearing)
