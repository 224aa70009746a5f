"""Inputs the library's public functions refuse by name (found by fuzzing them in stop 91).

Before: a complex record lost its imaginary part with numpy's ComplexWarning only; a record of
1e300 gave NaN features with overflow warnings; a list of fault rates stopped with
``AttributeError: 'list' object has no attribute 'items'``; a rate above fs/2 was scored in a
spectrum that cannot hold it; a non-numeric rate gave ``could not convert string to float``;
``shaft_rate_from_spectrum`` on a record too short for its search gave ``attempt to get argmax
of an empty sequence``; ``discrete_over_random_db`` took ``band=None`` to a TypeError and a
band above fs/2 without a word.
"""

import numpy as np
import pytest

import features as F
from features._validate import MAX_ABS_SAMPLE

FS = 12000.0
RATES = {"bpfo": 107.4, "bpfi": 162.2, "two_bsf": 141.2, "shaft": 29.95, "ftf": 11.9}

#: function name -> a call of it on a record x
ON_A_RECORD = {
    "envelope_spectrum": lambda x: F.envelope_spectrum(x, FS, fault_frequencies=RATES),
    "fault_evidence": lambda x: F.fault_evidence(x, FS, RATES),
    "envelope_scores": lambda x: F.envelope_scores(x, FS, RATES),
    "time_scores": lambda x: F.time_scores(x),
    "time_statistics": lambda x: F.time_statistics(x),
    "amplitude_spectrum": lambda x: F.amplitude_spectrum(x, FS),
    "kurtogram": lambda x: F.kurtogram(x, FS),
    "spectral_kurtosis_score": lambda x: F.spectral_kurtosis_score(x, FS),
    "velocity_band_rms": lambda x: F.velocity_band_rms(x, FS),
    "extract_features": lambda x: F.extract_features(x, FS, fault_frequencies=RATES),
}


@pytest.fixture(scope="module")
def record():
    return np.random.default_rng(91).standard_normal(12000)


@pytest.mark.parametrize("name", sorted(ON_A_RECORD))
def test_a_complex_record_is_refused_not_cut_to_its_real_part(name, record):
    with pytest.raises(F.FeatureError, match=r"is complex \(dtype complex128\)"):
        ON_A_RECORD[name](record + 1j * record)


@pytest.mark.parametrize("name", sorted(ON_A_RECORD))
def test_a_record_whose_fourth_powers_overflow_is_refused(name, record):
    with pytest.raises(F.FeatureError, match=r"magnitude 4\.01e\+300, outside the allowed"):
        ON_A_RECORD[name](record * 1e300)


def test_the_largest_record_allowed_gives_the_features_of_its_unit_record(record):
    # scale-free statistics are the same at the bound as at unit scale: nothing overflows
    scale = MAX_ABS_SAMPLE / np.max(np.abs(record))
    big, unit = F.time_scores(record * scale), F.time_scores(record)
    for key in ("kurtosis", "crest_factor"):
        assert big[key] == pytest.approx(unit[key], rel=1e-9), key
    stats = F.time_statistics(record * scale)
    assert all(np.isfinite(v) for v in stats.values())
    assert np.isfinite(F.spectral_kurtosis_score(record * scale, FS))


@pytest.mark.parametrize(
    "call",
    [
        lambda x, r: F.envelope_spectrum(x, FS, fault_frequencies=r),
        lambda x, r: F.envelope_scores(x, FS, r),
        lambda x, r: F.cpw_envelope_scores(x, FS, r),
        lambda x, r: F.select_band(x, FS, r),
        lambda x, r: F.extract_features(x, FS, fault_frequencies=r),
        lambda x, r: F.fault_bands(r),
    ],
    ids=["envelope_spectrum", "envelope_scores", "cpw", "select_band", "extract", "fault_bands"],
)
def test_fault_rates_that_are_no_mapping_are_refused_by_name(call, record):
    with pytest.raises(F.FeatureError, match=r"= \[107\.4\] is not a mapping of names to rates"):
        call(record, [107.4])


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda x, r: F.envelope_spectrum(x, FS, fault_frequencies=r), "fault_frequencies"),
        (lambda x, r: F.envelope_scores(x, FS, r), "fault_frequencies"),
        (lambda x, r: F.cpw_envelope_scores(x, FS, r), "fault_frequencies"),
        (lambda x, r: F.select_band(x, FS, r), "rates"),
    ],
    ids=["envelope_spectrum", "envelope_scores", "cpw", "select_band"],
)
def test_a_rate_at_or_above_half_the_sample_rate_is_refused(call, name, record):
    with pytest.raises(F.FeatureError, match=rf"{name}\['bpfo'\] = 6000 Hz is outside the allowed"):
        call(record, {"bpfo": FS / 2})
    call(record, {"bpfo": 107.4})  # a rate the record holds is read


