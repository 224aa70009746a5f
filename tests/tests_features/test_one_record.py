"""Functions that take one record refuse a stack of them by name, before any work.

Found by fuzzing the public functions with a two-row array (stop 87): nine of them stopped
with numpy's own broadcasting error, which names neither the parameter nor the function, and
``separate_discrete`` at fs = 1 Hz tried to allocate 215 GiB for its running median.
"""

import numpy as np
import pytest

import features as F

RATES = {"bpfo": 107.4, "bpfi": 162.2, "two_bsf": 141.2, "shaft": 29.95, "ftf": 11.9}

#: function name -> a call of it on (x, fs)
ONE_RECORD = {
    "separate_discrete": lambda x, fs: F.separate_discrete(x, fs, fundamentals=(29.95,)),
    "envelope_spectrum": lambda x, fs: F.envelope_spectrum(x, fs, fault_frequencies=RATES),
    "fault_evidence": lambda x, fs: F.fault_evidence(x, fs, RATES),
    "shaft_rate_from_spectrum": lambda x, fs: F.shaft_rate_from_spectrum(x, fs, 29.95),
    "velocity_band_rms": lambda x, fs: F.velocity_band_rms(x, fs),
    "band_rms": lambda x, fs: F.band_rms(x, fs, (10.0, 100.0)),
    "ar_prediction_error": lambda x, fs: F.ar_prediction_error(x, 10),
    "acceleration_from_velocity": lambda x, fs: F.acceleration_from_velocity(x, fs),
    "select_band": lambda x, fs: F.select_band(x, fs, {"bpfo": 107.4}),
    "envelope_scores": lambda x, fs: F.envelope_scores(x, fs, RATES),
    "time_scores": lambda x, fs: F.time_scores(x),
    "kurtogram": lambda x, fs: F.kurtogram(x, fs),
    "extract_features": lambda x, fs: F.extract_features(x, fs, fault_frequencies=RATES),
}


@pytest.mark.parametrize("fs", [12000.0, 1.0])
@pytest.mark.parametrize("name", sorted(ONE_RECORD))
def test_a_stack_of_records_is_refused_by_name(name, fs):
    x = np.random.default_rng(0).standard_normal(12000)
    with pytest.raises(F.FeatureError, match=rf"has shape \(2, 12000\); {name} takes a 1-D"):
        ONE_RECORD[name](np.stack([x, x]), fs)


def test_the_functions_that_take_an_axis_still_take_a_stack():
    x = np.random.default_rng(0).standard_normal((2, 4096))
    f, a = F.amplitude_spectrum(x, 12000.0)
    assert a.shape == (2, f.size)
    assert F.prewhiten(x).shape == x.shape
