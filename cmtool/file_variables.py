"""The sample rate and shaft speed a MATLAB or numpy file holds as scalar variables.

A record saved from MATLAB or numpy usually travels with its rate (``save rec.mat x fs``,
``np.savez("rec.npz", x=x, fs=fs)``): a scalar named as people name it, or the sampling
interval. ``cmtool diagnose`` takes them as the file's own (``--fs`` and ``--rpm`` against
them are warned of where they differ), as it takes the CWRU files' ``X097RPM``.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

__all__ = ["INTERVAL_NAMES", "RATE_NAMES", "SPEED_NAMES", "rate_and_speed"]

#: Names of a sample rate [Hz] (compared in lower case, ``_`` and spaces left out).
RATE_NAMES = frozenset(
    {"fs", "sr", "samplerate", "samplingrate", "samplingfrequency", "samplefrequency", "fsamp"}
)
#: Names of a sampling interval [s].
INTERVAL_NAMES = frozenset({"dt", "ts", "samplinginterval", "sampleinterval"})
#: Names of a shaft speed [rpm].
SPEED_NAMES = frozenset({"rpm", "shaftrpm", "speedrpm"})


def _key(name: str) -> str:
    return str(name).lower().replace("_", "").replace(" ", "")


def _scalar(value: Any) -> float | None:
    """A finite positive number held alone (a 1 x 1 MATLAB array, a 0-d numpy array)."""
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return None
    if array.size != 1:
        return None
    number = float(array.ravel()[0])
    return number if np.isfinite(number) and number > 0 else None


def rate_and_speed(variables: Mapping[str, Any]) -> dict[str, float]:
    """The ``fs_hz`` and ``rpm`` a file's scalar variables give, where they give one each.

    Parameters
    ----------
    variables : mapping of str to Any
        The file's variables (name -> value).

    Returns
    -------
    dict of str to float
        ``fs_hz`` [Hz] from a rate (``RATE_NAMES``) or an interval (``INTERVAL_NAMES``,
        inverted), and ``rpm`` [rev/min] (``SPEED_NAMES``); a quantity two variables give
        differently, or none gives, is left out.

    Examples
    --------
    >>> rate_and_speed({"x": [1.0, 2.0], "Fs": 25600, "RPM": 1480.0})
    {'fs_hz': 25600.0, 'rpm': 1480.0}
    >>> rate_and_speed({"dt": 1 / 12000})
    {'fs_hz': 12000.0}
    """
    found: dict[str, set[float]] = {"fs_hz": set(), "rpm": set()}
    for name, value in variables.items():
        key, number = _key(name), _scalar(value)
        if number is None:
            continue
        if key in RATE_NAMES:
            found["fs_hz"].add(number)
        elif key in INTERVAL_NAMES:
            found["fs_hz"].add(1.0 / number)
        elif key in SPEED_NAMES:
            found["rpm"].add(number)
    return {k: next(iter(v)) for k, v in found.items() if len(v) == 1}
