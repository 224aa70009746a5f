"""Discrete/random separation and fault-targeted band selection (features.separation)."""

import numpy as np
import pytest
from scipy import signal as sp_signal

import features
from features.separation import (
    candidate_bands,
    detection_threshold_db,
    remove_harmonics,
    select_band,
    separate_discrete,
)

FS = 12000.0


def _impacts(rate, n, rng, jitter=0.0, resonance=3000.0):
    """Impacts at ``rate`` [Hz] ringing at ``resonance``; jitter as a fraction of the period."""
    times = np.arange(0.0, n / FS, 1.0 / rate)
    times = times + rng.normal(0.0, jitter / rate, times.size)
    x = np.zeros(n)
    idx = np.clip(np.round(times * FS).astype(int), 0, n - 1)
    x[idx] = 1.0
    b, a = sp_signal.iirpeak(resonance, 15.0, FS)
    return sp_signal.lfilter(b, a, x)


def test_a_fundamental_above_half_the_rate_has_nothing_to_remove(rng):
    """A fundamental whose first harmonic lies above fs / 2 leaves the record as the others
    do (before, scipy's CZT refused a transform of no lines); a bad one is named by place."""
    x = rng.standard_normal(6000)
    alone = remove_harmonics(x, FS, (29.95,))
    assert np.array_equal(remove_harmonics(x, FS, (29.95, 0.6 * FS)), alone)
    with pytest.raises(features.FeatureError, match=r"fundamentals\[1\] = -2\.0 Hz"):
        remove_harmonics(x, FS, (29.95, -2.0))


def test_remove_harmonics_takes_out_exactly_periodic_parts_even_close_ones(rng):
    n = 24000
    t = np.arange(n) / FS
    shaft, ball_pass = 29.95, 107.36  # harmonic 43 of one is 0.5 Hz from harmonic 12 of the other
    periodic = sum(np.cos(2 * np.pi * k * shaft * t + k) / k for k in range(1, 60))
    periodic += sum(0.5 * np.sin(2 * np.pi * k * ball_pass * t + 0.3 * k) for k in range(1, 30))
    noise = 0.01 * rng.standard_normal(n)
    rest = remove_harmonics(periodic + noise, FS, (shaft, ball_pass))
    # what goes is the periodic part and the noise's own projection on the lines (2 x 230 of
    # 24000 degrees of freedom); what stays is the noise
    assert np.std(rest - noise) < 5e-3 * np.std(periodic)
    assert 0.9 * np.std(noise) < np.std(rest) < 1.2 * np.std(noise)
    # a noise-free periodic signal: the two families fitted jointly go to rounding, their
    # lines half a bin apart included (fitted in turn, four passes left 2.7e-3)
    left = remove_harmonics(periodic, FS, (shaft, ball_pass))
    assert np.std(left) < 1e-6 * np.std(periodic)
    single = sum(np.sin(2 * np.pi * k * ball_pass * t) for k in range(1, 30))
    assert np.std(remove_harmonics(single, FS, (ball_pass,))) < 1e-6 * np.std(single)
    rest = separate_discrete(periodic, FS, fundamentals=(shaft, ball_pass))
    floor = 10 ** (-features.instrument_floor.INSTRUMENT_FLOOR_DB / 20)
    assert np.std(rest) < 1.05 * floor * np.std(periodic)  # the instrument floor, nothing more


def test_kept_transforms_give_the_same_bits_for_each_records_own_family(rng, monkeypatch):
    """remove_harmonics keeps each family's transforms for the next record alike: a record's
    result is the same with them as made anew, a family of another fundamental or length gets
    its own, and what is kept stays within TRANSFORM_CACHE_BYTES."""
    sep = features.separation
    monkeypatch.setattr(sep, "_transform_cache", type(sep._transform_cache)())
    n = 6000
    t = np.arange(n) / FS
    signals = {
        f0: sum(np.cos(2 * np.pi * k * f0 * t + k) / k for k in range(1, 20))
        + 0.1 * rng.standard_normal(n)
        for f0 in (29.90, 29.92)  # the same number of harmonics below fs/2
    }
    fresh = {}
    for f0, x in signals.items():
        sep._transform_cache.clear()
        fresh[f0] = remove_harmonics(x, FS, (f0,))
    sep._transform_cache.clear()
    for _ in range(2):  # the second round from what the first kept
        for f0, x in signals.items():
            np.testing.assert_array_equal(remove_harmonics(x, FS, (f0,)), fresh[f0])
            shorter = remove_harmonics(x[:-500], FS, (f0,))
            assert shorter.size == n - 500
    assert len(sep._transform_cache) == 4
    one = next(iter(sep._transform_cache.values())).nbytes
    assert one > 16 * n  # the ramp and the two transforms' chirps
    monkeypatch.setattr(sep, "TRANSFORM_CACHE_BYTES", int(2.5 * one))
    remove_harmonics(signals[29.90], FS, (29.8,))
    assert len(sep._transform_cache) == 2
    assert sum(v.nbytes for v in sep._transform_cache.values()) <= 2.5 * one


