"""``cmtool realism``: how well a classifier tells a simulated dataset from measured recordings.

The realism gauge of issue 17. The recordings (a folder with a ``MANIFEST.csv``, the layout of
``../shared/data``) are cut into segments as long as the dataset's signals; every segment and
every simulated signal gets the scale-free features (no feature in the signal's unit: a
sensor's gain or unit gives nothing away) computed with its own bearing's rates; a random
forest learns "measured or simulated" under cross-validation grouped by recording (no
recording has segments on both sides of a split; each simulated signal is its own group). The
out-of-fold ROC AUC is the gauge: 0.5 means the two cannot be told apart, 1.0 that every
recording is recognised. The features the forest leans on most are what gives the simulation
away.

The gauge judges signals, not operating points: features that only repeat the context (the
shaft frequency in Hz, ``CONTEXT_UNITS``) are left out, or the forest would tell a recipe's
speed grid from the recordings' speeds however real the signals look.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from generators import BearingFrequencies, characteristic_frequencies
from generators import bearing as catalog_bearing

from .bench import CANONICAL
from .inputs import check_record_lengths, checked_frame
from .manifest import read_manifest
from .speeds import manifest_record

__all__ = [
    "realism",
    "recording_segments",
    "plot_realism",
    "context_columns",
    "feature_difference",
    "CONTEXT_UNITS",
    "REALISM_TREES",
    "SIMULATED_RANGE",
]

#: Trees of each of the gauge's random forests (one per fold and one for the importances).
REALISM_TREES = 300

#: Units of the features that repeat a signal's context instead of measuring the signal
#: (``features.feature_units``): the gauge leaves them out.
CONTEXT_UNITS = frozenset({"Hz"})


def context_columns(frequencies: BearingFrequencies, fs: float) -> dict[str, float]:
    """The feature extractor's context columns of a signal (``features.CONTEXT_COLUMNS``).

    Parameters
    ----------
    frequencies : generators.BearingFrequencies
        The bearing's characteristic frequencies at the signal's speed [Hz].
    fs : float
        Sample rate [Hz].

    Returns
    -------
    dict of str to float
        ``fs_hz`` and each rate's column [Hz].
    """
    f = frequencies
    return {
        "fs_hz": float(fs),
        "shaft_frequency_hz": f.shaft,
        "ftf_hz": f.ftf,
        "bpfo_hz": f.bpfo,
        "bpfi_hz": f.bpfi,
        "bsf_hz": f.bsf,
        "two_bsf_hz": f.two_bsf,
    }


def recording_segments(folder: str | Path, duration_s: float) -> pd.DataFrame:
    """The recordings of a manifest folder cut into segments of ``duration_s`` [s].

    Parameters
    ----------
    folder : str or Path
        Holds ``MANIFEST.csv`` (``file``, ``sampling_rate_hz``, ``shaft_rpm``, and ``bearing``
        or ``dataset``) and the files.
    duration_s : float
        Segment length [s] (a recording shorter than one segment is used whole).

    Returns
    -------
    DataFrame
        One row per segment: ``signal``, ``group`` (the file), ``rig`` (the manifest's
        ``dataset`` column, else the bearing), ``label`` (its ``fault_location`` as a verdict
        name, ``unknown`` without one), and the context columns of the feature extractor
        (``fs_hz``, ``shaft_frequency_hz``, ``ftf_hz``, ``bpfo_hz``, ``bpfi_hz``, ``bsf_hz``,
        ``two_bsf_hz``).
    """
    rows = []
    for entry in read_manifest(folder):
        x, rpm = manifest_record(entry)  # the tacho's speed where the entry names one
        fs = entry.fs_hz
        geometry = entry.geometry or catalog_bearing(entry.bearing)
        f = characteristic_frequencies(geometry, rpm / 60)
        n = max(1, int(round(duration_s * fs)))
        count = max(1, x.size // n)
        for i in range(count):
            segment = x[i * n : (i + 1) * n] if x.size >= n else x
            rows.append(
                {
                    "signal": segment,
                    "group": entry.file,
                    "rig": entry.rig,
                    "label": entry.label,
                    **context_columns(f, fs),
                }
            )
    return pd.DataFrame(rows)


def realism(
    simulated: pd.DataFrame,
    measured: pd.DataFrame,
    *,
    feature_set: str = "scale-free",
    random_state: int = 0,
    n_jobs: int | None = None,
    progress: Callable[[str, int, int], None] | None = None,
    n_estimators: int = REALISM_TREES,
) -> dict[str, Any]:
    """ROC AUC of telling ``measured`` segments from ``simulated`` signals, and why.

    Parameters
    ----------
    simulated : DataFrame
        A dataset (``cmtool.datasets.read_dataset``).
    measured : DataFrame
        Segments (:func:`recording_segments`): ``signal``, ``group`` and the context columns.
    feature_set : str
        ``features.FEATURE_SETS`` (scale-free by default: nothing in the signal's unit).
    random_state : int
        Seed of the forest.
    n_jobs : int, optional
        Worker processes (joblib's count: -1 all cores) of the feature extraction and of the
        forests' fits; None: one, this one.
    progress : callable, optional
        ``progress(stage, done, total)`` after each chunk of signals whose features are done.
    n_estimators : int
        Trees of each forest (``REALISM_TREES`` by default): fewer are faster and leave the
        AUC and the features' importances noisier.

    Returns
    -------
    dict
        ``auc``, ``folds``, ``trees`` (``n_estimators``), ``recordings``, ``segments``,
        ``simulated``, ``roc`` (false and true positive rates), ``features`` (name,
        importance) most telling first,
        ``differences`` (the same order: each feature's importance, unit and
        :func:`feature_difference`, which way measured and simulated differ),
        ``context_left_out`` (features that only repeat the context, not used), the
        out-of-fold ``scores`` and ``auc_by``: for each of the measured segments' ``rig`` and
        ``label`` columns that takes several values, the AUC of the same out-of-fold scores
        with only that value's segments against every simulated signal, or for a class
        against the simulated signals of the same class when there are any (like with like:
        real healthy bearings against simulated healthy ones), with the counts and what they
        were compared with (``against``: ``all`` or ``same class``; issue 17: per rig and per
        class) and, per class, ``differences``: the ``CLASS_DIFFERENCES`` features whose
        values tell that class's measured segments from its simulated signals best (each
        feature's own ROC AUC farthest from 0.5; :func:`feature_difference`).
    """
    from joblib import effective_n_jobs
    from sklearn.ensemble import RandomForestClassifier
    from sklearn.metrics import roc_auc_score, roc_curve
    from sklearn.model_selection import GroupKFold

    from features import FeatureExtractor, feature_units

    from .classifier import transform_in_chunks
    from .fits import fit_single_threaded, fold_fit, run_fits

    if isinstance(n_estimators, bool) or not isinstance(n_estimators, int) or n_estimators < 1:
        raise ValueError(f"n_estimators = {n_estimators!r} is outside the allowed range [1, inf)")
    checked_frame(simulated, "simulated", ("signal", "fs_hz"), "cmtool.datasets.read_dataset")
    checked_frame(measured, "measured", ("signal", "group", "fs_hz"), "recording_segments")
    check_record_lengths(simulated, "simulated")
    check_record_lengths(measured, "measured")
    groups_measured = measured["group"].astype(str).to_numpy()
    recordings = len(set(groups_measured))
    if recordings < 2:
        raise ValueError(
            f"{recordings} recording: a recording-level split needs at least two recordings"
        )
    columns = ["signal", "fs_hz", "shaft_frequency_hz", "ftf_hz", "bpfo_hz", "bpfi_hz"]
    columns += ["bsf_hz", "two_bsf_hz"]
    both = pd.concat([simulated[columns], measured[columns]], ignore_index=True)
    extractor = FeatureExtractor(feature_set=feature_set, n_jobs=n_jobs).fit(both)
    units = feature_units(extractor.faults, extractor.n_harmonics)
    names = list(extractor.get_feature_names_out())
    keep = [i for i, name in enumerate(names) if units.get(name) not in CONTEXT_UNITS]
    left_out = [name for name in names if units.get(name) in CONTEXT_UNITS]
    X = transform_in_chunks(extractor, both, "features", progress)[:, keep]
    names = [names[i] for i in keep]
    y = np.r_[np.zeros(len(simulated)), np.ones(len(measured))]
    groups = np.r_[[f"sim-{i}" for i in range(len(simulated))], groups_measured]
    folds = min(5, recordings)
    forest = RandomForestClassifier(
        n_estimators=n_estimators, class_weight="balanced", random_state=random_state
    )
    # each fold's forest and the one on everything (the features' importances), in n_jobs
    # processes on one thread each (cmtool.fits: the same forests, faster on a few hundred
    # signals than a forest's own threads)
    splits = list(GroupKFold(n_splits=folds).split(X, y, groups))
    calls = [(fold_fit, (forest, X, y, train, test, True, None)) for train, test in splits]
    calls.append((fit_single_threaded, (forest, X, y)))
    workers = 1 if n_jobs is None else effective_n_jobs(n_jobs)
    *fitted_folds, forest = run_fits(calls, workers)
    scores = np.zeros(len(y))
    for (_, test), (_, proba, _, _) in zip(splits, fitted_folds, strict=True):
        scores[test] = proba[:, 1]
    auc = float(roc_auc_score(y, scores))
    fpr, tpr, _ = roc_curve(y, scores)
    auc_by: dict[str, dict[str, dict[str, Any]]] = {}
    simulated_scores = scores[: len(simulated)]
    simulated_labels = (
        simulated["label"].astype(str).map(lambda v: CANONICAL.get(v, v)).to_numpy()
        if "label" in simulated
        else np.full(len(simulated), "")
    )
    for column in ("rig", "label"):
        if column not in measured or measured[column].nunique() < 2:
            continue
        values = measured[column].astype(str).to_numpy()
        auc_by[column] = {}
        for value in sorted(set(values)):
            rows = values == value
            mine = scores[len(simulated) :][rows]
            same = simulated_labels == value
            against = "same class" if column == "label" and same.any() else "all"
            theirs = simulated_scores[same] if against == "same class" else simulated_scores
            auc_by[column][value] = {
                "auc": float(
                    roc_auc_score(
                        np.r_[np.zeros(theirs.size), np.ones(mine.size)], np.r_[theirs, mine]
                    )
                ),
                "segments": int(mine.size),
                "simulated": int(theirs.size),
                "against": against,
            }
            if column == "label":
                sim_rows = same if against == "same class" else np.ones(same.size, dtype=bool)
                measured_rows = X[len(simulated) :][rows]
                telling = [
                    {
                        "feature": name,
                        **feature_difference(X[: len(simulated)][sim_rows, j], measured_rows[:, j]),
                        "unit": units.get(name, ""),
                    }
                    for j, name in enumerate(names)
                ]
                telling.sort(key=lambda d: -abs(d["auc"] - 0.5))
                auc_by[column][value]["differences"] = telling[:CLASS_DIFFERENCES]
    ranked = sorted(zip(names, forest.feature_importances_, strict=True), key=lambda item: -item[1])
    column = {name: j for j, name in enumerate(names)}
    differences = [
        {
            "feature": name,
            "importance": float(value),
            **feature_difference(X[y == 0, column[name]], X[y == 1, column[name]]),
            "unit": units.get(name, ""),
        }
        for name, value in ranked
    ]
    return {
        "auc": auc,
        "folds": folds,
        "trees": n_estimators,
        "recordings": recordings,
        "segments": int(len(measured)),
        "simulated": int(len(simulated)),
        "feature_set": feature_set,
        "context_left_out": left_out,
        "roc": {"false_positive_rate": fpr.tolist(), "true_positive_rate": tpr.tolist()},
        "features": [(name, float(value)) for name, value in ranked],
        "differences": differences,
        "scores": scores.tolist(),
        "auc_by": auc_by,
    }


#: Features listed per class in ``auc_by`` (those that tell the class's measured segments
#: from its simulated signals best).
CLASS_DIFFERENCES = 5

#: Quantiles [-] of the simulated values that bound "the simulated range" of a feature.
SIMULATED_RANGE = (0.01, 0.99)


def feature_difference(simulated: np.ndarray, measured: np.ndarray) -> dict[str, Any]:
    """Which way one feature differs between simulated signals and measured segments.

    Parameters
    ----------
    simulated, measured : numpy.ndarray, 1-D
        The feature's values [its unit] on the simulated signals and the measured segments.

    Returns
    -------
    dict
        ``simulated_median`` and ``measured_median`` [the feature's unit];
        ``simulated_range`` (its ``SIMULATED_RANGE`` quantiles); ``measured_below_range`` and
        ``measured_above_range``, the shares of measured segments outside it [-] (what no
        amount of reweighting the recipe's draws can reach: its ranges must widen or its
        physics change); ``auc``, the feature's own ROC AUC for "measured" [-] (0.5: alike,
        above 0.5: measured higher, below: lower); ``direction``, ``"measured higher"``,
        ``"measured lower"`` or ``"alike"`` (AUC within 0.4-0.6).
    """
    from scipy.stats import mannwhitneyu

    simulated = np.asarray(simulated, dtype=float)
    measured = np.asarray(measured, dtype=float)
    low, high = np.quantile(simulated, SIMULATED_RANGE)
    u = mannwhitneyu(measured, simulated, alternative="two-sided").statistic
    auc = float(u / (measured.size * simulated.size))
    direction = "measured higher" if auc > 0.6 else "measured lower" if auc < 0.4 else "alike"
    return {
        "simulated_median": float(np.median(simulated)),
        "measured_median": float(np.median(measured)),
        "simulated_range": [float(low), float(high)],
        "measured_below_range": float(np.mean(measured < low)),
        "measured_above_range": float(np.mean(measured > high)),
        "auc": auc,
        "direction": direction,
    }


def plot_realism(result: dict[str, Any], path: str | Path, *, top: int = 12) -> Path:
    """ROC curve of the gauge and the features that give the simulation away (PNG).

    The features' bars are coloured by which way the measured segments lie
    (:func:`feature_difference`: measured higher, lower, or alike).

    Parameters
    ----------
    result : dict
        :func:`realism`'s result.
    path : str or Path
        The PNG written.
    top : int
        How many features to show.

    Returns
    -------
    Path
    """
    from .plots import plt, save_figure

    path = Path(path)
    fig, (roc, bars) = plt.subplots(1, 2, figsize=(12, 4.8), width_ratios=(1, 1.4))
    roc.plot(result["roc"]["false_positive_rate"], result["roc"]["true_positive_rate"], lw=2)
    roc.plot([0, 1], [0, 1], "k--", lw=1, label="indistinguishable (AUC 0.5)")
    roc.set(
        xlabel="simulated signals taken for measured",
        ylabel="measured segments recognised",
        title=f"measured vs simulated: ROC AUC {result['auc']:.3f}",
    )
    roc.legend(loc="lower right")
    names = [n for n, _ in result["features"][:top]][::-1]
    values = [v for _, v in result["features"][:top]][::-1]
    way = {d["feature"]: d["direction"] for d in result.get("differences", [])}
    colours = {"measured higher": "tab:red", "measured lower": "tab:blue", "alike": "tab:gray"}
    bars.barh(names, values, color=[colours[way.get(n, "alike")] for n in names])
    for label, colour in colours.items():
        bars.barh([], [], color=colour, label=label)
    bars.legend(loc="lower right", fontsize=8)
    bars.set(xlabel="importance (mean decrease in impurity)", title="what gives it away")
    bars.tick_params(axis="y", labelsize=8)
    fig.tight_layout()
    return save_figure(fig, path, dpi=110)