def test_a_rate_that_is_no_number_is_named(record):
    with pytest.raises(F.FeatureError, match=r"fault_frequencies\['bpfo'\] = 'x' is not a number"):
        F.envelope_scores(record, FS, {"bpfo": "x"})


def test_the_1x_line_search_refuses_a_record_too_short_to_hold_it(record):
    with pytest.raises(F.FeatureError, match=r"x lasts 1\.2e-05 s .* at least 0\.0626 s"):
        F.shaft_rate_from_spectrum(record, 1e9, 29.95)
    # just over the length the message asks for, the search runs (no line: white noise)
    n = int(np.ceil(0.0626 * FS)) + 1
    assert not F.shaft_rate_from_spectrum(record[:n], FS, 29.95).found


def test_the_discrete_share_needs_a_band_inside_the_record(record):
    with pytest.raises(F.FeatureError, match=r"band = None is not a \(low, high\) pair"):
        F.discrete_over_random_db(record, FS, None)
    with pytest.raises(F.FeatureError, match=r"fs/2 = 6000 Hz"):
        F.discrete_over_random_db(record, FS, (5000.0, 9000.0))
    assert F.discrete_over_random_db(record, FS, (1000.0, 3000.0)) < 0.0  # noise: random


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda x: F.detection_threshold_db(float("nan")), r"n_bands = nan is not a whole number"),
        (
            lambda x: F.detection_threshold_db(10, searched_bins=float("inf")),
            r"searched_bins = inf",
        ),
        (lambda x: F.detection_threshold_db(10, floor_bins=float("nan")), r"floor_bins = nan"),
        (lambda x: F.amplitude_spectrum(x, FS, nperseg=float("nan")), r"nperseg = nan is not a"),
        (lambda x: F.power_spectral_density(x, FS, nperseg=float("inf")), r"nperseg = inf is not"),
        (lambda x: F.fault_bands(RATES, n_harmonics=float("nan")), r"n_harmonics = nan"),
        (
            lambda x: F.fault_bands(RATES, n_sidebands=-1),
            r"n_sidebands = -1 is outside the allowed",
        ),
        (
            lambda x: F.fault_bands(RATES, sidebands={"bpfi": float("nan")}),
            r"sidebands\['bpfi'\] = nan",
        ),
        (lambda x: F.feature_names(n_harmonics=0), r"n_harmonics = 0 is outside the allowed"),
        (lambda x: F.separate_discrete(x, FS, line_db=1e9), r"line_db = 1000000000\.0 dB is out"),
        (lambda x: F.separate_discrete(x, FS, window_hz=1e9), r"window_hz = 1000000000\.0 Hz"),
        (lambda x: F.held_offsets(x, FS, 107.4, (float("nan"),)), r"offsets\[0\] = nan"),
    ],
    ids=[
        "n_bands",
        "searched_bins",
        "floor_bins",
        "nperseg",
        "psd_nperseg",
        "n_harmonics",
        "n_sidebands",
        "sideband_spacing",
        "feature_names",
        "line_db",
        "window_hz",
        "lattice_offset",
    ],
)
def test_counts_and_settings_out_of_range_are_refused_by_name(call, message, record):
    # before: NaN thresholds without a word, "cannot convert float NaN to integer", bands
    # dropped for a negative sideband count, NaN band centres, an OverflowError and a
    # MemoryError (a running median 1e9 Hz wide)
    with pytest.raises(F.FeatureError, match=message):
        call(record)


def test_whole_numbers_given_as_floats_are_still_taken(record):
    assert F.detection_threshold_db(10.0, searched_bins=5.0, floor_bins=100.0) == pytest.approx(
        F.detection_threshold_db(10, searched_bins=5, floor_bins=100)
    )
    assert F.amplitude_spectrum(record, FS, nperseg=1024.0)[0].size == 513
    assert len(F.fault_bands(RATES, n_harmonics=2.0)) == 2 * len(RATES)
