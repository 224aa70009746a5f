"""Train and check a classifier on a synthetic dataset; save and load models safely.

The pipeline is ``features.FeatureExtractor`` (the feature table, computed once per signal)
followed by a scaler and a classifier. Candidates (random forest, extra trees, histogram
gradient boosting, logistic regression) are compared by cross-validation grouped by
``operating_point_id`` (no speed/load point in both train and test) and the best is refitted
on all data. Extrapolation is reported too: trained without the highest (lowest) speed or
load, tested on it.

Models are saved with joblib together with the feature names, the classes, the training
recipe and the versions of cmtool, scikit-learn and numpy; loading a model made by another
version raises ``ModelVersionError``.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import joblib
import numpy as np
import pandas as pd
import sklearn
from sklearn.base import clone
from sklearn.ensemble import (
    ExtraTreesClassifier,
    HistGradientBoostingClassifier,
    RandomForestClassifier,
)
from sklearn.linear_model import LogisticRegression
from sklearn.metrics import accuracy_score, classification_report, confusion_matrix
from sklearn.model_selection import GroupKFold
from sklearn.pipeline import Pipeline, make_pipeline
from sklearn.preprocessing import StandardScaler

import features

from . import __version__
from .io import atomic_write

__all__ = [
    "candidate_classifiers",
    "train",
    "evaluate",
    "save_model",
    "load_model",
    "ModelVersionError",
    "make_classifier",
]

MODEL_FORMAT = 1


class ModelVersionError(RuntimeError):
    """A saved model was made by another version of cmtool or scikit-learn."""


def candidate_classifiers(random_state: int = 0) -> dict[str, Any]:
    """The classifiers compared by :func:`train` (after a StandardScaler)."""
    return {
        "random_forest": RandomForestClassifier(
            n_estimators=300, random_state=random_state, n_jobs=-1
        ),
        "extra_trees": ExtraTreesClassifier(n_estimators=500, random_state=random_state, n_jobs=-1),
        "gradient_boosting": HistGradientBoostingClassifier(random_state=random_state),
        "logistic_regression": LogisticRegression(max_iter=5000, C=1.0),
    }


def make_classifier(name: str = "random_forest", *, random_state: int = 0, **extractor) -> Pipeline:
    """Full pipeline: FeatureExtractor -> StandardScaler -> classifier ``name``."""
    return Pipeline(
        [
            ("features", features.FeatureExtractor(**extractor)),
            ("scale", StandardScaler()),
            ("classify", candidate_classifiers(random_state)[name]),
        ]
    )


def _features(frame: pd.DataFrame, feature_set: str = "all") -> tuple[np.ndarray, list[str]]:
    ext = features.FeatureExtractor(feature_set=feature_set).fit(frame)
    return ext.transform(frame), list(ext.get_feature_names_out())


def _grouped_cv(X, y, groups, estimator, n_splits: int) -> tuple[float, np.ndarray]:
    cv = GroupKFold(n_splits=n_splits)
    pred = np.empty_like(y)
    for train_idx, test_idx in cv.split(X, y, groups):
        est = clone(estimator).fit(X[train_idx], y[train_idx])
        pred[test_idx] = est.predict(X[test_idx])
    return float(accuracy_score(y, pred)), pred


def _extrapolation(X, y, frame, estimator) -> dict[str, float]:
    out = {}
    for col in ("rpm", "radial_load_n"):
        values = frame[col].to_numpy()
        top = values.max()
        test = values >= top - 1e-9
        if test.all() or not test.any():
            continue
        est = clone(estimator).fit(X[~test], y[~test])
        out[f"{col}_above_training"] = float(accuracy_score(y[test], est.predict(X[test])))
        low = values <= values.min() + 1e-9
        if not low.all():
            est = clone(estimator).fit(X[~low], y[~low])
            out[f"{col}_below_training"] = float(accuracy_score(y[low], est.predict(X[low])))
    return out


def train(
    frame: pd.DataFrame,
    *,
    recipe: str = "",
    random_state: int = 0,
    n_splits: int | None = None,
    feature_set: str = "all",
) -> dict[str, Any]:
    """Fit the candidates with grouped cross-validation and keep the best.

    Parameters
    ----------
    frame : DataFrame
        A dataset (``cmtool.datasets.read_dataset``): ``signal``, ``label``,
        ``operating_point_id`` and the context columns.
    recipe : str
        The training recipe text (stored with the model).
    random_state : int
        Seed of the classifiers.
    n_splits : int, optional
        Grouped folds (default: min(5, number of operating points)).
    feature_set : {"all", "scale-free"}
        Features used (``features.FEATURE_SETS``); ``scale-free`` for a model that will meet
        measured signals (any sensor gain or unit).

    Returns
    -------
    dict
        The model bundle: ``pipeline`` (FeatureExtractor + scaler + best classifier, fitted on
        all data), ``classes``, ``feature_names``, ``scores`` (grouped-CV accuracy of every
        candidate), ``best``, ``extrapolation``, ``recipe``, ``versions``.
    """
    X, names = _features(frame, feature_set)
    y = frame["label"].astype(str).to_numpy()
    groups = frame["operating_point_id"].to_numpy()
    n_groups = len(np.unique(groups))
    if n_groups < 2:
        raise ValueError("the dataset has one operating point: grouped validation needs two")
    n_splits = n_splits or min(5, n_groups)
    scores, cv_predictions = {}, {}
    for name, clf in candidate_classifiers(random_state).items():
        est = make_pipeline(StandardScaler(), clf)
        scores[name], cv_predictions[name] = _grouped_cv(X, y, groups, est, n_splits)
    best = max(scores, key=scores.get)
    head = make_pipeline(StandardScaler(), candidate_classifiers(random_state)[best])
    extrapolation = _extrapolation(X, y, frame, head)
    pipeline = make_classifier(best, random_state=random_state, feature_set=feature_set)
    # the feature step is stateless: fit it, then fit the rest on the precomputed table
    pipeline.steps[0][1].fit(frame)
    pipeline.steps[1][1].fit(X)
    pipeline.steps[2][1].fit(pipeline.steps[1][1].transform(X), y)
    return {
        "format": MODEL_FORMAT,
        "pipeline": pipeline,
        "classes": sorted(set(y)),
        "feature_names": names,
        "scores": scores,
        "best": best,
        "n_splits": n_splits,
        "extrapolation": extrapolation,
        "recipe": recipe,
        "feature_set": feature_set,
        "signal_duration_s": float(np.median(frame["duration_s"]))
        if "duration_s" in frame.columns
        else None,
        "cv_labels": y.tolist(),
        "cv_predictions": cv_predictions[best].tolist(),
        "versions": {
            "cmtool": __version__,
            "sklearn": sklearn.__version__,
            "numpy": np.__version__,
        },
    }


def evaluate(bundle: dict[str, Any], frame: pd.DataFrame) -> dict[str, Any]:
    """Accuracy, per-class precision/recall and the confusion matrix of a model on a dataset."""
    y = frame["label"].astype(str).to_numpy()
    pred = bundle["pipeline"].predict(frame)
    labels = sorted(set(y) | set(pred))
    report = classification_report(y, pred, labels=labels, output_dict=True, zero_division=0)
    return {
        "accuracy": float(accuracy_score(y, pred)),
        "labels": labels,
        "confusion": confusion_matrix(y, pred, labels=labels).tolist(),
        "per_class": {
            k: {m: float(v[m]) for m in ("precision", "recall", "f1-score")}
            for k, v in report.items()
            if k in labels
        },
        "predictions": pred.tolist(),
    }


def save_model(bundle: dict[str, Any], path: str | Path) -> Path:
    """Write the model bundle (joblib) atomically, plus a readable ``.json`` summary."""
    path = Path(path)
    atomic_write(path, lambda tmp: joblib.dump(bundle, tmp))
    summary = {
        k: bundle[k]
        for k in (
            "best",
            "scores",
            "classes",
            "extrapolation",
            "versions",
            "feature_names",
            "n_splits",
        )
    }
    atomic_write(
        path.with_suffix(path.suffix + ".json"),
        lambda tmp: tmp.write_text(json.dumps(summary, indent=2)),
    )
    return path


def load_model(path: str | Path) -> dict[str, Any]:
    """Load a model bundle, refusing one made by another cmtool or scikit-learn version."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"model {path}: no such file")
    bundle = joblib.load(path)
    if not isinstance(bundle, dict) or bundle.get("format") != MODEL_FORMAT:
        raise ModelVersionError(
            f"model {path}: not a cmtool model (format "
            f"{bundle.get('format') if isinstance(bundle, dict) else '?'})"
        )
    versions = bundle.get("versions", {})
    for key, current in (("cmtool", __version__), ("sklearn", sklearn.__version__)):
        if versions.get(key) != current:
            raise ModelVersionError(
                f"model {path} was made with {key} {versions.get(key)}; this is {key} "
                f"{current}: retrain it with `cmtool train`"
            )
    return bundle
