"""The feature table as a scikit-learn transformer (works inside a Pipeline)."""

from __future__ import annotations

import warnings
from collections.abc import Callable, Iterable, Iterator, Mapping
from typing import Any

import numpy as np
import pandas as pd
from sklearn.base import BaseEstimator, TransformerMixin
from sklearn.utils.validation import check_is_fitted, validate_data

from ._validate import FeatureError
from .evidence import EVIDENCE_NAMES, fault_evidence
from .table import DEFAULT_FAULTS, extract_features, feature_names, feature_units

__all__ = ["FeatureExtractor", "CONTEXT_COLUMNS", "FEATURE_SETS"]

#: ``all``: every feature; ``scale-free``: only those without the signal's unit (ratios in dB,
#: shape factors, kurtosis, relative kurtogram band): invariant to the sensor's gain and unit,
#: the set to use when a model trained on simulated signals meets measured ones.
#: ``envelope``: only the envelope-spectrum line-to-floor ratios at the fault rates and their
#: sidebands [dB], the evidence of envelope analysis: independent of the transfer path's
#: gain, of the background level (above the floor) and of how impulsive the impacts look,
#: which a model of one machine cannot know for another.
#: ``evidence``: the analyst's evidence for each local fault (``features.evidence``): envelope
#: lines of the random part (the machine's periodic components removed) in the band where a
#: fault rate shows most clearly, searched within the slip, with sidebands and the margin
#: over the detection threshold; ratios at the bearing's own rates only.
#: ``evidence+scale-free``: both; the set that carried over best between simulated rigs
#: (benchmarks/cross_domain.py: mean balanced accuracy 0.85 from the CWRU to the MFPT rig
#: recipe and back, against 0.79 for scale-free and 0.81 for evidence alone), the default of
#: ``cmtool train``.
FEATURE_SETS = ("all", "scale-free", "envelope", "evidence", "evidence+scale-free")

#: DataFrame columns that carry each signal's context (dataset schema, Hz).
CONTEXT_COLUMNS = {
    "fs": "fs_hz",
    "shaft": "shaft_frequency_hz",
    "ftf": "ftf_hz",
    "bpfo": "bpfo_hz",
    "bpfi": "bpfi_hz",
    "bsf": "bsf_hz",
    "two_bsf": "two_bsf_hz",
}


def feature_rows_with_evidence(
    items: Iterable[tuple[np.ndarray, Mapping[str, float]]],
    faults: tuple[str, ...],
    n_harmonics: int,
    names: list[str],
    keep_evidence: bool = True,
) -> tuple[list[list[float]], list]:
    """Feature rows of ``(signal, context)`` items, and each signal's ``fault_evidence``.

    Parameters
    ----------
    items : iterable of (ndarray, dict)
        Signals [U] with their context (``fs`` [Hz] and the rates of ``CONTEXT_COLUMNS`` [Hz]).
    faults : tuple of str
        Fault frequencies measured.
    n_harmonics : int
        Harmonics per fault.
    names : list of str
        The features of each row, in order.
    keep_evidence : bool
        Return each signal's :class:`features.Evidence` (what its ``evidence_*`` features
        come from; a caller that also weighs the rule detector's evidence, ``cmtool train``'s
        calibration, need not compute it again). False returns an empty list and holds no
        evidence (each holds the signal's random part and spectra).

    Returns
    -------
    rows : list of list of float
        One row per item.
    evidence : list of Evidence or None
        Per item (None when ``names`` holds no ``evidence_*`` feature); empty unless
        ``keep_evidence``.
    """
    out, found = [], []
    evidence = any(name.startswith("evidence_") for name in names)
    table = any(not name.startswith("evidence_") for name in names)
    for signal, ctx in items:
        feats: dict[str, float] = {}
        result = None
        if evidence:
            result = fault_evidence(signal, ctx["fs"], ctx)
            feats.update(result.features)
        if table:
            feats.update(
                extract_features(
                    signal, ctx["fs"], fault_frequencies=ctx, faults=faults, n_harmonics=n_harmonics
                )
            )
        out.append([feats[name] for name in names])
        if keep_evidence:
            found.append(result)
    return out, found


def _feature_rows(items, faults, n_harmonics, names):
    return feature_rows_with_evidence(items, faults, n_harmonics, names, keep_evidence=False)[0]


#: What a worker process sends back of one warning: its category and message.
CaughtWarning = tuple[type[Warning], str]


