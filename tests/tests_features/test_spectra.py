"""Spectra on ideal synthetic signals with known answers (librosa's 'synthetic ideal' tier).

ANALYTIC_RTOL = 1e-9: a bin-centred tone under a Hann window reads exactly its amplitude
(coherent gain corrected), up to round-off.
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import features as F

ANALYTIC_RTOL = 1e-9


@settings(deadline=None, max_examples=30)
@given(amp=st.floats(1e-6, 1e3), bin_index=st.integers(5, 495), phase=st.floats(0, 6.28))
def test_bin_centred_tone_reads_its_amplitude(amp, bin_index, phase):
    fs, n = 1000.0, 1000
    t = np.arange(n) / fs
    f, a = F.amplitude_spectrum(amp * np.cos(2 * np.pi * bin_index * t + phase), fs)
    assert a[bin_index] == pytest.approx(amp, rel=ANALYTIC_RTOL)
    _, rms = F.amplitude_spectrum(
        amp * np.cos(2 * np.pi * bin_index * t + phase), fs, scaling="rms"
    )
    assert rms[bin_index] == pytest.approx(amp / np.sqrt(2), rel=ANALYTIC_RTOL)


def test_off_bin_tone_with_flattop_window():
    fs, n = 1000.0, 1000
    t = np.arange(n) / fs
    _, a = F.amplitude_spectrum(3.0 * np.sin(2 * np.pi * 100.4 * t), fs, window="flattop")
    assert a.max() == pytest.approx(3.0, rel=2e-3)  # flat-top scalloping loss < 0.02 dB


def test_averaged_spectrum_and_axis():
    rng = np.random.default_rng(1)
    fs = 2048.0
    t = np.arange(8192) / fs
    x = np.stack([np.cos(2 * np.pi * 64 * t), 2 * np.cos(2 * np.pi * 128 * t)])
    x = x + 0.01 * rng.standard_normal(x.shape)
    f, a = F.amplitude_spectrum(x.T, fs, nperseg=1024, axis=0)
    assert a.shape == (513, 2)
    assert a[np.argmin(abs(f - 64)), 0] == pytest.approx(1.0, rel=0.01)
    assert a[np.argmin(abs(f - 128)), 1] == pytest.approx(2.0, rel=0.01)


def test_psd_integrates_to_variance():
    rng = np.random.default_rng(2)
    x = rng.standard_normal(65536)
    f, p = F.power_spectral_density(x, 1000.0)
    assert np.trapezoid(p, f) == pytest.approx(1.0, rel=0.05)


def test_band_rms_is_parseval_over_the_bands_bins():
    rng = np.random.default_rng(3)
    fs, n = 1000.0, 4000
    t = np.arange(n) / fs
    x = 3.0 * np.cos(2 * np.pi * 120.0 * t) + rng.standard_normal(n)
    assert F.band_rms(x, fs, (0.0, fs / 2)) == pytest.approx(np.sqrt(np.mean(x**2)), rel=1e-12)
    low = F.band_rms(x, fs, (0.0, 250.0))
    high = F.band_rms(x, fs, (250.0, 500.0))
    assert low**2 + high**2 == pytest.approx(np.mean(x**2), rel=1e-12)  # bands tile
    # the tone (RMS 3 / sqrt 2) and the noise's share of a 10 Hz band
    tone = F.band_rms(x, fs, (115.0, 125.0))
    assert tone == pytest.approx(np.sqrt(4.5 + 10.0 / 500.0), rel=0.05)
    with pytest.raises(F.FeatureError, match=r"band = \(300, 600\) Hz"):
        F.band_rms(x, fs, (300.0, 600.0))


def test_velocity_from_acceleration():
    fs, n = 10000.0, 10000
    t = np.arange(n) / fs
    f0, v0 = 50.0, 2e-3
    accel = -v0 * 2 * np.pi * f0 * np.sin(2 * np.pi * f0 * t)  # d/dt of v0 cos
    vel = F.integrate_signal(accel, fs, low_cut=5.0)
    np.testing.assert_allclose(vel, v0 * np.cos(2 * np.pi * f0 * t), atol=1e-9)
    f, a = F.amplitude_spectrum(accel, fs)
    va = F.integrate_spectrum(f, a, low_cut=5.0)
    assert va[50] == pytest.approx(v0, rel=1e-9)
    assert va[2] == 0.0


def test_acceleration_from_velocity_is_the_derivative_and_undoes_the_bands_integration():
    """Tones that do not fit the record whole (the periodic extension jumps at the wrap):
    the derivative within 1e-4 of its amplitude away from the ends, where the jump would
    have made an impulse as large as the tone; and velocity_band_rms of the result gives the
    velocity's own bands (those of its DFT bins)."""
    fs, n = 12000.0, 8400  # 0.7 s
    t = np.arange(n) / fs
    rng = np.random.default_rng(4)
    velocity = 2.0 * np.sin(2 * np.pi * 107.3 * t + 0.4) + 0.5 * np.cos(2 * np.pi * 33.3 * t)
    exact = 2.0 * 2 * np.pi * 107.3 * np.cos(
        2 * np.pi * 107.3 * t + 0.4
    ) - 0.5 * 2 * np.pi * 33.3 * np.sin(2 * np.pi * 33.3 * t)
    a = F.acceleration_from_velocity(velocity, fs)
    scale = 2.0 * 2 * np.pi * 107.3
    assert np.max(np.abs(a - (exact - exact.mean()))[100:-100]) < 1e-4 * scale
    assert np.max(np.abs(a)) < 1.5 * scale  # no impulse at the wrap
    noise = velocity + 0.1 * rng.standard_normal(n)
    bands = {"a": (50.0, 300.0), "b": (300.0, 1800.0), "c": (1800.0, 5000.0)}
    spec = np.fft.rfft(noise - noise.mean())
    f = np.fft.rfftfreq(n, 1 / fs)
    power = 2 * np.abs(spec) ** 2 / n**2
    back = F.velocity_band_rms(F.acceleration_from_velocity(noise, fs), fs, bands)
    for name, (low, high) in bands.items():
        own = np.sqrt(power[(f >= low) & (f < high)].sum())
        assert back[name] == pytest.approx(own, rel=5e-3), name  # the line out: 0.1-0.16 %