def test_a_strong_line_beside_an_empty_family_goes_whole():
    """A simulated healthy bearing: a strong ball-pass line half a bin from a shaft harmonic.

    The shaft family holds nothing there; fitted in turn, the two families shared the line and
    four passes left 6.6 % of a 6205's RMS at 1797 rpm (its envelope then showed BPFO). The
    joint fit takes it out whole, at record lengths and rates where other pairs come close.
    """
    rng = np.random.default_rng(11)
    for fs, seconds in ((12000.0, 1.0), (25600.0, 1.0), (48000.0, 0.5), (25600.0, 2.0)):
        n = int(fs * seconds)
        t = np.arange(n) / fs
        shaft = rng.uniform(8.0, 60.0)
        ball_pass = shaft * rng.uniform(2.5, 6.0)
        k = 12
        # the shaft harmonic nearest to harmonic k of the ball pass, moved half a bin from it
        m = round(k * ball_pass / shaft)
        shaft = (k * ball_pass + 0.5 / seconds) / m
        periodic = sum(np.cos(2 * np.pi * j * ball_pass * t + j) / j for j in range(1, 20))
        periodic += 3.0 * np.cos(2 * np.pi * k * ball_pass * t)
        left = remove_harmonics(periodic, fs, (shaft, ball_pass))
        assert np.std(left) < 1e-6 * np.std(periodic), (fs, seconds, np.std(left))


def test_the_fits_gram_matrix_is_the_hann_windows_transform():
    from features.separation import _hann_gram, _hann_transform

    n = 1000
    w = np.hanning(n) / np.hanning(n).sum()
    t = np.arange(n)
    for bins in (0.0, 0.3, 1.0, 2.5, -0.7, 5.2, 19.5):
        nu = bins / n
        direct = np.sum(w * np.exp(-2j * np.pi * nu * t))
        assert abs(_hann_transform(np.array([nu]), n)[0] - direct) < 1e-12
    lines = np.array([0.2, 0.1, 0.1 + 0.5 / n, 0.1 + 30.0 / n])
    gram = _hann_gram(lines, n).toarray()
    assert np.allclose(gram, gram.conj().T)
    assert gram[1, 2] == pytest.approx(_hann_transform(np.array([-0.5 / n]), n)[0])
    assert abs(gram[1, 2]) > 0.8  # half a bin apart: the windows overlap most
    assert gram[1, 3] == 0 and gram[0, 1] == 0  # beyond COUPLED_BINS: left to the passes


