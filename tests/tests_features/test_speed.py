"""The shaft rate read from the spectrum's 1x line (features.shaft_rate_from_spectrum)."""

import numpy as np
import pytest

import features as F
from features.speed import SHAFT_LINE_DB

FS = 12000.0


def _shaft_lines(rate_hz: float, seconds: float = 1.0, amplitude: float = 0.3, seed: int = 0):
    """Unit white noise plus the shaft's 1x-4x lines (amplitude / order each)."""
    rng = np.random.default_rng(seed)
    t = np.arange(int(seconds * FS)) / FS
    lines = sum(amplitude / h * np.sin(2 * np.pi * h * rate_hz * t + h) for h in range(1, 5))
    return rng.standard_normal(t.size) + lines


@pytest.mark.parametrize("true_hz", [28.83, 29.95, 24.77, 97.0])
def test_the_1x_line_places_the_rate_within_a_tenth_of_a_bin(true_hz):
    """A 1 s record (1 Hz bins) given a speed 4 % high: the 1x line's interpolated peak
    (about 22 dB over the noise) is within 0.1 Hz of the true rate, inside the warning's
    1.5 % (0.45 Hz at 30 Hz) with room to spare."""
    estimate = F.shaft_rate_from_spectrum(_shaft_lines(true_hz), FS, 1.04 * true_hz)
    assert estimate.found and estimate.line_db > SHAFT_LINE_DB
    assert estimate.rate_hz == pytest.approx(true_hz, abs=0.1)
    assert estimate.deviation == pytest.approx(1 / 1.04 - 1, abs=0.004)


def test_no_line_no_rate_and_a_mains_line_is_not_taken_for_the_shaft():
    noise = np.random.default_rng(1).standard_normal(int(4 * FS))
    estimate = F.shaft_rate_from_spectrum(noise, FS, 30.0)
    assert not estimate.found and estimate.rate_hz == 30.0
    # a 4 s record (0.25 Hz bins), a strong 50 Hz line (mains) and no shaft line, the speed
    # given as 49.5 Hz (2970 rpm): neither the mains line nor its skirt is read as the shaft's
    t = np.arange(int(4 * FS)) / FS
    mains = noise + 5.0 * np.sin(2 * np.pi * 50.0 * t)
    assert not F.shaft_rate_from_spectrum(mains, FS, 49.5).found
    # with a shaft line at 48.0 Hz beside it (8 bins off), that line is found
    both = mains + 0.5 * np.sin(2 * np.pi * 48.0 * t)
    estimate = F.shaft_rate_from_spectrum(both, FS, 49.5)
    assert estimate.found and estimate.rate_hz == pytest.approx(48.0, abs=0.05)


def test_a_noise_free_records_faint_line_is_no_shaft_line():
    """A record with no floor of its own (a noise-free simulation) is judged over a good
    measurement chain's, INSTRUMENT_FLOOR_DB under its RMS: a line 80 dB under a strong
    ball-pass train is not the shaft's (against its own median it stood far over 12 dB);
    40 dB under, it is. The record's length is a fast FFT's and an awkward one (chirp-z)."""
    from features.instrument_floor import INSTRUMENT_FLOOR_DB

    for n in (12000, 12007):
        t = np.arange(n) / FS
        train = sum(np.sin(2 * np.pi * k * 172.07 * t + k) / k for k in range(1, 30))
        rms = np.std(train)
        for level_db, found in ((-80.0, False), (-40.0, True)):
            line = np.sqrt(2) * rms * 10 ** (level_db / 20) * np.sin(2 * np.pi * 46.5 * t)
            estimate = F.shaft_rate_from_spectrum(train + line, FS, 48.0)
            assert estimate.found is found, (n, level_db, estimate)
            if found:
                assert estimate.rate_hz == pytest.approx(46.5, abs=0.1)  # a tenth of a bin
                # its height over the chain's floor: the level over the floor's per-bin share
                chain_db = INSTRUMENT_FLOOR_DB + level_db + 10 * np.log10(n / 2 / np.log(2))
                assert estimate.line_db == pytest.approx(chain_db + 10 * np.log10(2 / 3), abs=1)