def test_a_rate_a_rounding_off_gives_the_same_band_figures():
    """A rate read from a time column (12000 Hz as 11999.99998, or 1e-6 off) puts the bins
    at the bands' edges a hair off them: the same bins count (they flipped one out and the
    next in: 0.25 % in the 300-1800 Hz band of a 2 s record)."""
    x = np.random.default_rng(5).standard_normal(24000)
    exact = F.velocity_band_rms(x, 12000.0)
    for fs in (11999.99998, 12000.0 * (1 + 1e-6), 12000.0 * (1 - 1e-6)):
        near = F.velocity_band_rms(x, fs)
        for name, value in exact.items():
            assert near[name] == pytest.approx(value, rel=2e-6), (fs, name)
        assert F.band_rms(x, fs, (50.0, 300.0)) == pytest.approx(
            F.band_rms(x, 12000.0, (50.0, 300.0)), rel=1e-12
        )


@pytest.mark.parametrize(
    ("x", "fs", "match"),
    [
        ([], 100.0, "0 samples"),
        ([1.0, np.nan, 2.0, 3.0], 100.0, "non-finite"),
        (np.ones(100), 0.0, "fs = 0.0"),
        (np.ones(100), float("nan"), "fs = nan"),
    ],
)
def test_bad_input(x, fs, match):
    with pytest.raises(F.FeatureError, match=match):
        F.amplitude_spectrum(x, fs)


def test_nperseg_too_long():
    with pytest.raises(F.FeatureError, match="nperseg = 200"):
        F.amplitude_spectrum(np.ones(100), 10.0, nperseg=200)


_X = np.random.default_rng(7).standard_normal(12000)
_RATES = {"bpfo": 107.4, "bpfi": 162.2, "two_bsf": 141.2, "ftf": 11.9, "shaft": 29.95}


@pytest.mark.parametrize(
    ("call", "said"),
    [
        (lambda: F.kurtogram(_X, 12e3, nlevel=2.5), r"nlevel = 2\.5 is not an integer"),
        (lambda: F.kurtogram(_X, 12e3, min_bandwidth=-1.0), r"min_bandwidth = -1\.0 Hz is out"),
        (lambda: F.integrate_signal(_X, 12e3, order=0), r"order = 0 is outside .*\[1, inf\]"),
        (lambda: F.integrate_spectrum(np.arange(9.0), np.ones(9), order=-1), r"order = -1"),
        (
            lambda: F.velocity_band_rms(_X, 12e3, {"low": (300.0, 50.0)}),
            r"bands\['low'\] = \(300, 50\) Hz is outside the allowed range",
        ),
        (
            lambda: F.extract_features(_X, 12e3, fault_frequencies=_RATES, n_harmonics=0),
            r"n_harmonics = 0 is outside the allowed range \[1, inf\]",
        ),
        (lambda: F.envelope_scores(_X, 12e3, _RATES, harmonics=0), r"harmonics = 0 is outside"),
        (
            lambda: F.harmonic_amplitudes(
                np.arange(9.0), np.ones(9), 2.0, n_harmonics=0, half_width=1.0
            ),
            r"n_harmonics = 0 is outside",
        ),
        (lambda: F.peak_offset_bins(np.ones(9), 0), r"k = 0 is outside the allowed range \[1, 7\]"),
        (lambda: F.slip_line(np.arange(99.0), np.ones(99), -5.0), r"line = -5\.0 Hz is outside"),
        (
            lambda: F.slip_line(np.arange(99.0), np.ones(99), 50.0, search=(0.01, -0.02)),
            r"search = \(0\.01, -0\.02\) is outside the allowed range",
        ),
        (lambda: F.candidate_bands(12e3, 0, min_bandwidth=100.0), r"n = 0 is outside"),
        (lambda: F.candidate_bands(12e3, 9000, min_bandwidth=-1.0), r"min_bandwidth = -1\.0 Hz"),
        (lambda: F.band_metrics(np.arange(9.0), np.ones(9), []), r"bands is a list; give the"),
    ],
)
def test_counts_orders_and_bands_that_mean_nothing_are_refused_by_name(call, said):
    """Before: a fractional nlevel truncated, a negative band width, an order of 0 or -1 (no
    integration, or a derivative), a reversed band read as empty, no harmonics (numpy's
    'mean of empty slice', 'max() arg is an empty sequence', 'need at least one array to
    stack') and a peak bin without neighbours all passed or failed obscurely."""
    with pytest.raises(F.FeatureError, match=said):
        call()
