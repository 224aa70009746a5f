"""Model files: save and load a ``cmtool train`` bundle safely, and fingerprint its data.

Models are saved in the skops format (a zip of JSON and numpy arrays: loading it constructs
only the types it is allowed to and runs no code from the file), together with the feature
names, the classes, the training recipe, the fingerprint of the training data and the versions
of cmtool, scikit-learn and numpy. Loading refuses, with ``ModelFormatError`` and before any
object is built, a file that is not such an archive, one that holds a type outside
``TRUSTED_TYPES`` and one of another format version; a model made by another cmtool or
scikit-learn version raises ``ModelVersionError``. Moved out of :mod:`cmtool.classifier`
unchanged in stop 54; ``cmtool.classifier`` still exports every name.
"""

from __future__ import annotations

import hashlib
import re
import zipfile
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import sklearn

from . import __version__
from .io import atomic_write, json_text

__all__ = [
    "MODEL_FORMAT",
    "TRUSTED_TYPES",
    "ModelFormatError",
    "ModelVersionError",
    "dataset_fingerprint",
    "load_model",
    "save_model",
    "signal_hashes",
    "training_overlap",
]

#: Version of the model file layout (2: skops archive with a training-data fingerprint; 1 was
#: a pickle and is refused).
MODEL_FORMAT = 2

#: Types outside skops' default set (scikit-learn estimators, numpy, builtins) that a cmtool
#: model may hold: the feature step, and the fitted trees of the candidate classifiers, which
#: skops rebuilds from their node arrays (no code runs). Anything else in a file is refused
#: before it is loaded.
TRUSTED_TYPES = (
    "features.transformer.FeatureExtractor",
    "sklearn.tree._tree.Tree",
    "sklearn.ensemble._hist_gradient_boosting.predictor.TreePredictor",
)


class ModelVersionError(ValueError):
    """A saved model was made by another version of cmtool or scikit-learn."""


class ModelFormatError(ValueError):
    """A file is not a cmtool model: not a skops archive, untrusted content, or old format."""


def signal_hashes(frame: pd.DataFrame, signal_column: str = "signal") -> list[str]:
    """Per signal, the first 16 hex digits of the SHA-256 of its float32 samples.

    Parameters
    ----------
    frame : DataFrame
        Signals in ``signal_column`` (1-D arrays).
    signal_column : str
        Column of the signals.

    Returns
    -------
    list of str
        One digest per row, in row order.
    """
    return [
        hashlib.sha256(np.ascontiguousarray(x, dtype=np.float32).tobytes()).hexdigest()[:16]
        for x in frame[signal_column]
    ]


def dataset_fingerprint(frame: pd.DataFrame, signal_column: str = "signal") -> str:
    """SHA-256 over the sorted per-signal digests: the same signals, the same fingerprint.

    Parameters
    ----------
    frame : DataFrame
        Signals in ``signal_column`` (1-D arrays); row order does not matter.
    signal_column : str
        Column of the signals.

    Returns
    -------
    str
        64 hexadecimal digits.
    """
    return hashlib.sha256("".join(sorted(signal_hashes(frame, signal_column))).encode()).hexdigest()


def training_overlap(bundle: dict[str, Any], frame: pd.DataFrame) -> float:
    """Fraction of a dataset's signals that the model was trained on (0 to 1).

    Parameters
    ----------
    bundle : dict
        A model bundle (:func:`train`, :func:`load_model`).
    frame : DataFrame
        The signals to score.

    Returns
    -------
    float
        Share of ``frame``'s signals whose samples are identical to a training signal's.
    """
    trained = set(bundle.get("training_signals", ()))
    if not len(frame):
        return 0.0
    return sum(h in trained for h in signal_hashes(frame)) / len(frame)


