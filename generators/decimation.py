"""The integration record's channels and their anti-alias decimation to the output rate.

An acceleration channel decimated from a record (``factor`` > 1) is the band-limited
derivative of the record's velocity column, not its acceleration column low-passed. The record
point-samples the run, and a local defect's impacts make the run's acceleration ring to tens
of kHz: what lies near a multiple of the record rate folds onto the band's low frequencies
before any filter can remove it (a pit's line at its own rate, 110 dB under its strongest
harmonic, came out 28 times too strong at 12 kHz, recorded at 48 kHz). The velocity holds the
same ringing divided by its frequency, so its folded part, differentiated at the line's
frequency, is smaller by that frequency over the ringing's (-53 dB for a 107 Hz line and
48 kHz records); in the band the derivative filter is exact to 0.2 %. What is further off
than the column was is the top of a 48 kHz band (3 kHz-0.45 fs about 3e-3 against 1.6e-3):
the velocity is RK4's quadrature of the force, whose content at 10-20 kHz a 20.83 us step
integrates less exactly than the column, which evaluates the force at the state, sees it
(1.2e-3 against 2.8e-4 at step starts alone; docs/performance.md, "Accelerations from the
velocity record").
"""

from __future__ import annotations

import functools
from collections.abc import Sequence

import numpy as np
from scipy import signal as sp_signal

from . import _filters
from ._kernels import N_OUT_ACCEL, N_OUT_STATE

#: Output channel -> (record array: 0 state, 1 acceleration; column).
CHANNEL_COLUMNS = {
    "housing_displacement_x": (0, 2),
    "housing_displacement_y": (0, 3),
    "housing_velocity_x": (0, 6),
    "housing_velocity_y": (0, 7),
    "housing_acceleration_x": (1, 2),
    "housing_acceleration_y": (1, 3),
    "shaft_displacement_x": (0, 0),
    "shaft_displacement_y": (0, 1),
    "shaft_velocity_x": (0, 4),
    "shaft_velocity_y": (0, 5),
    "shaft_acceleration_x": (1, 0),
    "shaft_acceleration_y": (1, 1),
}


#: Acceleration channel -> the velocity channel it is the derivative of.
VELOCITY_OF = {
    "housing_acceleration_x": "housing_velocity_x",
    "housing_acceleration_y": "housing_velocity_y",
    "shaft_acceleration_x": "shaft_velocity_x",
    "shaft_acceleration_y": "shaft_velocity_y",
}

#: Half-length of the differentiator convolved with the anti-alias FIR, per decimation factor
#: [records], and its Kaiser window's beta: the pair's response is j omega times the FIR's to
#: 0.06-0.23 % over 0-0.9 of the output band for factors 2-16 (:func:`decimation_taps`).
DIFFERENTIATOR_HALF_LENGTH = 5
DIFFERENTIATOR_BETA = 8.0


def filter_reach(factor: int) -> int:
    """Records on each side of an output sample that its decimation filter reads (0 at 1).

    ``resample_poly``'s half-length, 10 ``factor``, plus the accelerations' differentiator,
    ``DIFFERENTIATOR_HALF_LENGTH * factor``: a run records this many more before its first
    and after its last output sample (where its settling allows), so that no output sample
    is filtered from the line extension of the record's ends.

    Parameters
    ----------
    factor : int
        The decimation factor (records per output sample).

    Returns
    -------
    int
        Records.
    """
    return 0 if factor <= 1 else (10 + DIFFERENTIATOR_HALF_LENGTH) * factor


def differentiated(name: str, factor: int) -> bool:
    """Whether a channel is its velocity's derivative when decimated by ``factor``.

    An acceleration channel is when ``factor`` > 1; at ``factor`` 1 (no filter) it is its own
    acceleration column.

    Parameters
    ----------
    name : str
        The channel (``<body>_<quantity>_<axis>``).
    factor : int
        The decimation factor.

    Returns
    -------
    bool
    """
    return factor > 1 and name in VELOCITY_OF


