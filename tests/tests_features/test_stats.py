"""Time-domain statistics against closed forms."""

import numpy as np
import pytest

import features as F


def test_sine_statistics():
    t = np.arange(100000) / 100000.0
    s = F.time_statistics(3.0 * np.sin(2 * np.pi * 50 * t))
    assert s["rms"] == pytest.approx(3 / np.sqrt(2), rel=1e-6)
    assert s["peak"] == pytest.approx(3.0, rel=1e-6)
    assert s["crest_factor"] == pytest.approx(np.sqrt(2), rel=1e-6)
    assert s["kurtosis"] == pytest.approx(1.5, rel=1e-6)
    assert s["skewness"] == pytest.approx(0.0, abs=1e-9)
    assert s["shape_factor"] == pytest.approx(np.pi / (2 * np.sqrt(2)), rel=1e-6)
    assert s["impulse_factor"] == pytest.approx(np.pi / 2, rel=1e-6)


def test_gaussian_kurtosis_and_batch(rng):
    x = rng.standard_normal((3, 200000))
    s = F.time_statistics(x)
    np.testing.assert_allclose(s["kurtosis"], 3.0, atol=0.05)
    assert s["rms"].shape == (3,)
    assert set(s) == set(F.TIME_STATISTICS)


def test_a_constant_signal_has_statistics_of_zero_not_nan():
    """Kurtosis and skewness of a constant record are 0, as its crest and shape factors are
    (before: 0 / 0 = NaN with numpy's warning, which a feature table then carried)."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        one = F.time_statistics(np.full(50, 3.0))
        rows = F.time_statistics(np.vstack([np.full(50, 2.0), np.sin(np.arange(50.0))]))
    assert all(v == 0.0 for v in one.values())
    assert rows["kurtosis"][0] == 0.0 and rows["kurtosis"][1] > 1.0
