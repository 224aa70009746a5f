"""One verdict from the rule evidence and a trained model (``cmtool diagnose --model``).

The rule's candidates as probabilities over healthy and the three faults, a model's class
probabilities read as verdicts (a class learnt from waviness stands for ``healthy``), their
log-linear pooling and its calibration (fitted by ``cmtool train``), and what a model says
of a record outside what it was trained on (docs/diagnosis.md, "The pooled verdict's
confidence, calibrated by ``cmtool train``" and "A record outside what the model saw").
Moved out of :mod:`cmtool.diagnose` unchanged in stop 54; ``cmtool.diagnose`` still exports
every public name.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from generators.kinematics import BearingFrequencies

from .diagnosis import Diagnosis

__all__ = [
    "CANONICAL",
    "SEGMENT_FALSE_ALARM",
    "healthy_false_alarm",
    "segment_probabilities",
    "calibrated_confidence",
    "combine_verdicts",
    "model_label_verdict",
    "model_verdict",
    "outside_training",
    "pool_probabilities",
    "rule_probabilities",
    "verdict_probabilities",
]


#: Verdict names of labels (recipe labels, manifest fault locations, verdicts).
CANONICAL = {
    "healthy": "healthy",
    "normal": "healthy",
    "inner": "inner race",
    "inner race": "inner race",
    "outer": "outer race",
    "outer race": "outer race",
    "ball": "ball",
}


def rule_probabilities(candidates: list[dict]) -> dict[str, float]:
    """The rule detector's evidence as probabilities over healthy and the three faults.

    Each fault's confidence c_i (logistic in its margin over the threshold) is read as the
    probability that its line is real; a fault alone: c_i prod_{j != i} (1 - c_j), healthy:
    prod (1 - c_j); normalised.

    Parameters
    ----------
    candidates : list of dict
        ``Diagnosis.candidates`` (each with ``fault`` and ``confidence``).

    Returns
    -------
    dict of str to float
        ``healthy`` and each fault's probability; they sum to 1.
    """
    conf = {c["fault"]: float(c["confidence"]) for c in candidates}
    scores = {"healthy": float(np.prod([1.0 - v for v in conf.values()]))}
    for fault, value in conf.items():
        others = [1.0 - v for k, v in conf.items() if k != fault]
        scores[fault] = value * float(np.prod(others))
    total = sum(scores.values()) or 1.0
    return {k: v / total for k, v in scores.items()}


def model_label_verdict(label: str, class_kinds: dict | None = None) -> str | None:
    """The verdict a model's class label stands for (``CANONICAL``), or None.

    A class the model learnt from waviness (``class_kinds[label] == "waviness"``, recorded by
    ``cmtool train`` from the dataset's ``defect_kind``) is no local fault: it stands for
    ``healthy`` in the rule's verdicts (docs/diagnosis.md, "A model trained on waviness").

    Parameters
    ----------
    label : str
        A model's class label (``outer``, ``inner race``, ``healthy``, ...).
    class_kinds : dict, optional
        Label -> kind of defect (``cmtool.classifier.class_kinds``).

    Returns
    -------
    str or None
        ``healthy``, ``outer race``, ``inner race`` or ``ball``; None for a label that is
        none of them.
    """
    if class_kinds and class_kinds.get(str(label)) == "waviness":
        return "healthy"
    return CANONICAL.get(str(label))


def verdict_probabilities(
    model_probabilities: dict, class_kinds: dict | None = None
) -> dict[str, float]:
    """A model's class probabilities summed per verdict (:func:`model_label_verdict`).

    Parameters
    ----------
    model_probabilities : dict
        Class label -> probability.
    class_kinds : dict, optional
        Label -> kind of defect (``cmtool.classifier.class_kinds``).

    Returns
    -------
    dict of str to float
        Verdict -> probability (labels that stand for no verdict left out).
    """
    out: dict[str, float] = {}
    for label, value in model_probabilities.items():
        name = model_label_verdict(str(label), class_kinds)
        if name is not None:
            out[name] = out.get(name, 0.0) + float(value)
    return out


def pool_probabilities(
    rule_p: dict[str, float],
    model_probabilities: dict,
    class_kinds: dict | None = None,
    segments: int = 1,
) -> dict[str, float]:
    """Log-linear pooling of the rule's and a model's probabilities over the verdicts.

    p(class) proportional to p_rule^(n/(n+1)) p_model^(1/(n+1)), n the number of the model's
    segments in the record: each source weighs as much as the signal its opinion rests on.
    The rule reads the whole record; the model reads n segments as long as its training
    signals and combines them into one segment's opinion (:func:`segment_probabilities`).
    A record the model reads whole (n = 1, as its training signals): sqrt(p_rule p_model),
    each source counts as much (until stop 55 on every record). A class that either gives
    almost no chance stays unlikely. Model labels are read as verdicts
    (:func:`model_label_verdict`: by name, a class learnt from waviness as healthy when
    ``class_kinds`` says so); the result sums to 1. A verdict the model has no class for (a
    model trained on waviness has none for any local fault) is one it cannot tell from
    healthy: it gets the model's probability of healthy, so that the rule alone weighs it
    (until stop 52 it got none, and such a model turned every local fault healthy).

    Parameters
    ----------
    rule_p : dict of str to float
        The rule's probabilities (:func:`rule_probabilities`).
    model_probabilities : dict
        The model's class probabilities.
    class_kinds : dict, optional
        Label -> kind of defect (``cmtool.classifier.class_kinds``).
    segments : int
        n, the model's segments in the record (>= 1).

    Returns
    -------
    dict of str to float
        The pooled probability of each of ``rule_p``'s verdicts; they sum to 1.
    """
    model_p = verdict_probabilities(model_probabilities, class_kinds)
    if "healthy" in model_p:
        model_p = {k: model_p.get(k, model_p["healthy"]) for k in rule_p}
    if segments < 1:
        raise ValueError(f"segments must be at least 1, got {segments}")
    floor = 1e-6
    rule_weight = segments / (segments + 1.0)

    def weighted(rule_value: float, model_value: float) -> float:
        rule_value, model_value = max(rule_value, floor), max(model_value, floor)
        if segments == 1:  # the equal-weight pool exactly as before stop 55
            return math.sqrt(rule_value * model_value)
        return rule_value**rule_weight * model_value ** (1.0 - rule_weight)

    pooled = {k: weighted(rule_p.get(k, 0.0), model_p.get(k, 0.0)) for k in rule_p}
    total = sum(pooled.values())
    return {k: v / total for k, v in pooled.items()}


def calibrated_confidence(probability: float, calibration: dict | None) -> float:
    """The pooled verdict's probability through the model's calibration.

    A logistic in the probability's log-odds, fitted by ``cmtool train``
    (:func:`cmtool.classifier.pooled_calibration`); without one, the probability as it is.

    Parameters
    ----------
    probability : float
        The pooled verdict's probability, in [0, 1].
    calibration : dict or None
        ``slope`` and ``intercept`` of the logistic.

    Returns
    -------
    float
        The confidence, in (0, 1).
    """
    if not calibration:
        return probability
    p = min(max(probability, 1e-9), 1.0 - 1e-9)
    z = calibration["slope"] * math.log(p / (1.0 - p)) + calibration["intercept"]
    return 1.0 / (1.0 + math.exp(-z))


def combine_verdicts(diagnosis: Diagnosis) -> None:
    """One verdict from the rule evidence and the model's probabilities (log-linear pooling).

    The verdict follows :func:`pool_probabilities`, except where the pool favours a verdict
    the model has no class for (a model trained on waviness has none for any local fault):
    there the verdict and its confidence are the rule's. Its confidence is calibrated when the
    model carries a calibration of the pooled verdict (``pooled_calibration``: fitted by
    ``cmtool train`` on its out-of-fold predictions and the rule evidence of the same
    training signals). On a record the model reads as n segments (``segments`` in its
    verdict) the rule weighs n / (n + 1). The headline says what the verdict rests on,
    whether the two agree and how they were weighed.

    Parameters
    ----------
    diagnosis : Diagnosis
        A diagnosis with the rule's candidates and the model's verdict; its ``verdict``,
        ``confidence``, ``probabilities`` and ``basis`` are set here (nothing changes when
        the model gave no probabilities).
    """
    probabilities = diagnosis.model_verdict.get("probabilities")
    if not probabilities:
        return
    kinds = diagnosis.model_verdict.get("class_kinds")
    model_p = verdict_probabilities(probabilities, kinds)
    segments = int(diagnosis.model_verdict.get("segments") or 1)
    pooled = pool_probabilities(
        rule_probabilities(diagnosis.candidates), probabilities, kinds, segments
    )
    verdict = max(pooled, key=pooled.get)
    rule_label = diagnosis.rule_verdict["label"]
    model_label = max(model_p, key=model_p.get) if model_p else rule_label
    if rule_label == model_label:
        basis = f"the rule evidence and the model agree ({rule_label})"
    else:
        basis = (
            f"the rule evidence says {rule_label} "
            f"({diagnosis.rule_verdict['confidence']:.2f}) and the model {model_label} "
            f"({model_p[model_label]:.2f}): they disagree; the verdict follows their pooled "
            "probabilities"
        )
    if segments > 1:
        basis += (
            f"; the rule's evidence weighs {segments}/{segments + 1} against the model's (the "
            f"rule reads the whole record, the model {segments} segments combined into one "
            "opinion)"
        )
    label = str(diagnosis.model_verdict.get("label"))
    if kinds and kinds.get(label) == "waviness":
        basis += (
            f"; the model reads {label} waviness "
            f"({float(probabilities.get(label, 0.0)):.2f}), no local fault"
        )
    calibration = diagnosis.model_verdict.get("pooled_calibration")
    if verdict not in model_p:  # the model has no class for it: the rule's verdict, and its
        # confidence (the pool, in which the model cannot weigh that fault, may favour a fault
        # the rule did not detect: until stop 75 that fault was named with the confidence of
        # the rule's own verdict, healthy)
        if verdict == rule_label:
            basis += f"; the model learnt no {verdict}: the verdict and confidence are the rule's"
        else:
            basis += (
                f"; the pool leans to {verdict}, which the model learnt no class for and the "
                "rule does not name: the verdict and confidence are the rule's"
            )
        verdict = rule_label
        confidence = diagnosis.rule_verdict["confidence"]
    else:
        if calibration:
            basis += "; confidence calibrated on the model's out-of-fold training signals"
        confidence = calibrated_confidence(pooled[verdict], calibration)
    diagnosis.verdict = verdict
    diagnosis.confidence = round(confidence, 4)
    diagnosis.basis = basis
    diagnosis.probabilities = {k: round(v, 4) for k, v in pooled.items()}


#: A long record's false-alarm probability when its segments vote (:func:`segment_probabilities`):
#: three times the rule's per fault (``features.FALSE_ALARM``), one for each fault.
SEGMENT_FALSE_ALARM = 3e-4


def healthy_false_alarm(model: Any) -> float | None:
    """A model's own rate of calling a healthy signal a local fault.

    The share of its healthy training signals that its out-of-fold predictions
    (``cv_labels``, ``cv_predictions``, kept by ``cmtool train``) call a local fault, at least
    one over their number (a finite sample shows no model perfect); None for a bundle
    without them or without a healthy class.

    Parameters
    ----------
    model : dict or pipeline
        A model bundle (``cmtool train``).

    Returns
    -------
    float or None
        The rate, in (0, 1].
    """
    if not isinstance(model, dict) or "cv_labels" not in model or "cv_predictions" not in model:
        return None
    kinds = model.get("class_kinds")
    truth = [model_label_verdict(str(v), kinds) for v in model["cv_labels"]]
    called = [model_label_verdict(str(v), kinds) for v in model["cv_predictions"]]
    healthy = [c for t, c in zip(truth, called, strict=True) if t == "healthy"]
    if not healthy:
        return None
    wrong = sum(c not in (None, "healthy") for c in healthy)
    return max(wrong / len(healthy), 1.0 / len(healthy))


def segment_probabilities(
    proba: np.ndarray, classes: list[str], class_kinds: dict | None, false_alarm: float | None
) -> tuple[np.ndarray, int, bool]:
    """One record's class probabilities from its segments' (rows of ``proba``).

    A local fault strikes in bursts (a ball pit only while its spin axis keeps it on the
    contact track), so in a long record it can show in a few segments and not in the others,
    and the mean over all of them reads healthy (docs/realism.md 6, "Long records"). The
    segments vote: k of the n segments whose most probable class is a local fault; when the
    model's own false-alarm rate ``false_alarm`` (:func:`healthy_false_alarm`) makes k or more
    of n less likely than ``SEGMENT_FALSE_ALARM`` (binomial), the record's probabilities are
    the mean over those k segments, else the mean over all (as before stop 54, and always
    for one segment or an unknown rate).

    Parameters
    ----------
    proba : ndarray, shape (segments, classes)
        Each segment's class probabilities.
    classes : list of str
        The model's class labels (columns of ``proba``).
    class_kinds : dict, optional
        What each class was learnt from (:func:`model_label_verdict`: waviness classes are
        no local fault).
    false_alarm : float, optional
        The model's rate of calling a healthy signal a local fault; None: no vote.

    Returns
    -------
    (ndarray, int, bool)
        The record's probabilities (in ``classes``' order), k, and whether the k decided.
    """
    from scipy.stats import binom

    fault = np.array(
        [model_label_verdict(c, class_kinds) not in (None, "healthy") for c in classes]
    )
    faulty = fault[np.argmax(proba, axis=1)]
    k, n = int(faulty.sum()), len(proba)
    if (
        n >= 2
        and k
        and false_alarm is not None
        and binom.sf(k - 1, n, false_alarm) <= SEGMENT_FALSE_ALARM
    ):
        return proba[faulty].mean(axis=0), k, True
    return proba.mean(axis=0), k, False


def model_verdict(
    model: Any, x: np.ndarray, fs: float, freqs: BearingFrequencies, extra: dict
) -> dict:
    """Class and probabilities from a trained pipeline (``cmtool train``).

    A model trained on signals of T seconds (``signal_duration_s`` in the bundle) sees the
    recording as consecutive segments of T seconds (the line-to-floor ratios it learnt depend
    on the record length); a recording shorter than two segments is used whole. The segments'
    probabilities are combined by :func:`segment_probabilities` (the mean over those read as
    a local fault when more are than the model's false-alarm rate explains, else over all).
    ``segments`` in the result says how many were used, ``segments_read_as_fault`` how many
    the model read as a local fault and ``segments_combined`` which were averaged.

    Parameters
    ----------
    model : dict or pipeline
        A model bundle (``cmtool train``) or a fitted pipeline.
    x : ndarray
        The record [its unit].
    fs : float
        Sample rate [Hz].
    freqs : BearingFrequencies
        The bearing's characteristic frequencies at the record's speed [Hz].
    extra : dict
        Further context columns the model reads (as the dataset's).

    Returns
    -------
    dict
        ``label``, ``probabilities`` (class -> probability) where the model gives them,
        and the segments' counts above.
    """
    import pandas as pd

    pipeline = model["pipeline"] if isinstance(model, dict) else model
    duration = model.get("signal_duration_s") if isinstance(model, dict) else None
    x = np.asarray(x, dtype=float)
    segments = [x]
    if duration:
        n = int(round(duration * fs))
        count = x.size // n if n > 0 else 0
        if count >= 2:
            segments = [x[i * n : (i + 1) * n] for i in range(count)]
    context = {
        "fs_hz": fs,
        "shaft_frequency_hz": freqs.shaft,
        "ftf_hz": freqs.ftf,
        "bpfo_hz": freqs.bpfo,
        "bpfi_hz": freqs.bpfi,
        "bsf_hz": freqs.bsf,
        "two_bsf_hz": freqs.two_bsf,
        **extra,
    }
    frame = pd.DataFrame(
        {"signal": segments, **{k: [v] * len(segments) for k, v in context.items()}}
    )
    out: dict = {"segments": len(segments)}
    if isinstance(model, dict) and model.get("pooled_calibration"):
        out["pooled_calibration"] = model["pooled_calibration"]
    if isinstance(model, dict) and model.get("class_kinds"):
        out["class_kinds"] = dict(model["class_kinds"])
    if hasattr(pipeline, "predict_proba"):
        classes = [str(c) for c in pipeline.classes_]
        rate = healthy_false_alarm(model)
        kinds = model.get("class_kinds") if isinstance(model, dict) else None
        proba, k, voted = segment_probabilities(pipeline.predict_proba(frame), classes, kinds, rate)
        if len(segments) >= 2:
            out["segments_read_as_fault"] = k
            out["segments_combined"] = (
                f"the {k} of {len(segments)} segments read as a local fault (more than the "
                f"model's false-alarm rate {rate:.3g} makes likely)"
                if voted
                else "all"
            )
        out["label"] = classes[int(np.argmax(proba))]
        out["probabilities"] = {c: round(float(p), 4) for c, p in zip(classes, proba, strict=True)}
    else:
        labels, counts = np.unique(pipeline.predict(frame).astype(str), return_counts=True)
        out["label"] = str(labels[int(np.argmax(counts))])
    return out


def outside_training(model: Any, rpm: float, fs: float, bearing: str) -> list[str]:
    """Where a record lies outside what a model was trained on (``training_ranges``).

    Parameters
    ----------
    model : dict or estimator
        A ``cmtool train`` bundle (older bundles and bare estimators say nothing).
    rpm : float
        The record's shaft speed [rev/min].
    fs : float
        Its sample rate [Hz].
    bearing : str
        Its bearing's name.

    Returns
    -------
    list of str
        One warning per way the record is new to the model (speed or rate more than 1 %
        outside the model's, another bearing).
    """
    seen = model.get("training_ranges") if isinstance(model, dict) else None
    if not seen:
        return []
    out = []
    for value, key, unit in ((rpm, "rpm", "rpm"), (fs, "fs_hz", "Hz")):
        low, high = seen.get(key, (value, value))
        if not 0.99 * low <= value <= 1.01 * high:
            span = f"{low:g}" if low == high else f"{low:g}-{high:g}"
            out.append(
                f"the model was trained at {span} {unit} and this record is at {value:g} "
                f"{unit}: its probabilities are an extrapolation"
            )
    if seen.get("bearings") and bearing not in seen["bearings"]:
        out.append(
            f"the model was trained on the {', '.join(seen['bearings'])}, not the {bearing}: "
            "its probabilities rest on features normalised by the bearing's rates"
        )
    return out
