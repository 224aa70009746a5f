"""The feature table and its scikit-learn transformer."""

import pickle

import numpy as np
import pandas as pd
import pytest
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import StandardScaler
from sklearn.utils.estimator_checks import parametrize_with_checks

import features as F

CTX = {"shaft": 29.95, "ftf": 11.93, "bpfo": 107.36, "bpfi": 162.19, "two_bsf": 141.17}
FS = 12800.0


def impulses(rng, rate, n=12800, fs=FS, snr=1.0):
    t = np.arange(n) / fs
    x = np.zeros(n)
    x[(np.arange(0, n / fs, 1 / rate) * fs).astype(int)] = 1.0
    ring = np.exp(-t[:128] * 2000) * np.sin(2 * np.pi * 3500 * t[:128])
    x = np.convolve(x, ring)[:n]
    return x / x.std() + rng.standard_normal(n) / snr


def test_feature_names_units_and_order(rng):
    feats = F.extract_features(impulses(rng, CTX["bpfo"]), FS, fault_frequencies=CTX)
    assert list(feats) == F.feature_names()
    units = F.feature_units()
    assert units["rms"] == "U" and units["envelope_bpfo_h1_snr"] == "dB"
    assert all(np.isfinite(v) for v in feats.values())


@pytest.mark.parametrize("fault", ["bpfo", "bpfi", "two_bsf"])
def test_envelope_snr_points_at_the_impulse_rate(rng, fault):
    feats = F.extract_features(impulses(rng, CTX[fault]), FS, fault_frequencies=CTX)
    snr = {f: feats[f"envelope_{f}_h1_snr"] for f in ("bpfo", "bpfi", "two_bsf")}
    assert max(snr, key=snr.get) == fault
    assert snr[fault] > 10.0


def test_precomputed_spectra_are_used(rng):
    x = impulses(rng, CTX["bpfi"])
    spectra = F.compute_spectra(x, FS, band=(2500.0, 4500.0))
    a = F.extract_features(x, FS, fault_frequencies=CTX, spectra=spectra)
    b = F.extract_features(x, FS, fault_frequencies=CTX, band=(2500.0, 4500.0))
    assert a == b
    assert a["kurtogram_center_rel"] == pytest.approx(7000.0 / FS)


def test_missing_context_is_named(rng):
    with pytest.raises(F.FeatureError, match="no 'bpfi'"):
        F.extract_features(impulses(rng, 100.0), FS, fault_frequencies={"bpfo": 107.0})


def test_transformer_on_dataframe_and_array(rng):
    signals = [impulses(rng, CTX[f]) for f in ("bpfo", "bpfi", "two_bsf")]
    frame = pd.DataFrame(
        {
            "signal": signals,
            "fs_hz": FS,
            "shaft_frequency_hz": CTX["shaft"],
            "ftf_hz": CTX["ftf"],
            "bpfo_hz": CTX["bpfo"],
            "bpfi_hz": CTX["bpfi"],
            "two_bsf_hz": CTX["two_bsf"],
        }
    )
    ext = F.FeatureExtractor().fit(frame)
    table = ext.transform(frame)
    assert table.shape == (3, len(F.feature_names()))
    arr = F.FeatureExtractor(fs=FS, fault_frequencies=CTX).fit(np.stack(signals))
    np.testing.assert_allclose(arr.transform(np.stack(signals)), table)
    assert list(ext.get_feature_names_out()) == F.feature_names()
    # inside a pipeline, and picklable
    pipe = make_pipeline(F.FeatureExtractor(fs=FS, fault_frequencies=CTX), StandardScaler())
    out = pipe.fit_transform(np.stack(signals))
    again = pickle.loads(pickle.dumps(pipe)).transform(np.stack(signals))
    np.testing.assert_allclose(out, again)
    with pytest.raises(F.FeatureError, match="context columns"):
        ext.transform(frame.drop(columns=["bpfi_hz"]))