def keeping_warnings(function: Callable[..., Any], *args: Any) -> tuple[Any, list[CaughtWarning]]:
    """``function(*args)`` and the warnings it raised (category, message), in order.

    What a task run in a worker process returns, so that its warnings reach the caller
    (:class:`WarningRelay`) instead of being shown by each worker, out of reach of the
    caller's filters. The worker's own filters still apply (an ignored warning is not kept);
    a warning kept is not shown by the worker.

    Parameters
    ----------
    function : callable
        The task.
    *args : Any
        Its arguments.

    Returns
    -------
    result : Any
        What ``function`` returned.
    caught : list of (type, str)
        The warnings' categories and messages.

    Examples
    --------
    >>> import warnings
    >>> keeping_warnings(lambda v: warnings.warn(f"slow: {v}") or v, 3)
    (3, [(<class 'UserWarning'>, 'slow: 3')])
    """
    with warnings.catch_warnings(record=True) as caught:
        result = function(*args)
    return result, [(w.category, str(w.message)) for w in caught]


class WarningRelay:
    """Raises the warnings workers kept in this process, each category and message once."""

    def __init__(self) -> None:
        self._seen: set[CaughtWarning] = set()

    def __call__(self, caught: list[CaughtWarning]) -> None:
        """Warn of each of ``caught`` not yet warned of."""
        for category, message in caught:
            if (category, message) not in self._seen:
                self._seen.add((category, message))
                warnings.warn(message, category, stacklevel=2)


def map_in_processes(
    function: Callable[..., list], items: list, n_jobs: int | None, *args: Any
) -> list:
    """``function(part, *args)`` over ``items`` in ``n_jobs`` processes, results in order.

    ``function`` takes a list of items and returns one result per item; each process gets
    every ``n_jobs``-th item (round robin, so that costly items spread), and the results are
    put back in the items' order. A warning raised in a process is raised here, once
    (:func:`keeping_warnings`).

    Parameters
    ----------
    function : callable
        ``function(part, *args)``: one result per item of ``part``.
    items : list
        The items.
    n_jobs : int or None
        Processes (joblib's: -1 all cores); ``None`` or 1: in this process.
    *args : Any
        Further arguments of ``function``.

    Returns
    -------
    list
        The results, in the items' order.
    """
    if n_jobs in (None, 1) or len(items) < 2:
        return function(items, *args)
    from joblib import Parallel, delayed, effective_n_jobs

    jobs = effective_n_jobs(n_jobs)
    parts = Parallel(n_jobs=jobs)(
        delayed(keeping_warnings)(function, items[i::jobs], *args) for i in range(jobs)
    )
    out: list = [None] * len(items)
    relay = WarningRelay()
    for i, (part, caught) in enumerate(parts):
        relay(caught)
        out[i::jobs] = part
    return out