def test_a_line_just_outside_the_search_is_not_found_on_its_skirt():
    """A strong line 6.3 % under the rate given (outside the +/-5 % searched) makes the
    search's lower edge its largest bin, on the line's skirt: no 1x line is found there (the
    peak's interpolation put the rate at the outside line's own frequency), while the same
    line 4 % under is."""
    noise = 0.01 * np.random.default_rng(3).standard_normal(int(FS))
    t = np.arange(noise.size) / FS
    for below, found in ((0.063, False), (0.04, True)):
        x = noise + np.sin(2 * np.pi * 48.0 * (1 - below) * t)
        estimate = F.shaft_rate_from_spectrum(x, FS, 48.0)
        assert estimate.found is found, (below, estimate)
        assert 0.95 * 48.0 <= estimate.rate_hz <= 1.05 * 48.0


def test_bad_input_is_refused_by_name():
    x = _shaft_lines(30.0)
    with pytest.raises(F.FeatureError, match="search = 0.5"):
        F.shaft_rate_from_spectrum(x, FS, 30.0, search=0.5)
    with pytest.raises(F.FeatureError, match="given_hz"):
        F.shaft_rate_from_spectrum(x, FS, -30.0)
    with pytest.raises(F.FeatureError, match="given_hz = 5000"):
        F.shaft_rate_from_spectrum(x, FS, 5000.0)


def test_a_record_of_awkward_length_gets_the_padded_transforms_bins():
    # a length with a large prime factor takes the chirp-z path: the same bins as the FFT's
    from features.speed import _padded_spectrum

    rng = np.random.default_rng(5)
    n = 12007  # prime
    x = rng.standard_normal(n) * np.hanning(n)
    points = 16 * n
    first, last = 2400, 2900
    full = np.abs(np.fft.rfft(x, points))
    part = _padded_spectrum(x, points, first, last)
    np.testing.assert_allclose(
        part[first : last + 1], full[first : last + 1], rtol=0, atol=1e-9 * full.max()
    )
    assert part.shape == full.shape and not part[:first].any() and not part[last + 1 :].any()
    # and a fast length keeps the FFT itself
    fast = 16 * 12000
    np.testing.assert_array_equal(
        _padded_spectrum(x[:12000], fast, first, last), np.abs(np.fft.rfft(x[:12000], fast))
    )


def _pulse_train(rate_of_t, fs, seconds, *, duty=0.1, high=5.0, noise=0.0, seed=0):
    """A tachometer's pulses for a shaft rate rate_of_t(t) [Hz]: the phase integrated."""
    t = np.arange(int(seconds * fs)) / fs
    phase = np.cumsum(rate_of_t(t)) / fs
    x = np.where(phase % 1.0 < duty, high, 0.0)
    return x + noise * np.random.default_rng(seed).standard_normal(t.size)


@pytest.mark.parametrize(("fs", "noise"), [(48000.0, 0.05), (12000.0, 0.0), (12000.0, 0.5)])
def test_the_tachos_rate_is_the_shafts(fs, noise):
    """Edges interpolated at the 50 % level: the mean rate over ~290 revolutions within
    1e-5 (the edges' timing error, under a sample, over 10 s); a steady shaft's spread is
    the edges' jitter only (a sample in a 1/29 s revolution: < 0.5 %)."""
    x = _pulse_train(lambda t: np.full(t.size, 29.17), fs, 10.0, noise=noise)
    got = F.shaft_rate_from_tacho(x, fs)
    assert got.rate_hz == pytest.approx(29.17, rel=1e-5)
    assert got.variation < 0.005 and got.pulses in (291, 292)
    # two pulses a revolution, the pulse low instead of high: the same rate
    two = 5.0 - _pulse_train(lambda t: np.full(t.size, 2 * 29.17), fs, 10.0, duty=0.3)
    assert F.shaft_rate_from_tacho(two, fs, pulses_per_rev=2).rate_hz == pytest.approx(
        29.17, rel=1e-5
    )


def test_a_ramping_shafts_spread_is_its_rates():
    """28 -> 30 Hz over 10 s: the mean 29 Hz, and the spread that of a uniform range of 2 Hz,
    2 / sqrt(12) / 29 = 1.99 %."""
    x = _pulse_train(lambda t: 28.0 + 0.2 * t, 48000.0, 10.0)
    got = F.shaft_rate_from_tacho(x, 48000.0)
    assert got.rate_hz == pytest.approx(29.0, rel=2e-3)
    assert got.variation == pytest.approx(2.0 / np.sqrt(12.0) / 29.0, rel=0.05)


