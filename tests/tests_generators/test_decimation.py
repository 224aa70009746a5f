"""The anti-alias decimation kernel gives scipy's ``resample_poly`` bit for bit."""

import numpy as np
import pytest
from scipy import signal as sp_signal

from generators.decimation import (
    CHANNEL_COLUMNS,
    VELOCITY_OF,
    decimate,
    decimate_rows,
    decimation_taps,
)


def _records(rng, n, rows):
    """Rows of noise over six decades of scale, on a trend (the line extension matters)."""
    scale = 10.0 ** rng.uniform(-9, 3, rows)[:, None]
    return rng.normal(size=(rows, n)) * scale + np.linspace(-2.0, 5.0, n) * scale


@pytest.mark.parametrize("factor", [2, 3, 4, 8])
@pytest.mark.parametrize("n", [9, 400, 13201])
def test_rows_are_scipys_resample_poly_bit_for_bit(factor, n):
    rng = np.random.default_rng(factor * 1000 + n)
    x = _records(rng, n, 5)
    expected = sp_signal.resample_poly(x, 1, factor, axis=1, padtype="line")
    got = decimate_rows(x, factor)
    assert got.shape == expected.shape
    assert np.array_equal(got.view(np.int64), expected.view(np.int64))
    # a view into a wider buffer (the lanes' record) gives the same
    wide = np.zeros((5, n + 7))
    wide[:, :n] = x
    assert np.array_equal(decimate_rows(wide[:, :n], factor), got)


def test_channels_from_the_record_columns_are_scipys_bit_for_bit():
    """Displacements and velocities: their record column through ``resample_poly``; an
    acceleration: its velocity's column through ``resample_poly`` with the differentiating
    taps, over the record interval (the same bits either way)."""
    rng = np.random.default_rng(7)
    n = 4 * 3001
    record_dt = 1.0 / 48000.0
    state = _records(rng, n, 8).T.copy()
    accel = _records(rng, n, 4).T.copy()
    channels = list(CHANNEL_COLUMNS)
    got = decimate(state, accel, 4, channels, record_dt)
    for name in channels:
        if name in VELOCITY_OF:
            source = state[:, CHANNEL_COLUMNS[VELOCITY_OF[name]][1]]
            taps = decimation_taps(4, derivative=True)
            expected = sp_signal.resample_poly(source, 1, 4, window=taps, padtype="line")
            expected /= record_dt
        else:
            which, column = CHANNEL_COLUMNS[name]
            source = (state, accel)[which][:, column]
            expected = sp_signal.resample_poly(source, 1, 4, padtype="line")
        assert np.array_equal(got[name].view(np.int64), expected.view(np.int64)), name
    # the rows' kernel gives the same
    velocities = state[:, [CHANNEL_COLUMNS[VELOCITY_OF[name]][1] for name in VELOCITY_OF]].T
    rows = decimate_rows(np.ascontiguousarray(velocities), 4, record_dt)
    for row, name in zip(rows, VELOCITY_OF, strict=True):
        assert np.array_equal(row, got[name]), name
    with pytest.raises(ValueError, match="record_dt = None"):
        decimate(state, accel, 4, ["housing_acceleration_y"])
    # factor 1: the record's columns as they are, the accelerations' own
    plain = decimate(state, accel, 1, ["housing_velocity_y", "housing_acceleration_y"])
    assert np.array_equal(plain["housing_velocity_y"], state[:, 7])
    assert np.array_equal(plain["housing_acceleration_y"], accel[:, 3])