def source_column(name: str, factor: int) -> tuple[int, int]:
    """Record array (0 state, 1 acceleration) and column a channel is decimated from.

    The velocity's column where the channel is :func:`differentiated`.

    Parameters
    ----------
    name : str
        The channel.
    factor : int
        The decimation factor.

    Returns
    -------
    array, column : int
    """
    if differentiated(name, factor):
        return CHANNEL_COLUMNS[VELOCITY_OF[name]]
    return CHANNEL_COLUMNS[name]


def record_columns(channels: Sequence[str], factor: int = 1) -> np.ndarray:
    """Flags of the record's columns (states, then accelerations) that ``channels`` read.

    Parameters
    ----------
    channels : sequence of str
        The channels recorded.
    factor : int
        The decimation factor the record is made for (:func:`source_column`).

    Returns
    -------
    ndarray of bool
    """
    wanted = np.zeros(N_OUT_STATE + N_OUT_ACCEL, dtype=np.int64)
    for name in channels:
        which, column = source_column(name, factor)
        wanted[N_OUT_STATE * which + column] = 1
    return wanted


def decimate(
    out_state: np.ndarray,
    out_accel: np.ndarray,
    factor: int,
    channels: Sequence[str],
    record_dt: float | None = None,
) -> dict[str, np.ndarray]:
    """Anti-alias filter and downsample the integration record to the output rate.

    ``scipy.signal.resample_poly(record, 1, factor, padtype="line")`` of every requested
    displacement and velocity channel, computed by :func:`decimate_rows`'s kernel straight
    from the record's columns (one pass over the record): each output channel is a contiguous
    row of one block. An acceleration channel is its velocity column through the same FIR
    convolved with a differentiator, divided by ``record_dt`` (the record interval [s],
    required then); at ``factor`` 1 the record's columns are returned as they are.

    Parameters
    ----------
    out_state : ndarray
        The record of the states (records, states) [m, m/s].
    out_accel : ndarray
        The record of the accelerations (records, bodies' axes) [m/s^2].
    factor : int
        The decimation factor.
    channels : sequence of str
        The output channels.
    record_dt : float, optional
        The record interval [s] (needed for accelerations when ``factor`` > 1).

    Returns
    -------
    dict of str to ndarray
        Each channel at the output rate [SI unit].
    """
    records = (out_state, out_accel)
    if factor > 1 and out_state.shape[0] >= 2:
        result: dict[str, np.ndarray] = {}
        for derivative in (False, True):
            names = [name for name in channels if differentiated(name, factor) == derivative]
            if not names:
                continue
            if derivative and not (record_dt is not None and record_dt > 0):
                raise ValueError(
                    f"record_dt = {record_dt!r}: acceleration channels decimated by {factor} "
                    "need the record interval (> 0 s)"
                )
            columns = np.array([source_column(name, factor) for name in names], dtype=np.int64)
            taps, first, n_out = fir_design(factor, out_state.shape[0], derivative)
            block = _filters.fir_decimate_columns(
                out_state, out_accel, columns.reshape(-1, 2), taps, factor, first, n_out
            )
            if derivative:
                block /= record_dt
            result.update({name: block[c] for c, name in enumerate(names)})
        return {name: result[name] for name in channels}
    block = np.empty((len(channels), out_state.shape[0]))
    for c, name in enumerate(channels):
        which, column = CHANNEL_COLUMNS[name]
        block[c] = records[which][:, column]
    if factor > 1:
        block = sp_signal.resample_poly(block, 1, factor, axis=1, padtype="line")
    return {name: block[c] for c, name in enumerate(channels)}


