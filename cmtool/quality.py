"""Record quality checks of ``cmtool diagnose``: clipping, non-finite, constant, pulse records.

A clipped record's impacts are cut off at the converter's rail, and from a few per cent of
the samples on a plateau the rule's verdict changes for more than 5 % of simulated records
(docs/diagnosis.md, "Clipping"): :func:`check_clipping` refuses such a record,
:func:`check_signal_quality` warns of a lesser share and refuses a constant or non-finite one.
"""

from __future__ import annotations

import math

import numpy as np

#: Share of a record's samples at its full-scale values from which ``cmtool diagnose`` refuses
#: it (``--allow-clipping`` overrides). Measured on simulation (the CWRU-rig recipe's seed-777
#: draw, its 269 healthy and visible-fault signals; ``benchmarks/clipping.py``): with 0.1, 0.3
#: and 1 % of the samples clipped the rule's verdict changes for 1.5, 3.0 and 4.8 % of them,
#: with 3 % for 7.4 % (and 2 % of the healthy ones become faults), over the 5 % set before
#: the run (docs/diagnosis.md, "Clipping").
CLIPPING_ERROR_SHARE = 0.03


#: How many times more samples a clipped end holds than the next value inward. An unclipped
#: waveform's density rises toward its extremes at most as a sine's does (the arcsine law):
#: quantised, its extreme level holds 1.37 times the next one's samples (sqrt(1 / A) against
#: sqrt(3 / A) - sqrt(1 / A) at an amplitude of A counts), a Gaussian's fewer; a clipped end
#: piles up the whole tail beyond the rail.
PLATEAU_RATIO = 3.0


def clipped_share(x: np.ndarray) -> float:
    """Share of the samples on a plateau at the record's largest or smallest value.

    At each end, the samples within 1e-6 of the range of the extreme value count when there
    are at least two and ``PLATEAU_RATIO`` times as many as at the next distinct value inward:
    a clipped end is a plateau, while a quantised record that is not clipped holds about as
    many samples at its extreme level as at the next (a pure sine of 100 counts on a 16-bit
    converter has 3.2 % of its samples at each extreme, 2.3 % one count in; until stop 46 it
    counted as 6.4 % clipped). The two ends are judged apart, so a converter whose range is
    not symmetric (a 16-bit one reads -32768 to 32767) or a record with an offset is judged
    on both.

    Parameters
    ----------
    x : numpy.ndarray
        The record (any unit).

    Returns
    -------
    float
        The share [-], 0 for a constant record.
    """
    x = np.asarray(x, dtype=float)
    top, bottom = float(np.max(x)), float(np.min(x))
    tolerance = 1e-6 * (top - bottom)
    if tolerance == 0.0:
        return 0.0
    interior = (x > bottom + tolerance) & (x < top - tolerance)
    clipped = 0
    for sign, extreme in ((1.0, top), (-1.0, bottom)):
        depth = sign * (extreme - x)  # how far inside each sample lies, >= 0
        count = int(np.count_nonzero(depth <= tolerance))
        # the next value inward among the samples at neither end (none: a two-valued record)
        next_level = float(depth[interior].min()) if interior.any() else math.inf
        nearby = int(np.count_nonzero(np.abs(depth - next_level) <= tolerance))
        if count >= 2 and count >= PLATEAU_RATIO * nearby:
            clipped += count
    return float(clipped) / x.size


#: Share of a record's samples near its two extreme levels from which it is taken for a
#: pulse train (a tachometer's or a digital channel's), not a vibration: within a tenth of
#: its 1-99 % range of either end, each end holding 1 % or more. A Gaussian record puts
#: about 6 % of its samples there, a sine 41 % (the arcsine law), a square wave 100 %.
PULSE_SHARE = 0.9


def two_level_share(x: np.ndarray) -> float:
    """Share of the samples within a tenth of the 1-99 % range of the record's two ends.

    Parameters
    ----------
    x : numpy.ndarray
        The record (finite).

    Returns
    -------
    float
        The share in [0, 1]; 0 when either end holds under 1 % of the samples or the
        range is zero.
    """
    x = np.asarray(x, dtype=float)
    low, high = np.percentile(x, [1.0, 99.0])
    width = 0.1 * float(high - low)
    if not width > 0:
        return 0.0
    at_low = np.abs(x - low) <= width
    at_high = np.abs(x - high) <= width
    if min(float(np.mean(at_low)), float(np.mean(at_high))) < 0.01:
        return 0.0
    return float(np.mean(at_low | at_high))


def check_not_pulses(x: np.ndarray, name: str = "signal") -> None:
    """Refuse a record that takes two levels only (a tachometer's or digital channel's).

    Parameters
    ----------
    x : numpy.ndarray
        The record (finite).
    name : str
        What to call it in the error.

    Raises
    ------
    ValueError
        When :func:`two_level_share` is ``PULSE_SHARE`` or more.
    """
    share = two_level_share(x)
    if share >= PULSE_SHARE:
        low, high = np.percentile(np.asarray(x, dtype=float), [1.0, 99.0])
        raise ValueError(
            f"{name} takes two levels only ({share:.0%} of its samples near {low:.4g} or "
            f"{high:.4g}): a tachometer's or digital channel's pulses, not a vibration; "
            "diagnose the vibration's channel (--channel) and give this one as --tacho"
        )


