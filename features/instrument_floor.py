"""A good measurement chain's white floor, which the separation adds to records without one.

A record is never more exact than the chain that measured it: an accelerometer's and a
converter's own noise lie some 50 dB under a machine housing's vibration
(``INSTRUMENT_FLOOR_DB``). A simulation has no such floor, and its random part, after the
periodic fit, can hold nothing but numerical residue; :func:`add_instrument_floor` gives such a
record the floor a recording would have (docs/diagnosis.md, "Verdicts the instrument floor
decides"), and :func:`instrument_floor_median` says where that floor lies in a windowed
transform, for the readers that compare a line with it. Moved out of
:mod:`features.separation` unchanged in stop 77; ``features.separation`` still exports every
name but ``FLOOR_SEED`` (set it here).
"""

from __future__ import annotations

import math

import numpy as np

from ._validate import FeatureError

__all__ = [
    "INSTRUMENT_FLOOR_DB",
    "FLOOR_SKIP_DB",
    "FLOOR_SEED",
    "instrument_floor_median",
    "add_instrument_floor",
]

#: Noise floor of a good measurement chain under the record's RMS [dB]: an accelerometer's
#: own noise of ~10 ug/sqrt(Hz) over 5 kHz is 0.7 mg RMS, 43-63 dB under the 0.1-1 g of a
#: machine's bearing housing (a 16-bit converter with its full scale 20 dB over the RMS
#: reaches 78 dB). A simulation is no more exact than that: at its default step the
#: integration's alias products (harmonics near the step rate folded into the band) reach
#: 48-50 dB under the RMS of a healthy bearing at 600 rpm and 2000 N, and its error bound
#: allows 1 % (40 dB) per octave band. Nothing this far down is evidence of anything.
INSTRUMENT_FLOOR_DB = 50.0
#: The instrument floor is added only where the record's own broadband floor (its spectrum's
#: median after the periodic fit, read as a white level) lies less than this far above it
#: [dB]: a record with a floor of its own 20 dB higher (recordings, most simulations in noise)
#: would change by 1 % of its random part's power at most, and gets none (stops 75-76).
FLOOR_SKIP_DB = 20.0
#: Seed of the instrument floor's draw (with the record's length): where it is added, the
#: same draw for every record of a length, scaled to the record, so that the random part scales
#: with the record (any unit) and moves smoothly with it (until stop 76 the draw was seeded by
#: the record's first samples, so a record's unit, or a change in its last bits, chose it).
FLOOR_SEED = 15242


def instrument_floor_median(rms: float, window: np.ndarray) -> float:
    """The median a good chain's white floor has in a windowed transform of a record [U].

    White noise ``INSTRUMENT_FLOOR_DB`` under the record's RMS, transformed with ``window``
    (no normalisation: ``abs(rfft(x * window))``): each bin's magnitude is Rayleigh with
    E|X|^2 = sigma^2 sum(w^2), so its median is sigma sqrt(ln 2 sum(w^2)). A line read over
    this where a record's own floor is lower is read as a recording of it would be (the 1x-line
    search, the race waviness reader; the separation adds the floor itself).

    Parameters
    ----------
    rms : float
        The record's RMS [U], 0 or more.
    window : array_like, 1-D
        The window the transform applies (at least 4 samples).

    Returns
    -------
    float
        The floor's median magnitude [U].

    Raises
    ------
    FeatureError
        ``rms`` negative or not finite, or a window under 4 samples, named with the range.

    Examples
    --------
    >>> x = np.random.default_rng(0).normal(0.0, 10 ** (-INSTRUMENT_FLOOR_DB / 20), 48000)
    >>> w = np.hanning(x.size)
    >>> ratio = np.median(np.abs(np.fft.rfft(x * w))[1:-1]) / instrument_floor_median(1.0, w)
    >>> bool(abs(ratio - 1) < 0.02)
    True
    """
    if not (isinstance(rms, int | float | np.floating) and math.isfinite(rms) and rms >= 0.0):
        raise FeatureError(f"rms = {rms!r} is outside the allowed range [0, inf) [U]")
    window = np.asarray(window, dtype=float)
    if window.ndim != 1 or window.size < 4:
        raise FeatureError(
            f"window of {window.size} samples is outside the allowed range: 1-D, 4 or more"
        )
    sigma = float(rms) * 10.0 ** (-INSTRUMENT_FLOOR_DB / 20.0)
    return sigma * math.sqrt(math.log(2.0) * float(np.sum(window * window)))


def add_instrument_floor(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    """A record's random part with a good chain's floor where the record has none of its own.

    The floor is white, ``INSTRUMENT_FLOOR_DB`` under the RMS of the record ``x``; it is added
    to ``y`` only where the median bin power of ``y``'s spectrum (its own broadband floor:
    lines and resonances hardly move a median) lies less than ``FLOOR_SKIP_DB`` over the
    floor's (:func:`instrument_floor_median`). Its draw is one per record length
    (``FLOOR_SEED``), scaled to the record, so that the result scales with the record.

    Parameters
    ----------
    x : ndarray, 1-D
        The record [U].
    y : ndarray, 1-D
        Its random part (the record after the periodic fit), as long as ``x`` [U].

    Returns
    -------
    y : ndarray
        The random part, with the floor where it was added [U].
    spectrum : ndarray, complex
        ``numpy.fft.rfft`` of ``y`` minus its mean [U].
    floor_rms : float
        The floor's RMS [U]; 0 where none was added.

    Examples
    --------
    >>> x = np.sin(2 * np.pi * 50 * np.arange(4800) / 4800.0)
    >>> _, _, floor_rms = add_instrument_floor(x, np.zeros_like(x))  # nothing left: a floor
    >>> bool(abs(floor_rms / np.std(x) - 10 ** (-INSTRUMENT_FLOOR_DB / 20)) < 1e-12)
    True
    """
    n = x.size
    floor_rms = float(np.std(x)) * 10.0 ** (-INSTRUMENT_FLOOR_DB / 20.0)
    spec = np.fft.rfft(y - y.mean())
    # the record's own floor: its median bin power (lines and resonances hardly move a median)
    own = np.median(np.abs(spec[1 : (n + 1) // 2]) ** 2)
    reach = instrument_floor_median(float(np.std(x)), np.ones(n)) * 10.0 ** (FLOOR_SKIP_DB / 20.0)
    if 0.0 < floor_rms and own < reach**2:
        y = y + floor_rms * np.random.default_rng((FLOOR_SEED, n)).standard_normal(n)
        spec = np.fft.rfft(y - y.mean())
    else:
        floor_rms = 0.0
    return y, spec, floor_rms
