"""The lines a wavy inner race adds to the ball-pass series, and which of them a record holds.

Without slip a bearing's periodic vibration is a function of the shaft's angle and of the ball
set's, so its lines lie on the lattice m f_s + n BPFO. A wavy inner race of N_w lobes excites
each ball at N_w (f_s - f_c), weighed by that ball's load, which the stationary load zone makes
a function of the ball's angle; summed over the Z balls only the load zone's orders p = N_w + q Z
survive, so its lines lie at N_w f_s + q BPFO, and the Hertz law's curvature adds k N_w f_s + q
BPFO: BPFO-spaced series offset from the ball-pass series by k N_w f_s, slices of the lattice.
For N_w = Z (or a multiple of it), k Z f_s = k (BPFI + BPFO), so the slices are the series
k BPFI + n BPFO, whose beats in an envelope fall at BPFO: the rule read such a bearing as an
outer-race fault (docs/diagnosis.md, "Waviness read as a local fault"), while inner-race
waviness of other orders, off these slices, it already called healthy.

:func:`inner_race_lattice_offsets` gives those slices' offsets, :func:`held_offsets` those a
record holds power on: a slice is fitted (``features.separation.separate_discrete(...,
lattice=)``) only where its comb holds more than ``LATTICE_GATE`` times the median power of
``LATTICE_NULLS`` combs of the same spacing spread over the interval, what a random part puts
on any comb; a local fault's random impacts put no more on one comb than on another.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ._validate import FeatureError, check_fs, check_positive, check_record

__all__ = [
    "inner_race_lattice_offsets",
    "inner_race_lattice_orders",
    "held_offsets",
    "LATTICE_ORDERS",
    "LATTICE_GATE",
    "LATTICE_NULLS",
]

#: Harmonics k of the inner race's pass rate whose BPFO-spaced series are candidates
#: (the Hertz law's curvature makes k = 2-6 of a 1 um wavy race clear over its noise).
LATTICE_ORDERS = 6
#: A candidate series is fitted where its comb holds this many times the null combs' median
#: power (a comb of L lines on a random part holds a chi-square power with 2 L degrees of
#: freedom: for L >= 10 lines four times its median is 6 standard deviations or more above).
LATTICE_GATE = 4.0
#: Null combs of the same spacing at offsets (j + 1/2) spacing / LATTICE_NULLS.
LATTICE_NULLS = 24
#: Zero padding of the power spectrum the combs are read from (a line then lies within an
#: eighth of a bin of a read bin: a Hann window's scalloping there is under 0.2 dB).
_PADDING = 4


def inner_race_lattice_offsets(
    ball_pass_outer: float, ball_pass_inner: float, orders: int = LATTICE_ORDERS
) -> tuple[float, ...]:
    """Offsets [Hz] of the series k BPFI + n BPFO from the ball-pass series n BPFO.

    Parameters
    ----------
    ball_pass_outer : float
        BPFO, the series' spacing [Hz].
    ball_pass_inner : float
        BPFI [Hz].
    orders : int
        Harmonics k = 1 .. ``orders`` of BPFI, each with both signs (a real signal's lines
        at k BPFI + n BPFO have their mirrors at -k BPFI + n' BPFO).

    Returns
    -------
    tuple of float
        The offsets in [0, BPFO), +k BPFI and -k BPFI modulo BPFO for each k.

    Raises
    ------
    FeatureError
        A rate not positive, or ``orders`` under 1, named with its range.

    Examples
    --------
    >>> [round(o, 2) for o in inner_race_lattice_offsets(107.36, 162.19, orders=1)]
    [54.83, 52.53]
    """
    spacing = check_positive("ball_pass_outer", ball_pass_outer, unit="Hz")
    rate = check_positive("ball_pass_inner", ball_pass_inner, unit="Hz")
    if not isinstance(orders, int | np.integer) or orders < 1:
        raise FeatureError(f"orders = {orders!r} is outside the allowed range: an integer >= 1")
    return tuple(
        float((sign * k * rate) % spacing) for k in range(1, int(orders) + 1) for sign in (1, -1)
    )


def inner_race_lattice_orders(orders: int = LATTICE_ORDERS) -> tuple[int, ...]:
    """The signed harmonic k of BPFI of each offset :func:`inner_race_lattice_offsets` gives.

    Parameters
    ----------
    orders : int
        As :func:`inner_race_lattice_offsets`.

    Returns
    -------
    tuple of int
        +k for k BPFI, -k for -k BPFI, in the offsets' order.

    Examples
    --------
    >>> inner_race_lattice_orders(2)
    (1, -1, 2, -2)
    """
    if not isinstance(orders, int | np.integer) or orders < 1:
        raise FeatureError(f"orders = {orders!r} is outside the allowed range: an integer >= 1")
    return tuple(sign * k for k in range(1, int(orders) + 1) for sign in (1, -1))


def held_offsets(
    residue: np.ndarray, fs: float, spacing: float, offsets: Sequence[float]
) -> tuple[float, ...]:
    """The ``offsets`` whose series the record holds: their combs over ``LATTICE_GATE`` x null.

    Each comb is the lines offset + k spacing between ``margin`` and fs/2 - ``margin`` (the
    coupling width of ``features.separation.remove_harmonics``, 20 bins), read from the
    Hann-windowed record's power spectrum zero-padded ``_PADDING`` times (nearest bin), summed.
    An offset within one bin of 0 or of ``spacing`` is the series itself to a record this long
    and is never returned.

    Parameters
    ----------
    residue : array_like, 1-D
        The record with its known series already fitted out [U].
    fs : float
        Sample rate [Hz].
    spacing : float
        The series' spacing [Hz] (the ball-pass rate).
    offsets : sequence of float
        Candidate offsets [Hz], in [0, spacing).

    Returns
    -------
    tuple of float
        The candidates held, in their given order (empty when the comb is too short: fewer
        than 4 periods of ``spacing`` in the record, or no line in the band).

    Examples
    --------
    >>> fs = 12000.0; t = np.arange(12000) / fs
    >>> noise = np.random.default_rng(0).standard_normal(t.size)
    >>> comb = sum(np.cos(2 * np.pi * (37.0 + k * 100.0) * t) for k in range(5, 40))
    >>> held_offsets(noise + 0.5 * comb, fs, 100.0, (37.0, 61.0))
    (37.0,)
    """
    residue = check_record(residue, function="held_offsets", name="residue", min_length=64)
    fs = check_fs(fs)
    spacing = check_positive("spacing", spacing, unit="Hz")
    offsets = tuple(check_positive(f"offsets[{i}]", o, unit="Hz") for i, o in enumerate(offsets))
    n = residue.size
    duration = n / fs
    if spacing * duration < 4 or not offsets:
        return ()
    margin = 20.0 / duration
    window = np.hanning(n)
    power = np.abs(np.fft.rfft((residue - residue.mean()) * window, _PADDING * n)) ** 2
    bin_hz = fs / (_PADDING * n)

    def comb(offset: float) -> float:
        first = math.floor((margin - offset) / spacing) + 1
        last = math.floor((0.5 * fs - margin - offset) / spacing)
        if last < first:
            return 0.0
        lines = offset + spacing * np.arange(first, last + 1)
        return float(np.sum(power[np.rint(lines / bin_hz).astype(int)]))

    null = float(
        np.median([comb((j + 0.5) * spacing / LATTICE_NULLS) for j in range(LATTICE_NULLS)])
    )
    if null <= 0.0:
        return ()
    resolution = 1.0 / duration
    return tuple(
        float(o)
        for o in offsets
        if resolution <= o <= spacing - resolution and comb(o) > LATTICE_GATE * null
    )
