"""The segments of a long record vote (cmtool.pooling.segment_probabilities, stop 54): a
local fault that shows in more segments than the model's own false-alarm rate explains makes
the record faulty, where the mean over every segment read it healthy (docs/realism.md 6,
"Long records")."""

import numpy as np
import pytest

from cmtool.pooling import (
    SEGMENT_FALSE_ALARM,
    healthy_false_alarm,
    model_verdict,
    segment_probabilities,
)

CLASSES = ["ball", "healthy", "inner", "outer"]
LOCAL = {"ball": "localized", "healthy": "none", "inner": "localized", "outer": "localized"}
BALL = [0.7, 0.3, 0.0, 0.0]
HEALTHY = [0.1, 0.9, 0.0, 0.0]


def _segments(faulty: int, total: int = 10) -> np.ndarray:
    return np.array([BALL] * faulty + [HEALTHY] * (total - faulty))


def test_segments_vote_when_more_read_a_fault_than_the_false_alarm_rate_explains():
    # 10 segments, a model that calls 1 % of healthy signals a fault: P(3 or more) = 1.1e-4
    proba, k, voted = segment_probabilities(_segments(3), CLASSES, LOCAL, 0.01)
    assert (k, voted) == (3, True) and CLASSES[int(np.argmax(proba))] == "ball"
    assert proba == pytest.approx(np.array(BALL))
    # the mean over all ten reads healthy (0.28 against 0.72): what the vote is for
    assert CLASSES[int(np.argmax(_segments(3).mean(axis=0)))] == "healthy"
    # two of ten are what a 1 % false-alarm rate makes 4e-3 of the time: not enough
    proba, k, voted = segment_probabilities(_segments(2), CLASSES, LOCAL, 0.01)
    assert (k, voted) == (2, False) and CLASSES[int(np.argmax(proba))] == "healthy"
    assert 0.01 > SEGMENT_FALSE_ALARM  # the threshold is a record's, not a segment's


def test_no_vote_without_a_rate_for_one_segment_or_for_waviness_classes():
    for args in (
        (_segments(3), CLASSES, LOCAL, None),  # a bundle without out-of-fold predictions
        (_segments(1, total=1), CLASSES, LOCAL, 0.01),  # one segment
        (_segments(3), CLASSES, dict.fromkeys(CLASSES, "waviness"), 0.01),  # no local fault
    ):
        proba, _, voted = segment_probabilities(*args)
        assert not voted and proba == pytest.approx(args[0].mean(axis=0))


def test_a_models_false_alarm_rate_is_its_out_of_fold_healthy_errors_at_least_one_in_n():
    bundle = {
        "cv_labels": ["healthy"] * 50 + ["ball"] * 5,
        "cv_predictions": ["healthy"] * 48 + ["outer", "ball"] + ["ball"] * 5,
        "class_kinds": LOCAL,
    }
    assert healthy_false_alarm(bundle) == pytest.approx(2 / 50)
    bundle["cv_predictions"] = ["healthy"] * 50 + ["healthy"] * 5
    assert healthy_false_alarm(bundle) == pytest.approx(1 / 50)  # none wrong: not zero
    assert healthy_false_alarm({"pipeline": None}) is None


class _BurstReader:
    """A stand-in pipeline: a segment with a burst (RMS over 2) reads "ball"."""

    classes_ = np.array(CLASSES)

    def predict_proba(self, frame):
        return np.array([BALL if np.std(x) > 2 else HEALTHY for x in frame["signal"]])


@pytest.mark.parametrize(("bursts", "label"), [(3, "ball"), (2, "healthy")])
def test_model_verdict_reads_a_fault_in_three_of_ten_segments(bursts, label):
    from generators import bearing, characteristic_frequencies

    fs = 1000.0
    x = np.random.default_rng(0).normal(0.0, 1.0, 10_000)
    for second in range(bursts):
        x[second * 3000 : second * 3000 + 1000] *= 5.0
    model = {
        "pipeline": _BurstReader(),
        "signal_duration_s": 1.0,
        "class_kinds": LOCAL,
        "cv_labels": ["healthy"] * 100,
        "cv_predictions": ["healthy"] * 100,
    }
    freqs = characteristic_frequencies(bearing("6205"), 30.0)
    out = model_verdict(model, x, fs, freqs, {})
    assert out["label"] == label and out["segments"] == 10
    assert out["segments_read_as_fault"] == bursts
    assert ("read as a local fault" in out["segments_combined"]) == (label == "ball")
    from cmtool.report import model_verdict_text

    text = model_verdict_text(out)
    if label == "ball":
        assert "the 3 of 10 segments read as a local fault" in text and "0.01" in text
    else:
        assert text.endswith("10 segments of the record averaged")