def decimate_rows(
    records: np.ndarray, factor: int, derivative_dt: float | None = None
) -> np.ndarray:
    """Each row of ``records`` (records, n) anti-alias filtered and downsampled by ``factor``.

    The same bits as ``scipy.signal.resample_poly(records, 1, factor, axis=1,
    padtype="line")``: a linear-phase low-pass FIR (Kaiser window, beta 5, 20 ``factor`` + 1
    taps, cut-off at the output's Nyquist frequency), its delay compensated, the record
    extended on the line through its end samples; the kernel sums the same products in the
    same order, two to three times faster (``tests/tests_generators/test_decimation.py``).
    With ``derivative_dt`` (the record interval [s]) the rows are velocities and the result
    their band-limited derivative, the accelerations (:func:`fir_design`).

    Parameters
    ----------
    records : ndarray
        (records, n) [U].
    factor : int
        The decimation factor.
    derivative_dt : float, optional
        The record interval [s], for the derivative.

    Returns
    -------
    ndarray
        (records, ceil(n / factor)) [U, or U/s with ``derivative_dt``].
    """
    if factor <= 1:
        return records
    if records.shape[1] < 2:
        if derivative_dt is not None:
            raise ValueError(f"records of {records.shape[1]} sample(s) have no derivative")
        return sp_signal.resample_poly(records, 1, factor, axis=1, padtype="line")
    derivative = derivative_dt is not None
    taps, first, n_out = fir_design(factor, records.shape[1], derivative)
    out = _filters.fir_decimate_rows(records, taps, factor, first, n_out)
    if derivative:
        out /= derivative_dt
    return out


def decimation_taps(factor: int, derivative: bool = False) -> np.ndarray:
    """The decimation filter's taps, centred (odd length), before scipy's padding.

    ``resample_poly(x, 1, factor)``'s low-pass: ``firwin(20 factor + 1, 1 / factor)``, Kaiser
    window, beta 5. With ``derivative`` that FIR convolved with an ideal differentiator
    (``cos(pi k) / k``, k != 0) over ``DIFFERENTIATOR_HALF_LENGTH * factor`` records each side
    under a Kaiser window (``DIFFERENTIATOR_BETA``), scaled to a unit slope at 0 Hz: applied
    to a record, the derivative per record interval, centred as the FIR's output is.

    Parameters
    ----------
    factor : int
        The decimation factor.
    derivative : bool
        The differentiating filter.

    Returns
    -------
    ndarray
        The taps.
    """
    taps = sp_signal.firwin(20 * factor + 1, 1.0 / factor, window=("kaiser", 5.0))
    if not derivative:
        return taps
    reach = DIFFERENTIATOR_HALF_LENGTH * factor
    k = np.arange(-reach, reach + 1, dtype=float)
    k[reach] = 1.0  # the centre tap is 0: keep the division finite
    window = sp_signal.windows.kaiser(2 * reach + 1, DIFFERENTIATOR_BETA)
    differentiator = np.cos(np.pi * k) / k * window
    differentiator[reach] = 0.0
    differentiator /= -np.sum(np.arange(-reach, reach + 1) * differentiator)
    return np.convolve(taps, differentiator)


@functools.lru_cache(maxsize=32)
def fir_design(factor: int, n: int, derivative: bool = False) -> tuple[np.ndarray, int, int]:
    """The decimation filter as ``resample_poly(x, 1, factor)`` applies it to ``n`` samples.

    Parameters
    ----------
    factor : int
        The decimation factor.
    n : int
        The record's samples.
    derivative : bool
        The differentiating filter (:func:`decimation_taps`).

    Returns
    -------
    taps : ndarray
        The taps of :func:`decimation_taps` as scipy applies them (zero-padded so that the
        kept outputs are centred, then reversed).
    dropped : int
        The leading outputs scipy drops.
    length : int
        The output's length.
    """
    taps = decimation_taps(factor, derivative)
    half_len = (taps.shape[0] - 1) // 2
    pre = factor - half_len % factor
    first = (half_len + pre) // factor
    n_out = n // factor + bool(n % factor)
    post = 0
    while ((n - 1) + taps.shape[0] + pre + post - 1) // factor + 1 < n_out + first:
        post += 1
    padded = np.concatenate((np.zeros(pre), taps, np.zeros(post)))
    flipped = np.ascontiguousarray(padded[::-1])
    flipped.setflags(write=False)
    return flipped, first, n_out