def save_model(bundle: dict[str, Any], path: str | Path) -> Path:
    """Write the model bundle (skops archive) atomically, plus a readable ``.json`` summary.

    The archive holds JSON and numpy arrays only (no pickle): :func:`load_model` rebuilds it
    without running code from the file.

    Parameters
    ----------
    bundle : dict
        The model bundle (``cmtool.classifier.train``).
    path : str or Path
        The archive written (``.skops``); the summary is written beside it, ``.json``
        added to its name.

    Returns
    -------
    Path
    """
    import skops.io as sio

    path = Path(path)
    atomic_write(path, lambda tmp: sio.dump(bundle, tmp))
    summary = {
        k: bundle.get(k)
        for k in (
            "format",
            "best",
            "scores",
            "classes",
            "feature_set",
            "extrapolation",
            "versions",
            "training_fingerprint",
            "training_ranges",
            "feature_names",
            "n_splits",
        )
    }
    atomic_write(
        path.with_suffix(path.suffix + ".json"),
        lambda tmp: tmp.write_text(json_text(summary)),
    )
    return path


def load_model(path: str | Path) -> dict[str, Any]:
    """Load a model bundle safely, or refuse it with a message that says why.

    Parameters
    ----------
    path : str or Path
        A file written by :func:`save_model` (``cmtool train``).

    Returns
    -------
    dict
        The bundle (``pipeline``, ``classes``, ``feature_set``, ``training_fingerprint``, ...).

    Raises
    ------
    FileNotFoundError
        No such file.
    ModelFormatError
        Not a skops archive (a pickle, random bytes, a truncated file), a type outside
        skops' defaults and ``TRUSTED_TYPES``, another format version, or no valid
        training-data fingerprint. Checked before any object is built.
    ModelVersionError
        Made by another cmtool or scikit-learn version.
    """
    import skops.io as sio

    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"model {path}: no such file")
    what = f"model {path}"
    if not zipfile.is_zipfile(path):
        raise ModelFormatError(
            f"{what}: not a cmtool model file (cmtool writes skops archives; pickle and "
            "joblib files are refused because loading them can run code): retrain it with "
            "`cmtool train`"
        )
    try:
        untrusted = sio.get_untrusted_types(file=path)
    except Exception as err:  # noqa: BLE001 - any failure to read the archive's schema
        raise ModelFormatError(f"{what}: unreadable model archive ({err})") from None
    refused = sorted(set(untrusted) - set(TRUSTED_TYPES))
    if refused:
        raise ModelFormatError(
            f"{what}: holds types cmtool does not trust ({', '.join(refused[:5])}); "
            "refused without loading"
        )
    try:
        bundle = sio.load(path, trusted=list(TRUSTED_TYPES))
    except Exception as err:  # noqa: BLE001 - a damaged archive fails in many ways
        raise ModelFormatError(f"{what}: damaged model archive ({err})") from None
    if not isinstance(bundle, dict) or bundle.get("format") != MODEL_FORMAT:
        found = bundle.get("format") if isinstance(bundle, dict) else type(bundle).__name__
        raise ModelFormatError(
            f"{what}: not a cmtool model of format {MODEL_FORMAT} (found {found!r}); "
            "retrain it with `cmtool train`"
        )
    versions = bundle.get("versions", {})
    for key, current in (("cmtool", __version__), ("sklearn", sklearn.__version__)):
        if versions.get(key) != current:
            raise ModelVersionError(
                f"model {path} was made with {key} {versions.get(key)}; this is {key} "
                f"{current}: retrain it with `cmtool train`"
            )
    fingerprint = bundle.get("training_fingerprint")
    if not isinstance(fingerprint, str) or not re.fullmatch(r"[0-9a-f]{64}", fingerprint):
        raise ModelFormatError(f"{what}: no valid training-data fingerprint")
    pipeline = bundle.get("pipeline")
    if not hasattr(pipeline, "predict_proba") or not isinstance(bundle.get("classes"), list):
        raise ModelFormatError(f"{what}: holds no fitted classifier pipeline")
    return bundle
