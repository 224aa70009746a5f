"""The anti-alias decimation kernel gives scipy's ``resample_poly`` bit for bit."""

import numpy as np
import pytest
from scipy import signal as sp_signal

from generators.decimation import CHANNEL_COLUMNS, decimate, decimate_rows


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
    rng = np.random.default_rng(7)
    n = 4 * 3001
    state = _records(rng, n, 8).T.copy()
    accel = _records(rng, n, 4).T.copy()
    channels = list(CHANNEL_COLUMNS)
    got = decimate(state, accel, 4, channels)
    for name in channels:
        which, column = CHANNEL_COLUMNS[name]
        source = (state, accel)[which][:, column]
        expected = sp_signal.resample_poly(source, 1, 4, padtype="line")
        assert np.array_equal(got[name].view(np.int64), expected.view(np.int64)), name
    # factor 1: the record's columns as they are
    plain = decimate(state, accel, 1, ["housing_velocity_y"])["housing_velocity_y"]
    assert np.array_equal(plain, state[:, CHANNEL_COLUMNS["housing_velocity_y"][1]])