def non_finite_text(x: np.ndarray, name: str = "signal") -> str:
    """What an error says of a record holding NaN or inf: how many, and where the first is.

    Parameters
    ----------
    x : numpy.ndarray
        The record, with at least one sample that is not finite.
    name : str
        What to call it.

    Returns
    -------
    str
        For example "signal contains 1 non-finite values (NaN or inf), the first at sample
        5662 of 5663 (the last: a file cut short?)"; a reader leaves a cut line's missing
        value as NaN.
    """
    finite = np.isfinite(np.ravel(x))
    first = int(np.argmin(finite))
    where = f"the first at sample {first} of {finite.size}"
    if first == finite.size - 1:
        where += " (the last: a file cut short?)"
    bad = finite.size - int(np.count_nonzero(finite))
    return f"{name} contains {bad} non-finite values (NaN or inf), {where}"


def check_clipping(x: np.ndarray, name: str = "signal") -> None:
    """Refuse a record too clipped for the rule's verdict to be trusted.

    Parameters
    ----------
    x : numpy.ndarray
        The record.
    name : str
        What to call it in the error.

    Raises
    ------
    ValueError
        When at least ``CLIPPING_ERROR_SHARE`` of the samples sit on a plateau at the record's
        largest or smallest value (:func:`clipped_share`), a sample is NaN or infinite, or
        the record takes two levels only (:func:`check_not_pulses`).
    """
    x = np.asarray(x, dtype=float)
    if not np.all(np.isfinite(x)):  # an inf would pass for the largest value of a clipped one
        raise ValueError(non_finite_text(x, name))
    check_not_pulses(x, name)  # a clean pulse train is all plateaus: say what it is
    share = clipped_share(x)  # 0 for a constant record: diagnose_signal says what that is
    if share < CLIPPING_ERROR_SHARE:
        return
    raise ValueError(
        f"{name} is clipped: {share:.1%} of its samples sit at its largest or smallest value "
        f"({float(np.max(x)):.4g}, {float(np.min(x)):.4g}), over the {CLIPPING_ERROR_SHARE:.0%} "
        "allowed (from there the rule's verdict changes for more than 5 % of simulated "
        "records); record again with more headroom, or pass --allow-clipping to diagnose it "
        "anyway"
    )


def check_signal_quality(x: np.ndarray, name: str = "signal") -> list[str]:
    """Warnings for clipped signals; raises ValueError for a constant or non-finite one.

    Parameters
    ----------
    x : ndarray
        The record [its unit].
    name : str
        Its name in the messages.

    Returns
    -------
    list of str
        The warnings (empty for a clean record).

    Raises
    ------
    ValueError
        When the record holds NaN or inf, is constant, or takes two levels only
        (:func:`check_not_pulses`).
    """
    if not np.all(np.isfinite(x)):
        raise ValueError(non_finite_text(x, name))
    warnings = []
    peak = float(np.max(np.abs(x)))
    if peak == 0 or float(np.ptp(x)) == 0:
        raise ValueError(f"{name} is constant: nothing to diagnose")
    check_not_pulses(x, name)
    count = round(clipped_share(x) * x.size)
    if count > max(3, 1e-4 * x.size):
        warnings.append(
            f"signal looks clipped: {count} samples ({count / x.size:.2%}) at its largest or "
            f"smallest value ({float(np.max(x)):.4g}, {float(np.min(x)):.4g})"
        )
    return warnings


#: Share of a record's variance below the start of the overall vibration's band (ISO
#: 10816-3: 10 Hz, or 2 Hz for shafts at 600 rpm or less; at most half the shaft rate) from
#: which the record is said to drift. A machine's acceleration holds little there (a
#: Gaussian record's share is twice the frequency over the rate: 0.17 % below 10 Hz at 12
#: kHz; a shaft's 1x line lies above it), while an accelerometer settling after power-on
#: (an exponential of a few tenths of a second), a drift or a step puts most of its
#: variance there and, integrated, swamps the velocity figures (0.3 mm/s of noise read 14
#: mm/s overall with a 3 g settling of 0.1 s: docs/diagnosis.md, "A record that drifts").
DRIFT_SHARE = 0.5


def low_frequency_share(x: np.ndarray, fs: float, below_hz: float) -> float:
    """The share of a record's variance (its mean out) in the DFT bins below ``below_hz``.

    Parameters
    ----------
    x : ndarray
        The record [its unit].
    fs : float
        Sample rate [Hz].
    below_hz : float
        The frequency below which the variance is counted [Hz] (bins from the first up).

    Returns
    -------
    float
        The share, 0 to 1 (0 for a record too short to hold a bin below ``below_hz``).
    """
    x = np.asarray(x, dtype=float)
    power = np.abs(np.fft.rfft(x - x.mean())[1:]) ** 2
    total = float(power.sum())
    count = math.ceil(below_hz * x.size / fs) - 1  # bins 1 .. count lie below below_hz
    return float(power[: max(count, 0)].sum()) / total if total > 0 else 0.0


def check_drift(x: np.ndarray, fs: float, below_hz: float) -> list[str]:
    """A warning where ``DRIFT_SHARE`` or more of the record's variance lies below ``below_hz``.

    Parameters
    ----------
    x : ndarray
        The record, an acceleration [its unit].
    fs : float
        Sample rate [Hz].
    below_hz : float
        The start of the overall vibration's band [Hz] (:func:`cmtool.diagnose.overall_band`,
        at most half the shaft rate).

    Returns
    -------
    list of str
        The warning, or none.
    """
    share = low_frequency_share(x, fs, below_hz)
    if share < DRIFT_SHARE:
        return []
    return [
        f"{100 * share:.0f} % of the record's variance lies below {below_hz:g} Hz, where a "
        "machine's acceleration holds little: a sensor settling after power-on, a drift or a "
        "step; the velocity bands and the overall velocity hold it (leave the record's start "
        "out, or check the sensor and its cable)"
    ]