def test_a_tacho_without_pulses_is_refused_by_name():
    with pytest.raises(F.FeatureError, match="channel is constant"):
        F.shaft_rate_from_tacho(np.ones(1000), FS)
    # 1.5 s at 1 Hz: pulses at 0 and 1 s, and the one the record starts in is no edge
    one_rev = _pulse_train(lambda t: np.full(t.size, 1.0), FS, 1.5)
    with pytest.raises(F.FeatureError, match=r"1 rising edge\(s\) found, at least 3 needed"):
        F.shaft_rate_from_tacho(one_rev, FS)
    with pytest.raises(F.FeatureError, match="pulses_per_rev = 0"):
        F.shaft_rate_from_tacho(one_rev, FS, pulses_per_rev=0)


def test_a_vibration_given_as_the_tacho_is_refused_and_real_pulse_trains_are_not():
    """A channel whose crossings come at random (noise; a bearing's impacts at random
    spacing) read as pulses gave a "speed" (115,000 rpm from white noise at 12 kHz). A
    shaft cannot change its period by 10 % from one revolution to the next; a tachometer's
    pulses with their timing jitter, a run-up and lost pulses stay far under."""
    rng = np.random.default_rng(11)
    noise = rng.standard_normal(120000)
    with pytest.raises(F.FeatureError, match=r"period differs from the next by \d+ % .*no tach"):
        F.shaft_rate_from_tacho(noise, 12000.0)
    starts = np.zeros(120000)
    starts[np.cumsum(rng.integers(60, 180, 900))[:800]] = 1.0  # impacts at random spacing,
    ring = np.exp(-np.arange(60) / 15.0) * np.sin(2 * np.pi * 2000.0 * np.arange(60) / 12000.0)
    impacts = np.convolve(starts, ring)[:120000] + 0.2 * noise  # each ringing at 2 kHz
    with pytest.raises(F.FeatureError, match="a vibration's channel"):
        F.shaft_rate_from_tacho(impacts, 12000.0)
    run_up = _pulse_train(lambda t: 10.0 + 4.0 * t, 12000.0, 10.0)  # 10 -> 50 Hz
    assert F.shaft_rate_from_tacho(run_up, 12000.0).variation > 0.3
    lost = _pulse_train(lambda t: np.full(t.size, 30.0), 12000.0, 10.0, noise=0.3)
    edges = np.flatnonzero(np.diff((lost > 2.5).astype(int)) > 0)
    for start in edges[rng.random(edges.size) < 0.2]:  # a fifth of the pulses missing
        lost[start : start + 50] = 0.0
    assert F.shaft_rate_from_tacho(lost, 12000.0).rate_hz == pytest.approx(30.0, rel=0.25)


@pytest.mark.parametrize("fs", [12000.0, 48000.0])
@pytest.mark.parametrize("order", [3.585, 20.0])
def test_order_tracking_reads_the_record_at_equal_angles(fs, order):
    """A component at a fixed order of a shaft ramping 28 -> 31.2 Hz, resampled to constant
    speed: sample j is the component at the first edge's angle plus j rate / fs revolutions.
    The error bound is the edges' timing: a square pulse sampled without an anti-alias
    filter times each edge within half a sample, 0.5 / fs s or 0.5 rate / fs revolutions,
    which moves an order-k component by up to 2 pi k 0.5 rate / fs (x 1.25 for the
    interpolation between edges and samples)."""
    t = np.arange(int(4 * fs)) / fs
    phase = np.cumsum(28.0 + 0.8 * t) / fs
    tacho = np.where(phase % 1.0 < 0.05, 5.0, 0.0)
    speed = F.shaft_rate_from_tacho(tacho, fs)
    assert speed.variation > 0.02  # a ramp the untracked lines smear over
    y = F.order_track(np.sin(2 * np.pi * order * phase), fs, speed)
    first = np.round(np.interp(speed.edge_times[0], t, phase))  # an edge: a whole turn
    expected = np.sin(2 * np.pi * order * (first + np.arange(y.size) * speed.rate_hz / fs))
    bound = 1.25 * 2 * np.pi * order * 0.5 * 31.2 / fs
    assert np.abs(y - expected).max() < bound
    assert y.size == pytest.approx(speed.revolutions / speed.rate_hz * fs, abs=2)


def test_order_tracking_needs_edges_within_the_record():
    x = np.zeros(12000)
    speed = F.shaft_rate_from_tacho(_pulse_train(lambda t: np.full(t.size, 30.0), FS, 1.0), FS)
    with pytest.raises(F.FeatureError, match="order tracking needs three or more"):
        F.order_track(x[:100], FS, speed)  # the edges lie beyond a shorter record
