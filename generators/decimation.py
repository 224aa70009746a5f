"""The integration record's channels and their anti-alias decimation to the output rate."""

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


def record_columns(channels: Sequence[str]) -> np.ndarray:
    """Flags of the record's columns (states, then accelerations) that ``channels`` read."""
    wanted = np.zeros(N_OUT_STATE + N_OUT_ACCEL, dtype=np.int64)
    for name in channels:
        which, column = CHANNEL_COLUMNS[name]
        wanted[N_OUT_STATE * which + column] = 1
    return wanted


def decimate(
    out_state: np.ndarray, out_accel: np.ndarray, factor: int, channels: Sequence[str]
) -> dict[str, np.ndarray]:
    """Anti-alias filter and downsample the integration record to the output rate.

    ``scipy.signal.resample_poly(record, 1, factor, padtype="line")`` of every requested
    channel, computed by :func:`decimate_rows`'s kernel straight from the record's columns
    (one pass over the record): each output channel is a contiguous row of one block.
    """
    records = (out_state, out_accel)
    if factor > 1 and out_state.shape[0] >= 2:
        columns = np.array([CHANNEL_COLUMNS[name] for name in channels], dtype=np.int64)
        taps, first, n_out = fir_design(factor, out_state.shape[0])
        block = _filters.fir_decimate_columns(
            out_state, out_accel, columns.reshape(-1, 2), taps, factor, first, n_out
        )
        return {name: block[c] for c, name in enumerate(channels)}
    block = np.empty((len(channels), out_state.shape[0]))
    for c, name in enumerate(channels):
        which, column = CHANNEL_COLUMNS[name]
        block[c] = records[which][:, column]
    if factor > 1:
        block = sp_signal.resample_poly(block, 1, factor, axis=1, padtype="line")
    return {name: block[c] for c, name in enumerate(channels)}


def decimate_rows(records: np.ndarray, factor: int) -> np.ndarray:
    """Each row of ``records`` (records, n) anti-alias filtered and downsampled by ``factor``.

    The same bits as ``scipy.signal.resample_poly(records, 1, factor, axis=1,
    padtype="line")``: a linear-phase low-pass FIR (Kaiser window, beta 5, 20 ``factor`` + 1
    taps, cut-off at the output's Nyquist frequency), its delay compensated, the record
    extended on the line through its end samples; the kernel sums the same products in the
    same order, two to three times faster (``tests/tests_generators/test_decimation.py``).
    """
    if factor <= 1:
        return records
    if records.shape[1] < 2:
        return sp_signal.resample_poly(records, 1, factor, axis=1, padtype="line")
    taps, first, n_out = fir_design(factor, records.shape[1])
    return _filters.fir_decimate_rows(records, taps, factor, first, n_out)


@functools.lru_cache(maxsize=32)
def fir_design(factor: int, n: int) -> tuple[np.ndarray, int, int]:
    """The anti-alias filter of ``resample_poly(x, 1, factor)`` for records of ``n`` samples.

    Returns the taps as scipy applies them (zero-padded so that the kept outputs are centred,
    then reversed), the number of leading outputs scipy drops, and the output length.
    """
    half_len = 10 * factor
    taps = sp_signal.firwin(2 * half_len + 1, 1.0 / factor, window=("kaiser", 5.0))
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