def test_feature_sets_select_columns_and_scale_free_is_gain_invariant(rng):
    signals = np.stack([impulses(rng, CTX[f]) for f in ("bpfo", "bpfi", "two_bsf")])
    full = F.FeatureExtractor(fs=FS, fault_frequencies=CTX).fit(signals)
    names = list(full.get_feature_names_out())
    table = full.transform(signals)
    units = F.feature_units()
    for feature_set in ("scale-free", "envelope"):
        ext = F.FeatureExtractor(fs=FS, fault_frequencies=CTX, feature_set=feature_set)
        sub = list(ext.fit(signals).get_feature_names_out())
        assert sub and set(sub) < set(names) and all(units[n] != "U" for n in sub)
        picked = table[:, [names.index(n) for n in sub]]
        np.testing.assert_allclose(ext.transform(signals), picked)
        # a sensor gain (here 9.81: g -> m/s^2) changes nothing in these sets
        np.testing.assert_allclose(ext.transform(9.81 * signals), picked, rtol=1e-6, atol=1e-9)
    envelope = F.FeatureExtractor(fs=FS, fault_frequencies=CTX, feature_set="envelope")
    assert all(n.startswith("envelope_") for n in envelope.fit(signals).get_feature_names_out())
    with pytest.raises(F.FeatureError, match="feature_set = 'raw'"):
        F.FeatureExtractor(fs=FS, fault_frequencies=CTX, feature_set="raw").fit(signals)


# scikit-learn's common checks feed 2-10 "features" per row: as signals they are too short for
# any spectral feature (a kurtogram needs 64 samples), so the checks that call transform on
# such data cannot apply; the same properties (pickling, pipelines, order and subset
# invariance, idempotence) are tested on real signal lengths above and below.
_TOO_SHORT = "signals of 2-10 samples are too short for spectral features"
EXPECTED_FAILED = {
    name: _TOO_SHORT
    for name in (
        "check_fit_score_takes_y",
        "check_n_features_in_after_fitting",
        "check_estimators_dtypes",
        "check_dtype_object",
        "check_pipeline_consistency",
        "check_estimators_pickle",
        "check_f_contiguous_array_estimator",
        "check_transformer_data_not_an_array",
        "check_transformer_general",
        "check_transformer_preserve_dtypes",
        "check_methods_sample_order_invariance",
        "check_methods_subset_invariance",
        "check_dict_unchanged",
        "check_fit_idempotent",
    )
}


@parametrize_with_checks(
    [
        F.FeatureExtractor(
            fs=1000.0,
            fault_frequencies={
                "shaft": 10.0,
                "ftf": 4.0,
                "bpfo": 36.0,
                "bpfi": 54.0,
                "two_bsf": 47.0,
            },
        )
    ],
    expected_failed_checks=lambda est: EXPECTED_FAILED,
)
def test_sklearn_compatible(estimator, check):
    check(estimator)


def test_order_and_subset_invariance_on_real_lengths(rng):
    signals = np.stack([impulses(rng, CTX[f]) for f in ("bpfo", "bpfi", "two_bsf", "bpfo")])
    ext = F.FeatureExtractor(fs=FS, fault_frequencies=CTX).fit(signals)
    full = ext.transform(signals)
    np.testing.assert_allclose(ext.transform(signals[::-1]), full[::-1])
    np.testing.assert_allclose(ext.transform(signals[1:3]), full[1:3])
    np.testing.assert_allclose(ext.fit(signals).transform(signals), full)


def test_parallel_transform_equals_serial(rng):
    signals = np.stack([impulses(rng, CTX[f]) for f in ("bpfo", "bpfi", "two_bsf", "bpfo")])
    serial = F.FeatureExtractor(fs=FS, fault_frequencies=CTX).fit(signals).transform(signals)
    parallel = F.FeatureExtractor(fs=FS, fault_frequencies=CTX, n_jobs=2).fit(signals)
    np.testing.assert_array_equal(parallel.transform(signals), serial)


def test_kurtogram_band_stays_below_nyquist(rng):
    # white noise often selects the top band; its edge must not round above fs/2
    for seed in range(5):
        kg = F.kurtogram(np.random.default_rng(seed).standard_normal(25600), 25600.0)
        low, high = kg.band
        assert 0.0 <= low < high <= 12800.0


def test_shaft_frequency_feature_comes_from_the_context(rng):
    signals = np.stack([impulses(rng, CTX["bpfo"]) for _ in range(2)])
    ext = F.FeatureExtractor(fs=FS, fault_frequencies=CTX).fit(signals)
    names = list(ext.get_feature_names_out())
    assert F.feature_units()["shaft_frequency"] == "Hz"
    np.testing.assert_array_equal(ext.transform(signals)[:, names.index("shaft_frequency")], 29.95)
    no_shaft = {k: v for k, v in CTX.items() if k != "shaft"}
    with pytest.raises(F.FeatureError, match="'shaft'"):
        F.FeatureExtractor(fs=FS, fault_frequencies=no_shaft).fit(signals).transform(signals)
    # the envelope set does not use it, so it needs no shaft frequency
    F.FeatureExtractor(fs=FS, fault_frequencies=no_shaft, feature_set="envelope").fit(
        signals
    ).transform(signals)
