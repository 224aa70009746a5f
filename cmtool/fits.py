"""The model fits of ``cmtool train``, spread over worker processes.

``train`` fits each candidate classifier once per grouped fold, then the kept one once per
end of the speed and load ranges and once on everything: 25 fits for five folds. A forest on
a few hundred signals is mostly scikit-learn's per-tree overhead, which its own threads
(``n_jobs=-1``) do not spread: on two cores they cost 30-85 % more CPU for the same wall time
(stop 89, docs/performance.md). So every fit here runs on one thread, and the fits, which are
independent, run in ``workers`` processes. A fit's trees do not depend on ``n_jobs``, so the
model is the same for any count of workers. (The candidates of :mod:`cmtool.classifier` are
made single-threaded anyway; a model given with threads gets them back after its fit.)
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from sklearn.base import clone

from features.transformer import WarningRelay, keeping_warnings

#: ``progress(stage, done, total)``, as :mod:`cmtool.classifier` reports.
Progress = Callable[[str, int, int], None]

#: The stage :func:`run_fits` reports to ``progress``.
FIT_STAGE = "model fits"


def single_threaded(estimator: Any) -> Any:
    """An unfitted copy of ``estimator`` whose every ``n_jobs`` parameter that is set is 1.

    Parameters
    ----------
    estimator : estimator
        A scikit-learn estimator or pipeline.

    Returns
    -------
    estimator
        The copy (``estimator`` itself is left as it came).
    """
    copy = clone(estimator)
    one = {key: 1 for key in _n_jobs(copy)}
    return copy.set_params(**one) if one else copy


def _n_jobs(estimator: Any) -> dict[str, Any]:
    """The ``n_jobs`` parameters of ``estimator`` (and its steps) that ask for threads.

    Those left at None are not listed: ``LogisticRegression`` warns that its own does
    nothing since scikit-learn 1.8 when one is given.
    """
    return {
        key: value
        for key, value in estimator.get_params().items()
        if (key == "n_jobs" or key.endswith("__n_jobs")) and value not in (None, 1)
    }


def fit_single_threaded(estimator: Any, X: np.ndarray, y: np.ndarray) -> Any:
    """``estimator`` fitted on one thread, then given back its own ``n_jobs`` (for predicting).

    Parameters
    ----------
    estimator : estimator
        An unfitted scikit-learn estimator or pipeline (cloned, not changed).
    X : ndarray
        The feature table, a row per signal.
    y : ndarray
        The labels.

    Returns
    -------
    estimator
        The fitted copy, with ``estimator``'s ``n_jobs`` settings.
    """
    jobs = _n_jobs(estimator)
    fitted = single_threaded(estimator).fit(X, y)
    return fitted.set_params(**jobs) if jobs else fitted


def fold_fit(
    estimator: Any,
    X: np.ndarray,
    y: np.ndarray,
    train_index: np.ndarray,
    test_index: np.ndarray,
    probabilities: bool,
    X_extra: np.ndarray | None,
) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None, np.ndarray]:
    """One grouped fold: fit on ``train_index``, predict ``test_index`` (and ``X_extra``).

    Parameters
    ----------
    estimator : estimator
        The unfitted estimator (cloned, on one thread).
    X, y : ndarray
        Every signal's features and label.
    train_index, test_index : ndarray
        The fold's rows.
    probabilities : bool
        Also the class probabilities of the test rows and of ``X_extra``.
    X_extra : ndarray or None
        Signals in no fold, scored by this fold's model when ``probabilities``.

    Returns
    -------
    predicted : ndarray
        The test rows' labels.
    proba, proba_extra : ndarray or None
        Their class probabilities and ``X_extra``'s (columns: ``classes``).
    classes : ndarray
        The classes the fold's model saw.
    """
    model = single_threaded(estimator).fit(X[train_index], y[train_index])
    predicted = model.predict(X[test_index])
    if not probabilities:
        return predicted, None, None, model.classes_
    extra = None
    if X_extra is not None and len(X_extra):
        extra = model.predict_proba(X_extra)
    return predicted, model.predict_proba(X[test_index]), extra, model.classes_


def held_out_accuracy(estimator: Any, X: np.ndarray, y: np.ndarray, test: np.ndarray) -> float:
    """Accuracy on the rows ``test`` of a model fitted on the others (one thread).

    Parameters
    ----------
    estimator : estimator
        The unfitted estimator.
    X, y : ndarray
        Every signal's features and label.
    test : ndarray of bool
        The rows held out.

    Returns
    -------
    float
        The share of the held-out rows predicted right.
    """
    model = single_threaded(estimator).fit(X[~test], y[~test])
    return float(np.mean(model.predict(X[test]) == y[test]))


def run_fits(
    calls: Sequence[tuple[Callable[..., Any], tuple]],
    workers: int = 1,
    progress: Progress | None = None,
    *,
    done: int = 0,
    total: int | None = None,
) -> list:
    """``function(*args)`` for each of ``calls``, in ``workers`` processes; results in order.

    Warnings raised in a worker are raised here, each once. ``progress(FIT_STAGE, done,
    total)`` after each call (counting from ``done``, of ``total``: several batches can share
    one bar).

    Parameters
    ----------
    calls : sequence of (callable, tuple)
        The functions (importable: a worker imports them) and their arguments.
    workers : int
        Processes; 1: one after the other, here.
    progress : callable, optional
        The progress report.
    done : int
        Fits counted before this batch.
    total : int, optional
        Fits in all; default ``done + len(calls)``.

    Returns
    -------
    list
        What each call returned.
    """
    total = done + len(calls) if total is None else total
    out: list = []
    if workers <= 1 or len(calls) < 2:
        results = (function(*args) for function, args in calls)
        relay = None
    else:
        from joblib import Parallel, delayed

        parallel = Parallel(n_jobs=min(workers, len(calls)), return_as="generator")
        results = parallel(delayed(keeping_warnings)(function, *args) for function, args in calls)
        relay = WarningRelay()
    for result in results:
        if relay is not None:
            result, caught = result
            relay(caught)
        out.append(result)
        if progress is not None:
            progress(FIT_STAGE, done + len(out), total)
    return out
