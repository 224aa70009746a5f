"""Fault bands and band metrics (bearingFaultBands / faultBandMetrics style)."""

import numpy as np
import pytest

import features as F

CTX = {"bpfo": 107.36, "bpfi": 162.19, "two_bsf": 141.17}


def test_fault_bands_harmonics_and_sidebands():
    bands = F.fault_bands(CTX, n_harmonics=2, sidebands={"bpfi": 29.95}, width=4.0)
    bpfi = bands[bands.fault == "bpfi"]
    assert len(bpfi) == 6  # 2 harmonics x (-1, 0, +1)
    row = bpfi[(bpfi.harmonic == 2) & (bpfi.sideband == 1)].iloc[0]
    assert row.center_hz == pytest.approx(2 * 162.19 + 29.95)
    assert row.high_hz - row.low_hz == pytest.approx(4.0)
    assert set(bands.fault) == {"bpfo", "bpfi", "two_bsf"}
    orders = F.fault_bands(CTX, shaft_frequency=29.95, domain="order")
    assert orders.loc[0, "center"] == pytest.approx(107.36 / 29.95)


def test_band_metrics_find_the_tones():
    fs, n = 4096.0, 4096 * 4
    t = np.arange(n) / fs
    x = 2.0 * np.cos(2 * np.pi * 107.36 * t) + 0.5 * np.cos(2 * np.pi * 2 * 162.19 * t)
    f, a = F.amplitude_spectrum(x, fs, window="flattop")
    metrics = F.band_metrics(f, a, F.fault_bands(CTX, n_harmonics=2, width=2.0))
    assert list(metrics.columns) == list(F.BAND_METRIC_COLUMNS)
    m = metrics.set_index("band")
    assert m.loc["bpfo_1x", "peak_amplitude"] == pytest.approx(2.0, rel=0.01)
    assert m.loc["bpfo_1x", "peak_frequency_hz"] == pytest.approx(107.36, abs=0.25)
    assert m.loc["bpfi_2x", "peak_amplitude"] == pytest.approx(0.5, rel=0.01)
    assert m.loc["two_bsf_1x", "peak_amplitude"] < 1e-3
    assert m.loc["total", "peak_amplitude"] == pytest.approx(2.0, rel=0.01)
    assert m.loc["total", "band_power"] == pytest.approx(m.drop("total").band_power.sum())


def test_band_amplitude_and_harmonics():
    f = np.arange(0, 500.0, 0.5)
    s = np.zeros_like(f)
    s[[200, 400, 600]] = [3.0, 2.0, 1.0]  # 100, 200, 300 Hz
    assert F.band_amplitude(f, s, 100.2, half_width=0.5) == 3.0
    np.testing.assert_array_equal(F.harmonic_amplitudes(f, s, 100.0, half_width=0.3), [3, 2, 1])
    assert F.band_amplitude(f, s, 900.0, half_width=1.0) == 0.0


def test_bad_bands():
    with pytest.raises(F.FeatureError, match="fault_frequencies\\['bpfo'\\]"):
        F.fault_bands({"bpfo": -1.0})
    with pytest.raises(F.FeatureError, match="shaft_frequency is required"):
        F.fault_bands(CTX, domain="order")
    with pytest.raises(F.FeatureError, match="half_width"):
        F.band_amplitude(np.arange(10.0), np.ones(10), 5.0, half_width=0.0)


def test_line_snr_floor_guard_and_edge():
    """A 100 Hz line 40 dB over a flat floor; the floor leaves out the line's skirt;
    a band past the spectrum's end measures nothing; the half width is validated."""
    from features import FeatureError, line_snr

    f = np.arange(0.0, 500.0, 0.5)
    a = np.full(f.size, 0.01)
    a[200] = 1.0
    assert line_snr(f, a, 100.0, half_width=1.0) == pytest.approx((40.0, 1.0, 0.01))
    # the line's own skirt (a Hann leakage of 3 bins) stays out of the floor with guard 3
    skirt = a.copy()
    skirt[198:203] = 0.5
    skirt[200] = 1.0
    assert line_snr(f, skirt, 100.0, half_width=0.75, guard=3.0)[2] == pytest.approx(0.01)
    assert line_snr(f, a, 499.5, half_width=1.0) == (0.0, 0.0, 0.0)
    with pytest.raises(FeatureError, match="half_width"):
        line_snr(f, a, 100.0, half_width=0.0)


@pytest.mark.parametrize("center", [float("nan"), float("inf")])
def test_a_line_that_is_no_frequency_is_refused_by_name(center):
    from features import FeatureError, band_amplitude, line_snr

    f = np.arange(0.0, 500.0, 0.5)
    a = np.full(f.size, 0.01)
    for measure in (line_snr, band_amplitude):
        with pytest.raises(FeatureError, match=rf"center = {center} Hz is not a finite"):
            measure(f, a, center, half_width=1.0)


def _line_snr_whole_spectrum(f, s, center, half_width, guard):
    """line_snr's definition over every bin (before stop 36 it ran so)."""
    df = f[1] - f[0]
    hw = max(half_width, df)
    near = np.abs(f - center)
    line = near <= hw
    if not line.any() or center + hw > f[-1]:
        return 0.0, 0.0, 0.0
    peak = float(s[line].max())
    window = (near <= max(0.10 * center, 10 * df)) & ~(near <= guard * hw)
    floor = float(np.median(s[window])) if window.any() else 0.0
    snr = float(20.0 * np.log10(max(peak, 1e-300) / max(floor, 1e-300))) if peak > 0 else 0.0
    return snr, peak, floor


def test_line_snr_on_its_slice_equals_the_whole_spectrum_bit_for_bit():
    rng = np.random.default_rng(36)
    for fs, n in ((25600.0, 25600), (12000.0, 12000), (97656.0, 50000), (1000.0, 700)):
        f = np.fft.rfftfreq(n, 1 / fs)
        for trial in range(150):
            s = np.abs(rng.standard_normal(f.size))
            center = (
                float(f[rng.integers(0, f.size)])  # on a bin
                if trial % 3 == 0
                else float(rng.uniform(-5.0, 0.55 * fs))  # anywhere, past both ends too
            )
            half_width = float(rng.choice([0.1, 0.7, 1.5 * (f[1] - f[0]), 4.0]))
            for guard in (1.0, 2.0, 5.0):
                assert F.line_snr(f, s, center, half_width=half_width, guard=guard) == (
                    _line_snr_whole_spectrum(f, s, center, half_width, guard)
                )
