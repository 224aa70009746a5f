"""Envelope analysis and the kurtogram on synthetic signals with known answers."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import features as F


def am_signal(fm, depth, fc=3000.0, fs=20000.0, n=20000):
    t = np.arange(n) / fs
    return (1 + depth * np.cos(2 * np.pi * fm * t)) * np.cos(2 * np.pi * fc * t), fs


@settings(deadline=None, max_examples=20)
@given(fm=st.integers(20, 400), depth=st.floats(0.05, 0.9))
def test_am_carrier_gives_envelope_peak_at_modulation(fm, depth):
    x, fs = am_signal(fm, depth)
    f, a = F.envelope_spectrum(x, fs, band=(2000.0, 4000.0))
    assert f[np.argmax(a[5:]) + 5] == pytest.approx(fm, abs=f[1])
    assert a[np.argmin(abs(f - fm))] == pytest.approx(depth, rel=1e-3)


def test_squared_envelope():
    x, fs = am_signal(100, 0.5)
    f, a = F.envelope_spectrum(x, fs, band=(2000.0, 4000.0), method="squared")
    # (1 + m cos)^2 = 1 + 2 m cos + ...: line at fm of amplitude 2m = 1.0
    assert a[100] == pytest.approx(1.0, rel=1e-3)


def impulse_train_in_noise(rng, fs=25600.0, n=25600, rate=107.0, resonance=6000.0, snr=0.7):
    t = np.arange(n) / fs
    x = np.zeros(n)
    x[(np.arange(0, n / fs, 1 / rate) * fs).astype(int)] = 1.0
    ring = np.exp(-t[:256] * 1500) * np.sin(2 * np.pi * resonance * t[:256])
    x = np.convolve(x, ring)[:n]
    x /= x.std()
    return x + rng.standard_normal(n) / snr, fs


def test_kurtogram_finds_the_impulse_band(rng):
    x, fs = impulse_train_in_noise(rng)
    kg = F.kurtogram(x, fs, nlevel=6)
    low, high = kg.band
    assert low <= 6000.0 <= high
    assert kg.bandwidth <= fs / 4
    assert kg.kurtosis > 1.0
    assert kg.matrix.shape[0] == len(kg.levels)


def test_kurtogram_of_gaussian_noise_is_flat(rng):
    kg = F.kurtogram(rng.standard_normal(25600), 25600.0, nlevel=5)
    assert abs(kg.kurtosis) < 0.5  # spectral kurtosis of stationary Gaussian noise is 0


def test_envelope_spectrum_with_automatic_band(rng):
    x, fs = impulse_train_in_noise(rng)
    f, a, band = F.envelope_spectrum(x, fs, return_band=True)
    assert band[0] <= 6000.0 <= band[1]
    window = (f > 50) & (f < 400)
    assert f[window][np.argmax(a[window])] == pytest.approx(107.0, abs=f[1])


def test_prewhitening_removes_a_strong_tone(rng):
    x, fs = impulse_train_in_noise(rng)
    t = np.arange(x.size) / fs
    masked = x + 50 * np.cos(2 * np.pi * 6000 * t)  # a discrete tone hides the impulses
    f, a = F.envelope_spectrum(masked, fs, band=(4000.0, 8000.0), prewhitening=True)
    window = (f > 50) & (f < 400)
    assert f[window][np.argmax(a[window])] == pytest.approx(107.0, abs=f[1])


def test_bad_envelope_input():
    x, fs = am_signal(100, 0.5)
    with pytest.raises(F.FeatureError, match="band = \\(2000, 12000\\)"):
        F.envelope_spectrum(x, fs, band=(2000.0, 12000.0))
    with pytest.raises(F.FeatureError, match="method"):
        F.envelope(x, fs, method="abs")
    with pytest.raises(F.FeatureError, match="at least 64"):
        F.kurtogram(x[:10], fs)
    with pytest.raises(F.FeatureError, match="nlevel = 20"):
        F.kurtogram(x, fs, nlevel=20)
    # samples x channels where a signal a row is expected: the message says which axis
    columns = np.stack([x, x], axis=1)
    with pytest.raises(F.FeatureError, match=r"2 samples along its last axis \(shape \("):
        F.envelope_spectrum(columns, fs)
