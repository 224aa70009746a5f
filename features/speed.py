"""The shaft's running speed read from a record's spectrum: its 1x line near a given speed.

An analyst checks the speed a recording was labelled with against the spectrum's 1x line
before reading any fault rate off it: an induction motor runs 1-4 % below its synchronous
speed (more under load), and fault lines searched at rates computed from a speed 2 % off are
searched in the wrong place (docs/diagnosis.md, "The speed the rates come from").
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.fft

from ._validate import (
    FeatureError,
    check_count,
    check_fs,
    check_positive,
    check_record,
)
from .chirp_z import ChirpZ
from .instrument_floor import instrument_floor_median
from .spectra import peak_offset_bins

__all__ = [
    "SpeedEstimate",
    "TachoSpeed",
    "shaft_rate_from_spectrum",
    "shaft_rate_from_tacho",
    "order_track",
    "ORDER_TRACK_UPSAMPLING",
    "SPEED_SEARCH",
    "SHAFT_LINE_DB",
    "MAINS_HZ",
]

#: The 1x line is searched this far either side of the given rate (fraction): an induction
#: motor's slip at full load is 1-4 % (more for small motors), a tachometer's error far less.
SPEED_SEARCH = 0.05
#: The 1x line counts as found this far over its floor [dB] (the median of the spectrum
#: within 20 % of the given rate).
SHAFT_LINE_DB = 12.0
#: Mains frequencies [Hz]: the bins within three of one of their harmonics are not searched
#: (a 1x line there cannot be told from the electrical one).
MAINS_HZ = (50.0, 60.0)
#: Zero padding of the spectrum (its bins this many times finer than the record's), less
#: for a record of over 262,144 samples (at most 2**22 points transformed, or twice the
#: record: a 10 s record at 48 kHz then holds about 80 MB while it is read).
_PAD = 16


@dataclass(frozen=True)
class SpeedEstimate:
    """The shaft rate the spectrum's 1x line shows near a given rate.

    Attributes
    ----------
    rate_hz : float
        The estimated shaft rate [Hz] (``given_hz`` when no 1x line is found).
    given_hz : float
        The rate it was searched about [Hz].
    line_db : float
        The 1x line's height over its floor [dB].
    found : bool
        Whether a 1x line stands ``SHAFT_LINE_DB`` or more over its floor.
    """

    rate_hz: float
    given_hz: float
    line_db: float
    found: bool

    @property
    def deviation(self) -> float:
        """``rate_hz / given_hz - 1`` (negative: the shaft runs slower than given)."""
        return self.rate_hz / self.given_hz - 1.0


def _peak(
    spectrum: np.ndarray, fine: float, low: float, high: float, mask_hz: float
) -> tuple[float, float]:
    """The largest bin of ``spectrum`` in [low, high] Hz away from the mains harmonics.

    Bins within ``mask_hz`` of a harmonic of ``MAINS_HZ`` are left out. Returns its
    frequency [Hz] (parabolic interpolation on the log amplitude) and its amplitude, 0 when
    every bin is masked or the bin is the search's first or last and the spectrum rises
    beyond it (the skirt of a line outside the search, whose interpolation would put the
    rate at that line's frequency).
    """
    lo = max(1, int(math.ceil(low / fine)))
    hi = min(spectrum.size - 2, int(math.floor(high / fine)))
    f = np.arange(lo, hi + 1) * fine
    part = spectrum[lo : hi + 1].copy()
    for m in MAINS_HZ:
        part[np.abs(f - m * np.maximum(np.round(f / m), 1.0)) <= mask_hz] = 0.0
    k = lo + int(np.argmax(part))
    outward = (k == lo and spectrum[k - 1] > spectrum[k]) or (
        k == hi and spectrum[k + 1] > spectrum[k]
    )
    if part[k - lo] <= 0.0 or outward:
        return float(k * fine), 0.0
    return (k + peak_offset_bins(spectrum, k)) * fine, float(spectrum[k])


def _padded_spectrum(xw: np.ndarray, points: int, first_bin: int, last_bin: int) -> np.ndarray:
    """``abs(rfft(xw, points))``, computed only in bins ``first_bin..last_bin`` (0 elsewhere).

    A transform length with prime factors other than 2, 3 and 5 (a measured record's length
    times the padding) makes the FFT slow (0.8-2 s for the CWRU files' 1.9-3.9 million
    points); the chirp-z transform then evaluates the same bins (the same DTFT samples, within
    1e-8 of the largest) from the record alone. Lengths the FFT does fast keep the FFT.
    """
    if scipy.fft.next_fast_len(points, real=True) == points:
        return np.abs(np.fft.rfft(xw, points))
    spectrum = np.zeros(points // 2 + 1)
    count = last_bin - first_bin + 1
    transform = ChirpZ(xw.size, count, -1.0 / points, first_bin / points)
    spectrum[first_bin : last_bin + 1] = np.abs(transform(xw))
    return spectrum


def shaft_rate_from_spectrum(
    x: np.ndarray, fs: float, given_hz: float, *, search: float = SPEED_SEARCH
) -> SpeedEstimate:
    """The shaft rate the record's 1x line shows within ``search`` of ``given_hz``.

    The largest line of the record's Hann-windowed spectrum (zero-padded) within ``search`` of
    ``given_hz`` is the 1x line if it stands ``SHAFT_LINE_DB`` over the median of the spectrum
    within 20 % of ``given_hz`` and the spectrum two bins either side is 6 dB lower (a line,
    not the skirt of a stronger one); bins within three of a harmonic of 50 or 60 Hz (mains)
    are not searched. The median is taken no lower than that of a good measurement chain's
    white floor, ``features.instrument_floor.INSTRUMENT_FLOOR_DB`` under the record's RMS (the
    floor the separation adds): a noise-free simulated record has no floor of its own, and
    content 130-160 dB under its RMS (rounding, far leakage) was taken for the shaft's line,
    which then moved every fault rate. Its frequency is the peak's, interpolated; the
    search's first or last bin on the skirt of a line outside the search is no line. Its
    harmonics are not used: on the CWRU rig's recipe the fan-end 6203's outer-race line
    (3.05 x the shaft rate) and the 60 Hz mains harmonics stand next to the 2x-4x lines and
    pulled the rate by 1-2 % when they were (docs/diagnosis.md, "The speed the rates come
    from").

    Parameters
    ----------
    x : array_like, 1-D
        The record [any unit].
    fs : float
        Sample rate [Hz].
    given_hz : float
        The shaft rate the record is labelled with [Hz].
    search : float
        Fraction of ``given_hz`` searched either side (0 < search < 0.2).

    Returns
    -------
    SpeedEstimate
        ``found`` False when no 1x line stands out, or the largest is the skirt of a stronger
        line (the rate is then ``given_hz``).

    Examples
    --------
    >>> fs = 4096.0
    >>> t = np.arange(int(2 * fs)) / fs
    >>> x = sum(np.sin(2 * np.pi * h * 28.8 * t) / h for h in range(1, 5))
    >>> x = x + 0.01 * np.random.default_rng(0).standard_normal(t.size)
    >>> estimate = shaft_rate_from_spectrum(x, fs, 30.0)
    >>> round(estimate.rate_hz, 2), estimate.found, round(estimate.deviation, 3)
    (28.8, True, -0.04)
    """
    x = check_record(x, function="shaft_rate_from_spectrum", min_length=64)
    fs = check_fs(fs)
    given_hz = check_positive("given_hz", given_hz, unit="Hz")
    if not 0.0 < search < 0.2:
        raise FeatureError(f"search = {search!r} is outside the allowed range (0, 0.2)")
    if 1.2 * given_hz >= fs / 2.56:
        raise FeatureError(
            f"given_hz = {given_hz:g} Hz: the 1x line's neighbourhood lies above fs / 2.56 = "
            f"{fs / 2.56:g} Hz"
        )
    n = x.size
    df = fs / n
    pad = max(2, min(_PAD, 2**22 // n))
    fine = df / pad
    if 2.0 * search * given_hz < 3.0 * fine:  # fewer than three bins: no peak to interpolate
        raise FeatureError(
            f"x lasts {n / fs:.3g} s ({n} samples at fs = {fs:g} Hz): its spectrum, zero-padded "
            f"{pad} times, has bins {fine:.3g} Hz apart, too coarse for the 1x line's search of "
            f"+/-{search:.0%} about given_hz = {given_hz:g} Hz; at least "
            f"{3.0 / (2.0 * search * given_hz * pad):.3g} s are needed"
        )
    # the bins read below: the floor's (within 20 %) and the search's, with the Hann main
    # lobe's two bins either side and the interpolation's neighbour
    first_bin = max(0, int(0.8 * given_hz / fine) - 2 * pad - 1)
    last_bin = min(pad * n // 2, int(math.ceil(1.2 * given_hz / fine)) + 2 * pad + 2)
    window = np.hanning(n)
    spectrum = _padded_spectrum((x - x.mean()) * window, pad * n, first_bin, last_bin)
    near = spectrum[int(0.8 * given_hz / fine) : int(math.ceil(1.2 * given_hz / fine)) + 1]
    # no lower than a good measurement chain's white floor (INSTRUMENT_FLOOR_DB under the RMS)
    floor = max(float(np.median(near)), instrument_floor_median(float(np.std(x)), window))
    low, high = given_hz * (1 - search), given_hz * (1 + search)
    first, height = _peak(spectrum, fine, low, high, mask_hz=3.0 * df)
    line_db = 20.0 * math.log10(max(height, 1e-300) / max(floor, 1e-300))
    # a line, not the skirt of a stronger one outside the search (a mains line masked): the
    # spectrum two bins either side of it (the Hann window's main lobe) 6 dB lower or more
    k = int(round(first / fine))
    sides = spectrum[[max(0, k - 2 * pad), min(spectrum.size - 1, k + 2 * pad)]]
    if line_db < SHAFT_LINE_DB or np.any(sides > height * 10 ** (-6.0 / 20.0)):
        return SpeedEstimate(given_hz, given_hz, round(line_db, 2), False)
    return SpeedEstimate(float(first), float(given_hz), round(line_db, 2), True)


@dataclass(frozen=True)
class TachoSpeed:
    """The shaft rate a tachometer's pulse train gives.

    Attributes
    ----------
    rate_hz : float
        The mean shaft rate over the record [Hz]: whole revolutions between the first and
        the last rising edge over the time between them.
    variation : float
        Standard deviation of the rate revolution by revolution over the mean [-] (0 for a
        steady shaft; jitter of the edges' timing adds about its own spread over a period).
    pulses : int
        Rising edges found.
    revolutions : float
        Revolutions between the first and the last edge.
    edge_times : ndarray
        The rising edges' times [s] from the record's first sample
        (:func:`order_track` resamples with them).
    """

    rate_hz: float
    variation: float
    pulses: int
    revolutions: float
    edge_times: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False, compare=False)


#: Largest median change of a revolution's period from one revolution to the next (fraction
#: of the median period) that a tachometer's channel may show. A shaft's inertia keeps it
#: small: edges timed within a sample, 5-300 Hz shafts at 12 kHz, a run-up from 10 to 50 Hz
#: in 10 s and a fifth of the pulses lost all stay under 0.6 %; an accelerometer's or noise
#: channel read as pulses gives 40-150 % (datasets/small, white noise; stop 88). A channel
#: ringing at one frequency in clean bursts can pass (its crossings within a burst are
#: regular): with noise a fifth of the ringing's amplitude, 106 %; a twentieth, 9.9 %.
TACHO_PERIOD_JUMP = 0.1


def shaft_rate_from_tacho(pulses: np.ndarray, fs: float, pulses_per_rev: int = 1) -> TachoSpeed:
    """The shaft rate from a tachometer or key-phasor channel.

    Rising edges are found with hysteresis (up through 60 % of the way from the channel's
    1st to its 99th percentile, after it was below 40 %), each edge's time interpolated
    between the two samples around the 50 % level; the rate is the revolutions between the
    first and the last edge over the time between them.

    Parameters
    ----------
    pulses : array_like
        The tachometer's channel, sampled with the vibration [V or any unit].
    fs : float
        Sample rate [Hz].
    pulses_per_rev : int
        Pulses per shaft revolution (1 for a key-phasor or a reflective mark).

    Returns
    -------
    TachoSpeed
        Mean rate [Hz], its revolution-to-revolution variation, the edges and revolutions
        counted.

    Raises
    ------
    FeatureError
        The channel has no two levels, fewer than ``2 pulses_per_rev + 1`` rising edges (two
        revolutions), or revolutions whose periods jump by more than ``TACHO_PERIOD_JUMP``
        from one to the next (median): no shaft's pulses.
    """
    x = check_record(pulses, function="shaft_rate_from_tacho", name="pulses", min_length=16)
    fs = check_fs(fs)
    pulses_per_rev = check_count("pulses_per_rev", pulses_per_rev, high=10_000)
    low, high = np.percentile(x, [1.0, 99.0])
    if not high > low:
        raise FeatureError("pulses: the tachometer channel is constant (no pulses)")
    level = (x - low) / (high - low)
    above = level > 0.6
    outside = np.flatnonzero(above | (level < 0.4))  # the samples outside the hysteresis band
    state = above[outside]
    # a rising edge: the first sample above 60 % after one below 40 %
    rises = outside[1:][state[1:] & ~state[:-1]]
    under = np.flatnonzero(level < 0.5)
    j = under[np.searchsorted(under, rises) - 1]  # the last sample under 50 % before each
    a, b = level[j], level[j + 1]
    edges = (j + (0.5 - a) / (b - a)) / fs
    needed = 2 * pulses_per_rev + 1
    if len(edges) < needed:
        raise FeatureError(
            f"pulses: {len(edges)} rising edge(s) found, at least {needed} needed (two "
            f"revolutions at {pulses_per_rev} pulse(s) per revolution)"
        )
    times = edges
    revolutions = (times.size - 1) / pulses_per_rev
    rate = revolutions / float(times[-1] - times[0])
    per_rev = times[::pulses_per_rev]
    periods = np.diff(per_rev)
    jump = float(np.median(np.abs(np.diff(periods))) / np.median(periods))
    if jump > TACHO_PERIOD_JUMP:
        raise FeatureError(
            f"pulses: one revolution's period differs from the next by {100 * jump:.0f} % "
            f"(median of {periods.size - 1}), over the {100 * TACHO_PERIOD_JUMP:.0f} % a "
            "shaft's inertia allows: no tachometer's pulse train (a vibration's channel? "
            "pulses_per_rev too few for uneven marks?)"
        )
    rates = 1.0 / np.diff(per_rev)
    variation = float(np.std(rates) / rate) if rates.size > 1 else 0.0
    return TachoSpeed(
        rate_hz=float(rate),
        variation=variation,
        pulses=int(times.size),
        revolutions=revolutions,
        edge_times=times,
    )


#: Upsampling before :func:`order_track` interpolates between samples (linear interpolation
#: of a record upsampled 8 times keeps content up to 0.4 fs within about 0.3 %).
ORDER_TRACK_UPSAMPLING = 8


def order_track(x: np.ndarray, fs: float, tacho: TachoSpeed, pulses_per_rev: int = 1) -> np.ndarray:
    """Resample a record to constant shaft speed (computed order tracking).

    The shaft's angle between the tachometer's edges is interpolated monotonically (PCHIP
    of the edges' times against their revolutions), and the record is read at equal steps
    of angle, ``tacho.rate_hz / fs`` revolutions apart, between the first and the last
    edge: the result is what the same machine would record at ``fs`` running steadily at
    the mean speed ``tacho.rate_hz``, so that lines at a fixed order of the shaft (a fault's
    rates) stay lines while the speed drifts (Fyfe and Munck 1997). Between samples the
    record is read by linear interpolation of its ``ORDER_TRACK_UPSAMPLING`` times upsampled
    copy, made block by block (a 60 s record at 48 kHz: 0.6 s and 87 MB at the peak, the
    23 MB result included, where upsampling it whole took 1.4 s and 620 MB;
    ``benchmarks/bench_order_track.py``).

    Parameters
    ----------
    x : array_like
        The record [U], sampled with the tachometer.
    fs : float
        Sample rate [Hz]; the result's too.
    tacho : TachoSpeed
        :func:`shaft_rate_from_tacho` of the record's tachometer channel.
    pulses_per_rev : int
        The tachometer's pulses per revolution (as given to :func:`shaft_rate_from_tacho`).

    Returns
    -------
    ndarray
        The record at constant shaft speed [U], about ``tacho.revolutions / tacho.rate_hz *
        fs`` samples (the part before the first edge and after the last is not kept).

    Raises
    ------
    FeatureError
        ``tacho`` has fewer than three edges, or edges beyond the record.
    """
    from scipy.interpolate import PchipInterpolator

    x = check_record(x, function="order_track", min_length=16)
    fs = check_fs(fs)
    pulses_per_rev = check_count("pulses_per_rev", pulses_per_rev, high=10_000)
    times = np.asarray(tacho.edge_times, dtype=float)
    if times.size < 3 or times[0] < 0.0 or times[-1] > (x.size - 1) / fs:
        raise FeatureError(
            f"tacho: {times.size} edges within 0-{(x.size - 1) / fs:g} s; order tracking needs "
            "three or more within the record"
        )
    revolutions = np.arange(times.size) / pulses_per_rev
    time_at = PchipInterpolator(revolutions, times)  # the time each angle is reached
    step = tacho.rate_hz / fs  # revolutions per output sample: fs at the mean speed
    positions = time_at(np.arange(0.0, revolutions[-1], step)) * fs  # in input samples
    return _read_between_samples(x, positions, ORDER_TRACK_UPSAMPLING)


#: Output samples :func:`_read_between_samples` makes at a time (about 17 MB of upsampled
#: record each, whatever the record's length), and input samples either side of a block
#: upsampled with it (more than resample_poly's filter reaches: 10 input samples).
_BLOCK = 1 << 18
_BLOCK_PAD = 64


def _read_between_samples(x: np.ndarray, positions: np.ndarray, up: int) -> np.ndarray:
    """``x`` at rising fractional sample positions, block by block.

    Linear interpolation of ``x`` upsampled ``up`` times (the upsampled record whole would
    take ``up`` times its memory).
    """
    from scipy.signal import resample_poly

    out = np.empty(positions.size)
    for start in range(0, positions.size, _BLOCK):
        p = positions[start : start + _BLOCK]
        lo = max(int(p[0]) - _BLOCK_PAD, 0)
        hi = min(int(np.ceil(p[-1])) + _BLOCK_PAD + 1, x.size)
        fine = resample_poly(x[lo:hi], up, 1)
        q = (p - lo) * up
        i = np.clip(q.astype(np.int64), 0, fine.size - 2)
        frac = q - i
        out[start : start + _BLOCK] = fine[i] * (1.0 - frac) + fine[i + 1] * frac
    return out