def test_the_chirp_z_transform_is_its_definition_as_scipys_is(rng):
    """The families' transforms (set up from their phases, stop 90) give the sums they stand
    for, at a 1 s record's length at 25.6 kHz where the chirp's phase reaches 3e8 turns x f0 /
    fs, and agree with scipy.signal.CZT (whose complex powers cost 7 ms a set-up)."""
    from features.chirp_z import ChirpZ
    from features.separation import _HarmonicTransforms

    n, fs, f0, offset, first = 25600, 25600.0, 29.37, 11.3, 3
    count = int((0.5 * fs) // f0) - 2
    x = rng.standard_normal(n)
    step, start = f0 / fs, (offset + first * f0) / fs
    analysis = ChirpZ(n, count, -step, start)(x)
    some = np.arange(0, count, 37)  # the definition, summed directly at some of the lines
    direct = np.array(
        [np.sum(x * np.exp(-2j * np.pi * (start + j * step) * np.arange(n))) for j in some]
    )
    scale = np.abs(direct).max()
    assert np.abs(analysis[some] - direct).max() < 1e-9 * scale
    scipys = sp_signal.CZT(n, m=count, w=np.exp(-2j * np.pi * step), a=np.exp(2j * np.pi * start))
    assert np.abs(analysis - scipys(x)).max() < 1e-8 * scale
    amplitudes = rng.standard_normal(count) + 1j * rng.standard_normal(count)
    family = _HarmonicTransforms(n, f0, offset, first, count, fs)
    series = family.synthesise(amplitudes)
    t = np.arange(0, n, 613) / fs
    lines = offset + f0 * np.arange(first, first + count)
    direct = np.real(np.exp(2j * np.pi * np.outer(t, lines)) @ amplitudes)
    assert np.abs(series[np.arange(0, n, 613)] - direct).max() < 1e-9 * np.abs(direct).max()
    weights = np.hanning(n) / np.hanning(n).sum()  # the projections the fit uses
    projections = family.analyse(x, weights)
    direct = (x * weights) @ np.exp(-2j * np.pi * np.outer(np.arange(n) / fs, lines[some]))
    assert np.abs(projections[some] - direct).max() < 1e-9 * np.abs(projections).max()
    with pytest.raises(ValueError, match="set up for 25600 samples, not 100"):
        ChirpZ(n, count, -step, start)(x[:100])


def test_separation_keeps_jittered_impacts_and_drops_periodic_ones(rng):
    n, rate = 12000, FS / 112
    rates = {"bpfo": rate, "bpfi": 162.2, "two_bsf": 141.2}
    periodic = _impacts(FS / 112, n, rng)  # a whole number of samples per period
    jittered = _impacts(rate, n, rng, jitter=0.02)
    floor = 0.05 * np.std(jittered) * rng.standard_normal(n)
    for x, seen in ((jittered + floor, True), (periodic + floor, False)):
        chosen = select_band(separate_discrete(x, FS, fundamentals=(rate,)), FS, rates)
        assert (chosen.score_db >= chosen.threshold_db) is seen, chosen.score_db
        if seen:
            assert chosen.rate == "bpfo"
    # without separation the periodic train is as visible as the jittered one
    plain = select_band(periodic + floor, FS, rates)
    assert plain.score_db > plain.threshold_db + 10


def test_a_noise_free_periodic_signal_leaves_only_the_instrument_floor():
    t = np.arange(24000) / FS
    x = sum(np.cos(2 * np.pi * k * 107.4 * t) / k for k in range(1, 40))
    rest = separate_discrete(x, FS, fundamentals=(107.4,))
    floor = np.std(x) * 10 ** (-features.instrument_floor.INSTRUMENT_FLOOR_DB / 20)
    assert np.std(rest) == pytest.approx(floor, rel=0.1)
    chosen = select_band(rest, FS, {"bpfo": 107.4, "bpfi": 162.2})
    assert chosen.score_db < chosen.threshold_db


def test_the_instrument_floor_goes_only_to_a_record_without_one_and_scales_with_it(
    monkeypatch, rng
):
    """The floor is added where the record has none of its own (a noise-free periodic train)
    and not to the same train in noise 30 dB over it (its random part does not depend on the
    floor's seed); either way the random part is the record's in any unit, to rounding (until
    stop 76 the record's first samples seeded the floor, so its unit drew it), and a record
    changed in its last digits leaves a random part changed as little."""
    t = np.arange(12000) / FS
    periodic = sum(np.cos(2 * np.pi * k * 107.4 * t + k) / k for k in range(1, 40))
    noisy = periodic + 0.1 * rng.standard_normal(t.size)
    seed = features.instrument_floor.FLOOR_SEED
    for x, floored in ((periodic, True), (noisy, False)):
        rest = separate_discrete(x, FS, fundamentals=(107.4,))
        with monkeypatch.context() as m:
            m.setattr(features.instrument_floor, "FLOOR_SEED", seed + 1)
            redrawn = separate_discrete(x, FS, fundamentals=(107.4,))
        assert np.array_equal(redrawn, rest) is not floored
        floor = np.std(x) * 10 ** (-features.instrument_floor.INSTRUMENT_FLOOR_DB / 20)
        if floored:
            assert np.std(rest) == pytest.approx(floor, rel=0.1)
        stated = separate_discrete(x, FS, fundamentals=(107.4,), return_floor=True)
        np.testing.assert_array_equal(stated[0], rest)
        assert stated[1] == (pytest.approx(floor, rel=1e-12) if floored else 0.0)
        for scale in (1.0 / 9.80665, 1000.0, 1.0 + 1e-12):
            scaled = separate_discrete(scale * x, FS, fundamentals=(107.4,))
            assert np.max(np.abs(scaled / scale - rest)) <= 1e-9 * np.std(rest), scale


def test_threshold_from_rayleigh_statistics_and_false_alarms_on_noise():
    # known median, one band, five bins at 1e-4: 20 log10 of sqrt(2 ln 5e4) / 1.177, + 1 dB
    assert detection_threshold_db(1) == pytest.approx(11.934 + 1.0, abs=0.01)
    assert detection_threshold_db(36) > detection_threshold_db(6) > detection_threshold_db(1)
    with pytest.raises(features.FeatureError, match="n_bands = 0"):
        detection_threshold_db(0)
    # Gaussian noise: the chosen band's best line exceeds the threshold set for a false-alarm
    # probability p per rate at most p x rates (union bound), and not far below it
    rng = np.random.default_rng(2024)
    p, rates = 0.02, {"a": 97.3, "b": 143.9, "c": 171.1}
    hits = 0
    trials = 300
    for _ in range(trials):
        chosen = select_band(rng.standard_normal(12000), FS, rates)
        hits += chosen.score_db >= detection_threshold_db(
            len(chosen.bands), p, chosen.searched_bins, chosen.floor_bins
        )
    # binomial: 300 trials at the bound 0.06 give at most 0.06 + 3 x 0.014
    assert 0.003 < hits / trials < 3 * p + 3 * np.sqrt(3 * p / trials)


def test_candidate_bands_respect_width_and_the_analyser_span():
    bands = candidate_bands(FS, 12000, min_bandwidth=500.0)
    assert all(high - low >= 500.0 for low, high in bands)
    assert max(high for _, high in bands) == pytest.approx(FS / 2.56)
    assert len(set(bands)) == len(bands)


def test_candidate_bands_can_start_above_a_lowest_frequency():
    """``min_frequency`` raises every band's lower edge (the widest band then starts there),
    drops the bands left too narrow, keeps the rest of the tree as it was, and refuses a
    negative value naming it; 0 is the tree unchanged."""
    tree = candidate_bands(FS, 12000, min_bandwidth=500.0)
    raised = candidate_bands(FS, 12000, min_bandwidth=500.0, min_frequency=600.0)
    assert candidate_bands(FS, 12000, min_bandwidth=500.0, min_frequency=0.0) == tree
    assert raised[0] == (600.0, pytest.approx(FS / 2.56))
    assert all(low >= 600.0 and high - low >= 500.0 for low, high in raised)
    expected = {(max(lo, 600.0), hi) for lo, hi in tree if hi - max(lo, 600.0) >= 500.0}
    assert set(raised) == expected
    assert (0.0, 750.0) in tree and all(high > 1100.0 for _, high in raised)
    with pytest.raises(features.FeatureError, match=r"min_frequency = -1\.0 Hz"):
        candidate_bands(FS, 12000, min_bandwidth=500.0, min_frequency=-1.0)


def test_library_envelope_band_is_the_diagnose_band(rng):
    from cmtool.diagnose import diagnose_signal
    from generators import bearing, characteristic_frequencies

    f = characteristic_frequencies(bearing("6205"), 1797 / 60)
    x = _impacts(f.bpfi, 24000, rng, jitter=0.015) + 0.1 * rng.standard_normal(24000)
    d = diagnose_signal(x, FS, 1797.0, "6205")
    _, _, band = features.envelope_spectrum(
        x,
        FS,
        fault_frequencies={"bpfo": f.bpfo, "bpfi": f.bpfi, "two_bsf": f.two_bsf, "shaft": f.shaft},
        return_band=True,
    )
    assert d.verdict == "inner race"
    assert band == pytest.approx(d.band_hz)
    # a ball pit's bursts, whose band the cage rate chooses: the same band, with the cage
    # rate given or derived from the shaft rate, BPFO and BPFI (shaft x BPFO / (BPFO + BPFI))
    assert f.shaft * f.bpfo / (f.bpfo + f.bpfi) == pytest.approx(f.ftf, rel=1e-12)
    ball = _ball_pit_bursts(rng, 1.0, 24000)
    d = diagnose_signal(ball, FS, 1797.0, "6205")
    assert d.verdict == "ball"
    rates = {"bpfo": f.bpfo, "bpfi": f.bpfi, "two_bsf": f.two_bsf, "shaft": f.shaft}
    for given in (rates, {**rates, "ftf": f.ftf}):
        _, _, band = features.envelope_spectrum(ball, FS, fault_frequencies=given, return_band=True)
        assert band == pytest.approx(d.band_hz)


def test_line_probabilities_share_the_threshold_scale():
    # a fundamental exactly at the detection threshold has, over every band, the threshold's
    # false-alarm probability; the inverse maps it back to the threshold
    from features.separation import FALSE_ALARM, line_false_alarm, ratio_for_false_alarm

    for n_bands, searched, floor in ((36, 5, 100), (12, 3, 60), (1, 9, 40)):
        threshold = detection_threshold_db(n_bands, searched_bins=searched, floor_bins=floor)
        p = n_bands * line_false_alarm(threshold, searched, floor)
        assert p == pytest.approx(FALSE_ALARM, rel=2e-3)
        back = ratio_for_false_alarm(FALSE_ALARM, n_bands, searched, floor)
        assert back == pytest.approx(threshold, abs=0.01)
        # monotone: a higher line is less likely under noise
        ratios = np.linspace(0.0, 30.0, 61)
        probabilities = [line_false_alarm(r, searched, floor) for r in ratios]
        assert np.all(np.diff(probabilities) <= 0.0)


def test_the_exceedance_leaves_out_only_terms_that_are_exactly_zero():
    # _exceedance skips the grid points where exp(-(k x)^2 / 2) underflows; summed over the
    # whole row, it must give the bits of evaluating every term, for curve grids, odd k
    # (the cut-off's neighbours, 0, huge values), arrays in any order and scalars
    from features.false_alarm import (
        _CURVE_DB,
        _UNDERFLOW_KX,
        CALIBRATION_DB,
        _exceedance,
        _median_density,
    )

    def every_term(k, searched, floor):
        x, density = _median_density(floor)
        kk = np.atleast_1d(np.asarray(k, dtype=float))[:, None]
        with np.errstate(divide="ignore"):
            above = -np.expm1(searched * np.log1p(-np.exp(-0.5 * (kk * x) ** 2)))
        return np.sum(above * density, axis=1) * (x[1] - x[0])

    rng = np.random.default_rng(91)
    x, _ = _median_density(3)
    cut = _UNDERFLOW_KX / x[1::97]
    ks = np.concatenate(
        [
            10.0 ** ((_CURVE_DB - CALIBRATION_DB) / 20.0) * 1.1774,
            np.nextafter(cut, 0.0),
            cut,
            np.nextafter(cut, np.inf),
            [0.0, 1e-9, 1e6],
            10.0 ** rng.uniform(-3.0, 4.0, 500),
        ]
    )
    ks = ks[rng.permutation(ks.size)]
    with np.errstate(divide="ignore"):
        for searched, floor in ((1, 3), (5, 25), (13, 50), (125, 400)):
            got = _exceedance(ks, searched, floor)
            want = every_term(ks, searched, floor)
            assert np.array_equal(got.view(np.int64), want.view(np.int64)), (searched, floor)
            for k in ks[:20]:
                assert _exceedance(float(k), searched, floor) == every_term(k, searched, floor)[0]


def _family(ratios, bins=5, floor=100):
    names = ("1x", "2x", "3x", "1x-", "1x+")[: len(ratios)]
    return [(n, (r, 100.0, bins, floor)) for n, r in zip(names, ratios, strict=True)]


def test_a_family_of_moderate_lines_is_detected_where_its_fundamental_alone_is_not():
    from features.evidence import _weigh

    n_bands = 36
    threshold = detection_threshold_db(n_bands, searched_bins=5, floor_bins=100)
    below = threshold - 2.0
    # inner-race pattern: fundamental under the threshold, 2x, 3x and both shaft sidebands up
    family = _weigh(_family([below, 12.0, 11.0, 11.0, 11.0]), n_bands, 5, 100)
    assert family["detected"] and family["evidence_db"] >= threshold
    # the fundamental alone at the same height: not detected
    alone = _weigh(_family([below, 0.0, 0.0]), n_bands, 5, 100)
    assert not alone["detected"] and alone["evidence_db"] < threshold
    # one clear fundamental keeps its weight (Bonferroni over two tests: at most 0.6 dB lost)
    clear = _weigh(_family([threshold + 1.0, 0.0, 0.0]), n_bands, 5, 100)
    assert clear["detected"] and clear["evidence_db"] > threshold + 0.4
    # and the figure rises with every line of the family
    more = _weigh(_family([below, 12.0, 11.0, 11.0, 14.0]), n_bands, 5, 100)
    assert more["evidence_db"] > family["evidence_db"]


def test_weighed_evidence_keeps_its_false_alarm_rate_on_noise(rng):
    # 1 s records of Gaussian noise through the whole chain (separation, band choice, lines):
    # the fraction where any of the three faults' weighed probability is <= 0.1 stays under
    # the union bound 0.3 (measured 0.124 over 2,000 records:
    # benchmarks/calibrate_detection.py --combined-only), and is no trivial 0 either
    ctx = {"bpfo": 107.4, "bpfi": 162.2, "two_bsf": 141.2, "shaft": 29.95, "ftf": 11.9}
    smallest = [
        min(
            v["false_alarm"]
            for v in features.fault_evidence(rng.standard_normal(12000), FS, ctx).combined.values()
        )
        for _ in range(100)
    ]
    rate = float(np.mean(np.array(smallest) <= 0.1))
    assert 0.02 <= rate <= 0.3


# 6205 at 1797 rpm [Hz]
BPFO, BPFI, TWO_BSF, FTF, SHAFT = 107.36, 162.19, 141.17, 11.93, 29.95


def test_select_band_scores_a_rate_only_from_its_floor(rng):
    """Two low tones FTF apart beat at FTF in every band from 0 Hz that holds both (that is
    not envelope analysis); a 3 kHz ring modulated at FTF is. With the cage rate's floor at 3
    x the fastest fault rate the selection demodulates the ring; without it, the beat."""
    t = np.arange(12000) / FS
    beat = np.cos(2 * np.pi * 150.0 * t) + np.cos(2 * np.pi * (150.0 + FTF) * t)
    ring = (1.0 + 0.5 * np.cos(2 * np.pi * FTF * t)) * np.cos(2 * np.pi * 3000.0 * t)
    x = beat + 0.05 * ring + 0.01 * rng.standard_normal(t.size)
    rates = {"bpfo": BPFO, "bpfi": BPFI, "two_bsf": TWO_BSF, "ftf": FTF}
    floor = 3.0 * BPFI
    free = select_band(x, FS, rates)
    assert free.rate == "ftf" and free.band[0] < floor
    floored = select_band(x, FS, rates, floors={"ftf": floor})
    assert floored.rate == "ftf" and floored.band[0] <= 3000.0 <= floored.band[1]
    assert floored.band[0] >= floor
    low = np.array([lo for lo, _ in floored.bands]) < floor
    assert np.all(np.isneginf(floored.scores_db[low, 3]))
    assert np.all(np.isfinite(floored.scores_db[:, :3]))
    assert np.array_equal(floored.scores_db[~low], free.scores_db[~low])
    # the command's choice (features.band_selection.fault_band): the cage rate from 3 x the
    # fastest rate and, since B15, every band from there too; on the whole tree it is the
    # floored selection above
    faults = {k: rates[k] for k in rates if k != "ftf"}
    whole = features.band_selection.fault_band(x, FS, faults, FTF, min_frequency=0.0)
    assert whole.band == floored.band and whole.rates[-1] == "ftf"
    chosen = features.band_selection.fault_band(x, FS, faults, FTF)
    assert all(lo >= floor for lo, _ in chosen.bands) and len(chosen.bands) < len(free.bands)
    assert chosen.rate == "ftf" and chosen.band[0] <= 3000.0 <= chosen.band[1]
    with pytest.raises(features.FeatureError, match="floors names 'cage'"):
        select_band(x, FS, rates, floors={"cage": floor})
    with pytest.raises(features.FeatureError, match="leave no band"):
        select_band(x, FS, {"ftf": FTF}, floors={"ftf": FS})


def _ball_pit_bursts(rng, noise: float, n: int = 12000) -> np.ndarray:
    """A ball pit's impacts, 2 x BSF apart with 1.5 % jitter, struck only while its ball
    crosses the load zone (a third of each cage turn, strongest in its middle), each ringing
    at 3.2 kHz; white noise ``noise`` x the impacts' RMS."""
    t = np.arange(200) / FS
    ring = np.exp(-800.0 * t) * np.sin(2 * np.pi * 3200.0 * t)
    x = np.zeros(n)
    time = 0.0
    while time < n / FS:
        time += (1.0 + 0.015 * rng.standard_normal()) / TWO_BSF
        phase = (time * FTF) % 1.0
        i = int(time * FS)
        if phase < 1.0 / 3.0 and i + ring.size < n:
            x[i : i + ring.size] += ring * np.sin(3.0 * np.pi * phase)
    return x + noise * np.std(x) * rng.standard_normal(n)


def test_the_cage_rate_finds_a_ball_pits_bursts(monkeypatch):
    """A ball pit strikes in bursts once per cage turn (Randall and Antoni 2011): its cage line
    stands where its slip-smeared 2 x BSF family is weak. In noise 4.5 x the impacts' RMS,
    twelve records: the ball is detected in 9 or more of them with the cage rate choosing the
    band and weighed in the ball's family (11 when written), in 6 or fewer without (3); pure
    noise gives no ball either way."""
    from features import fault_evidence

    rates = {"bpfo": BPFO, "bpfi": BPFI, "two_bsf": TWO_BSF, "ftf": FTF, "shaft": SHAFT}
    records = [_ball_pit_bursts(np.random.default_rng(seed), 4.5) for seed in range(12)]
    noise = [np.random.default_rng(100 + seed).standard_normal(12000) for seed in range(12)]

    def balls(signals) -> int:
        return sum(fault_evidence(x, FS, rates).combined["two_bsf"]["detected"] for x in signals)

    assert balls(records) >= 9
    assert balls(noise) == 0
    shipped = features.band_selection.fault_band
    monkeypatch.setattr(
        features.evidence, "fault_band", lambda x, fs, r, cage=None, **o: shipped(x, fs, r, **o)
    )
    monkeypatch.setattr(features.evidence, "CAGE_HARMONICS", ())
    assert balls(records) <= 6
    assert balls(noise) == 0


def test_every_bands_line_ratio_at_once_is_each_bands_own_to_the_bit(rng):
    """select_band measures a rate's line in all its bands' envelope spectra in one pass
    (stop 63): the same ratios, bins searched and floor bins, to the bit, as measuring each
    band alone, in bands long enough to hold the line's floor and in bands too short for it
    (a short record's narrowest bands), for rates from 2 Hz to near a band's top."""
    from features.band_selection import _band_envelope_spectrum, _ratio_db, _ratio_db_bands

    for n, fs in ((12000, FS), (2400, FS), (48000, 48000.0)):
        x = _impacts(BPFI, n, rng, jitter=0.01) + 0.3 * rng.standard_normal(n)
        spec = np.fft.fft((x - x.mean()) * sp_signal.windows.tukey(n, 0.05))
        bands = candidate_bands(fs, n, min_bandwidth=3 * BPFI)
        spectra = [_band_envelope_spectrum(spec, fs / n, low, high) for low, high in bands]
        sizes = {freqs.size for freqs, _ in spectra}
        assert len(sizes) > 2  # bands of several widths
        for line in (2.0, FTF, BPFO, BPFI, TWO_BSF, 900.0, 0.45 * min(h - lo for lo, h in bands)):
            alone = [_ratio_db(freqs, amp, line) for freqs, amp in spectra]
            assert _ratio_db_bands(spectra, fs / n, line) == alone, (n, line)