class FeatureExtractor(TransformerMixin, BaseEstimator):
    """Signals in, feature table out (``features.extract_features`` per signal).

    Input either

    * a DataFrame with a ``signal_column`` of 1-D arrays and the context columns
      ``fs_hz, shaft_frequency_hz, ftf_hz, bpfo_hz, bpfi_hz, two_bsf_hz`` (one value per row:
      signals of different speeds and sample rates mix freely), or
    * a 2-D array, one signal per row, with ``fs`` and ``fault_frequencies`` given here.

    Parameters
    ----------
    fs : float, optional
        Sample rate [Hz] for array input.
    fault_frequencies : mapping of str to float, optional
        Context for array input [Hz] (``ftf, bpfo, bpfi, two_bsf`` and ``shaft``).
    faults : tuple of str
        Fault frequencies measured.
    n_harmonics : int
        Harmonics per fault.
    signal_column : str
        Column of the signals in DataFrame input.
    n_jobs : int or None
        Worker processes for the transform (joblib; ``None`` or 1: in this process,
        -1: all cores). Signals are independent, so the table is the same for any value.
    feature_set : {"all", "scale-free", "envelope", "evidence", "evidence+scale-free"}
        Which features (``FEATURE_SETS``): every feature; those without the signal's unit
        (ratios, dB, kurtosis); the envelope lines' ratios to their floor [dB]; the rule's
        weighed evidence (``features.EVIDENCE_NAMES``); the last two together (the default
        of ``cmtool train``).
    """

    def __init__(
        self,
        fs: float | None = None,
        fault_frequencies: Mapping[str, float] | None = None,
        faults: tuple[str, ...] = DEFAULT_FAULTS,
        n_harmonics: int = 3,
        signal_column: str = "signal",
        n_jobs: int | None = None,
        feature_set: str = "all",
    ):
        self.n_jobs = n_jobs
        self.feature_set = feature_set
        self.fs = fs
        self.fault_frequencies = fault_frequencies
        self.faults = faults
        self.n_harmonics = n_harmonics
        self.signal_column = signal_column

    def signals_with_context(
        self, X: pd.DataFrame | np.ndarray
    ) -> Iterator[tuple[np.ndarray, dict[str, float]]]:
        """Each signal of ``X`` with its context, in order, as ``transform`` reads them.

        Parameters
        ----------
        X : pandas.DataFrame or array_like, shape (n_signals, n_samples)
            The signals [any unit] and, in a DataFrame, the context columns
            (``CONTEXT_COLUMNS``: sample rate [Hz], fault rates [Hz], shaft rate [Hz]).

        Yields
        ------
        signal : numpy.ndarray
            One signal as floats.
        context : dict
            ``{"fs": ..., "bpfo": ..., ...}`` [Hz], the keys of ``CONTEXT_COLUMNS`` that
            ``X`` gives (array input: ``fs`` and ``fault_frequencies``).
        """
        if isinstance(X, pd.DataFrame):
            if self.signal_column not in X.columns:
                raise FeatureError(f"X has no column {self.signal_column!r} (the signals)")
            needed = [CONTEXT_COLUMNS[k] for k in ("fs", *self.faults, "shaft")]
            missing = [c for c in needed if c not in X.columns]
            if missing:
                raise FeatureError(f"X is missing the context columns {missing}")
            for _, row in X.iterrows():
                ctx = {k: float(row[c]) for k, c in CONTEXT_COLUMNS.items() if c in X.columns}
                yield np.asarray(row[self.signal_column], dtype=float), ctx
            return
        arr = np.asarray(X, dtype=float)
        if arr.ndim != 2:
            raise ValueError(f"X has shape {arr.shape}; expected (n_signals, n_samples)")
        if self.fs is None or self.fault_frequencies is None:
            raise FeatureError(
                "array input needs fs and fault_frequencies (or pass a DataFrame "
                "with the context columns)"
            )
        ctx = {"fs": float(self.fs), **{k: float(v) for k, v in self.fault_frequencies.items()}}
        if "shaft_frequency" in self.feature_names_out_ and "shaft" not in ctx:
            raise FeatureError(
                "fault_frequencies has no 'shaft' [Hz]; the feature set "
                f"{self.feature_set!r} includes the shaft frequency"
            )
        for row in arr:
            yield row, ctx

    def fit(self, X: pd.DataFrame | np.ndarray, y: object = None) -> FeatureExtractor:
        """Check the input and record the feature names (the transform has no state).

        Parameters
        ----------
        X : pandas.DataFrame or ndarray
            Signals: a DataFrame as in the class description, or one signal per row [U].
        y : object, optional
            Ignored (scikit-learn's signature).

        Returns
        -------
        FeatureExtractor
            This extractor, fitted.
        """
        if not isinstance(X, pd.DataFrame):
            validate_data(self, X, dtype=np.float64, ensure_min_features=2)
        if self.feature_set not in FEATURE_SETS:
            raise FeatureError(f"feature_set = {self.feature_set!r} is not one of {FEATURE_SETS}")
        names = feature_names(self.faults, self.n_harmonics)
        if self.feature_set in ("scale-free", "evidence+scale-free"):
            units = feature_units(self.faults, self.n_harmonics)
            names = [n for n in names if units[n] != "U"]
            if self.feature_set == "evidence+scale-free":
                names = [*EVIDENCE_NAMES, *names]
        elif self.feature_set == "envelope":
            names = [n for n in names if n.startswith("envelope_") and n.endswith("_snr")]
        elif self.feature_set == "evidence":
            names = list(EVIDENCE_NAMES)
        self.feature_names_out_ = np.array(names, dtype=object)
        return self

    def transform(self, X: pd.DataFrame | np.ndarray) -> np.ndarray:
        """Feature matrix, shape (n_signals, n_features).

        Parameters
        ----------
        X : pandas.DataFrame or ndarray
            Signals, as for :meth:`fit` (an array's rows as long as fit's).

        Returns
        -------
        ndarray
            One row per signal, one column per name of :meth:`get_feature_names_out`, in the
            unit ``features.feature_units`` gives each.
        """
        check_is_fitted(self, "feature_names_out_")
        if not isinstance(X, pd.DataFrame):
            # the count of samples per signal is checked against fit's first (any count, even
            # one, gets scikit-learn's "X has n features, but ... is expecting m" error)
            X = validate_data(self, X, dtype=np.float64, reset=False, ensure_min_features=1)
        names = list(self.feature_names_out_)
        items = list(self.signals_with_context(X))
        rows = map_in_processes(
            _feature_rows, items, self.n_jobs, self.faults, self.n_harmonics, names
        )
        return np.asarray(rows, dtype=float).reshape(len(items), len(names))

    def get_feature_names_out(self, input_features: object = None) -> np.ndarray:
        """Names of the output features.

        Parameters
        ----------
        input_features : object, optional
            Ignored (scikit-learn's signature: the output names do not depend on the input's).

        Returns
        -------
        ndarray of str
            The feature names, in the columns' order.
        """
        check_is_fitted(self, "feature_names_out_")
        return self.feature_names_out_.copy()
