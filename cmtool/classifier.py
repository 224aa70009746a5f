"""Train and check a classifier on a synthetic dataset; save and load models safely.

The pipeline is ``features.FeatureExtractor`` (the feature table, computed once per signal)
followed by a scaler and a classifier. Candidates (random forest, extra trees, histogram
gradient boosting, logistic regression) are compared by cross-validation grouped by
``operating_point_id`` (no speed/load point in both train and test) and the best is refitted
on all data. Extrapolation is reported too: trained without the highest (lowest) speed or
load, tested on it.

Models are saved and loaded safely by :mod:`cmtool.model_files` (skops archives that run no
code when loaded), whose names this module still exports.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pandas as pd
import sklearn
from sklearn.ensemble import (
    ExtraTreesClassifier,
    HistGradientBoostingClassifier,
    RandomForestClassifier,
)
from sklearn.linear_model import LogisticRegression
from sklearn.metrics import (
    accuracy_score,
    balanced_accuracy_score,
    classification_report,
    confusion_matrix,
)
from sklearn.model_selection import GroupKFold
from sklearn.pipeline import Pipeline, make_pipeline
from sklearn.preprocessing import StandardScaler

import features
from generators import bearing
from generators.params import check_int

from . import __version__
from .fits import fit_single_threaded, fold_fit, held_out_accuracy, run_fits
from .inputs import check_record_lengths, checked_frame, checked_workers
from .model_files import (  # the model files, kept importable from here
    MODEL_FORMAT,
    TRUSTED_TYPES,
    ModelFormatError,
    ModelVersionError,
    dataset_fingerprint,
    load_model,
    save_model,
    signal_hashes,
    training_overlap,
)

__all__ = [
    "candidate_classifiers",
    "train",
    "evaluate",
    "save_model",
    "load_model",
    "ModelVersionError",
    "ModelFormatError",
    "make_classifier",
    "dataset_fingerprint",
    "signal_hashes",
    "training_overlap",
    "TRUSTED_TYPES",
    "pooled_calibration",
    "expected_calibration_error",
]

#: Classes weighed inversely to their counts in training: a dataset's class proportions are
#: the recipe's counts less the faults too faint to show (``visible_faults``: most ball pits
#: never meet the races), not how often a machine has each fault, and a model should not
#: call a ball fault healthy because the ball class lost examples to that filter. Measured on
#: simulation only (``benchmarks/cross_domain.py --classifiers [--class-weight none]``,
#: CWRU-rig and MFPT-rig recipes, evidence+scale-free, trained on one rig and scored on the
#: other, mean balanced accuracy of both directions, unweighted -> weighted): random forest
#: 0.824 -> 0.848, extra trees 0.871 -> 0.894, gradient boosting 0.877 -> 0.895, logistic
#: regression 0.790 -> 0.789; healthy recall 0.94-1.00 (docs/realism.md 6).
CLASS_WEIGHT = "balanced"
#: :func:`train`'s default choice of classifier: the one the dataset's recipe names in
#: ``[training] classifier`` (the rig recipes name the one that carried over best between the
#: simulated rigs: docs/realism.md 6), else the best grouped cross-validation score.
FROM_RECIPE = "recipe"


def recipe_classifier(recipe: str) -> str | None:
    """The classifier a recipe's text names in ``[training] classifier`` (None: none named).

    Parameters
    ----------
    recipe : str
        The recipe's TOML text (text that is not TOML names none).

    Returns
    -------
    str or None
        The classifier's name (a key of :func:`candidate_classifiers`), as written.
    """
    import tomllib

    try:
        named = tomllib.loads(recipe).get("training", {}).get("classifier")
    except (tomllib.TOMLDecodeError, AttributeError):
        return None
    return named if isinstance(named, str) else None


def candidate_classifiers(
    random_state: int = 0, class_weight: str | None = CLASS_WEIGHT
) -> dict[str, Any]:
    """The classifiers compared by :func:`train` (after a scaler).

    Parameters
    ----------
    random_state : int
        Seed of the randomised ones (forests, gradient boosting).
    class_weight : str or None
        scikit-learn's ``class_weight`` for every one (``"balanced"``: classes weighed by
        their counts; None: unweighted).

    Returns
    -------
    dict of str to estimator
        ``random_forest``, ``extra_trees``, ``gradient_boosting`` and
        ``logistic_regression``, unfitted.
    """
    weight = class_weight
    return {
        # forests on one thread: on the few hundred or thousand signals a model predicts at
        # once, scikit-learn's threads cost more than they spread (docs/performance.md, stop
        # 89); train spreads its fits over processes (cmtool.fits)
        "random_forest": RandomForestClassifier(
            n_estimators=300, random_state=random_state, class_weight=weight
        ),
        "extra_trees": ExtraTreesClassifier(
            n_estimators=500, random_state=random_state, class_weight=weight
        ),
        "gradient_boosting": HistGradientBoostingClassifier(
            random_state=random_state, class_weight=weight
        ),
        "logistic_regression": LogisticRegression(max_iter=5000, C=1.0, class_weight=weight),
    }


def make_classifier(
    name: str = "random_forest", *, random_state: int = 0, **extractor: Any
) -> Pipeline:
    """Full pipeline: FeatureExtractor -> StandardScaler -> classifier ``name``.

    Parameters
    ----------
    name : str
        A key of :func:`candidate_classifiers`.
    random_state : int
        The classifier's seed.
    **extractor : Any
        Parameters of ``features.FeatureExtractor`` (``feature_set``, ``n_jobs``, ...).

    Returns
    -------
    sklearn.pipeline.Pipeline
        Unfitted; its steps are named ``features``, ``scale`` and ``classify``.
    """
    return Pipeline(
        [
            ("features", features.FeatureExtractor(**extractor)),
            ("scale", StandardScaler()),
            ("classify", candidate_classifiers(random_state)[name]),
        ]
    )


#: The columns :func:`train` reads of a dataset: the signals, their labels and operating
#: points, and what the features, the rule's evidence and the extrapolation check need of
#: each (rate [Hz], speed [rev/min], load [N], bearing, characteristic frequencies [Hz]).
TRAINING_COLUMNS = (
    "signal",
    "label",
    "operating_point_id",
    "fs_hz",
    "rpm",
    "radial_load_n",
    "bearing",
    "shaft_frequency_hz",
    "ftf_hz",
    "bpfo_hz",
    "bpfi_hz",
    "two_bsf_hz",
)
#: Default feature set of :func:`train` and ``cmtool train``: the one that carried over best
#: between simulated rigs (``benchmarks/cross_domain.py``; features.FEATURE_SETS).
DEFAULT_FEATURE_SET = "evidence+scale-free"
#: Faulty training signals whose fault SNR (where the fault stands out) is below this are left
#: out by default [dB]: nothing in them can show the fault their label names.
MIN_FAULT_SNR_DB = -10.0


def visible_faults(frame: pd.DataFrame, min_fault_snr_db: float | None) -> pd.Series:
    """Rows to train on: healthy signals, and faulty ones whose fault SNR reaches the floor.

    Parameters
    ----------
    frame : DataFrame
        A dataset; without a ``fault_snr_db`` column every row is kept.
    min_fault_snr_db : float or None
        Floor [dB]; None keeps every row.

    Returns
    -------
    Series of bool
        True for the rows kept (a NaN fault SNR, as healthy signals have, is kept).
    """
    if min_fault_snr_db is None or "fault_snr_db" not in frame.columns:
        return pd.Series(True, index=frame.index)
    return ~(frame["fault_snr_db"] < min_fault_snr_db)


#: Signals per progress report of :func:`train`'s long stage (per worker).
PROGRESS_CHUNK = 32

#: ``progress(stage, done, total)``: what :func:`train` reports after each chunk of signals.
Progress = Callable[[str, int, int], None]


def _chunks(total: int, workers: int) -> list[slice]:
    """Consecutive slices of ``PROGRESS_CHUNK`` signals per worker covering ``range(total)``."""
    size = PROGRESS_CHUNK * max(1, workers)
    return [slice(start, min(start + size, total)) for start in range(0, total, size)]


def _table_and_rule_chunk(
    items: list[tuple], names: list[str], faults: tuple[str, ...], n_harmonics: int
) -> list[tuple[list[float], dict[str, float]]]:
    """Each signal's feature row and rule probabilities, its evidence computed once.

    ``items`` are the extractor's ``(signal, context)`` with the ``(fs, rpm, bearing)`` the
    rule reads. The row's ``fault_evidence`` is the rule's own when the dataset's context
    holds exactly the rates the rule computes from the bearing and speed; otherwise the rule
    computes its own (the result is the same either way).
    """
    from .diagnose import rule_candidates, rule_context, rule_probabilities

    pairs = [(signal, ctx) for signal, ctx, _ in items]
    rows, found = features.transformer.feature_rows_with_evidence(pairs, faults, n_harmonics, names)
    out = []
    for (signal, ctx, (fs, rpm, name)), row, evidence in zip(items, rows, found, strict=True):
        x = np.asarray(signal, dtype=float)
        _, _, rates, _ = rule_context(x, fs, rpm, bearing(name))
        same = evidence is not None and ctx.get("fs") == fs
        if not (same and all(ctx.get(k) == v for k, v in rates.items())):
            evidence = features.fault_evidence(x, fs, rates)
        out.append((row, rule_probabilities(rule_candidates(evidence, rates))))
    return out


def _table_and_rule(
    frame: pd.DataFrame,
    feature_set: str,
    *,
    workers: int = 1,
    progress: Progress | None = None,
) -> tuple[np.ndarray, list[str], list[dict[str, float]]]:
    """The feature table of ``frame`` and the rule detector's probabilities of each signal.

    In ``workers`` processes, chunk by chunk; the same for any ``workers`` and chunking as
    the extractor's table and ``cmtool.diagnose.diagnose_signal``'s rule, one signal at a
    time.
    """
    ext = features.FeatureExtractor(feature_set=feature_set).fit(frame)
    names = list(ext.get_feature_names_out())
    rule_rows = zip(frame["fs_hz"], frame["rpm"], frame["bearing"], strict=True)
    signals = ext.signals_with_context(frame)
    items = [(*item, rule) for item, rule in zip(signals, rule_rows, strict=True)]
    table: list = []
    rule: list[dict[str, float]] = []
    for part in _chunks(len(items), workers):
        done = features.transformer.map_in_processes(
            _table_and_rule_chunk, items[part], workers, names, ext.faults, ext.n_harmonics
        )
        table.extend(row for row, _ in done)
        rule.extend(probabilities for _, probabilities in done)
        if progress is not None:
            progress("features and rule evidence", part.stop, len(items))
    array = np.asarray(table, dtype=float).reshape(len(items), len(names))
    return array, names, rule


def transform_in_chunks(
    extractor: features.FeatureExtractor,
    frame: pd.DataFrame,
    stage: str,
    progress: Progress | None = None,
) -> np.ndarray:
    """``extractor.transform(frame)``, chunk by chunk, reporting ``progress(stage, done, total)``.

    Chunks of ``PROGRESS_CHUNK`` signals per worker (``extractor.n_jobs``); each signal's
    features are its own, so the table is the one a single call makes.

    Parameters
    ----------
    extractor : features.FeatureExtractor
        A fitted extractor.
    frame : DataFrame
        Signals with their context columns (a dataset).
    stage : str
        The stage named to ``progress``.
    progress : callable, optional
        ``progress(stage, signals done, signals in all)``; None: one call, no reports.

    Returns
    -------
    ndarray
        The feature table, a row per signal of ``frame`` [each feature's unit].
    """
    if progress is None:
        return extractor.transform(frame)
    workers = extractor.n_jobs if isinstance(extractor.n_jobs, int) and extractor.n_jobs > 0 else 1
    parts = []
    for part in _chunks(len(frame), workers):
        parts.append(extractor.transform(frame.iloc[part]))
        progress(stage, part.stop, len(frame))
    return np.concatenate(parts) if parts else extractor.transform(frame)


def _out_of_fold(
    X: np.ndarray,
    y: np.ndarray,
    groups: np.ndarray,
    estimator: Any,
    n_splits: int,
    *,
    probabilities: bool = False,
    X_extra: np.ndarray | None = None,
    workers: int = 1,
) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None]:
    """Each signal's prediction by the grouped fold's model that did not see its group.

    With ``probabilities`` also the class probabilities (columns: the sorted labels of
    ``y``; a class a fold's model never saw has 0) and those of ``X_extra`` (signals in no
    fold) averaged over the folds' models: what :func:`pooled_calibration` weighs. One fit
    per fold serves the score and the calibration; the folds are fitted in ``workers``
    processes (:func:`cmtool.fits.run_fits`).
    """
    folds = list(GroupKFold(n_splits=n_splits).split(X, y, groups))
    results = run_fits(_fold_calls(X, y, folds, estimator, probabilities, X_extra), workers)
    return _assemble_folds(y, folds, results, probabilities, X_extra)


def _fold_calls(X, y, folds, estimator, probabilities: bool, X_extra) -> list[tuple]:
    """The :func:`cmtool.fits.fold_fit` calls of ``folds``, in their order."""
    return [(fold_fit, (estimator, X, y, tr, te, probabilities, X_extra)) for tr, te in folds]


def _assemble_folds(y, folds, results, probabilities: bool, X_extra) -> tuple:
    """:func:`_out_of_fold`'s predictions from the folds' :func:`cmtool.fits.fold_fit`."""
    classes = np.array(sorted(set(y)))
    pred = np.empty_like(y)
    proba = np.zeros((len(y), classes.size)) if probabilities else None
    extra = None
    if probabilities and X_extra is not None and len(X_extra):
        extra = np.zeros((len(X_extra), classes.size))
    for (_, test_idx), (predicted, p, p_extra, seen) in zip(folds, results, strict=True):
        pred[test_idx] = predicted
        if proba is not None:
            columns = np.searchsorted(classes, seen)
            proba[np.ix_(test_idx, columns)] = p
            if extra is not None:
                extra[:, columns] += p_extra / len(folds)
    return pred, proba, extra


def _grouped_cv(X, y, groups, estimator, n_splits: int) -> tuple[float, np.ndarray]:
    pred, _, _ = _out_of_fold(X, y, groups, estimator, n_splits)
    return float(balanced_accuracy_score(y, pred)), pred


#: The share of the training signals held out at each end of the speed and load ranges to score
#: how a model extrapolates. A grid recipe's extreme level holds more (the small recipe: a
#: quarter of the speeds, a third of the loads) and is held out whole; a randomised recipe's
#: extreme value is one signal, which would score 0 or 1.
EXTRAPOLATION_SHARE = 0.1


def extreme_masks(
    values: np.ndarray, share: float = EXTRAPOLATION_SHARE
) -> tuple[np.ndarray, np.ndarray]:
    """The signals at the top and at the bottom of one operating variable.

    Parameters
    ----------
    values : numpy.ndarray
        The variable per signal (shaft speed [rpm] or radial load [N]).
    share : float
        The least share held out at each end: every signal at or above the ``1 - share``
        quantile, and at or below the ``share`` quantile (a grid's whole extreme level).

    Returns
    -------
    tuple of numpy.ndarray
        Boolean masks (top, bottom).
    """
    values = np.asarray(values, dtype=float)
    top = values >= np.quantile(values, 1.0 - share) - 1e-9
    bottom = values <= np.quantile(values, share) + 1e-9
    return top, bottom


def _extrapolation_masks(frame: pd.DataFrame) -> list[tuple[str, np.ndarray]]:
    """Each end of the speed and load ranges a model is scored on, trained without it."""
    out = []
    for col in ("rpm", "radial_load_n"):
        masks = extreme_masks(frame[col].to_numpy())
        for side, test in zip(("above", "below"), masks, strict=True):
            if test.all() or not test.any():
                continue
            out.append((f"{col}_{side}_training", test))
    return out


def class_kinds(frame: pd.DataFrame) -> dict[str, str]:
    """What each label of a dataset is: ``none``, ``waviness``, ``localized`` or ``mixed``.

    From the ``defect_kind`` column (empty without one): ``diagnose`` reads a class learnt
    from waviness as no local fault (:func:`cmtool.diagnose.model_label_verdict`).

    Parameters
    ----------
    frame : pandas.DataFrame
        A dataset (:func:`cmtool.datasets.read_dataset`).

    Returns
    -------
    dict of str to str
        Label -> kind of defect its signals carry.
    """
    if "defect_kind" not in frame.columns:
        return {}
    out = {}
    for label, kinds in frame.groupby("label")["defect_kind"]:
        values = sorted({str(k) for k in kinds})
        out[str(label)] = values[0] if len(values) == 1 else "mixed"
    return out


def training_ranges(frame: pd.DataFrame) -> dict[str, list]:
    """What a model saw: shaft speeds [rpm], sample rates [Hz] (lowest, highest), bearings.

    ``diagnose`` says when a record lies outside them (:func:`cmtool.diagnose.outside_training`).

    Parameters
    ----------
    frame : pandas.DataFrame
        The training dataset.

    Returns
    -------
    dict of str to list
        ``rpm`` [rev/min] and ``fs_hz`` [Hz] as [lowest, highest], and the ``bearings``' names,
        each where the dataset has the column.
    """
    out: dict[str, list] = {}
    for column in ("rpm", "fs_hz"):
        if column in frame.columns:
            values = frame[column].astype(float)
            out[column] = [float(values.min()), float(values.max())]
    if "bearing" in frame.columns:
        out["bearings"] = sorted({str(b) for b in frame["bearing"]})
    return out


def pooled_calibration(
    frame: pd.DataFrame,
    X: pd.DataFrame,
    y: np.ndarray,
    groups: np.ndarray,
    estimator: Any,
    n_splits: int,
    left_out: pd.DataFrame | None = None,
    X_left_out: pd.DataFrame | None = None,
    *,
    rule: list[dict[str, float]],
    out_of_fold: tuple[np.ndarray, np.ndarray | None] | None = None,
) -> dict | None:
    """Calibration of ``diagnose``'s pooled verdict (rule + this model) on the training data.

    The model's out-of-fold probabilities (grouped folds, as in training; the signals left
    out of training, faults too faint to learn from, scored by every fold's model and
    averaged) are pooled with the rule detector's probabilities of the same signals
    (``cmtool.diagnose``); the pooled verdict's probability is mapped to P(the verdict is
    right) by a logistic in its log-odds. The left-out signals count: a diagnosis meets
    them too, and without them the calibration is over-confident. None when every pooled
    verdict is right (or every one wrong): nothing to fit. ``rule`` holds the rule detector's
    probabilities (``cmtool.diagnose.rule_probabilities``) of ``frame``'s rows, then of
    ``left_out``'s (:func:`_table_and_rule` computes them with the features).
    ``out_of_fold``: the model's out-of-fold probabilities of ``frame``'s rows and the
    left-out signals' fold average, where :func:`train`'s cross-validation already has
    them (the same folds and estimator, so the same figures); None fits the folds here.

    Parameters
    ----------
    frame : pandas.DataFrame
        The training signals kept (labels in ``label``).
    X : pandas.DataFrame
        Their feature table.
    y : ndarray
        Their labels.
    groups : ndarray
        Their operating point (the folds' groups).
    estimator : estimator
        The scaler and classifier whose out-of-fold probabilities are pooled.
    n_splits : int
        Grouped folds.
    left_out, X_left_out : pandas.DataFrame, optional
        The signals left out of training (too faint) and their feature table.
    rule : list of dict of str to float
        The rule detector's probabilities of each signal (see above).
    out_of_fold : (ndarray, ndarray or None), optional
        The model's out-of-fold probabilities, where already computed (see above).

    Returns
    -------
    dict or None
        ``slope``, ``intercept``, ``signals``, and the expected calibration error (10 bins)
        before and after on these signals (``ece_pooled``, ``ece_calibrated``; in-sample).
    """
    from .diagnose import model_label_verdict, pool_probabilities

    kinds = class_kinds(frame)

    classes = np.array(sorted(set(y)))
    extra = 0 if left_out is None else len(left_out)
    if out_of_fold is None:
        _, proba, proba_left_out = _out_of_fold(
            X, y, groups, estimator, n_splits, probabilities=True, X_extra=X_left_out
        )
    else:
        proba, proba_left_out = out_of_fold
    if extra:
        frame = pd.concat([frame, left_out], ignore_index=True)
        proba = np.vstack([proba, proba_left_out])
    if len(rule) != len(frame):
        raise ValueError(
            f"rule holds {len(rule)} probabilities for {len(frame)} signals (the kept ones, "
            "then the left-out ones)"
        )
    top, right = [], []
    for i, label in enumerate(frame["label"]):
        pooled = pool_probabilities(rule[i], dict(zip(classes, proba[i], strict=True)), kinds)
        verdict = max(pooled, key=pooled.get)
        top.append(pooled[verdict])
        right.append(verdict == model_label_verdict(str(label), kinds))
    top, right = np.clip(np.array(top), 1e-9, 1 - 1e-9), np.array(right)
    if right.all() or not right.any():
        return None
    logit = np.log(top / (1.0 - top)).reshape(-1, 1)
    fit = LogisticRegression(C=1e6).fit(logit, right)
    calibrated = fit.predict_proba(logit)[:, 1]
    return {
        "slope": float(fit.coef_[0, 0]),
        "intercept": float(fit.intercept_[0]),
        "signals": int(right.size),
        "ece_pooled": expected_calibration_error(top, right),
        "ece_calibrated": expected_calibration_error(calibrated, right),
    }


def expected_calibration_error(
    confidence: np.ndarray, correct: np.ndarray, bins: int = 10
) -> float:
    """Mean |accuracy - confidence| over equal-width confidence bins, weighted by count.

    Parameters
    ----------
    confidence : ndarray
        Stated confidences in [0, 1].
    correct : ndarray of bool
        Whether each answer was right.
    bins : int
        Equal-width bins over [0, 1].

    Returns
    -------
    float
        The expected calibration error (0: calibrated).
    """
    edges = np.linspace(0.0, 1.0, bins + 1)
    index = np.clip(np.digitize(confidence, edges) - 1, 0, bins - 1)
    total = 0.0
    for b in range(bins):
        inside = index == b
        if inside.any():
            total += inside.mean() * abs(correct[inside].mean() - confidence[inside].mean())
    return float(total)


def train(
    frame: pd.DataFrame,
    *,
    recipe: str = "",
    random_state: int = 0,
    n_splits: int | None = None,
    feature_set: str = DEFAULT_FEATURE_SET,
    min_fault_snr_db: float | None = MIN_FAULT_SNR_DB,
    classifier: str | None = FROM_RECIPE,
    workers: int = 1,
    progress: Progress | None = None,
) -> dict[str, Any]:
    """Score the candidates with grouped cross-validation; keep ``classifier`` (or the best).

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
        Grouped folds, 2 .. the number of operating points (default: min(5, that number)).
    feature_set : str
        Features used (``features.FEATURE_SETS``); the default ``evidence+scale-free`` carried
        over best between simulated rigs and holds nothing in the signal's unit (any sensor
        gain or unit).
    min_fault_snr_db : float or None
        Faulty signals with a ``fault_snr_db`` below this are left out [dB] (None: none);
        the count left out is in the bundle (``left_out``).
    classifier : str or None
        The candidate kept (``candidate_classifiers``); ``FROM_RECIPE`` (default): the one
        ``recipe`` names in ``[training] classifier``, else the best grouped-CV score, which
        None always keeps.
    workers : int
        Processes, at least 1, for every signal's features and the rule detector's evidence
        for the pooled calibration (one ``fault_evidence`` serves both), then for the model
        fits, each on one thread (:mod:`cmtool.fits`); the bundle is the same for any count.
    progress : callable, optional
        ``progress(stage, done, total)`` after each chunk of signals (``stage``: ``"features
        and rule evidence"``), then after each model fit (``"model fits"``).

    Returns
    -------
    dict
        The model bundle: ``pipeline`` (FeatureExtractor + scaler + best classifier, fitted on
        all data), ``classes``, ``feature_names``, ``scores`` (grouped-CV balanced accuracy,
        the mean of the per-class recalls, of every candidate), ``best`` (the one kept),
        ``extrapolation`` (accuracy of the kept classifier at each end of the speed and load
        ranges, trained without it: :func:`extreme_masks`), ``recipe``, ``versions``,
        ``pooled_calibration`` (:func:`pooled_calibration`) and ``class_kinds``
        (:func:`class_kinds`).
    """
    if min_fault_snr_db is not None and not math.isfinite(min_fault_snr_db):
        raise ValueError(f"min_fault_snr_db = {min_fault_snr_db!r} is not a finite number [dB]")
    if isinstance(random_state, bool) or not 0 <= int(random_state) <= 2**32 - 1:
        raise ValueError(
            f"random_state = {random_state!r} is outside the allowed range [0, 2**32 - 1]"
        )
    workers = checked_workers(workers)
    frame = checked_frame(frame, "frame", TRAINING_COLUMNS, "cmtool.datasets.read_dataset")
    check_record_lengths(frame)
    kept = visible_faults(frame, min_fault_snr_db)
    left_out = int((~kept).sum())
    faint = frame[~kept.to_numpy()].reset_index(drop=True)
    frame = frame[kept.to_numpy()].reset_index(drop=True)
    labels = sorted(frame["label"].astype(str).unique())
    if len(labels) < 2:  # refused before the features are computed
        raise ValueError(
            f"the dataset's signals kept for training have {len(labels)} label(s) "
            f"({', '.join(labels) or 'none'}; {left_out} faint faults left out by "
            f"min_fault_snr_db = {min_fault_snr_db}): a classifier needs at least two"
        )
    groups = frame["operating_point_id"].to_numpy()
    n_groups = len(np.unique(groups))
    if n_groups < 2:
        raise ValueError("the dataset has one operating point: grouped validation needs two")
    if n_splits is None:
        n_splits = min(5, n_groups)
    else:  # folds by operating point: at least two, at most one point each
        n_splits = check_int("n_splits", n_splits, low=2, high=n_groups)
    if classifier == FROM_RECIPE:
        classifier = recipe_classifier(recipe)
    candidates = candidate_classifiers(random_state)
    if classifier is not None and classifier not in candidates:
        raise ValueError(
            f"classifier = {classifier!r} is not one of {sorted(candidates)} (or None: the "
            "best grouped cross-validation score)"
        )
    # one pass computes every signal's features and the rule's evidence for the calibration
    # (kept signals first, then the faint ones, as pooled_calibration orders them)
    table, names, rule = _table_and_rule(
        pd.concat([frame, faint], ignore_index=True) if len(faint) else frame,
        feature_set,
        workers=workers,
        progress=progress,
    )
    X, X_faint = table[: len(frame)], (table[len(frame) :] if len(faint) else None)
    y = frame["label"].astype(str).to_numpy()
    # every model fit, in ``workers`` processes on one thread each (cmtool.fits): each
    # candidate on each grouped fold (the probabilities for the calibration from the same
    # fits, of each candidate that may be kept), then the kept one without each end of the
    # speed and load ranges and on everything
    folds = list(GroupKFold(n_splits=n_splits).split(X, y, groups))
    masks = _extrapolation_masks(frame)
    total = len(candidates) * len(folds) + len(masks) + 1
    calls = []
    for name, clf in candidates.items():
        keepable = classifier in (None, name)
        est = make_pipeline(StandardScaler(), clf)
        calls += _fold_calls(X, y, folds, est, keepable, X_faint)
    results = run_fits(calls, workers, progress, total=total)
    scores, cv_predictions, probabilities = {}, {}, {}
    for i, name in enumerate(candidates):
        mine = results[i * len(folds) : (i + 1) * len(folds)]
        pred, proba, proba_faint = _assemble_folds(
            y, folds, mine, classifier in (None, name), X_faint
        )
        scores[name] = float(balanced_accuracy_score(y, pred))
        cv_predictions[name], probabilities[name] = pred, (proba, proba_faint)
    best = classifier if classifier is not None else max(scores, key=scores.get)
    head = make_pipeline(StandardScaler(), candidate_classifiers(random_state)[best])
    calibration = pooled_calibration(
        frame,
        X,
        y,
        groups,
        head,
        n_splits,
        faint if len(faint) else None,
        X_faint,
        rule=rule,
        out_of_fold=probabilities[best],
    )
    pipeline = make_classifier(best, random_state=random_state, feature_set=feature_set)
    # the feature step is stateless: fit it, then fit the rest on the precomputed table
    pipeline.steps[0][1].fit(frame)
    scaled = pipeline.steps[1][1].fit(X).transform(X)
    calls = [(held_out_accuracy, (head, X, y, test)) for _, test in masks]
    calls.append((fit_single_threaded, (pipeline.steps[2][1], scaled, y)))
    *held_out, fitted = run_fits(calls, workers, progress, done=total - len(calls), total=total)
    extrapolation = dict(zip([key for key, _ in masks], held_out, strict=True))
    pipeline.steps[2] = (pipeline.steps[2][0], fitted)
    return {
        "format": MODEL_FORMAT,
        "training_fingerprint": dataset_fingerprint(frame),
        "training_signals": sorted(signal_hashes(frame)),
        "pipeline": pipeline,
        "classes": sorted(set(y)),
        "feature_names": names,
        "scores": scores,
        "best": best,
        "n_splits": n_splits,
        "extrapolation": extrapolation,
        "recipe": recipe,
        "feature_set": feature_set,
        "left_out": left_out,
        "min_fault_snr_db": min_fault_snr_db,
        "signal_duration_s": float(np.median(frame["duration_s"]))
        if "duration_s" in frame.columns
        else None,
        "pooled_calibration": calibration,
        "class_kinds": class_kinds(frame),
        "training_ranges": training_ranges(frame),
        "cv_labels": y.tolist(),
        "cv_predictions": cv_predictions[best].tolist(),
        "versions": {
            "cmtool": __version__,
            "sklearn": sklearn.__version__,
            "numpy": np.__version__,
        },
    }


def evaluate(
    bundle: dict[str, Any],
    frame: pd.DataFrame,
    *,
    workers: int = 1,
    progress: Progress | None = None,
) -> dict[str, Any]:
    """Accuracy, per-class precision/recall and the confusion matrix of a model on a dataset.

    A dataset of several bearings (rigs) is also scored per bearing (``by_rig``: signals,
    accuracy and each class's recall), so that one rig's accuracy does not hide in
    another's.

    Parameters
    ----------
    bundle : dict
        A model bundle (:func:`train`, ``cmtool.model_files.load_model``).
    frame : pandas.DataFrame
        The dataset scored (labels in ``label``).
    workers : int
        Processes that extract the features, at least 1 (the result is the same for any
        count).
    progress : callable, optional
        ``progress(stage, done, total)``, called after each chunk of signals.

    Returns
    -------
    dict
        ``accuracy``, ``labels``, ``confusion`` (rows: true labels, columns: predicted, in
        the order of ``labels``), ``per_class`` precision, recall and F1, ``predictions``
        and ``by_rig``.
    """
    workers = checked_workers(workers)
    check_record_lengths(frame)
    y = frame["label"].astype(str).to_numpy()
    pipeline = bundle["pipeline"]
    extractor = copy.copy(pipeline[0])  # the bundle's own extractor is left as it came
    extractor.n_jobs = workers
    table = transform_in_chunks(extractor, frame, "features", progress)
    pred = pipeline[1:].predict(table)
    learnt = getattr(pipeline[-1], "classes_", [])  # a class absent here: a column of zeros
    labels = sorted(set(y) | set(pred) | {str(c) for c in learnt})
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
        "by_rig": scores_by_rig(
            frame["bearing"] if "bearing" in frame else None, y, pred, labels=labels
        ),
    }


def scores_by_rig(
    bearings: Any,
    truth: np.ndarray,
    predicted: np.ndarray,
    *,
    labels: list[str] | None = None,
) -> dict[str, dict]:
    """Per bearing (rig) of signals from several: signals, accuracy and each class's recall.

    Parameters
    ----------
    bearings : array_like of str, or None
        Each signal's bearing.
    truth, predicted : ndarray
        Each signal's label and the model's.
    labels : list of str, optional
        With them, each bearing's ``confusion`` matrix too (rows true, columns predicted, in
        this order).

    Returns
    -------
    dict of str to dict
        Per bearing: ``signals``, ``accuracy``, ``recall`` (per true class) and, with
        ``labels``, ``confusion``; {} when the signals come from one bearing (or none is
        given): the totals say it all.
    """
    if bearings is None:
        return {}
    rigs = np.asarray(bearings).astype(str)
    if len(set(rigs)) < 2:
        return {}
    truth, predicted = np.asarray(truth), np.asarray(predicted)
    out = {}
    for rig in sorted(set(rigs)):
        mine = rigs == rig
        truth_rig, said = truth[mine], predicted[mine]
        out[rig] = {
            "signals": int(mine.sum()),
            "accuracy": float(np.mean(truth_rig == said)),
            "recall": {
                c: float(np.mean(said[truth_rig == c] == c)) for c in sorted(set(truth_rig))
            },
        }
        if labels is not None:
            matrix = confusion_matrix(truth_rig, said, labels=labels)
            out[rig]["confusion"] = matrix.tolist()
    return out
