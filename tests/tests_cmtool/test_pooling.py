"""The segments of a long record vote (cmtool.pooling.segment_probabilities, stop 54): a
local fault that shows in more segments than the model's own false-alarm rate explains makes
the record faulty, where the mean over every segment read it healthy (docs/realism.md 6,
"Long records")."""

from types import SimpleNamespace

import numpy as np
import pytest

from cmtool.pooling import (
    SEGMENT_FALSE_ALARM,
    combine_verdicts,
    healthy_false_alarm,
    model_verdict,
    pool_probabilities,
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


RULE_OUTER = {"healthy": 0.02, "inner race": 0.02, "outer race": 0.9, "ball": 0.06}
MODEL_BALL = {"ball": 0.97, "healthy": 0.01, "inner": 0.01, "outer": 0.01}


def test_the_pool_weighs_each_source_by_the_signal_it_rests_on():
    """On a record the model reads whole both count alike, sqrt(p_rule p_model); on one it
    reads as n segments the rule, which reads all of it, weighs n / (n + 1) (stop 55)."""
    one = pool_probabilities(RULE_OUTER, MODEL_BALL)
    alike = {k: np.sqrt(RULE_OUTER[k] * MODEL_BALL[k.split()[0]]) for k in RULE_OUTER}
    total = sum(alike.values())
    assert one == {k: v / total for k, v in alike.items()}  # exactly as before stop 55
    rng = np.random.default_rng(55)  # to the last bit, so that 1 s verdicts and the
    for rule_p, model_p in rng.dirichlet(np.ones(4), size=(50, 2)):  # calibration stay
        rule = dict(zip(RULE_OUTER, rule_p, strict=True))
        model = dict(zip(MODEL_BALL, model_p, strict=True))
        alike = {k: np.sqrt(rule[k] * model[k.split()[0]]) for k in rule}
        total = sum(alike.values())
        assert pool_probabilities(rule, model) == {k: v / total for k, v in alike.items()}
    assert max(one, key=one.get) == "ball"  # a confident model outvotes the rule on 1 s
    ten = pool_probabilities(RULE_OUTER, MODEL_BALL, segments=10)
    weighted = {k: RULE_OUTER[k] ** (10 / 11) * MODEL_BALL[k.split()[0]] ** (1 / 11) for k in one}
    total = sum(weighted.values())
    assert ten == pytest.approx({k: v / total for k, v in weighted.items()}, rel=1e-12)
    assert max(ten, key=ten.get) == "outer race"  # on 10 s the rule's evidence leads
    with pytest.raises(ValueError, match="segments must be at least 1, got 0"):
        pool_probabilities(RULE_OUTER, MODEL_BALL, segments=0)


def test_the_pooled_verdict_takes_the_models_segment_count():
    candidates = [{"fault": k, "confidence": v} for k, v in (("outer race", 0.9), ("ball", 0.1))]
    verdicts = {}
    for segments in (1, 10):
        diagnosis = SimpleNamespace(
            candidates=candidates,
            rule_verdict={"label": "outer race", "confidence": 0.9},
            model_verdict={"label": "ball", "probabilities": MODEL_BALL, "segments": segments},
        )
        combine_verdicts(diagnosis)
        verdicts[segments] = (diagnosis.verdict, diagnosis.basis)
    assert verdicts[1][0] == "ball" and verdicts[10][0] == "outer race"
    assert "10 segments" in verdicts[10][1] and "segments" not in verdicts[1][1]


def test_a_fault_the_model_cannot_weigh_is_named_only_where_the_rule_detects_it():
    """A model that learnt waviness only has no class for a local fault: each fault gets its
    probability of healthy, so the pool follows the rule's probabilities, and an outer-race
    candidate just under the threshold (confidence 0.55, not detected: a wavy ball of the
    small recipe's seed-2031 draw) leads it. The verdict stays the rule's own, healthy with its
    confidence, as the basis says; until stop 75 the pooled verdict named the outer race with
    the confidence of the rule's healthy verdict, 0.32. A fault the rule detects keeps its
    name and confidence (stop 52)."""
    candidates = [
        {"fault": fault, "confidence": value}
        for fault, value in (("outer race", 0.554), ("inner race", 0.227), ("ball", 0.118))
    ]
    wavy_model = {
        "label": "ball",
        "probabilities": {"ball": 0.99, "healthy": 0.01},
        "class_kinds": {"ball": "waviness", "healthy": "none"},
    }
    said = {
        "healthy": "the pool leans to outer race, which the model learnt no class for and the "
        "rule does not name: the verdict and confidence are the rule's",
        "outer race": "the model learnt no outer race: the verdict and confidence are the rule's",
    }
    for rule_label, confidence, detected in (("healthy", 0.3226, False), ("outer race", 0.7, True)):
        diagnosis = SimpleNamespace(
            candidates=[dict(c, detected=detected and i == 0) for i, c in enumerate(candidates)],
            rule_verdict={"label": rule_label, "confidence": confidence},
            model_verdict=wavy_model,
        )
        combine_verdicts(diagnosis)
        assert max(diagnosis.probabilities, key=diagnosis.probabilities.get) == "outer race"
        assert (diagnosis.verdict, diagnosis.confidence) == (rule_label, confidence)
        assert said[rule_label] in diagnosis.basis
